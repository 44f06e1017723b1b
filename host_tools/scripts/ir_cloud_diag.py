#!/usr/bin/env python3
"""Diagnosis of the IR pipeline in clouds (docs/results/ir_clutter.md, "Clouds: diagnosis and the
stage's edge term"). For each seed: `pft sim` of a sweep point (raw frames),
the stage's whitened residual by tests/tools/pre_probe (the pipeline's stage settings: tile 32,
temporal background, alpha 0.15), `pft run` of the pipeline on the same frames; then

  - the residual against the local gradient of the scene (|grad| of the frame smoothed by a
    Gaussian of 1 px, in temporal sigmas per pixel): rms, share above 3 sigma, 3x3 peaks >= 3
    per 10^4 pixels and the lag-1 correlation of a pixel's residual over consecutive frames, per
    gradient band, target neighbourhoods left out;
  - every false TBD track (never within 3 px of a truth point at the same frame): the gradient
    and the residual at its first position;
  - every injected target: detected or not, the gradient along its path, its whitened peak
    and the rank of its 3x3 peak among the frame's 3x3 peaks (births draw from the 256 highest).

Needs numpy, scipy and matplotlib. Not a test. Usage:

  python3 host_tools/scripts/ir_cloud_diag.py BUILD OUT [--seeds 1-10] [--snr 09]
      [--background clear] [--patch JSON] [--figure PNG --figure-seed 2 --figure-frame 60]
"""
import argparse
import csv
import json
import os
import subprocess

import numpy as np
from scipy import ndimage

from ir_diag_assoc import associate, tracks_by_id

HERE = os.path.dirname(os.path.abspath(__file__))
SC = os.path.join(HERE, '..', 'scenarios', 'tbd_ir')
W, H, SIGMA_T = 384, 288, 20.0
GBANDS = [0, 1, 2, 4, 8, 16, 32, 1e9]


def run(cmd):
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)


def seq(build, out, snr, seed, patch, probe_args):
    d = os.path.join(out, f's{seed}')
    os.makedirs(d, exist_ok=True)
    s = json.load(open(os.path.join(SC, f'sweep_snr_{snr}db.json')))
    for sec, val in patch.items():
        if sec == 'background' and val == 'clear':
            s['background'] = {"source": "procedural", "cloud_cover": 0, "horizon": None}
        elif isinstance(val, dict) and isinstance(s.get(sec), dict):
            s[sec].update(val)
        else:
            s[sec] = val
    sc = os.path.join(d, 'scenario.json')
    json.dump(s, open(sc, 'w'), indent=1)
    if not os.path.exists(os.path.join(d, 'frames.u16')):
        run([os.path.join(build, 'host_tools', 'pft'), 'sim', '--scenario', sc, '--seed', str(seed),
             '--out', d, '--format', 'raw', '-q'])
    res = os.path.join(d, 'res.i16')
    if not os.path.exists(res):
        run([os.path.join(build, 'tests', 'tools', 'pre_probe'), os.path.join(d, 'frames.u16'),
             str(W), str(H), '14', 'tile=32', 'peaks=0'] + probe_args + ['out=' + res])
    if not os.path.exists(os.path.join(d, 'run', 'tracks.csv')):
        run([os.path.join(build, 'host_tools', 'pft'), 'run', '--sequence', d, '--out',
             os.path.join(d, 'run'), '--no-video', '-q'])
    z = np.fromfile(os.path.join(d, 'frames.u16'), dtype='<u2').reshape(-1, H, W) & 0x3FFF
    r = np.fromfile(res, dtype='<i2').reshape(-1, H, W)
    truth = list(csv.DictReader(open(os.path.join(d, 'truth.csv'))))
    tracks = list(csv.DictReader(open(os.path.join(d, 'run', 'tracks.csv'))))
    return z, r, truth, tracks


def grad(frame):
    s = ndimage.gaussian_filter(frame.astype(np.float32), 1.0)
    gy, gx = np.gradient(s)
    return np.hypot(gx, gy) / SIGMA_T


def peaks3(wf):
    mx = ndimage.maximum_filter(wf, size=3, mode='constant', cval=-1e9)
    return (wf == mx) & (wf >= 3.0)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('build')
    ap.add_argument('out')
    ap.add_argument('--seeds', default='1-10')
    ap.add_argument('--snr', default='09')
    ap.add_argument('--patch', default='{}')
    ap.add_argument('--background')
    ap.add_argument('--probe', default='', help='extra pre_probe key=value arguments, space separated')
    ap.add_argument('--skip', type=int, default=20)
    ap.add_argument('--figure')
    ap.add_argument('--figure-seed', type=int, default=2)
    ap.add_argument('--figure-frame', type=int, default=60)
    a = ap.parse_args()
    lo, hi = (int(v) for v in a.seeds.split('-'))
    patch = json.loads(a.patch)
    if a.background:
        patch['background'] = a.background
    probe_args = a.probe.split()
    nb = len(GBANDS) - 1
    npx, s2, n3, npk = np.zeros(nb), np.zeros(nb), np.zeros(nb), np.zeros(nb)
    c1, c1n = np.zeros(nb), np.zeros(nb)  # lag-1 products (same pixel, consecutive frames)
    false_rows, tgt_rows = [], []
    for seed in range(lo, hi + 1):
        z, r, truth, tracks = seq(a.build, a.out, a.snr, seed, patch, probe_args)
        nf = r.shape[0]
        tpos = {}
        for t in truth:
            tpos.setdefault(int(t['frame']), []).append((float(t['x']), float(t['y']), int(t['id']), t['kind']))
        # tracks: associated if within 3 px of a truth point at the same frame, at any frame
        byid = tracks_by_id(tracks)
        assoc = associate(truth, byid)
        gcache = {}

        def g_of(k):
            if k not in gcache:
                gcache[k] = grad(z[k])
            return gcache[k]

        for k in range(a.skip, nf):
            valid = r[k] != -32768
            wf = np.where(valid, r[k] / 256.0, 0.0)
            near = np.zeros((H, W), bool)
            for tx, ty, _, _ in tpos.get(k + 1, []):
                x0, y0 = int(round(tx)), int(round(ty))
                near[max(0, y0 - 4):y0 + 5, max(0, x0 - 4):x0 + 5] = True
            sel = valid & ~near
            g = g_of(k)
            pk = peaks3(wf) & sel
            idx = np.digitize(g[sel], GBANDS) - 1
            np.add.at(npx, idx, 1)
            np.add.at(s2, idx, wf[sel] ** 2)
            np.add.at(n3, idx, (wf[sel] > 3.0).astype(float))
            np.add.at(npk, np.digitize(g[pk], GBANDS) - 1, 1)
            vp = r[k - 1] != -32768
            both = sel & vp
            wp = r[k - 1][both] / 256.0
            np.add.at(c1, np.digitize(g[both], GBANDS) - 1, wf[both] * wp)
            np.add.at(c1n, np.digitize(g[both], GBANDS) - 1, 1)
        for tid, pts in byid.items():
            if tid in assoc:
                continue
            fr, x, y = pts[0]
            k = fr - 1
            g = g_of(k)
            xi, yi = min(W - 1, max(0, int(round(x)))), min(H - 1, max(0, int(round(y))))
            rk = r[k][max(0, yi - 1):yi + 2, max(0, xi - 1):xi + 2]
            wmax = rk[rk != -32768].max() / 256.0 if (rk != -32768).any() else float('nan')
            false_rows.append((seed, tid, fr, x, y, len(pts), float(g[yi, xi]),
                               float(np.mean(g >= g[yi, xi])), wmax))
        for gid in sorted({int(t['id']) for t in truth if t['kind'] == 'injected'}):
            pts = [(int(t['frame']), float(t['x']), float(t['y'])) for t in truth if int(t['id']) == gid]
            det = any(gid in s for s in assoc.values())
            gs, ws, ranks = [], [], []
            for fr, x, y in pts:
                k = fr - 1
                if k < 1 or k >= nf:
                    continue
                xi, yi = int(round(x)), int(round(y))
                if not (1 <= xi < W - 1 and 1 <= yi < H - 1):
                    continue
                valid = r[k] != -32768
                wf = np.where(valid, r[k] / 256.0, -1e9)
                wt = wf[yi - 1:yi + 2, xi - 1:xi + 2].max()
                if wt < -1e8:
                    continue
                mx = ndimage.maximum_filter(wf, size=3, mode='constant', cval=-1e9)
                pk = (wf == mx) & valid
                gs.append(float(g_of(k)[yi, xi]))
                ws.append(float(wt))
                ranks.append(int(np.count_nonzero(wf[pk] > wt)))
            if ws:
                tgt_rows.append((seed, gid, det, len(ws), float(np.median(gs)), float(np.mean(ws)),
                                 float(np.median(ranks)), float(np.mean(np.array(ranks) < 256))))
        if a.figure and seed == a.figure_seed:
            make_figure(a.figure, z, r, byid, assoc, tpos, a.figure_frame, g_of(a.figure_frame - 1))
    print(f'seeds {lo}-{hi}, {a.snr} dB, patch {json.dumps(patch)}, probe {a.probe!r}, frames > {a.skip}')
    print('\n| gradient (sigma_t / px) | pixels | residual rms | share > 3 sigma | 3x3 peaks >= 3 per 10^4 px | lag-1 correlation |')
    print('|---|---|---|---|---|---|')
    for i in range(nb):
        if npx[i] == 0:
            continue
        hi_s = '' if GBANDS[i + 1] > 1e8 else f'{GBANDS[i + 1]:g}'
        print(f'| {GBANDS[i]:g}–{hi_s} | {100 * npx[i] / npx.sum():.1f} % | {np.sqrt(s2[i] / npx[i]):.2f} | '
              f'{n3[i] / npx[i]:.4f} | {1e4 * npk[i] / npx[i]:.1f} | {c1[i] / c1n[i] / (s2[i] / npx[i]):.2f} |')
    tot = npx.sum()
    print(f'| all | 100 % | {np.sqrt(s2.sum() / tot):.2f} | {n3.sum() / tot:.4f} | {1e4 * npk.sum() / tot:.1f} | '
          f'{c1.sum() / c1n.sum() / (s2.sum() / tot):.2f} |')
    print(f'\nfalse tracks: {len(false_rows)}')
    if false_rows:
        fg = np.array([f[6] for f in false_rows])
        fl = np.array([f[5] for f in false_rows])
        fw = np.array([f[8] for f in false_rows])
        share = npx / tot
        print('  first-position gradient (sigma_t/px): median %.1f; share in bands %s (pixels: %s)' % (
            np.median(fg), ' '.join(f'{100 * np.mean((fg >= GBANDS[i]) & (fg < GBANDS[i + 1])):.0f}%' for i in range(nb)),
            ' '.join(f'{100 * s:.0f}%' for s in share)))
        print('  reported frames: median %.0f, mean %.1f; stage residual max 3x3 at first position: median %.2f' % (
            np.median(fl), fl.mean(), np.nanmedian(fw)))
    print(f'\ninjected targets: {len(tgt_rows)}, detected {sum(t[2] for t in tgt_rows)}')
    print('| seed | id | detected | frames | median gradient | mean whitened peak | median rank of its peak | share of frames in the top 256 |')
    print('|---|---|---|---|---|---|---|---|')
    for t in tgt_rows:
        print(f'| {t[0]} | {t[1]} | {"yes" if t[2] else "no"} | {t[3]} | {t[4]:.1f} | {t[5]:.2f} | {t[6]:.0f} | {100 * t[7]:.0f} % |')
    for det in (True, False):
        sub = [t for t in tgt_rows if t[2] == det]
        if sub:
            print('%s: %d, median gradient %.1f, mean whitened peak %.2f, median rank %.0f, top-256 share %.0f %%' % (
                'detected' if det else 'missed', len(sub), np.median([t[4] for t in sub]),
                np.mean([t[5] for t in sub]), np.median([t[6] for t in sub]), 100 * np.mean([t[7] for t in sub])))


def make_figure(path, z, r, byid, assoc, tpos, frame, g):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    k = frame - 1
    valid = r[k] != -32768
    wf = np.where(valid, r[k] / 256.0, 0.0)
    # local rms of the whitened residual over 7 x 7 (1.0 where the tile sigma fits)
    lr = np.sqrt(ndimage.uniform_filter(wf ** 2, 7))
    fig, ax = plt.subplots(2, 2, figsize=(10, 7.6))
    panels = [(z[k], 'frame %d (counts)' % frame, 'gray', None),
              (np.clip(g, 0, 64), '|grad| of the scene (sigma_t / px, clipped at 64)', 'magma', None),
              (np.clip(wf, -5, 5), 'whitened residual of the stage (sigma, clipped at 5)', 'RdBu_r', (-5, 5)),
              (np.clip(lr, 0, 4), 'local rms of the whitened residual, 7 x 7 (1 = tile sigma right)', 'viridis', (0, 4))]
    for a, (img, title, cmap, lim) in zip(ax.flat, panels):
        im = a.imshow(img, cmap=cmap, vmin=None if lim is None else lim[0], vmax=None if lim is None else lim[1])
        a.set_title(title, fontsize=8)
        a.set_xticks([])
        a.set_yticks([])
        fig.colorbar(im, ax=a, fraction=0.035)
    for tid, pts in byid.items():
        xs = [p[1] for p in pts]
        ys = [p[2] for p in pts]
        c = 'lime' if tid in assoc else 'red'
        for a in ax.flat:
            a.plot(xs, ys, '-', color=c, lw=0.8)
            a.plot(xs[0], ys[0], 'o', color=c, ms=3, mfc='none')
    for tx, ty, _, _ in tpos.get(frame, []):
        for a in ax.flat:
            a.plot(tx, ty, 's', color='cyan', ms=6, mfc='none')
    fig.suptitle('TBD tracks over the run (red: false, green: on a target; o: first point), '
                 'cyan squares: targets at frame %d' % frame, fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=80)


if __name__ == '__main__':
    main()
