#!/usr/bin/env python3
"""Writes cornell-32.exr: Mitsuba 3.9.1's own render of its cornell_box() at 32 x 32, box
filter, path tracer of maximum depth 8 and Russian roulette from depth 5 (as
scenes/cornell.toml sets snell's), 65536 samples per pixel of its independent sampler.
tests/integration/path.rs holds snell's Cornell box to it pixel by pixel (a z-test).

    pip install mitsuba==3.9.1 && apt-get install libllvm19
    python3 tests/data/mitsuba/cornell_fixture.py"""

import os

os.environ.setdefault("DRJIT_LIBLLVM_PATH", "/usr/lib/x86_64-linux-gnu/libLLVM-19.so")
import mitsuba as mi  # noqa: E402

mi.set_variant("llvm_ad_rgb")
d = mi.cornell_box()
d["sensor"]["film"]["width"] = 32
d["sensor"]["film"]["height"] = 32
d["sensor"]["film"]["rfilter"] = {"type": "box"}
d["sensor"]["film"]["pixel_format"] = "rgb"
d["sensor"]["sampler"] = {"type": "independent", "sample_count": 65536}
d["integrator"] = {"type": "path", "max_depth": 8, "rr_depth": 5}
image = mi.render(mi.load_dict(d), spp=65536, seed=7)
out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "cornell-32.exr")
mi.Bitmap(image).write(out)
print(f"{out}: Mitsuba {mi.__version__}")
