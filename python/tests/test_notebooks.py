"""Executes the course notebooks (../../notebooks/*.ipynb) headless and pokes their widget.

Each notebook runs top to bottom in a fresh `python3` kernel from a temporary working
directory; then an extra cell moves the first control of the notebook's `demo`
(an ``ipywidgets.interactive``) to another valid value and calls ``demo.update()``, failing
if the callback raised, and asserts the variable the notebook leaves when its main
agreement cell ran.

Run: cd /tmp && python -m pytest path/to/python/tests/test_notebooks.py -q
"""

import pathlib
import sys
import time

import pytest

nbformat = pytest.importorskip("nbformat")
nbclient = pytest.importorskip("nbclient")
pytest.importorskip("ipywidgets")
pytest.importorskip("ipykernel")

ROOT = pathlib.Path(__file__).resolve().parent.parent.parent
NOTEBOOKS = ROOT / "notebooks"
# The kernel manager whose client does not miss a reply's wake-up (see its module).
sys.path.insert(0, str(ROOT / "tools"))
from patient_kernel import PatientKernelManager  # noqa: E402

# The variable each notebook sets to True in the cell that asserts its central promise.
PROOF = {
    "01-visible-surfaces.ipynb": "scanline_matches_ray_cast",
    "02-hard-shadows.ipynb": "exact_methods_agree",
    "03-soft-shadows.ipynb": "sampled_soft_shadows_converge",
    "04-light-volumes.ipynb": "ray_marching_converges",
    "05-texture.ipynb": "perspective_uv_exact",
    "06-environment-mapping.ipynb": "sphere_map_rims_worst",
    "07-radiosity.ipynb": "form_factors_match_closed_form",
    "08-global-illumination.ipynb": "reductions_hold",
}

POKE = '''
import sys as _sys
import lumiere as _lumiere
_errors = []
_ip = get_ipython()
_show = _ip.showtraceback
def _record(*args, **kwargs):
    _errors.append(repr(_sys.exc_info()[1]))
    return _show(*args, **kwargs)
_ip.showtraceback = _record  # interactive.update() reports a callback's exception this way
try:
    _w = demo.children[0]
    _before = _w.value
    if getattr(_w, "options", None):
        _w.index = (_w.index + 1) % len(_w.options)
    elif isinstance(_w.value, bool):
        _w.value = not _w.value
    else:
        _w.value = _w.min if _w.value != _w.min else _w.max
    assert _w.value != _before, "the first control did not change"
    demo.update()
finally:
    _ip.showtraceback = _show
assert not _errors, "demo's callback raised: " + "; ".join(_errors)
assert {proof} is True
print("kernel:", _sys.executable, "lumiere:", _lumiere.__file__)
'''


def notebook_files():
    return sorted(NOTEBOOKS.glob("*.ipynb"))


def test_every_topic_has_a_notebook():
    assert sorted(p.name for p in notebook_files()) == sorted(PROOF)


@pytest.mark.parametrize("path", notebook_files(), ids=lambda p: p.stem)
def test_notebook_runs(path, tmp_path):
    nb = nbformat.read(path, as_version=4)
    for cell in nb.cells:
        if cell.cell_type == "code":
            assert not cell.outputs and cell.execution_count is None, "store notebooks without outputs"
    assert nb.cells[0].source.splitlines()[0] == "import lumiere, numpy as np, matplotlib.pyplot as plt"
    nb.cells.append(nbformat.v4.new_code_cell(POKE.replace("{proof}", PROOF[path.name])))
    client = nbclient.NotebookClient(
        nb,
        timeout=600,
        kernel_name="python3",
        kernel_manager_class=PatientKernelManager,
        resources={"metadata": {"path": str(tmp_path)}},
    )
    start = time.perf_counter()
    client.execute()  # raises CellExecutionError on any failing cell, the appended one included
    elapsed = time.perf_counter() - start
    text = "".join(o.get("text", "") for o in nb.cells[-1].outputs if o.output_type == "stream")
    assert "kernel:" in text, nb.cells[-1].outputs
    # The kernel is this interpreter's environment, with the installed package.
    assert str(pathlib.Path(sys.executable).parent.parent) in text, text
    print(f"{path.name}: executed in {elapsed:.1f} s; {text.strip()}")
