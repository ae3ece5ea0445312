"""Rendering from Python gives the command line's pixels, its errors and its files."""

import os
import threading

import numpy as np
import pytest

import snell


@pytest.mark.parametrize(
    "scene, args",
    [
        ("scenes/seed.toml", dict(width=96, height=64, spp=4)),
        ("scenes/cornell.toml", dict(width=48, height=48, spp=8, seed=3)),
        ("scenes/seed.toml", dict(width=40, height=40, spp=3, integrator="path")),
    ],
)
def test_the_same_pixels_as_the_command_line_bit_for_bit(repo, run_cli, tmp_path, scene, args):
    img = snell.render(repo / scene, **args)
    flags = []
    for key, value in args.items():
        flags += [f"--{key}", value]
    exr = tmp_path / "cli.exr"
    run_cli("render", repo / scene, "-o", exr, "--quiet", *flags)
    cli = snell.read(exr)
    assert img.shape == (args["height"], args["width"], 3) and img.dtype == np.float32
    assert np.array_equal(img, cli), f"largest difference {np.abs(img - cli).max()}"
    assert img.max() > 0, "something was lit"
    # The PNG a notebook shows is the command line's PNG, byte for byte.
    png = tmp_path / "cli.png"
    run_cli("render", repo / scene, "-o", png, "--quiet", *flags)
    assert img._repr_png_() == png.read_bytes()


def test_settings_are_the_scenes_unless_given(repo):
    scene = snell.load(repo / "scenes/seed.toml")
    s = scene.settings
    assert (s["width"], s["height"], s["spp"], s["integrator"]) == (1024, 1024, 16, "whitted")
    img = snell.render(scene, width=32, height=16, spp=1)
    assert img.shape == (16, 32, 3) and img.spp == 1 and img.complete


def test_a_bad_setting_is_a_settings_error_with_the_command_lines_words(repo):
    with pytest.raises(snell.SettingsError, match="square number"):
        snell.render(repo / "scenes/seed.toml", spp=10, width=8, height=8)
    with pytest.raises(ValueError, match="integrator must be"):
        snell.render(repo / "scenes/seed.toml", integrator="photon", width=8, height=8)
    with pytest.raises(ValueError, match="positive number of seconds"):
        snell.render(repo / "scenes/seed.toml", time=-1.0, width=8, height=8)


def test_debug_views_come_back_as_arrays(repo):
    out = snell.render(repo / "scenes/seed.toml", width=24, height=16, spp=1,
                       aovs=["normal", "depth", "albedo"])
    assert sorted(out) == ["albedo", "depth", "image", "normal"]
    assert out["normal"].shape == (16, 24, 3) and out["depth"].shape == (16, 24, 1)
    # The floor's normal points up where the bottom row sees it.
    assert np.allclose(out["normal"][15, 12], [0, 1, 0], atol=1e-4)
    with pytest.raises(ValueError, match="no debug view"):
        snell.render(repo / "scenes/seed.toml", width=8, height=8, aovs=["nromal"])
    with pytest.raises(ValueError, match="path tracer's"):
        snell.render(repo / "scenes/seed.toml", width=8, height=8, aovs=["variance"])
    v = snell.render(repo / "scenes/seed.toml", width=8, height=8, spp=4, integrator="path",
                     aovs=["variance"])
    assert v["variance"].shape == (8, 8, 1) and (v["variance"] >= 0).all()


def test_adaptive_sampling_gives_the_command_lines_pixels_and_maps_its_samples(repo, run_cli, tmp_path):
    args = dict(width=32, height=32, spp=256, seed=2)
    out = snell.render(repo / "scenes/cornell.toml", noise=0.1, aovs=["spp"], **args)
    spp = out["spp"][..., 0]
    assert spp.shape == (32, 32) and spp.min() == 16 and spp.max() == 256
    exr = tmp_path / "cli.exr"
    run_cli("render", repo / "scenes/cornell.toml", "-o", exr, "--quiet", "--noise", "0.1",
            "--width", 32, "--height", 32, "--spp", 256, "--seed", 2)
    assert np.array_equal(out["image"], snell.read(exr))
    with pytest.raises(snell.SettingsError, match="noise threshold"):
        snell.render(repo / "scenes/cornell.toml", noise=0.0, width=8, height=8)
    with pytest.raises(snell.SettingsError, match="path tracer's"):
        snell.render(repo / "scenes/seed.toml", noise=0.05, width=8, height=8)


# A wheel built with the `denoise` feature is tested with SNELL_DENOISE=1 (docs/denoise.md;
# CI tests the plain one): each build is checked to be the one meant, so that neither test
# below passes by being skipped in the build that should run it.
WANT_DENOISER = os.environ.get("SNELL_DENOISE") == "1"


def test_the_module_says_whether_it_denoises():
    assert snell.CAN_DENOISE is WANT_DENOISER


@pytest.mark.skipif(WANT_DENOISER, reason="the wheel built with the denoiser")
def test_denoise_in_a_build_without_the_feature_says_how_to_get_it(repo):
    # Asked for a denoiser, a build without one says how to build it, before rendering.
    with pytest.raises(snell.SettingsError, match="pip install pyoidn"):
        snell.render(repo / "scenes/cornell.toml", denoise=True, width=8, height=8)


@pytest.mark.skipif(not WANT_DENOISER, reason="the wheel built without the denoiser")
def test_the_denoised_cornell_box_is_closer_to_its_reference(repo):
    # As the command line's test (tests/integration/denoise.rs): 32 x 32, 16 samples a
    # pixel, against the 65536-sample reference, in linear and in display values.
    out = snell.render(repo / "scenes/cornell.toml", denoise=True, width=32, height=32, spp=16)
    raw, denoised = out["image"], out["denoised"]
    ref = snell.read(repo / "tests/data/cornell-32-ref.exr")
    assert raw.shape == denoised.shape == ref.shape == (32, 32, 3)
    for cut in (np.inf, 1.0):
        rmse = lambda img: float(np.sqrt(np.mean((np.minimum(img, cut) - np.minimum(ref, cut)) ** 2)))  # noqa: E731
        assert rmse(denoised) < 0.8 * rmse(raw), (cut, rmse(denoised), rmse(raw))


def test_progress_is_reported_to_the_end_and_its_errors_stop_the_render(repo):
    calls = []
    snell.render(repo / "scenes/seed.toml", width=32, height=32, spp=4,
                 progress=lambda done, total: calls.append((done, total)))
    assert calls and calls[-1] == (32 * 32 * 4, 32 * 32 * 4)
    assert all(d <= t for d, t in calls)

    def fails(done, total):
        raise RuntimeError("stop here")

    # Long enough for the first report to come (every tenth of a second).
    with pytest.raises(RuntimeError, match="stop here"):
        snell.render(repo / "scenes/cornell.toml", width=256, height=256, spp=4096,
                     progress=fails)


def test_two_threads_render_at_once_and_the_interpreter_runs_meanwhile(repo):
    scene = snell.load(repo / "scenes/seed.toml")
    alone = snell.render(scene, width=64, height=64, spp=4)
    results = [None, None]

    def worker(i):
        results[i] = snell.render(scene, width=64, height=64, spp=4, threads=1)

    threads = [threading.Thread(target=worker, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert all(np.array_equal(r, alone) for r in results)
    big = threading.Thread(target=lambda: snell.render(scene, width=256, height=256, spp=16))
    count = 0
    big.start()
    while big.is_alive():
        count += 1
    big.join()
    # Had the render held the lock, this loop would have run once or twice.
    assert count > 1000, f"the interpreter ran {count} loops during a render"


def test_many_renders_do_not_grow_the_process():
    import os

    def rss_mib():
        with open("/proc/self/statm") as f:
            return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 2**20

    scene = snell.loads(
        '[image]\nwidth = 64\nheight = 64\n[camera]\nlook_at = [0, 0, -1]\n'
        '[[lights]]\ntype = "point"\nposition = [0, 5, 0]\n[materials.m]\ncolor = 0.5\n'
        '[[objects]]\ntype = "sphere"\ncenter = [0, 0, -3]\nradius = 1\nmaterial = "m"\n'
    )
    for _ in range(20):
        snell.render(scene)
    before = rss_mib()
    count = 0
    for _ in range(300):
        snell.render(scene, aovs=["normal"])
        count += 1
    assert count == 300
    grew = rss_mib() - before
    assert grew < 5, f"300 renders grew the process by {grew:.1f} MiB"


def test_progress_true_shows_a_bar_that_ends_full(repo, capsys):
    snell.render(repo / "scenes/seed.toml", width=32, height=32, spp=4, progress=True)
    err = capsys.readouterr().err
    # tqdm's bar where tqdm is installed, else snell's own line; either ends at 100 %.
    assert "100%" in err.replace(" ", ""), err


def test_light_path_expressions_come_back_by_name_and_add_up(repo, run_cli, tmp_path):
    args = dict(width=32, height=24, spp=4)
    out = snell.render(repo / "scenes/cornell.toml", **args,
                       lpe=["emission", "direct", "indirect", "specular", "walls=C<RD'red'>.*L"])
    assert set(out) == {"image", "emission", "direct", "indirect", "specular", "walls"}
    parts = out["emission"] + out["direct"] + out["indirect"] + out["specular"]
    assert np.allclose(parts, out["image"], rtol=1e-5, atol=1e-6)
    assert out["walls"].max() > 0 and isinstance(out["walls"], snell.Image)
    # The same pixels as the command line's EXR layers, and the picture unchanged.
    exr = tmp_path / "c.exr"
    run_cli("render", repo / "scenes/cornell.toml", "-o", exr, "--quiet", "--width", 32,
            "--height", 24, "--spp", 4, "--lpe", "direct")
    assert np.array_equal(out["image"], snell.read(exr))
    assert np.array_equal(out["image"], snell.render(repo / "scenes/cornell.toml", **args))


@pytest.mark.parametrize(
    "lpe, words",
    [
        (["x=C<RX>L"], "column 4: `X` is not an event"),
        (["x=LC"], "a path starts at the camera"),
        (["nope"], "neither NAME=EXPR nor a preset"),
        (["a=CL", "a=CDL"], "two light path expressions are named `a`"),
    ],
)
def test_a_bad_expression_is_a_settings_error(repo, lpe, words):
    with pytest.raises(snell.SettingsError, match=None) as e:
        snell.render(repo / "scenes/cornell.toml", width=8, height=8, spp=1, lpe=lpe)
    assert words in str(e.value)


def test_whitted_refuses_expressions(repo):
    with pytest.raises(ValueError) as e:
        snell.render(repo / "scenes/seed.toml", width=8, height=8, spp=1, lpe=["direct"])
    assert "path tracer" in str(e.value)


def test_light_tracing_from_python_agrees_with_the_path_tracer(repo):
    args = dict(width=16, height=16, spp=256, seed=1)
    light = snell.render(repo / "scenes/cornell.toml", integrator="light", **args)
    path = snell.render(repo / "scenes/cornell.toml", integrator="path", **args)
    assert light.shape == (16, 16, 3)
    assert abs(light.mean() - path.mean()) < 0.03 * path.mean()
    with pytest.raises(ValueError, match="\"light\""):
        snell.render(repo / "scenes/cornell.toml", integrator="lite", **args)


def test_bdpt_from_python_agrees_with_the_path_tracer(repo):
    args = dict(width=16, height=16, spp=256, seed=1)
    bdpt = snell.render(repo / "scenes/cornell.toml", integrator="bdpt", **args)
    path = snell.render(repo / "scenes/cornell.toml", integrator="path", **args)
    assert bdpt.shape == (16, 16, 3)
    assert abs(bdpt.mean() - path.mean()) < 0.03 * path.mean()
