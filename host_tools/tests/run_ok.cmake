# run_ok(cmd args...): runs a command in a host test script (cmake -P); a non-zero exit fails
# the test with the command and its output. The command's stdout and stderr are left in
# run_out and run_err in the caller's scope. Included by input_forms.cmake,
# operating_points.cmake and shard_merge.cmake.
function(run_ok)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "failed (${rc}): ${ARGN}\n${out}\n${err}")
  endif()
  set(run_out "${out}" PARENT_SCOPE)
  set(run_err "${err}" PARENT_SCOPE)
endfunction()
