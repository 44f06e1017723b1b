#!/usr/bin/env python3
"""Which injected targets change outcome between two `pft eval` runs of the tbd_ir kind on the
same seeds, and whether the change comes with a change of the stage's residual at them
(docs/results/ir_clutter.md, "Branch irband2"). Not a test.

  ir_churn.py outcomes A B [LABEL_A LABEL_B]   (A, B: DIR or DIR1,DIR2,... replicates, the
      detection per target their mean) per border of entry (`entry` of per_run, the
      summary's by_entry borders): targets, detected in A and in B, lost (A only), gained
      (B only), the paired difference B - A in points with two standard errors: over targets
      (sd of the per-target 0/1 differences / sqrt(n)) and over seeds (the per-seed sums'
      spread, for targets of one run sharing its draws)
  ir_churn.py stage A B      from the traces (`--trace A/trace`): the stage's matched residual at
      the injected targets (`mf_stage`) compared frame by frame, by distance from the nearest
      border; the inside targets (> 8 px) that changed outcome, with their mean residual change
  ir_churn.py layers A [B ...]   the track layers by where they were handed over (within 4 px
      of the right or bottom border, of the left or top border, inside) and whether they were
      ever within 3 px of a target (`near_all`), with their layer-frames
  ir_churn.py edge A [B ...]    the layers on no target handed over near the right and bottom
      borders, by their rounded hand-over column (336-345) and row (260-269)
  ir_churn.py search A [B ...]  the inside targets' frames (after the first) without a track
      layer within 3 px: the search layer's existence probability above 0.5, "held elsewhere"
      (above 0.5 with under half of its live particles within 3 px of the target), a hypothesis
      on it (half or more within 3 px), a birth within 3 px
  ir_churn.py need D E [F ...]   the number of seeds a paired difference of 1 point needs for a
      standard error of 0.5 points (two s.e.) from the per-seed spread of the pairs (D, E),
      (D, F), ... pooled (five targets per seed as the real files make)

A and B are `pft eval --out` folders (summary.json; trace/ for stage). Python 3 standard
library only.
"""
import collections
import csv
import glob
import json
import math
import os
import sys

BORDERS = ['right', 'bottom', 'left', 'top', 'inside', 'all']


def outcomes(dirs):
    """{(seed, target id): (border, detected)}; DIR1,DIR2,... (replicates of one setting, e.g. other seed_offset
    values, and other seed ranges): detected is the mean over the folders that hold the target"""
    acc = {}
    for d in dirs.split(','):
        s = json.load(open(os.path.join(d, 'summary.json')))
        for r in s['per_run']:
            for t in r['targets']:
                if t['kind'] == 'injected':
                    k = (r['seed'], t['id'])
                    e, n, v = acc.get(k, (t['entry'], 0, 0.0))
                    acc[k] = (e, n + 1, v + (1.0 if t['detected'] else 0.0))
    return {k: (e, v / n) for k, (e, n, v) in acc.items()}


def pair_rows(a, b):
    """per border: (n, det A, det B, lost, gained, mean diff, s.e. targets, s.e. seeds)"""
    A, B = outcomes(a), outcomes(b)
    keys = sorted(set(A) & set(B))
    seeds = sorted(set(k[0] for k in keys))
    out = collections.OrderedDict()
    for border in BORDERS:
        ks = [k for k in keys if border == 'all' or A[k][0] == border]
        n = len(ks)
        if n < 2:
            continue
        d = [B[k][1] - A[k][1] for k in ks]
        m = sum(d) / n
        se_t = math.sqrt(sum((x - m) ** 2 for x in d) / (n - 1) / n)
        per = collections.Counter()
        for k in ks:
            per[k[0]] += B[k][1] - A[k][1]
        D = [per[s] for s in seeds]
        ms = sum(D) / len(D)
        se_s = math.sqrt(len(D) * sum((x - ms) ** 2 for x in D) / (len(D) - 1)) / n
        out[border] = (n, sum(A[k][1] for k in ks), sum(B[k][1] for k in ks),
                       sum(A[k][1] > B[k][1] for k in ks), sum(B[k][1] > A[k][1] for k in ks),
                       m, se_t, se_s, D)
    return out


def cmd_outcomes(a, b, la='A', lb='B'):
    print(f'| {lb} − {la} | targets | {la} | {lb} | lost | gained | changed | paired, points (± s.e. over targets) |'
          ' ± s.e. over seeds |')
    print('|---|---|---|---|---|---|---|---|---|')
    for border, (n, da, db, lo, ga, m, st, ss, _) in pair_rows(a, b).items():
        print(f'| {border} | {n} | {da:g} | {db:g} | {lo} | {ga} | {lo + ga} | {100 * m:+.1f} ± {100 * st:.1f} |'
              f' ± {100 * ss:.1f} |')


def read_targets(path):
    g = {}
    with open(path) as f:
        for r in csv.DictReader(f):
            g[(int(r['frame']), int(r['tid']))] = r
    return g


def cmd_stage(a, b):
    W = H = None
    s = json.load(open(os.path.join(a, 'summary.json')))
    inj = set()
    for r in s['per_run']:
        for t in r['targets']:
            if t['kind'] == 'injected':
                inj.add((r['seed'], t['id']))
    W, H = s['per_run'][0].get('width', 346), s['per_run'][0].get('height', 270)
    cnt = collections.defaultdict(lambda: [0, 0])
    diff = collections.defaultdict(list)
    per_t = collections.defaultdict(list)
    for pa in sorted(glob.glob(os.path.join(a, 'trace', 's*_targets.csv'))):
        pb = os.path.join(b, 'trace', os.path.basename(pa))
        if not os.path.exists(pb):
            continue
        ga, gb = read_targets(pa), read_targets(pb)
        for k, rb in gb.items():
            ra = ga.get(k)
            seed = int(rb['seed'])
            if ra is None or k[0] <= 1 or (seed, k[1]) not in inj:
                continue
            x, y = float(rb['x']), float(rb['y'])
            dist = min(x, y, W - 1 - x, H - 1 - y)
            bk = '<= 4 px' if dist <= 4 else ('4-8 px' if dist <= 8 else '> 8 px')
            v = float(rb['mf_stage']) - float(ra['mf_stage'])
            cnt[bk][1] += 1
            cnt[bk][0] += abs(v) > 1e-3
            diff[bk].append(v)
            if bk == '> 8 px':
                per_t[(seed, k[1])].append(v)
    print('| distance from the nearest border | target-frames | differing (> 0.001 σ) | mean difference B − A (σ) |'
          ' mean abs. difference (σ) | > 0.5 σ |')
    print('|---|---|---|---|---|---|')
    for bk in ('<= 4 px', '4-8 px', '> 8 px'):
        v = diff[bk]
        if v:
            print(f'| {bk} | {cnt[bk][1]} | {cnt[bk][0]} | {sum(v) / len(v):+.4f} | '
                  f'{sum(abs(x) for x in v) / len(v):.4f} | {sum(abs(x) > 0.5 for x in v)} |')
    A, B = outcomes(a), outcomes(b)
    print('\n| inside targets (> 8 px) | targets | mean residual change (σ) | mean change < −0.1 σ | > +0.1 σ |'
          ' 3 or more frames changed by > 0.5 σ |')
    print('|---|---|---|---|---|---|')
    for cls in ('lost', 'gained', 'same'):
        rows = []
        for k, v in per_t.items():
            if k not in A or k not in B or A[k][0] != 'inside':
                continue
            c = 'lost' if A[k][1] and not B[k][1] else ('gained' if B[k][1] and not A[k][1] else 'same')
            if c == cls:
                rows.append((sum(v) / len(v), sum(abs(x) > 0.5 for x in v)))
        if rows:
            print(f'| {cls} | {len(rows)} | {sum(r[0] for r in rows) / len(rows):+.3f} | '
                  f'{sum(r[0] < -0.1 for r in rows)} | {sum(r[0] > 0.1 for r in rows)} | {sum(r[1] >= 3 for r in rows)} |')


def cmd_layers(dirs):
    print('| run | where handed over | layers on no target (layer-frames) | layers on a target (layer-frames) |')
    print('|---|---|---|---|')
    for d in dirs:
        s = json.load(open(os.path.join(d, 'summary.json')))
        W, H = s['per_run'][0].get('width', 346), s['per_run'][0].get('height', 270)
        c = collections.Counter()
        fr = collections.Counter()
        for p in glob.glob(os.path.join(d, 'trace', 's*_tracks.csv')):
            with open(p) as f:
                for r in csv.DictReader(f):
                    x, y = float(r['hx']), float(r['hy'])
                    if W - 1 - x <= 4 or H - 1 - y <= 4:
                        w = 'right/bottom, <= 4 px'
                    elif x <= 4 or y <= 4:
                        w = 'left/top, <= 4 px'
                    else:
                        w = 'inside'
                    on = bool(r['near_all'])
                    c[(w, on)] += 1
                    fr[(w, on)] += int(r['alive'])
        for w in ('right/bottom, <= 4 px', 'left/top, <= 4 px', 'inside'):
            print(f'| {os.path.basename(d.rstrip("/"))} | {w} | {c[(w, False)]} ({fr[(w, False)]}) | '
                  f'{c[(w, True)]} ({fr[(w, True)]}) |')


def cmd_edge(dirs):
    print('| run | layers on no target by hand-over column 336 … 345 | by hand-over row 260 … 269 |')
    print('|---|---|---|')
    for d in dirs:
        cx, cy = collections.Counter(), collections.Counter()
        for p in glob.glob(os.path.join(d, 'trace', 's*_tracks.csv')):
            with open(p) as f:
                for r in csv.DictReader(f):
                    if r['near_all']:
                        continue
                    x, y = float(r['hx']), float(r['hy'])
                    cx[int(round(x))] += x >= 336
                    cy[int(round(y))] += y >= 260
        print(f'| {os.path.basename(d.rstrip("/"))} | ' + ' '.join(str(cx[k]) for k in range(336, 346)) + ' | ' +
              ' '.join(str(cy[k]) for k in range(260, 270)) + ' |')


def cmd_search(dirs):
    print('| run | inside target-frames without a track layer on them | search P > 0.5 | held elsewhere |'
          ' hypothesis on it | birth within 3 px |')
    print('|---|---|---|---|---|---|')
    for d in dirs:
        A = outcomes(d)
        c = collections.Counter()
        for p in glob.glob(os.path.join(d, 'trace', 's*_targets.csv')):
            with open(p) as f:
                for r in csv.DictReader(f):
                    k = (int(r['seed']), int(r['tid']))
                    if k not in A or A[k][0] != 'inside' or int(r['frame']) <= 1:
                        continue
                    if r['trk_d'] != '' and float(r['trk_d']) <= 3.0:
                        continue
                    alive = int(r['alive'])
                    share = int(r['alive_near']) / alive if alive else 0.0
                    sp = float(r['search_p'])
                    c['n'] += 1
                    c['p'] += sp > 0.5
                    c['held'] += sp > 0.5 and share < 0.5
                    c['hyp'] += share >= 0.5
                    c['b3'] += int(r['births3']) > 0
        n = max(1, c['n'])
        print(f'| {os.path.basename(d.rstrip("/"))} | {c["n"]} | {c["p"] / n:.3f} | {c["held"] / n:.3f} | '
              f'{c["hyp"] / n:.3f} | {c["b3"] / n:.3f} |')


def cmd_need(ref, others):
    """seeds for s.e. 0.5 points of a paired difference, from the pooled per-seed variance"""
    var, n_t, n_s = [], 0, 0
    for o in others:
        rows = pair_rows(ref, o)
        n, D = rows['all'][0], rows['all'][8]
        m = sum(D) / len(D)
        var.append(sum((x - m) ** 2 for x in D) / (len(D) - 1))
        n_t, n_s = n, len(D)
    v = sum(var) / len(var)  # variance of one seed's summed 0/1 difference
    tps = n_t / n_s          # targets per seed
    for se in (1.0, 0.5, 0.33):
        seeds = v / (tps * se / 100.0) ** 2
        print(f'per-seed variance {v:.3f} (targets per seed {tps:.2f}): s.e. {se} points needs {seeds:.0f} seeds')


def main():
    a = sys.argv[1:]
    if len(a) >= 3 and a[0] == 'outcomes':
        cmd_outcomes(*a[1:5])
    elif len(a) == 3 and a[0] == 'stage':
        cmd_stage(a[1], a[2])
    elif len(a) >= 2 and a[0] == 'layers':
        cmd_layers(a[1:])
    elif len(a) >= 2 and a[0] == 'edge':
        cmd_edge(a[1:])
    elif len(a) >= 2 and a[0] == 'search':
        cmd_search(a[1:])
    elif len(a) >= 3 and a[0] == 'need':
        cmd_need(a[1], a[2:])
    else:
        sys.exit(__doc__)


if __name__ == '__main__':
    main()
