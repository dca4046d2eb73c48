"""The notebooks in notebooks/: stored with their outputs (they read on GitHub), made by
notebooks/make_notebooks.py from the cells it holds, and they run again from top to bottom
with outputs of the same kinds; a comparison result renders in a notebook as its report
section (checked through nbclient's HTML output)."""

from __future__ import annotations

import importlib.util
import re
from pathlib import Path

import pytest

NOTEBOOK_DIR = Path(__file__).resolve().parents[1] / "notebooks"
#: Seconds a cell may take.
CELL_TIMEOUT = 300

nbformat = pytest.importorskip("nbformat", reason="nbformat not installed (pip install -e .[test])")
nbclient = pytest.importorskip("nbclient", reason="nbclient not installed (pip install -e .[test])")


def _maker():
    spec = importlib.util.spec_from_file_location("make_notebooks",
                                                  NOTEBOOK_DIR / "make_notebooks.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def _kinds(nb) -> list[list[tuple[str, ...]]]:
    r"""Per code cell, its outputs' kinds: stream name or the MIME types shown. Consecutive
    chunks of one stream count once: how a kernel splits printed text into chunks depends on
    when it flushes (a cold cache's longer first cell gave two where the stored run had one)."""
    out = []
    for c in nb.cells:
        if c.cell_type != "code":
            continue
        kinds: list[tuple[str, ...]] = []
        for o in c.get("outputs", []):
            kind = (o["output_type"], o.get("name", ""), *sorted(o.get("data", {})))
            if not (kind[0] == "stream" and kinds and kinds[-1] == kind):
                kinds.append(kind)
        out.append(kinds)
    return out


def _execute(nb, path: Path = NOTEBOOK_DIR):
    nbclient.NotebookClient(nb, timeout=CELL_TIMEOUT, kernel_name="python3",
                            resources={"metadata": {"path": str(path)}}).execute()
    errors = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])
              if o.get("output_type") == "error"]
    assert not errors, errors
    return nb


def test_the_notebooks_are_the_ones_make_notebooks_writes():
    maker = _maker()
    assert sorted(maker.NOTEBOOKS) == sorted(p.name for p in NOTEBOOK_DIR.glob("*.ipynb"))
    for name in maker.NOTEBOOKS:
        stored = nbformat.read(NOTEBOOK_DIR / name, as_version=4)
        made = maker.build(name)
        assert [(c.cell_type, c.source) for c in stored.cells] == \
            [(c.cell_type, c.source) for c in made.cells], \
            f"{name} is not what make_notebooks.py writes: run it again"
        code = [c for c in stored.cells if c.cell_type == "code"]
        silent = [c.source.startswith("MY_NOTES = ") for c in code]     # an assignment only
        assert [bool(k) for k in _kinds(stored)] == [not s for s in silent], \
            f"{name} is stored without its outputs: run make_notebooks.py"


@pytest.mark.slow
@pytest.mark.parametrize("path", sorted(NOTEBOOK_DIR.glob("*.ipynb")), ids=lambda p: p.name)
def test_notebook_runs_again_with_the_outputs_it_stores(path):
    stored = nbformat.read(path, as_version=4)
    again = nbformat.read(path, as_version=4)
    for cell in again.cells:
        if cell.cell_type == "code":
            cell.outputs = []
    _execute(again)
    assert _kinds(again) == _kinds(stored)


def test_a_result_renders_in_a_notebook_as_its_report_section(tmp_path):
    r"""A derivation with a planted sign, compared in a kernel, shown as the cell's value: the
    HTML nbclient receives is the report's section, causes first, the planted element marked
    in the document's matrix."""
    from nbformat.v4 import new_code_cell, new_notebook

    from wheeled_dyn.derivations import builtin_derivations
    rod = next(p for p in builtin_derivations("seed000") if p.name == "p4_4_rod_pendulum.toml")
    planted = tmp_path / "rod_planted.toml"
    text = rod.read_text(encoding="utf-8")
    assert "m*g*l/2*sin(theta) = 0" in text
    planted.write_text(text.replace("m*g*l/2*sin(theta) = 0", "-m*g*l/2*sin(theta) = 0"),
                       encoding="utf-8")
    nb = new_notebook(cells=[new_code_cell(
        "from wheeled_dyn.compare import ComparisonEngine\n"
        "from wheeled_dyn.derivations import load_derivation\n"
        f"result = ComparisonEngine(samples=40, param_sets=2).compare(load_derivation({str(planted)!r}))\n"
        "result")], metadata={"kernelspec": {"name": "python3", "display_name": "Python 3",
                                             "language": "python"}})
    _execute(nb, tmp_path)
    (shown,) = [o for o in nb.cells[0].outputs if o["output_type"] == "execute_result"]
    html = shown["data"]["text/html"]
    assert html.startswith('<div class="wheeled-dyn-result"><style>')
    assert shown["data"]["text/plain"].startswith("<DerivationResult rod_planted.toml: ")
    section = html[html.index('<section id="d-rod_planted">'):]
    causes, matrices = section.index('class="causes"'), section.index('class="pair"')
    assert causes < matrices
    assert "sign: the document has the opposite sign" in section[causes:matrices]
    (q_document,) = re.findall(r'<b>Q</b> <span class="note">\(document.*?</table>', section)
    assert re.search(r'<td class="v-differs"[^>]*title="differs; sign', q_document), q_document
