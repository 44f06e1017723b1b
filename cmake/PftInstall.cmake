# Install rules for the CMake package (find_package(pftrack COMPONENTS float|q16)) and the
# pkg-config files. A float and a q16 build install into one prefix side by side:
#   include/pft/*.h                              public headers (identical in both builds)
#   include/pftrack_<numeric>/pft/pft_build_config.h   the one header that differs
#   lib/libpftrack_<numeric>.a, lib/libpftrack_port_<numeric>.a
#   lib/cmake/pftrack/pftrackConfig.cmake         shared: loads the installed number types
#   lib/cmake/pftrack/pftrack_<numeric>Targets.cmake   pftrack::pftrack_<numeric>, pftrack::pftrack_port_<numeric>
#   lib/pkgconfig/pftrack_<numeric>.pc, lib/pkgconfig/pftrack_port_<numeric>.pc
#   share/pftrack/scenarios/, bin/pft            host tools (PFT_BUILD_HOST_TOOLS)
include(CMakePackageConfigHelpers)
set(PFT_CMAKE_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/pftrack")
install(EXPORT pftrack_${PFT_NUMERIC}Targets NAMESPACE pftrack:: DESTINATION "${PFT_CMAKE_DIR}")
configure_package_config_file("${CMAKE_CURRENT_LIST_DIR}/pftrackConfig.cmake.in"
  "${CMAKE_CURRENT_BINARY_DIR}/pftrackConfig.cmake" INSTALL_DESTINATION "${PFT_CMAKE_DIR}")
write_basic_package_version_file("${CMAKE_CURRENT_BINARY_DIR}/pftrackConfigVersion.cmake"
  COMPATIBILITY SameMinorVersion)
install(FILES "${CMAKE_CURRENT_BINARY_DIR}/pftrackConfig.cmake"
              "${CMAKE_CURRENT_BINARY_DIR}/pftrackConfigVersion.cmake" DESTINATION "${PFT_CMAKE_DIR}")

# pkg-config: prefix relative to the .pc file, so the prefix can be moved
set(PFT_PC_DIR "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
file(RELATIVE_PATH PFT_PC_TO_PREFIX "/p/${PFT_PC_DIR}" "/p")
string(REGEX REPLACE "/$" "" PFT_PC_TO_PREFIX "${PFT_PC_TO_PREFIX}")
set(PFT_PC_LIBS "-l${PFT_LIB_NAME}")
if(PFT_NUMERIC STREQUAL "float")
  set(PFT_PC_LIBS "${PFT_PC_LIBS} -lm")
endif()
set(PFT_PC_PORT_CFLAGS "")
if(PFT_TARGET STREQUAL "mps2")
  set(PFT_PC_PORT_CFLAGS " -DPFT_PORT_MPS2=1")
endif()
configure_file("${CMAKE_CURRENT_LIST_DIR}/pftrack_numeric.pc.in"
               "${CMAKE_CURRENT_BINARY_DIR}/${PFT_LIB_NAME}.pc" @ONLY)
configure_file("${CMAKE_CURRENT_LIST_DIR}/pftrack_port_numeric.pc.in"
               "${CMAKE_CURRENT_BINARY_DIR}/${PFT_PORT_LIB_NAME}.pc" @ONLY)
install(FILES "${CMAKE_CURRENT_BINARY_DIR}/${PFT_LIB_NAME}.pc"
              "${CMAKE_CURRENT_BINARY_DIR}/${PFT_PORT_LIB_NAME}.pc" DESTINATION "${PFT_PC_DIR}")
