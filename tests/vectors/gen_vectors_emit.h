/* Printing of the golden-vector generators (host builds only): a C array of 32-bit values,
 * eight a line, as tests/vectors/<name>_q16_vectors.h holds them. */
#ifndef PFT_GEN_VECTORS_EMIT_H
#define PFT_GEN_VECTORS_EMIT_H
#include <stdint.h>
#include <stdio.h>

static inline const char *pft_gv_sep(size_t i)
{
    return i == 0 ? "\n    " : (i % 8u) ? ", " : ",\n    ";
}

static inline void pft_gv_emit_i32(const char *name, const int32_t *v, size_t n)
{
    printf("static const int32_t %s[%u] = {", name, (unsigned)n);
    for (size_t i = 0; i < n; ++i) {
        printf("%s%ld", pft_gv_sep(i), (long)v[i]);
    }
    printf("\n};\n");
}

static inline void pft_gv_emit_u32(const char *name, const uint32_t *v, size_t n)
{
    printf("static const uint32_t %s[%u] = {", name, (unsigned)n);
    for (size_t i = 0; i < n; ++i) {
        printf("%s%luu", pft_gv_sep(i), (unsigned long)v[i]);
    }
    printf("\n};\n");
}
#endif
