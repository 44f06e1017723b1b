# Finds Unity (ThrowTheSwitch) for the unit tests and defines the static library `unity`.
# Order: UNITY_SOURCE_DIR (a folder holding src/unity.c; .ci/setup-deps.sh fills .deps/unity
# from Debian's cjson source package), else FetchContent of the upstream tag where online.
# Unity's sources are never committed to this repository.
set(UNITY_SOURCE_DIR "" CACHE PATH "Folder with Unity's src/unity.c (offline copy)")
if(UNITY_SOURCE_DIR AND EXISTS "${UNITY_SOURCE_DIR}/src/unity.c")
  set(_unity_src "${UNITY_SOURCE_DIR}/src")
else()
  include(FetchContent)
  FetchContent_Declare(unity_upstream GIT_REPOSITORY https://github.com/ThrowTheSwitch/Unity.git
                       GIT_TAG v2.6.0 GIT_SHALLOW TRUE)
  FetchContent_MakeAvailable(unity_upstream)
  set(_unity_src "${unity_upstream_SOURCE_DIR}/src")
  if(NOT EXISTS "${_unity_src}/unity.c")
    message(FATAL_ERROR "Unity not found: run .ci/setup-deps.sh or set UNITY_SOURCE_DIR")
  endif()
endif()
add_library(unity STATIC "${_unity_src}/unity.c")
target_include_directories(unity PUBLIC "${_unity_src}" "${PROJECT_SOURCE_DIR}/tests/support")
target_compile_definitions(unity PUBLIC UNITY_INCLUDE_CONFIG_H)
