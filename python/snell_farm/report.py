"""The progress line while a job runs and the account of what it cost at the end."""

import sys
import time
from dataclasses import dataclass
from typing import Optional, TextIO

from .units import format_bytes, format_seconds


@dataclass
class Costs:
    """What a job spent, summed over its tasks."""

    frames: int = 0
    """Frames rendered by this run."""
    skipped: int = 0
    """Frames whose output was there already."""
    tasks: int = 0
    workers: int = 0
    """Tasks the cluster runs at once (its CPUs / CPUs per task)."""
    wall_s: float = 0.0
    """The whole job, from the command to its end."""
    render_wall_s: float = 0.0
    """From the first task sent to the last frame written."""
    snell_s: float = 0.0
    unpack_s: float = 0.0
    pack_bytes: int = 0
    result_bytes: int = 0
    fetch_s: float = 0.0
    merge_s: float = 0.0
    retried: Optional[int] = 0
    """Attempts beyond the first; None when unknown."""

    @property
    def idle_s(self) -> float:
        """Worker time not spent in snell: workers x render wall time - task time."""
        return max(0.0, self.workers * self.render_wall_s - self.snell_s)

    def lines(self) -> str:
        """The report, a few lines of text."""
        out = [f"snell-farm: {self.frames} frame{'s' if self.frames != 1 else ''} rendered"
               + (f", {self.skipped} skipped (already there)" if self.skipped else "")
               + (f", {self.tasks} tasks on {self.workers} workers" if self.tasks else "")]
        out.append(f"  wall time      {format_seconds(self.wall_s)}")
        if self.tasks:
            out.append(f"  task time      {format_seconds(self.snell_s)} in snell "
                       f"(mean {self.snell_s / self.tasks:.2f} s a task), {format_seconds(self.unpack_s)} unpacking")
            out.append(f"  transfer       pack {format_bytes(self.pack_bytes)} (sent once), results "
                       f"{format_bytes(self.result_bytes)} fetched in {format_seconds(self.fetch_s)}")
            out.append(f"  merge          {format_seconds(self.merge_s)}")
            share = self.idle_s / (self.workers * self.render_wall_s) if self.workers and self.render_wall_s else 0.0
            out.append(f"  idle workers   {format_seconds(self.idle_s)} ({self.workers} workers x "
                       f"{format_seconds(self.render_wall_s)} - task time; {share:.0%})")
            out.append(f"  tasks retried  {self.retried if self.retried is not None else 'unknown'}")
        return "\n".join(out)


class Progress:
    """One line on stderr: frames done, tasks done, ETA from the mean task rate.

    On a terminal the line is redrawn in place; otherwise a plain line is printed at most
    every ``interval`` seconds (and when the job ends). Silent when ``quiet``.
    """

    def __init__(self, frames: int, tasks: int, quiet: bool = False, stream: Optional[TextIO] = None,
                 interval: float = 5.0) -> None:
        self.frames, self.tasks = frames, tasks
        self.frames_done = self.tasks_done = 0
        self.quiet, self.interval = quiet, interval
        self.stream = stream if stream is not None else sys.stderr
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()
        self.start = time.monotonic()
        self.last = 0.0
        self.drawn = False

    def text(self) -> str:
        elapsed = time.monotonic() - self.start
        line = f"frames {self.frames_done}/{self.frames}, tasks {self.tasks_done}/{self.tasks}"
        if 0 < self.tasks_done < self.tasks:
            rate = self.tasks_done / elapsed if elapsed > 0 else 0.0
            if rate > 0:
                line += f", ETA {format_seconds((self.tasks - self.tasks_done) / rate)}"
        elif self.tasks_done == self.tasks:
            line += f", {format_seconds(elapsed)}"
        return line

    def update(self, tasks_done: int, frames_done: int, force: bool = False) -> None:
        """Record the counts and show them if it is time to."""
        self.tasks_done, self.frames_done = tasks_done, frames_done
        if self.quiet:
            return
        now = time.monotonic()
        if self.tty:
            if force or now - self.last >= 0.1:
                self.stream.write("\r\x1b[K" + self.text())
                self.stream.flush()
                self.last, self.drawn = now, True
        elif force or now - self.last >= self.interval:
            self.stream.write(self.text() + "\n")
            self.stream.flush()
            self.last = now

    def finish(self) -> None:
        """End the line (on a terminal) so that what follows starts on its own."""
        if not self.quiet and self.tty and self.drawn:
            self.stream.write("\n")
            self.stream.flush()
            self.drawn = False
