#!/usr/bin/env python3
"""Markdown tables of docs/results/pte.md from the summaries written by pte_results.sh.

Usage: pte_tables.py OUT_DIR   (OUT_DIR/{float,q16}/{snr_sweep,snr_sweep_dp10,...}/summary.json)
"""
import json
import os
import sys


def load(out, build, name):
    p = os.path.join(out, build, name, 'summary.json')
    return json.load(open(p)) if os.path.exists(p) else None


def fmt(v, d=3):
    return '-' if v is None else f'{v:.{d}f}'


def main():
    out = sys.argv[1]
    cols = []  # (header, build, summary name, method)
    for name, method in [('snr_sweep', 'pte'), ('snr_sweep_pte_exact', 'pte'), ('snr_sweep', 'dp'),
                         ('snr_sweep_dp10', 'dp'), ('snr_sweep', 'dbt')]:
        for build in ('float', 'q16'):
            s = load(out, build, name)
            if s is None:
                continue
            lab = next((r['label'] for r in s['results'] if r['method'] == method), method)
            if name.endswith('pte_exact'):
                lab += ' exact'
            cols.append((f'{lab} {build}', s, method))
    if not cols:
        sys.exit('no summaries under ' + out)
    snrs = cols[0][1]['snr_db']
    runs = cols[0][1]['runs']
    print(f'Runs per point: {runs} (seeds {cols[0][1]["seeds"][0]}..{cols[0][1]["seeds"][1]}).\n')
    for key, title, d in [('detection_prob', 'Detection probability (Fig. 5b)', 3),
                          ('reliable3_prob', '3-frame reliable tracking probability (Fig. 5c)', 3),
                          ('false_track_prob', 'False-track probability (Fig. 5d)', 3),
                          ('rmse_cells', 'RMSE of correct points, cells (Fig. 5a)', 3),
                          ('us_per_frame', 'Wall time per frame in the sweep, us (2 shared cores)', 1)]:
        print(f'### {title}\n')
        print('| SNR dB | ' + ' | '.join(c[0] for c in cols) + ' |')
        print('|---|' + '---|' * len(cols))
        for snr in snrs:
            row = []
            for _, s, m in cols:
                r = next((r for r in s['results'] if r['method'] == m and r['snr_db'] == snr), None)
                row.append(fmt(r[key] if r else None, d))
            print(f'| {snr:g} | ' + ' | '.join(row) + ' |')
        print()
    print('### First SNR from which each criterion holds at every higher SNR\n')
    print('| method | Pd > 0.9 | reliable > 0.9 | false < 0.1 | RMSE < 3 | all four |')
    print('|---|---|---|---|---|---|')
    for h, s, m in cols:
        f = s['first_snr_meeting'][m]
        v = [f[k] for k in ('detection_prob_above_0.9', 'reliable3_above_0.9', 'false_track_below_0.1',
                            'rmse_below_3', 'all_four')]
        print(f'| {h} | ' + ' | '.join('never' if x is None else f'{x:g} dB' for x in v) + ' |')
    print()
    for name, title in [('air_turn_6db', 'Air target, 6 dB'), ('sea_boat_6db', 'Boat in K-clutter, SCNR 6 dB')]:
        print(f'### {title} ({runs} runs)\n')
        print('| method | build | Pd | reliable3 | false | RMSE | us/frame | false (with coasting) | threshold |')
        print('|---|---|---|---|---|---|---|---|---|')
        for build in ('float', 'q16'):
            s = load(out, build, name)
            if s is None:
                continue
            for r in s['results']:
                st = s['settings'][r['method']]
                thr = st.get('init_threshold', st.get('threshold'))
                print(f"| {r['label']} | {build} | {fmt(r['detection_prob'])} | {fmt(r['reliable3_prob'])} | "
                      f"{fmt(r['false_track_prob'])} | {fmt(r['rmse_cells'])} | {fmt(r['us_per_frame'], 1)} | "
                      f"{fmt(r['with_coasting']['false_track_prob'])} | {fmt(thr, 2)} |")
        print()


if __name__ == '__main__':
    main()
