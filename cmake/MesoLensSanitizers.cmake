# SPDX-License-Identifier: GPL-3.0-or-later
# AddressSanitizer + UndefinedBehaviorSanitizer for the whole build (tests included).
# Run the Python tests of such a build with LD_PRELOAD of libasan; the CTest setup does that.
option(MESOLENS_ENABLE_SANITIZERS "Build with AddressSanitizer and UndefinedBehaviorSanitizer" OFF)
if (MESOLENS_ENABLE_SANITIZERS)
  set(mesolens_sanitizer_flags -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined)
  add_compile_options(${mesolens_sanitizer_flags})
  add_link_options(-fsanitize=address,undefined)
endif ()
# ThreadSanitizer for the whole build (not with the two above): the determinism test's two
# pipelines in two threads are its race check.
option(MESOLENS_ENABLE_THREAD_SANITIZER "Build with ThreadSanitizer" OFF)
if (MESOLENS_ENABLE_THREAD_SANITIZER)
  if (MESOLENS_ENABLE_SANITIZERS)
    message(FATAL_ERROR "ThreadSanitizer cannot be combined with MESOLENS_ENABLE_SANITIZERS")
  endif ()
  add_compile_options(-fsanitize=thread -fno-omit-frame-pointer)
  add_link_options(-fsanitize=thread)
endif ()
# Fuzz targets: every library instrumented for libFuzzer's coverage, with the sanitizers.
if (MESOLENS_BUILD_FUZZERS)
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined -fno-omit-frame-pointer
                      -fno-sanitize-recover=undefined)
  add_link_options(-fsanitize=address,undefined)
endif ()
