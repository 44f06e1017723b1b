#!/usr/bin/env python3
"""Markdown tables of docs/results/tsa_ak.md from the partial summaries of `pft eval --shard`
(the shards that finished, even when not all did, so `pft merge` cannot combine them).

Usage: tsa_partials.py OUT [LAST_SEED]
  OUT/{float,csrt,q16}_swing_<level>[_loss]/partial_<k>_of_<n>.json, each with one record per
  run (csrt: a float build's evaluation of the trackers too slow for every seed);
  LAST_SEED: only the runs of seeds up to it (the same seeds for every build and scenario when
  the shards of one finished earlier than another's).

The measures are those of `pft eval` (host_tools/tsa/tsa_commands.cpp): a frame succeeds at
IoU > 0.5 and centre error < 20 px (the scenario's), or < 10 px (the project's); a run when
>= 90 % of its scored frames do; blank frames are not scored; frames to re-acquire from the
summary's per-run value (-1: never). Time: thread CPU time of the update per frame.
"""
import glob
import json
import math
import os
import sys

LEVELS = [('3_1', '3/1'), ('8_3', '8/3'), ('15_5', '15/5')]
NAMES = {'tsa': 'TSA-AK', 'tsa_paper': 'TSA, paper settings', 'ncv': 'NCV', 'ts': 'TS',
         'kcf': 'OpenCV KCF', 'csrt': 'OpenCV CSRT'}
ORDER = ['tsa', 'tsa_paper', 'ncv', 'ts', 'kcf', 'csrt']


LAST_SEED = None


def listed(items, most=6):
    """The items, or their count when there are more than `most`."""
    return ', '.join(items) if len(items) <= most else '%d runs' % len(items)


def load(out, b, lv, loss):
    """Per tracker: the list of (seed, run trace) over every partial file found."""
    d = os.path.join(out, '%s_swing_%s%s' % (b, lv, '_loss' if loss else ''))
    runs = {}
    for p in sorted(glob.glob(os.path.join(d, 'partial_*_of_*.json'))):
        j = json.load(open(p))
        for r in j['run_records']:
            if LAST_SEED is not None and r['seed'] > LAST_SEED:
                continue
            for t in r['trackers']:
                runs.setdefault(t['tracker'], []).append((r['seed'], t))
    return runs


def seeds_of(runs):
    s = sorted({seed for v in runs.values() for seed, _ in v})
    return '%d..%d' % (s[0], s[-1]) if s and s[-1] - s[0] + 1 == len(s) else ','.join(map(str, s))


def measures(v, run_min=0.9):
    ok = okp = n = 0
    runs_ok = 0
    errs = []
    cpu = []
    below = []
    reacq = []
    for seed, t in v:
        o = sum(a for a, s in zip(t['ok'], t['scored']) if s)
        op = sum(a for a, s in zip(t['ok_project'], t['scored']) if s)
        sc = sum(t['scored'])
        ok += o
        okp += op
        n += sc
        if sc and o >= math.ceil(run_min * sc):
            runs_ok += 1
        if sc and o / sc < run_min:
            below.append('%d: %.2f' % (seed, o / sc))
        errs += [e for e, s in zip(t['err'], t['scored']) if s and e is not None]
        cpu += [c for c in t['cpu_us'] if c is not None]
        if t['reacquire'] != -2:
            reacq.append(t['reacquire'])
    errs.sort()
    return {'ok': ok / n if n else 0.0, 'okp': okp / n if n else 0.0, 'runs': len(v),
            'runs_ok': runs_ok, 'below': below, 'mean': sum(errs) / len(errs) if errs else 0.0,
            'median': errs[len(errs) // 2] if errs else 0.0,
            'cpu': sum(cpu) / len(cpu) if cpu else 0.0, 'reacq': reacq}


def rows(out, forced):
    """(level label, tracker, build, runs, measures) of every table row, in table order."""
    for lv, lab in LEVELS:
        for d in ('float', 'csrt', 'q16'):
            b = 'q16' if d == 'q16' else 'float'
            runs = load(out, d, lv, forced)
            for k in ORDER:
                if k in runs:
                    yield lab, k, b, runs, measures(runs[k])


def main():
    global LAST_SEED
    out = sys.argv[1]
    if len(sys.argv) > 2:
        LAST_SEED = int(sys.argv[2])
    print('### Success on the swing levels (300 frames, 5 sudden reversals)\n')
    print('| level | tracker | build | seeds | frames ok (IoU > 0.5, < 20 px) | frames ok (project: '
          '< 10 px) | runs ok (>= 90 % of frames, 20 px) | runs below 0.9 (seed: rate) '
          '| mean / median centre error px | us/frame CPU |')
    print('|---|---|---|---|---|---|---|---|---|---|')
    for lab, k, b, runs, m in rows(out, False):
        print('| %s | %s | %s | %s | %.3f | %.3f | %d/%d | %s | %.1f / %.1f | %.0f |' % (
            lab, NAMES[k], b, seeds_of(runs), m['ok'], m['okp'], m['runs_ok'], m['runs'],
            listed(m['below']) or '-', m['mean'], m['median'], m['cpu']))
    print('\n### Forced loss (120 frames, frames 61-70 blank)\n')
    print('| level | tracker | build | seeds | re-acquired within 15 frames | median frames to '
          're-acquire | never | runs above 15 frames (seed: frames) | frames ok outside the '
          'blank (20 px) |')
    print('|---|---|---|---|---|---|---|---|---|')
    for lab, k, b, runs, m in rows(out, True):
        q = m['reacq']
        within = sum(1 for x in q if 0 <= x <= 15)
        late = ['%d: %d' % (seed, t['reacquire']) for seed, t in runs[k]
                if not 0 <= t['reacquire'] <= 15]
        srt = sorted(x if x >= 0 else 10 ** 9 for x in q)
        med = srt[len(srt) // 2] if srt else -1
        print('| %s | %s | %s | %s | %d/%d | %s | %d | %s | %.3f |' % (
            lab, NAMES[k], b, seeds_of(runs), within, len(q),
            'never' if med == 10 ** 9 else str(med), sum(1 for x in q if x < 0),
            listed(late) or '-', m['ok']))


if __name__ == '__main__':
    main()
