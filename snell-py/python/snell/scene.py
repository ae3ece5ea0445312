"""Scenes: built from a file, from text or from a dict, and edited from Python.

A `Scene` keeps its definition (the scene file's tables as a dict) and the scene built
from it. Edit the definition (`scene.camera["position"] = [0, 1, 5]`,
`scene.materials["red"]["color"] = [0, 0, 1]`, `scene.add({...})`) and the next render
builds it again, reusing the images and meshes already read."""

from __future__ import annotations

import copy
import json
import os
from typing import Any, Dict, List, Optional, Union

from . import _snell

try:  # Python 3.11 on
    import tomllib as _toml
except ModuleNotFoundError:  # pragma: no cover - older Pythons
    import tomli as _toml  # type: ignore[no-redef]

PathLike = Union[str, "os.PathLike[str]"]


class Scene:
    """A scene: its definition (`definition`, a dict as the scene file has it) and the scene
    built from it. Build one with `snell.load`, `snell.loads` or `snell.load_dict`."""

    def __init__(self, native: Optional["_snell.NativeScene"], text: str, format: str, base_dir: str, name: str,
                 assets: "_snell.Assets", frame: int = 0) -> None:
        self._native = native
        self._frame = frame
        self._text = text
        self._format = format
        self._base_dir = base_dir
        self._name = name
        # The name messages give the text built from: `(edited)` after an edit.
        self._message_name = name
        self._assets = assets
        self._definition: Optional[Dict[str, Any]] = None
        # The definition as last built, to tell whether it has been edited since.
        self._built: Optional[str] = None

    # ---- the definition ------------------------------------------------------------------

    @property
    def definition(self) -> Dict[str, Any]:
        """The scene's tables as a dict (read from its text at first use). Edit it in place;
        the next render builds the scene again."""
        if self._definition is None:
            if self._format == "toml":
                self._definition = _toml.loads(self._text)
            else:
                self._definition = json.loads(self._text)
            self._built = _dump(self._definition, sort_keys=True)
        return self._definition

    def _table(self, key: str, empty) -> Any:
        return self.definition.setdefault(key, empty)

    @property
    def image(self) -> Dict[str, Any]:
        """The `[image]` table (width, height, samples, integrator ...)."""
        return self._table("image", {})

    @property
    def camera(self) -> Dict[str, Any]:
        """The `[camera]` table (position, look_at, fov ...)."""
        return self._table("camera", {})

    @property
    def materials(self) -> Dict[str, Dict[str, Any]]:
        """The materials by name."""
        return self._table("materials", {})

    @property
    def textures(self) -> Dict[str, Dict[str, Any]]:
        """The textures by name."""
        return self._table("textures", {})

    @property
    def objects(self) -> List[Dict[str, Any]]:
        """The `[[objects]]`, in order."""
        return self._table("objects", [])

    @property
    def lights(self) -> List[Dict[str, Any]]:
        """The `[[lights]]`, in order."""
        return self._table("lights", [])

    def add(self, obj: Dict[str, Any]) -> Dict[str, Any]:
        """Adds an object (a dict as an `[[objects]]` entry: `{"type": "sphere", "center":
        [0, 1, 0], "radius": 1, "material": "red"}`) and returns it."""
        if not isinstance(obj, dict):
            raise TypeError(f"an object is a dict, not {type(obj).__name__}")
        self.objects.append(obj)
        return obj

    def copy(self) -> "Scene":
        """An independent copy (its own definition; the images read are shared)."""
        other = Scene(self._native, self._text, self._format, self._base_dir, self._name, self._assets,
                      self._frame)
        other._message_name = self._message_name
        if self._definition is not None:
            other._definition = copy.deepcopy(self._definition)
            other._built = self._built
        return other

    # ---- the built scene -----------------------------------------------------------------

    def build(self) -> "_snell.NativeScene":
        """The scene built from its definition as it is now, at its frame: built again
        (raising `SceneError` for any problem) if the definition changed since the last
        build."""
        if self._definition is not None:
            now = _dump(self._definition, sort_keys=True)
            if now != self._built:
                # Messages name the edited text (`scene.source`), whose lines they count.
                self._text, self._format, self._built = _dump(self._definition, indent=2), "json", now
                self._message_name = f"{self._name} (edited)"
                self._native = None
        if self._native is None or self._native.frame[0] != self._frame:
            self._native = _snell.loads(self._text, self._format, self._message_name, self._base_dir,
                                        self._assets, self._frame)
        return self._native

    @property
    def settings(self) -> Dict[str, Any]:
        """Width, height, samples per pixel, seed, integrator and maximum depth, as built."""
        width, height, spp, seed, integrator, max_depth = self.build().settings
        return {
            "width": width,
            "height": height,
            "spp": spp,
            "seed": seed,
            "integrator": integrator,
            "max_depth": max_depth,
        }

    @property
    def frame(self) -> int:
        """The frame of the scene's `[animation]` it is built at (0 for a still)."""
        return self._frame

    @property
    def frames(self) -> int:
        """How many frames the scene's `[animation]` has (1 for a still)."""
        return self.build().frame[1]

    def at_frame(self, frame: int) -> "Scene":
        """The scene at another frame of its animation: a copy built there (its edits and the
        images read kept)."""
        other = self.copy()
        other._frame = int(frame)
        other.build()
        return other

    @property
    def path(self) -> str:
        """The file the scene came from (or the name given to text)."""
        return self._name

    @property
    def source(self) -> str:
        """The text the scene was last built from (JSON after an edit)."""
        return self.build().source

    @property
    def warnings(self) -> List[str]:
        """What the build warned of."""
        return self.build().warnings

    @property
    def files(self) -> List[str]:
        """The files the build read (textures, meshes)."""
        return self.build().files

    def summary(self) -> str:
        """`snell check`'s summary."""
        return self.build().summary()

    def __repr__(self) -> str:
        s = self.settings
        return (f"<snell.Scene {self._name!r}: {s['width']} x {s['height']}, {s['spp']} spp, "
                f"{s['integrator']}>")


def _plain(value: Any) -> Any:
    """numpy arrays and numbers (a camera position computed with numpy) as lists and
    numbers, which a scene's tables hold."""
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"a scene holds numbers, strings, lists and tables, not {type(value).__name__}")


def _dump(definition: Dict[str, Any], **options: Any) -> str:
    return json.dumps(definition, default=_plain, **options)


def load(path: PathLike, frame: int = 0) -> Scene:
    """Reads, checks and builds the scene file `path` (`.toml` or `.json`) at `frame` of its
    `[animation]` (a still has frame 0 only); relative paths in it resolve against its
    folder. Raises `SceneError` with every problem found."""
    name = os.fspath(path)
    assets = _snell.Assets()
    native = _snell.load(name, assets, frame)
    fmt = "json" if name.lower().endswith(".json") else "toml"
    base = os.path.dirname(name) or "."
    return Scene(native, native.source, fmt, base, name, assets, frame)


def loads(text: str, format: str = "toml", base_dir: PathLike = ".", name: str = "<string>",
          frame: int = 0) -> Scene:
    """Builds a scene from `text` (`format` `"toml"` or `"json"`) at `frame` of its
    animation; relative paths resolve against `base_dir`, and messages name it `name`."""
    fmt = format.lower()
    assets = _snell.Assets()
    native = _snell.loads(text, fmt, name, os.fspath(base_dir), assets, frame)
    return Scene(native, text, fmt, os.fspath(base_dir), name, assets, frame)


def load_dict(definition: Dict[str, Any], base_dir: PathLike = ".", name: str = "<dict>",
              frame: int = 0) -> Scene:
    """Builds a scene from a dict shaped as a scene file (`{"camera": {...}, "objects":
    [...]}`); relative paths resolve against `base_dir`. The scene keeps a copy."""
    definition = copy.deepcopy(definition)
    text = _dump(definition, indent=2)
    scene = loads(text, "json", base_dir, name, frame)
    scene._definition = definition
    scene._built = _dump(definition, sort_keys=True)
    return scene
