#!/usr/bin/env bash
# Ray throughput through the Stanford bunny: Embree 4 (PyPI embreex, one thread) against
# snell (every core, then one thread), on the very same rays, in one run.
#   bench/vs-embree.sh [MESH.obj]
# Needs Python 3 with `pip install embreex numpy`. The rays: 1024 x 1024 camera rays framed
# on the model, and 1,048,576 random rays from inside its bounding box (bench/embree_rays.py
# writes them; examples/trace_rays.rs traces them through a scene holding only the mesh).
set -euo pipefail
cd "$(dirname "$0")/.."
mesh=${1:-assets/models/stanford-bunny.obj}
python3 -c "import embreex, numpy" 2>/dev/null || {
  echo "vs-embree.sh: needs Python with embreex and numpy (pip install embreex numpy)" >&2
  exit 2
}
cargo build --release --quiet --example trace_rays
rays=$(mktemp -d)
trap 'rm -rf "$rays"' EXIT
echo "== Embree (one thread)"
python3 bench/embree_rays.py "$mesh" --write-rays "$rays"
echo
echo "== snell (all cores)"
./target/release/examples/trace_rays "$mesh" "$rays/camera.rays" "$rays/incoherent.rays" | tee "$rays/snell.txt"
echo
echo "== snell (one thread)"
./target/release/examples/trace_rays "$mesh" "$rays/camera.rays" "$rays/incoherent.rays" --threads 1 | tee "$rays/snell1.txt"
echo
python3 - "$rays" <<'PY'
import json, os, sys
d = sys.argv[1]
embree = json.load(open(f"{d}/embree.json"))
def snell(name):
    rows = {}
    for line in open(f"{d}/{name}"):
        parts = line.split()
        if len(parts) == 5 and parts[0] in ("camera", "incoherent"):
            rows[parts[0]] = (int(parts[2]), float(parts[4]))
    return rows
all_cores, one = snell("snell.txt"), snell("snell1.txt")
print(f"{'rays':<12}{'Embree 1 thread':>18}{'snell all cores':>18}{'snell 1 thread':>16}{'hits (E / s)':>22}")
for k in ("camera", "incoherent"):
    e = embree["sets"][k]
    er = e["rays_per_second"] / 1e6
    print(f"{k:<12}{er:>14.2f} M/s{all_cores[k][1]:>14.2f} M/s{one[k][1]:>12.2f} M/s"
          f"{e['hits']:>12} / {all_cores[k][0]}")
# The issue's goal: per core at least what Embree does on one thread.
cores = os.cpu_count() or 1
print(f"\nsnell per core against Embree's one thread ({cores} cores; 1.00 is the goal):")
for k in ("camera", "incoherent"):
    er = embree["sets"][k]["rays_per_second"] / 1e6
    print(f"  {k:<12}{all_cores[k][1] / cores / er:>6.2f} (all cores / {cores})"
          f"{one[k][1] / er:>8.2f} (one thread)")
PY
