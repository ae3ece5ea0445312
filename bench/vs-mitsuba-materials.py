#!/usr/bin/env python3
"""Each material against its Mitsuba 3 namesake in a rendered image, not only point by point.

Eight balls in a row, each alone in its own image (so no ball lights another), under the
sunset environment map (assets/env/venice-sunset.hdr), path tracer, max depth 16, box
filter, 96 x 96 pixels and 1024 samples a pixel in both renderers; the script prints, for
each ball, snell's mean over the ball's pixels over Mitsuba's, per channel. Converged
images of the same scene agree within about 1 % (the noise of 1024 samples of a small
image is a few tenths of a per cent of the mean); the materials:

    red plastic (alpha 0.1), white rough plastic (alpha 0.5), smooth green plastic,
    gold (alpha 0.2), copper mirror, rough glass (alpha 0.2), a thin pane, and
    `metallic` 0.4 (a blendbsdf of roughplastic and a tinted roughconductor)

    pip install mitsuba numpy && apt-get install libllvm19
    cargo build --release
    python3 bench/vs-mitsuba-materials.py [--spp 1024] [--snell target/release/snell]

src/bsdf/mitsuba_tests.rs checks the BSDFs value by value against Mitsuba's own numbers;
this checks that the path tracer around them gives the same pictures. A manual check, not
run by CI (it needs Mitsuba).
"""
import argparse
import os
import subprocess
import sys
import tempfile

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
ENV = os.path.join(REPO, 'assets', 'env', 'venice-sunset.hdr')
SIZE, MAX_DEPTH = 96, 16
RED, WHITE, GREEN, TINT = [0.7, 0.05, 0.05], [0.9, 0.9, 0.9], [0.1, 0.6, 0.2], [0.9, 0.6, 0.3]


def rgb(v):
    return {'type': 'rgb', 'value': v}


# (name, snell's material keys, Mitsuba's bsdf)
MATERIALS = [
    ('red plastic 0.1', f'type = "plastic"\ncolor = {RED}\nroughness = 0.1',
     {'type': 'roughplastic', 'distribution': 'ggx', 'alpha': 0.1, 'int_ior': 1.5, 'ext_ior': 1.0,
      'diffuse_reflectance': rgb(RED)}),
    ('white plastic 0.5', f'type = "plastic"\ncolor = {WHITE}\nroughness = 0.5',
     {'type': 'roughplastic', 'distribution': 'ggx', 'alpha': 0.5, 'int_ior': 1.5, 'ext_ior': 1.0,
      'diffuse_reflectance': rgb(WHITE)}),
    ('green plastic', f'type = "plastic"\ncolor = {GREEN}',
     {'type': 'plastic', 'int_ior': 1.5, 'ext_ior': 1.0, 'diffuse_reflectance': rgb(GREEN)}),
    ('gold 0.2', 'type = "conductor"\nmetal = "Au"\nroughness = 0.2',
     {'type': 'roughconductor', 'distribution': 'ggx', 'alpha': 0.2, 'material': 'Au'}),
    ('copper mirror', 'type = "conductor"\nmetal = "Cu"',
     {'type': 'conductor', 'material': 'Cu'}),
    ('rough glass 0.2', 'type = "dielectric"\nior = 1.5\nroughness = 0.2',
     {'type': 'roughdielectric', 'distribution': 'ggx', 'alpha': 0.2, 'int_ior': 1.5,
      'ext_ior': 1.0}),
    ('thin pane', 'type = "thin"\nior = 1.5',
     {'type': 'thindielectric', 'int_ior': 1.5, 'ext_ior': 1.0}),
    ('metallic 0.4', f'type = "metallic"\ncolor = {TINT}\nroughness = 0.3\nmetallic = 0.4',
     {'type': 'blendbsdf', 'weight': 0.4,
      'coat': {'type': 'roughplastic', 'distribution': 'ggx', 'alpha': 0.3, 'int_ior': 1.5,
               'ext_ior': 1.0, 'diffuse_reflectance': rgb(TINT)},
      'metal': {'type': 'roughconductor', 'distribution': 'ggx', 'alpha': 0.3,
                'material': 'none', 'specular_reflectance': rgb(TINT)}}),
]


def snell_scene(keys, spp):
    return f'''[image]
width = {SIZE}
height = {SIZE}
samples = {spp}
max_depth = {MAX_DEPTH}
filter = {{ type = "box" }}
[integrator]
type = "path"
[camera]
position = [0, 0, 4]
look_at = [0, 0, 0]
fov = 20
[environment]
type = "image"
file = "{ENV}"
[materials.ball]
{keys}
[[objects]]
type = "sphere"
center = [0, 0, 0]
radius = 0.6
material = "ball"
'''


def mitsuba_image(mi, bsdf, spp):
    T = mi.ScalarTransform4f
    scene = mi.load_dict({
        'type': 'scene', 'integrator': {'type': 'path', 'max_depth': MAX_DEPTH},
        'sensor': {'type': 'perspective', 'fov': 20, 'fov_axis': 'y',
                   'to_world': T().look_at(origin=[0, 0, 4], target=[0, 0, 0], up=[0, 1, 0]),
                   'film': {'type': 'hdrfilm', 'width': SIZE, 'height': SIZE,
                            'rfilter': {'type': 'box'}, 'pixel_format': 'rgb'},
                   'sampler': {'type': 'independent', 'sample_count': spp}},
        # Mitsuba's envmap faces its image's centre toward +z, snell's toward -z.
        'env': {'type': 'envmap', 'filename': ENV, 'to_world': T().rotate([0, 1, 0], 180)},
        'ball': {'type': 'sphere', 'center': [0, 0, 0], 'radius': 0.6, 'bsdf': bsdf},
    })
    return np.array(mi.render(scene))[..., :3]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--spp', type=int, default=1024)
    ap.add_argument('--snell', default=os.path.join(REPO, 'target', 'release', 'snell'))
    args = ap.parse_args()
    os.environ.setdefault('DRJIT_LIBLLVM_PATH', '/usr/lib/x86_64-linux-gnu/libLLVM-19.so')
    import mitsuba as mi
    mi.set_variant('llvm_ad_rgb')
    # The ball's pixels: those within 0.9 of its silhouette's radius (fov 20 at distance 4).
    r_px = 0.6 / np.sqrt(16 - 0.36) / np.tan(np.radians(10)) * SIZE / 2 * 0.9
    y, x = np.mgrid[0:SIZE, 0:SIZE] + 0.5
    mask = (x - SIZE / 2) ** 2 + (y - SIZE / 2) ** 2 < r_px ** 2
    worst = 0.0
    with tempfile.TemporaryDirectory() as tmp:
        for name, keys, bsdf in MATERIALS:
            toml, exr = os.path.join(tmp, 'ball.toml'), os.path.join(tmp, 'ball.exr')
            with open(toml, 'w') as f:
                f.write(snell_scene(keys, args.spp))
            subprocess.run([args.snell, 'render', toml, '-o', exr, '--quiet'], check=True)
            ours = np.array(mi.Bitmap(exr))[..., :3]
            theirs = mitsuba_image(mi, bsdf, args.spp)
            ratio = ours[mask].mean(axis=0) / theirs[mask].mean(axis=0)
            worst = max(worst, float(np.abs(ratio - 1).max()))
            print(f'{name:20s} snell / Mitsuba over the ball: '
                  + '  '.join(f'{c} {v:.4f}' for c, v in zip('RGB', ratio)))
    print(f'largest difference {worst * 100:.2f} % ({mask.sum()} pixels a ball, {args.spp} spp)')


if __name__ == '__main__':
    sys.exit(main())
