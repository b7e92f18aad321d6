# SPDX-License-Identifier: GPL-3.0-or-later
# Installs the build into PREFIX, then configures, builds and runs Examples/Consumer against it
# with find_package(MesoLens), and checks the Python package from the install tree.
file(REMOVE_RECURSE "${PREFIX}" "${CONSUMER_BUILD}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD}" --prefix "${PREFIX}"
  RESULT_VARIABLE status OUTPUT_QUIET)
if (NOT status EQUAL 0)
  message(FATAL_ERROR "cmake --install failed")
endif ()
set(consumer_flags "")
set(python_environment "PYTHONPATH=${PREFIX}/lib/python3/dist-packages")
if (SANITIZE)
  # Libraries built with the sanitizers (SANITIZE: their -fsanitize= list) need the runtime in
  # whatever links them, and preloaded in Python.
  set(consumer_flags "-DCMAKE_EXE_LINKER_FLAGS=-fsanitize=${SANITIZE}")
  list(APPEND python_environment "LD_PRELOAD=${PRELOAD}")
  if (SANITIZE MATCHES "address")
    list(APPEND python_environment "ASAN_OPTIONS=detect_leaks=0")
  endif ()
endif ()
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${SOURCE}" -B "${CONSUMER_BUILD}"
  "-DCMAKE_PREFIX_PATH=${PREFIX}" -DCMAKE_BUILD_TYPE=Release ${consumer_flags}
  RESULT_VARIABLE status)
if (NOT status EQUAL 0)
  message(FATAL_ERROR "find_package(MesoLens) failed")
endif ()
execute_process(COMMAND "${CMAKE_COMMAND}" --build "${CONSUMER_BUILD}" RESULT_VARIABLE status)
if (NOT status EQUAL 0)
  message(FATAL_ERROR "the consumer did not build")
endif ()
execute_process(COMMAND "${CONSUMER_BUILD}/count_atoms" "${PDB}" RESULT_VARIABLE status
  OUTPUT_VARIABLE output)
message(STATUS "count_atoms: ${output}")
if (NOT status EQUAL 0 OR NOT output MATCHES "327 atoms, 337 bonds")
  message(FATAL_ERROR "the consumer gave a wrong answer: ${output}")
endif ()
if (PYTHON)
  execute_process(COMMAND "${CMAKE_COMMAND}" -E env ${python_environment}
    "${PYTHON}" -c "import vtkmodules.all, mesolens; r = mesolens.vtkMesoStructureReader(); r.SetFileName('${PDB}'); r.Update(); print(r.GetOutput().GetNumberOfPoints(), 'atoms from', mesolens.__file__)"
    RESULT_VARIABLE status OUTPUT_VARIABLE output)
  message(STATUS "python: ${output}")
  if (NOT status EQUAL 0 OR NOT output MATCHES "^327 atoms from ${PREFIX}")
    message(FATAL_ERROR "the installed Python package does not work: ${output}")
  endif ()
endif ()
