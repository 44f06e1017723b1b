# Compiler settings of pftrack's own targets. Nothing here reaches a consumer's targets: the
# language level travels as a compile feature (c_std_99, satisfied by any newer default), the
# warnings are PRIVATE, and warnings-as-errors needs PFT_WERROR=ON (every preset and CI set it).
#
# pft_strict_c(<target>)   C99 without extensions, the library's full warning set
# pft_warnings(<target>)   the shorter set used by the ports, tests and tools
# pft_pic(<target>)        position-independent code unless bare metal (CMAKE_SYSTEM_NAME
#                          Generic); an explicit CMAKE_POSITION_INDEPENDENT_CODE wins

set(PFT_STRICT_C_WARNINGS -Wall -Wextra -pedantic -Wdouble-promotion -Wconversion -Wshadow
    -Wstrict-prototypes)

function(pft_werror target)
  if(PFT_WERROR AND CMAKE_C_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()

function(pft_strict_c target)
  set_target_properties(${target} PROPERTIES C_STANDARD 99 C_STANDARD_REQUIRED ON C_EXTENSIONS OFF)
  target_compile_features(${target} PUBLIC c_std_99)
  if(CMAKE_C_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE ${PFT_STRICT_C_WARNINGS})
  endif()
  pft_werror(${target})
endfunction()

function(pft_warnings target)
  if(CMAKE_C_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE $<$<COMPILE_LANGUAGE:C>:-Wall -Wextra -pedantic -Wconversion>)
  endif()
  pft_werror(${target})
endfunction()

function(pft_pic target)
  if(DEFINED CMAKE_POSITION_INDEPENDENT_CODE)
    return() # the user's choice, already applied to every target
  endif()
  if(NOT CMAKE_SYSTEM_NAME STREQUAL "Generic")
    # hosted builds: the archive may be linked into a shared object or a PIE
    set_target_properties(${target} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  endif()
endfunction()
