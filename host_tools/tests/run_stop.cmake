# cmake -DPFT=pft -DWORK=dir -DSRC=host_tools -P run_stop.cmake
# `pft run` on a sequence whose later frame is bad (docs/host_tools.md, "pft run"): a folder of
# the small procedural tbd_ir sequence's PGM frames (tests/tbd_ir_small.json, 96 x 72, seed 1,
# frames 1..12, no sidecar) whose frame 10 is a 4 x 4 PGM. The run must stop with exit status 2
# and one `pft: error:` line naming input frame 10 and the 9 frames processed before it, and
# the streamed outputs must be closed with those 9 frames in them: --stage-out's header and
# rows 1..9 (frame and seq 1..9, in order), --residual-out exactly 9 frames of 96 x 72 int16,
# and the overlay (overlay.avi) finished, not dropped; tracks.csv and tracks.json (and the DBT's
# dbt_tracks.*) written for those 9 frames, tracks.json marked "stopped_at_input_frame": 10 with
# "frames": 9. Needs nothing outside the source tree.
include(${CMAKE_CURRENT_LIST_DIR}/run_ok.cmake)

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/frames)
set(sc "${SRC}/tests/tbd_ir_small.json")
run_ok(${PFT} sim --scenario ${sc} --seed 1 --out ${WORK}/seq -q)
# a plain folder (no sequence.json): the image-folder reader, which refuses a frame of another size
foreach(k RANGE 1 12)
  string(LENGTH "${k}" nd)
  set(name "frame_00${k}.pgm")
  if(nd EQUAL 1)
    set(name "frame_000${k}.pgm")
  endif()
  if(k EQUAL 10)
    file(WRITE ${WORK}/frames/${name} "P2\n4 4\n255\n0 0 0 0\n0 0 0 0\n0 0 0 0\n0 0 0 0\n")
  else()
    file(COPY_FILE ${WORK}/seq/${name} ${WORK}/frames/${name})
  endif()
endforeach()

execute_process(COMMAND ${PFT} run --scenario ${sc} --sequence ${WORK}/frames --out ${WORK}/run -q
                        --stage-out ${WORK}/stage.csv --residual-out ${WORK}/res.i16
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc STREQUAL "2")
  message(FATAL_ERROR "expected exit status 2, got ${rc}\n${out}\n${err}")
endif()
if(NOT err MATCHES "(^|\n)pft: error: run: [^\n]*: stopped at input frame 10: [^\n]*frame 10 is 4x4, the first was 96x72 \\(9 frame\\(s\\) processed before it; [^\n]*/run/tracks.csv, tracks.json and the streamed outputs keep them\\)")
  message(FATAL_ERROR "stderr does not name the bad frame and the frames kept:\n${err}")
endif()

file(STRINGS ${WORK}/stage.csv rows)
list(LENGTH rows n)
if(NOT n EQUAL 10)
  message(FATAL_ERROR "stage.csv: ${n} lines, expected the header and 9 rows:\n${rows}")
endif()
list(GET rows 0 head)
if(NOT head STREQUAL "frame,seq,shift_x_px,shift_y_px,flags,sigma_mean,n_masked")
  message(FATAL_ERROR "stage.csv header: '${head}'")
endif()
foreach(k RANGE 1 9)
  list(GET rows ${k} r)
  if(NOT r MATCHES "^${k},${k},[-0-9.]+,[-0-9.]+,[0-9]+,[0-9.]+,[0-9]+$")
    message(FATAL_ERROR "stage.csv row ${k}: '${r}'")
  endif()
endforeach()

file(SIZE ${WORK}/res.i16 bytes)
math(EXPR want "9 * 96 * 72 * 2")
if(NOT bytes EQUAL want)
  message(FATAL_ERROR "res.i16: ${bytes} bytes, expected ${want} (9 frames of 96 x 72 int16)")
endif()

if(NOT EXISTS ${WORK}/run/overlay.avi)
  message(FATAL_ERROR "run/overlay.avi: not written (the overlay of the 9 frames should be finished)")
endif()
file(SIZE ${WORK}/run/overlay.avi vbytes)
if(vbytes EQUAL 0)
  message(FATAL_ERROR "run/overlay.avi is empty")
endif()
foreach(f tracks.csv tracks.json dbt_tracks.csv dbt_tracks.json)
  if(NOT EXISTS ${WORK}/run/${f})
    message(FATAL_ERROR "run/${f}: not written for the 9 frames before the bad one")
  endif()
endforeach()
file(STRINGS ${WORK}/run/tracks.csv trows LIMIT_COUNT 1)
if(NOT trows STREQUAL "frame,track,x,y,vx,vy,intensity,p_exist,first_frame")
  message(FATAL_ERROR "run/tracks.csv header: '${trows}'")
endif()
file(READ ${WORK}/run/tracks.json tj)
string(JSON stopped ERROR_VARIABLE jerr GET "${tj}" stopped_at_input_frame)
string(JSON nfr GET "${tj}" frames)
if(jerr OR NOT stopped EQUAL 10 OR NOT nfr EQUAL 9)
  message(FATAL_ERROR "run/tracks.json: stopped_at_input_frame '${stopped}' (${jerr}), frames '${nfr}'; expected 10 and 9")
endif()
message(STATUS "run_stop: passed (exit 2, 9 rows, ${bytes} residual bytes, overlay ${vbytes} bytes)")
