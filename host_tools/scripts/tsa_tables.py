#!/usr/bin/env python3
"""Markdown tables of docs/results/tsa_ak.md from the summaries tsa_results.sh writes.

Usage: tsa_tables.py OUT   (OUT/{float,q16}_swing_<level>[_loss]/summary.json)
"""
import json
import os
import sys

LEVELS = [('3_1', '3/1'), ('8_3', '8/3'), ('15_5', '15/5')]
NAMES = {'tsa': 'TSA-AK', 'tsa_paper': 'TSA, paper settings', 'ncv': 'NCV', 'ts': 'TS',
         'kcf': 'OpenCV KCF', 'csrt': 'OpenCV CSRT'}


def load(out, b, lv, loss):
    p = os.path.join(out, '%s_swing_%s%s' % (b, lv, '_loss' if loss else ''), 'summary.json')
    return json.load(open(p)) if os.path.exists(p) else None


def rows(s):
    return {t['tracker']: t for t in s['trackers']}


def main():
    out = sys.argv[1]
    print('### Success on the swing levels (300 frames, 5 sudden reversals)\n')
    print('| level | tracker | build | frames ok (IoU > 0.5, < 20 px) | frames ok (project: < 10 px) '
          '| runs ok (>= 90 % of frames, 20 px) | mean / median centre error px '
          '| us/frame wall | us/frame CPU |')
    print('|---|---|---|---|---|---|---|---|---|')
    for lv, lab in LEVELS:
        for b in ('float', 'q16'):
            s = load(out, b, lv, False)
            if not s:
                continue
            r = rows(s)
            for k in ['tsa', 'tsa_paper', 'ncv', 'ts', 'kcf', 'csrt']:
                if k not in r:
                    continue
                t = r[k]
                print('| %s | %s | %s | %.3f | %.3f | %d/%d | %.1f / %.1f | %.0f | %.0f |' % (
                    lab, NAMES[k], b, t['success_rate'], t['success_rate_project'], t['runs_succeeded'],
                    t['runs'], t['mean_center_error'], t['median_center_error'], t['us_per_frame'],
                    t['cpu_us_per_frame']))
    print('\n### Forced loss (120 frames, frames 61-70 blank)\n')
    print('| level | tracker | build | re-acquired within 15 frames | median frames to re-acquire '
          '| never | frames ok outside the blank (20 px) |')
    print('|---|---|---|---|---|---|---|')
    for lv, lab in LEVELS:
        for b in ('float', 'q16'):
            s = load(out, b, lv, True)
            if not s:
                continue
            r = rows(s)
            for k in ['tsa', 'tsa_paper', 'ncv', 'ts', 'kcf', 'csrt']:
                if k not in r:
                    continue
                t = r[k]
                re = t.get('reacquire_frames', [])
                ok = [q for q in re if q >= 0]
                med = sorted(ok)[len(ok) // 2] if ok else float('nan')
                print('| %s | %s | %s | %d/%d | %s | %d | %.3f |' % (
                    lab, NAMES[k], b, t.get('reacquired_within_15', 0), t['runs'],
                    '%d' % med if ok else '-', len(re) - len(ok), t['success_rate']))
    print('\n### Speed in the same run (float build, thread CPU time per update)\n')
    print('| level | TSA-AK us | KCF us | CSRT us | KCF / TSA-AK | CSRT / TSA-AK |')
    print('|---|---|---|---|---|---|')
    for lv, lab in LEVELS:
        s = load(out, 'float', lv, False)
        if not s:
            continue
        r = rows(s)
        if not all(k in r for k in ('tsa', 'kcf', 'csrt')):
            continue
        a, k, c = (r[x]['cpu_us_per_frame'] for x in ('tsa', 'kcf', 'csrt'))
        print('| %s | %.0f | %.0f | %.0f | %.1f | %.0f |' % (lab, a, k, c, k / a, c / a))


if __name__ == '__main__':
    main()
