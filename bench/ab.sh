#!/usr/bin/env bash
# Compares two snell binaries on one scene, fairly on a small noisy machine: both render at
# once, one thread each on a core of its own (taskset), and swap cores every round, so that
# whatever else the machine is doing slows both alike. Prints each one's best time and the
# median of B's time over A's: below 1, B is faster.
#   bench/ab.sh [-n ROUNDS] [-s SIZE] [-w] SCENE A B
# -w (whole machine): A and B take turns, each on every core, for what one thread cannot
# show (how the threads share the work, the single-threaded start and end of a render).
# For example, against the last commit's build:
#   cp target/release/snell /tmp/snell-before   # build the old commit first
#   cargo build --release && bench/ab.sh scenes/seed.toml /tmp/snell-before target/release/snell
set -euo pipefail
n=10; size=512; whole=0
while [ $# -gt 0 ]; do case "$1" in
  -n) n=$2; shift 2;; -s) size=$2; shift 2;; -w) whole=1; shift;; *) break;; esac; done
[ $# -eq 3 ] || { echo "usage: bench/ab.sh [-n ROUNDS] [-s SIZE] [-w] SCENE A B" >&2; exit 2; }
scene=$1; a=$2; b=$3
[ "$whole" = 1 ] || [ "$(nproc)" -ge 2 ] || { echo "bench/ab.sh: needs two cores (or -w)" >&2; exit 2; }
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
run() { # cores binary name [render flags...]
  local s e cores=$1 bin=$2 name=$3
  shift 3
  s=$(date +%s.%N)
  taskset -c "$cores" "$bin" render "$scene" -o "$out/$name.png" --width "$size" --height "$size" \
    --spp 16 --quiet "$@"
  e=$(date +%s.%N)
  python3 -c "print($e - $s)" > "$out/$name.t"
}
for i in $(seq "$n"); do
  if [ "$whole" = 1 ]; then
    # Turns, A first on odd rounds and B first on even ones.
    all="0-$(($(nproc) - 1))"
    if [ $((i % 2)) = 1 ]; then run "$all" "$a" a; run "$all" "$b" b
    else run "$all" "$b" b; run "$all" "$a" a; fi
  else
    ca=$((i % 2)); cb=$((1 - i % 2))
    run "$ca" "$a" a --threads 1 & run "$cb" "$b" b --threads 1 & wait
  fi
  echo "$(cat "$out/a.t") $(cat "$out/b.t")"
done | python3 -c "
import statistics, sys
rows = [tuple(map(float, l.split())) for l in sys.stdin if l.strip()]
r = [b / a for a, b in rows]
print(f'A best {min(a for a, _ in rows):.3f} s  B best {min(b for _, b in rows):.3f} s  '
      f'B/A median {statistics.median(r):.3f} (from {min(r):.3f} to {max(r):.3f}, {len(r)} rounds)')
"
