#!/usr/bin/env python3
"""snell's environment light against Mitsuba 3's ``envmap``, on one scene written for both.

The scene: four balls (a rough conductor with a given complex index, smooth glass, a white
diffuse ball, a perfect mirror) on a diffuse disk, lit only by an HDR environment map
(assets/env/studio.hdr by default, turned about y), path tracer, max_depth 8, rr_depth 5,
box filter, 320 x 180.  Materials are those both renderers define the same way (no
plastic, no named metals, whose RGB tables differ).

What it does, in one run
------------------------
(a) Writes the scene as snell TOML (WORKDIR/env.toml) and as a Mitsuba dict; Mitsuba's
    ``envmap`` puts its image's centre column toward +z where snell's faces -z, so Mitsuba's
    gets ``to_world`` = rotate(y, ROTATE + 180).
(b) Renders a reference with each at --ref-spp samples (Mitsuba in chunks with seeds 1000,
    1001, ..., in variant llvm_ad_rgb), cached in WORKDIR and reused unless --fresh.
(c) Times each renderer at --spp (Mitsuba: ``mi.render`` after a warm-up, scene loading not
    counted; snell: the whole process) and takes each image's RMSE against its own
    reference.
(d) Prints the agreement of the two references: the mean relative difference
    sum|A-B|/sum|B| (snell A, Mitsuba B), RMSE and per-channel mean ratios, and what the
    references' own noise alone gives (from two half-sample references of snell's).

How to run
----------
    pip install mitsuba numpy && apt-get install libllvm19
    cargo build --release
    python3 bench/vs-mitsuba-env.py                           # studio.hdr
    python3 bench/vs-mitsuba-env.py --env assets/env/venice-sunset.hdr --rotate 0

A manual benchmark, not run by CI.  Helpers (reading and writing EXR, the comparison) come
from bench/vs-mitsuba.py.
"""
import argparse
import importlib.util
import os
import subprocess
import time

import numpy as np

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
_spec = importlib.util.spec_from_file_location('vs_mitsuba', os.path.join(REPO, 'bench', 'vs-mitsuba.py'))
vm = importlib.util.module_from_spec(_spec)
_spec.loader.exec_module(vm)

WIDTH, HEIGHT = 320, 180
MAX_DEPTH, RR_DEPTH = 8, 5
CAMERA = dict(origin=[0, 2.2, 7.5], target=[0, 0.6, 0], fov=32)
# (centre, radius, material)
BALLS = [
    ([-2.4, 0.7, 0.0], 0.7, 'metal'),
    ([-0.8, 0.7, 0.6], 0.7, 'glass'),
    ([0.8, 0.7, -0.2], 0.7, 'chalk'),
    ([2.4, 0.7, 0.4], 0.7, 'mirror'),
]
FLOOR_RADIUS, FLOOR_ALBEDO = 6.0, 0.45
METAL_ETA, METAL_K, METAL_ALPHA = [0.2, 0.45, 1.4], [3.6, 2.4, 1.9], 0.15


def snell_toml(env, rotate, spp):
    balls = ''.join(
        f'[[objects]]\ntype = "sphere"\ncenter = {c}\nradius = {r}\nmaterial = "{m}"\n' for c, r, m in BALLS)
    return f'''# Written by bench/vs-mitsuba-env.py: the same scene is given to Mitsuba 3.
[image]
width = {WIDTH}
height = {HEIGHT}
samples = {spp}
max_depth = {MAX_DEPTH}
filter = {{ type = "box" }}
[integrator]
type = "path"
sampler = "independent"
rr_depth = {RR_DEPTH}
[camera]
position = {CAMERA['origin']}
look_at = {CAMERA['target']}
fov = {CAMERA['fov']}
[environment]
type = "image"
file = "{env}"
rotate = [0, {rotate}, 0]
[materials.floor]
type = "diffuse"
color = {FLOOR_ALBEDO}
[materials.metal]
type = "conductor"
eta = {METAL_ETA}
k = {METAL_K}
roughness = {METAL_ALPHA}
[materials.glass]
type = "dielectric"
ior = 1.5
[materials.chalk]
type = "diffuse"
color = 0.8
[materials.mirror]
type = "conductor"
[[objects]]
type = "disk"
center = [0, 0, 0]
normal = [0, 1, 0]
radius = {FLOOR_RADIUS}
material = "floor"
{balls}'''


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


def snell_render(args, toml, spp, seed, out):
    cmd = [os.path.join(REPO, args.snell), 'render', toml, '--spp', str(spp), '--seed', str(seed),
           '--output', out]
    t0 = time.perf_counter()
    subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL, cwd=REPO)
    return time.perf_counter() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument('--snell', default='target/release/snell')
    ap.add_argument('--env', default='assets/env/studio.hdr', help='environment map (relative to the repo root)')
    ap.add_argument('--rotate', type=float, default=-90, help="snell's rotate about y, degrees")
    ap.add_argument('--ref-spp', type=int, default=2048)
    ap.add_argument('--ref-chunk', type=int, default=256)
    ap.add_argument('--spp', type=int, default=64, help='samples per pixel of the timed renders')
    ap.add_argument('--repeats', type=int, default=3)
    ap.add_argument('--workdir', default=os.path.join(REPO, 'target', 'vs-mitsuba-env'))
    ap.add_argument('--fresh', action='store_true', help='render the references again')
    ap.add_argument('--peers', default=os.environ.get('SNELL_PEERS', '/work/shared/peers'))
    args = ap.parse_args()

    os.makedirs(args.workdir, exist_ok=True)
    env = os.path.abspath(os.path.join(REPO, args.env))
    compare, compare_src = vm.get_compare(args.peers)
    mi, dr = vm.import_mitsuba(0)
    tag = f'{os.path.splitext(os.path.basename(env))[0]}-{args.rotate:g}-{args.ref_spp}'
    toml = os.path.join(args.workdir, 'env.toml')
    with open(toml, 'w') as f:
        f.write(snell_toml(os.path.relpath(env, args.workdir), args.rotate, args.spp))

    scene = mitsuba_scene(mi, env, args.rotate)
    mref = os.path.join(args.workdir, f'mitsuba-{tag}.exr')
    if args.fresh or not os.path.exists(mref):
        acc = np.zeros((HEIGHT, WIDTH, 3))
        chunks = max(1, args.ref_spp // args.ref_chunk)
        for i in range(chunks):
            img, _ = vm.mitsuba_render(mi, dr, scene, args.ref_chunk, vm.REF_SEED_BASE + i)
            acc += np.array(img, dtype=np.float64)[..., :3]
        vm.write_exr(mi, mref, acc / chunks)
    sref = [os.path.join(args.workdir, f'snell-{tag}-{h}.exr') for h in 'ab']
    for seed, path in enumerate(sref):
        if args.fresh or not os.path.exists(path):
            snell_render(args, toml, args.ref_spp // 2, 1000 + seed, path)
    a, b = (vm.read_exr(mi, p) for p in sref)
    s_ref, m_ref = (a + b) / 2, vm.read_exr(mi, mref)

    vm.mitsuba_render(mi, dr, scene, args.spp, vm.WARMUP_SEED)
    m_time, m_img = min((vm.mitsuba_render(mi, dr, scene, args.spp, 0)[::-1] for _ in range(args.repeats)),
                        key=lambda t: t[0])
    m_img = np.array(m_img, dtype=np.float64)[..., :3]
    s_out = os.path.join(args.workdir, f'snell-{args.spp}.exr')
    s_time = min(snell_render(args, toml, args.spp, 0, s_out) for _ in range(args.repeats))
    s_img = vm.read_exr(mi, s_out)

    rmse = lambda x, y: float(np.sqrt(np.mean((x - y) ** 2)))
    print(f'scene: {args.env} rotated {args.rotate:g} degrees about y, {WIDTH}x{HEIGHT}, metric: {compare_src}')
    print(f'{"":8} {"spp":>5} {"time s":>8} {"RMSE vs own ref":>16}')
    print(f'{"mitsuba":8} {args.spp:>5} {m_time:>8.3f} {rmse(m_img, m_ref):>16.5f}')
    print(f'{"snell":8} {args.spp:>5} {s_time:>8.3f} {rmse(s_img, s_ref):>16.5f}')
    c = compare(s_ref.astype(np.float32), m_ref.astype(np.float32))
    noise = compare(a.astype(np.float32), b.astype(np.float32))['mean_rel_diff'] / 2 ** 0.5
    print(f"references ({args.ref_spp} spp each): mean relative difference {c['mean_rel_diff']:.5f} "
          f"(their noise alone, estimated: {noise:.5f}), RMSE {c['rmse']:.5f}, "
          f"mean ratio snell/mitsuba {', '.join(f'{x:.4f}' for x in c['mean_ratio_a_over_b'])}")


if __name__ == '__main__':
    main()
