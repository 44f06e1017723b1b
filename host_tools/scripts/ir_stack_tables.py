#!/usr/bin/env python3
"""Paired tables of docs/results/ir_clutter.md, section "Branch irstack": TBD's detection and
false tracks per 1000 frames for variants of one tracker block on the real backgrounds, paired by
seed against the first point, from `pft eval` summaries of the tbd_ir kind. Not a test.

The measures and the paired differences are ir_hold12_tables.py's (detected: ratio of sums over
runs; false tracks per 1000 frames: mean of the per-run rates); this adds a seed range (to read
seeds 1-29 out of a 1-116 evaluation), the false tracks' count and the false rate's upper end
(mean + 1 s.e.).

Usage:
  python3 host_tools/scripts/ir_stack_tables.py [--seeds A-B] [--fine] POINT [POINT ...]
      POINT = LABEL=tbd:DIR (or dbt:DIR; DIR1,DIR2 pools evaluations), as in ir_hold12_tables.py
      --fine: the false-track rates with two decimals and a column of the mean delay to the first
      report (frames, over the detected targets)
  The paired cells read "no common seeds" where a point shares fewer than two seeds with the
  first (points over other seed ranges can share one table).
"""
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from ir_hold12_tables import load, pairable, parse, paired, paired_cells, per_seed, stats, fmt  # noqa: E402


def main():
    args = sys.argv[1:]
    if args and args[0] in ('-h', '--help'):
        print(__doc__)
        return
    bad = [a for a in args if not a.startswith('--') and '=' not in a and not a[:1].isdigit()]
    if bad:
        sys.exit('ir_stack_tables.py: %r is not a POINT (LABEL=tbd:DIR)\n%s' % (bad[0], __doc__))
    lo, hi = 1, 10 ** 9
    fine = False
    while args and args[0] in ('--seeds', '--fine'):
        if args[0] == '--fine':
            fine = True
            args = args[1:]
            continue
        a, b = args[1].split('-')
        lo, hi = int(a), int(b)
        args = args[2:]
    if not args:
        sys.exit(__doc__)
    ref = None
    if fine:
        print('| point | runs | targets | detected (± s.e.) | false tracks | false / 1000 fr. (± s.e.) | upper end |'
              ' delay, frames | detected − first, points (paired ± s.e.) | false − first (paired ± s.e.) |')
        print('|---|---|---|---|---|---|---|---|---|---|')
    else:
        print('| point | runs | targets | detected (± s.e.) | false tracks | false / 1000 fr. (± s.e.) | upper end |'
              ' detected − first, points (paired ± s.e.) | false − first (paired ± s.e.) |')
        print('|---|---|---|---|---|---|---|---|---|')
    for lab, trk, dirs in (parse(x) for x in args):
        per = [r for r in load(trk, dirs) if lo <= r['seed'] <= hi]
        st = stats(per_seed(per))
        nf = sum(r['false_tracks'] for r in per)
        ref_before = ref
        dd, df = paired_cells(st, ref)
        ref = ref or st
        if not fine:
            print('| %s | %d | %d | %s | %d | %s | %.1f | %s | %s |' % (
                lab, st['runs'], st['targets'], fmt(st['pd'], 100, ' %'), nf, fmt(st['false']),
                st['false'][0] + st['false'][1], dd, df))
            continue
        if ref_before is not None and pairable(st, ref_before):
            (a, b), (c, d) = paired(st, ref_before)
            dd, df = '%+.1f ± %.1f' % (100 * a, 100 * b), '%+.2f ± %.2f' % (c, d)
        print('| %s | %d | %d | %.1f %% (± %.1f) | %d | %.2f (± %.2f) | %.2f | %.1f | %s | %s |' % (
            lab, st['runs'], st['targets'], 100 * st['pd'][0], 100 * st['pd'][1], nf, st['false'][0],
            st['false'][1], st['false'][0] + st['false'][1], st['delay'][0], dd, df))


if __name__ == '__main__':
    main()
