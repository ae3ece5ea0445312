#!/usr/bin/env bash
# Times snell against POV-Ray 3.7 on the seed scene, 1024 x 1024 at 16 samples per pixel,
# alternating the two in one run (absolute times are noisy on a shared machine; the ratio
# is the figure to report). Needs the shared folder beside the checkout (or SNELL_SHARED).
#   bench/vs-povray.sh [-n RUNS]
set -euo pipefail
cd "$(dirname "$0")/.."
shared=${SNELL_SHARED:-../shared}
[ -x "$shared/bench/vs-povray" ] || { echo "vs-povray.sh: $shared/bench/vs-povray not found (set SNELL_SHARED)" >&2; exit 2; }
cargo build --release --quiet
out=$(mktemp -d)
exec bash "$shared/bench/vs-povray" "$@" -s 1024 -a 4 -- \
  ./target/release/snell render scenes/seed.toml -o "$out/snell.png" --width 1024 --height 1024 --spp 16 --quiet
