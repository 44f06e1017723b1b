#!/usr/bin/env python3
"""Lines up the frames a TSA-AK run fails with the scenario's events and the tracker's state.

Usage: tsa_failed_frames.py SIM_DIR RUN_DIR [--diag DIAG_FILE] [--window W] [--all]
       tsa_failed_frames.py --partials EVAL_DIR [--tracker tsa]
  --partials: every failed frame of every run in the partial summaries of `pft eval --shard`
           (EVAL_DIR/partial_*_of_*.json): per seed the frame numbers (1-based, frame 1 is the
           start), centre error and IoU, and the totals;
  SIM_DIR: `pft sim --scenario S --seed K --out SIM_DIR` (truth.csv: per frame the truth box,
           the camera's swing velocity camera_vx, the sensor gain, the motion blur length and
           the sudden reversals taken);
  RUN_DIR: `pft run --scenario S --sequence SIM_DIR --no-video --out RUN_DIR` (tracks.csv: per
           frame the estimate's centre and box, rho, rho of the pioneer, beta, state, alive);
  --diag:  optional per-frame lines "DIAG,frame,x,y,best particle x,y,rho,local best x,y,rho,
           rho at the estimate,..." (truth coordinates; the local best: the highest rho of the
           gain-1 template within +-14 px of the estimate) from a temporarily instrumented
           `pft run` (not part of the tool; see docs/results/tsa_ak.md, branch tsa11);
  --window W: a failed frame is "after a reversal" when a reversal was taken in the W frames
           before it or at it (default 6).
A frame fails as in `pft eval`: IoU <= 0.5 or centre error >= 20 px (frame 1 is the start and
is not scored). Prints one line per failed frame (--all: every frame) and a summary of the
failed frames against the others.
"""
import argparse
import csv
import math
import sys


def read_csv(path):
    with open(path) as f:
        return list(csv.DictReader(f))


def iou(a, b):
    ax0, ay0, aw, ah = a
    bx0, by0, bw, bh = b
    ix = max(0.0, min(ax0 + aw, bx0 + bw) - max(ax0, bx0))
    iy = max(0.0, min(ay0 + ah, by0 + bh) - max(ay0, by0))
    inter = ix * iy
    u = aw * ah + bw * bh - inter
    return inter / u if u > 0 else 0.0


def partials(d, tracker):
    """Failed frames per run of the partial summaries in d."""
    import glob
    import json
    total = failed = 0
    per = []
    for p in sorted(glob.glob(d + '/partial_*_of_*.json')):
        for r in json.load(open(p))['run_records']:
            for t in r['trackers']:
                if t['tracker'] != tracker:
                    continue
                bad = [(k + 2, t['err'][k], t['iou'][k]) for k in range(len(t['ok']))
                       if t['scored'][k] and not t['ok'][k]]
                total += sum(t['scored'])
                failed += len(bad)
                if bad:
                    per.append((r['seed'], bad))
    for seed, bad in sorted(per, key=lambda x: -len(x[1])):
        print('seed %d: %d failed: %s' % (seed, len(bad), ', '.join(
            '%d (%.1f px, IoU %.2f)' % b for b in bad)))
    print('failed %d of %d scored frames (%.4f ok) in %d runs' % (
        failed, total, 1 - failed / total if total else 0, len(per)))


def main():
    if len(sys.argv) > 1 and sys.argv[1] == '--partials':
        ap = argparse.ArgumentParser()
        ap.add_argument('--partials')
        ap.add_argument('--tracker', default='tsa')
        a = ap.parse_args()
        partials(a.partials, a.tracker)
        return
    ap = argparse.ArgumentParser()
    ap.add_argument('sim')
    ap.add_argument('run')
    ap.add_argument('--diag')
    ap.add_argument('--window', type=int, default=6)
    ap.add_argument('--all', action='store_true')
    ap.add_argument('--tracks', default='tracks.csv')
    a = ap.parse_args()
    truth = {int(r['frame']): r for r in read_csv(a.sim + '/truth.csv')}
    tracks = {int(r['frame']): r for r in read_csv(a.run + '/' + a.tracks)}
    diag = {}
    if a.diag:
        for line in open(a.diag):
            if line.startswith('DIAG,'):
                v = line.strip().split(',')[1:]
                diag[int(v[0])] = [float(x) for x in v]
    frames = sorted(tracks)
    rev = [k for k in sorted(truth) if int(float(truth[k].get('reversal', 0) or 0))]
    rows = []
    for k in frames:
        t = truth[k]
        r = tracks[k]
        cx, cy = float(t['cx']), float(t['cy'])
        tb = (float(t['box_x']), float(t['box_y']), float(t['box_w']), float(t['box_h']))
        ex, ey = float(r['x']), float(r['y'])
        eb = (float(r['box_x']), float(r['box_y']), float(r['box_w']), float(r['box_h']))
        err = math.hypot(ex - cx, ey - cy)
        ov = iou(eb, tb)
        vx = float(t['camera_vx'])
        vx_prev = float(truth[k - 1]['camera_vx']) if k - 1 in truth else vx
        since = [k - q for q in rev if q <= k]
        row = {'frame': k, 'fail': not (ov > 0.5 and err < 20.0), 'err': err, 'iou': ov,
               'dx': ex - cx, 'dy': ey - cy, 'vx': vx, 'ax': vx - vx_prev,
               'since_rev': min(since) if since else 999,
               'gain': float(t.get('gain', 1) or 1), 'blur': float(t.get('blur_px', 0) or 0),
               'rho': float(r['rho']), 'rho_p': float(r['rho_pioneer']), 'beta': float(r['beta']),
               'state': int(r['state']), 'alive': int(r['alive']),
               'box_w': eb[2], 'box_h': eb[3], 'truth_w': tb[2], 'truth_h': tb[3]}
        g_prev = float(truth[k - 1].get('gain', 1) or 1) if k - 1 in truth else row['gain']
        row['dgain'] = row['gain'] - g_prev
        if k in diag:
            d = diag[k]
            row['best_err'] = math.hypot(d[3] - cx, d[4] - cy)
            row['best_rho'] = d[5]
            row['local_err'] = math.hypot(d[6] - cx, d[7] - cy)
            row['local_rho'] = d[8]
            row['rho_est_q'] = d[9]
        rows.append(row)
    keys = ['frame', 'err', 'iou', 'dx', 'dy', 'vx', 'ax', 'since_rev', 'gain', 'dgain', 'blur',
            'rho', 'rho_p', 'beta', 'state', 'alive', 'box_w', 'box_h', 'truth_w', 'truth_h']
    if diag:
        keys += ['best_err', 'best_rho', 'local_err', 'local_rho', 'rho_est_q']
    print(' '.join('%9s' % k for k in keys))
    for row in rows:
        if row['fail'] or a.all:
            print(' '.join(('%9d' % row[k]) if isinstance(row[k], int) else ('%9.3f' % row[k])
                           for k in keys if k in row))

    def mean(rs, k):
        v = [r[k] for r in rs if k in r]
        return sum(v) / len(v) if v else float('nan')
    fail = [r for r in rows if r['fail']]
    ok = [r for r in rows if not r['fail']]
    print('reversals taken at frames:', rev)
    print('failed %d of %d frames' % (len(fail), len(rows)))
    print('%-22s %10s %10s' % ('mean of', 'failed', 'other'))
    for k in ['err', 'iou', '|vx|', '|ax|', 'after_rev', '|gain-1|', '|dgain|', 'blur', 'rho',
              'rho_p', 'beta', 'alive', 'box_w', 'box_h', 'truth_w', 'truth_h', 'best_err',
              'local_err', 'local_rho', 'rho_est_q']:
        def val(r, k=k):
            if k == '|vx|':
                return abs(r['vx'])
            if k == '|ax|':
                return abs(r['ax'])
            if k == 'after_rev':
                return 1.0 if r['since_rev'] <= a.window else 0.0
            if k == '|gain-1|':
                return abs(r['gain'] - 1)
            if k == '|dgain|':
                return abs(r['dgain'])
            return r.get(k)
        fv = [val(r) for r in fail if val(r) is not None]
        ov = [val(r) for r in ok if val(r) is not None]
        if fv or ov:
            print('%-22s %10.3f %10.3f' % (k, sum(fv) / len(fv) if fv else float('nan'),
                                          sum(ov) / len(ov) if ov else float('nan')))


if __name__ == '__main__':
    main()
