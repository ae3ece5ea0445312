#!/usr/bin/env bash
# Renders the pictures of the README and docs/ from the scene files, one command each, so
# that a picture and its caption cannot drift apart: each caption's samples are the ones
# this script renders with (tests/integration/docs.rs checks them against the README).
#   docs/images/make.sh            # every picture (about 10 minutes on two cores)
#   docs/images/make.sh seed cornell   # only these
# Not made here: cornell-mitsuba.png (Mitsuba 3's own render: bench/vs-mitsuba.py) and
# serve.png (the browser test's screenshot: SNELL_SCREENSHOT=docs/images/serve.png cargo
# test browser -- --include-ignored). The orbit strip needs Python with Pillow.
set -euo pipefail
cd "$(dirname "$0")/../.."
cargo build --release --quiet
snell=target/release/snell
out=docs/images
wanted=("$@")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# render NAME SCENE [FLAGS...]: docs/images/NAME.png, unless names were given and this is not one.
render() {
  local name=$1
  shift
  if [ ${#wanted[@]} -gt 0 ] && [[ ! " ${wanted[*]} " =~ " ${name%%/*} " ]]; then return; fi
  echo "== $name"
  "$snell" render "$@" -o "$out/$name.png" --quiet
}

render seed scenes/seed.toml
render seed-path scenes/seed.toml --integrator path --spp 64
render seed-bdpt scenes/seed.toml --integrator bdpt --spp 256
render showcase scenes/showcase.toml
render detail scenes/detail.toml
render materials scenes/materials.toml
render environment scenes/environment.toml
render outdoor-noon scenes/outdoor-noon.toml
render outdoor-sunset scenes/outdoor-sunset.toml
render solids scenes/solids.toml
render gltf scenes/gltf.toml
render khronos scenes/khronos.toml
render bunny scenes/bunny.toml --width 640 --height 640
render spot scenes/spot.toml --width 640 --height 480
render field scenes/field.toml --width 960 --height 540
render cornell scenes/cornell.toml --spp 4096
render caustics scenes/caustics.toml
render prism scenes/prism.toml
render bdpt/cornell scenes/cornell.toml --integrator bdpt --aov strategies --width 160 --height 160 --spp 256
render caustics-path scenes/caustics.toml --integrator path
render caustics-light scenes/caustics.toml --integrator light
render far-checker-filtered scenes/far-checker.toml
sed 's/^filter_textures = true/filter_textures = false/' scenes/far-checker.toml > scenes/far-checker.point.toml
render far-checker-point scenes/far-checker.point.toml
rm scenes/far-checker.point.toml
render debugging/seed scenes/seed.toml --width 256 --height 256 --aov all
render debugging/earth-turned scenes/debugging/earth-turned.toml --width 256 --height 256 --aov uv
render debugging/floor-stripes scenes/debugging/floor-stripes.toml --width 256 --height 256 --aov uv
render debugging/sunken-cylinder scenes/debugging/sunken-cylinder.toml --width 256 --height 256 --aov object
render debugging/glass-disk scenes/debugging/glass-disk.toml --width 256 --height 256
render lpe/cornell scenes/cornell.toml --width 256 --height 256 --spp 1024 --lpe emission --lpe direct --lpe indirect
render lpe/seed scenes/seed.toml --integrator path --width 256 --height 256 --spp 256 --lpe direct --lpe indirect --lpe specular --lpe caustics

# lab NAME ARGS...: docs/images/NAME.png from `snell lab ARGS -o ...`.
lab() {
  local name=$1
  shift
  if [ ${#wanted[@]} -gt 0 ] && [[ ! " ${wanted[*]} " =~ " ${name} " ]]; then return; fi
  echo "== $name"
  "$snell" lab "$@" -o "$out/$name.png" > /dev/null
}
lab lab-plastic bsdf plastic --roughness 0.3
lab lab-gold-grazing bsdf conductor --param 'metal="Au"' --roughness 0.1 --angle 80
lab lab-cornell-light light scenes/cornell.toml --from 0,-0.5,0
lab lab-environment light scenes/environment.toml --from 0,0.5,0

if [ ${#wanted[@]} -eq 0 ] || [[ " ${wanted[*]} " =~ " orbit-strip " ]]; then
  echo "== orbit-strip"
  "$snell" render scenes/orbit.toml --frames 0..40 --width 200 --height 200 -o "$tmp/f_##.png" --quiet
  python3 - "$tmp" "$out/orbit-strip.png" <<'PY'
import sys
from PIL import Image
frames = [Image.open(f"{sys.argv[1]}/f_{n:02}.png") for n in range(0, 41, 8)]
strip = Image.new("RGB", (6 * 200 + 5 * 4, 200), (255, 255, 255))
for i, f in enumerate(frames):
    strip.paste(f, (i * 204, 0))
strip.save(sys.argv[2])
PY
fi
