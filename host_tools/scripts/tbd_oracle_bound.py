#!/usr/bin/env python3
"""Lower bound on the appearance delay of any track-before-detect of one dim point target,
against the image size, at a given false-alarm rate per frame (docs/results/tbd.md,
"How fast can any detector be on a larger image?").

The oracle knows everything but the target's position: its birth frame, its velocity, its
sub-pixel offset and amplitude. After n frames it sums the PSF-matched-filter outputs along the
trajectory from each possible start pixel, S_n(p) = sum_k MF_k(p + v k) / sqrt(n) (unit variance
under noise), and declares the target at the first n where some S_n(p) exceeds a threshold T.
Under white Gaussian noise the n-frame sum of unit-variance matched-filter fields is again such
a field, so the false-alarm probability per frame, P(max_p S_n(p) > T), does not depend on n:
T is the (1 - r) quantile of the maximum of one matched-filter image over the A pixels,
measured here by Monte Carlo. At the true start pixel S_n ~ N(d sqrt(n), 1), d = (A/sigma)
sqrt(sum h^2) with h the PSF sampled at the pixels and normalised to peak 1 (model of
docs/algorithms.md section 1). Delay = frames of data needed minus one (the measure of
`pft eval`: 0 when the first frame present is already associated).

Usage: tbd_oracle_bound.py [--snr-db 6] [--psf-sigma 0.7] [--sizes 20 64 256]
                           [--rates 0.0275 0.001] [--noise-images 20000] [--seed 1]
Needs numpy and scipy.
"""
import argparse

import numpy as np
from scipy.ndimage import convolve


def psf_kernel(sigma, dx, dy, half=3):
    ax = np.arange(-half, half + 1)
    xx, yy = np.meshgrid(ax - dx, ax - dy)
    return np.exp(-(xx ** 2 + yy ** 2) / (2 * sigma ** 2))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--snr-db", type=float, default=6.0)
    ap.add_argument("--psf-sigma", type=float, default=0.7)
    ap.add_argument("--sizes", type=int, nargs="+", default=[20, 64, 256])
    ap.add_argument("--rates", type=float, nargs="+", default=[0.0275, 0.001])
    ap.add_argument("--noise-images", type=int, default=20000)
    ap.add_argument("--walks", type=int, default=200000)
    ap.add_argument("--max-frames", type=int, default=40)
    ap.add_argument("--seed", type=int, default=1)
    a = ap.parse_args()
    rng = np.random.default_rng(a.seed)
    amp = 10 ** (a.snr_db / 20)
    # d over sub-pixel offsets (uniform), the oracle matched to the true offset
    offs = [(ox, oy) for ox in np.linspace(-0.5, 0.5, 5) for oy in np.linspace(-0.5, 0.5, 5)]
    d_all = [amp * np.sqrt((psf_kernel(a.psf_sigma, ox, oy) ** 2).sum()) for ox, oy in offs]
    d = float(np.mean(d_all))
    print(f"SNR {a.snr_db} dB: peak/sigma {amp:.3f}; matched-filter SNR per frame d = {d:.3f} "
          f"({min(d_all):.3f}-{max(d_all):.3f} over the sub-pixel offset)")
    k = psf_kernel(a.psf_sigma, 0, 0)
    k = k / np.sqrt((k ** 2).sum())  # unit-variance matched filter
    print(f"{'size':>8} {'rate/frame':>10} {'T':>6} {'frames of data (mean)':>22} "
          f"{'delay bound (mean)':>18} {'P(delay <= 3)':>14}")
    for n in a.sizes:
        left = a.noise_images
        maxima = []
        chunk = max(1, min(left, 2_000_000 // (n * n)))
        while left > 0:
            m = min(chunk, left)
            z = rng.standard_normal((m, n, n))
            mf = np.stack([convolve(z[i], k, mode="wrap") for i in range(m)])
            maxima.append(mf.reshape(m, -1).max(axis=1))
            left -= m
        maxima = np.concatenate(maxima)
        for r in a.rates:
            T = float(np.quantile(maxima, 1 - r))
            # first n with S_n > T, S_n = (d n + W_n) / sqrt(n), W a Gaussian random walk
            w = np.cumsum(rng.standard_normal((a.walks, a.max_frames)), axis=1)
            nn = np.arange(1, a.max_frames + 1)
            s = (d * nn + w) / np.sqrt(nn)
            hit = s > T
            first = np.where(hit.any(axis=1), hit.argmax(axis=1) + 1, a.max_frames + 1)
            delay = first - 1
            print(f"{n:>4}x{n:<3} {r:>10.4g} {T:>6.2f} {first.mean():>22.2f} {delay.mean():>18.2f} "
                  f"{(delay <= 3).mean():>14.2f}")


if __name__ == "__main__":
    main()
