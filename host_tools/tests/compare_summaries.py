#!/usr/bin/env python3
"""Compares two eval summaries field by field (ctest host_*_shard_merge): every field must be
equal, numbers bit for bit (JSON numbers from pft round-trip exactly), except the fields that
record the invocation and the clock: command_line, threads, timing, shards (top level) and
the measured times anywhere: ns_per_step (pf), us_per_frame (pte, tsa) and cpu_us_per_frame (tsa).
Usage: compare_summaries.py A.json B.json   (exit 0 and "identical" when equal)"""
import json
import sys

SKIP_TOP = {'command_line', 'threads', 'timing', 'shards'}
SKIP_ANY = {'ns_per_step', 'us_per_frame', 'cpu_us_per_frame'}


def strip(j, top=True):
    if isinstance(j, dict):
        return {k: strip(v, False) for k, v in j.items()
                if k not in SKIP_ANY and not (top and k in SKIP_TOP)}
    if isinstance(j, list):
        return [strip(v, False) for v in j]
    return j


def first_diff(a, b, path=''):
    if type(a) is not type(b):
        return path or '/'
    if isinstance(a, dict):
        for k in sorted(set(a) | set(b)):
            if k not in a or k not in b:
                return f'{path}/{k}'
            d = first_diff(a[k], b[k], f'{path}/{k}')
            if d:
                return d
        return None
    if isinstance(a, list):
        if len(a) != len(b):
            return f'{path} (length {len(a)} vs {len(b)})'
        for i, (x, y) in enumerate(zip(a, b)):
            d = first_diff(x, y, f'{path}/{i}')
            if d:
                return d
        return None
    return None if a == b else f'{path}: {a!r} vs {b!r}'


def main():
    a = strip(json.load(open(sys.argv[1])))
    b = strip(json.load(open(sys.argv[2])))
    d = first_diff(a, b)
    if d:
        print(f'DIFFERENT at {d}')
        return 1
    n = len(json.dumps(a))
    print(f'identical ({n} characters of JSON compared; skipped {sorted(SKIP_TOP | SKIP_ANY)})')
    return 0


if __name__ == '__main__':
    sys.exit(main())
