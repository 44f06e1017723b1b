/*
 * Golden-vector generator for the tbd family (host q16 build only): the per-frame results of
 * the standalone RBPF-TBD / PF-TBD filters and of the multi-target manager (paper, recommended,
 * a variant preset and the recommended one with births from the multi-frame integration) on
 * the integer-rendered scene of gv_scene.h, and a few measurement-model
 * calls (tbd_vectors_spec.h). tests/unit/test_tbd_golden.c replays them on every preset.
 *
 *   build/host-q16/tests/gen_tbd_vectors > tests/vectors/tbd_q16_vectors.h
 */
#include <stdio.h>
#include <string.h>

#include "gv_emit.h"
#include "tbd_vectors_spec.h"

int main(void)
{
#ifndef PFT_NUMERIC_Q16
    fprintf(stderr, "gen_tbd_vectors: build with PFT_NUMERIC=q16\n");
    return 1;
#else
    static pft_tv_results_t r;
    pft_tv_compute(&r);
    pft_gv_emit_head("gen_tbd_vectors", "tbd_q16_vectors.h", "PFT_TBD_Q16_VECTORS_H");
    pft_gv_emit_rows("tv_filt_rbpf", &r.filt_rbpf[0][0], PFT_TV_FILTER_FRAMES, PFT_TV_FROW);
    pft_gv_emit_rows("tv_filt_pf", &r.filt_pf[0][0], PFT_TV_FILTER_FRAMES, PFT_TV_FROW);
    pft_gv_emit_rows("tv_mgr_paper", &r.mgr_paper[0][0], PFT_TV_MGR_FRAMES, PFT_TV_MROW);
    pft_gv_emit_rows("tv_mgr_rec", &r.mgr_rec[0][0], PFT_TV_MGR_FRAMES, PFT_TV_MROW);
    pft_gv_emit_rows("tv_mgr_var", &r.mgr_var[0][0], PFT_TV_MGR_FRAMES, PFT_TV_MROW);
    pft_gv_emit_rows("tv_mgr_integ", &r.mgr_integ[0][0], PFT_TV_MGR_FRAMES, PFT_TV_MROW);
    pft_gv_emit_rows("tv_meas", r.meas, 1, PFT_TV_MEAS);
    printf("#endif\n");
    return 0;
#endif
}
