/*
 * pre_probe: runs the preprocessing stage (pft_pre.h) over a headerless raw sequence of
 * little-endian u16 frames and prints one CSV line of statistics per frame; optionally writes
 * the whitened residual (int16 Q8.8, PFT_RES16_MASKED for masked pixels) of every frame.
 * A host exploration tool for docs/results/ir_clutter.md ("Preprocessing building blocks"),
 * driven by host_tools/scripts/pre_explore.py; not a test.
 *
 *   pre_probe IN.u16 W H BITS [key=value ...] [out=RES.i16] [sig=SIGMA.u32]
 *   (sig= writes every frame's tile sigmas, pft_pre_sigma: uint32 Q16.16 counts, row-major)
 *   keys: method=local|temporal ro rg alpha search iters step cubic col tile current interp
 *         floor edge peaks thr sstep severy rbin sbrk anchor; clutter=1 runs the clutter map (pft_pre_clutter_*) after the
 *         stage (then out= writes its output), with cmean cblur cbox calpha cthr
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "pft/pft_pre.h"

static int arg_int(const char *a, const char *key, long *v)
{
    size_t n = strlen(key);
    if (strncmp(a, key, n) == 0 && a[n] == '=') {
        *v = strtol(a + n + 1, NULL, 10);
        return 1;
    }
    return 0;
}

int main(int argc, char **argv)
{
    if (argc < 5) {
        fprintf(stderr, "usage: pre_probe IN.u16 W H BITS [key=value ...]\n");
        return 2;
    }
    pft_pre_config_t cfg;
    pft_pre_config_default(&cfg);
    cfg.width = (uint16_t)atoi(argv[2]);
    cfg.height = (uint16_t)atoi(argv[3]);
    cfg.bit_depth = (uint8_t)atoi(argv[4]);
    const char *out_path = NULL, *sig_path = NULL;
    pft_pre_clutter_config_t ccfg;
    pft_pre_clutter_config_default(&ccfg);
    int clutter = 0;
    for (int i = 5; i < argc; ++i) {
        long v;
        if (strcmp(argv[i], "method=local") == 0) {
            cfg.method = PFT_PRE_BG_LOCAL;
        } else if (strcmp(argv[i], "method=temporal") == 0) {
            cfg.method = PFT_PRE_BG_TEMPORAL;
        } else if (strncmp(argv[i], "out=", 4) == 0) {
            out_path = argv[i] + 4;
        } else if (strncmp(argv[i], "sig=", 4) == 0) {
            sig_path = argv[i] + 4;
        } else if (arg_int(argv[i], "clutter", &v)) {
            clutter = v != 0;
        } else if (arg_int(argv[i], "cmean", &v)) {
            ccfg.mean = v != 0;
        } else if (arg_int(argv[i], "cbox", &v)) {
            ccfg.box = v != 0;
        } else if (arg_int(argv[i], "cblur", &v)) {
            ccfg.blur = (uint8_t)v;
        } else if (arg_int(argv[i], "calpha", &v)) {
            ccfg.alpha = (uint16_t)v;
        } else if (arg_int(argv[i], "cthr", &v)) {
            ccfg.thr = (uint16_t)v;
        } else if (arg_int(argv[i], "ro", &v)) {
            cfg.local_outer = (uint8_t)v;
        } else if (arg_int(argv[i], "rg", &v)) {
            cfg.local_guard = (uint8_t)v;
        } else if (arg_int(argv[i], "alpha", &v)) {
            cfg.bg_alpha = (uint16_t)v;
        } else if (arg_int(argv[i], "search", &v)) {
            cfg.reg_search = (uint8_t)v;
        } else if (arg_int(argv[i], "iters", &v)) {
            cfg.reg_iters = (uint8_t)v;
        } else if (arg_int(argv[i], "cubic", &v)) {
            cfg.warp_cubic = v != 0;
        } else if (arg_int(argv[i], "step", &v)) {
            cfg.reg_step = (uint8_t)v;
        } else if (arg_int(argv[i], "sstep", &v)) {
            cfg.sigma_step = (uint8_t)v;
        } else if (arg_int(argv[i], "severy", &v)) {
            cfg.sigma_every = (uint8_t)v;
        } else if (arg_int(argv[i], "rbin", &v)) {
            cfg.reg_bin = v != 0;
        } else if (arg_int(argv[i], "sbrk", &v)) {
            cfg.sigma_bracket = v != 0;
        } else if (arg_int(argv[i], "anchor", &v)) {
            cfg.bg_anchor = v != 0;
        } else if (arg_int(argv[i], "col", &v)) {
            cfg.col_alpha = (uint16_t)v;
        } else if (arg_int(argv[i], "tile", &v)) {
            cfg.tile = (uint8_t)v;
        } else if (arg_int(argv[i], "current", &v)) {
            cfg.sigma_current = v != 0;
        } else if (arg_int(argv[i], "interp", &v)) {
            cfg.sigma_interp = v != 0;
        } else if (arg_int(argv[i], "floor", &v)) {
            cfg.sigma_floor = (uint16_t)v;
        } else if (arg_int(argv[i], "edge", &v)) {
            cfg.edge_k = (uint16_t)v;
        } else if (arg_int(argv[i], "peaks", &v)) {
            cfg.peak_max = (uint16_t)v;
        } else if (arg_int(argv[i], "thr", &v)) {
            cfg.peak_threshold = (int16_t)v;
        } else {
            fprintf(stderr, "pre_probe: unknown argument %s\n", argv[i]);
            return 2;
        }
    }
    const char *field = NULL;
    if (pft_pre_config_check(&cfg, &field) != PFT_OK) {
        fprintf(stderr, "pre_probe: refused configuration field %s\n", field);
        return 2;
    }
    size_t need = pft_pre_workspace_size(&cfg);
    void *work = malloc(need);
    static pft_pre_t pre;
    if (work == NULL || pft_pre_init(&pre, &cfg, work, need) != PFT_OK) {
        fprintf(stderr, "pre_probe: init failed\n");
        return 1;
    }
    static pft_pre_clutter_t cl;
    void *cwork = NULL;
    if (clutter) {
        ccfg.width = cfg.width;
        ccfg.height = cfg.height;
        if (pft_pre_clutter_config_check(&ccfg, &field) != PFT_OK) {
            fprintf(stderr, "pre_probe: refused clutter configuration field %s\n", field);
            return 2;
        }
        const size_t cneed = pft_pre_clutter_workspace_size(&ccfg);
        cwork = malloc(cneed);
        if (cwork == NULL || pft_pre_clutter_init(&cl, &ccfg, cwork, cneed) != PFT_OK) {
            fprintf(stderr, "pre_probe: clutter init failed\n");
            return 1;
        }
    }
    FILE *in = fopen(argv[1], "rb");
    FILE *out = out_path != NULL ? fopen(out_path, "wb") : NULL;
    if (in == NULL || (out_path != NULL && out == NULL)) {
        fprintf(stderr, "pre_probe: cannot open files\n");
        return 1;
    }
    FILE *sig = sig_path != NULL ? fopen(sig_path, "wb") : NULL;
    if (sig_path != NULL && sig == NULL) {
        fprintf(stderr, "pre_probe: cannot open %s\n", sig_path);
        return 1;
    }
    const size_t npix = (size_t)cfg.width * cfg.height;
    uint16_t *buf = malloc(npix * 2u);
    printf("frame,flags,shift_x,shift_y,sd_x,sd_y,coarse_x,coarse_y,reg_rms,sigma_min,sigma_mean,"
           "sigma_max,masked,peaks,candidates\n");
    for (uint32_t k = 0; fread(buf, 2u, npix, in) == npix; ++k) {
        pft_frame_t f;
        memset(&f, 0, sizeof f);
        f.data = buf;
        f.width = cfg.width;
        f.height = cfg.height;
        f.stride_bytes = 2u * cfg.width;
        f.format = PFT_PIX_U16;
        f.bit_depth = cfg.bit_depth;
        f.seq = k;
        pft_status_t s = pft_pre_update(&pre, &f);
        if (s != PFT_OK) {
            fprintf(stderr, "pre_probe: frame %u: %s\n", k, pft_status_str(s));
            return 1;
        }
        pft_pre_stats_t st;
        pft_pre_stats(&pre, &st);
        if (clutter) {
            pft_frame_t r;
            pft_pre_frame(&pre, &r);
            const bool ev = (st.flags & (PFT_PRE_FLAG_CONSTANT | PFT_PRE_FLAG_ALL_MASKED |
                                         PFT_PRE_FLAG_REG_LOST)) == 0u;
            s = pft_pre_clutter_update(&cl, &r, st.shift[0], st.shift[1], ev);
            if (s != PFT_OK) {
                fprintf(stderr, "pre_probe: clutter frame %u: %s\n", k, pft_status_str(s));
                return 1;
            }
        }
        printf("%u,%u,%.5f,%.5f,%.5f,%.5f,%d,%d,%.3f,%.3f,%.3f,%.3f,%u,%u,%u\n", k, st.flags,
               st.shift[0] / 65536.0, st.shift[1] / 65536.0, st.shift_sd[0] / 65536.0,
               st.shift_sd[1] / 65536.0, st.shift_coarse[0], st.shift_coarse[1],
               st.reg_rms / 65536.0, st.sigma_min / 65536.0, st.sigma_mean / 65536.0,
               st.sigma_max / 65536.0, st.n_masked, st.n_peaks, st.n_candidates);
        if (sig != NULL) { /* every tile's sigma, uint32 Q16.16 counts, row-major */
            static uint32_t tsig[4096];
            const size_t nt = pft_pre_sigma(&pre, tsig, 4096u);
            fwrite(tsig, 4u, nt < 4096u ? nt : 4096u, sig);
        }
        if (out != NULL) {
            pft_frame_t r;
            if (clutter) {
                pft_pre_clutter_frame(&cl, &r);
            } else {
                pft_pre_frame(&pre, &r);
            }
            fwrite(r.data, 2u, npix, out);
        }
    }
    fclose(in);
    if (sig != NULL) {
        fclose(sig);
    }
    if (out != NULL) {
        fclose(out);
    }
    free(buf);
    free(work);
    free(cwork);
    return 0;
}
