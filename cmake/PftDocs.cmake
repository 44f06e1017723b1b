# API documentation: target `docs` (when Doxygen is found) runs docs/Doxyfile with its output
# and warning list in <build>/docs (html/, doxygen-warnings.txt) and prints the warnings per
# header. The ctest docs_doxygen (tests/CMakeLists.txt) fails on any warning in the headers of
# PFT_DOCS_CLEAN_HEADERS, and on any warning at all with PFT_DOCS_WERROR=ON; add a header to
# the list once it is clean, so it stays clean.
set(PFT_DOCS_CLEAN_HEADERS pft_types.h pft_real.h pft_rng.h pft_resample.h pft_kalman.h
    pft_workspace.h pft_config.h pft.h pft_pf.h pft_pte.h pft_pre.h pft_tbd.h pft_tbd_scene.h pft_pf_models.h pft_tsa.h
    pft_port.h pft_port_file.h pft_port_mem.h pft_port_template.h pft_port_mps2.h)
find_package(Doxygen QUIET)
if(DOXYGEN_FOUND)
  set(PFT_DOXYFILE "${PROJECT_BINARY_DIR}/docs/Doxyfile")
  set(PFT_DOXYGEN_LOG "${PROJECT_BINARY_DIR}/docs/doxygen-warnings.txt")
  file(MAKE_DIRECTORY "${PROJECT_BINARY_DIR}/docs")
  file(WRITE "${PFT_DOXYFILE}.tmp"
       "@INCLUDE = ${PROJECT_SOURCE_DIR}/docs/Doxyfile\n"
       "OUTPUT_DIRECTORY = ${PROJECT_BINARY_DIR}/docs\n"
       "WARN_LOGFILE = ${PFT_DOXYGEN_LOG}\n"
       "PROJECT_NUMBER = ${PROJECT_VERSION}\n")
  configure_file("${PFT_DOXYFILE}.tmp" "${PFT_DOXYFILE}" COPYONLY)
  add_custom_target(docs
    COMMAND ${CMAKE_COMMAND} -DDOXYGEN=${DOXYGEN_EXECUTABLE} -DDOXYFILE=${PFT_DOXYFILE}
            -DSRC=${PROJECT_SOURCE_DIR} -DLOG=${PFT_DOXYGEN_LOG} -P ${PROJECT_SOURCE_DIR}/cmake/check_docs.cmake
    COMMENT "Doxygen: ${PROJECT_BINARY_DIR}/docs/html/index.html" VERBATIM)
endif()
