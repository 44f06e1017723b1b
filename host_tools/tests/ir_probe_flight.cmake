# cmake -DPFT=pft -DPROBE=ir_probe -DWORK=dir -DSRC=host_tools -P ir_probe_flight.cmake
# tests/tools/ir_probe -c against the host pipeline (docs/results/ir_clutter.md, "Branch
# ircost31"): `pft bench --probe-out` on tests/tbd_ir_flight_small.json (the flight build's
# tracker block of real_frames_low_false_rate.json on 96 x 72 procedural frames, 80 frames,
# seed 1) writes the frames, the library configurations the pipeline runs with (probe.cfg) and
# what the pipeline computed per frame (expect.txt: the stage's flags and shift, a checksum of
# the clutter map's output, the reported tracks after the scene-motion test with all bits of
# their fields); ir_probe -c must print the same lines from the same frames and configuration.
# So a field the host sets but the probe does not read, a call the probe makes differently or a
# step between the calls that the probe misses fails here. The test also requires tracks on
# at least 5 frames (float 7, q16 14 at this commit; the comparison covers the manager and the scene-motion test) and frames with and
# without the flat field's and map's work (every call runs). Needs nothing outside the source tree.
include(${CMAKE_CURRENT_LIST_DIR}/run_ok.cmake)
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
run_ok(${PFT} bench --scenario ${SRC}/tests/tbd_ir_flight_small.json --frames 80 --seed 1 --probe-out ${WORK} -q)
foreach(f probe.cfg frames.u16 expect.txt)
  if(NOT EXISTS ${WORK}/${f})
    message(FATAL_ERROR "pft bench --probe-out wrote no ${f}")
  endif()
endforeach()
file(SIZE ${WORK}/frames.u16 sz)
math(EXPR want "96 * 72 * 2 * 80")
if(NOT sz EQUAL want)
  message(FATAL_ERROR "frames.u16: ${sz} bytes, not ${want} (80 frames of 96 x 72)")
endif()
file(STRINGS ${WORK}/probe.cfg cfg)
foreach(k "pipeline.flat 1" "pipeline.clutter 1" "pipeline.scene 1" "pre.bg_anchor 1" "tbd.search_layers 3" "tbd.n_search 4000")
  list(FIND cfg "${k}" at)
  if(at LESS 0)
    message(FATAL_ERROR "probe.cfg has no line '${k}' (the scenario's flight build)")
  endif()
endforeach()
run_ok(${PROBE} -c ${WORK}/probe.cfg ${WORK}/frames.u16 80)
file(WRITE ${WORK}/probe.txt "${run_out}")
file(STRINGS ${WORK}/probe.txt got REGEX "^F ")
file(STRINGS ${WORK}/expect.txt want)
list(LENGTH got ng)
list(LENGTH want nw)
if(NOT ng EQUAL 80 OR NOT nw EQUAL 80)
  message(FATAL_ERROR "${ng} probe lines, ${nw} expected lines (80 frames)")
endif()
set(with_tracks 0)
foreach(i RANGE 79)
  list(GET got ${i} g)
  list(GET want ${i} w)
  if(NOT g STREQUAL w)
    message(FATAL_ERROR "frame ${i} + 1: ir_probe -c and the host pipeline differ\n probe: ${g}\n host:  ${w}")
  endif()
  if(NOT g MATCHES " tracks 0$")
    math(EXPR with_tracks "${with_tracks} + 1")
  endif()
endforeach()
if(with_tracks LESS 5)
  message(FATAL_ERROR "reported tracks on ${with_tracks} frames only: the comparison hardly covers the manager")
endif()
message(STATUS "ir_probe -c = host pipeline on 80 frames, reported tracks on ${with_tracks}")
