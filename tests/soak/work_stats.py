#!/usr/bin/env python3
"""Per-frame work of one tracker from the soak (called by tests/soak/run_soak.sh).

work_stats.py COUNTS TRACE BUILD TRACKER WARM
COUNTS: one instruction count per update, in order (from callgrind's per-update dumps or from
the QEMU plugin qemu_marks.c); TRACE: pft_soak --trace output, one "trace <frame> <tracks> [p]"
line per update. The first WARM updates are left out. Prints median, mean, max and max/median,
the same per load (tracks after the update; and by the tracks before it) and, for tbd and pf, a least-squares model
instructions = a + b p + c tracks of the state after the frame before.
"""
import statistics, sys
counts, trace, t, k, warm = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], int(sys.argv[5])
tot = [int(l) for l in open(counts) if l.strip()]
tr = [l.split() for l in open(trace) if l.startswith("trace ")]
if len(tot) != len(tr):
    sys.exit("work_stats: %d counted updates but %d trace lines" % (len(tot), len(tr)))
load = [int(x[2]) for x in tr]
n = min(len(tot), len(load))
pairs = list(zip(load[:n], tot[:n]))[warm:]
vals = [v for _, v in pairs]
med = statistics.median(vals)
by = {}
for l, v in pairs:
    by.setdefault(l, []).append(v)
per = "  ".join("load %d: %d frames, max/median %.2f" % (l, len(v), max(v) / statistics.median(v))
                for l, v in sorted(by.items()))
print("work %-5s %-8s frames %4d  instructions per update: median %.0f  mean %.0f  max %.0f  max/median %.2f  |  %s"
      % (t, k, len(vals), med, statistics.mean(vals), max(vals), max(vals) / med, per))
# the same grouped by the tracks live before the update (the ones it steps)
byb = {}
for i in range(max(warm, 1), n):
    byb.setdefault(load[i - 1], []).append(tot[i])
print("work %-5s %-8s by tracks before the update: %s" % (t, k, "  ".join(
    "%d: %d frames, median %.0f, max %.0f, max/median %.2f"
    % (l, len(v), statistics.median(v), max(v), max(v) / statistics.median(v)) for l, v in sorted(byb.items()))))
if tr and len(tr[0]) > 3:
    # tbd, pf: only particles with E = 1 are moved and weighed on the pixels, and their share at
    # frame i follows the existence probability p after frame i - 1; least squares
    # instructions = a + b p(i-1) + c tracks(i-1), and how far any frame lies above that model
    p = [float(x[3]) for x in tr]
    rows = [(1.0, p[i - 1], float(load[i - 1]), float(tot[i])) for i in range(max(warm, 1), n)]
    m = 3 if len(set(r[2] for r in rows)) > 1 else 2
    A = [[sum(r[a] * r[b] for r in rows) for b in range(m)] for a in range(m)]
    y = [sum(r[a] * r[3] for r in rows) for a in range(m)]
    for c in range(m):  # Gauss-Jordan on the normal equations
        piv = A[c][c]
        A[c] = [v / piv for v in A[c]]; y[c] /= piv
        for r2 in range(m):
            if r2 != c and A[r2][c] != 0.0:
                f_ = A[r2][c]
                A[r2] = [u - f_ * v for u, v in zip(A[r2], A[c])]; y[r2] -= f_ * y[c]
    fit = [sum(y[a] * r[a] for a in range(m)) for r in rows]
    obs = [r[3] for r in rows]
    mean = sum(obs) / len(obs)
    r2 = 1.0 - sum((o - f_) ** 2 for o, f_ in zip(obs, fit)) / sum((o - mean) ** 2 for o in obs)
    worst = max(o / f_ for o, f_ in zip(obs, fit))
    print("work %-5s %-8s model a + b p + c tracks: a %.0f  b %.0f%s  R^2 %.3f  max observed/model %.2f"
          "  (p = 1, no track: %.0f = %.2f x median)"
          % (t, k, y[0], y[1], ("  c %.0f" % y[2]) if m == 3 else "", r2, worst, y[0] + y[1], (y[0] + y[1]) / med))
