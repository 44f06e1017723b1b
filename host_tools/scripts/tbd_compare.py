#!/usr/bin/env python3
"""Side-by-side comparison of two sets of tbd_figures.sh results (stdlib only), e.g. the same
evaluations made with two library versions:

    tbd_compare.py OLD_DIR NEW_DIR

For every evaluation present in both (single_*, two_case*) and every target it prints
appearance delay, disappearance delay, correct frames and RMSE as "old / new (z)", where
z = (new - old) / sqrt(se_old^2 + se_new^2) from the jackknife / run standard errors that each
summary.json records. The runs use the same seeds, but a library whose random draws differ
gives independent Monte Carlo samples, so |z| is roughly standard normal when the two agree:
about 5 % of the comparisons beyond 2, almost none beyond 3. The last line counts them."""
import json
import math
import os
import sys

MEASURES = [("appear", "appearance_delay", 2), ("disappear", "disappearance_delay", 2),
            ("correct /16", "correct_frames", 2), ("RMSE", "rmse", 3)]


def load(d):
    res = {}
    for name in sorted(os.listdir(d)):
        p = os.path.join(d, name, "summary.json")
        if os.path.isfile(p):
            with open(p) as f:
                res[name] = json.load(f)
    return res


def key(name, s):
    if name.startswith("single_"):
        return (0, s["snr_db"], s["filter"] != "rbpf", s["particles"], "")
    return (1, 0, False, 0, name)


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    old, new = load(sys.argv[1]), load(sys.argv[2])
    names = sorted((n for n in old if n in new), key=lambda n: key(n, new[n]))
    zs = []
    print("| evaluation | target | " + " | ".join(m[0] + " old / new (z)" for m in MEASURES) + " |")
    print("|---|---|" + "---|" * len(MEASURES))
    for n in names:
        for to, tn in zip(old[n]["targets"], new[n]["targets"]):
            cells = []
            for _, k, p in MEASURES:
                a, b = to.get(k), tn.get(k)
                sa, sb = to.get(k + "_se"), tn.get(k + "_se")
                if a is None or b is None or not sa or not sb:
                    cells.append("-")
                    continue
                z = (b - a) / math.sqrt(sa * sa + sb * sb)
                zs.append(z)
                cells.append(f"{a:.{p}f} / {b:.{p}f} ({z:+.1f})")
            print(f"| {n} | {tn['id']} | " + " | ".join(cells) + " |")
    if zs:
        a = [abs(z) for z in zs]
        print(f"\n{len(zs)} comparisons: |z| > 2 in {sum(v > 2 for v in a)}, |z| > 3 in "
              f"{sum(v > 3 for v in a)}, largest |z| {max(a):.2f}, mean z {sum(zs) / len(zs):+.2f}")


if __name__ == "__main__":
    main()
