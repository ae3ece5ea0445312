"""The cost report and the progress line."""

import io

from snell_farm.report import Costs, Progress
from snell_farm.units import format_bytes, format_seconds


def test_units():
    assert format_seconds(2.5) == "2.50s"
    assert format_seconds(83.4) == "1m23.4s"
    assert format_seconds(4000) == "1h06m40s"
    assert format_bytes(1536) == "1.5 KiB"
    assert format_bytes(12) == "12 bytes"


def test_costs_lines():
    costs = Costs(frames=4, skipped=2, tasks=16, workers=2, wall_s=10, render_wall_s=8, snell_s=12,
                  unpack_s=0.1, pack_bytes=2048, result_bytes=3 << 20, fetch_s=0.2, merge_s=0.5, retried=1)
    text = costs.lines()
    assert costs.idle_s == 4
    for part in ("4 frames rendered, 2 skipped", "16 tasks on 2 workers", "wall time      10.0s",
                 "12.0s in snell", "pack 2.0 KiB", "results 3.0 MiB", "merge          0.50s",
                 "idle workers   4.00s", "25%", "tasks retried  1"):
        assert part in text, part


def test_progress_plain_text_and_quiet():
    stream = io.StringIO()
    progress = Progress(frames=3, tasks=12, stream=stream, interval=1000)
    progress.update(1, 0)
    progress.update(2, 0)  # within the interval: not printed
    progress.update(12, 3, force=True)
    progress.finish()
    lines = stream.getvalue().splitlines()
    assert len(lines) == 2 and lines[0].startswith("frames 0/3, tasks 1/12, ETA ")
    assert lines[1].startswith("frames 3/3, tasks 12/12")
    assert "\r" not in stream.getvalue()
    quiet = io.StringIO()
    Progress(frames=1, tasks=1, quiet=True, stream=quiet).update(1, 1, force=True)
    assert quiet.getvalue() == ""
