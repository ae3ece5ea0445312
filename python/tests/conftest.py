"""Fixtures: the snell binary under test, a local Ray cluster of 2 CPUs, reference frames."""

import os
import shutil
import subprocess
from pathlib import Path

import pytest

PYTHON_DIR = Path(__file__).resolve().parents[1]
REPO = PYTHON_DIR.parent
DATA = Path(__file__).resolve().parent / "data"
ANIM = DATA / "anim.toml"


def _find_snell() -> Path:
    given = os.environ.get("SNELL_BIN")
    if given:
        if not (os.path.isfile(given) and os.access(given, os.X_OK)):
            pytest.fail(f"SNELL_BIN={given} is not an executable file")
        return Path(given)
    # The newer of the release and debug builds: a stale one must not stand for the code.
    built = [REPO / "target" / profile / "snell" for profile in ("release", "debug")]
    built = [p for p in built if p.is_file()]
    if built:
        return max(built, key=lambda p: p.stat().st_mtime)
    pytest.fail(
        "no snell binary: build it with `cargo build --release` in the repository root "
        f"({REPO}), or point SNELL_BIN at one"
    )


@pytest.fixture(scope="session")
def snell_bin(tmp_path_factory: pytest.TempPathFactory) -> str:
    """A copy of the snell binary (so a rebuild does not change it under the tests); fails,
    never skips, when there is none or when it lacks the commands the farm needs."""
    source = _find_snell()
    copy = tmp_path_factory.mktemp("snell") / "snell"
    shutil.copy2(source, copy)
    helps = subprocess.run([str(copy), "render", "--help"], capture_output=True, text=True).stdout
    if "--frames" not in helps or "--region" not in helps:
        pytest.fail(f"{source} has no `render --frames` or `--region`: rebuild it (cargo build --release)")
    return str(copy)


@pytest.fixture(scope="session")
def ray_cluster():
    """One local Ray instance of 2 CPUs for the whole session; the driver uses it as it is."""
    import ray

    ray.init(address="local", num_cpus=2, include_dashboard=False,
             runtime_env={"env_vars": {"PYTHONPATH": os.pathsep.join(
                 p for p in (str(PYTHON_DIR), os.environ.get("PYTHONPATH", "")) if p)}})
    yield
    ray.shutdown()


@pytest.fixture(scope="session")
def reference(snell_bin: str, tmp_path_factory: pytest.TempPathFactory) -> Path:
    """Frames 0..3 of the test scene rendered by `snell render --frames` on one machine."""
    folder = tmp_path_factory.mktemp("reference")
    result = subprocess.run(
        [snell_bin, "render", str(ANIM), "--frames", "0..3", "-o", str(folder / "f_####.png"), "--quiet"],
        capture_output=True, text=True,
    )
    assert result.returncode == 0, result.stderr
    return folder
