# cmake -DPFT=<pft> -DSCENARIO=<a kind "pte" scenario> -DOUT=<dir> -P kind_alias_test.cmake
# Writes a copy of SCENARIO with the former kind name "radar", runs `pft sim` on it and passes
# when it exits 0 with the renaming note on stderr.
file(READ "${SCENARIO}" text)
string(REPLACE "\"kind\": \"pte\"" "\"kind\": \"radar\"" text "${text}")
if(NOT text MATCHES "\"kind\": \"radar\"")
  message(FATAL_ERROR "${SCENARIO} has no \"kind\": \"pte\"")
endif()
file(MAKE_DIRECTORY "${OUT}")
file(WRITE "${OUT}/radar_kind.json" "${text}")
execute_process(COMMAND "${PFT}" sim --scenario "${OUT}/radar_kind.json" --out "${OUT}/sim" -q
                RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pft sim on kind \"radar\" failed (${rc}):\n${err}")
endif()
if(NOT err MATCHES "scenario kind \"radar\" is now called \"pte\"")
  message(FATAL_ERROR "no renaming note on stderr:\n${err}")
endif()
message(STATUS "ok: ${err}")
