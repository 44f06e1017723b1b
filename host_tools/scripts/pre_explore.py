#!/usr/bin/env python3
"""Exploration of the preprocessing stage (pft_pre.h) on drifting IR scenes; the numbers of
docs/results/ir_clutter.md, "Preprocessing building blocks". Not a test.

A scene is a background image (a real 8-bit IR frame scaled x64 to 14 bits, or a procedural
cloud field), blurred by the optics (Gaussian, sigma 0.7 px), translated by a cumulative drift
(dx, dy per frame plus N(0, jitter) per axis), with temporal noise N(0, sigma_t) counts and an
optional sensor-fixed column offset N(0, sigma_col) per column, rounded and clipped to 14 bits.
The stage runs through tests/tools/pre_probe (built from the library); the script compares the
registration with the true frame-to-frame shifts and the residual with the temporal noise.

  python3 host_tools/scripts/pre_explore.py PROBE [--images DIR | --procedural N] [options]
"""
import argparse
import csv
import io
import os
import subprocess
import sys
import tempfile

import numpy as np
from scipy import ndimage


def procedural(seed, w=384, h=288):
    """A cloud-like 14-bit background: sum of smoothed noise octaves, a sky gradient."""
    rng = np.random.default_rng(seed)
    img = np.zeros((h, w))
    for s, a in ((32, 1.0), (12, 0.5), (5, 0.25), (2, 0.12)):
        img += a * ndimage.gaussian_filter(rng.standard_normal((h, w)), s) * s
    img = (img - img.min()) / (np.ptp(img) + 1e-9)
    yy = np.linspace(0, 1, h)[:, None]
    return 2000 + 9000 * (0.6 * img + 0.4 * yy)


def load_image(path):
    from matplotlib import image as mpimg
    a = mpimg.imread(path)
    if a.ndim == 3:
        a = a[..., :3].mean(axis=2)
    if a.dtype != np.uint8:
        a = np.round(a * 255.0)
    return a.astype(np.float64) * 64.0


def make_sequence(bg, n, drift, jitter, sigma_t, sigma_col, blur, seed):
    rng = np.random.default_rng(seed)
    h, w = bg.shape
    base = ndimage.gaussian_filter(bg, blur) if blur > 0 else bg
    pos = np.zeros(2)
    shifts = []
    col = rng.normal(0.0, sigma_col, w) if sigma_col > 0 else np.zeros(w)
    frames = np.empty((n, h, w), np.uint16)
    for k in range(n):
        if k > 0:
            step = np.array(drift) + rng.normal(0.0, jitter, 2)
            pos += step
            shifts.append(step.copy())
        else:
            shifts.append(np.zeros(2))
        img = ndimage.shift(base, (pos[1], pos[0]), order=3, mode='reflect')
        img = img + rng.normal(0.0, sigma_t, (h, w)) + col[None, :]
        frames[k] = np.clip(np.round(img), 0, 16383).astype(np.uint16)
    return frames, np.array(shifts)


def run_probe(probe, frames, args, out=False):
    n, h, w = frames.shape
    with tempfile.TemporaryDirectory() as d:
        fin = os.path.join(d, 'in.u16')
        frames.astype('<u2').tofile(fin)
        cmd = [probe, fin, str(w), str(h), '14'] + args
        fres = os.path.join(d, 'res.i16')
        if out:
            cmd.append('out=' + fres)
        r = subprocess.run(cmd, capture_output=True, text=True, check=True)
        rows = list(csv.DictReader(io.StringIO(r.stdout)))
        res = np.fromfile(fres, '<i2').reshape(n, h, w) if out else None
    return rows, res


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('probe')
    ap.add_argument('--images', help='folder of 8-bit PNG frames (the ir_sky development set)')
    ap.add_argument('--procedural', type=int, default=0, help='number of procedural scenes')
    ap.add_argument('--limit', type=int, default=0, help='use the first N images only')
    ap.add_argument('--frames', type=int, default=30)
    ap.add_argument('--drift', type=float, nargs=2, default=(0.3, 0.2))
    ap.add_argument('--jitter', type=float, default=0.1)
    ap.add_argument('--sigma-t', type=float, default=64.0)
    ap.add_argument('--sigma-col', type=float, default=0.0)
    ap.add_argument('--blur', type=float, default=0.7)
    ap.add_argument('--skip', type=int, default=10, help='frames left out of the residual figures')
    ap.add_argument('--method', default='temporal')
    ap.add_argument('--seed', type=int, default=1)
    ap.add_argument('--set', default='', help='"key=value ..." passed to pre_probe')
    ap.add_argument('--size', default='384x288', help='procedural scene size WxH')
    ap.add_argument('--write-seq', help='write the first scene as raw u16 frames here and stop')
    a = ap.parse_args()

    scenes = []
    if a.images:
        names = sorted(f for f in os.listdir(a.images) if f.lower().endswith('.png'))
        if a.limit:
            names = names[:a.limit]
        scenes += [(nm, load_image(os.path.join(a.images, nm))) for nm in names]
    pw, ph = (int(v) for v in a.size.split('x'))
    for i in range(a.procedural):
        scenes.append(('procedural%d' % i, procedural(a.seed * 1000 + i, pw, ph)))
    if not scenes:
        sys.exit('no scene: give --images or --procedural')

    if a.write_seq:
        frames, _ = make_sequence(scenes[0][1], a.frames, a.drift, a.jitter, a.sigma_t,
                                  a.sigma_col, a.blur, a.seed * 7919)
        frames.astype('<u2').tofile(a.write_seq)
        print('wrote %d frames %dx%d to %s' % (a.frames, frames.shape[2], frames.shape[1],
                                               a.write_seq))
        return
    errs, ratio_std, ratio_mad, sds = [], [], [], []
    for si, (name, bg) in enumerate(scenes):
        frames, truth = make_sequence(bg, a.frames, a.drift, a.jitter, a.sigma_t, a.sigma_col,
                                      a.blur, a.seed * 7919 + si)
        common = ['method=' + a.method] + a.set.split()
        rows, _ = run_probe(a.probe, frames, common)
        # raw residual in counts: every tile sigma floored at 8 sigma_t (above any tile sigma
        # here), so a Q8.8 value q is q * floor / 4096 counts (floor in counts Q4; one LSB is
        # sigma_t / 32)
        floor_q4 = min(65535, int(round(128 * a.sigma_t)))
        _, res = run_probe(a.probe, frames, common + ['floor=%d' % floor_q4], out=True)
        for k, r in enumerate(rows):
            if k == 0 or a.method != 'temporal':
                continue
            fl = int(r['flags'])
            if fl & (1 << 6):
                continue
            e = np.array([float(r['shift_x']), float(r['shift_y'])]) - truth[k]
            errs.append(e)
            sds.append([float(r['sd_x']), float(r['sd_y'])])
        for k in range(a.skip, a.frames):
            v = res[k][res[k] != -32768].astype(np.float64) * (floor_q4 / 4096.0)
            ratio_std.append(v.std() / a.sigma_t)
            ratio_mad.append(float(rows[k]['sigma_mean']) / a.sigma_t)
    print('scenes %d, frames %d each, drift %s, jitter %.2f, sigma_t %.0f, sigma_col %.0f'
          % (len(scenes), a.frames, a.drift, a.jitter, a.sigma_t, a.sigma_col))
    if errs:
        e = np.array(errs)
        print('shift error (px): rms x %.4f y %.4f, max |e| %.4f; predicted sd median %.4f'
              % (np.sqrt((e[:, 0] ** 2).mean()), np.sqrt((e[:, 1] ** 2).mean()),
                 np.abs(e).max(), np.median(np.array(sds))))
    rs, rm = np.array(ratio_std), np.array(ratio_mad)
    print('residual std / sigma_t: median %.3f, 90%% %.3f, max %.3f'
          % (np.median(rs), np.percentile(rs, 90), rs.max()))
    print('tile sigma (MAD) mean / sigma_t: median %.3f, 90%% %.3f, max %.3f'
          % (np.median(rm), np.percentile(rm, 90), rm.max()))


if __name__ == '__main__':
    main()
