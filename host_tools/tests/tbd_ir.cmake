# ctests of the input forms of `pft run` and of kind tbd_ir (included by host_tools/CMakeLists.txt).
# A fixture simulates two sequences (the shipped two-target tbd case and a small tbd_ir one)
# and rewrites their frames as a PGM folder, 16-bit PNG, 16-bit TIFF and headerless u16 dumps
# (little- and big-endian, with a header to skip); the tests check that every form gives the
# same tracks, that bad --raw specs and truncated dumps are refused with exit status 2 and a
# message naming the file and the field, and the tbd_ir self-checks and scenarios.
add_executable(pft_frames_convert ${CMAKE_CURRENT_LIST_DIR}/frames_convert.cpp)
target_link_libraries(pft_frames_convert PRIVATE ${OpenCV_LIBS})
target_include_directories(pft_frames_convert PRIVATE ${OpenCV_INCLUDE_DIRS})

set(_ir_work "${CMAKE_CURRENT_BINARY_DIR}/input_forms")
set(_ir_args "-DPFT=$<TARGET_FILE:pft>" "-DCONV=$<TARGET_FILE:pft_frames_convert>"
             "-DWORK=${_ir_work}" "-DSRC=${CMAKE_CURRENT_SOURCE_DIR}")
function(pft_input_test name mode)
  add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} ${_ir_args} -DMODE=${mode}
                                -P ${CMAKE_CURRENT_SOURCE_DIR}/tests/input_forms.cmake)
  set_tests_properties(${name} PROPERTIES LABELS "host" FIXTURES_REQUIRED pft_input_data)
endfunction()
add_test(NAME host_input_setup COMMAND ${CMAKE_COMMAND} ${_ir_args} -DMODE=setup
                               -P ${CMAKE_CURRENT_SOURCE_DIR}/tests/input_forms.cmake)
set_tests_properties(host_input_setup PROPERTIES LABELS "host" FIXTURES_SETUP pft_input_data)
pft_input_test(host_input_forms_tbd tbd)
pft_input_test(host_input_forms_tbd_ir tbd_ir)
pft_input_test(host_input_raw_errors raw_errors)
pft_input_test(host_tbd_ir_sim_formats sim_formats)
pft_input_test(host_tbd_ir_real_frames real_frames)
pft_input_test(host_input_lost_frames lost_frames)
pft_input_test(host_input_bit_depth bit_depth)
pft_input_test(host_tbd_ir_eval_backgrounds eval_backgrounds)

add_test(NAME host_tbd_ir_selftest COMMAND pft selftest --kind tbd_ir)
set_tests_properties(host_tbd_ir_selftest PROPERTIES LABELS "host"
                     PASS_REGULAR_EXPRESSION "tbd_ir selftest: passed" FAIL_REGULAR_EXPRESSION "FAIL")
# Every shipped procedural tbd_ir scenario simulates and tracks 2 frames (the real_frames*
# files need a folder of images: host_tbd_ir_real_frames runs them on a fixture).
file(GLOB PFT_TBD_IR_SCENARIOS CONFIGURE_DEPENDS "${CMAKE_CURRENT_SOURCE_DIR}/scenarios/tbd_ir/*.json")
foreach(sc ${PFT_TBD_IR_SCENARIOS})
  get_filename_component(n ${sc} NAME_WE)
  if(NOT n MATCHES "^real_frames")
    add_test(NAME host_tbd_ir_scenario_${n} COMMAND pft bench --scenario ${sc} --frames 2 -q)
    set_tests_properties(host_tbd_ir_scenario_${n} PROPERTIES LABELS "host")
  endif()
endforeach()
# The low-false-rate procedural file's tracker block reaches the pipeline (the hold, the
# flat-field correction, the gated mean, the integration): host_tools/tests/operating_points.cmake
add_test(NAME host_tbd_ir_operating_points
         COMMAND ${CMAKE_COMMAND} -DPFT=$<TARGET_FILE:pft> -DWORK=${CMAKE_CURRENT_BINARY_DIR}/operating_points
                 -DSRC=${CMAKE_CURRENT_SOURCE_DIR} -P ${CMAKE_CURRENT_SOURCE_DIR}/tests/operating_points.cmake)
set_tests_properties(host_tbd_ir_operating_points PROPERTIES LABELS "host")
# dbt.preprocess (DBT's own preprocessing): the summary says "shared" or "own", the setting
# changes DBT's figures only, and the same settings give the shared figures:
# host_tools/tests/dbt_preprocess.cmake
add_test(NAME host_tbd_ir_dbt_preprocess
         COMMAND ${CMAKE_COMMAND} -DPFT=$<TARGET_FILE:pft> -DWORK=${CMAKE_CURRENT_BINARY_DIR}/dbt_preprocess
                 -DSRC=${CMAKE_CURRENT_SOURCE_DIR} -P ${CMAKE_CURRENT_SOURCE_DIR}/tests/dbt_preprocess.cmake)
set_tests_properties(host_tbd_ir_dbt_preprocess PROPERTIES LABELS "host")
# `pft run --stage-out`: one row per frame, the stage's shifts against the sim's platform steps
# (and the CSV parsed in integer micro-pixels): host_tools/tests/stage_out.cmake
add_test(NAME host_tbd_ir_stage_out
         COMMAND ${CMAKE_COMMAND} -DPFT=$<TARGET_FILE:pft> -DWORK=${CMAKE_CURRENT_BINARY_DIR}/stage_out
                 -DSRC=${CMAKE_CURRENT_SOURCE_DIR} -P ${CMAKE_CURRENT_SOURCE_DIR}/tests/stage_out.cmake)
set_tests_properties(host_tbd_ir_stage_out PROPERTIES LABELS "host")
# `pft eval --trace DIR` reads every search layer (search_layers 3 and 1: the new columns, the
# summary the same without --trace): host_tools/tests/eval_trace.cmake
add_test(NAME host_tbd_ir_eval_trace
         COMMAND ${CMAKE_COMMAND} -DPFT=$<TARGET_FILE:pft> -DWORK=${CMAKE_CURRENT_BINARY_DIR}/eval_trace
                 -DSRC=${CMAKE_CURRENT_SOURCE_DIR} -P ${CMAKE_CURRENT_SOURCE_DIR}/tests/eval_trace.cmake)
set_tests_properties(host_tbd_ir_eval_trace PROPERTIES LABELS "host")
# `pft run` stopped by a bad frame part-way: exit 2, the frame named, the streamed outputs
# (--stage-out, --residual-out, the overlay) closed with the frames before it:
# host_tools/tests/run_stop.cmake
add_test(NAME host_tbd_ir_run_stop
         COMMAND ${CMAKE_COMMAND} -DPFT=$<TARGET_FILE:pft> -DWORK=${CMAKE_CURRENT_BINARY_DIR}/run_stop
                 -DSRC=${CMAKE_CURRENT_SOURCE_DIR} -P ${CMAKE_CURRENT_SOURCE_DIR}/tests/run_stop.cmake)
set_tests_properties(host_tbd_ir_run_stop PROPERTIES LABELS "host")
# `pft sim`'s platform.warp: the exact warps put a ramp scene at platform.csv's positions to
# within 1 count, the default (OpenCV's cubic) does not: host_tools/tests/sim_warp.cmake
foreach(_warp opencv bspline catmull_rom)
  add_test(NAME host_tbd_ir_sim_warp_${_warp}
           COMMAND ${CMAKE_COMMAND} -DPFT=$<TARGET_FILE:pft> -DWORK=${CMAKE_CURRENT_BINARY_DIR}/sim_warp_${_warp}
                   -DWARP=${_warp} -P ${CMAKE_CURRENT_SOURCE_DIR}/tests/sim_warp.cmake)
  set_tests_properties(host_tbd_ir_sim_warp_${_warp} PROPERTIES LABELS "host")
endforeach()
# The pipeline's plumbing: on a clear sky at 15 dB it confirms at least 5 of the 6 targets.
add_test(NAME host_tbd_ir_clear_sky COMMAND pft demo --scenario ${CMAKE_CURRENT_SOURCE_DIR}/scenarios/tbd_ir/clear_sky_128x96.json)
set_tests_properties(host_tbd_ir_clear_sky PROPERTIES LABELS "host"
                     PASS_REGULAR_EXPRESSION "TBD +injected +6 +(100\\.0|83\\.3)%")
