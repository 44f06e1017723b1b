# cmake -DPFT=pft -DWORK=dir -DSRC=host_tools -P dbt_preprocess.cmake
# The scenario's dbt.preprocess (docs/host_tools.md, "IR scenario files"): DBT's own preprocessing.
# On the small test sequence (tests/tbd_ir_small.json with its targets at 20 dB, 2 runs):
#  - without dbt.preprocess the summary says "dbt_preprocess": "shared";
#  - with dbt.preprocess {"preprocess": "spatial"} (TBD's stage is the temporal one) it says "own",
#    TBD's summary is the shared run's and DBT's differs from it (the setting reaches DBT and
#    only DBT);
#  - with the scene-motion test off (the only part of the TBD pipeline that writes into its
#    clutter map) and dbt.preprocess {} (a block that sets nothing: the library's defaults,
#    which is what the test file's tracker block uses) DBT's summary is the shared run's: the
#    second pipeline is the same preprocessing, fed the same frames.
# Needs nothing outside the source tree.
include(${CMAKE_CURRENT_LIST_DIR}/run_ok.cmake)

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
file(READ ${SRC}/tests/tbd_ir_small.json js)
# bright targets (20 dB), so that both trackers have tracks to compare
string(JSON js SET "${js}" targets snr_db 20)
file(WRITE ${WORK}/shared.json "${js}")
string(JSON v SET "${js}" dbt "{\"preprocess\": {\"preprocess\": \"spatial\"}}")
file(WRITE ${WORK}/own_spatial.json "${v}")
string(JSON ns SET "${js}" tracker scene_frames 0)
file(WRITE ${WORK}/shared_noscene.json "${ns}")
string(JSON v SET "${ns}" dbt "{\"preprocess\": {}}")
file(WRITE ${WORK}/own_same.json "${v}")

foreach(c shared own_spatial shared_noscene own_same)
  run_ok(${PFT} eval --scenario ${WORK}/${c}.json --runs 2 --threads 1 -q --out ${WORK}/${c})
  file(READ ${WORK}/${c}/summary.json s_${c})
endforeach()

function(expect_mode c want)
  string(JSON got GET "${s_${c}}" dbt_preprocess)
  if(NOT got STREQUAL want)
    message(FATAL_ERROR "${c}: summary dbt_preprocess is '${got}', expected '${want}'")
  endif()
endfunction()
expect_mode(shared shared)
expect_mode(shared_noscene shared)
expect_mode(own_spatial own)
expect_mode(own_same own)

# a tracker's part of a summary: its averaged measures and per-run figures (the seeds are the same)
function(part out c tracker)
  if(tracker STREQUAL "tbd")
    string(JSON a GET "${s_${c}}" averaged)
    string(JSON p GET "${s_${c}}" per_run)
  else()
    string(JSON a GET "${s_${c}}" dbt averaged)
    string(JSON p GET "${s_${c}}" dbt per_run)
    string(JSON d GET "${s_${c}}" dbt detections_per_frame)
    string(APPEND a " detections ${d}")
  endif()
  set(${out} "${a}\n${p}" PARENT_SCOPE)
endfunction()

part(t0 shared tbd)
part(t1 own_spatial tbd)
if(NOT t0 STREQUAL t1)
  message(FATAL_ERROR "dbt.preprocess changed TBD's figures:\nshared: ${t0}\nown: ${t1}")
endif()
part(d0 shared dbt)
part(d1 own_spatial dbt)
if(d0 STREQUAL d1)
  message(FATAL_ERROR "dbt.preprocess {preprocess: spatial} left DBT's figures as the shared run's: it does not reach DBT")
endif()
foreach(c shared own_same)
  string(JSON nt GET "${s_${c}}" dbt averaged tracks_per_run)
  if(nt EQUAL 0)
    message(FATAL_ERROR "${c}: DBT has no track on the test sequence: the comparisons below cannot fail")
  endif()
endforeach()
part(d2 shared_noscene dbt)
part(d3 own_same dbt)
if(NOT d2 STREQUAL d3)
  message(FATAL_ERROR "DBT on its own copy of the same preprocessing differs from DBT on the shared residual:\nshared: ${d2}\nown: ${d3}")
endif()
message(STATUS "shared/own said; own spatial changes DBT only; own with the same settings gives the shared DBT figures")
