#!/usr/bin/env python3
"""The real-background sweep of docs/results/ir_clutter.md per kind of background ("Branch
irsweep (2026-12-03): real backgrounds, 3-15 dB, per kind of background").

  classify IR_SKY_DIR [--kinds CSV]
      The criterion behind host_tools/scripts/ir_sky_kinds.csv, measured on every image: the
      residual of a local-mean background (the image less the mean of its 11 x 11 window
      without the central 5 x 5, grey levels of the 8-bit image, borders reflected), with
      the labelled objects (17 x 17 px around each label) left out:
        structures   more than 0.01 % of the pixels with |residual| > 40 grey levels (hot
                     or cold objects with sharp outlines: towers, buildings, trees, a cross);
        clear_sky    otherwise, when fewer than 2 % of the pixels have |residual| > 4;
        cloud_edges  the rest.
      Prints the figures and the kind per image, and where it differs from the CSV.

  tables OUT [--kinds CSV] [--max-seed N] [--plot PNG [--plot-tag TAG]] [--ir-sky DIR] [--tag TAG]
      Reads every OUT/<numeric>_<dB>_s<seed>/summary.json written by ir_real_sweep.sh
      (blocks of seeds of one build and SNR are pooled; runs with a seed above N are left
      out), maps each run to the kind of its background image and prints, per kind, SNR,
      tracker and build: runs, frames, injected targets, Pd (detected / targets, with its
      binomial standard error), appearance delay, RMSE over the correct points, share of
      correct target-frames, false tracks (count and per 1000 frames, with the Poisson
      standard error). Then the goals of issue #9 per kind, and (with --ir-sky) where the
      false tracks start: the gradient of the background image at the track's first position,
      in temporal sigmas per pixel, against the image's share of pixels in each band.
      --plot writes Pd against SNR per kind, TBD beside DBT, float and q16.

  tradeoff OUT --tags TAG,TAG [--max-seed N] [--build float]
      Per kind and SNR: TBD (the shipped sweep) beside DBT at the shipped false-alarm rate and
      at the variants TAG (e.g. pfa1e-4, pfa1e-3 written by ir_real_sweep.sh with a PATCH of
      dbt.pfa): Pd and false tracks per 1000 frames, on the same runs (seeds <= N).

Needs numpy (and scipy, PIL for classify and --ir-sky, matplotlib for --plot). Not a test;
the ir_sky images are evaluation data and never needed by a test.
"""
import argparse
import csv
import glob
import json
import math
import os
import re
import sys

KINDS = ['clear_sky', 'cloud_edges', 'structures']
KIND_TITLE = {'clear_sky': 'clear sky', 'cloud_edges': 'cloud edges', 'structures': 'structures'}
HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_KINDS = os.path.join(HERE, 'ir_sky_kinds.csv')


def read_kinds(path):
    with open(path) as f:
        return {r['file']: r['kind'] for r in csv.DictReader(f)}


# ----------------------------------------------------------------------------- classify
def local_residual(img):
    import numpy as np
    from scipy import ndimage
    b11 = ndimage.uniform_filter(img, 11, mode='reflect') * 121.0
    b5 = ndimage.uniform_filter(img, 5, mode='reflect') * 25.0
    return img - (b11 - b5) / 96.0


def label_mask(png, shape):
    import numpy as np
    m = np.ones(shape, bool)
    txt = png[:-4] + '.txt'
    if os.path.exists(txt):
        for ln in open(txt):
            p = ln.split()
            if len(p) < 5:
                continue
            x, y = int(float(p[1]) * shape[1]), int(float(p[2]) * shape[0])
            m[max(0, y - 8):y + 9, max(0, x - 8):x + 9] = False
    return m


def criterion(png):
    import numpy as np
    from PIL import Image
    img = np.asarray(Image.open(png).convert('L'), dtype=np.float64)
    a = np.abs(local_residual(img))
    m = label_mask(png, img.shape)
    s4 = float((a[m] > 4).mean())
    s40 = float((a[m] > 40).mean())
    kind = 'structures' if s40 > 1e-4 else 'clear_sky' if s4 < 0.02 else 'cloud_edges'
    return s4, s40, kind


def cmd_classify(args):
    kinds = read_kinds(args.kinds)
    bad = 0
    print('| image | pixels with \\|residual\\| > 4 | > 40 | kind (criterion) | CSV |')
    print('|---|---|---|---|---|')
    for png in sorted(glob.glob(os.path.join(args.ir_sky, '*.png'))):
        name = os.path.basename(png)
        s4, s40, kind = criterion(png)
        csv_kind = kinds.get(name, '(missing)')
        bad += csv_kind != kind
        print(f'| {name} | {100 * s4:.2f} % | {100 * s40:.3f} % | {kind} | {csv_kind}'
              f'{"" if csv_kind == kind else " (differs)"} |')
    print(f'\n{bad} image(s) where the CSV differs from the criterion')
    return 1 if bad else 0


# ----------------------------------------------------------------------------- tables
def load_runs(out, max_seed, tag=None):
    """{(numeric, db): {'tbd': [run], 'dbt': [run], 'scenario': json}}, runs with their image."""
    res = {}
    for p in sorted(glob.glob(os.path.join(out, '*', 'summary.json'))):
        m = re.match(r'(float|q16)_(\d\d)_s(\d+)(?:_(.+))?$', os.path.basename(os.path.dirname(p)))
        if not m or (m.group(4) or '') != (tag or ''):
            continue
        s = json.load(open(p))
        key = (m.group(1), int(m.group(2)))
        e = res.setdefault(key, {'tbd': [], 'dbt': [], 'scenario': s.get('scenario_json', {}), 'dirs': []})
        e['dirs'].append(os.path.dirname(p))
        for who, per in (('tbd', s['per_run']), ('dbt', s['dbt']['per_run'])):
            for i, r in enumerate(per):
                if max_seed and r['seed'] > max_seed:
                    continue
                r = dict(r)
                r['image'] = os.path.basename(s['per_run'][i]['background'])
                e[who].append(r)
    for e in res.values():
        for who in ('tbd', 'dbt'):
            seeds = [r['seed'] for r in e[who]]
            if len(seeds) != len(set(seeds)):
                sys.exit(f'{e["dirs"]}: a seed appears twice')
    return res


def group(runs, kind, kinds):
    """The measures of the injected targets over the runs whose image is of `kind`."""
    g = {'runs': 0, 'frames': 0, 'targets': 0, 'detected': 0, 'delay': 0.0, 'present': 0,
         'correct': 0, 'sq': 0.0, 'false': 0, 'false_list': [], 'labelled': 0, 'labelled_det': 0}
    for r in runs:
        if kind and kinds.get(r['image']) != kind:
            continue
        g['runs'] += 1
        g['frames'] += r['frames']
        g['false'] += r['false_tracks']
        g['false_list'] += [dict(f, image=r['image'], seed=r['seed']) for f in r.get('false_track_list', [])]
        for t in r['targets']:
            if t['kind'] != 'injected':
                g['labelled'] += 1
                g['labelled_det'] += bool(t['detected'])
                continue
            g['targets'] += 1
            g['present'] += t['present_frames']
            g['correct'] += t['correct_frames']
            g['sq'] += t['correct_sq_error_px2']
            if t['detected']:
                g['detected'] += 1
                g['delay'] += t['appearance_delay']
    n = g['targets']
    g['pd'] = g['detected'] / n if n else None
    g['pd_se'] = math.sqrt(g['pd'] * (1 - g['pd']) / n) if n else None
    g['delay_mean'] = g['delay'] / g['detected'] if g['detected'] else None
    g['rmse'] = math.sqrt(g['sq'] / g['correct']) if g['correct'] else None
    g['correct_frac'] = g['correct'] / g['present'] if g['present'] else None
    g['false_rate'] = 1000.0 * g['false'] / g['frames'] if g['frames'] else None
    g['false_se'] = 1000.0 * math.sqrt(g['false']) / g['frames'] if g['frames'] else None
    return g


def f(v, p=1, pct=False):
    if v is None:
        return '–'
    return f'{100 * v:.0f} %' if pct else f'{v:.{p}f}'


def cmd_tables(args):
    kinds = read_kinds(args.kinds)
    res = load_runs(args.out, args.max_seed, args.tag)
    if not res:
        sys.exit(f'{args.out}: no summaries')
    nums = [n for n in ('float', 'q16') if any(k[0] == n for k in res)]
    dbs = sorted({k[1] for k in res})
    G = {}
    for (num, db), e in res.items():
        for who in ('tbd', 'dbt'):
            for kind in KINDS + [None]:
                G[(kind, db, who, num)] = group(e[who], kind, kinds)
    seeds = sorted({r['seed'] for e in res.values() for r in e['tbd']})
    print(f'seeds {seeds[0]}..{seeds[-1]} ({len(seeds)} runs per build and SNR where complete); '
          f'builds {", ".join(nums)}; SNR {", ".join(str(d) for d in dbs)} dB\n')
    for kind in KINDS + [None]:
        title = KIND_TITLE.get(kind, 'all 29 backgrounds')
        imgs = sorted(k for k, v in kinds.items() if v == kind) if kind else None
        print(f'#### {title}' + (f' ({len(imgs)} images)' if imgs else '') + '\n')
        print(f'| {title}: SNR dB | tracker | build | runs | frames | targets | Pd (± s.e.) | delay | RMSE | '
              'correct | false tracks | false / 1000 fr. (± s.e.) |')
        print('|---' * 12 + '|')
        for db in dbs:
            for who in ('tbd', 'dbt'):
                for num in nums:
                    g = G.get((kind, db, who, num))
                    if not g or not g['runs']:
                        continue
                    print(f"| {db:02d} | {who.upper()} | {num} | {g['runs']} | {g['frames']} | {g['targets']} | "
                          f"{f(g['pd'], pct=True)} ({g['detected']}; ± {f(g['pd_se'], pct=True)}) | "
                          f"{f(g['delay_mean'])} | {f(g['rmse'], 3)} | {f(g['correct_frac'], pct=True)} | "
                          f"{g['false']} | {f(g['false_rate'])} (± {f(g['false_se'])}) |")
        print()
    goals(G, nums, dbs)
    if args.ir_sky:
        origins(G, nums, dbs, args.ir_sky, res)
    if args.plot:
        extra = {}
        if args.plot_tag:
            for (num, db), e in load_runs(args.out, args.max_seed, args.plot_tag).items():
                if num == 'float':
                    for kind in KINDS:
                        extra[(kind, db)] = group(e['dbt'], kind, kinds)
        plot(G, nums, dbs, args.plot, extra, args.plot_tag)


def goals(G, nums, dbs):
    print('#### Against the goals of issue #9\n')
    print('| kind | build | TBD at 9 dB: Pd, false / 1000 fr. | goal 1 (>= 90 %, <= 1) | DBT Pd by SNR | '
          'TBD Pd by SNR | where TBD first reaches DBT\'s Pd (DBT SNR -> TBD SNR: shift; false / 1000 fr. TBD, DBT) |')
    print('|---' * 7 + '|')
    for kind in KINDS + [None]:
        for num in nums:
            t9 = G.get((kind, 9, 'tbd', num))
            if not t9 or not t9['runs']:
                continue
            met = t9['pd'] is not None and t9['pd'] >= 0.9 and t9['false_rate'] <= 1.0
            series = {w: ' / '.join(f(G[(kind, d, w, num)]['pd'], pct=True) for d in dbs
                                    if (kind, d, w, num) in G) for w in ('tbd', 'dbt')}
            reach = []
            for dd in dbs:
                dg = G.get((kind, dd, 'dbt', num))
                if not dg or not dg['pd']:
                    continue
                for d in dbs:
                    t = G.get((kind, d, 'tbd', num))
                    if t and t['pd'] is not None and t['pd'] >= dg['pd']:
                        reach.append(f"{dd} -> {d}: {dd - d:+d} dB; {f(t['false_rate'])}, {f(dg['false_rate'])}")
                        break
                else:
                    reach.append(f"{dd} -> none")
            print(f"| {KIND_TITLE.get(kind, 'all')} | {num} | {f(t9['pd'], pct=True)}, {f(t9['false_rate'])} | "
                  f"{'met' if met else 'not met'} | {series['dbt']} | {series['tbd']} | {'<br>'.join(reach) or '–'} |")
    print()


def origins(G, nums, dbs, ir_sky, res):
    """Where the false tracks start: the gradient of the background image there."""
    import numpy as np
    from PIL import Image
    from scipy import ndimage
    grad, share = {}, {}
    bands = [(0, 3), (3, 10), (10, 30), (30, 1e9)]
    for png in glob.glob(os.path.join(ir_sky, '*.png')):
        img = np.asarray(Image.open(png).convert('L'), dtype=np.float64)
        name = os.path.basename(png)
        grad[name] = img
    print('#### Where the false tracks start (gradient of the background at the first reported position)\n')
    print('Gradient: |grad| of the background image smoothed by a Gaussian of 1 px, scaled to the '
          'sensor (x scale) over the temporal sigma, in sigma per pixel, the maximum within 2 px of the '
          'start; "area" is the share of the images\' pixels in the band (the same images, each once).\n')
    hdr = ' | '.join(f'{lo}–{hi if hi < 1e9 else "∞"} σ/px' for lo, hi in bands)
    print(f'| kind | tracker | build | false tracks | {hdr} | reported 1–2 frames | first frame <= 10 |'
          ' within 8 px of the frame edge | within 10 px of a labelled object | in the image\'s lowest third |')
    print('|---' * (9 + len(bands)) + '|')
    scen = next(iter(res.values()))['scenario']
    scale = 2.0 ** (scen.get('sensor', {}).get('bit_depth', 14) - 8)
    sig = scen.get('sensor', {}).get('noise_sigma', 20)
    W = scen.get('image', {}).get('width', 384)
    H = scen.get('image', {}).get('height', 288)
    labels = {}
    for name, img in grad.items():
        txt = os.path.join(ir_sky, name[:-4] + '.txt')
        labels[name] = []
        if os.path.exists(txt):
            for ln in open(txt):
                p = ln.split()
                if len(p) >= 5:
                    labels[name].append((float(p[1]) * img.shape[1], float(p[2]) * img.shape[0]))
    gmax = {}
    for name, img in grad.items():
        g = ndimage.gaussian_gradient_magnitude(img * scale, 1.0) / sig
        gmax[name] = (g, ndimage.maximum_filter(g, 5))

    def at(name, x, y):
        g = gmax[name][1]
        h, w = g.shape
        xi, yi = int(round(x)), int(round(y))
        xi = -xi if xi < 0 else 2 * (w - 1) - xi if xi >= w else xi
        yi = -yi if yi < 0 else 2 * (h - 1) - yi if yi >= h else yi
        return g[min(max(yi, 0), h - 1), min(max(xi, 0), w - 1)]

    from collections import defaultdict
    kinds = read_kinds(DEFAULT_KINDS)
    for kind in KINDS:
        area = np.concatenate([gmax[n][1].ravel() for n in gmax if kinds.get(n) == kind])
        area_s = [((area >= lo) & (area < hi)).mean() for lo, hi in bands]
        for who in ('tbd', 'dbt'):
            for num in nums:
                fl = []
                for d in dbs:
                    g = G.get((kind, d, who, num))
                    if g:
                        fl += g['false_list']
                if not fl:
                    print(f'| {KIND_TITLE[kind]} | {who.upper()} | {num} | 0 |' + ' – |' * (len(bands) + 5))
                    continue
                v = np.array([at(t['image'], t['scene_x'], t['scene_y']) for t in fl])
                cells = ' | '.join(f'{100 * ((v >= lo) & (v < hi)).mean():.0f} % ({100 * a:.0f} %)'
                                   for (lo, hi), a in zip(bands, area_s))
                short = np.mean([t['reported_frames'] <= 2 for t in fl])
                early = np.mean([t['first_frame'] <= 10 for t in fl])
                edge = np.mean([min(t['x'], t['y'], W - 1 - t['x'], H - 1 - t['y']) < 8 for t in fl])
                near = np.mean([any(math.hypot(t['scene_x'] - lx, t['scene_y'] - ly) <= 10
                                    for lx, ly in labels[t['image']]) for t in fl])
                low = np.mean([t['scene_y'] >= 2.0 * grad[t['image']].shape[0] / 3.0 for t in fl])
                print(f'| {KIND_TITLE[kind]} | {who.upper()} | {num} | {len(fl)} | {cells} | '
                      f'{100 * short:.0f} % | {100 * early:.0f} % | {100 * edge:.0f} % | {100 * near:.0f} % | '
                      f'{100 * low:.0f} % |')
    print('\n(band cells: share of the false tracks (share of the area); all SNRs pooled)\n')
    print('Images with the most false tracks (all SNRs pooled; false tracks per 1000 frames):\n')
    for who in ('tbd', 'dbt'):
        for num in nums:
            per, frames = defaultdict(int), defaultdict(int)
            for d in dbs:
                e = res.get((num, d))
                if not e:
                    continue
                for r in e[who]:
                    per[r['image']] += r['false_tracks']
                    frames[r['image']] += r['frames']
            for kind in KINDS:
                top = sorted((n for n in frames if kinds.get(n) == kind), key=lambda n: -per[n] / frames[n])[:4]
                print(f"- {who.upper()} {num}, {KIND_TITLE[kind]}: " +
                      ', '.join(f"{n[:-4]} {1000.0 * per[n] / frames[n]:.0f}" for n in top))
    print()


def plot(G, nums, dbs, path, extra=None, extra_tag=None):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    fig, axs = plt.subplots(1, 3, figsize=(12, 3.8), sharey=True)
    for ax, kind in zip(axs, KINDS):
        for who, col in (('tbd', 'tab:blue'), ('dbt', 'tab:red')):
            for num, ls, mk in (('float', '-', 'o'), ('q16', '--', 's')):
                pts = [(d, G[(kind, d, who, num)]) for d in dbs if (kind, d, who, num) in G
                       and G[(kind, d, who, num)]['targets']]
                if not pts:
                    continue
                x = [d for d, _ in pts]
                y = [100 * g['pd'] for _, g in pts]
                e = [100 * g['pd_se'] for _, g in pts]
                fr = sum(g['false'] for _, g in pts) * 1000.0 / max(1, sum(g['frames'] for _, g in pts))
                ax.errorbar(x, y, yerr=e, color=col, ls=ls, marker=mk, ms=4, capsize=2,
                            label=f'{who.upper()} {num} ({fr:.1f} false / 1000 fr.)')
        pts = [(d, extra[(kind, d)]) for d in dbs if extra and (kind, d) in extra]
        if pts:
            fr = sum(g['false'] for _, g in pts) * 1000.0 / max(1, sum(g['frames'] for _, g in pts))
            ax.errorbar([d for d, _ in pts], [100 * g['pd'] for _, g in pts],
                        yerr=[100 * g['pd_se'] for _, g in pts], color='tab:orange', ls=':', marker='^',
                        ms=4, capsize=2, label=f'DBT float, {extra_tag} ({fr:.1f} false / 1000 fr.)')
        n = G.get((kind, 9, 'tbd', 'float'))
        ax.set_title(f"{KIND_TITLE[kind]} ({n['runs'] if n else 0} runs, "
                     f"{n['targets'] if n else 0} targets per point)")
        ax.axhline(90, color='grey', lw=0.6, ls=':')
        ax.set_xlabel('SNR (dB, peak over temporal σ)')
        ax.set_xticks(dbs)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7, loc='upper left')
    axs[0].set_ylabel('injected targets detected (%)')
    axs[0].set_ylim(-2, 102)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    print(f'wrote {path}')


def cmd_tradeoff(args):
    kinds = read_kinds(args.kinds)
    tags = [''] + [t for t in args.tags.split(',') if t]
    data = {t: load_runs(args.out, args.max_seed, t) for t in tags}
    dbs = sorted({k[1] for k in data[''] if k[0] == args.build})
    print(f'| kind: SNR dB | TBD: Pd | false / 1000 fr. | ' +
          ' | '.join(f'DBT {t or "shipped"}: Pd | false / 1000 fr.' for t in tags) + ' | targets |')
    print('|---' * (4 + 2 * len(tags)) + '|')
    for kind in KINDS + [None]:
        for db in dbs:
            e = data[''].get((args.build, db))
            if not e:
                continue
            t = group(e['tbd'], kind, kinds)
            cells = [f"{f(t['pd'], pct=True)} | {f(t['false_rate'])}"]
            for tag in tags:
                d = data[tag].get((args.build, db))
                if not d:
                    cells.append('– | –')
                    continue
                g = group(d['dbt'], kind, kinds)
                if g['targets'] != t['targets']:
                    sys.exit(f'{tag} {db} dB: not the same runs as the shipped sweep')
                cells.append(f"{f(g['pd'], pct=True)} | {f(g['false_rate'])}")
            print(f"| {KIND_TITLE.get(kind, 'all')}: {db:02d} | {' | '.join(cells)} | {t['targets']} |")
    return 0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest='cmd', required=True)
    c = sub.add_parser('classify')
    c.add_argument('ir_sky')
    c.add_argument('--kinds', default=DEFAULT_KINDS)
    t = sub.add_parser('tables')
    t.add_argument('out')
    t.add_argument('--kinds', default=DEFAULT_KINDS)
    t.add_argument('--max-seed', type=int, default=0)
    t.add_argument('--plot')
    t.add_argument('--ir-sky')
    t.add_argument('--plot-tag', help='also plot DBT (float) of this variant, e.g. pfa1e-4')
    t.add_argument('--tag', help='the variant of ir_real_sweep.sh (TAG) to read instead of the shipped sweep')
    o = sub.add_parser('tradeoff')
    o.add_argument('out')
    o.add_argument('--tags', required=True)
    o.add_argument('--kinds', default=DEFAULT_KINDS)
    o.add_argument('--max-seed', type=int, default=0)
    o.add_argument('--build', default='float')
    args = ap.parse_args()
    return {'classify': cmd_classify, 'tables': cmd_tables, 'tradeoff': cmd_tradeoff}[args.cmd](args)


if __name__ == '__main__':
    sys.exit(main())
