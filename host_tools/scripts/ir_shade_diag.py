#!/usr/bin/env python3
"""Where the shaded sensor loses its 9 dB targets (docs/results/ir_clutter.md, section "Branch
irshade3"), paired by seed and target against the flat sensor, from two `pft eval --trace`
runs of the same seeds (the same targets and backgrounds) and their summary.json. Not a test.

  ir_shade_diag.py FLAT_TRACE FLAT_SUMMARY SHADED_TRACE SHADED_SUMMARY [--seeds 1-116]
                   [--miss SHADED_MISS_LIST] [--size 346x270] [--drift 0.3,0.1] [--vignetting 0.2]

Per injected target (trace rows after frame 1, medians over its frames):
  rho      its distance from the frame centre over the corner's (the simulator's vignetting is
           1 - v rho^2, fixed to the sensor);
  dgdt     the gain's change per frame that a scene point drifting with the platform sees at
           the target's position (-2 v (p - c) . drift / rho_max^2), the lag term of
           docs/algorithms.md 9.10;
  vs       its speed against the scene (mean velocity in the frame plus the drift);
  edge     where it starts (inside, or within 2 px of a border: left, top, right, bottom);
  z        the stage's matched residual (after the flat-field step) over its local robust sd
           ((mf_stage - loc_med_stage) / loc_sd_stage), z_map the same after the clutter map;
  res_sd   the stage residual's own robust sd around it (res_sd_stage): 1 where the tile
           sigma that whitened it is the residual's spread, below 1 where it is too large.
Tables: detection by band (flat, shaded, paired difference), the residual's statistics by
band, and (with --miss: ir_miss_diag.py --list of the shaded run) the shaded-only misses by
the category of ir_miss_diag.py, by res_sd and by entry edge.
"""
import argparse
import collections
import csv
import json
import math
import re
import statistics as st


def load(trace, summ, seeds, W, H, drift, vig):
    cx, cy = (W - 1) / 2, (H - 1) / 2
    r2max = cx * cx + cy * cy
    S = json.load(open(summ))
    det = {}
    for r in S['per_run']:
        if r['seed'] in seeds:
            for t in r['targets']:
                if t['kind'] == 'injected':
                    det[(r['seed'], t['id'])] = t['detected']
    out = {}
    for s in seeds:
        rows = collections.defaultdict(list)
        for r in csv.DictReader(open(f'{trace}/s{s}_targets.csv')):
            if r['labelled'] != '1':
                rows[int(r['tid'])].append(r)
        for tid, rr in rows.items():
            if (s, tid) not in det:
                continue
            rr.sort(key=lambda r: int(r['frame']))
            d = collections.defaultdict(list)
            for r in rr:
                x, y = float(r['x']), float(r['y'])
                d['rho'].append(math.sqrt(((x - cx) ** 2 + (y - cy) ** 2) / r2max))
                d['dgdt'].append(-2 * vig * ((x - cx) * drift[0] + (y - cy) * drift[1]) / r2max)
                sd = float(r['loc_sd_stage'] or 0)
                if int(r['frame']) > 1 and sd > 0:
                    d['z'].append((float(r['mf_stage']) - float(r['loc_med_stage'])) / sd)
                    d['med'].append(float(r['loc_med_stage']))
                    d['res_sd'].append(float(r['res_sd_stage']))
                sd = float(r['loc_sd'] or 0)
                if int(r['frame']) > 1 and sd > 0:
                    d['z_map'].append((float(r['mf_at']) - float(r['loc_med'])) / sd)
            n = max(1, int(rr[-1]['frame']) - int(rr[0]['frame']))
            vx = (float(rr[-1]['x']) - float(rr[0]['x'])) / n + drift[0]
            vy = (float(rr[-1]['y']) - float(rr[0]['y'])) / n + drift[1]
            x0, y0 = float(rr[0]['x']), float(rr[0]['y'])
            e = 'inside'
            if x0 < 2:
                e = 'left'
            elif x0 > W - 3:
                e = 'right'
            elif y0 < 2:
                e = 'top'
            elif y0 > H - 3:
                e = 'bottom'
            m = {k: st.median(v) for k, v in d.items() if v}
            m.update(vs=math.hypot(vx, vy), edge=e, det=det[(s, tid)])
            out[(s, tid)] = m
    return out


def med(D, ks, f):
    v = [D[k][f] for k in ks if f in D[k]]
    return st.median(v) if v else float('nan')


def bands(A, B, keys, keyf, edges, name):
    print(f'\n| {name} | targets | flat detected | shaded detected | shaded − flat, points (paired ± s.e.) '
          '| z flat | z shaded | z_map flat | z_map shaded | res_sd flat | res_sd shaded | mean offset flat | mean offset shaded |')
    print('|---|---|---|---|---|---|---|---|---|---|---|---|---|')
    for lab, lo, hi in edges:
        ks = [k for k in keys if lo <= keyf(B[k]) < hi]
        if not ks:
            continue
        df = [B[k]['det'] - A[k]['det'] for k in ks]
        se = st.stdev(df) / math.sqrt(len(ks)) if len(ks) > 1 else 0.0
        print(f'| {lab} | {len(ks)} | {100 * st.mean(A[k]["det"] for k in ks):.1f} % | '
              f'{100 * st.mean(B[k]["det"] for k in ks):.1f} % | {100 * st.mean(df):+.1f} ± {100 * se:.1f} | '
              + ' | '.join(f'{med(A, ks, f):.2f} | {med(B, ks, f):.2f}' for f in ('z', 'z_map', 'res_sd', 'med')) + ' |')


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('flat_trace')
    ap.add_argument('flat_summary')
    ap.add_argument('shaded_trace')
    ap.add_argument('shaded_summary')
    ap.add_argument('--seeds', default='1-116')
    ap.add_argument('--miss')
    ap.add_argument('--size', default='346x270')
    ap.add_argument('--drift', default='0.3,0.1')
    ap.add_argument('--vignetting', type=float, default=0.2)
    a = ap.parse_args()
    lo, hi = (int(x) for x in a.seeds.split('-'))
    W, H = (int(x) for x in a.size.split('x'))
    drift = [float(x) for x in a.drift.split(',')]
    seeds = range(lo, hi + 1)
    A = load(a.flat_trace, a.flat_summary, seeds, W, H, drift, a.vignetting)
    B = load(a.shaded_trace, a.shaded_summary, seeds, W, H, drift, a.vignetting)
    keys = sorted(set(A) & set(B))
    bands(A, B, keys, lambda d: d['rho'], [('0–0.4', 0, 0.4), ('0.4–0.6', 0.4, 0.6), ('0.6–0.8', 0.6, 0.8),
                                            ('0.8–1', 0.8, 2), ('all', 0, 2)], 'radius / corner radius')
    bands(A, B, keys, lambda d: d['dgdt'] * 1000,
          [('< −0.4', -99, -0.4), ('−0.4 – −0.15', -0.4, -0.15), ('−0.15 – 0.15', -0.15, 0.15),
           ('0.15 – 0.4', 0.15, 0.4), ('> 0.4', 0.4, 99)], 'gain change per frame at the target, 1e-3')
    bands(A, B, keys, lambda d: d['vs'], [('< 0.3', 0, 0.3), ('0.3–0.6', 0.3, 0.6), ('0.6–1', 0.6, 1.0),
                                           ('> 1', 1.0, 99)], 'speed against the scene, px/frame')
    order = ['inside', 'left', 'top', 'right', 'bottom']
    bands(A, B, keys, lambda d: order.index(d['edge']),
          [(e, i, i + 1) for i, e in enumerate(order)], 'start')
    bands(A, B, keys, lambda d: d.get('res_sd', 1.0), [('res_sd shaded < 0.85', 0, 0.85),
                                                      ('res_sd shaded >= 0.85', 0.85, 99)], 'residual sd')
    if a.miss:
        cat = {}
        for line in open(a.miss):
            m = re.match(r'\s+seed (\d+) tid (\d+) (\S+)\s+(\S+)\s+z', line)
            if m:
                cat[(int(m[1]), int(m[2]))] = m[4]
        ks = [k for k in keys if A[k]['det'] and not B[k]['det']]
        print(f'\n{len(ks)} shaded-only misses, {sum(1 for k in keys if B[k]["det"] and not A[k]["det"])} flat-only')
        print('\n| category (ir_miss_diag.py, shaded run) | targets | res_sd < 0.85 | res_sd >= 0.85 | '
              + ' | '.join(order) + ' |')
        print('|---|---|---|---|' + '---|' * len(order))
        tab = collections.defaultdict(collections.Counter)
        for k in ks:
            c = cat.get(k, '?')
            for key in (c, 'all'):
                tab[key]['n'] += 1
                tab[key]['lo' if B[k].get('res_sd', 1.0) < 0.85 else 'hi'] += 1
                tab[key][B[k]['edge']] += 1
        for c in sorted(tab, key=lambda c: (c == 'all', -tab[c]['n'])):
            t = tab[c]
            print(f'| {c} | {t["n"]} | {t["lo"]} | {t["hi"]} | ' + ' | '.join(str(t[e]) for e in order) + ' |')


if __name__ == '__main__':
    main()
