#!/usr/bin/env python3
"""How far the stage's tile sigma is from the residual's own local spread (docs/results/
ir_clutter.md, section "Branch irsig"). Not a test.

  ir_tile_sd.py one RESIDUAL SEQUENCE_JSON > T.json
      RESIDUAL: `pft run --residual-out` (int16, Q8.8 sigma units, width x height per frame);
      SEQUENCE_JSON: the `pft sim` folder's sequence.json (width, height). Per 32 x 32 tile of
      the residual, per frame from 31 on: the robust sd about the tile's own median
      (1.4826 median |v - median v|, the nonzero pixels: masked ones are 0; frames with fewer
      than 64 skipped), its median over the frames; the tile's centre distance from the frame
      centre over the corner's (rho). 1 where the tile sigma that whitened the residual is its
      spread, below 1 where the sigma is too large.
  ir_tile_sd.py table DIR SEEDS NAME=CONFIG ...
      from DIR/t_CONFIG_SEED.json and DIR/st_CONFIG_SEED.csv (`pft run --stage-out`): per
      configuration the mean of the stage's sigma_mean over frames 31 on and seeds, the tiles'
      robust sd (median, 10th and 1st percentile, smallest, tiles under 0.85) and its median by
      rho band. SEEDS: A-B.
"""
import csv
import json
import statistics as st
import sys

import numpy as np

T = 32


def one(res, seqj):
    sj = json.load(open(seqj))
    W, H = sj['width'], sj['height']
    a = np.fromfile(res, dtype='<i2')
    nf = a.size // (W * H)
    a = a[:nf * W * H].reshape(nf, H, W).astype(np.float32) / 256.0
    out = []
    for ty in range(0, H, T):
        for tx in range(0, W, T):
            blk = a[30:, ty:ty + T, tx:tx + T].reshape(nf - 30, -1)
            sds = []
            for f in blk:
                v = f[f != 0]
                if v.size < 64:
                    continue
                sds.append(1.4826 * float(np.median(np.abs(v - np.median(v)))))
            if sds:
                cx = tx + min(T, W - tx) / 2 - W / 2
                cy = ty + min(T, H - ty) / 2 - H / 2
                out.append({'tx': tx, 'ty': ty, 'rho': float(np.hypot(cx, cy) / np.hypot(W / 2, H / 2)),
                            'sd': float(np.median(sds))})
    print(json.dumps({'W': W, 'H': H, 'tiles': out}))


def table(d, seeds, named):
    lo, hi = (int(x) for x in seeds.split('-'))
    bands = [(0, .4), (.4, .6), (.6, .8), (.8, 1.01)]
    print('| configuration | tiles | stage sigma_mean, counts | robust sd: median | 10th pct | 1st pct | smallest '
          '| tiles < 0.85 | ' + ' | '.join(f'median, rho {a}–{min(b, 1)}' for a, b in bands) + ' |')
    print('|' + '---|' * (8 + len(bands)))
    for nc in named:
        name, c = nc.split('=')
        sd, byb, sig = [], [[] for _ in bands], []
        for s in range(lo, hi + 1):
            for t in json.load(open(f'{d}/t_{c}_{s}.json'))['tiles']:
                sd.append(t['sd'])
                for i, (a, b) in enumerate(bands):
                    if a <= t['rho'] < b:
                        byb[i].append(t['sd'])
            rows = list(csv.DictReader(open(f'{d}/st_{c}_{s}.csv')))
            sig.append(st.mean(float(r['sigma_mean']) for r in rows if int(r['frame']) > 30))
        sd.sort()
        n = len(sd)
        low = sum(x < 0.85 for x in sd)
        print(f'| {name} | {n} | {st.mean(sig):.2f} | {st.median(sd):.3f} | {sd[n // 10]:.3f} | {sd[n // 100]:.3f} '
              f'| {sd[0]:.3f} | {low} ({100 * low / n:.1f} %) | ' + ' | '.join(f'{st.median(b):.3f}' for b in byb) + ' |')


if __name__ == '__main__':
    if len(sys.argv) >= 4 and sys.argv[1] == 'one':
        one(sys.argv[2], sys.argv[3])
    elif len(sys.argv) >= 5 and sys.argv[1] == 'table':
        table(sys.argv[2], sys.argv[3], sys.argv[4:])
    else:
        sys.exit(__doc__)
