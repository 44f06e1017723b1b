#!/usr/bin/env python3
"""Markdown tables of docs/results/pf.md from the outputs of host_tools/scripts/pf_results.sh.

Usage: pf_tables.py RESULTS_DIR
RESULTS_DIR holds gordon_bearings_{float,q16}/, gordon_bearings_scale1_{float,q16}/ (eval
summaries), bench_bearings_{float,q16}/bench.json, pf_tbd_{2,5}db_{float,q16}/ (eval
summaries) and optionally callgrind/table.md."""
import json
import math
import os
import sys


def load(d, *p):
    f = os.path.join(d, *p)
    return json.load(open(f)) if os.path.exists(f) else None


def f4(v, p=4):
    return "-" if v is None or (isinstance(v, float) and not math.isfinite(v)) else f"{v:.{p}f}"


def by(summary, label, n):
    for f in summary["filters"]:
        if f["label"] == label and f["particles"] == n:
            return f
    return None


def table1(s, build):
    n = s["table_particles"]
    labs = [e["label"] for e in s["engines"]]
    print(f"\n**{build}**, N = {n}, {s['runs']} runs (seeds {s['seeds'][0]}..{s['seeds'][-1]}); "
          "each cell RMSE x / RMSE y\n")
    print("| k | " + " | ".join(labs) + " |")
    print("|---|" + "---|" * len(labs))
    rows = [by(s, l, n) for l in labs]
    for k in range(s["steps"]):
        cells = [f"{r['rmse_x_per_step'][k]:.4f} / {r['rmse_y_per_step'][k]:.4f}" for r in rows]
        print(f"| {k + 1} | " + " | ".join(cells) + " |")
    cells = [f"**{r['rmse_x']:.4f} / {r['rmse_y']:.4f}**" for r in rows]
    print("| all | " + " | ".join(cells) + " |")


def table3(sums):
    builds = list(sums)
    s0 = sums[builds[0]]
    labs = [e["label"] for e in s0["engines"]]
    print("\nRMSE (radial, all steps) +- standard error over runs; in brackets the RMS distance to "
          "the 100k-particle reference filter's mean\n")
    print("| N | " + " | ".join(f"{l} {b}" for b in builds for l in labs) + " |")
    print("|---|" + "---|" * (len(labs) * len(builds)))
    for n in s0["particle_counts"]:
        cells = []
        for b in builds:
            for l in labs:
                r = by(sums[b], l, n)
                cells.append(f"{r['rmse']:.4f} +- {r['rmse_se']:.4f} ({f4(r['rmse_to_reference'], 3)})")
        print(f"| {n} | " + " | ".join(cells) + " |")
    cells = []
    for b in builds:
        ref = sums[b].get("reference_filter") or {}
        cells.append(f"{ref.get('label', '-')}: {f4(ref.get('rmse'))}")
    print("\nReference filter RMSE to the truth (the floor): " + "; ".join(
        f"{b} {c}" for b, c in zip(builds, cells)))


def bearing_off(sums):
    builds = list(sums)
    s0 = sums[builds[0]]
    labs = [e["label"] for e in s0["engines"]]
    ks = [1, 6, 12, 18, 24]
    print("\nRuns (of " + str(s0["runs"]) + ") whose estimate's bearing atan2(y^, x^) is more than 5 sqrt(r) "
          "off the true bearing, at steps " + ", ".join(map(str, ks)) + " (a filter whose particle cloud "
          "no longer covers the measured bearing)\n")
    print("| N | " + " | ".join(f"{l} {b}" for b in builds for l in labs) + " |")
    print("|---|" + "---|" * (len(labs) * len(builds)))
    for n in s0["particle_counts"]:
        cells = []
        for b in builds:
            for l in labs:
                r = by(sums[b], l, n)
                cells.append(" ".join(str(int(r["bearing_off_runs_per_step"][k - 1])) for k in ks))
        print(f"| {n} | " + " | ".join(cells) + " |")


def paired(sums):
    builds = list(sums)
    s0 = sums[builds[0]]
    pairs = []
    for p in s0["paired"]:
        key = (p["a"], p["b"])
        if key not in pairs:
            pairs.append(key)
    print("\nFraction of runs in which A's per-run RMS error is below B's (same sequences; binomial "
          "standard error about 0.05 at 100 runs)\n")
    print("| N | " + " | ".join(f"{a} < {b} ({bd})" for bd in builds for a, b in pairs) + " |")
    print("|---|" + "---|" * (len(pairs) * len(builds)))
    for n in s0["particle_counts"]:
        cells = []
        for bd in builds:
            m = {(p["a"], p["b"]): p["fraction"] for p in sums[bd]["paired"] if p["particles"] == n}
            cells += [f"{m[k]:.2f}" for k in pairs]
        print(f"| {n} | " + " | ".join(cells) + " |")


def table2(benches, sums):
    builds = list(benches)
    labs = []
    for e in benches[builds[0]]["entries"]:
        if e["label"] not in labs:
            labs.append(e["label"])
    ns = sorted({e["particles"] for e in benches[builds[0]]["entries"]})
    runs = benches[builds[0]]["runs"]
    print(f"\nFastest of {runs} timed runs (24 steps each) of `pft bench`, one thread: us per step, in "
          "brackets ns per particle-step (the minimum is the statistic least disturbed by other load "
          "on a shared machine)\n")
    print("| N | " + " | ".join(f"{l} {b}" for b in builds for l in labs) + " |")
    print("|---|" + "---|" * (len(labs) * len(builds)))
    for n in ns:
        cells = []
        for b in builds:
            for l in labs:
                e = next(x for x in benches[b]["entries"] if x["label"] == l and x["particles"] == n)
                cells.append(f"{e['ns_per_step_min'] / 1000:.1f} ({e['ns_per_particle_step_min']:.0f})")
        print(f"| {n} | " + " | ".join(cells) + " |")


def tbd(sums):
    print("\n| SNR | build | filter | N | appearance delay (frames) | detected runs | correct frames (of 16) "
          "| RMSE (px) | PCRLB matched | false tracks/run | us/frame | correct frames - APF-TBD 6000 | delay - APF-TBD 6000 |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for (snr, b), s in sums.items():
        for f in s["filters"]:
            d1 = "-" if f["correct_frames_minus_first"] is None else \
                f"{f['correct_frames_minus_first']:+.2f} +- {f['correct_frames_minus_first_se']:.2f}"
            d2 = "-" if f["appearance_delay_minus_first"] is None else \
                f"{f['appearance_delay_minus_first']:+.2f} +- {f['appearance_delay_minus_first_se']:.2f}"
            print(f"| {snr} dB | {b} | {f['label']} | {f['particles']} | "
                  f"{f4(f['appearance_delay'], 2)} +- {f4(f['appearance_delay_se'], 2)} | {f['detected_runs']} | "
                  f"{f4(f['correct_frames'], 2)} +- {f4(f['correct_frames_se'], 2)} | {f4(f['rmse'], 3)} | "
                  f"{f4(f['pcrlb_matched'], 3)} | {f4(f['false_tracks'], 2)} | {f['ns_per_step'] / 1000:.0f} | {d1} | {d2} |")
    print("\nEqual-compute calibration (median time per frame, the two filters alternating):\n")
    for (snr, b), s in sums.items():
        for lab, c in s["calibration"].items():
            print(f"- {snr} dB {b}: {lab} matches {c['match_time_of']}: "
                  f"{c['reference_ns_per_frame'] / 1000:.0f} vs {c['ns_per_frame_at_reference_n'] / 1000:.0f} us/frame "
                  f"at N = {c['reference_particles']} -> N = {c['particles']}")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    d = sys.argv[1]
    sums = {b: load(d, f"gordon_bearings_{b}", "summary.json") for b in ("float", "q16")}
    sums = {b: s for b, s in sums.items() if s}
    print("## Table 1: RMSE per step")
    for b, s in sums.items():
        table1(s, b)
    print("\n## Table 3: RMSE against N")
    table3(sums)
    bearing_off(sums)
    paired(sums)
    benches = {b: load(d, f"bench_bearings_{b}", "bench.json") for b in ("float", "q16")}
    benches = {b: s for b, s in benches.items() if s}
    if benches:
        print("\n## Table 2: time")
        table2(benches, sums)
    cg = os.path.join(d, "callgrind", "table.md")
    if os.path.exists(cg):
        print("\nCallgrind instructions (pft_pf_update only):\n")
        print(open(cg).read())
    t = {}
    for snr in (2, 5):
        for b in ("float", "q16"):
            s = load(d, f"pf_tbd_{snr}db_{b}", "summary.json")
            if s:
                t[(snr, b)] = s
    if t:
        print("\n## APF-TBD")
        tbd(t)


if __name__ == "__main__":
    main()
