#!/usr/bin/env python3
"""Rows 'main / branch (difference, in standard errors of the difference)' of PTE-TBD in two
`pft eval` summaries of the same scenario and seeds, as in docs/results/pte.md (sections
"Branch pte12", "pte15", "pte16", "pte17"): standard errors binomial over the frames
(detection; reliable over its denominator), over the declared points (false-track
probability), and RMSE / sqrt(2 correct points) for the RMSE; then both GOSPA values.

Usage: pte_pair_rows.py "LABEL=MAIN_DIR,BRANCH_DIR" [...]   (DIR: a pft eval --out directory)
"""
import json, math, sys
def res(d):
    s = json.load(open(d + '/summary.json'))
    return [r for r in s['results'] if r['method'] == 'pte'][0]
def row(label, a, b):
    out = []
    for key, n in (('detection_prob', 'true_frames'), ('reliable3_prob', 'reliable_den'),
                   ('false_track_prob', 'declared_points'), ('rmse_cells', 'correct_points')):
        x, y = a[key], b[key]
        if key == 'rmse_cells':
            sa, sb = x / math.sqrt(2 * a[n]), y / math.sqrt(2 * b[n])
        else:
            sa, sb = math.sqrt(x * (1 - x) / a[n]), math.sqrt(y * (1 - y) / b[n])
        se = math.hypot(sa, sb)
        d = y - x
        z = '' if abs(d) < 5e-5 else ', %+.1f SE' % (d / se if se > 0 else float('nan'))
        out.append('%.4f / %.4f (%+.4f%s)' % (x, y, d, z))
    out.append('%.4f / %.4f' % (a['gospa'], b['gospa']))
    print('| ' + label + ' | ' + ' | '.join(out) + ' |')
for arg in sys.argv[1:]:
    label, a, b = arg.split('=', 1)[0], *arg.split('=', 1)[1].split(',')
    row(label, res(a), res(b))
