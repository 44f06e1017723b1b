#!/usr/bin/env python3
"""Figure of docs/results/ir_clutter.md, section "Branch irlowfa": detected against false tracks
per 1000 frames for the shipped tbd_ir files, one arrow per scene and SNR from the default file
to its low-false-rate twin. The measures are ir_hold12_tables.py's (imported, not copied): a
point is LABEL=TRACKER:DIR as there (DIR1,DIR2 pools blocks of seeds); the points come in
pairs, default first, low-false-rate second, and the pair's label is the text before " | ".
Not a test.

Usage:
  python3 host_tools/scripts/ir_lowfa_plot.py OUT.png TITLE "GROUP | default=tbd:DIR" "GROUP | low=tbd:DIR" ...
"""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from ir_hold12_tables import load, parse, per_seed, stats  # noqa: E402


def main():
    if len(sys.argv) < 5 or (len(sys.argv) - 3) % 2:
        sys.exit(__doc__)
    import matplotlib
    matplotlib.use('Agg')
    import matplotlib.pyplot as plt
    out, title = sys.argv[1], sys.argv[2]
    pts = [parse(a) for a in sys.argv[3:]]
    fig, ax = plt.subplots(figsize=(7.6, 4.6))
    for i in range(0, len(pts), 2):
        xy = []
        for lab, trk, dirs in pts[i:i + 2]:
            st = stats(per_seed(load(trk, dirs)))
            xy.append((st['false'][0], 100 * st['pd'][0], st['false'][1], 100 * st['pd'][1]))
        group = pts[i][0].split(' | ')[0]
        c = 'C%d' % (i // 2)
        for (x, y, xe, ye), m in zip(xy, ('o', 's')):
            ax.errorbar([x], [y], xerr=[xe], yerr=[ye], fmt=m, color=c, capsize=3,
                        mfc=c if m == 'o' else 'white')
        ax.annotate('', xy=xy[1][:2], xytext=xy[0][:2],
                    arrowprops=dict(arrowstyle='->', color=c, lw=1.2))
        ax.plot([], [], '-', color=c, label=group)
    ax.plot([], [], 'o', color='grey', label='default file')
    ax.plot([], [], 's', color='grey', mfc='white', label='low_false_rate file')
    ax.set_xscale('symlog', linthresh=1.0)
    ax.set_xlim(0, 40)
    ax.set_xticks([0, 0.5, 1, 2, 5, 10, 20, 40])
    ax.set_xticklabels(['0', '0.5', '1', '2', '5', '10', '20', '40'])
    ax.set_xlabel('false tracks per 1000 frames (± 1 s.e.; linear below 1)')
    ax.set_ylabel('injected targets detected, % (± 1 s.e.)')
    ax.set_ylim(0, 100)
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=8, loc='upper left', bbox_to_anchor=(1.01, 1.0))
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == '__main__':
    main()
