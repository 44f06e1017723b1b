#!/usr/bin/env python3
"""Why the IR pipeline's false tracks are reported on one frame (docs/results/ir_clutter.md,
"Branch irrep"). Replays the scene-motion test's report decision (docs/algorithms.md 9.11 steps
2, 4-6, with real_frames_low_false_rate.json's values: n 5, fit 0.2 px, early 0.5 px, scene_hold
7, the short hold 2 at a spread of at most 0.4 px and p_exist >= 0.99, the entering-edge hold 6 px
/ 0.2 / 0.2 on the 346 x 270 frame) on the layers of `pft eval --trace DIR` runs (clutter
decisions taken from the run), checks it against the trace's reported column, and

  ir_short_why.py table NAME=DIR[,DIR...] ...   per false track (the summary beside DIR, DIR
      without its "_tr" suffix, names them) and per injected target's first report: the path
      that reported it (short hold or 7-pass hold), existence, spread, speed against the scene,
      and what stopped the reports; a markdown table
  ir_short_why.py screen DIR [DIR ...]   the same report rule with candidate changes to the
      short hold: base-false layers still reported, targets detected and lost (a reported frame
      within 3 px of an injected target's truth point; a screen, not pft eval's association)

The replay is in double precision, the library's test in Q16.16: about 0.1 % of the fed frames
decide differently. Not a test.
"""
import csv, glob, math, os, sys, collections, json
W, H = 346, 270
N = 5; HOLD = 7; SH = 2; SP2 = 0.4**2; PE = 0.99; FIT = 0.2; EARLY = 0.5
EDGE, STILL, SHIFT = 6.0, 0.2, 0.2

def fit_ok(h):
    k = len(h)
    if k < 3: return True
    ss = 0.0
    ts = [i - (k - 1) / 2 for i in range(k)]
    tt = sum(t * t for t in ts)
    for c in (0, 1):
        xs = [p[c] for p in h]; m = sum(xs) / k
        v = sum(t * x for t, x in zip(ts, xs)) / tt
        ss += sum((x - m - v * t) ** 2 for x, t in zip(xs, ts))
    return ss <= k * FIT * FIT + 1e-12

def edge_hold(h):
    m = min(len(h) - 1, N)
    if m < 1: return False
    a, b = h[-1 - m], h[-1]
    for c, side in ((0, W), (1, H)):
        d = b[c] - a[c]; ds = b[c + 2] - a[c + 2]
        if abs(d) >= m * STILL: continue
        if ds < 0 and -ds >= m * SHIFT and b[c] >= side - 1 - EDGE: return True
        if ds > 0 and ds >= m * SHIFT and b[c] <= EDGE: return True
    return False

def replay(rows):
    """per fed frame: dict with status"""
    hist = []; passed = 0; out = []
    for r in rows:
        dec = int(r['scene_dec'])
        if dec < 0:
            out.append(dict(frame=int(r['frame']), st='notfed', r=r)); continue
        hist.append((float(r['rx']), float(r['ry']), float(r['scene_x']), float(r['scene_y'])))
        if len(hist) > N + 1: hist.pop(0)
        var = float(r['cov_xx']) + float(r['cov_yy']); p = float(r['p_exist'])
        e = dict(frame=int(r['frame']), r=r, var=var, p=p, dec=dec, rep=r['reported'] == '1')
        if dec == 2:
            e['st'] = 'clutter'; out.append(e); continue
        if r['tentative'] == '1':
            e['st'] = 'tentative'; out.append(e); continue
        k = len(hist)
        early = False
        if 4 <= k < N + 1:
            a, b = hist[-4], hist[-1]
            dx = (b[0] - a[0]) - (b[2] - a[2]); dy = (b[1] - a[1]) - (b[3] - a[3])
            early = dx * dx + dy * dy >= (3 * EARLY) ** 2
        ps = (k >= N + 1 or early) and fit_ok(hist)
        e['k'] = k; e['early'] = early and k < N + 1
        a, b = hist[0], hist[-1]; m = k - 1
        e['v'] = math.hypot((b[0]-a[0])-(b[2]-a[2]), (b[1]-a[1])-(b[3]-a[3])) / max(m, 1)
        a = hist[-4] if k >= 4 else hist[0]; m3 = min(3, k - 1)
        e['v3'] = math.hypot((b[0]-a[0])-(b[2]-a[2]), (b[1]-a[1])-(b[3]-a[3])) / max(m3, 1)
        if ps and edge_hold(hist):
            e['st'] = 'edge'; out.append(e); continue
        if not ps:
            e['st'] = 'fail'; out.append(e); continue
        compact = var <= SP2 and p >= PE
        passed = min(passed + 1, HOLD)
        need = SH if compact else HOLD
        e['passed'] = passed; e['compact'] = compact
        if passed >= need:
            e['st'] = 'report'; e['path'] = 'hold7' if passed >= HOLD else 'short'
        else:
            e['st'] = 'held'
        out.append(e)
    return out

def main(pairs):
    res = []
    mism = 0; tot = 0
    for tdir, summ in pairs:
        S = json.load(open(summ))
        false_ids = {(r['seed'], f['id']) for r in S['per_run'] for f in r['false_track_list']}
        for lf in sorted(glob.glob(os.path.join(tdir, 's*_layers.csv'))):
            seed = int(os.path.basename(lf)[1:].split('_')[0])
            tracks = {int(t['id']): t for t in csv.DictReader(open(lf.replace('_layers', '_tracks')))}
            by = collections.defaultdict(list)
            for r in csv.DictReader(open(lf)):
                by[int(r['id'])].append(r)
            for tid, rows in by.items():
                rows.sort(key=lambda r: int(r['frame']))
                ev = replay(rows)
                for e in ev:
                    if 'rep' in e:
                        tot += 1
                        if (e['st'] == 'report') != e['rep']: mism += 1
                reps = [i for i, e in enumerate(ev) if e['st'] == 'report']
                if not reps: continue
                t = tracks.get(tid, {})
                isf = (seed, tid) in false_ids
                # target: the layer's near_rep_tid (truth nearest at reports), injected only
                near = [e['r']['near_tid'] for e in ev if e['st'] == 'report']
                lab = [e['r']['near_labelled'] for e in ev if e['st'] == 'report']
                i0 = reps[0]
                res.append(dict(run=tdir, seed=seed, id=tid, false=isf, ev=ev, i0=i0, reps=reps, track=t,
                                near=near, lab=lab))
    print('replay mismatches', mism, 'of', tot, file=sys.stderr)
    return res


def feats(x):
    ev = x['ev']; i0 = x['i0']; e = ev[i0]
    fed = [j for j in range(len(ev)) if ev[j]['st'] != 'notfed']
    prev = [ev[j] for j in fed if j < i0]
    d = dict(path=e['path'], passed=e['passed'], p=e['p'], sd=e['var'] ** .5, frame=e['frame'],
             age=int(e['r']['age']), lr=float(e['r']['log_mean_lr']))
    # previous fed frame's state and whether it was the frame before
    pv = prev[-1] if prev else None
    d['prev_st'] = pv['st'] if pv else '-'
    d['prev_consec'] = bool(pv and pv['frame'] == e['frame'] - 1)
    d['prev_pass'] = bool(pv and pv['st'] in ('held', 'report') and pv['frame'] == e['frame'] - 1)
    d['p1'] = pv['p'] if pv else float('nan')
    d['sd1'] = pv['var'] ** .5 if pv else float('nan')
    d['p2'] = prev[-2]['p'] if len(prev) >= 2 else float('nan')
    d['compact1'] = bool(pv and pv['var'] <= SP2 and pv['p'] >= PE)
    d['pmin3'] = min([q['p'] for q in prev[-3:]] + [e['p']])
    d['lr1'] = float(pv['r']['log_mean_lr']) if pv else float('nan')
    # what stopped the reports: the state after the last report
    il = x['reps'][-1]
    nxt = [ev[j] for j in range(il + 1, len(ev))]
    t = x['track']
    if not nxt:
        stop = 'ended:' + (t.get('reason') or 'run end')
    else:
        n0 = nxt[0]
        if n0['st'] == 'held':
            stop = 'held:' + ('exist<0.99' if n0['p'] < PE and n0['var'] <= SP2 else 'wide' if n0['p'] >= PE else 'wide+exist')
        else:
            stop = n0['st']
    d['stop'] = stop
    d['nrep'] = len(x['reps'])
    d['k'] = e['k']; d['early'] = e['early']; d['v'] = e['v']; d['v3'] = e['v3']
    d['k_all'] = [ev[j]['k'] for j in x['reps']]
    d['after'] = [(q['frame'], q['st'], round(q['p'], 3), round(q['var'] ** .5, 2)) for q in ev[i0 + 1:i0 + 4]]
    d['before'] = [(q['frame'], q['st'], round(q['p'], 3), round(q['var'] ** .5, 2)) for q in prev[-3:]]
    return d


def collect(dirs):
    res = main([(d, d[:-3] + '/summary.json') for d in dirs])
    F = []; T = []
    for x in res:
        f = feats(x)
        f['seed'] = x['seed']; f['id'] = x['id']; f['src'] = x['run']
        if x['false']:
            F.append(f)
        elif any(l == '0' and n not in ('', '0') for n, l in zip(x['near'], x['lab'])):
            r0 = x['ev'][x['i0']]['r']
            f['tgt'] = r0['near_tid'] if r0['near_labelled'] == '0' else ''
            f['tgt_d'] = r0['near_d']
            T.append(f)
    return F, T


def table(specs):
    groups = []
    for spec in specs:
        name, files = spec.split('=')
        F, T = collect(files.split(','))
        first = {}
        for x in T:
            if not x['tgt'] or x['tgt_d'] == '' or float(x['tgt_d']) > 3: continue
            key = (x['src'], x['seed'], x['tgt'])
            if key not in first or x['frame'] < first[key]['frame']: first[key] = x
        groups.append((name + ' false tracks', F)); groups.append((name + " targets' first reports", list(first.values())))
    def med(v): v = sorted(v); return v[len(v) // 2]
    rows = [
     ('count', lambda L: str(len(L))),
     ('reported on 1 frame / 2 / ≥ 3', lambda L: '%d / %d / %d' % (sum(f['nrep']==1 for f in L), sum(f['nrep']==2 for f in L), sum(f['nrep']>=3 for f in L))),
     ('path: short hold (2 compact passes) / 7-pass hold', lambda L: '%d / %d' % (sum(f['path']=='short' for f in L), sum(f['path']=='hold7' for f in L))),
     ('pass count at the report: 2 / 3 / 4–6 / 7', lambda L: '%d / %d / %d / %d' % (sum(f['passed']==2 for f in L), sum(f['passed']==3 for f in L), sum(4<=f['passed']<=6 for f in L), sum(f['passed']==7 for f in L))),
     ('report at the full window (n + 1 positions) / early (4–5 positions)', lambda L: '%d / %d' % (sum(f['k']==6 for f in L), sum(f['k']<6 for f in L))),
     ('p_exist at the report, median (min)', lambda L: '%.4f (%.4f)' % (med([f['p'] for f in L]), min(f['p'] for f in L))),
     ('p_exist one frame before ≥ 0.99', lambda L: '%d' % sum(f['p1']>=0.99 for f in L)),
     ('p_exist not fallen since the frame before', lambda L: '%d' % sum(f['p']>=f['p1'] for f in L)),
     ('spread √(xx+yy) at the report, median (max), px', lambda L: '%.3f (%.3f)' % (med([f['sd'] for f in L]), max(f['sd'] for f in L))),
     ('previous pass compact at p ≥ 0.99 too', lambda L: '%d' % sum(f['compact1'] for f in L)),
     ('the frame before a pass too', lambda L: '%d' % sum(f['prev_pass'] for f in L)),
     ('speed against the scene over the window at the report < 0.35 px/frame (median)', lambda L: '%d (%.2f)' % (sum(f['v']<0.35 for f in L), med([f['v'] for f in L]))),
     ('after the last report: ended below θ_end', lambda L: str(sum(f['stop']=='ended:existence' for f in L))),
     ('  ended: slot taken by another layer', lambda L: str(sum(f['stop']=='ended:slot_reused' for f in L))),
     ('  CLUTTER (scene gate)', lambda L: str(sum(f['stop']=='clutter' for f in L))),
     ('  held: short hold lapsed (p_exist < 0.99, compact)', lambda L: str(sum(f['stop']=='held:exist<0.99' for f in L))),
     ('  held: spread > 0.4 px (p ≥ 0.99) / both', lambda L: '%d / %d' % (sum(f['stop']=='held:wide' for f in L), sum(f['stop']=='held:wide+exist' for f in L))),
     ('  no pass (line fit / early test)', lambda L: str(sum(f['stop']=='fail' for f in L))),
     ('  edge hold / tentative', lambda L: '%d / %d' % (sum(f['stop']=='edge' for f in L), sum(f['stop']=='tentative' for f in L))),
     ('  reported to the run\'s end', lambda L: str(sum(f['stop']=='ended:run end' for f in L))),
    ]
    print('| | ' + ' | '.join(n for n, _ in groups) + ' |')
    print('|---' * (len(groups) + 1) + '|')
    for rn, fn in rows:
        print('| ' + rn + ' | ' + ' | '.join(fn(L) for _, L in groups) + ' |')


RULES = {}
def rule(name):
    def d(f): RULES[name] = f; return f
    return d
# each rule: (e, prev_fed, passes_hist) -> whether the short hold may report at this frame
@rule('base')
def _(e, pv, P): return True
@rule('consec')   # previous fed frame a pass, one frame before
def _(e, pv, P): return pv is not None and pv['frame'] == e['frame'] - 1 and pv['st'] in ('held', 'report')
@rule('pnotfall')
def _(e, pv, P): return pv is not None and e['p'] >= pv['p']
@rule('prevcompact')  # the previous pass compact at high existence too
def _(e, pv, P): return len(P) >= 2 and P[-2]['var'] <= SP2 and P[-2]['p'] >= PE
@rule('prevcompact_consec')
def _(e, pv, P): return len(P) >= 2 and P[-2]['var'] <= SP2 and P[-2]['p'] >= PE and P[-2]['frame'] == e['frame'] - 1
for th in (0.2, 0.25, 0.3, 0.35):
    RULES['v>=%g' % th] = (lambda th: lambda e, pv, P: e['v'] >= th)(th)

def pc(P): return len(P) >= 2 and P[-2]['var'] <= SP2 and P[-2]['p'] >= PE
for th in (0.25, 0.35, 0.5):
    RULES['v>=%g|prevcompact' % th] = (lambda th: lambda e, pv, P: e['v'] >= th or pc(P))(th)
    RULES['v>=%g|p1>=.99' % th] = (lambda th: lambda e, pv, P: e['v'] >= th or (pv is not None and pv['p'] >= 0.99))(th)
for th in (0.25, 0.35, 0.5):
    for nd in (3, 4):
        RULES['v>=%g else %d' % (th, nd)] = (lambda th, nd: lambda e, pv, P: True if e['v'] >= th else nd)(th, nd)
def replay_rule(rows, R):
    hist = []; passed = 0; out = []; pv = None; P = []
    for r in rows:
        dec = int(r['scene_dec'])
        if dec < 0: continue
        hist.append((float(r['rx']), float(r['ry']), float(r['scene_x']), float(r['scene_y'])))
        if len(hist) > N + 1: hist.pop(0)
        var = float(r['cov_xx']) + float(r['cov_yy']); p = float(r['p_exist'])
        e = dict(frame=int(r['frame']), var=var, p=p, r=r, st='x')
        k = len(hist)
        if dec == 2 or r['tentative'] == '1':
            e['st'] = 'clutter'; pv = e; continue
        early = False
        if 4 <= k < N + 1:
            a, b = hist[-4], hist[-1]
            dx = (b[0] - a[0]) - (b[2] - a[2]); dy = (b[1] - a[1]) - (b[3] - a[3])
            early = dx * dx + dy * dy >= (3 * EARLY) ** 2
        a, b = hist[0], hist[-1]
        e['v'] = math.hypot((b[0]-a[0])-(b[2]-a[2]), (b[1]-a[1])-(b[3]-a[3])) / max(k - 1, 1)
        ps = (k >= N + 1 or early) and fit_ok(hist)
        if ps and edge_hold(hist): e['st'] = 'edge'; pv = e; continue
        if not ps: e['st'] = 'fail'; pv = e; continue
        P.append(e)
        compact = var <= SP2 and p >= PE
        rr = R(e, pv, P)
        passed = min(passed + 1, HOLD)
        need = (SH if rr is True else HOLD if rr is False else rr) if compact else HOLD
        e['st'] = 'report' if passed >= need else 'held'
        if e['st'] == 'report': out.append(e)
        pv = e
    return out

def screen(dirs):
    data = []
    for d in dirs:
        S = json.load(open(d[:-3] + '/summary.json'))
        fl = {(r['seed'], f['id']) for r in S['per_run'] for f in r['false_track_list']}
        det = {(r['seed'], t['id']) for r in S['per_run'] for t in r['targets'] if t['kind'] == 'injected' and t['detected']}
        inj = sum(1 for r in S['per_run'] for t in r['targets'] if t['kind'] == 'injected')
        runs = []
        for lf in sorted(glob.glob(d + '/s*_layers.csv')):
            seed = int(os.path.basename(lf)[1:].split('_')[0])
            by = collections.defaultdict(list)
            for r in csv.DictReader(open(lf)): by[int(r['id'])].append(r)
            for v in by.values(): v.sort(key=lambda r: int(r['frame']))
            runs.append((seed, by))
        data.append((d, fl, det, inj, runs))
    for name, R in RULES.items():
        tf = 0; tfb = 0; dt = 0; lost = 0; gained = 0; ninj = 0; frep = collections.Counter()
        for d, fl, det, inj, runs in data:
            ninj += inj
            mydet = set()
            for seed, by in runs:
                for tid, rows in by.items():
                    reps = replay_rule(rows, R)
                    hit = False
                    for e in reps:
                        r = e['r']
                        if r['near_labelled'] == '0' and r['near_tid'] not in ('', '0') and r['near_d'] != '' and float(r['near_d']) <= 3.0:
                            mydet.add((seed, int(r['near_tid']))); hit = True
                    if (seed, tid) in fl:
                        tfb += 1
                        if reps: tf += 1; frep[len(reps)] += 1
            lost += len(det - mydet); gained += len(mydet - det); dt += len(det & mydet) + len(mydet - det)
        print('%-20s false(of base-false layers still reported) %3d/%3d  detected(screen) %4d/%d  lost %d gained %d  reps %s' % (name, tf, tfb, dt, ninj, lost, gained, dict(sorted(frep.items()))))


if __name__ == '__main__':
    if len(sys.argv) < 3 or sys.argv[1] not in ('table', 'screen'):
        sys.exit(__doc__)
    (table if sys.argv[1] == 'table' else screen)(sys.argv[2:])
