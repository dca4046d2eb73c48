r"""A row that is a combination of the true equations whose parts differ in size beyond the
comparison's tolerance cannot be decided, whatever it agrees with: the two-link arm of
:mod:`published_forms` (Spong, Hutchinson & Vidyasagar's equations) with its first equation
replaced by eq1 + w·eq2.

- w = 1e10 with link 1's own gravity term left out of eq1: the missing term is 1e-10 of the
  row, below the tolerance of 1e-7 — it "agreed", the system right. Now undecided.
- w = 1e12, right: W = [[1, 1e12], [0, 1]] is invertible (det 1), but its rows are parallel
  to 1e-12 — eq2 was "not independent", the system not right. Now undecided, nothing lost.
- w = 1e5 with the same term left out: it differs (decided), and w = 2, right, agrees.

The summary says "not decided as a system" where an equation is undecided (it said nothing).
"""

from __future__ import annotations

import pytest
import sympy as sp

import published_forms as P
from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import Verdict
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.report.summary import system_word

#: Engine grid.
SAMPLES, PARAM_SETS = 200, 3


def _combined(tmp_path, weight: str, drop: bool):
    D, c, phi = P.arm(None)
    if drop:
        phi = phi - sp.Matrix([P.m1 * P.lc1 * P.g * sp.cos(P.q1), 0])   # eq1's own gravity
    acc = sp.Matrix([P.ddq1, P.ddq2])
    lhs = [sp.sstr((D[i, :] * acc)[0] + c[i] + phi[i]) for i in range(2)]
    eqs = [f"{lhs[0]} + ({weight})*({lhs[1]}) = tau1 + ({weight})*tau2", f"{lhs[1]} = tau2"]
    path = tmp_path / "combined.toml"
    path.write_text(P.ARM_HEAD.format(form="combined", error="", model=P.DATA /
                                      "two_link_arm.toml",
                                      eqs=",\n".join(f'  "{e}"' for e in eqs)))
    engine = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)
    return engine.compare(load_derivation(path))


@pytest.mark.parametrize("weight, drop, first, system", [
    ("1e10", True, Verdict.UNDECIDED, None),
    ("1e12", False, Verdict.UNDECIDED, None),
    ("1e5", True, Verdict.DIFFERS, False),
    ("2", False, Verdict.AGREES, True),
])
def test_parts_beyond_the_tolerance_are_undecided(tmp_path, weight, drop, first, system):
    result = _combined(tmp_path, weight, drop)
    assert [e.verdict for e in result.equations] == [first, Verdict.AGREES], result.equations
    assert result.equivalent is system
    if first == Verdict.UNDECIDED:
        said = " ".join(t for t in result.equations[0].texts)
        assert "parts differ in size by a factor" in said, said
    assert system_word(result) == {None: "not decided as a system", False:
                                   "not right as a system", True: ""}[system]


def test_an_equation_lost_beside_one_beyond_precision_is_still_lost():
    r"""W is called singular no more only where the equations left undecided for precision
    make it so: eq1 + 1e12·eq2 beside eq2 is nearly dependent by precision alone, but with
    eq2 written twice beside it, the repeated equation is lost whatever the first says."""
    import numpy as np

    from wheeled_dyn.compare.judge.equivalence import EquationDecision, _precision_only
    S = 4
    undecided = EquationDecision(Verdict.UNDECIDED, (), 0.0, np.zeros((S, 3)), True)
    agrees = EquationDecision(Verdict.AGREES, (), 0.0, np.zeros((S, 3)))
    near = np.broadcast_to(np.array([[1.0, 1e12, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]),
                           (S, 3, 3))
    lost = np.broadcast_to(np.array([[1.0, 1e12, 0.0], [0.0, 1.0, 0.0], [0.0, 1.0, 0.0]]),
                           (S, 3, 3))
    assert _precision_only(near, [undecided, agrees, agrees])
    assert not _precision_only(lost, [undecided, agrees, agrees])
    assert not _precision_only(near, [agrees, agrees, agrees])
