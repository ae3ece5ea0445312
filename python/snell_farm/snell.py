"""The snell binary, as the driver calls it: find it, ``check --json`` a scene, ``merge`` a frame."""

import json
import os
import shutil
import subprocess
from dataclasses import dataclass
from typing import List, Optional, Sequence

from .errors import FarmError


@dataclass(frozen=True)
class SceneInfo:
    """What ``snell check SCENE --json`` says of a scene."""

    width: int
    height: int
    frames: int
    fps: float
    files: List[str]
    warnings: List[str]
    integrator: str = "whitted"
    """whitted, path, light or bdpt."""
    noise: Optional[float] = None
    """Adaptive sampling's threshold, where the scene samples adaptively."""


def find_snell(given: Optional[str]) -> str:
    """The absolute path of the snell binary: ``given`` (a path or a name on PATH), else
    ``snell`` on PATH. Raises FarmError when there is none."""
    name = given or "snell"
    if os.sep in name or (os.altsep and os.altsep in name):
        if os.path.isfile(name) and os.access(name, os.X_OK):
            return os.path.abspath(name)
        raise FarmError(f"{name}: no snell binary there (build it with `cargo build --release`)", 2)
    found = shutil.which(name)
    if found is None:
        raise FarmError(f"`{name}` is not on PATH: install snell (`cargo install --path .`) or give --snell PATH", 2)
    return os.path.abspath(found)


def _stderr(result: "subprocess.CompletedProcess[str]") -> str:
    return (result.stderr or "").strip()


def check(snell: str, scene: str, width: Optional[int] = None, height: Optional[int] = None) -> SceneInfo:
    """Run ``snell check SCENE --json``; raises FarmError (exit 2) with snell's messages for a
    bad scene, or when this snell does not give the JSON."""
    command = [snell, "check", scene, "--json"]
    if width is not None:
        command += ["--width", str(width)]
    if height is not None:
        command += ["--height", str(height)]
    try:
        result = subprocess.run(command, stdin=subprocess.DEVNULL, capture_output=True, text=True)
    except OSError as err:
        raise FarmError(f"cannot run {snell}: {err.strerror}", 2)
    if result.returncode != 0:
        raise FarmError(f"snell check {scene} failed (exit status {result.returncode}):\n{_stderr(result)}", 2)
    try:
        data = json.loads(result.stdout)
        return SceneInfo(
            width=int(data["width"]),
            height=int(data["height"]),
            frames=int(data.get("frames", 1)),
            fps=float(data.get("fps", 0) or 0),
            files=[str(f) for f in data.get("files", [])],
            warnings=[str(w) for w in data.get("warnings", [])],
            integrator=str(data.get("integrator", "whitted")),
            noise=None if data.get("noise") is None else float(data["noise"]),
        )
    except (ValueError, KeyError, TypeError) as err:
        raise FarmError(f"`snell check {scene} --json` did not print the expected JSON ({err}); is {snell} too old?", 2)


def merge(snell: str, parts: Sequence[str], output: str) -> None:
    """Run ``snell merge PARTS -o OUTPUT``; raises FarmError with snell's messages on failure."""
    command = [snell, "merge", *parts, "-o", output]
    try:
        result = subprocess.run(command, stdin=subprocess.DEVNULL, capture_output=True, text=True)
    except OSError as err:
        raise FarmError(f"cannot run {snell}: {err.strerror}")
    if result.returncode != 0:
        raise FarmError(f"snell merge to {output} failed (exit status {result.returncode}):\n{_stderr(result)}")
