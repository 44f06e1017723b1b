# The APF module of the host tools (kinds "bearings" and "apf_tbd"): sources compiled into
# `pft` (they register themselves), self-test and scenario smoke tests. Included from
# host_tools/CMakeLists.txt after the `pft` target exists.
file(GLOB PFT_HOST_APF CONFIGURE_DEPENDS "${CMAKE_CURRENT_LIST_DIR}/*.cpp")
target_sources(pft PRIVATE ${PFT_HOST_APF})

if(PFT_BUILD_TESTS)
  add_test(NAME host_bearings_selftest COMMAND pft selftest --kind bearings)
  set_tests_properties(host_bearings_selftest PROPERTIES LABELS "host"
                       PASS_REGULAR_EXPRESSION "bearings selftest: passed" FAIL_REGULAR_EXPRESSION "FAIL")
  file(GLOB PFT_APF_SCENARIOS CONFIGURE_DEPENDS "${CMAKE_CURRENT_LIST_DIR}/../scenarios/apf/*.json")
  foreach(sc ${PFT_APF_SCENARIOS})
    get_filename_component(n ${sc} NAME_WE)
    add_test(NAME host_apf_scenario_${n} COMMAND pft bench --scenario ${sc} --frames 3 --runs 1 --particles 50 -q)
    set_tests_properties(host_apf_scenario_${n} PROPERTIES LABELS "host")
  endforeach()
endif()

# Bad input: a clear message naming the field (pft_expect_error comes from host_tools/CMakeLists.txt).
if(PFT_BUILD_TESTS AND COMMAND pft_expect_error)
  pft_expect_error(apf_bad_engine "filters\\[0\\].engine" eval --scenario ${CMAKE_CURRENT_LIST_DIR}/tests/bad_engine.json)
  pft_expect_error(apf_bad_match "match_time_of: no filter labelled" eval --scenario ${CMAKE_CURRENT_LIST_DIR}/tests/bad_match.json)
endif()
