#!/usr/bin/env python3
"""Checks that two generated golden headers (tbd_q16_vectors.h or pf_q16_vectors.h, before and
after the change of pixel convention) differ by exactly the shift of the positions by one pixel
(dx = dy = 1, i.e. -65536 in Q16.16 raw units; region bounds by -1) and in nothing else.
Usage: tests/vectors/pixel_shift_check.py tbd|pf OLD NEW
(OLD e.g. from `git show 75c7de5:tests/vectors/tbd_q16_vectors.h`)."""
import re, sys

def arrays(path):
    txt = open(path).read()
    out = {}
    for m in re.finditer(r'static const uint32_t (\w+)\[(\d+)\]\[(\d+)\] = \{(.*?)\n\};', txt, re.S):
        rows = [[int(v.rstrip('u')) for v in r.split(',')] for r in re.findall(r'\{([^{}]*)\}', m.group(4))]
        out[m.group(1)] = rows
    return out

S = 65536
def sh(v, d=S):  # v - d as uint32
    return (v - d) & 0xFFFFFFFF

def expect_tbd(name, old):
    exp = [list(r) for r in old]
    if name.startswith('tv_filt'):
        for r in exp:
            if r[0] == 1:
                r[1], r[2] = sh(r[1]), sh(r[2])
    elif name.startswith('tv_mgr'):
        maxt = 3
        for r in exp:
            if r[0] == 1:
                r[1], r[2] = sh(r[1]), sh(r[2])
            nt, ne = r[5], r[6]
            for i in range(min(nt, maxt)):
                r[7 + 2 * i], r[8 + 2 * i] = sh(r[7 + 2 * i]), sh(r[8 + 2 * i])
            for i in range(min(ne, maxt + 1)):
                o = 7 + 2 * maxt + 2 * i
                r[o], r[o + 1] = sh(r[o]), sh(r[o + 1])
    elif name == 'tv_meas':
        r = exp[0]
        for q in range(4):
            for k in range(4):
                r[9 * q + k] = sh(r[9 * q + k], 1)
    return exp

def expect_pf(name, old):
    exp = [list(r) for r in old]
    if name.startswith('pv_tbd'):
        ever = False
        for r in exp:
            ever = ever or r[13] > 0
            if ever:  # the estimate holds a (last) mean of live particles: shifted
                r[0], r[2] = sh(r[0]), sh(r[2])
            n = r[13]
            r[14], r[15] = sh(r[14], n * S), sh(r[15], n * S)
    return exp

fam, old, new = sys.argv[1], arrays(sys.argv[2]), arrays(sys.argv[3])
assert old.keys() == new.keys(), (old.keys(), new.keys())
bad = 0
shifted = 0
for name in old:
    exp = (expect_tbd if fam == 'tbd' else expect_pf)(name, old[name])
    for k, (e, n, o) in enumerate(zip(exp, new[name], old[name])):
        if e != n:
            bad += 1
            print(f'{name} row {k}: expected {e}\n    got {n}')
        shifted += sum(1 for a, b in zip(o, n) if a != b)
print(f'{fam}: {len(old)} arrays, {shifted} values shifted, {bad} rows differ otherwise')
sys.exit(1 if bad else 0)
