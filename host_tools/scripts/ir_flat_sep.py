#!/usr/bin/env python3
"""Which mechanism makes the slow residual offset on the real backgrounds (docs/results/
ir_clutter.md, "Branch irnuc"): for each seed of the 9 dB sweep point, `pft sim` (run i on
ir_sky image (i - 1) mod 29) with the sensor's vignetting as given and with 0, then the stage
alone (tests/tools/pre_probe, library defaults) over the raw frames, and

  - registration: the stage's shift against the simulator's true frame-to-frame shift
    (platform.csv: the scene moves by minus the platform's step), rms error and mean error per
    axis over frames 3..100, with and without vignetting;
  - lag of the temporal background behind the sensor-fixed gain g (the simulator's
    1 - v r^2 / r_max^2): with the scene moving by u px per frame and the background a
    recursive mean with weight a, the background at p holds the scene seen through
    g(p - k u) k frames ago, weight a (1 - a)^k: b = S (g - L grad g . u), L = (1 - a) / a,
    so the residual r = S L grad g . u, S = z / g the scene, in the stage's sigma. The
    predicted map (from the time mean of the frames) against the measured time mean of the
    whitened residual (frames 21..100), both as 9 x 9 means 8 px from the border: the slope
    of the measured on the predicted, their correlation, and the rms of each and of the
    measured less the predicted.

Needs numpy and scipy; evaluation only (the ir_sky images are not part of the project).

  python3 host_tools/scripts/ir_flat_sep.py BUILD OUT --ir-sky DIR [--seeds 1-29] [--vignetting 0.2]
"""
import argparse
import csv
import json
import os
import subprocess

import numpy as np
from scipy import ndimage as nd

HERE = os.path.dirname(os.path.abspath(__file__))
SC = os.path.join(HERE, '..', 'scenarios', 'tbd_ir', 'sweep_snr_09db.json')
KINDS = os.path.join(HERE, 'ir_sky_kinds.csv')
W, H = 384, 288
ALPHA = 9830 / 65536.0  # the stage's default bg_alpha


def run_seed(a, seed, vig):
    d = os.path.join(a.out, f'v{vig:g}_s{seed}')
    os.makedirs(d, exist_ok=True)
    s = json.load(open(SC))
    s['sensor']['vignetting'] = vig
    json.dump(s, open(os.path.join(d, 'scenario.json'), 'w'))
    if not os.path.exists(os.path.join(d, 'frames.u16')):
        subprocess.run(['nice', os.path.join(a.build, 'host_tools', 'pft'), 'sim', '--scenario',
                        os.path.join(d, 'scenario.json'), '--seed', str(seed), '--out', d, '--format', 'raw',
                        '-q', '--backgrounds', a.ir_sky], check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
    if not os.path.exists(os.path.join(d, 'probe.csv')):
        with open(os.path.join(d, 'probe.csv'), 'w') as fo:
            subprocess.run(['nice', os.path.join(a.build, 'tests', 'tools', 'pre_probe'),
                            os.path.join(d, 'frames.u16'), str(W), str(H), '14',
                            'out=' + os.path.join(d, 'res.i16')], check=True, stdout=fo)
    pr = list(csv.DictReader(open(os.path.join(d, 'probe.csv'))))
    pl = np.array([[float(r['x']), float(r['y'])] for r in csv.DictReader(open(os.path.join(d, 'platform.csv')))])
    true = -(pl[1:] - pl[:-1])  # frame k (0-based, k >= 1): the scene's step
    est = np.array([[float(r['shift_x']), float(r['shift_y'])] for r in pr])[1:]
    err = (est - true)[2:]
    z = np.fromfile(os.path.join(d, 'frames.u16'), np.uint16).reshape(-1, H, W).astype(np.float64)
    r = np.fromfile(os.path.join(d, 'res.i16'), np.int16).reshape(-1, H, W)
    rm = np.where(r == -32768, 0.0, r / 256.0)[20:].mean(0)
    cx, cy = (W - 1) / 2.0, (H - 1) / 2.0
    yy, xx = np.mgrid[0:H, 0:W].astype(np.float64)
    r2max = cx * cx + cy * cy
    g = 1.0 - vig * ((xx - cx) ** 2 + (yy - cy) ** 2) / r2max
    gx, gy = -2.0 * vig * (xx - cx) / r2max, -2.0 * vig * (yy - cy) / r2max
    u = true[2:].mean(0)
    sig = np.mean([float(q['sigma_mean']) for q in pr[20:]])
    scene = z[20:].mean(0) / g
    pred = scene * (1.0 - ALPHA) / ALPHA * (gx * u[0] + gy * u[1]) / sig
    m9 = nd.uniform_filter(rm, 9)[8:-8, 8:-8].ravel()
    p9 = nd.uniform_filter(pred, 9)[8:-8, 8:-8].ravel()
    slope = float(np.dot(m9, p9) / np.dot(p9, p9)) if np.dot(p9, p9) > 0 else float('nan')
    corr = float(np.corrcoef(m9, p9)[0, 1]) if p9.std() > 0 else float('nan')
    return dict(err_rms=np.sqrt((err ** 2).mean(0)), err_mean=err.mean(0), meas=np.sqrt((m9 ** 2).mean()),
                pred=np.sqrt((p9 ** 2).mean()), left=np.sqrt(((m9 - p9) ** 2).mean()), slope=slope, corr=corr,
                scene=float(scene.mean()))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('build')
    ap.add_argument('out')
    ap.add_argument('--ir-sky', required=True)
    ap.add_argument('--seeds', default='1-29')
    ap.add_argument('--vignetting', type=float, default=0.2)
    a = ap.parse_args()
    lo, hi = (int(v) for v in a.seeds.split('-'))
    kinds = dict(csv.reader(open(KINDS)))
    files = sorted(f for f in os.listdir(a.ir_sky) if f.endswith('.png'))
    res = {}
    for seed in range(lo, hi + 1):
        kind = kinds[files[(seed - 1) % len(files)]]
        for vig in (a.vignetting, 0.0):
            res.setdefault((kind, vig), []).append(run_seed(a, seed, vig))
    print(f'seeds {lo}-{hi}, 9 dB sweep point, stage defaults (bg_alpha {ALPHA:.3f}: L = {(1 - ALPHA) / ALPHA:.2f} frames)')
    print('\n| kind | vignetting | runs | shift error rms x / y (px) | mean error x / y (px) | time-mean residual, 9 x 9, rms (sigma) | lag term predicted, rms | slope measured / predicted | correlation | measured less predicted, rms |')
    print('|---|---|---|---|---|---|---|---|---|---|')
    for kind in sorted({k for k, _ in res}):
        for vig in (a.vignetting, 0.0):
            v = res[(kind, vig)]
            f = lambda key: np.mean([q[key] for q in v], axis=0)
            er, em = f('err_rms'), f('err_mean')
            print(f'| {kind} | {vig:g} | {len(v)} | {er[0]:.4f} / {er[1]:.4f} | {em[0]:+.4f} / {em[1]:+.4f} | '
                  f'{f("meas"):.3f} | {f("pred"):.3f} | {np.nanmedian([q["slope"] for q in v]):.2f} | '
                  f'{np.nanmedian([q["corr"] for q in v]):.2f} | {f("left"):.3f} |')
    print('\n(means over the runs; slope and correlation: medians)')


if __name__ == '__main__':
    main()
