#!/usr/bin/env python3
"""Markdown tables of TBD beside DBT from the eval summaries written by ir_results.sh.

Usage: ir_tables.py OUT   (the OUT of host_tools/scripts/ir_results.sh)
"""
import json
import os
import sys


def fmt(v, p=2, pct=False):
    if v is None:
        return '–'
    return f'{100 * v:.0f} %' if pct else f'{v:.{p}f}'


def cells(g, false_rate):
    return (f"{fmt(g['detection_probability'], pct=True)} | {fmt(g['appearance_delay'], 1)} | "
            f"{fmt(g['rmse'], 3)} | {fmt(g['correct_fraction'], pct=True)} | {fmt(false_rate, 0)}")


def table(out, title, rows):
    lines = [f'| {title} | TBD: Pd | delay | RMSE | correct | false / 1000 fr. '
             '| DBT: Pd | delay | RMSE | correct | false / 1000 fr. | DBT detections / frame | targets |',
             '|---' * 13 + '|']
    for label, name in rows:
        p = os.path.join(out, name, 'summary.json')
        if not os.path.exists(p):
            continue
        s = json.load(open(p))
        a, d = s['averaged'], s['dbt']['averaged']
        lines.append(f"| {label} | {cells(a, a['false_tracks_per_1000_frames'])} | "
                     f"{cells(d, d['false_tracks_per_1000_frames'])} | "
                     f"{s['dbt']['detections_per_frame']:.1f} | {a['targets']} |")
    print('\n'.join(lines) + '\n')


def main():
    out = sys.argv[1]
    dbs = ['03', '06', '09', '12', '15']
    for kind, title in [('float_temporal', 'clouds, temporal: SNR dB'),
                        ('float_spatial', 'clouds, spatial: SNR dB'),
                        ('float_clearsky', 'clear sky, temporal: SNR dB')]:
        table(out, title, [(db, f'{kind}_{db}') for db in dbs])
    table(out, 'clouds, temporal: SNR dB, DBT pfa',
          [(f'{db}, {pfa}', f'float_{"temporal_" + db if pfa == "1e-5" else "pfa" + pfa + "_" + db}')
           for db in ['12', '15'] for pfa in ['1e-5', '1e-7', '1e-9']])
    table(out, 'clear sky: SNR dB, DBT pfa',
          [(f'{db}, {pfa}', f'float_{"clearsky_" + db if pfa == "1e-5" else "cspfa" + pfa + "_" + db}')
           for db in ['06', '09', '12'] for pfa in ['1e-5', '1e-4', '1e-3']])
    table(out, 'q16 build',
          [('clouds, temporal, 9 dB', 'q16_temporal_09'), ('clear sky, 12 dB', 'q16_clearsky_12')])


if __name__ == '__main__':
    main()
