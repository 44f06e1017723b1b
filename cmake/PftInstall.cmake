# CMake package (find_package(pftrack)) and pkg-config file for the installed library.
include(CMakePackageConfigHelpers)
set(PFT_CMAKE_DIR "${CMAKE_INSTALL_LIBDIR}/cmake/pftrack")
install(EXPORT pftrackTargets NAMESPACE pftrack:: DESTINATION "${PFT_CMAKE_DIR}")
configure_package_config_file("${CMAKE_CURRENT_LIST_DIR}/pftrackConfig.cmake.in"
  "${CMAKE_CURRENT_BINARY_DIR}/pftrackConfig.cmake" INSTALL_DESTINATION "${PFT_CMAKE_DIR}")
write_basic_package_version_file("${CMAKE_CURRENT_BINARY_DIR}/pftrackConfigVersion.cmake"
  COMPATIBILITY SameMinorVersion)
install(FILES "${CMAKE_CURRENT_BINARY_DIR}/pftrackConfig.cmake"
              "${CMAKE_CURRENT_BINARY_DIR}/pftrackConfigVersion.cmake" DESTINATION "${PFT_CMAKE_DIR}")
set(PFT_PC_LIBS "-l${PFT_LIB_NAME}")
if(PFT_NUMERIC STREQUAL "float")
  set(PFT_PC_LIBS "${PFT_PC_LIBS} -lm")
endif()
configure_file("${CMAKE_CURRENT_LIST_DIR}/pftrack.pc.in" "${CMAKE_CURRENT_BINARY_DIR}/pftrack.pc" @ONLY)
install(FILES "${CMAKE_CURRENT_BINARY_DIR}/pftrack.pc" DESTINATION "${CMAKE_INSTALL_LIBDIR}/pkgconfig")
