r"""A form solved for the accelerations, read back through its inputs
(:mod:`wheeled_dyn.compare.judge.unsolved`): the two-link arm of :mod:`published_forms`
(Spong, Hutchinson & Vidyasagar's equations) solved by SymPy, :math:`\ddot q = D^{-1}(\tau -
c - \phi)`, with errors planted in the source before solving.

- Several errors at once — link 1's own inertia dropped from :math:`d_{11}`, the sign of
  :math:`h\dot q_2^2` in the first equation, the second equation's gravity term left out:
  the inertia read back from the inputs is the document's, and the equations read back
  with it name the other two (only the point mass was named: both errors were blamed on it).
- The inputs exchanged, or one of the wrong sign: the inertia "read back" from them is no
  inertia matrix (not symmetric), and nothing is said of it (it was "the inertia matrix the
  document inverted differs", an inverse of the true one).
"""

from __future__ import annotations

from pathlib import Path

import pytest
import sympy as sp

import published_forms as P
from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.derivations import load_derivation

#: Engine grid.
SAMPLES, PARAM_SETS = 200, 3


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)


def _solved(tmp_path: Path, D: sp.Matrix, c: sp.Matrix, phi: sp.Matrix,
            tau: sp.Matrix | None = None) -> Path:
    tau = tau if tau is not None else sp.Matrix([P.tau1, P.tau2])
    sol = D.LUsolve(tau - c - phi)
    eqs = [f"ddq1 = {sp.sstr(sol[0])}", f"ddq2 = {sp.sstr(sol[1])}"]
    path = tmp_path / "solved.toml"
    path.write_text(P.ARM_HEAD.format(form="solved", error=", planted", model=P.DATA /
                                      "two_link_arm.toml",
                                      eqs=",\n".join(f'  "{e}"' for e in eqs)))
    return path


def _said(result) -> str:
    return " ".join(t for e in result.equations for t in e.texts)


def test_three_errors_before_solving_are_named_beside_the_inertia(engine, tmp_path):
    D, c, phi = P.arm("dropped")                              # I1 left out of d11
    h = -P.m2 * P.l1 * P.lc2 * sp.sin(P.q2)
    c = c + sp.Matrix([-2 * h * P.dq2 ** 2, 0])              # the sign of h*dq2**2
    phi = sp.Matrix([phi[0], 0])                              # eq. 2's gravity left out
    result = engine.compare(load_derivation(_solved(tmp_path, D, c, phi)))
    assert result.equivalent is False
    said = _said(result)
    for named in ("A[1,1]: the moment of inertia Iyy(link1) about its own centre of mass is "
                  "missing, a point mass", "h[1]:dq2*dq2: the document has the opposite sign",
                  "Q[2]: the document has 0"):
        assert named in said, said


@pytest.mark.parametrize("tau", [[P.tau2, P.tau1], [P.tau1, -P.tau2]])
def test_wrong_inputs_are_not_read_as_an_inverted_inertia(engine, tmp_path, tau):
    D, c, phi = P.arm(None)
    result = engine.compare(load_derivation(_solved(tmp_path, D, c, phi, sp.Matrix(tau))))
    assert result.equivalent is False
    assert "the inertia matrix the document inverted" not in _said(result), _said(result)
    assert not any("the inertia matrix the document inverted" in t
                   for r in result.records for t in r.texts)
