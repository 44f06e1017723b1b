/**
 * @file pft_config.h
 * @brief Compile-time options of pftrack. Every option has a documented default here.
 *
 * To override, define PFT_USER_CONFIG as a header name (e.g. -DPFT_USER_CONFIG='"my_pft.h"')
 * and set PFT_CFG_* macros in it. The number type is fixed by the build: pft_build_config.h,
 * written by CMake (installed per number type, in include/pftrack_q16/pft or
 * include/pftrack_float/pft) or, without CMake, a one-line header `#define PFT_NUMERIC_Q16 1`
 * (or PFT_NUMERIC_FLOAT). An application compiled for one number type and linked with the
 * library of the other fails to link (PFT_LINK_NAME).
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

/**
 * @def PFT_LINK_NAME
 * @brief Link name of an entry point in this number type: `PFT_LINK_NAME(pft_tbd_init)` is
 * `pft_tbd_init_q16` in a q16 build and `pft_tbd_init_float` in a float build.
 *
 * Link-time check of the number type: the entry points that every user of an object calls
 * first (each tracker's `pft_X_init`, and `pft_ws_init` and `pft_rng_seed` of the core) are
 * renamed below to their link names. The library and the application include this same
 * header, so a matching pair links as usual; an application compiled with the q16 headers
 * and linked with the float library (or the other way round) stops at link time with
 * "undefined reference to `pft_tbd_init_q16'", the suffix naming the number type the
 * application was compiled for. Source code keeps the plain names; the suffixed ones appear
 * only in symbol tables, map files and debuggers. A new tracker family adds its init
 * function to the list (no change in lib/src is needed).
 */
#if defined(PFT_NUMERIC_Q16)
#define PFT_LINK_NAME(name) name##_q16
#else
#define PFT_LINK_NAME(name) name##_float
#endif
/** @cond PFT_LINK_NAMES */
#define pft_ws_init PFT_LINK_NAME(pft_ws_init)
#define pft_rng_seed PFT_LINK_NAME(pft_rng_seed)
#define pft_pf_init PFT_LINK_NAME(pft_pf_init)
#define pft_tbd_init PFT_LINK_NAME(pft_tbd_init)
#define pft_tsa_init PFT_LINK_NAME(pft_tsa_init)
#define pft_pte_init PFT_LINK_NAME(pft_pte_init)
#define pft_pte_dp_init PFT_LINK_NAME(pft_pte_dp_init)
#define pft_pte_dbt_init PFT_LINK_NAME(pft_pte_dbt_init)
/** @endcond */

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
