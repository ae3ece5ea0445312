"""The farm end to end, on a local Ray cluster of 2 CPUs with the real snell binary: its
frames must be the bytes of `snell render --frames` on one machine."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

from conftest import ANIM, DATA, PYTHON_DIR
from snell_farm.cli import main

pytestmark = pytest.mark.usefixtures("ray_cluster")


def farm(snell_bin, *args):
    return main(["render", *map(str, args), "--snell", snell_bin])


def same(a: Path, b: Path) -> bool:
    return a.read_bytes() == b.read_bytes()


def test_frames_by_tiles_equal_one_render(snell_bin, reference, tmp_path, capsys):
    assert farm(snell_bin, ANIM, "--frames", "0..2", "--tiles", "2x2", "-o", tmp_path / "out" / "f_####.png") == 0
    for frame in range(3):
        assert same(tmp_path / "out" / f"f_{frame:04d}.png", reference / f"f_{frame:04d}.png"), frame
    assert sorted(os.listdir(tmp_path / "out")) == ["f_0000.png", "f_0001.png", "f_0002.png"]
    out, err = capsys.readouterr()
    assert "3 frames rendered" in out and "12 tasks on 2 workers" in out and "tasks retried  0" in out
    assert "frames 3/3, tasks 12/12" in err


def test_tile_size_and_exr_equal_one_render(snell_bin, tmp_path, capsys):
    whole = tmp_path / "whole.exr"
    subprocess.run([snell_bin, "render", str(ANIM), "--frames", "3", "-o", str(whole), "--quiet"], check=True)
    assert farm(snell_bin, ANIM, "--frames", "3", "--tile-size", "20", "-o", tmp_path / "farm.exr", "--quiet") == 0
    assert same(tmp_path / "farm.exr", whole)
    assert capsys.readouterr() == ("", "")  # --quiet: nothing but errors
    assert sorted(os.listdir(tmp_path)) == ["farm.exr", "whole.exr"]  # no staging file left


def test_size_and_samples_overrides(snell_bin, tmp_path):
    size = ["--width", "40", "--height", "20", "--spp", "1"]
    whole = tmp_path / "whole.png"
    subprocess.run([snell_bin, "render", str(ANIM), "--frames", "1", "-o", str(whole), "--quiet", *size], check=True)
    assert farm(snell_bin, ANIM, "--frames", "1", "--tiles", "3x3", "-o", tmp_path / "farm.png", "--quiet", *size) == 0
    assert same(tmp_path / "farm.png", whole)


#: Stands in for snell: the first tile (`--region`) it is asked for kills the worker that
#: started it (SIGKILL, as the kernel's out-of-memory killer would) and makes a note;
#: every other call is snell's.
KILLER = """#!/bin/sh
case " $* " in
  *" --region "*)
    if mkdir "{marker}" 2>/dev/null; then
      echo "killed worker $PPID" > "{marker}/note"
      kill -9 $PPID
      sleep 5
    fi;;
esac
exec "{snell}" "$@"
"""


def test_a_killed_worker_loses_no_frame(snell_bin, reference, tmp_path, capsys):
    marker = tmp_path / "killed"
    killer = tmp_path / "snell-killer"
    killer.write_text(KILLER.format(marker=marker, snell=snell_bin))
    killer.chmod(0o755)
    out = tmp_path / "out" / "f_####.png"
    assert farm(str(killer), ANIM, "--frames", "0..1", "--tiles", "2x2", "-o", out) == 0
    assert (marker / "note").read_text().startswith("killed worker "), "no worker was killed"
    for frame in range(2):
        assert same(tmp_path / "out" / f"f_{frame:04d}.png", reference / f"f_{frame:04d}.png"), frame
    assert "tasks retried  1" in capsys.readouterr().out


def test_a_stopped_job_resumes(snell_bin, reference, tmp_path, capsys):
    out = tmp_path / "out"
    assert farm(snell_bin, ANIM, "--frames", "0..1", "--tiles", "1x2", "-o", out / "f_####.png") == 0
    before = {f: os.stat(out / f"f_{f:04d}.png") for f in (0, 1)}
    capsys.readouterr()
    assert farm(snell_bin, ANIM, "--frames", "0..3", "--tiles", "1x2", "-o", out / "f_####.png") == 0
    report = capsys.readouterr()
    assert "2 of 4 frames are there already, skipped" in report.err
    assert "2 frames rendered, 2 skipped" in report.out and "4 tasks" in report.out
    for f in (0, 1):
        after = os.stat(out / f"f_{f:04d}.png")
        assert (after.st_ino, after.st_mtime_ns) == (before[f].st_ino, before[f].st_mtime_ns), f
    for frame in range(4):
        assert same(out / f"f_{frame:04d}.png", reference / f"f_{frame:04d}.png"), frame
    # everything there: nothing to do, and Ray is not even needed
    assert farm(snell_bin, ANIM, "-o", out / "f_####.png", "--quiet") == 0
    assert capsys.readouterr() == ("", "")


def test_a_broken_scene_is_a_clear_error(snell_bin, tmp_path):
    """Run as a command (its own process): exit status 2, snell's message, no traceback."""
    broken = tmp_path / "broken.toml"
    broken.write_text('[camera]\nposition = [0, 0, 0]\nlook_at = [0, 0, -1]\n\n[[objects]]\ntype = "spere"\n')
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [str(PYTHON_DIR), os.environ.get("PYTHONPATH")])))
    result = subprocess.run([sys.executable, "-m", "snell_farm", "render", str(broken), "-o", str(tmp_path / "x.png"),
                             "--snell", snell_bin], capture_output=True, text=True, env=env, timeout=120)
    assert result.returncode == 2
    assert "snell-farm: error: snell check" in result.stderr and "spere" in result.stderr
    assert "Traceback" not in result.stderr + result.stdout
    assert not (tmp_path / "x.png").exists()


def test_a_failing_snell_stops_the_job(snell_bin, tmp_path, capsys):
    """snell fails in every task: the job stops after the retries with snell's stderr,
    exit status 1, no traceback, and no frame written."""
    failing = tmp_path / "snell"
    failing.write_text(f'#!/bin/sh\nif [ "$1" = render ]; then echo "error: out of cheese" >&2; exit 1; fi\n'
                       f'exec "{snell_bin}" "$@"\n')
    failing.chmod(0o755)
    code = main(["render", str(ANIM), "--frames", "0..1", "--tiles", "2x1", "-o", str(tmp_path / "out" / "f_##.png"),
                 "--snell", str(failing), "--retries", "1"])
    err = capsys.readouterr().err
    assert code == 1
    assert "failed after 2 attempts" in err and "exited with status 1" in err and "out of cheese" in err
    assert "Traceback" not in err
    assert not (tmp_path / "out").exists() or os.listdir(tmp_path / "out") == []


@pytest.mark.parametrize("args, message", [
    (["--frames", "2..9"], "has frames 0..3"),
    (["--frames", "0..1", "-o", "one.png"], "put a run of #"),
    (["--tiles", "49x1"], "does not fit"),
])
def test_bad_jobs_are_refused(snell_bin, tmp_path, capsys, args, message):
    if "-o" not in args:
        args = args + ["-o", "f_####.png"]
    args = [str(tmp_path / a) if a.endswith(".png") else a for a in args]
    assert main(["render", str(ANIM), "--snell", snell_bin, *args]) == 2
    assert message in capsys.readouterr().err
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("integrator, image, message", [
    ("light", "", "light tracing lands each pixel's light anywhere"),
    ("bdpt", "", "bdpt lands each pixel's light paths anywhere"),
    ("path", "noise = 0.05\n", "adaptive sampling decides a pixel's samples"),
])
def test_scenes_that_cannot_be_split_into_regions_are_refused(snell_bin, tmp_path, capsys, integrator, image,
                                                             message):
    """Every task renders a region: a scene whose pixels depend on other pixels' samples is
    refused before any task, with exit status 2, rather than failing on every worker."""
    scene = tmp_path / "s.toml"
    scene.write_text(f"[image]\nwidth = 16\nheight = 16\n{image}\n[integrator]\ntype = \"{integrator}\"\n\n"
                     "[camera]\nposition = [0, 0, 3]\nlook_at = [0, 0, 0]\n\n"
                     "[[lights]]\ntype = \"point\"\nposition = [0, 2, 2]\nintensity = 10\n\n"
                     "[materials.m]\ncolor = 0.5\n\n"
                     "[[objects]]\ntype = \"sphere\"\ncenter = [0, 0, 0]\nradius = 1\nmaterial = \"m\"\n")
    assert main(["render", str(scene), "-o", str(tmp_path / "x.png"), "--snell", snell_bin]) == 2
    err = capsys.readouterr().err
    assert message in err and "render it with `snell render` instead" in err, err
    assert sorted(os.listdir(tmp_path)) == ["s.toml"]


def test_a_missing_scene(snell_bin, tmp_path, capsys):
    assert main(["render", str(DATA / "no-such.toml"), "-o", str(tmp_path / "x.png"), "--snell", snell_bin]) == 2
    assert "no such scene file" in capsys.readouterr().err
