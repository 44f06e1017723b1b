# cmake -DCMD="pft;args..." -DEXPECT=regex [-DEXIT=n] -P expect_error.cmake
# Passes when the command exits with status EXIT (default 2, the host tools' status for every
# usage or input error; never a crash or signal), a line of its stderr starts with "pft: error: " and
# matches EXPECT.
if(NOT DEFINED EXIT OR EXIT STREQUAL "")
  set(EXIT 2)
endif()
execute_process(COMMAND ${CMD} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc STREQUAL "${EXIT}")
  message(FATAL_ERROR "expected exit ${EXIT}, got ${rc}\n${out}\n${err}")
endif()
if(NOT err MATCHES "(^|\n)pft: error: ")
  message(FATAL_ERROR "stderr has no line starting with 'pft: error: ':\n${err}")
endif()
if(NOT err MATCHES "${EXPECT}")
  message(FATAL_ERROR "stderr does not match '${EXPECT}':\n${err}")
endif()
message(STATUS "ok: exit ${rc}: ${err}")
