#!/usr/bin/env python3
"""Per-frame cost of PTE-TBD against sliding DP-TBD and the Kalman DBT on the same frames.

Instructions per frame come from callgrind (exact and repeatable): `--toggle-collect` on the
library's update function, so simulation and tool code are not counted, and `--dump-after` on
the same function, so every frame gets its own count. Printed per configuration: the mean over
the frames (the figure the cost goal is judged on), the median, and the worst frame with its
number (PTE-TBD's initiation search runs every init_period = 10 frames while a track slot is
free, so its frames are not alike). With --wall, also the wall time per frame outside valgrind
(median of 5 `pft bench` runs; noisy on a shared machine).

Configurations: the air scenario (150 cells, 300 frames, 6 dB) with PTE-TBD (table and exact
operators, and with the manoeuvre test), DP-TBD K = 10 and K = 20 and the DBT; the sharp turn
(air_sharp_turn_6db) with PTE-TBD with and without the manoeuvre test; the same target in a ten times wider window
(1500 cells) with PTE-TBD and DP-TBD K = 20. Thresholds come from a first ordinary run
(noise-only Monte Carlo) and are written into the scenario, so valgrind does not run the
Monte Carlo.

Usage: pte_callgrind.py [--wall] [--only SUBSTRING] [--name-builds] OUT_DIR BUILD_DIR [BUILD_DIR...]
  e.g. python3 host_tools/scripts/pte_callgrind.py build/instr build/host-float build/host-q16
Markdown tables on stdout: one row per build and configuration, then the ratios
DP-TBD K=20 / PTE-TBD (mean instructions per frame).
"""
import argparse
import glob
import json
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SC = os.path.join(HERE, '..', 'scenarios', 'pte')
FN = {'pte': 'pft_pte_update', 'dp': 'pft_pte_dp_update', 'dbt': 'pft_pte_dbt_update'}
CONFIGS = [  # (window label, scenario file, method, overrides, row label)
    ('150 cells', 'air_turn_6db.json', 'pte', {}, 'PTE-TBD M=40'),
    ('150 cells', 'air_turn_6db.json', 'pte', {'op': 'exact'}, 'PTE-TBD M=40 exact'),
    ('150 cells', 'air_turn_6db.json', 'dp', {'frames': 10}, 'DP-TBD K=10'),
    ('150 cells', 'air_turn_6db.json', 'dp', {'frames': 20}, 'DP-TBD K=20'),
    ('150 cells', 'air_turn_6db.json', 'dbt', {}, 'Kalman DBT'),
    ('150 cells', 'air_turn_6db.json', 'pte', {'short_len': 10, 'man_z': 1.25}, 'PTE-TBD M=40 Ms=10 (manoeuvre test)'),
    ('150 cells, sharp turn', 'air_sharp_turn_6db.json', 'pte', {}, 'PTE-TBD M=40'),
    ('150 cells, sharp turn', 'air_sharp_turn_6db.json', 'pte', {'short_len': 10, 'man_z': 1.25},
     'PTE-TBD M=40 Ms=10 (manoeuvre test)'),
    ('1500 cells', 'air_turn_wide_bench.json', 'pte', {}, 'PTE-TBD M=40'),
    ('1500 cells', 'air_turn_wide_bench.json', 'dp', {'frames': 20}, 'DP-TBD K=20'),
]


def run(cmd):
    return subprocess.run(cmd, check=True, capture_output=True, text=True)


def per_frame_instructions(prefix):
    """Instruction counts of the dumps prefix.1, prefix.2, ... (one per update call)."""
    counts = []
    for path in glob.glob(prefix + '.*'):
        m = re.search(r'\.(\d+)$', path)
        if not m:
            continue
        with open(path) as f:
            for line in f:
                mm = re.match(r'^(totals|summary):\s*(\d+)', line)
                if mm:
                    counts.append((int(m.group(1)), int(mm.group(2))))
                    break
        os.remove(path)
    counts.sort()
    return [c for _, c in counts]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--wall', action='store_true', help='also wall time per frame (5 pft bench runs)')
    ap.add_argument('--only', default='', help='only configurations whose row label contains this')
    ap.add_argument('--name-builds', action='store_true',
                    help='label rows with the build directory too (to compare builds of the same numeric type)')
    ap.add_argument('out')
    ap.add_argument('builds', nargs='+')
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    head = '| build | window | method | mean | median | worst (frame) | workspace bytes |'
    if a.wall:
        head += ' wall us/frame (median) |'
    print('Instructions per frame (callgrind, update call only; 300 frames, seed 1, 6 dB):\n')
    print(head)
    print('|' + '---|' * (head.count('|') - 1))
    means = {}
    for b in a.builds:
        pft = os.path.join(b, 'host_tools', 'pft')
        for i, (window, scen, m, ov, label) in enumerate(CONFIGS):
            if a.only and a.only not in label and a.only not in window:
                continue
            s = json.load(open(os.path.join(SC, scen)))
            s['eval']['methods'] = [m]
            s.setdefault('methods', {})
            s['methods'][m] = dict(s['methods'].get(m, {}), **ov)
            tag = f'{os.path.basename(os.path.normpath(b))}_{i}_{m}'
            vpath = os.path.join(a.out, tag + '.json')
            json.dump(s, open(vpath, 'w'), indent=1)
            # thresholds from the ordinary Monte Carlo, then fixed in the scenario
            run([pft, 'eval', '--scenario', vpath, '--runs', '1', '--threads', '1', '--out',
                 os.path.join(a.out, tag + '.eval'), '-q'])
            st = json.load(open(os.path.join(a.out, tag + '.eval', 'summary.json')))['settings'][m]
            if m == 'pte':
                s['methods'][m]['init_threshold'] = st['init_threshold']
            elif m == 'dp':
                s['methods'][m]['threshold'] = st['threshold']
            json.dump(s, open(vpath, 'w'), indent=1)
            reps = '5' if a.wall else '1'
            run([pft, 'bench', '--scenario', vpath, '--runs', reps, '--out', os.path.join(a.out, tag + '.wall'), '-q'])
            bj = json.load(open(os.path.join(a.out, tag + '.wall', 'bench.json')))
            prefix = os.path.join(a.out, tag + '.cg')
            for old in glob.glob(prefix + '*'):
                os.remove(old)
            run(['valgrind', '--tool=callgrind', f'--toggle-collect={FN[m]}', f'--dump-after={FN[m]}',
                 '--dump-instr=no', '--dump-line=no', f'--callgrind-out-file={prefix}', pft, 'bench',
                 '--scenario', vpath, '-q'])
            ir = per_frame_instructions(prefix)
            if os.path.exists(prefix):
                os.remove(prefix)
            frames = bj['frames']
            if len(ir) != frames:
                sys.exit(f'{tag}: {len(ir)} dumps for {frames} frames')
            json.dump({'label': label, 'window': window, 'numeric': bj['numeric'], 'instructions': ir},
                      open(os.path.join(a.out, tag + '.frames.json'), 'w'))
            mean = sum(ir) / len(ir)
            med = sorted(ir)[len(ir) // 2]
            worst = max(ir)
            bname = f"{bj['numeric']} ({os.path.basename(os.path.normpath(b))})" if a.name_builds else bj['numeric']
            means[(bname, window, label)] = mean
            bm = bj['methods'][m]
            row = (f"| {bname} | {window} | {label} | {mean:,.0f} | {med:,} | "
                   f"{worst:,} ({ir.index(worst) + 1}) | {bm['workspace_bytes']} |")
            if a.wall:
                row += f" {bm['median_us_per_frame']:.1f} |"
            print(row, flush=True)
    rows = []
    for (num, window, label), v in sorted(means.items()):
        dp = means.get((num, window, 'DP-TBD K=20'))
        if label == 'PTE-TBD M=40' and dp:
            rows.append(f'| {num} | {window} | {dp / v:.1f} |')
    if rows:
        print('\nDP-TBD K=20 / PTE-TBD M=40, mean instructions per frame:\n')
        print('| build | window | ratio |')
        print('|---|---|---|')
        print('\n'.join(rows))


if __name__ == '__main__':
    main()
