#!/usr/bin/env python3
"""The crossing pairs after they separate (docs/results/ir_clutter.md, "Branch irsplit"): for every
injected target of a crossing pair (the two injected targets of largest id of a run,
host_tools/tbd/ir_sim.cpp), what happens after the closest frame: how many frames it is in view
with the pair more than SEP px apart, whether the search layer puts a hypothesis on it, whether
it gets a track layer of its own and what the scene-motion test does with that layer, and whether
the PSF subtraction around the partner's track covers it. Reads the trace of `pft eval --trace
DIR` and the same run's summary.json.

  ir_split_diag.py TRACE_DIR SUMMARY_JSON [--sep PX] [--list] [--frames]

Rules (ir_miss_diag.py's and ir_cross_diag.py's): a hypothesis is >= 50 % of the search layer's
live particles within 3 px; the search layer is "elsewhere" when its P > 0.5 and under 50 % of its
particles are within 3 px; a layer of its own is a track layer within 3 px of the target that is
not the one nearest to the partner (within 3 px of it); "covered" is the target within 2.5 px
(Chebyshev) of the track layer nearest to its partner (the 5 x 5 window the search layer's
residual subtracts, docs/algorithms.md 2.7). The scene-motion test's decisions per frame are the
layers file's scene_dec (0 hold, 1 report, 2 clutter, -1 not fed). Not a test.
"""
import argparse
import collections
import json
import math

from ir_cross_diag import crossing_pair, pair_frames, read_csv


def fnum(v):
    return float(v) if v not in ('', None) else float('nan')


def med(v):
    v = sorted(x for x in v if x == x)
    return v[len(v) // 2] if v else float('nan')


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('trace')
    ap.add_argument('summary')
    ap.add_argument('--sep', type=float, default=3.0, help='the pair "apart": more than this (px)')
    ap.add_argument('--list', action='store_true', help='one line per missed pair target')
    ap.add_argument('--frames', action='store_true', help='with --list: one token per frame after the closest')
    a = ap.parse_args()
    summ = json.load(open(a.summary))
    out = []
    for run in summ['per_run']:
        seed = run['seed']
        pair, _ = crossing_pair(run)
        if pair is None:
            continue
        by, sep, kc = pair_frames(a.trace, seed, pair)
        if kc is None:
            continue
        lay = collections.defaultdict(dict)  # frame -> id -> layer row
        for r in read_csv(f'{a.trace}/s{seed}_layers.csv'):
            lay[int(r['frame'])][int(r['id'])] = r
        life = {int(r['id']): r for r in read_csv(f'{a.trace}/s{seed}_tracks.csv')}
        ida, idb = pair[0]['id'], pair[1]['id']
        for t in pair:
            tid = t['id']
            par = idb if tid == ida else ida

            def nearest(f, x, y):
                best, bd = None, 1e9
                for L in lay[f].values():
                    d = math.hypot(fnum(L['x']) - x, fnum(L['y']) - y)
                    if d < bd:
                        best, bd = L, d
                return best, bd

            d = dict(seed=seed, tid=tid, detected=bool(t['detected']), kc=kc, post=0, hyp=0, elsewhere=0,
                     covered=0, own=0, first_hyp=None, first_own=None, own_layers={}, z=[], rep_par=0,
                     par_layer=0, toks=[], first_apart=None, delay=t['appearance_delay'],
                     first_frame=t['first_frame'])
            for f in sorted(by):
                if f <= kc or tid not in by[f]:
                    continue
                r = by[f][tid]
                x, y = fnum(r['x']), fnum(r['y'])
                s = sep.get(f, float('inf'))
                if s <= a.sep:
                    d['toks'].append(f'{f - kc:+d}:{s:.0f}')
                    continue
                if d['first_apart'] is None:
                    d['first_apart'] = f
                d['post'] += 1
                alive = int(r['alive'])
                share = int(r['alive_near']) / alive if alive else 0.0
                hyp = share >= 0.5
                d['hyp'] += hyp
                if hyp and d['first_hyp'] is None:
                    d['first_hyp'] = f
                d['elsewhere'] += fnum(r['search_p']) > 0.5 and not hyp
                d['z'].append(fnum(r['mfsub_at']))
                p = by[f].get(par)
                pl, pd = (None, 1e9) if p is None else nearest(f, fnum(p['x']), fnum(p['y']))
                if pl is not None and pd <= 3.0:
                    d['par_layer'] += 1
                    d['rep_par'] += pl['reported'] == '1'
                    cov = max(abs(fnum(pl['x']) - x), abs(fnum(pl['y']) - y)) <= 2.5
                    d['covered'] += cov
                else:
                    cov = False
                own = None
                for L in lay[f].values():
                    if math.hypot(fnum(L['x']) - x, fnum(L['y']) - y) <= 3.0 and (pl is None or pd > 3.0 or L['id'] != pl['id']):
                        own = L
                if own is not None:
                    d['own'] += 1
                    if d['first_own'] is None:
                        d['first_own'] = f
                    d['own_layers'].setdefault(int(own['id']), []).append(int(own['scene_dec']))
                tok = f'{f - kc:+d}:{s:.0f}' + ('H' if hyp else '') + ('E' if fnum(r['search_p']) > 0.5 and not hyp else '') + \
                      ('C' if cov else '') + (f"O{own['scene_dec']}" if own is not None else '') + \
                      ('R' if r['rep_d'] != '' and fnum(r['rep_d']) <= 3.0 else '')
                d['toks'].append(tok)
            for lid in d['own_layers']:
                L = life[lid]
                d['own_layers'][lid] = (int(L['handover']) - kc, L['reason'] or 'alive_at_end', int(L['alive']),
                                        int(L['reported']), ''.join({'-1': '-', '0': 'h', '1': 'r', '2': 'c'}[str(v)]
                                                                    for v in d['own_layers'][lid]))
            out.append(d)
    n = len(out)
    det = [d for d in out if d['detected']]
    miss = [d for d in out if not d['detected']]
    print(f'pair targets {n}, detected {len(det)} ({100.0 * len(det) / max(1, n):.1f} %), missed {len(miss)}; '
          f'"apart": the pair more than {a.sep:g} px apart, after the closest frame')
    for name, grp in (('missed', miss), ('detected', det)):
        if not grp:
            continue
        post = [d['post'] for d in grp]
        print(f'\n{name} ({len(grp)}): frames in view apart after the closest frame: median {med(post)}, '
              f'0 for {sum(p == 0 for p in post)}, 1-5 for {sum(1 <= p <= 5 for p in post)}, '
              f'6-10 for {sum(6 <= p <= 10 for p in post)}, > 10 for {sum(p > 10 for p in post)}')
        ap_ = [d for d in grp if d['post'] > 0]
        print(f'  of the {len(ap_)} apart at some frame: a hypothesis on it {sum(d["hyp"] > 0 for d in ap_)}, '
              f'a layer of its own {sum(d["own"] > 0 for d in ap_)}; frames apart {sum(d["post"] for d in ap_)}: '
              f'hypothesis {sum(d["hyp"] for d in ap_)}, search layer elsewhere {sum(d["elsewhere"] for d in ap_)}, '
              f'covered by the partner\'s subtraction {sum(d["covered"] for d in ap_)}, '
              f'partner under a layer {sum(d["par_layer"] for d in ap_)} (reported {sum(d["rep_par"] for d in ap_)}), '
              f'own layer {sum(d["own"] for d in ap_)}; median matched residual at it {med(sum((d["z"] for d in ap_), [])):.2f}')
        fh = [d['first_hyp'] - d['first_apart'] for d in ap_ if d['first_hyp'] is not None]
        fo = [d['first_own'] - d['first_apart'] for d in ap_ if d['first_own'] is not None]
        print(f'  frames from the first apart frame to the first hypothesis: median {med(fh)} {sorted(fh)}')
        print(f'  to the first layer of its own: median {med(fo)} {sorted(fo)}')
        ends = collections.Counter()
        for d in ap_:
            for lid, v in d['own_layers'].items():
                held = 'c' in v[4] and 'clutter' or ('r' in v[4] and 'reported' or ('h' in v[4] and 'held' or 'not_fed'))
                ends[(v[1], held)] += 1
        print('  its own layers (end, what the scene test did while on it): ' +
              ', '.join(f'{k[0]}/{k[1]} {v}' for k, v in ends.most_common()))
    if a.list:
        print('\nseed tid  apart  hyp elsewh covered own | own layers (hand-over less closest, end, frames alive, '
              'reported, scene decisions while on it: h hold, r report, c clutter, - not fed)')
        for d in miss:
            lay_s = '; '.join(f'{lid}: {v[0]:+d} {v[1]} {v[2]} fr rep {v[3]} {v[4]}' for lid, v in d['own_layers'].items())
            print(f"{d['seed']:4d} {d['tid']:3d} {d['post']:6d} {d['hyp']:4d} {d['elsewhere']:6d} {d['covered']:7d} "
                  f"{d['own']:3d} | {lay_s}")
            if a.frames:
                print('      ' + ' '.join(d['toks']))


if __name__ == '__main__':
    main()
