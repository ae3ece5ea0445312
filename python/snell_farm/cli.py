"""The ``snell-farm`` command line."""

import argparse
import os
import signal
import sys
from typing import Callable, List, Optional, TypeVar

from . import patterns, tasks
from .driver import JobSpec, run
from .errors import FarmError

T = TypeVar("T")


def _typed(parse: Callable[[str], T], what: str) -> Callable[[str], T]:
    """An argparse type from a parser that raises ValueError with a message."""

    def convert(text: str) -> T:
        try:
            return parse(text)
        except ValueError as err:
            raise argparse.ArgumentTypeError(str(err) or f"`{text}` is not {what}")

    convert.__name__ = what
    return convert


def _positive(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise ValueError(f"`{text}` is not a whole number")
    if value < 1:
        raise ValueError(f"`{text}`: must be 1 or more")
    return value


def _count(text: str) -> int:
    try:
        value = int(text)
    except ValueError:
        raise ValueError(f"`{text}` is not a whole number")
    if value < 0:
        raise ValueError(f"`{text}`: must be 0 or more")
    return value


def parser() -> argparse.ArgumentParser:
    """The argument parser of ``snell-farm``."""
    top = argparse.ArgumentParser(
        prog="snell-farm",
        description="Render snell scenes on a Ray cluster, frame by frame and tile by tile; every frame "
                    "has the same bytes as `snell render` of it on one machine.",
    )
    commands = top.add_subparsers(dest="command", metavar="COMMAND", required=True)
    render = commands.add_parser(
        "render",
        help="render frames of a scene",
        description="Render frames of a scene on a Ray cluster. Frames whose output exists already are "
                    "skipped, so a stopped job resumes when run again.",
        epilog="Exit status: 0 done, 1 a task or merge failed, 2 bad command line or scene, 130 interrupted.",
    )
    render.add_argument("scene", metavar="SCENE", help="the scene file (.toml or .json)")
    render.add_argument("--frames", metavar="A..B", type=_typed(patterns.parse_frames, "frames"),
                        help="frames A to B (both included), or one frame N [default: every frame of the scene]")
    render.add_argument("-o", "--output", metavar="OUT", required=True,
                        help="output image, .png or .exr; a run of # takes the zero-padded frame number "
                             "(out/frame_####.png), needed with more than one frame")
    tiling = render.add_mutually_exclusive_group()
    tiling.add_argument("--tiles", metavar="CxR", type=_typed(tasks.parse_grid, "tiles"),
                        help="split each frame into C columns x R rows of tiles [default: 1x1]")
    tiling.add_argument("--tile-size", metavar="PIXELS", type=_typed(_positive, "tile size"),
                        help="split each frame into square tiles of this many pixels")
    where = render.add_mutually_exclusive_group()
    where.add_argument("--address", metavar="auto|HOST:PORT",
                       help="join this Ray cluster [default: start a local Ray instance on this machine]")
    where.add_argument("--workers", metavar="N", type=_typed(_positive, "workers"),
                       help="CPUs of the local Ray instance [default: all]")
    render.add_argument("--connect-timeout", metavar="SECONDS", type=_typed(_positive, "connect timeout"),
                        default=30, help="give up on a cluster that has not answered in this long [default: 30]")
    render.add_argument("--snell", metavar="PATH",
                        help="the snell binary, at the same path on every worker [default: snell on PATH]")
    render.add_argument("--width", metavar="W", type=_typed(_positive, "width"), help="image width (overrides the scene)")
    render.add_argument("--height", metavar="H", type=_typed(_positive, "height"), help="image height (overrides the scene)")
    render.add_argument("--spp", metavar="N", type=_typed(_positive, "samples"), help="samples per pixel (overrides the scene)")
    render.add_argument("--cpus-per-task", metavar="N", type=_typed(_positive, "CPUs"), default=1,
                        help="CPUs (snell threads) of each task [default: 1]")
    render.add_argument("--retries", metavar="N", type=_typed(_count, "retries"), default=3,
                        help="times a failed task is tried again [default: 3]")
    render.add_argument("-q", "--quiet", action="store_true", help="print nothing but errors")
    top.set_defaults(render_parser=render)
    return top


def _terminate_as_interrupt() -> None:
    """Let SIGTERM stop a job as Ctrl-C does: tasks cancelled, Ray shut down, whole frames kept."""

    def interrupt(signum: int, frame: object) -> None:
        raise KeyboardInterrupt

    try:
        signal.signal(signal.SIGTERM, interrupt)
    except ValueError:  # not the main thread
        pass


def main(argv: Optional[List[str]] = None) -> int:
    """Run ``snell-farm``; returns the exit status."""
    top = parser()
    args = top.parse_args(argv)
    ext = os.path.splitext(args.output)[1].lower()
    if ext not in (".png", ".exr"):
        args.render_parser.error(f"-o {args.output}: the output must end in .png or .exr")
    spec = JobSpec(
        scene=args.scene, output=args.output, frames=args.frames, grid=args.tiles, tile_size=args.tile_size,
        address=args.address, workers=args.workers, connect_timeout=args.connect_timeout, snell=args.snell, width=args.width, height=args.height,
        spp=args.spp, cpus_per_task=args.cpus_per_task, retries=args.retries, quiet=args.quiet,
    )
    _terminate_as_interrupt()
    try:
        costs = run(spec)
    except FarmError as err:
        print(f"snell-farm: error: {err}", file=sys.stderr, flush=True)
        return err.exit_code
    except KeyboardInterrupt:
        print("snell-farm: interrupted; the frames written are whole: run the same command again to go on",
              file=sys.stderr, flush=True)
        return 130
    if not args.quiet:
        print(costs.lines(), flush=True)
    return 0
