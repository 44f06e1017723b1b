#!/usr/bin/env python3
"""Instructions per source function, inlined code included, from a callgrind profile of a
build with debug information (-g): callgrind charges every instruction to its source line,
also when the function was inlined, so summing lines by the function that encloses them in
the source gives a per-kernel breakdown that function-level profiles cannot (the hot loop is
one function after inlining).

    tbd_components.py CALLGRIND_OUT DIVISOR [--top N] [--groups]

prints, for every source function with cost, instructions / DIVISOR (e.g. particle updates)
and the share of the total; --groups sums them into the steps of a TBD update (the names of
docs/results/tbd.md). Run it on a callgrind.out of a build with -g, e.g. one written by
host_tools/scripts/callgrind.py.
"""
import re
import sys
from collections import defaultdict


def parse(path):
    names = {"fl": {}, "fn": {}}
    cost = defaultdict(int)  # (file, line) -> Ir
    cur_fl = cur_file = None
    last_line = 0
    skip_next = False
    name_re = re.compile(r"^\((\d+)\)(?: (.*))?$")

    def resolve(kind, val):
        m = name_re.match(val)
        if not m:
            return val
        i, n = m.group(1), m.group(2)
        table = names["fl"] if kind in ("fl", "fi", "fe", "cfl", "cfi") else names["fn"]
        if n is not None:
            table[i] = n
        return table.get(i, i)

    with open(path) as f:
        for raw in f:
            line = raw.rstrip("\n")
            if not line or line[0] in "#":
                continue
            if "=" in line and not line[0].isdigit() and line[0] not in "+-*":
                key, _, val = line.partition("=")
                if key in ("fl",):
                    cur_fl = cur_file = resolve("fl", val)
                elif key in ("fi", "fe"):
                    cur_file = resolve(key, val)
                elif key == "fn":
                    resolve("fn", val)
                    cur_file = cur_fl
                elif key in ("cfl", "cfi", "cfn"):
                    resolve(key, val)
                elif key == "calls":
                    skip_next = True
                continue
            parts = line.split()
            if not parts or not (parts[0][0].isdigit() or parts[0][0] in "+-*"):
                continue
            p = parts[0]
            if p == "*":
                ln = last_line
            elif p[0] in "+-":
                ln = last_line + int(p)
            else:
                ln = int(p)
            last_line = ln
            if skip_next:
                skip_next = False
                continue
            if len(parts) > 1 and cur_file is not None:
                cost[(cur_file, ln)] += int(parts[1])
    return cost


FUNC_RE = re.compile(r"^(?:static\s+)?(?:inline\s+)?[A-Za-z_][\w\s\*]*?\b([A-Za-z_]\w*)\s*\(")


def function_spans(path):
    """(start, end, name) of every function definition at file scope (C, brace matching)."""
    try:
        lines = open(path).read().split("\n")
    except OSError:
        return []
    spans = []
    depth = 0
    pending = None
    start = None
    for i, text in enumerate(lines, 1):
        stripped = text.strip()
        if depth == 0:
            m = FUNC_RE.match(text)
            if (m and not stripped.startswith(("#", "/*", "*", "typedef", "return"))
                    and not stripped.endswith(";")):
                pending = (i, m.group(1))
        opens = text.count("{")
        closes = text.count("}")
        if depth == 0 and opens > 0 and pending is not None:
            start = pending
            pending = None
        depth += opens - closes
        if depth == 0 and start is not None and closes > 0:
            spans.append((start[0], i, start[1]))
            start = None
    return spans


GROUPS = [
    ("likelihood (window centre, taps, 3x3 sums)",
     {"pft_kcell_", "pft_tbd_cell_", "pft_ktaps_", "pft_tbd_llr3_", "pft_tbd_llr_", "pft_tbd_clip_",
      "pft_kspot3_", "pft_krow3_", "pft_kspot_end_", "pft_kmulq_", "weigh_", "pft_tbd_llr_exact_",
      "pft_kspot_"}),
    ("random draws (existence, Gaussians)",
     {"pft_rng_next_", "pft_rng_rotl_", "pft_rng_zig_", "pft_zig_fast_", "pft_zig_real_",
      "pft_rng_zig_slow_", "zig_slow_", "pft_zig_exp2_q31_", "pft_zig_f_q31_", "pft_zig_neglog_q24_",
      "pft_zig_tail_q24_", "pft_tbd_exist_draw_", "pft_rng_u32"}),
    ("move: Kalman / CV step, intensity", {"rbpf_move_", "pft_kmad1_", "pft_kmad2_", "pft_ksat_",
                                           "pft_tbd_pf_move_"}),
    ("existence logic, births", {"move_", "pft_tbd_birth_", "pft_rng_below", "pft_rng_uniform",
                                 "pft_rng_uniform_range", "pft_from_u32_frac"}),
    ("weights exp(lw - max)", {"weights_", "pft_kwexp_"}),
    ("estimates, ESS, resampling walk", {"estimate_and_count_", "pft_acc_wx_", "pft_kwnorm_",
                                         "pft_kmulr_", "pft_kspread_", "pft_sys_take_",
                                         "pft_sys_next_", "pft_sys_init_", "pft_kess_",
                                         "est_finish_", "pft_krecip_"}),
    ("resampling copies (in place)", {"replicate_", "copy_particle_"}),
]


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    path, div = sys.argv[1], float(sys.argv[2])
    top = 30
    if "--top" in sys.argv:
        top = int(sys.argv[sys.argv.index("--top") + 1])
    cost = parse(path)
    total = sum(cost.values())
    spans = {}
    per_fn = defaultdict(int)
    for (fname, ln), c in cost.items():
        if fname not in spans:
            spans[fname] = function_spans(fname)
        name = None
        for a, b, n in spans[fname]:
            if a <= ln <= b:
                name = n
                break
        base = fname.split("/")[-1]
        per_fn[(base, name or "?")] += c
    rows = sorted(per_fn.items(), key=lambda kv: -kv[1])
    if "--groups" in sys.argv:
        acc = defaultdict(int)
        for (base, name), c in per_fn.items():
            g = next((label for label, names in GROUPS if name in names), "other (frame, scene, helpers)")
            acc[g] += c
        order = [label for label, _ in GROUPS] + ["other (frame, scene, helpers)"]
        for label in order:
            print("%-46s %8.1f" % (label, acc[label] / div))
        print("%-46s %8.1f" % ("total", total / div))
        return
    print("%-22s %-30s %10s %6s" % ("file", "function (inlined code included)", "Ir/unit", "share"))
    for (base, name), c in rows[:top]:
        print("%-22s %-30s %10.1f %5.1f%%" % (base, name, c / div, 100.0 * c / total))
    print("%-22s %-30s %10.1f" % ("", "total", total / div))


if __name__ == "__main__":
    main()
