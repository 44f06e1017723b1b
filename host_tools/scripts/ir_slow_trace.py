#!/usr/bin/env python3
"""Where the residual of the injected targets goes, by their speed against the scene
(docs/results/ir_clutter.md, section "Branch irslow"). Not a test.

  ir_slow_trace.py NAME=TRACE_DIR,SUMMARY_JSON [NAME=...] [--seeds 1-29]

Per injected target and traced block, the median over its frames after the first of
  z_stage = (mf_stage - loc_med_stage) / loc_sd_stage   the PSF-matched stage residual (after the
                                                       flat-field correction, before the clutter map)
  z_map   = (mf_at - loc_med) / loc_sd                 the same on the residual TBD takes (after the map)
(`pft eval --trace` columns; ir_miss_diag.py's z is z_map), and whether the evaluation detected it
(ir_miss_diag.py's categories). Speed against the scene as ir_stack_pair.py (the target's mean
velocity less the run's labelled objects').
"""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import ir_stack_pair  # noqa: E402
import collections, statistics  # noqa: E402,E401

BANDS = ((0.0, 0.15), (0.15, 0.3), (0.3, 0.6), (0.6, 1.0), (1.0, 9.0))


def stage_z(trace, seeds):
    out = {}
    for seed in seeds:
        trows = ir_stack_pair.target_rows(trace, seed)
        if trows is None:
            continue
        rows = collections.defaultdict(list)
        for tid, rr in trows.items():
            for r in rr:
                if r['labelled'] == '1' or int(r['frame']) <= 1:
                    continue
                s = float(r.get('loc_sd_stage') or 0)
                if s > 0:
                    rows[tid].append((float(r['mf_stage']) - float(r['loc_med_stage'])) / s)
        for tid, z in rows.items():
            out[(seed, tid)] = statistics.median(z)
    return out


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('blocks', nargs='+')
    ap.add_argument('--seeds', default='1-116')
    a = ap.parse_args()
    lo, hi = (int(x) for x in a.seeds.split('-'))
    seeds = range(lo, hi + 1)
    data = []
    for b in a.blocks:
        name, rest = b.split('=', 1)
        tr, sm = rest.split(',')
        c = ir_stack_pair.cats(tr, sm)
        p = ir_stack_pair.traces(tr, hi)
        zs = stage_z(tr, seeds)
        data.append((name, c, p, zs))
    keys = sorted(k for k in data[0][2] if k[0] in seeds and all(k in d[2] and k in d[1] for d in data))
    print(f'{len(keys)} injected targets, seeds {lo}-{hi}')
    print('| block | speed vs scene, px/frame | targets | detected | median z stage | median z after map | median z after map - stage (paired) |')
    print('|---|---|---|---|---|---|---|')
    base = data[0][2]
    for name, c, p, zs in data:
        for blo, bhi in BANDS + ((0.0, 9.0),):
            ks = [k for k in keys if blo <= base[k]['vs'] < bhi]
            if not ks:
                continue
            band = 'all' if (blo, bhi) == (0.0, 9.0) else f'[{blo:.2f}, {bhi:.2f})'
            print('| %s | %s | %d | %d | %.2f | %.2f | %+.2f |' % (
                name, band, len(ks), sum(c[k] == 'detected' for k in ks), ir_stack_pair.med(zs.get(k, float('nan')) for k in ks),
                ir_stack_pair.med(p[k]['z'] for k in ks), ir_stack_pair.med(p[k]['z'] - zs.get(k, float('nan')) for k in ks)))


if __name__ == '__main__':
    main()
