#!/usr/bin/env python3
"""The stage's per-step registration error on `pft sim` sequences (docs/results/ir_clutter.md,
"Branch irreg"). Not a test.

  ir_reg_steps.py runs   SCEN.json OUT [--seeds 1-29] [--backgrounds DIR] [--pft PATH]
  ir_reg_steps.py table  OUT [OUT ...]
  ir_reg_steps.py pair   OUT_A OUT_B

`runs` makes, per seed N, `pft sim --scenario SCEN.json --seed N` and
`pft run --stage-out OUT/sN/stage.csv` of it, keeps stage.csv and the sim's platform.csv in
OUT/sN and deletes the frames. `table` prints, per folder, the error of step k (k = 2..F)
e_k = shift_k + (p_k - p_{k-1}) (the stage's shift is the scene's move, z(p) = b(p - shift);
platform.csv's p_k is where frame k's pixel (0, 0) sees the scene): rms per axis, largest |e|,
mean per axis, pooled over the seeds; and the same against the path as the default warp
("opencv": cv::warpAffine INTER_CUBIC) renders it: p_k rounded to 1/32 px as warpAffine does
(to 1/1024, + 1/64, floor to 1/32), plus the kernel's shift of a linear scene at the fraction t,
g(t) = -2 (a + 1/2) t (1 - t)(1 - 2t) with a = -0.75 (a low-frequency model; meaningless for
sequences made with platform.warp "bspline" or "catmull_rom"). `pair` prints the mean over
the common seeds of the per-seed rms difference B - A per axis and its standard error.
Needs numpy.
"""
import csv
import os
import subprocess
import sys

import numpy as np

A_OPENCV = -0.75


def g(t, a=A_OPENCV):
    return -2.0 * (a + 0.5) * t * (1.0 - t) * (1.0 - 2.0 * t)


def rounded(p):
    q = np.round(p * 1024.0).astype(np.int64) + 16
    return np.floor_divide(q, 32) / 32.0


def load(d):
    st = list(csv.DictReader(open(os.path.join(d, 'stage.csv'))))
    pl = list(csv.DictReader(open(os.path.join(d, 'platform.csv'))))
    s = np.array([[float(r['shift_x_px']), float(r['shift_y_px'])] for r in st])
    p = np.array([[float(r['x']), float(r['y'])] for r in pl])
    return s, p[:len(s)]


def seeds_of(out):
    return sorted(int(x[1:]) for x in os.listdir(out)
                  if x.startswith('s') and x[1:].isdigit() and os.path.exists(os.path.join(out, x, 'stage.csv')))


def errors(out, n, model=False):
    s, p = load(os.path.join(out, 's%d' % n))
    if model:
        # mirroring (an integer offset) leaves the fraction unchanged
        q = rounded(p)
        p = q + g(q - np.floor(q))
    return s[1:] + (p[1:] - p[:-1])


def parse_seeds(text):
    out = []
    for part in text.split(','):
        a, _, b = part.partition('-')
        out += list(range(int(a), int(b or a) + 1))
    return out


def cmd_runs(args):
    scen, out = args[0], args[1]
    seeds, bg, pft = list(range(1, 30)), None, 'build/host-float/host_tools/pft'
    i = 2
    while i < len(args):
        if args[i] == '--seeds':
            seeds = parse_seeds(args[i + 1])
        elif args[i] == '--backgrounds':
            bg = args[i + 1]
        elif args[i] == '--pft':
            pft = args[i + 1]
        else:
            sys.exit('unknown option ' + args[i])
        i += 2
    for n in seeds:
        d = os.path.join(out, 's%d' % n)
        if os.path.exists(os.path.join(d, 'stage.csv')):
            continue
        os.makedirs(d, exist_ok=True)
        seq = os.path.join(d, 'seq')
        sim = [pft, 'sim', '--scenario', scen, '--seed', str(n), '--out', seq, '-q']
        if bg:
            sim += ['--backgrounds', bg]
        subprocess.run(sim, check=True)
        subprocess.run([pft, 'run', '--sequence', seq, '--scenario', scen, '--no-video', '-q',
                        '--stage-out', os.path.join(d, 'stage.tmp'), '--out', os.path.join(d, 'run')],
                       check=True)
        os.replace(os.path.join(d, 'stage.tmp'), os.path.join(d, 'stage.csv'))
        os.replace(os.path.join(seq, 'platform.csv'), os.path.join(d, 'platform.csv'))
        subprocess.run(['rm', '-rf', seq], check=True)


def cmd_table(outs):
    print('| run | seeds | steps | rms x / y (px) | largest (px) | mean x / y (px) | '
          'against the opencv-rendered path: rms x / y |')
    print('|---|---|---|---|---|---|---|')
    for out in outs:
        seeds = seeds_of(out)
        e = np.concatenate([errors(out, n) for n in seeds])
        m = np.concatenate([errors(out, n, True) for n in seeds])
        r, rm = np.sqrt((e ** 2).mean(axis=0)), np.sqrt((m ** 2).mean(axis=0))
        print('| %s | %d | %d | %.4f / %.4f | %.3f | %+.4f / %+.4f | %.4f / %.4f |'
              % (out, len(seeds), len(e), r[0], r[1], np.abs(e).max(), e[:, 0].mean(), e[:, 1].mean(),
                 rm[0], rm[1]))


def cmd_pair(a, b):
    common = sorted(set(seeds_of(a)) & set(seeds_of(b)))
    ra = np.array([np.sqrt((errors(a, n) ** 2).mean(axis=0)) for n in common])
    rb = np.array([np.sqrt((errors(b, n) ** 2).mean(axis=0)) for n in common])
    d = rb - ra
    se = d.std(axis=0, ddof=1) / np.sqrt(len(common))
    print('%s -> %s: %d seeds; per-seed rms x %.4f -> %.4f, difference %+.4f +- %.4f; '
          'y %.4f -> %.4f, difference %+.4f +- %.4f'
          % (a, b, len(common), ra[:, 0].mean(), rb[:, 0].mean(), d[:, 0].mean(), se[0],
             ra[:, 1].mean(), rb[:, 1].mean(), d[:, 1].mean(), se[1]))


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    c = sys.argv[1]
    if c == 'runs':
        cmd_runs(sys.argv[2:])
    elif c == 'table':
        cmd_table(sys.argv[2:])
    elif c == 'pair' and len(sys.argv) == 4:
        cmd_pair(sys.argv[2], sys.argv[3])
    else:
        sys.exit(__doc__)


if __name__ == '__main__':
    main()
