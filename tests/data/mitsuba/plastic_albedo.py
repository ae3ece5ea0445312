#!/usr/bin/env python3
"""Prints how much light Mitsuba 3's rough plastic returns straight on: a white
`roughplastic` (GGX, index 1.5) lit and seen along the normal, the mean of its `sample`
weights over 200,000 samples, at alpha 0.1, 0.3 and 1. `src/bsdf/mitsuba_tests.rs`
(`a_white_rough_plastic_returns_what_mitsubas_does`) holds snell's plastic to these numbers.

    pip install mitsuba==3.9.1
    python3 tests/data/mitsuba/plastic_albedo.py

Printed by Mitsuba 3.9.1: 0.1 0.90894, 0.3 0.69153, 1.0 0.33567."""

import random

import mitsuba as mi

mi.set_variant("scalar_rgb")
for alpha in [0.1, 0.3, 1.0]:
    bsdf = mi.load_dict({"type": "roughplastic", "distribution": "ggx", "alpha": alpha, "int_ior": 1.5,
                         "diffuse_reflectance": {"type": "rgb", "value": [1, 1, 1]}})
    si = mi.SurfaceInteraction3f()
    si.wi = mi.Vector3f(0, 0, 1)
    ctx, rng, n, total = mi.BSDFContext(), random.Random(1), 200000, 0.0
    for _ in range(n):
        _, weight = bsdf.sample(ctx, si, rng.random(), mi.Point2f(rng.random(), rng.random()))
        total += weight[0]
    print(alpha, f"{total / n:.5f}")
