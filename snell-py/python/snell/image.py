"""Pictures as numpy arrays: `Image` (an array that shows itself in a notebook), and
reading and writing PNG and EXR files."""

from __future__ import annotations

import os
from typing import Optional, Union

import numpy as np

from . import _snell

PathLike = Union[str, "os.PathLike[str]"]


class Image(np.ndarray):
    """A linear picture, float32, height x width x 3: a numpy array in every way, which a
    notebook shows as a PNG (after `exposure` stops and the `tonemap` curve, as the scene's
    own PNG would be written).

    `spp` is the samples per pixel it holds and `complete` whether the render finished."""

    exposure: float
    tonemap: str
    spp: Optional[int]
    complete: bool

    def __new__(
        cls,
        array,
        exposure: float = 0.0,
        tonemap: str = "clamp",
        spp: Optional[int] = None,
        complete: bool = True,
    ) -> "Image":
        obj = np.asarray(array, dtype=np.float32).view(cls)
        obj.exposure = float(exposure)
        obj.tonemap = tonemap
        obj.spp = spp
        obj.complete = complete
        return obj

    def __array_finalize__(self, obj) -> None:
        self.exposure = getattr(obj, "exposure", 0.0)
        self.tonemap = getattr(obj, "tonemap", "clamp")
        self.spp = getattr(obj, "spp", None)
        self.complete = getattr(obj, "complete", True)

    def to_png(self, exposure: Optional[float] = None, tonemap: Optional[str] = None) -> bytes:
        """The PNG file's bytes: 8-bit sRGB after the exposure and tone curve (the image's
        own unless given)."""
        return _snell.encode_png(
            _rgb(self),
            self.exposure if exposure is None else exposure,
            self.tonemap if tonemap is None else tonemap,
        )

    def _repr_png_(self) -> Optional[bytes]:
        # Only a whole picture shows as one (a row or a channel of it is plain numbers).
        if self.ndim != 3 or self.shape[2] != 3 or self.shape[0] == 0 or self.shape[1] == 0:
            return None
        return self.to_png()

    def write(self, path: PathLike, exposure: Optional[float] = None, tonemap: Optional[str] = None) -> None:
        """Writes the picture to `path` (see `snell.write`), with the image's own exposure
        and tone curve unless given."""
        write(
            self,
            path,
            exposure=self.exposure if exposure is None else exposure,
            tonemap=self.tonemap if tonemap is None else tonemap,
        )


def _rgb(array) -> np.ndarray:
    """`array` as float32, height x width x 3: a grey image (height x width) is repeated
    into three channels, and a fourth (alpha) channel is left out."""
    a = np.asarray(array, dtype=np.float32)
    if a.ndim == 2:
        a = np.repeat(a[:, :, None], 3, axis=2)
    if a.ndim != 3 or a.shape[2] not in (3, 4):
        raise ValueError(
            f"an image is height x width x 3 (or x 4, or height x width), not {a.shape}"
        )
    if a.shape[2] == 4:
        a = a[:, :, :3]
    return np.ascontiguousarray(a)


def write(image, path: PathLike, exposure: float = 0.0, tonemap: str = "clamp") -> None:
    """Writes `image` (linear, height x width x 3) to `path`: a `.png` as 8-bit sRGB after
    `exposure` stops and the tone curve (`"clamp"`, `"reinhard"` or `"aces"`), an `.exr` as
    32-bit linear floats. The file is written beside and renamed into place, so an old file
    is never left half overwritten."""
    _snell.write(_rgb(image), os.fspath(path), float(exposure), tonemap)


def read(path: PathLike) -> Image:
    """Reads a PNG, JPEG, BMP, HDR or EXR file as a linear `Image` (8-bit files are taken as
    sRGB and made linear, as snell's textures are; float files as they are)."""
    return Image(_snell.read(os.fspath(path)))
