"""Writing and reading pictures."""

import os

import numpy as np
import pytest

import snell


def test_exr_keeps_every_float_and_png_every_byte(tmp_path):
    rng = np.random.default_rng(1)
    img = rng.random((5, 7, 3), dtype=np.float32) * 4
    snell.write(img, tmp_path / "a.exr")
    assert np.array_equal(snell.read(tmp_path / "a.exr"), img)
    snell.write(img, tmp_path / "a.png")
    back = snell.read(tmp_path / "a.png")
    # Clamped, encoded as 8-bit sRGB and decoded again: within half an sRGB step.
    assert np.abs(back - np.clip(img, 0, 1)).max() < 0.01
    assert sorted(os.listdir(tmp_path)) == ["a.exr", "a.png"], "no temporary files left"


def test_exposure_and_curves(tmp_path):
    grey = np.full((2, 2, 3), 0.25, dtype=np.float32)
    snell.write(grey, tmp_path / "up.png", exposure=1)
    assert np.allclose(snell.read(tmp_path / "up.png"), 0.5, atol=0.005)
    # 2.0 through Narkowicz's ACES fit is 0.915: below white, where clamping gives 1.
    snell.write(grey * 8, tmp_path / "aces.png", tonemap="aces")
    assert np.allclose(snell.read(tmp_path / "aces.png"), 0.915, atol=0.01)
    with pytest.raises(ValueError, match="no tone curve"):
        snell.write(grey, tmp_path / "x.png", tonemap="filmic")


def test_shapes_and_failures(tmp_path):
    snell.write(np.zeros((3, 4)), tmp_path / "grey.png")
    assert snell.read(tmp_path / "grey.png").shape == (3, 4, 3)
    snell.write(np.zeros((3, 4, 4)), tmp_path / "rgba.png")
    with pytest.raises(ValueError, match="height x width x 3"):
        snell.write(np.zeros((3, 4, 2)), tmp_path / "x.png")
    with pytest.raises(OSError):
        snell.write(np.zeros((3, 4, 3)), tmp_path / "no" / "folder" / "x.png")
    with pytest.raises(OSError):
        snell.write(np.zeros((3, 4, 3)), tmp_path / "x.tiff")
    with pytest.raises(OSError):
        snell.read(tmp_path / "none.png")


def test_an_image_shows_itself_and_stays_an_array():
    img = snell.Image(np.full((4, 6, 3), 0.5), exposure=0, tonemap="clamp")
    png = img._repr_png_()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    assert isinstance(img, np.ndarray) and img.dtype == np.float32
    assert (img * 2).max() == 1.0
    assert img[0]._repr_png_() is None, "a row is not a picture"
    assert img[:2, :3].exposure == 0
