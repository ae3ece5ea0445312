"""Shared fixtures: the repository's scenes, and the `snell` command line the module is
checked against (the one `cargo test` or `cargo build` made)."""

import os
import pathlib
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def repo() -> pathlib.Path:
    return REPO


@pytest.fixture(scope="session")
def cli() -> str:
    """The command line: $SNELL_BIN, else target/debug/snell (built by `cargo test`)."""
    path = os.environ.get("SNELL_BIN") or str(REPO / "target" / "debug" / "snell")
    assert os.access(path, os.X_OK), (
        f"{path} is not there: build the command line first (cargo build), or set SNELL_BIN"
    )
    return path


@pytest.fixture
def run_cli(cli):
    def run(*args, check=True):
        return subprocess.run([cli, *map(str, args)], capture_output=True, text=True, check=check)

    return run
