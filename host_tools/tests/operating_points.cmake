# cmake -DPFT=pft -DWORK=dir -DSRC=host_tools -P operating_points.cmake
# The low-false-rate twin of the procedural demo file (scenarios/tbd_ir/procedural_low_false_rate.json,
# docs/tuning.md "IR operating points"): its tracker block reaches the pipeline. A copy of the
# shipped file with a small sequence (128x96, 40 frames, 3 targets at 15 dB, 3000 search
# particles; every other tracker field as shipped) is simulated once and run by `pft run` as
# shipped and with one field of its block undone at a time:
#  - scene_hold 7 against 1 (both without the spread-dependent hold): the held run's tracks.csv
#    is the unheld run's rows less the first 6 reported rows of every track (and the unheld run
#    has a track of at least 7 rows, so the check can fail);
#  - the spread-dependent hold (scene_spread_px 0.35, scene_spread_hold 3, scene_spread_exist 0.99) removed: the tracks
#    change, and the shipped run reports at least as many rows (its hold is shorter for steady
#    tracks);
#  - flat_block 0, clutter_mean false: the residual the manager sees (--residual-out) changes;
#  - integ_alpha removed: the tracks change (the births come from the integration);
#  - bg_anchor, clutter_anchor toggled (bg_anchor off with the fields that need it): the
#    residual the manager sees changes;
#  - the gated background update (bg_gate 0.25 with bg_gate_young 16 and bg_gate_local
#    "relative", the shaded real-frame twin's) removed: the residual changes; bg_gate_young,
#    bg_gate_local and bg_masked_taps "all" each removed alone: the residual changes;
#  - handover_in_scale 0.8 removed: the tracks change;
#  - search_layers 2 removed (twenty-ninth round): the tracks change. The entering-edge hold it is
#    shipped with (scene_edge_px 6) holds nothing on this short sequence; its rule is test_edge_hold's;
#  - flat_rescale removed: the residual changes (flat_block 0 removes it too: it needs flat_block);
#  - the clutter map's mean floor (clutter_mean_floor 1 after clutter_floor_age 30 frames, twenty-
#    second round) removed, and its age removed alone (the floor from the first frame): the residual
#    changes.
# The real-frame twins (real_frames_low_false_rate.json and real_frames_shaded_low_false_rate.json)
# need real backgrounds to run; only their documented blocks are checked here, and the three
# files' dbt.preprocess (DBT on their default twins' preprocessing).
# Needs nothing outside the source tree.
cmake_policy(SET CMP0057 NEW) # if(IN_LIST)
include(${CMAKE_CURRENT_LIST_DIR}/run_ok.cmake)

set(shipped "${SRC}/scenarios/tbd_ir/procedural_low_false_rate.json")
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
file(READ ${shipped} js)

# each shipped block is the documented one (a change of a file must change this test and docs);
# CMake reads JSON true as ON and prints doubles with 17 digits (0.2, 0.7)
# (`where` is the JSON path of the block: "tracker", or "dbt;preprocess" for DBT's own)
function(check_at file where)
  file(READ ${file} j)
  foreach(kv ${ARGN})
    string(REPLACE "=" ";" kv "${kv}")
    list(GET kv 0 k)
    list(GET kv 1 v)
    string(JSON got GET "${j}" ${where} ${k})
    if(NOT got STREQUAL v)
      string(REPLACE ";" "." at "${where}")
      message(FATAL_ERROR "${file}: ${at}.${k} is '${got}', the documented setting is '${v}'")
    endif()
  endforeach()
endfunction()
function(check_block file)
  check_at(${file} tracker ${ARGN})
endfunction()
set(common "flat_block=32" "flat_relative=ON" "clutter_mean=ON" "clutter_persist=4"
           "clutter_alpha=0.20000000000000001" "integ_alpha=0.69999999999999996" "bg_anchor=ON"
           "theta_end=0.20000000000000001" "particles=24000" "bg_stale_reinit=32")
check_block(${shipped} ${common} "scene_hold=7" "scene_spread_px=0.34999999999999998" "scene_spread_hold=3" "scene_spread_exist=0.98999999999999999"
            "search_layers=2" "scene_edge_px=6.0" "scene_edge_still_px=0.20000000000000001" "scene_edge_shift_px=0.20000000000000001"
            "clutter_mean_floor=1.0" "clutter_floor_age=30" "clutter_anchor=ON" "bg_gate=0.25" "bg_gate_young=16"
            "bg_gate_local=relative" "bg_masked_taps=all" "handover_in_scale=0.80000000000000004" "flat_rescale=ON")
# the real-frame twin (real backgrounds needed to run it: only its block is checked); since the
# thirtieth round three search layers with the short hold's speed bound (scene_move_px, scene_move_hold;
# its rule is test_move_bound's)
check_block(${SRC}/scenarios/tbd_ir/real_frames_low_false_rate.json ${common} "scene_hold=7" "scene_spread_px=0.40000000000000002" "scene_spread_hold=2" "scene_spread_exist=0.98999999999999999" "bg_gate=0.25" "clutter_mean_floor=1.0" "clutter_floor_age=15"
            "bg_gate_young=16" "handover_in_scale=0.80000000000000004" "search_layers=3" "scene_edge_px=6.0"
            "scene_edge_still_px=0.20000000000000001" "scene_edge_shift_px=0.20000000000000001"
            "scene_move_px=0.34999999999999998" "scene_move_hold=3")
# its twin for a shaded sensor: the same block with the gate on the innovation less its tile's share
# and the cells next to masked pixels updated from their valid taps (bg_masked_taps "all"), the flat-field
# step's output over its running robust sd (flat_rescale, branch irshade3) with scene_hold 6
check_block(${SRC}/scenarios/tbd_ir/real_frames_shaded_low_false_rate.json ${common} "scene_hold=6"
            "search_layers=2" "scene_edge_px=6.0" "scene_edge_still_px=0.20000000000000001" "scene_edge_shift_px=0.20000000000000001"
            "scene_spread_px=0.45000000000000001" "scene_spread_hold=3" "scene_spread_exist=0.98999999999999999" "bg_gate=0.25"
            "bg_gate_young=16" "handover_in_scale=0.80000000000000004" "bg_gate_local=relative"
            "bg_masked_taps=all" "flat_rescale=ON")

# DBT's own preprocessing in the three files (dbt.preprocess): their default twins' (real_frames.json
# sets no preprocessing field; procedural_384x288.json's tracker block sets the ones below)
function(check_dbt file)
  check_at(${file} "dbt;preprocess" ${ARGN})
endfunction()
set(real_pre "preprocess=temporal" "bg_anchor=OFF" "flat_block=0" "clutter_alpha=0.10000000000000001" "clutter_mean=OFF")
check_dbt(${SRC}/scenarios/tbd_ir/real_frames_low_false_rate.json ${real_pre})
check_dbt(${SRC}/scenarios/tbd_ir/real_frames_shaded_low_false_rate.json ${real_pre})
check_dbt(${shipped} "preprocess=temporal" "clutter_mean=ON" "clutter_persist=4" "clutter_alpha=0.20000000000000001"
          "clutter_anchor=ON" "background_radius=5" "guard_radius=2" "tile=32")
string(JSON js SET "${js}" image "{\"width\": 128, \"height\": 96}")
string(JSON js SET "${js}" frames 40)
string(JSON js SET "${js}" targets snr_db 15)
string(JSON js SET "${js}" targets count 3)
string(JSON js SET "${js}" tracker particles 3000)
file(WRITE ${WORK}/lf.json "${js}")
# the fixed hold alone (the spread-dependent hold removed), and with scene_hold 1
string(JSON nospread REMOVE "${js}" tracker scene_spread_px)
string(JSON nospread REMOVE "${nospread}" tracker scene_spread_hold)
string(JSON nospread REMOVE "${nospread}" tracker scene_spread_exist)  # needs scene_spread_px
file(WRITE ${WORK}/nospread.json "${nospread}")
string(JSON v SET "${nospread}" tracker scene_hold 1)
file(WRITE ${WORK}/hold1.json "${v}")
string(JSON v SET "${js}" tracker flat_block 0)
string(JSON v REMOVE "${v}" tracker flat_rescale)
file(WRITE ${WORK}/noflat.json "${v}")
string(JSON v SET "${js}" tracker clutter_mean false)
string(JSON v SET "${v}" tracker clutter_persist 0)
string(JSON v REMOVE "${v}" tracker clutter_mean_floor)  # the floor and its age need the mean
string(JSON v REMOVE "${v}" tracker clutter_floor_age)
file(WRITE ${WORK}/nomean.json "${v}")
string(JSON v REMOVE "${js}" tracker integ_alpha)
file(WRITE ${WORK}/nointeg.json "${v}")
# the anchored background and the anchored clutter map: each toggled against the shipped block
# (absent reads as false)
foreach(f bg_anchor clutter_anchor)
  string(JSON cur ERROR_VARIABLE err GET "${js}" tracker ${f})
  if(err OR NOT cur)
    string(JSON v SET "${js}" tracker ${f} true)
  else()
    string(JSON v SET "${js}" tracker ${f} false)
    if(f STREQUAL "bg_anchor")  # the fields that refine the anchored background need it
      foreach(g bg_gate bg_gate_young bg_gate_local bg_masked_taps)
        string(JSON v REMOVE "${v}" tracker ${g})
      endforeach()
    endif()
  endif()
  file(WRITE ${WORK}/tog_${f}.json "${v}")
endforeach()
# the gated update undone as a whole (bg_gate_young and bg_gate_local need bg_gate), then each of
# the fields that refine it, and handover_in_scale, removed alone
string(JSON v REMOVE "${js}" tracker bg_gate)
string(JSON v REMOVE "${v}" tracker bg_gate_young)
string(JSON v REMOVE "${v}" tracker bg_gate_local)
file(WRITE ${WORK}/nogate.json "${v}")
foreach(f bg_gate_young bg_gate_local bg_masked_taps handover_in_scale flat_rescale clutter_floor_age search_layers)
  string(JSON v REMOVE "${js}" tracker ${f})
  file(WRITE ${WORK}/no_${f}.json "${v}")
endforeach()
# the mean floor undone (its age needs it)
string(JSON v REMOVE "${js}" tracker clutter_mean_floor)
string(JSON v REMOVE "${v}" tracker clutter_floor_age)
file(WRITE ${WORK}/nofloor.json "${v}")

run_ok(${PFT} sim --scenario ${WORK}/lf.json --seed 1 --out ${WORK}/seq -q)
foreach(c lf nospread hold1 noflat nomean nointeg tog_bg_anchor tog_clutter_anchor nogate no_bg_gate_young no_bg_gate_local
          no_bg_masked_taps no_handover_in_scale no_flat_rescale nofloor no_clutter_floor_age no_search_layers)
  run_ok(${PFT} run --scenario ${WORK}/${c}.json --sequence ${WORK}/seq --out ${WORK}/run_${c} --no-video -q
         --residual-out ${WORK}/run_${c}/res.i16)
endforeach()

# tracks.csv rows per track id, in order, without the header
function(rows_by_track file prefix)
  file(STRINGS ${file} rows)
  list(REMOVE_AT rows 0)
  set(ids "")
  foreach(r ${rows})
    string(REPLACE "," ";" f "${r}")
    list(GET f 1 id)
    if(NOT id IN_LIST ids)
      list(APPEND ids ${id})
      set(${prefix}_${id} "")
    endif()
    list(APPEND ${prefix}_${id} "${r}")
  endforeach()
  set(${prefix}_ids ${ids} PARENT_SCOPE)
  foreach(id ${ids})
    set(${prefix}_${id} "${${prefix}_${id}}" PARENT_SCOPE)
  endforeach()
endfunction()

rows_by_track(${WORK}/run_hold1/tracks.csv k1)
set(expect "")
set(long 0)
foreach(id ${k1_ids})
  list(LENGTH k1_${id} n)
  if(n GREATER 6)
    math(EXPR long "${long} + 1")
    list(SUBLIST k1_${id} 6 -1 kept)
    list(APPEND expect ${kept})
  endif()
endforeach()
if(long EQUAL 0)
  message(FATAL_ERROR "scene_hold 1 gave no track of 7 or more reported rows: the hold cannot be seen")
endif()
file(STRINGS ${WORK}/run_nospread/tracks.csv got)
list(REMOVE_AT got 0)
list(SORT expect)
list(SORT got)
if(NOT expect STREQUAL got)
  message(FATAL_ERROR "the fixed hold's tracks are not scene_hold 1's less the first 6 reported rows of "
                      "each track (scene_hold 7 not in effect?)\nexpected: ${expect}\ngot: ${got}")
endif()
list(LENGTH got ngot)
message(STATUS "scene_hold 7: ${ngot} rows of ${long} track(s), the unheld run's less 6 per track")
# the spread-dependent hold reaches the scene-motion test: the shipped run's tracks differ, with more rows
file(STRINGS ${WORK}/run_lf/tracks.csv shipped_rows)
list(REMOVE_AT shipped_rows 0)
list(SORT shipped_rows)
list(LENGTH shipped_rows nship)
if(shipped_rows STREQUAL got OR nship LESS ngot)
  message(FATAL_ERROR "the spread-dependent hold: the shipped run has ${nship} rows against the fixed hold's ${ngot} "
                      "(expected more: scene_spread_px not in effect?)")
endif()
message(STATUS "scene_spread_px 0.35: ${nship} rows against the fixed hold's ${ngot}")

foreach(c noflat nomean tog_bg_anchor tog_clutter_anchor nogate no_bg_gate_young no_bg_gate_local no_bg_masked_taps
          no_flat_rescale nofloor no_clutter_floor_age)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/run_lf/res.i16 ${WORK}/run_${c}/res.i16
                  RESULT_VARIABLE same)
  if(same EQUAL 0)
    message(FATAL_ERROR "${c}: the residual is the shipped file's: its field does not reach the pipeline")
  endif()
endforeach()
foreach(c nointeg no_handover_in_scale no_search_layers)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/run_lf/tracks.csv ${WORK}/run_${c}/tracks.csv
                  RESULT_VARIABLE same)
  if(same EQUAL 0)
    message(FATAL_ERROR "${c}: the tracks are the shipped file's: its field does not reach the manager")
  endif()
endforeach()
message(STATUS "flat_block, flat_rescale, clutter_mean, bg_anchor, clutter_anchor, bg_gate, bg_gate_young, bg_gate_local and bg_masked_taps change the residual, integ_alpha, handover_in_scale and search_layers the tracks")
