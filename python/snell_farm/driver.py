"""The job: check the scene, skip frames already written, send tasks to Ray, merge each
frame as soon as its tiles are in, and account for what it cost."""

import os
import shutil
import sys
import tempfile
import time
from dataclasses import dataclass
from typing import Any, Dict, List, Optional, TextIO, Tuple

from . import patterns, snell, tasks
from .cluster import connected, task_slots
from .errors import FarmError
from .pack import pack_scene
from .report import Costs, Progress
from .worker import AttemptLog, TileJob, render_tile



@dataclass
class JobSpec:
    """A render job, as the command line gives it."""

    scene: str
    output: str
    frames: Optional[range] = None
    """None: every frame of the scene."""
    grid: Optional[Tuple[int, int]] = None
    """Columns x rows of tiles; None with no tile_size: one tile."""
    tile_size: Optional[int] = None
    address: Optional[str] = None
    workers: Optional[int] = None
    connect_timeout: float = 30.0
    """Seconds to wait for Ray to start or answer."""
    snell: Optional[str] = None
    width: Optional[int] = None
    height: Optional[int] = None
    spp: Optional[int] = None
    cpus_per_task: int = 1
    retries: int = 3
    quiet: bool = False


def _say(quiet: bool, text: str, stream: TextIO) -> None:
    if not quiet:
        print(text, file=stream, flush=True)


def write_frame(snell_bin: str, parts: Dict[int, bytes], output: str) -> None:
    """Merge a frame's tiles into ``output``, which appears whole or not at all.

    The tiles go to a temporary folder; ``snell merge`` writes a hidden file beside the
    output, which is renamed onto it.
    """
    folder = os.path.dirname(os.path.abspath(output))
    os.makedirs(folder, exist_ok=True)
    base, ext = os.path.splitext(os.path.basename(output))
    staging = os.path.join(folder, f".{base}.snell-farm-{os.getpid()}{ext}")
    scratch = tempfile.mkdtemp(prefix="snell-farm-merge-")
    try:
        names = []
        for tile, data in sorted(parts.items()):
            name = os.path.join(scratch, f"tile_{tile:05d}.exr")
            with open(name, "wb") as handle:
                handle.write(data)
            names.append(name)
        snell.merge(snell_bin, names, staging)
        os.replace(staging, output)
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
        if os.path.exists(staging):
            os.remove(staging)


def _failure(err: BaseException, task: tasks.Task, attempts: int) -> FarmError:
    """The message for a task that failed for good."""
    import ray.exceptions

    where = f"frame {task.frame}, tile {task.tile} ({task.region})"
    if isinstance(err, ray.exceptions.RayTaskError):
        cause = getattr(err, "cause", None) or err
        return FarmError(f"{where} failed after {attempts} attempts: {cause}")
    if isinstance(err, ray.exceptions.WorkerCrashedError):
        return FarmError(f"{where}: its worker died {attempts} times (killed, out of memory?); stopping")
    return FarmError(f"{where} failed after {attempts} attempts: {err}")


def plan(spec: JobSpec, snell_bin: str) -> Tuple[snell.SceneInfo, Dict[int, str], List[tasks.Region]]:
    """Check the scene and arguments: the scene's facts, every frame's output, the tiles."""
    if not os.path.isfile(spec.scene):
        raise FarmError(f"{spec.scene}: no such scene file", 2)
    info = snell.check(snell_bin, spec.scene, spec.width, spec.height)
    # Every task renders a region, which these scenes cannot take yet: refused before any
    # worker tries (and fails) three times.
    unsplittable = {
        "light": "light tracing lands each pixel's light anywhere on the film",
        "bdpt": "bdpt lands each pixel's light paths anywhere on the film",
    }.get(info.integrator)
    if unsplittable is None and info.noise is not None:
        unsplittable = "adaptive sampling decides a pixel's samples from its neighbours'"
    if unsplittable is not None:
        raise FarmError(f"{spec.scene}: snell-farm renders a scene in regions, and {unsplittable}; "
                        "render it with `snell render` instead", 2)
    frames = spec.frames if spec.frames is not None else range(info.frames)
    if frames[-1] >= info.frames:
        have = "has only frame 0" if info.frames == 1 else f"has frames 0..{info.frames - 1}"
        raise FarmError(f"--frames {patterns.format_frames(frames)}: {spec.scene} {have}", 2)
    try:
        outputs = patterns.outputs(spec.output, list(frames))
        if spec.tile_size is not None:
            regions = tasks.regions_of_size(info.width, info.height, spec.tile_size)
        else:
            columns, rows = spec.grid or (1, 1)
            regions = tasks.grid(info.width, info.height, columns, rows)
    except ValueError as err:
        raise FarmError(str(err), 2)
    return info, outputs, regions


def run(spec: JobSpec, stream: Optional[TextIO] = None) -> Costs:
    """Run a job to its end; returns its costs. Raises FarmError when it cannot finish.

    Messages and the progress line go to ``stream`` (stderr by default).
    """
    stream = stream if stream is not None else sys.stderr
    started = time.perf_counter()
    snell_bin = snell.find_snell(spec.snell)
    info, outputs, regions = plan(spec, snell_bin)
    for warning in info.warnings:
        _say(spec.quiet, f"snell-farm: warning: {warning}", stream)
    costs = Costs()
    todo = [frame for frame, path in outputs.items() if not os.path.exists(path)]
    costs.skipped = len(outputs) - len(todo)
    if costs.skipped:
        _say(spec.quiet, f"snell-farm: {costs.skipped} of {len(outputs)} frames are there already, skipped", stream)
    if not todo:
        costs.wall_s = time.perf_counter() - started
        return costs

    job = tasks.split(todo, regions)
    pack = pack_scene(spec.scene, info.files)
    costs.pack_bytes = len(pack.data)
    overrides: List[str] = []
    for flag, value in (("--width", spec.width), ("--height", spec.height), ("--spp", spec.spp)):
        if value is not None:
            overrides += [flag, str(value)]

    with connected(spec.address, spec.workers, spec.connect_timeout):
        import ray

        costs.workers = task_slots(spec.cpus_per_task)
        remote = ray.remote(render_tile).options(
            num_cpus=spec.cpus_per_task, max_retries=spec.retries, retry_exceptions=True)
        try:
            log: Any = ray.remote(num_cpus=0)(AttemptLog).remote()
        except Exception:
            log = None
        tile_job = TileJob(snell_bin, [ray.put(pack.data)], pack.digest, pack.scene, overrides,
                           spec.cpus_per_task)
        window = max(2 * costs.workers, len(regions) + costs.workers)
        progress = Progress(len(todo), len(job), spec.quiet, stream)
        render_start = time.perf_counter()
        pending: Dict[Any, tasks.Task] = {}
        parts: Dict[int, Dict[int, bytes]] = {}
        queue = iter(job)
        done = frames_done = 0
        more = True
        try:
            while more or pending:
                while more and len(pending) < window:
                    task = next(queue, None)
                    if task is None:
                        more = False
                        break
                    ref = remote.remote(tile_job, task.frame, task.region.arg(), log, task.key())
                    pending[ref] = task
                ready, _ = ray.wait(list(pending), num_returns=1, timeout=1.0)
                if ready:
                    ready, _ = ray.wait(list(pending), num_returns=len(pending), timeout=0)
                for ref in ready:
                    task = pending.pop(ref)
                    fetch_start = time.perf_counter()
                    try:
                        result = ray.get(ref)
                    except ray.exceptions.RayError as err:
                        raise _failure(err, task, spec.retries + 1) from None
                    costs.fetch_s += time.perf_counter() - fetch_start
                    costs.result_bytes += len(result["exr"])
                    costs.snell_s += result["snell_s"]
                    costs.unpack_s += result["unpack_s"]
                    done += 1
                    tiles = parts.setdefault(task.frame, {})
                    tiles[task.tile] = result["exr"]
                    if len(tiles) == len(regions):
                        merge_start = time.perf_counter()
                        write_frame(snell_bin, parts.pop(task.frame), outputs[task.frame])
                        costs.merge_s += time.perf_counter() - merge_start
                        frames_done += 1
                progress.update(done, frames_done, force=not more and not pending)
        except BaseException:
            # A local instance's processes are killed with it (and each snell with its
            # worker), so its tasks are left alone: any cancel races with the reply of a task
            # that has just finished, and Ray's core worker then fails a check ("Tried to
            # complete task that was not pending") and takes the whole process down. On a
            # cluster the tasks must be stopped: cancelled in the task (it kills its snell),
            # not by killing its worker, which makes that race likelier.
            if spec.address:
                for ref in pending:
                    try:
                        ray.cancel(ref)
                    except Exception:
                        pass
            raise
        finally:
            progress.finish()
        costs.render_wall_s = time.perf_counter() - render_start
        costs.tasks, costs.frames = len(job), frames_done
        try:
            costs.retried = ray.get(log.retried.remote(), timeout=30) if log is not None else None
        except Exception:
            costs.retried = None
    costs.wall_s = time.perf_counter() - started
    return costs
