#!/usr/bin/env python3
"""A clairvoyant detection bound on the IR pipeline's residual (docs/results/ir_clutter.md,
"Branch irbound"): could any tracker that sees only the stage's residual confirm the injected
targets at a given false-detection rate?

Inputs, per seed, made by the project's tools (kind tbd_ir, e.g. the 9 dB sweep point with the
best setting + integ_alpha 0.7):
  pft sim --scenario S --seed N --backgrounds IR_SKY --format raw --out SIM/<db>_s<N>
  pft run --sequence SIM/<db>_s<N> --scenario S --no-video --out RUN/<db>_s<N> \\
          --residual-out RUN/<db>_s<N>/res.i16
(the residual the TBD manager sees, int16 Q8.8 in units of the stage's tile sigma; truth.csv
and sequence.json from the sim folder; the frames themselves are not read). targets and clutter take
another residual of the same layout with --res NAME (NAME.f32: float32 in tile-sigma units, e.g. a
prototype of host_tools/scripts/ir_bg_proto.py, "Branch irbg"); each residual needs its own --cache.

  ir_bound.py inputs   --pft build/host-float/host_tools/pft --scenario S --backgrounds IR_SKY \\
                       --sim SIM --run RUN --db 09 --seeds 1-29      (the two commands above per seed,
                       `nice`; the raw frames are deleted once the residual is written)
  ir_bound.py targets  --sim SIM --run RUN --db 09 --seeds 1-29 --cache C
  ir_bound.py clutter  --sim SIM --run RUN --db 09 --seeds 1-29 --cache C [--every 5] [--dv 0.05]
  ir_bound.py report   --cache C --dbs 06 09 12 [--tbd DB=SUMMARY.json ...] [--trace-list FILE]
                       [--fig PNG] [--max-seed 29] [--curves-out CURVES.json]
  ir_bound.py objects  --cache C --k 12 --above 11 [--tag T]   (the distinct clutter objects above a threshold:
                       seed, position in the frame and the scene, speed against the scene; "Branch irbound2")
  ir_bound.py roc      LABEL=CURVES.json ... --db 09 --ks 12 20 --fig PNG   (curves of several reports in one figure)

--post NAME[:k=v,...][+NAME...] (targets, clutter, report; "Branch irdir"): each residual frame goes through
these filters, left to right, before the matched filter, in targets, clutter and its --white reference;
the cache files carry the suffix _post-<spec> so the unfiltered files and outputs stay as they are, and
report --post reads that filter's files. dir:d=2 (for 4 orientations r less the mean of the pixels at
+-d along it, the smallest of the four), mean:n=15,g=5 (the mean of the n x n square less its g x g core
subtracted), median:n=9,g=3 (the same with the median; slow), rms:n=15,g=5[,robust=abs|mad|rms][,floor=0.25][,valid=1]
(each pixel in the local rms of the n x n square less its g x g core).

The statistic. MF_t = the residual of frame t correlated with the 7 x 7 point-sampled PSF
(Gaussian, sigma 0.7 px, the sim's) normalised to unit energy (unit variance under white unit
noise). Along a path p_t, S_K(t) = sum_{j<K} MF_{t-j}(p_{t-j}) / sd_K, with sd_K the robust
(1.4826 MAD) sd of the same K-frame sum along straight paths at target-free positions (the
clutter search's own sums, pooled over seeds): unit variance under the residual's noise,
clutter left in the tail.
  targets: per injected target and frame: the residual at its nearest pixel (tile sigmas), the
    matched value there, the sub-pixel matched value (kernel centred on the true position), the
    local z of "Branch irmiss" (matched value less the median, over the robust sd, of the 31 x 31
    square without its 7 x 7 core), and the K-frame sums (K = 3, 5, 8, 12) along the TRUE path
    (nearest pixel of the true position in each frame) for every window inside its life.
  clutter: the motion-matched search over the whole frame: every end pixel, every straight path
    of integer offsets round(v j) (j = 1..K-1) for v on a grid of step --dv px/frame over the
    sim's speeds (0.3-1.2 px/frame, any direction), evaluated as a tree of shared prefixes so
    one pass gives K = 3, 5, 8, 12; the matched frames are zeroed within --excl px of every
    truth point (injected and labelled) of their frame; windows end at every --every-th frame
    whose K frames all carry a residual. Per window and K: the largest sum over all pixels and
    paths, the same over the paths whose velocity is more than --scene-gate px/frame from the
    scene's (the platform's drift reversed), and sums' robust sd for sd_K.
  report: thresholds T(r) on the per-frame maximum for r false detections per frame (the tail
    above the 90th percentile fitted with a generalised Pareto law beyond the data), the
    clairvoyant detection (a target counts when S_K > T in at least one window of its life),
    per K, SNR and kind of background, beside TBD's measured detection from pft eval summaries,
    and the ROC figure.
Needs numpy, scipy (and matplotlib for --fig). Not a test.
"""
import argparse
import collections
import csv
import glob
import json
import math
import os
import re
import sys

import numpy as np
from scipy import ndimage

from ir_real_kinds import DEFAULT_KINDS, KINDS, read_kinds  # the kinds of the ir_sky images

HERE = os.path.dirname(os.path.abspath(__file__))
KS = (3, 5, 8, 12, 20, 30)


def seeds_arg(s):
    a, _, b = s.partition('-')
    return list(range(int(a), int(b or a) + 1))


def psf(dx=0.0, dy=0.0, sigma=0.7, half=3):
    ax = np.arange(-half, half + 1)
    xx, yy = np.meshgrid(ax - dx, ax - dy)
    k = np.exp(-(xx ** 2 + yy ** 2) / (2 * sigma ** 2))
    return k / np.sqrt((k ** 2).sum())


def load(sim, run, db, seed, res_name='res.i16'):
    """The sim's truth and platform path, and the residual RUN/<db>_s<seed>/<res_name>: int16 Q8.8
    (pft run --residual-out) or, for a name ending in .f32, float32 in the same units and layout
    (a prototype's residual, e.g. host_tools/scripts/ir_bg_proto.py)."""
    sd = os.path.join(sim, f'{db}_s{seed}')
    q = json.load(open(os.path.join(sd, 'sequence.json')))
    w, h, f = q['width'], q['height'], q['frames']
    path = os.path.join(run, f'{db}_s{seed}', res_name)
    if res_name.endswith('.f32'):
        res = np.fromfile(path, '<f4').reshape(f, h, w).astype(np.float32)
    else:
        res = np.fromfile(path, '<i2').reshape(f, h, w).astype(np.float32) / 256.0
    truth = collections.defaultdict(list)
    for r in csv.DictReader(open(os.path.join(sd, 'truth.csv'))):
        truth[int(r['frame'])].append((int(r['id']), float(r['x']), float(r['y']), r['kind']))
    plat = [(float(r['x']), float(r['y'])) for r in csv.DictReader(open(os.path.join(sd, 'platform.csv')))]
    return q, res, truth, plat


def matched(res):
    k = psf()
    return np.stack([ndimage.correlate(fr, k, mode='constant') for fr in res]).astype(np.float32)


def robust_sd(v):
    v = np.asarray(v, dtype=np.float64)
    return 1.4826 * float(np.median(np.abs(v - np.median(v))))


# ---------------------------------------------------------------- post-processing of the residual (--post)
def _shift(r, dx, dy):
    """r[..., y + dy, x + dx], zero outside the frame."""
    out = np.zeros_like(r)
    h, w = r.shape[-2:]
    ys, yd = (slice(dy, h), slice(0, h - dy)) if dy >= 0 else (slice(0, h + dy), slice(-dy, h))
    xs, xd = (slice(dx, w), slice(0, w - dx)) if dx >= 0 else (slice(0, w + dx), slice(-dx, w))
    out[..., yd, xd] = r[..., ys, xs]
    return out


def _ring_mean(r, n, g):
    """Mean over the n x n square less its g x g core (g 0: no core), per frame."""
    a = ndimage.uniform_filter(r, size=(1, n, n), mode='constant') * float(n * n)
    if g > 0:
        a -= ndimage.uniform_filter(r, size=(1, g, g), mode='constant') * float(g * g)
    return a / float(n * n - g * g)


def _ring_fp(n, g):
    fp = np.ones((n, n), bool)
    if g > 0:
        c0 = (n - g) // 2
        fp[c0:c0 + g, c0:c0 + g] = False
    return fp


def post_dir(r, d=2, center=1):
    """(a) directional difference: per pixel and for 4 orientations (0, 90, 45, 135 degrees), r less
    the mean of the two pixels at +-d px along it (diagonals at (+-d, +-d)); the smallest of the four;
    with center 1, less its median over the frame's nonzero pixels (the smallest of four differences is
    biased low, about -0.73 of the noise's sd on white noise, and the search needs a zero-centred field)."""
    out = None
    for ox, oy in ((1, 0), (0, 1), (1, 1), (1, -1)):
        v = r - 0.5 * (_shift(r, d * ox, d * oy) + _shift(r, -d * ox, -d * oy))
        out = v if out is None else np.minimum(out, v)
    if center:
        for t in range(len(out)):
            nz = r[t] != 0
            if nz.any():
                out[t] -= np.float32(np.median(out[t][nz]))
    return out


def post_mean(r, n=15, g=5):
    """(b) the mean of the n x n neighbourhood less its g x g guard core subtracted."""
    return r - _ring_mean(r, n, g)


def post_median(r, n=9, g=3):
    """(b') the median of the n x n neighbourhood less its g x g guard core subtracted."""
    fp = _ring_fp(n, g)
    return np.stack([fr - ndimage.median_filter(fr, footprint=fp, mode='constant') for fr in r])


def post_rms(r, n=15, g=5, floor=0.25, robust='abs', valid=0):
    """(c) each pixel in the local rms of the n x n neighbourhood less its g x g guard core: robust
    'abs' = sqrt(pi / 2) x the mean |r| there (1 for unit Gaussian noise), 'mad' = 1.4826 x the median
    |r| (slower), 'rms' = the plain rms; the scale held at >= floor. valid 0: the ring's mean over all
    its n^2 - g^2 places, zeros outside the frame and at zero pixels counted (the scale too low within
    n / 2 px of the border, which raises the border: the first form measured); valid 1: over the
    ring's nonzero pixels only ('abs' and 'rms')."""
    if robust == 'mad':
        fp = _ring_fp(n, g)
        s = np.stack([1.4826 * ndimage.median_filter(np.abs(fr), footprint=fp, mode='constant') for fr in r])
    elif robust == 'rms':
        s = np.sqrt(np.maximum(_ring_mean(r * r, n, g), 0.0))
    else:
        s = math.sqrt(math.pi / 2.0) * _ring_mean(np.abs(r), n, g)
    if valid and robust != 'mad':
        share = _ring_mean((r != 0).astype(np.float32), n, g)
        s = np.where(share > 0.25, s / np.maximum(share, 0.25), 0.0)
        if robust == 'rms':
            s = s * np.sqrt(np.maximum(share, 0.25))  # s was sqrt(mean r^2 over all places)
    return r / np.maximum(s, floor)


POSTS = {'dir': post_dir, 'mean': post_mean, 'median': post_median, 'rms': post_rms}


def parse_post(spec):
    """'NAME[:k=v,...][+NAME[:k=v,...]]...' -> [(function, kwargs)], applied left to right."""
    steps = []
    for part in spec.split('+'):
        name, _, params = part.partition(':')
        kw = {}
        for kv in filter(None, params.split(',')):
            k, _, v = kv.partition('=')
            try:
                kw[k] = int(v)
            except ValueError:
                try:
                    kw[k] = float(v)
                except ValueError:
                    kw[k] = v
        steps.append((POSTS[name], kw))
    return steps


def post_tag(spec):
    """The cache files' suffix of a --post spec ('' without one)."""
    return '' if not spec else '_post-' + re.sub(r'[^A-Za-z0-9.=-]+', '_', spec)


def apply_post(res, spec):
    """The residual stack (frames, h, w) through the --post filters; frames without a residual
    (all zero) stay zero."""
    if not spec:
        return res
    ev = np.array([bool(fr.any()) for fr in res])
    for fn, kw in parse_post(spec):
        res = fn(res, **kw).astype(np.float32)
    res[~ev] = 0.0
    return res


# ---------------------------------------------------------------- inputs
def cmd_inputs(a):
    import subprocess
    for seed in seeds_arg(a.seeds):
        sd = os.path.join(a.sim, f'{a.db}_s{seed}')
        rd = os.path.join(a.run, f'{a.db}_s{seed}')
        if os.path.exists(os.path.join(rd, 'res.i16')):
            continue
        os.makedirs(rd, exist_ok=True)
        subprocess.run(['nice', a.pft, 'sim', '--scenario', a.scenario, '--seed', str(seed), '--backgrounds',
                        a.backgrounds, '--format', 'raw', '--out', sd], check=True, stdout=subprocess.DEVNULL,
                       stderr=subprocess.DEVNULL)
        with open(rd + '.log', 'w') as log:
            subprocess.run(['nice', a.pft, 'run', '--sequence', sd, '--scenario', a.scenario, '--out', rd,
                            '--no-video', '--residual-out', os.path.join(rd, 'res.i16.tmp')], check=True,
                           stdout=log, stderr=subprocess.STDOUT)
        os.replace(os.path.join(rd, 'res.i16.tmp'), os.path.join(rd, 'res.i16'))
        if not a.keep_frames:
            os.remove(os.path.join(sd, 'frames.u16'))
        print(f'inputs {a.db} seed {seed}', flush=True)


# ---------------------------------------------------------------- targets
def cmd_targets(a):
    os.makedirs(a.cache, exist_ok=True)
    for seed in seeds_arg(a.seeds):
        out = os.path.join(a.cache, f'tg_{a.db}_s{seed}{post_tag(a.post)}.json')
        if os.path.exists(out):
            continue
        q, res, truth, _ = load(a.sim, a.run, a.db, seed, a.res)
        res = apply_post(res, a.post)
        f, h, w = res.shape
        mf = matched(res)
        ev = [bool(res[t].any()) for t in range(f)]  # frames with a residual (1-based t+1)
        # noise of the residual and of MF at target-free pixels (frames with a residual)
        free = np.ones((h, w), bool)
        rs, ms = [], []
        for t in range(f):
            if not ev[t]:
                continue
            m = free.copy()
            for _, x, y, _ in truth.get(t + 1, []):
                xi, yi = int(round(x)), int(round(y))
                m[max(0, yi - 5):yi + 6, max(0, xi - 5):xi + 6] = False
            m &= res[t] != 0
            rs.append(res[t][m][::7])
            ms.append(mf[t][m][::7])
        rs, ms = np.concatenate(rs), np.concatenate(ms)
        tg = collections.defaultdict(list)
        for t in range(1, f + 1):
            for tid, x, y, kind in truth.get(t, []):
                if kind == 'injected':
                    tg[tid].append((t, x, y))
        targets = []
        for tid, pts in sorted(tg.items()):
            rows = []
            for t, x, y in pts:
                xi, yi = int(round(x)), int(round(y))
                inside = 0 <= xi < w and 0 <= yi < h
                if not inside or not ev[t - 1]:
                    rows.append(dict(t=t, x=x, y=y, xi=xi, yi=yi, ok=False))
                    continue
                pad = np.pad(res[t - 1], 3)[yi:yi + 7, xi:xi + 7]
                sub = float((pad * psf(x - xi, y - yi)).sum())
                sq = mf[t - 1][max(0, yi - 15):yi + 16, max(0, xi - 15):xi + 16].copy()
                cy, cx = yi - max(0, yi - 15), xi - max(0, xi - 15)
                ring = np.ones(sq.shape, bool)
                ring[max(0, cy - 3):cy + 4, max(0, cx - 3):cx + 4] = False
                med, lsd = float(np.median(sq[ring])), robust_sd(sq[ring])
                rows.append(dict(t=t, x=x, y=y, xi=xi, yi=yi, ok=True, amp=float(res[t - 1, yi, xi]),
                                 mf=float(mf[t - 1, yi, xi]), mf_sub=sub,
                                 z=(float(mf[t - 1, yi, xi]) - med) / lsd if lsd > 0 else float('nan')))
            # K-frame sums along the true path (nearest pixels), windows wholly inside its life
            sums = {}
            for K in KS:
                s = []
                for i in range(K - 1, len(rows)):
                    win = rows[i - K + 1:i + 1]
                    if all(r['ok'] for r in win) and win[-1]['t'] - win[0]['t'] == K - 1:
                        s.append((win[-1]['t'], float(sum(r['mf'] for r in win))))
                sums[K] = s
            v = [(pts[i + 1][1] - pts[i][1], pts[i + 1][2] - pts[i][2]) for i in range(len(pts) - 1)]
            vel = (float(np.mean([p[0] for p in v])), float(np.mean([p[1] for p in v]))) if v else (0.0, 0.0)
            targets.append(dict(id=tid, frames=len(pts), first=pts[0][0], vel=vel, rows=rows,
                                sums={str(K): s for K, s in sums.items()}))
        plat = [(float(r['x']), float(r['y'])) for r in csv.DictReader(
            open(os.path.join(a.sim, f'{a.db}_s{seed}', 'platform.csv')))]
        json.dump(dict(seed=seed, db=a.db, background=q.get('background', ''), frames=f,
                       evidence_frames=int(sum(ev)), res_sd=float(rs.std()), res_rsd=robust_sd(rs),
                       mf_sd=float(ms.std()), mf_rsd=robust_sd(ms),
                       scene_v=[-(plat[-1][0] - plat[0][0]) / (len(plat) - 1),
                                -(plat[-1][1] - plat[0][1]) / (len(plat) - 1)],
                       targets=targets), open(out, 'w'))
        print(f'targets {a.db} seed {seed}: {len(targets)} injected', flush=True)


# ---------------------------------------------------------------- clutter
def path_tree(kmax, dv, vmin, vmax, scene_v, gate, phases=1):
    """Distinct integer offset paths round(v j), j = 1..kmax-1, over a velocity grid; returns the
    prefix tree as a list of nodes (depth, offset, parent index, nonscene flag) in DFS order."""
    g = np.arange(-vmax, vmax + 1e-9, dv)
    j = np.arange(1, kmax)
    ph = (np.arange(phases) + 0.5) / phases - 0.5  # sub-pixel start phases (1: the pixel centre)
    paths = {}
    for vx in g:
        for vy in g:
            sp = math.hypot(vx, vy)
            if sp < vmin - 1e-9 or sp > vmax + 1e-9:
                continue
            ns = math.hypot(vx - scene_v[0], vy - scene_v[1]) > gate
            for fx in ph:
                for fy in ph:
                    # the position at frame t - j is p - v j for a target moving at v
                    ox = (np.floor(fx - vx * j + 0.5) - np.floor(fx + 0.5)).astype(int)
                    oy = (np.floor(fy - vy * j + 0.5) - np.floor(fy + 0.5)).astype(int)
                    key = tuple(zip(ox.tolist(), oy.tolist()))
                    paths[key] = paths.get(key, False) or ns
    nodes = {}
    for key, ns in paths.items():
        for d in range(1, kmax):
            pre = key[:d]
            nodes[pre] = nodes.get(pre, False) or ns
    order = sorted(nodes)  # lexicographic = DFS order (prefix before its extensions)
    return order, nodes, len(paths)


def cmd_clutter(a):
    os.makedirs(a.cache, exist_ok=True)
    ks = sorted(a.ks)
    kmax = max(ks)
    tree = None
    for seed in seeds_arg(a.seeds):
        out = os.path.join(a.cache, f'cl_{a.db}_s{seed}{post_tag(a.post)}{a.tag}.json')
        if os.path.exists(out):
            continue
        q, res, truth, plat = load(a.sim, a.run, a.db, seed, a.res)
        if a.white:  # the reference: the same search on white unit Gaussian noise in place of the residual
            ev0 = np.array([bool(fr.any()) for fr in res])
            res = np.random.default_rng(1000 + seed).standard_normal(res.shape).astype(np.float32)
            res[~ev0] = 0.0
        res = apply_post(res, a.post)
        scene_v = (-(plat[-1][0] - plat[0][0]) / (len(plat) - 1), -(plat[-1][1] - plat[0][1]) / (len(plat) - 1))
        if tree is None:
            order, flags, npaths = path_tree(kmax, a.dv, a.vmin, a.vmax, scene_v, a.scene_gate, a.phases)
            tree = (order, flags, npaths)
            print(f'{npaths} paths of {kmax} frames, {len(order)} tree nodes (dv {a.dv})', flush=True)
        order, flags, npaths = tree
        depth_n = collections.Counter(len(n) for n in order)
        f, h, w = res.shape
        mf = matched(res)
        ev = np.array([bool(res[t].any()) for t in range(f)])
        yy, xx = np.mgrid[0:h, 0:w]
        for t in range(f):  # zero the matched frame around every truth point of its frame
            for _, x, y, _ in truth.get(t + 1, []):
                xi, yi = int(round(x)), int(round(y))
                y0, x0 = max(0, yi - a.excl), max(0, xi - a.excl)
                mf[t, y0:yi + a.excl + 1, x0:xi + a.excl + 1] = 0.0
        P = int(math.ceil(a.vmax * (kmax - 1))) + 2
        pad = np.pad(mf, ((0, 0), (P, P), (P, P)))
        acc = np.zeros((kmax, h, w), np.float32)
        wins = []
        rng = np.random.default_rng(seed)
        for te in range(f, 0, -a.every):  # 1-based end frames
            t = te - 1
            rec = {'t': te}
            if t - (min(ks) - 1) < 0 or not ev[t - min(ks) + 1:t + 1].all():
                continue
            acc[0] = mf[t]
            best = {K: [-1e9, None] for K in ks}
            bestns = {K: -1e9 for K in ks}
            sds = collections.defaultdict(list)
            L = 0  # consecutive frames with a residual ending at t
            while t - L >= 0 and ev[t - L]:
                L += 1
            valid = {K: K <= L for K in ks}
            mmap = {K: np.full((h, w), -1e9, np.float32) for K in ks if valid[K]}
            for node in order:
                d = len(node)
                if d > L - 1:  # validity is by depth, so no skipped node has a visited descendant
                    continue
                ox, oy = node[-1]
                np.add(acc[d - 1], pad[t - d, P + oy:P + oy + h, P + ox:P + ox + w], out=acc[d])
                K = d + 1
                if K in ks and valid[K]:
                    m = float(acc[d].max())
                    if m > best[K][0]:
                        i = int(acc[d].argmax())
                        best[K] = [m, (i % w, i // w, [node[-1][0] / d, node[-1][1] / d])]
                    if flags[node] and m > bestns[K]:
                        bestns[K] = m
                    np.maximum(mmap[K], acc[d], out=mmap[K])
                    if rng.random() < max(a.sd_share, 8.0 / depth_n[d]):
                        sds[K].append(robust_sd(acc[d][::5, ::5]))
            for K in ks:
                if valid[K]:
                    # the clutter's candidates: local maxima (9 x 9) of the best sum over the paths per
                    # end pixel, the strongest --cands of them, in frame and scene coordinates
                    mm = mmap[K]
                    lm = np.flatnonzero((mm == ndimage.maximum_filter(mm, 9)) & (mm > 0))
                    top = lm[np.argsort(mm.ravel()[lm])[::-1][:a.cands]]
                    px, py = plat[t]
                    rec[K] = dict(max=best[K][0], arg=best[K][1], max_ns=bestns[K],
                                  sd=float(np.median(sds[K])) if sds[K] else None,
                                  cands=[[round(float(mm.ravel()[i]), 3), int(i % w), int(i // w),
                                          round(int(i % w) + px, 2), round(int(i // w) + py, 2)] for i in top])
            wins.append(rec)
        json.dump(dict(seed=seed, db=a.db, background=q.get('background', ''), dv=a.dv, every=a.every,
                       excl=a.excl, scene_v=scene_v, scene_gate=a.scene_gate, paths=npaths,
                       nodes=len(order), windows=[{str(k): v for k, v in r.items()} for r in wins]),
                  open(out, 'w'))
        print(f'clutter {a.db} seed {seed}: {len(wins)} windows', flush=True)


# ---------------------------------------------------------------- report
def gpd_tail(m):
    """(u, p_u, genpareto params) for the maxima above their 90th percentile."""
    from scipy import stats
    m = np.sort(np.asarray(m))
    u = float(np.quantile(m, 0.9))
    ex = m[m > u] - u
    c, loc, sc = stats.genpareto.fit(ex, floc=0.0)
    return u, float((m > u).mean()), (c, sc)


def rate_at(m, T, tail):
    """P(per-frame maximum > T): empirical below the tail's start, fitted above it."""
    from scipy import stats
    u, pu, (c, sc) = tail
    if T <= u:
        return float((np.asarray(m) > T).mean())
    return pu * float(stats.genpareto.sf(T - u, c, scale=sc))


def thr_for(m, r, tail):
    from scipy import stats
    u, pu, (c, sc) = tail
    if r >= pu:
        return float(np.quantile(m, 1 - r))
    return u + float(stats.genpareto.isf(r / pu, c, scale=sc))


def event_counts(cl, K, sd, ts, radius, gate, min_span=5):
    """Distinct clutter objects above each threshold: the candidates above T, linked when within
    `radius` px in scene coordinates (any frame of the run), counted once per linked group.
    Returns the counts, the counts without the groups that stay in the scene (spanning at least
    `min_span` frames with a fitted motion against the scene of at most `gate` px/frame: what the
    pipeline's scene-motion test rejects), and the lowest candidate kept (the search's floor)."""
    from scipy.sparse import csgraph, coo_matrix
    from scipy.spatial import cKDTree
    k = str(K)
    out = np.zeros(len(ts))
    out_mv = np.zeros(len(ts))
    trunc = 0
    for c in cl:
        cand = []
        for wi in c['windows']:
            if wi.get(k) and wi[k].get('cands'):
                cc = wi[k]['cands']
                cand += [(v / sd, xs, ys, wi['t']) for v, _, _, xs, ys in cc]
                trunc = max(trunc, cc[-1][0] / sd)
        if not cand:
            continue
        cand = np.array(cand)
        for i, T in enumerate(ts):
            sub = cand[cand[:, 0] > T]
            if len(sub) == 0:
                continue
            pairs = cKDTree(sub[:, 1:3]).query_pairs(radius, output_type='ndarray')
            g = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(len(sub), len(sub))) \
                if len(pairs) else coo_matrix((len(sub), len(sub)))
            n, lab = csgraph.connected_components(g, directed=False)
            out[i] += n
            for L in range(n):
                m = sub[lab == L]
                span = m[:, 3].max() - m[:, 3].min()
                if span >= min_span:
                    vx = np.polyfit(m[:, 3], m[:, 1], 1)[0]
                    vy = np.polyfit(m[:, 3], m[:, 2], 1)[0]
                    if math.hypot(vx, vy) <= gate:
                        continue
                out_mv[i] += 1
    return out, out_mv, trunc


def cmd_report(a):
    km = read_kinds(DEFAULT_KINDS)
    src = {}  # K -> the clutter files holding it (the first tag that has it)
    for tag in a.clutter_tags:
        pat = re.compile(rf'cl_{a.clutter_db}_s\d+{re.escape(post_tag(a.post) + tag)}\.json$')
        cl = [json.load(open(p)) for p in sorted(glob.glob(os.path.join(a.cache, f'cl_{a.clutter_db}_s*.json')))
              if pat.search(os.path.basename(p))]
        cl = [c for c in cl if c['seed'] <= a.max_seed]
        if not cl:
            continue
        print(f'clutter{tag}: {len(cl)} seeds ({min(c["seed"] for c in cl)}-{max(c["seed"] for c in cl)}), '
              f'{cl[0]["paths"]} paths / {cl[0]["nodes"]} tree nodes (dv {cl[0]["dv"]} px/frame), '
              f'windows every {cl[0]["every"]} frames, truth points zeroed within {cl[0]["excl"]} px')
        for K in KS:
            if K not in src and any(w.get(str(K)) for c in cl for w in c['windows']):
                src[K] = cl
    ks = [K for K in KS if K in src]
    if not ks:
        sys.exit('no clutter files')
    gate = src[ks[0]][0]['scene_gate']
    sdK, mx, mxns, mxk = {}, {}, {}, {}
    for K in ks:
        k = str(K)
        cl = src[K]
        per_seed = [np.median([w[k]['sd'] for w in c['windows'] if w.get(k) and w[k]['sd']]) for c in cl
                    if any(w.get(k) and w[k]['sd'] for w in c['windows'])]
        sdK[K] = float(np.median(per_seed))
        mx[K] = np.array([w[k]['max'] / sdK[K] for c in cl for w in c['windows'] if w.get(k)])
        mxns[K] = np.array([w[k]['max_ns'] / sdK[K] for c in cl for w in c['windows'] if w.get(k)])
        mxk[K] = collections.defaultdict(list)
        for c in cl:
            kind = km.get(os.path.basename(c['background']), 'procedural')
            mxk[K][kind] += [w[k]['max'] / sdK[K] for w in c['windows'] if w.get(k)]
        print(f'K {K:2d}: sd of the K-sum at target-free positions {sdK[K]:.3f} (sqrt(K) = {math.sqrt(K):.3f}; '
              f'per seed {min(per_seed):.3f}-{max(per_seed):.3f}); {len(mx[K])} windows of {len(cl)} seeds')
    rates = [1e-3, 1e-2]
    tails = {K: gpd_tail(mx[K]) for K in ks}
    tails_ns = {K: gpd_tail(mxns[K]) for K in ks}
    T = {(K, r): thr_for(mx[K], r, tails[K]) for K in ks for r in rates}
    Tns = {(K, r): thr_for(mxns[K], r, tails_ns[K]) for K in ks for r in rates}
    ts = np.arange(4.0, 30.0, 0.1)
    ev, evm, Tev, Tevm, trunc = {}, {}, {}, {}, {}
    for K in ks:
        frames = 100.0 * len(src[K])
        ev[K], evm[K], trunc[K] = event_counts(src[K], K, sdK[K], ts, a.radius, gate)
        for r in rates:
            ok = np.flatnonzero(ev[K] * 1000.0 / frames <= 1000.0 * r)
            Tev[K, r] = float(ts[ok[0]]) if len(ok) else float('nan')
            ok = np.flatnonzero(evm[K] * 1000.0 / frames <= 1000.0 * r)
            Tevm[K, r] = float(ts[ok[0]]) if len(ok) else float('nan')
    print('\nper-frame maximum of S_K over the frame and the paths (unit-variance units); thresholds for r false '
          'detections per frame (T) and for r distinct false objects per frame (Tev: candidates linked within '
          f'{a.radius} px in scene coordinates over the run, counted once):')
    print('K   median   90 %    99 %    largest   T(1/1000)  T(10/1000)  Tev(1/1000)  Tev(10/1000)  '
          'Tmv(1/1000)  Tmv(10/1000)  no scene-like paths: T(1/1000) T(10/1000)   lowest kept candidate')
    for K in ks:
        m = mx[K]
        print(f'{K:<3d} {np.median(m):6.2f}  {np.quantile(m, .9):6.2f}  {np.quantile(m, .99):6.2f}  {m.max():7.2f}  '
              f'{T[K, 1e-3]:9.2f}  {T[K, 1e-2]:9.2f}  {Tev[K, 1e-3]:10.2f}  {Tev[K, 1e-2]:10.2f}   '
              f'{Tevm[K, 1e-3]:10.2f}  {Tevm[K, 1e-2]:10.2f}   '
              f'{Tns[K, 1e-3]:10.2f}  {Tns[K, 1e-2]:10.2f}   {trunc[K]:6.2f}')
    print('(Tmv: distinct objects less those that stay in the scene, >= 5 frames with a fitted motion against the '
          f'scene <= {gate} px/frame, what the pipeline\'s scene-motion test rejects)')
    for K in ks:
        fr = 100.0 * len(src[K])
        print(f'distinct false objects per 1000 frames at T = 8, 10, 12, 14, K {K}: ' +
              ', '.join(f'{1000 * ev[K][np.argmin(np.abs(ts - x))] / fr:.1f}' for x in (8, 10, 12, 14)) +
              '; moving against the scene: ' +
              ', '.join(f'{1000 * evm[K][np.argmin(np.abs(ts - x))] / fr:.1f}' for x in (8, 10, 12, 14)))
    print('per kind, median / largest per-frame maximum:')
    for K in ks:
        print(f'  K {K:2d}: ' + ', '.join(f'{kd} {np.median(v):.2f} / {np.max(v):.2f} ({len(v)})'
                                           for kd, v in sorted(mxk[K].items())))
    # targets
    tbd = {}
    for spec in a.tbd or []:
        db, _, path = spec.partition('=')
        tbd[db] = json.load(open(path))
    cats = {}
    if a.trace_list:
        for line in open(a.trace_list):
            p = line.split()
            if len(p) > 5 and p[0] == 'seed' and p[2] == 'tid':
                cats[(int(p[1]), int(p[3]))] = p[5]
    res_rows = []
    curves = {}
    for db in a.dbs:
        tpat = re.compile(rf'tg_{db}_s\d+{re.escape(post_tag(a.post))}\.json$')
        tg = [json.load(open(p)) for p in sorted(glob.glob(os.path.join(a.cache, f'tg_{db}_s*.json')))
              if tpat.search(os.path.basename(p))]
        tg = [t for t in tg if t['seed'] <= a.max_seed]
        if not tg:
            continue
        allt = []
        for s in tg:
            kind = km.get(os.path.basename(s['background']), 'procedural')
            for t in s['targets']:
                rows = [r for r in t['rows'] if r['ok'] and r['t'] > 1]
                best = {K: max([v for _, v in t['sums'][str(K)]], default=float('-inf')) / sdK[K] for K in ks}
                rel = math.hypot(t['vel'][0] - s['scene_v'][0], t['vel'][1] - s['scene_v'][1])
                allt.append(dict(seed=s['seed'], id=t['id'], kind=kind, frames=t['frames'], best=best,
                                 sums={K: [(te, v / sdK[K]) for te, v in t['sums'][str(K)]] for K in ks},
                                 first=t['first'], rel=rel,
                                 amp=np.median([r['amp'] for r in rows]) if rows else float('nan'),
                                 mf=np.median([r['mf'] for r in rows]) if rows else float('nan'),
                                 mf_sub=np.median([r['mf_sub'] for r in rows]) if rows else float('nan'),
                                 z=np.median([r['z'] for r in rows]) if rows else float('nan')))
        n = len(allt)
        print(f'\n{db} dB: {n} injected targets in {len(tg)} seeds; residual sd at target-free pixels '
              f'{np.median([s["res_sd"] for s in tg]):.3f} (robust {np.median([s["res_rsd"] for s in tg]):.3f}), '
              f'matched {np.median([s["mf_sd"] for s in tg]):.3f} (robust {np.median([s["mf_rsd"] for s in tg]):.3f}) '
              f'(medians over seeds)')
        q = lambda v: ' / '.join(f'{x:.2f}' for x in np.nanquantile(v, [.1, .5, .9]))
        print(f'  per target, median over its frames (10 / 50 / 90 % over targets): residual at the nearest '
              f'pixel {q([t["amp"] for t in allt])}; matched {q([t["mf"] for t in allt])}; '
              f'sub-pixel matched {q([t["mf_sub"] for t in allt])}; local z {q([t["z"] for t in allt])}')
        for K in ks:
            print(f'  K {K:2d}: best window on the true path, 10 / 50 / 90 %: {q([t["best"][K] for t in allt])}; '
                  f'targets with no full window: {sum(1 for t in allt if t["best"][K] == float("-inf"))}')
        det = {}
        for t in allt:
            d = tbd.get(db)
            if d:
                for run in d['per_run']:
                    if run['seed'] == t['seed']:
                        for x in run['targets']:
                            if x['kind'] == 'injected' and x['id'] == t['id']:
                                det[(t['seed'], t['id'])] = bool(x['detected'])
        for r in rates:
            for K in ks:
                hit = [t['best'][K] > T[K, r] for t in allt]
                hit_ev = [t['best'][K] > Tev[K, r] for t in allt]
                byk_ev = collections.defaultdict(lambda: [0, 0])
                for t, h in zip(allt, hit_ev):
                    byk_ev[t['kind']][0] += h
                    byk_ev[t['kind']][1] += 1
                hit_ns = [t['best'][K] > Tns[K, r] and t['rel'] > gate for t in allt]
                hit_mv = [t['best'][K] > Tevm[K, r] and t['rel'] > gate for t in allt]
                byk = collections.defaultdict(lambda: [0, 0])
                for t, h in zip(allt, hit):
                    byk[t['kind']][0] += h
                    byk[t['kind']][1] += 1
                first = [min((te for te, v in t['sums'][K] if v > Tev[K, r]), default=None) for t in allt]
                delay = [f - t['first'] for f, t in zip(first, allt) if f is not None]
                row = dict(db=db, rate=r, K=K, T=T[K, r], pd=sum(hit) / n, n=n, pd_ns=sum(hit_ns) / n,
                           Tns=Tns[K, r], kinds={k: v[0] / v[1] for k, v in byk.items()},
                           kinds_n={k: v[1] for k, v in byk.items()},
                           delay=float(np.median(delay)) if delay else None,
                           Tev=Tev[K, r], pd_ev=sum(hit_ev) / n, kinds_ev={k: v[0] / v[1] for k, v in byk_ev.items()},
                           Tmv=Tevm[K, r], pd_mv=sum(hit_mv) / n)
                if det:
                    both = sum(1 for t, h in zip(allt, hit_ev) if h and det.get((t['seed'], t['id'])))
                    bo = sum(1 for t, h in zip(allt, hit_ev) if h and not det.get((t['seed'], t['id'])))
                    to = sum(1 for t, h in zip(allt, hit_ev) if not h and det.get((t['seed'], t['id'])))
                    row['paired'] = (both, bo, to)
                    if cats:
                        gap = collections.Counter(cats.get((t['seed'], t['id']), '?') for t, h in zip(allt, hit_ev)
                                                  if h and not det.get((t['seed'], t['id'])))
                        row['gap'] = dict(gap)
                    # the same pairing for the moving-objects threshold (Tmv; targets slow against the scene missed)
                    row['paired_mv'] = tuple(sum(1 for t, h in zip(allt, hit_mv) if h == hb and bool(det.get(
                        (t['seed'], t['id']))) == db_) for hb, db_ in ((True, True), (True, False), (False, True)))
                    if cats:
                        row['gap_mv'] = dict(collections.Counter(
                            cats.get((t['seed'], t['id']), '?') for t, h in zip(allt, hit_mv)
                            if h and not det.get((t['seed'], t['id']))))
                res_rows.append(row)
        # ROC per K: Pd against false detections per 1000 frames
        for K in ks:
            lo, hi = np.quantile(mx[K], 0.5), thr_for(mx[K], 1e-4, tails[K])
            tt = np.linspace(lo, hi, 200)
            curves[(db, K, 'frame')] = [(1000 * rate_at(mx[K], x, tails[K]), np.mean([t['best'][K] > x for t in allt]))
                                        for x in tt]
            fr = 100.0 * len(src[K])
            curves[(db, K, 'event')] = [(1000 * e / fr, np.mean([t['best'][K] > x for t in allt]))
                                        for x, e in zip(ts, ev[K]) if e > 0]
            for rr in a.at_rates or []:
                # the largest detection whose threshold gives at most rr distinct false objects per 1000 frames
                # (thresholds with no false object at all count too: the curve leaves them out for its log axis)
                ok = [np.mean([t['best'][K] > x for t in allt]) for x, e in zip(ts, ev[K]) if 1000 * e / fr <= rr]
                print(f'  {db} dB K {K}: at <= {rr} distinct false objects per 1000 frames: '
                      f'{100 * max(ok, default=0):.0f} %')
            curves[(db, K, 'moving')] = [(1000 * e / fr, np.mean([t['best'][K] > x and t['rel'] > gate for t in allt]))
                                         for x, e in zip(ts, evm[K]) if e > 0]
        if det:
            tb = tbd[db]['averaged'] if 'averaged' in tbd[db] else {}
            print(f'  TBD measured on the same seeds: {sum(det.values())} of {len(det)} detected')
    print('\nclairvoyant detection (a target counts when its true-path K-sum exceeds T in one window of its life):')
    print('SNR  rate/1000  K  | per frame: T   Pd    clear/cloud/struct (n)         frames to 1st (Tev) | no scene paths: T  Pd '
          '| distinct objects: Tev  Pd   clear/cloud/struct | moving objects: Tmv  Pd | paired with TBD at Tev '
          '(both / bound only / TBD only), bound-only by irmiss category | the same at Tmv')
    for r in res_rows:
        kd = ' / '.join(f'{r["kinds"].get(k, float("nan")):.0%} ({r["kinds_n"].get(k, 0)})' for k in KINDS)
        ke = ' / '.join(f'{r["kinds_ev"].get(k, float("nan")):.0%}' for k in KINDS)
        print(f'{r["db"]}   {1000 * r["rate"]:5.0f}    {r["K"]:2d} | {r["T"]:5.2f}  {r["pd"]:5.1%}  {kd:30s} '
              f'{r["delay"] if r["delay"] is not None else "-":>6} | {r["Tns"]:5.2f} {r["pd_ns"]:5.1%} | '
              f'{r["Tev"]:5.2f} {r["pd_ev"]:5.1%}  {ke:16s} | {r["Tmv"]:5.2f} {r["pd_mv"]:5.1%} | '
              f'{r.get("paired", "")}  {r.get("gap", "")}'
              + (f' | at Tmv: {r["paired_mv"]}  {r.get("gap_mv", "")}' if 'paired_mv' in r else ''))
    for db, d in tbd.items():
        av = d.get('averaged', {})
        print(f'TBD / DBT measured {db} dB: ' + json.dumps({k: av.get(k) for k in sorted(av) if 'tbd' in k.lower()
                                                            or 'dbt' in k.lower()})[:600])
    if a.curves_out:
        json.dump(dict(post=a.post, curves=[dict(db=db, K=K, kind=kd, points=c) for (db, K, kd), c in curves.items()]),
                  open(a.curves_out, 'w'))
        print(f'wrote {a.curves_out}')
    if a.fig:
        import matplotlib
        matplotlib.use('Agg')
        import matplotlib.pyplot as plt
        fig, axs = plt.subplots(1, len(a.dbs), figsize=(5 * len(a.dbs), 4.2), sharey=True)
        axs = np.atleast_1d(axs)
        for ax, db in zip(axs, a.dbs):
            for i, K in enumerate(KS):
                c = curves.get((db, K, 'event'))
                if c:
                    ax.plot([max(x, 1e-2) for x, _ in c], [100 * y for _, y in c], color=f'C{i}',
                            label=f'clairvoyant K={K} (distinct false objects)')
                c = curves.get((db, K, 'frame'))
                if c:
                    ax.plot([max(x, 1e-2) for x, _ in c], [100 * y for _, y in c], color=f'C{i}', ls='--', lw=0.8,
                            label='dashed: frames with a false detection' if i == len(ks) - 1 else None)
            for spec in a.points or []:
                p = spec.split(':')
                if p[0] == db:
                    ax.plot(float(p[3]), float(p[2]), 'o' if p[1] == 'TBD' else 's', ms=7,
                            label=f'{p[1]} measured' if len(p) < 5 else p[4])
            ax.axvline(1.0, color='grey', ls=':', lw=1)
            ax.axhline(90, color='grey', ls=':', lw=1)
            ax.set_xscale('log')
            ax.set_xlim(1e-2, 1e3)
            ax.set_xlabel('false detections per 1000 frames')
            ax.set_title(f'{int(db)} dB, 29 ir_sky backgrounds, seeds {a.seed_label}', fontsize=10)
            ax.grid(alpha=0.3)
        axs[0].set_ylabel('targets detected (%)')
        axs[-1].legend(fontsize=7, loc='lower right')
        fig.tight_layout()
        fig.savefig(a.fig, dpi=110)
        print(f'wrote {a.fig}')


# ---------------------------------------------------------------- objects
def cmd_objects(a):
    """The distinct clutter objects above --above (units of sd_K) of one K, as report's distinct-object
    count links them (candidates within --radius px in scene coordinates, any frame of the run): per
    object its seed, background, largest S_K, windows, first and last end frame, position of the
    largest (scene and frame) and, for objects spanning >= 5 frames, its fitted speed against the
    scene (report's Tmv drops those at <= the clutter files' scene gate). sd_K as report computes it."""
    from scipy.sparse import csgraph, coo_matrix
    from scipy.spatial import cKDTree
    k = str(a.k)
    pat = re.compile(rf'cl_{a.clutter_db}_s\d+{re.escape(post_tag(a.post) + a.tag)}\.json$')
    cl = [json.load(open(p)) for p in sorted(glob.glob(os.path.join(a.cache, f'cl_{a.clutter_db}_s*.json')))
          if pat.search(os.path.basename(p))]
    cl = sorted((c for c in cl if c['seed'] <= a.max_seed and any(w.get(k) for w in c['windows'])),
                key=lambda c: c['seed'])
    if not cl:
        sys.exit('no clutter files with K = %s' % k)
    sd = float(np.median([np.median([w[k]['sd'] for w in c['windows'] if w.get(k) and w[k]['sd']]) for c in cl
                          if any(w.get(k) and w[k]['sd'] for w in c['windows'])]))
    gate = cl[0]['scene_gate']
    print(f'K {a.k}: sd_K {sd:.3f}; {len(cl)} seeds; objects above {a.above} sd_K (linked within {a.radius} px '
          f'in scene coordinates); scene-fixed: >= 5 frames, fitted speed against the scene <= {gate} px/frame')
    for c in cl:
        cand = [(v / sd, xs, ys, w['t'], x, y) for w in c['windows'] if w.get(k) and w[k].get('cands')
                for v, x, y, xs, ys in w[k]['cands']]
        cand = np.array(cand) if cand else np.zeros((0, 6))
        sub = cand[cand[:, 0] > a.above]
        if len(sub) == 0:
            continue
        pairs = cKDTree(sub[:, 1:3]).query_pairs(a.radius, output_type='ndarray')
        g = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(len(sub), len(sub))) \
            if len(pairs) else coo_matrix((len(sub), len(sub)))
        n, lab = csgraph.connected_components(g, directed=False)
        for L in range(n):
            m = sub[lab == L]
            span = m[:, 3].max() - m[:, 3].min()
            v = (math.hypot(np.polyfit(m[:, 3], m[:, 1], 1)[0], np.polyfit(m[:, 3], m[:, 2], 1)[0])
                 if span >= 5 else None)
            i = int(m[:, 0].argmax())
            print(f'seed {c["seed"]:3d} {os.path.basename(c["background"])} max {m[i, 0]:5.1f} windows {len(m):3d} '
                  f'end frames {int(m[:, 3].min())}-{int(m[:, 3].max())} scene ({m[i, 1]:.0f}, {m[i, 2]:.0f}) '
                  f'frame ({m[i, 4]:.0f}, {m[i, 5]:.0f}) '
                  + ('speed against the scene -' if v is None else
                     f'speed against the scene {v:.2f}' + (' (scene-fixed)' if v <= gate else '')))


def cmd_roc(a):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5.2, 3.8))
    styles = ['-', '--', '-.', ':']
    for i, spec in enumerate(a.curves):
        label, _, path = spec.partition('=')
        d = json.load(open(path))
        for j, K in enumerate(a.ks):
            c = [x for x in d['curves'] if x['db'] == a.db and x['K'] == K and x['kind'] == 'event']
            if c:
                pts = c[0]['points']
                ax.plot([max(x, 1e-2) for x, _ in pts], [100 * y for _, y in pts], color=f'C{j}',
                        ls=styles[i % len(styles)], label=f'{label}, K={K}')
    ax.axvline(1.0, color='grey', ls=':', lw=1)
    ax.axhline(90, color='grey', ls=':', lw=1)
    ax.set_xscale('log')
    ax.set_xlim(1e-1, 1e3)
    ax.set_ylim(0, 100)
    ax.set_xlabel('distinct false objects per 1000 frames')
    ax.set_ylabel('targets detected (%)')
    ax.set_title(a.title, fontsize=9)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, loc='upper left')
    fig.tight_layout()
    fig.savefig(a.fig, dpi=90)
    print(f'wrote {a.fig}')


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    sp = ap.add_subparsers(dest='cmd', required=True)
    for name in ('inputs', 'targets', 'clutter'):
        p = sp.add_parser(name)
        if name == 'inputs':
            p.add_argument('--pft', required=True)
            p.add_argument('--scenario', required=True)
            p.add_argument('--backgrounds', required=True)
            p.add_argument('--keep-frames', action='store_true',
                           help='keep the sim\'s frames.u16 (for ir_bg_proto.py); deleted by default')
        p.add_argument('--sim', required=True)
        p.add_argument('--run', required=True)
        p.add_argument('--db', required=True)
        p.add_argument('--seeds', required=True)
        if name != 'inputs':
            p.add_argument('--cache', required=True)
            p.add_argument('--res', default='res.i16',
                           help='the residual file in RUN/<db>_s<N>/: res.i16 (int16 Q8.8, pft run) or NAME.f32 '
                           '(float32, tile-sigma units, e.g. ir_bg_proto.py); give each residual its own --cache')
            p.add_argument('--post', default='', help='NAME[:k=v,...][+NAME...]: filter each residual frame before '
                           'the matched filter (dir, mean, median, rms; see post_*); its own cache files')
        if name == 'clutter':
            p.add_argument('--every', type=int, default=5, help='windows end at every N-th frame')
            p.add_argument('--dv', type=float, default=0.05, help='velocity grid step, px/frame')
            p.add_argument('--vmin', type=float, default=0.3)
            p.add_argument('--vmax', type=float, default=1.2)
            p.add_argument('--excl', type=int, default=5, help='px zeroed around every truth point')
            p.add_argument('--scene-gate', type=float, default=0.15)
            p.add_argument('--sd-share', type=float, default=0.02, help='share of paths whose sums give sd_K')
            p.add_argument('--cands', type=int, default=40, help='clutter candidates kept per window and K')
            p.add_argument('--phases', type=int, default=1, help='sub-pixel start phases per axis of the paths')
            p.add_argument('--ks', type=int, nargs='+', default=[3, 5, 8, 12], help='window lengths (frames)')
            p.add_argument('--tag', default='', help='suffix of the cache files (a variant)')
            p.add_argument('--white', action='store_true',
                           help='search white unit Gaussian noise instead of the residual (a reference; use a --tag)')
    p = sp.add_parser('report')
    p.add_argument('--cache', required=True)
    p.add_argument('--dbs', nargs='+', default=['06', '09', '12'])
    p.add_argument('--clutter-db', default='09')
    p.add_argument('--clutter-tags', nargs='+', default=[''], help='clutter files of these tags (clutter --tag)')
    p.add_argument('--tbd', nargs='*', help='DB=summary.json of pft eval on the same seeds')
    p.add_argument('--points', nargs='*', help='DB:TBD|DBT:Pd%%:false/1000[:label] measured points for the figure')
    p.add_argument('--trace-list', help='ir_miss_diag.py --list output of the 9 dB runs')
    p.add_argument('--max-seed', type=int, default=1000)
    p.add_argument('--seed-label', default='1-29', help='seeds named in the figure titles')
    p.add_argument('--radius', type=float, default=4.0, help='px: candidates this close in scene coordinates are one object')
    p.add_argument('--fig')
    p.add_argument('--post', default='', help='read the cache files of this --post filter (targets and clutter)')
    p.add_argument('--at-rates', type=float, nargs='*', help='print the detection at these false objects / 1000 frames')
    p.add_argument('--curves-out', help='write the ROC curves (distinct objects and frames, per SNR and K) to this JSON')
    p = sp.add_parser('objects', help='the distinct clutter objects above a threshold of one K (what sets report\'s '
                      'Tev and Tmv), with their seed, position and speed against the scene')
    p.add_argument('--cache', required=True)
    p.add_argument('--k', type=int, default=12)
    p.add_argument('--above', type=float, default=10.0, help='threshold, units of sd_K')
    p.add_argument('--clutter-db', default='09')
    p.add_argument('--tag', default='', help='the clutter files of this clutter --tag')
    p.add_argument('--post', default='')
    p.add_argument('--radius', type=float, default=4.0)
    p.add_argument('--max-seed', type=int, default=1000)
    p = sp.add_parser('roc', help='one ROC figure from several report --curves-out files (e.g. a --post filter '
                      'beside the unfiltered residual)')
    p.add_argument('curves', nargs='+', help='LABEL=FILE.json')
    p.add_argument('--db', default='09')
    p.add_argument('--ks', type=int, nargs='+', default=[12, 20])
    p.add_argument('--title', default='')
    p.add_argument('--fig', required=True)
    a = ap.parse_args()
    {'inputs': cmd_inputs, 'targets': cmd_targets, 'clutter': cmd_clutter, 'report': cmd_report,
     'objects': cmd_objects, 'roc': cmd_roc}[a.cmd](a)


if __name__ == '__main__':
    main()
