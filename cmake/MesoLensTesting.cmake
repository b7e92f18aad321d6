# SPDX-License-Identifier: GPL-3.0-or-later
find_package(GTest REQUIRED)
include(GoogleTest)

# Every test gets the data folders; tests needing ../shared/data skip (CTest reports them as
# skipped, not passed) when it is absent.
set(mesolens_test_definitions
  MESOLENS_DATA_DIR="${MESOLENS_DATA_DIR}"
  MESOLENS_SHARED_DATA_DIR="${MESOLENS_SHARED_DATA_DIR}"
  MESOLENS_BASELINE_DIR="${CMAKE_SOURCE_DIR}/Testing/Baseline"
  MESOLENS_SOURCE_DIR="${CMAKE_SOURCE_DIR}"
  MESOLENS_TEST_OUTPUT_DIR="${CMAKE_BINARY_DIR}/Testing/Output")
file(MAKE_DIRECTORY "${CMAKE_BINARY_DIR}/Testing/Output")

# mesolens_add_gtest(<name> LABEL <label> SOURCES ... LIBRARIES ...)
function(mesolens_add_gtest name)
  cmake_parse_arguments(arg "" "LABEL;TIMEOUT" "SOURCES;LIBRARIES" ${ARGN})
  add_executable(${name} ${arg_SOURCES})
  target_link_libraries(${name} PRIVATE ${arg_LIBRARIES} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE ${mesolens_test_definitions})
  target_include_directories(${name} PRIVATE "${CMAKE_SOURCE_DIR}/Testing/Support")
  if (NOT arg_TIMEOUT)
    set(arg_TIMEOUT 300)
  endif ()
  set(environment ${mesolens_tsan_environment})
  if (MESOLENS_ENABLE_SANITIZERS AND arg_LABEL STREQUAL "render")
    # As for the image tests: Mesa's GL driver leaks a few bytes LeakSanitizer cannot attribute.
    set(environment "ASAN_OPTIONS=detect_leaks=0")
  endif ()
  gtest_discover_tests(${name}
    PROPERTIES LABELS "${arg_LABEL}" TIMEOUT ${arg_TIMEOUT}
               SKIP_REGULAR_EXPRESSION "\\[  SKIPPED \\]"
               ENVIRONMENT "${environment}"
    DISCOVERY_TIMEOUT 60)
endfunction()

# ThreadSanitizer's reports wholly inside uninstrumented third-party code (Mesa's software GL
# driver, Open MPI's runtime) are suppressed (Testing/Support/tsan.supp); every other report
# fails a test.
set(mesolens_tsan_environment "")
if (MESOLENS_ENABLE_THREAD_SANITIZER)
  set(mesolens_tsan_environment
    "TSAN_OPTIONS=suppressions=${CMAKE_SOURCE_DIR}/Testing/Support/tsan.supp")
endif ()

# Python tests run with Debian's interpreter (which has vtkmodules) and the build's package.
set(MESOLENS_PYTHON_EXECUTABLE "/usr/bin/python3" CACHE FILEPATH "Python with vtkmodules")
function(mesolens_add_python_test name script)
  cmake_parse_arguments(arg "" "LABEL" "ARGS;INTERPRETER" ${ARGN})
  if (NOT arg_LABEL)
    set(arg_LABEL python)
  endif ()
  if (NOT arg_INTERPRETER)
    set(arg_INTERPRETER "${MESOLENS_PYTHON_EXECUTABLE}")
  endif ()
  add_test(NAME ${name} COMMAND ${arg_INTERPRETER} "${script}" ${arg_ARGS})
  set(environment
    "PYTHONPATH=${MESOLENS_PYTHONPATH}"
    "MESOLENS_DATA_DIR=${MESOLENS_DATA_DIR}"
    "MESOLENS_SHARED_DATA_DIR=${MESOLENS_SHARED_DATA_DIR}"
    "MESOLENS_BASELINE_DIR=${CMAKE_SOURCE_DIR}/Testing/Baseline"
    "MESOLENS_TEST_OUTPUT_DIR=${CMAKE_BINARY_DIR}/Testing/Output"
    "PYTHONDONTWRITEBYTECODE=1")
  list(APPEND environment ${MESOLENS_SANITIZED_PYTHON_ENVIRONMENT} ${mesolens_tsan_environment})
  set_tests_properties(${name} PROPERTIES
    LABELS "${arg_LABEL}" ENVIRONMENT "${environment}" SKIP_RETURN_CODE 77 TIMEOUT 300)
endfunction()

# Strict image comparison (Testing/Support/mesolens_compare_images.cxx).
add_executable(mesolens_compare_images "${CMAKE_SOURCE_DIR}/Testing/Support/mesolens_compare_images.cxx")
target_link_libraries(mesolens_compare_images PRIVATE VTK::IOImage VTK::CommonDataModel)

# mesolens_add_image_test(<name> BASELINE <png> COMMAND <program> <args>... [WILL_FAIL] [PYTHON]
#                         [THRESHOLDS <pixel threshold> <max fraction>])
# Runs the program, which must write ${MESOLENS_TEST_OUTPUT_DIR}/<name>.png (pass it with
# @IMAGE@ in the arguments), then compares that image with Testing/Baseline/<png> (by default
# strictly: 16 levels per pixel, 0.2 % of the pixels; THRESHOLDS loosens that for pictures drawn
# by a different method). WILL_FAIL: the test passes only when the comparison finds the picture
# different (a render that fails is no pass). PYTHON: the program runs the wrapped modules or the
# plugin in a Python (python3, pvbatch, pvpython), which needs the sanitizer runtime preloaded
# in a sanitizer build.
function(mesolens_add_image_test name)
  cmake_parse_arguments(arg "WILL_FAIL;PYTHON" "BASELINE;LABEL" "COMMAND;THRESHOLDS" ${ARGN})
  if (NOT arg_LABEL)
    set(arg_LABEL render)
  endif ()
  set(image "${CMAKE_BINARY_DIR}/Testing/Output/${name}.png")
  string(REPLACE "@IMAGE@" "${image}" command "${arg_COMMAND}")
  set(preload "")
  if (arg_PYTHON)
    set(preload "${MESOLENS_SANITIZER_PRELOAD}")
  endif ()
  add_test(NAME ${name} COMMAND "${CMAKE_COMMAND}"
    "-DCOMMAND=${command}" "-DIMAGE=${image}" "-DPRELOAD=${preload}"
    "-DBASELINE=${CMAKE_SOURCE_DIR}/Testing/Baseline/${arg_BASELINE}"
    "-DCOMPARE=$<TARGET_FILE:mesolens_compare_images>" "-DTHRESHOLDS=${arg_THRESHOLDS}"
    -P "${CMAKE_SOURCE_DIR}/cmake/MesoLensRunImageTest.cmake")
  set_tests_properties(${name} PROPERTIES LABELS "${arg_LABEL}" TIMEOUT 300)
  if (arg_WILL_FAIL)
    # It must fail at the comparison, not earlier: a crashed or missing render is no proof.
    set_tests_properties(${name} PROPERTIES
      PASS_REGULAR_EXPRESSION "the image differs from its baseline")
  endif ()
  if (MESOLENS_ENABLE_SANITIZERS)
    # Mesa's GL driver, loaded and unloaded at run time, leaks a few hundred bytes that
    # LeakSanitizer cannot attribute to a module; leak checks stay on for the other tests.
    set_tests_properties(${name} PROPERTIES ENVIRONMENT "ASAN_OPTIONS=detect_leaks=0")
  elseif (MESOLENS_ENABLE_THREAD_SANITIZER)
    set_tests_properties(${name} PROPERTIES ENVIRONMENT "${mesolens_tsan_environment}")
  endif ()
endfunction()
