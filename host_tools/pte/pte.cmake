# The pte module of the host tools (kind "pte", formerly "radar": PTE-TBD, DP-TBD and Kalman
# DBT on range-time images): sources compiled into `pft` (they register themselves), self-test
# and scenario smoke tests. Included from host_tools/CMakeLists.txt after the `pft` target exists.
file(GLOB PFT_HOST_PTE CONFIGURE_DEPENDS "${CMAKE_CURRENT_LIST_DIR}/*.cpp")
target_sources(pft PRIVATE ${PFT_HOST_PTE})

if(PFT_BUILD_TESTS)
  add_test(NAME host_pte_selftest COMMAND pft selftest --kind pte)
  set_tests_properties(host_pte_selftest PROPERTIES LABELS "host"
                       PASS_REGULAR_EXPRESSION "pte selftest: passed" FAIL_REGULAR_EXPRESSION "FAIL")
  # Every shipped scenario parses and simulates (no threshold Monte Carlo).
  file(GLOB PFT_PTE_SCENARIOS CONFIGURE_DEPENDS "${CMAKE_CURRENT_LIST_DIR}/../scenarios/pte/*.json")
  foreach(sc ${PFT_PTE_SCENARIOS})
    get_filename_component(n ${sc} NAME_WE)
    add_test(NAME host_pte_scenario_${n}
             COMMAND pft sim --scenario ${sc} --out ${CMAKE_CURRENT_BINARY_DIR}/pte_sim_${n} -q)
    set_tests_properties(host_pte_scenario_${n} PROPERTIES LABELS "host")
  endforeach()
  # The three methods run end to end on the air scenario (threshold Monte Carlo included).
  add_test(NAME host_pte_bench COMMAND pft bench --scenario ${CMAKE_CURRENT_LIST_DIR}/../scenarios/pte/air_turn_6db.json
                                       --frames 40 -q)
  set_tests_properties(host_pte_bench PROPERTIES LABELS "host")
  # A scenario written with the former kind name "radar" still runs, with a note on stderr.
  add_test(NAME host_pte_kind_alias
           COMMAND ${CMAKE_COMMAND} -DPFT=$<TARGET_FILE:pft>
                   -DSCENARIO=${CMAKE_CURRENT_LIST_DIR}/../scenarios/pte/air_turn_6db.json
                   -DOUT=${CMAKE_CURRENT_BINARY_DIR}/pte_kind_alias -P ${CMAKE_CURRENT_LIST_DIR}/kind_alias_test.cmake)
  set_tests_properties(host_pte_kind_alias PROPERTIES LABELS "host")
  # Bad input: a clear message and a non-zero exit.
  add_test(NAME host_pte_bad_option
           COMMAND ${CMAKE_COMMAND} "-DCMD=$<TARGET_FILE:pft>;eval;--scenario;${CMAKE_CURRENT_LIST_DIR}/../scenarios/pte/air_turn_6db.json;--filter;pf"
                   "-DEXPECT=takes no --filter" -P ${CMAKE_CURRENT_LIST_DIR}/../tests/expect_error.cmake)
  set_tests_properties(host_pte_bad_option PROPERTIES LABELS "host")
endif()
# Campaigns: 4 shards + pft merge give the single run's summary (host_tools/tests/shard_merge.cmake).
if(PFT_BUILD_TESTS AND COMMAND pft_shard_merge_test)
  pft_shard_merge_test(pte ${CMAKE_CURRENT_LIST_DIR}/tests/pte_small.json 8)
endif()
