#!/usr/bin/env bash
# Renders a set of small scenes with two snell binaries and compares the files byte for byte:
# for a refactoring, which must change no picture. Prints one line a picture and exits 1 if
# any differ.
#   bench/same-bytes.sh A B      (e.g. a copy of the last commit's target/release/snell, and the new one)
set -euo pipefail
cd "$(dirname "$0")/.."
[ $# -eq 2 ] || { echo "usage: bench/same-bytes.sh BINARY_A BINARY_B" >&2; exit 2; }
out=$(mktemp -d); trap 'rm -rf "$out"' EXIT
cases=(
  "seed|scenes/seed.toml --width 256 --height 256"
  "seed-path|scenes/seed.toml --width 128 --height 128 --integrator path --spp 16"
  "cornell|scenes/cornell.toml --width 128 --height 128 --spp 16"
  "environment|scenes/environment.toml --width 160 --height 90 --spp 8"
  "materials|scenes/materials.toml --width 160 --height 80 --spp 8"
  "gltf|scenes/gltf.toml --width 160 --height 90 --spp 4"
  "detail|scenes/detail.toml --width 160 --height 90 --spp 4"
  "solids|scenes/solids.toml --width 160 --height 90 --spp 4"
  "aov|scenes/seed.toml --width 96 --height 96 --aov all"
  "exr|scenes/outdoor-sunset.toml --width 96 --height 54 --spp 4 EXR"
)
differ=0
for c in "${cases[@]}"; do
  name=${c%%|*}; args=${c#*|}
  ext=png; [[ $args == *EXR ]] && { ext=exr; args=${args% EXR}; }
  for side in a b; do
    bin=$1; [ $side = b ] && bin=$2
    mkdir -p "$out/$side"
    # shellcheck disable=SC2086
    "$bin" render $args -o "$out/$side/$name.$ext" --quiet
  done
  for f in "$out"/a/"$name".*; do
    g="$out/b/$(basename "$f")"
    if cmp -s "$f" "$g"; then echo "same    $(basename "$f")"; else echo "DIFFERS $(basename "$f")"; differ=1; fi
  done
done
exit $differ
