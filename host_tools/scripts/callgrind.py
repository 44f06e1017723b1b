#!/usr/bin/env python3
"""Instruction counts of the library's trackers under callgrind (exact and repeatable; wall time
on a shared machine is not), for every family: one measurement written once.

For each build and each case of a spec file it runs one pft command (by default `pft bench
--scenario S ARGS --out DIR`) under `valgrind --tool=callgrind --toggle-collect=FUNCTION`, so
only the library's update function (and what it calls) is counted, not the simulation or the
tool; the JSON that same run writes (bench.json by default) gives the units (frames or steps),
particle counts and extra columns. With "per_frame", callgrind also dumps after every call of
the function, and the table gives the mean (instructions/unit), the median and the worst call.
Optionally a timed `pft bench` outside valgrind adds a wall-time column. Prints a markdown table,
then the ratios the spec asks for.

Usage: callgrind.py [--only TEXT] [--name-builds] OUT_DIR SPEC.json BUILD_DIR [BUILD_DIR...]
  e.g. host_tools/scripts/callgrind.py build/cg host_tools/scripts/callgrind/tbd.json build/host-float build/host-q16
  --only TEXT    only the cases whose label contains TEXT
  --name-builds  label each row with its build directory too (two builds of one numeric type)
Specs: host_tools/scripts/callgrind/{tbd,pf,pte,tsa,ir,pre}.json. A spec has "title", "cases" and
optionally "ratios": [{"name": "...", "numerator": LABEL, "denominator": LABEL}] (instructions
per unit of two cases, per build). A case:
  {"label": "...", "scenario": "tbd/single_6db.json" (under host_tools/scenarios),
   "function": "pft_tbd_filter_update", "args": ["--runs", "1"],
   "only_filter": "SIS",                  scenarios with a "filters" list: keep this one only
   "filter_particles": 6000,              ... and give it this particle count (drops match_time_of)
   "overrides": {"scene": {"frames": 100}},   merged into the scenario copy (objects key by key)
   "prepare": {"args": ["eval", "--runs", "1"], "file": "summary.json",
               "copy": {"/methods/pte/init_threshold": "/settings/pte/init_threshold"}},
                                          run `pft ARGS --scenario COPY --out DIR -q` first and copy
                                          values of its FILE into the scenario copy (scenario
                                          pointer: file pointer), e.g. thresholds from a Monte Carlo
   "setup": [["sim", "--scenario", "{scenario}", "--seed", "1", "--out", "{work}/sim"]],
                                          pft commands run before the measurement
   "command": ["track", "--sequence", "{work}/sim", "--box", "524,239,25,30"],
                                          the measured pft command instead of bench (--out DIR -q
                                          are appended); {scenario}: the scenario copy, {work}: a
                                          directory of this build and case
   "output": "tracks.json",               the JSON the measured command writes (default bench.json)
   "per_frame": true,                     one count per call: units = calls (checked against
                                          "units" when that is given too)
   "units": "/frames" or a number,        units per run: JSON pointer into the output or a number
   "unit_name": "frame",
   "particles": "/particle_updates" | N,  pointer: particle-units in total; number: particles per unit
   "columns": {"workspace bytes": "/workspace_bytes",
               "kernel box": {"csv": "tracks.csv", "row": 0, "format": "{box_w:.0f} x {box_h:.0f}"}},
                                          extra values: pointers into the output, or fields of a
                                          row of a CSV file the measured command wrote
   "wall": {"runs": 5, "pointer": "/median_s_per_frame", "scale": 1000, "name": "wall ms/frame (median)"}}
A case may measure a program of the build directory instead of pft (no scenario, no output JSON):
  {"label": "...", "program": "tests/tools/pre_probe", "function": "pft_pre_update",
   "setup_commands": [["/usr/bin/python3", "{src}/host_tools/scripts/pre_explore.py", ...]],
                                          commands run first ({src}: the repository, {build}: the
                                          build directory, {work}: as above)
   "command": ["{work}/seq.u16", "384", "288", "14", "method=temporal"],   the program's arguments
   "per_frame": true, "skip_calls": 1,    drop the first calls (e.g. a background's start)
   "units": 11}                           a number: the calls counted
"""
import argparse
import csv
import glob
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


def set_pointer(doc, ptr, value):
    parts = ptr.lstrip('/').split('/')
    v = doc
    for part in parts[:-1]:
        v = v.setdefault(part, {})
    v[parts[-1]] = value


def merge(dst, src):
    """src merged into dst: objects key by key, everything else replaced."""
    for k, v in src.items():
        if isinstance(v, dict) and isinstance(dst.get(k), dict):
            merge(dst[k], v)
        else:
            dst[k] = v
    return dst


def run(cmd, log=None):
    if log is None:
        return subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    with open(log, 'w') as f:
        return subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, stderr=f)


def scenario_copy(case, out, tag, pft):
    """The case's scenario: reduced to one filter, overridden, prepared (written to OUT_DIR)."""
    src = os.path.join(SCEN, case['scenario'])
    if not any(k in case for k in ('only_filter', 'overrides', 'prepare')):
        return src
    j = json.load(open(src))
    if 'only_filter' in case:
        j['filters'] = [f for f in j['filters'] if f.get('label') == case['only_filter']]
        if not j['filters']:
            sys.exit(f"no filter {case['only_filter']} in {src}")
        if 'filter_particles' in case:
            j['filters'][0].pop('match_time_of', None)
            j['filters'][0]['particles'] = int(case['filter_particles'])
    if 'base' in j:  # keep the base scenario reachable from the copy
        j['base'] = os.path.normpath(os.path.join(os.path.dirname(src), j['base']))
    merge(j, case.get('overrides', {}))
    dest = os.path.join(out, tag + '.json')
    json.dump(j, open(dest, 'w'), indent=1)
    prep = case.get('prepare')
    if prep:
        pdir = os.path.join(out, tag + '.prepare')
        run([pft, *prep['args'], '--scenario', dest, '--out', pdir, '-q'])
        pj = json.load(open(os.path.join(pdir, prep.get('file', 'summary.json'))))
        for dst, sp in prep['copy'].items():
            set_pointer(j, dst, pointer(pj, sp))
        json.dump(j, open(dest, 'w'), indent=1)
    return dest


def instructions(cg_file):
    for line in open(cg_file):
        m = re.match(r'^(totals|summary):\s*(\d+)', line)
        if m:
            return int(m.group(2))
    sys.exit(f'no instruction total in {cg_file}')


def per_call_instructions(prefix):
    """Instruction counts of the dumps prefix.1, prefix.2, ... (one per call), in call order;
    the dump at program end (prefix itself) is removed."""
    counts = []
    for path in glob.glob(prefix + '.*'):
        m = re.search(r'\.(\d+)$', path)
        if not m:
            continue
        counts.append((int(m.group(1)), instructions(path)))
        os.remove(path)
    if os.path.exists(prefix):
        os.remove(prefix)
    counts.sort()
    return [c for _, c in counts]


SRC = os.path.normpath(os.path.join(HERE, '..', '..'))


def subst(args, scen, work, build=''):
    return [a.replace('{scenario}', scen).replace('{work}', work).replace('{src}', SRC)
            .replace('{build}', build) for a in args]


def numeric_of(build):
    """float or q16: the number type of a build directory (its generated pft_build_config.h)."""
    with open(os.path.join(build, 'lib', 'include', 'pft', 'pft_build_config.h')) as f:
        m = re.search(r'#define PFT_NUMERIC_(\w+) 1', f.read())
    return m.group(1).lower() if m else '?'


def measure(pft, case, scen, out, tag):
    """Instructions of one measured run under callgrind (the total, and per call with
    per_frame), and the output JSON of that run."""
    work = os.path.join(out, tag + '.work')
    os.makedirs(work, exist_ok=True)
    build = os.path.dirname(os.path.dirname(pft))
    for s in case.get('setup_commands', []):
        run(subst(s, scen, work, build))
    for s in case.get('setup', []):
        run([pft, *subst(s, scen, work), '-q'])
    cg = os.path.join(out, tag + '.callgrind.out')
    for old in glob.glob(cg + '*'):
        os.remove(old)
    bdir = os.path.join(out, tag + '.cg')
    cmd = subst(case.get('command', ['bench', '--scenario', '{scenario}', *case.get('args', [])]), scen, work, build)
    fn = case['function']
    vg = ['valgrind', '--tool=callgrind', f'--toggle-collect={fn}', f'--callgrind-out-file={cg}']
    if case.get('per_frame'):
        vg += [f'--dump-after={fn}', '--dump-instr=no', '--dump-line=no']
    log = os.path.join(out, tag + '.valgrind.log')
    if 'program' in case:
        run(vg + [os.path.join(build, case['program']), *cmd], log=log)
    else:
        run(vg + [pft, *cmd, '--out', bdir, '-q'], log=log)
    per_call = per_call_instructions(cg) if case.get('per_frame') else None
    if per_call is not None:
        per_call = per_call[case.get('skip_calls', 0):]
    total = sum(per_call) if per_call is not None else instructions(cg)
    if 'program' in case:
        return total, per_call, work, {'numeric': numeric_of(build)}
    return total, per_call, bdir, json.load(open(os.path.join(bdir, case.get('output', 'bench.json'))))


def column(case, spec, bj, bdir):
    if isinstance(spec, dict):
        with open(os.path.join(bdir, spec['csv'])) as f:
            row = list(csv.DictReader(f))[spec.get('row', 0)]
        return spec['format'].format(**{k: float(v) for k, v in row.items() if re.match(r'^-?[\d.]+$', v or '')})
    return str(pointer(bj, spec))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0],
                                 epilog='See the module docstring (this file) for the spec format.')
    ap.add_argument('--only', default='', help='only the cases whose label contains this')
    ap.add_argument('--name-builds', action='store_true', help='label rows with the build directory too')
    ap.add_argument('out')
    ap.add_argument('spec')
    ap.add_argument('builds', nargs='+')
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    spec = json.load(open(a.spec))
    cases = [c for c in spec['cases'] if a.only in c['label']]
    extra = []
    for c in cases:
        for k in c.get('columns', {}):
            if k not in extra:
                extra.append(k)
    wall_names = []
    for c in cases:
        if 'wall' in c and c['wall']['name'] not in wall_names:
            wall_names.append(c['wall']['name'])
    per_frame = any(c.get('per_frame') for c in cases)
    head = ['build', 'case', 'units', 'instructions/unit']
    if per_frame:
        head += ['median/unit', 'worst unit (its number)']
    head += ['instructions/particle-unit'] + extra + wall_names
    print('| ' + ' | '.join(head) + ' |')
    print('|' + '---|' * len(head))
    per_unit = {}
    for b in a.builds:
        pft = os.path.join(b, 'host_tools', 'pft')
        if not os.access(pft, os.X_OK):
            sys.exit(f'no {pft}')
        for i, c in enumerate(spec['cases']):
            if c not in cases:
                continue
            tag = f"{os.path.basename(os.path.normpath(b))}_{i}"
            scen = scenario_copy(c, a.out, tag, pft) if 'scenario' in c else ''
            ir, calls, bdir, bj = measure(pft, c, scen, a.out, tag)
            if calls is not None:
                units = float(len(calls))
                if 'units' in c and float(pointer(bj, c['units'])) != units:
                    sys.exit(f"{tag}: {len(calls)} calls of {c['function']} for {pointer(bj, c['units'])} units")
                json.dump({'label': c['label'], 'numeric': bj.get('numeric'), 'instructions': calls},
                          open(os.path.join(a.out, tag + '.calls.json'), 'w'))
            else:
                units = float(pointer(bj, c['units']))
            p = c.get('particles')
            if p is None:
                per_particle = ''
            elif isinstance(p, str):
                per_particle = f'{ir / float(pointer(bj, p)):,.0f}'
            else:
                per_particle = f'{ir / units / p:,.0f}'
            bname = bj.get('numeric', '?')
            if a.name_builds:
                bname += f' ({os.path.basename(os.path.normpath(b))})'
            per_unit[(bname, c['label'])] = ir / units
            row = [bname, c['label'], f"{units:.0f} {c.get('unit_name', 'frame')}s", f'{ir / units:,.0f}']
            if per_frame:
                if calls:
                    worst = max(calls)
                    row += [f'{sorted(calls)[len(calls) // 2]:,}', f'{worst:,} ({calls.index(worst) + 1})']
                else:
                    row += ['', '']
            row.append(per_particle)
            for k in extra:
                row.append(column(c, c['columns'][k], bj, bdir) if k in c.get('columns', {}) else '')
            for wn in wall_names:
                w = c.get('wall')
                if not w or w['name'] != wn:
                    row.append('')
                    continue
                wdir = os.path.join(a.out, tag + '.wall')
                run([pft, 'bench', '--scenario', scen, *c.get('args', []), '--runs', str(w['runs']), '--out', wdir,
                     '-q'])
                wj = json.load(open(os.path.join(wdir, 'bench.json')))
                row.append(f"{float(pointer(wj, w['pointer'])) * w.get('scale', 1):.3f}")
            print('| ' + ' | '.join(row) + ' |', flush=True)
    rows = []
    builds = list(dict.fromkeys(k[0] for k in per_unit))
    for r in spec.get('ratios', []):
        for bname in builds:
            num, den = per_unit.get((bname, r['numerator'])), per_unit.get((bname, r['denominator']))
            if num and den:
                rows.append(f"| {bname} | {r['name']} | {num / den:.1f} |")
    if rows:
        print('\nRatios of instructions per unit:\n')
        print('| build | ratio | value |')
        print('|---|---|---|')
        print('\n'.join(rows))


if __name__ == '__main__':
    main()
