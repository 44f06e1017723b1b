#!/usr/bin/env python3
"""Why the injected targets of a traced IR run are missed, stage by stage, with the shipped
report rule replayed per track layer (docs/results/ir_clutter.md, "Branch irmiss,
the second"). Reads the traces of `pft eval --trace DIR` (docs/host_tools.md) and the same
runs' summary.json; several NAME=TRACE_DIR,SUMMARY pairs are pooled (e.g. two manager seeds).

  ir_miss_why.py TRACE_DIR,SUMMARY [TRACE_DIR,SUMMARY ...] [--hold 7 --spread-px 0.4
      --spread-hold 2 --spread-exist 0.99] [--list]

Each missed injected target gets ONE category, the first that applies, in this order:
  shared      a reported track within 3 px of it in some frame, which the evaluation (one
              track per target and frame, nearest first) gave to another target;
  late        a track layer that was within 3 px of it is reported, but never while within
              3 px of it (split: the report starts after the target's last frame / before);
  layer:*     a track layer within 3 px of it in some frame (layers.csv, the distance to this
              target), none reported there. The furthest step of the scene-motion test that
              any of its layers reached on a frame within 3 px of the target (replayed,
              docs/algorithms.md 9.11): hold (passed the gate and the line fit, too few
              passes: the passes it had, and on how many of them the frame was compact but
              below the existence bound / wider than the spread bound) > fit (the straight-line
              fit failed; hold:exist_bound / hold:wide when some pass was compact but below the
              bound / wide, hold:compact when every pass took the short hold) > short (fewer than n + 1 positions and no early report) > clutter
              (the gate found it moving with the scene: CLUTTER, the clutter map raised) >
              not_fed (tentative); with the way that layer ended (existence below theta_end,
              the disappearance test, alive at the run's end, ...);
  no_layer:*  no track layer ever within 3 px: hypothesis (>= 50 % of the search layer's live
              particles within 3 px in some frame, never handed over) / weak (the matched
              residual after the clutter map below 2 local robust sd on most frames) / strong
              (not weak, no hypothesis). For these also: the stage residual (before the clutter
              map) not weak on most frames while the map's output is ("map_ate").
Besides the category, every target (missed and detected) gets: the image index ((seed - 1)
mod 29) and its kind (ir_sky_kinds.csv), its speed against the scene (mean frame velocity plus
the platform's drift), frames present, first frame, entry border, the least distance to the
image border over its life, whether it is one of the run's crossing pair (the two injected
targets of largest id). Python 3 only (no numpy). Not a test.
"""
import argparse
import collections
import csv
import json
import math
import os

import statistics

HERE = os.path.dirname(os.path.abspath(__file__))
W, H = 384, 288


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def fnum(v):
    return float(v) if v not in ('', None) else float('nan')


def fit_rms(pts):
    m = len(pts)
    if m < 3:
        return 0.0
    t = [i - (m - 1) / 2.0 for i in range(m)]
    tt = sum(u * u for u in t)
    ss = 0.0
    for c in range(2):
        v = [p[c] for p in pts]
        mv = sum(v) / m
        b = sum(u * w for u, w in zip(t, v)) / tt
        ss += sum((w - mv - b * u) ** 2 for u, w in zip(t, v))
    return math.sqrt(ss / m)


def replay(rows, R):
    """one layer's rows sorted by frame: sets r['step'] on each (the scene-motion test's step)"""
    mm = R.frames + 1
    hist = []
    clutter = False
    passed = 0
    for r in rows:
        dec = int(r['scene_dec'])
        r['passes'] = passed
        if dec < 0:
            r['step'] = 'not_fed'
            continue
        hist.append((float(r['rx']), float(r['ry']), float(r['scene_x']), float(r['scene_y'])))
        if len(hist) > mm:
            hist.pop(0)
        k = len(hist)
        if not clutter and k == mm:
            dx = (hist[-1][0] - hist[0][0]) - (hist[-1][2] - hist[0][2])
            dy = (hist[-1][1] - hist[0][1]) - (hist[-1][3] - hist[0][3])
            if math.hypot(dx, dy) < R.frames * R.gate:
                clutter = True
        if clutter or dec == 2:
            r['step'] = 'clutter'
            continue
        early = False
        if R.early > 0 and 4 <= k < mm:
            dx = (hist[-1][0] - hist[-4][0]) - (hist[-1][2] - hist[-4][2])
            dy = (hist[-1][1] - hist[-4][1]) - (hist[-1][3] - hist[-4][3])
            early = math.hypot(dx, dy) >= 3 * R.early
        if not (k >= mm or early):
            r['step'] = 'short'
            continue
        if R.fit > 0 and fit_rms([(h[0], h[1]) for h in hist]) > R.fit:
            r['step'] = 'fit'
            continue
        passed += 1
        r['passes'] = passed
        sp = math.sqrt(max(0.0, float(r['cov_xx']) + float(r['cov_yy'])))
        compact = R.spread_px > 0 and sp <= R.spread_px
        r['compact'] = compact
        r['exist_ok'] = (R.spread_exist <= 0 or float(r['p_exist']) >= R.spread_exist)
        need = R.spread_hold if (compact and r['exist_ok']) else R.hold
        r['step'] = 'report' if passed >= need else 'hold'
    return rows


RANK = {'report': 6, 'hold': 5, 'fit': 4, 'short': 3, 'clutter': 2, 'not_fed': 1}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('runs', nargs='+', help='TRACE_DIR,SUMMARY_JSON')
    ap.add_argument('--kinds', default=os.path.join(HERE, 'ir_sky_kinds.csv'))
    ap.add_argument('--frames', type=int, default=5)
    ap.add_argument('--gate', type=float, default=0.15)
    ap.add_argument('--fit', type=float, default=0.2)
    ap.add_argument('--early', type=float, default=0.5)
    ap.add_argument('--hold', type=int, default=7)
    ap.add_argument('--spread-px', type=float, default=0.4)
    ap.add_argument('--spread-hold', type=int, default=2)
    ap.add_argument('--spread-exist', type=float, default=0.99)
    ap.add_argument('--drift', default='0.3,0.1')
    ap.add_argument('--theta1', type=float, default=0.6, help='the search layer\'s hand-over threshold (preset recommended)')
    ap.add_argument('--list', action='store_true')
    ap.add_argument('--csv', help='one row per injected target')
    R = ap.parse_args()
    drift = [float(v) for v in R.drift.split(',')]
    kinds_rows = read_csv(R.kinds)
    kinds = {r['file']: r['kind'] for r in kinds_rows}
    images = sorted(kinds)  # run i takes image (i - 1) mod count of the folder's sorted files
    agree = collections.Counter()
    out = []
    for spec in R.runs:
        trace, summary = spec.split(',')
        summ = json.load(open(summary))
        for run in summ['per_run']:
            seed = run['seed']
            img = os.path.basename(run.get('background', '')) or images[(seed - 1) % len(images)]
            kind = kinds.get(img, '?')
            tg = collections.defaultdict(dict)  # tid -> frame -> row
            for r in read_csv(os.path.join(trace, f's{seed}_targets.csv')):
                tg[int(r['tid'])][int(r['frame'])] = r
            layers = collections.defaultdict(list)
            for r in read_csv(os.path.join(trace, f's{seed}_layers.csv')):
                layers[int(r['id'])].append(r)
            tracks = {int(r['id']): r for r in read_csv(os.path.join(trace, f's{seed}_tracks.csv'))}
            for lid, rows in layers.items():
                rows.sort(key=lambda r: int(r['frame']))
                replay(rows, R)
                for r in rows:
                    agree[(r['step'] == 'report', r['reported'] == '1')] += 1
            inj = sorted((t for t in run['targets'] if t['kind'] == 'injected'), key=lambda t: t['id'])
            pair_ids = {t['id'] for t in inj[-2:]}
            # reported tracks per frame: to find who took a target's shared report
            for t in inj:
                tid = t['id']
                fr = tg.get(tid, {})
                frames = sorted(fr)
                xs = [float(fr[k]['x']) for k in frames]
                ys = [float(fr[k]['y']) for k in frames]
                n = max(1, len(frames) - 1)
                sp = math.hypot((xs[-1] - xs[0]) / n + drift[0], (ys[-1] - ys[0]) / n + drift[1]) if len(frames) > 1 else float('nan')
                bd = min(min(x, y, W - 1 - x, H - 1 - y) for x, y in zip(xs, ys)) if frames else float('nan')
                # the layers within 3 px of the target, per frame
                on = collections.defaultdict(list)  # lid -> rows within 3 px
                for lid, rows in layers.items():
                    for r in rows:
                        k = int(r['frame'])
                        if k in fr and math.hypot(float(r['x']) - float(fr[k]['x']), float(r['y']) - float(fr[k]['y'])) <= 3.0:
                            on[lid].append(r)
                # residual strength per frame after and before the clutter map
                z, zs, share = [], [], []
                for k in frames:
                    if k <= 1:
                        continue
                    r = fr[k]
                    sd, sds = fnum(r['loc_sd']), fnum(r['loc_sd_stage'])
                    if sd > 0:
                        z.append((fnum(r['mf_at']) - fnum(r['loc_med'])) / sd)
                    if sds > 0:
                        zs.append((fnum(r['mf_stage']) - fnum(r['loc_med_stage'])) / sds)
                    al = int(r['alive'])
                    share.append(int(r['alive_near']) / al if al else 0.0)
                weak = (sum(v < 2.0 for v in z) > len(z) / 2) if z else True
                weak_stage = (sum(v < 2.0 for v in zs) > len(zs) / 2) if zs else True
                zmed = statistics.median(z) if z else float('nan')
                # the clock: the first frame a layer is within 3 px of it, the first frame such a
                # layer is fed to the test, passes it (replayed), and the first report on it
                on_fr = sorted(int(r['frame']) for rows in on.values() for r in rows)
                pass_fr = sorted(int(r['frame']) for rows in on.values() for r in rows if r['step'] in ('hold', 'report'))
                t_on = on_fr[0] if on_fr else None
                t_pass = pass_fr[0] if pass_fr else None
                t_rep = t['first_frame'] + t['appearance_delay'] if t['detected'] else None
                # the search layer's existence probability on the frames before that first layer
                p_before = [fnum(fr[t_on - d]['search_p']) if t_on is not None and (t_on - d) in fr else None
                            for d in (1, 2)]
                run_hi = 0
                if t_on is not None:
                    k = t_on - 1
                    while k in fr and fnum(fr[k]['search_p']) >= R.theta1:
                        run_hi += 1
                        k -= 1
                c, sub, detail = '', '', ''
                if t['detected']:
                    c = 'detected'
                else:
                    rep_on = [r for rows in on.values() for r in rows if r['reported'] == '1']
                    rep_lids = {lid for lid in on if any(r['reported'] == '1' for r in layers[lid])}
                    if rep_on:
                        c = 'shared'
                    elif rep_lids:
                        c = 'late'
                        firsts = [min(int(r['frame']) for r in layers[l] if r['reported'] == '1') for l in rep_lids]
                        sub = 'after_target_left' if min(firsts) > frames[-1] else 'off_target_while_reported'
                    elif on:
                        best, bl = None, None
                        for lid, rows in on.items():
                            for r in rows:
                                if best is None or RANK[r['step']] > RANK[best['step']] or (
                                        RANK[r['step']] == RANK[best['step']] and r.get('passes', 0) > best.get('passes', 0)):
                                    best, bl = r, lid
                        c = 'layer'
                        sub = best['step']
                        tr = tracks.get(bl, {})
                        end = tr.get('reason', '') or 'alive_at_end'
                        onr = on[bl]
                        if sub == 'hold':
                            # the passes on this layer: compact frames below the existence bound, wide frames
                            ps = [r for r in layers[bl] if r['step'] in ('hold', 'report')]
                            nb = sum(1 for r in ps if r.get('compact') and not r.get('exist_ok'))
                            nw = sum(1 for r in ps if not r.get('compact'))
                            why = ('exist_bound' if nb else 'wide') if (nb or nw) else 'compact'
                            detail = f'passes {best["passes"]} (compact<bound {nb}, wide {nw})'
                            sub = f'hold:{why}'
                        sub += '|' + end
                        detail += f' layer {bl} alive {tr.get("alive")} on {len(onr)} fr, p_end {float(layers[bl][-1]["p_exist"]):.2f}'
                    else:
                        c = 'no_layer'
                        sub = ('hypothesis' if (max(share) if share else 0) >= 0.5 else
                               'weak' if weak else 'strong')
                        if weak and not weak_stage:
                            sub += '+map_ate'
                out.append(dict(seed=seed, tid=tid, img=(seed - 1) % 29, kind=kind, cat=c, sub=sub,
                                detail=detail, speed=sp, present=t['present_frames'], first=t['first_frame'],
                                last=t['last_frame'], entry=t.get('entry', ''), border=bd,
                                pair=tid in pair_ids, zmed=zmed, weak=weak, weak_stage=weak_stage,
                                t_on=t_on, t_pass=t_pass, t_rep=t_rep, p_before=p_before, run_hi=run_hi))
    tot = sum(agree.values())
    print(f'replay against the trace\'s reported column: {agree[(True, True)] + agree[(False, False)]} of {tot} '
          f'layer-frames agree (replay report / trace not: {agree[(True, False)]}, trace report / replay not: {agree[(False, True)]})')
    inj = len(out)
    miss = [o for o in out if o['cat'] != 'detected']
    det = [o for o in out if o['cat'] == 'detected']
    print(f'{inj} injected targets, {len(det)} detected ({100.0 * len(det) / inj:.1f} %), {len(miss)} missed')
    print('\n| category | missed | share of misses |')
    print('|---|---|---|')
    cc = collections.Counter(o['cat'] + (':' + o['sub'] if o['sub'] else '') for o in miss)
    for k, v in sorted(cc.items(), key=lambda kv: -kv[1]):
        print(f'| {k} | {v} | {100.0 * v / len(miss):.1f} % |')
    top = collections.Counter(o['cat'] + (':' + o['sub'].split('|')[0] if o['cat'] == 'layer' else '') for o in miss)
    print('\n| category (coarse) | missed | share |')
    print('|---|---|---|')
    for k, v in sorted(top.items(), key=lambda kv: -kv[1]):
        print(f'| {k} | {v} | {100.0 * v / len(miss):.1f} % |')

    def table(name, key, bins):
        print(f'\n| {name} | targets | detected | missed | miss rate | share of misses |')
        print('|---|---|---|---|---|---|')
        for lab, f in bins:
            a = [o for o in out if f(key(o))]
            m = [o for o in a if o['cat'] != 'detected']
            if a:
                print(f'| {lab} | {len(a)} | {len(a) - len(m)} | {len(m)} | {100.0 * len(m) / len(a):.1f} % | '
                      f'{100.0 * len(m) / len(miss):.1f} % |')

    table('speed vs scene, px/frame', lambda o: o['speed'],
          [('< 0.3', lambda v: v < 0.3), ('0.3-0.6', lambda v: 0.3 <= v < 0.6), ('0.6-1.0', lambda v: 0.6 <= v < 1.0),
           ('>= 1.0', lambda v: v >= 1.0)])
    table('frames present', lambda o: o['present'],
          [('< 25', lambda v: v < 25), ('25-49', lambda v: 25 <= v < 50), ('50-79', lambda v: 50 <= v < 80),
           ('>= 80', lambda v: v >= 80)])
    table('first frame', lambda o: o['first'],
          [('1', lambda v: v == 1), ('2-50', lambda v: 2 <= v <= 50), ('51-75', lambda v: 51 <= v <= 75),
           ('76-100', lambda v: v > 75)])
    table('least distance to the border, px', lambda o: o['border'],
          [('< 2', lambda v: v < 2), ('2-10', lambda v: 2 <= v < 10), ('>= 10', lambda v: v >= 10)])
    table('entry', lambda o: o['entry'], [(k, (lambda k: lambda v: v == k)(k)) for k in
                                          ('inside', 'left', 'right', 'top', 'bottom')])
    table('crossing pair', lambda o: o['pair'], [('pair', lambda v: v), ('other', lambda v: not v)])
    table('kind of background', lambda o: o['kind'], [(k, (lambda k: lambda v: v == k)(k)) for k in
                                                      ('clear_sky', 'cloud_edges', 'structures')])
    table('image index', lambda o: o['img'], [(str(i), (lambda i: lambda v: v == i)(i)) for i in range(29)])
    # category x attribute
    print('\n| missed: category | n | speed < 0.3 | pair | present < 25 | first > 75 | border < 10 px | weak residual | median speed |')
    print('|---|---|---|---|---|---|---|---|---|')
    for k, _ in sorted(top.items(), key=lambda kv: -kv[1]):
        m = [o for o in miss if o['cat'] + (':' + o['sub'].split('|')[0] if o['cat'] == 'layer' else '') == k]
        print(f'| {k} | {len(m)} | {sum(o["speed"] < 0.3 for o in m)} | {sum(o["pair"] for o in m)} | '
              f'{sum(o["present"] < 25 for o in m)} | {sum(o["first"] > 75 for o in m)} | '
              f'{sum(o["border"] < 10 for o in m)} | {sum(o["weak"] for o in m)} | {statistics.median([o["speed"] for o in m]):.2f} |')
    m = det
    print(f'| (detected) | {len(m)} | {sum(o["speed"] < 0.3 for o in m)} | {sum(o["pair"] for o in m)} | '
          f'{sum(o["present"] < 25 for o in m)} | {sum(o["first"] > 75 for o in m)} | '
          f'{sum(o["border"] < 10 for o in m)} | {sum(o["weak"] for o in m)} | {statistics.median([o["speed"] for o in m]):.2f} |')
    # the clock of the detected targets (frames from the target's first frame), by frames present
    print('\n| targets (frames present) | n | first frame to a layer on it | layer to its first pass | first pass to the report | first frame to the report |')
    print('|---|---|---|---|---|---|')
    med = lambda v: statistics.median(v) if v else float('nan')
    for lab, f in (('detected, < 25', lambda o: o['present'] < 25), ('detected, 25-49', lambda o: 25 <= o['present'] < 50),
                   ('detected, >= 50', lambda o: o['present'] >= 50), ('detected, all', lambda o: True)):
        m = [o for o in det if f(o) and o['t_on'] is not None and o['t_pass'] is not None]
        print(f'| {lab} | {len(m)} | {med([o["t_on"] - o["first"] for o in m]):.0f} | {med([o["t_pass"] - o["t_on"] for o in m]):.0f} | '
              f'{med([o["t_rep"] - o["t_pass"] for o in m]):.0f} | {med([o["t_rep"] - o["first"] for o in m]):.0f} |')
    m = [o for o in miss if o['t_on'] is not None]
    print(f'| missed with a layer on it | {len(m)} | {med([o["t_on"] - o["first"] for o in m]):.0f} | '
          f'{med([o["t_pass"] - o["t_on"] for o in m if o["t_pass"] is not None]):.0f} ({sum(o["t_pass"] is not None for o in m)} passed) | – | – |')
    m = [o for o in miss if o['t_on'] is None]
    print(f'| missed, no layer on it | {len(m)} | – | – | – | – |')
    m = [o for o in miss if o['present'] < 25]
    print(f'  missed with fewer than 25 frames present: {len(m)}; a layer on it {sum(o["t_on"] is not None for o in m)}, '
          f'median first frame {med([o["first"] for o in m]):.0f}, median frames present {med([o["present"] for o in m]):.0f}; '
          f'ends at the run\'s last frame {sum(o["last"] == 100 for o in m)}')
    # how the search layer's existence probability P reaches theta1 before the first layer on a target
    m = [o for o in out if o['t_on'] is not None]
    print(f'\nthe {len(m)} targets with a layer within 3 px (detected or not): P on the frames before the first such layer')
    bins = ((0.0, 0.2), (0.2, 0.4), (0.4, R.theta1), (R.theta1, 1.01))
    for d in (1, 2):
        cnt = collections.Counter()
        for o in m:
            v = o['p_before'][d - 1]
            cnt['none' if v is None else next(f'{a:.1f}-{b:.2f}' for a, b in bins if a <= v < b)] += 1
        print(f'  P at (first layer - {d}): ' + ', '.join(f'{k} {v}' for k, v in sorted(cnt.items())))
    cnt = collections.Counter(min(o['run_hi'], 4) for o in m)
    print(f'  frames in a row with P >= {R.theta1} just before the first layer (4: 4 or more): ' +
          ', '.join(f'{k}: {v}' for k, v in sorted(cnt.items())))
    if R.list:
        for o in miss:
            print('  seed %(seed)d tid %(tid)d img %(img)d %(kind)s %(cat)s:%(sub)s speed %(speed).2f present %(present)d '
                  'first %(first)d border %(border).0f pair %(pair)d z %(zmed).2f %(detail)s' % o)
    if R.csv:
        with open(R.csv, 'w', newline='') as f:
            w = csv.DictWriter(f, fieldnames=list(out[0].keys()))
            w.writeheader()
            w.writerows(out)


if __name__ == '__main__':
    main()
