# Finds Unity (ThrowTheSwitch) for the unit tests and defines the static library `unity`.
# Order: UNITY_SOURCE_DIR (a folder holding src/unity.c; .ci/setup-deps.sh fills .deps/unity
# from Debian's cjson source package and every preset points here), else a shallow clone of the
# upstream tag into the build tree where online. When neither works, configuration stops with
# the way out. Unity's sources are never committed to this repository.
set(UNITY_SOURCE_DIR "" CACHE PATH "Folder with Unity's src/unity.c (offline copy)")
set(_unity_hint
    "The unit tests (PFT_BUILD_TESTS=ON) need Unity. Run\n"
    "    bash .ci/setup-deps.sh\n"
    "which puts it in .deps/unity (the presets' UNITY_SOURCE_DIR), or set UNITY_SOURCE_DIR to a "
    "folder holding src/unity.c, or configure with -DPFT_BUILD_TESTS=OFF.")
string(CONCAT _unity_hint ${_unity_hint})

if(UNITY_SOURCE_DIR AND EXISTS "${UNITY_SOURCE_DIR}/src/unity.c")
  set(_unity_src "${UNITY_SOURCE_DIR}/src")
else()
  set(_unity_clone "${CMAKE_BINARY_DIR}/_deps/unity-src")
  set(_unity_why "")
  if(UNITY_SOURCE_DIR)
    set(_unity_why "UNITY_SOURCE_DIR=${UNITY_SOURCE_DIR} holds no src/unity.c. ")
  endif()
  if(NOT EXISTS "${_unity_clone}/src/unity.c")
    find_package(Git QUIET)
    if(FETCHCONTENT_FULLY_DISCONNECTED)
      set(_unity_err "downloads are off (FETCHCONTENT_FULLY_DISCONNECTED)")
    elseif(NOT GIT_FOUND)
      set(_unity_err "git not found")
    else()
      message(STATUS "Unity: not in UNITY_SOURCE_DIR, trying a shallow clone of v2.6.0")
      file(REMOVE_RECURSE "${_unity_clone}")
      execute_process(COMMAND "${GIT_EXECUTABLE}" clone --quiet --depth 1 --branch v2.6.0
                              https://github.com/ThrowTheSwitch/Unity.git "${_unity_clone}"
                      RESULT_VARIABLE _rc ERROR_VARIABLE _unity_err OUTPUT_QUIET TIMEOUT 120)
      string(STRIP "${_unity_err}" _unity_err)
    endif()
  endif()
  if(NOT EXISTS "${_unity_clone}/src/unity.c")
    file(REMOVE_RECURSE "${_unity_clone}")
    message(FATAL_ERROR "Unity not found. ${_unity_why}Download failed: ${_unity_err}\n${_unity_hint}")
  endif()
  set(_unity_src "${_unity_clone}/src")
endif()
add_library(unity STATIC "${_unity_src}/unity.c")
target_include_directories(unity PUBLIC "${_unity_src}" "${PROJECT_SOURCE_DIR}/tests/support")
target_compile_definitions(unity PUBLIC UNITY_INCLUDE_CONFIG_H)
