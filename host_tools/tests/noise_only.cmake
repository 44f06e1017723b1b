# ctest host_tbd_noise_only: a noise-only tbd eval writes null (not 0) for the per-target means
# (pcrlb, true_frames, correct_frames, detection_rate) and the table prints "-" for them.
# -DPFT=... -DSCENARIO=... -DOUT=...
execute_process(COMMAND ${PFT} eval --scenario ${SCENARIO} --runs 2 --particles 200 --out ${OUT}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "FAIL: pft eval exited ${rc}\n${err}")
endif()
if(out MATCHES "0\\.0000")
  message(FATAL_ERROR "FAIL: the table prints 0.0000 for a measure that does not exist\n${out}")
endif()
file(READ ${OUT}/summary.json js)
foreach(f pcrlb true_frames correct_frames detection_rate appearance_delay_all_runs rmse)
  string(JSON t TYPE "${js}" averaged ${f})
  if(NOT t STREQUAL "NULL")
    string(JSON v GET "${js}" averaged ${f})
    message(FATAL_ERROR "FAIL: averaged.${f} is ${v}, expected null")
  endif()
endforeach()
string(JSON g GET "${js}" averaged gospa)
message("noise only: per-target means null; GOSPA ${g} (false points only)")
