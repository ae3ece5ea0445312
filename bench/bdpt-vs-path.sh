#!/usr/bin/env bash
# Equal-time error of bidirectional path tracing against the path tracer on a caustic scene
# (scenes/caustics.toml by default): a converged bidirectional reference (REF_SPP samples a
# pixel, rendered once and kept in the output folder), then each integrator for the same
# wall-clock time (--time, whole passes), each picture's error against the reference as the
# RMSE and the relative MSE ../shared/peers/compare_exr.py prints (here: the luminance's
# RMSE over the image, and its ratio path / bdpt). Light the path tracer cannot find (a point
# light through glass) counts as its error, as a photograph would count it.
#   bench/bdpt-vs-path.sh [-t SECONDS] [-r REF_SPP] [-s WIDTH] [SCENE]
set -euo pipefail
time_s=10; ref_spp=1024; width=240
while [ $# -gt 0 ]; do case "$1" in
  -t) time_s=$2; shift 2;; -r) ref_spp=$2; shift 2;; -s) width=$2; shift 2;; *) break;; esac; done
scene=${1:-scenes/caustics.toml}
height=$((width * 3 / 4))
snell=${SNELL:-target/release/snell}
out=${OUT:-/tmp/bdpt-vs-path}
mkdir -p "$out"
ref="$out/ref-$(basename "$scene" .toml)-$width-$ref_spp-seed99.exr"
size=(--width "$width" --height "$height")
if [ ! -f "$ref" ]; then
  echo "rendering the reference: bdpt, $ref_spp spp ..." >&2
  # A seed of its own: the renders compared must not share its samples.
  "$snell" render "$scene" --integrator bdpt --spp "$ref_spp" --seed 99 "${size[@]}" -q -o "$ref"
fi
for integrator in path bdpt; do
  "$snell" render "$scene" --integrator "$integrator" --spp 65536 --time "$time_s" \
    "${size[@]}" -o "$out/$integrator.exr" 2>&1 | sed -n 's/^wrote //p'
done
python3 - "$ref" "$out/path.exr" "$out/bdpt.exr" <<'PY'
import sys
import numpy as np
import OpenEXR, Imath
def lum(path):
    f = OpenEXR.InputFile(path)
    dw = f.header()["dataWindow"]
    w, h = dw.max.x - dw.min.x + 1, dw.max.y - dw.min.y + 1
    ch = [np.frombuffer(f.channel(c, Imath.PixelType(Imath.PixelType.FLOAT)), np.float32) for c in "RGB"]
    return (0.2126 * ch[0] + 0.7152 * ch[1] + 0.0722 * ch[2]).reshape(h, w).astype(np.float64)
ref, path, bdpt = (lum(p) for p in sys.argv[1:4])
rmse = lambda a: float(np.sqrt(np.mean((a - ref) ** 2)))
rel = lambda a: float(np.mean((a - ref) ** 2 / (ref ** 2 + 1e-2)))
print(f"RMSE against the reference: path {rmse(path):.5f}, bdpt {rmse(bdpt):.5f}, ratio {rmse(path) / rmse(bdpt):.2f}")
print(f"relMSE: path {rel(path):.5f}, bdpt {rel(bdpt):.5f}, ratio {rel(path) / rel(bdpt):.2f}")
PY
