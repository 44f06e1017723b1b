#!/usr/bin/env python3
"""Check (or print) the stage's histogram-bin table in lib/src/pre/pre_update.c.

The table `bin_lut_` of lib/src/pre/pre_update.c (read by `hist_add_`) holds, at index v + 1023 for |v| < 1024, the bin
that `pft_pre_bin_(|v|)` (lib/src/pre/pre_int.h) computes: |v| itself below 16, then 8 bins
per octave, bin 8 (e - 3) + (|v| >> (e - 3)) with e = floor(log2(|v| | 8)).

  python3 host_tools/scripts/pre_bin_table.py --check   # exit 1 if any entry differs
  python3 host_tools/scripts/pre_bin_table.py --print   # the entries, 16 per line
"""
import argparse
import pathlib
import re
import sys

LUT = 1024


def pre_bin(v):
    e3 = (v | 8).bit_length() - 1 - 3
    return (e3 << 3) + (v >> e3)


def expected():
    return [pre_bin(abs(v)) for v in range(-(LUT - 1), LUT)]


def parsed(path):
    text = path.read_text()
    m = re.search(r"bin_lut_\[PFT_PRE_BIN_N_\]\s*=\s*\{([^}]*)\}", text)
    if not m:
        sys.exit(f"pre_bin_table: no bin_lut_ table found in {path}")
    return [int(t) for t in m.group(1).replace("\n", " ").split(",") if t.strip()]


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--print", action="store_true")
    ap.add_argument("--source", default=str(pathlib.Path(__file__).resolve().parents[2]
                                          / "lib" / "src" / "pre" / "pre_update.c"))
    a = ap.parse_args()
    want = expected()
    if a.print:
        for i in range(0, len(want), 16):
            print("        " + ", ".join(str(x) for x in want[i:i + 16]) + ",")
    if a.check:
        got = parsed(pathlib.Path(a.source))
        if len(got) != len(want):
            print(f"pre_bin_table: {len(got)} entries, expected {len(want)}")
            return 1
        bad = [i for i in range(len(want)) if got[i] != want[i]]
        if bad:
            i = bad[0]
            print(f"pre_bin_table: {len(bad)} entries differ, first v = {i - (LUT - 1)}: "
                  f"table {got[i]}, pft_pre_bin_ {want[i]}")
            return 1
        print(f"pre_bin_table: all {len(want)} entries equal pft_pre_bin_(|v|)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
