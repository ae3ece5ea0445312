#!/usr/bin/env python3
"""Equal-time error on a caustic scene: snell's bdpt and path tracer against Mitsuba 3's path
tracer, the peer's own renderer of the same scene.

The scene (written here for both): a glass ball (index 1.5) on a grey floor (a rectangle),
lit by a point light above and behind it and by a small emitting ball to the left, seen by a
perspective camera, 240 x 180, box filter, max_depth 10. The point light's caustic under the
glass ball is found only by light paths: neither path tracer finds it; the small ball's
caustic they find rarely.

What it does
------------
1. snell's reference: ``snell render --integrator bdpt --spp REF --seed 99``.
2. Agreement of the two scenes: snell's path tracer and Mitsuba's, both at REF spp, must
   agree (mean relative difference printed; both miss the same caustic), so that what
   follows compares renderers, not scenes.
3. Equal time: snell ``--integrator path --time T``, snell ``--integrator bdpt --time T``,
   and Mitsuba ``path`` (variant llvm_ad_rgb) with as many samples as fit in T seconds (its
   JIT compile not counted; in chunks of 64 samples, averaged), each image's RMSE and relative MSE of the luminance against the
   reference.

    pip install mitsuba numpy; apt-get install libllvm19
    cargo build --release && python3 bench/bdpt-vs-mitsuba.py [--time 10] [--ref 4096]

A manual benchmark, not run by CI; its figures go to docs/perf-log.md.
"""
import argparse
import os
import subprocess
import sys
import tempfile
import time

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
W, H = 240, 180
SNELL_SCENE = """
[image]
width = 240
height = 180
samples = 16
background = 0
max_depth = 10
filter = { type = "box" }
[integrator]
type = "bdpt"
[camera]
position = [0, 2.2, 4.2]
look_at = [0, 0.3, 0]
fov = 38
[materials.floor]
type = "diffuse"
color = 0.75
[materials.glass]
type = "dielectric"
ior = 1.5
[materials.lamp]
type = "diffuse"
color = 0
emission = 30
[[lights]]
type = "point"
position = [1, 3, -1.5]
intensity = 15
[[objects]]
type = "rectangle"
corner = [-4, 0, -4]
edge_u = [0, 0, 8]
edge_v = [8, 0, 0]
material = "floor"
[[objects]]
type = "sphere"
center = [0, 0.5, 0]
radius = 0.5
material = "glass"
[[objects]]
type = "sphere"
center = [-1.5, 1.2, 1]
radius = 0.1
material = "lamp"
"""


def mitsuba_scene(mi, spp):
    T = mi.ScalarTransform4f
    return mi.load_dict({
        'type': 'scene',
        'integrator': {'type': 'path', 'max_depth': 10, 'rr_depth': 5},
        'sensor': {
            'type': 'perspective', 'fov': 38, 'fov_axis': 'y',
            'to_world': T().look_at(origin=[0, 2.2, 4.2], target=[0, 0.3, 0], up=[0, 1, 0]),
            'sampler': {'type': 'independent', 'sample_count': spp},
            'film': {'type': 'hdrfilm', 'width': W, 'height': H, 'rfilter': {'type': 'box'},
                     'pixel_format': 'rgb'},
        },
        'light': {'type': 'point', 'position': [1, 3, -1.5],
                  'intensity': {'type': 'rgb', 'value': [15, 15, 15]}},
        'floor': {'type': 'rectangle',
                  'to_world': T().rotate([1, 0, 0], -90).scale([4, 4, 1]),
                  'bsdf': {'type': 'diffuse', 'reflectance': {'type': 'rgb', 'value': [0.75] * 3}}},
        'ball': {'type': 'sphere', 'center': [0, 0.5, 0], 'radius': 0.5,
                 'bsdf': {'type': 'dielectric', 'int_ior': 1.5, 'ext_ior': 1.0}},
        'lamp': {'type': 'sphere', 'center': [-1.5, 1.2, 1], 'radius': 0.1,
                 'emitter': {'type': 'area', 'radiance': {'type': 'rgb', 'value': [30] * 3}},
                 'bsdf': {'type': 'diffuse', 'reflectance': {'type': 'rgb', 'value': [0, 0, 0]}}},
    })


CHUNK = 64


def render_chunked(mi, dr, spp, seed):
    """Mitsuba's render of `spp` samples a pixel as chunks of 64 with seeds of their own,
    averaged: one wavefront of thousands of samples a pixel swamps the memory."""
    scene = mitsuba_scene(mi, CHUNK)
    chunks = max(1, spp // CHUNK)
    total = None
    for k in range(chunks):
        img = np.array(mi.render(scene, seed=seed * 100000 + k), dtype=np.float64)
        total = img if total is None else total + img
    dr.sync_thread()
    return total / chunks, chunks * CHUNK


def lum(img):
    img = np.asarray(img, dtype=np.float64)[..., :3]
    return 0.2126 * img[..., 0] + 0.7152 * img[..., 1] + 0.0722 * img[..., 2]


def read_exr(mi, path):
    return np.array(mi.Bitmap(path).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32))


def snell(args, scene, out, *flags):
    cmd = [args.snell, 'render', scene, '-o', out, '--quiet', *flags]
    subprocess.run(cmd, check=True, cwd=REPO)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--time', type=float, default=10.0)
    ap.add_argument('--ref', type=int, default=4096)
    ap.add_argument('--snell', default=os.path.join(REPO, 'target/release/snell'))
    ap.add_argument('--out', default=os.path.join(tempfile.gettempdir(), 'bdpt-vs-mitsuba'))
    args = ap.parse_args()
    os.makedirs(args.out, exist_ok=True)
    if not os.environ.get('DRJIT_LIBLLVM_PATH') and os.path.exists('/usr/lib/x86_64-linux-gnu/libLLVM-19.so'):
        os.environ['DRJIT_LIBLLVM_PATH'] = '/usr/lib/x86_64-linux-gnu/libLLVM-19.so'
    import mitsuba as mi
    import drjit as dr
    mi.set_variant('llvm_ad_rgb')
    scene = os.path.join(args.out, 'ball.toml')
    with open(scene, 'w') as f:
        f.write(SNELL_SCENE)
    p = lambda name: os.path.join(args.out, name)
    if not os.path.exists(p('ref-bdpt.exr')):
        snell(args, scene, p('ref-bdpt.exr'), '--spp', str(args.ref), '--seed', '99')
    if not os.path.exists(p('ref-path.exr')):
        snell(args, scene, p('ref-path.exr'), '--integrator', 'path', '--spp', str(args.ref), '--seed', '98')
    mitsuba_ref, _ = render_chunked(mi, dr, args.ref, 7)
    ref = lum(read_exr(mi, p('ref-bdpt.exr')))
    sp, mp = lum(read_exr(mi, p('ref-path.exr'))), lum(mitsuba_ref)
    print(f'scenes agree: snell path against Mitsuba path, mean relative difference '
          f'{np.abs(sp - mp).sum() / np.abs(mp).sum():.4f}, means {sp.mean():.5f} / {mp.mean():.5f}; '
          f'bdpt reference mean {ref.mean():.5f}')
    rows = []
    for integrator in ['path', 'bdpt']:
        start = time.time()
        snell(args, scene, p(f'{integrator}.exr'), '--integrator', integrator,
              '--spp', '65536', '--time', str(args.time))
        rows.append((f'snell {integrator}', time.time() - start, lum(read_exr(mi, p(f'{integrator}.exr')))))
    # Mitsuba: time a few chunks (after a warm-up that compiles), then as many as fit.
    render_chunked(mi, dr, CHUNK, 1)
    start = time.time()
    render_chunked(mi, dr, 4 * CHUNK, 2)
    per = (time.time() - start) / (4 * CHUNK)
    start = time.time()
    img, spp = render_chunked(mi, dr, max(CHUNK, int(args.time / per)), 3)
    rows.append((f'Mitsuba path ({spp} spp)', time.time() - start, lum(img)))
    print(f'{"":24} {"seconds":>8} {"RMSE":>9} {"relMSE":>9}')
    for name, secs, img in rows:
        rmse = np.sqrt(np.mean((img - ref) ** 2))
        rel = np.mean((img - ref) ** 2 / (ref ** 2 + 1e-2))
        print(f'{name:24} {secs:8.2f} {rmse:9.5f} {rel:9.5f}')


if __name__ == '__main__':
    sys.exit(main())
