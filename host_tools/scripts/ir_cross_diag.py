#!/usr/bin/env python3
"""The crossing pairs of the IR sweep scenarios (docs/results/ir_clutter.md, "Branch ircross"):
for the injected targets that ir_miss_diag.py puts in category (d) (under the track of their
crossing partner), how long the pair is close, whether the target had a search hypothesis or a
track layer of its own while apart from its partner, and, as a control, how soon the other
injected targets of the same runs are confirmed. Reads the trace of `pft eval --trace DIR` and
the same run's summary.json.

  ir_cross_diag.py TRACE_DIR SUMMARY_JSON [--frames]

The crossing pair of a run is its two injected targets of largest id (host_tools/tbd/ir_sim.cpp
makes the random targets first, then the pair). The (d) rule is ir_miss_diag.py's: not detected,
a track layer within 3 px of it in some frame, and one of those layers reported while within 3 px
of it (d_shared) or reported at another time (d_late). "Apart": the pair more than 6 px apart.
A hypothesis: >= 50 % of the search layer's live particles within 3 px. A layer of its own: the
nearest track layer within 3 px of the target and not within 3 px of the partner. Not a test.
"""
import argparse
import collections
import csv
import json
import math


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def crossing_pair(run):
    """The run's injected targets sorted by id: the last two (the pair the simulation makes
    cross) and the others; (None, all of them) with fewer than two."""
    inj = sorted((t for t in run['targets'] if t['kind'] == 'injected'), key=lambda t: t['id'])
    return (inj[-2:], inj[:-2]) if len(inj) >= 2 else (None, inj)


def pair_frames(trace, seed, pair):
    """The targets file of run `seed` by frame and target id, the pair's separation (px) in
    every frame where both are in view, and the frame of their closest approach (None when
    they never share a frame)."""
    by = collections.defaultdict(dict)
    for r in read_csv(f'{trace}/s{seed}_targets.csv'):
        by[int(r['frame'])][int(r['tid'])] = r
    ida, idb = pair[0]['id'], pair[1]['id']
    both = [f for f in sorted(by) if ida in by[f] and idb in by[f]]
    sep = {f: math.hypot(float(by[f][ida]['x']) - float(by[f][idb]['x']),
                         float(by[f][ida]['y']) - float(by[f][idb]['y'])) for f in both}
    return by, sep, (min(sep, key=sep.get) if sep else None)


def near_ids(s):
    return {int(p.split(':')[0]) for p in s.split(';') if p}


def within(r, d):
    return r != '' and float(r) <= d


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('trace')
    ap.add_argument('summary')
    ap.add_argument('--frames', action='store_true', help='one character line per frame of each (d) target')
    a = ap.parse_args()
    summ = json.load(open(a.summary))
    others = []          # (detected, appearance delay) of the injected targets outside the pair
    pair_first = []      # first associated frame of a detected pair target less the pair's closest frame
    pair_det = collections.Counter()
    dlist = []
    for run in summ['per_run']:
        seed = run['seed']
        pair, rest = crossing_pair(run)
        if pair is None:
            continue
        others += [(t['detected'], t['appearance_delay']) for t in rest]
        pair_det[sum(bool(t['detected']) for t in pair)] += 1
        by, sep, kc = pair_frames(a.trace, seed, pair)
        both = list(sep)  # frames with both in view, in order
        layers = read_csv(f'{a.trace}/s{seed}_tracks.csv')
        ida, idb = pair[0]['id'], pair[1]['id']
        if kc is None:
            continue
        for t in pair:
            if t['detected']:
                pair_first.append(t['first_frame'] + t['appearance_delay'] - kc)
                continue
            tid = t['id']
            on = [L for L in layers if tid in near_ids(L['near_all'])]
            if not on:
                continue
            if any(tid in near_ids(L['near_rep_all']) for L in on):
                cat = 'd_shared'
            elif any(int(L['reported']) > 0 for L in on):
                cat = 'd_late'
            else:
                continue
            par = idb if tid == ida else ida
            fr = [f for f in sorted(by) if tid in by[f] and f > 1]

            def hyp(f):
                r = by[f][tid]
                return int(r['alive']) > 0 and int(r['alive_near']) / int(r['alive']) >= 0.5

            def layer(f):  # None, 'own' or 'shared'
                r = by[f][tid]
                if not within(r['trk_d'], 3.0):
                    return None
                p = by[f].get(par)
                if p is not None and p['trk_id'] == r['trk_id'] and within(p['trk_d'], 3.0):
                    return 'shared'
                return 'own'

            apart = [f for f in fr if f not in sep or sep[f] > 6.0]
            pre = [f for f in apart if f < kc]
            post = [f for f in apart if f > kc]
            shared = [f for f in fr if layer(f) == 'shared']
            rep = [f for f in fr if within(by[f][tid]['rep_d'], 3.0)]
            hand = [(int(L['handover']), L['reason'], int(L['alive']), L['reported']) for L in on]
            hsep = [round(sep.get(h, float('nan')), 1) for h, _, _, _ in hand]
            dlist.append(dict(
                seed=seed, tid=tid, cat=cat, n=len(fr), c3=sum(sep[f] <= 3.0 for f in both),
                c6=sum(sep[f] <= 6.0 for f in both), pre=len(pre), post=len(post),
                hyp_pre=sum(map(hyp, pre)), hyp_post=sum(map(hyp, post)),
                own_pre=sum(layer(f) == 'own' for f in pre), own_post=sum(layer(f) == 'own' for f in post),
                shared=len(shared), rep=len(rep), rep_sep=max((sep[f] for f in rep if f in sep), default=float('nan')),
                hand=hand, hsep=hsep,
                line=' '.join(f"{f - kc:+d}:{sep.get(f, -1):.0f}{'H' if hyp(f) else ''}"
                              f"{({'own': 'O', 'shared': 'S'}.get(layer(f), ''))}{'R' if f in rep else ''}"
                              for f in fr)))
    print('(d) targets: frames alive, frames with the pair within 3 / 6 px, frames apart (> 6 px) before / after '
          'the closest frame, of those with a search hypothesis on it and with a track layer of its own, frames '
          'under a layer shared with the partner, frames a reported track was within 3 px (largest pair '
          'separation then), the layers within 3 px (hand-over frame, pair separation at it, end reason, frames '
          'alive, frames reported)')
    print('seed tid cat       alive <=3 <=6 apart_pre/post hyp_pre/post own_pre/post shared rep(sep) layers')
    for d in dlist:
        lay = '; '.join(f'h{h} sep {s} {why or "alive"} {al} fr rep {rp}' for (h, why, al, rp), s in zip(d['hand'], d['hsep']))
        print(f"{d['seed']:4d} {d['tid']:3d} {d['cat']:9s} {d['n']:5d} {d['c3']:3d} {d['c6']:3d} {d['pre']:7d}/{d['post']:<6d} "
              f"{d['hyp_pre']:7d}/{d['hyp_post']:<4d} {d['own_pre']:7d}/{d['own_post']:<4d} {d['shared']:6d} "
              f"{d['rep']:3d}({d['rep_sep']:.1f}) {lay}")
        if a.frames:
            print('     frame-closest:sep[H hypothesis][O own layer|S shared layer][R reported within 3 px]')
            print('    ', d['line'])
    n = len(others)
    print(f'\npairs with 0 / 1 / 2 targets detected: {pair_det[0]} / {pair_det[1]} / {pair_det[2]}; '
          f'pair targets detected {sum(k * v for k, v in pair_det.items())} of {2 * sum(pair_det.values())}')
    delays = sorted(dl for det, dl in others if det)
    print(f'other injected targets: {n}, detected {len(delays)}, appearance delays {delays}')
    pair_first.sort()
    if pair_first:
        print(f'detected pair targets: first association less the closest frame, median '
              f'{pair_first[len(pair_first) // 2]}, {pair_first}')
    exp = 0.0
    for d in dlist:
        L = max(d['pre'], d['post'])
        p = sum(1 for dl in delays if dl <= L) / n if n else float('nan')
        exp += p
        print(f"  seed {d['seed']} tid {d['tid']}: longest apart stretch {L} frames; share of the other targets "
              f"confirmed within {L} frames of their start {p:.2f}")
    print(f'expected detections of the (d) targets at the other targets\' rate over their longest apart stretch: {exp:.1f}')


if __name__ == '__main__':
    main()
