#!/usr/bin/env python3
"""Adaptive sampling (`--noise`) against uniform sampling, at equal error.

For each scene: a converged reference (a uniform render of many samples, cached in
WORKDIR), then uniform renders at a rising series of sample counts and adaptive renders at a
falling series of noise thresholds (capped at --cap samples a pixel), each timed as a whole
process and measured against the reference. For every adaptive render, the time a uniform
render would take to reach its error (log-log interpolated between the uniform renders);
their ratio is what adaptive sampling saves (below 1 it pays).

Three error measures: the mean relative difference (the sum of the absolute differences over
the sum of the reference, in luminance: the measure the comparisons with Mitsuba use), the
relative mean squared error (each pixel's squared difference over its squared value plus
0.01, averaged), and the 95th percentile of the pixels' relative differences (`|x - r| / (r
+ 0.01)`, the threshold's own measure: how far off the worst pixels are, which is what a
threshold on every pixel promises to bound).

The scenes: the Cornell box (scenes/cornell.toml); `env`, issue 44's environment scene (four
balls of metal, glass, chalk and mirror on a disk under a generated sky with a 3-degree sun,
320 x 180, written into WORKDIR by bench/env_scene.py); and the
courtyard (scenes/outdoor-noon.toml, a sky and a real-sized sun, whose caustics through glass
are fireflies that rule every error measure).

What any allocation could do
----------------------------
The reference is rendered with the variance view, which gives each pixel's spread per sample
(sigma) and mean (mu). From them, before any timing, the script prints what sampling the same
pixels differently could gain at best, as a share of uniform sampling's samples at equal
expected error: samples in proportion to sigma^(2/3) (the least mean absolute error for a
given total), in proportion to sigma / sqrt(mu^2 + 0.01) (the least relative MSE), and the
ideal threshold (each pixel exactly the samples that bring its relative error to the
threshold, none below 16 or above the cap: what `--noise` aims at, with its noise estimates
exact). Where the first two are above 0.7, no allocation of samples to pixels reaches the
goal on that scene, however well it estimates the noise.

How to run
----------
    pip install numpy OpenEXR
    cargo build --release
    python3 bench/adaptive.py                 # the Cornell box and the environment scene, 2 threads
    python3 bench/adaptive.py --scenes cornell --ref-spp 8192

A manual benchmark, not run by CI.
"""
import argparse
import math
import os
import subprocess
import sys
import time

import numpy as np
import OpenEXR

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCENES = {
    'cornell': ('scenes/cornell.toml', 256, 256),
    'env': (None, 320, 180),  # written into the work folder by env_scene()
    'courtyard': ('scenes/outdoor-noon.toml', 320, 180),
}
LUM = np.array([0.2126, 0.7152, 0.0722])


def read_exr(path, layer=None):
    with OpenEXR.File(path, separate_channels=True) as f:
        ch = f.channels()
        if layer:
            return ch[layer].pixels.astype(np.float64)
        return np.stack([ch[c].pixels for c in ('R', 'G', 'B')], -1).astype(np.float64)


def env_scene(workdir):
    """Issue 44's environment scene (bench/env_scene.py, with its generated sun and sky),
    written into `workdir`; its path."""
    sys.path.insert(0, os.path.join(REPO, 'bench'))
    import env_scene as env
    sky = os.path.join(workdir, 'sun-sky.exr')
    if not os.path.exists(sky):
        env.sun_sky(sky)
    path = os.path.join(workdir, 'env.toml')
    with open(path, 'w') as f:
        f.write(env.snell_toml('sun-sky.exr', 0, 'sobol'))
    return path


def has_layer(path, name):
    with OpenEXR.File(path, separate_channels=True) as f:
        return name in f.channels()


def bounds(ref, variance, ref_spp, cap, noise_list):
    """What allocating samples to pixels could gain at best (see the module's doc), from the
    reference's colours and its variance view (the variance of its mean at `ref_spp`)."""
    mu = (ref @ LUM).ravel()
    sigma = np.sqrt(np.maximum(variance.ravel(), 0) * ref_spp)
    a = sigma / np.sqrt(mu ** 2 + 0.01)
    rho = sigma / (mu + 0.01)

    def shares(n):
        # Samples n per pixel against uniform's at the same expected error: mean absolute
        # error goes as sum(sigma / sqrt(n)), relative MSE as sum(a^2 / n).
        m = n.mean()
        return ((np.sum(sigma / np.sqrt(n)) / (np.sum(sigma) / math.sqrt(m))) ** 2,
                np.sum(a ** 2 / n) / (np.sum(a ** 2) / m))

    s23 = np.sum(sigma ** (2 / 3))
    print(f'best any allocation: {s23 ** 3 / (sigma.size * np.sum(sigma) ** 2):.3f} (mean rel diff, '
          f'n ~ sigma^(2/3)), {np.sum(a) ** 2 / (a.size * np.sum(a ** 2)):.3f} (relMSE, n ~ a) of uniform\'s samples')
    for noise in noise_list:
        n = np.clip(rho ** 2 / noise ** 2, 16, cap)
        ma, rel = shares(n)
        print(f'ideal threshold {noise:g}: {n.mean():.1f} spp on average, {ma:.3f} (mean rel diff), '
              f'{rel:.3f} (relMSE) of uniform\'s samples')


def render(snell, scene, w, h, out, spp, extra, threads):
    cmd = [snell, 'render', os.path.join(REPO, scene), '-o', out, '--width', str(w), '--height',
           str(h), '--spp', str(spp), '--threads', str(threads), '--quiet'] + extra
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True)
    return time.perf_counter() - t0


def errors(img, ref):
    a, b = img @ LUM, ref @ LUM
    mrd = np.abs(a - b).sum() / b.sum()
    relmse = np.mean((a - b) ** 2 / (b ** 2 + 0.01))
    p95 = np.percentile(np.abs(a - b) / (b + 0.01), 95)
    return mrd, relmse, p95


def loglog(points, target):
    """The time at which the (time, error) points reach `target`, log-log interpolated."""
    pts = sorted(points, key=lambda p: -p[1])
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if e1 <= target <= e0 and e0 > e1:
            f = (math.log(e0) - math.log(target)) / (math.log(e0) - math.log(e1))
            return math.exp(math.log(t0) + f * (math.log(t1) - math.log(t0)))
    return None


def main():
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('--snell', default=os.path.join(REPO, 'target', 'release', 'snell'))
    p.add_argument('--workdir', default=os.path.join(REPO, 'target', 'adaptive-bench'))
    p.add_argument('--scenes', default='cornell,env')
    p.add_argument('--ref-spp', type=int, default=4096)
    p.add_argument('--spp-list', default='16,32,64,128,256,512')
    p.add_argument('--noise-list', default='0.2,0.1,0.05,0.03,0.02')
    p.add_argument('--cap', type=int, default=2048)
    p.add_argument('--threads', type=int, default=2)
    p.add_argument('--repeats', type=int, default=2, help='best of N times per render')
    a = p.parse_args()
    os.makedirs(a.workdir, exist_ok=True)
    for name in a.scenes.split(','):
        scene, w, h = SCENES[name]
        scene = scene or env_scene(a.workdir)
        ref_path = os.path.join(a.workdir, f'{name}-ref-{a.ref_spp}.exr')
        # A reference cached by an older version of this script has no variance view.
        if not (os.path.exists(ref_path) and has_layer(ref_path, 'variance.Y')):
            print(f'{name}: reference at {a.ref_spp} spp ...', flush=True)
            render(a.snell, scene, w, h, ref_path, a.ref_spp, ['--seed', '1000', '--aov', 'variance'], a.threads)
        ref = read_exr(ref_path)
        out = os.path.join(a.workdir, f'{name}.exr')
        uniform = []
        noise_list = [float(x) for x in a.noise_list.split(',')]
        print(f'\n{name} ({w} x {h}), reference {a.ref_spp} spp; whole-process times, best of {a.repeats}')
        bounds(ref, read_exr(ref_path, 'variance.Y'), a.ref_spp, a.cap, noise_list)
        print(f'{"run":>18} {"time s":>8} {"mean rel diff":>14} {"relMSE":>10} {"p95 rel":>8}')
        for spp in map(int, a.spp_list.split(',')):
            t = min(render(a.snell, scene, w, h, out, spp, [], a.threads) for _ in range(a.repeats))
            mrd, rel, p95 = errors(read_exr(out), ref)
            uniform.append((t, mrd, rel, p95))
            print(f'{f"uniform {spp}":>18} {t:8.3f} {mrd:14.5f} {rel:10.3e} {p95:8.4f}')
        ratios = []
        for noise in noise_list:
            t = min(render(a.snell, scene, w, h, out, a.cap, ['--noise', str(noise)], a.threads)
                    for _ in range(a.repeats))
            mrd, rel, p95 = errors(read_exr(out), ref)
            tm = loglog([(u[0], u[1]) for u in uniform], mrd)
            tr = loglog([(u[0], u[2]) for u in uniform], rel)
            tp = loglog([(u[0], u[3]) for u in uniform], p95)
            fmt = lambda x: f'{x:.3f}' if x else '  -  '  # noqa: E731
            print(f'{f"noise {noise}":>18} {t:8.3f} {mrd:14.5f} {rel:10.3e} {p95:8.4f}   equal-error time '
                  f'ratio: {fmt(tm and t / tm)} (mean rel diff), {fmt(tr and t / tr)} (relMSE), '
                  f'{fmt(tp and t / tp)} (p95)')
            ratios.append((tm and t / tm, tr and t / tr, tp and t / tp))
        for k, what in enumerate(('mean rel diff', 'relMSE', 'p95 rel')):
            got = [r[k] for r in ratios if r[k]]
            if got:
                print(f'{name}: median ratio {np.median(got):.3f} ({what}) over {len(got)} thresholds')


if __name__ == '__main__':
    main()
