"""Ctrl-C stops a render cleanly, with the picture so far; the process goes on."""

import subprocess
import sys
import textwrap

import pytest

CHILD = textwrap.dedent(
    """
    import os, signal, sys, time
    import numpy as np
    import snell

    # Python leaves Ctrl-C ignored where the process was started with it ignored (a
    # background job of a script): the test sets the interpreter's own handler.
    signal.signal(signal.SIGINT, signal.default_int_handler)
    sent = []

    def progress(done, total):
        # Ctrl-C as soon as the render is under way (the handler runs at the next check).
        if not sent:
            sent.append(time.monotonic())
            os.kill(os.getpid(), signal.SIGINT)

    try:
        snell.render(sys.argv[1], width=96, height=96, spp=int(sys.argv[2]),
                     integrator=sys.argv[3], progress=progress)
        print("finished")
    except snell.Interrupted as e:
        img = e.image
        waited = time.monotonic() - sent[0]
        print("interrupted", img.shape, img.complete, bool(np.isfinite(img).all()),
              waited < 5, isinstance(e, KeyboardInterrupt))
    # The interpreter is whole: it renders again.
    print("again", snell.render(sys.argv[1], width=8, height=8, spp=1).shape)
    """
)


@pytest.mark.parametrize(
    "scene, spp, integrator",
    [("scenes/cornell.toml", 65536, "path"), ("scenes/seed.toml", 40_000, "whitted")],
)
def test_ctrl_c_stops_the_render_with_what_is_done(repo, scene, spp, integrator):
    child = subprocess.run(
        [sys.executable, "-c", CHILD, str(repo / scene), str(spp), integrator],
        capture_output=True, text=True, timeout=120,
    )
    assert child.returncode == 0, child.stderr
    lines = child.stdout.splitlines()
    assert lines == ["interrupted (96, 96, 3) False True True True", "again (8, 8, 3)"], child.stdout
