#!/usr/bin/env python3
"""Per-frame cost of PTE-TBD against sliding DP-TBD (and the Kalman DBT) on the same frames:
instructions per frame under callgrind (exact and repeatable; --toggle-collect on the
library's update function, so simulation and tool code are not counted) and wall time per
frame outside valgrind (median of `pft bench`, noisy on this shared machine).

Configurations: the air scenario (150 cells, 300 frames, 6 dB) with PTE-TBD (table and exact
operators), DP-TBD K = 10 and K = 20, DBT; the same target in a ten times wider range window
(1500 cells) with PTE-TBD and DP-TBD K = 20. Thresholds are taken from a first ordinary run
(noise-only Monte Carlo) and written into the scenario, so valgrind does not run the
Monte Carlo.

Usage: pte_callgrind.py OUT_DIR BUILD_DIR [BUILD_DIR...]   (markdown table on stdout)
"""
import json
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SC = os.path.join(HERE, '..', 'scenarios', 'pte')
FN = {'pte': 'pft_pte_update', 'dp': 'pft_pte_dp_update', 'dbt': 'pft_pte_dbt_update'}
CONFIGS = [  # (label, scenario file, method, overrides)
    ('air 150 cells', 'air_turn_6db.json', 'pte', {}),
    ('air 150 cells', 'air_turn_6db.json', 'pte', {'op': 'exact'}),
    ('air 150 cells', 'air_turn_6db.json', 'dp', {'frames': 10}),
    ('air 150 cells', 'air_turn_6db.json', 'dp', {'frames': 20}),
    ('air 150 cells', 'air_turn_6db.json', 'dbt', {}),
    ('air 1500 cells', 'air_turn_wide_bench.json', 'pte', {}),
    ('air 1500 cells', 'air_turn_wide_bench.json', 'dp', {'frames': 20}),
]


def run(cmd, **kw):
    return subprocess.run(cmd, check=True, capture_output=True, text=True, **kw)


def main():
    out = sys.argv[1]
    builds = sys.argv[2:]
    os.makedirs(out, exist_ok=True)
    print('| build | frames | method | instructions/frame | wall us/frame (median) | workspace bytes |')
    print('|---|---|---|---|---|---|')
    for b in builds:
        pft = os.path.join(b, 'host_tools', 'pft')
        for i, (label, scen, m, ov) in enumerate(CONFIGS):
            s = json.load(open(os.path.join(SC, scen)))
            s['eval']['methods'] = [m]
            s.setdefault('methods', {})
            s['methods'][m] = dict(s['methods'].get(m, {}), **ov)
            tag = f'{os.path.basename(b)}_{i}_{m}'
            vpath = os.path.join(out, tag + '.json')
            json.dump(s, open(vpath, 'w'), indent=1)
            # thresholds from the ordinary Monte Carlo, then fixed in the scenario
            run([pft, 'eval', '--scenario', vpath, '--runs', '1', '--threads', '1', '--out',
                 os.path.join(out, tag + '.eval'), '-q'])
            st = json.load(open(os.path.join(out, tag + '.eval', 'summary.json')))['settings'][m]
            if m == 'pte':
                s['methods'][m]['init_threshold'] = st['init_threshold']
            elif m == 'dp':
                s['methods'][m]['threshold'] = st['threshold']
            json.dump(s, open(vpath, 'w'), indent=1)
            run([pft, 'bench', '--scenario', vpath, '--runs', '5', '--out', os.path.join(out, tag + '.wall'), '-q'])
            bj = json.load(open(os.path.join(out, tag + '.wall', 'bench.json')))
            cg = os.path.join(out, tag + '.callgrind.out')
            run(['valgrind', '--tool=callgrind', f'--toggle-collect={FN[m]}', f'--callgrind-out-file={cg}',
                 pft, 'bench', '--scenario', vpath, '-q'])
            ir = None
            for line in open(cg):
                mm = re.match(r'^(totals|summary):\s*(\d+)', line)
                if mm:
                    ir = int(mm.group(2))
                    break
            frames = bj['frames']
            bm = bj['methods'][m]
            print(f"| {bj['numeric']} | {label}, {frames} | {bm['label']}"
                  f"{' exact' if ov.get('op') == 'exact' else ''} | {ir / frames:,.0f} | "
                  f"{bm['median_us_per_frame']:.1f} | {bm['workspace_bytes']} |", flush=True)


if __name__ == '__main__':
    main()
