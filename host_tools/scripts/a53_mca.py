#!/usr/bin/env python3
"""A cycle model of the IR pipeline on a Cortex-A53 (docs/results/ir_clutter.md, "Branch irmca").

QEMU counts the instructions of the aarch64 presets' build (section "Branch ira53"); this script
turns them into modelled cycles with llvm-mca's Cortex-A53 scheduling model. It is a model:

1. `run`: tests/tools/ir_probe of an aarch64 build (or another program with the work markers,
   --exe/--args) under qemu-aarch64 with the plugin tests/soak/qemu_marks.c: out= the
   instructions per call, prof= per function, blocks= per translated block, and with --mem its
   data-cache model (mem=). Odd regions are ir_probe's stage calls, even ones the manager's
   (ir_probe's MARKS argument 2, which run passes: the clutter map between them is not
   bracketed, so it is not modelled).
2. `model`: maps the block counts onto `objdump -d` of the same executable (the library's
   objects as linked: -O3, no LTO), finds in each function of >= 0.5 % of its region its hot
   loops (from each backward-branch target, the dominant path: at every conditional branch the
   more used edge, back to the start), feeds each loop body to `llvm-mca -mtriple=aarch64
   -mcpu=cortex-a53` (and, for comparison, cortex-a55), and weights each loop's cycles per
   instruction by the instructions of the block profile it covers; a function's instructions
   outside its modelled loops get its region's mean loop CPI. llvm-mca models in-order dual
   issue, the units and latencies of LLVM's scheduling model, every load an L1 hit, every branch
   predicted, a call as free (replaced by a nop; the callee is modelled where it is). What it
   leaves out is estimated beside it: cache misses from the plugin's cache model at an assumed
   L2 and DRAM latency (with and without the strided misses prefetched), and one misprediction
   per departure from a loop's dominant path at an assumed penalty.
3. `three`: the clutter map as well ("Lead: the A53 model with the clutter map"): a run with
   ir_probe's MARKS 2 (stage, manager) and one with MARKS 1 (map, manager) on the same frames
   and settings (--args), each modelled (the second with --regions map,manager), give the three
   calls' modelled cycles per frame; the manager's counts must agree between the two runs.
4. `check`: llvm-mca on small kernels whose A53 timing is known (the dual-issue rule and
   published measurements on an A53), to show where the model is right and where it is not.
5. `model --regions A,B,C,...` with K names other than two: a run whose work markers bracket K
   calls in turn each frame, as `ir_probe -c` (the flight build, docs/results/ir_clutter.md
   "Branch ircost31" and "Branch ircost44") brackets stage, flat, map, manager, after. The
   plugin's block counts come in two columns (odd and even regions), which with K odd do not
   follow the regions, so they are summed and each function goes to the region whose root
   function reaches it by direct calls in the disassembly (--roots, default irp_f_NAME for each
   NAME: ir_probe -c's); the instructions a region's out= count holds beyond its own functions
   (shared functions, the C library, the markers) are reported and charged in proportion. The
   report adds a table per call (each region's instructions, cycles and CPI, and the total) to
   the per-frame one; --calls must cover whole frames (run --calls 66-200 with K = 5: frames
   14-40), and --frames-from numbers the frames of the whole run (the tables start at it or at
   the first profiled frame, whichever is later). The default two regions give the reports
   they gave before.

  bash tests/soak/run_soak.sh plugin
  python3 host_tools/scripts/a53_mca.py run --build build/aarch64-float \
      --frames build/ir-cost/frames-384x288/frames.u16 --n 100 --out build/a53-mca/float --mem
  python3 host_tools/scripts/a53_mca.py model --build build/aarch64-float --run build/a53-mca/float \
      [--debug-exe build/a53-g-float/tests/tools/ir_probe]
  python3 host_tools/scripts/a53_mca.py three --run-stage R2 --model-stage R2.md --run-map R1 --model-map R1.md
  python3 host_tools/scripts/a53_mca.py check
  # the flight build (ir_cost_targets.sh with IRC_FLIGHT made DIR/probe.cfg, DIR/frames.u16):
  python3 host_tools/scripts/a53_mca.py run --build build/irc-aarch64-float \
      --args "-c DIR/probe.cfg DIR/frames.u16 40" --calls 66-200 --mem --out build/a53-mca/flight
  python3 host_tools/scripts/a53_mca.py model --build build/irc-aarch64-float --run build/a53-mca/flight \
      --regions stage,flat,map,manager,after --calls 66-200 --frames-from 14

(--debug-exe: the same preset built with -DCMAKE_C_FLAGS=-g into another directory; the script
checks its code is instruction for instruction the same and names each loop's source line.)
Needs qemu-aarch64, aarch64-linux-gnu binutils and llvm-mca (Debian's `llvm`, 14).
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..'))
PLUGIN = os.path.join(ROOT, 'build', 'qemu-plugin', 'qemu_marks.so')
MCA_ITER = 200
CLOCK = 1.2e9

COND_BR = re.compile(r'^(b\.\w+|cbz|cbnz|tbz|tbnz)$')


def sh(cmd, **kw):
    return subprocess.run(cmd, check=True, capture_output=True, text=True, **kw).stdout


# ---------------------------------------------------------------------------------------- run
def cmd_run(a):
    exe = a.exe or os.path.join(a.build, 'tests', 'tools', 'ir_probe')
    w, h = a.size.split('x')
    os.makedirs(a.out, exist_ok=True)
    plug = '%s,out=%s,prof=%s,blocks=%s' % (PLUGIN, os.path.join(a.out, 'counts.txt'),
                                             os.path.join(a.out, 'prof.txt'),
                                             os.path.join(a.out, 'blocks.txt'))
    if a.mem:
        plug += ',mem=%s,l1=%d,l2=%d' % (os.path.join(a.out, 'mem.txt'), a.l1, a.l2)
    if a.calls:
        i, j = a.calls.split('-')
        plug += ',from=%d,to=%d' % (int(i), int(j))
    # MARKS 2: ir_probe leaves the clutter map's call outside the work markers, so the plugin's
    # regions alternate stage (odd), manager (even), as the model reads them
    args = a.args.split() if a.args else [a.frames, w, h, '14', str(a.n), '1', '12000', 'inplace', '0', '2']
    cmd = ['nice', '-n', '10', 'qemu-aarch64', '-L', '/usr/aarch64-linux-gnu', '-plugin', plug, exe] + args
    log = subprocess.run(cmd, capture_output=True, text=True)
    open(os.path.join(a.out, 'log.txt'), 'w').write(log.stdout + log.stderr)
    if log.returncode != 0 or (not a.args and 'ir_probe: done' not in log.stdout):
        sys.exit('a53_mca.py: ir_probe failed, see %s/log.txt' % a.out)
    print('a53_mca.py: %s' % a.out)


# ----------------------------------------------------------------------------- disassembly
def disassemble(exe):
    """{name: [(addr, mnemonic, operands)]} of every function of the executable."""
    funcs, cur = {}, None
    out = sh(['aarch64-linux-gnu-objdump', '-d', '--no-show-raw-insn', exe])
    for line in out.splitlines():
        m = re.match(r'^([0-9a-f]+) <(.+)>:$', line)
        if m:
            cur = funcs.setdefault(m.group(2), [])
            continue
        m = re.match(r'^\s+([0-9a-f]+):\s+(\S+)\s*(.*)$', line)
        if m and cur is not None:
            ops = m.group(3).split('//')[0].strip()
            cur.append((int(m.group(1), 16), m.group(2), ops))
    return funcs


def branch_target(mn, ops):
    if mn == 'b' or mn == 'bl' or COND_BR.match(mn):
        m = re.search(r'([0-9a-f]+) <', ops)
        if m:
            return int(m.group(1), 16)
    return None


def mca_text(body):
    """The loop body as llvm-mca input: branch targets and pc-relative symbols become a label; a
    call becomes a nop (llvm-mca would charge it 100 cycles; the callee's instructions are
    modelled in the callee, the call and return themselves are not)."""
    lines = ['L0:']
    for _, mn, ops in body:
        if mn in ('bl', 'blr'):
            lines.append('\tnop')
            continue
        ops = re.sub(r'[0-9a-f]+ <[^>]*>', 'L0', ops)
        ops = re.sub(r'#(-?[0-9]+)\s*$', r'#\1', ops)
        lines.append('\t%s\t%s' % (mn, ops) if ops else '\t' + mn)
    return '\n'.join(lines) + '\n'


def llvm_mca(text, mca='llvm-mca', cpu='cortex-a53'):
    with tempfile.NamedTemporaryFile('w', suffix='.s', delete=False) as f:
        f.write(text)
        path = f.name
    try:
        out = subprocess.run([mca, '-mtriple=aarch64', '-mcpu=' + cpu, '-iterations=%d' % MCA_ITER,
                              '-bottleneck-analysis', path], capture_output=True, text=True)
    finally:
        os.unlink(path)
    if out.returncode != 0:
        raise RuntimeError(out.stderr)
    s = out.stdout
    r = {'cycles': int(re.search(r'Total Cycles:\s+(\d+)', s).group(1)),
         'insns': int(re.search(r'Instructions:\s+(\d+)', s).group(1)),
         'ipc': float(re.search(r'IPC:\s+([0-9.]+)', s).group(1))}
    rp = re.search(r'Resource Pressure\s+\[\s*([0-9.]+)%', s)
    dd = re.search(r'Data Dependencies:\s+\[\s*([0-9.]+)%', s)
    r['res_pct'] = float(rp.group(1)) if rp else 0.0
    r['dep_pct'] = float(dd.group(1)) if dd else 0.0
    # resource pressure per iteration: the busiest unit
    names = dict(re.findall(r'^\[([0-9.]+)\]\s+-\s+(\S+)$', s, re.M))
    m = re.search(r'Resource pressure per iteration:\n(.*)\n(.*)\n', s)
    busiest = ('-', 0.0)
    if m:
        heads = re.findall(r'\[([0-9.]+)\]', m.group(1))
        vals = m.group(2).split()
        per_unit = {}
        for hd, v in zip(heads, vals):
            name = names.get(hd, hd)
            if name == 'A53UnitALU':
                name = 'A53UnitALU (2)'
            per_unit[name] = per_unit.get(name, 0.0) + (0.0 if v == '-' else float(v))
        if 'A53UnitALU (2)' in per_unit:
            per_unit['A53UnitALU (2)'] /= 2.0  # two ALU pipes: pressure per pipe
        busiest = max(per_unit.items(), key=lambda kv: kv[1])
    r['busiest'] = busiest
    info = s.split('Instruction Info:')[1].split('Resources:')[0] if 'Instruction Info:' in s else ''
    r['lat'] = []
    for line in info.splitlines():
        m = re.match(r'^\s*(\d+)\s+(\d+)\s+([0-9.]+)\s+(?:[*U]\s+)*(\S+)', line)
        if m:
            r['lat'].append((m.group(4), int(m.group(2))))
    return r


def bottleneck(r, n):
    """What bounds the loop in llvm-mca's model: the issue width (two a cycle), the busiest unit,
    or (neither) the in-order stalls on results; then the kinds of the longest latencies."""
    cyc = r['cycles'] / MCA_ITER
    unit, load = r['busiest']
    if cyc <= (n / 2.0) * 1.1:
        return 'issue width (2 per cycle)'
    if load >= 0.9 * cyc:
        return '%s busy %.0f of %.0f cycles' % (unit.replace('A53Unit', ''), load, cyc)
    kinds = {}
    for mn, lat in r['lat']:
        if lat < 4 or mn.startswith('st'):
            continue  # a store's latency holds nothing up
        if mn.startswith('ld'):
            k = 'loads'
        elif mn in ('udiv', 'sdiv', 'fdiv', 'fsqrt'):
            k = mn
        elif mn.startswith(('mul', 'madd', 'msub', 'umull', 'smull', 'umulh', 'smulh', 'umaddl', 'smaddl')):
            k = 'integer multiplies'
        else:
            k = 'FP/SIMD'
        c, l = kinds.get(k, (0, 0))
        kinds[k] = (c + 1, max(l, lat))
    top = sorted(kinds.items(), key=lambda kv: -kv[1][0] * kv[1][1])[:2]
    return 'result latency: ' + ', '.join('%d %s (%d cycles)' % (c, k, l) for k, (c, l) in top)


# --------------------------------------------------------------------------------- profile
def load_blocks(path, funcs):
    """Per-instruction entry counts [odd, even] keyed by the executable's address."""
    addr_of = {n: ins[0][0] for n, ins in funcs.items() if ins}
    blocks = []
    base = None
    for line in open(path):
        if line.startswith('#'):
            sys.exit('a53_mca.py: %s: %s' % (path, line.strip()))
        v, n, o, e, name = line.split(None, 4)
        v, n, o, e, name = int(v, 16), int(n), int(o), int(e), name.strip()
        blocks.append((v, n, o, e))
        if base is None and name == 'pft_work_mark_begin':
            base = v - addr_of[name]
    if base is None:
        sys.exit('a53_mca.py: no block of pft_work_mark_begin in %s' % path)
    cnt = {}
    for v, n, o, e in blocks:
        for k in range(n):
            c = cnt.setdefault(v - base + 4 * k, [0, 0])
            c[0] += o
            c[1] += e
    return cnt


def branch_targets(ins):
    """{target address: number of branches to it} inside the function."""
    tg = {}
    for addr, mn, ops in ins:
        t = branch_target(mn, ops)
        if t is not None and mn != 'bl':
            tg[t] = tg.get(t, 0) + 1
    return tg


def edges(ins, idx, i, cnt, reg, tg):
    """(taken, fall-through) counts of the conditional branch ins[i]. Exact when the next
    instruction is reached only by falling through (fall-through = its count, taken = the rest);
    otherwise, when the target is reached only by this branch, taken = the target's count;
    otherwise the two successors' counts (an approximation at a join)."""
    addr, mn, ops = ins[i]
    t = branch_target(mn, ops)
    c = cnt.get(addr, (0, 0))[reg]
    ft = ins[i + 1][0] if i + 1 < len(ins) else None
    cf = cnt.get(ft, (0, 0))[reg]
    if ft is not None and ft not in tg:
        return max(0, c - cf), cf
    ct = cnt.get(t, (0, 0))[reg]
    prev_falls = t in idx and idx[t] > 0 and ins[idx[t] - 1][1] not in ('b', 'ret', 'br')
    if tg.get(t, 0) == 1 and not prev_falls:
        return ct, max(0, c - ct)
    return ct, cf


def dominant_loop(ins, idx, start, cnt, reg, tg, to_ret=False):
    """The dominant path from instruction index `start` back to it (at every conditional
    branch the more used edge), or None if it leaves the function or closes elsewhere; with
    to_ret, the dominant path from `start` to the function's return instead."""
    seen, path, i = set(), [], start
    while True:
        if i in seen or i < 0 or i >= len(ins) or len(path) > 3000:
            return None
        seen.add(i)
        addr, mn, ops = ins[i]
        path.append(ins[i])
        if to_ret and mn == 'ret':
            return path
        if mn in ('ret', 'br', 'blr'):
            return None
        t = branch_target(mn, ops)
        nxt = i + 1
        if mn == 'b':
            if t not in idx:
                return None
            nxt = idx[t]
        elif COND_BR.match(mn) and t in idx:
            taken, fall = edges(ins, idx, i, cnt, reg, tg)
            if taken > fall:
                nxt = idx[t]
        if nxt == start:
            return path
        i = nxt


def departures(ins, idx, path, cnt, reg, tg):
    """How often execution leaves the loop's dominant path: at each conditional branch of the
    path, the count of the edge the path does not take (a loop exit or a branch going its
    rarer way; an upper estimate of the mispredictions if each departure costs one)."""
    n = 0
    for k, (addr, mn, ops) in enumerate(path):
        if not COND_BR.match(mn) or branch_target(mn, ops) not in idx:
            continue
        taken, fall = edges(ins, idx, idx[addr], cnt, reg, tg)
        nxt = path[(k + 1) % len(path)][0]
        n += fall if nxt == branch_target(mn, ops) else taken
    return n


def find_loops(ins, cnt, r, tot):
    """The function's hot loops in region r: (start index, path, iterations, covered), the
    heaviest first, until 97 % of its instructions are covered (at most 6 loops)."""
    idx = {addr: i for i, (addr, _, _) in enumerate(ins)}
    tg = branch_targets(ins)
    cands = set()
    for addr, mn, ops in ins:
        t = branch_target(mn, ops)
        if t is not None and mn != 'bl' and t <= addr and t in idx:
            cands.add(idx[t])
    found = []
    for s in cands:
        p = dominant_loop(ins, idx, s, cnt, r, tg)
        if p:
            it = cnt.get(ins[s][0], (0, 0))[r]
            # instructions of the path executed in its iterations (an instruction of the
            # path cannot run more often than the loop's start for the path's sake)
            cov = sum(min(cnt.get(x[0], (0, 0))[r], it) for x in p)
            found.append((cov, s, p, it))
    if not found and ins:
        # no loop: a function called once per particle or pixel; its dominant path from the
        # entry to the return, as if the calls ran back to back
        p = dominant_loop(ins, idx, 0, cnt, r, tg, to_ret=True)
        if p:
            it = cnt.get(ins[0][0], (0, 0))[r]
            found.append((sum(min(cnt.get(x[0], (0, 0))[r], it) for x in p), 0, p, it))
    found.sort(key=lambda f: -f[0])
    chosen, used, covered = [], set(), 0
    for cov, s, p, it in found:
        if cov < 0.01 * tot or len(chosen) >= 6 or covered >= 0.97 * tot:
            break
        if ins[s][0] in used:
            continue
        chosen.append((s, p, it, cov, departures(ins, idx, p, cnt, r, tg)))
        used.update(x[0] for x in p)
        covered += cov
    return chosen


def model_loops(a, cpus, name, reg, ins, cnt, col, tot):
    """The modelled loops of one function (its counts in column col, tot instructions)."""
    fl = []
    for s, p, it, cov, dep in find_loops(ins, cnt, col, tot):
        m = {c: llvm_mca(mca_text(p), a.mca, c) for c in cpus}
        fl.append({'fn': name, 'reg': reg, 'start': ins[s][0], 'n': len(p), 'iters': it,
                   'body': p[-1][1] == 'ret', 'cov': cov, 'dep': dep, 'mca': m,
                   'cpi': {c: m[c]['cycles'] / MCA_ITER / len(p) for c in cpus},
                   'bn': bottleneck(m[cpus[0]], len(p))})
    return fl


def charge(fns, fb, cpus, cyc):
    """Each function's cycles: its modelled loops at their CPI, the rest at fb[region, cpu];
    sets f['cv'] (instructions in modelled loops) and f['cpi'], adds the cycles to cyc."""
    for f in fns:
        cv = min(sum(l['cov'] for l in f['loops']), f['tot'])
        scale = cv / sum(l['cov'] for l in f['loops']) if f['loops'] else 0.0
        f['cv'] = cv
        f['cpi'] = {}
        for c in cpus:
            y = sum(l['cov'] * l['cpi'][c] for l in f['loops']) * scale + (f['tot'] - cv) * fb[f['reg'], c]
            cyc[f['reg'], c] += y
            f['cpi'][c] = y / f['tot']


def loop_sources(a, funcs, loops):
    """--debug-exe: each loop's source line (the same code built with -g: gcc's -g changes no
    instruction; checked), by start address."""
    where = {}
    if not a.debug_exe:
        return where
    if [x[1:] for f in disassemble(a.debug_exe).values() for x in f] != [x[1:] for f in funcs.values() for x in f]:
        sys.exit('a53_mca.py: %s is not the same code as %s' % (a.debug_exe, a.exe_used))
    for l in loops:
        # -i prints the inline chain (innermost first): one address at a time
        o = sh(['aarch64-linux-gnu-addr2line', '-e', a.debug_exe, '-f', '-i', '0x%x' % l['start']]).split('\n')
        fn, fl = o[0], o[1]
        where[l['start']] = '%s:%s' % (os.path.basename(fl.split(' ')[0]).split(':')[0] if ':' in fl else fl,
                                       fl.split(':')[1].split(' ')[0] if ':' in fl else '?') + (' (%s)' % fn)
    return where


def load_mem(run, key):
    """The plugin's cache model (RUN/mem.txt, if the run had --mem): the five counts (accesses,
    L1 misses, of them strided, L2 misses, of them strided) summed by key(fields of the line)."""
    mem = {}
    mpath = os.path.join(run, 'mem.txt')
    if os.path.exists(mpath):
        for line in open(mpath):
            f = line.split()
            k = key(f)
            mem[k] = [x + int(y) for x, y in zip(mem.get(k, [0] * 5), f[2:7])]
    return mem


def stalls(a, lat, l1, l1s, l2, l2s):
    """(strided misses prefetched, no prefetch) stall cycles: without prefetch every L1 miss
    waits the L2 and every L2 miss the DRAM; with a stride prefetcher that keeps up, only the
    misses off a stride wait."""
    npf = (l1 - l2) * a.l2_cycles + l2 * lat
    pf = ((l1 - l1s) - (l2 - l2s)) * a.l2_cycles + (l2 - l2s) * lat
    return pf, npf


def print_fn_tables(P, fns, order, rname, big_enough, cpus, nf, where, unit):
    """The loops table and the functions table (per `unit`: call or frame)."""
    c0 = cpus[0]
    P('| region | function | instructions / %s | loop at | instructions / iteration | iterations / %s | share | %s cycles / iteration | IPC | bottleneck | %s |'
      % (unit, unit, c0, ' | '.join('%s cycles / iteration' % c for c in cpus[1:])))
    P('|---|---|---:|---|---:|---:|---:|---:|---:|---|%s' % ('---:|' * (len(cpus) - 1)))
    for f in sorted(fns, key=order):
        for l in f['loops']:
            m = l['mca']
            P('| %s | `%s` | %.3f M | 0x%x%s | %d | %.0f | %.0f %% | %.1f | %.2f | %s | %s |'
              % (rname(f), l['fn'], f['tot'] / nf / 1e6, l['start'],
                 (' ' + where[l['start']] if l['start'] in where else '') + (' [entry to return]' if l['body'] else ''),
                 l['n'], l['iters'] / nf, 100.0 * l['cov'] / f['tot'], m[c0]['cycles'] / MCA_ITER, m[c0]['ipc'],
                 l['bn'], ' | '.join('%.1f' % (m[c]['cycles'] / MCA_ITER) for c in cpus[1:])))
    P('')
    P('Functions (the part outside the modelled loops at its region\'s mean loop CPI):')
    P('')
    P('| region | function | instructions / %s | in modelled loops | %s |' % (unit, ' | '.join('CPI %s' % c for c in cpus)))
    P('|---|---|---:|---:|%s' % ('---:|' * len(cpus)))
    for f in sorted(fns, key=lambda f: -f['tot']):
        if big_enough(f):
            P('| %s | `%s` | %.3f M | %.0f %% | %s |' % (rname(f), f['fn'], f['tot'] / nf / 1e6,
                                                      100.0 * f['cv'] / f['tot'],
                                                      ' | '.join('%.2f' % f['cpi'][c] for c in cpus)))
    P('')


def print_cov(P, names, cov_r, cpi, cpus):
    P('| region | instructions in modelled loops | %s |' % ' | '.join('CPI %s' % c for c in cpus))
    P('|---|---:|%s' % ('---:|' * len(cpus)))
    for r, name in enumerate(names):
        P('| %s | %.1f %% | %s |' % (name, 100 * cov_r[r], ' | '.join('%.3f' % cpi[r, c] for c in cpus)))
    P('')


def print_mem(P, a, unit, nf, rows):
    """rows: (region name, function, [accesses, L1, L1 strided, L2, L2 strided] over nf units)."""
    P('Cache model (the plugin\'s mem=: L1 %s, L2 %s; per %s; strided = within 2 lines of the same '
      'instruction\'s previous miss):' % (a.l1_label, a.l2_label, unit))
    P('')
    P('| region | function | accesses | L1 misses | of them strided | L2 misses | of them strided |')
    P('|---|---|---:|---:|---:|---:|---:|')
    for rn, name, v in rows:
        P('| %s | `%s` | %.0f | %.0f | %.0f %% | %.0f | %.0f %% |'
          % (rn, name, v[0] / nf, v[1] / nf, 100.0 * v[2] / max(v[1], 1), v[3] / nf, 100.0 * v[4] / max(v[3], 1)))
    P('')


def print_left_out(P, a, lat, rows):
    """rows: (region, L1 misses, L2 misses, stall no prefetch, stall prefetched, departures, their
    cost) per call."""
    P('Left out by llvm-mca, estimated per call (assumptions: an L1 miss that hits the L2 waits %d '
      'cycles, an L2 miss %.0f ns = %.0f cycles, a mispredicted branch %d cycles; each departure from a '
      'modelled loop\'s dominant path counted as one misprediction; in-order: nothing hides a wait):'
      % (a.l2_cycles, a.dram_ns, lat, a.mispredict))
    P('')
    P('| region | L1 misses | L2 misses | stall, no prefetch | stall, strided misses prefetched | departures | their cost |')
    P('|---|---:|---:|---:|---:|---:|---:|')
    for name, l1, l2, npf, pf, dep, mp in rows:
        P('| %s | %.0f | %.0f | %.2f M cycles | %.2f M cycles | %.0f | %.2f M cycles |'
          % (name, l1, l2, npf / 1e6, pf / 1e6, dep, mp / 1e6))
    P('')


def print_per_frame(P, against, rows, cpus, cpi, extra, allm):
    """Per frame: rows of (label, instructions per region); extra[r] = (prefetched stalls, no
    prefetch stalls, mispredictions) per call at the mean allm[r] instructions."""
    K = len(allm)
    P('Per frame at %.1f GHz (the stalls scaled by the frame\'s instructions against the mean of %s; the largest frame at the mean\'s CPI):' % (CLOCK / 1e9, against))
    P('')
    P('| frame | model | instructions | cycles | CPI | frames/s | + stalls, strided misses prefetched: CPI | frames/s | + stalls, no prefetch: CPI | frames/s |')
    P('|---|---|---:|---:|---:|---:|---:|---:|---:|---:|')
    for label, ins in rows:
        for c in cpus:
            base = sum(ins[q] * cpi[q, c] for q in range(K))
            sc = [ins[q] / allm[q] if allm[q] else 0.0 for q in range(K)]
            e1 = sum((extra[q][0] + extra[q][2]) * sc[q] for q in range(K))  # strided prefetched
            e2 = sum((extra[q][1] + extra[q][2]) * sc[q] for q in range(K))  # no prefetch
            n = sum(ins)
            P('| %s | %s | %.2f M | %.2f M | %.2f | %.1f | %.2f | %.1f | %.2f | %.1f |'
              % (label, c, n / 1e6, base / 1e6, base / n, CLOCK / base, (base + e1) / n, CLOCK / (base + e1),
                 (base + e2) / n, CLOCK / (base + e2)))


def cmd_model(a):
    exe = a.exe or os.path.join(a.build, 'tests', 'tools', 'ir_probe')
    a.exe_used = exe
    cpus = a.cpus.split(',')
    regions = a.regions.split(',')
    if len(regions) != 2:
        return cmd_model_k(a, exe, cpus, regions)
    funcs = disassemble(exe)
    cnt = load_blocks(os.path.join(a.run, 'blocks.txt'), funcs)
    counts = [int(x) for x in open(os.path.join(a.run, 'counts.txt')).read().split()]
    first = 1
    if a.calls:  # the run profiled only these calls (run --calls)
        first, last = (int(x) for x in a.calls.split('-'))
        counts = counts[first - 1:last]
    if (first - 1) % 2:
        sys.exit('a53_mca.py: --calls must start at an odd call (the profile\'s parities)')
    nf = len(counts) // 2
    per = [counts[0::2], counts[1::2]]
    prof = {}
    for line in open(os.path.join(a.run, 'prof.txt')):
        o, e, name = line.split(None, 2)
        prof[name.strip()] = (int(o), int(e))
    ptot = [sum(v[r] for v in prof.values()) for r in (0, 1)]

    loops, fns, rtot = [], [], [0, 0]
    for name, ins in funcs.items():
        for r in (0, 1):
            tot = sum(cnt.get(addr, (0, 0))[r] for addr, _, _ in ins)
            if tot == 0:
                continue
            rtot[r] += tot
            fl = model_loops(a, cpus, name, r, ins, cnt, r, tot) if tot >= a.min_share * ptot[r] else []
            fns.append({'fn': name, 'reg': r, 'tot': tot, 'loops': fl})
            loops.extend(fl)
    # fallback CPI: the region's modelled loops, weighted by the instructions they cover
    fb = {}
    for r in (0, 1):
        cv = sum(l['cov'] for l in loops if l['reg'] == r)
        for c in cpus:
            fb[r, c] = sum(l['cov'] * l['cpi'][c] for l in loops if l['reg'] == r) / cv
    cyc = {(r, c): 0.0 for r in (0, 1) for c in cpus}
    charge(fns, fb, cpus, cyc)
    cpi = {(r, c): cyc[r, c] / rtot[r] for r in (0, 1) for c in cpus}
    where = loop_sources(a, funcs, loops)
    cov_r = [sum(f['cv'] for f in fns if f['reg'] == r) / rtot[r] for r in (0, 1)]

    out = []
    P = out.append
    c0 = cpus[0]
    P('%s, run %s: %d calls of each region (%s = odd, %s = even); instructions from the block '
      'profile %.0f / %.0f, from prof= %.0f / %.0f.' % (exe, a.run, nf, regions[0], regions[1],
                                                        rtot[0], rtot[1], ptot[0], ptot[1]))
    P('')
    P('Loops (per call of the region: instructions of the function, iterations; share = the '
      'function\'s instructions the loop covers; cycles per iteration and IPC of llvm-mca %s, '
      'its bottleneck; %s for comparison):' % (c0, ', '.join(cpus[1:])))
    P('')
    print_fn_tables(P, fns, lambda f: (f['reg'], -f['tot']), lambda f: regions[f['reg']],
                    lambda f: f['tot'] >= a.min_share * ptot[f['reg']], cpus, nf, where, 'call')
    print_cov(P, regions, cov_r, cpi, cpus)

    # what the model leaves out: cache misses (the plugin's cache model, mem=) and mispredictions
    mem = load_mem(a.run, lambda f: (f[0], int(f[1])))
    lat = a.dram_ns * 1e-9 * CLOCK
    extra = {}
    for r in (0, 1):
        acc, l1, l1s, l2, l2s = [sum(v[i] for k, v in mem.items() if k[1] == r) for i in range(5)]
        pf, npf = stalls(a, lat, l1, l1s, l2, l2s)
        mp = sum(l['dep'] for l in loops if l['reg'] == r) * a.mispredict
        extra[r] = (pf / nf, npf / nf, mp / nf, (acc, l1, l1s, l2, l2s))
    if mem:
        print_mem(P, a, 'call', nf, [(regions[r], name, v)
                                 for (name, r), v in sorted(mem.items(), key=lambda kv: (kv[0][1], -kv[1][1]))
                                 if v[1] >= 0.02 * nf * 1000 or v[3] >= 0.02 * nf * 1000])
    print_left_out(P, a, lat, [(regions[r], extra[r][3][1] / nf, extra[r][3][3] / nf, extra[r][1], extra[r][0],
                                extra[r][2] / a.mispredict, extra[r][2]) for r in (0, 1)])
    if a.frames_from > 0:
        fr = list(range(a.frames_from - 1, nf))
        big = max(fr, key=lambda i: per[0][i] + per[1][i])
        rows = [('mean of calls %d..%d' % (a.frames_from, nf), [sum(per[r][i] for i in fr) / len(fr) for r in (0, 1)]),
                ('largest (call %d)' % (big + 1), [per[0][big], per[1][big]])]
        print_per_frame(P, 'all calls', rows, cpus, cpi, extra, [sum(per[r]) / nf for r in (0, 1)])
    else:
        # every call the same kind (e.g. one tracker of pft_soak): per call, both parities
        allc = [(counts[i], i % 2) for i in range(a.skip, len(counts))]
        allm = [sum(per[r]) / nf for r in (0, 1)]
        P('Per call (calls %d..%d, both parities; the stalls scaled by the call\'s instructions):' % (a.skip + 1, len(counts)))
        P('')
        P('| call | model | instructions | cycles | CPI | + stalls, strided prefetched: CPI | + stalls, no prefetch: CPI |')
        P('|---|---|---:|---:|---:|---:|---:|')
        big = max(allc, key=lambda x: x[0])
        for label, sel in (('mean', allc), ('largest', [big])):
            for c in cpus:
                ins = sum(x[0] for x in sel) / len(sel)
                base = sum(x[0] * cpi[x[1], c] for x in sel) / len(sel)
                e1 = sum((extra[x[1]][0] + extra[x[1]][2]) * x[0] / allm[x[1]] for x in sel) / len(sel)
                e2 = sum((extra[x[1]][1] + extra[x[1]][2]) * x[0] / allm[x[1]] for x in sel) / len(sel)
                P('| %s | %s | %.0f | %.0f | %.2f | %.2f | %.2f |' % (label, c, ins, base, base / ins,
                                                                   (base + e1) / ins, (base + e2) / ins))
    print('\n'.join(out))


# ------------------------------------------------------------------- K regions per frame
def call_graph(funcs):
    """{function: the functions it calls or branches into directly}: a bl, or a b / conditional
    branch to another function's first instruction (a tail call, a jump into a .cold part)."""
    entry = {ins[0][0]: n for n, ins in funcs.items() if ins}
    g = {}
    for n, ins in funcs.items():
        s = set()
        for addr, mn, ops in ins:
            t = branch_target(mn, ops)
            if t is not None and t in entry and entry[t] != n:
                s.add(entry[t])
        g[n] = s
    return g


def reach(g, root):
    seen, todo = {root}, [root]
    while todo:
        for m in g.get(todo.pop(), ()):
            if m not in seen:
                seen.add(m)
                todo.append(m)
    return seen


def cmd_model_k(a, exe, cpus, regions):
    """K regions per frame (K = len(--regions), not 2): the work markers bracket K calls in turn
    each frame (ir_probe -c: stage, flat, map, manager, after). The plugin counts blocks in odd
    and even regions only, and with K odd a region's parity changes from frame to frame, so the
    two columns are summed and each function is given to the region whose root function
    (--roots, default irp_f_NAME for each region name) reaches it through direct calls in the
    disassembly. A function reached from several roots (or none: the probe's own wrapper) is
    shared: its instructions, those outside the executable (the C library) and the markers' are
    what the region's count (out=, exact) holds beyond its own functions, and they are charged
    per region in that proportion (the shared functions at their own modelled CPI, the rest at the
    region's mean). A function's loops are found and modelled on its counts over all regions."""
    K = len(regions)
    roots = a.roots.split(',') if a.roots else ['irp_f_' + r for r in regions]
    if len(roots) != K:
        sys.exit('a53_mca.py: --roots names %d functions for %d regions' % (len(roots), K))
    funcs = disassemble(exe)
    for r in roots:
        if r not in funcs:
            sys.exit('a53_mca.py: root function %s not in %s' % (r, exe))
    cnt2 = load_blocks(os.path.join(a.run, 'blocks.txt'), funcs)
    cnt = {ad: [c[0] + c[1], 0] for ad, c in cnt2.items()}  # all regions, in column 0
    counts = [int(x) for x in open(os.path.join(a.run, 'counts.txt')).read().split()]
    first = 1
    if a.calls:  # the run profiled only these calls (run --calls)
        first, last = (int(x) for x in a.calls.split('-'))
        counts = counts[first - 1:last]
    if (first - 1) % K or len(counts) % K:
        sys.exit('a53_mca.py: the profiled calls must be whole frames of %d calls' % K)
    f0 = (first - 1) // K  # frames before the first profiled one
    nf = len(counts) // K
    per = [counts[k::K] for k in range(K)]
    ctot = [sum(per[k]) for k in range(K)]
    ptot = 0
    for line in open(os.path.join(a.run, 'prof.txt')):
        o, e, name = line.split(None, 2)
        ptot += int(o) + int(e)
    g = call_graph(funcs)
    owner = {}
    for k, r in enumerate(roots):
        for f in reach(g, r):
            owner.setdefault(f, set()).add(k)

    loops, fns = [], []
    shared_min = a.min_share * sum(ctot)
    for name, ins in funcs.items():
        tot = sum(cnt.get(addr, (0, 0))[0] for addr, _, _ in ins)
        if tot == 0:
            continue
        ks = owner.get(name, set())
        reg = next(iter(ks)) if len(ks) == 1 else -1  # -1: shared
        big = tot >= (a.min_share * ctot[reg] if reg >= 0 else shared_min)
        fl = model_loops(a, cpus, name, reg, ins, cnt, 0, tot) if big else []
        fns.append({'fn': name, 'reg': reg, 'ks': ks, 'tot': tot, 'loops': fl})
        loops.extend(fl)
    # fallback CPI: a region's modelled loops (the shared functions': every loop's)
    fb = {}
    for r in list(range(K)) + [-1]:
        sel = [l for l in loops if l['reg'] == r or r == -1]
        cv = sum(l['cov'] for l in sel)
        for c in cpus:
            fb[r, c] = sum(l['cov'] * l['cpi'][c] for l in sel) / cv if cv else fb[-1, c] if (-1, c) in fb else 1.0
    for r in range(K):  # a region without a modelled loop of its own: every loop's
        if not any(l['reg'] == r for l in loops):
            for c in cpus:
                sel = loops
                fb[r, c] = sum(l['cov'] * l['cpi'][c] for l in sel) / sum(l['cov'] for l in sel)
    cyc = {(r, c): 0.0 for r in list(range(K)) + [-1] for c in cpus}
    itot = {r: 0 for r in list(range(K)) + [-1]}
    for f in fns:
        itot[f['reg']] += f['tot']
    charge(fns, fb, cpus, cyc)
    # each region's count beyond its own functions: the shared functions, the C library, the
    # markers; the shared functions' instructions given out in proportion to it
    resid = [ctot[r] - itot[r] for r in range(K)]
    if min(resid) < 0:
        sys.exit('a53_mca.py: a region\'s own functions exceed its count (%s): wrong roots?' % resid)
    rs = sum(resid)
    share = [x / rs if rs else 0.0 for x in resid]
    cpi = {}
    for r in range(K):
        for c in cpus:
            own = cyc[r, c] / itot[r] if itot[r] else fb[r, c]
            shr = itot[-1] * share[r]
            sh_cpi = cyc[-1, c] / itot[-1] if itot[-1] else own
            rest = max(0.0, resid[r] - shr)  # outside the executable's functions: the region's CPI
            cpi[r, c] = (itot[r] * own + shr * sh_cpi + rest * own) / ctot[r] if ctot[r] else 0.0
    where = loop_sources(a, funcs, loops)

    def rname(f):
        return regions[f['reg']] if f['reg'] >= 0 else 'shared (%s)' % ('+'.join(regions[k] for k in sorted(f['ks'])) or 'none')
    out = []
    P = out.append
    c0 = cpus[0]
    P('%s, run %s: %d frames (%d to %d) of %d calls each (%s; roots %s); instructions of the '
      'profiled calls from out= %.0f, from the block profile %.0f, from prof= %.0f.'
      % (exe, a.run, nf, f0 + 1, f0 + nf, K, ', '.join(regions), ', '.join(roots), sum(ctot),
         sum(itot.values()), ptot))
    P('')
    P('Loops (per frame: instructions of the function, iterations; share = the function\'s '
      'instructions the loop covers; cycles per iteration and IPC of llvm-mca %s, its bottleneck; '
      '%s for comparison):' % (c0, ', '.join(cpus[1:])))
    P('')
    print_fn_tables(P, fns, lambda f: (f['reg'] if f['reg'] >= 0 else K, -f['tot']), rname,
                    lambda f: f['tot'] >= a.min_share * (ctot[f['reg']] if f['reg'] >= 0 else sum(ctot)),
                    cpus, nf, where, 'frame')
    P('Where each region\'s instructions are (per call): its own functions (reached from its root '
      'only), the rest (shared functions, the C library, the markers) and the shared functions\' '
      'part of it given to the region (%.4f M per frame in all, at CPI %s):'
      % (itot[-1] / nf / 1e6, ' / '.join('%.2f' % (cyc[-1, c] / itot[-1] if itot[-1] else 0.0) for c in cpus)))
    P('')
    P('| region | instructions / call | own functions | rest | of it shared functions |')
    P('|---|---:|---:|---:|---:|')
    for r in range(K):
        P('| %s | %.4f M | %.4f M | %.4f M | %.4f M |' % (regions[r], ctot[r] / nf / 1e6, itot[r] / nf / 1e6,
                                                         resid[r] / nf / 1e6, itot[-1] * share[r] / nf / 1e6))
    P('')
    cov_r = []
    for r in range(K):
        cv = sum(f['cv'] for f in fns if f['reg'] == r) + sum(f['cv'] for f in fns if f['reg'] == -1) * share[r]
        cov_r.append(cv / ctot[r] if ctot[r] else 0.0)
    print_cov(P, regions, cov_r, cpi, cpus)

    # what the model leaves out: cache misses (the plugin's mem=, both parities summed) and
    # mispredictions; a shared function's (or one outside the executable) in the same proportion
    mem = load_mem(a.run, lambda f: f[0])
    regof = {f['fn']: f['reg'] for f in fns}
    lat = a.dram_ns * 1e-9 * CLOCK
    extra, memr = {}, {}
    for r in range(K):
        v5 = [0.0] * 5
        for name, v in mem.items():
            w = 1.0 if regof.get(name, -1) == r else share[r] if regof.get(name, -1) == -1 else 0.0
            v5 = [x + w * y for x, y in zip(v5, v)]
        acc, l1, l1s, l2, l2s = v5
        pf, npf = stalls(a, lat, l1, l1s, l2, l2s)
        dep = sum(l['dep'] * (1.0 if l['reg'] == r else share[r] if l['reg'] == -1 else 0.0) for l in loops)
        extra[r] = (pf / nf, npf / nf, dep * a.mispredict / nf)
        memr[r] = (acc / nf, l1 / nf, l1s / nf, l2 / nf, l2s / nf, dep / nf)
    if mem:
        print_mem(P, a, 'frame', nf, [(regions[regof.get(name, -1)] if regof.get(name, -1) >= 0 else 'shared', name, v)
                                      for name, v in sorted(mem.items(), key=lambda kv: (regof.get(kv[0], -1) % (K + 1), -kv[1][1]))
                                      if v[1] >= 0.02 * nf * 1000 or v[3] >= 0.02 * nf * 1000])
    print_left_out(P, a, lat, [(regions[r], memr[r][1], memr[r][3], extra[r][1], extra[r][0], memr[r][5], extra[r][2])
                               for r in range(K)])

    # per call and per frame over frames N..end (absolute frame numbers)
    lo = max(a.frames_from, f0 + 1) - f0 - 1
    fr = list(range(lo, nf))
    allm = [ctot[r] / nf for r in range(K)]
    P('Per call, mean of frames %d..%d at %.1f GHz (cycles = instructions x the region\'s modelled CPI; '
      'the stalls scaled by the call\'s instructions against the mean of the profiled frames):'
      % (f0 + lo + 1, f0 + nf, CLOCK / 1e9))
    P('')
    P('| call | model | instructions | cycles | CPI | + stalls, strided misses prefetched: cycles | CPI | + stalls, no prefetch: cycles | CPI |')
    P('|---|---|---:|---:|---:|---:|---:|---:|---:|')
    for r in list(range(K)) + [None]:
        for c in cpus:
            rr = range(K) if r is None else [r]
            ins = sum(sum(per[q][i] for i in fr) / len(fr) for q in rr)
            base = sum(sum(per[q][i] for i in fr) / len(fr) * cpi[q, c] for q in rr)
            sc = {q: (sum(per[q][i] for i in fr) / len(fr) / allm[q] if allm[q] else 0.0) for q in rr}
            e1 = sum((extra[q][0] + extra[q][2]) * sc[q] for q in rr)
            e2 = sum((extra[q][1] + extra[q][2]) * sc[q] for q in rr)
            P('| %s | %s | %.3f M | %.3f M | %.2f | %.3f M | %.2f | %.3f M | %.2f |'
              % ('**total**' if r is None else regions[r], c, ins / 1e6, base / 1e6, base / ins if ins else 0.0,
                 (base + e1) / 1e6, (base + e1) / ins if ins else 0.0, (base + e2) / 1e6,
                 (base + e2) / ins if ins else 0.0))
    P('')
    tot_f = [sum(per[q][i] for q in range(K)) for i in range(nf)]
    big = max(fr, key=lambda i: tot_f[i])
    rows = [('mean of frames %d..%d' % (f0 + lo + 1, f0 + nf), [sum(per[q][i] for i in fr) / len(fr) for q in range(K)]),
            ('largest (frame %d)' % (f0 + big + 1), [per[q][big] for q in range(K)])]
    print_per_frame(P, 'the profiled frames', rows, cpus, cpi, extra, allm)
    print('\n'.join(out))


# ----------------------------------------------------------------------------------- check
# Small kernels, llvm-mca's steady state per iteration against what the A53 does. "expected":
# from the pipeline's dual-issue rule (two ALU instructions a cycle) and from measurements on
# an A53 published with daniestevez/qsdr (qsdr-benchmarks/tests/instruction_benchmark/aarch64:
# add result latency 1; fadd and fmul .4s issue 1, result latency 4; ldr d result latency 3;
# ldr q and ldp issue 2 cycles), as a loop-carried chain would see them.
CHECKS = [
    ('8 independent adds', 'add x1, x1, #1\nadd x2, x2, #1\nadd x3, x3, #1\nadd x4, x4, #1\n'
     'add x5, x5, #1\nadd x6, x6, #1\nadd x7, x7, #1\nadd x8, x8, #1\n', 4.0,
     'dual issue of two ALU instructions'),
    ('8 dependent adds', 'add x1, x1, #1\n' * 8, 8.0, 'add result latency 1 (qsdr: at most 8)'),
    ('4 dependent fadd s', 'fadd s0, s0, s1\n' * 4, 16.0, 'fadd result latency 4 (qsdr: .4s; scalar assumed the same)'),
    ('4 dependent fmul s', 'fmul s0, s0, s1\n' * 4, 16.0, 'fmul result latency 4 (qsdr: .4s; scalar assumed the same)'),
    ('4 independent fmul .4s', 'fmul v0.4s, v0.4s, v31.4s\nfmul v1.4s, v1.4s, v31.4s\n'
     'fmul v2.4s, v2.4s, v31.4s\nfmul v3.4s, v3.4s, v31.4s\n', 4.0, 'fmul .4s issue 1 (qsdr)'),
    ('4 (ldr d, dependent fadd) pairs, fadd chain', 'ldr d0, [x0]\nfadd d1, d1, d0\nldr d2, [x0, #8]\n'
     'fadd d1, d1, d2\nldr d3, [x0, #16]\nfadd d1, d1, d3\nldr d4, [x0, #24]\nfadd d1, d1, d4\n', 16.0,
     'the fadd chain (4 x 4), the loads hidden (ldr d latency 3, qsdr)'),
    ('pointer chase: ldr x0, [x0]', 'ldr x0, [x0]\n', 3.0, 'load-to-use 3 (qsdr: ldr d; assumed the same for x)'),
    ('4 independent ldr q', 'ldr q0, [x0]\nldr q1, [x0, #16]\nldr q2, [x0, #32]\nldr q3, [x0, #48]\n', 8.0,
     'ldr q issues in 2 cycles (qsdr)'),
    ('2 independent ldp d', 'ldp d0, d1, [x0]\nldp d2, d3, [x0, #16]\n', 4.0, 'ldp issues in 2 cycles (qsdr)'),
]


def model_cpis(path):
    """The region CPI rows of a model report: {region: [cpi per llvm-mca model]}, and the models."""
    cpis, cpus, on = {}, None, False
    for line in open(path):
        if line.startswith('| region | instructions in modelled loops'):
            cpus = [c.strip()[4:] for c in line.strip().strip('|').split('|')[2:]]
            on = True
        elif on and line.startswith('|') and not line.startswith('|---'):
            f = [c.strip() for c in line.strip().strip('|').split('|')]
            cpis[f[0]] = [float(x) for x in f[2:]]
        elif on and not line.startswith('|'):
            break
    if not cpis:
        sys.exit('a53_mca.py: no region CPI table in %s' % path)
    return cpis, cpus


def cmd_three(a):
    """The three calls of ir_probe per frame from two runs: MARKS 2 (stage, manager) and MARKS 1
    (map, manager), each with its model report; the manager's counts must be the same in both."""
    def counts(run):
        c = [int(x) for x in open(os.path.join(run, 'counts.txt')).read().split()]
        return c[0::2], c[1::2]
    st, mg = counts(a.run_stage)
    mp, mg1 = counts(a.run_map)
    if mg != mg1:
        sys.exit('a53_mca.py: the two runs\' manager counts differ: not the same frames or settings')
    c2, cpus = model_cpis(a.model_stage)
    c1, cpus1 = model_cpis(a.model_map)
    if cpus != cpus1:
        sys.exit('a53_mca.py: the two reports used different llvm-mca models')
    fr = range(a.frames_from - 1, len(st))
    print('| model | instructions (stage + map + manager) | stage / map / manager CPI | cycles | CPI | frames/s at %.1f GHz | largest frame: cycles | frames/s |' % (CLOCK / 1e9))
    print('|---|---:|---|---:|---:|---:|---:|---:|')
    for k, cpu in enumerate(cpus):
        cs, cm, cg = c2['stage'][k], c1['map'][k], c1['manager'][k]
        ins = [st[i] + mp[i] + mg[i] for i in fr]
        cyc = [st[i] * cs + mp[i] * cm + mg[i] * cg for i in fr]
        mi, mc, xc = sum(ins) / len(fr), sum(cyc) / len(fr), max(cyc)
        print('| %s | %.2f M (%.2f / %.2f / %.2f) | %.3f / %.3f / %.3f | %.2f M | %.2f | %.1f | %.2f M | %.1f |'
              % (cpu, mi / 1e6, sum(st[i] for i in fr) / len(fr) / 1e6, sum(mp[i] for i in fr) / len(fr) / 1e6,
                 sum(mg[i] for i in fr) / len(fr) / 1e6, cs, cm, cg, mc / 1e6, mc / mi, CLOCK / mc, xc / 1e6, CLOCK / xc))


def cmd_check(a):
    print('| kernel | expected on the A53 | llvm-mca cortex-a53 | llvm-mca cortex-a55 | source of the expectation |')
    print('|---|---:|---:|---:|---|')
    for name, body, exp, why in CHECKS:
        r = [llvm_mca('L0:\n' + body, a.mca, cpu) for cpu in ('cortex-a53', 'cortex-a55')]
        print('| %s | %.0f | %.2f | %.2f | %s |' % (name, exp, r[0]['cycles'] / MCA_ITER, r[1]['cycles'] / MCA_ITER, why))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    sub = ap.add_subparsers(dest='cmd', required=True)
    r = sub.add_parser('run')
    r.add_argument('--build', help='an aarch64 build: its tests/tools/ir_probe runs')
    r.add_argument('--exe', help='another program with the work markers (e.g. tests/soak/pft_soak)')
    r.add_argument('--args', help='its arguments (one string; default: ir_probe\'s)')
    r.add_argument('--frames', help='ir_probe\'s frames (pft sim --format raw)')
    r.add_argument('--size', default='384x288')
    r.add_argument('--n', type=int, default=100)
    r.add_argument('--out', required=True)
    r.add_argument('--calls', help='I-J: profile only calls I..J (a program running several trackers in turn)')
    r.add_argument('--mem', action='store_true', help='also the plugin\'s cache model (mem=, slow)')
    r.add_argument('--l1', type=int, default=32768, help='L1 data cache bytes (4-way)')
    r.add_argument('--l2', type=int, default=524288, help='L2 bytes (16-way)')
    m = sub.add_parser('model')
    m.add_argument('--build', help='an aarch64 build: its tests/tools/ir_probe')
    m.add_argument('--exe', help='the executable that ran (default: BUILD/tests/tools/ir_probe)')
    m.add_argument('--debug-exe', help='the same program built with -g: each loop\'s source line')
    m.add_argument('--regions', default='stage,manager',
                   help='names of the odd and the even regions; K names other than 2: K calls per frame '
                        '(ir_probe -c: stage,flat,map,manager,after)')
    m.add_argument('--roots', help='with K regions: the function each region\'s call runs, comma-separated '
                                   '(default irp_f_NAME, ir_probe -c\'s)')
    m.add_argument('--cpus', default='cortex-a53,cortex-a55', help='llvm-mca models, the first is the model')
    m.add_argument('--frames-from', type=int, default=2,
                   help='per-frame table (stage + manager) over frames N..end; 0: a per-call table instead '
                        '(with K regions: the tables over frames N..end, N a frame of the whole run)')
    m.add_argument('--calls', help='I-J: the calls the run profiled (run --calls)')
    m.add_argument('--skip', type=int, default=0, help='with --frames-from 0: calls left out at the start')
    m.add_argument('--run', required=True)
    m.add_argument('--min-share', type=float, default=0.005,
                   help='functions below this share of their region keep the fallback CPI')
    m.add_argument('--mca', default='llvm-mca')
    m.add_argument('--dram-ns', type=float, default=150.0, help='DRAM latency per missed line, ns')
    m.add_argument('--l2-cycles', type=int, default=13, help='L2 hit latency, cycles (assumed)')
    m.add_argument('--mispredict', type=int, default=8, help='cycles lost per mispredicted branch')
    m.add_argument('--l1-label', default='32 KB 4-way', help='the cache model the run used (for the table)')
    m.add_argument('--l2-label', default='512 KB 16-way', help='the cache model the run used (for the table)')
    t = sub.add_parser('three', help='the three calls per frame from a MARKS 2 and a MARKS 1 run')
    t.add_argument('--run-stage', required=True, help='run with ir_probe MARKS 2 (stage, manager)')
    t.add_argument('--model-stage', required=True, help='its model report')
    t.add_argument('--run-map', required=True, help='run with ir_probe MARKS 1 (map, manager), same frames and settings')
    t.add_argument('--model-map', required=True, help='its model report (model --regions map,manager)')
    t.add_argument('--frames-from', type=int, default=2)
    c = sub.add_parser('check')
    c.add_argument('--mca', default='llvm-mca')
    a = ap.parse_args()
    {'run': cmd_run, 'model': cmd_model, 'three': cmd_three, 'check': cmd_check}[a.cmd](a)


if __name__ == '__main__':
    main()
