#!/usr/bin/env python3
"""Why injected targets are missed and false tracks confirmed on the real backgrounds
(docs/results/ir_clutter.md, "Branch irdet (2026-12-03)"). For each seed of the 9 dB sweep point:
`pft sim` (raw frames; --ir-sky: run i on image (i - 1) mod 29, else the procedural sky of the
patch), `pft run --residual-out` (the residual the TBD manager sees, every frame), then

  - per injected target and frame (frames > 10, 6 px from the border): the residual at its
    nearest pixel against the nominal peak there (A exp(-d^2 / 2 psf^2), A = 2.818 at 9 dB),
    the rms of the residual on a ring 4-6 px around it, the PSF-matched value (3 x 3 taps,
    unit noise) at its 3 x 3 maximum and its rank among the frame's PSF-matched 3 x 3 local
    maxima (births draw from the 256 highest), split by kind and detected / missed;
  - the residual's statistics away from the border: rms, tails, the 256th and 64th highest
    PSF-matched peaks, the lag-1 correlation in time (same pixel) and along x, and its slowly
    varying part: the 9 x 9 mean per frame and the 9 x 9 mean of its time mean over frames
    21-100 (rms; white unit noise gives 0.111 and 0.012);
  - every false track (never within 3 px of a truth point): frames reported, the residual's
    3 x 3 maximum and the ring rms where it starts.

Needs numpy and scipy. Not a test; the ir_sky images are evaluation data only. Usage:

  python3 host_tools/scripts/ir_real_diag.py BUILD OUT --ir-sky DIR [--seeds 1-29] [--patch JSON]
  python3 host_tools/scripts/ir_real_diag.py BUILD OUT --seeds 5-8 --patch '{"background": {"source": "procedural", "cloud_cover": 0, "horizon": null}}'
"""
import argparse
import csv
import json
import os
import subprocess

import numpy as np
from scipy import ndimage as nd

from ir_diag_assoc import associate, tracks_by_id

HERE = os.path.dirname(os.path.abspath(__file__))
SC = os.path.join(HERE, '..', 'scenarios', 'tbd_ir', 'sweep_snr_09db.json')
KINDS = os.path.join(HERE, 'ir_sky_kinds.csv')
W, H = 384, 288
K1 = np.exp(-np.arange(-1, 2) ** 2 / (2 * 0.49))
KER = np.outer(K1, K1) / np.sqrt((np.outer(K1, K1) ** 2).sum())


def one_seed(a, seed, patch, files, kinds, rows, frows, stats):
    d = os.path.join(a.out, f's{seed}')
    os.makedirs(d, exist_ok=True)
    s = json.load(open(SC))
    for k, v in patch.items():
        if isinstance(v, dict) and isinstance(s.get(k), dict):
            s[k].update(v)
        else:
            s[k] = v
    json.dump(s, open(os.path.join(d, 'scenario.json'), 'w'))
    pft = os.path.join(a.build, 'host_tools', 'pft')
    if a.ir_sky:
        kind = kinds[files[(seed - 1) % len(files)]]
        bg = ['--backgrounds', a.ir_sky]
    else:
        kind = 'procedural ' + ('clear' if s['background'].get('cloud_cover') == 0 else 'clouds')
        bg = []
    if not os.path.exists(os.path.join(d, 'frames.u16')):
        subprocess.run(['nice', pft, 'sim', '--scenario', os.path.join(d, 'scenario.json'), '--seed', str(seed),
                        '--out', d, '--format', 'raw', '-q'] + bg, check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
    if not os.path.exists(os.path.join(d, 'res.i16')):
        subprocess.run(['nice', pft, 'run', '--sequence', d, '--out', os.path.join(d, 'run'), '--no-video', '-q',
                        '--residual-out', os.path.join(d, 'res.i16')], check=True, stdout=subprocess.DEVNULL)
    r = np.fromfile(os.path.join(d, 'res.i16'), np.int16).reshape(-1, H, W).astype(np.float32) / 256.0
    nf = r.shape[0]
    truth = list(csv.DictReader(open(os.path.join(d, 'truth.csv'))))
    tracks = list(csv.DictReader(open(os.path.join(d, 'run', 'tracks.csv'))))
    byid = tracks_by_id(tracks)
    assoc = associate(truth, byid)
    cache = {}

    def matched(k):
        if k not in cache:
            z = nd.correlate(r[k], KER, mode='constant')
            mx = nd.maximum_filter(z, 3, mode='constant', cval=-1e9)
            cache[k] = (z, np.sort(z[(z == mx) & (z > 1.0)])[::-1])
        return cache[k]

    def ring(k, xi, yi):
        q = r[k][yi - 6:yi + 7, xi - 6:xi + 7].copy()
        q[3:10, 3:10] = np.nan
        return float(np.sqrt(np.nanmean(q ** 2)))

    for gid in sorted({int(t['id']) for t in truth if t['kind'] == 'injected'}):
        det = any(gid in v for v in assoc.values())
        for t in truth:
            if int(t['id']) != gid:
                continue
            fr, x, y = int(t['frame']), float(t['x']), float(t['y'])
            k = fr - 1
            xi, yi = int(round(x)), int(round(y))
            if k < 10 or k >= nf or not (6 <= xi < W - 6 and 6 <= yi < H - 6):
                continue
            z, pk = matched(k)
            zt = z[yi - 1:yi + 2, xi - 1:xi + 2].max()
            rows.append((kind, det, (seed, gid), r[k][yi, xi], 2.818 * np.exp(-((x - xi) ** 2 + (y - yi) ** 2) / 0.98),
                         ring(k, xi, yi), zt, int(np.searchsorted(-pk, -zt))))
    for tid, pts in byid.items():
        if tid in assoc:
            continue
        fr, x, y = pts[0]
        k = fr - 1
        xi, yi = min(W - 7, max(6, int(round(x)))), min(H - 7, max(6, int(round(y))))
        frows.append((kind, len(pts), float(r[k][yi - 1:yi + 2, xi - 1:xi + 2].max()), ring(k, xi, yi)))
    st = stats.setdefault(kind, [])
    for k in range(20, nf, 5):
        x = r[k][8:-8, 8:-8]
        z, pk = matched(k)
        b = nd.uniform_filter(r[k], 9)[8:-8, 8:-8]
        st.append((np.sqrt(np.mean(x ** 2)), np.mean(np.abs(x) > 3), pk[255], pk[63],
                   np.mean(x * r[k - 1][8:-8, 8:-8]) / np.mean(x ** 2),
                   np.mean(x[:, 1:] * x[:, :-1]) / np.mean(x ** 2), np.sqrt(np.mean(b ** 2)), np.nan))
    tm = nd.uniform_filter(r[20:].mean(0), 9)[8:-8, 8:-8]
    st.append((np.nan,) * 7 + (np.sqrt(np.mean(tm ** 2)),))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('build')
    ap.add_argument('out')
    ap.add_argument('--ir-sky')
    ap.add_argument('--seeds', default='1-29')
    ap.add_argument('--patch', default='{}')
    a = ap.parse_args()
    lo, hi = (int(v) for v in a.seeds.split('-'))
    patch = json.loads(a.patch)
    kinds = dict(csv.reader(open(KINDS)))
    files = sorted(f for f in os.listdir(a.ir_sky) if f.endswith('.png')) if a.ir_sky else []
    rows, frows, stats = [], [], {}
    for seed in range(lo, hi + 1):
        one_seed(a, seed, patch, files, kinds, rows, frows, stats)
    print(f'seeds {lo}-{hi}, 9 dB, patch {json.dumps(patch)}, {"ir_sky" if a.ir_sky else "procedural"}')
    print('\n| kind | targets | target-frames | residual at the pixel / nominal | ring rms | PSF-matched value | frames among the 256 highest peaks | median rank |')
    print('|---|---|---|---|---|---|---|---|')
    for key in sorted({(r_[0], r_[1]) for r_ in rows}):
        v = [r_ for r_ in rows if (r_[0], r_[1]) == key]
        val, nom, lr, zt, rk = (np.array([r_[i] for r_ in v], float) for i in (3, 4, 5, 6, 7))
        print(f'| {key[0]}, {"detected" if key[1] else "missed"} | {len({r_[2] for r_ in v})} | {len(v)} | '
              f'{val.mean() / nom.mean():.2f} | {np.median(lr):.2f} | {zt.mean():.2f} | {100 * np.mean(rk < 256):.0f} % | {np.median(rk):.0f} |')
    print('\n| kind | rms | share > 3 sigma (Gaussian 0.0027) | 256th / 64th PSF-matched peak | lag-1 in time | lag-1 along x | 9 x 9 mean, rms (white 0.111) | 9 x 9 mean of the time mean, rms (white 0.012) |')
    print('|---|---|---|---|---|---|---|---|')
    for kind, st in sorted(stats.items()):
        s_ = np.array(st, float)
        m = np.nanmean(s_, 0)
        print(f'| {kind} | {m[0]:.3f} | {m[1]:.4f} | {m[2]:.2f} / {m[3]:.2f} | {m[4]:.3f} | {m[5]:.3f} | {m[6]:.3f} | {m[7]:.3f} |')
    print('\n| kind | false tracks | frames reported (median) | residual 3 x 3 maximum at the start (median) | ring rms (median) |')
    print('|---|---|---|---|---|')
    for kind in sorted({f[0] for f in frows}):
        v = np.array([f[1:] for f in frows if f[0] == kind], float)
        print(f'| {kind} | {len(v)} | {np.median(v[:, 0]):.0f} | {np.median(v[:, 1]):.2f} | {np.median(v[:, 2]):.2f} |')


if __name__ == '__main__':
    main()
