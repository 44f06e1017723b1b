#!/usr/bin/env python3
"""Full-frame TBD runs of docs/results/tbd.md ("Full frames"): one `pft eval` per line of a
plan, each on a scenario of host_tools/scenarios/tbd with filter fields overridden, and a
Markdown table of the averaged measures.

  host_tools/scripts/tbd_full_frames.py BUILD OUT PLAN [--runs N] [--threads 2]

BUILD is a host build directory (BUILD/host_tools/pft), OUT the results directory, PLAN one of
the plans below. A line is (label, scenario, {filter overrides}); the overridden scenario is
written to OUT/<label>/scenario.json and evaluated there (the summary records the seeds).
Runs already present (OUT/<label>/summary.json) are not run again.
"""
import argparse
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
SCEN = os.path.join(HERE, "..", "scenarios", "tbd")

PEAKS = {"birth_peaks": 32, "peak_gamma": 1.0}

PLANS = {
    # step 1-2: births from B_k against births from peaks, 20x20 / 64x64 / 256x256, one target
    "sizes": [
        ("b_20", "full_6db_20.json", {}),
        ("b_64", "full_6db_64.json", {}),
        ("b_256", "full_6db_256.json", {}),
        ("peaks_20", "full_6db_20.json", PEAKS),
        ("peaks_64", "full_6db_64.json", PEAKS),
        ("peaks_256", "full_6db_256.json", PEAKS),
    ],
    # the shipped two-target cases, before and after
    "two": [
        ("two1_b", "two_case1.json", {}),
        ("two2_b", "two_case2.json", {}),
        ("two3_b", "two_case3.json", {}),
        ("two1_peaks", "two_case1.json", PEAKS),
        ("two2_peaks", "two_case2.json", PEAKS),
        ("two3_peaks", "two_case3.json", PEAKS),
        ("two1_pkc", "two_case1.json", {**PEAKS, "birth_correction": True}),
        ("two2_pkc", "two_case2.json", {**PEAKS, "birth_correction": True}),
        ("two3_pkc", "two_case3.json", {**PEAKS, "birth_correction": True}),
        ("two1_bc", "two_case1.json", {"birth_correction": True}),
        ("two2_bc", "two_case2.json", {"birth_correction": True}),
        ("two3_bc", "two_case3.json", {"birth_correction": True}),
    ],
    # white noise: false tracks
    "noise": [
        ("noise_b", "noise_20.json", {}),
        ("noise_peaks", "noise_20.json", PEAKS),
    ],
}


def corr_plan():
    """Peaks with the importance correction log(K / A) of the births (birth_correction)."""
    lines = []
    for k in (32, 128, 512):
        for size in (20, 64, 256):
            if size == 20 and k > 128:
                continue
            f = {"birth_peaks": k, "peak_gamma": 1.0, "birth_correction": True}
            lines.append((f"corr_k{k}_{size}", f"full_6db_{size}.json", f))
        lines.append((f"corr_k{k}_noise", "noise_20.json", f))
    return lines


PLANS["corr"] = corr_plan()
PLANS["corr_b"] = [("corr_b_" + s, f"full_6db_{s}.json", {"birth_correction": True})
                   for s in ("20", "64", "256")] + [
                      ("corr_b_noise", "noise_20.json", {"birth_correction": True})]


BERN = {"birth_share": 0.5}
BERN_PK = {"birth_share": 0.5, "birth_peaks": 32, "birth_correction": True}
PLANS["bern"] = [
    ("bs5_20", "full_6db_20.json", BERN),
    ("bs5_64", "full_6db_64.json", BERN),
    ("bs5_256", "full_6db_256.json", BERN),
    ("bs5pk_20", "full_6db_20.json", BERN_PK),
    ("bs5pk_64", "full_6db_64.json", BERN_PK),
    ("bs5pk_256", "full_6db_256.json", BERN_PK),
    ("bs5_noise", "noise_20.json", BERN),
    ("bs5pk_noise", "noise_20.json", BERN_PK),
    ("two1_bs5", "two_case1.json", BERN),
    ("two2_bs5", "two_case2.json", BERN),
    ("two3_bs5", "two_case3.json", BERN),
    ("two1_bs5pk", "two_case1.json", BERN_PK),
    ("two2_bs5pk", "two_case2.json", BERN_PK),
    ("two3_bs5pk", "two_case3.json", BERN_PK),
]

PLANS["eight"] = [
    ("t8_b", "full_8t_256.json", {}),
    ("t8_bs5pk", "full_8t_256.json", BERN_PK),
]


def confirm_plan():
    """Sequential confirmation (confirm_frames m) and theta1: noise and the two-target cases."""
    lines = []
    for m, th in [(1, 0.6), (1, 0.8), (1, 0.9), (2, 0.6), (2, 0.8), (3, 0.6), (3, 0.8), (4, 0.6)]:
        f = {"confirm_frames": m, "theta1": th}
        tag = f"m{m}t{int(th * 10)}"
        lines.append((f"noise_{tag}", "noise_20.json", f))
        for c in (1, 2, 3):
            lines.append((f"two{c}_{tag}", f"two_case{c}.json", f))
    return lines


def bern_confirm_plan():
    """The Bernoulli layer (birth_share 0.5) with theta1 and confirm_frames."""
    lines = []
    for m, th in [(1, 0.7), (1, 0.8), (2, 0.6), (2, 0.8)]:
        f = {**BERN, "confirm_frames": m, "theta1": th}
        tag = f"bs5m{m}t{int(th * 10)}"
        lines.append((f"noise_{tag}", "noise_20.json", f))
        for c in (1, 2, 3):
            lines.append((f"two{c}_{tag}", f"two_case{c}.json", f))
    return lines


PLANS["bern_confirm"] = bern_confirm_plan()


def with_peaks(lines):
    return [(l + "_pk", s, {**PEAKS, **f}) for (l, s, f) in lines]


PLANS["confirm"] = confirm_plan()
PLANS["confirm_peaks"] = with_peaks(confirm_plan())


def run(build, out, label, scen, over, runs, threads):
    d = os.path.join(out, label)
    summ = os.path.join(d, "summary.json")
    if not os.path.exists(summ):
        os.makedirs(d, exist_ok=True)
        s = json.load(open(os.path.join(SCEN, scen)))
        s["filter"].update(over)
        sp = os.path.join(d, "scenario.json")
        json.dump(s, open(sp, "w"), indent=1)
        cmd = [os.path.join(build, "host_tools", "pft"), "eval", "--scenario", sp, "--out", d,
               "--threads", str(threads), "-q"]
        if runs:
            cmd += ["--runs", str(runs)]
        subprocess.run(cmd, check=True)
    return json.load(open(summ))


def fmt(v, nd=2):
    return "-" if v is None else f"{v:.{nd}f}"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("build")
    ap.add_argument("out")
    ap.add_argument("plan", choices=sorted(PLANS) + ["lines"])
    ap.add_argument("--line", nargs=3, action="append", default=[],
                    metavar=("LABEL", "SCENARIO", "JSON"),
                    help="plan 'lines': one run (label, scenario file, filter overrides)")
    ap.add_argument("--runs", type=int, default=0)
    ap.add_argument("--threads", type=int, default=2)
    a = ap.parse_args()
    print("| run | scenario | overrides | runs | frames | appearance | detected | correct of 16 | "
          "false tracks/run | per 1000 frames |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    plan = PLANS.get(a.plan) or [(l, sc, json.loads(o)) for (l, sc, o) in a.line]
    for label, scen, over in plan:
        j = run(a.build, a.out, label, scen, over, a.runs, a.threads)
        av = j["averaged"]
        runs = len(j["per_run"]) if isinstance(j.get("per_run"), list) else a.runs
        frames = json.load(open(os.path.join(SCEN, scen)))["frames"]
        ft = av.get("false_tracks")
        print(f"| {label} | {scen} | {json.dumps(over)} | {runs} | {frames} | "
              f"{fmt(av.get('appearance_delay'))} | {fmt(av.get('detection_rate'))} | "
              f"{fmt(av.get('correct_frames'))} | {fmt(ft, 3)} | "
              f"{fmt(None if ft is None else 1000.0 * ft / frames)} |")
        sys.stdout.flush()


if __name__ == "__main__":
    main()
