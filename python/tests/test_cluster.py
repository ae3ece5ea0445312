"""Reaching Ray: an address where nothing listens fails at once, one that never answers as
Ray fails within --connect-timeout, and SIGTERM acts within a second or two whether the job
is joining a cluster or rendering on its own local instance, where Ray's warning about its
default token authentication no longer shows."""

import signal
import socket
import subprocess
import sys
import threading
import time

from conftest import ANIM


def farm(*args, **popen):
    return subprocess.Popen([sys.executable, "-m", "snell_farm", "render", str(ANIM), *args],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, **popen)


def silent_listener():
    """A port that accepts connections and never says anything (not Ray)."""
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(16)
    held = []

    def accept():
        while True:
            try:
                held.append(server.accept()[0])
            except OSError:
                return

    threading.Thread(target=accept, daemon=True).start()
    return server


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def test_nothing_listening_fails_at_once(snell_bin, tmp_path):
    port = free_port()
    start = time.monotonic()
    p = farm("-o", str(tmp_path / "x_####.png"), "--address", f"127.0.0.1:{port}", "--snell", snell_bin)
    out, err = p.communicate(timeout=60)
    assert p.returncode == 1, err
    assert time.monotonic() - start < 10
    assert f"cannot reach the Ray cluster at 127.0.0.1:{port}" in err, err
    assert "ray start --head" in err
    assert "Traceback" not in err and not list(tmp_path.iterdir())


def test_a_cluster_that_never_answers_fails_within_the_timeout(snell_bin, tmp_path):
    server = silent_listener()
    port = server.getsockname()[1]
    start = time.monotonic()
    p = farm("-o", str(tmp_path / "x_####.png"), "--address", f"127.0.0.1:{port}", "--connect-timeout", "3",
             "--snell", snell_bin)
    out, err = p.communicate(timeout=60)
    took = time.monotonic() - start
    server.close()
    assert p.returncode == 1, err
    assert 3 <= took < 15, took
    assert "no answer within 3 s (--connect-timeout)" in err, err


def test_sigterm_while_joining_acts_at_once(snell_bin, tmp_path):
    server = silent_listener()
    port = server.getsockname()[1]
    p = farm("-o", str(tmp_path / "x_####.png"), "--address", f"127.0.0.1:{port}", "--snell", snell_bin)
    time.sleep(2)
    sent = time.monotonic()
    p.send_signal(signal.SIGTERM)
    out, err = p.communicate(timeout=60)
    took = time.monotonic() - sent
    server.close()
    assert p.returncode == 130, err
    assert took < 5, took
    assert "interrupted while joining" in err, err


def test_sigterm_while_rendering_acts_within_two_seconds(snell_bin, tmp_path):
    # Its own local instance (not the tests' shared one), with a job long enough to stop.
    p = farm("-o", str(tmp_path / "f_####.png"), "--frames", "0..3", "--tiles", "2x2", "--spp", "4096",
             "--workers", "2", "--snell", snell_bin)
    lines = []
    reader = threading.Thread(target=lambda: lines.extend(p.stderr), daemon=True)
    reader.start()
    deadline = time.monotonic() + 60
    while not any("frames 0/" in line for line in lines):
        assert p.poll() is None and time.monotonic() < deadline, "".join(lines)
        time.sleep(0.1)
    time.sleep(1)
    sent = time.monotonic()
    p.send_signal(signal.SIGTERM)
    p.wait(timeout=60)
    took = time.monotonic() - sent
    reader.join(timeout=10)
    assert p.returncode == 130, "".join(lines)
    assert took < 4, took
    assert any("interrupted; the frames written are whole" in line for line in lines), "".join(lines)
    # Ray's warning about its default token authentication, on every run, is silenced.
    assert not any("Token authentication" in line for line in lines), "".join(lines)
