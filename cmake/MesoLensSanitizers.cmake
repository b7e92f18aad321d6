# SPDX-License-Identifier: GPL-3.0-or-later
# AddressSanitizer + UndefinedBehaviorSanitizer for the whole build (tests included).
option(MESOLENS_ENABLE_SANITIZERS "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
# ThreadSanitizer for the whole build (not with the two above): the determinism test's two
# pipelines in two threads are its race check.
option(MESOLENS_ENABLE_THREAD_SANITIZER "Build with ThreadSanitizer" OFF)
# MESOLENS_SANITIZE: the build's -fsanitize= list, empty without sanitizers (what links the
# libraries needs it too, as the installed-package test's consumer does).
set(MESOLENS_SANITIZE "")
if (MESOLENS_ENABLE_SANITIZERS)
  set(MESOLENS_SANITIZE "address,undefined")
  add_compile_options(-fsanitize=${MESOLENS_SANITIZE} -fno-omit-frame-pointer
                      -fno-sanitize-recover=undefined)
endif ()
if (MESOLENS_ENABLE_THREAD_SANITIZER)
  if (MESOLENS_ENABLE_SANITIZERS)
    message(FATAL_ERROR "ThreadSanitizer cannot be combined with MESOLENS_ENABLE_SANITIZERS")
  endif ()
  set(MESOLENS_SANITIZE "thread")
  add_compile_options(-fsanitize=${MESOLENS_SANITIZE} -fno-omit-frame-pointer)
endif ()
if (MESOLENS_SANITIZE)
  add_link_options(-fsanitize=${MESOLENS_SANITIZE})
endif ()
# A sanitized build's Python modules need the sanitizer's runtime loaded first, and libstdc++
# with it (otherwise ASan cannot intercept C++ exceptions thrown in our libraries): every Python
# the build runs (the ParaView proxies, the tests) gets LD_PRELOAD=MESOLENS_SANITIZER_PRELOAD.
# Python itself leaks by design, so leak detection is off there.
set(MESOLENS_SANITIZER_PRELOAD "")
set(MESOLENS_SANITIZED_PYTHON_ENVIRONMENT "")
if (MESOLENS_SANITIZE)
  if (MESOLENS_ENABLE_SANITIZERS)
    set(runtime libasan.so)
  else ()
    set(runtime libtsan.so)
  endif ()
  execute_process(COMMAND ${CMAKE_CXX_COMPILER} -print-file-name=${runtime}
    OUTPUT_VARIABLE sanitizer_library OUTPUT_STRIP_TRAILING_WHITESPACE)
  execute_process(COMMAND ${CMAKE_CXX_COMPILER} -print-file-name=libstdc++.so.6
    OUTPUT_VARIABLE stdcxx_library OUTPUT_STRIP_TRAILING_WHITESPACE)
  set(MESOLENS_SANITIZER_PRELOAD "${sanitizer_library}:${stdcxx_library}")
  set(MESOLENS_SANITIZED_PYTHON_ENVIRONMENT "LD_PRELOAD=${MESOLENS_SANITIZER_PRELOAD}")
  if (MESOLENS_ENABLE_SANITIZERS)
    list(APPEND MESOLENS_SANITIZED_PYTHON_ENVIRONMENT "ASAN_OPTIONS=detect_leaks=0")
  endif ()
endif ()
# Fuzz targets: every library instrumented for libFuzzer's coverage, with the sanitizers.
if (MESOLENS_BUILD_FUZZERS)
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer
                      -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif ()
