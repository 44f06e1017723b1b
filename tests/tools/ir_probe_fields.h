/*
 * ir_probe_fields.h: the fields of the library configurations that the IR pipeline's flight
 * build sets up (host_tools/tbd/ir_pipeline.cpp), one X-macro list per configuration struct,
 * shared by the writer (`pft bench --probe-out DIR`, host_tools/tbd/ir_probe_out.cpp) and the
 * reader (tests/tools/ir_probe.c, mode -c), so that both name the same keys.
 *
 * Each entry is X(FIELD, KIND, TYPE): FIELD the member (an array element written out, as
 * vel_mean[0]), KIND U (unsigned integer, bool or enum, written in decimal), I (signed integer)
 * or R (pft_real_t: its 32 bits written in hex, exact in both builds; the file names its
 * numeric, and a reader of the other numeric refuses it), TYPE the member's type (the reader's
 * cast). The key of a field is "<section>.<FIELD>" with the sections pre, flat, clutter, tbd,
 * scene.
 *
 * A field added to one of these structs must be added here: the writer checks on x86-64 that
 * the sizes of the listed fields add up to the struct's size less its known padding (a field
 * that fits into padding is not caught), and the host test host_ir_probe_flight (ctest) runs
 * ir_probe on a small flight-build scenario against the host pipeline, bit for bit.
 */
#ifndef PFT_TESTS_IR_PROBE_FIELDS_H
#define PFT_TESTS_IR_PROBE_FIELDS_H

/* pft_pre_config_t (bad_map is not listed: the pipeline sets none, and the writer refuses one) */
#define IRP_PRE_FIELDS(X)                        \
    X(width, U, uint16_t)                        \
    X(height, U, uint16_t)                       \
    X(format, U, pft_pixfmt_t)                   \
    X(bit_depth, U, uint8_t)                     \
    X(method, U, pft_pre_bg_t)                   \
    X(sat_level, U, uint16_t)                    \
    X(dead_level, U, uint16_t)                   \
    X(local_outer, U, uint8_t)                   \
    X(local_guard, U, uint8_t)                   \
    X(bg_alpha, U, uint16_t)                     \
    X(reg_search, U, uint8_t)                    \
    X(reg_iters, U, uint8_t)                     \
    X(reg_step, U, uint8_t)                      \
    X(warp_cubic, U, bool)                       \
    X(col_alpha, U, uint16_t)                    \
    X(tile, U, uint8_t)                          \
    X(sigma_interp, U, bool)                     \
    X(sigma_current, U, bool)                    \
    X(sigma_floor, U, uint16_t)                  \
    X(edge_k, U, uint16_t)                       \
    X(peak_max, U, uint16_t)                     \
    X(peak_threshold, I, int16_t)                \
    X(inplace, U, bool)                          \
    X(sigma_step, U, uint8_t)                    \
    X(sigma_every, U, uint8_t)                   \
    X(reg_bin, U, bool)                          \
    X(sigma_bracket, U, bool)                    \
    X(bg_anchor, U, bool)                        \
    X(bg_gate, U, uint16_t)                      \
    X(bg_gate_shift, U, uint8_t)                 \
    X(bg_gate_young, U, uint8_t)                 \
    X(bg_gate_local, U, uint8_t)                 \
    X(bg_masked_taps, U, uint8_t)                \
    X(bg_stale_reinit, U, uint8_t)               \
    X(bg_young_clip, U, uint16_t)                \
    X(sigma_level, U, bool)                      \
    X(bg_edge_narrow, U, uint8_t)                \
    X(bg_young_scale, U, bool)

/* pft_pre_flat_config_t */
#define IRP_FLAT_FIELDS(X)                       \
    X(width, U, uint16_t)                        \
    X(height, U, uint16_t)                       \
    X(block, U, uint8_t)                         \
    X(alpha, U, uint16_t)                        \
    X(gate, U, uint16_t)                         \
    X(relative, U, bool)                         \
    X(rescale, U, bool)

/* pft_pre_clutter_config_t */
#define IRP_CLUTTER_FIELDS(X)                    \
    X(width, U, uint16_t)                        \
    X(height, U, uint16_t)                       \
    X(alpha, U, uint16_t)                        \
    X(blur, U, uint8_t)                          \
    X(box, U, bool)                              \
    X(mean, U, bool)                             \
    X(thr, U, uint16_t)                          \
    X(veto, U, uint16_t)                         \
    X(persist, U, uint8_t)                       \
    X(excess, U, uint16_t)                       \
    X(inplace, U, bool)                          \
    X(block, U, uint8_t)                         \
    X(map8, U, bool)                             \
    X(anchor, U, bool)                           \
    X(mean_floor, U, uint16_t)                   \
    X(floor_age, U, uint8_t)

/* pft_tbd_config_t */
#define IRP_TBD_FIELDS(X)                        \
    X(width, U, uint16_t)                        \
    X(height, U, uint16_t)                       \
    X(dx, R, pft_real_t)                         \
    X(dy, R, pft_real_t)                         \
    X(psf_sigma, R, pft_real_t)                  \
    X(noise_sigma, R, pft_real_t)                \
    X(pixel_gain, R, pft_real_t)                 \
    X(pixel_offset, R, pft_real_t)               \
    X(window, U, uint8_t)                        \
    X(T, R, pft_real_t)                          \
    X(q1, R, pft_real_t)                         \
    X(q2, R, pft_real_t)                         \
    X(pb, R, pft_real_t)                         \
    X(pd, R, pft_real_t)                         \
    X(eta, R, pft_real_t)                        \
    X(gamma, R, pft_real_t)                      \
    X(i_min, R, pft_real_t)                      \
    X(i_max, R, pft_real_t)                      \
    X(vel_mean[0], R, pft_real_t)                \
    X(vel_mean[1], R, pft_real_t)                \
    X(vel_var[0], R, pft_real_t)                 \
    X(vel_var[1], R, pft_real_t)                 \
    X(birth_correction, U, bool)                 \
    X(birth_peaks, U, uint16_t)                  \
    X(peak_gamma, R, pft_real_t)                 \
    X(peak_tile, U, uint8_t)                     \
    X(peak_quota, U, uint8_t)                    \
    X(birth_share, R, pft_real_t)                \
    X(theta1, R, pft_real_t)                     \
    X(confirm_frames, U, uint8_t)                \
    X(dis_r, U, uint8_t)                         \
    X(dis_prev, U, uint8_t)                      \
    X(dis_ratio, R, pft_real_t)                  \
    X(dis_ratio_test, U, bool)                   \
    X(theta_end, R, pft_real_t)                  \
    X(d_margin, U, uint8_t)                      \
    X(d_current, U, bool)                        \
    X(force_constraint, U, bool)                 \
    X(d_region, U, pft_tbd_dregion_t)            \
    X(residual_search, U, bool)                  \
    X(residual_tracks, U, bool)                  \
    X(residual_margin, U, uint8_t)               \
    X(handover_gate, U, uint8_t)                 \
    X(end_lr_frames, U, uint8_t)                 \
    X(end_lr_max, R, pft_real_t)                 \
    X(n_search, U, uint32_t)                     \
    X(n_track, U, uint32_t)                      \
    X(max_targets, U, uint16_t)                  \
    X(kind, U, pft_tbd_kind_t)                   \
    X(kf_variant, U, pft_tbd_kf_variant_t)       \
    X(seed, U, uint64_t)                         \
    X(seq_mode, U, pft_seq_mode_t)               \
    X(max_gap, U, uint16_t)                      \
    X(frame_format, U, pft_pixfmt_t)             \
    X(sprt_accept, R, pft_real_t)                \
    X(sprt_reject, R, pft_real_t)                \
    X(shape_ring, R, pft_real_t)                 \
    X(sprt_start, U, uint8_t)                    \
    X(integ_alpha, R, pft_real_t)                \
    X(end_grace_frames, U, uint8_t)              \
    X(theta_end_grace, R, pft_real_t)            \
    X(end_persist, U, uint8_t)                   \
    X(handover_in_scale, R, pft_real_t)          \
    X(split_px, R, pft_real_t)                   \
    X(split_share, R, pft_real_t)                \
    X(resid_split, R, pft_real_t)                \
    X(resid_split_frames, U, uint8_t)            \
    X(resid_split_age, U, uint8_t)               \
    X(search_layers, U, uint8_t)                 \
    X(search_sep, R, pft_real_t)                 \
    X(search_hold, R, pft_real_t)

/* pft_tbd_scene_config_t */
#define IRP_SCENE_FIELDS(X)                      \
    X(frames, U, uint32_t)                       \
    X(max_tracks, U, uint32_t)                   \
    X(gate_px, R, pft_real_t)                    \
    X(fit_px, R, pft_real_t)                     \
    X(early_px, R, pft_real_t)                   \
    X(forget_frames, U, uint32_t)                \
    X(width, U, uint32_t)                        \
    X(height, U, uint32_t)                       \
    X(hold_frames, U, uint32_t)                  \
    X(spread_px, R, pft_real_t)                  \
    X(spread_hold, U, uint32_t)                  \
    X(slow_frames, U, uint32_t)                  \
    X(slow_low_px, R, pft_real_t)                \
    X(slow_gate_px, R, pft_real_t)               \
    X(spread_exist, R, pft_real_t)               \
    X(edge_px, R, pft_real_t)                    \
    X(edge_still_px, R, pft_real_t)              \
    X(edge_shift_px, R, pft_real_t)              \
    X(move_px, R, pft_real_t)                    \
    X(move_hold, U, uint32_t)

/* The pipeline's own settings between the calls (IrPipeline::preprocess and ::step), key
 * "pipeline.<name>", unsigned: bits (the frames' bit depth), flat (the flat-field step runs:
 * flat_block > 0), flat_relative (its level frame is the raw frame), clutter (the clutter map
 * runs: clutter_alpha > 0), scene (the scene-motion test runs: scene_frames > 0),
 * scene_tentative (the test also takes the tentative tracks of age > 0), integ_shift (the
 * manager is given the stage's shift, pft_tbd_set_shift, on frames with evidence). */
#define IRP_PIPELINE_FIELDS(X) \
    X(bits)                    \
    X(flat)                    \
    X(flat_relative)           \
    X(clutter)                 \
    X(scene)                   \
    X(scene_tentative)         \
    X(integ_shift)

#endif
