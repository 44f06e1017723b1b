#!/usr/bin/env python3
"""The matched residual beside the track layers (docs/results/ir_clutter.md, "Branch irresid"):
per track layer and frame, the trace's resid_m is the largest matched residual (the frame minus
the layer's own PSF, filtered with the PSF's 3 x 3 taps, m = sum g r / sqrt(sum g^2)) on the
pixels 1.5-5 px from the layer and 3 px or more from every other track (pft_tbd resid_split,
which must be on in the traced run: a threshold it never reaches, e.g. 50 with 8 frames, keeps the
run's outputs). This script sorts those layer-frames:

  pair   the crossing pair's targets (the two injected targets of largest id of a run) in the
         frames after their closest frame with the pair more than SEP px apart, with no track layer
         of their own (none within 3 px that is not the one nearest the partner): the layer
         nearest the partner (within 3 px of it), its ring max, and whether that max lies within
         1.5 px of the target ("on"); split by the target's detection in the run;
  clutter  every layer-frame whose ring max lies more than 3 px from every truth point
           (injected and labelled);

and then, for thresholds T and frames-in-a-row N, how many pair targets would get a layer (the
ring max on the target at >= T on N frames in a row of one layer) and how many layers would
start on clutter (runs of N frames at >= T, the peak more than 3 px from every truth point, the
peak within 2 px of the last frame's), per 1000 frames, optionally only for layers of age <= A.

  ir_resid_diag.py TRACE_DIR SUMMARY_JSON [--sep PX] [--age A]

Not a test.
"""
import argparse
import collections
import json
import math

from ir_cross_diag import crossing_pair, pair_frames, read_csv


def fnum(v):
    return float(v) if v not in ('', None) else float('nan')


def pct(v, q):
    v = sorted(v)
    return v[min(len(v) - 1, int(q * len(v)))] if v else float('nan')


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('trace')
    ap.add_argument('summary')
    ap.add_argument('--sep', type=float, default=3.0)
    ap.add_argument('--age', type=int, default=-1, help='only layers of age <= A (frames since hand-over)')
    a = ap.parse_args()
    summ = json.load(open(a.summary))
    frames_total = 0
    pair_on = {True: [], False: []}     # detected -> ring max values when on the target
    pair_all = {True: 0, False: 0}      # detected -> apart frames with the partner's layer tested
    pair_seq = {True: [], False: []}    # detected -> per target: list of (frame, m) on it
    clutter = []                        # ring max of clutter layer-frames
    clutter_seq = []                    # per layer: list of (frame, m, x, y, is_clutter)
    n_layer_frames = 0
    for run in summ['per_run']:
        seed = run['seed']
        frames_total += summ['frames']
        rows = read_csv(f'{a.trace}/s{seed}_layers.csv')
        lay = collections.defaultdict(dict)
        per_layer = collections.defaultdict(list)
        for r in rows:
            if a.age >= 0 and int(r['age']) > a.age:
                continue
            lay[int(r['frame'])][int(r['id'])] = r
            if r['resid_m'] in ('', '0.000'):
                continue
            n_layer_frames += 1
            is_cl = r['resid_d'] == '' or fnum(r['resid_d']) > 3.0
            m = fnum(r['resid_m'])
            if is_cl:
                clutter.append(m)
            per_layer[int(r['id'])].append((int(r['frame']), m, fnum(r['resid_x']), fnum(r['resid_y']), is_cl))
        clutter_seq.extend(per_layer.values())
        pair, _ = crossing_pair(run)
        if pair is None:
            continue
        by, sep, kc = pair_frames(a.trace, seed, pair)
        if kc is None:
            continue
        for t in pair:
            tid = t['id']
            par = pair[1]['id'] if tid == pair[0]['id'] else pair[0]['id']
            det = bool(t['detected'])
            seq = []
            for f in sorted(by):
                if f <= kc or tid not in by[f] or par not in by[f] or sep.get(f, 0) <= a.sep:
                    continue
                tx, ty = fnum(by[f][tid]['x']), fnum(by[f][tid]['y'])
                px, py = fnum(by[f][par]['x']), fnum(by[f][par]['y'])
                near_par, bd = None, 3.0
                for L in lay[f].values():
                    d = math.hypot(fnum(L['x']) - px, fnum(L['y']) - py)
                    if d <= bd:
                        near_par, bd = L, d
                own = any(math.hypot(fnum(L['x']) - tx, fnum(L['y']) - ty) <= 3.0 and L is not near_par
                          for L in lay[f].values())
                if own or near_par is None or near_par['resid_m'] in ('', '0.000'):
                    continue
                pair_all[det] += 1
                on = near_par['resid_tid'] == str(tid) and fnum(near_par['resid_d']) <= 1.5
                if on:
                    pair_on[det].append(fnum(near_par['resid_m']))
                seq.append((f, fnum(near_par['resid_m']) if on else -1.0))
            pair_seq[det].append(((seed, tid), seq))
    print(f'runs {len(summ["per_run"])}, frames {frames_total}, tested layer-frames {n_layer_frames}'
          f'{"" if a.age < 0 else f", layers of age <= {a.age}"}')
    for det in (False, True):
        v = pair_on[det]
        print(f'pair targets {"detected" if det else "missed"}: {len(pair_seq[det])} targets, '
              f'{pair_all[det]} apart frames under the partner\'s layer (no layer of their own), '
              f'ring max on the target in {len(v)}: m 10/50/90 % = '
              f'{pct(v, 0.1):.2f} / {pct(v, 0.5):.2f} / {pct(v, 0.9):.2f}')
    print(f'clutter layer-frames {len(clutter)}: m 50/90/99/99.9 % = {pct(clutter, 0.5):.2f} / '
          f'{pct(clutter, 0.9):.2f} / {pct(clutter, 0.99):.2f} / {pct(clutter, 0.999):.2f}')
    print('T    N  missed pair targets reached  detected pair targets reached  clutter starts (per 1000 frames)')
    for N in (1, 2, 3):
        for T in (2.5, 3.0, 3.5, 4.0, 4.5, 5.0, 6.0):
            reach = {}
            for det in (False, True):
                c = 0
                for _key, seq in pair_seq[det]:
                    run_n, last = 0, None
                    hit = False
                    for f, m in seq:
                        run_n = run_n + 1 if (m >= T and last == f - 1 and run_n > 0) else (1 if m >= T else 0)
                        last = f
                        if run_n >= N:
                            hit = True
                            break
                    c += hit
                reach[det] = c
            starts = 0
            for seq in clutter_seq:
                run_n, lf, lx, ly = 0, None, None, None
                for f, m, x, y, is_cl in seq:
                    if m >= T:
                        if run_n > 0 and lf == f - 1 and math.hypot(x - lx, y - ly) <= 2.0:
                            run_n += 1
                        else:
                            run_n = 1
                    else:
                        run_n = 0
                    lf, lx, ly = f, x, y
                    if run_n >= N:
                        if is_cl:
                            starts += 1
                        run_n = 0
            print(f'{T:<4} {N}  {reach[False]:>3} of {len(pair_seq[False]):<3}                    '
                  f'{reach[True]:>3} of {len(pair_seq[True]):<3}                    {starts:>5} '
                  f'({1000.0 * starts / frames_total:.2f})')


if __name__ == '__main__':
    main()
