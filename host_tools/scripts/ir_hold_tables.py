#!/usr/bin/env python3
"""Tables and figure of docs/results/ir_clutter.md, section "Branch irhold": report lengths of
TBD's false tracks and of its tracks on targets, and the report hold (`scene_hold`) against the
existing levers, from `pft eval` summaries of the tbd_ir kind. Not a test.

Per setting (LABEL=DIR, DIR holding a summary.json; LABEL=DIR1,DIR2 pools the runs of several):
- detected: injected targets associated with a reported track in some frame / injected targets,
  a ratio of sums over runs, its standard error from the per-run residuals d_i - p n_i;
- delay: frames from a detected target's first frame to its first associated report (the same
  ratio form over the detected targets);
- false tracks per 1000 frames: the mean of the per-run rates, its standard error from their
  spread;
- the paired difference to the first setting (same seeds, same sequences), per seed.

`lengths` prints, per setting, the report length of every false track (per_run[].
false_track_list) and of every track associated with a target in some frame (per_run[].
target_track_list, written by pft eval from branch irhold on): the reported frames and the span
(last reported frame - first + 1), as counts by bins and quantiles.

Usage:
  python3 host_tools/scripts/ir_hold_tables.py table LABEL=DIR [LABEL=DIR ...]
  python3 host_tools/scripts/ir_hold_tables.py lengths LABEL=DIR [LABEL=DIR ...]
  python3 host_tools/scripts/ir_hold_tables.py plot OUT.png TITLE HOLD_LABELS... -- LEVER_LABELS... -- LABEL=DIR ...
"""
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ir_demo_tables import mean_se, ratio  # noqa: E402  (one form of the tables' statistics)


def load(dirs):
    per = []
    for d in dirs.split(','):
        with open(os.path.join(d, 'summary.json')) as f:
            per += json.load(f)['per_run']
    per.sort(key=lambda r: r['seed'])
    return per


def per_seed(per):
    """seed -> (injected, detected, delay sum, false per 1000 frames)"""
    out = {}
    for r in per:
        ts = [t for t in r['targets'] if t['kind'] == 'injected']
        d = [t for t in ts if t['detected']]
        out[r['seed']] = (len(ts), len(d), sum(t['appearance_delay'] for t in d),
                          1000.0 * r['false_tracks'] / r['frames'])
    return out


def stats(per):
    s = per_seed(per)
    v = list(s.values())
    pd = ratio([x[1] for x in v], [x[0] for x in v])
    dl = ratio([x[2] for x in v], [x[1] for x in v])
    fa = mean_se([x[3] for x in v])
    return {'runs': len(v), 'targets': sum(x[0] for x in v), 'detected': sum(x[1] for x in v),
            'pd': pd, 'delay': dl, 'false': fa, 'seeds': s}


def table(sets):
    ref = None
    print('| setting | runs | targets | detected (± s.e.) | delay, frames (± s.e.) | false / 1000 fr. (± s.e.) |'
          ' detected − first, points (paired ± s.e.) | false − first (paired ± s.e.) |')
    print('|---|---|---|---|---|---|---|---|')
    for lab, d in sets:
        st = stats(load(d))
        if ref is None:
            ref = st
            dd = df = '–'
        else:
            common = sorted(set(st['seeds']) & set(ref['seeds']))
            a = [st['seeds'][k] for k in common]
            b = [ref['seeds'][k] for k in common]
            # detection difference as a ratio over the common seeds' injected targets
            num = [x[1] - y[1] for x, y in zip(a, b)]
            den = [x[0] for x in a]
            m, se = ratio(num, den)
            dd = '%+.1f ± %.1f' % (100 * m, 100 * se)
            m, se = mean_se([x[3] - y[3] for x, y in zip(a, b)])
            df = '%+.1f ± %.1f' % (m, se)
        print('| %s | %d | %d | %.1f %% (± %.1f) | %.1f (± %.1f) | %.1f (± %.1f) | %s | %s |' % (
            lab, st['runs'], st['targets'], 100 * st['pd'][0], 100 * st['pd'][1], st['delay'][0],
            st['delay'][1], st['false'][0], st['false'][1], dd, df))


def quant(v, q):
    if not v:
        return float('nan')
    v = sorted(v)
    return v[min(len(v) - 1, int(q * len(v)))]


def lengths(sets):
    bins = [(1, 1), (2, 2), (3, 3), (4, 5), (6, 10), (11, 30), (31, 1000)]
    head = ' | '.join('%d' % a if a == b else ('%d–%d' % (a, b) if b < 1000 else '≥ %d' % a) for a, b in bins)
    print('| setting | tracks | measure | ' + head + ' | median | 90 % |')
    print('|---|---|---|' + '---|' * len(bins) + '---|---|')
    for lab, d in sets:
        per = load(d)
        for kind, key in (('false', 'false_track_list'), ('on a target', 'target_track_list')):
            tr = [t for r in per for t in r.get(key, [])]
            if key == 'target_track_list' and not any(key in r for r in per):
                continue
            for meas in ('reported', 'span'):
                v = [t['reported_frames'] if meas == 'reported' else t['last_frame'] - t['first_frame'] + 1 for t in tr]
                cells = []
                for a, b in bins:
                    c = sum(1 for x in v if a <= x <= b)
                    cells.append('%d (%.0f %%)' % (c, 100.0 * c / len(v)) if v else '–')
                print('| %s | %s: %d | %s | %s | %s | %s |' % (
                    lab, kind, len(v), 'reported frames' if meas == 'reported' else 'span, frames',
                    ' | '.join(cells), quant(v, 0.5), quant(v, 0.9)))


def plot(argv):
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    out, title = argv[0], argv[1]
    rest = argv[2:]
    i = rest.index('--')
    hold = rest[:i]
    rest = rest[i + 1:]
    j = rest.index('--')
    lever = rest[:j]
    sets = dict(a.split('=', 1) for a in rest[j + 1:])
    fig, ax = plt.subplots(figsize=(6.4, 4.4))
    for labs, style, name in ((lever, 's--', 'existing levers'), (hold, 'o-', 'report hold k')):
        xs, ys, xe, ye = [], [], [], []
        for lab in labs:
            st = stats(load(sets[lab]))
            xs.append(st['false'][0]); xe.append(st['false'][1])
            ys.append(100 * st['pd'][0]); ye.append(100 * st['pd'][1])
        order = sorted(range(len(xs)), key=lambda k: xs[k])
        ax.errorbar([xs[k] for k in order], [ys[k] for k in order], xerr=[xe[k] for k in order],
                    yerr=[ye[k] for k in order], fmt=style, capsize=3, label=name)
        for k in range(len(xs)):
            ax.annotate(labs[k], (xs[k], ys[k]), textcoords='offset points', xytext=(4, 4), fontsize=7)
    ax.axvline(1.0, color='grey', lw=0.8, ls=':')
    ax.axhline(90.0, color='grey', lw=0.8, ls=':')
    ax.set_xlabel('TBD false tracks per 1000 frames (± 1 s.e.)')
    ax.set_ylabel('injected targets detected, % (± 1 s.e.)')
    ax.set_title(title, fontsize=9)
    ax.set_xlim(left=0)
    ax.set_ylim(0, 100)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


def main():
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    cmd = sys.argv[1]
    if cmd == 'plot':
        plot(sys.argv[2:])
        return
    sets = [a.split('=', 1) for a in sys.argv[2:]]
    if cmd == 'table':
        table(sets)
    elif cmd == 'lengths':
        lengths(sets)
    else:
        sys.exit(__doc__)


if __name__ == '__main__':
    main()
