"""The native half of `snell` (Rust, through pyo3). Use the package `snell`; these are the
functions it calls."""

from os import PathLike
from typing import Any, Callable, Dict, List, Optional, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

class SceneError(Exception): ...
class SettingsError(ValueError): ...

class Assets:
    """Images and meshes kept between builds of a scene."""

    def __init__(self) -> None: ...

class NativeScene:
    """A built scene (immutable)."""

    @property
    def settings(self) -> Tuple[int, int, int, int, str, int]: ...
    @property
    def tone(self) -> Tuple[float, str]: ...
    @property
    def path(self) -> str: ...
    @property
    def source(self) -> str: ...
    @property
    def warnings(self) -> List[str]: ...
    @property
    def files(self) -> List[str]: ...
    @property
    def frame(self) -> Tuple[int, int]: ...
    @property
    def load_seconds(self) -> float: ...
    def summary(self) -> str: ...

def load(path: Union[str, PathLike[str]], assets: Optional[Assets] = None, frame: int = 0) -> NativeScene: ...
def loads(
    text: str,
    format: str,
    name: Union[str, PathLike[str]],
    base_dir: Union[str, PathLike[str]],
    assets: Optional[Assets] = None,
    frame: int = 0,
) -> NativeScene: ...
def render(
    scene: NativeScene,
    spp: Optional[int] = None,
    seed: Optional[int] = None,
    width: Optional[int] = None,
    height: Optional[int] = None,
    integrator: Optional[str] = None,
    time: Optional[float] = None,
    threads: Optional[int] = None,
    aovs: Optional[List[str]] = None,
    progress: Optional[Callable[[int, int], Any]] = None,
    lpe: Optional[List[str]] = None,
    noise: Optional[float] = None,
    denoise: bool = False,
) -> Dict[str, Any]: ...
def explain(
    scene: NativeScene, x: int, y: int, sample: Optional[int] = None, max_rays: int = 200
) -> str: ...
def write(
    array: npt.NDArray[np.float32],
    path: Union[str, PathLike[str]],
    exposure: float = 0.0,
    tonemap: str = "clamp",
) -> None: ...
def read(path: Union[str, PathLike[str]]) -> npt.NDArray[np.float32]: ...
def encode_png(array: npt.NDArray[np.float32], exposure: float = 0.0, tonemap: str = "clamp") -> bytes: ...
