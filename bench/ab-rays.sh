#!/usr/bin/env bash
# Compares two builds of examples/trace_rays on the rays of bench/vs-embree.sh, fairly on a
# small noisy machine: both trace at once, one thread each on a core of its own (taskset),
# swapping cores every round, and the script prints, per set of rays, each build's best
# speed and the median of B's speed over A's (above 1, B is faster).
#   bench/ab-rays.sh [-n ROUNDS] [--any] [MESH.obj] A B
# A and B are trace_rays binaries, for example:
#   cargo build --release --example trace_rays && cp target/release/examples/trace_rays /tmp/before
#   (change something) cargo build --release --example trace_rays
#   bench/ab-rays.sh /tmp/before target/release/examples/trace_rays
# Four sets: the full camera and random sets of bench/vs-embree.sh (the issue's measure; a
# million rays each, streamed from memory), and two that stay in the cache, 16 rows of the
# camera rays through the middle of the picture and the first 16,384 random rays, traced 40
# times each. Streaming the rays from memory costs random rays about an eighth of their
# speed and moves single runs by 5 to 10 %; the small sets show the work of the walk alone
# (see docs/perf-log.md). --any traces shadow rays (trace_rays --any). Needs Python 3 with
# numpy and embreex (bench/embree_rays.py writes the rays; Embree traces nothing here).
set -euo pipefail
cd "$(dirname "$0")/.."
rounds=4; any=()
while [ $# -gt 0 ]; do case "$1" in
  -n) rounds=$2; shift 2;;
  --any) any=(--any); shift;;
  -*) echo "usage: bench/ab-rays.sh [-n ROUNDS] [--any] [MESH.obj] A B" >&2; exit 2;;
  *) break;; esac; done
[[ "$rounds" =~ ^[1-9][0-9]*$ ]] || { echo "ab-rays.sh: -n needs a whole number of rounds, 1 or more" >&2; exit 2; }
case $# in
  2) mesh=assets/models/stanford-bunny.obj; a=$1; b=$2;;
  3) mesh=$1; a=$2; b=$3;;
  *) echo "usage: bench/ab-rays.sh [-n ROUNDS] [--any] [MESH.obj] A B" >&2; exit 2;;
esac
for bin in "$a" "$b"; do
  [ -x "$bin" ] || { echo "ab-rays.sh: $bin is not an executable trace_rays" >&2; exit 2; }
done
[ "$(nproc)" -ge 2 ] || { echo "ab-rays.sh: needs two cores" >&2; exit 2; }
python3 -c "import embreex, numpy" 2>/dev/null || {
  echo "ab-rays.sh: needs Python with embreex and numpy (pip install embreex numpy)" >&2
  exit 2
}
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
python3 bench/embree_rays.py "$mesh" --write-rays "$out" --rays-only > /dev/null
python3 - "$out" <<'PY'
import sys
import numpy as np
d = sys.argv[1]
camera = np.fromfile(f"{d}/camera.rays", dtype="<f4").reshape(1024, 1024, 6)
camera[504:520].tofile(f"{d}/camera-cached.rays")
np.fromfile(f"{d}/incoherent.rays", dtype="<f4").reshape(-1, 6)[:16384].tofile(f"{d}/random-cached.rays")
PY
run() { # core binary name
  taskset -c "$1" "$2" "$mesh" "$out/camera.rays" "$out/incoherent.rays" --threads 1 --repeats 3 "${any[@]}" > "$out/$3.full"
  taskset -c "$1" "$2" "$mesh" "$out/camera-cached.rays" "$out/random-cached.rays" --threads 1 --repeats 40 "${any[@]}" > "$out/$3.cached"
}
for i in $(seq "$rounds"); do
  ca=$((i % 2)); cb=$((1 - i % 2))
  run "$ca" "$a" "a.$i" & run "$cb" "$b" "b.$i" & wait
done
python3 - "$out" "$rounds" <<'PY'
import statistics, sys
d, rounds = sys.argv[1], int(sys.argv[2])
def speeds(name):
    rows = {}
    for kind in ("full", "cached"):
        for line in open(f"{d}/{name}.{kind}"):
            p = line.split()
            if len(p) == 5 and p[0] in ("camera", "incoherent", "camera-cached", "random-cached"):
                rows[p[0]] = (int(p[2]), float(p[4]))
    return rows
a = [speeds(f"a.{i}") for i in range(1, rounds + 1)]
b = [speeds(f"b.{i}") for i in range(1, rounds + 1)]
labels = {"camera": "camera", "incoherent": "random", "camera-cached": "camera, cached", "random-cached": "random, cached"}
for k, label in labels.items():
    q = [y[k][1] / x[k][1] for x, y in zip(a, b)]
    warn = "" if all(x[k][0] == y[k][0] for x, y in zip(a, b)) else "   (hit counts differ!)"
    print(f"{label:<16} A best {max(x[k][1] for x in a):7.2f} M/s  B best {max(y[k][1] for y in b):7.2f} M/s"
          f"  B/A median {statistics.median(q):.3f} ({min(q):.3f} to {max(q):.3f}){warn}")
PY
