#!/usr/bin/env python3
"""snell-farm's scaling on this machine: an animated scene rendered with 1 and then 2 Ray
workers (local instances of 1 and 2 CPUs), beside snell alone on 1 and 2 threads, with the
overhead each task costs (scheduling, transfer, merge) and the fixed cost of one snell
process (start, scene load) measured on its own. docs/farm.md holds the figures and the
projection made from them.

    pip install ./python            # once (Ray and snell-farm)
    cargo build --release
    python3 bench/farm-scaling.py [--scene scenes/orbit.toml] [--frames 0..23] [--tiles 2x2]

Prints a table, and the same figures as JSON with --json.
"""

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "python"))

from snell_farm.cluster import connected  # noqa: E402
from snell_farm.driver import JobSpec, run  # noqa: E402


def snell_alone(snell: str, scene: str, first: int, last: int, threads: int, extra: list) -> float:
    """Seconds for `snell render --frames` of the range on one machine."""
    with tempfile.TemporaryDirectory() as out:
        start = time.perf_counter()
        subprocess.run([snell, "render", scene, "--frames", f"{first}..{last}", "-o",
                        os.path.join(out, "f_####.png"), "--quiet", "--threads", str(threads)] + extra,
                       check=True)
        return time.perf_counter() - start


def fixed_cost(snell: str, scene: str, extra: list, runs: int = 10) -> float:
    """Median seconds of a snell process that renders one pixel: start-up and scene load."""
    times = []
    with tempfile.TemporaryDirectory() as out:
        for _ in range(runs):
            start = time.perf_counter()
            subprocess.run([snell, "render", scene, "--frames", "0", "--region", "0,0,1,1", "-o",
                            os.path.join(out, "p.exr"), "--quiet", "--threads", "1"] + extra, check=True)
            times.append(time.perf_counter() - start)
    return statistics.median(times)


def farm(snell: str, scene: str, first: int, last: int, grid, workers: int, args) -> dict:
    with tempfile.TemporaryDirectory() as out, connected(None, workers):
        spec = JobSpec(scene=scene, output=os.path.join(out, "f_####.png"), frames=range(first, last + 1),
                       grid=grid, snell=snell, width=args.width, height=args.height, spp=args.spp, quiet=True)
        costs = run(spec)
        frame_bytes = os.path.getsize(os.path.join(out, f"f_{first:04d}.png"))
    tasks = costs.tasks
    return {
        "workers": costs.workers,
        "wall_s": costs.wall_s,
        "render_wall_s": costs.render_wall_s,
        "tasks": tasks,
        "snell_s_per_task": costs.snell_s / tasks,
        "overhead_s_per_task": (costs.workers * costs.render_wall_s - costs.snell_s) / tasks,
        "fetch_s_per_task": costs.fetch_s / tasks,
        "merge_s_per_frame": costs.merge_s / costs.frames,
        "result_bytes_per_frame": costs.result_bytes / costs.frames,
        "png_bytes_per_frame": frame_bytes,
        "pack_bytes": costs.pack_bytes,
    }


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--scene", default=str(REPO / "scenes" / "orbit.toml"))
    parser.add_argument("--frames", default="0..23")
    parser.add_argument("--tiles", default="2x2")
    parser.add_argument("--snell", default=str(REPO / "target" / "release" / "snell"))
    parser.add_argument("--width", type=int)
    parser.add_argument("--height", type=int)
    parser.add_argument("--spp", type=int)
    parser.add_argument("--json", action="store_true")
    args = parser.parse_args()
    if not os.access(args.snell, os.X_OK):
        print(f"no snell at {args.snell}: cargo build --release", file=sys.stderr)
        return 2
    first, last = (int(x) for x in args.frames.split(".."))
    columns, rows = (int(x) for x in args.tiles.split("x"))
    extra = []
    for flag, value in (("--width", args.width), ("--height", args.height), ("--spp", args.spp)):
        if value is not None:
            extra += [flag, str(value)]
    frames = last - first + 1
    results = {
        "scene": os.path.relpath(args.scene, REPO),
        "frames": frames,
        "tiles": args.tiles,
        "snell_alone_1_thread_s": snell_alone(args.snell, args.scene, first, last, 1, extra),
        "snell_alone_2_threads_s": snell_alone(args.snell, args.scene, first, last, 2, extra),
        "snell_process_fixed_s": fixed_cost(args.snell, args.scene, extra),
        "farm": [farm(args.snell, args.scene, first, last, (columns, rows), n, args) for n in (1, 2)],
    }
    one, two = results["farm"]
    results["speedup_2_over_1"] = one["render_wall_s"] / two["render_wall_s"]
    if args.json:
        print(json.dumps(results, indent=2))
        return 0
    print(f"{results['scene']}: {frames} frames, {args.tiles} tiles, {one['tasks']} tasks")
    print(f"snell alone:   1 thread {results['snell_alone_1_thread_s']:.2f} s, "
          f"2 threads {results['snell_alone_2_threads_s']:.2f} s")
    print(f"one snell process rendering one pixel (start-up, scene load): "
          f"{1000 * results['snell_process_fixed_s']:.0f} ms")
    print("workers  job wall  render wall  snell/task  overhead/task  fetch/task  merge/frame  result/frame")
    for r in results["farm"]:
        print(f"{r['workers']:>7}  {r['wall_s']:7.2f}s  {r['render_wall_s']:10.2f}s  "
              f"{1000 * r['snell_s_per_task']:8.0f}ms  {1000 * r['overhead_s_per_task']:11.0f}ms  "
              f"{1000 * r['fetch_s_per_task']:8.1f}ms  {1000 * r['merge_s_per_frame']:9.0f}ms  "
              f"{r['result_bytes_per_frame'] / 1024:9.0f}KiB")
    print(f"speed-up, 2 workers over 1 (render wall): {results['speedup_2_over_1']:.2f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
