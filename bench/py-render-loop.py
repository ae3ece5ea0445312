#!/usr/bin/env python3
"""The Python module over many renders: the process's resident memory before and after N
renders of the seed scene at 256 x 256, 4 spp (a leak shows as growth), and the time one
render takes from the call to the returned array (median and best).

    pip install ./snell-py && python3 bench/py-render-loop.py [--renders 1000]
"""

import argparse
import os
import pathlib
import statistics
import time

import snell


def rss_mib() -> float:
    with open("/proc/self/statm") as f:
        pages = int(f.read().split()[1])
    return pages * os.sysconf("SC_PAGE_SIZE") / 2**20


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--renders", type=int, default=1000)
    ap.add_argument("--scene", default=str(pathlib.Path(__file__).resolve().parents[1] / "scenes/seed.toml"))
    args = ap.parse_args()
    scene = snell.load(args.scene)
    # Warm up: the thread pool, the allocator's arenas, numpy.
    for _ in range(20):
        snell.render(scene, width=256, height=256, spp=4)
    before = rss_mib()
    times = []
    for i in range(args.renders):
        t = time.perf_counter()
        img = snell.render(scene, width=256, height=256, spp=4)
        times.append(time.perf_counter() - t)
        del img
    after = rss_mib()
    print(f"{args.renders} renders of {args.scene} at 256 x 256, 4 spp")
    print(f"RSS {before:.1f} MiB before, {after:.1f} MiB after: {after - before:+.2f} MiB")
    print(f"one render: median {statistics.median(times) * 1000:.1f} ms, best {min(times) * 1000:.1f} ms")


if __name__ == "__main__":
    main()
