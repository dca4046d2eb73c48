r"""A linearised document's report shows the truth it is judged against: the linearisation of
the true equations at the declared point, so that truth − document names the stiffness and the
corrected equation is linear.

The uniform rod hinged at one end, linearised about hanging straight down (θ = 0, θ measured
from the downward vertical): (m l²/3) θ̈ + (m g l/2) θ = 0, ω² = 3g/(2l) (Meriam & Kraige,
*Engineering Mechanics: Dynamics*, the compound pendulum; seed 000's 4.4), divided by m l²/3
as a textbook writes it, θ̈ + (3g/2l) θ = 0. With the stiffness doubled the report shows
K = 3g/(2l) beside the document's 3g/l, truth − document −3g/(2l), and the corrected
equation θ̈ + 3gθ/(2l) = 0 (no sin θ: the truth linearised)."""

from __future__ import annotations

import pytest
import sympy as sp

import wheeled_dyn as wd
from wheeled_dyn.compare.records import DiagnosisKind as K, Verdict

g, l, theta = sp.symbols("g l theta")


def _rod(stiffness, **more):
    return wd.compare(
        "rod_pendulum", coordinates={"positions": ["theta"], "configuration": {"theta": "theta"}},
        A=sp.Matrix([[1]]), C=sp.zeros(1, 1), Q=sp.Matrix([stiffness * theta]),
        symbols={"m": "M(rod)", "l": "length(rod)", "g": "g"},
        assumes={"uniform": ["rod"], "linearised_about": {"theta": 0.0}, **more})


def test_the_right_linearisation_agrees_and_shows_the_linear_truth():
    result = _rod(3 * g / (2 * l))
    records = {r.element: r for r in result.records}
    assert all(r.verdict == Verdict.AGREES for r in records.values())
    assert sp.simplify(sp.sympify(records["Q[1]"].truth) - 3 * g * theta / (2 * l)) == 0
    assert sp.simplify(sp.sympify(records["K[1,1]"].truth) - 3 * g / (2 * l)) == 0


@pytest.mark.parametrize("wrong,kind", [(3 * g / l, K.FACTOR), (-3 * g / (2 * l), K.SIGN)])
def test_a_wrong_stiffness_is_shown_against_the_linearised_truth(wrong, kind):
    result = _rod(wrong)
    k = next(r for r in result.records if r.element == "K[1,1]")
    assert k.verdict == Verdict.DIFFERS and any(d.kind == kind for d in k.diagnoses)
    truth, document, residual = (sp.sympify(x) for x in (k.truth, k.document, k.residual))
    assert sp.simplify(document - wrong) == 0
    assert sp.simplify(truth - 3 * g / (2 * l)) == 0
    assert sp.simplify(truth - document - residual) == 0
    (equation,) = [e for e in result.equations if e.verdict == Verdict.DIFFERS]
    assert "sin" not in equation.corrected and "theta" in equation.corrected


def test_the_stiffness_is_in_the_reports_matrices():
    r"""The HTML report's matrices show K beside A, C, Q, B (its Q cell agrees at the point;
    the stiffness that differs is K's cell, marked)."""
    from wheeled_dyn.report.html import derivation_html
    page = derivation_html(_rod(3 * g / l))
    assert "<b>K</b>" in page and 'class="v-differs"' in page.split("<b>K</b>", 1)[1]


@pytest.mark.parametrize("stiffness, verdict", [
    (3 * g / (2 * l), Verdict.AGREES), (-3 * g / (2 * l), Verdict.DIFFERS),
    (3 * g / l, Verdict.DIFFERS), (0, Verdict.DIFFERS), (-30 * g / l, Verdict.DIFFERS)])
def test_a_potential_from_the_equilibrium_still_compares_the_stiffness(stiffness, verdict):
    r"""``potential = "equilibrium"`` makes the truth's Q zero at the point (springs the model
    lacks balance gravity there), never its stiffness: with it, the hanging rod's stiffness
    of the wrong sign (unstable), doubled, dropped or ×−20 "agreed" with no trace (K was not
    compared at all)."""
    result = _rod(stiffness, potential="equilibrium")
    k = next(r for r in result.records if r.element == "K[1,1]")
    assert k.verdict == verdict, k.texts
    assert result.equivalent is (verdict == Verdict.AGREES)


def test_a_point_at_pi_is_shown_as_pi():
    r"""The rod linearised about upright (θ = π, given as the float 3.141592653589793) with
    its stiffness of the wrong sign: the truth shown is exact at π, K = −3g/(2l) and
    Q = −3g(θ − π)/(2l), not ``cos(314159265358979/100000000000000)``."""
    import math
    result = wd.compare(
        "rod_pendulum", coordinates={"positions": ["theta"], "configuration": {"theta": "theta"}},
        A=sp.Matrix([[1]]), C=sp.zeros(1, 1), Q=sp.Matrix([3 * g / (2 * l) * (theta - sp.pi)]),
        symbols={"m": "M(rod)", "l": "length(rod)", "g": "g"},
        assumes={"uniform": ["rod"], "linearised_about": {"theta": math.pi}})
    records = {r.element: r for r in result.records}
    assert records["K[1,1]"].verdict == Verdict.DIFFERS
    assert sp.sympify(records["K[1,1]"].truth) == -3 * g / (2 * l)
    assert sp.sympify(records["K[1,1]"].residual) == -3 * g / l
    assert sp.simplify(sp.sympify(records["Q[1]"].truth) + 3 * g * (theta - sp.pi) / (2 * l)) == 0
    assert "314159" not in records["Q[1]"].truth


@pytest.mark.parametrize("error", [None, "sign", "dropped"])
def test_velocity_products_a_linearised_document_keeps_are_compared_in_full(tmp_path, error):
    r"""The cart-pole's nonlinear equations (Florian 2007, :mod:`published_forms`) declared
    linearised about the upright pole: its one velocity product, the centripetal
    m l θ̇² sin θ, vanishes at θ = 0 right or wrong. Written right, the file agrees; with its
    sign reversed it differs, the product named with the sign; with the coupling m l cos θ ẍ
    dropped from the pole's equation it differs in A (the control: an error the
    linearisation sees itself)."""
    import published_forms as P
    from wheeled_dyn.compare.engine import ComparisonEngine
    from wheeled_dyn.derivations import load_derivation
    path = P.write(tmp_path, "pole", "equations", error)
    path.write_text(path.read_text().replace(
        "[assumes]\n", "[assumes]\nlinearised_about = { x = 0.0, theta = 0.0 }\n"))
    result = ComparisonEngine(samples=200, param_sets=3, seed=2026).compare(
        load_derivation(path))
    assert result.equivalent is (error is None), [(r.element, r.texts) for r in result.records
                                                  if r.verdict != Verdict.AGREES]
    if error == "sign":
        product = next(r for r in result.records if r.element == "h[1]:dtheta*dtheta")
        assert product.verdict == Verdict.DIFFERS and K.SIGN in product.kinds
        assert any(c.kind == "sign" and "h[1]:dtheta*dtheta" in c.elements
                   for c in result.causes), result.causes


def test_a_velocity_product_with_a_number_for_its_coefficient_differs_as_linearised(tmp_path):
    r"""The same file with its centripetal term frozen to a number times θ̇² (m l θ̇², no
    sin θ): no second judgement is needed — linearised, the truth has no velocity product
    and the document's differs there already."""
    import published_forms as P
    from wheeled_dyn.compare.engine import ComparisonEngine
    from wheeled_dyn.derivations import load_derivation
    path = P.write(tmp_path, "pole", "equations", None)
    text = path.read_text()
    assert text.count("dtheta**2*l*m*sin(theta)") == 1
    path.write_text(text.replace("dtheta**2*l*m*sin(theta)", "dtheta**2*l*m").replace(
        "[assumes]\n", "[assumes]\nlinearised_about = { x = 0.0, theta = 0.0 }\n"))
    result = ComparisonEngine(samples=200, param_sets=3, seed=2026).compare(
        load_derivation(path))
    assert result.equivalent is False
    product = next(r for r in result.records if r.element == "h[1]:dtheta*dtheta")
    assert product.verdict == Verdict.DIFFERS, product.texts
