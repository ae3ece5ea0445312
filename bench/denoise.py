#!/usr/bin/env python3
"""The denoiser (`--denoise`) on the Cornell box: RMSE against a converged reference.

Renders scenes/cornell.toml at 512 x 512: a reference (--ref-spp, cached in WORKDIR), the
raw picture at 16 and 256 samples a pixel, and the 16-sample picture denoised (the layer
`denoised` of the EXR), and prints each one's RMSE and mean relative difference against the
reference, with the time the denoiser took (the `denoised it in` line: guides and OIDN).

How to run
----------
    pip install pyoidn numpy OpenEXR
    OIDN_DIR=$(python3 -c 'import pyoidn, os; print(os.path.dirname(pyoidn.__file__))')/oidn \\
        cargo build --release --features denoise
    python3 bench/denoise.py

A manual benchmark, not run by CI (CI's build has no denoiser).
"""
import argparse
import os
import re
import subprocess
import time

import numpy as np
import OpenEXR

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def read(path, layer=None):
    with OpenEXR.File(path, separate_channels=True) as f:
        ch = f.channels()
        names = [f'{layer}.{c}' if layer else c for c in 'RGB']
        return np.stack([ch[n].pixels for n in names], -1).astype(np.float64)


def render(snell, out, spp, extra, size):
    cmd = [snell, 'render', os.path.join(REPO, 'scenes/cornell.toml'), '-o', out, '--width',
           str(size), '--height', str(size), '--spp', str(spp)] + extra
    t0 = time.perf_counter()
    said = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    return time.perf_counter() - t0, said


def errors(img, ref):
    rmse = float(np.sqrt(np.mean((img - ref) ** 2)))
    lum = np.array([0.2126, 0.7152, 0.0722])
    mrd = float(np.abs(img @ lum - ref @ lum).sum() / (ref @ lum).sum())
    return rmse, mrd


def main():
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('--snell', default=os.path.join(REPO, 'target', 'release', 'snell'))
    p.add_argument('--workdir', default=os.path.join(REPO, 'target', 'denoise-bench'))
    p.add_argument('--ref-spp', type=int, default=2048)
    p.add_argument('--size', type=int, default=512)
    a = p.parse_args()
    os.makedirs(a.workdir, exist_ok=True)
    ref_path = os.path.join(a.workdir, f'ref-{a.size}-{a.ref_spp}.exr')
    if not os.path.exists(ref_path):
        print(f'reference at {a.ref_spp} spp ...', flush=True)
        render(a.snell, ref_path, a.ref_spp, ['--seed', '1000', '--quiet'], a.size)
    ref = read(ref_path)
    out = os.path.join(a.workdir, 'x.exr')
    print(f'Cornell box {a.size} x {a.size}, reference {a.ref_spp} spp')
    for spp in (16, 256):
        t, _ = render(a.snell, out, spp, [], a.size)
        rmse, mrd = errors(read(out), ref)
        print(f'raw {spp:>4} spp: RMSE {rmse:.5f}, mean rel diff {mrd:.5f}  ({t:.2f} s whole process)')
    t, said = render(a.snell, out, 16, ['--denoise'], a.size)
    rmse, mrd = errors(read(out, 'denoised'), ref)
    took = re.search(r'denoised it in ([0-9.]+) s', said)
    print(f'denoised 16 spp: RMSE {rmse:.5f}, mean rel diff {mrd:.5f}  ({t:.2f} s whole process, '
          f'denoiser {took.group(1) if took else "?"} s)')


if __name__ == '__main__':
    main()
