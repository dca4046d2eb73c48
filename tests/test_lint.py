r"""The parts of the package that are clean stay clean: ``ruff`` (rules F and C90, McCabe
complexity at most 15, ``[tool.ruff]`` of pyproject.toml) and ``mypy`` (``[tool.mypy]``) find
nothing in them.

The list grows as parts are made clean (:data:`CLEAN`, less :data:`NOT_YET`); once it is the
whole package, ``.ci/run`` runs both tools on ``src`` and this test can go. Each tool runs as
``python -m ...`` of the interpreter running the tests (the one ``./wd test`` installs them
in); where one is not installed its test is skipped.
"""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
PACKAGE = ROOT / "src" / "wheeled_dyn"
#: Folders of the package (every module in them) and ``"."`` (its top-level modules) that
#: ruff and mypy find clean.
CLEAN = (".", "cli", "compare", "constraints", "coordinates", "dynamics", "models", "report",
         "simulate", "symbolic", "viewer")
#: Modules inside :data:`CLEAN` folders that are not clean yet.
NOT_YET: tuple[str, ...] = ()
#: Longest time either tool may take (s): a cold mypy run over these modules takes 15-30 s
#: on a shared two-core machine.
TIMEOUT = 600


def clean_modules() -> list[str]:
    r"""The modules both tools are run on, relative to the checkout."""
    out = []
    for folder in CLEAN:
        here = PACKAGE / folder
        found = here.glob("*.py") if folder == "." else here.rglob("*.py")
        out += [p for p in found if str(p.relative_to(PACKAGE)) not in NOT_YET]
    return sorted(str(p.relative_to(ROOT)) for p in out)


def _run(tool: str, *args: str) -> subprocess.CompletedProcess:
    if importlib.util.find_spec(tool) is None:
        pytest.skip(f"{tool} is not installed (it comes with the test extras: ./wd test)")
    return subprocess.run([sys.executable, "-m", tool, *args], cwd=ROOT, capture_output=True,
                          text=True, timeout=TIMEOUT)


def test_the_lists_name_modules_that_exist() -> None:
    missing = [f for f in CLEAN if not (PACKAGE / f).is_dir()]
    missing += [f for f in NOT_YET if not (PACKAGE / f).is_file()]
    assert not missing, f"named in CLEAN or NOT_YET but not in the package: {missing}"
    assert len(clean_modules()) > 100


def test_ruff_finds_nothing() -> None:
    done = _run("ruff", "check", "--no-cache", *clean_modules())
    assert done.returncode == 0, f"ruff check:\n{done.stdout}{done.stderr}"


@pytest.mark.slow
def test_mypy_finds_nothing() -> None:
    # no cache: each run checks from scratch and writes nothing into the checkout
    done = _run("mypy", "--cache-dir", "/dev/null", *clean_modules())
    assert done.returncode == 0, f"mypy:\n{done.stdout}{done.stderr}"
