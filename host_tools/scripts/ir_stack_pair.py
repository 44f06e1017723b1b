#!/usr/bin/env python3
"""Two `pft eval --trace` runs of the same sequences (same scenario simulation and seeds, two tracker
blocks) compared target by target: where the targets that one block detects and the other misses
are lost (ir_miss_diag.py's categories), their PSF-matched residual strength and its local sd
under both blocks, and their speed against the scene (docs/results/ir_clutter.md, section
"Branch irstack"). Not a test.

  ir_stack_pair.py TRACE_A SUMMARY_A TRACE_B SUMMARY_B [--max-seed N]

Per injected target and block, over its frames after the first: z = (mf_at - loc_med) / loc_sd
(ir_miss_diag.py's residual strength), loc_sd (the robust sd of the matched residual around it)
and mf_at (the matched residual at it). Scene speed: the target's mean velocity in the frame over
its life minus the scene's, the scene's velocity being the mean velocity of the run's labelled
objects (they move with the scene); the sequences are the same under both blocks.
"""
import argparse
import collections
import csv
import os
import statistics
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))


def cats(trace, summary):
    out = subprocess.run([sys.executable, os.path.join(HERE, 'ir_miss_diag.py'), trace, summary, '--list'],
                         capture_output=True, text=True, check=True).stdout
    c = {}
    for line in out.splitlines():
        p = line.split()
        if len(p) > 5 and p[0] == 'seed' and p[2] == 'tid':
            c[(int(p[1]), int(p[3]))] = p[5]
    return c


def target_rows(trace, seed):
    """The rows of s<seed>_targets.csv of a `pft eval --trace` folder by target id, or None."""
    f = os.path.join(trace, f's{seed}_targets.csv')
    if not os.path.exists(f):
        return None
    rows = collections.defaultdict(list)
    with open(f) as fh:
        for r in csv.DictReader(fh):
            rows[int(r['tid'])].append(r)
    return rows


def traces(trace, max_seed):
    per = {}
    scene = {}
    for seed in range(1, max_seed + 1):
        rows = target_rows(trace, seed)
        if rows is None:
            continue
        vl = []
        for tid, rr in rows.items():
            rr.sort(key=lambda r: int(r['frame']))
            if rr[0]['labelled'] == '1' and len(rr) > 10:
                n = int(rr[-1]['frame']) - int(rr[0]['frame'])
                vl.append(((float(rr[-1]['x']) - float(rr[0]['x'])) / n, (float(rr[-1]['y']) - float(rr[0]['y'])) / n))
        scene[seed] = (statistics.mean(v[0] for v in vl), statistics.mean(v[1] for v in vl)) if vl else (0.0, 0.0)
        for tid, rr in rows.items():
            if rr[0]['labelled'] == '1':
                continue
            z, sd, mf = [], [], []
            for r in rr:
                if int(r['frame']) <= 1:
                    continue
                s = float(r['loc_sd'] or 0)
                if s > 0:
                    z.append((float(r['mf_at']) - float(r['loc_med'])) / s)
                    sd.append(s)
                    mf.append(float(r['mf_at']))
            n = max(1, int(rr[-1]['frame']) - int(rr[0]['frame']))
            v = ((float(rr[-1]['x']) - float(rr[0]['x'])) / n - scene[seed][0],
                 (float(rr[-1]['y']) - float(rr[0]['y'])) / n - scene[seed][1])
            per[(seed, tid)] = {'z': statistics.median(z) if z else float('nan'),
                                'sd': statistics.median(sd) if sd else float('nan'),
                                'mf': statistics.median(mf) if mf else float('nan'),
                                'vs': (v[0] ** 2 + v[1] ** 2) ** 0.5}
    return per


def med(v):
    v = [x for x in v if x == x]
    return statistics.median(v) if v else float('nan')


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('ta')
    ap.add_argument('sa')
    ap.add_argument('tb')
    ap.add_argument('sb')
    ap.add_argument('--max-seed', type=int, default=116)
    a = ap.parse_args()
    ca, cb = cats(a.ta, a.sa), cats(a.tb, a.sb)
    pa, pb = traces(a.ta, a.max_seed), traces(a.tb, a.max_seed)
    keys = sorted(k for k in ca if k in cb and k in pa and k in pb and k[0] <= a.max_seed)
    print(f'{len(keys)} injected targets in both')
    print('\ncategory under A -> under B (targets)')
    tr = collections.Counter((ca[k], cb[k]) for k in keys)
    for (x, y), n in sorted(tr.items(), key=lambda t: -t[1]):
        if x != y:
            print(f'  {x:14s} -> {y:14s} {n}')
    print(f'  unchanged {sum(n for (x, y), n in tr.items() if x == y)}')
    groups = {'all': keys,
              'detected by both': [k for k in keys if ca[k] == 'detected' and cb[k] == 'detected'],
              'A only (lost under B)': [k for k in keys if ca[k] == 'detected' and cb[k] != 'detected'],
              'B only (lost under A)': [k for k in keys if ca[k] != 'detected' and cb[k] == 'detected'],
              'neither': [k for k in keys if ca[k] != 'detected' and cb[k] != 'detected']}
    print('\n| targets | n | median z A | median z B | median z B - A (paired) | local sd A | local sd B |'
          ' matched residual A | matched residual B | median scene speed, px/frame | share < 0.3 px/frame |')
    print('|---|---|---|---|---|---|---|---|---|---|---|')
    for g, ks in groups.items():
        if not ks:
            continue
        print('| %s | %d | %.2f | %.2f | %+.2f | %.3f | %.3f | %.2f | %.2f | %.2f | %.0f %% |' % (
            g, len(ks), med(pa[k]['z'] for k in ks), med(pb[k]['z'] for k in ks),
            med(pb[k]['z'] - pa[k]['z'] for k in ks), med(pa[k]['sd'] for k in ks), med(pb[k]['sd'] for k in ks),
            med(pa[k]['mf'] for k in ks), med(pb[k]['mf'] for k in ks), med(pa[k]['vs'] for k in ks),
            100.0 * sum(pa[k]['vs'] < 0.3 for k in ks) / len(ks)))
    print('\nby scene speed (px/frame): detected under A / under B (targets)')
    for lo, hi in ((0, 0.3), (0.3, 0.6), (0.6, 1.0), (1.0, 9.0)):
        ks = [k for k in keys if lo <= pa[k]['vs'] < hi]
        if ks:
            print('  [%.1f, %.1f): %d targets, A %d, B %d, median z A %.2f B %.2f' % (
                lo, hi, len(ks), sum(ca[k] == 'detected' for k in ks), sum(cb[k] == 'detected' for k in ks),
                med(pa[k]['z'] for k in ks), med(pb[k]['z'] for k in ks)))


if __name__ == '__main__':
    main()
