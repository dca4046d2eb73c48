r"""Equations of motion of systems no shipped document covers, in the forms authors publish
them (:mod:`published_forms`: a two-link arm after Spong, Hutchinson & Vidyasagar; a cart-pole
after Florian 2007 and Barto, Sutton & Anderson 1983), each written by SymPy from the same
source equations:

- every correct form is right as a system (its equations equivalent to the truth's) and every
  element agrees in the frame the form is written in;
- each form with one planted error (made in the source equations, before the form is derived)
  is not equivalent; where the form keeps the terms apart (written out, matrices, a row
  divided or replaced by a combination, Kane's), exactly the elements whose printed
  expression the error changed are flagged — an independent oracle: SymPy compares the
  element's expression in the file with and without the error — and each is named by the
  error's kind; in the solved forms the error is flagged where it lands and named in the
  document's symbols.
"""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

import published_forms as P
from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import DiagnosisKind as K
from wheeled_dyn.compare.sides.elements import element_expr, element_label
from wheeled_dyn.derivations import load_derivation

#: Engine grid.
SAMPLES, PARAM_SETS = 200, 3
ARM_FORMS = ("equations", "matrices", "solved", "simulation", "divided", "combined", "kane")
POLE_FORMS = ("equations", "divided", "solved", "kane")
#: Forms that solve for the accelerations (an error lands in every element it reaches).
SOLVED = ("solved", "simulation")
#: The diagnosis kind that names each planted error.
KIND = {("arm", "sign"): K.SIGN, ("arm", "factor"): K.FACTOR,
        ("arm", "dropped"): K.POINT_MASS, ("arm", "swap"): K.SWAP, ("arm", "gravity"): K.MISSING,
        ("pole", "point_mass"): K.POINT_MASS, ("pole", "sign"): K.SIGN,
        ("pole", "dropped"): K.MISSING, ("pole", "trig"): K.SWAP}


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)


def _cases(errors: bool) -> list:
    out = []
    for system, forms, kinds in (("arm", ARM_FORMS, P.ARM_ERRORS),
                                 ("pole", POLE_FORMS, P.POLE_ERRORS)):
        for form in forms:
            out += [(system, form, e) for e in kinds] if errors else [(system, form)]
    return out


def _expressions(path) -> dict[str, sp.Expr]:
    r"""Every element's expression as the file prints it (A, C, Q, B and h's products)."""
    d = load_derivation(path)
    terms = d.read_off(assume=True, unscale=False)
    exprs = {"A": terms.A, "Q": terms.Q, "B": terms.B, "h": terms.h, "C": d.C}
    n, out = d.n, {}
    for key in ("A", "C", "B"):
        M = exprs[key]
        if M is not None:
            out.update({element_label(key, (i, j), d.velocities): M[i, j]
                        for i in range(n) for j in range(M.shape[1])})
    out.update({element_label("Q", (i,), d.velocities): terms.Q[i] for i in range(n)})
    out.update({element_label("h", (i, j, k), d.velocities):
                element_expr(exprs, "h", (i, j, k), d.velocities)
                for i in range(n) for j in range(n) for k in range(j, n)})
    return out


#: Random points at which the two printed expressions of an element are compared, and the
#: relative difference that counts as a change.
ORACLE_POINTS, ORACLE_TOL = 3, 1e-9


def _changed(right, wrong) -> set[str]:
    r"""The elements whose printed expression the planted error changed: the expressions
    with and without it evaluated by SymPy at random values of every name (seeded)."""
    a, b = _expressions(right), _expressions(wrong)
    names = sorted(set().union(*(sp.sympify(x).free_symbols for x in (*a.values(),
                                                                      *b.values()))), key=str)
    rng = np.random.default_rng(SEED)
    points = [dict(zip(names, rng.uniform(0.3, 1.3, len(names)))) for _ in range(ORACLE_POINTS)]
    out = set()
    for e in a:
        for point in points:
            va, vb = (complex(sp.sympify(x).evalf(subs=point)) for x in (a[e], b[e]))
            if abs(va - vb) > ORACLE_TOL * max(abs(va), abs(vb), 1.0):
                out.add(e)
                break
    return out


@pytest.mark.parametrize("system, form", _cases(False))
def test_every_correct_form_agrees(engine, tmp_path, system, form):
    result = engine.compare(load_derivation(P.write(tmp_path, system, form, None)))
    wrong = [(r.element, r.verdict, r.texts) for r in result.records
             if r.verdict not in ("agrees", "factorization")]
    assert not wrong, wrong
    assert result.equivalent is True, [e.texts for e in result.equations]
    assert not any(c.kind in ("sign", "factor", "swap", "missing_physics", "point_mass",
                              "not_equivalent") for c in result.causes), result.causes


@pytest.mark.parametrize("system, form, error", _cases(True))
def test_a_planted_error_is_flagged_where_it_is_and_named(engine, tmp_path, system, form,
                                                          error):
    right = P.write(tmp_path, system, form, None)
    wrong_path = P.write(tmp_path, system, form, error)
    result = engine.compare(load_derivation(wrong_path))
    assert result.equivalent is False
    flagged = {r.element: r for r in result.records
               if r.verdict not in ("agrees", "factorization")}
    changed = _changed(right, wrong_path)
    assert flagged, changed
    kind = KIND[(system, error)]
    if form not in SOLVED:
        assert set(flagged) == changed, (set(flagged), changed)
        for element, r in flagged.items():
            assert kind in r.kinds, (element, r.texts)
        return
    rows = {int(e.split("[")[1].split("]")[0].split(",")[0]) for e in changed}
    assert all(int(e.split("[")[1].split("]")[0].split(",")[0]) in rows for e in flagged)
    named = " ".join(t for r in flagged.values() for t in r.texts) + " " + " ".join(
        t for e in result.equations for t in e.texts)
    if system == "arm" and error in ("dropped", "swap"):
        # the inertia the document inverted, read back from its inputs' coefficients
        assert "the inertia matrix the document inverted" in named, named
        assert ("truth − document = I1" if error == "dropped" else "lc1**2*m2") in named
    else:                 # the pole's point mass too (read back from its solved form)
        assert any(kind in r.kinds for r in flagged.values()), named


def test_the_arm_divided_by_its_inertia_names_the_divisor(engine, tmp_path):
    result = engine.compare(load_derivation(P.write(tmp_path, "arm", "divided", None)))
    assert result.equations[1].frame == "the true equation divided by I2 + lc2**2*m2"
    assert result.row_functions[1] == "1/(I2 + lc2**2*m2)"


def test_the_pole_equation_divided_by_m_l_is_consistent_in_its_units(engine, tmp_path):
    r"""The textbook's pole equation divided by m l: a row scaled by a dimensional factor is
    consistent in itself (no unit finding)."""
    result = engine.compare(load_derivation(P.write(tmp_path, "pole", "divided", None)))
    assert not any(K.DIMENSION in r.kinds for r in result.records)
    assert "divided by l*m" in result.equations[1].frame


@pytest.mark.parametrize("form", ["equations", "kane"])
def test_a_point_mass_for_the_pole_is_named_as_such(engine, tmp_path, form):
    r"""The point-mass pendulum's m l² for the uniform pole's 4/3 m l²: not only "factor
    3/4" but the pole's own inertia about its centre missing, and that is the cause; its
    moment written positive in Kane's form too (it was "-l**2*m/3": that row is −1 × the
    true one)."""
    result = engine.compare(load_derivation(P.write(tmp_path, "pole", form, "point_mass")))
    (record,) = [r for r in result.records if r.verdict == "differs"]
    assert record.kinds[0] == K.POINT_MASS and "pole" in record.texts[0], record.texts
    assert "(l**2*m/3 in the document's symbols)" in record.texts[0], record.texts
    assert any(c.kind == "point_mass" and record.element in c.elements for c in result.causes)


@pytest.mark.parametrize("form", ["equations", "matrices", "kane"])
def test_a_point_mass_link_in_every_inertia_is_named_in_every_form(engine, tmp_path, form):
    r"""Link 2 a point mass: I2 lacking from all four elements of A, so no two elements of a
    row share a ratio with the truth. In Kane's form (both rows negated) the rows were read
    as 0.81 × the true one (an element of A's own ratio) and as the true one: the right
    velocity, gravity and input terms "differed" by 1.234 or by their sign, and the
    inertias were "right if link 2 is uniform". The terms' common ratio, −1, is the row's."""
    result = engine.compare(load_derivation(P.write(tmp_path, "arm", form, "point_mass2")))
    wrong = {r.element for r in result.records if r.verdict != "agrees"}
    assert wrong == {"A[1,1]", "A[1,2]", "A[2,1]", "A[2,2]"}, [
        (r.element, r.texts) for r in result.records if r.verdict != "agrees"]
    assert all(r.kinds[0] == K.POINT_MASS for r in result.records if r.element in wrong)
    # the body named: link 2, not "the body"
    assert all("the document treats link2 as a point mass" in r.texts[0]
               for r in result.records if r.element in wrong)


def test_a_row_with_the_reaction_eliminated_names_an_error_of_its_own_terms(engine, tmp_path):
    r"""The cart's equation with the pole's reaction eliminated, eq1 − (3 cos θ/(4l)) eq2 (the
    weights are simple expressions of the document's names: the form's own combination, as
    good as a constant). Right, it agrees; the centripetal sign flipped in it, or its gravity
    term (3/4) m g sin θ cos θ written with 1/4, has exactly that element flagged and named —
    not the row's inertia elements, which agree in that frame. (An error in the pole's own
    equation, carried into the combined row with it, is not yet undone there.)"""
    right = P.write(tmp_path, "pole", "combined", None)
    result = engine.compare(load_derivation(right))
    assert result.equivalent is True and all(r.verdict == "agrees" for r in result.records)
    sign = P.write(tmp_path, "pole", "combined", "sign")
    flagged = {r.element: r for r in engine.compare(load_derivation(sign)).records
               if r.verdict != "agrees"}
    assert set(flagged) == {"h[1]:dtheta*dtheta"}, set(flagged)
    assert K.SIGN in flagged["h[1]:dtheta*dtheta"].kinds
    text = right.read_text()
    gravity = "- (3*cos(theta)/(4*l))*("
    assert gravity in text
    wrong = tmp_path / "pole_combined_gravity.toml"
    wrong.write_text(text.replace(gravity, "- (3*cos(theta)/(4*l))*(g*l*m*sin(theta)*2/3 + ", 1))
    flagged = {r.element: r for r in engine.compare(load_derivation(wrong)).records
               if r.verdict != "agrees"}
    assert set(flagged) == {"Q[1]"}, set(flagged)
    assert set(flagged["Q[1]"].kinds) & {K.FACTOR, K.EXTRA, K.MISSING}, flagged["Q[1]"].texts


@pytest.mark.parametrize("units", [True, False])
def test_a_mass_written_for_another_is_named_with_or_without_units(engine, tmp_path, units):
    r"""The cart's mass M written for the pole's m in the pole's gravity term. A file that
    declares no units still says which symbols are masses (``M = "M(cart)"``,
    ``m = "M(pole)"``): it was "the document lacks a factor m/M" without units."""
    import re
    path = P.write(tmp_path, "pole", "equations", None)
    text = path.read_text().replace("- g*l*m*sin(theta)", "- M*g*l*sin(theta)")
    if not units:
        text = re.sub(r', units = "[^"]*"', "", text)
    path.write_text(text)
    result = engine.compare(load_derivation(path))
    (record,) = [r for r in result.records if r.verdict == "differs"]
    assert record.element == "Q[2]" and record.kinds[0] == K.SWAP, record.texts
    assert record.texts[0] == "swap: M where m fits", record.texts


#: What the arm's equations, read back before they were solved, say of each planted error.
READ_BACK = {"sign": "h[1]:dq2*dq2: the document has the opposite sign",
             "factor": "h[1]:dq1*dq2: the document is 1/2 × the truth",
             "dropped": "A[1,1]: the moment of inertia Iyy(link1) about its own centre of mass "
                        "is missing, a point mass (truth − document = I1)",
             "swap": "A[1,1]: l1 and lc1, one written where the other fits",
             "gravity": "Q[2]: the document has 0 (truth − document = g*lc2*m2*cos(q1 + q2))"}


@pytest.mark.parametrize("form", SOLVED)
@pytest.mark.parametrize("error", P.ARM_ERRORS)
def test_every_element_a_solved_error_reaches_names_it(engine, tmp_path, form, error):
    r"""One planted error of the source equations reaches many elements of a solved form, each
    a rational function of every parameter: every element flagged names it — by its own
    diagnosis of the error's kind, or by the equations read back before solving (the term
    as the author wrote it: "A[1,1] truth − document = I1") — none is left unnamed ("no
    single-term diagnosis") or named only by a residual of many terms."""
    result = engine.compare(load_derivation(P.write(tmp_path, "arm", form, error)))
    flagged = [r for r in result.records if r.verdict not in ("agrees", "factorization")]
    assert flagged
    for r in flagged:
        assert KIND[("arm", error)] in r.kinds or READ_BACK[error] in r.texts[0], \
            (r.element, r.texts)


@pytest.mark.parametrize("error", ["point_mass", "dropped", "sign"])
def test_the_cart_row_less_the_pole_row_names_the_error_in_its_frame(engine, tmp_path, error):
    r"""The cart-pole with the pole's reaction eliminated from the cart's equation
    (eq1 − (3 cos θ/(4l))·eq2, weights that are functions of the state) and an error in what
    was combined: the row is read in that frame — its weights simple expressions of the
    document's names, as good as a constant — and only the elements the error changed are
    flagged and named (a point mass was read in the true eq1's frame, with a term "the
    truth does not have" and a factor 1/4 beside it). A cos written for a sin is left out:
    in the combined row it is "a factor sin θ/cos θ" missing, not a swap."""
    test_a_planted_error_is_flagged_where_it_is_and_named(engine, tmp_path, "pole",
                                                          "combined", error)
    result = engine.compare(load_derivation(P.write(tmp_path, "pole", "combined", error)))
    assert result.equations[0].frame.startswith("= eq1 - 3*eq2*cos(theta)/(4*l)"), \
        result.equations[0].frame


def test_a_form_solved_second_acceleration_first_names_each_equation_by_its_own(engine,
                                                                                 tmp_path):
    r"""Simulation code prints :math:`\ddot q_2 = \dots` first: its first equation is
    q2's (its row of the document's A is q2's unit row), named so, whatever the order of the
    positions; the second, q1's written with :math:`\ddot q_2` in it, keeps its place."""
    result = engine.compare(load_derivation(P.write(tmp_path, "arm", "simulation", None)))
    labels = [e.label for e in result.equations]
    assert labels == ["equation 1 (q2)", "equation 2 (q1)"], labels


def test_a_tiny_combination_weight_is_said_as_the_number_it_is(engine, tmp_path):
    r"""The elbow's equation plus 10⁻⁶ × the shoulder's (right): it agrees, and its frame is
    said ``eq1/1000000 + eq2``, not ``eq1/(1000000*sin(q2)**2 + 1000000*cos(q2)**2)`` (the
    weight's fit, where round-off leaves the constant weight varying by a part in 10⁹)."""
    path = P.write(tmp_path, "arm", "equations", None)
    (l1, r1), (l2, r2) = (e.split(" = ") for e in P.arm_forms()["equations"])
    text = path.read_text()
    path.write_text(text.replace(f"{l2} = {r2}", f"{l2} + ({l1})/1000000 = {r2} + ({r1})/1000000"))
    result = engine.compare(load_derivation(path))
    assert result.equivalent is True
    assert result.equations[1].frame == "= eq1/1000000 + eq2 (eq k: the true equation k)", \
        result.equations[1].frame


def test_symbols_without_units_group_by_the_parameters_they_name(engine, tmp_path):
    r"""A file (or the Python API) that declares no units and maps a hanging arm's lengths as
    ``lc2 = "-CZ(link2)"`` (a number times one link parameter): lc1 written for lc2 in the
    elbow's own inertia is named "lc1 where lc2 fits" (it was "lacks lc2**2*m2; has
    lc1**2*m2 too much", a term missing, since only a bare parameter call grouped symbols)."""
    from wheeled_dyn.compare.sides.elements import swap_groups
    path = tmp_path / "acrobot_no_units.toml"
    text = (P.DATA / "acrobot_simulation.toml").read_text()
    for name in ("lc1", "lc2", "l1"):
        line = next(x for x in text.splitlines() if x.startswith(f"{name} ="))
        text = text.replace(line, line.replace(', units = "m"', ""))
    text = text.replace('l1 = { value = "l1" }', 'l1 = { value = "-origin_z(elbow)" }')
    for name in ("acrobot.toml", "acrobot.urdf"):
        (tmp_path / name).write_text((P.DATA / name).read_text())
    path.write_text(text)
    d = load_derivation(path)
    lengths = next(g for g in swap_groups(d) if d.namespace["lc1"] in g)
    assert {str(s) for s in lengths} >= {"lc1", "lc2", "l1"}, lengths
