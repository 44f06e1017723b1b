#!/usr/bin/env python3
"""Where the procedural scenario's missed targets are (docs/results/ir_clutter.md, section "Branch
irproc"): the region of the built-in procedural scene each injected target crosses, and a table of
the missed targets by cause (host_tools/scripts/ir_miss_diag.py --list) and region, with the
targets' life against the delay to the first report. Not a test.

  ir_proc_regions.py regions --pft PFT --scenario S --seeds A-B --out REGIONS.json [--work DIR]
  ir_proc_regions.py table SUMMARY_JSON MISS_LIST REGIONS.json

regions: per seed, `pft sim --format raw` of the scenario and of the same scenario with
background.cloud_cover 0 (the generator draws the same numbers: the same ridge, structures,
cloud field and targets; only the clouds' threshold changes, which the script checks on the two
truth.csv). Each target frame is classified on 7 x 7 pixels around its truth point, both frames
smoothed by a Gaussian of 1.5 px:
  horizon_edge  the cloud-free frame crosses GROUND (5800 counts: the sky at most 0.34 of full
                scale, the ground at least 0.46 x 0.8 with the vignetting) within the 7 x 7
                (the ridge, and the structures standing on it);
  ground        the cloud-free frame above GROUND at the point;
  cloud_edge    the clouds' share (frame less cloud-free frame) spans more than 500 counts over
                the 7 x 7 (25 temporal sigmas: a soft edge of cloud_edge_px);
  cloud         the clouds' share above 200 counts at the point;
  sky           otherwise.
A target's region is the one of most of its frames; its entry edge is the border within 2 px of
its first truth point (inside when none; key "edges" of REGIONS.json, "SEED_ID": edge). Needs
numpy and scipy (/usr/bin/python3).
table: targets and detection by region, by entry edge and by life (frames present), and the
missed targets by ir_miss_diag.py's category and region, with those whose life is shorter than
the median delay to the first report of the detected targets.
"""
import argparse
import collections
import csv
import json
import os
import re
import shutil
import subprocess

GROUND = 5800.0
EDGE_SPAN = 500.0
CLOUD = 200.0
W, H = 384, 288
REGIONS = ['sky', 'cloud', 'cloud_edge', 'horizon_edge', 'ground']


def cmd_regions(a):
    import numpy as np
    from scipy import ndimage
    sc = json.load(open(a.scenario))
    clear = json.loads(json.dumps(sc))
    clear['background']['cloud_cover'] = 0
    os.makedirs(a.work, exist_ok=True)
    sca = os.path.join(a.work, 'cloud_free.json')
    json.dump(clear, open(sca, 'w'))
    lo, hi = map(int, a.seeds.split('-'))
    frames = sc['frames']
    res = {'edges': {}}
    for seed in range(lo, hi + 1):
        dirs = []
        for tag, s in (('f', a.scenario), ('a', sca)):
            d = os.path.join(a.work, 'sim_' + tag)
            shutil.rmtree(d, ignore_errors=True)
            subprocess.run([a.pft, 'sim', '--scenario', s, '--seed', str(seed), '--format', 'raw', '--out', d, '-q'],
                           check=True)
            dirs.append(d)
        if open(dirs[0] + '/truth.csv').read() != open(dirs[1] + '/truth.csv').read():
            raise SystemExit('seed %d: the cloud-free scene has other targets' % seed)
        fr = np.memmap(dirs[0] + '/frames.u16', dtype='<u2', mode='r').reshape(frames, H, W)
        fa = np.memmap(dirs[1] + '/frames.u16', dtype='<u2', mode='r').reshape(frames, H, W)
        per = collections.defaultdict(list)
        for r in csv.DictReader(open(dirs[0] + '/truth.csv')):
            if r['kind'] != 'injected':
                continue
            f = int(r['frame'])
            key = '%d_%s' % (seed, r['id'])
            if key not in res['edges']:
                x, y = float(r['x']), float(r['y'])
                res['edges'][key] = ('bottom' if y >= H - 2 else 'top' if y <= 1 else 'left' if x <= 1 else
                                     'right' if x >= W - 2 else 'inside')
            xi, yi = int(round(float(r['x']))), int(round(float(r['y'])))
            if not (0 <= xi < W and 0 <= yi < H):
                continue
            x0, x1, y0, y1 = max(0, xi - 8), min(W, xi + 9), max(0, yi - 8), min(H, yi + 9)
            pf = ndimage.gaussian_filter(fr[f - 1, y0:y1, x0:x1].astype(float), 1.5)
            pa = ndimage.gaussian_filter(fa[f - 1, y0:y1, x0:x1].astype(float), 1.5)
            cx, cy = xi - x0, yi - y0
            na = pa[max(0, cy - 3):cy + 4, max(0, cx - 3):cx + 4]
            nf = pf[max(0, cy - 3):cy + 4, max(0, cx - 3):cx + 4]
            if na.max() > GROUND >= na.min():
                reg = 'horizon_edge'
            elif pa[cy, cx] > GROUND:
                reg = 'ground'
            else:
                c = nf - na
                if c.max() - c.min() > EDGE_SPAN:
                    reg = 'cloud_edge'
                elif c[min(cy, 3), min(cx, 3)] > CLOUD:
                    reg = 'cloud'
                else:
                    reg = 'sky'
            per[int(r['id'])].append(reg)
        res[seed] = dict(per)
        print('seed', seed, {t: collections.Counter(v).most_common(1)[0] for t, v in per.items()}, flush=True)
    json.dump(res, open(a.out, 'w'))


def cmd_table(a):
    summ = json.load(open(a.summary))
    regs = json.load(open(a.regions))
    cat = {}
    for line in open(a.miss_list):
        m = re.match(r'\s+seed (\d+) tid (\d+) (\S+)\s+(\S+)\s+z', line)
        if m:
            cat[(int(m.group(1)), int(m.group(2)))] = m.group(4)
    rows = []
    for run in summ['per_run']:
        for t in run['targets']:
            if t['kind'] != 'injected':
                continue
            rr = regs[str(run['seed'])].get(str(t['id']), [])
            maj = collections.Counter(rr).most_common(1)[0][0] if rr else 'outside'
            rows.append(dict(det=t['detected'], delay=t['appearance_delay'], life=t['present_frames'],
                             region=maj, cat=cat.get((run['seed'], t['id']), '?'),
                             edge=regs.get('edges', {}).get('%d_%d' % (run['seed'], t['id']), '?')))
    dl = sorted(r['delay'] for r in rows if r['det'])
    med = dl[len(dl) // 2]
    print('%d targets, %d detected; delay to the first report of the detected: median %d frames' % (
        len(rows), sum(r['det'] for r in rows), med))
    print('\n| region (most frames) | targets | detected | share |\n|---|---|---|---|')
    for g in REGIONS + ['outside']:
        s = [r for r in rows if r['region'] == g]
        if s:
            n = sum(r['det'] for r in s)
            print('| %s | %d | %d | %.1f %% |' % (g, len(s), n, 100.0 * n / len(s)))
    print('\n| entry edge | targets | detected | share | median life |\n|---|---|---|---|---|')
    for g in ['inside', 'top', 'bottom', 'left', 'right', '?']:
        s = [r for r in rows if r['edge'] == g]
        if s:
            n = sum(r['det'] for r in s)
            lf = sorted(r['life'] for r in s)
            print('| %s | %d | %d | %.1f %% | %d |' % (g, len(s), n, 100.0 * n / len(s), lf[len(lf) // 2]))
    print('\n| life, frames | targets | detected | share |\n|---|---|---|---|')
    for lo, hi in ((15, 24), (25, 34), (35, 49), (50, 74), (75, 100)):
        s = [r for r in rows if lo <= r['life'] <= hi]
        if s:
            n = sum(r['det'] for r in s)
            print('| %d–%d | %d | %d | %.1f %% |' % (lo, hi, len(s), n, 100.0 * n / len(s)))
    print('\n| cause | ' + ' | '.join(REGIONS) + ' | life < %d | all |' % med)
    print('|---' * (len(REGIONS) + 3) + '|')
    groups = [(c, [r for r in rows if not r['det'] and r['cat'] == c]) for c in
              ['a_weak', 'b_no_evidence', 'b_no_handover', 'c_dropped', 'c_scene', 'd_shared', 'd_late', '?']]
    groups.append(('all missed', [r for r in rows if not r['det']]))
    groups.append(('detected', [r for r in rows if r['det']]))
    for c, s in groups:
        if s:
            print('| %s | ' % c + ' | '.join(str(sum(r['region'] == g for r in s)) for g in REGIONS) +
                  ' | %d | %d |' % (sum(r['life'] < med for r in s), len(s)))


def main():
    ap = argparse.ArgumentParser()
    sub = ap.add_subparsers(dest='cmd', required=True)
    p = sub.add_parser('regions')
    p.add_argument('--pft', required=True)
    p.add_argument('--scenario', required=True)
    p.add_argument('--seeds', required=True)
    p.add_argument('--out', required=True)
    p.add_argument('--work', default='out/ir_proc_regions')
    p = sub.add_parser('table')
    p.add_argument('summary')
    p.add_argument('miss_list')
    p.add_argument('regions')
    a = ap.parse_args()
    cmd_regions(a) if a.cmd == 'regions' else cmd_table(a)


if __name__ == '__main__':
    main()
