# The "vis" kind of the host tools (TSA-AK visual tracker, issue 5): semi-synthetic airborne
# sequences over the opencv-doc aerial photographs, pftrack's TSA-AK / NCV / TS against
# OpenCV's KCF, CSRT, MOSSE and MIL (contrib tracking module, when found), and `pft track`.
# Included from host_tools/CMakeLists.txt after the `pft` target exists.
file(GLOB PFT_HOST_VIS CONFIGURE_DEPENDS "${CMAKE_CURRENT_LIST_DIR}/*.cpp")
target_sources(pft PRIVATE ${PFT_HOST_VIS})
find_package(OpenCV QUIET COMPONENTS tracking video)
if(OpenCV_tracking_FOUND OR TARGET opencv_tracking)
  target_link_libraries(pft PRIVATE opencv_tracking opencv_video)
  target_compile_definitions(pft PRIVATE PFT_HAVE_CV_TRACKING=1)
else()
  message(STATUS "pftrack host tools: OpenCV tracking (contrib) not found; bench vis runs without KCF/CSRT/MOSSE/MIL")
endif()

if(PFT_BUILD_TESTS)
  add_test(NAME host_vis_selftest COMMAND pft selftest --kind vis)
  set_tests_properties(host_vis_selftest PROPERTIES LABELS "host"
                       PASS_REGULAR_EXPRESSION "vis selftest: passed" FAIL_REGULAR_EXPRESSION "FAIL")
  file(GLOB PFT_VIS_SCENARIOS CONFIGURE_DEPENDS "${CMAKE_CURRENT_LIST_DIR}/../scenarios/vis/*.json")
  foreach(sc ${PFT_VIS_SCENARIOS})
    get_filename_component(n ${sc} NAME_WE)
    add_test(NAME host_vis_scenario_${n} COMMAND pft bench --scenario ${sc} --frames 5 --runs 1 -q)
    set_tests_properties(host_vis_scenario_${n} PROPERTIES LABELS "host")
  endforeach()
endif()
