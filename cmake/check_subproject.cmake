# A consumer that does add_subdirectory(pftrack) with no options (tests/subproject) must
# configure and build offline: no Unity, no tests, no install rules, no -Werror, no -std flag
# or warning flags on its own sources; on bare metal (TOOLCHAIN given) no -fPIC either.
# Then, with the tests asked for and Unity absent offline, configuration must stop and say to
# run .ci/setup-deps.sh.
# Usage: cmake -DSRC=<source dir> -DSCRATCH=<dir> -DCC=<c compiler> [-DTOOLCHAIN=<file>]
#              [-DGENERATOR=<gen>] -P check_subproject.cmake
file(REMOVE_RECURSE "${SCRATCH}")
if(NOT GENERATOR)
  set(GENERATOR "Unix Makefiles")
endif()

function(check_consumer dir)
  execute_process(COMMAND ${CMAKE_COMMAND} -S "${SRC}/tests/subproject" -B "${dir}" -G "${GENERATOR}"
                          -DPFTRACK_DIR=${SRC} -DCMAKE_EXPORT_COMPILE_COMMANDS=ON ${ARGN}
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "add_subdirectory consumer failed to configure:\n${out}\n${err}")
  endif()
  if(EXISTS "${dir}/_deps" OR EXISTS "${dir}/pftrack/tests")
    message(FATAL_ERROR "add_subdirectory consumer configured pftrack's tests or fetched Unity")
  endif()
  execute_process(COMMAND ${CMAKE_COMMAND} --build "${dir}" --parallel 2
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "add_subdirectory consumer failed to build:\n${out}\n${err}")
  endif()
  file(READ "${dir}/compile_commands.json" cc)
  if(cc MATCHES "-Werror")
    message(FATAL_ERROR "-Werror reaches a consumer that did not ask for it (${dir}/compile_commands.json)")
  endif()
  string(REGEX MATCH "\"command\": \"[^\"]*\",[ \n]*\"file\": \"[^\"]*tests/install/main.c\"" own "${cc}")
  if(NOT own)
    message(FATAL_ERROR "no compile command for the consumer's main.c in ${dir}/compile_commands.json")
  endif()
  if(own MATCHES " -std=| -W")
    message(FATAL_ERROR "pftrack imposes flags on the consumer's own sources: ${own}")
  endif()
  set(cc "${cc}" PARENT_SCOPE)
endfunction()

check_consumer("${SCRATCH}/host" -DCMAKE_C_COMPILER=${CC})
execute_process(COMMAND "${SCRATCH}/host/consumer" RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "add_subdirectory consumer failed to run (${rc}): ${out}")
endif()
message(STATUS "add_subdirectory consumer (host): ${out}")

if(TOOLCHAIN)
  check_consumer("${SCRATCH}/baremetal" -DCMAKE_TOOLCHAIN_FILE=${TOOLCHAIN} -DPFT_NUMERIC=q16)
  if(cc MATCHES "-fPIC|-fPIE")
    message(FATAL_ERROR "position-independent code on a bare-metal build (${SCRATCH}/baremetal)")
  endif()
  message(STATUS "add_subdirectory consumer (${TOOLCHAIN}): built, no -fPIC, no -Werror")
endif()

execute_process(COMMAND ${CMAKE_COMMAND} -S "${SRC}/tests/subproject" -B "${SCRATCH}/tests_on" -G "${GENERATOR}"
                        -DPFTRACK_DIR=${SRC} -DCMAKE_C_COMPILER=${CC} -DPFT_BUILD_TESTS=ON
                        -DUNITY_SOURCE_DIR=${SCRATCH}/no_unity -DFETCHCONTENT_FULLY_DISCONNECTED=ON
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0 OR NOT err MATCHES "bash \\.ci/setup-deps\\.sh")
  message(FATAL_ERROR "PFT_BUILD_TESTS=ON without Unity did not stop with the setup-deps hint:\n${out}\n${err}")
endif()
message(STATUS "PFT_BUILD_TESTS=ON without Unity: stops with the hint to run bash .ci/setup-deps.sh")
