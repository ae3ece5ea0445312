#!/usr/bin/env python3
"""snell's environment light against Mitsuba 3's ``envmap``, on one scene written for both.

The scene: four balls (a rough conductor with a given complex index, smooth glass, a white
diffuse ball, a perfect mirror) on a diffuse disk, lit only by an HDR environment map
(assets/env/venice-sunset.hdr by default), path tracer, max_depth 8, rr_depth 5,
box filter, 320 x 180.  Materials are those both renderers define the same way (no
plastic, no named metals, whose RGB tables differ).

What it does
------------
Writes the scene as snell TOML (WORKDIR/env.toml) and as a Mitsuba dict, then runs
bench/vs-mitsuba.py's comparison on them: Mitsuba (llvm_ad_rgb) at 64 spp, timed after a
warm-up, its RMSE against its own converged reference; snell at a rising series of sample
counts, timed as whole processes, each against snell's own reference; the time at which
snell reaches Mitsuba's 64-spp RMSE (log-log interpolated), and the agreement of the two
references (mean relative difference, the 2 % check).  References are cached in WORKDIR
(default target/vs-mitsuba-env), one per map and turn.  Mitsuba's ``envmap`` puts its image's
centre column toward +z where snell's faces -z, so Mitsuba's gets ``to_world`` =
rotate(y, ROTATE + 180).

How to run
----------
    pip install mitsuba numpy OpenEXR && apt-get install libllvm19
    cargo build --release
    python3 bench/vs-mitsuba-env.py --repeats 3 --spp-list 8,12,16,20,24,32,48 --no-stop
    python3 bench/vs-mitsuba-env.py --env assets/env/studio.hdr --rotate -90
    python3 bench/vs-mitsuba-env.py --sun-sky      # a generated sky with a 3-degree sun

``--sun-sky`` lights the scene with a map this script makes (WORKDIR/sun-sky.exr, 2048 x 1024,
32-bit float): a blue sky fading to a pale horizon over a dark ground, and a sun 3 degrees
across, 40 degrees up, whose light on the floor is about four times the sky's: the small
bright source that tests how each renderer samples an environment (issue 44's second scene).

The studio map's bare bulb (radiance 3728 over a mean of 1.9) seen through the glass and the
mirror makes caustics that neither renderer converges in 4096 samples: its references
differ by about their own noise, which is several per cent; the sunset's do not.

A manual benchmark, not run by CI.
"""
import argparse
import importlib.util
import os
import sys

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
_spec = importlib.util.spec_from_file_location('vs_mitsuba', os.path.join(REPO, 'bench', 'vs-mitsuba.py'))
vm = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(vm)

sys.path.insert(0, os.path.join(REPO, 'bench'))
from env_scene import (BALLS, CAMERA, FLOOR_ALBEDO, FLOOR_RADIUS, HEIGHT, MAX_DEPTH,  # noqa: E402
                       METAL_ALPHA, METAL_ETA, METAL_K, RR_DEPTH, WIDTH, snell_toml, sun_sky)


def mitsuba_scene(mi, env, rotate):
    T = mi.ScalarTransform4f
    rgb = lambda v: {'type': 'rgb', 'value': v}
    bsdfs = {
        'metal': {'type': 'roughconductor', 'distribution': 'ggx', 'alpha': METAL_ALPHA,
                  'eta': rgb(METAL_ETA), 'k': rgb(METAL_K)},
        'glass': {'type': 'dielectric', 'int_ior': 1.5, 'ext_ior': 1.0},
        'chalk': {'type': 'diffuse', 'reflectance': rgb([0.8] * 3)},
        'mirror': {'type': 'conductor', 'material': 'none'},
    }
    d = {
        'type': 'scene',
        'integrator': {'type': 'path', 'max_depth': MAX_DEPTH, 'rr_depth': RR_DEPTH},
        'sensor': {
            'type': 'perspective', 'fov': CAMERA['fov'], 'fov_axis': 'y',
            'to_world': T().look_at(origin=CAMERA['origin'], target=CAMERA['target'], up=[0, 1, 0]),
            'film': {'type': 'hdrfilm', 'width': WIDTH, 'height': HEIGHT, 'rfilter': {'type': 'box'},
                     'pixel_format': 'rgb'},
            'sampler': {'type': 'independent'},
        },
        'env': {'type': 'envmap', 'filename': env, 'to_world': T().rotate([0, 1, 0], rotate + 180)},
        'floor': {'type': 'disk', 'to_world': T().rotate([1, 0, 0], -90).scale(FLOOR_RADIUS),
                  'bsdf': {'type': 'diffuse', 'reflectance': rgb([FLOOR_ALBEDO] * 3)}},
    }
    for i, (c, r, m) in enumerate(BALLS):
        d[f'ball{i}'] = {'type': 'sphere', 'center': c, 'radius': r, 'bsdf': bsdfs[m]}
    return mi.load_dict(d)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter,
                                 epilog='Every other option is bench/vs-mitsuba.py\'s (--spp-list, --repeats, '
                                        '--ref-spp, --snell-ref-spp, --no-stop, ...).')
    ap.add_argument('--env', default='assets/env/venice-sunset.hdr', help='environment map (relative to the repo root)')
    ap.add_argument('--rotate', type=float, default=0, help="snell's rotate about y, degrees")
    ap.add_argument('--sampler', default='sobol', choices=['sobol', 'independent'], help="snell's sampler")
    ap.add_argument('--workdir', default=os.path.join(REPO, 'target', 'vs-mitsuba-env'))
    ap.add_argument('--sun-sky', action='store_true', help='light the scene with a generated sky and a 3-degree sun instead of --env')
    args, rest = ap.parse_known_args()
    os.makedirs(args.workdir, exist_ok=True)
    env = os.path.abspath(os.path.join(REPO, args.env))
    if args.sun_sky:
        env = os.path.join(os.path.abspath(args.workdir), 'sun-sky.exr')
        if not os.path.exists(env):
            sun_sky(env)
        args.env = os.path.relpath(env, REPO)
    toml = os.path.join(args.workdir, 'env.toml')
    with open(toml, 'w') as f:
        f.write(snell_toml(os.path.relpath(env, args.workdir), args.rotate, args.sampler))
    tag = f'{os.path.splitext(os.path.basename(env))[0]}-{args.rotate:g}'
    vm.WIDTH, vm.HEIGHT = WIDTH, HEIGHT
    vm.mitsuba_scene = lambda mi: mitsuba_scene(mi, env, args.rotate)
    sys.argv = [sys.argv[0], '--scene', toml, '--workdir', args.workdir,
                '--mitsuba-ref', os.path.join(args.workdir, f'mitsuba-ref-{tag}.exr'),
                '--snell-ref', os.path.join(args.workdir, f'snell-ref-{tag}-{args.sampler}.exr')] + rest
    print(f'scene: {args.env} turned {args.rotate:g} degrees about y; snell sampler {args.sampler}; '
          f'snell scene {os.path.relpath(toml, REPO)}')
    vm.main()


if __name__ == '__main__':
    main()
