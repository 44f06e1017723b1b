#!/usr/bin/env python3
"""How the IR pipeline's TBD track layers end, from the per-frame layer rows of `pft eval --trace
DIR` (s<seed>_layers.csv, host_tools/tbd/ir_trace.hpp) with the same run's s<seed>_tracks.csv
and summary.json (docs/results/ir_clutter.md, "Branch irend").

  ir_end_trace.py TRACE_DIR SUMMARY_JSON [--max-age N]

Each track layer is put in one group:
  target_reported  reported, and within 3 px of an injected target in a reported frame;
  false            reported and counted false by the evaluation;
  c_target         on an injected target (within 3 px in some frame) of a target that no
                   reported track was associated with, never reported, ended by the manager
                   (category (c) of ir_miss_diag.py, by layer);
  target_other     on an injected target, never reported, the target detected by another layer;
  clutter          never reported, never within 3 px of an injected target (clutter, or a
                   labelled real object of the image);
  other            the rest (reported on a labelled object only, alive at the run's end, ...).
Per group: the layers' life (frames alive), how they end, the existence probability P and the
intensity by age (frames since the hand-over), the frame log likelihood ratio of the frame that
ended them, and the distance to the nearest injected target at the last frame.
Needs only the standard library. Not a test.
"""
import argparse
import collections
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from ir_miss_diag import read_csv, near_map, fnum  # noqa: E402


def q(v, p):
    v = sorted(x for x in v if x == x)
    if not v:
        return float('nan')
    return v[min(len(v) - 1, int(p * len(v)))]



def age_table(groups, ages, cell, width):
    """One row per layer group, one cell per age: cell(the layer rows of that age)."""
    for g in ['target_reported', 'c_target', 'target_other', 'false', 'clutter']:
        L = groups.get(g, [])
        if not L:
            continue
        cells = [cell([r for _, lr in L for r in lr if int(r['age']) == x]) for x in ages]
        print(f'{g:16s} ' + ' '.join(f'{c:>{width}s}' for c in cells))

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('trace')
    ap.add_argument('summary')
    ap.add_argument('--max-age', type=int, default=6)
    ap.add_argument('--theta', type=float, default=0.2,
                    help="the block's theta_end: with end_grace_frames or end_persist, layers listed "
                         "with P below it were kept by the option")
    a = ap.parse_args()
    summ = json.load(open(a.summary))
    groups = collections.defaultdict(list)
    for run in summ['per_run']:
        seed = run['seed']
        tk = os.path.join(a.trace, f's{seed}_tracks.csv')
        tl = os.path.join(a.trace, f's{seed}_layers.csv')
        if not (os.path.exists(tk) and os.path.exists(tl)):
            continue
        injected = {t['id']: t for t in run['targets'] if t['kind'] == 'injected'}
        rows = collections.defaultdict(list)
        for r in read_csv(tl):
            rows[int(r['id'])].append(r)
        # per frame, each injected target's distance to every layer is in the layer rows only
        # for the nearest truth point; take the distance to the nearest injected target
        for tr in read_csv(tk):
            lid = int(tr['id'])
            lr = sorted(rows.get(lid, []), key=lambda r: int(r['frame']))
            near = near_map(tr['near_all'])
            near_rep = near_map(tr['near_rep_all'])
            on_inj = [t for t in near if t in injected]
            rep = int(tr['reported']) > 0
            if rep and tr['is_false'] == '1':
                g = 'false'
            elif rep and any(t in injected for t in near_rep):
                g = 'target_reported'
            elif not rep and on_inj and tr['reason'] not in ('',):
                g = 'c_target' if not any(injected[t]['detected'] for t in on_inj) else 'target_other'
            elif not rep and not near and tr['reason'] not in ('',):
                g = 'clutter'
            else:
                g = 'other'
            groups[g].append((tr, lr))
    ages = list(range(a.max_age + 1))
    print('group            layers  life: median (q25-q75)  ended by: reason counts')
    for g in ['target_reported', 'c_target', 'target_other', 'false', 'clutter', 'other']:
        L = groups.get(g, [])
        if not L:
            continue
        life = [int(tr['alive']) for tr, _ in L]
        why = collections.Counter(tr['reason'] or 'alive_at_end' for tr, _ in L)
        print(f'{g:16s} {len(L):6d}  {q(life, .5):4.0f} ({q(life, .25):.0f}-{q(life, .75):.0f})   '
              + ', '.join(f'{k} {v}' for k, v in why.most_common()))
    print('\nexistence probability P by age (median; share of layers alive at that age with P < 0.5):')
    print(f'{"group":16s} ' + ' '.join(f'{"age " + str(x):>14s}' for x in ages))

    def p_cell(rows):
        ps = [fnum(r['p_exist']) for r in rows]
        return f'{q(ps, .5):.2f} {sum(p < 0.5 for p in ps) / max(1, len(ps)):.2f} n{len(ps):<4d}' if ps else '-'

    def lr_cell(rows):
        v = [fnum(r['log_mean_lr']) for r in rows]
        return f'{q(v, .5):+.2f}' if v else '-'

    age_table(groups, ages, p_cell, 14)
    print('\nframe log likelihood ratio log_mean_lr by age (median):')
    age_table(groups, ages, lr_cell, 8)
    print('\nper layer (medians): hand-over P, intensity at the hand-over and at its last row (the '
          'frame before the end), P and log_mean_lr there, its distance to the nearest truth point there '
          '(rows whose nearest is an injected target; the share within 1.5 px), and the sum and largest '
          'of its log_mean_lr after the hand-over:')
    print(f'{"group":16s} {"hand P":>7s} {"hand I":>7s} {"last I":>7s} {"I last/hand":>11s} '
          f'{"last P":>7s} {"last lr":>8s} {"d last":>7s} {"d last<=1.5":>11s} {"sum lr":>7s} {"max lr":>7s}')
    for g in ['target_reported', 'c_target', 'target_other', 'false', 'clutter']:
        L = groups.get(g, [])
        if not L:
            continue
        hp = [fnum(tr['hp']) for tr, _ in L]
        hi = [fnum(tr['hi']) for tr, _ in L]
        li = [fnum(tr['li']) for tr, _ in L]
        ratio = [fnum(tr['li']) / fnum(tr['hi']) for tr, _ in L if fnum(tr['hi']) > 0]
        lastp = [fnum(lr[-1]['p_exist']) for _, lr in L if lr]
        lastlr = [fnum(lr[-1]['log_mean_lr']) for _, lr in L if lr]
        dl = [fnum(lr[-1]['near_d']) for _, lr in L if lr and lr[-1]['near_labelled'] == '0']
        slr = [sum(fnum(r['log_mean_lr']) for r in lr[1:]) for _, lr in L if len(lr) > 1]
        mlr = [max(fnum(r['log_mean_lr']) for r in lr[1:]) for _, lr in L if len(lr) > 1]
        print(f'{g:16s} {q(hp, .5):7.2f} {q(hi, .5):7.2f} {q(li, .5):7.2f} {q(ratio, .5):11.2f} '
              f'{q(lastp, .5):7.2f} {q(lastlr, .5):+8.2f} {q(dl, .5):7.2f} '
              f'{sum(d <= 1.5 for d in dl) / max(1, len(dl)):11.2f} {q(slr, .5):+7.2f} {q(mlr, .5):+7.2f}')
    # the c_target layers: how many would live on with a lower threshold for the young
    print('\nc_target and clutter layers by the age at which they ended (frames alive):')
    for g in ['c_target', 'target_other', 'clutter']:
        L = groups.get(g, [])
        if not L:
            continue
        c = collections.Counter(min(int(tr['alive']), 10) for tr, _ in L)
        print(f'  {g:14s} ' + ', '.join(f'{k}{"+" if k == 10 else ""}: {c[k]}' for k in sorted(c)))
    # layers kept through a frame below theta_end (only with end_grace_frames or end_persist)
    print(f'\nlayers listed in a frame with P below {a.theta} (kept by an end option), and of them '
          f'back at or above it the next frame:')
    for g in ['c_target', 'target_other', 'clutter', 'false', 'target_reported']:
        L = groups.get(g, [])
        kept = back = 0
        for _, lr in L:
            ps = [fnum(r['p_exist']) for r in lr]
            low = [i for i, p in enumerate(ps) if p < a.theta]
            kept += bool(low)
            back += any(i + 1 < len(ps) and ps[i + 1] >= a.theta for i in low)
        print(f'  {g:16s} {len(L):5d} layers, {kept:5d} kept, {back:5d} back')
    # the c_target layers' P in the frame before the end
    print('\nP of the last alive frame (the frame before the end test) per group, quantiles 10/25/50/75/90 %:')
    for g in ['c_target', 'target_other', 'clutter', 'false', 'target_reported']:
        L = groups.get(g, [])
        v = [fnum(lr[-1]['p_exist']) for _, lr in L if lr]
        if v:
            print(f'  {g:16s} ' + ' '.join(f'{q(v, p):.2f}' for p in (.1, .25, .5, .75, .9)))


if __name__ == '__main__':
    main()
