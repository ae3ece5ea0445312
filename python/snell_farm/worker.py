"""What a worker does for one task: unpack the scene (once), run snell on one tile, and
return the tile's EXR with its timings.

``render_tile`` is plain Python (it is tested without Ray); the driver wraps it with
``ray.remote`` and the job's ``num_cpus``, ``max_retries`` and ``retry_exceptions``.
"""

import os
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Dict, List, Optional

from .pack import unpack_cached

#: How much of snell's stderr a failure carries (the end of it, where the error is).
STDERR_LIMIT = 8000


class SnellFailed(Exception):
    """``snell render`` failed on a worker; the message holds its exit status and stderr."""


def _die_with_parent() -> None:  # pragma: no cover - runs in the child between fork and exec
    """Ask Linux to kill snell when the worker that started it dies (SIGKILL included)."""
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL)  # PR_SET_PDEATHSIG
    except Exception:
        pass


def _scratch_folder() -> str:
    """A new folder for one task's output, named by this process; folders left by processes
    that died (a killed worker) are removed first."""
    root = os.path.join(tempfile.gettempdir(), "snell-farm", "tiles")
    os.makedirs(root, exist_ok=True)
    for name in os.listdir(root):
        pid = name.split("-", 1)[0]
        if os.name == "posix" and pid.isdigit() and int(pid) != os.getpid():
            try:
                os.kill(int(pid), 0)
            except ProcessLookupError:
                shutil.rmtree(os.path.join(root, name), ignore_errors=True)
            except OSError:
                pass
    return tempfile.mkdtemp(prefix=f"{os.getpid()}-", dir=root)


@dataclass(frozen=True)
class TileJob:
    """What every task of a job shares: the snell binary, the packed scene and the flags.

    ``pack_box`` is a one-element list holding the pack's ObjectRef (inside a list so that
    Ray does not fetch it for every task: it is fetched only when a process has not
    unpacked it yet); ``digest`` names the pack and ``scene`` the scene file inside it;
    ``overrides`` are flags for every ``snell render``; ``threads`` its ``--threads``.
    """

    snell: str
    pack_box: List[Any]
    digest: str
    scene: str
    overrides: List[str] = field(default_factory=list)
    threads: int = 1


def render_tile(
    job: TileJob,
    frame: int,
    region: str,
    attempts: Any = None,
    key: str = "",
    load: Optional[Callable[[], bytes]] = None,
) -> Dict[str, Any]:
    """Render ``region`` (``X0,Y0,X1,Y1``) of frame ``frame`` of the job's packed scene.

    ``attempts`` is the job's attempt log (an actor) or None, and ``key`` the task's name in
    it; ``load`` replaces the fetch of the pack in tests. Returns ``{"exr": bytes, "snell_s",
    "unpack_s", "node", "pid"}``; raises SnellFailed with snell's stderr when snell fails.
    """
    if attempts is not None:
        import ray

        ray.get(attempts.started.remote(key))
    if load is None:

        def load() -> bytes:
            import ray

            return ray.get(job.pack_box[0])

    folder, unpack_s = unpack_cached(job.digest, load)
    scratch = _scratch_folder()
    output = os.path.join(scratch, "tile.exr")
    command = [job.snell, "render", os.path.join(folder, job.scene), "--frames", str(frame), "--region", region,
               "-o", output, "--quiet", "--threads", str(job.threads)] + list(job.overrides)
    try:
        start = time.perf_counter()
        try:
            process = subprocess.Popen(
                command,
                cwd=folder,
                stdin=subprocess.DEVNULL,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.PIPE,
                preexec_fn=_die_with_parent if sys.platform.startswith("linux") else None,
            )
        except OSError as err:
            raise SnellFailed(f"cannot run {job.snell} on this worker: {err.strerror}") from None
        try:
            _, err_bytes = process.communicate()
        except BaseException:
            # The task was cancelled (Ray raises KeyboardInterrupt in it): snell goes too.
            process.kill()
            process.wait()
            raise
        snell_s = time.perf_counter() - start
        stderr = err_bytes.decode("utf-8", "replace").strip()[-STDERR_LIMIT:]
        if process.returncode != 0:
            status = (f"was killed by signal {-process.returncode}" if process.returncode < 0
                      else f"exited with status {process.returncode}")
            raise SnellFailed(f"snell render {status} (frame {frame}, region {region})" + (f":\n{stderr}" if stderr else ""))
        try:
            with open(output, "rb") as handle:
                exr = handle.read()
        except OSError as err:
            raise SnellFailed(f"snell render wrote no region file (frame {frame}, region {region}): {err.strerror}") from None
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    return {"exr": exr, "snell_s": snell_s, "unpack_s": unpack_s, "node": socket.gethostname(), "pid": os.getpid()}


class AttemptLog:
    """An actor counting the attempts at each task, so the driver can report retries
    (Ray re-runs a task without telling the caller)."""

    def __init__(self) -> None:
        self.counts: Dict[str, int] = {}

    def started(self, key: str) -> None:
        self.counts[key] = self.counts.get(key, 0) + 1

    def retried(self) -> int:
        """Attempts beyond the first, over all tasks."""
        return sum(n - 1 for n in self.counts.values())
