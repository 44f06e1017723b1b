#!/usr/bin/env python3
"""The injected targets' matched SNR from the simulator to the residual TBD reads
(docs/results/ir_clutter.md, section "Branch irsnr"). Not a test.

  ir_snr_budget.py NAME=TRACE_DIR [NAME=...] [--seeds 1-29] [--snr-db 9] [--psf 0.7]
                   [--drift 0.3,0.1] [--csv OUT.csv]

Per injected target (`pft eval --trace` rows, frames after the first) and traced block:
  z_stage = (mf_stage - loc_med_stage) / loc_sd_stage  the stage's residual (after the flat-field
                                                      step, before the clutter map), as ir_slow_trace.py
  z_map   = (mf_at - loc_med) / loc_sd                 the residual TBD takes (after the map)
  s_stage = mf_stage - loc_med_stage                   the matched signal in the stage's own sigma units
  n_stage = loc_sd_stage                               the matched filter's robust sd around the target
  p_stage = res_sd_stage                               the stage residual's own robust sd there (a
                                                      trace column since branch irsnr; n_stage / p_stage
                                                      is 1 on white noise, above 1 where the residual is
                                                      positively correlated over the PSF's extent)
  zsub_stage, zsub_map: the same with the filter centred on the true sub-pixel position
                       ((mfsub_stage - loc_med_stage) / loc_sd_stage, columns since branch irsnr),
                       what a likelihood evaluated at the true position weighs
and the expected matched value of the injected point alone on unit white noise, from its true
sub-pixel position (amplitude 10^(snr_db/20) noise sigmas, Gaussian of sd psf):
  ideal_sub  = A sqrt(sum_p g(p - x)^2)                 a filter centred on the true position
  ideal_near = A sum_p g(p - x) k(p - round(x))         the trace's filter, centred on the nearest pixel
                                                        (7 x 7 point-sampled Gaussian, unit noise gain)
Each target's value is its median over its frames; a table row gives the median over targets by
band of speed against the scene (the target's mean velocity in the frame plus the platform's
drift; bands from the first block, targets paired by seed and id across blocks), and the paired
difference of z_stage against the first block (mean +- standard error over targets).
"""
import argparse
import csv
import math
import os
import statistics

BANDS = ((0.0, 0.3), (0.3, 1.0), (1.0, 9.0), (0.0, 9.0))


def kernel(psf, R=3):
    k = {}
    ss = 0.0
    for b in range(-R, R + 1):
        for a in range(-R, R + 1):
            g = math.exp(-(a * a + b * b) / (2 * psf * psf))
            k[(a, b)] = g
            ss += g * g
    n = math.sqrt(ss)
    return {p: v / n for p, v in k.items()}


def ideal(x, y, amp, psf, ker):
    xi, yi = round(x), round(y)
    dx, dy = x - xi, y - yi
    near = 0.0
    for (a, b), kv in ker.items():
        near += kv * math.exp(-((a - dx) ** 2 + (b - dy) ** 2) / (2 * psf * psf))
    ss = 0.0
    for b in range(-6, 7):
        for a in range(-6, 7):
            g = math.exp(-((a - dx) ** 2 + (b - dy) ** 2) / (2 * psf * psf))
            ss += g * g
    return amp * near, amp * math.sqrt(ss)


def load(trace, seeds, amp, psf, ker, drift):
    out = {}
    for seed in seeds:
        f = os.path.join(trace, f's{seed}_targets.csv')
        if not os.path.exists(f):
            continue
        rows = {}
        with open(f) as fh:
            for r in csv.DictReader(fh):
                if r['labelled'] == '1':
                    continue
                rows.setdefault(int(r['tid']), []).append(r)
        for tid, rr in rows.items():
            rr.sort(key=lambda r: int(r['frame']))
            vals = {k: [] for k in ('z_stage', 'z_map', 's_stage', 'n_stage', 'p_stage', 'ideal_near', 'ideal_sub', 'eff',
                                     'zsub_stage', 'zsub_map')}
            for r in rr:
                if int(r['frame']) <= 1:
                    continue
                x, y = float(r['x']), float(r['y'])
                near, sub = ideal(x, y, amp, psf, ker)
                s = float(r.get('loc_sd_stage') or 0)
                if s > 0:
                    zs = (float(r['mf_stage']) - float(r['loc_med_stage'])) / s
                    vals['z_stage'].append(zs)
                    vals['s_stage'].append(float(r['mf_stage']) - float(r['loc_med_stage']))
                    vals['n_stage'].append(s)
                    if r.get('mfsub_stage'):
                        vals['zsub_stage'].append((float(r['mfsub_stage']) - float(r['loc_med_stage'])) / s)
                    p = float(r.get('res_sd_stage') or 0)
                    if p > 0:
                        vals['p_stage'].append(p)
                    vals['eff'].append(zs / near)
                s = float(r.get('loc_sd') or 0)
                if s > 0:
                    vals['z_map'].append((float(r['mf_at']) - float(r['loc_med'])) / s)
                    if r.get('mfsub_at'):
                        vals['zsub_map'].append((float(r['mfsub_at']) - float(r['loc_med'])) / s)
                vals['ideal_near'].append(near)
                vals['ideal_sub'].append(sub)
            if not vals['z_stage']:
                continue
            n = max(1, int(rr[-1]['frame']) - int(rr[0]['frame']))
            vx = (float(rr[-1]['x']) - float(rr[0]['x'])) / n + drift[0]
            vy = (float(rr[-1]['y']) - float(rr[0]['y'])) / n + drift[1]
            d = {k: (statistics.median(v) if v else float('nan')) for k, v in vals.items()}
            d['vs'] = math.hypot(vx, vy)
            d['frames'] = len(vals['z_stage'])
            out[(seed, tid)] = d
    return out


def med(v):
    v = [x for x in v if x == x]
    return statistics.median(v) if v else float('nan')


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('blocks', nargs='+')
    ap.add_argument('--seeds', default='1-29')
    ap.add_argument('--snr-db', type=float, default=9.0)
    ap.add_argument('--psf', type=float, default=0.7)
    ap.add_argument('--drift', default='0.3,0.1')
    ap.add_argument('--csv', default='')
    a = ap.parse_args()
    lo, hi = (int(x) for x in a.seeds.split('-'))
    seeds = range(lo, hi + 1)
    amp = 10 ** (a.snr_db / 20)
    ker = kernel(a.psf)
    drift = [float(x) for x in a.drift.split(',')]
    data = [(b.split('=', 1)[0], load(b.split('=', 1)[1], seeds, amp, a.psf, ker, drift)) for b in a.blocks]
    base = data[0][1]
    keys = sorted(k for k in base if all(k in d for _, d in data))
    print(f'{len(keys)} injected targets in every block, seeds {lo}-{hi}; amplitude {amp:.3f} sigma, psf {a.psf}')
    print('| block | speed vs scene, px/frame | targets | ideal sub-pixel | ideal nearest pixel | z stage | '
          'z stage / ideal nearest, dB | z after map | signal (stage sigma) | matched sd (stage sigma) | '
          'pixel sd (stage sigma) | z stage − first (paired, mean ± s.e.) | sub-pixel z stage | sub-pixel z after map | '
          'sub-pixel z after map − first (paired) |')
    print('|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|')
    for name, d in data:
        for blo, bhi in BANDS:
            ks = [k for k in keys if blo <= base[k]['vs'] < bhi]
            if not ks:
                continue
            band = 'all' if (blo, bhi) == (0.0, 9.0) else f'[{blo:.1f}, {bhi:.1f})'
            diff = [d[k]['z_stage'] - base[k]['z_stage'] for k in ks]
            m = statistics.mean(diff)
            se = statistics.stdev(diff) / math.sqrt(len(diff)) if len(diff) > 1 else float('nan')
            zs, zn = med(d[k]['z_stage'] for k in ks), med(d[k]['ideal_near'] for k in ks)
            dsub = [d[k]['zsub_map'] - base[k]['zsub_map'] for k in ks]
            dsub = [x for x in dsub if x == x]
            msub = statistics.mean(dsub) if dsub else float('nan')
            ssub = statistics.stdev(dsub) / math.sqrt(len(dsub)) if len(dsub) > 1 else float('nan')
            print('| %s | %s | %d | %.2f | %.2f | %.2f | %+.2f | %.2f | %.2f | %.3f | %.3f | %s | %.2f | %.2f | %s |' % (
                name, band, len(ks), med(d[k]['ideal_sub'] for k in ks), zn, zs,
                20 * math.log10(zs / zn) if zs > 0 else float('nan'), med(d[k]['z_map'] for k in ks),
                med(d[k]['s_stage'] for k in ks), med(d[k]['n_stage'] for k in ks), med(d[k]['p_stage'] for k in ks),
                '–' if d is base else '%+.2f ± %.2f' % (m, se),
                med(d[k]['zsub_stage'] for k in ks), med(d[k]['zsub_map'] for k in ks),
                '–' if d is base else '%+.2f ± %.2f' % (msub, ssub)))
    if a.csv:
        with open(a.csv, 'w', newline='') as fh:
            w = csv.writer(fh)
            w.writerow(['block', 'seed', 'tid', 'vs', 'frames', 'z_stage', 'z_map', 's_stage', 'n_stage',
                        'p_stage', 'ideal_near', 'ideal_sub', 'zsub_stage', 'zsub_map'])
            for name, d in data:
                for k in keys:
                    r = d[k]
                    w.writerow([name, k[0], k[1], '%.3f' % r['vs'], r['frames']] +
                               ['%.4f' % r[c] for c in ('z_stage', 'z_map', 's_stage', 'n_stage', 'p_stage', 'ideal_near', 'ideal_sub', 'zsub_stage', 'zsub_map')])


if __name__ == '__main__':
    main()
