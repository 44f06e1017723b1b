#!/usr/bin/env python3
"""Sequence-by-sequence difference between two `pft eval` summaries of the bearings kind
(e.g. the float and the q16 build, or q16 at scale 1000 and at scale 1), from their
"estimates_at_table_particles": the same seeds give the same measurements and the same
integer random stream, so a difference is arithmetic (SIS) or arithmetic that flipped a
resampling decision (SIR, APF).

Usage: compare_builds.py A/summary.json B/summary.json [--md]
Prints per filter: runs compared, median and 90th percentile over runs of the RMS distance
between the two estimates (benchmark units, over all steps), the fraction of runs closer
than 1e-3, and both builds' RMSE to the truth."""
import json
import math
import sys


def main():
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    md = "--md" in sys.argv
    if len(args) != 2:
        sys.exit(__doc__)
    a, b = (json.load(open(p)) for p in args)
    if a["seeds"] != b["seeds"]:
        sys.exit("the summaries use different seeds")
    ea, eb = a["estimates_at_table_particles"], b["estimates_at_table_particles"]
    rm = {f["label"] + "@" + str(f["particles"]): f["rmse"] for f in a["filters"]}
    rb = {f["label"] + "@" + str(f["particles"]): f["rmse"] for f in b["filters"]}
    n = a["table_particles"]
    if md:
        print("| filter | N | runs | median RMS distance | 90th pct | runs < 1e-3 | RMSE A | RMSE B |")
        print("|---|---|---|---|---|---|---|---|")
    for lab in ea:
        if lab not in eb:
            continue
        d = []
        for ra, rb_ in zip(ea[lab], eb[lab]):
            s = sum((x1 - x2) ** 2 + (y1 - y2) ** 2 for (x1, y1), (x2, y2) in zip(ra, rb_))
            d.append(math.sqrt(s / len(ra)))
        d.sort()
        med = d[len(d) // 2] if len(d) % 2 else 0.5 * (d[len(d) // 2 - 1] + d[len(d) // 2])
        p90 = d[min(len(d) - 1, int(math.ceil(0.9 * len(d))) - 1)]
        close = sum(1 for v in d if v < 1e-3) / len(d)
        key = lab + "@" + str(n)
        if md:
            print(f"| {lab} | {n} | {len(d)} | {med:.2e} | {p90:.2e} | {close:.2f} | {rm[key]:.4f} | {rb[key]:.4f} |")
        else:
            print(f"{lab:8s} N={n} runs={len(d)} median {med:.3e} p90 {p90:.3e} "
                  f"close {close:.2f} rmse {rm[key]:.4f} / {rb[key]:.4f}")


if __name__ == "__main__":
    main()
