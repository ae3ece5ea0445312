"""Frame ranges (``A..B``, ``N``) and output patterns (``out/frame_####.png``)."""

import os
import re
from typing import Dict, Sequence

_HASHES = re.compile(r"#+")
_FRAMES = re.compile(r"^\s*(\d+)\s*(?:\.\.\s*(\d+)\s*)?$")


def parse_frames(text: str) -> range:
    """Parse ``A..B`` (A to B inclusive) or ``N`` (that frame alone) into a range.

    Raises ValueError with a message fit for the command line on anything else.
    """
    match = _FRAMES.match(text)
    if not match:
        raise ValueError(f"`{text}` is not a frame or a range of frames: write N or A..B (both ends included), e.g. 0..239")
    first = int(match.group(1))
    last = int(match.group(2)) if match.group(2) is not None else first
    if last < first:
        raise ValueError(f"the range `{text}` ends before it starts: write A..B with A <= B")
    return range(first, last + 1)


def format_frames(frames: range) -> str:
    """The ``A..B`` (or ``N``) form of a range of frames."""
    if len(frames) == 1:
        return str(frames.start)
    return f"{frames.start}..{frames[-1]}"


def has_placeholder(pattern: str) -> bool:
    """Whether the file name of ``pattern`` (not its folders) holds a run of ``#``."""
    return _HASHES.search(os.path.basename(pattern)) is not None


def fill(pattern: str, frame: int) -> str:
    """Replace every run of ``#`` in the file name of ``pattern`` with ``frame``, zero-padded
    to the run's length, as ``snell render --frames`` does; folders are left as they are.

    A frame number with more digits than the run is written whole: ``##`` and 123 give 123.
    """
    folder, name = os.path.split(pattern)
    name = _HASHES.sub(lambda m: str(frame).zfill(len(m.group(0))), name)
    return os.path.join(folder, name) if folder else name


def outputs(pattern: str, frames: Sequence[int]) -> Dict[int, str]:
    """The output path of each frame.

    Raises ValueError when more than one frame would go to the same file (no ``#`` in the
    pattern).
    """
    if len(frames) > 1 and not has_placeholder(pattern):
        raise ValueError(
            f"{len(frames)} frames would all be written to {pattern}: put a run of # in the output's "
            "file name for the frame number, e.g. out/frame_####.png"
        )
    return {frame: fill(pattern, frame) for frame in frames}
