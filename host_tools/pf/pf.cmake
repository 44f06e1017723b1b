# The pf module of the host tools (kinds "pf_bearings" and "pf_tbd"; the old names "bearings"
# and "apf_tbd" still select them): sources compiled into
# `pft` (they register themselves), self-test and scenario smoke tests. Included from
# host_tools/CMakeLists.txt after the `pft` target exists.
file(GLOB PFT_HOST_PF CONFIGURE_DEPENDS "${CMAKE_CURRENT_LIST_DIR}/*.cpp")
target_sources(pft PRIVATE ${PFT_HOST_PF})

if(PFT_BUILD_TESTS)
  add_test(NAME host_pf_bearings_selftest COMMAND pft selftest --kind pf_bearings)
  set_tests_properties(host_pf_bearings_selftest PROPERTIES LABELS "host"
                       PASS_REGULAR_EXPRESSION "pf_bearings selftest: passed" FAIL_REGULAR_EXPRESSION "FAIL")
  # the old kind name still selects the module, with a note
  add_test(NAME host_pf_kind_alias COMMAND pft bench --scenario ${CMAKE_CURRENT_LIST_DIR}/tests/old_kind_bearings.json
                                           --frames 3 --runs 1 --particles 50 -q)
  set_tests_properties(host_pf_kind_alias PROPERTIES LABELS "host"
                       PASS_REGULAR_EXPRESSION "kind \"bearings\" is now called \"pf_bearings\"" FAIL_REGULAR_EXPRESSION "FAIL")
  file(GLOB PFT_PF_SCENARIOS CONFIGURE_DEPENDS "${CMAKE_CURRENT_LIST_DIR}/../scenarios/pf/*.json")
  foreach(sc ${PFT_PF_SCENARIOS})
    get_filename_component(n ${sc} NAME_WE)
    add_test(NAME host_pf_scenario_${n} COMMAND pft bench --scenario ${sc} --frames 3 --runs 1 --particles 50 -q)
    set_tests_properties(host_pf_scenario_${n} PROPERTIES LABELS "host")
  endforeach()
endif()

# Bad input: a clear message naming the field (pft_expect_error comes from host_tools/CMakeLists.txt).
if(PFT_BUILD_TESTS AND COMMAND pft_expect_error)
  pft_expect_error(pf_bad_engine "filters\\[0\\].engine" eval --scenario ${CMAKE_CURRENT_LIST_DIR}/tests/bad_engine.json)
  pft_expect_error(pf_bad_match "match_time_of: no filter labelled" eval --scenario ${CMAKE_CURRENT_LIST_DIR}/tests/bad_match.json)
endif()

# Campaigns: 4 shards + pft merge give the single run's summary (host_tools/tests/shard_merge.cmake).
if(PFT_BUILD_TESTS AND COMMAND pft_shard_merge_test)
  pft_shard_merge_test(pf_tbd ${CMAKE_CURRENT_LIST_DIR}/tests/pf_tbd_small.json 8)
  pft_shard_merge_test(pf_bearings ${CMAKE_CURRENT_LIST_DIR}/tests/bearings_small.json 8)
endif()
