"""The scene and every file it reads, packed into one tar in memory for Ray's object store.

Paths in the tar are relative to the deepest folder holding the scene and all its files,
so a scene that reads ``../assets/earth.jpg`` finds it again where the pack is unpacked.
A worker unpacks a pack once into a cache folder named by the pack's hash.
"""

import hashlib
import io
import os
import shutil
import tarfile
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path, PurePosixPath
from typing import Callable, Dict, List, Sequence, Set, Tuple

from .errors import FarmError
from .units import format_bytes

#: The largest pack a job sends (the scene and its files, in bytes): 1 GiB.
MAX_PACK_BYTES = 1 << 30


@dataclass(frozen=True)
class Pack:
    """A packed scene: the tar's bytes, their SHA-256, and where the scene is inside."""

    data: bytes = field(repr=False)
    digest: str
    scene: str
    """The scene's path inside the pack (POSIX, relative)."""
    root: str
    """The folder on the driver that the pack's paths are relative to."""
    members: Tuple[str, ...]


def _physical(path: str) -> str:
    """``path`` with its folders resolved (symbolic links, ``..``) but its last name kept.

    The kernel resolves a scene's ``../assets/x.jpg`` through the real folders; a file that
    is itself a link is packed under its own name with its target's content.
    """
    absolute = path if os.path.isabs(path) else os.path.join(os.getcwd(), path)
    folder, name = os.path.split(absolute)  # not abspath: it would drop `link/..` by the text
    return os.path.join(os.path.realpath(folder), name)



def pack_scene(scene: str, files: Sequence[str], limit: int = MAX_PACK_BYTES) -> Pack:
    """Pack ``scene`` and ``files`` (the files it reads) into a tar in memory.

    The tar is the same bytes for the same files (sorted, no times or owners), so its hash
    names its content. Raises FarmError when a file cannot be read or all of them together
    come to more than ``limit`` bytes.
    """
    scene_path = _physical(scene)
    paths: List[str] = []
    for path in [scene_path] + [_physical(f) for f in files]:
        if path not in paths:
            paths.append(path)
    try:
        root = os.path.commonpath([os.path.dirname(p) for p in paths])
    except ValueError:
        raise FarmError("the scene and its files have no folder in common (different drives?): they cannot be packed")

    sizes: Dict[str, int] = {}
    for path in paths:
        try:
            if not os.path.isfile(path):
                raise FarmError(f"{path}: the scene reads it, but it is not a file", 2)
            sizes[path] = os.path.getsize(path)
        except OSError as err:
            raise FarmError(f"{path}: cannot read it ({err.strerror})", 2)
    total = sum(sizes.values())
    if total > limit:
        largest = sorted(sizes, key=sizes.get, reverse=True)[:3]
        listed = ", ".join(f"{p} ({format_bytes(sizes[p])})" for p in largest)
        raise FarmError(
            f"the scene and its files come to {format_bytes(total)}, more than the {format_bytes(limit)} a job sends "
            f"through Ray's object store; the largest: {listed}",
            2,
        )

    names = {path: PurePosixPath(*Path(os.path.relpath(path, root)).parts).as_posix() for path in paths}
    buffer = io.BytesIO()
    with tarfile.open(fileobj=buffer, mode="w", format=tarfile.PAX_FORMAT) as tar:
        for path in sorted(paths, key=names.get):
            info = tarfile.TarInfo(names[path])
            info.mode = 0o644
            info.mtime = 0
            try:
                with open(path, "rb") as handle:
                    info.size = os.fstat(handle.fileno()).st_size
                    tar.addfile(info, handle)
            except OSError as err:  # tarfile's "unexpected end of data" is an OSError too
                raise FarmError(f"{path}: cannot read it ({err.strerror or err})", 2)
    data = buffer.getvalue()
    if len(data) > limit:
        raise FarmError(f"the packed scene comes to {format_bytes(len(data))}, more than the {format_bytes(limit)} a job sends", 2)
    return Pack(
        data=data,
        digest=hashlib.sha256(data).hexdigest(),
        scene=names[scene_path],
        root=root,
        members=tuple(sorted(names.values())),
    )


def _safe_target(dest: str, name: str) -> str:
    """Where member ``name`` goes under ``dest``; ValueError for an absolute name or ``..``."""
    parts = PurePosixPath(name).parts
    if not parts or PurePosixPath(name).is_absolute() or ".." in parts or "\\" in name:
        raise ValueError(f"unsafe path in a scene pack: {name!r}")
    return os.path.join(dest, *parts)


def unpack(data: bytes, dest: str) -> List[str]:
    """Unpack a pack's regular files into the folder ``dest``; returns their names.

    Anything but plain files and folders (links, devices), absolute names and ``..`` are
    refused with ValueError, whatever made the tar.
    """
    names: List[str] = []
    with tarfile.open(fileobj=io.BytesIO(data), mode="r:") as tar:
        for member in tar:
            target = _safe_target(dest, member.name)
            if member.isdir():
                os.makedirs(target, exist_ok=True)
                continue
            if not member.isfile():
                raise ValueError(f"a scene pack holds only files, not {member.name!r}")
            os.makedirs(os.path.dirname(target), exist_ok=True)
            source = tar.extractfile(member)
            assert source is not None
            with open(target, "wb") as out:
                shutil.copyfileobj(source, out)
            names.append(member.name)
    return names


def cache_root() -> str:
    """The folder, in this machine's temporary folder, that packs are unpacked into."""
    return os.path.join(tempfile.gettempdir(), "snell-farm", "packs")


_UNPACKED: Set[str] = set()


def unpack_cached(digest: str, load: Callable[[], bytes], root: str = "") -> Tuple[str, float]:
    """The folder holding pack ``digest``, unpacked once per process; and the seconds spent.

    ``load`` gives the pack's bytes when they are needed (a cache miss). The pack is
    unpacked into a fresh temporary folder and renamed to ``<root>/<digest>``, so a folder
    under that name is always whole; when two processes race, the first rename wins and
    the other's copy is removed. Raises ValueError when the bytes do not match the digest.
    """
    root = root or cache_root()
    final = os.path.join(root, digest)
    if final in _UNPACKED and os.path.isdir(final):
        return final, 0.0
    start = time.perf_counter()
    if not os.path.isdir(final):
        data = load()
        if hashlib.sha256(data).hexdigest() != digest:
            raise ValueError("a scene pack arrived with the wrong content (its hash differs)")
        os.makedirs(root, exist_ok=True)
        scratch = tempfile.mkdtemp(prefix=f".{digest[:16]}-", dir=root)
        try:
            unpack(data, scratch)
            try:
                os.rename(scratch, final)
            except OSError:
                if not os.path.isdir(final):
                    raise
        finally:
            if os.path.isdir(scratch):
                shutil.rmtree(scratch, ignore_errors=True)
    _UNPACKED.add(final)
    return final, time.perf_counter() - start
