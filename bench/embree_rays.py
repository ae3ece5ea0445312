#!/usr/bin/env python3
"""Embree 4 single-thread ray throughput on an OBJ mesh (reference for snell).

What it measures
----------------
Closest-hit throughput (rays per second) of Intel Embree 4, driven through the
PyPI binding ``embreex``, on one thread, for two fixed ray sets traced against
one triangle mesh (by default the Stanford bunny, 69,451 triangles):

* ``camera``: 1024 x 1024 primary rays of a pinhole camera.  The camera sits on
  the +z side of the mesh's bounding-box centre C and looks down -z (up +y,
  right +x).  Its vertical field of view is 40 degrees and its distance to C is
  r / sin(20 deg), r = half the bounding-box diagonal, so the bounding sphere
  just fills the vertical field of view.  Ray k = row * 1024 + col goes through
  the centre of pixel (col, row); row 0 is the top of the image.  All rays start
  at the eye; directions are unit length (normalised in float64, then rounded to
  float32).
* ``incoherent``: 1,048,576 rays, origins uniform in the bounding box, then
  directions uniform on the unit sphere (normalised Gaussian triples), drawn in
  that order from ``numpy.random.default_rng(1)`` in float64 and rounded to
  float32.

Every ray is traced with tnear = 0 and tfar = +inf.  A ray hits when Embree
returns a valid primitive id; the t-sum is the float64 sum of the hit distances
(numpy pairwise summation of the float32 tfar values of the hits).

How Embree is driven (embreex 4.4.0.post1)
------------------------------------------
``EmbreeScene.run(origins, directions, dists, ...)`` is a Cython loop that calls
``rtcIntersect1`` (closest hit) once per ray, in order, on the calling thread:
no ray packets or streams, no worker threads.  Per set the script makes

1. one untimed reference pass with ``output=1``, which returns per-ray
   ``primID``/``geomID`` (-1 on a miss), ``u``/``v``, ``Ng`` and ``tfar``; hits
   (primID >= 0) and the t-sum are taken from it;
2. ``--repeats`` timed passes (default 3, best reported) with
   ``query="DISTANCE"``: the same ``rtcIntersect1`` loop, which only writes each
   ray's tfar into the ``dists`` array passed in (+inf is left on a miss).  That
   array is filled with +inf before the timer starts, so the timed call
   allocates nothing; ``output=1`` would allocate and page in ~28 bytes per ray
   of output inside the call, which cost ~30% on the camera set here.  Each
   timed pass must reproduce the reference hits and t-sum exactly.

Then ``--repeats`` timed passes with ``query="OCCLUDED"`` (``rtcOccluded1`` per ray,
any hit, as a shadow ray asks), whose count of blocked rays must equal the hits; their
best is reported as ``any_hit`` (this call allocates its 4-byte-a-ray result inside the
timer).

The BVH build (``rtcCommitScene``) happens lazily on the first ``run`` call;
this script triggers it with a one-ray call before any timing, so only the
tracing call itself is timed (``time.perf_counter`` around ``run``).  The
process CPU time over each timed call is recorded too: CPU/wall <= 1.0 means no
second thread was busy (below 1.0 means the process was preempted on a loaded
machine; the best pass is usually ~1.0).

The scene uses Embree's default scene flags (no RTC_SCENE_FLAG_ROBUST) and
build quality unless ``--robust`` is given; note that embreex's own default is
robust=True.  Embree's FTZ/DAZ recommendation for the MXCSR register is not
applied (Python does not set it).

Ray files (``--write-rays DIR``)
--------------------------------
``DIR/camera.rays`` and ``DIR/incoherent.rays``: raw little-endian float32,
no header, N rows of 6 values ``ox oy oz dx dy dz`` (24 bytes per ray; N is the
file size / 24).  These are exactly the arrays that Embree traces.
``DIR/embree.json``: versions, mesh facts and, per set, ray count, hits, t-sum,
best time and rays per second.

Usage (from the repository root)
--------------------------------
    pip install embreex numpy
    python3 bench/embree_rays.py --write-rays /tmp/rays
    python3 bench/embree_rays.py --write-rays /tmp/rays --rays-only   # no tracing
    python3 bench/embree_rays.py path/to/mesh.obj --repeats 5 --robust
"""

from __future__ import annotations

import argparse
import json
import math
import re
import sys
import time
from importlib.metadata import version as package_version
from pathlib import Path

import numpy as np
from embreex import mesh_construction, rtcore, rtcore_scene

REPO_ROOT = Path(__file__).resolve().parent.parent
DEFAULT_OBJ = REPO_ROOT.parent / "shared" / "models" / "stanford-bunny.obj"

SEED = 1
IMAGE_SIZE = 1024
FOV_Y_DEG = 40.0
INCOHERENT_COUNT = 1 << 20
RAY_DTYPE = np.dtype("<f4")

# "/vt/vn" tails of face corners ("a/b", "a//c", "a/b/c"): everything from the
# first slash to the end of the token.
_CORNER_TAIL = re.compile(r"/\S*")


# --------------------------------------------------------------------------- OBJ


def load_obj(path: Path) -> tuple[np.ndarray, np.ndarray]:
    """Read the positions and faces of an OBJ file.

    Handles ``v x y z [w]`` and ``f`` lines whose corners are ``a``, ``a/b``,
    ``a//c`` or ``a/b/c``, with 1-based or negative (relative) indices.
    Polygons are fan-triangulated around their first corner.  Other lines are
    ignored.

    Returns (vertices float32 [V, 3], triangles int32 [T, 3]), 0-based.
    """
    lines = path.read_text(encoding="utf-8", errors="replace").splitlines()

    v_rows: list[str] = []  # "x y z ..." of each v line
    f_rows: list[str] = []  # corners of each f line
    f_vcount: list[int] = []  # vertices defined before each f line
    for line in lines:
        parts = line.split(None, 1)
        if len(parts) != 2:
            continue
        if parts[0] == "v":
            v_rows.append(parts[1])
        elif parts[0] == "f":
            f_rows.append(parts[1])
            f_vcount.append(len(v_rows))

    if not v_rows or not f_rows:
        raise ValueError(f"{path}: no vertices or no faces")

    vertices = np.array([row.split()[:3] for row in v_rows], dtype=np.float64)
    if vertices.shape[1] != 3:
        raise ValueError(f"{path}: a v line has fewer than 3 coordinates")

    # One flat array of position indices, plus the corner count of each face.
    stripped = _CORNER_TAIL.sub("", "\n".join(f_rows)).split("\n")
    corners = np.fromiter((len(row.split()) for row in stripped), dtype=np.int64, count=len(stripped))
    flat = np.array(" ".join(stripped).split(), dtype=np.int64)
    if np.any(corners < 3):
        raise ValueError(f"{path}: a face has fewer than 3 corners")
    if np.any(flat == 0):
        raise ValueError(f"{path}: face index 0 is not valid OBJ")

    # 1-based -> 0-based; negative indices count back from the last vertex
    # defined before that face line.
    defined = np.repeat(np.asarray(f_vcount, dtype=np.int64), corners)
    flat = np.where(flat > 0, flat - 1, defined + flat)
    if flat.min() < 0 or flat.max() >= len(vertices):
        raise ValueError(f"{path}: face index out of range")

    # Fan triangulation: face with corners c0..c(k-1) -> (c0, cj, cj+1), j=1..k-2.
    start = np.concatenate(([0], np.cumsum(corners)[:-1]))
    tris_per_face = corners - 2
    face_of_tri = np.repeat(np.arange(len(corners)), tris_per_face)
    first_tri = np.concatenate(([0], np.cumsum(tris_per_face)[:-1]))
    j = np.arange(len(face_of_tri)) - first_tri[face_of_tri] + 1
    s = start[face_of_tri]
    triangles = np.stack([flat[s], flat[s + j], flat[s + j + 1]], axis=1)

    return vertices.astype(np.float32), triangles.astype(np.int32)


# -------------------------------------------------------------------- ray sets


def bounds(vertices: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Axis-aligned bounding box (lo, hi) in float64."""
    v = vertices.astype(np.float64)
    return v.min(axis=0), v.max(axis=0)


def pack_rays(origins: np.ndarray, directions: np.ndarray) -> np.ndarray:
    """[N, 6] little-endian float32 array (ox, oy, oz, dx, dy, dz)."""
    rays = np.empty((len(origins), 6), dtype=RAY_DTYPE)
    rays[:, :3] = origins
    rays[:, 3:] = directions
    return rays


def camera_rays(lo: np.ndarray, hi: np.ndarray, size: int = IMAGE_SIZE, fov_y_deg: float = FOV_Y_DEG) -> np.ndarray:
    """Pinhole primary rays, one per pixel centre, row-major from the top row."""
    centre = 0.5 * (lo + hi)
    radius = 0.5 * float(np.linalg.norm(hi - lo))
    half_fov = math.radians(fov_y_deg) / 2.0
    eye = centre + np.array([0.0, 0.0, radius / math.sin(half_fov)])

    tan_half = math.tan(half_fov)  # square image: same extent in x and y
    ndc = (np.arange(size, dtype=np.float64) + 0.5) * (2.0 / size) - 1.0
    x = ndc * tan_half  # column -> +x
    y = -ndc * tan_half  # row 0 is the top -> +y
    yy, xx = np.meshgrid(y, x, indexing="ij")
    directions = np.stack([xx, yy, -np.ones_like(xx)], axis=-1).reshape(-1, 3)
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    origins = np.broadcast_to(eye, directions.shape)
    return pack_rays(origins, directions)


def incoherent_rays(lo: np.ndarray, hi: np.ndarray, count: int = INCOHERENT_COUNT, seed: int = SEED) -> np.ndarray:
    """Origins uniform in the box, then directions uniform on the sphere."""
    rng = np.random.default_rng(seed)
    origins = lo + (hi - lo) * rng.random((count, 3))
    directions = rng.standard_normal((count, 3))
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    return pack_rays(origins, directions)


def write_rays(path: Path, rays: np.ndarray) -> None:
    np.ascontiguousarray(rays, dtype=RAY_DTYPE).tofile(path)


# ---------------------------------------------------------------------- embree


def build_scene(vertices: np.ndarray, triangles: np.ndarray, robust: bool) -> tuple[rtcore_scene.EmbreeScene, float]:
    """Create the scene, build its BVH, and return (scene, build seconds)."""
    t0 = time.perf_counter()
    scene = rtcore_scene.EmbreeScene(robust=robust)
    # The geometry is attached to (and kept alive by) the Embree scene.
    mesh_construction.TriangleMesh(scene, vertices, triangles)
    # run() commits (builds the BVH) lazily on its first call: do that here,
    # with one ray, so the build is never inside a timed call.
    one = np.zeros((1, 3), dtype=np.float32)
    scene.run(one, one + np.float32(1.0), dists=np.full(1, np.inf, np.float32))
    return scene, time.perf_counter() - t0


def hit_summary(tfar: np.ndarray, hit: np.ndarray) -> tuple[int, float]:
    """(number of hits, float64 sum of their t)."""
    return int(hit.sum()), float(np.sum(tfar[hit], dtype=np.float64))


def trace(scene: rtcore_scene.EmbreeScene, rays: np.ndarray, repeats: int) -> dict:
    """Check the hits once (output=1), then time `repeats` closest-hit passes."""
    origins = np.ascontiguousarray(rays[:, :3])
    directions = np.ascontiguousarray(rays[:, 3:])

    # Untimed reference pass with full hit records: a hit has a valid primID.
    result = scene.run(origins, directions, dists=np.full(len(rays), np.inf, np.float32), output=1)
    hit = result["primID"] >= 0
    if not np.array_equal(hit, np.isfinite(result["tfar"])):
        raise RuntimeError("Embree reported a hit with infinite t or a miss with finite t")
    reference = hit_summary(result["tfar"], hit)

    times: list[float] = []
    cpu_ratios: list[float] = []
    for _ in range(repeats):
        tfar = np.full(len(rays), np.inf, dtype=np.float32)  # written in place
        c0 = time.process_time()
        t0 = time.perf_counter()
        scene.run(origins, directions, dists=tfar, query="DISTANCE")
        wall = time.perf_counter() - t0
        cpu = time.process_time() - c0
        times.append(wall)
        cpu_ratios.append(cpu / wall)
        summary = hit_summary(tfar, np.isfinite(tfar))
        if summary != reference:
            raise RuntimeError(f"timed pass disagrees with the reference pass: {summary} vs {reference}")

    best = int(np.argmin(times))

    # Any hit (shadow rays): rtcOccluded1 per ray, which stops at the first hit found.
    # run() allocates its 4-byte-a-ray result inside the timed call.
    any_times: list[float] = []
    for _ in range(repeats):
        t0 = time.perf_counter()
        occluded = scene.run(origins, directions, dists=np.full(len(rays), np.inf, np.float32), query="OCCLUDED")
        any_times.append(time.perf_counter() - t0)
        if int((occluded == 0).sum()) != reference[0]:
            raise RuntimeError("rtcOccluded1 found a different number of rays blocked than rtcIntersect1 hits")
    return {
        "rays": len(rays),
        "hits": reference[0],
        "t_sum": reference[1],
        "best_seconds": times[best],
        "rays_per_second": len(rays) / times[best],
        "seconds": times,
        "cpu_over_wall": cpu_ratios,
        "best_cpu_over_wall": cpu_ratios[best],
        "any_hit": {"occluded": reference[0], "best_seconds": min(any_times), "rays_per_second": len(rays) / min(any_times), "seconds": any_times},
    }


def embree_version() -> str:
    """'4.x.y' from embreex's EmbreeDevice repr ('Embree version:  4.x.y')."""
    text = repr(rtcore.EmbreeDevice())
    match = re.search(r"(\d+\.\d+\.\d+)", text)
    return match.group(1) if match else text


# ------------------------------------------------------------------------ main


def parse_args(argv: list[str] | None) -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n", 1)[0])
    parser.add_argument("obj", nargs="?", type=Path, default=DEFAULT_OBJ, help=f"OBJ mesh (default: {DEFAULT_OBJ})")
    parser.add_argument("--write-rays", metavar="DIR", type=Path, help="write camera.rays, incoherent.rays and embree.json into DIR")
    parser.add_argument("--repeats", type=int, default=3, help="timed runs per ray set; the best is reported (default 3)")
    parser.add_argument("--robust", action="store_true", help="build the scene with RTC_SCENE_FLAG_ROBUST")
    parser.add_argument("--rays-only", action="store_true", help="with --write-rays: write the ray files and stop, tracing nothing")
    args = parser.parse_args(argv)
    if args.rays_only and not args.write_rays:
        parser.error("--rays-only needs --write-rays DIR")
    if args.repeats < 1:
        parser.error("--repeats must be at least 1")
    return args


def main(argv: list[str] | None = None) -> int:
    args = parse_args(argv)

    t0 = time.perf_counter()
    vertices, triangles = load_obj(args.obj)
    load_seconds = time.perf_counter() - t0
    lo, hi = bounds(vertices)

    ray_sets = {"camera": camera_rays(lo, hi), "incoherent": incoherent_rays(lo, hi)}
    if args.write_rays:
        args.write_rays.mkdir(parents=True, exist_ok=True)
        for name, rays in ray_sets.items():
            write_rays(args.write_rays / f"{name}.rays", rays)
        if args.rays_only:
            print(f"wrote {', '.join(f'{n}.rays' for n in ray_sets)} to {args.write_rays}")
            return 0

    scene, build_seconds = build_scene(vertices, triangles, args.robust)
    results = {name: trace(scene, rays, args.repeats) for name, rays in ray_sets.items()}

    versions = {"embreex": package_version("embreex"), "embree": embree_version(), "numpy": np.__version__, "python": sys.version.split()[0]}
    print(f"embreex {versions['embreex']}, Embree {versions['embree']}, numpy {versions['numpy']}, Python {versions['python']}")
    print(f"mesh {args.obj}: {len(vertices)} vertices, {len(triangles)} triangles (parsed in {load_seconds:.2f} s)")
    print(f"scene build (rtcCommitScene, not timed below): {build_seconds * 1e3:.1f} ms, robust={args.robust}")
    print(f"single thread, rtcIntersect1 per ray, best of {args.repeats}")
    print()
    print(f"{'set':<12}{'rays':>10}{'hits':>10}{'t sum':>20}{'Mrays/s':>10}{'cpu/wall':>10}{'any hit Mrays/s':>17}")
    for name, r in results.items():
        print(f"{name:<12}{r['rays']:>10}{r['hits']:>10}{r['t_sum']:>20.6f}{r['rays_per_second'] / 1e6:>10.3f}{r['best_cpu_over_wall']:>10.2f}{r['any_hit']['rays_per_second'] / 1e6:>17.3f}")

    if args.write_rays:
        report = {
            "versions": versions,
            "mesh": {"path": str(args.obj), "vertices": len(vertices), "triangles": len(triangles), "bounds_lo": lo.tolist(), "bounds_hi": hi.tolist()},
            "settings": {"threads": 1, "query": "rtcIntersect1 closest hit; any_hit: rtcOccluded1", "tnear": 0.0, "tfar": "inf", "robust": args.robust, "repeats": args.repeats, "seed": SEED},
            "ray_file_format": "raw little-endian float32, N x 6: ox oy oz dx dy dz",
            "build_seconds": build_seconds,
            "sets": results,
        }
        (args.write_rays / "embree.json").write_text(json.dumps(report, indent=2) + "\n")
        print(f"\nwrote {', '.join(f'{n}.rays' for n in ray_sets)} and embree.json to {args.write_rays}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
