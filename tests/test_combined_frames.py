r"""Equations replaced by a combination of the true ones, with an error in what was combined:
the frame each is explained in is still the combination the form says, so the error is named
where it is, and nothing right is blamed.

Two systems written for the tests (``data/published``): a reaction-wheel pendulum after
M. W. Spong, P. Corke, R. Lozano, *Nonlinear control of the reaction wheel pendulum*,
Automatica 37 (2001) — its first equation replaced by eq1 − eq2, the wheel's torque then in
both; and a double inverted pendulum on a cart after A. Bogdanov, *Optimal control of a double
inverted pendulum on a cart*, OGI tech. report CSE-04-006 (2004) — its second equation
replaced by eq2 − (d23/d33) eq3, the first step of eliminating the upper link's acceleration.

- **Constant weights, an error in the combined inertia** (the pendulum's d11 without I2, or
  with lc1 written for l1): the frame that leaves the first inertia column out has the weights
  (1, −1) at every sample of every parameter set — a combination of numbers, as good as a
  constant factor. It was scored as fitting two weights, lost to the identity on a tie, and
  the row was explained as the true first equation: "the term −I2 has the wrong sign", a
  point-mass wheel in A[1,2], the torque "a term the truth does not have".
- **Weights that are functions, an error in a term of the combined equation** (the cart's
  upper link's gravity term left out of eq3, and so of the combination): the equations read
  back before they were combined (rows times :math:`AA_{doc}^{-1}`) have the truth's inputs
  and one entry wrong; :math:`A_{doc,2}A^{-1}` is then the form's combination, and only the
  gravity terms differ — not three inertias "too much" and a false energy cause.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import DiagnosisKind as K
from wheeled_dyn.derivations import load_derivation

DATA = Path(__file__).parent / "data" / "published"
#: Engine grid.
SAMPLES, PARAM_SETS = 200, 3


def _compare(tmp_path: Path, system: str, *planted: tuple[str, str]):
    r"""``data/published/<system>_combined.toml`` with each (old, new) of ``planted``
    replaced, compared."""
    for name in (f"{system}.toml", f"{system}.urdf"):
        (tmp_path / name).write_text((DATA / name).read_text())
    text = (DATA / f"{system}_combined.toml").read_text()
    for old, new in planted:
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    path = tmp_path / "doc.toml"
    path.write_text(text)
    engine = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)
    return engine.compare(load_derivation(path))


def _flagged(result) -> dict:
    return {r.element: r for r in result.records if r.verdict not in ("agrees",
                                                                      "factorization")}


def test_the_right_combined_forms_agree(tmp_path):
    for system, frame in (("rwp", "eq1 - eq2"), ("dipc", "")):
        result = _compare(tmp_path, system)
        assert result.equivalent is True and not _flagged(result), system
        if frame:
            assert frame in result.equations[0].frame, result.equations[0].frame


@pytest.mark.parametrize("old, new, kind, text", [
    # d11 without I2: the wheel's own inertia missing from the combined row
    ("I1*ddq1 + I2*ddq1 + I2*ddq2", "I1*ddq1 + I2*ddq2", K.POINT_MASS, "Iyy(wheel)"),
    # lc1 written for l1 in m2 l1²
    ("ddq1*l1**2*m2", "ddq1*lc1**2*m2", K.SWAP, "lc1"),
])
def test_an_error_in_a_row_combined_with_numbers_is_named_in_its_frame(tmp_path, old, new,
                                                                        kind, text):
    result = _compare(tmp_path, "rwp", (old, new))
    assert result.equivalent is False
    assert "eq1 - eq2" in result.equations[0].frame, result.equations[0].frame
    flagged = _flagged(result)
    assert set(flagged) == {"A[1,1]"}, {e: r.texts for e, r in flagged.items()}
    assert flagged["A[1,1]"].kinds[0] == kind, flagged["A[1,1]"].texts
    assert text in flagged["A[1,1]"].texts[0], flagged["A[1,1]"].texts


def test_a_term_dropped_from_an_equation_combined_with_functions_is_named_alone(tmp_path):
    # the term left out of eq3, and so of the combination eq2 - (d23/d33) eq3 printed
    result = _compare(tmp_path, "dipc",
                      (" + ddx*l2*m2*cos(th2) - g*l2*m2*sin(th2)) = 0 - (",
                       " + ddx*l2*m2*cos(th2)) = 0 - ("),
                      (" + ddx*l2*m2*cos(th2) - g*l2*m2*sin(th2) = 0\"",
                       " + ddx*l2*m2*cos(th2) = 0\""))
    assert result.equivalent is False
    flagged = _flagged(result)
    assert set(flagged) <= {"Q[2]", "Q[3]"} and flagged, \
        {e: r.texts for e, r in flagged.items()}
    assert all(r.kinds[0] == K.MISSING for r in flagged.values()), \
        {e: r.texts for e, r in flagged.items()}
    assert not any(c.kind in ("energy", "not_positive_definite") for c in result.causes), \
        result.causes


def test_a_combination_whose_inertia_columns_both_carry_the_error_is_read_as_one(tmp_path):
    r"""The two-link arm of :mod:`published_forms` (Spong, Hutchinson & Vidyasagar) with
    :math:`l_{c1}` written for :math:`l_1` in :math:`d_{12}` and :math:`d_{21}` alike, its
    first equation replaced by eq1 − eq2: both inertia columns of the combined row carry the
    error, so no frame that keeps one of them fits the row with numbers; its velocity,
    gravity and input terms alone give the weights (1, −1) at every sample. It was read as
    the true eq1, with a gravity term "missing" and a velocity term "swapped"; now as
    eq1 − eq2, and the swap named where it is."""
    import published_forms as P
    import sympy as sp
    D, c, phi = P.arm(None)
    wrong = D[0, 1].subs(P.l1, P.lc1)
    D = sp.Matrix([[D[0, 0], wrong], [wrong, D[1, 1]]])
    acc = sp.Matrix([P.ddq1, P.ddq2])
    lhs = [sp.sstr((D[i, :] * acc)[0] + c[i] + phi[i]) for i in range(2)]
    eqs = [f"{lhs[0]} - ({lhs[1]}) = tau1 - tau2", f"{lhs[1]} = tau2"]
    path = tmp_path / "combined.toml"
    path.write_text(P.ARM_HEAD.format(form="combined", error=", lc1 for l1 in d12, d21",
                                      model=P.DATA / "two_link_arm.toml",
                                      eqs=",\n".join(f'  "{e}"' for e in eqs)))
    result = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED).compare(
        load_derivation(path))
    assert result.equivalent is False
    assert "eq1 - eq2" in result.equations[0].frame, result.equations[0].frame
    flagged = _flagged(result)
    assert set(flagged) == {"A[1,1]", "A[1,2]", "A[2,1]"}, set(flagged)
    for r in flagged.values():
        assert r.kinds[0] == K.SWAP and "lc1 where l1 fits" in r.texts[0], r.texts
