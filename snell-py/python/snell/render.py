"""Rendering and explaining pixels."""

from __future__ import annotations

import json
import os
import sys
from typing import Any, Callable, Dict, Iterable, Optional, Union

from . import _snell
from .image import Image
from .scene import Scene, load

Progress = Union[bool, Callable[[int, int], Any], None]


class Interrupted(KeyboardInterrupt):
    """Ctrl-C (or a notebook's interrupt) stopped a render. `image` is the picture as far
    as it got: the path tracer's passes so far (every pixel, fewer samples), or Whitted's
    finished tiles (the rest black)."""

    def __init__(self, image: Image) -> None:
        super().__init__("the render was interrupted; the picture so far is in .image")
        self.image = image


def _scene(scene: Union[Scene, str, "os.PathLike[str]"]) -> Scene:
    return scene if isinstance(scene, Scene) else load(scene)


class _Bar:
    """A progress bar: tqdm's (its notebook widget in Jupyter) where tqdm is installed, else
    one line on standard error."""

    def __init__(self) -> None:
        self.bar = None
        try:
            from tqdm.auto import tqdm

            self.tqdm = tqdm
        except ImportError:
            self.tqdm = None
        self.shown = -1

    def __call__(self, done: int, total: int) -> None:
        if self.tqdm is not None:
            if self.bar is None:
                self.bar = self.tqdm(total=total, unit="sample", unit_scale=True)
            self.bar.update(done - self.bar.n)
            return
        percent = 100 * done // max(total, 1)
        if percent != self.shown:
            self.shown = percent
            sys.stderr.write(f"\rrendering: {percent:3d} %")
            sys.stderr.flush()

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
        elif self.shown >= 0:
            sys.stderr.write("\n")


def render(
    scene: Union[Scene, str, "os.PathLike[str]"],
    spp: Optional[int] = None,
    seed: Optional[int] = None,
    width: Optional[int] = None,
    height: Optional[int] = None,
    integrator: Optional[str] = None,
    time: Optional[float] = None,
    threads: Optional[int] = None,
    aovs: Optional[Iterable[str]] = None,
    progress: Progress = None,
    lpe: Optional[Iterable[str]] = None,
    noise: Optional[float] = None,
    denoise: bool = False,
) -> Union[Image, Dict[str, Any]]:
    """Renders `scene` (a `Scene` or a scene file's path) as `snell render` would, with the
    settings given here in place of the scene's: samples per pixel, seed, size, integrator
    (`"whitted"`, `"path"`, `"light"` or `"bdpt"`), and for the path tracer, light tracing
    and bdpt `time`, seconds after which it stops
    at the end of a pass. `threads` defaults to every core. The interpreter's lock is
    released while it renders.

    Returns the picture, an `Image` (float32, height x width x 3, linear: the values an EXR
    of it holds). With `aovs` (debug views: `"normal"`, `"uv"`, `"depth"`, `"albedo"`,
    `"object"`, `"material"`, `"bounces"`, `"variance"`, `"spp"`), returns a dict of arrays:
    `"image"` and each view (height x width x its channels).

    `noise`: adaptive sampling (path tracer), as `snell render --noise`: after 16 samples a
    pixel takes more only while its estimated relative error, or a neighbour's, is above
    this (`0.01` is 1 %), `spp` the most it takes; the `"spp"` view shows where the samples
    went. A threshold outside (0, 1] or another integrator raises `SettingsError`.

    `denoise=True`: the dict also holds `"denoised"`, the picture denoised by Intel Open Image
    Denoise (as `snell render --denoise`), where the module was built with the `denoise`
    feature (docs/denoise.md); otherwise `SettingsError` says how to build it, before any
    work.

    `lpe`: light path expressions (path tracer), each `"NAME=EXPR"` (`"walls=C<RD'red'>.*L"`)
    or a preset (`"direct"`, `"indirect"`, `"specular"`, `"emission"`, `"caustics"`,
    `"per-light"`); see docs/lpe.md. With them, or with a scene that lists its own
    (`[[image.lpe]]`), the dict also holds each expression's `Image` by its name, made from the
    picture's own samples (`emission`, `direct`, `indirect` and `specular` add up to it). A
    mistake raises `SettingsError` (a `ValueError`) with its column, before rendering.

    `progress`: `True` for a bar (tqdm's where installed), or a function called with
    (samples done, samples in all) a few times a second. Ctrl-C stops the render and raises
    `Interrupted`, carrying the picture so far."""
    built = _scene(scene).build()
    views = list(aovs) if aovs is not None else []
    expressions = list(lpe) if lpe is not None else []
    bar = _Bar() if progress is True else None
    callback = bar if bar is not None else (progress or None)
    try:
        out = _snell.render(built, spp, seed, width, height, integrator, time, threads, views,
                            callback, expressions, noise, denoise)
    finally:
        if bar is not None:
            bar.close()
    exposure, tonemap = built.tone
    image = Image(out["image"], exposure=exposure, tonemap=tonemap, spp=out["spp"],
                  complete=out["complete"])
    if out["interrupted"]:
        raise Interrupted(image)
    if aovs is None and lpe is None and not out["lpe"] and not denoise:
        return image
    result: Dict[str, Any] = {"image": image}
    result.update(out["aovs"])
    for name, layer in out["lpe"].items():
        result[name] = Image(layer, exposure=exposure, tonemap=tonemap, spp=out["spp"],
                             complete=out["complete"])
    if "denoised" in out:
        result["denoised"] = Image(out["denoised"], exposure=exposure, tonemap=tonemap,
                                   spp=out["spp"], complete=out["complete"])
    return result


def explain(
    scene: Union[Scene, str, "os.PathLike[str]"],
    x: int,
    y: int,
    sample: Optional[int] = None,
    max_rays: int = 200,
) -> Dict[str, Any]:
    """Why pixel (`x`, `y`) has its colour: the document `snell explain --json` prints, as
    a dict. Under Whitted, the tree of rays through the pixel's centre, or of sample `sample`
    as the renderer takes it (at most `max_rays` rays);
    under the path tracer, the path of sample `sample` (0 unless given), every vertex with
    what it added (under light tracing, which traces no camera paths, the same, said so in
    its `note`); under bdpt, that sample's two subpaths and its strategies. Each hit `point`
    has a `screen` position beside it, for drawing the path over the picture."""
    return json.loads(_snell.explain(_scene(scene).build(), x, y, sample, max_rays))
