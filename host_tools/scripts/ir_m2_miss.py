#!/usr/bin/env python3
"""Where the shipped low-false-rate block's misses are (docs/results/ir_clutter.md, "Branch
irm2miss"): every injected target of `pft eval` summaries, by frames in view, entry border,
crossing pair, background kind and speed against the scene, with what happened to the missed
ones, read from the same runs' `pft eval --trace DIR` folders.

  ir_m2_miss.py SUMMARY_JSON:TRACE_DIR [SUMMARY_JSON:TRACE_DIR ...] [--list]

What happened to a missed target (the first rule that holds, in this order):
  shared        a track reported within 3 px of it that the evaluation gave to another target
                (under its crossing partner or a neighbour);
  late          a track layer on it (within 3 px in some frame) reported, but never while within
                3 px of it;
  ended         a track layer on it, never reported, ended by the manager (tracks.csv reason:
                existence below theta_end, the disappearance test, slot reused, ...) while the
                target was still in view: the reason and the replayed state of its last frame on
                the target are counted;
  held          a track layer on it, never reported, alive until the target left (or the run
                ended): the replayed report rule's state on the layer's last frame on the target
                (7-pass hold of a wide or low-existence layer, the speed bound's 3-pass hold of a
                compact slow one, the edge hold, no pass of the line fit or early test, the
                scene gate's clutter, tentative);
  no_handover   no track layer on it, but a search layer held it (>= 50 % of its live particles
                within 3 px) in some frame;
  no_birth      neither: no birth candidate within 3 px in any frame (targets.csv births3);
  birth_only    birth candidates within 3 px in some frame, but no search layer's hypothesis.
                The search columns are the layer's nearest to the point in traces made since
                branch irtrace3; older traces read the manager's first search layer only, so with
                search_layers > 1 no_handover and birth_only are one group there ("no track
                layer", as branch irm2miss reported them).
The report rule is replayed in double precision from the layers file (algorithms.md 9.11 steps
2, 4-6 with the shipped file's values: n 5, fit 0.2 px, early 0.5 px, hold 7, short hold 2 at a
spread of at most 0.4 px and p_exist >= 0.99, speed bound 0.35 px per frame with a 3-pass hold,
edge hold 6 px / 0.2 / 0.2 on the 346 x 270 frame); its mismatches against the trace's reported
column are printed. Speed against the scene: the truth path's displacement over its frames in view
less the scene's cumulative shift over them (the layers file's scene_x/scene_y, interpolated over
frames without a layer), per frame. The crossing pair: a run's two injected targets of largest id
(host_tools/tbd/ir_sim.cpp). For ended / held the layer read is the one with the most frames
within 3 px of the target (layers.csv near_tid / near_d). Printed besides the category table: one
cause per missed target (the category, with a layer that reached the target with 6 or fewer
frames in view left, and one the gate found CLUTTER, split out), and the missed targets on which
any layer had a held pass within 3 px (passed step 2, kept from the report by the 7-pass hold,
the speed bound, the short hold or the edge hold): the most any hold rule could give back.
Not a test.
"""
import collections
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
from ir_miss_diag import near_map, read_csv  # noqa: E402  (the trace's CSV reader and near-list parser)
from ir_short_why import edge_hold, fit_ok  # noqa: E402  (steps 2 and 6 of the rule; its values: fit 0.2 px, edge 6 / 0.2 / 0.2)

W, H = 346, 270
N = 5
HOLD = 7
SH = 2
SP2 = 0.4 ** 2
PE = 0.99
EARLY = 0.5
MOVE, MOVE_HOLD = 0.35, 3


def replay(rows):
    """The report rule per fed frame of one layer: a list of dicts with 'st' in notfed,
    clutter, tentative, edge, young (fewer than n + 1 positions and no early pass), fail (the
    line fit at n + 1 positions), held7 (wide or low existence), heldmove (compact but slower
    than the speed bound), heldshort (compact, fewer than 2 passes), report."""
    hist = []
    passed = 0
    out = []
    for r in rows:
        dec = int(r['scene_dec'])
        e = dict(frame=int(r['frame']), r=r, rep=r['reported'] == '1')
        if dec < 0:
            e['st'] = 'notfed'
            out.append(e)
            continue
        hist.append((float(r['rx']), float(r['ry']), float(r['scene_x']), float(r['scene_y'])))
        if len(hist) > N + 1:
            hist.pop(0)
        var = float(r['cov_xx']) + float(r['cov_yy'])
        p = float(r['p_exist'])
        e.update(var=var, p=p)
        if dec == 2:
            e['st'] = 'clutter'
            out.append(e)
            continue
        if r['tentative'] == '1':
            e['st'] = 'tentative'
            out.append(e)
            continue
        k = len(hist)
        early = False
        if 4 <= k < N + 1:
            a, b = hist[-4], hist[-1]
            dx = (b[0] - a[0]) - (b[2] - a[2])
            dy = (b[1] - a[1]) - (b[3] - a[3])
            early = dx * dx + dy * dy >= (3 * EARLY) ** 2
        ps = (k >= N + 1 or early) and fit_ok(hist)
        a, b = hist[0], hist[-1]
        m = k - 1
        e['v'] = math.hypot((b[0] - a[0]) - (b[2] - a[2]), (b[1] - a[1]) - (b[3] - a[3])) / max(m, 1)
        if ps and edge_hold(hist):
            e['st'] = 'edge'
            out.append(e)
            continue
        if not ps:
            e['st'] = 'fail' if k >= N + 1 else 'young'
            out.append(e)
            continue
        compact = var <= SP2 and p >= PE
        fast = e['v'] >= MOVE
        passed = min(passed + 1, HOLD)
        need = (SH if fast else MOVE_HOLD) if compact else HOLD
        e['passed'] = passed
        if passed >= need:
            e['st'] = 'report'
        else:
            e['st'] = 'heldshort' if compact and fast else ('heldmove' if compact else 'held7')
        out.append(e)
    return out


def scene_track(layers, frames):
    """frame -> cumulative scene shift (x, y), interpolated over frames without a layer."""
    known = {}
    for r in layers:
        known[int(r['frame'])] = (float(r['scene_x']), float(r['scene_y']))
    ks = sorted(known)
    out = {}
    for f in range(1, frames + 1):
        if f in known:
            out[f] = known[f]
            continue
        lo = [k for k in ks if k < f]
        hi = [k for k in ks if k > f]
        if lo and hi:
            a, b = lo[-1], hi[0]
            t = (f - a) / (b - a)
            out[f] = tuple(known[a][i] + t * (known[b][i] - known[a][i]) for i in (0, 1))
        elif lo:
            a = lo[-1]
            out[f] = (known[a][0] - 0.3 * (f - a), known[a][1] - 0.1 * (f - a))
        elif hi:
            b = hi[0]
            out[f] = (known[b][0] + 0.3 * (b - f), known[b][1] + 0.1 * (b - f))
        else:
            out[f] = (-0.3 * f, -0.1 * f)
    return out


def analyse(summ_path, trace):
    kinds = {r['file']: r['kind'] for r in read_csv(os.path.join(HERE, 'ir_sky_kinds.csv'))}
    S = json.load(open(summ_path))
    res = []
    mism = tot = 0
    for run in S['per_run']:
        seed = run['seed']
        kind = kinds.get(os.path.basename(run.get('background', '')), 'procedural')
        tp = os.path.join(trace, f's{seed}_targets.csv')
        if not os.path.exists(tp):
            continue
        trows = collections.defaultdict(list)
        for r in read_csv(tp):
            trows[int(r['tid'])].append(r)
        tracks = {int(t['id']): t for t in read_csv(os.path.join(trace, f's{seed}_tracks.csv'))}
        layers = read_csv(os.path.join(trace, f's{seed}_layers.csv'))
        by = collections.defaultdict(list)
        for r in layers:
            by[int(r['id'])].append(r)
        ev = {}
        for lid, rows in by.items():
            rows.sort(key=lambda r: int(r['frame']))
            ev[lid] = replay(rows)
            for e in ev[lid]:
                if e['st'] != 'notfed':
                    tot += 1
                    mism += (e['st'] == 'report') != e['rep']
        scene = scene_track(layers, run['frames'])
        inj = sorted((t for t in run['targets'] if t['kind'] == 'injected'), key=lambda t: t['id'])
        pair = {t['id'] for t in inj[-2:]} if len(inj) >= 2 else set()
        for t in inj:
            tid = t['id']
            rr = sorted(trows.get(tid, []), key=lambda r: int(r['frame']))
            fr = [int(r['frame']) for r in rr]
            if len(rr) >= 2:
                a, b = rr[0], rr[-1]
                sa, sb = scene[int(a['frame'])], scene[int(b['frame'])]
                v = math.hypot((float(b['x']) - float(a['x'])) - (sb[0] - sa[0]),
                               (float(b['y']) - float(a['y'])) - (sb[1] - sa[1])) / (len(rr) - 1)
            else:
                v = float('nan')
            d = dict(seed=seed, tid=tid, kind=kind, entry=t['entry'], frames=t['present_frames'],
                     pair=tid in pair, v=v, detected=t['detected'], src=summ_path, delay=t['appearance_delay'])
            res.append(d)
            if t['detected']:
                continue
            on = [tr for tr in tracks.values() if tid in near_map(tr['near_all'])]
            last_in_view = max(fr) if fr else 0
            if any(tid in near_map(tr['near_rep_all']) for tr in on):
                c, sub = 'shared', ''
            elif any(int(tr['reported']) > 0 for tr in on):
                c, sub = 'late', ''
            elif on:
                # each layer on it: its last frame within 3 px of the target and the state there
                best = None
                d['held_pass'] = set()
                for tr in on:
                    lid = int(tr['id'])
                    es = [e for e in ev.get(lid, []) if e['r']['near_tid'] == str(tid)
                          and e['r']['near_d'] != '' and float(e['r']['near_d']) <= 3.0]
                    if not es:
                        continue
                    d['held_pass'] |= {e['st'] for e in es if e['st'] in ('held7', 'heldmove', 'heldshort', 'edge')}
                    lastf = es[-1]['frame']
                    end = int(tr['end']) if tr['end'] not in ('', '0') else 0
                    ended_on = end and end <= last_in_view and tr['reason'] not in ('',)
                    # the frame states while on the target
                    sts = collections.Counter(e['st'] for e in es)
                    cand = (len(es), lid, tr, es[-1]['st'], ended_on, sts, lastf, es[0]['frame'])
                    if best is None or cand[0] > best[0]:
                        best = cand
                if best is None:
                    c, sub = 'held', 'no replayed frame'
                else:
                    n_on, lid, tr, st, ended_on, sts, _, first_on = best
                    d['wait'] = first_on - min(fr) if fr else -1  # frames in view before the layer reached it
                    d['left'] = last_in_view - first_on + 1        # frames in view from then on
                    top = sts.most_common(1)[0][0]
                    gone = best[6] >= last_in_view - 1
                    if ended_on:
                        c, sub = 'ended', f"{tr['reason']} (last state {st})"
                    else:
                        where = 'on it to its last frame' if gone else 'layer left it'
                        c, sub = 'held', f'{st} ({where})'
                    d['on_frames'] = n_on
                    d['sts'] = dict(sts)
            else:
                evid = max((int(r['alive_near']) / int(r['alive']) if int(r['alive']) else 0.0)
                           for r in rr) if rr else 0.0
                births = sum(int(r['births3']) > 0 for r in rr)
                if evid >= 0.5:
                    c, sub = 'no_handover', ''
                elif births:
                    c, sub = 'birth_only', ''
                else:
                    c, sub = 'no_birth', ''
            d['cat'] = c
            d['sub'] = sub
    print(f'{summ_path}: replay mismatches {mism} of {tot} fed layer frames', file=sys.stderr)
    return res


def vbin(v):
    if v != v:
        return 'n/a'
    return '< 0.15' if v < 0.15 else '0.15-0.35' if v < 0.35 else '0.35-0.6' if v < 0.6 else '0.6-1.0' if v < 1.0 else '>= 1.0'


def fbin(n):
    return '<= 20' if n <= 20 else '21-40' if n <= 40 else '41-70' if n <= 70 else '> 70'


CATS = ['no_birth', 'birth_only', 'no_handover', 'ended', 'held', 'shared', 'late']


def main(argv):
    if any(a in ('-h', '--help') for a in argv):
        print(__doc__)
        return
    lst = '--list' in argv
    res = []
    for a in argv:
        if a.startswith('--'):
            continue
        if ':' not in a:
            sys.exit('ir_m2_miss.py: %r is not SUMMARY.json:TRACE_DIR\n%s' % (a, __doc__))
        s, t = a.split(':', 1)
        res += analyse(s, t)
    if not res:
        sys.exit('ir_m2_miss.py: no injected targets in the summaries given')
    miss = [d for d in res if not d['detected']]
    print(f'{len(res)} injected targets, {len(miss)} missed ({100.0 * len(miss) / len(res):.1f} %)\n')
    groups = [('frames in view', lambda d: fbin(d['frames']), ['<= 20', '21-40', '41-70', '> 70']),
              ('entry', lambda d: d['entry'], ['inside', 'left', 'top', 'bottom', 'right']),
              ('crossing pair', lambda d: 'pair' if d['pair'] else 'other', ['pair', 'other']),
              ('background', lambda d: d['kind'], ['clear_sky', 'cloud_edges', 'structures']),
              ('speed against the scene (px/frame)', lambda d: vbin(d['v']),
               ['< 0.15', '0.15-0.35', '0.35-0.6', '0.6-1.0', '>= 1.0'])]
    print('| category | targets | missed | detected | ' + ' | '.join(CATS) + ' |')
    print('|---' * (4 + len(CATS)) + '|')
    for gname, fn, keys in groups:
        for k in keys:
            sel = [d for d in res if fn(d) == k]
            if not sel:
                continue
            ms = [d for d in sel if not d['detected']]
            cc = collections.Counter(d['cat'] for d in ms)
            print(f'| {gname}: {k} | {len(sel)} | {len(ms)} | {100.0 * (1 - len(ms) / len(sel)):.1f} % | '
                  + ' | '.join(str(cc[c]) for c in CATS) + ' |')
    cc = collections.Counter(d['cat'] for d in miss)
    print(f'| all | {len(res)} | {len(miss)} | {100.0 * (1 - len(miss) / len(res)):.1f} % | '
          + ' | '.join(str(cc[c]) for c in CATS) + ' |')
    print()
    for c in CATS:
        sub = collections.Counter(d['sub'] for d in miss if d['cat'] == c and d['sub'])
        if sub:
            print(f'{c}: ' + '; '.join(f'{k} {v}' for k, v in sub.most_common()))
    # two-way: frames in view x what happened
    print('\n| frames in view | ' + ' | '.join(CATS) + ' |')
    print('|---' * (1 + len(CATS)) + '|')
    for k in ['<= 20', '21-40', '41-70', '> 70']:
        cc = collections.Counter(d['cat'] for d in miss if fbin(d['frames']) == k)
        print(f'| {k} | ' + ' | '.join(str(cc[c]) for c in CATS) + ' |')
    # the layers' time budget: a layer that reached its target with 6 frames or fewer left can be
    # reported only by the early path (4 positions and 2 passes: its 5th frame) or not at all
    print('\n| ended / held: frames in view from the layer\'s first frame on the target | ended | held |')
    print('|---|---|---|')
    for lab, f in (('<= 6', lambda x: x <= 6), ('7-15', lambda x: 7 <= x <= 15), ('> 15', lambda x: x > 15)):
        print(f'| {lab} | ' + ' | '.join(str(sum(1 for d in miss if d['cat'] == c and 'left' in d and f(d['left'])))
                                        for c in ('ended', 'held')) + ' |')
    # one cause per missed target: the category, with a layer's time budget and state split out
    def cause(d):
        c = d['cat']
        if c in ('no_birth', 'birth_only', 'no_handover'):
            return 'no track layer'
        if c in ('shared', 'late'):
            return c
        if 'left' not in d:
            return 'layer within 3 px, never the nearest layer to it'
        if d['left'] <= 6:
            return 'layer reached it with <= 6 frames in view left'
        st = d['sub'].split(' (last state ')[-1].rstrip(')') if c == 'ended' else d['sub'].split(' (')[0]
        if st == 'clutter':
            return 'layer > 6 frames, found CLUTTER by the scene gate'
        return f'layer > 6 frames, {c}, last state {st}'
    causes = collections.defaultdict(list)
    for d in miss:
        causes[cause(d)].append(d)
    print('\n| cause | missed | share | right / bottom entry | structures | <= 40 frames | crossing pair | < 0.35 px/frame |')
    print('|---' * 8 + '|')
    for k, v in sorted(causes.items(), key=lambda kv: -len(kv[1])):
        print(f'| {k} | {len(v)} | {100.0 * len(v) / len(miss):.1f} % | '
              f"{sum(d['entry'] in ('right', 'bottom') for d in v)} | {sum(d['kind'] == 'structures' for d in v)} | "
              f"{sum(d['frames'] <= 40 for d in v)} | {sum(d['pair'] for d in v)} | {sum(d['v'] < 0.35 for d in v)} |")
    # the most any hold could give back: misses with a frame, within 3 px of the target, on
    # which one of its layers passed step 2 of the test but a hold kept it from the report
    hp = [d for d in miss if d.get('held_pass')]
    print(f'\nmissed targets with a held pass within 3 px (any layer): {len(hp)}; by hold: ' +
          ', '.join(f"{k} {sum(k in d['held_pass'] for d in hp)}" for k in ('held7', 'heldmove', 'heldshort', 'edge')))
    ws = sorted(d['wait'] for d in miss if 'wait' in d and d['wait'] >= 0)
    if ws:
        print(f'frames in view before a layer reached the target (ended / held): median {ws[len(ws) // 2]}, '
              f'quartiles {ws[len(ws) // 4]} / {ws[3 * len(ws) // 4]} of {len(ws)}')
    dl = sorted(t for t in (d.get('delay') for d in res if d['detected']) if t is not None)
    if dl:
        print(f'detected targets\' delay to the first report: median {dl[len(dl) // 2]}, quartiles '
              f'{dl[len(dl) // 4]} / {dl[3 * len(dl) // 4]} of {len(dl)}')
    if lst:
        for d in miss:
            print('  %s seed %d tid %d %s %s frames %d pair %d v %.2f %s %s %s wait %s left %s' % (
                os.path.basename(os.path.dirname(d['src'])), d['seed'], d['tid'], d['kind'], d['entry'],
                d['frames'], d['pair'], d['v'], d['cat'], d['sub'], d.get('sts', ''), d.get('wait', '-'),
                d.get('left', '-')))


if __name__ == '__main__':
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1:])
