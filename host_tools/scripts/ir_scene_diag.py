#!/usr/bin/env python3
"""Which step of the scene-motion test (docs/algorithms.md 9.11) held the missed targets of
categories c_scene and d_late of ir_miss_diag.py, and what the false tracks it lets through look
like (docs/results/ir_clutter.md, "Branch irfit"), from the trace of `pft eval --trace DIR`
(the layers file's scene_x, scene_y, scene_dec, cov_xx, cov_yy, rx, ry columns) and the same
run's summary.json.

  ir_scene_diag.py TRACE_DIR SUMMARY_JSON [--frames 5 --gate 0.15 --fit 0.2 --early 0.5 --hold 4]
                   [--list]

The test is replayed per track id from the positions the pipeline fed it (rx, ry: the manager's
estimate; scene_x, scene_y: the scene's cumulative shift), in floating point, and each frame of a
layer within 3 px of a missed target is given the step that decided it:
  clutter   the clutter gate (9.11 step 1);
  tentative the manager's sequential test still running (step 3; not fed to the test);
  short     fewer than n + 1 positions and no early report (step 2's count);
  fit       enough positions (or early) but the straight-line fit's rms above fit_px (step 2);
  hold      passed, but fewer than hold_frames passes so far (step 4);
  report    reported.
A target's step is the last one its layers reached while on it (report > hold > fit > short >
tentative; clutter when a layer on it was found clutter). The replay's decisions are checked
against the pipeline's own (scene_dec) and the agreement is printed. Needs numpy. Not a test.
"""
import argparse
import collections
import csv
import json
import math
import os
import subprocess
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
ORDER = ['tentative', 'short', 'fit', 'hold', 'report']


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def fit_rms(pts):
    """rms (2-D) of the least-squares straight line at constant speed through pts [(x, y)]"""
    m = len(pts)
    if m < 3:
        return 0.0
    a = np.asarray(pts, dtype=float)
    t = np.arange(m) - (m - 1) / 2.0
    ss = 0.0
    for c in range(2):
        v = a[:, c]
        b = (t * v).sum() / (t * t).sum()
        r = v - v.mean() - b * t
        ss += (r * r).sum()
    return math.sqrt(ss / m)


def replay(rows, a):
    """rows: one layer's rows (sorted by frame). Adds 'step', 'rms', 'k' to the rows fed to the test."""
    mm = a.frames + 1
    hist = []
    clutter = False
    passed = 0
    for r in rows:
        dec = int(r['scene_dec'])
        if dec < 0:
            r['step'] = 'tentative' if r['tentative'] == '1' else 'not_fed'
            r['rms'] = float('nan')
            continue
        p = (float(r['rx']), float(r['ry']), float(r['scene_x']), float(r['scene_y']))
        hist.append(p)
        if len(hist) > mm:
            hist.pop(0)
        k = len(hist)
        r['k'] = k
        if not clutter and k == mm:
            dx = (hist[-1][0] - hist[0][0]) - (hist[-1][2] - hist[0][2])
            dy = (hist[-1][1] - hist[0][1]) - (hist[-1][3] - hist[0][3])
            if math.hypot(dx, dy) < a.frames * a.gate:
                clutter = True
        rms = fit_rms([(h[0], h[1]) for h in hist])
        r['rms'] = rms
        if clutter:
            r['step'] = 'clutter'
            r['mine'] = 2
            continue
        early = False
        if a.early > 0 and 4 <= k < mm:
            dx = (hist[-1][0] - hist[-4][0]) - (hist[-1][2] - hist[-4][2])
            dy = (hist[-1][1] - hist[-4][1]) - (hist[-1][3] - hist[-4][3])
            early = math.hypot(dx, dy) >= 3 * a.early
        if not (k >= mm or early):
            r['step'] = 'short'
            r['mine'] = 0
        elif a.fit > 0 and rms > a.fit:
            r['step'] = 'fit'
            r['mine'] = 0
        else:
            passed = min(passed + 1, a.hold)
            r['step'] = 'report' if passed >= a.hold else 'hold'
            r['mine'] = 1 if passed >= a.hold else 0
    return rows


def med(v):
    v = sorted(x for x in v if x == x)
    return v[len(v) // 2] if v else float('nan')


def q(v, f):
    v = sorted(x for x in v if x == x)
    return v[min(len(v) - 1, int(f * len(v)))] if v else float('nan')


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('trace')
    ap.add_argument('summary')
    ap.add_argument('--frames', type=int, default=5)
    ap.add_argument('--gate', type=float, default=0.15)
    ap.add_argument('--fit', type=float, default=0.2)
    ap.add_argument('--early', type=float, default=0.5)
    ap.add_argument('--hold', type=int, default=4)
    ap.add_argument('--list', action='store_true')
    a = ap.parse_args()
    # the categories of ir_miss_diag.py
    out = subprocess.run([sys.executable, os.path.join(HERE, 'ir_miss_diag.py'), a.trace, a.summary, '--list'],
                         check=True, capture_output=True, text=True).stdout
    cat = {}
    for line in out.splitlines():
        w = line.split()
        if len(w) > 5 and w[0] == 'seed' and w[2] == 'tid':
            cat[(int(w[1]), int(w[3]))] = w[5]
    summ = json.load(open(a.summary))
    agree = collections.Counter()
    tab = collections.defaultdict(list)
    fals = []
    det_rms = []
    frames_total = 0
    for run in summ['per_run']:
        seed = run['seed']
        frames_total += run['frames']
        lp = os.path.join(a.trace, f's{seed}_layers.csv')
        if not os.path.exists(lp):
            continue
        layers = collections.defaultdict(list)
        for r in read_csv(lp):
            layers[int(r['id'])].append(r)
        for rows in layers.values():
            rows.sort(key=lambda r: int(r['frame']))
            replay(rows, a)
            for r in rows:
                if 'mine' in r:
                    d = int(r['scene_dec'])
                    agree['same' if r['mine'] == d or (r['mine'] == 0 and d == 0) else 'differ'] += 1
        truth = collections.defaultdict(dict)
        for r in read_csv(os.path.join(a.trace, f's{seed}_targets.csv')):
            truth[int(r['tid'])][int(r['frame'])] = (float(r['x']), float(r['y']))
        scene = {}
        for rows in layers.values():
            for r in rows:
                scene[int(r['frame'])] = (float(r['scene_x']), float(r['scene_y']))
        tracks = {int(t['id']): t for t in read_csv(os.path.join(a.trace, f's{seed}_tracks.csv'))}
        for t in run['targets']:
            if t['kind'] != 'injected':
                continue
            c = cat.get((seed, t['id']), 'detected' if t['detected'] else '?')
            tid = t['id']
            # speed against the scene over the target's frames with a known scene shift
            fr = sorted(f for f in truth[tid] if f in scene)
            sp = float('nan')
            if len(fr) >= 2:
                f0, f1 = fr[0], fr[-1]
                dx = (truth[tid][f1][0] - truth[tid][f0][0]) - (scene[f1][0] - scene[f0][0])
                dy = (truth[tid][f1][1] - truth[tid][f0][1]) - (scene[f1][1] - scene[f0][1])
                sp = math.hypot(dx, dy) / (f1 - f0)
            on = [(lid, [r for r in rows if r['near_tid'] == str(tid) and r['near_d'] != '' and float(r['near_d']) <= 3.0])
                  for lid, rows in layers.items()]
            on = [(lid, rr) for lid, rr in on if rr]
            if c == 'detected':
                det_rms += [r['rms'] for _, rr in on for r in rr if r.get('step') in ('report', 'hold', 'fit')]
            if c not in ('c_scene', 'd_late'):
                continue
            steps = collections.Counter(r.get('step') for _, rr in on for r in rr)
            if steps['clutter']:
                step = 'clutter'
            else:
                step = next((s for s in reversed(ORDER) if steps[s]), 'not_fed')
            err = [float(r['near_d']) for _, rr in on for r in rr]
            rms = [r['rms'] for _, rr in on for r in rr if r.get('step') in ('fit', 'hold', 'report', 'short')]
            cov = [math.sqrt(max(0.0, float(r['cov_xx']) + float(r['cov_yy']))) for _, rr in on for r in rr]
            # d_late: where its layers were while reported
            rep_d = []
            for lid, rows in layers.items():
                if any(r in rr for l2, rr in on if l2 == lid for r in rows):
                    for r in rows:
                        if r['reported'] == '1':
                            f = int(r['frame'])
                            if f in truth[tid]:
                                rep_d.append(math.hypot(float(r['x']) - truth[tid][f][0], float(r['y']) - truth[tid][f][1]))
                            else:
                                rep_d.append(float('inf'))
            tab[(c, step)].append(dict(seed=seed, tid=tid, err=med(err), rms=med(rms), fit_fail=steps['fit'],
                                       steps=dict(steps), speed=sp, frames=t['present_frames'], cov=med(cov),
                                       rep_d=med(rep_d) if rep_d else float('nan'),
                                       rep_gone=sum(d == float('inf') for d in rep_d), n_rep=len(rep_d)))
        for lid, rows in layers.items():
            tr = tracks.get(lid)
            if tr is None or tr['is_false'] != '1':
                continue
            life = max(1, int(tr['alive']))
            mvx = (float(tr['lx']) - float(tr['hx'])) - float(tr['scene_dx'])
            mvy = (float(tr['ly']) - float(tr['hy'])) - float(tr['scene_dy'])
            rep = [r for r in rows if r['reported'] == '1']
            fals.append(dict(seed=seed, id=lid, rms=med([r['rms'] for r in rep]), speed=math.hypot(mvx, mvy) / life,
                             reported=len(rep), alive=life,
                             cov=med([math.sqrt(max(0.0, float(r['cov_xx']) + float(r['cov_yy']))) for r in rep])))
    print(f'replay against the pipeline\'s decisions: {agree["same"]} same, {agree["differ"]} differ')
    print('\nmissed targets by the step that held them (c_scene, d_late of ir_miss_diag.py)')
    print(f'{"category":9s} {"step":10s} {"n":>3s} {"err px":>7s} {"fit rms":>8s} {"frames fit>tol":>14s} '
          f'{"spread px":>9s} {"speed vs scene":>14s} {"frames in view":>14s} {"rep. dist":>9s}')
    for (c, step), v in sorted(tab.items()):
        print(f'{c:9s} {step:10s} {len(v):3d} {med([x["err"] for x in v]):7.2f} {med([x["rms"] for x in v]):8.3f} '
              f'{med([x["fit_fail"] for x in v]):14.0f} {med([x["cov"] for x in v]):9.2f} '
              f'{med([x["speed"] for x in v]):14.2f} {med([x["frames"] for x in v]):14.0f} '
              f'{med([x["rep_d"] for x in v]):9.2f}')
    if a.list:
        for (c, step), v in sorted(tab.items()):
            for x in v:
                print(f'  {c} {step} seed {x["seed"]} tid {x["tid"]} err {x["err"]:.2f} rms {x["rms"]:.3f} '
                      f'spread {x["cov"]:.2f} speed {x["speed"]:.2f} frames {x["frames"]} steps {x["steps"]} '
                      f'reported {x["n_rep"]} (gone {x["rep_gone"]}) dist {x["rep_d"]:.2f}')
    print(f'\ndetected targets: fit rms of their layers (frames tested): median {med(det_rms):.3f}, '
          f'90 % {q(det_rms, 0.9):.3f}, share above {a.fit}: '
          f'{sum(x > a.fit for x in det_rms) / max(1, len(det_rms)):.2f}')
    print(f'\nfalse tracks: {len(fals)} ({1000.0 * len(fals) / max(1, frames_total):.2f} per 1000 frames)')
    print('  fit rms while reported: ' + ', '.join(f'{x["rms"]:.3f}' for x in sorted(fals, key=lambda x: x['rms'])))
    print('  speed against the scene (px/frame): ' + ', '.join(f'{x["speed"]:.2f}' for x in sorted(fals, key=lambda x: x['speed'])))
    print('  frames reported: ' + ', '.join(str(x['reported']) for x in sorted(fals, key=lambda x: x['reported'])))
    if a.list:
        for x in fals:
            print(f'  false seed {x["seed"]} id {x["id"]} rms {x["rms"]:.3f} speed {x["speed"]:.2f} '
                  f'reported {x["reported"]} alive {x["alive"]} spread {x["cov"]:.2f}')


if __name__ == '__main__':
    main()
