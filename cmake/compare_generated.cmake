# Runs GEN, writing its stdout to OUT, and fails unless OUT equals the committed REF.
execute_process(COMMAND "${GEN}" OUTPUT_FILE "${OUT}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "${GEN} failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files "${OUT}" "${REF}" RESULT_VARIABLE diff)
if(NOT diff EQUAL 0)
  message(FATAL_ERROR "${REF} is stale: the code now generates ${OUT}. If the change of q16 "
                      "results is intended, copy it over and commit it.")
endif()
message(STATUS "${REF} matches the generator's output")
