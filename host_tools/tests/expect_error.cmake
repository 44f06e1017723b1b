# cmake -DCMD="pft;args..." -DEXPECT=regex -P expect_error.cmake
# Passes when the command exits with a non-zero status (not a crash/signal) and its stderr
# matches EXPECT.
execute_process(COMMAND ${CMD} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0)
  message(FATAL_ERROR "expected a non-zero exit, got 0\n${out}\n${err}")
endif()
if(NOT rc MATCHES "^[0-9]+$" OR rc GREATER 100)
  message(FATAL_ERROR "abnormal termination: ${rc}\n${err}")
endif()
if(NOT err MATCHES "${EXPECT}")
  message(FATAL_ERROR "stderr does not match '${EXPECT}':\n${err}")
endif()
message(STATUS "ok: exit ${rc}: ${err}")
