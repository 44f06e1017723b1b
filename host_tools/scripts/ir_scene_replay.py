#!/usr/bin/env python3
"""Replays the scene-motion test's report decision (docs/algorithms.md 9.11 steps 2 and 4) on the
trace of a `pft eval --trace DIR` run made with scene_hold 1, under other report rules, and scores
them as `pft eval` does (a target is detected when a reported track is associated with it, nearest
first within d_assoc, in some frame; a reported track never associated is a false track)
(docs/results/ir_clutter.md, "Branch irfit"). Only the report and hold decisions are replayed:
the clutter gate (step 1) raises the clutter map and so feeds back into the manager, and is taken
from the run as it was (scene_dec 2). Exact for rules that change only which frames are reported
(the manager does not see the report); a screen, the figures of the results page come from
`pft eval` runs.

  ir_scene_replay.py TRACE_DIR SUMMARY_JSON --rule hold=4 --rule hold=4,fit=0.3 \\
      --rule hold=4,fast=0.6,fast_hold=2 --rule hold=4,fit_sd=1.0

Rule keys: hold (k), fit (px rms, 0: off), early (px per frame), frames (n), fast and fast_hold
(a track whose displacement against the scene over its held positions is at least fast px per
frame is reported from its fast_hold-th pass), fit_sd (the fit's tolerance max(fit, fit_sd * the
layer's position spread sqrt(cov_xx + cov_yy))), minpos (reported only from the minpos-th
position fed). Needs numpy. Not a test.
"""
import argparse
import collections
import json
import math
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from ir_scene_diag import read_csv, fit_rms  # noqa: E402


def parse_rule(s):
    r = dict(hold=4, fit=0.2, early=0.5, frames=5, fast=0.0, fast_hold=0, fit_sd=0.0, gate=0.15, minpos=0, tight=0.0, tight_hold=0)
    for kv in s.split(','):
        k, v = kv.split('=')
        r[k] = float(v) if k not in ('hold', 'frames', 'fast_hold', 'minpos', 'tight_hold') else int(v)
    return r


def reported_frames(rows, R):
    """the frames of one layer (rows sorted by frame) reported under rule R"""
    mm = R['frames'] + 1
    hist = []
    passed = 0
    fed = 0
    out = set()
    for r in rows:
        dec = int(r['scene_dec'])
        if dec < 0:
            continue
        fed += 1
        hist.append((float(r['rx']), float(r['ry']), float(r['scene_x']), float(r['scene_y'])))
        if len(hist) > mm:
            hist.pop(0)
        if dec == 2:  # the clutter gate, as it was
            continue
        k = len(hist)
        early = False
        if R['early'] > 0 and 4 <= k < mm:
            dx = (hist[-1][0] - hist[-4][0]) - (hist[-1][2] - hist[-4][2])
            dy = (hist[-1][1] - hist[-4][1]) - (hist[-1][3] - hist[-4][3])
            early = math.hypot(dx, dy) >= 3 * R['early']
        if not (k >= mm or early):
            continue
        tol = R['fit']
        if R['fit_sd'] > 0:
            tol = max(tol, R['fit_sd'] * math.sqrt(max(0.0, float(r['cov_xx']) + float(r['cov_yy']))))
        if tol > 0 and fit_rms([(h[0], h[1]) for h in hist]) > tol:
            continue
        passed += 1
        need = R['hold']
        if R['fast'] > 0 and R['fast_hold'] > 0:
            dx = (hist[-1][0] - hist[0][0]) - (hist[-1][2] - hist[0][2])
            dy = (hist[-1][1] - hist[0][1]) - (hist[-1][3] - hist[0][3])
            if math.hypot(dx, dy) >= R['fast'] * (k - 1):
                need = min(need, R['fast_hold'])
        if R['tight'] > 0 and math.sqrt(max(0.0, float(r['cov_xx']) + float(r['cov_yy']))) <= R['tight']:
            need = min(need, R['tight_hold'])
        if passed >= need and fed >= R['minpos']:
            out.add(int(r['frame']))
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('trace')
    ap.add_argument('summary')
    ap.add_argument('--rule', action='append', default=[])
    ap.add_argument('--d-assoc', type=float, default=3.0)
    a = ap.parse_args()
    summ = json.load(open(a.summary))
    runs = []
    for run in summ['per_run']:
        seed = run['seed']
        lp = os.path.join(a.trace, f's{seed}_layers.csv')
        layers = collections.defaultdict(list)
        for r in read_csv(lp):
            layers[int(r['id'])].append(r)
        for rows in layers.values():
            rows.sort(key=lambda r: int(r['frame']))
        truth = collections.defaultdict(list)
        for r in read_csv(os.path.join(a.trace, f's{seed}_targets.csv')):
            truth[int(r['frame'])].append((int(r['tid']), float(r['x']), float(r['y']), r['labelled'] == '1'))
        inj = [t['id'] for t in run['targets'] if t['kind'] == 'injected']
        runs.append((seed, run['frames'], layers, truth, inj))
    print('| rule | runs | targets | detected | false tracks | per 1000 frames | detected − first (paired by seed) | false − first (paired) |')
    print('|---|---|---|---|---|---|---|---|')
    first = None
    for rs in a.rule:
        R = parse_rule(rs)
        per = []
        nt = nd = nf = fr = 0
        for seed, frames, layers, truth, inj in runs:
            rep = collections.defaultdict(list)  # frame -> [(id, x, y)]
            for lid, rows in layers.items():
                fs = reported_frames(rows, R)
                for r in rows:
                    if int(r['frame']) in fs:
                        rep[int(r['frame'])].append((lid, float(r['x']), float(r['y'])))
            assoc = {lid: False for f in rep.values() for lid, _, _ in f}
            det = set()
            for f, trs in rep.items():
                tr = truth.get(f, [])
                c = sorted((math.hypot(x - t[1], y - t[2]), i, j) for i, (lid, x, y) in enumerate(trs)
                           for j, t in enumerate(tr) if math.hypot(x - t[1], y - t[2]) <= a.d_assoc)
                ui, uj = set(), set()
                for d, i, j in c:
                    if i in ui or j in uj:
                        continue
                    ui.add(i)
                    uj.add(j)
                    assoc[trs[i][0]] = True
                    det.add(tr[j][0])
            d = sum(t in det for t in inj)
            f = sum(not v for v in assoc.values())
            per.append((d, f, len(inj), frames))
            nt += len(inj)
            nd += d
            nf += f
            fr += frames
        if first is None:
            first = per
            dd = ff = '–'
        else:
            x = np.array([(p[0] / 1.0 - q[0]) for p, q in zip(per, first)])
            y = np.array([(p[1] - q[1]) for p, q in zip(per, first)])
            n = len(per)
            dd = f'{100 * x.sum() / nt:+.1f} ± {100 * x.std(ddof=1) * math.sqrt(n) / nt:.1f}'
            ff = f'{1000 * y.sum() / fr:+.1f} ± {1000 * y.std(ddof=1) * math.sqrt(n) / fr:.1f}'
        print(f'| {rs} | {len(per)} | {nt} | {100 * nd / nt:.1f} % | {nf} | {1000 * nf / fr:.2f} | {dd} | {ff} |')


if __name__ == '__main__':
    main()
