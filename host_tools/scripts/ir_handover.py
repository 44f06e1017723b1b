#!/usr/bin/env python3
"""Why a search layer that held a target never handed it over (docs/results/ir_clutter.md,
"Branch irhand30"): for the missed targets that ir_m2_miss.py puts in its no_handover group, and
for a comparison group of detected targets, the frames a search layer held the target and that
layer's existence probability over them, read from `pft eval --trace DIR` folders made since
branch irtrace3 (targets.csv: search_layer, search_p, search_p_max, alive, alive_near, above;
tracks.csv: handover, hx, hy, handover_layer).

  ir_handover.py SUMMARY_JSON:TRACE_DIR [SUMMARY_JSON:TRACE_DIR ...] [--theta1 P] [--frames]

Held: in a frame (a truth row of targets.csv), >= 50 % of the live particles of the search
layer whose estimate is nearest to the target lie within 3 px of it (ir_m2_miss.py's rule). The
trace's rows are written after the frame's update, so a layer that hands over at frame k shows no
live particle at k. The hand-over rule replayed (docs/algorithms.md 2.14, theta1 0.6 and
confirm_frames 2 as the shipped file leaves them): a layer hands over at the second frame in a row
with P > theta1, the largest P of the layers whose count is reached, one per frame.

Reason for a no_handover miss (the first that holds, in this order):
  handover_off     the holding layer handed over at a held frame or the next one, but the new
                   track was placed more than 3 px from the target (tracks.csv hx, hy);
  barred           the holding layer's count reached confirm_frames on a held frame and another
                   layer (larger P) handed over instead;
  last_frame_only  held only at the run's last frame (a count of 2 cannot be reached);
  single_frames    P > theta1 on some held frame, never on two held frames in a row;
  below_theta1     P never above theta1 on a held frame.
Noted besides: the holding layer handing over a spot farther than 3 px from the target within 2
frames after a held frame (its mass moved to another spot while its count ran on), the largest
n_tracks on held frames (max_targets bars a hand-over at 8), frames of the run left after the
first held frame. Comparison group (the detected targets that entered at the right or bottom
border with <= 40 frames in view): frames from the first held frame to the hand-over of the first
track layer within 3 px of the target (tracks.csv near_all), per target and as quartiles.
--frames prints every held frame. Not a test.
"""
import collections
import csv
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import ir_m2_miss  # noqa: E402

THETA1 = 0.6


def held_rows(rows):
    out = []
    for r in rows:
        a, n = int(r['alive']), int(r['alive_near'])
        if a and n / a >= 0.5:
            out.append(r)
    return out


def runs_of(frames):
    """'a-b,c' of a sorted list of frames."""
    s, out = None, []
    for f in frames + [None]:
        if s is not None and (f is None or f != e + 1):
            out.append(f'{s}' if s == e else f'{s}-{e}')
            s = None
        if f is None:
            break
        if s is None:
            s = f
        e = f
    return ','.join(out)


def load(trace, seed):
    t = collections.defaultdict(list)
    for r in ir_m2_miss.read_csv(os.path.join(trace, f's{seed}_targets.csv')):
        t[int(r['tid'])].append(r)
    for v in t.values():
        v.sort(key=lambda r: int(r['frame']))
    tracks = ir_m2_miss.read_csv(os.path.join(trace, f's{seed}_tracks.csv'))
    return t, tracks


def pos_at(rows, f):
    for r in rows:
        if int(r['frame']) == f:
            return float(r['x']), float(r['y'])
    return None


def miss_row(d, rows, tracks, nframes, theta1):
    hr = held_rows(rows)
    hf = [int(r['frame']) for r in hr]
    ps = [float(r['search_p']) for r in hr]
    pm = [float(r['search_p_max']) for r in hr if r['search_p_max'] != '']
    ab = [int(r['above']) for r in hr]
    # hand-overs from a holding layer at a held frame or within 2 frames after one
    hos = []
    for r in hr:
        f, lay = int(r['frame']), r['search_layer']
        for t in tracks:
            k = int(t['handover'])
            if t['handover_layer'] == lay and f <= k <= f + 2:
                p = pos_at(rows, k)
                dist = ((float(t['hx']) - p[0]) ** 2 + (float(t['hy']) - p[1]) ** 2) ** 0.5 if p else float('nan')
                hos.append((k, int(lay), dist, int(t['id']), k - f))
    hos = sorted(set(hos))
    # barred: a held frame whose layer's count reached 2 (above >= 2), a hand-over from another layer
    barred = []
    for r in hr:
        if int(r['above']) >= 2:
            f = int(r['frame'])
            other = [t for t in tracks if int(t['handover']) == f and t['handover_layer'] != r['search_layer']]
            barred.append((f, [int(t['handover_layer']) if t['handover_layer'] not in ('', '-1') else -1 for t in other]))
    # P > theta1 on two held frames in a row (the count of the nearest layer: 'above')
    # the holding layer at the frame after the last held one (not held there): its count and P,
    # and whether another layer handed over at that frame
    after = None
    if hr:
        f1, lay = int(hr[-1]['frame']) + 1, hr[-1]['search_layer']
        nxt = [r for r in rows if int(r['frame']) == f1]
        if nxt and nxt[0]['search_layer'] == lay and int(nxt[0]['above']) >= 2:
            other = [t['handover_layer'] for t in tracks if int(t['handover']) == f1 and t['handover_layer'] != lay]
            after = (f1, lay, float(nxt[0]['search_p']), int(nxt[0]['alive_near']), int(nxt[0]['alive']), other)
    close_off = [h for h in hos if h[4] <= 1 and h[2] > 3.0 and h[2] <= 10.0]
    if close_off:
        reason = 'handover_off'
    elif barred:
        reason = 'barred'
    elif hf == [nframes]:
        reason = 'last_frame_only'
    elif any(p > theta1 for p in ps):
        reason = 'single_frames'
    else:
        reason = 'below_theta1'
    jumped = [h for h in hos if h[2] > 10.0]
    return dict(held=hf, ps=ps, pmax=max(pm) if pm else float('nan'), above=max(ab) if ab else 0,
                layers=sorted({int(r['search_layer']) for r in hr}), hos=hos, jumped=jumped, barred=barred,
                ntr=max(int(r['n_tracks']) for r in hr) if hr else 0, reason=reason,
                trk=min((float(r['trk_d']) for r in hr if r['trk_d'] != ''), default=float('nan')),
                first=int(rows[0]['frame']) if rows else 0, last=int(rows[-1]['frame']) if rows else 0,
                left=int(rows[-1]['frame']) - hf[0] + 1 if hf else 0, nframes=nframes, after=after)


def main(argv):
    if not argv or any(a in ('-h', '--help') for a in argv):
        print(__doc__)
        return
    theta1 = THETA1
    if '--theta1' in argv:
        theta1 = float(argv[argv.index('--theta1') + 1])
    show = '--frames' in argv
    pairs = [a for a in argv if ':' in a]
    miss, comp = [], []
    for a in pairs:
        s, tr = a.split(':', 1)
        S = json.load(open(s))
        nframes = S['frames']
        res = ir_m2_miss.analyse(s, tr)
        tag = os.path.basename(os.path.dirname(s))
        ff = {(run['seed'], t['id']): t['first_frame'] for run in S['per_run'] for t in run['targets']}
        cache = {}
        for d in res:
            if d['seed'] not in cache:
                cache[d['seed']] = load(tr, d['seed'])
            trows, tracks = cache[d['seed']]
            rows = trows.get(d['tid'], [])
            if not d['detected'] and d.get('cat') == 'no_handover':
                m = miss_row(d, rows, tracks, nframes, theta1)
                m.update(tag=tag, seed=d['seed'], tid=d['tid'], entry=d['entry'], frames=d['frames'], kind=d['kind'])
                miss.append(m)
                if show:
                    print(f"{tag} seed {d['seed']} tid {d['tid']}")
                    for r in held_rows(rows):
                        print('   frame %s layer %s P %s Pmax %s above %s near %s/%s n_tracks %s' % (
                            r['frame'], r['search_layer'], r['search_p'], r['search_p_max'] or '-', r['above'],
                            r['alive_near'], r['alive'], r['n_tracks']))
            elif d['detected'] and d['entry'] in ('right', 'bottom') and d['frames'] <= 40:
                hf = [int(r['frame']) for r in held_rows(rows)]
                on = [t for t in tracks if d['tid'] in ir_m2_miss.near_map(t['near_all'])]
                ho = min((int(t['handover']) for t in on), default=None)
                first = int(rows[0]['frame']) if rows else 0
                # the first held frame at or before the hand-over (the track's layer is cleared
                # at the hand-over, so a later held frame is another layer)
                hb = [f for f in hf if ho is None or f <= ho]
                comp.append(dict(tag=tag, seed=d['seed'], tid=d['tid'], entry=d['entry'], frames=d['frames'],
                                 first=first, last=int(rows[-1]['frame']) if rows else 0, nframes=nframes,
                                 held1=hb[0] if hb else None, ho=ho, delay=d['delay'],
                                 report=ff[(d['seed'], d['tid'])] + d['delay'] if d['delay'] is not None else None))
    print(f'no_handover misses: {len(miss)} (theta1 {theta1})\n')
    print('| # | run | seed | tid | entry | in view (frames) | held frames (nearest layer) | P on held frames | '
          'largest P within 3 px | largest count | frames in view from the first held | nearest track layer (px) | reason | noted |')
    print('|---' * 14 + '|')
    for i, m in enumerate(sorted(miss, key=lambda m: (m['reason'], m['tag'], m['seed'])), 1):
        notes = []
        for h in sorted({(h[0], h[1], round(h[2])) for h in m['hos'] if h[2] > 3.0}):
            notes.append(f'layer {h[1]} handed over {h[2]} px away at {h[0]}')
        if m['after']:
            f1, lay, p, n, a, o = m['after']
            notes.append(f'layer {lay} count 2 at {f1} (P {p:.2f}, {n}/{a} near), layer {",".join(o) or "none"} handed over')
        for f, o in m['barred']:
            notes.append(f'count 2 at {f}; layer {",".join(map(str, o)) or "none"} handed over')
        if m['ntr'] >= 8:
            notes.append('n_tracks 8')
        print(f"| {i} | {m['tag'][2:].replace('_s1', '')} | {m['seed']} | {m['tid']} | {m['entry']} | "
              f"{m['first']}-{m['last']} ({m['frames']}) | {runs_of(m['held'])} (L{'/'.join(map(str, m['layers']))}) | "
              f"{' '.join('%.2f' % p for p in m['ps'])} | {'-' if m['pmax'] != m['pmax'] else '%.2f' % m['pmax']} | {m['above']} | {m['left']} | "
              f"{m['trk']:.0f} | {m['reason']} | {'; '.join(notes)} |")
    cc = collections.Counter(m['reason'] for m in miss)
    print('\n| reason | misses | last in view at the run\'s last frame | held first in the run\'s last 6 frames |')
    print('|---|---|---|---|')
    for k in ('handover_off', 'barred', 'last_frame_only', 'single_frames', 'below_theta1'):
        sel = [m for m in miss if m['reason'] == k]
        print(f"| {k} | {cc[k]} | {sum(m['last'] >= m['nframes'] for m in sel)} | "
              f"{sum(m['nframes'] - m['held'][0] + 1 <= 6 for m in sel)} |")
    print(f"| all | {len(miss)} | {sum(m['last'] >= m['nframes'] for m in miss)} | {sum(m['nframes'] - m['held'][0] + 1 <= 6 for m in miss)} |")
    print(f"\nmisses with the holding layer handing over a spot > 10 px away within 2 frames: "
          f"{sum(bool(m['jumped']) for m in miss)}; with n_tracks 8 on a held frame: {sum(m['ntr'] >= 8 for m in miss)}")
    print(f'\ncomparison: detected, right or bottom entry, <= 40 frames in view: {len(comp)}')
    ok = [c for c in comp if c['held1'] is not None and c['ho'] is not None]
    dl = sorted(c['ho'] - c['held1'] for c in ok)
    fv = sorted(c['held1'] - c['first'] for c in ok)
    rem = sorted(c['last'] - c['ho'] + 1 for c in comp if c['ho'] is not None)
    q = lambda v: f'median {v[len(v) // 2]}, quartiles {v[len(v) // 4]} / {v[3 * len(v) // 4]}, range {v[0]}-{v[-1]} (of {len(v)})' if v else 'none'
    print(f"  held before the hand-over and a hand-over: {len(ok)}; no held frame before it: "
          f"{sum(c['held1'] is None and c['ho'] is not None for c in comp)}; no track layer found: {sum(c['ho'] is None for c in comp)}")
    print(f'  frames from the first held frame to the hand-over: {q(dl)}')
    print('  ' + ', '.join(f'{k}: {v}' for k, v in sorted(collections.Counter(dl).items())))
    print(f'  frames in view before the first held frame: {q(fv)}')
    print(f'  frames in view from the hand-over on: {q(rem)}')
    ad = sorted(c['delay'] for c in comp if c['delay'] is not None)
    hr_ = sorted(c['report'] - c['ho'] for c in comp if c['report'] is not None and c['ho'] is not None)
    print(f'  frames from the hand-over to the first frame with a reported track on it: {q(hr_)}')
    print(f'  appearance delay (the summary\'s first frame to the first frame with a track on it): {q(ad)}')
    print(f"  last in view at the run's last frame: {sum(c['last'] >= c['nframes'] for c in comp)} of {len(comp)}")
    lm = sorted(m['left'] for m in miss if m['held'])
    print(f'\nmisses: frames in view from the first held frame (itself counted): {q(lm)}')
    if hr_ and dl:
        need = min(dl) + hr_[0]
        print(f'misses with at least {need} frames in view after the first held frame (the fastest hand-over, '
              f'{min(dl)}, plus the fastest report after one, {hr_[0]}): {sum(m["left"] - 1 >= need for m in miss)}; '
              f'at the comparison medians ({dl[len(dl) // 2]} + {hr_[len(hr_) // 2]}): '
              f'{sum(m["left"] - 1 >= dl[len(dl) // 2] + hr_[len(hr_) // 2] for m in miss)}')
    fm = sorted(m['held'][0] - m['first'] for m in miss if m['held'])
    print(f'misses: frames in view before the first held frame: {q(fm)}')


if __name__ == '__main__':
    main(sys.argv[1:])
