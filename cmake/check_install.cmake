# Installs this build into a scratch prefix and builds and runs tests/install/ against it,
# through find_package(pftrack) and through pkg-config.
# With -DSIDE_BY_SIDE=ON it also builds the library in the other number type (lib and port
# only) and installs both into one prefix, then checks that
#   - each number type keeps its own pft_build_config.h, archives and .pc files;
#   - a consumer of each builds and runs (find_package COMPONENTS, and pkg-config);
#   - find_package(pftrack) without a component refuses, naming the choice;
#   - q16 headers with the float library (and the reverse) fail to link, naming the type.
# Usage: cmake -DBUILD=<build dir> -DSRC=<source dir> -DSCRATCH=<dir> -DCC=<c compiler>
#              -DNUMERIC=<float|q16> [-DSIDE_BY_SIDE=ON] [-DGENERATOR=<gen>] -P check_install.cmake
file(REMOVE_RECURSE "${SCRATCH}")
if(NUMERIC STREQUAL "q16")
  set(OTHER float)
else()
  set(OTHER q16)
endif()
if(NOT GENERATOR)
  set(GENERATOR "Unix Makefiles")
endif()

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
endfunction()

function(expect_file path)
  if(NOT EXISTS "${path}")
    message(FATAL_ERROR "not installed: ${path}")
  endif()
endfunction()

# find_package consumer of <prefix>, optionally asking for component <want>; runs it and
# checks it was compiled for <numeric>
function(cmake_consumer prefix want numeric)
  set(dir "${SCRATCH}/consumer_${want}${numeric}")
  run("configure find_package consumer (${want})" ${CMAKE_COMMAND} -S "${SRC}/tests/install" -B "${dir}"
      -G "${GENERATOR}" -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_C_COMPILER=${CC} -DPFT_WANT=${want})
  run("build find_package consumer (${want})" ${CMAKE_COMMAND} --build "${dir}")
  run("run find_package consumer (${want})" "${dir}/consumer")
  if(NOT out MATCHES "numeric ${numeric}")
    message(FATAL_ERROR "find_package consumer (${want}) was not compiled for ${numeric}: ${out}")
  endif()
  message(STATUS "find_package(pftrack ${want}): ${out}")
endfunction()

# pkg-config consumer: cflags of package <cpkg>, libs of package <lpkg>; returns rc and output
function(pc_consumer prefix cpkg lpkg exe)
  set(ENV{PKG_CONFIG_PATH} "${prefix}/lib/pkgconfig")
  run("pkg-config --cflags ${cpkg}" ${PKG_CONFIG} --cflags ${cpkg})
  string(STRIP "${out}" cflags)
  run("pkg-config --libs ${lpkg}" ${PKG_CONFIG} --libs ${lpkg})
  string(STRIP "${out}" libs)
  separate_arguments(cflags UNIX_COMMAND "${cflags}")
  separate_arguments(libs UNIX_COMMAND "${libs}")
  execute_process(COMMAND ${CC} ${cflags} "${SRC}/tests/install/main.c" ${libs} -o "${exe}"
                  RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
  set(pc_rc "${rc}" PARENT_SCOPE)
  set(pc_out "${o}${e}" PARENT_SCOPE)
  set(pc_flags "${cflags} ${libs}" PARENT_SCOPE)
endfunction()

function(pc_consumer_ok prefix numeric)
  pc_consumer("${prefix}" pftrack_port_${numeric} pftrack_port_${numeric} "${SCRATCH}/pc_${numeric}")
  if(NOT pc_rc EQUAL 0)
    message(FATAL_ERROR "pkg-config consumer (${numeric}) failed to build with ${pc_flags}:\n${pc_out}")
  endif()
  run("run pkg-config consumer (${numeric})" "${SCRATCH}/pc_${numeric}")
  if(NOT out MATCHES "numeric ${numeric}")
    message(FATAL_ERROR "pkg-config consumer was not compiled for ${numeric}: ${out}")
  endif()
  message(STATUS "pkg-config pftrack_port_${numeric}: ${out}")
endfunction()

find_program(PKG_CONFIG pkg-config)

# --- this build alone
set(P1 "${SCRATCH}/prefix")
run("cmake --install" ${CMAKE_COMMAND} --install "${BUILD}" --prefix "${P1}")
expect_file("${P1}/include/pftrack_${NUMERIC}/pft/pft_build_config.h")
expect_file("${P1}/include/pft/pft.h")
expect_file("${P1}/include/pft/pft_port.h")
if(EXISTS "${P1}/include/pft/pft_build_config.h")
  message(FATAL_ERROR "pft_build_config.h installed into the shared include/pft")
endif()
if(EXISTS "${P1}/include/pft/pft_port_mps2.h")
  message(FATAL_ERROR "pft_port_mps2.h installed by a build without the mps2 port")
endif()
cmake_consumer("${P1}" "" ${NUMERIC})
if(PKG_CONFIG)
  pc_consumer_ok("${P1}" ${NUMERIC})
endif()
if(NOT SIDE_BY_SIDE)
  return()
endif()

# --- both number types in one prefix
set(OB "${SCRATCH}/build_${OTHER}")
run("configure the ${OTHER} build" ${CMAKE_COMMAND} -S "${SRC}" -B "${OB}" -G "${GENERATOR}"
    -DCMAKE_C_COMPILER=${CC} -DCMAKE_BUILD_TYPE=Release -DPFT_NUMERIC=${OTHER}
    -DPFT_BUILD_TESTS=OFF -DPFT_INSTALL=ON -DPFT_WERROR=ON)
run("build the ${OTHER} build" ${CMAKE_COMMAND} --build "${OB}" --parallel 2)
set(P2 "${SCRATCH}/both")
run("install ${NUMERIC}" ${CMAKE_COMMAND} --install "${BUILD}" --prefix "${P2}")
run("install ${OTHER}" ${CMAKE_COMMAND} --install "${OB}" --prefix "${P2}")
foreach(t float q16)
  expect_file("${P2}/include/pftrack_${t}/pft/pft_build_config.h")
  expect_file("${P2}/lib/libpftrack_${t}.a")
  expect_file("${P2}/lib/libpftrack_port_${t}.a")
  expect_file("${P2}/lib/cmake/pftrack/pftrack_${t}Targets.cmake")
  expect_file("${P2}/lib/pkgconfig/pftrack_${t}.pc")
  expect_file("${P2}/lib/pkgconfig/pftrack_port_${t}.pc")
  string(TOUPPER "${t}" T)
  file(READ "${P2}/include/pftrack_${t}/pft/pft_build_config.h" h)
  if(NOT h MATCHES "#define PFT_NUMERIC_${T} 1")
    message(FATAL_ERROR "include/pftrack_${t}/pft/pft_build_config.h is not the ${t} one:\n${h}")
  endif()
  cmake_consumer("${P2}" ${t} ${t})
  if(PKG_CONFIG)
    pc_consumer_ok("${P2}" ${t})
  endif()
endforeach()

execute_process(COMMAND ${CMAKE_COMMAND} -S "${SRC}/tests/install" -B "${SCRATCH}/consumer_ambiguous"
                -G "${GENERATOR}" -DCMAKE_PREFIX_PATH=${P2} -DCMAKE_C_COMPILER=${CC}
                RESULT_VARIABLE rc OUTPUT_VARIABLE o ERROR_VARIABLE e)
if(rc EQUAL 0 OR NOT "${o}${e}" MATCHES "both the float and the q16 build")
  message(FATAL_ERROR "find_package(pftrack) without a component did not refuse a prefix with both:\n${o}${e}")
endif()
message(STATUS "find_package(pftrack) with both installed and no component: refused, as it should")

if(PKG_CONFIG)
  foreach(pair "q16;float" "float;q16")
    list(GET pair 0 hdr)
    list(GET pair 1 lib)
    pc_consumer("${P2}" pftrack_${hdr} "pftrack_port_${lib}" "${SCRATCH}/mismatch_${hdr}_${lib}")
    if(pc_rc EQUAL 0)
      message(FATAL_ERROR "${hdr} headers with the ${lib} library linked: the number-type check failed")
    endif()
    if(NOT pc_out MATCHES "undefined reference to `pft_[a-z_]+_${hdr}'")
      message(FATAL_ERROR "${hdr} headers with the ${lib} library failed, but not on the number type:\n${pc_out}")
    endif()
    string(REGEX MATCH "undefined reference to `pft_[a-z_]+_${hdr}'" why "${pc_out}")
    message(STATUS "${hdr} headers + ${lib} library: link refused (${why})")
  endforeach()
endif()
