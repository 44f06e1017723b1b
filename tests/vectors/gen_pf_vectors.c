/*
 * Golden-vector generator for the pf family (host q16 build only): the per-step results of the
 * engine's SIS / SIR / APF on the bearings, linear-Gaussian and TBD pixel models
 * (pf_vectors_spec.h). tests/unit/test_pf_golden.c replays them on every preset.
 *
 *   build/host-q16/tests/gen_pf_vectors > tests/vectors/pf_q16_vectors.h
 */
#include <stdio.h>
#include <string.h>

#include "gv_emit.h"
#include "pf_vectors_spec.h"

int main(void)
{
#ifndef PFT_NUMERIC_Q16
    fprintf(stderr, "gen_pf_vectors: build with PFT_NUMERIC=q16\n");
    return 1;
#else
    static pft_pv_results_t r;
    pft_pv_compute(&r);
    pft_gv_emit_head("gen_pf_vectors", "pf_q16_vectors.h", "PFT_PF_Q16_VECTORS_H");
    static const char *const brg[4] = {"pv_brg_sis", "pv_brg_sir", "pv_brg_apf", "pv_brg_apf_known"};
    static const char *const lg[4] = {"pv_lg_sis", "pv_lg_sir", "pv_lg_apf", "pv_lg_sir_known"};
    static const char *const tbd[2] = {"pv_tbd_sir", "pv_tbd_apf"};
    for (int i = 0; i < 4; ++i) {
        pft_gv_emit_rows(brg[i], &r.brg[i][0][0], PFT_PV_BRG_STEPS, PFT_PV_ROW);
    }
    for (int i = 0; i < 4; ++i) {
        pft_gv_emit_rows(lg[i], &r.lg[i][0][0], PFT_PV_LG_STEPS, PFT_PV_ROW);
    }
    for (int i = 0; i < 2; ++i) {
        pft_gv_emit_rows(tbd[i], &r.tbd[i][0][0], PFT_PV_TBD_STEPS, PFT_PV_ROW);
    }
    printf("#endif\n");
    return 0;
#endif
}
