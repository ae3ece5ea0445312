"""The example notebook (examples/snell-tour.ipynb) runs from top to bottom in a real
Jupyter kernel (nbclient), as a reader would run it."""

import pytest


def test_the_tour_notebook_runs(repo):
    try:
        import nbclient
        import nbformat
    except ImportError as e:  # a failure, not a skip: CI installs them
        pytest.fail(f"{e}: pip install nbclient nbformat ipykernel matplotlib (the [notebook] extra)")
    nb = nbformat.read(repo / "examples/snell-tour.ipynb", as_version=4)
    client = nbclient.NotebookClient(
        nb, timeout=300, kernel_name="python3", resources={"metadata": {"path": str(repo)}}
    )
    client.execute()
    code = [c for c in nb.cells if c.cell_type == "code"]
    assert len(code) == 5
    outputs = [o for c in code for o in c.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    # The pictures showed as pictures: the two renders (their _repr_png_) and two plots.
    pngs = [o for o in outputs if "image/png" in o.get("data", {})]
    assert len(pngs) == 4, [sorted(o.get("data", {})) for o in outputs]
    text = "".join(o.get("text", "") for o in outputs)
    assert "rays drawn" in text and "fitted slope" in text


def test_a_notebooks_interrupt_stops_a_render_with_what_is_done(repo):
    """The kernel's interrupt (the notebook's stop button sends SIGINT to the kernel) ends
    a long render at once with snell.Interrupted, and the kernel goes on."""
    import time

    from jupyter_client.manager import start_new_kernel

    km, kc = start_new_kernel(kernel_name="python3", cwd=str(repo))
    try:
        code = (
            "import snell\n"
            "try:\n"
            "    snell.render('scenes/cornell.toml', width=64, height=64, spp=65536)\n"
            "except snell.Interrupted as e:\n"
            "    print('interrupted', e.image.shape, e.image.complete, e.image.spp >= 1)\n"
        )
        msg_id = kc.execute(code)
        time.sleep(2.0)  # the render is under way (it would take minutes)
        km.interrupt_kernel()
        out = []
        while True:
            msg = kc.get_iopub_msg(timeout=60)
            if msg["parent_header"].get("msg_id") != msg_id:
                continue
            if msg["msg_type"] == "stream":
                out.append(msg["content"]["text"])
            if msg["msg_type"] == "status" and msg["content"]["execution_state"] == "idle":
                break
        assert "".join(out) == "interrupted (64, 64, 3) False True\n", out
        reply = kc.execute_interactive("print(snell.render('scenes/seed.toml', width=8, height=8, spp=1).shape)", timeout=60)
        assert reply["content"]["status"] == "ok"
    finally:
        kc.stop_channels()
        km.shutdown_kernel(now=True)
