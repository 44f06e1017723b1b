#!/usr/bin/env python3
"""The three tables of PTE-TBD's q16 exp for -12 < x <= 0 (exp_neg_ in lib/src/pte/pte_track.c)
and an exhaustive check of the kernel they feed (docs/fixed_point.md, "PTE-TBD Kalman algebra
and square root").

u = -x in Q16.16 (0 <= u < 12 * 2^16 < 2^20) splits into u = 2^13 a + 2^6 b + c and
exp(-u / 2^16) = exp(-a / 8) exp(-b / 1024) exp(-c / 65536); each entry is round(2^31 exp(...)).

Usage: pte_exp_tables.py          print the C arrays
       pte_exp_tables.py --check  every u of the domain: the kernel's result against exp (its
                                  largest error in LSB) and against pft_exp's Horner kernel
                                  (pft_q16_exp_core_ of lib/src/core/q16_int.h, the same
                                  integer steps), printing every argument where they differ
"""
import math
import re
import sys

SIZES = (('hi', 96, 2.0 ** 13 / 2.0 ** 16), ('mid', 128, 2.0 ** 6 / 2.0 ** 16), ('lo', 64, 2.0 ** -16))
DOMAIN = 12 * 65536  # u in [0, DOMAIN)


def tables():
    return {name: [round(math.exp(-i * step) * 2 ** 31) for i in range(n)] for name, n, step in SIZES}


def kernel(t, u):
    """exp_neg_(-u) of pte_track.c, the same integer steps."""
    v = t['hi'][u >> 13] * t['mid'][(u >> 6) & 127]  # Q62
    v = (v + (1 << 29)) >> 30  # Q32
    v = v * t['lo'][u & 63]  # Q63
    return (v + (1 << 46)) >> 47


LN2_Q48 = 195103586505167
INV_LN2_Q30 = 1549082005
C = (4294967296, 4294967296, 2147483648, 715827883, 178956971, 35791394, 5965232, 852176,
     106522, 11836, 1184, 108)


def pft_exp_core(x):
    """pft_q16_exp_core_ of lib/src/core/q16_int.h for x <= 0 (Python's >> floors as C's
    arithmetic shift does)."""
    xq = x * (1 << 32)
    k = ((x * INV_LN2_Q30) >> 46) + 1
    r = k * LN2_Q48 - xq
    for _ in range(2):
        if r < 0:
            r += LN2_Q48
            k += 1
        elif r >= LN2_Q48:
            r -= LN2_Q48
            k -= 1
    r32 = (r + 32768) >> 16
    p = C[11]
    for i in range(10, -1, -1):
        p = C[i] - ((p * r32 + 0x80000000) >> 32)
    s = 16 - k
    return (p + (1 << (s - 1))) >> s


def main():
    t = tables()
    if '--check' not in sys.argv[1:] and '--verify' not in sys.argv[1:]:
        for name, vals in t.items():
            print(f'static const uint32_t exp_{name}_[{len(vals)}] = {{')
            for i in range(0, len(vals), 6):
                print('    ' + ', '.join(f'{v}u' for v in vals[i:i + 6]) + ',')
            print('};')
        return
    if '--verify' in sys.argv[1:]:
        src = open(sys.argv[sys.argv.index('--verify') + 1]).read()
        for name, vals in t.items():
            m = re.search(r'exp_%s_\[(\d+)\] = \{([^}]*)\}' % name, src)
            got = [int(v.strip().rstrip('u')) for v in m.group(2).split(',') if v.strip()] if m else None
            if got != vals:
                sys.exit(f'exp_{name}_ in the source is not the generated table')
    worst = 0.0
    diff = 0
    wdiff = 0
    for u in range(DOMAIN):
        e = math.exp(-u / 65536.0) * 65536.0
        k = kernel(t, u)
        worst = max(worst, abs(k - e))
        h = pft_exp_core(-u)
        if h != k:
            diff += 1
            wdiff = max(wdiff, abs(h - k))
            print(f'u = {u}: table {k}, pft_exp {h}, exp {e:.7f} ({abs(e - math.floor(e) - 0.5):.1e} LSB from a tie)')
    print(f'{DOMAIN} arguments: largest error of the table kernel {worst:.6f} LSB; '
          f'{diff} differ from pft_exp')
    if '--verify' in sys.argv[1:] and (worst > 0.50003 or diff > 6 or wdiff > 1):
        sys.exit('the table kernel is outside its documented bounds')


if __name__ == '__main__':
    main()
