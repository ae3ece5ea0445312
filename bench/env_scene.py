"""Issue 44's environment scene, as bench scripts share it: four balls (a rough conductor
with a given complex index, smooth glass, a white diffuse ball, a perfect mirror) on a
diffuse disk, lit only by an environment map, path tracer, max_depth 8, rr_depth 5, box
filter, 320 x 180; its snell TOML, and the generated sky with a 3-degree sun
(`sun_sky`) that lights it in bench/vs-mitsuba-env.py --sun-sky and bench/adaptive.py.
Mitsuba's version of the scene is in bench/vs-mitsuba-env.py.
"""

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


def snell_toml(env, rotate, sampler):
    balls = ''.join(
        f'[[objects]]\ntype = "sphere"\ncenter = {c}\nradius = {r}\nmaterial = "{m}"\n' for c, r, m in BALLS)
    return f'''# Written by bench/env_scene.py: the same scene is given to Mitsuba 3 by bench/vs-mitsuba-env.py.
[image]
width = {WIDTH}
height = {HEIGHT}
samples = 64
max_depth = {MAX_DEPTH}
filter = {{ type = "box" }}
[integrator]
type = "path"
sampler = "{sampler}"
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


def sun_sky(path, width=2048, height=1024, sun_elevation=40.0, sun_azimuth=30.0, sun_degrees=3.0):
    """Writes the generated sky (see the module's doc) as a float RGB EXR at `path`: rows are
    latitudes (the top row the zenith), columns longitudes, as every equirectangular map.
    Needs numpy and OpenEXR only (bench/adaptive.py lights a scene with it too)."""
    import numpy as np
    import OpenEXR
    v = (np.arange(height) + 0.5) / height
    u = (np.arange(width) + 0.5) / width
    lat = np.pi * (0.5 - v)[:, None] * np.ones((1, width))
    lon = 2 * np.pi * (u - 0.5)[None, :] * np.ones((height, 1))
    up = np.clip(np.sin(lat), 0, 1)[..., None]
    zenith, horizon = np.array([0.12, 0.28, 0.75]), np.array([0.85, 0.9, 0.95])
    sky = horizon + (zenith - horizon) * up ** 0.5
    ground = np.array([0.12, 0.11, 0.10])
    img = np.where((lat > 0)[..., None], sky, ground)
    # The sun: a disk of `sun_degrees` across around its direction.
    d = np.stack([np.cos(lat) * np.sin(lon), np.sin(lat), np.cos(lat) * np.cos(lon)], -1)
    e, a = np.radians(sun_elevation), np.radians(sun_azimuth)
    s = np.array([np.cos(e) * np.sin(a), np.sin(e), np.cos(e) * np.cos(a)])
    half = np.radians(sun_degrees / 2)
    solid = 2 * np.pi * (1 - np.cos(half))
    # Irradiance on the floor about four times the sky's (the sky's is about pi x its mean).
    radiance = 4 * np.pi * 0.55 / (solid * np.sin(e))
    inside = (d @ s) > np.cos(half)
    img[inside] = np.array([1.0, 0.95, 0.85]) * radiance
    header = {'compression': OpenEXR.ZIP_COMPRESSION, 'type': OpenEXR.scanlineimage}
    OpenEXR.File(header, {'RGB': img.astype(np.float32)}).write(path)
