r"""The coupling of a cart-pole written wrong where an author derives it once and uses it in
both equations — :math:`A_{12} = A_{21} = ml\cos\theta` as :math:`Ml\cos\theta` (one symbol for
another) or :math:`2ml\cos\theta` — then the equations solved for the accelerations, or the
pole's reaction eliminated from the cart's equation (Barto, Sutton & Anderson 1983; Florian
2007, "Correct equations for the dynamics of the cart-pole system"): the error is named as
that symmetric pair of the equations before they were solved or combined, in the document's
symbols, on the rows it reached. As printed, the solved rows had "no single-term diagnosis"
and the combined row "a term the truth does not have".

And where the combination's weight carries the error — the cart's equation less
:math:`A_{12}/A_{22}` times the pole's, as the first step of solving writes it, with the pole
taken as a point mass (:math:`ml^2` for :math:`\tfrac43ml^2`) or the coupling wrong — no frame
fits the combined row better than the row as printed, and it was named by terms it "leaves
out" or that "the truth does not have"; the wrong entry of the source equations, found with
the combination it implies, names it.

Equations: :func:`published_forms.cart_pole` (the right file of its forms), with the coupling
and the pole's inertia as parameters here.
"""

from __future__ import annotations

from pathlib import Path

import pytest
import sympy as sp

from conftest import SEED
from published_forms import DATA, POLE_HEAD, F, M, _s, ddth, ddx, dth, g, l, m, th
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import DiagnosisKind as K
from wheeled_dyn.compare.records import Verdict
from wheeled_dyn.derivations import load_derivation

#: Engine grid.
SAMPLES, PARAM_SETS = 300, 3
COUPLING = m * l * sp.cos(th)
INERTIA = sp.Rational(4, 3) * m * l ** 2
#: Planted errors: (coupling, pole's inertia about the pivot) and the kind that names them.
ERRORS = {"swap": (M * l * sp.cos(th), INERTIA, K.SWAP),
          "factor": (2 * m * l * sp.cos(th), INERTIA, K.FACTOR)}
#: Diagnoses that name a term of the row as printed (the combined row's own terms).
AS_PRINTED = (K.MISSING, K.EXTRA, K.SIGN)


def _equations(coupling: sp.Expr, inertia: sp.Expr) -> tuple[sp.Expr, sp.Expr]:
    cart = (M + m) * ddx + coupling * ddth - m * l * dth ** 2 * sp.sin(th) - F
    pole = coupling * ddx + inertia * ddth - m * g * l * sp.sin(th)
    return cart, pole


def _forms(coupling: sp.Expr, inertia: sp.Expr) -> dict[str, list[str]]:
    cart, pole = _equations(coupling, inertia)
    (sol,) = sp.solve([cart, pole], [ddx, ddth], dict=True)
    weight = coupling / inertia
    return {
        "solved": [f"ddx = {_s(sp.simplify(sol[ddx]))}",
                   f"ddtheta = {_s(sp.simplify(sol[ddth]))}"],
        "combined": [f"{_s(cart)} - (3*cos(theta)/(4*l))*({_s(pole)}) = 0", f"{_s(pole)} = 0"],
        "eliminated": [f"{_s(cart)} - ({_s(weight)})*({_s(pole)}) = 0", f"{_s(pole)} = 0"],
    }


def _compare(folder: Path, form: str, name: str, coupling: sp.Expr, inertia: sp.Expr):
    eqs = _forms(coupling, inertia)[form]
    path = folder / f"pole_{form}_{name}.toml"
    path.write_text(POLE_HEAD.format(form=form, error=f", {name}", model=DATA / "cart_pole.toml",
                                     eqs=",\n".join(f'  "{e}"' for e in eqs)))
    engine = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)
    return engine.compare(load_derivation(path))


@pytest.mark.parametrize("form", ["solved", "combined", "eliminated"])
def test_every_right_form_agrees(tmp_path, form):
    result = _compare(tmp_path, form, "right", COUPLING, INERTIA)
    assert result.equivalent is True, result.equations


@pytest.mark.parametrize("form", ["solved", "combined", "eliminated"])
@pytest.mark.parametrize("error", sorted(ERRORS))
def test_a_wrong_coupling_is_named_as_the_symmetric_pair(tmp_path, form, error):
    coupling, inertia, kind = ERRORS[error]
    result = _compare(tmp_path, form, error, coupling, inertia)
    assert result.equivalent is False
    row = [r for r in result.records if r.element.startswith(("A[1,", "Q[1]", "B[1,", "h[1]"))
           and r.verdict == Verdict.DIFFERS]
    assert row, [(r.element, r.verdict) for r in result.records]
    for r in row:
        first = r.diagnoses[0]
        assert first.kind == kind, (r.element, [d.text for d in r.diagnoses])
        assert not any(d.kind in AS_PRINTED for d in r.diagnoses), (r.element, r.diagnoses)
    pair = [r for r in row if "A[1,2]" in r.diagnoses[0].text
            and "A[2,1], the same symmetric entry" in r.diagnoses[0].text]
    if form != "combined":      # combined with the right weight, a row's own terms name it too
        assert len(pair) == len(row), [(r.element, r.diagnoses[0].text) for r in row]
    if error == "swap":
        assert all("m and M" in r.diagnoses[0].text or "M where m fits" in r.diagnoses[0].text
                   for r in row), [r.diagnoses[0].text for r in row]


def test_a_point_mass_in_the_combinations_weight_is_named(tmp_path):
    result = _compare(tmp_path, "eliminated", "point_mass", COUPLING, m * l ** 2)
    assert result.equivalent is False
    combined = [r for r in result.records if r.element.startswith("A[1,")
                and r.verdict == Verdict.DIFFERS]
    assert combined
    for r in combined:
        assert r.diagnoses[0].kind == K.POINT_MASS, (r.element, r.diagnoses)
        assert not any(d.kind in AS_PRINTED for d in r.diagnoses), (r.element, r.diagnoses)



@pytest.mark.parametrize("error", ["point_mass", "sign", "dropped"])
def test_a_form_neither_solved_nor_combined_is_not_said_read_back(tmp_path, error):
    r"""The cart-pole's pole equation divided by m·l (published_forms' "divided" form, a row
    scaled, none combined) with one error: its elements name it; no equation is said "read
    back before it was solved or combined" (the one wrong entry found there combines no
    rows)."""
    import published_forms as P
    engine = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)
    result = engine.compare(load_derivation(P.write(tmp_path, "pole", "divided", error)))
    assert result.equivalent is False
    said = [d.text for e in result.equations for d in e.diagnoses]
    assert not any("read back" in t for t in said), said
