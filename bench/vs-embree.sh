#!/usr/bin/env bash
# Ray throughput through the Stanford bunny: Embree 4 (PyPI embreex, one thread) against
# snell (every core, then one thread), on the very same rays, in one run: closest hits, then
# any hit (shadow rays, which stop at the first hit found). Embree runs twice a round: with
# its default scene flags (the issue's baseline), and in robust mode (RTC_SCENE_FLAG_ROBUST:
# robust traversal and no arithmetic shortcuts, against rays slipping through shared edges),
# the nearer match to snell's watertight triangle test, which is always on.
#   bench/vs-embree.sh [-n ROUNDS] [MESH.obj]
# Needs Python 3 with `pip install embreex numpy`. The rays: 1024 x 1024 camera rays framed
# on the model, and 1,048,576 random rays from inside its bounding box (bench/embree_rays.py
# writes them; examples/trace_rays.rs traces them through a scene holding only the mesh).
# -n ROUNDS repeats the runs in turn and compares each tracer's best: the machine's
# speed drifts within minutes, and Embree's with it.
set -euo pipefail
cd "$(dirname "$0")/.."
rounds=1
while [ $# -gt 0 ]; do case "$1" in
  -n) rounds=$2; shift 2;;
  -*) echo "usage: bench/vs-embree.sh [-n ROUNDS] [MESH.obj]" >&2; exit 2;;
  *) break;; esac; done
[[ "$rounds" =~ ^[1-9][0-9]*$ ]] || { echo "vs-embree.sh: -n needs a whole number of rounds, 1 or more" >&2; exit 2; }
mesh=${1:-assets/models/stanford-bunny.obj}
python3 -c "import embreex, numpy" 2>/dev/null || {
  echo "vs-embree.sh: needs Python with embreex and numpy (pip install embreex numpy)" >&2
  exit 2
}
cargo build --release --quiet --example trace_rays
rays=$(mktemp -d)
trap 'rm -rf "$rays"' EXIT
# Each round runs Embree, then snell on every core, then snell on one thread, on the same
# rays: the machine's speed drifts within minutes, so the rounds alternate the tracers and
# the summary compares each one's best.
for r in $(seq "$rounds"); do
  echo "== round $r of $rounds: Embree (one thread)"
  python3 bench/embree_rays.py "$mesh" --write-rays "$rays"
  cp "$rays/embree.json" "$rays/embree.$r.json"
  echo
  echo "== round $r of $rounds: Embree, robust mode (one thread)"
  python3 bench/embree_rays.py "$mesh" --robust --write-rays "$rays/robust"
  cp "$rays/robust/embree.json" "$rays/robust.$r.json"
  echo
  echo "== round $r of $rounds: snell (all cores)"
  ./target/release/examples/trace_rays "$mesh" "$rays/camera.rays" "$rays/incoherent.rays" | tee "$rays/snell.$r.txt"
  echo
  echo "== round $r of $rounds: snell (one thread)"
  ./target/release/examples/trace_rays "$mesh" "$rays/camera.rays" "$rays/incoherent.rays" --threads 1 | tee "$rays/snell1.$r.txt"
  echo
  echo "== round $r of $rounds: snell, any hit (all cores, then one thread)"
  ./target/release/examples/trace_rays "$mesh" "$rays/camera.rays" "$rays/incoherent.rays" --any | tee "$rays/snellany.$r.txt"
  ./target/release/examples/trace_rays "$mesh" "$rays/camera.rays" "$rays/incoherent.rays" --any --threads 1 | tee "$rays/snellany1.$r.txt"
  echo
done
python3 - "$rays" "$rounds" <<'PY'
import json, os, sys
d, rounds = sys.argv[1], int(sys.argv[2])
def snell(name):
    rows = {}
    for line in open(f"{d}/{name}"):
        parts = line.split()
        if len(parts) == 5 and parts[0] in ("camera", "incoherent"):
            rows[parts[0]] = (int(parts[2]), float(parts[4]))
    return rows
kinds = ("camera", "incoherent")
embree = [json.load(open(f"{d}/embree.{r}.json"))["sets"] for r in range(1, rounds + 1)]
robust = [json.load(open(f"{d}/robust.{r}.json"))["sets"] for r in range(1, rounds + 1)]
cores = os.cpu_count() or 1

def compare(title, embree, embree_speed, prefix):
    """One table: Embree's best against snell's best (all cores, one thread), hits, and
    snell's speed per core as a fraction of Embree's on one thread (the issue's goal)."""
    all_cores = [snell(f"{prefix}.{r}.txt") for r in range(1, rounds + 1)]
    one = [snell(f"{prefix}1.{r}.txt") for r in range(1, rounds + 1)]
    best = {
        k: (
            max(embree_speed(e[k]) for e in embree) / 1e6,
            max(s[k][1] for s in all_cores),
            max(s[k][1] for s in one),
        )
        for k in kinds
    }
    print(f"{title}, best of {rounds} round(s):")
    print(f"{'rays':<12}{'Embree 1 thread':>18}{'snell all cores':>18}{'snell 1 thread':>16}{'hits (E / s)':>22}")
    for k in kinds:
        e, a, o = best[k]
        print(f"{k:<12}{e:>14.2f} M/s{a:>14.2f} M/s{o:>12.2f} M/s"
              f"{embree[0][k]['hits']:>12} / {all_cores[0][k][0]}")
        if any(s[k][0] != embree[0][k]["hits"] for s in all_cores + one):
            print(f"  warning: snell's {k} hit count differs from Embree's")
    print(f"\nsnell per core against Embree's one thread ({cores} cores; 1.00 is the goal):")
    for k in kinds:
        e, a, o = best[k]
        line = f"  {k:<12}{a / cores / e:>6.2f} (all cores / {cores}){o / e:>8.2f} (one thread)"
        if rounds > 1:
            per_round = [s[k][1] / cores / (embree_speed(x[k]) / 1e6) for s, x in zip(all_cores, embree)]
            line += f"   per round, all cores: {min(per_round):.2f} to {max(per_round):.2f}"
        print(line)

closest = lambda s: s["rays_per_second"]
any_hit = lambda s: s["any_hit"]["rays_per_second"]
compare("closest hit (rtcIntersect1; Scene::intersect)", embree, closest, "snell")
print()
compare("any hit, as shadow rays (rtcOccluded1; trace_rays --any)", embree, any_hit, "snellany")
# Embree's default mode trades accuracy at triangle edges for speed; RTC_SCENE_FLAG_ROBUST
# does not, as snell's watertight test does not: the nearer like-for-like comparison.
print()
compare("closest hit, Embree in robust mode (RTC_SCENE_FLAG_ROBUST)", robust, closest, "snell")
print()
compare("any hit, Embree in robust mode (RTC_SCENE_FLAG_ROBUST)", robust, any_hit, "snellany")
PY
