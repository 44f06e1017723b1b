#!/usr/bin/env python3
"""Instruction counts of the library's trackers under callgrind (exact and repeatable; wall time
on a shared machine is not), for every family: one measurement written once.

For each build and each case of a spec file it runs `pft bench --scenario S ARGS --out DIR`
under `valgrind --tool=callgrind --toggle-collect=FUNCTION`, so only the library's update
function (and what it calls) is counted, not the simulation or the tool; the bench.json written
by that same run gives the units (frames or steps) and particle counts. Optionally a timed
`pft bench` outside valgrind adds a wall-time column. Prints a markdown table.

Usage: callgrind.py OUT_DIR SPEC.json BUILD_DIR [BUILD_DIR...]
  e.g. host_tools/scripts/callgrind.py build/cg host_tools/scripts/callgrind/tbd.json build/host-float build/host-q16
Specs: host_tools/scripts/callgrind/{tbd,pf}.json. A case:
  {"label": "...", "scenario": "tbd/single_6db.json" (under host_tools/scenarios),
   "function": "pft_tbd_filter_update", "args": ["--runs", "1"],
   "only_filter": "SIS",                  scenarios with a "filters" list: keep this one only
   "filter_particles": 6000,              ... and give it this particle count (drops match_time_of)
   "units": "/frames" or a number,        units per run: JSON pointer into bench.json or a number
   "unit_name": "frame",
   "particles": "/particle_updates" | N,  pointer: particle-units in total; number: particles per unit
   "columns": {"workspace bytes": "/workspace_bytes"},   extra bench.json values
   "wall": {"runs": 5, "pointer": "/median_s_per_frame", "scale": 1000, "name": "wall ms/frame (median)"}}
"""
import json
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SCEN = os.path.normpath(os.path.join(HERE, '..', 'scenarios'))


def pointer(doc, ptr):
    """Value at a JSON pointer ("/a/0/b"), or the number itself."""
    if isinstance(ptr, (int, float)):
        return ptr
    v = doc
    for part in ptr.lstrip('/').split('/'):
        v = v[int(part)] if isinstance(v, list) else v[part]
    return v


def scenario_copy(case, out, tag):
    """The case's scenario, reduced to one filter when asked (written to OUT_DIR)."""
    src = os.path.join(SCEN, case['scenario'])
    if 'only_filter' not in case:
        return src
    j = json.load(open(src))
    j['filters'] = [f for f in j['filters'] if f.get('label') == case['only_filter']]
    if not j['filters']:
        sys.exit(f"no filter {case['only_filter']} in {src}")
    if 'filter_particles' in case:
        j['filters'][0].pop('match_time_of', None)
        j['filters'][0]['particles'] = int(case['filter_particles'])
    if 'base' in j:  # keep the base scenario reachable from the copy
        j['base'] = os.path.normpath(os.path.join(os.path.dirname(src), j['base']))
    dest = os.path.join(out, tag + '.json')
    json.dump(j, open(dest, 'w'), indent=1)
    return dest


def instructions(cg_file):
    for line in open(cg_file):
        m = re.match(r'^(totals|summary):\s*(\d+)', line)
        if m:
            return int(m.group(2))
    sys.exit(f'no instruction total in {cg_file}')


def measure(pft, case, scen, out, tag):
    """Instructions of one bench run under callgrind, and the bench.json of that run."""
    cg = os.path.join(out, tag + '.callgrind.out')
    bdir = os.path.join(out, tag + '.cg')
    cmd = ['valgrind', '--tool=callgrind', f"--toggle-collect={case['function']}", f'--callgrind-out-file={cg}',
           pft, 'bench', '--scenario', scen, *case.get('args', []), '--out', bdir, '-q']
    with open(os.path.join(out, tag + '.valgrind.log'), 'w') as log:
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=log)
    return instructions(cg), json.load(open(os.path.join(bdir, 'bench.json')))


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    out, spec_file, builds = sys.argv[1], sys.argv[2], sys.argv[3:]
    os.makedirs(out, exist_ok=True)
    spec = json.load(open(spec_file))
    cases = spec['cases']
    extra = []
    for c in cases:
        for k in c.get('columns', {}):
            if k not in extra:
                extra.append(k)
    wall_names = []
    for c in cases:
        if 'wall' in c and c['wall']['name'] not in wall_names:
            wall_names.append(c['wall']['name'])
    head = ['build', 'case', 'units', 'instructions/unit', 'instructions/particle-unit'] + extra + wall_names
    print('| ' + ' | '.join(head) + ' |')
    print('|' + '---|' * len(head))
    for b in builds:
        pft = os.path.join(b, 'host_tools', 'pft')
        if not os.access(pft, os.X_OK):
            sys.exit(f'no {pft}')
        for i, c in enumerate(cases):
            tag = f"{os.path.basename(os.path.normpath(b))}_{i}"
            scen = scenario_copy(c, out, tag)
            ir, bj = measure(pft, c, scen, out, tag)
            units = float(pointer(bj, c['units']))
            p = c.get('particles')
            if p is None:
                per_particle = ''
            elif isinstance(p, str):
                per_particle = f'{ir / float(pointer(bj, p)):,.0f}'
            else:
                per_particle = f'{ir / units / p:,.0f}'
            row = [bj.get('numeric', '?'), c['label'], f"{units:.0f} {c.get('unit_name', 'frame')}s",
                   f'{ir / units:,.0f}', per_particle]
            for k in extra:
                row.append(str(pointer(bj, c['columns'][k])) if k in c.get('columns', {}) else '')
            for wn in wall_names:
                w = c.get('wall')
                if not w or w['name'] != wn:
                    row.append('')
                    continue
                wdir = os.path.join(out, tag + '.wall')
                subprocess.run([pft, 'bench', '--scenario', scen, *c.get('args', []), '--runs', str(w['runs']),
                                '--out', wdir, '-q'], check=True, stdout=subprocess.DEVNULL)
                wj = json.load(open(os.path.join(wdir, 'bench.json')))
                row.append(f"{float(pointer(wj, w['pointer'])) * w.get('scale', 1):.3f}")
            print('| ' + ' | '.join(row) + ' |', flush=True)


if __name__ == '__main__':
    main()
