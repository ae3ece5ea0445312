#!/usr/bin/env python3
"""Equal-error time of snell's path tracer against Mitsuba 3 on Mitsuba's cornell_box().

What it does, in one run
------------------------
(a) Mitsuba: loads ``mi.cornell_box()`` in variant ``llvm_ad_rgb`` with the film set to
    512 x 512 and a box reconstruction filter (``{'type': 'box'}``; the dict's own film is
    256 x 256 with a Gaussian filter), integrator ``path`` max_depth 8, rr_depth 5, sampler
    ``independent``.  It renders once untimed (warm-up: JIT compilation, or a load from Dr.Jit's
    kernel cache in ~/.drjit), then times ``mi.render(spp=64, seed=0)`` up to ``dr.sync_thread()``
    (best of --repeats).  Scene loading and compilation are not in that time.  The image's RMSE
    is taken against a converged Mitsuba reference (--mitsuba-ref); when that file is missing it
    is rendered first, --ref-spp samples (default 4096) in chunks of --ref-chunk (default 256),
    each chunk with its own seed (1000, 1001, ...; never the timed image's seed 0), averaged in
    float64 and written as float32 RGB EXR.
(b) snell: runs ``SNELL render SCENE --integrator path --spp N --output OUT.exr`` (plus any
    --snell-arg) from the repository root for a rising series of N (--spp-list), timing each
    process's wall clock (so snell's times include process start, scene load and BVH build,
    which Mitsuba's do not) and the render's own time (from snell's closing line: its samples
    over its rate, the like-for-like figure), and takes each image's RMSE against a snell reference
    (--snell-ref; rendered with ``--spp`` --snell-ref-spp, default 4096, when missing).  The
    series stops at the first N whose RMSE is at or below Mitsuba's 64-spp RMSE (--no-stop runs
    it all).  The equal-error time is interpolated in log-log between the two runs that bracket
    Mitsuba's RMSE; the first measured run that reaches it is printed too.
(c) Prints a table, the ratio snell_time / mitsuba_time, and the agreement of the two
    references (snell's as A, Mitsuba's as B): mean relative difference sum|A-B|/sum|B|
    (the 2 % check), RMSE and per-channel mean ratios.  Both references carry their own
    noise; the script prints an estimate of the mean relative difference that noise alone gives.

Each side's RMSE is measured against its own renderer's reference, so the equal-error time
compares noise, not bias; bias shows up in (c).

How to run
----------
    pip install mitsuba numpy         # mitsuba 3.9.1 was used to write this
    apt-get install libllvm19         # for the llvm_* variants (Debian package)
    cargo build --release
    nice -n 19 python3 bench/vs-mitsuba.py                       # all of (a), (b), (c)
    python3 bench/vs-mitsuba.py --skip-snell                     # (a) only (makes the Mitsuba reference)
    python3 bench/vs-mitsuba.py --skip-snell --snell-ref X.exr   # (a), and (c) with X.exr as snell's reference

DRJIT_LIBLLVM_PATH is set to /usr/lib/x86_64-linux-gnu/libLLVM-19.so when it is unset and that
file exists.  EXRs are read with mitsuba.Bitmap (as RGB; alpha dropped, one channel broadcast).
The metric is compare() from compare_exr.py (imported from --peers, default ../shared/peers
beside the checkout, when there; otherwise the copy below).  This script is a manual benchmark, not run by CI.
"""
import argparse
import math
import os
import re
import subprocess
import sys
import time

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
LIBLLVM = '/usr/lib/x86_64-linux-gnu/libLLVM-19.so'
WIDTH = HEIGHT = 512
MAX_DEPTH = 8
MITSUBA_SPP = 64
MITSUBA_SEED = 0
WARMUP_SEED = 1
REF_SEED_BASE = 1000


def compare_fallback(a, b):
    """Copy of the core of compare() in ../shared/peers/compare_exr.py (B is the reference)."""
    if a.shape != b.shape:
        raise SystemExit(f'shape mismatch: {a.shape} vs {b.shape}')
    d = a - b
    res = {
        'mean_rel_diff': float(np.abs(d).sum() / np.abs(b).sum()),
        'rmse': float(np.sqrt(np.mean(d * d))),
        'mean_a': [float(x) for x in a.reshape(-1, 3).mean(0)],
        'mean_b': [float(x) for x in b.reshape(-1, 3).mean(0)],
        'max_abs_diff': float(np.abs(d).max()),
        'nonfinite_a': int((~np.isfinite(a)).sum()),
        'nonfinite_b': int((~np.isfinite(b)).sum()),
    }
    res['mean_ratio_a_over_b'] = [x / y if y else float('nan') for x, y in zip(res['mean_a'], res['mean_b'])]
    return res


def get_compare(peers):
    if peers and os.path.isfile(os.path.join(peers, 'compare_exr.py')):
        sys.path.insert(0, peers)
        sys.dont_write_bytecode = True  # no __pycache__ in the peers folder
        try:
            import compare_exr  # noqa: only compare() is used: its read_exr() switches Mitsuba's variant
            return compare_exr.compare, os.path.join(peers, 'compare_exr.py')
        except Exception as e:  # pragma: no cover
            print(f'note: could not import compare_exr from {peers} ({e}); using the built-in copy')
        finally:
            sys.path.remove(peers)
    return compare_fallback, 'built-in copy of compare_exr.compare'


def import_mitsuba(threads):
    if 'DRJIT_LIBLLVM_PATH' not in os.environ and os.path.exists(LIBLLVM):
        os.environ['DRJIT_LIBLLVM_PATH'] = LIBLLVM
    import drjit as dr
    import mitsuba as mi
    mi.set_variant('llvm_ad_rgb')
    if threads:
        dr.set_thread_count(threads)
    return mi, dr


def read_exr(mi, path):
    """Linear RGB float64 H x W x 3 via mitsuba.Bitmap (no variant change)."""
    a = np.array(mi.Bitmap(path), dtype=np.float64)
    if a.ndim == 2:
        a = a[..., None]
    if a.shape[2] == 1:
        a = np.repeat(a, 3, axis=2)
    return a[..., :3]


def write_exr(mi, path, img):
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    mi.Bitmap(np.ascontiguousarray(img, dtype=np.float32)).write(path)


def mitsuba_scene(mi):
    d = mi.cornell_box()
    d['sensor']['film']['width'] = WIDTH
    d['sensor']['film']['height'] = HEIGHT
    d['sensor']['film']['rfilter'] = {'type': 'box'}
    d['sensor']['sampler']['type'] = 'independent'
    d['integrator'] = {'type': 'path', 'max_depth': MAX_DEPTH, 'rr_depth': 5}
    return mi.load_dict(d)


def mitsuba_render(mi, dr, scene, spp, seed):
    t0 = time.perf_counter()
    img = mi.render(scene, spp=spp, seed=seed)
    dr.eval(img)
    dr.sync_thread()
    return img, time.perf_counter() - t0


def make_mitsuba_ref(mi, dr, scene, path, spp, chunk):
    n = max(1, math.ceil(spp / chunk))
    print(f'mitsuba reference: {path} missing; rendering {n} x {chunk} spp (seeds {REF_SEED_BASE}..{REF_SEED_BASE + n - 1})')
    acc = None
    t0 = time.perf_counter()
    for i in range(n):
        img, t = mitsuba_render(mi, dr, scene, chunk, REF_SEED_BASE + i)
        a = np.array(img, dtype=np.float64)
        acc = a if acc is None else acc + a
        print(f'  chunk {i + 1}/{n}: {t:.1f} s', flush=True)
    write_exr(mi, path, acc / n)
    total = time.perf_counter() - t0
    print(f'mitsuba reference: {n * chunk} spp in {total:.1f} s, written to {path}')
    return total


def run_snell(snell, scene, spp, out, extra):
    """The process's wall-clock time, and the render's own (snell's closing line: its samples
    over its rate, which leave out process start, scene load and writing, as Mitsuba's time
    leaves out loading and compilation)."""
    cmd = [snell, 'render', scene, '--integrator', 'path', '--spp', str(spp), '--output', out] + extra
    t0 = time.perf_counter()
    p = subprocess.run(cmd, cwd=REPO, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    t = time.perf_counter() - t0
    if p.returncode != 0:
        sys.stdout.write(p.stdout)
        raise SystemExit(f'snell failed (exit {p.returncode}): {" ".join(cmd)}')
    m = re.search(r'(\d+) samples in [\d.]+ s \(([\d.]+) M samples/s', p.stdout)
    render = int(m.group(1)) / (float(m.group(2)) * 1e6) if m else t
    return t, render


def loglog_time(rows, target):
    """rows: [(spp, time, rmse)] in run order.  Time at which RMSE reaches target, interpolated
    in log(time)-log(rmse) between the bracketing runs; (time, first_row_reaching, note)."""
    for i, (spp, t, e) in enumerate(rows):
        if e <= target:
            if i == 0:
                return t, rows[i], 'the first run already reaches it: its time is an upper bound'
            _, t1, e1 = rows[i - 1]
            if e1 == e:
                return t, rows[i], ''
            f = (math.log(target) - math.log(e1)) / (math.log(e) - math.log(e1))
            return math.exp(math.log(t1) + f * (math.log(t) - math.log(t1))), rows[i], ''
    return None, None, 'no run reached it'


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--snell', default='target/release/snell', help='snell binary (relative to the repo root)')
    ap.add_argument('--scene', default='scenes/cornell.toml', help='snell scene (relative to the repo root)')
    ap.add_argument('--mitsuba-ref', default=os.path.join(REPO, 'target', 'vs-mitsuba', 'mitsuba-ref.exr'),
                    help='converged Mitsuba reference EXR (made with --ref-spp if missing)')
    ap.add_argument('--ref-spp', type=int, default=4096, help='spp of the Mitsuba reference if it must be made')
    ap.add_argument('--ref-chunk', type=int, default=256, help='spp per Mitsuba reference render call')
    ap.add_argument('--snell-ref', default=os.path.join(REPO, 'target', 'vs-mitsuba', 'snell-ref.exr'),
                    help='snell reference EXR (made with --snell-ref-spp if missing)')
    ap.add_argument('--snell-ref-spp', type=int, default=4096)
    ap.add_argument('--spp-list', default='4,8,16,32,64,128,256,512,1024',
                    help='comma-separated rising spp series for snell')
    ap.add_argument('--no-stop', action='store_true', help='run the whole series, not only up to the first run that reaches the target')
    ap.add_argument('--snell-arg', action='append', default=[], help='extra argument for snell (repeatable)')
    ap.add_argument('--repeats', type=int, default=1, help='timed repeats per measurement (the best is kept)')
    ap.add_argument('--threads', type=int, default=0, help="Dr.Jit thread count (default: Dr.Jit's own, all cores)")
    ap.add_argument('--workdir', default=os.path.join(REPO, 'target', 'vs-mitsuba'), help='where snell images and the Mitsuba 64-spp image go')
    ap.add_argument('--peers', default=os.environ.get('SNELL_PEERS', os.path.join(REPO, '..', 'shared', 'peers')),
                    help='folder holding compare_exr.py (default: ../shared/peers beside the checkout)')
    ap.add_argument('--skip-snell', action='store_true', help='skip (b); (c) still runs if --snell-ref exists')
    args = ap.parse_args()

    compare, compare_src = get_compare(args.peers)
    mi, dr = import_mitsuba(args.threads)
    os.makedirs(args.workdir, exist_ok=True)
    print(f'mitsuba {mi.__version__}, drjit {dr.__version__}, variant {mi.variant()}, '
          f'{dr.thread_count()} Dr.Jit threads, {os.cpu_count()} CPUs; metric: {compare_src}')

    # (a) Mitsuba
    t0 = time.perf_counter()
    scene = mitsuba_scene(mi)
    t_load = time.perf_counter() - t0
    ref_time = None
    if not os.path.exists(args.mitsuba_ref):
        ref_time = make_mitsuba_ref(mi, dr, scene, args.mitsuba_ref, args.ref_spp, args.ref_chunk)
    mref = read_exr(mi, args.mitsuba_ref)
    _, t_warm = mitsuba_render(mi, dr, scene, MITSUBA_SPP, WARMUP_SEED)
    times = []
    for _ in range(max(1, args.repeats)):
        img, t = mitsuba_render(mi, dr, scene, MITSUBA_SPP, MITSUBA_SEED)
        times.append(t)
    t_mi = min(times)
    m64 = np.array(img, dtype=np.float64)[..., :3]
    m64_path = os.path.join(args.workdir, f'mitsuba-{MITSUBA_SPP}.exr')
    write_exr(mi, m64_path, m64)
    rm = compare(m64, mref)
    target = rm['rmse']
    print(f'\n(a) Mitsuba {WIDTH}x{HEIGHT}, path max_depth {MAX_DEPTH}, box filter, {MITSUBA_SPP} spp seed {MITSUBA_SEED}')
    print(f'    scene load {t_load:.3f} s; warm-up render (JIT or kernel cache) {t_warm:.2f} s')
    print(f'    timed render: {t_mi:.3f} s (' + ', '.join(f'{x:.3f}' for x in times) + ')')
    print(f'    RMSE vs {args.mitsuba_ref}: {target:.6f}  (mean rel diff {rm["mean_rel_diff"]:.5f}); image {m64_path}')

    # (b) snell
    rows = []
    snell = args.snell if os.path.isabs(args.snell) else os.path.join(REPO, args.snell)
    if not args.skip_snell:
        if not os.path.exists(snell):
            raise SystemExit(f'snell binary {snell} not found (cargo build --release, or --snell)')
        if not os.path.exists(args.snell_ref):
            print(f'\nsnell reference: {args.snell_ref} missing; rendering {args.snell_ref_spp} spp')
            os.makedirs(os.path.dirname(os.path.abspath(args.snell_ref)), exist_ok=True)
            t, _ = run_snell(snell, args.scene, args.snell_ref_spp, args.snell_ref, args.snell_arg)
            print(f'snell reference: {t:.1f} s')
        sref = read_exr(mi, args.snell_ref)
        print(f'\n(b) snell {args.scene}, --integrator path; RMSE vs {args.snell_ref}; target RMSE {target:.6f}')
        print(f'    {"spp":>6} {"time s":>9} {"render s":>9} {"RMSE":>10}  reaches')
        for spp in [int(x) for x in args.spp_list.split(',') if x.strip()]:
            out = os.path.join(args.workdir, f'snell-{spp}.exr')
            runs = [run_snell(snell, args.scene, spp, out, args.snell_arg) for _ in range(max(1, args.repeats))]
            t, tr = min(r[0] for r in runs), min(r[1] for r in runs)
            e = compare(read_exr(mi, out), sref)['rmse']
            rows.append((spp, t, e, tr))
            print(f'    {spp:>6} {t:>9.3f} {tr:>9.3f} {e:>10.6f}  {"yes" if e <= target else "no"}', flush=True)
            if e <= target and not args.no_stop:
                break
    else:
        sref = read_exr(mi, args.snell_ref) if os.path.exists(args.snell_ref) else None

    # (c) summary
    print('\n(c) summary')
    print(f'    {"renderer":<10} {"spp":>6} {"time s":>9} {"RMSE":>10}')
    print(f'    {"mitsuba":<10} {MITSUBA_SPP:>6} {t_mi:>9.3f} {target:>10.6f}')
    for spp, t, e, _ in rows:
        print(f'    {"snell":<10} {spp:>6} {t:>9.3f} {e:>10.6f}')
    if rows:
        t_render, _, _ = loglog_time([(spp, tr, e) for spp, _, e, tr in rows], target)
        t_eq, first, note = loglog_time([r[:3] for r in rows], target)
        if t_eq is None:
            print(f'    snell never reached RMSE {target:.6f} ({note}); extend --spp-list')
        else:
            print(f'    snell time at Mitsuba\'s {MITSUBA_SPP}-spp RMSE (log-log interpolated): {t_eq:.3f} s'
                  + (f'  [{note}]' if note else ''))
            print(f'    first measured snell run reaching it: {first[0]} spp, {first[1]:.3f} s, RMSE {first[2]:.6f}')
            print(f'    ratio snell_time / mitsuba_time = {t_eq / t_mi:.3f} (interpolated), '
                  f'{first[1] / t_mi:.3f} (first run reaching it)')
            if t_render is not None:
                print(f'    like for like (snell\'s render alone, as Mitsuba\'s time is: no start-up, load '
                      f'or writing): {t_render:.3f} s, ratio {t_render / t_mi:.3f} (interpolated)')
    if sref is not None:
        r = compare(sref, mref)
        print(f'    references: A = {args.snell_ref}, B = {args.mitsuba_ref}')
        print(f'    mean relative difference sum|A-B|/sum|B| = {r["mean_rel_diff"]:.5f}  '
              f'({"within" if r["mean_rel_diff"] <= 0.02 else "OUTSIDE"} 2 %)')
        print(f'    RMSE = {r["rmse"]:.6f}; per-channel mean ratio A/B = '
              + ' '.join(f'{x:.5f}' for x in r['mean_ratio_a_over_b']))
        # Noise floor: the 64-spp image's mean rel diff scaled to two independent references of
        # --ref-spp / --snell-ref-spp samples (noise ~ 1/sqrt(spp); mean |diff| of two adds in quadrature).
        floor = rm['mean_rel_diff'] * math.sqrt(MITSUBA_SPP / args.ref_spp + MITSUBA_SPP / args.snell_ref_spp)
        print(f'    (noise alone gives roughly {floor:.5f}: {args.ref_spp}- and {args.snell_ref_spp}-spp references, '
              f'both taken to be as noisy per sample as Mitsuba)')
        if r['mean_rel_diff'] > 0.02:
            for name, f in (('left-right', mref[:, ::-1]), ('top-bottom', mref[::-1])):
                rf = compare(sref, f)['mean_rel_diff']
                if rf < r['mean_rel_diff'] * 0.7:
                    print(f'    note: against Mitsuba\'s reference flipped {name} it is {rf:.5f}: orientation?')
    else:
        print(f'    (no snell reference at {args.snell_ref}: reference agreement not checked)')
    if ref_time is not None:
        print(f'    (Mitsuba reference was made in this run: {ref_time:.1f} s)')


if __name__ == '__main__':
    main()
