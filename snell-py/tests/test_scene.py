"""Scenes from files, text and dicts; edited from Python and built again; their errors."""

import shutil

import numpy as np
import pytest

import snell

SMALL = """
[image]
width = 32
height = 24
samples = 1
[camera]
position = [0, 0, 4]
look_at = [0, 0, 0]
[[lights]]
type = "point"
position = [2, 4, 4]
[materials.red]
color = [0.8, 0.1, 0.1]
[[objects]]
type = "sphere"
center = [0, 0, 0]
radius = 1
material = "red"
"""


def test_text_a_dict_and_a_file_give_the_same_scene(tmp_path):
    path = tmp_path / "small.toml"
    path.write_text(SMALL)
    from_file = snell.render(snell.load(path))
    from_text = snell.render(snell.loads(SMALL))
    definition = snell.load(path).definition
    from_dict = snell.render(snell.load_dict(definition))
    assert from_file.shape == (24, 32, 3)
    assert np.array_equal(from_file, from_text) and np.array_equal(from_file, from_dict)
    assert from_file[12, 16, 0] > from_file[12, 16, 2], "the sphere is red in the middle"


def test_an_edit_is_rendered_and_can_be_undone():
    scene = snell.loads(SMALL)
    red = snell.render(scene)
    scene.materials["red"]["color"] = [0.1, 0.1, 0.8]
    blue = snell.render(scene)
    assert blue[12, 16, 2] > blue[12, 16, 0]
    scene.materials["red"]["color"] = [0.8, 0.1, 0.1]
    assert np.array_equal(snell.render(scene), red)
    # The camera moved back: the sphere looks smaller.
    scene.camera["position"] = [0, 0, 12]
    far = snell.render(scene)
    lit = lambda img: int((img.sum(axis=2) > 0.05).sum())
    assert lit(far) < lit(red) / 4, (lit(far), lit(red))
    # A sphere added to the right.
    scene.camera["position"] = [0, 0, 4]
    scene.add({"type": "sphere", "center": [1.6, 0, 0], "radius": 0.3, "material": "red"})
    more = snell.render(scene)
    assert lit(more) > lit(red)
    assert len(scene.objects) == 2


def test_a_copy_is_edited_on_its_own():
    scene = snell.loads(SMALL)
    other = scene.copy()
    other.materials["red"]["color"] = [0, 1, 0]
    assert scene.materials["red"]["color"] == [0.8, 0.1, 0.1]
    assert not np.array_equal(snell.render(scene), snell.render(other))


def test_a_rebuild_reads_no_texture_again(repo, tmp_path):
    # The seed scene with its Earth beside it. After the first build the Earth's file is
    # replaced by a grey picture: an edited scene built from what was read still shows the
    # Earth, where a new load reads the grey.
    (tmp_path / "scenes").mkdir()
    (tmp_path / "assets").mkdir()
    shutil.copy(repo / "scenes/seed.toml", tmp_path / "scenes/seed.toml")
    shutil.copy(repo / "assets/earth.jpg", tmp_path / "assets/earth.jpg")
    scene = snell.load(tmp_path / "scenes/seed.toml")
    first = snell.render(scene, width=48, height=48, spp=1)
    snell.write(np.full((8, 16, 3), 0.5), tmp_path / "grey.png")
    (tmp_path / "grey.png").replace(tmp_path / "assets/earth.jpg")  # read by its content
    scene.materials["red"]["color"] = [0, 0, 1]
    edited = snell.render(scene, width=48, height=48, spp=1)
    fresh = snell.load(tmp_path / "scenes/seed.toml")
    fresh.materials["red"]["color"] = [0, 0, 1]
    grey = snell.render(fresh, width=48, height=48, spp=1)
    assert not np.array_equal(first, edited), "the edit shows"
    assert not np.array_equal(edited, grey), "the rebuild kept the Earth it had read"


def test_problems_carry_the_command_lines_location_and_words(run_cli, tmp_path):
    bad = tmp_path / "bad.toml"
    bad.write_text('[camera]\nlook_at = [0, 0, -1]\n[materials.m]\ncolor = "blue"\n')
    with pytest.raises(snell.SceneError) as e:
        snell.load(bad)
    message = str(e.value)
    assert message.startswith(f"{bad}:4:9: materials.m.color: invalid type"), message
    cli = run_cli("render", bad, "-o", tmp_path / "x.png", check=False)
    assert cli.returncode == 2
    assert f"{bad}:4:9" in cli.stderr
    assert message.split(":4:9: ", 1)[1].split(" (")[0] in cli.stderr
    # An edit that breaks the scene names the edited text, whose lines it counts.
    scene = snell.loads(SMALL, name="small.toml")
    scene.materials["red"]["color"] = "blue"
    with pytest.raises(snell.SceneError, match=r"small.toml \(edited\):\d+:\d+: materials.red.color"):
        snell.render(scene)
    with pytest.raises(snell.SceneError, match="cannot read the scene file"):
        snell.load(tmp_path / "none.toml")
    with pytest.raises(ValueError, match="format must be"):
        snell.loads(SMALL, format="yaml")


def test_explain_is_the_command_lines_document(repo, run_cli):
    import json

    scene = snell.load(repo / "scenes/seed.toml")
    doc = snell.explain(scene, 512, 600)
    cli = json.loads(run_cli("explain", repo / "scenes/seed.toml", "--pixel", "512,600", "--json").stdout)
    # The same document, with each hit's place on the picture beside its point.
    def unplaced(node):
        if isinstance(node, dict):
            return {k: unplaced(v) for k, v in node.items() if k != "screen"}
        if isinstance(node, list):
            return [unplaced(v) for v in node]
        return node

    assert doc["tree"]["hit"]["screen"] == [512.5, 600.5]
    assert unplaced(doc) == cli
    with pytest.raises(ValueError, match="outside"):
        snell.explain(scene, 5000, 0)
    path = snell.explain(snell.load(repo / "scenes/cornell.toml"), 256, 256, sample=2)
    assert path["integrator"] == "path" and path["sample"] == 2
    with pytest.raises(ValueError, match="sample 64 does not exist"):
        snell.explain(snell.load(repo / "scenes/cornell.toml"), 256, 256, sample=64)
    # Under Whitted, a sample as the renderer takes it, as the command line gives it.
    seed16 = snell.load(repo / "scenes/seed.toml")
    seed16.image["samples"] = 16
    one = snell.explain(seed16, 512, 600, sample=5)
    cli = json.loads(
        run_cli("explain", repo / "scenes/seed.toml", "--pixel", "512,600", "--spp", "16", "--sample", "5", "--json").stdout
    )
    assert one["sample"] == 5 and unplaced(one) == cli
    # Under bdpt, the sample's subpaths and strategies, as the command line gives them.
    caustics = repo / "scenes/caustics.toml"
    bd = snell.explain(snell.load(caustics), 240, 300, sample=1)
    cli = json.loads(run_cli("explain", caustics, "--pixel", "240,300", "--sample", "1", "--json").stdout)
    assert bd["integrator"] == "bdpt" and bd["camera_path"][0]["what"] == "the eye"
    assert unplaced(bd) == cli


def test_numpy_values_are_taken_as_numbers_and_other_objects_refused():
    scene = snell.loads(SMALL)
    before = snell.render(scene)
    scene.camera["position"] = np.array([0.0, 0.0, 6.0])
    scene.materials["red"]["color"] = np.float32(0.5)
    after = snell.render(scene)
    assert not np.array_equal(before, after)
    scene.camera["position"] = object()
    with pytest.raises(TypeError, match="a scene holds numbers"):
        snell.render(scene)
    # Bad sizes are the interpreter's errors, never a crash.
    with pytest.raises(OverflowError):
        snell.render(snell.loads(SMALL), width=10**12)
    with pytest.raises(snell.SettingsError):
        snell.render(snell.loads(SMALL), width=0)


def test_a_frame_of_an_animation_is_the_command_lines_frame(repo, run_cli, tmp_path):
    scene = snell.load(repo / "scenes/orbit.toml", frame=5)
    assert (scene.frame, scene.frames) == (5, 48)
    img = snell.render(scene, width=48, height=32, spp=1)
    run_cli("render", repo / "scenes/orbit.toml", "--frames", "5..5", "-o", tmp_path / "f.exr",
            "--width", 48, "--height", 32, "--spp", 1, "--quiet")
    assert np.array_equal(img, snell.read(tmp_path / "f.exr"))
    later = scene.at_frame(24)
    assert later.frame == 24 and scene.frame == 5
    assert not np.array_equal(snell.render(later, width=48, height=32, spp=1), img)
    # An edit not yet built goes with the copy to its frame (the TOML file's scene, edited,
    # is built from its tables as JSON).
    scene.camera["fov"] = 20
    narrow = scene.at_frame(24)
    assert narrow.camera["fov"] == 20 and "(edited)" not in narrow.path
    assert not np.array_equal(snell.render(narrow, width=48, height=32, spp=1),
                              snell.render(later, width=48, height=32, spp=1))
    with pytest.raises(snell.SceneError, match="frame 60 was asked for"):
        snell.load(repo / "scenes/orbit.toml", frame=60)
    with pytest.raises(snell.SceneError, match="no \\[animation\\]"):
        snell.load(repo / "scenes/seed.toml", frame=3)
