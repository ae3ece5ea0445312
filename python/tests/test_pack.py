"""Packing a scene and its files: relative layout kept, round trip, limits, safe unpacking."""

import io
import os
import tarfile
import threading

import pytest

from snell_farm.errors import FarmError
from snell_farm.pack import pack_scene, unpack, unpack_cached


@pytest.fixture
def project(tmp_path):
    """project/scenes/s.toml reading ../assets/earth.jpg and maps/bump.png beside it."""
    (tmp_path / "project" / "scenes" / "maps").mkdir(parents=True)
    (tmp_path / "project" / "assets").mkdir()
    scene = tmp_path / "project" / "scenes" / "s.toml"
    scene.write_text('file = "../assets/earth.jpg"\n')
    (tmp_path / "project" / "assets" / "earth.jpg").write_bytes(b"\xff\xd8earth" * 100)
    (tmp_path / "project" / "scenes" / "maps" / "bump.png").write_bytes(b"\x89PNGbump")
    files = [str(tmp_path / "project" / "assets" / "earth.jpg"), str(tmp_path / "project" / "scenes" / "maps" / "bump.png")]
    return scene, files


def test_pack_keeps_the_relative_layout_and_round_trips(project, tmp_path):
    scene, files = project
    pack = pack_scene(str(scene), files)
    assert pack.root == os.path.realpath(tmp_path / "project")
    assert pack.scene == "scenes/s.toml"
    assert pack.members == ("assets/earth.jpg", "scenes/maps/bump.png", "scenes/s.toml")
    out = tmp_path / "out"
    out.mkdir()
    assert sorted(unpack(pack.data, str(out))) == list(pack.members)
    for name in pack.members:
        assert (out / name).read_bytes() == (tmp_path / "project" / name).read_bytes()
    # the scene's relative path still leads to its texture
    assert (out / "scenes" / ".." / "assets" / "earth.jpg").is_file()


def test_pack_is_the_same_bytes_for_the_same_files(project):
    scene, files = project
    first = pack_scene(str(scene), files)
    os.utime(scene, (0, 12345))
    again = pack_scene(str(scene), list(reversed(files)) + [str(scene)])
    assert first.data == again.data and first.digest == again.digest


def test_pack_through_a_linked_folder_and_a_linked_file(project, tmp_path):
    scene, files = project
    (tmp_path / "link").symlink_to(tmp_path / "project" / "scenes")
    (tmp_path / "project" / "assets" / "alias.jpg").symlink_to(tmp_path / "project" / "assets" / "earth.jpg")
    pack = pack_scene(str(tmp_path / "link" / "s.toml"), [str(tmp_path / "link" / ".." / "assets" / "alias.jpg")])
    assert pack.members == ("assets/alias.jpg", "scenes/s.toml")
    out = tmp_path / "out"
    out.mkdir()
    unpack(pack.data, str(out))
    assert not (out / "assets" / "alias.jpg").is_symlink()
    assert (out / "assets" / "alias.jpg").read_bytes() == (tmp_path / "project" / "assets" / "earth.jpg").read_bytes()


def test_pack_refuses_too_much(project):
    scene, files = project
    with pytest.raises(FarmError, match="more than the 512 bytes") as err:
        pack_scene(str(scene), files, limit=512)
    assert "earth.jpg" in str(err.value) and err.value.exit_code == 2


def test_pack_refuses_a_missing_file(project):
    scene, files = project
    with pytest.raises(FarmError, match="not a file"):
        pack_scene(str(scene), files + [str(scene.parent / "gone.png")])


def _tar(add):
    buffer = io.BytesIO()
    with tarfile.open(fileobj=buffer, mode="w") as tar:
        add(tar)
    return buffer.getvalue()


@pytest.mark.parametrize("name", ["../evil", "/etc/evil", "a/../../evil"])
def test_unpack_refuses_names_outside(tmp_path, name):
    def add(tar):
        info = tarfile.TarInfo(name)
        info.size = 1
        tar.addfile(info, io.BytesIO(b"x"))

    with pytest.raises(ValueError, match="unsafe"):
        unpack(_tar(add), str(tmp_path))
    assert not (tmp_path.parent / "evil").exists()


def test_unpack_refuses_links(tmp_path):
    def add(tar):
        info = tarfile.TarInfo("link")
        info.type = tarfile.SYMTYPE
        info.linkname = "/etc/passwd"
        tar.addfile(info)

    with pytest.raises(ValueError, match="only files"):
        unpack(_tar(add), str(tmp_path))


def test_unpack_cached_unpacks_once_and_checks_the_hash(project, tmp_path):
    scene, files = project
    pack = pack_scene(str(scene), files)
    loads = []

    def load():
        loads.append(1)
        return pack.data

    root = str(tmp_path / "cache")
    folder, _ = unpack_cached(pack.digest, load, root)
    again, seconds = unpack_cached(pack.digest, load, root)
    assert folder == again == os.path.join(root, pack.digest) and seconds == 0.0 and len(loads) == 1
    assert os.path.isfile(os.path.join(folder, pack.scene))
    with pytest.raises(ValueError, match="hash"):
        unpack_cached("0" * 64, load, root)
    assert sorted(os.listdir(root)) == [pack.digest]  # no scratch folder left behind


def test_unpack_cached_racing_processes_agree(project, tmp_path):
    """Several unpackers at once (threads standing for processes): one folder, whole."""
    import snell_farm.pack as pack_module

    scene, files = project
    pack = pack_scene(str(scene), files)
    root = str(tmp_path / "cache")
    results, barrier = [], threading.Barrier(4)

    def racer():
        barrier.wait()
        results.append(pack_module.unpack_cached(pack.digest, lambda: pack.data, root)[0])
        pack_module._UNPACKED.clear()  # as if each were its own process

    threads = [threading.Thread(target=racer) for _ in range(4)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert len(results) == 4 and set(results) == {os.path.join(root, pack.digest)}
    assert sorted(os.listdir(root)) == [pack.digest]
    assert (tmp_path / "cache" / pack.digest / "assets" / "earth.jpg").is_file()
