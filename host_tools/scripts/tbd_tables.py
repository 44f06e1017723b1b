#!/usr/bin/env python3
"""Markdown tables from the summary.json files written by tbd_figures.sh (stdlib only).
Usage: tbd_tables.py OUT_DIR [OTHER_OUT_DIR]  (a second directory adds a 'vs' column set,
e.g. float against q16)."""
import json
import os
import sys


def load(d):
    res = {}
    for name in sorted(os.listdir(d)):
        p = os.path.join(d, name, "summary.json")
        if os.path.isfile(p):
            with open(p) as f:
                res[name] = json.load(f)
    return res


def f(v, p=2):
    return "-" if v is None else f"{v:.{p}f}"


def single_table(a, num):
    print(f"### Single target ({num})\n")
    print("| SNR dB | filter | N | appear | disappear | correct /16 | RMSE | floor (16-fr) | RMSE/floor | "
          "floor matched | RMSE all | false tracks/run | detected |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    singles = [s for k, s in a.items() if k.startswith("single_")]
    singles.sort(key=lambda s: (s["snr_db"], s["filter"] != "rbpf", s["particles"]))
    for s in singles:
        t = s["targets"][0]
        print(f"| {s['snr_db']:.0f} | {s['filter'].upper()}-TBD | {s['particles']} | {f(t['appearance_delay'])} | "
              f"{f(t['disappearance_delay'])} | {f(t['correct_frames'])} | {f(t['rmse'], 3)} ± {f(t.get('rmse_se'), 3)} | "
              f"{f(t['pcrlb'], 3)} | {f(t['rmse_over_pcrlb'])} | {f(t['pcrlb_matched'], 3)} | {f(t['rmse_all_assigned'], 3)} | "
              f"{f(s['averaged']['false_tracks'])} | {t['detected_runs']}/{s['runs']} |")


def two_target_tables(a, num):
    print(f"\n### Two targets, 6 dB ({num})\n")
    print("| case | preset | target | appear | confirm | disappear | correct /16 | RMSE | floor | RMSE/floor | "
          "floor matched | false tracks/run | detected | censored | paper appear/disapp./correct/RMSE |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for k in sorted(a):
        if not k.startswith("two_"):
            continue
        s = a[k]
        ref = {r["id"]: r for r in s.get("reference", {}).get("targets", [])}
        rows = list(s["targets"]) + [dict(s["averaged"], id="mean")]
        for t in rows:
            r = ref.get(t["id"])
            paper = (f"{r['appearance_delay']} / {r['disappearance_delay']} / {r['correct_frames']} / {r['rmse']}"
                     if r else "")
            ratio = (t["rmse"] / t["pcrlb"]) if t.get("rmse") and t.get("pcrlb") else None
            print(f"| {s['scenario'][-1]} | {s['preset']} | {t['id']} | {f(t['appearance_delay'])} | "
                  f"{f(t.get('confirmation_delay'))} | "
                  f"{f(t['disappearance_delay'])} | {f(t['correct_frames'])} | {f(t['rmse'], 3)}"
                  f"{(' ± ' + f(t['rmse_se'], 3)) if t.get('rmse_se') is not None else ''} | "
                  f"{f(t['pcrlb'], 3)} | {f(ratio)} | {f(t.get('pcrlb_matched'), 3)} | {f(t['false_tracks'])} | "
                  f"{t.get('detected_runs', '')} | {t.get('censored_disappearances', '')} | {paper} |")
    # means over the three cases, per preset (the paper's "mean" row)
    print(f"\n### Two targets, mean over cases 1-3 and both targets ({num})\n")
    print("| preset | appear | disappear | correct /16 | RMSE | floor | false tracks/run |")
    print("|---|---|---|---|---|---|---|")
    for preset in ("paper", "recommended"):
        ss = [s for k, s in a.items() if k.startswith("two_") and s["preset"] == preset]
        if not ss:
            continue
        def mean(key):
            v = [s["averaged"][key] for s in ss if s["averaged"][key] is not None]
            return sum(v) / len(v) if v else None
        print(f"| {preset} | {f(mean('appearance_delay'))} | {f(mean('disappearance_delay'))} | "
              f"{f(mean('correct_frames'))} | {f(mean('rmse'), 3)} | {f(mean('pcrlb'), 3)} | "
              f"{f(mean('false_tracks'))} |")
    print("| paper Table 1 | 2.74 | 1.13 | 12.12 | 0.1772 | (floor 0.386) | - |")


def build_comparison(a, b, num):
    num_b = next(iter(b.values()))["numeric"]
    print(f"\n### {num} against {num_b}, per target (diff % of {num_b}; z = diff / combined "
          "standard error)\n")
    print(f"| configuration | target | appear {num} / {num_b} (z) | disappear (z) | correct (diff %, z) | "
          "RMSE (diff %, z) |")
    print("|---|---|---|---|---|---|")
    worst = {"correct_frames": 0.0, "rmse": 0.0}
    for k in sorted(a):
        if k not in b:
            continue
        for ta, tb in zip(a[k]["targets"], b[k]["targets"]):
            cells = []
            for m in ("appearance_delay", "disappearance_delay", "correct_frames", "rmse"):
                x, y = ta[m], tb[m]
                sx, sy = ta.get(m + "_se"), tb.get(m + "_se")
                z = None
                if None not in (x, y, sx, sy) and (sx * sx + sy * sy) > 0:
                    z = (x - y) / (sx * sx + sy * sy) ** 0.5
                d = None if (x is None or y in (None, 0)) else 100.0 * (x - y) / abs(y)
                if m in worst and d is not None:
                    worst[m] = max(worst[m], abs(d))
                if m in ("correct_frames", "rmse"):
                    p = 3 if m == "rmse" else 2
                    cells.append(f"{f(x, p)} / {f(y, p)} ({f(d, 1)}%, {f(z, 1)})")
                else:
                    cells.append(f"{f(x)} / {f(y)} ({f(z, 1)})")
            print(f"| {k} | {ta['id']} | " + " | ".join(cells) + " |")
    print(f"\nLargest |difference|: correct frames {worst['correct_frames']:.1f}%, "
          f"RMSE {worst['rmse']:.1f}%.")


def main():
    a = load(sys.argv[1])
    if not a:
        sys.exit("no summaries in " + sys.argv[1])
    num = next(iter(a.values()))["numeric"]
    single_table(a, num)
    two_target_tables(a, num)
    if len(sys.argv) > 2:
        build_comparison(a, load(sys.argv[2]), num)


if __name__ == "__main__":
    main()
