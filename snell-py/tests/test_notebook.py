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
