"""Splitting a job into tasks: one frame and one tile (a rectangle of the image) each."""

import math
import re
from dataclasses import dataclass
from typing import Iterable, List, Tuple

_GRID = re.compile(r"^\s*(\d+)\s*[xX]\s*(\d+)\s*$")


@dataclass(frozen=True)
class Region:
    """Columns x0..x1 and rows y0..y1 of the image, ends exclusive, (0, 0) the top left."""

    x0: int
    y0: int
    x1: int
    y1: int

    @property
    def width(self) -> int:
        return self.x1 - self.x0

    @property
    def height(self) -> int:
        return self.y1 - self.y0

    def arg(self) -> str:
        """The region as ``snell render --region`` takes it: ``X0,Y0,X1,Y1``."""
        return f"{self.x0},{self.y0},{self.x1},{self.y1}"

    def __str__(self) -> str:
        return f"x {self.x0}..{self.x1}, y {self.y0}..{self.y1}"


@dataclass(frozen=True)
class Task:
    """One unit of work: tile number ``tile`` (row-major) of frame ``frame``."""

    frame: int
    tile: int
    region: Region

    def key(self) -> str:
        """A name for the task, unique within a job."""
        return f"{self.frame}/{self.tile}"


def parse_grid(text: str) -> Tuple[int, int]:
    """Parse ``CxR`` (columns x rows, both at least 1). Raises ValueError otherwise."""
    match = _GRID.match(text)
    if not match:
        raise ValueError(f"`{text}` is not a grid of tiles: write COLUMNSxROWS, e.g. 4x4")
    columns, rows = int(match.group(1)), int(match.group(2))
    if columns < 1 or rows < 1:
        raise ValueError(f"`{text}`: a grid needs at least one column and one row")
    return columns, rows


def _cuts(size: int, parts: int) -> List[int]:
    """Where ``parts`` pieces of ``size // parts`` begin, the last taking the remainder."""
    step = size // parts
    return [i * step for i in range(parts)] + [size]


def grid(width: int, height: int, columns: int, rows: int) -> List[Region]:
    """``columns`` x ``rows`` tiles over a ``width`` x ``height`` image, row by row.

    Every tile but the last of its row (column) is ``width // columns`` wide (``height //
    rows`` high); the last takes the remainder. Every pixel is in exactly one tile. Raises
    ValueError when the grid has more columns or rows than the image has pixels.
    """
    if columns > width or rows > height:
        raise ValueError(
            f"a grid of {columns}x{rows} tiles does not fit a {width} x {height} image: "
            "at most one column per pixel of width and one row per pixel of height"
        )
    xs, ys = _cuts(width, columns), _cuts(height, rows)
    return [Region(xs[c], ys[r], xs[c + 1], ys[r + 1]) for r in range(rows) for c in range(columns)]


def grid_for_size(width: int, height: int, size: int) -> Tuple[int, int]:
    """The columns and rows of square tiles of ``size`` pixels (the last ones smaller)."""
    if size < 1:
        raise ValueError("a tile is at least 1 pixel")
    return math.ceil(width / size), math.ceil(height / size)


def regions_of_size(width: int, height: int, size: int) -> List[Region]:
    """Tiles of ``size`` x ``size`` pixels over the image, the last row and column cut short."""
    columns, rows = grid_for_size(width, height, size)
    xs = [min(i * size, width) for i in range(columns + 1)]
    ys = [min(i * size, height) for i in range(rows + 1)]
    return [Region(xs[c], ys[r], xs[c + 1], ys[r + 1]) for r in range(rows) for c in range(columns)]


def split(frames: Iterable[int], regions: List[Region]) -> List[Task]:
    """Every (frame, tile) pair, frame by frame so that frames complete in order."""
    return [Task(frame, i, region) for frame in frames for i, region in enumerate(regions)]
