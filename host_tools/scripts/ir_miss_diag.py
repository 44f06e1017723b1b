#!/usr/bin/env python3
"""Where the IR pipeline's TBD manager loses the injected targets, and what its false tracks sit
on (docs/results/ir_clutter.md, "Branch irmiss"), from the trace of `pft eval --trace DIR`
(host_tools/tbd/ir_trace.hpp) and the same run's summary.json.

  ir_miss_diag.py TRACE_DIR SUMMARY_JSON [--kinds CSV] [--ir-sky DIR] [--list]

Every injected target is put in the category of the first stage it never passed, in the
order of the pipeline (the decision rules are printed with the table):
  detected      a reported track was associated with it (the evaluation's own verdict);
  a_weak        no search-layer hypothesis on it (never >= EVID of the search layer's live
                particles within 3 px) and its residual is weak: the PSF-matched residual at
                its pixel, over the robust sd of the matched residual around it (31 x 31 less
                the 7 x 7 core), below 2 on most of its frames;
  b_no_evidence no hypothesis on it although its residual is not weak on most frames;
  b_no_handover a hypothesis on it in some frame, but no track layer ever within 3 px of it;
  c_dropped     a track layer on it (within 3 px in at least one frame), ended by the manager
                before the pipeline reported it (the end test read from the layer: existence
                probability below theta_end, the disappearance test, no live particle, ...);
  c_scene       a track layer on it never reported, but not ended early: alive at the run's
                end (too late) or longer than the scene-motion test's frames (the scene-motion
                or the straight-line test held it back);
  d_shared      a track reported within 3 px of it, which the evaluation (one track per target
                and frame, nearest first) gave to another target: the two targets of a crossing
                pair under one track, the second never with a track of its own;
  d_late        a track layer on it reported, but never within 3 px of it while reported (too
                late: the target had gone, or the track had drifted off it).
Needs numpy (and PIL with --ir-sky for the false tracks' backgrounds). Not a test.
"""
import argparse
import collections
import csv
import glob
import json
import math
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
KINDS = ['clear_sky', 'cloud_edges', 'structures']
EVID = 0.5   # share of the search layer's live particles within 3 px: a hypothesis on the target
WEAK_Z = 2.0


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def near_map(s):
    """'id:frames;id:frames' -> {id: frames}"""
    return {int(a): int(b) for a, b in (p.split(':') for p in s.split(';') if p)}


def fnum(v):
    return float(v) if v not in ('', None) else float('nan')


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('trace')
    ap.add_argument('summary')
    ap.add_argument('--kinds', default=os.path.join(HERE, 'ir_sky_kinds.csv'))
    ap.add_argument('--ir-sky')
    ap.add_argument('--list', action='store_true', help='one line per target')
    ap.add_argument('--scene-frames', type=int, default=5)
    a = ap.parse_args()
    kinds = {r['file']: r['kind'] for r in read_csv(a.kinds)}
    summ = json.load(open(a.summary))
    cats = collections.OrderedDict((k, collections.Counter()) for k in
                                   ['detected', 'a_weak', 'b_no_evidence', 'b_no_handover', 'c_dropped',
                                    'c_scene', 'd_shared', 'd_late'])
    sub = collections.defaultdict(collections.Counter)
    allz = collections.defaultdict(list)
    lines = []
    ftr = []
    n_tr = 0
    slot_full = collections.Counter()
    for run in summ['per_run']:
        seed = run['seed']
        kind = kinds.get(os.path.basename(run.get('background', '')), 'procedural')
        tp = os.path.join(a.trace, f's{seed}_targets.csv')
        tk = os.path.join(a.trace, f's{seed}_tracks.csv')
        if not os.path.exists(tp):
            continue
        rows = collections.defaultdict(list)
        for r in read_csv(tp):
            rows[int(r['tid'])].append(r)
        tracks = read_csv(tk)
        n_tr += len(tracks)
        for t in run['targets']:
            if t['kind'] != 'injected':
                continue
            tid = t['id']
            rr = rows.get(tid, [])
            # residual strength per frame (frames after the first, inside the image)
            zs, share, ranks = [], [], []
            busy = 0  # frames with the search layer's P > 0.5 and under half its particles near the target
            full = 0  # frames with every track slot taken
            for r in rr:
                if int(r['frame']) <= 1:
                    continue
                sd = fnum(r['loc_sd'])
                if sd > 0:
                    zs.append((fnum(r['mf_at']) - fnum(r['loc_med'])) / sd)
                alive = int(r['alive'])
                share.append(int(r['alive_near']) / alive if alive else 0.0)
                busy += fnum(r['search_p']) > 0.5 and share[-1] < 0.5
                full += int(r['n_tracks']) >= summ.get('tracker', {}).get('max_targets', 8)
                ranks.append(int(r['rank']))
            zmed = sorted(zs)[len(zs) // 2] if zs else float('nan')
            weak = (sum(z < WEAK_Z for z in zs) > len(zs) / 2) if zs else True
            evid = max(share) if share else 0.0
            on = [tr for tr in tracks if tid in near_map(tr['near_all'])]
            rep_on = [tr for tr in on if int(tr['reported']) > 0]
            if t['detected']:
                c = 'detected'
            elif on:
                if any(tid in near_map(tr['near_rep_all']) for tr in on):
                    c = 'd_shared'  # reported within 3 px, but the evaluation gave the track to another target
                elif rep_on:
                    c = 'd_late'
                elif any(tr['reason'] not in ('',) for tr in on) and all(
                        int(tr['alive']) <= a.scene_frames or tr['reason'] != '' for tr in on) and not any(
                        tr['scene_flag'] == '1' for tr in on):
                    c = 'c_dropped'
                    for tr in on:
                        why = tr['reason'] or 'alive_at_end'
                        if tr['merged'] == '1':
                            why += '+merged'
                        sub['c_dropped'][why] += 1
                else:
                    c = 'c_scene'
                    for tr in on:
                        sub['c_scene']['scene_flag' if tr['scene_flag'] == '1' else
                                       ('short' if int(tr['alive']) <= a.scene_frames else 'line_fit_or_left')] += 1
            elif evid >= EVID:
                c = 'b_no_handover'
                # why: the search layer's P at its best frame, the slots
                best = max((r for r in rr if int(r['frame']) > 1),
                           key=lambda r: int(r['alive_near']) / max(1, int(r['alive'])))
                sub['b_no_handover']['P>0.6' if fnum(best['search_p']) > 0.6 else 'P<=0.6'] += 1
                if any(int(r['n_tracks']) >= 8 for r in rr):
                    sub['b_no_handover']['slots_full_some_frame'] += 1
            elif weak:
                c = 'a_weak'
            else:
                c = 'b_no_evidence'
            cats[c][kind] += 1
            cats[c]['all'] += 1
            allz[c].append(zmed)
            allz[c + '_rank'].append(sorted(ranks)[len(ranks) // 2] if ranks else -1)
            allz[c + '_evid'].append(evid)
            allz[c + '_b3'].append(sum(int(r['births3']) > 0 for r in rr) / max(1, len(rr)))
            allz[c + '_busy'].append(busy / max(1, len(share)))
            slot_full[c] += full
            lines.append((seed, tid, kind, c, zmed, evid, len(on), t['present_frames']))
        for tr in tracks:
            if tr['is_false'] == '1':
                ftr.append(dict(tr, kind=kind, image=run.get('background', '')))
    frames = sum(r['frames'] for r in summ['per_run'])
    n = sum(c['all'] for c in cats.values())
    print(f'{n} injected targets, {len(summ["per_run"])} runs, {frames} frames, {n_tr} track layers')
    print(f'rules: hypothesis = >= {EVID:.0%} of the search layer\'s live particles within 3 px in some frame; '
          f'weak = matched residual < {WEAK_Z} local robust sd on most frames')
    print(f'{"category":15s} {"all":>5s} ' + ' '.join(f'{k:>12s}' for k in KINDS) +
          '   median z   median rank   max hyp. share   frames with a birth <= 3 px')
    for c, cnt in cats.items():
        zz = sorted(allz[c])
        rk = sorted(allz[c + '_rank'])
        ev = sorted(allz[c + '_evid'])
        b3 = allz[c + '_b3']
        print(f'{c:15s} {cnt["all"]:5d} ' + ' '.join(f'{cnt[k]:12d}' for k in KINDS) +
              (f'   {zz[len(zz)//2]:8.2f}   {rk[len(rk)//2]:11d}   {ev[len(ev)//2]:14.2f}   {sum(b3)/len(b3):.2f}'
               if zz else ''))
    for c in cats:
        bz = sorted(allz[c + '_busy'])
        if bz:
            print(f'  {c}: search layer held elsewhere (P > 0.5, < 50 % of it within 3 px) in a median '
                  f'{bz[len(bz) // 2]:.2f} of the frames; frames with every track slot taken: {slot_full[c]}')
    for c, s in sub.items():
        print(f'  {c}: ' + ', '.join(f'{k} {v}' for k, v in s.most_common()))
    # the residual strength of every injected target, by detection
    for c in cats:
        zz = [z for z in allz[c] if z == z]
        if zz:
            print(f'  {c}: median z < 2 on {sum(z < 2 for z in zz)} of {len(zz)}, < 1 on {sum(z < 1 for z in zz)}')
    if a.list:
        for l in lines:
            print('  seed %d tid %d %-12s %-14s z %.2f hyp %.2f tracks on it %d frames %d' % l)
    # false tracks
    print(f'\nfalse tracks: {len(ftr)} ({1000.0 * len(ftr) / frames:.1f} per 1000 frames)')
    fc = collections.Counter()
    fk = collections.defaultdict(collections.Counter)
    bg = {}
    if a.ir_sky:
        import numpy as np
        from PIL import Image
        from scipy import ndimage
    for tr in ftr:
        x, y = fnum(tr['false_x']), fnum(tr['false_y'])
        life = max(1, int(tr['alive']))
        mvx = (fnum(tr['lx']) - fnum(tr['hx'])) - fnum(tr['scene_dx'])
        mvy = (fnum(tr['ly']) - fnum(tr['hy'])) - fnum(tr['scene_dy'])
        speed = math.hypot(mvx, mvy) / life
        if near_map(tr['near_all']):
            c = 'on_a_truth_point (duplicate or offset)'
        elif x < 8 or y < 8 or x > 384 - 9 or y > 288 - 9:
            c = 'image_border (8 px)'
        elif a.ir_sky:
            img = bg.get(tr['image'])
            if img is None:
                im = np.asarray(Image.open(os.path.join(a.ir_sky, os.path.basename(tr['image']))).convert('L'),
                                dtype=float)
                b11 = ndimage.uniform_filter(im, 11, mode='reflect') * 121.0
                b5 = ndimage.uniform_filter(im, 5, mode='reflect') * 25.0
                img = bg[tr['image']] = np.abs(im - (b11 - b5) / 96.0)
            sx, sy = fnum(tr['false_scene_x']), fnum(tr['false_scene_y'])
            h, w = img.shape
            xi = min(max(int(round(sx)), 0), w - 1)
            yi = min(max(int(round(sy)), 0), h - 1)
            v = img[max(0, yi - 3):yi + 4, max(0, xi - 3):xi + 4].max()
            c = ('structure (|local residual| > 40 grey levels within 3 px)' if v > 40 else
                 'cloud texture (> 4)' if v > 4 else 'smooth sky (<= 4)')
        else:
            c = 'elsewhere'
        fc[c] += 1
        fk[c][tr['kind']] += 1
        fk[c]['slow'] += speed < 0.3
    print(f'{"sits on":60s} {"all":>4s} ' + ' '.join(f'{k:>12s}' for k in KINDS) + '  moving < 0.3 px/fr vs scene')
    for c, v in fc.most_common():
        print(f'{c:60s} {v:4d} ' + ' '.join(f'{fk[c][k]:12d}' for k in KINDS) + f'  {fk[c]["slow"]:5d}')


if __name__ == '__main__':
    main()
