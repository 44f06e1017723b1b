# cmake -DPFT=pft -DCONV=pft_frames_convert -DWORK=dir -DSRC=host_tools -DMODE=... -P input_forms.cmake
# MODE setup: simulate and convert (the fixture); tbd, tbd_ir: same tracks from every form;
# raw_errors: refused --raw specs and truncated dumps; sim_formats: tbd_ir pgm and raw output
# read back alike; real_frames: a folder background with a YOLO label (and the low-false-rate
# twin of real_frames.json on it); lost_frames: pft sim
# with lost frames, read back with the gaps in seq.
cmake_policy(SET CMP0057 NEW) # if(IN_LIST)
include(${CMAKE_CURRENT_LIST_DIR}/run_ok.cmake)

# the command must exit with status 2 and print `pft: error: <regex>` on stderr
function(expect_refused regex)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 2)
    message(FATAL_ERROR "expected exit status 2, got ${rc}: ${ARGN}\n${out}\n${err}")
  endif()
  if(NOT err MATCHES "pft: error: ${regex}")
    message(FATAL_ERROR "stderr does not match 'pft: error: ${regex}':\n${err}")
  endif()
  message(STATUS "refused as expected: ${err}")
endfunction()

# `pft run` output `out` and its tracks.csv in `dir`: `nfiles` frames read, no track row at a
# lost frame (list `lost`), and the last row's frame past the file count (the gaps were seen:
# frames counted one by one would end at the number of files); sets maxf in the caller
function(check_lost_run who out dir nfiles lost)
  if(NOT out MATCHES "${nfiles} frames, [0-9]+ skipped")
    message(FATAL_ERROR "${who}: expected ${nfiles} frames read and the lost ones skipped:\n${out}")
  endif()
  file(STRINGS ${dir}/tracks.csv rows)
  list(REMOVE_AT rows 0)
  set(last 0)
  foreach(r ${rows})
    string(REGEX MATCH "^[0-9]+" f "${r}")
    if(f IN_LIST lost)
      message(FATAL_ERROR "${who}: a track row at lost frame ${f}")
    endif()
    if(f GREATER last)
      set(last ${f})
    endif()
  endforeach()
  if(NOT last GREATER nfiles)
    message(FATAL_ERROR "${who}: last track frame ${last} is not past the ${nfiles} files: gaps not seen")
  endif()
  set(maxf ${last} PARENT_SCOPE)
endfunction()

function(same_tracks ref)
  foreach(f ${ARGN})
    execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${ref} ${f} RESULT_VARIABLE rc)
    if(NOT rc EQUAL 0)
      file(READ ${ref} a)
      file(READ ${f} b)
      message(FATAL_ERROR "${f} differs from ${ref}\n--- ${ref}\n${a}\n--- ${f}\n${b}")
    endif()
  endforeach()
endfunction()

set(two "${SRC}/scenarios/tbd/two_case1.json")
set(small "${SRC}/tests/tbd_ir_small.json")

if(MODE STREQUAL "setup")
  file(REMOVE_RECURSE ${WORK})
  file(MAKE_DIRECTORY ${WORK})
  foreach(k tbd tbd_ir)
    if(k STREQUAL "tbd")
      run_ok(${PFT} sim --scenario ${two} --out ${WORK}/${k}_sim -q)
    else()
      run_ok(${PFT} sim --scenario ${small} --out ${WORK}/${k}_sim -q)
    endif()
    # the same frames without the sidecar: PGM copied as they are, PNG and TIFF re-encoded
    file(GLOB frames ${WORK}/${k}_sim/frame_*.pgm)
    file(COPY ${frames} DESTINATION ${WORK}/${k}_pgm)
    run_ok(${CONV} ${WORK}/${k}_sim ${WORK}/${k}_png png)
    run_ok(${CONV} ${WORK}/${k}_sim ${WORK}/${k}_tiff tiff)
    file(MAKE_DIRECTORY ${WORK}/${k}_raw)
    run_ok(${CONV} ${WORK}/${k}_sim ${WORK}/${k}_raw/le.u16 raw)
    run_ok(${CONV} ${WORK}/${k}_sim ${WORK}/${k}_raw/be.u16 raw be skip=512)
    run_ok(${CONV} ${WORK}/${k}_sim ${WORK}/${k}_raw/cut.u16 raw cut=100)
  endforeach()
  message(STATUS "input forms written to ${WORK}")

elseif(MODE STREQUAL "tbd")
  # the shipped two-target case from 5 forms with no sidecar: sigma estimated, same tracks
  set(outs "")
  foreach(form pgm png tiff)
    run_ok(${PFT} run --sequence ${WORK}/tbd_${form} --scenario ${two} --truth ${WORK}/tbd_sim/truth.csv
           --no-video --out ${WORK}/run_tbd_${form})
    if(NOT run_out MATCHES "no sidecar; estimated from the first 8 frames: background [0-9.]+, noise sigma [0-9.]+")
      message(FATAL_ERROR "${form}: the estimated sigma is not printed:\n${run_out}")
    endif()
    list(APPEND outs ${WORK}/run_tbd_${form}/tracks.csv)
    set(out_${form} "${run_out}")
  endforeach()
  run_ok(${PFT} run --sequence ${WORK}/tbd_raw/le.u16 --raw 20x20 --scenario ${two} --no-video -q
         --out ${WORK}/run_tbd_raw_le)
  run_ok(${PFT} run --sequence ${WORK}/tbd_raw/be.u16 --raw 20x20:16:be:skip=512 --scenario ${two}
         --no-video -q --out ${WORK}/run_tbd_raw_be)
  same_tracks(${WORK}/run_tbd_pgm/tracks.csv ${outs} ${WORK}/run_tbd_raw_le/tracks.csv
              ${WORK}/run_tbd_raw_be/tracks.csv)
  # 16-bit TIFF: both targets found (before the fix: 6 tracks, all false)
  string(REGEX MATCH "Tracks found: [0-9]+" n "${out_tiff}")
  string(REGEX MATCHALL "-> target T[12]" hits "${out_tiff}")
  list(REMOVE_DUPLICATES hits)
  list(LENGTH hits nhit)
  if(NOT nhit EQUAL 2)
    message(FATAL_ERROR "16-bit TIFF: expected tracks on both targets:\n${out_tiff}")
  endif()
  message(STATUS "same tracks from PGM, PNG, TIFF, raw le and raw be; TIFF: ${n}, both targets")

elseif(MODE STREQUAL "tbd_ir")
  # no scenario and no sidecar: the IR pipeline with its default settings, same tracks
  set(outs "")
  foreach(form pgm png tiff)
    run_ok(${PFT} run --sequence ${WORK}/tbd_ir_${form} --no-video --out ${WORK}/run_ir_${form})
    if(NOT run_out MATCHES "72, 24 frames, 14 bits")
      message(FATAL_ERROR "${form}: expected 24 frames of 14 bits:\n${run_out}")
    endif()
    list(APPEND outs ${WORK}/run_ir_${form}/tracks.csv)
  endforeach()
  run_ok(${PFT} run --sequence ${WORK}/tbd_ir_raw/le.u16 --raw 96x72:14 --no-video -q --out ${WORK}/run_ir_raw_le)
  run_ok(${PFT} run --sequence ${WORK}/tbd_ir_raw/be.u16 --raw 96x72:14:be:skip=512 --no-video -q
         --out ${WORK}/run_ir_raw_be)
  same_tracks(${WORK}/run_ir_pgm/tracks.csv ${outs} ${WORK}/run_ir_raw_le/tracks.csv ${WORK}/run_ir_raw_be/tracks.csv)
  # and the pft sim directory itself (sidecar: its scenario, truth and seed)
  run_ok(${PFT} run --sequence ${WORK}/tbd_ir_sim --no-video --out ${WORK}/run_ir_sim)
  if(NOT run_out MATCHES "Versus truth")
    message(FATAL_ERROR "the pft sim directory's truth was not used:\n${run_out}")
  endif()
  # pft demo --sequence without --scenario takes the sidecar's scenario, as pft run does (before:
  # the tbd kind's two-target settings, refused on the tbd_ir truth file)
  run_ok(${PFT} demo --sequence ${WORK}/tbd_ir_sim --out ${WORK}/demo_ir_sim)
  if(NOT run_out MATCHES "Versus truth" OR NOT run_out MATCHES "DBT tracks found")
    message(FATAL_ERROR "pft demo --sequence: not the IR pipeline on the sidecar's scenario:\n${run_out}")
  endif()
  same_tracks(${WORK}/run_ir_sim/tracks.csv ${WORK}/demo_ir_sim/tracks.csv)
  message(STATUS "same tracks from PGM, PNG, TIFF, raw le and raw be")

elseif(MODE STREQUAL "raw_errors")
  set(d ${WORK}/tbd_raw)
  expect_refused("[^\n]*le.u16: --raw 20x: field H: expected a number"
                 ${PFT} run --sequence ${d}/le.u16 --raw 20x --scenario ${two} --no-video --out ${WORK}/bad)
  expect_refused("[^\n]*le.u16: --raw 20\\*20: field WxH: expected WIDTHxHEIGHT"
                 ${PFT} run --sequence ${d}/le.u16 --raw 20*20 --scenario ${two} --no-video --out ${WORK}/bad)
  expect_refused("[^\n]*le.u16: --raw 20x20:17: field bits: 17 is outside 1..16"
                 ${PFT} run --sequence ${d}/le.u16 --raw 20x20:17 --scenario ${two} --no-video --out ${WORK}/bad)
  expect_refused("[^\n]*le.u16: --raw 20x20:little: field 2 \\(\"little\"\\)"
                 ${PFT} run --sequence ${d}/le.u16 --raw 20x20:little --scenario ${two} --no-video --out ${WORK}/bad)
  expect_refused("[^\n]*le.u16: --raw 20x20:skip=x: field skip: expected a byte count"
                 ${PFT} run --sequence ${d}/le.u16 --raw 20x20:skip=x --scenario ${two} --no-video --out ${WORK}/bad)
  expect_refused("[^\n]*le.u16: --raw 0x20: field W: 0 is outside 1..65535"
                 ${PFT} run --sequence ${d}/le.u16 --raw 0x20 --scenario ${two} --no-video --out ${WORK}/bad)
  # truncated dumps: a cut file, a wrong geometry, a skip beyond the end
  expect_refused("[^\n]*cut.u16: --raw 20x20: field WxH: [0-9]+ bytes after skip=0 are not a whole number of 20x20 u16 frames"
                 ${PFT} run --sequence ${d}/cut.u16 --raw 20x20 --scenario ${two} --no-video --out ${WORK}/bad)
  expect_refused("[^\n]*le.u16: --raw 21x20: field WxH: "
                 ${PFT} run --sequence ${d}/le.u16 --raw 21x20 --scenario ${two} --no-video --out ${WORK}/bad)
  expect_refused("[^\n]*le.u16: --raw 20x20:skip=99999999: field skip: 99999999 bytes of header, but the file has only"
                 ${PFT} run --sequence ${d}/le.u16 --raw 20x20:skip=99999999 --scenario ${two} --no-video --out ${WORK}/bad)
  expect_refused("[^\n]*le.u16: looks like a headerless dump: give its geometry with --raw"
                 ${PFT} run --sequence ${d}/le.u16 --scenario ${two} --no-video --out ${WORK}/bad)
  expect_refused("[^\n]*no_such.u16: no such file or directory"
                 ${PFT} run --sequence ${d}/no_such.u16 --raw 20x20 --scenario ${two} --no-video --out ${WORK}/bad)

elseif(MODE STREQUAL "sim_formats")
  # tbd_ir frames written as raw u16 with a sidecar read back as the PGM ones
  run_ok(${PFT} sim --scenario ${small} --format raw --out ${WORK}/ir_sim_raw -q)
  run_ok(${PFT} run --sequence ${WORK}/ir_sim_raw --no-video -q --out ${WORK}/run_ir_sim_raw)
  run_ok(${PFT} run --sequence ${WORK}/tbd_ir_sim --no-video -q --out ${WORK}/run_ir_sim_pgm)
  same_tracks(${WORK}/run_ir_sim_pgm/tracks.csv ${WORK}/run_ir_sim_raw/tracks.csv)
  file(READ ${WORK}/ir_sim_raw/truth.csv t)
  if(NOT t MATCHES "^frame,id,x,y,snr_db,kind\n[0-9]+,[0-9]+,[-0-9.e]+,[-0-9.e]+,12,injected\n")
    message(FATAL_ERROR "truth.csv is not frame,id,x,y,snr_db,kind:\n${t}")
  endif()

elseif(MODE STREQUAL "real_frames")
  # a folder of "real" backgrounds: one 8-bit PNG (a simulated frame >> 6) with a YOLO label
  file(MAKE_DIRECTORY ${WORK}/bg)
  run_ok(${CONV} ${WORK}/tbd_ir_sim/frame_0001.pgm ${WORK}/bg/img_01.png png8)
  file(WRITE ${WORK}/bg/img_01.txt "0 0.5 0.25 0.03 0.04\n")
  run_ok(${PFT} sim --scenario ${SRC}/scenarios/tbd_ir/real_frames.json --backgrounds ${WORK}/bg
         --out ${WORK}/ir_real -q)
  file(READ ${WORK}/ir_real/truth.csv t)
  # the labelled object moves with the scene: 0-based centre (47.5, 17.5) of the image
  # minus the platform position
  if(NOT t MATCHES ",1001,[-0-9.e]+,[-0-9.e]+,[-0-9.e]*,labelled\n")
    message(FATAL_ERROR "no labelled object in truth.csv:\n${t}")
  endif()
  expect_refused("[^\n]*no_such_dir: background folder not found"
                 ${PFT} sim --scenario ${SRC}/scenarios/tbd_ir/real_frames.json --backgrounds ${WORK}/no_such_dir
                 --out ${WORK}/bad -q)
  # its low-false-rate twin (docs/tuning.md, IR operating points) simulates the same sequence
  # (the pairing of the results pages rests on it) and `pft run` accepts its tracker block
  set(low ${SRC}/scenarios/tbd_ir/real_frames_low_false_rate.json)
  run_ok(${PFT} sim --scenario ${low} --backgrounds ${WORK}/bg --out ${WORK}/ir_real_low -q)
  file(GLOB fa RELATIVE ${WORK}/ir_real ${WORK}/ir_real/frame_*.pgm)
  file(GLOB fb RELATIVE ${WORK}/ir_real_low ${WORK}/ir_real_low/frame_*.pgm)
  list(LENGTH fa na)
  if(NOT fa STREQUAL fb OR na LESS 2)
    message(FATAL_ERROR "real_frames_low_false_rate.json: not the frames of real_frames.json (${na})")
  endif()
  foreach(f ${fa} truth.csv)
    execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/ir_real/${f} ${WORK}/ir_real_low/${f}
                    RESULT_VARIABLE diff)
    if(NOT diff EQUAL 0)
      message(FATAL_ERROR "real_frames_low_false_rate.json simulates another ${f} than real_frames.json")
    endif()
  endforeach()
  run_ok(${PFT} run --scenario ${low} --sequence ${WORK}/ir_real_low --out ${WORK}/run_real_low --no-video -q)
  if(NOT EXISTS ${WORK}/run_real_low/tracks.csv)
    message(FATAL_ERROR "pft run of real_frames_low_false_rate.json wrote no tracks.csv")
  endif()
  # the twin for a shaded sensor (vignetting 0.2, bg_gate_local): simulated and run on the same
  # fixture; its frames are not real_frames.json's (the shading)
  set(shaded ${SRC}/scenarios/tbd_ir/real_frames_shaded_low_false_rate.json)
  run_ok(${PFT} sim --scenario ${shaded} --backgrounds ${WORK}/bg --out ${WORK}/ir_real_shaded -q)
  list(GET fa 0 f0)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/ir_real/${f0} ${WORK}/ir_real_shaded/${f0}
                  RESULT_VARIABLE diff)
  if(diff EQUAL 0)
    message(FATAL_ERROR "real_frames_shaded_low_false_rate.json: ${f0} has no shading")
  endif()
  run_ok(${PFT} run --scenario ${shaded} --sequence ${WORK}/ir_real_shaded --out ${WORK}/run_real_shaded --no-video -q)
  if(NOT EXISTS ${WORK}/run_real_shaded/tracks.csv)
    message(FATAL_ERROR "pft run of real_frames_shaded_low_false_rate.json wrote no tracks.csv")
  endif()
elseif(MODE STREQUAL "lost_frames")
  # pft sim loses frames as pft eval does (eval.drop_prob, the same per seed): no file for
  # them, listed in the sidecar; pft run, from the sim directory (port/file pattern) and from
  # a plain PGM folder (OpenCV, numbers in the names), sees them as gaps in seq: the tracks'
  # frame numbers are the files' numbers, never a lost one
  set(drop "${SRC}/scenarios/tbd/two_case1_drop10_use.json")
  run_ok(${PFT} sim --scenario ${drop} --seed 3 --out ${WORK}/lost_sim -q)
  file(READ ${WORK}/lost_sim/sequence.json side)
  string(JSON lost GET "${side}" lost_frames)
  string(JSON nlost LENGTH "${side}" lost_frames)
  if(nlost LESS 2)
    message(FATAL_ERROR "expected lost frames in the sidecar: ${lost}")
  endif()
  set(lost_nums "")
  math(EXPR last "${nlost} - 1")
  foreach(i RANGE ${last})
    string(JSON n GET "${side}" lost_frames ${i})
    list(APPEND lost_nums ${n})
    string(LENGTH "000${n}" len)
    math(EXPR from "${len} - 4")
    string(SUBSTRING "000${n}" ${from} 4 n4)
    if(EXISTS ${WORK}/lost_sim/frame_${n4}.pgm)
      message(FATAL_ERROR "lost frame ${n} has a file")
    endif()
  endforeach()
  file(GLOB frames ${WORK}/lost_sim/frame_*.pgm)
  list(LENGTH frames nfiles)
  file(COPY ${frames} DESTINATION ${WORK}/lost_pgm)
  run_ok(${PFT} run --sequence ${WORK}/lost_sim --no-video --out ${WORK}/run_lost_sim)
  set(out_sim "${run_out}")
  run_ok(${PFT} run --sequence ${WORK}/lost_pgm --scenario ${drop} --truth ${WORK}/lost_sim/truth.csv
         --no-video --out ${WORK}/run_lost_pgm)
  set(out_pgm "${run_out}")
  foreach(form sim pgm)
    check_lost_run(${form} "${out_${form}}" ${WORK}/run_lost_${form} ${nfiles} "${lost_nums}")
  endforeach()
  message(STATUS "lost frames ${lost}: no files; both readers see the gaps (last track frame ${maxf} of ${nfiles} files)")
  # kind tbd_ir: the same for the IR pipeline (eval.drop_prob and eval.drop_frames 20-22)
  set(irdrop "${SRC}/scenarios/tbd_ir/clear_sky_128x96_drop10.json")
  run_ok(${PFT} sim --scenario ${irdrop} --seed 3 --out ${WORK}/ir_lost_sim -q)
  file(READ ${WORK}/ir_lost_sim/sequence.json side)
  string(JSON nlost LENGTH "${side}" lost_frames)
  set(ir_lost "")
  math(EXPR last "${nlost} - 1")
  foreach(i RANGE ${last})
    string(JSON n GET "${side}" lost_frames ${i})
    list(APPEND ir_lost ${n})
  endforeach()
  foreach(n 20 21 22)
    if(NOT n IN_LIST ir_lost)
      message(FATAL_ERROR "tbd_ir: listed lost frame ${n} is not in the sidecar's lost_frames: ${ir_lost}")
    endif()
    if(EXISTS ${WORK}/ir_lost_sim/frame_00${n}.pgm)
      message(FATAL_ERROR "tbd_ir: lost frame ${n} has a file")
    endif()
  endforeach()
  file(GLOB irframes ${WORK}/ir_lost_sim/frame_*.pgm)
  list(LENGTH irframes nir)
  math(EXPR expect "60 - ${nlost}")
  if(NOT nir EQUAL expect)
    message(FATAL_ERROR "tbd_ir: ${nir} files, expected 60 - ${nlost} lost")
  endif()
  run_ok(${PFT} run --sequence ${WORK}/ir_lost_sim --no-video --out ${WORK}/run_ir_lost)
  check_lost_run(tbd_ir "${run_out}" ${WORK}/run_ir_lost ${nir} "${ir_lost}")
  # pft eval loses the same frames in memory and says how many per run
  run_ok(${PFT} eval --scenario ${irdrop} --runs 1 --seed 3 --threads 1 --out ${WORK}/ir_lost_eval -q)
  file(READ ${WORK}/ir_lost_eval/summary.json sum)
  string(JSON evlost GET "${sum}" per_run 0 lost_frames)
  if(NOT evlost EQUAL nlost)
    message(FATAL_ERROR "tbd_ir: pft eval lost ${evlost} frames of seed 3, pft sim ${nlost}")
  endif()
  # raw output cannot show a lost frame: refused before anything is written
  expect_refused("[^\n]*clear_sky_128x96_drop10.json: eval.drop_prob / eval.drop_frames lose frames"
                 ${PFT} sim --scenario ${irdrop} --format raw --out ${WORK}/ir_lost_raw -q)
  message(STATUS "tbd_ir lost frames ${ir_lost}: no files, gaps seen by pft run (last track frame ${maxf} of ${nir} files), pft eval the same")
elseif(MODE STREQUAL "bit_depth")
  # kind tbd_ir's bit depth (docs/host_tools.md, "Bit depth"): a declared depth is honoured,
  # a detected one covers only the first 8 frames, and a later frame with pixels above it is
  # refused (before: clipped and masked as saturated without a word)
  set(d ${WORK}/bits)
  file(REMOVE_RECURSE ${d})
  file(MAKE_DIRECTORY ${d})
  # the 14-bit sim frames (saturated pixels at 16383) with the first 8 shifted to 12 bits
  run_ok(${CONV} ${WORK}/tbd_ir_sim ${d}/dim_head png shift=2 first=8)
  expect_refused("run: [^\n]*dim_head: stopped at input frame 9: frame 9 has [0-9]+ pixel\\(s\\) above 12 bits \\(largest 16383 > 4095; the bit depth was detected from the largest value of the first 8 frame\\(s\\)\\)[^\n]*--bits"
                 ${PFT} run --sequence ${d}/dim_head --no-video --out ${d}/run_dim)
  run_ok(${PFT} run --sequence ${d}/dim_head --bits 14 --no-video --out ${d}/run_dim14)
  if(NOT run_out MATCHES "bit depth 14 given by --bits" OR NOT run_out MATCHES "24 frames, 0 skipped")
    message(FATAL_ERROR "--bits 14: expected 24 frames at 14 bits:\n${run_out}")
  endif()
  # refused at frame 1: no frame processed, so no overlay.avi (before: a video of 0 frames)
  expect_refused("run: [^\n]*dim_head: stopped at input frame 1: frame 1 has [0-9]+ pixel\\(s\\) above 10 bits [^\n]*given by --bits"
                 ${PFT} run --sequence ${d}/dim_head --bits 10 --out ${d}/run_dim10)
  file(GLOB left ${d}/run_dim10/*)
  if(left)
    message(FATAL_ERROR "a run refused at its first frame left files: ${left}")
  endif()
  # a dump of 12-bit values declared 14 bits stays 14 bits (before: lowered to 12); without
  # bits in the spec the depth is detected
  run_ok(${CONV} ${WORK}/tbd_ir_sim ${d}/all12.u16 raw shift=2)
  run_ok(${PFT} run --sequence ${d}/all12.u16 --raw 96x72:14 --no-video --frames 2 --out ${d}/run_raw14)
  if(NOT run_out MATCHES "96x72, 24 frames, 14 bits" OR NOT run_out MATCHES "bit depth 14 declared by the input")
    message(FATAL_ERROR "--raw 96x72:14: the declared 14 bits were not kept:\n${run_out}")
  endif()
  run_ok(${PFT} run --sequence ${d}/all12.u16 --raw 96x72 --no-video --frames 2 --out ${d}/run_raw)
  if(NOT run_out MATCHES "96x72, 24 frames, 12 bits" OR NOT run_out MATCHES "bit depth 12 detected")
    message(FATAL_ERROR "--raw 96x72: expected 12 bits detected:\n${run_out}")
  endif()
  # a PGM's maxval (16383) declares 14 bits
  run_ok(${PFT} run --sequence ${WORK}/tbd_ir_pgm --no-video --frames 2 --out ${d}/run_pgm)
  if(NOT run_out MATCHES "bit depth 14 declared by the input")
    message(FATAL_ERROR "PGM maxval 16383: expected 14 bits declared:\n${run_out}")
  endif()
  # only kind tbd_ir takes --bits
  expect_refused("--bits 14: only kind tbd_ir takes a bit depth \\(this is kind tbd"
                 ${PFT} run --sequence ${WORK}/tbd_pgm --scenario ${two} --bits 14 --no-video --out ${d}/run_tbd)
  message(STATUS "bit depth: declared kept, detected checked on every frame, --bits honoured")
elseif(MODE STREQUAL "eval_backgrounds")
  # pft eval of a folder scenario on backgrounds of other sizes and depths than 384x288 8-bit:
  # a 16-bit PGM (96x72, 14-bit values) and an 8-bit JPEG with a YOLO label; the summary keeps
  # the header every kind's summary starts with (docs/host_tools.md, "eval summary")
  set(d ${WORK}/eval_bg)
  file(REMOVE_RECURSE ${d})
  file(MAKE_DIRECTORY ${d}/bg)
  file(COPY ${WORK}/tbd_ir_sim/frame_0001.pgm DESTINATION ${d}/bg)
  run_ok(${CONV} ${WORK}/tbd_ir_sim/frame_0002.pgm ${d}/bg/frame_0002.jpg png8)
  file(WRITE ${d}/bg/frame_0002.txt "0 0.5 0.5 0.04 0.05\n")
  run_ok(${PFT} eval --scenario ${SRC}/scenarios/tbd_ir/real_frames.json --backgrounds ${d}/bg
         --runs 2 --threads 1 --particles 2000 --out ${d}/ev -q)
  file(READ ${d}/ev/summary.json sum)
  foreach(key tool tool_version git_describe kind scenario scenario_file scenario_hash description tag
          numeric runs base_seed seeds threads command_line timing averaged by_kind per_run dbt)
    string(JSON t ERROR_VARIABLE e TYPE "${sum}" ${key})
    if(e)
      message(FATAL_ERROR "summary.json has no ${key} (the header of every kind's summary)")
    endif()
  endforeach()
  string(JSON cpu GET "${sum}" timing cpu_s)
  string(JSON hash GET "${sum}" scenario_hash)
  string(JSON b0 GET "${sum}" per_run 0 background)
  string(JSON b1 GET "${sum}" per_run 1 background)
  string(JSON np GET "${sum}" tracker particles)
  # the tracker record also lists the block's other fields as set (real_frames.json: bg_stale_reinit 32)
  string(JSON stale ERROR_VARIABLE e2 GET "${sum}" tracker bg_stale_reinit)
  if(e2 OR NOT stale EQUAL 32)
    message(FATAL_ERROR "summary: tracker.bg_stale_reinit '${stale}' (${e2}), expected 32 as real_frames.json sets it")
  endif()
  string(JSON lab ERROR_VARIABLE e GET "${sum}" by_kind labelled targets)
  if(NOT hash MATCHES "^fnv1a64:" OR NOT b0 MATCHES "frame_0001.pgm$" OR NOT b1 MATCHES "frame_0002.jpg$"
     OR NOT np EQUAL 2000 OR e OR NOT lab EQUAL 1)
    message(FATAL_ERROR "summary: hash ${hash}, backgrounds ${b0} ${b1}, particles ${np}, labelled ${lab} ${e}")
  endif()
  message(STATUS "eval on a 16-bit PGM and an 8-bit JPEG background: header complete (cpu_s ${cpu}), label read")
  # a 16-bit PNG does not say its bit depth (a PGM does, by its maxval): without
  # background.scale one whose values leave the top bit free is refused, not scaled by
  # 2^(14 - 16); with "scale": 1 it is read as frames of the sensor's depth
  run_ok(${CONV} ${WORK}/tbd_ir_sim ${d}/png16 png)
  file(MAKE_DIRECTORY ${d}/bg16)
  file(COPY ${d}/png16/frame_0001.png DESTINATION ${d}/bg16)
  expect_refused("[^\n]*frame_0001.png: a 16-bit image whose values fit in 14 bits \\(largest 16383\\)[^\n]*give background.scale"
                 ${PFT} sim --scenario ${SRC}/scenarios/tbd_ir/real_frames.json --backgrounds ${d}/bg16 --out ${d}/sim16 -q)
  if(EXISTS ${d}/sim16/sequence.json)
    message(FATAL_ERROR "a refused background left a sequence.json")
  endif()
  # the same frame as a PGM of maxval 65535 (as OpenCV writes it): refused alike
  run_ok(${CONV} ${d}/bg16 ${d}/bg16pgm pgm)
  expect_refused("[^\n]*frame_0001.pgm: a 16-bit image whose values fit in 14 bits"
                 ${PFT} sim --scenario ${SRC}/scenarios/tbd_ir/real_frames.json --backgrounds ${d}/bg16pgm --out ${d}/sim16p -q)
  file(READ ${SRC}/scenarios/tbd_ir/real_frames.json sc)
  string(JSON sc SET "${sc}" background scale 1)
  file(WRITE ${d}/scale1.json "${sc}")
  run_ok(${PFT} sim --scenario ${d}/scale1.json --backgrounds ${d}/bg16 --out ${d}/sim16s -q)
else()
  message(FATAL_ERROR "unknown MODE ${MODE}")
endif()
