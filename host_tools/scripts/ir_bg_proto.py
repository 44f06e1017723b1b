#!/usr/bin/env python3
"""Numpy prototypes of the IR stage's temporal background, for the clairvoyant bound of
host_tools/scripts/ir_bound.py (docs/results/ir_clutter.md, "Branch irbg"). Not a test, not the
library: an experiment on whether the background estimate makes the residual's clutter tail.

Each prototype reads a `pft sim --format raw` sequence (frames.u16, sequence.json, platform.csv)
and writes a residual of the layout of `pft run --residual-out` (frames x height x width, row-major)
as float32 in units of the tile sigma (res.f32; 0 at masked pixels and on frames without
evidence), which `ir_bound.py targets|clutter --res res.f32` reads in place of res.i16.
The platform path is the sim's TRUE one (platform.csv: frame k's pixel (x, y) sees the scene at
(x + px_k, y + py_k)), so registration error is out of the comparison; or, with
--shifts estimated:RUN, the path summed from the library's own frame-to-frame estimates
(RUN/<db>_s<N>/stage.csv of `pft run --stage-out`: p_k = p_1 - sum of the stage's shifts of frames
2..k, anchored at the true p_1), used for everything the true path drives (the re-warp's step, the
anchored grid's position, the clutter map's carry).

Methods (--method):
  rewarp   today's scheme (docs/algorithms.md 9.4): the background b, in the previous frame's
           coordinates, is warped to the current frame at every frame (separable Catmull-Rom,
           the shift rounded to 1/256 px as the library does), b <- warp(b) + alpha (z - c - warp(b));
           pixels whose taps reach outside the frame are masked and restart from z.
  anchor   the background B kept in fixed scene coordinates (an integer grid of the scene, the
           canvas covering the whole path: the same as a frame-sized grid re-anchored by whole
           pixels): each frame is interpolated ONCE into the grid by the inverse warp (z~),
           B <- B + alpha (z~ - B) where all of z~'s taps are inside the frame (new cells start
           from z~), and B is read into the frame by one warp for the residual.
  anchor_median  as anchor, but the background is the median of the last --nmed frames' z~
           in the grid (a non-recursive reference; memory --nmed frames).
--interp cubic (Catmull-Rom) | linear (bilinear) for both warps.
Common to all: dead (z = 0) and saturated (z = 2^bits - 1) pixels masked (residual 0, no update:
the predicted background stands in for them); alpha = max(alpha, 1/(n + 1)) while the
background holds n < 1/alpha frames (the library's warm-up); sensor-fixed column offsets as the
library's 9.5 (c += col_alpha (m - m17), m the column mean over every 4th row of r clipped at
+-3 tile sigmas of the last frame); the tile sigma 1.4826 x median |r| per 32 x 32 tile of
valid pixels (tiles with fewer than 64 take the mean of the others; floor 0.5 counts), its
reciprocal interpolated bilinearly between tile centres; frame 1 has no residual. Not modelled:
the library's flat field and clutter map, the registration (true shifts instead), Q8 weights.
--gain true divides each frame by the sim's TRUE sensor-fixed vignetting gain (1 - v r^2 / r_max^2,
v = sensor.vignetting of the scenario in sequence.json; ir_sim.cpp), the clairvoyant stand-in for
the library's flat field: without it the background's lag behind the vignetting ("Branch irnuc")
leaves a smooth residual offset (about 0.27 sigma rms on seed 1) that dominates the K-frame sums.

--map-anchor: the same map kept on an integer grid of the scene (nearest cell; no carry warp).
--map applies a float emulation of the library's clutter map with the gated mean (docs/algorithms.md
9.9: m and mu carried with the scene by the true shift, bilinear; M the 3 x 3 box mean of m before the
update; c = r - mu, w = c / sqrt(M) where M > 2; m <- m + a (min(c^2, 64) - m), mu <- mu + a (clip(r, +-8) - mu)
where |r| <= 1.5 or the persistence counter >= 4 frames; a = max(0.2, 1/n)): the settings of the best
setting's scenario (clutter_alpha 0.2, clutter_persist 4), without the library's integer rounding.

  ir_bg_proto.py --sim SIM --out RUNX --db 09 --seeds 1-29 --method anchor [--interp cubic]
                 [--alpha 0.15] [--gain none|true] [--map] [--shifts true|estimated:RUN] [--evidence-from RUN]   (zero the frames that RUN's res.i16 has
                 all zero: the library's frames without evidence)
Needs numpy (and scipy for --map).
"""
import argparse
import csv
import json
import os

import numpy as np


def seeds_arg(s):
    a, _, b = s.partition('-')
    return list(range(int(a), int(b or a) + 1))


def weights(f, interp):
    """Taps at offsets -1, 0, 1, 2 for a sample at fraction f in [0, 1) past tap 0."""
    if interp == 'linear':
        return np.array([0.0, 1.0 - f, f, 0.0])
    f2, f3 = f * f, f * f * f
    return np.array([(-f3 + 2 * f2 - f) / 2, (3 * f3 - 5 * f2 + 2) / 2, (-3 * f3 + 4 * f2 + f) / 2, (f3 - f2) / 2])


def interp_axis(a, ok, base, f, n, axis, interp):
    """out[i] = sum_t w_t a[i + base + t] (t = -1..2) along axis, for i in 0..n-1; out_ok where
    every tap of non-zero weight is inside a and ok there."""
    w = weights(f, interp)
    L = a.shape[axis]
    out = np.zeros(a.shape[:axis] + (n,) + a.shape[axis + 1:], np.float64)
    good = np.ones(out.shape, bool)
    i = np.arange(n)
    for t, wt in zip((-1, 0, 1, 2), w):
        if wt == 0.0:
            continue
        j = i + base + t
        inside = (j >= 0) & (j < L)
        jc = np.clip(j, 0, L - 1)
        v = np.take(a, jc, axis=axis)
        o = np.take(ok, jc, axis=axis)
        sh = [1] * a.ndim
        sh[axis] = n
        inside = inside.reshape(sh)
        out += wt * np.where(inside, v, 0.0)
        good &= inside & o
    return out, good


def warp2(a, ok, bx, fx, by, fy, h, w, interp):
    """a sampled at (i + by + fy, j + bx + fx) for the h x w output grid, separable."""
    t, tok = interp_axis(a, ok, by, fy, h, 0, interp)
    return interp_axis(t, tok, bx, fx, w, 1, interp)


def split(v):
    n = int(np.floor(v))
    return n, v - n


class Sigma:
    """Tile sigma (MAD) and its reciprocal interpolated between tile centres."""

    def __init__(self, h, w, tile=32, floor=0.5):
        self.h, self.w, self.tile, self.floor = h, w, tile, floor
        self.ty, self.tx = (h + tile - 1) // tile, (w + tile - 1) // tile
        self.sig = None

    def update(self, r, ok):
        T = self.tile
        s = np.full((self.ty, self.tx), np.nan)
        for i in range(self.ty):
            for j in range(self.tx):
                blk = r[i * T:(i + 1) * T, j * T:(j + 1) * T][ok[i * T:(i + 1) * T, j * T:(j + 1) * T]]
                if blk.size >= max(16, T * T // 16):
                    s[i, j] = 1.4826 * np.median(np.abs(blk))
        if np.isnan(s).all():
            s = self.sig if self.sig is not None else np.full((self.ty, self.tx), 1.0)
        else:
            s = np.where(np.isnan(s), np.nanmean(s), s)
        self.sig = np.maximum(s, self.floor)
        return self.sig

    def per_pixel(self):
        """1 / sigma at every pixel, bilinear between tile centres, held beyond the outer centres."""
        T = self.tile
        inv = 1.0 / self.sig
        cy = (np.arange(self.ty) + 0.5) * T - 0.5
        cx = (np.arange(self.tx) + 0.5) * T - 0.5
        yy = np.clip(np.interp(np.arange(self.h), cy, np.arange(self.ty)), 0, self.ty - 1)
        xx = np.clip(np.interp(np.arange(self.w), cx, np.arange(self.tx)), 0, self.tx - 1)
        y0 = np.minimum(np.floor(yy).astype(int), self.ty - 2) if self.ty > 1 else np.zeros(self.h, int)
        x0 = np.minimum(np.floor(xx).astype(int), self.tx - 2) if self.tx > 1 else np.zeros(self.w, int)
        fy = (yy - y0)[:, None]
        fx = (xx - x0)[None, :]
        y1 = np.minimum(y0 + 1, self.ty - 1)
        x1 = np.minimum(x0 + 1, self.tx - 1)
        a = inv[y0][:, x0] * (1 - fx) + inv[y0][:, x1] * fx
        b = inv[y1][:, x0] * (1 - fx) + inv[y1][:, x1] * fx
        return a * (1 - fy) + b * fy

    def tile_map(self):
        T = self.tile
        return np.kron(self.sig, np.ones((T, T)))[:self.h, :self.w]


def column_update(c, r, ok, sigmap, gamma=1.0 / 16):
    """9.5: c += gamma (m - m17), m the column mean over every 4th row of r clipped at +-3 sigma."""
    rr = np.clip(r[::4], -3 * sigmap[::4], 3 * sigmap[::4]) * ok[::4]
    m = rr.sum(0) / np.maximum(ok[::4].sum(0), 1)
    w = len(m)
    cs = np.concatenate([[0.0], np.cumsum(m)])
    lo = np.clip(np.arange(w) - 8, 0, w)
    hi = np.clip(np.arange(w) + 9, 0, w)
    m17 = (cs[hi] - cs[lo]) / (hi - lo)
    return c + gamma * (m - m17)


class ClutterMap:
    """Float emulation of pft_pre_clutter_* with the gated mean (9.9), on the whitened residual."""

    def __init__(self, h, w, alpha=0.2, thr=2.0, persist=4, excess=1.5, blur=1):
        self.m = np.ones((h, w))
        self.mu = np.zeros((h, w))
        self.p = np.zeros((h, w))
        self.n = 0
        self.h, self.w = h, w
        self.alpha, self.thr, self.persist, self.excess, self.blur = alpha, thr, persist, excess, blur

    def carry(self, d):
        """Frame k's pixel x sees what frame k-1 saw at x + d: bilinear, new pixels reset."""
        nx, fx = split(d[0])
        ny, fy = split(d[1])
        out = []
        for arr, fill in ((self.m, 1.0), (self.mu, 0.0), (self.p, 0.0)):
            v, ok = warp2(arr, np.ones(arr.shape, bool), nx, fx, ny, fy, self.h, self.w, 'linear')
            out.append(np.where(ok, v, fill))
        self.m, self.mu, self.p = out

    def step(self, r, ok):
        from scipy import ndimage
        n = 2 * self.blur + 1
        M = ndimage.uniform_filter(self.m, size=n, mode='nearest')
        c = r - self.mu
        w = np.where(M > self.thr, c / np.sqrt(np.maximum(M, 1e-9)), c) * ok
        self.n += 1
        a = max(self.alpha, 1.0 / self.n)
        big = np.abs(r) > self.excess
        self.p = np.where(ok, np.where(big, np.minimum(self.p + 1, 2 * self.persist), np.maximum(self.p - 0.5, 0)),
                          self.p)
        self.m = np.where(ok, self.m + a * (np.minimum(c * c, 64.0) - self.m), self.m)
        learn = ok & (~big | (self.p >= self.persist))
        self.mu = np.where(learn, self.mu + a * (np.clip(r, -8, 8) - self.mu), self.mu)
        return w


def estimated_path(path, plat, F):
    """The platform path summed from `pft run --stage-out`'s per-frame shifts: the stage's shift of
    frame k (z(p) = b(p - shift)) is the scene's move, -(p_k - p_{k-1}) in platform.csv's terms, so
    p_k = p_1 - sum_{j=2..k} shift_j, anchored at the true p_1 (a constant offset of the whole path
    changes nothing but the grid's origin). Rows are frames 1..F in order; frame 1's shift is 0."""
    rows = list(csv.DictReader(open(path)))
    if len(rows) != F:
        raise SystemExit(f'{path}: {len(rows)} rows for {F} frames')
    s = np.array([(float(r['shift_x_px']), float(r['shift_y_px'])) for r in rows])
    s[0] = 0.0
    return plat[0][None, :] - np.cumsum(s, axis=0)


class AnchoredClutterMap(ClutterMap):
    """--map-anchor: the same map kept on an integer grid of the scene (the canvas of the whole
    path) instead of carried by a bilinear warp at every frame: frame pixel (y, x) reads and
    writes the cell (y + round(py_k) - oy, x + round(px_k) - ox), no interpolation (the cell's
    statistics are those of scene points up to 0.5 px from the pixel). Cells not seen yet hold
    what the carry gives a new pixel (m 1, mu 0, counter 0)."""

    def __init__(self, h, w, ch, cw, origin):
        super().__init__(ch, cw)
        self.fh, self.fw, self.origin = h, w, origin
        self.at = (0, 0)

    def carry(self, d):  # unused: the position is set by place()
        raise AssertionError

    def place(self, p):
        self.at = (int(np.round(p[1])) - self.origin[1], int(np.round(p[0])) - self.origin[0])

    def step(self, r, ok):
        from scipy import ndimage
        y0, x0 = self.at
        sl = (slice(y0, y0 + self.fh), slice(x0, x0 + self.fw))
        n = 2 * self.blur + 1
        M = ndimage.uniform_filter(self.m, size=n, mode='nearest')[sl]
        m, mu, p = self.m[sl], self.mu[sl], self.p[sl]
        c = r - mu
        w = np.where(M > self.thr, c / np.sqrt(np.maximum(M, 1e-9)), c) * ok
        self.n += 1
        a = max(self.alpha, 1.0 / self.n)
        big = np.abs(r) > self.excess
        self.p[sl] = np.where(ok, np.where(big, np.minimum(p + 1, 2 * self.persist), np.maximum(p - 0.5, 0)), p)
        self.m[sl] = np.where(ok, m + a * (np.minimum(c * c, 64.0) - m), m)
        learn = ok & (~big | (self.p[sl] >= self.persist))
        self.mu[sl] = np.where(learn, mu + a * (np.clip(r, -8, 8) - mu), mu)
        return w


def run_seed(a, seed):
    sd = os.path.join(a.sim, f'{a.db}_s{seed}')
    q = json.load(open(os.path.join(sd, 'sequence.json')))
    W, H, F, bits = q['width'], q['height'], q['frames'], q.get('bit_depth', 14)
    fs = (1 << bits) - 1
    frames = np.fromfile(os.path.join(sd, 'frames.u16'), '<u2').reshape(F, H, W)
    plat = np.array([(float(r['x']), float(r['y'])) for r in csv.DictReader(open(os.path.join(sd, 'platform.csv')))])
    if a.shifts != 'true':
        plat = estimated_path(os.path.join(a.shifts.split(':', 1)[1], f'{a.db}_s{seed}', 'stage.csv'), plat, F)
    gain = np.ones((H, W))
    if a.gain == 'true':
        v = float(q['scenario']['sensor'].get('vignetting', 0.0))
        cx, cy = (W - 1) / 2.0, (H - 1) / 2.0
        yy, xx = np.mgrid[0:H, 0:W]
        gain = 1.0 - v * ((xx - cx) ** 2 + (yy - cy) ** 2) / (cx * cx + cy * cy)
    evid = np.ones(F, bool)
    if a.evidence_from:
        lib = np.memmap(os.path.join(a.evidence_from, f'{a.db}_s{seed}', 'res.i16'), '<i2', 'r', shape=(F, H, W))
        evid = np.array([bool(lib[t].any()) for t in range(F)])
    out = np.zeros((F, H, W), np.float32)
    sig = Sigma(H, W)
    c = np.zeros(W)
    nb = 0  # frames the background holds (the library's warm-up count)
    cmap = ClutterMap(H, W) if a.map and not a.map_anchor else None
    if a.map_anchor:
        mox, moy = int(np.round(plat[:, 0].min())) - 1, int(np.round(plat[:, 1].min())) - 1
        MW = W + int(np.round(plat[:, 0].max())) - int(np.round(plat[:, 0].min())) + 2
        MH = H + int(np.round(plat[:, 1].max())) - int(np.round(plat[:, 1].min())) + 2
        cmap = AnchoredClutterMap(H, W, MH, MW, (mox, moy))
    alpha = a.alpha
    ip = a.interp
    if a.method != 'rewarp':
        ox, oy = int(np.floor(plat[:, 0].min())) - 3, int(np.floor(plat[:, 1].min())) - 3
        CW = W + int(np.ceil(plat[:, 0].max() - plat[:, 0].min())) + 7
        CH = H + int(np.ceil(plat[:, 1].max() - plat[:, 1].min())) + 7
        B = np.zeros((CH, CW))
        Bok = np.zeros((CH, CW), bool)
        hist = []  # anchor_median: the last frames' z~ in the grid
    for k in range(F):
        z = frames[k].astype(np.float64)
        zm = (z > 0) & (z < fs)  # dead and saturated pixels masked
        zc = z / gain - c[None, :]
        if a.method == 'rewarp':
            if k == 0:
                b, bok = zc.copy(), zm.copy()
                nb = 1
                continue
            d = plat[k] - plat[k - 1]
            d = np.round(d * 256.0) / 256.0  # the library's 1/256 px shift
            nx, fx = split(d[0])
            ny, fy = split(d[1])
            bh, bhok = warp2(b, bok, nx, fx, ny, fy, H, W, ip)
        else:
            nx, fx = split(plat[k][0] - ox)
            ny, fy = split(plat[k][1] - oy)
            if k > 0:
                if a.method == 'anchor_median':
                    bh, bhok = warp2(B, Bok, nx, fx, ny, fy, H, W, ip)
                else:
                    bh, bhok = warp2(B, Bok, nx, fx, ny, fy, H, W, ip)
        if k > 0:
            ok = bhok & zm
            r = np.where(ok, zc - bh, 0.0)
            sig.update(r, ok)
            if evid[k]:
                wr = r * sig.per_pixel() * ok
                if cmap is not None:
                    if a.map_anchor:
                        cmap.place(plat[k])
                    elif cmap.n > 0:
                        cmap.carry(plat[k] - plat[k - 1])
                    wr = cmap.step(wr, ok)
                out[k] = wr.astype(np.float32)
            c = column_update(c, r, ok, sig.tile_map())
        # background update
        ae = max(alpha, 1.0 / (nb + 1))
        if a.method == 'rewarp':
            upd = np.where(bhok & zm, bh + ae * (zc - bh), bh)
            b = np.where(bhok, upd, np.where(zm, zc, bh))
            bok = bhok | zm
            nb += 1
        else:
            # the frame (its masked pixels replaced by the prediction) interpolated once into the grid
            zf = zc if k == 0 else np.where(zm, zc, np.where(bhok, bh, zc))
            zfok = zm if k == 0 else (zm | bhok)
            # grid cell X sees frame position X - p: base X - ox - n - 1 ... with fraction 1 - f
            gx, gfx = (-nx, 0.0) if fx == 0.0 else (-nx - 1, 1.0 - fx)
            gy, gfy = (-ny, 0.0) if fy == 0.0 else (-ny - 1, 1.0 - fy)
            zt, ztok = warp2(zf, zfok, gx, gfx, gy, gfy, CH, CW, ip)
            if a.method == 'anchor_median':
                hist.append((zt, ztok))
                hist = hist[-a.nmed:]
                st = np.stack([np.where(o, v, np.nan) for v, o in hist])
                with np.errstate(all='ignore'):
                    import warnings
                    with warnings.catch_warnings():
                        warnings.simplefilter('ignore')
                        med = np.nanmedian(st, axis=0)
                Bok = ~np.isnan(med)
                B = np.where(Bok, med, 0.0)
            else:
                B = np.where(ztok & Bok, B + ae * (zt - B), np.where(ztok, zt, B))
                Bok = Bok | ztok
            nb += 1
    od = os.path.join(a.out, f'{a.db}_s{seed}')
    os.makedirs(od, exist_ok=True)
    out.tofile(os.path.join(od, 'res.f32.tmp'))
    os.replace(os.path.join(od, 'res.f32.tmp'), os.path.join(od, 'res.f32'))
    return float(np.median([np.std(out[t][out[t] != 0]) for t in range(F) if out[t].any()]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    ap.add_argument('--sim', required=True)
    ap.add_argument('--out', required=True)
    ap.add_argument('--db', default='09')
    ap.add_argument('--seeds', required=True)
    ap.add_argument('--method', choices=('rewarp', 'anchor', 'anchor_median'), required=True)
    ap.add_argument('--interp', choices=('cubic', 'linear'), default='cubic')
    ap.add_argument('--alpha', type=float, default=0.15)
    ap.add_argument('--gain', choices=('none', 'true'), default='none',
                    help='true: divide by the sim\'s true vignetting gain (a clairvoyant flat field)')
    ap.add_argument('--map', action='store_true', help='the clutter map with the gated mean after the stage')
    ap.add_argument('--map-anchor', action='store_true',
                    help='the clutter map (implies --map) kept on an integer grid of the scene, read and written '
                         'at the nearest cell, instead of carried by a bilinear warp at every frame')
    ap.add_argument('--shifts', default='true',
                    help='true: the sim\'s platform.csv; estimated:RUN: the path summed from RUN/<db>_s<N>/stage.csv '
                         '(pft run --stage-out), for the background and the clutter map alike')
    ap.add_argument('--nmed', type=int, default=9, help='anchor_median: frames in the median')
    ap.add_argument('--evidence-from', help='RUN folder of pft run --residual-out: its all-zero frames stay zero')
    a = ap.parse_args()
    a.map = a.map or a.map_anchor
    for seed in seeds_arg(a.seeds):
        if os.path.exists(os.path.join(a.out, f'{a.db}_s{seed}', 'res.f32')):
            continue
        s = run_seed(a, seed)
        print(f'{a.method}/{a.interp} {a.db} seed {seed}: median per-frame sd of the residual {s:.3f}', flush=True)


if __name__ == '__main__':
    main()
