"""An element that overflows (``exp(exp(exp(M1)))``) is 'undecided', silently.

A shipped derivation with one element replaced by a triple exponential of a mass (inf at every
sample) is compared through the command line: the element's verdict in report.json is
'undecided', and stderr carries no NumPy ``RuntimeWarning`` (with the generated code of the
compiled expression). The document's compiled functions themselves
(:class:`~wheeled_dyn.compare.sides.evaluate.DocumentFunctions`) give inf without a warning.
"""

from __future__ import annotations

import json
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np
import pytest

from conftest import SEED
from wheeled_dyn.derivations import builtin_derivations

SEED001 = {p.name: p for p in builtin_derivations("seed001")}
#: Seconds one comparison may take at most (a hang fails instead of blocking the suite).
CLI_TIMEOUT = 240
#: Random states at which the compiled functions are evaluated.
N_STATES = 50
#: Mass of the body (kg) at which exp(exp(exp(M1))) overflows (exp(exp(60)) is already inf).
BODY_MASS = 60.0
OVERFLOW = "exp(exp(exp({})))"

#: case: (shipped file, text replaced, its replacement, element expected 'undecided').
CASES = {
    "matrix": ("eq25_lagrange.toml", "YZ1*cos(phi) + XZ1*sin(phi),   ZZ1]",
               "YZ1*cos(phi) + XZ1*sin(phi),   " + OVERFLOW.format("M1") + "]", "A[3,3]"),
    "equations": ("report3_eq4_5.toml", "(m*l**2 + I + eta**2*I_m)*ddtheta",
                  OVERFLOW.format("m") + "*ddtheta", "A[2,2]"),
}


def _mutated(folder: Path, case: str) -> Path:
    name, old, new, _ = CASES[case]
    text = SEED001[name].read_text()
    assert text.count(old) == 1, old
    path = folder / f"overflow_{case}.toml"
    path.write_text(text.replace(old, new))
    return path


@pytest.fixture(scope="module")
def compared(tmp_path_factory) -> dict[str, tuple[subprocess.CompletedProcess, dict]]:
    r"""Each case compared once by ``wheeled-dyn compare wip FILE --out DIR``: the finished
    process and its report.json."""
    out = {}
    for case in CASES:
        folder = tmp_path_factory.mktemp(case)
        proc = subprocess.run([sys.executable, "-m", "wheeled_dyn.cli.main", "compare", "wip",
                               str(_mutated(folder, case)), "--out", str(folder / "out")],
                              capture_output=True, text=True, timeout=CLI_TIMEOUT)
        report = json.loads((folder / "out" / "report.json").read_text()) \
            if proc.returncode == 0 else {}
        out[case] = (proc, report)
    return out


@pytest.mark.parametrize("case", sorted(CASES))
def test_overflowing_element_is_undecided(compared, case):
    proc, report = compared[case]
    assert proc.returncode == 0, proc.stderr
    (doc,) = report["derivations"]
    verdicts = {r["element"]: r["verdict"] for r in doc["records"]}
    assert verdicts[CASES[case][3]] == "undecided"
    assert "agrees" in verdicts.values()            # the other elements are still judged


@pytest.mark.parametrize("case", sorted(CASES))
def test_overflow_prints_no_runtime_warning(compared, case):
    proc, _ = compared[case]
    assert proc.returncode == 0, proc.stderr
    assert "RuntimeWarning" not in proc.stderr and "lambdifygenerated" not in proc.stderr, \
        proc.stderr


def test_document_functions_give_inf_without_a_warning(tmp_path):
    from wheeled_dyn.compare.sides.document import DocumentFunctions
    from wheeled_dyn.derivations import load_derivation
    d = load_derivation(_mutated(tmp_path, "matrix"))
    funcs = DocumentFunctions(d, d.A, d.C, d.Q, None, None, None)
    rng = np.random.default_rng(SEED)
    q = rng.uniform(-1.0, 1.0, (N_STATES, len(d.positions)))
    nu = rng.uniform(-1.0, 1.0, (N_STATES, len(d.velocities)))
    values = {p: np.full(N_STATES, BODY_MASS if p.name == "M1" else 1.0) for p in funcs.params}
    element = d.A[2, 2]
    with warnings.catch_warnings():
        warnings.simplefilter("error")               # any warning fails the test
        arrays = funcs.evaluate(q, nu, values)
        compiled = funcs.compiled(element)(*q.T, *nu.T, *(values[p] for p in funcs.params))
    assert np.all(np.isposinf(arrays.A[:, 2, 2])) and np.all(np.isposinf(compiled))
    assert np.all(np.isfinite(np.delete(arrays.A.reshape(N_STATES, -1), 8, axis=1)))


@pytest.mark.parametrize("case", sorted(CASES))
def test_overflow_gives_no_energy_verdict(compared, case):
    r"""The power identity on an overflowing document is not decided (no "conserves")."""
    _, report = compared[case]
    (doc,) = report["derivations"]
    assert doc["energy"] is None or doc["energy"]["conserves"] is False
