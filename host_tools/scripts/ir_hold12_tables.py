#!/usr/bin/env python3
"""Tables and figure of docs/results/ir_clutter.md, section "Branch irhold12": TBD at 12 dB
(and 9 dB) with the report hold against DBT at 15 dB at several false-alarm rates, on the real
backgrounds, from `pft eval` summaries of the tbd_ir kind. Not a test.

A point is LABEL=TRACKER:DIR, TRACKER `tbd` (summary.json's top-level per_run) or `dbt`
(summary.json's dbt.per_run); DIR1,DIR2 pools the runs of several evaluations (blocks of
seeds). Measures as in ir_hold_tables.py: detected = injected targets associated with a
reported track in some frame / injected targets (ratio of sums over runs, standard error from
the per-run residuals); delay = frames from a detected target's first frame to its first
associated report; false tracks per 1000 frames = mean of the per-run rates (s.e. from their
spread). Paired columns: the difference to the table's first point, per seed over the common
seeds (run i of every evaluation uses the same background image; the sequences differ where the
SNR differs, so the pairing removes the background's share of the spread only).

Usage:
  python3 host_tools/scripts/ir_hold12_tables.py table POINT [POINT ...]
  python3 host_tools/scripts/ir_hold12_tables.py kinds POINT [POINT ...]     (per kind of background,
      host_tools/scripts/ir_sky_kinds.csv)
  python3 host_tools/scripts/ir_hold12_tables.py plot OUT.png TITLE POINT [POINT ...]
"""
import csv
import json
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from ir_demo_tables import mean_se, ratio  # noqa: E402

KINDS = ['clear_sky', 'cloud_edges', 'structures']


def kinds_of():
    with open(os.path.join(HERE, 'ir_sky_kinds.csv')) as f:
        return {r['file']: r['kind'] for r in csv.DictReader(f)}


def parse(arg):
    lab, rest = arg.split('=', 1)
    trk, dirs = rest.split(':', 1)
    return lab, trk, dirs


def load(trk, dirs):
    per = []
    for d in dirs.split(','):
        with open(os.path.join(d, 'summary.json')) as f:
            s = json.load(f)
        runs = s['per_run'] if trk == 'tbd' else s['dbt']['per_run']
        bg = {r['seed']: r.get('background', '') for r in s['per_run']}
        for r in runs:
            r = dict(r)
            r['background'] = bg.get(r['seed'], '')
            per.append(r)
    per.sort(key=lambda r: r['seed'])
    return per


def per_seed(per, kind=None):
    km = kinds_of()
    out = {}
    for r in per:
        if kind is not None and km.get(os.path.basename(r['background'])) != kind:
            continue
        ts = [t for t in r['targets'] if t['kind'] == 'injected']
        d = [t for t in ts if t['detected']]
        out.setdefault(r['seed'], []).append((len(ts), len(d), sum(t['appearance_delay'] for t in d),
                                              1000.0 * r['false_tracks'] / r['frames']))
    # several evaluations of one seed (other manager seeds, `seed_offset`) are pooled: their
    # counts summed, their false-track rates averaged
    return {k: (sum(x[0] for x in v), sum(x[1] for x in v), sum(x[2] for x in v),
                sum(x[3] for x in v) / len(v)) for k, v in out.items()}


def stats(s):
    v = list(s.values())
    return {'runs': len(v), 'targets': sum(x[0] for x in v), 'pd': ratio([x[1] for x in v], [x[0] for x in v]),
            'delay': ratio([x[2] for x in v], [x[1] for x in v]), 'false': mean_se([x[3] for x in v]), 'seeds': s}


def pairable(st, ref):
    """Whether two points share the two seeds or more a paired difference needs."""
    return len(set(st['seeds']) & set(ref['seeds'])) >= 2


def paired(st, ref):
    common = sorted(set(st['seeds']) & set(ref['seeds']))
    a = [st['seeds'][k] for k in common]
    b = [ref['seeds'][k] for k in common]
    # detection: difference of the two ratios, its s.e. from the per-seed residuals of both
    pa = sum(x[1] for x in a) / sum(x[0] for x in a)
    pb = sum(y[1] for y in b) / sum(y[0] for y in b)
    R = len(common)
    ra = [(x[1] - pa * x[0]) / (sum(z[0] for z in a) / R) - (y[1] - pb * y[0]) / (sum(z[0] for z in b) / R)
          for x, y in zip(a, b)]
    m = sum(ra) / R
    se = (sum((e - m) ** 2 for e in ra) / (R * (R - 1))) ** 0.5
    dd = (pa - pb, se)
    df = mean_se([x[3] - y[3] for x, y in zip(a, b)])
    return dd, df


def fmt(x, scale=1.0, unit=''):
    return '%.1f%s (± %.1f)' % (scale * x[0], unit, scale * x[1])


def paired_cells(st, ref):
    """The two paired-difference cells of a row against the reference row (None: the first)."""
    if ref is None:
        return '–', '–'
    if not pairable(st, ref):
        return 'no common seeds', 'no common seeds'
    (a, b), (c, d) = paired(st, ref)
    return '%+.1f ± %.1f' % (100 * a, 100 * b), '%+.1f ± %.1f' % (c, d)


def table(points):
    ref = None
    print('| point | runs | targets | detected (± s.e.) | delay, frames (± s.e.) | false / 1000 fr. (± s.e.) |'
          ' detected − first, points (paired ± s.e.) | false − first (paired ± s.e.) |')
    print('|---|---|---|---|---|---|---|---|')
    for lab, trk, dirs in points:
        st = stats(per_seed(load(trk, dirs)))
        dd, df = paired_cells(st, ref)
        ref = ref or st
        print('| %s | %d | %d | %s | %s | %s | %s | %s |' % (
            lab, st['runs'], st['targets'], fmt(st['pd'], 100, ' %'),
            fmt(st['delay']), fmt(st['false']), dd, df))


def kinds(points):
    print('| point | kind | runs | targets | detected (± s.e.) | delay, frames (± s.e.) | false / 1000 fr. (± s.e.) |')
    print('|---|---|---|---|---|---|---|')
    for lab, trk, dirs in points:
        per = load(trk, dirs)
        for k in KINDS:
            st = stats(per_seed(per, k))
            print('| %s | %s | %d | %d | %s | %s | %s |' % (
                lab, k.replace('_', ' '), st['runs'], st['targets'], fmt(st['pd'], 100, ' %'), fmt(st['delay']),
                fmt(st['false'])))


def plot(argv):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    out, title = argv[0], argv[1]
    pts = [parse(a) for a in argv[2:]]
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    groups = {}
    for lab, trk, dirs in pts:
        groups.setdefault(lab.split(' ')[0], []).append((lab, trk, dirs))
    styles = ['o-', 's--', '^-.', 'd:']
    ymin = 100.0
    for i, (g, lst) in enumerate(groups.items()):
        xs, ys, xe, ye, ls = [], [], [], [], []
        for lab, trk, dirs in lst:
            st = stats(per_seed(load(trk, dirs)))
            xs.append(st['false'][0]); xe.append(st['false'][1])
            ys.append(100 * st['pd'][0]); ye.append(100 * st['pd'][1]); ls.append(lab.split(' ', 1)[-1])
        ymin = min([ymin] + [y - e for y, e in zip(ys, ye)])
        o = sorted(range(len(xs)), key=lambda k: xs[k])
        ax.errorbar([xs[k] for k in o], [ys[k] for k in o], xerr=[xe[k] for k in o], yerr=[ye[k] for k in o],
                    fmt=styles[i % len(styles)], capsize=3, label=g)
        for k in range(len(xs)):
            ax.annotate(ls[k], (xs[k], ys[k]), textcoords='offset points', xytext=(4, -10), fontsize=7)
    ax.set_xscale('symlog', linthresh=1.0)
    ax.set_xlabel('false tracks per 1000 frames (± 1 s.e.; linear below 1)')
    ax.set_ylabel('injected targets detected, % (± 1 s.e.)')
    ax.set_title(title, fontsize=9)
    ax.set_ylim(max(0.0, 10.0 * int(ymin / 10.0) - 10.0), 100)
    ax.legend(fontsize=8, loc='lower right')
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    cmd = sys.argv[1]
    if cmd == 'plot':
        plot(sys.argv[2:])
    elif cmd == 'table':
        table([parse(a) for a in sys.argv[2:]])
    elif cmd == 'kinds':
        kinds([parse(a) for a in sys.argv[2:]])
    else:
        sys.exit(__doc__)


if __name__ == '__main__':
    main()
