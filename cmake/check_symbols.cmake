# Checks the undefined symbols of the built library (run by CTest as `lib_symbols`):
#   every build: no heap (malloc/free/calloc/realloc), no stdio, no double-precision libm or
#                soft-double helpers (the library is single precision or fixed point);
#   q16 builds:  no libm at all and no soft-float helpers (__aeabi_f*, __aeabi_d*, __*sf*, __*df*).
# Usage: cmake -DNM=<nm> -DLIB=<archive> -DNUMERIC=<float|q16> -P check_symbols.cmake
execute_process(COMMAND "${NM}" -u "${LIB}" OUTPUT_VARIABLE out RESULT_VARIABLE rc ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "nm failed on ${LIB}: ${err}")
endif()
string(REGEX MATCHALL "[ \t]U[ \t]+[A-Za-z0-9_.@]+" undef "${out}")
set(names "")
foreach(u ${undef})
  string(REGEX REPLACE "^[ \t]U[ \t]+" "" n "${u}")
  string(REGEX REPLACE "@.*$" "" n "${n}")
  list(APPEND names "${n}")
endforeach()
list(REMOVE_DUPLICATES names)

set(forbidden_all "^(malloc|free|calloc|realloc|aligned_alloc|posix_memalign|printf|fprintf|sprintf|snprintf|vprintf|vfprintf|puts|fputs|putchar|fputc|fopen|fclose|fread|fwrite|fflush|stdout|stderr|__printf_chk|__fprintf_chk|__sprintf_chk|__snprintf_chk)$"
                  "^(sqrt|exp|log|sin|cos|atan2|atan|floor|ceil|fabs|pow|round|lround|fmod)$"
                  "^(__aeabi_d.*|__extendsfdf2|__truncdfsf2|__adddf3|__subdf3|__muldf3|__divdf3)$")
set(forbidden_q16 "^(sqrtf|expf|logf|sinf|cosf|atan2f|atanf|floorf|ceilf|fabsf|powf|roundf|lroundf|fmodf)$"
                  "^(__aeabi_f.*|__aeabi_i2f|__aeabi_ui2f|__aeabi_l2f|__addsf3|__subsf3|__mulsf3|__divsf3|__floatsisf|__fixsfsi)$")
set(patterns ${forbidden_all})
if(NUMERIC STREQUAL "q16")
  list(APPEND patterns ${forbidden_q16})
endif()
set(bad "")
foreach(n ${names})
  foreach(p ${patterns})
    if(n MATCHES "${p}")
      list(APPEND bad "${n}")
    endif()
  endforeach()
endforeach()
list(LENGTH names count)
if(bad)
  list(REMOVE_DUPLICATES bad)
  message(FATAL_ERROR "${LIB} (${NUMERIC}) references forbidden symbols: ${bad}")
endif()
message(STATUS "${LIB} (${NUMERIC}): ${count} undefined symbols, none forbidden: ${names}")
