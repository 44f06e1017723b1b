# The "tsa" kind of the host tools (TSA-AK visual tracker, formerly kind "vis"): semi-synthetic
# airborne sequences over the opencv-doc aerial photographs, pftrack's TSA-AK / NCV / TS against
# OpenCV's KCF, CSRT, MOSSE and MIL (contrib tracking module, when found), and `pft track`.
# Included from host_tools/CMakeLists.txt after the `pft` target exists.
file(GLOB PFT_HOST_TSA CONFIGURE_DEPENDS "${CMAKE_CURRENT_LIST_DIR}/*.cpp")
target_sources(pft PRIVATE ${PFT_HOST_TSA})
find_package(OpenCV QUIET COMPONENTS tracking video)
if(OpenCV_tracking_FOUND OR TARGET opencv_tracking)
  target_link_libraries(pft PRIVATE opencv_tracking opencv_video)
  target_compile_definitions(pft PRIVATE PFT_HAVE_CV_TRACKING=1)
else()
  message(STATUS "pftrack host tools: OpenCV tracking (contrib) not found; bench tsa runs without KCF/CSRT/MOSSE/MIL")
endif()

if(PFT_BUILD_TESTS)
  add_test(NAME host_tsa_selftest COMMAND pft selftest --kind tsa)
  set_tests_properties(host_tsa_selftest PROPERTIES LABELS "host"
                       PASS_REGULAR_EXPRESSION "tsa selftest: passed" FAIL_REGULAR_EXPRESSION "FAIL")
  file(GLOB PFT_TSA_SCENARIOS CONFIGURE_DEPENDS "${CMAKE_CURRENT_LIST_DIR}/../scenarios/tsa/*.json")
  foreach(sc ${PFT_TSA_SCENARIOS})
    get_filename_component(n ${sc} NAME_WE)
    add_test(NAME host_tsa_scenario_${n} COMMAND pft bench --scenario ${sc} --frames 5 --runs 1 -q)
    set_tests_properties(host_tsa_scenario_${n} PROPERTIES LABELS "host")
  endforeach()
  # a scenario written with the earlier kind name "vis" still runs (with a note on stderr)
  add_test(NAME host_tsa_kind_alias_vis
           COMMAND pft bench --scenario ${CMAKE_CURRENT_LIST_DIR}/vis_kind.json --frames 2 --runs 1 -q)
  set_tests_properties(host_tsa_kind_alias_vis PROPERTIES LABELS "host" FAIL_REGULAR_EXPRESSION "error"
                       PASS_REGULAR_EXPRESSION "scenario kind \"vis\" is now called \"tsa\"")
endif()
# Campaigns: 4 shards + pft merge give the single run's summary (host_tools/tests/shard_merge.cmake).
if(PFT_BUILD_TESTS AND COMMAND pft_shard_merge_test)
  pft_shard_merge_test(tsa ${CMAKE_CURRENT_LIST_DIR}/tests/tsa_small.json 8)
endif()
# `pft track` goes through the kind registry: a short simulated sequence tracked from a box, and
# its errors (exit 2, "pft: error: ...").
if(PFT_BUILD_TESTS)
  add_test(NAME host_tsa_track_sim
           COMMAND pft sim --scenario ${CMAKE_CURRENT_LIST_DIR}/tests/tsa_small.json --seed 1
                   --out ${CMAKE_CURRENT_BINARY_DIR}/tsa_track_sim -q)
  set_tests_properties(host_tsa_track_sim PROPERTIES LABELS "host" FIXTURES_SETUP tsa_track_seq)
  add_test(NAME host_tsa_track
           COMMAND pft track --sequence ${CMAKE_CURRENT_BINARY_DIR}/tsa_track_sim --box 524,239,25,30
                   --frames 8 --out ${CMAKE_CURRENT_BINARY_DIR}/tsa_track_out)
  set_tests_properties(host_tsa_track PROPERTIES LABELS "host" FIXTURES_REQUIRED tsa_track_seq
                       PASS_REGULAR_EXPRESSION "8 frames 640x480, tsa: " FAIL_REGULAR_EXPRESSION "error")
  foreach(case
      "no_region|give exactly one of --box, --polygon, --init|track;--sequence;x"
      "other_kind|kind \"pte\" has no `track` command|track;--sequence;x;--box;1,1,8,8;--scenario;${CMAKE_CURRENT_LIST_DIR}/../pte/tests/pte_small.json"
      "bad_motion|--motion: .*not in|track;--sequence;x;--box;1,1,8,8;--motion;cv")
    string(REPLACE "|" ";" parts "${case}")
    list(GET parts 0 name)
    list(GET parts 1 expect)
    list(SUBLIST parts 2 -1 args)
    add_test(NAME host_tsa_track_error_${name}
             COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:pft>;${args}" "-DEXPECT=${expect}"
                     -P ${CMAKE_CURRENT_LIST_DIR}/../tests/expect_error.cmake)
    set_tests_properties(host_tsa_track_error_${name} PROPERTIES LABELS "host")
  endforeach()
endif()
