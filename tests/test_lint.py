r"""The whole package stays clean: ``ruff`` (rules F and C90, McCabe complexity at most 15,
``[tool.ruff]`` of pyproject.toml) and ``mypy`` (``[tool.mypy]``) find nothing in
``src/wheeled_dyn``. ``.ci/run`` runs both tools as well; here they run as ``python -m ...``
of the interpreter running the tests (the one ``./wd test`` installs them in), each skipped
with its reason where it is not installed. Checked to fail: an unused import (ruff) and a
wrong return type (mypy) planted in a module of the package.
"""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "src" / "wheeled_dyn"
#: Longest time either tool may take (s): a cold mypy run over the package takes 30-90 s on
#: a shared two-core machine.
TIMEOUT = 600


def _run(tool: str, *args: str) -> subprocess.CompletedProcess:
    if importlib.util.find_spec(tool) is None:
        pytest.skip(f"{tool} is not installed (it comes with the test extras: ./wd test)")
    return subprocess.run([sys.executable, "-m", tool, *args], cwd=ROOT, capture_output=True,
                          text=True, timeout=TIMEOUT)


def test_the_package_has_its_modules() -> None:
    assert len(list(PACKAGE.rglob("*.py"))) > 150


def test_ruff_finds_nothing() -> None:
    done = _run("ruff", "check", "--no-cache", str(PACKAGE.relative_to(ROOT)))
    assert done.returncode == 0, f"ruff check:\n{done.stdout}{done.stderr}"


@pytest.mark.slow
def test_mypy_finds_nothing() -> None:
    # no cache: each run checks from scratch and writes nothing into the checkout
    done = _run("mypy", "--cache-dir", "/dev/null", str(PACKAGE.relative_to(ROOT)))
    assert done.returncode == 0, f"mypy:\n{done.stdout}{done.stderr}"
