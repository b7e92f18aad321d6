# SPDX-License-Identifier: GPL-3.0-or-later
# Driver of one image test: run COMMAND (a ;-list) that writes IMAGE, then compare it with
# BASELINE using COMPARE (with THRESHOLDS, a ;-list of its optional arguments, when given).
# Fails when either step fails. PRELOAD (optional): LD_PRELOAD for COMMAND alone (a sanitizer's
# runtime for a Python that loads sanitized modules; not for this script's own cmake).
file(REMOVE "${IMAGE}")
if (PRELOAD)
  set(COMMAND "${CMAKE_COMMAND}" -E env "LD_PRELOAD=${PRELOAD}" ${COMMAND})
endif ()
execute_process(COMMAND ${COMMAND} RESULT_VARIABLE status)
if (NOT status EQUAL 0)
  message(FATAL_ERROR "the rendering command failed (${status}): ${COMMAND}")
endif ()
execute_process(COMMAND "${COMPARE}" "${IMAGE}" "${BASELINE}" ${THRESHOLDS} RESULT_VARIABLE status)
if (NOT status EQUAL 0)
  message(FATAL_ERROR "the image differs from its baseline")
endif ()
