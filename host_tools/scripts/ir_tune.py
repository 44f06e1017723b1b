#!/usr/bin/env python3
"""Tuning lines of the IR pipeline's TBD settings (docs/results/ir_clutter.md, "Full-frame
TBD in the pipeline"): each line is a shipped sweep point (host_tools/scenarios/tbd_ir) with a
patch of its sections, evaluated with `pft eval` and summarised in one table row.

Usage: ir_tune.py BUILD OUT [--runs N] [--threads T] LINE...
  LINE = NAME:SNR:JSON   e.g.  pk:09:'{"tracker": {"birth_peaks": 32}}'
  a JSON "background" of "clear" stands for a clear sky (no clouds, no horizon).
Evaluations already in OUT/NAME_SNR are reused; the patched scenario is written beside them.
"""
import argparse
import json
import os
import subprocess

HERE = os.path.dirname(os.path.abspath(__file__))
SC = os.path.join(HERE, '..', 'scenarios', 'tbd_ir')
CLEAR = {"source": "procedural", "cloud_cover": 0, "horizon": None}


def fmt(v, p=2, pct=False):
    if v is None:
        return '–'
    return f'{100 * v:.0f} %' if pct else f'{v:.{p}f}'


def cells(g):
    return (f"{fmt(g['detection_probability'], pct=True)} | {fmt(g['appearance_delay'], 1)} | "
            f"{fmt(g['correct_fraction'], pct=True)} | {fmt(g['false_tracks_per_1000_frames'], 0)}")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('build')
    ap.add_argument('out')
    ap.add_argument('--runs', type=int, default=20)
    ap.add_argument('--threads', type=int, default=2)
    ap.add_argument('lines', nargs='+')
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    print('| line | SNR | TBD: Pd | delay | correct | false / 1000 fr. | DBT: Pd | delay | correct | false / 1000 fr. |')
    print('|---' * 10 + '|')
    for line in a.lines:
        name, snr, patch = line.split(':', 2)
        s = json.load(open(os.path.join(SC, f'sweep_snr_{snr}db.json')))
        for sec, val in json.loads(patch).items():
            if sec == 'background' and val == 'clear':
                s['background'] = dict(CLEAR)
            elif isinstance(val, dict) and isinstance(s.get(sec), dict) and sec != 'background':
                s[sec].update(val)
            else:
                s[sec] = val
        d = os.path.join(a.out, f'{name}_{snr}')
        os.makedirs(d, exist_ok=True)
        scen = os.path.join(d, 'scenario.json')
        json.dump(s, open(scen, 'w'), indent=1)
        summ = os.path.join(d, 'summary.json')
        if not os.path.exists(summ):
            subprocess.run([os.path.join(a.build, 'host_tools', 'pft'), 'eval', '--scenario', scen,
                            '--runs', str(a.runs), '--threads', str(a.threads), '--out', d, '-q'],
                           check=True)
        r = json.load(open(summ))
        print(f"| {name} | {snr} | {cells(r['averaged'])} | {cells(r['dbt']['averaged'])} |", flush=True)


if __name__ == '__main__':
    main()
