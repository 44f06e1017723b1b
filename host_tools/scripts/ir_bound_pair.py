#!/usr/bin/env python3
"""Paired clairvoyant detection of two residuals (docs/results/ir_clutter.md, "Branch irbg2").

  ir_bound_pair.py REP_A CACHE_A REP_B CACHE_B K

REP_X: the output of `ir_bound.py report` for residual X (its sd_K and its Tev(1/1000) and
Tev(10/1000) at K are read from it); CACHE_X: its `--cache` folder (tg_09_sN.json). Prints, per
rate, the targets found by both, by A only and by B only, and McNemar's z; a target counts for X
when its best true-path K-sum over X's sd_K exceeds X's own Tev, as `report` counts it.
Not a test."""
import sys, json, glob, re, os, math
def parse(rep, K):
    sd = tev = None
    for line in open(rep):
        m = re.match(rf'K {K}: sd of the K-sum at target-free positions ([0-9.]+)', line)
        if m: sd = float(m.group(1))
        f = line.split()
        if len(f) > 9 and f[0] == str(K) and re.match(r'^[0-9.]+$', f[1]) and not line.startswith('K'):
            tev = (float(f[7]), float(f[8]))
    return sd, tev
def best(cache, K, sd):
    out = {}
    for p in glob.glob(os.path.join(cache, 'tg_09_s*.json')):
        if not re.search(r'tg_09_s\d+\.json$', p): continue
        s = json.load(open(p))
        for t in s['targets']:
            out[(s['seed'], t['id'])] = max([v for _, v in t['sums'][str(K)]], default=-math.inf) / sd
    return out
ra, ca, rb, cb, K = sys.argv[1:6]
sa, ta = parse(ra, K); sb, tb = parse(rb, K)
ba, bb = best(ca, K, sa), best(cb, K, sb)
assert ba.keys() == bb.keys(), 'different targets'
for i, rate in enumerate((1, 10)):
    ha = {k: v > ta[i] for k, v in ba.items()}; hb = {k: v > tb[i] for k, v in bb.items()}
    both = sum(ha[k] and hb[k] for k in ha); ao = sum(ha[k] and not hb[k] for k in ha); bo = sum(hb[k] and not ha[k] for k in ha)
    z = (bo - ao) / math.sqrt(ao + bo) if ao + bo else 0.0
    print(f'K {K} <= {rate}/1000: Tev A {ta[i]} B {tb[i]}; n {len(ha)}: both {both}, A only {ao}, B only {bo}; McNemar z {z:.1f}')
