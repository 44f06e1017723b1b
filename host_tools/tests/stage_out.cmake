# cmake -DPFT=pft -DWORK=dir -DSRC=host_tools -P stage_out.cmake
# `pft run --stage-out` (docs/host_tools.md): on the small procedural tbd_ir sequence
# (tests/tbd_ir_small.json, 96 x 72, 24 frames, seed 1) the CSV has its header and one row per
# frame (frames 1..24 in order, seq as the frame's), and the stage's shift of frame k (z(p) =
# b(p - shift): the scene's move) is the sim's platform step -(p_k - p_{k-1}) (platform.csv: frame
# k's pixel x sees the scene at x + p_k), frame 1's shift is 0, with an rms error over frames
# 2..24 below BOUND per axis.
# BOUND: docs/results/ir_clutter.md, "Registration": 0.004-0.015 px rms at sigma_t 16-64 on the
# procedural scenes (full-size frames), the largest errors 4-5 times the rms; this frame has 1/16
# of a 384 x 288 frame's pixels (4 times the error for the same noise): about 0.06 px, and 0.1 px
# with the margin. A wrong sign gives about twice the step (0.3 to 0.7 px here) and fails.
# Values are compared in integer micro-pixels (CMake's math is integer). Needs nothing outside
# the source tree.
include(${CMAKE_CURRENT_LIST_DIR}/run_ok.cmake)
set(BOUND_UPX 100000)  # 0.1 px

file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
set(sc "${SRC}/tests/tbd_ir_small.json")
run_ok(${PFT} sim --scenario ${sc} --seed 1 --out ${WORK}/seq -q)
run_ok(${PFT} run --scenario ${sc} --sequence ${WORK}/seq --out ${WORK}/run --no-video -q
       --stage-out ${WORK}/stage.csv)

include(${CMAKE_CURRENT_LIST_DIR}/to_micro.cmake)  # to_micro()

# self-check of the parser (the test's own arithmetic)
foreach(c "0.5=500000" "-15.3395137=-15339513" "1e-05=10" "-2.5E+01=-25000000" "0.000000=0" "3=3000000")
  string(REPLACE "=" ";" c "${c}")
  list(GET c 0 s)
  list(GET c 1 want)
  to_micro("${s}" got)
  if(NOT got EQUAL want)
    message(FATAL_ERROR "to_micro(${s}) = ${got}, not ${want}")
  endif()
endforeach()

file(STRINGS ${WORK}/seq/platform.csv prows)
file(STRINGS ${WORK}/stage.csv srows)
list(GET srows 0 head)
if(NOT head STREQUAL "frame,seq,shift_x_px,shift_y_px,flags,sigma_mean,n_masked")
  message(FATAL_ERROR "stage.csv header: '${head}'")
endif()
list(REMOVE_AT prows 0)
list(REMOVE_AT srows 0)
list(LENGTH prows np)
list(LENGTH srows ns)
if(NOT np EQUAL 24 OR NOT ns EQUAL np)
  message(FATAL_ERROR "${ns} rows in stage.csv for ${np} frames in platform.csv (24 simulated)")
endif()

set(sx 0)
set(sy 0)
set(n 0)
math(EXPR last "${np} - 1")
foreach(i RANGE 0 ${last})
  list(GET srows ${i} r)
  string(REPLACE "," ";" r "${r}")
  list(LENGTH r nc)
  if(NOT nc EQUAL 7)
    message(FATAL_ERROR "stage.csv row ${i}: ${nc} fields")
  endif()
  list(GET r 0 frame)
  list(GET r 1 seq)
  math(EXPR k "${i} + 1")
  if(NOT frame EQUAL k)
    message(FATAL_ERROR "stage.csv row ${k} is frame ${frame}")
  endif()
  if(NOT seq EQUAL k)
    message(FATAL_ERROR "stage.csv row ${k} has seq ${seq} (the sim's frame k has seq k)")
  endif()
  list(GET r 2 ex)
  list(GET r 3 ey)
  to_micro("${ex}" ex)
  to_micro("${ey}" ey)
  list(GET prows ${i} p)
  string(REPLACE "," ";" p "${p}")
  list(GET p 1 px)
  list(GET p 2 py)
  to_micro("${px}" px)
  to_micro("${py}" py)
  if(i EQUAL 0)
    if(NOT ex EQUAL 0 OR NOT ey EQUAL 0)
      message(FATAL_ERROR "frame 1's shift is ${ex}, ${ey} micro-px, not 0")
    endif()
  else()
    # the error: shift_k - (-(p_k - p_{k-1})) = shift_k + p_k - p_{k-1}
    math(EXPR dx "${ex} + ${px} - ${qx}")
    math(EXPR dy "${ey} + ${py} - ${qy}")
    math(EXPR sx "${sx} + ${dx} * ${dx}")
    math(EXPR sy "${sy} + ${dy} * ${dy}")
    math(EXPR n "${n} + 1")
  endif()
  set(qx ${px})
  set(qy ${py})
endforeach()

# rms < BOUND  <=>  sum of squares < n * BOUND^2 (micro-px^2, 64-bit)
math(EXPR lim "${n} * ${BOUND_UPX} * ${BOUND_UPX}")
math(EXPR msx "${sx} / ${n}")
math(EXPR msy "${sy} / ${n}")
message(STATUS "stage_out: ${n} frame steps, mean squared shift error x ${msx}, y ${msy} micro-px^2 "
               "(bound ${BOUND_UPX}^2)")
if(NOT sx LESS lim OR NOT sy LESS lim)
  message(FATAL_ERROR "the stage's shifts miss the sim's platform steps: mean squared error x ${msx}, "
                      "y ${msy} micro-px^2, bound ${BOUND_UPX}^2")
endif()
message(STATUS "stage_out: passed")
