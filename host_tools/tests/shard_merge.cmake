# ctest host_<kind>_shard_merge: one `pft eval` of RUNS runs against `pft eval --shard K/4`
# (K = 1..4, one thread each) combined by `pft merge`; compare_summaries.py must find the two
# summaries identical apart from the invocation and clock fields.
# -DPFT=... -DSCENARIO=... -DRUNS=... -DOUT=... -DPYTHON=... -DCOMPARE=... [-DEXTRA=arg;arg]
file(REMOVE_RECURSE ${OUT})
include(${CMAKE_CURRENT_LIST_DIR}/run_ok.cmake)
run_ok(${PFT} eval --scenario ${SCENARIO} --runs ${RUNS} --threads 2 --out ${OUT}/single -q ${EXTRA})
foreach(k 1 2 3 4)
  run_ok(${PFT} eval --scenario ${SCENARIO} --runs ${RUNS} --threads 1 --shard ${k}/4 --out ${OUT}/parts -q ${EXTRA})
endforeach()
run_ok(${PFT} merge ${OUT}/parts/partial_4_of_4.json ${OUT}/parts/partial_2_of_4.json
               ${OUT}/parts/partial_1_of_4.json ${OUT}/parts/partial_3_of_4.json --out ${OUT}/merged -q)
execute_process(COMMAND ${PYTHON} ${COMPARE} ${OUT}/single/summary.json ${OUT}/merged/summary.json
                RESULT_VARIABLE rc OUTPUT_VARIABLE out)
message("${out}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "FAIL: merged summary differs from the single run")
endif()
