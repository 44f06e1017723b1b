#!/usr/bin/env python3
"""Tables of docs/results/ir_clutter.md, section "Branch irdemo": `pft eval` summaries of the
procedural demo scenario (tbd_ir/procedural_384x288.json) and its tracker variants, with
standard errors from the per-run spread.

For TBD and DBT: injected targets detected / injected (a ratio over runs: its standard error
from the per-run residuals d_i - p n_i), the appearance delay (sum of delays / detected, the same
ratio form), the RMSE of the correct frames (ratio of squared errors to correct frames, then the
delta method), false tracks per 1000 frames (mean of the per-run rates). TBD's false tracks are
split by the first reported position: right border (x >= 352, the side where the drifting scene
enters, section "Border false tracks of the procedural demo: diagnosis"), the other borders
(x < 32, y < 32 or y >= 256) and the interior. The last table gives each setting minus the
first one, paired by seed (the same sequences), with the standard error of the per-seed
differences. Not a test.

With --grad PFT SCENARIO WORK it also splits the interior false tracks by the scene under their
first position: each seed's sequence is made again by `PFT sim --scenario SCENARIO --seed S
--format raw` (the sequence `pft eval` ran for that seed; the tracker block does not change
it), and the gradient of that frame smoothed by a Gaussian of 1 px, in temporal sigmas (20
counts) per pixel, largest over the 3 x 3 pixels around the position, puts the track in a band:
< 2 (smooth sky, cloud interiors, ground texture), 2-8, >= 8 (cloud edges, the horizon,
structures). Needs numpy and scipy then.

Usage: python3 host_tools/scripts/ir_demo_tables.py [--grad PFT SCENARIO WORK] LABEL=OUTDIR [LABEL=OUTDIR ...]
(each OUTDIR holds a `pft eval` summary.json; LABEL=DIR1,DIR2 pools the runs of several)
"""
import json
import math
import os
import sys

W, H, B = 384, 288, 32


def ratio(num, den):
    """Ratio of sums over runs and its standard error from the per-run residuals."""
    R = len(num)
    N, D = sum(num), sum(den)
    if D == 0 or R < 2:
        return float('nan'), float('nan')
    p = N / D
    if sum(1 for b in den if b) < 2:  # one run holds all of it: no spread to estimate from
        return p, float('nan')
    var = sum((a - p * b) ** 2 for a, b in zip(num, den)) / (R * (R - 1))
    return p, math.sqrt(var) / (D / R)


def mean_se(v):
    R = len(v)
    m = sum(v) / R
    sd = math.sqrt(sum((x - m) ** 2 for x in v) / (R - 1)) if R > 1 else float('nan')
    return m, sd / math.sqrt(R)


def tracker(per):
    det, inj, dsum, ndet, sq, cor, fr = [], [], [], [], [], [], []
    for r in per:
        ts = [t for t in r['targets'] if t['kind'] == 'injected']
        inj.append(len(ts))
        d = [t for t in ts if t['detected']]
        det.append(len(d))
        ndet.append(len(d))
        dsum.append(sum(t['appearance_delay'] for t in d))
        sq.append(sum(t['correct_sq_error_px2'] for t in ts))
        cor.append(sum(t['correct_frames'] for t in ts))
        fr.append(1000.0 * r['false_tracks'] / r['frames'])
    pd, pd_se = ratio(det, inj)
    dl, dl_se = ratio(dsum, ndet)
    mse, mse_se = ratio(sq, cor)
    rmse = math.sqrt(mse) if mse == mse else float('nan')
    rmse_se = mse_se / (2 * rmse) if rmse > 0 else float('nan')
    fa, fa_se = mean_se(fr)
    return dict(det=sum(det), inj=sum(inj), pd=pd, pd_se=pd_se, delay=dl, delay_se=dl_se,
                rmse=rmse, rmse_se=rmse_se, fa=fa, fa_se=fa_se)


def kinds(per):
    right, other, inner = [], [], []
    for r in per:
        k = [0, 0, 0]
        for f in r['false_track_list']:
            x, y = f['x'], f['y']
            if x >= W - B:
                k[0] += 1
            elif x < B or y < B or y >= H - B:
                k[1] += 1
            else:
                k[2] += 1
        s = 1000.0 / r['frames']
        right.append(k[0] * s)
        other.append(k[1] * s)
        inner.append(k[2] * s)
    return [mean_se(v) for v in (right, other, inner)]


def per_run(per):
    """Per seed: injected targets detected, injected, false tracks per 1000 frames."""
    out = {}
    for r in per:
        ts = [t for t in r['targets'] if t['kind'] == 'injected']
        out[r['seed']] = (sum(1 for t in ts if t['detected']), len(ts), 1000.0 * r['false_tracks'] / r['frames'])
    return out


def paired(a, b):
    """b minus a over the seeds both ran (the same sequences): detection points and false
    tracks per 1000 frames, each with the standard error of the per-seed differences."""
    A, B = per_run(a), per_run(b)
    seeds = sorted(set(A) & set(B))
    inj = sum(A[s][1] for s in seeds)
    dd = [(B[s][0] - A[s][0]) / (inj / len(seeds)) for s in seeds]
    df = [B[s][2] - A[s][2] for s in seeds]
    return mean_se(dd), mean_se(df)


SIGMA_T, GBANDS = 20.0, (2.0, 8.0)


def grad_bands(rows, pft, scenario, work):
    """Per setting: interior false tracks per 1000 frames in each gradient band (mean, s.e.)."""
    import subprocess
    import numpy as np
    from scipy import ndimage
    seeds = sorted({r['seed'] for _, s, _, _, _ in rows for r in s['per_run']})
    counts = {lab: {} for lab, *_ in rows}
    for seed in seeds:
        d = os.path.join(work, f's{seed}')
        subprocess.run([pft, 'sim', '--scenario', scenario, '--seed', str(seed), '--format', 'raw',
                        '--out', d, '-q'], check=True, stdout=subprocess.DEVNULL)
        z = np.memmap(os.path.join(d, 'frames.u16'), dtype='<u2', mode='r')
        cache = {}
        for lab, s, *_ in rows:
            r = next(r for r in s['per_run'] if r['seed'] == seed)
            k = [0, 0, 0]
            for f in r['false_track_list']:
                x, y = f['x'], f['y']
                if x >= W - B or x < B or y < B or y >= H - B:
                    continue
                fr = f['first_frame']
                if fr not in cache:
                    img = np.asarray(z[(fr - 1) * W * H:fr * W * H], dtype=np.float64).reshape(H, W)
                    sm = ndimage.gaussian_filter(img, 1.0)
                    gy, gx = np.gradient(sm)
                    cache[fr] = ndimage.maximum_filter(np.hypot(gx, gy) / SIGMA_T, size=3)
                g = cache[fr][int(round(y)), int(round(x))]
                k[0 if g < GBANDS[0] else 1 if g < GBANDS[1] else 2] += 1
            counts[lab][seed] = [c * 1000.0 / r['frames'] for c in k]
        del z
        os.remove(os.path.join(d, 'frames.u16'))
    return {lab: [mean_se([v[i] for v in c.values()]) for i in range(3)] for lab, c in counts.items()}


def emit(*a):
    """print, with a standard error that cannot be estimated shown as a dash"""
    print(*(x.replace('(± nan)', '(± –)').replace('nan', '–') if isinstance(x, str) else x for x in a))


def main():
    rows = []
    args = sys.argv[1:]
    grad = None
    if args and args[0] == '--grad':
        grad, args = args[1:4], args[4:]
    for arg in args:
        label, dirs = arg.split('=', 1)
        s = None
        for d in dirs.split(','):  # several OUTDIRs (other seeds of the same setting) pooled
            one = json.load(open(os.path.join(d, 'summary.json')))
            if s is None:
                s = one
            else:
                s['runs'] += one['runs']
                s['per_run'] += one['per_run']
                s['dbt']['per_run'] += one['dbt']['per_run']
        rows.append((label, s, tracker(s['per_run']), tracker(s['dbt']['per_run']), kinds(s['per_run'])))
    emit('| setting | runs | TBD detected (± s.e.) | delay | RMSE (px) | false / 1000 fr. | '
          'DBT detected | DBT delay | DBT RMSE | DBT false / 1000 fr. |')
    emit('|---|---|---|---|---|---|---|---|---|---|')
    for label, s, t, d, _ in rows:
        emit(f"| {label} | {s['runs']} | {t['det']} / {t['inj']} = {100 * t['pd']:.1f} % (± {100 * t['pd_se']:.1f}) "
              f"| {t['delay']:.1f} (± {t['delay_se']:.1f}) | {t['rmse']:.3f} (± {t['rmse_se']:.3f}) "
              f"| {t['fa']:.1f} (± {t['fa_se']:.1f}) "
              f"| {d['det']} / {d['inj']} = {100 * d['pd']:.1f} % (± {100 * d['pd_se']:.1f}) "
              f"| {d['delay']:.1f} (± {d['delay_se']:.1f}) | {d['rmse']:.3f} (± {d['rmse_se']:.3f}) "
              f"| {d['fa']:.1f} (± {d['fa_se']:.1f}) |")
    emit()
    emit('| setting | TBD false / 1000 fr.: right border x ≥ 352 | other borders | interior |')
    emit('|---|---|---|---|')
    for label, s, t, d, k in rows:
        emit(f"| {label} | " + ' | '.join(f'{m:.1f} (± {e:.1f})' for m, e in k) + ' |')
    if grad:
        gb = grad_bands(rows, *grad)
        emit()
        emit('| setting | interior false / 1000 fr.: scene gradient < 2 σ/px | 2–8 | ≥ 8 (cloud edges, horizon, structures) |')
        emit('|---|---|---|---|')
        for label, *_ in rows:
            emit(f"| {label} | " + ' | '.join(f'{m:.1f} (± {e:.1f})' for m, e in gb[label]) + ' |')
    emit()
    emit(f'| setting | TBD detection minus {rows[0][0]}\'s, points (± s.e., paired by seed) | '
          'TBD false / 1000 fr. minus (± s.e.) | DBT detection minus | DBT false / 1000 fr. minus |')
    emit('|---|---|---|---|---|')
    for label, s, t, d, k in rows[1:]:
        (m1, e1), (m2, e2) = paired(rows[0][1]['per_run'], s['per_run'])
        (m3, e3), (m4, e4) = paired(rows[0][1]['dbt']['per_run'], s['dbt']['per_run'])
        emit(f"| {label} | {100 * m1:+.1f} (± {100 * e1:.1f}) | {m2:+.1f} (± {e2:.1f}) "
              f"| {100 * m3:+.1f} (± {100 * e3:.1f}) | {m4:+.1f} (± {e4:.1f}) |")


if __name__ == '__main__':
    main()
