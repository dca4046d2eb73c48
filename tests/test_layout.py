r"""The layout of ``compare/`` as stages, data flowing one way: a module may import only from
its own stage or from stages before it

.. code-block:: text

    records, runtime, presentation ← grid ← sides ← judge ← readings ← causes ← steps
                                   ← engine ← other_documents   (and cli/ after all of them)

and nothing in the package imports the command line (``cli/``) or the reports
(``report/``). ``judge/`` and ``causes/`` decide and explain from numbers and typed records,
so they never import ``presentation/`` (text for the reports). Every import statement counts,
also one inside a function. No module of the package is longer than :data:`MAX_LINES`.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[1] / "src" / "wheeled_dyn"
COMPARE = PACKAGE / "compare"
#: The stages of ``compare/`` in the order data flows (a stage may import from its own rank
#: and from lower ones).
RANK = {"records": 0, "runtime": 0, "presentation": 0, "grid": 1, "sides": 2, "judge": 3,
        "readings": 4, "causes": 5, "steps": 6, "engine": 7, "other_documents": 8}
#: Stages that may not read presentation text.
NO_PRESENTATION = ("judge", "causes")
#: Longest module of the package (lines).
MAX_LINES = 400
#: The one import against the flow, and why: a result displays itself in a notebook
#: (``DerivationResult._repr_html_``, called by IPython) as the report renders it, imported
#: when it is displayed.
ALLOWED = {("records/result.py", "wheeled_dyn.report.notebook")}


def _stage(path: Path) -> str | None:
    parts = path.relative_to(COMPARE).with_suffix("").parts
    return None if parts == ("__init__",) else parts[0]


def _imports(path: Path) -> list[tuple[int, str]]:
    r"""Absolute names of the modules ``path`` imports from the package, with their line."""
    tree = ast.parse(path.read_text(), str(path))
    module = ".".join(path.relative_to(PACKAGE.parent).with_suffix("").parts)
    package = module if path.name == "__init__.py" else module.rpartition(".")[0]
    package = package.removesuffix(".__init__")
    out = []
    for node in ast.walk(tree):
        if isinstance(node, ast.ImportFrom):
            if node.level:
                base = package.split(".")
                base = base[:len(base) - node.level + 1]
                target = ".".join(base + ([node.module] if node.module else []))
            else:
                target = node.module or ""
            names = [target] if node.module else [f"{target}.{a.name}" for a in node.names]
            out += [(node.lineno, n) for n in names]
        elif isinstance(node, ast.Import):
            out += [(node.lineno, a.name) for a in node.names]
    return [(line, n) for line, n in out if n.startswith("wheeled_dyn")]


def _compare_modules() -> list[Path]:
    return sorted(p for p in COMPARE.rglob("*.py") if _stage(p) is not None)


@pytest.mark.parametrize("path", _compare_modules(), ids=lambda p: str(p.relative_to(COMPARE)))
def test_compare_imports_flow_one_way(path: Path) -> None:
    here = _stage(path)
    wrong = []
    for line, name in _imports(path):
        if (str(path.relative_to(COMPARE)), name) in ALLOWED:
            continue
        if name.startswith(("wheeled_dyn.cli", "wheeled_dyn.report")):
            wrong.append(f"line {line}: {name} (the command line and the reports come after)")
            continue
        if not name.startswith("wheeled_dyn.compare."):
            continue
        there = name.split(".")[2]
        if there not in RANK:
            continue
        if RANK[there] > RANK[here] or (here in NO_PRESENTATION and there == "presentation"):
            wrong.append(f"line {line}: {name} ({there} may not be imported by {here})")
    assert not wrong, f"{path.relative_to(PACKAGE)} imports against the flow:\n" + "\n".join(wrong)


def test_every_stage_is_known() -> None:
    stages = {_stage(p) for p in _compare_modules()}
    assert stages <= set(RANK), f"compare/ has folders or modules outside the stages: " \
                                f"{sorted(stages - set(RANK))}"


def test_modules_are_short() -> None:
    long = {str(p.relative_to(PACKAGE)): n for p in PACKAGE.rglob("*.py")
            if (n := len(p.read_text().splitlines())) > MAX_LINES}
    assert not long, f"modules over {MAX_LINES} lines: {long}"


def test_the_engine_leaves_slow_imports_to_where_they_are_used() -> None:
    r"""Importing the comparison engine (what every ``compare`` starts with) does not import
    what only some comparisons use: SciPy's optimizers (0.5 s here, for the search of a
    vanishing factor), yourdfpy (URDFs read before come from the cache)."""
    import subprocess
    import sys
    code = ("import sys, wheeled_dyn.compare.engine; "
            "print(sorted(m for m in ('scipy.optimize', 'yourdfpy') if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         check=True).stdout.strip()
    assert out == "[]", out
