#!/usr/bin/env python3
"""Writes bsdf.json: Mitsuba 3's own `eval`, `pdf` and `sample` of every BSDF that one of
snell's materials names as its counterpart, over a grid of directions and parameters.
`src/bsdf/mitsuba_tests.rs` checks snell's BSDFs against these numbers within 1 %.

    pip install mitsuba==3.9.1
    python3 tests/data/mitsuba/bsdf_fixture.py

Directions are written in snell's convention: `wo` toward the viewer (Mitsuba's `si.wi`),
`wi` toward the light (the `wo` that Mitsuba's `eval` takes and `sample` returns), in the
local frame (z the normal). Mitsuba's `eval` is `f(wo, wi) |cos wi|`; for a delta lobe,
`sample`'s `pdf` is the lobe's probability."""

import json
import re
import math
import os

import mitsuba as mi

mi.set_variant("scalar_rgb")

OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "bsdf.json")
ALPHAS = [0.05, 0.1, 0.3, 0.7]


def direction(theta_deg, phi_deg=0.0, below=False):
    t, p = math.radians(theta_deg), math.radians(phi_deg)
    z = math.cos(t) * (-1.0 if below else 1.0)
    return [math.sin(t) * math.cos(p), math.sin(t) * math.sin(p), z]


WO_FRONT = [direction(t) for t in [0.0, 30.0, 55.0, 70.0, 82.0]]
WI_FRONT = [direction(t, p) for t in [5.0, 25.0, 45.0, 65.0, 80.0, 88.0]
            for p in [0.0, 90.0, 180.0]]
WI_BACK = [direction(t, p, below=True) for t in [5.0, 30.0, 55.0, 80.0] for p in [0.0, 180.0]]
WO_BACK = [direction(t, below=True) for t in [0.0, 30.0, 45.0, 70.0]]
SAMPLE_POINTS = [(0.01, 0.3, 0.6), (0.5, 0.7, 0.2), (0.99, 0.45, 0.85)]


def interaction(wo):
    si = mi.SurfaceInteraction3f()
    si.wi = mi.Vector3f(*wo)
    return si


def rgb(v):
    return {"type": "rgb", "value": list(v)}


def evaluations(bsdf, wos, wis):
    ctx = mi.BSDFContext()
    rows = []
    for wo in wos:
        si = interaction(wo)
        for wi in wis:
            e = bsdf.eval(ctx, si, mi.Vector3f(*wi))
            p = bsdf.pdf(ctx, si, mi.Vector3f(*wi))
            rows.append(wo + wi + [e[0], e[1], e[2], float(p)])
    return rows


def samples(bsdf, wos):
    """What `sample` draws: for a delta lobe its direction, `f |cos wi|` (the weight times
    the lobe's chance) and the chance; for any other lobe the direction, and `eval` and
    `pdf` there (the weight that `sample` works out inside may take another microfacet
    normal than the one the two directions give, which matters only at grazing angles)."""
    ctx = mi.BSDFContext()
    rows = []
    for wo in wos:
        si = interaction(wo)
        for s1, s2x, s2y in SAMPLE_POINTS:
            bs, w = bsdf.sample(ctx, si, s1, mi.Point2f(s2x, s2y))
            delta = mi.has_flag(bs.sampled_type, mi.BSDFFlags.Delta)
            if delta:
                f, pdf = [w[k] * bs.pdf for k in range(3)], float(bs.pdf)
            else:
                e = bsdf.eval(ctx, si, bs.wo)
                f, pdf = [e[0], e[1], e[2]], float(bsdf.pdf(ctx, si, bs.wo))
            rows.append(wo + [s1, s2x, s2y] + list(bs.wo) + f + [pdf, 1.0 if delta else 0.0])
    return rows


cases = []


def case(snell, mitsuba, wos, wis, sample_too=False):
    bsdf = mi.load_dict(mitsuba)
    c = {"snell": snell, "mitsuba": mitsuba, "eval": evaluations(bsdf, wos, wis)}
    if sample_too:
        c["sample"] = samples(bsdf, wos)
    cases.append(c)


COLOUR = [0.8, 0.3, 0.1]

# diffuse
case({"type": "diffuse", "color": COLOUR},
     {"type": "diffuse", "reflectance": rgb(COLOUR)}, WO_FRONT, WI_FRONT + WI_BACK)

# conductor and roughconductor, by name
for metal in ["Au", "Ag", "Cu", "Al"]:
    case({"type": "conductor", "metal": metal, "roughness": 0.0},
         {"type": "conductor", "material": metal}, WO_FRONT, [], sample_too=True)
    for a in ALPHAS:
        case({"type": "conductor", "metal": metal, "roughness": a},
             {"type": "roughconductor", "distribution": "ggx", "alpha": a, "material": metal},
             WO_FRONT, WI_FRONT + WI_BACK, sample_too=True)
# a tinted perfect mirror (glTF's metal)
for a in [0.0] + ALPHAS:
    kind = {"type": "conductor"} if a == 0.0 else {"type": "roughconductor", "distribution": "ggx", "alpha": a}
    case({"type": "conductor", "metal": "none", "tint": COLOUR, "roughness": a},
         dict(kind, material="none", specular_reflectance=rgb(COLOUR)),
         WO_FRONT, [] if a == 0.0 else WI_FRONT, sample_too=True)

# dielectric and roughdielectric, from outside and from inside
for eta in [1.5, 1.33]:
    case({"type": "dielectric", "ior": eta, "roughness": 0.0},
         {"type": "dielectric", "int_ior": eta, "ext_ior": 1.0}, WO_FRONT + WO_BACK, [],
         sample_too=True)
    for a in ALPHAS:
        case({"type": "dielectric", "ior": eta, "roughness": a},
             {"type": "roughdielectric", "distribution": "ggx", "alpha": a, "int_ior": eta,
              "ext_ior": 1.0},
             WO_FRONT + WO_BACK, WI_FRONT + WI_BACK, sample_too=True)

# thindielectric
for eta in [1.5, 1.33]:
    case({"type": "thin", "ior": eta},
         {"type": "thindielectric", "int_ior": eta, "ext_ior": 1.0}, WO_FRONT + WO_BACK, [],
         sample_too=True)

# plastic and roughplastic
for eta, colour in [(1.5, COLOUR), (1.5, [1.0, 1.0, 1.0]), (1.9, COLOUR)]:
    case({"type": "plastic", "color": colour, "ior": eta, "roughness": 0.0},
         {"type": "plastic", "diffuse_reflectance": rgb(colour), "int_ior": eta, "ext_ior": 1.0},
         WO_FRONT, WI_FRONT + WI_BACK, sample_too=True)
    for a in ALPHAS:
        case({"type": "plastic", "color": colour, "ior": eta, "roughness": a},
             {"type": "roughplastic", "distribution": "ggx", "alpha": a,
              "diffuse_reflectance": rgb(colour), "int_ior": eta, "ext_ior": 1.0},
             WO_FRONT, WI_FRONT + WI_BACK, sample_too=True)

# metallic: blendbsdf of the coated base and the tinted mirror, `weight` the metal's share
for m in [0.3, 0.7]:
    for a in [0.0, 0.1, 0.3]:
        if a == 0.0:
            coat = {"type": "plastic", "diffuse_reflectance": rgb(COLOUR), "int_ior": 1.5, "ext_ior": 1.0}
            metal = {"type": "conductor", "material": "none", "specular_reflectance": rgb(COLOUR)}
        else:
            coat = {"type": "roughplastic", "distribution": "ggx", "alpha": a,
                    "diffuse_reflectance": rgb(COLOUR), "int_ior": 1.5, "ext_ior": 1.0}
            metal = {"type": "roughconductor", "distribution": "ggx", "alpha": a,
                     "material": "none", "specular_reflectance": rgb(COLOUR)}
        # No samples of the smooth blend: Mitsuba's blendbsdf weighs a delta lobe's chance
        # against the other part's density at its direction, quantities of different
        # measures; snell gives a delta its part's weight alone (docs/materials.md).
        case({"type": "metallic", "color": COLOUR, "ior": 1.5, "roughness": a, "metallic": m},
             {"type": "blendbsdf", "weight": m, "coat": coat, "metal": metal},
             WO_FRONT, WI_FRONT, sample_too=a > 0.0)

with open(OUT, "w") as f:
    text = json.dumps({"mitsuba": mi.__version__, "variant": mi.variant(), "cases": cases},
                      separators=(",", ":"))
    # Seven significant digits: Mitsuba computes in single precision.
    f.write(re.sub(r"-?\d+\.\d+(e-?\d+)?", lambda m: "%.7g" % float(m.group(0)), text))
    f.write("\n")
n_eval = sum(len(c["eval"]) for c in cases)
n_sample = sum(len(c.get("sample", [])) for c in cases)
print(f"{OUT}: {len(cases)} cases, {n_eval} evaluations, {n_sample} samples")
