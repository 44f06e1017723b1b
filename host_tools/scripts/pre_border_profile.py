#!/usr/bin/env python3
"""Column profile of the whitened residual written by tests/tools/pre_probe (out=RES.i16):
per column band, the mean, the mean square and the fractions of |r| > 3 and r > 3 of the unmasked
residual (sigma units), frames after --skip, rows more than --margin from the top and bottom.
Standard library only. docs/results/ir_clutter.md, "Border false tracks". Not a test.

  python3 host_tools/scripts/pre_border_profile.py RES.i16 W H [--skip 20] [--margin 8]
      [--mirror]    (write the input u16 frames mirrored left-right to OUT and stop:
                     pre_border_profile.py IN.u16 W H --mirror OUT.u16)
"""
import argparse
import array

MASKED = -32768


def bands(w):
    """Column bands: finer at both borders."""
    edges = [0, 2, 4, 8, 16, 32, 64, w // 2, w - 64, w - 32, w - 16, w - 8, w - 4, w - 2, w]
    return [(a, b) for a, b in zip(edges, edges[1:]) if b > a]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("file")
    ap.add_argument("w", type=int)
    ap.add_argument("h", type=int)
    ap.add_argument("--skip", type=int, default=20)
    ap.add_argument("--margin", type=int, default=8)
    ap.add_argument("--mirror")
    a = ap.parse_args()
    w, h, npix = a.w, a.h, a.w * a.h
    if a.mirror:
        src = array.array("H")
        with open(a.file, "rb") as f:
            src.frombytes(f.read())
        out = array.array("H")
        for r in range(len(src) // w):
            row = src[r * w:(r + 1) * w]
            row.reverse()
            out.extend(row)
        with open(a.mirror, "wb") as f:
            f.write(out.tobytes())
        return
    s1, s2, nx, ex, ep = [0.0] * w, [0.0] * w, [0] * w, [0] * w, [0] * w
    k = 0
    with open(a.file, "rb") as f:
        while True:
            b = f.read(2 * npix)
            if len(b) < 2 * npix:
                break
            k += 1
            if k <= a.skip:
                continue
            r = array.array("h")
            r.frombytes(b)
            for y in range(a.margin, h - a.margin):
                row = r[y * w:(y + 1) * w]
                for x in range(w):
                    q = row[x]
                    if q == MASKED:
                        continue
                    e = q / 256.0
                    s1[x] += e
                    s2[x] += e * e
                    nx[x] += 1
                    ex[x] += abs(e) > 3.0
                    ep[x] += e > 3.0
    print("frames %d (first %d left out), rows %d..%d" % (k, a.skip, a.margin, h - 1 - a.margin))
    print("columns     mean   mean_sq  P(|r|>3)  P(r>3)  unmasked")
    for lo, hi in bands(w):
        n = sum(nx[lo:hi])
        tot = (hi - lo) * (h - 2 * a.margin) * max(k - a.skip, 0)
        if n == 0:
            print("%3d-%3d       -        -         -       -     0/%d" % (lo, hi - 1, tot))
            continue
        print("%3d-%3d  %+6.3f  %7.3f  %8.4f  %6.4f  %d/%d" % (lo, hi - 1, sum(s1[lo:hi]) / n,
              sum(s2[lo:hi]) / n, sum(ex[lo:hi]) / n, sum(ep[lo:hi]) / n, n, tot))


if __name__ == "__main__":
    main()
