"""A task's work without Ray: unpack, run snell on a tile, return its bytes or its error."""

import os
import subprocess
import sys

import pytest

from snell_farm.pack import pack_scene
from snell_farm.worker import SnellFailed, TileJob, render_tile

FAKE = """#!{python}
import os, sys
args = sys.argv[1:]
if os.environ.get("FAKE_FAIL"):
    sys.stderr.write("error: out of cheese\\n")
    sys.exit(1)
out = args[args.index("-o") + 1]
scene = args[1]
assert os.path.isfile(scene) and os.path.isfile(os.path.join(os.path.dirname(scene), "..", "assets", "t.png"))
with open(out, "w") as f:
    f.write(" ".join(args[2:]).replace(out, "OUT") + " cwd_has_scene=" + str(os.path.isfile(os.path.join(os.getcwd(), "scenes", "s.toml"))))
"""


@pytest.fixture
def setup(tmp_path, monkeypatch):
    monkeypatch.setenv("TMPDIR", str(tmp_path / "tmp"))
    (tmp_path / "tmp").mkdir()
    import tempfile

    monkeypatch.setattr(tempfile, "tempdir", None)
    (tmp_path / "p" / "scenes").mkdir(parents=True)
    (tmp_path / "p" / "assets").mkdir()
    (tmp_path / "p" / "scenes" / "s.toml").write_text("scene")
    (tmp_path / "p" / "assets" / "t.png").write_bytes(b"png")
    pack = pack_scene(str(tmp_path / "p" / "scenes" / "s.toml"), [str(tmp_path / "p" / "assets" / "t.png")])
    fake = tmp_path / "snell"
    fake.write_text(FAKE.format(python=sys.executable))
    fake.chmod(0o755)
    return pack, str(fake), tmp_path


def test_render_tile_runs_snell_in_the_unpacked_scene(setup):
    pack, fake, tmp_path = setup
    job = TileJob(fake, [None], pack.digest, pack.scene, ["--spp", "1"], 3)
    result = render_tile(job, 2, "0,0,24,16", load=lambda: pack.data)
    assert result["exr"].decode() == ("--frames 2 --region 0,0,24,16 -o OUT --quiet --threads 3 --spp 1 "
                                      "cwd_has_scene=True")
    assert result["snell_s"] > 0 and result["unpack_s"] > 0
    again = render_tile(TileJob(fake, [None], pack.digest, pack.scene), 3, "0,0,24,16", load=lambda: 1 / 0)
    assert again["unpack_s"] == 0.0  # unpacked once per process: the pack is not loaded again
    assert os.listdir(tmp_path / "tmp" / "snell-farm" / "tiles") == []


def test_render_tile_removes_what_dead_workers_left(setup):
    pack, fake, tmp_path = setup
    tiles = tmp_path / "tmp" / "snell-farm" / "tiles"
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True, text=True)
    (tiles / f"{dead.stdout.strip()}-abc").mkdir(parents=True)
    (tiles / f"{dead.stdout.strip()}-abc" / "tile.exr").write_bytes(b"half")
    (tiles / f"{os.getppid()}-live").mkdir()
    render_tile(TileJob(fake, [None], pack.digest, pack.scene), 0, "0,0,1,1", load=lambda: pack.data)
    assert os.listdir(tiles) == [f"{os.getppid()}-live"]


def test_render_tile_raises_with_snells_stderr(setup, monkeypatch):
    pack, fake, _ = setup
    monkeypatch.setenv("FAKE_FAIL", "1")
    with pytest.raises(SnellFailed, match=r"exited with status 1 \(frame 0, region 0,0,1,1\):\nerror: out of cheese"):
        render_tile(TileJob(fake, [None], pack.digest, pack.scene), 0, "0,0,1,1", load=lambda: pack.data)


def test_render_tile_without_snell(setup):
    pack, _, tmp_path = setup
    with pytest.raises(SnellFailed, match="cannot run"):
        render_tile(TileJob(str(tmp_path / "nothing"), [None], pack.digest, pack.scene), 0, "0,0,1,1",
                    load=lambda: pack.data)
