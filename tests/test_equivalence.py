r"""What decides that a document's equations are right: their equivalence to the true ones.

- Linearised documents are compared with the truth's linearisation at the stated point: a
  pendulum with ten times its stiffness, or with the sign that makes the hanging rod
  unstable, differs (the stiffness K = ∂Q/∂q is compared; it never was before);
- second-order relations a document derives from its linearised equations (seed 000's 7.2:
  part (c)'s K is right, part (e)'s k has the wrong sign);
- an equation multiplied by a function that vanishes somewhere (0 = 0 at θ = 0) is not
  equivalent; an equation replaced by another times cos θ (one equation lost) is not either,
  and neither crashes;
- the equivalence verdict is the system's: an equation right but for its scale is right.

The pendulum is seed 000's 4.4 rod (the shipped ``rod_pendulum`` model): mass m, length l,
:math:`\tfrac13ml^2\ddot\theta + \tfrac12mgl\sin\theta = 0`, linearised about θ = 0.
"""

from __future__ import annotations

import numpy as np
import pytest

from conftest import SEED
from shipped_copies import published_copy
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.judge import equivalence
from wheeled_dyn.compare.records import DiagnosisKind as K
from wheeled_dyn.compare.steps.records import compare_steps
from wheeled_dyn.derivations import builtin_derivations, load_derivation

SAMPLES, PARAM_SETS = 200, 3

ROD = '''title = "Rod pendulum ({name})"
model = "rod_pendulum"
[coordinates]
positions = ["theta"]
kind = "holonomic"
rolling = "none"
configuration = {{ theta = "theta" }}
units = {{ theta = "rad" }}
[symbols]
m = {{ value = "4*MZ(rod)**2/(3*YY(rod))", units = "kg" }}
l = {{ value = "-3*YY(rod)/(2*MZ(rod))", units = "m" }}
g = {{ value = "g", units = "m/s**2" }}
[assumes]
families = ["urdf_structure"]
{assumes}
[matrices]
equations = ["{equation}"]
'''


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)


def _rod(engine, tmp_path, name, equation, linearised=True):
    path = tmp_path / f"{name}.toml"
    path.write_text(ROD.format(name=name, equation=equation, assumes=(
        "linearised_about = { theta = 0.0 }" if linearised else "")))
    return engine.compare(load_derivation(path))


def test_linearised_pendulum_agrees(engine, tmp_path):
    result = _rod(engine, tmp_path, "right", "1/3*m*l**2*ddtheta + m*g*l/2*theta = 0")
    assert result.equivalent is True
    assert {r.element for r in result.records} >= {"A[1,1]", "K[1,1]", "Q[1]"}
    assert all(r.verdict == "agrees" for r in result.records)


@pytest.mark.parametrize("equation, term", [
    ("1/3*m*l**2*ddtheta + m*g*l/2*sin(theta) = 0", "Q[1] = g*l*m*sin(theta)/2"),
    ("1/3*m*l**2*ddtheta + m*g*l/2*theta - 5*m*g*l*theta**2 = 0", "Q[1] = "),
])
def test_equations_declared_linearised_that_are_not_say_so(engine, tmp_path, equation, term):
    r"""The file declares its equations linearised, but they are not linear in the deviation:
    compared at the point, to first order, they agree (a higher-order term, right or wrong,
    is not seen there: a probe's cart-pole with its centripetal term's sign wrong agreed with
    nothing said), and the first cause says which terms are not linear."""
    from wheeled_dyn.compare.records import CauseKind
    result = _rod(engine, tmp_path, "nonlinear", equation)
    assert result.equivalent is True
    first = result.causes[0]
    assert first.kind == CauseKind.FILE_ERROR, result.causes
    assert "not linear in the deviations" in first.explanation and term in first.explanation
    right = _rod(engine, tmp_path, "linear", "1/3*m*l**2*ddtheta + m*g*l/2*theta = 0")
    assert not any(c.kind == CauseKind.FILE_ERROR for c in right.causes), right.causes


@pytest.mark.parametrize("equation, kind, factor", [
    ("1/3*m*l**2*ddtheta + 10*m*g*l/2*theta = 0", K.FACTOR, "10"),
    ("1/3*m*l**2*ddtheta - m*g*l/2*theta = 0", K.SIGN, "-1"),      # the hanging rod unstable
])
def test_a_wrong_stiffness_differs(engine, tmp_path, equation, kind, factor):
    result = _rod(engine, tmp_path, "wrong", equation)
    assert result.equivalent is False
    (record,) = [r for r in result.records if r.verdict != "agrees"]
    assert record.element == "K[1,1]" and record.kinds[0] == kind, record.texts
    assert record.diagnoses[0].factor == factor


def test_second_order_relations_of_7_2(tmp_path):
    r"""Part (c)'s Δq'' + K Δq = 0 agrees; part (e)'s q'' + k q = 0 prints k with the wrong
    sign: each of its two relations differs by the sign of its q (r) term."""
    path = builtin_derivations("seed000")[0].parent / "p7_2_linearised_steps.toml"
    records = {r.element: r for r in compare_steps(load_derivation(path), SEED)}
    part_c = [r for e, r in records.items() if e.startswith("(c)")]
    part_e = [r for e, r in records.items() if e.startswith("7.2 (e) (3), (4)")]
    assert len(part_c) == len(part_e) == 2
    assert all(r.verdict == "agrees" for r in part_c), [r.texts for r in part_c]
    assert all(r.verdict == "differs" for r in part_e)
    assert [r.diagnoses[0].product for r in part_e] == ["q", "r"]
    assert all(r.kinds[0] == K.SIGN for r in part_e), [r.texts for r in part_e]


def test_an_equation_multiplied_by_a_vanishing_factor_is_not_equivalent(engine, tmp_path):
    r"""sin θ × the pendulum's equation: 0 = 0 at θ = 0, so the equations are not equivalent
    there — never "divided by a quantity that does not vanish"."""
    result = _rod(engine, tmp_path, "times_sin", "sin(theta)*(1/3*m*l**2*ddtheta + "
                  "m*g*l/2*sin(theta)) = 0", linearised=False)
    assert result.equivalent is False
    (equation,) = result.equations
    assert equation.verdict == "differs"
    assert K.SINGULAR in [d.kind for d in equation.diagnoses], equation.texts
    assert any(c.kind == "not_equivalent" for c in result.causes), result.causes


@pytest.mark.parametrize("factor", ["(cos(theta) - 1/2)**2", "(theta - 1)**2",
                                    "(sin(theta) - 3/10)**4"])
def test_an_equation_times_a_factor_touching_zero_is_not_equivalent(engine, tmp_path, factor):
    r"""A factor that vanishes without changing sign, away from the special positions
    (:math:`\theta = \pi/3`, 1, asin 0.3): 0 = 0 there, the equation lost. Its determinant
    has one sign at every sample, and a row scaled to 1 hides it: it "agreed". The engine
    searches the state where the row is least and finds its zero
    (:mod:`wheeled_dyn.compare.engine.special`)."""
    result = _rod(engine, tmp_path, "touching", f"{factor}*(1/3*m*l**2*ddtheta + "
                  "m*g*l/2*sin(theta)) = 0", linearised=False)
    assert result.equivalent is False
    (equation,) = result.equations
    assert K.SINGULAR in [d.kind for d in equation.diagnoses], equation.texts


@pytest.mark.parametrize("factor", ["(21/20 + cos(theta))", "(2 + cos(theta))**2",
                                    "(theta**2 + 1/100)"])
def test_a_factor_near_zero_that_does_not_vanish_is_right(engine, tmp_path, factor):
    r"""The same search on factors that come near zero but never reach it (1/20, 1/100 at
    their least): the equation is the true one times them, right."""
    result = _rod(engine, tmp_path, "near", f"{factor}*(1/3*m*l**2*ddtheta + "
                  "m*g*l/2*sin(theta)) = 0", linearised=False)
    assert result.equivalent is True, [c.explanation for c in result.causes]


def test_a_combination_whose_weights_become_dependent_is_not_equivalent(engine, tmp_path):
    r"""The arm's second equation replaced by its first plus :math:`(\cos q_2 - \tfrac12)^2`
    × its second: no row vanishes, but at :math:`q_2 = \pm\pi/3` the two are the same
    equation (det W touches zero without changing sign)."""
    import published_forms as P
    path = P.write(tmp_path, "arm", "equations", None)
    text = path.read_text()
    first, second = (line.strip().strip('",') for line in
                     text.split("equations = [")[1].split("]")[0].strip().splitlines())
    (l1, r1), (l2, r2) = first.split(" = "), second.split(" = ")
    f = "(cos(q2) - 1/2)**2"
    path.write_text(text.replace(second, f"{l1} + {f}*({l2}) = {r1} + {f}*({r2})"))
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    assert any(K.SINGULAR in [d.kind for d in e.diagnoses] for e in result.equations)


def test_an_equation_divided_by_a_function_that_does_not_vanish_is_right(engine, tmp_path):
    result = _rod(engine, tmp_path, "over_2_plus_cos", "(1/3*m*l**2*ddtheta + "
                  "m*g*l/2*sin(theta))/(2 + cos(theta)) = 0", linearised=False)
    assert result.equivalent is True
    assert all(r.verdict == "agrees" for r in result.records)


def test_an_equation_replaced_by_another_times_cos_is_not_equivalent(engine, tmp_path):
    r"""The arm's second equation replaced by cos(q2) × its first: W is singular everywhere
    (an equation lost): not equivalent, named, and no crash."""
    import published_forms as P
    path = P.write(tmp_path, "arm", "equations", None)
    text = path.read_text()
    first, second = (line.strip().strip('",') for line in
                     text.split("equations = [")[1].split("]")[0].strip().splitlines())
    lhs, rhs = first.split(" = ")
    text = text.replace(second, f"cos(q2)*({lhs}) = cos(q2)*({rhs})")
    path.write_text(text)
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    assert any(K.SINGULAR in [d.kind for d in e.diagnoses] for e in result.equations)


def test_overflow_never_decides():
    r"""A term overflowing to inf at some samples: the equation is undecided where it agrees
    elsewhere, and differs where a finite sample already differs — inf is never a scale."""
    rng = np.random.default_rng(SEED)
    S, n = 60, 2
    A = np.eye(n) + 0.1 * rng.normal(size=(S, n, n))
    A = A @ np.swapaxes(A, 1, 2)
    nvec = rng.normal(size=(S, n))
    truth = equivalence.Side(A, nvec, None)
    doc = nvec.copy()
    doc[:3, 0] = np.inf
    decision = equivalence.decide(equivalence.Side(A.copy(), doc, None), truth, 2)
    assert decision.equations[0].verdict == "undecided"
    assert decision.equations[1].verdict == "agrees"
    doc[10:, 0] += 1.0                                   # and wrong where finite
    decision = equivalence.decide(equivalence.Side(A.copy(), doc, None), truth, 2)
    assert decision.equations[0].verdict == "differs"
    assert np.isfinite(decision.equations[0].max_error)


def test_an_equation_divided_by_a_vanishing_factor_is_the_one_named(engine, tmp_path):
    r"""The arm's second equation divided by cos(q2): undefined where cos(q2) = 0, so the
    equations are not equivalent there — and it is that equation, not the untouched first,
    that is named (det W changes sign through a pole, not a zero)."""
    import published_forms as P
    path = P.write(tmp_path, "arm", "equations", None)
    text = path.read_text()
    second = [line.strip().strip('",') for line in
              text.split("equations = [")[1].split("]")[0].strip().splitlines()][1]
    lhs, rhs = second.split(" = ")
    path.write_text(text.replace(second, f"({lhs})/cos(q2) = ({rhs})/cos(q2)"))
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    first, divided = result.equations
    assert first.verdict == "agrees", first.texts
    assert divided.verdict == "differs"
    assert K.SINGULAR in [d.kind for d in divided.diagnoses], divided.texts
    assert "unbounded" in next(d.text for d in divided.diagnoses if d.kind == K.SINGULAR)
    from wheeled_dyn.report.markdown import summary_lines
    assert summary_lines(result)[0].endswith("; not right as a system")  # though 0 differ


@pytest.mark.parametrize("pole", [True, False])
def test_a_sign_change_through_a_pole_or_a_zero_names_its_equation(pole):
    r"""W = diag(1, f(θ)) with f = 1/cos θ (a pole) or cos θ (a zero), θ drawn at random: the
    second equation is the one named either way, and the kind is told apart."""
    theta = np.random.default_rng(SEED).uniform(-np.pi, np.pi, 400)
    f = 1 / np.cos(theta) if pole else np.cos(theta)
    W = np.zeros((len(theta), 2, 2))
    W[:, 0, 0], W[:, 1, 1] = 1.0, f
    W[:, 0, 1] = 0.3 * np.sin(theta)                 # a weight that does not vanish with f
    rows, through_pole = equivalence.sign_changes(W, 1)
    assert rows == (1,) and through_pole is pole


@pytest.mark.parametrize("printed, agrees", [("2*", True), ("", False)])
def test_a_declared_row_scale_binds(engine, tmp_path, printed, agrees):
    r"""``[rows] scale = ["2"]``: the file says the document printed 2 × the true equation.
    Printed so, it agrees (and no undeclared factor is reported); printed unscaled, the
    equation is right in itself but not as declared: it differs as declared, and a
    ``file_error`` cause says the declaration is probably wrong and claims its elements,
    which say they differ only as declared — no term of theirs is diagnosed (a factor 1/2)
    and no power identity is read through the declared scale."""
    path = tmp_path / "declared.toml"
    path.write_text(ROD.format(name="declared", assumes="", equation=(
        f"{printed}(1/3*m*l**2*ddtheta + m*g*l/2*sin(theta)) = 0")) + '[rows]\nscale = ["2"]\n')
    result = engine.compare(load_derivation(path))
    (equation,) = result.equations
    assert result.row_factors == (None,)
    if agrees:
        assert result.equivalent is True and equation.verdict == "agrees"
        assert not any(c.kind == "file_error" for c in result.causes)
        return
    assert result.equivalent is False and equation.verdict == "differs"
    assert K.DECLARED in [d.kind for d in equation.diagnoses]
    (cause,) = [c for c in result.causes if c.kind == "file_error"]
    differing = [r for r in result.records if r.verdict != "agrees"]
    assert differing and {r.element for r in differing} <= set(cause.elements), cause
    assert all(r.diagnoses[0].kind == K.DECLARED and {d.kind for d in r.diagnoses}
               <= {K.DECLARED, K.RESIDUAL} for r in differing), differing
    assert [c for c in result.causes if set(c.elements) & {r.element for r in differing}] \
        == [cause], result.causes
    assert result.energy is not None and result.energy.conserves, result.energy


#: The double pendulum's first equation declared twice the true one.
SCALED = ("[matrices]", '[rows]\nscale = ["2", "1"]\n\n[matrices]')


def test_a_contradicted_row_scale_leaves_the_power_identity_to_the_other_rows(engine,
                                                                              tmp_path):
    r"""The double pendulum with springs (``data/published``), its first equation declared
    twice the true one but printed as it is, its second with the sign of its centripetal
    term flipped: the power identity is read with the first row as printed, and the second
    row's gyroscopic term that does work is said (it was not checked at all)."""
    path = published_copy(tmp_path, "double_pendulum", "double_pendulum_springs",
                          ("- m2*L1*a2*sin(th1 - th2)*dth1**2",
                           "+ m2*L1*a2*sin(th1 - th2)*dth1**2"), SCALED)
    result = engine.compare(load_derivation(path))
    assert any(c.kind == "file_error" for c in result.causes), result.causes
    assert result.energy is not None and not result.energy.conserves, result.energy


#: The double pendulum's two equations, as the file prints them.
FIRST = ("(J1 + m2*L1**2)*ddth1 + m2*L1*a2*cos(th1 - th2)*ddth2 + m2*L1*a2*sin(th1 - th2)*dth2**2"
         " + m1*a1*g*sin(th1) + m2*L1*g*sin(th1) + k1*(th1 - r1) - k2*(th2 - th1 - r2) = T1 - T2")
SECOND = ("m2*L1*a2*cos(th1 - th2)*ddth1 + (I2 + m2*a2**2)*ddth2 - m2*L1*a2*sin(th1 - th2)*"
          "dth1**2 + m2*a2*g*sin(th2) + k2*(th2 - th1 - r2) = T2")


@pytest.mark.parametrize("reordered", [False, True])
def test_a_row_scale_declares_the_equation_of_its_position(engine, tmp_path, reordered):
    r"""The double pendulum's second equation multiplied by 2: declared ``["1", "2"]`` in the
    order of the positions it agrees; printed first and declared ``["2", "1"]`` in the
    printed order, the declaration binds (equation 1 declared twice the true equation 1)
    and its cause says what the equation is — the true equation 2 times 2 — and how the
    scales are ordered."""
    doubled = f"2*({SECOND.split(' = ')[0]}) = 2*T2"
    rows = f'  "{doubled}",\n  "{FIRST}",' if reordered else f'  "{FIRST}",\n  "{doubled}",'
    scale = '["2", "1"]' if reordered else '["1", "2"]'
    path = published_copy(tmp_path, "double_pendulum", "double_pendulum_springs",
                          (f'  "{FIRST}",\n  "{SECOND}",', rows),
                          ("[matrices]", f'[rows]\nscale = {scale}\n\n[matrices]'))
    result = engine.compare(load_derivation(path))
    assert result.equivalent is (not reordered)
    if not reordered:
        return
    (cause,) = [c for c in result.causes if c.kind == "file_error"
                and "declares equation 1" in c.explanation]
    assert "true equation 2 times 2" in cause.explanation
    assert "in the order of the positions" in cause.explanation


def test_a_row_scaled_in_part_only_names_the_elements_scaled(engine, tmp_path):
    r"""The double pendulum's first equation declared twice the true one, only its right side
    (the inputs) doubled: its cause says the inputs' elements are as declared and the others
    as printed — where it said "but for those named on their own" and named none."""
    lhs, rhs = FIRST.split(" = ")
    path = published_copy(tmp_path, "double_pendulum", "double_pendulum_springs",
                          (FIRST, f"{lhs} = 2*({rhs})"),
                          ("[matrices]", '[rows]\nscale = ["2", "1"]\n\n[matrices]'))
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    (cause,) = [c for c in result.causes if c.kind == "file_error"
                and "declares equation 1" in c.explanation]
    assert "but for B[1,1], B[1,2], as declared" in cause.explanation, cause.explanation
    assert "in part only" in cause.explanation


@pytest.mark.parametrize("declared", [False, True], ids=["undeclared", "declared-twice"])
def test_a_term_error_in_a_row_that_contradicts_its_declared_scale_is_named(engine, tmp_path,
                                                                             declared):
    r"""The double pendulum with springs, the sign of its first equation's centripetal term
    flipped; declared twice the true one but printed as it is, every element of the row
    differs as declared: the right ones say they differ only as declared, a ``file_error``
    cause claims them, and the flipped term is named as printed, its sign (it was "the
    document is −1/2 × the truth", and every right element "1/2 × the truth"); the power
    identity reads the row as printed, as without the declaration."""
    path = published_copy(tmp_path, "double_pendulum", "double_pendulum_springs",
                          ("+ m2*L1*a2*sin(th1 - th2)*dth2**2",
                           "- m2*L1*a2*sin(th1 - th2)*dth2**2"), *([SCALED] if declared else []))
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    (h,) = [r for r in result.records if r.element == "h[1]:dth2*dth2"]
    assert h.verdict == "differs" and h.diagnoses[0].kind == K.SIGN, h.diagnoses
    assert result.energy is not None and not result.energy.conserves
    assert "2*L1*a2*dth1*dth2**2*m2" in result.energy.residual, result.energy
    if not declared:
        return
    (cause,) = [c for c in result.causes if c.kind == "file_error"]
    row = {r.element for r in result.records if r.index[0] == 0 and r.key in "AQBh"
           and r.verdict == "differs"}
    assert {"A[1,1]", "Q[1]", "B[1,1]"} <= set(cause.elements), cause
    assert set(cause.elements) == row - {"h[1]:dth2*dth2"}, cause
    assert all(r.diagnoses[0].kind == K.DECLARED for r in result.records
               if r.element in cause.elements)


def test_constraints_stated_where_the_model_has_none_are_not_left_aside(engine, tmp_path):
    r"""The rod pendulum (no rolling) with a constraint its file states, θ̇ = 0: the model
    has no such constraint, so the document is not right, whatever its equation — the
    declaration binds, it is not set aside with a note."""
    path = tmp_path / "constrained.toml"
    path.write_text(ROD.format(name="constrained", assumes="", equation=(
        "1/3*m*l**2*ddtheta + m*g*l/2*sin(theta) = 0"))
        + '[constraints]\nequations = ["dtheta = 0"]\n')
    result = engine.compare(load_derivation(path))
    assert result.constraints_agree is False and result.equivalent is False
    assert all(e.verdict == "agrees" for e in result.equations)
    assert any(c.kind == "not_equivalent" and "does not have" in c.explanation
               for c in result.causes), result.causes


@pytest.mark.parametrize("equation, wrong", [
    ("1/3*m*l**2*ddtheta + m*g*l*sin(theta) = 0", "Q[1]"),        # gravity twice what fits
    ("2/3*m*l**2*ddtheta + m*g*l/2*sin(theta) = 0", "A[1,1]"),    # the inertia twice
    ("-(1/3*m*l**2 + m*l**2)*ddtheta - m*g*l/2*sin(theta) = 0", "A[1,1]")])   # Kane's, wrong A
def test_a_row_blames_the_term_that_is_off(engine, tmp_path, equation, wrong):
    r"""A row with one inertia: one vote against one, the inertia's ratio is the row's and
    the gravity term twice what fits is named (not the inertia "1/2 × the truth"); in Kane's
    form (the row negated) with a wrong inertia, the gravity term's −1 is the row's."""
    result = _rod(engine, tmp_path, "blame", equation, linearised=False)
    differing = {r.element for r in result.records if r.verdict != "agrees"}
    assert differing == {wrong}, [(r.element, r.texts) for r in result.records]


@pytest.mark.parametrize("factor, named", [("(M - m)**2", "(M - m)**2"), ("(M - 3*m)", "M - 3*m"),
                                           ("(M + m)", None), ("(M + 3*m)*l**2", None),
                                           ("(M + m*cos(theta)**2)", None)])
def test_an_equation_times_a_factor_of_the_masses_that_may_vanish_is_not_equivalent(
        engine, tmp_path, factor, named):
    r"""The cart-pole's pole equation (``published_forms``: Florian 2007) times a factor of
    its parameters: :math:`(M - m)^2` never changes sign and is not zero for the drawn
    parameter sets, but a cart as heavy as its pole is a cart-pole too — there the equation
    is lost (it agreed); it is named in the document's symbols. A factor that cannot vanish
    for positive masses, alone or with a length or the state, leaves it right."""
    import published_forms as P
    cart, pole = P.pole_forms(None)["equations"]
    path = tmp_path / "factor.toml"
    path.write_text(P.POLE_HEAD.format(
        form="times a factor", error="", model=P.DATA / "cart_pole.toml",
        eqs=f'  "{cart}",\n  "({factor})*({pole.removesuffix(" = 0")}) = 0"'))
    result = engine.compare(load_derivation(path))
    assert result.equivalent is (named is None), [c.explanation for c in result.causes]
    singular = [d for d in result.equations[1].diagnoses if d.kind == K.SINGULAR]
    assert (named is None) is (not singular)
    if named is not None and "**2" in factor:       # a square: only the factor's robots
        assert f"the factor {named}," in singular[0].text, singular[0].text


@pytest.mark.parametrize("weight, equivalent", [("(m1 - m2)", False), ("(I1 - 4*I2)", False),
                                                ("(m1 + m2)", True), ("(I1 + lc2**2*m2)", True)])
def test_a_combination_lost_for_some_robot_of_the_model_is_not_equivalent(engine, tmp_path,
                                                                          weight, equivalent):
    r"""The two-link arm of Spong et al. (``published_forms``) with its second equation
    replaced by eq1 + weight × eq2: :math:`\det W` is the weight, a factor of the masses no
    row shares. Where it may vanish for a robot of the model — links of other densities, or
    the two parameter sets drawn on either side of it — an equation is lost there (it agreed:
    no parameter set drawn makes it zero); where it cannot, it is a combination."""
    import published_forms as P
    first, second = (e.removesuffix(" = tau1").removesuffix(" = tau2")
                     for e in P.arm_forms(None)["equations"])
    path = tmp_path / "combined.toml"
    path.write_text(P.ARM_HEAD.format(
        form="combined", error="", model=P.DATA / "two_link_arm.toml",
        eqs=f'  "{first} = tau1",\n  "{first} + {weight}*({second}) = tau1 + {weight}*tau2"'))
    result = engine.compare(load_derivation(path))
    assert result.equivalent is equivalent, [c.explanation for c in result.causes]
    singular = any(d.kind == K.SINGULAR for e in result.equations for d in e.diagnoses)
    assert singular is not equivalent


@pytest.mark.parametrize("C, still", [("1", "1"), ("theta + m*l**2*dtheta", "theta")])
def test_a_c_element_without_a_velocity_is_no_factorisation(engine, tmp_path, C, still):
    r"""The rod pendulum's C written as 1 (or with a term free of θ̇): C q̇ has a term linear
    in θ̇, which the products of h do not see. Its element was "only the factorisation of C
    differs; C q̇ agrees" though C q̇ = θ̇ ≠ 0; it differs, the term named."""
    path = tmp_path / "c.toml"
    path.write_text(f'''title = "rod, C without a velocity"
model = "rod_pendulum"
[coordinates]
positions = ["theta"]
configuration = {{ theta = "theta" }}
[symbols]
m = "M(rod)"
l = "length(rod)"
g = "g"
[assumes]
uniform = ["rod"]
[matrices]
A = "[[m*l**2/3]]"
C = "[[{C}]]"
Q = "[m*g*l/2*sin(theta)]"
''')
    result = engine.compare(load_derivation(path))
    (c,) = [r for r in result.records if r.element == "C[1,1]"]
    assert c.verdict == "differs", c.texts
    assert any(d.kind == K.EXTRA and d.terms == (still,) for d in c.diagnoses), c.texts
    assert result.equivalent is False


@pytest.mark.parametrize("factor, equivalent", [("(Jyy - Jzz)", False), ("(Jxx - lc2**2*m2)", False),
                                                ("(Jyy + Jzz)", True)])
def test_an_equation_times_a_factor_of_one_links_inertias_is_not_equivalent(engine, tmp_path,
                                                                            factor, equivalent):
    r"""The Furuta pendulum (``data/published/furuta*``, written for the tests) with its
    pendulum's equation times a factor of that one link's inertias: Jyy − Jzz vanishes for a
    pendulum symmetric about its rod, Jxx − lc2² m2 for one whose radius of gyration about
    its centre is its centre's distance from the joint — robots of the model (rods or a mass
    added at its centre), where the equation is lost; neither vanishes for a change of its
    density alone, and both agreed. Jyy + Jzz cannot vanish."""
    from pathlib import Path
    data = Path(__file__).parent / "data" / "published"
    for name in ("furuta.toml", "furuta.urdf"):
        (tmp_path / name).write_text((data / name).read_text())
    text = (data / "furuta_equations.toml").read_text()
    second = text.split("equations = [\n")[1].splitlines()[1].strip().strip('",')
    lhs = second.removesuffix(" = 0")
    assert lhs != second
    path = tmp_path / "doc.toml"
    path.write_text(text.replace(second, f"{factor}*({lhs}) = 0"))
    result = engine.compare(load_derivation(path))
    assert result.equivalent is equivalent, [c.explanation for c in result.causes]
    singular = any(d.kind == K.SINGULAR for d in result.equations[1].diagnoses)
    assert singular is not equivalent
