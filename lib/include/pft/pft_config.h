/**
 * @file pft_config.h
 * @brief Compile-time options of pftrack. Every option has a documented default here.
 *
 * To override, define PFT_USER_CONFIG as a header name (e.g. -DPFT_USER_CONFIG='"my_pft.h"')
 * and set PFT_CFG_* macros in it. The number type is fixed by the build (pft_build_config.h,
 * written by CMake), so installed headers always match the built library.
 */
#ifndef PFT_CONFIG_H
#define PFT_CONFIG_H

#ifdef PFT_USER_CONFIG
#include PFT_USER_CONFIG
#endif

#include "pft/pft_build_config.h"

/* PFT_NUMERIC_Q16 (1) or PFT_NUMERIC_FLOAT (1): exactly one, from pft_build_config.h. */
#if defined(PFT_NUMERIC_Q16) && defined(PFT_NUMERIC_FLOAT)
#error "pftrack: PFT_NUMERIC_Q16 and PFT_NUMERIC_FLOAT are both defined"
#endif
#if !defined(PFT_NUMERIC_Q16) && !defined(PFT_NUMERIC_FLOAT)
#error "pftrack: no number type: define PFT_NUMERIC_Q16 or PFT_NUMERIC_FLOAT (CMake: PFT_NUMERIC)"
#endif

/** Assertion used on internal invariants (never on user input, which gets a status code).
 *  A port may define it to trap or log; default: compiled out. */
#ifndef PFT_ASSERT
#define PFT_ASSERT(cond) ((void)0)
#endif

/** Largest particle count any filter accepts (bounds every loop; indices are uint32_t). */
#ifndef PFT_CFG_MAX_PARTICLES
#define PFT_CFG_MAX_PARTICLES 262144u
#endif
#if PFT_CFG_MAX_PARTICLES > 4194304u
#error "PFT_CFG_MAX_PARTICLES above 2^22 would overflow the q16 weight accumulator"
#endif

/** Largest image side accepted by the trackers. */
#ifndef PFT_CFG_MAX_IMAGE_SIDE
#define PFT_CFG_MAX_IMAGE_SIDE 8192u
#endif

#endif
