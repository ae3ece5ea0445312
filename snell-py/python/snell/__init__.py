"""snell, a ray tracer for learning, teaching and making images, from Python and Jupyter.

    import snell
    scene = snell.load("scenes/seed.toml")
    img = snell.render(scene, spp=4)          # float32 array, height x width x 3, linear
    scene.materials["red"]["color"] = [0.1, 0.3, 1.0]
    img = snell.render(scene, spp=4)          # built again; its texture files are not read again
    snell.write(img, "seed.png")              # or .exr
    tree = snell.explain(scene, 512, 600)     # what `snell explain --json` prints

A render's pixels are the command line's, bit for bit (`snell render -o x.exr` of the same
scene and settings). Problems in a scene raise `snell.SceneError` with the command line's
`file:line:col: message` lines; Ctrl-C stops a render and raises `snell.Interrupted`, which
carries the picture as far as it got. `snell.CAN_DENOISE` says whether this build has the
denoiser (`render(..., denoise=True)`; the `denoise` feature, docs/denoise.md).
"""

from ._snell import CAN_DENOISE, SceneError, SettingsError, __version__
from .image import Image, read, write
from .render import Interrupted, explain, render
from .scene import Scene, load, load_dict, loads

__all__ = [
    "CAN_DENOISE",
    "Image",
    "Interrupted",
    "Scene",
    "SceneError",
    "SettingsError",
    "__version__",
    "explain",
    "load",
    "load_dict",
    "loads",
    "read",
    "render",
    "write",
]
