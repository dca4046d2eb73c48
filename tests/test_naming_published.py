r"""Errors named in the document's symbols on systems no shipped file covers: errors in the
arguments of sines and cosines, and approximations of them, on the two-link arm of Spong,
Hutchinson & Vidyasagar (*Robot Modeling and Control*, §7.4: gravity :math:`m_2l_{c2}g\cos(q_1 + q_2)`, inertia
:math:`m_2l_1l_{c2}\cos q_2`) and the cart-pole of Florian (2007) (gravity
:math:`mgl\sin\theta`), both written by SymPy (:mod:`published_forms`):

- a sign flipped inside an argument (cos(q1 − q2) where cos(q1 + q2) fits), a position added
  to one (cos(q1 + q2) where cos q2 fits), a tangent for a sine — each a ``swap`` naming what
  is written and what fits;
- a small angle in a sum of positions (1 written where cos(q1 + q2) fits) — a
  ``small_angle`` in q1 + q2; two terms approximated together beside a bare angle that is
  right, on a sprung double pendulum (``data/published/double_pendulum*``);
- the same pendulum solved for its accelerations with a wrong inverted inertia: the symbol
  written for another, in the solved rows' own frame.
"""

from __future__ import annotations

from pathlib import Path

import pytest
import sympy as sp

import published_forms as P
from conftest import SEED
from shipped_copies import published_copy
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import DiagnosisKind as K
from wheeled_dyn.compare.records import CauseKind, Verdict
from wheeled_dyn.derivations import load_derivation

SAMPLES, PARAM_SETS = 200, 3
DATA = Path(__file__).parent / "data" / "published"


def _pendulum(folder: Path, name: str) -> str:
    r"""The text of the sprung double pendulum's derivation ``name``, its model copied into
    ``folder`` (the file names it by a relative path)."""
    for own in ("double_pendulum.toml", "double_pendulum.urdf"):
        (folder / own).write_text((DATA / own).read_text())
    return (DATA / name).read_text()


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)


def _flagged(engine, tmp_path, system: str, old: str, new: str, count: int = 1):
    path = P.write(tmp_path, system, "equations", None)
    text = path.read_text()
    assert text.count(old) >= count, (old, text)
    path.write_text(text.replace(old, new, count))
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    return {r.element: r for r in result.records if r.verdict != "agrees"}


@pytest.mark.parametrize("system, old, new, element, written, fits", [
    ("arm", "g*lc2*m2*cos(q1 + q2)", "g*lc2*m2*cos(q1 - q2)", "Q[1]", "cos(q1 - q2)",
     "cos(q1 + q2)"),
    ("arm", "ddq2*(I2 + m2*(l1*lc2*cos(q2)", "ddq2*(I2 + m2*(l1*lc2*cos(q1 + q2)", "A[1,2]",
     "cos(q1 + q2)", "cos(q2)"),
    ("pole", "g*l*m*sin(theta)", "g*l*m*tan(theta)", "Q[2]", "tan(theta)", "sin(theta)"),
])
def test_a_wrong_argument_or_function_is_named(engine, tmp_path, system, old, new, element,
                                               written, fits):
    flagged = _flagged(engine, tmp_path, system, old, new)
    assert flagged
    assert set(flagged) == {element}, set(flagged)
    for record in flagged.values():
        swaps = [d for d in record.diagnoses if d.kind == K.SWAP]
        assert swaps and swaps[0].written == written, record.texts
        assert swaps[0].fits == fits


def test_a_small_angle_in_a_sum_of_positions_is_named(engine, tmp_path):
    r"""The arm's first gravity term cos(q1 + q2) taken as 1 (angles from the horizontal: the
    link near it), the second equation keeping it: a small angle in q1 + q2, named so."""
    flagged = _flagged(engine, tmp_path, "arm", "g*lc2*m2*cos(q1 + q2)", "g*lc2*m2")
    assert set(flagged) == {"Q[1]"}, set(flagged)
    small = [d for d in flagged["Q[1]"].diagnoses if d.kind == K.SMALL_ANGLE]
    assert small and small[0].position == "q1 + q2", flagged["Q[1]"].texts
    assert small[0].fits == "cos(q1 + q2)"


def test_two_terms_read_as_small_angles_together_beside_a_bare_angle(engine, tmp_path):
    r"""A double pendulum with torsional springs (``data/published/double_pendulum_springs``,
    right: it agrees): its first gravity terms m1 a1 g sin θ1 + m2 L1 g sin θ1 written with
    θ1 for sin θ1 in both, while the spring's k1 (θ1 − r1) keeps its own bare θ1 (reading
    every θ1 as sin θ1 does not fit, nor one term alone): a small angle in θ1, both terms."""
    text = _pendulum(tmp_path, "double_pendulum_springs.toml")
    right = tmp_path / "right.toml"
    right.write_text(text)
    assert engine.compare(load_derivation(right)).equivalent is True
    old = "m1*a1*g*sin(th1) + m2*L1*g*sin(th1)"
    assert old in text
    wrong = tmp_path / "wrong.toml"
    wrong.write_text(text.replace(old, "m1*a1*g*th1 + m2*L1*g*th1"))
    flagged = {r.element: r for r in engine.compare(load_derivation(wrong)).records
               if r.verdict != "agrees"}
    assert set(flagged) == {"Q[1]"}, set(flagged)
    small = [d for d in flagged["Q[1]"].diagnoses if d.kind == K.SMALL_ANGLE]
    assert small and small[0].position == "th1", flagged["Q[1]"].texts


def test_a_solved_form_names_the_symbol_of_its_wrong_inverted_inertia(engine, tmp_path):
    r"""The sprung double pendulum solved for its accelerations as simulation code writes it
    (θ̈ = D⁻¹ f with the 2 × 2 inverse written out): right, it agrees; with the link's inertia
    about its centre I1 written where the one about the hip J1 belongs in the inverted
    matrix, the rows keep their solved frame (the form says which combination they are) and
    the error is named in the document's symbols: I1 where J1 fits."""
    text = _pendulum(tmp_path, "double_pendulum_solved.toml")
    right = tmp_path / "solved.toml"
    right.write_text(text)
    assert engine.compare(load_derivation(right)).equivalent is True
    wrong = tmp_path / "solved_I1.toml"
    wrong.write_text(text.replace('a11 = "J1 + m2*L1**2"', 'a11 = "I1 + m2*L1**2"'))
    result = engine.compare(load_derivation(wrong))
    assert result.equivalent is False
    swaps = [d for r in result.records for d in r.diagnoses if d.kind == K.SWAP]
    assert any(d.written == "I1" and d.fits == "J1" for d in swaps), \
        [r.texts for r in result.records if r.verdict != "agrees"]
    assert all(r.verdict == "agrees" for r in result.records if r.key == "A")


@pytest.mark.parametrize("old, new, element, kind", [
    ("+ k1*(th1 - r1) -", "- k1*(th1 - r1) -", "Q[1]", K.SIGN),
    ("sin(th2) + k2*(th2 - th1 - r2)", "sin(th2) + 2*k2*(th2 - th1 - r2)", "Q[2]", K.FACTOR),
])
def test_a_spring_term_of_several_parts_is_named_whole(engine, tmp_path, old, new, element,
                                                      kind):
    r"""The sprung double pendulum's k1 (θ1 − r1) with its sign flipped, k2 (θ2 − θ1 − r2)
    doubled: one printed term of two or three expanded ones, named as a whole (its terms with
    k1, or k2), where each expanded term alone fits nothing."""
    text = _pendulum(tmp_path, "double_pendulum_springs.toml")
    assert old in text
    wrong = tmp_path / "spring.toml"
    wrong.write_text(text.replace(old, new))
    flagged = {r.element: r for r in engine.compare(load_derivation(wrong)).records
               if r.verdict != "agrees"}
    assert set(flagged) == {element}, set(flagged)
    named = [d for d in flagged[element].diagnoses if d.kind == kind]
    assert named and ("k1" if element == "Q[1]" else "k2") in named[0].term, \
        flagged[element].texts


def test_a_dropped_inertia_is_named_in_the_documents_symbols(engine, tmp_path):
    r"""The arm with I1 left out of d11: a body treated as a point mass, the missing moment
    named by the model's link and, in the document's symbols, as I1."""
    path = P.write(tmp_path, "arm", "equations", "dropped")
    flagged = {r.element: r for r in engine.compare(load_derivation(path)).records
               if r.verdict != "agrees"}
    assert set(flagged) == {"A[1,1]"}, set(flagged)
    point = [d for d in flagged["A[1,1]"].diagnoses if d.kind == K.POINT_MASS]
    assert point and point[0].terms == ("I1",), flagged["A[1,1]"].texts


def test_a_row_divided_by_a_two_term_inertia_of_a_larger_system_is_identified(engine,
                                                                               tmp_path):
    r"""A three-link planar arm (``data/published/three_link_arm*``, the Lagrange equations
    derived with SymPy) with its third equation divided by its diagonal inertia
    I3 + lc3² m3: right, and the divisor named — the search for a short sum, refused over
    more than 16 candidate names, goes on over those without a sine or cosine."""
    for own in ("three_link_arm.toml", "three_link_arm.urdf"):
        (tmp_path / own).write_text((DATA / own).read_text())
    path = tmp_path / "divided.toml"
    path.write_text((DATA / "three_link_arm_divided.toml").read_text())
    result = engine.compare(load_derivation(path))
    assert result.equivalent is True
    assert result.equations[2].frame == "the true equation divided by I3 + lc3**2*m3", \
        result.equations[2].frame


def test_units_name_the_term_whose_dimension_differs_from_the_rows(engine, tmp_path):
    r"""The pendulum's second equation multiplied through by L1/a2 (a dimensionless ratio)
    and expanded, with I2*L1 written for I2*L1/a2: the term of A[2,2] whose dimension is not
    the row's is named, not its right neighbour L1*a2*m2."""
    text = _pendulum(tmp_path, "double_pendulum_springs.toml")
    second = [line.strip().strip('",') for line in
              text.split("equations = [")[1].split("]")[0].strip().splitlines()][1]
    scaled = ("m2*L1**2*cos(th1 - th2)*ddth1 + (I2*L1 + m2*a2*L1)*ddth2 - m2*L1**2*sin(th1 - "
              "th2)*dth1**2 + m2*L1*g*sin(th2) + k2*L1/a2*(th2 - th1 - r2) = L1*T2/a2")
    path = tmp_path / "scaled.toml"
    path.write_text(text.replace(second, scaled))
    records = {r.element: r for r in engine.compare(load_derivation(path)).records}
    units = [d.text for d in records["A[2,2]"].diagnoses if d.kind == K.DIMENSION]
    assert units and "I2*L1 is" in units[0], records["A[2,2]"].texts


def test_units_name_the_odd_term_where_the_positions_have_none(engine, tmp_path):
    r"""A double pendulum on a cart (``data/published/cart_double_pendulum*``, written for the
    tests) whose file gives its positions no units, with the length a1 dropped from the
    gravity term a1 g m1 sin θ1: Q[2] has one term in N beside one in N·m. The row's
    dimension is what its input T (N·m) says — the term in N is named; the tie of Q[2]'s two
    terms named its right neighbour L1 g m2 sin θ1, and B[2,2] was "dimensionless, expected
    m⁻¹" (an element whose own terms disagree no longer votes for its row's dimension)."""
    for name in ("cart_double_pendulum.toml", "cart_double_pendulum.urdf"):
        (tmp_path / name).write_text((DATA / name).read_text())
    text = (DATA / "cart_double_pendulum_equations.toml").read_text()
    assert text.count("+ a1*g*m1*sin(th1) = T") == 1
    path = tmp_path / "doc.toml"
    path.write_text(text.replace("+ a1*g*m1*sin(th1) = T", "+ g*m1*sin(th1) = T"))
    records = {r.element: r for r in engine.compare(load_derivation(path)).records}
    units = [d.text for d in records["Q[2]"].diagnoses if d.kind == K.DIMENSION]
    assert units and "term g*m1*sin(th1) is kg·m·s^-2" in units[0], records["Q[2]"].texts
    assert not any(d.kind == K.DIMENSION for d in records["B[2,2]"].diagnoses)


@pytest.mark.parametrize("old, new, named", [
    ("+ a1*dth1**2*m1*sin(th1)", "- a1*dth1**2*m1*sin(th1)",
     "h[1]:dth1*dth1: the term -a1*m1*sin(th1) has the wrong sign "
     "(truth − document = -2*a1*m1*sin(th1))"),
    ("T - a1*g*m1*sin(th1)", "T - 2*a1*g*m1*sin(th1)",
     "Q[2]: the term a1*g*m1*sin(th1) is 2 × what fits (truth − document = "
     "-a1*g*m1*sin(th1))")])
def test_a_solved_form_names_the_term_of_the_equations_it_solved(engine, tmp_path, old, new,
                                                                named):
    r"""The double pendulum on a cart solved for its accelerations by Cramer's rule
    (``data/published/cart_double_pendulum_solved.toml``, written for the tests) with one
    term of the equations it solved wrong — a velocity term's sign, a gravity term doubled:
    every solved row differs and none was named (its two inputs cannot give back its
    inertia matrix). Read back before solving (its rows times A A_doc⁻¹, its inputs'
    coefficients then the truth's), the term is named in its symbols, against the truth's
    term (the sign of the one, the other 2 × what fits)."""
    said = _solved_with(engine, tmp_path, "cart_double_pendulum",
                        "cart_double_pendulum_solved", old, new)
    assert "read back before it was solved or combined" in said and named in said, said


def _solved_with(engine, tmp_path, model: str, form: str, old: str, new: str) -> str:
    r"""What the equations of ``data/published/<form>.toml`` (model ``<model>``) with ``old``
    planted as ``new`` say; they must not be equivalent."""
    for name in (model + ".toml", model + ".urdf"):
        (tmp_path / name).write_text((DATA / name).read_text())
    text = (DATA / (form + ".toml")).read_text()
    assert text.count(old) == 1, old
    path = tmp_path / "doc.toml"
    path.write_text(text.replace(old, new))
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    return " ".join(t for e in result.equations for t in e.texts)



@pytest.mark.parametrize("files, old, new, named", [
    # a symbol written for another in a product of the equations it solved
    (("cart_double_pendulum",), "- L1*g*m2*sin(th1) + T", "- a1*g*m2*sin(th1) + T",
     "Q[2]: L1 and a1, one written where the other fits (truth − document = "
     "g*m2*(L1 - a1)*sin(th1))"),
    (("double_pendulum", "double_pendulum_solved"), "(m1*a1 + m2*L1)*g*sin(th1)",
     "(m1*a1 + m2*a1)*g*sin(th1)", "Q[1]: L1 and a1, one written where the other fits "
     "(truth − document = g*m2*(L1 - a1)*sin(th1))"),
    # ... in the inertia it inverted, with as many inputs as coordinates
    (("double_pendulum", "double_pendulum_solved"), 'a12 = "m2*L1*a2*cos(th1 - th2)"',
     'a12 = "m2*a1*a2*cos(th1 - th2)"',
     "A[1,2]: L1 and a1, one written where the other fits (truth − document = "
     "a2*m2*(L1 - a1)*cos(th1 - th2))"),
    # ... and with fewer inputs (two) than coordinates (three): a symbol for another, an
    # inertia dropped, a sign (it was "no single-term diagnosis" on every solved element)
    (("cart_double_pendulum",), 'M22 = "I1 + L1**2*m2 + a1**2*m1"',
     'M22 = "I1 + a1**2*m2 + a1**2*m1"', "A[2,2]: L1 and a1, one written where the other "
     "fits (truth − document = m2*(L1**2 - a1**2))"),
    (("cart_double_pendulum",), 'M22 = "I1 + L1**2*m2 + a1**2*m1"',
     'M22 = "L1**2*m2 + a1**2*m1"', "A[2,2]: the moment of inertia Iyy(link1) about its own "
     "centre of mass is missing, a point mass (truth − document = I1)"),
    (("cart_double_pendulum",), 'M22 = "I1 + L1**2*m2 + a1**2*m1"',
     'M22 = "I1 + L1**2*m2"', "A[2,2]: the parallel-axis term of link1 about its x or y axis "
     "is missing: the inertia about the centre of mass where the one about the joint's axis "
     "fits (truth − document = a1**2*m1)"),
    (("cart_double_pendulum",), 'M12 = "(L1*m2 + a1*m1)*cos(th1)"',
     'M12 = "(L1*m2 - a1*m1)*cos(th1)"',
     "A[1,2]: the term a1*m1*cos(th1) has the wrong sign (truth − document = "
     "2*a1*m1*cos(th1))"),
])
def test_a_solved_form_names_a_symbol_for_another_and_its_inverted_inertia(
        engine, tmp_path, files, old, new, named):
    r"""Equations solved for the accelerations (simulation code; ``data/published``, written
    for the tests) with one planted error: a symbol written for another in a product (a1, the
    centre's distance, for L1, the link's length) of the equations solved or of the inertia
    inverted, an inertia dropped, a parallel-axis term dropped (named as the matrix form's
    element is; it was "a term the document leaves out"), a sign. Each is named in the document's symbols, read back
    before solving: the source equations' terms (a monomial times the difference of the two
    symbols), or the inertia inverted — from the inputs' coefficients where the inputs are as
    many as the coordinates, else from the inputs', gravity and velocity terms' together."""
    model, form = files[0], (files[1] if len(files) > 1 else files[0] + "_solved")
    said = _solved_with(engine, tmp_path, model, form, old, new)
    assert named in said, said


#: The Furuta pendulum's equations (``data/published/furuta_equations.toml``) solved for the
#: accelerations as simulation code writes them, A q̈ + h + q = B u inverted by hand (one
#: input for two coordinates).
FURUTA_SOLVED = """
[definitions]
a11 = "J1 + m1*lc1**2 + L1**2*m2 + Jyy*sin(al)**2 + Jzz*cos(al)**2 + lc2**2*m2*sin(al)**2"
a12 = "L1*lc2*m2*cos(al)"
a22 = "Jxx + lc2**2*m2"
h1 = "2*(Jyy - Jzz + lc2**2*m2)*dal*dth*sin(al)*cos(al) - L1*dal**2*lc2*m2*sin(al)"
h2 = "-(Jyy - Jzz + lc2**2*m2)*dth**2*sin(al)*cos(al)"
q2 = "g*lc2*m2*sin(al)"

[matrices]
equations = [
  "ddth = (a22*(tau - h1) - a12*(-h2 - q2))/(a11*a22 - a12**2)",
  "ddal = (a11*(-h2 - q2) - a12*(tau - h1))/(a11*a22 - a12**2)",
]
"""


@pytest.mark.parametrize("coupling", ["L1*lc2*m2*cos(al)", "-L1*lc2*m2*cos(al)"],
                         ids=["right", "opposite-sign"])
def test_a_coupling_inertias_sign_before_solving_is_the_cause(engine, tmp_path, coupling):
    r"""The Furuta pendulum solved for its accelerations: right, it agrees; its coupling
    inertia a12 written with the opposite sign, then inverted, every solved element it
    reaches has a term of the opposite sign, and the cause that claims them names the
    coupling, A[1,2] = A[2,1], read back before solving (it was "sign: the document has the
    opposite sign — Q[1], …", the solved elements' own)."""
    for name in ("furuta.toml", "furuta.urdf"):
        (tmp_path / name).write_text((DATA / name).read_text())
    text = (DATA / "furuta_equations.toml").read_text()
    solved = FURUTA_SOLVED.replace('a12 = "L1*lc2*m2*cos(al)"', f'a12 = "{coupling}"')
    path = tmp_path / "doc.toml"
    path.write_text(text[:text.index("[matrices]")] + solved)
    result = engine.compare(load_derivation(path))
    if not coupling.startswith("-"):
        assert result.equivalent is True, [c.explanation for c in result.causes]
        return
    assert result.equivalent is False
    differing = {r.element for r in result.records if r.verdict == "differs" and r.key != "C"}
    claiming = [c for c in result.causes if set(c.elements) & differing]
    assert claiming and "A[1,2]: the document has the opposite sign" in \
        claiming[0].explanation, [c.explanation for c in result.causes]


def test_two_symbols_exchanged_in_a_term_are_named(engine, tmp_path):
    r"""The differential drive in (v, ω) (``data/published/dd_swivel_vw.toml`` on the robot
    without its caster, ``dd_robot``) with the
    wheels' yaw inertia written :math:`2R^2I_w/L^2` for :math:`2L^2I_w/R^2` (R and L, two
    lengths, exchanged in one term): the element is named as the exchange (it was "no
    single-term diagnosis")."""
    path = published_copy(tmp_path, "dd_robot", "dd_swivel_vw",        # no caster
                          ('model = "dd_swivel.toml"', 'model = "dd_robot.toml"'),
                          ("(I + 2*L**2*I_w/R**2)*domega", "(I + 2*R**2*I_w/L**2)*domega"))
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    flagged = {r.element: r for r in result.records if r.verdict != "agrees"}
    assert set(flagged) == {"A[2,2]"}, set(flagged)
    (swap,) = [x for x in flagged["A[2,2]"].diagnoses if x.kind == K.SWAP]
    assert swap.written == "2*I_w*R**2/L**2" and swap.fits == "2*I_w*L**2/R**2", swap


def test_a_gravity_term_dropped_before_solving_is_named_on_every_element_it_reaches(
        engine, tmp_path):
    r"""The double pendulum solved for its accelerations with link 2's gravity term left out
    of its second equation before solving: both solved rows' gravity elements differ, each a
    rational function of every parameter (one was "no single-term diagnosis", the other
    named by a term of eleven factors); both now say the term as the source equation lacks
    it."""
    for name in ("double_pendulum.toml", "double_pendulum.urdf"):
        (tmp_path / name).write_text((DATA / name).read_text())
    text = (DATA / "double_pendulum_solved.toml").read_text()
    old = " + m2*a2*g*sin(th2) + k2"
    assert text.count(old) == 1
    path = tmp_path / "doc.toml"
    path.write_text(text.replace(old, " + k2"))
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    flagged = {r.element: r for r in result.records if r.verdict != "agrees"}
    assert set(flagged) == {"Q[1]", "Q[2]"}, set(flagged)
    for r in flagged.values():
        assert "the equations differ: Q[2]: the document lacks a2*g*m2*sin(th2)" in \
            r.texts[0], r.texts


def _acrobot(tmp_path: Path, old: str, new: str):
    r"""The acrobot solved as simulation code does (``data/published/acrobot_simulation.toml``,
    Tedrake's equations, written for the tests) with ``old`` planted as ``new``, compared."""
    for name in ("acrobot.toml", "acrobot.urdf"):
        (tmp_path / name).write_text((DATA / name).read_text())
    text = (DATA / "acrobot_simulation.toml").read_text()
    assert text.count(old) == 1, old
    path = tmp_path / "doc.toml"
    path.write_text(text.replace(old, new))
    return ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(load_derivation(path))


def test_a_term_dropped_before_solving_is_not_a_term_too_many(tmp_path):
    r"""The acrobot's second equation without link 2's gravity term, then solved (one input
    for two coordinates): in the solved frame the element shows terms the document has "too
    much", and the cause was "a term the truth does not have"; the equations read back before
    solving say the term it lacks, and that is the cause."""
    result = _acrobot(tmp_path, " - g*lc2*m2*(I1 + I2 + l1**2*m2 + 2*l1*lc2*m2*cos(q2))*"
                      "sin(q1 + q2)", "")
    assert result.equivalent is False
    q2 = next(r for r in result.records if r.element == "Q[2]")
    assert "Q[2]: the document has 0 (truth − document = g*lc2*m2*sin(q1 + q2))" in \
        q2.texts[0], q2.texts
    causes = {c.explanation: c.elements for c in result.causes if c.kind == "missing_physics"}
    said = "a term the document leaves out; Q[2] lacks g*lc2*m2*sin(q1 + q2)"
    assert "Q[2]" in causes.get(said, ()), causes
    assert not any(c.kind == "extra_term" for c in result.causes), result.causes


def test_a_divisor_printed_with_the_error_names_it_before_the_division(tmp_path):
    r"""The acrobot's first equation written out and divided by its own diagonal inertia,
    with lc1 written for l1 in it (and so in the divisor): every element but the
    acceleration's own agrees in the frame of that divisor, and the one left differing is
    a ratio of two inertias; taken back before the division it is the swap."""
    for name in ("acrobot.toml", "acrobot.urdf"):
        (tmp_path / name).write_text((DATA / name).read_text())
    text = (DATA / "acrobot_simulation.toml").read_text()
    d11 = "(I1 + I2 + lc1**2*m2 + 2*l1*lc2*m2*cos(q2))"
    first = (f"ddq1 + (I2 + l1*lc2*m2*cos(q2))*ddq2/{d11} + (-2*dq1*dq2*l1*lc2*m2*sin(q2) - "
             f"dq2**2*l1*lc2*m2*sin(q2) + g*lc1*m1*sin(q1) + g*m2*(l1*sin(q1) + lc2*sin(q1 + "
             f"q2)))/{d11} = 0")
    second = ("I2*ddq2 + (I2 + l1*lc2*m2*cos(q2))*ddq1 + dq1**2*l1*lc2*m2*sin(q2) + "
              "g*lc2*m2*sin(q1 + q2) = u")
    head = text[:text.index("[matrices]")]
    path = tmp_path / "doc.toml"
    path.write_text(head + f'[matrices]\nequations = [\n  "{first}",\n  "{second}"\n]\n')
    result = ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(
        load_derivation(path))
    assert result.equivalent is False
    flagged = {r.element: r for r in result.records if r.verdict != "agrees"}
    assert set(flagged) == {"A[1,1]"}, set(flagged)
    record = flagged["A[1,1]"]
    assert record.kinds[0] == K.SWAP, record.texts
    assert "before the document divided its equation by its own quantity: l1 and lc1, one " \
        "written where the other fits" in record.texts[0], record.texts


def test_a_solved_cart_pole_with_a_cos_for_a_sin_names_it_not_its_inertia(engine, tmp_path):
    r"""The cart-pole solved as Barto et al.'s simulation computes it, with cos written for sin
    in its gravity term: one input for two coordinates, and the gravity term alone carries
    the pole's row of the weights, so its inertia cannot be read back (it was, and a wrong
    inertia was named); the equations read back before solving name the term instead."""
    result = engine.compare(load_derivation(P.write(tmp_path, "pole", "solved", "trig")))
    assert result.equivalent is False
    said = " ".join(t for e in result.equations for t in e.texts)
    assert "the inertia matrix the document inverted" not in said, said
    assert "Q[2]: cos(theta) and sin(theta), one written where the other fits (truth − " \
        "document = g*l*m*(-sin(theta) + cos(theta)))" in said, said


@pytest.mark.parametrize("old, new, term", [
    # the gravity term left out of the division by d22
    (" + g*lc2*m2*cos(q1 + q2))/(I2 + lc2**2*m2) =", ")/(I2 + lc2**2*m2) + g*lc2*m2*cos(q1 + q2) =",
     "g*lc2*m2*cos(q1 + q2)"),
    # I2 of the coupling inertia d21 left out of it (one term of A[2,1])
    ("(ddq1*(I2 + m2*(l1*lc2*cos(q2) + lc2**2))", "ddq1*I2 + (ddq1*(m2*(l1*lc2*cos(q2) + "
     "lc2**2))", "I2")])
def test_a_term_left_out_of_a_rows_division_is_named(engine, tmp_path, old, new, term):
    r"""The arm's second equation divided by its diagonal inertia d22 (a textbook's step),
    with one term not divided — an element's only term, or one of its terms: that term is
    named, not "no single-term diagnosis" (the row is the true equation times a factor that
    varies from sample to sample, so no constant factor names it)."""
    path = P.write(tmp_path, "arm", "divided", None)
    text = path.read_text()
    assert text.count(old) == 1, old
    path.write_text(text.replace(old, new))
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    flagged = [r for r in result.records if r.verdict == "differs"]
    assert len(flagged) == 1, [(r.element, r.texts) for r in flagged]
    said = [d for d in flagged[0].diagnoses if d.kind == K.FACTOR]
    assert said and said[0].term == term and "is not divided as the rest of its row" in \
        said[0].text, flagged[0].texts


def test_a_symbol_for_another_in_the_models_proportions_is_a_swap_not_a_factor(engine,
                                                                              tmp_path):
    r"""The differential-drive robot of ``data/published/dd_multipliers.toml`` with its wheels
    declared in their URDF's proportions and I_w (about the axle) written for I_m (about a
    diameter) in the yaw inertia: the ratio of the two is one number for every wheel the
    family allows, so the term is "that number × what fits" too; the symbol written for the
    other is said first, and is the cause (it read "the term 2*I_w is 16/9 × what fits")."""
    from wheeled_dyn.compare.records import CauseKind
    text = (DATA / "dd_multipliers.toml").read_text()
    old = 'I = "I_c + m_c*d**2 + 2*m_w*L**2 + 2*I_m"'
    assert text.count(old) == 1 and text.count('families = ["urdf_structure"]') == 1
    text = text.replace(old, old.replace("2*I_m", "2*I_w")).replace(
        'families = ["urdf_structure"]', 'families = ["urdf_proportions"]')
    for own in ("dd_robot.toml", "dd_robot.urdf"):
        (tmp_path / own).write_text((DATA / own).read_text())
    path = tmp_path / "dd.toml"
    path.write_text(text)
    result = engine.compare(load_derivation(path))
    flagged = [r for r in result.records if r.verdict == "differs"]
    assert [r.element for r in flagged] == ["A[3,3]"], [(r.element, r.texts) for r in flagged]
    first = flagged[0].diagnoses[0]
    assert first.kind == K.SWAP and (first.written, first.fits) == ("I_w", "I_m"), \
        flagged[0].texts
    assert any(c.kind == CauseKind.SWAP and "A[3,3]" in c.elements for c in result.causes)


def test_a_symbol_to_another_power_in_one_term_is_named(engine, tmp_path):
    r"""The arm's d11 with l1 where l1² fits in m2 l1² only (l1 stays right in the other terms
    of the element, so no element-wide power fits): named in the term (it was "truth −
    document" only)."""
    path = P.write(tmp_path, "arm", "matrices", None)
    text = path.read_text()
    old = '"I1 + I2 + lc1**2*m1 + m2*(l1**2 + 2*l1*lc2*cos(q2) + lc2**2)"'
    assert text.count(old) == 1
    path.write_text(text.replace(old, old.replace("m2*(l1**2 +", "m2*(l1 +")))
    flagged = [r for r in engine.compare(load_derivation(path)).records
               if r.verdict == "differs"]
    assert [r.element for r in flagged] == ["A[1,1]"], [(r.element, r.texts) for r in flagged]
    power = [d for d in flagged[0].diagnoses if d.kind == K.POWER]
    assert power and (power[0].written, power[0].fits, power[0].term) == ("l1", "l1**2",
                                                                          "l1*m2"), \
        flagged[0].texts

def test_a_term_written_too_much_is_named_so(engine, tmp_path):
    r"""The arm's d11 with a term −lc2² m1 written in it that the truth lacks: the document
    has it too much (truth − document = +lc2² m1 is the same sum, told backwards)."""
    path = P.write(tmp_path, "arm", "matrices", None)
    text = path.read_text()
    assert "lc1**2*m1" in text
    path.write_text(text.replace("lc1**2*m1", "lc1**2*m1 - lc2**2*m1", 1))
    flagged = {r.element: r for r in engine.compare(load_derivation(path)).records
               if r.verdict != "agrees"}
    assert set(flagged) == {"A[1,1]"}, set(flagged)
    extra = [d for d in flagged["A[1,1]"].diagnoses if d.kind == K.EXTRA]
    assert extra and "has -lc2**2*m1 too much" in extra[0].text, flagged["A[1,1]"].texts


@pytest.mark.parametrize("form, old, new, element, lacks", [
    ("kane", "- ddx*(M + m)", "- ddx*m", "A[1,1]", "lacks -M"),
    ("equations", "+ ddx*(M + m)", "+ ddx*m", "A[1,1]", "lacks M")])
def test_a_term_dropped_is_named_missing_whatever_its_sign(engine, tmp_path, form, old, new,
                                                          element, lacks):
    r"""The cart-pole with a term dropped, in Kane's form (every term negated: the cart's
    mass in the cart's −(M + m)ẍ) and as its equations: the document lacks the term, in the
    sign the row is read in — the term the truth has, not "−m too much" (a negative term
    dropped was told as its negative written too much whenever no written term was like
    it, or every one was of its sign)."""
    path = P.write(tmp_path, "pole", form, None)
    text = path.read_text()
    assert text.count(old) == 1, (old, text)
    path.write_text(text.replace(old, new))
    flagged = {r.element: r for r in engine.compare(load_derivation(path)).records
               if r.verdict != "agrees"}
    assert element in flagged, set(flagged)
    named = [d for d in flagged[element].diagnoses if d.kind in (K.MISSING, K.EXTRA)]
    assert named and named[0].kind == K.MISSING and lacks in named[0].text, \
        flagged[element].texts


def test_quasi_velocity_equations_are_labelled_by_their_velocity(engine):
    r"""Seed 000's Euler equations of a free body in its body rates p, q, r (quasi-velocities):
    equation 4 is p's, not the yaw angle's."""
    from wheeled_dyn.derivations import builtin_derivations
    path = next(p for p in builtin_derivations("seed000") if p.name.startswith("p7_2_euler"))
    d = load_derivation(path)
    assert d.coordinates.kind == "quasi"
    labels = [e.label for e in engine.compare(d).equations]
    assert labels == [f"equation {i + 1} ({v})" for i, v in enumerate(d.velocities)], labels


def test_a_moment_written_too_large_is_a_factor_not_a_point_mass(engine, tmp_path):
    r"""The cart-pole's uniform pole with 2 m l² for 4/3 m l² about its hinge: the document
    has more than the truth, so no body is treated as a point mass (that would be a moment
    lacking, × −2 of its own moment here); the element is a factor 3/2 of the truth."""
    path = P.write(tmp_path, "pole", "equations", None)
    text = path.read_text()
    assert "4*ddtheta*l**2*m/3" in text
    path.write_text(text.replace("4*ddtheta*l**2*m/3", "2*ddtheta*l**2*m"))
    flagged = {r.element: r for r in engine.compare(load_derivation(path)).records
               if r.verdict != "agrees"}
    assert set(flagged) == {"A[2,2]"}, set(flagged)
    kinds = [d.kind for d in flagged["A[2,2]"].diagnoses]
    assert K.FACTOR in kinds and K.POINT_MASS not in kinds, flagged["A[2,2]"].texts


@pytest.mark.parametrize("old, new, kind, term", [
    ("dq1**2*(l1*l2*m3*sin(q2) + l1*lc2*m2*sin(q2)",
     "dq1**2*(l1*l2*m3*sin(q2) - l1*lc2*m2*sin(q2)", K.SIGN, "-l1*lc2*m2*sin(q2)"),
    ("dq1**2*(l1*l2*m3*sin(q2) + l1*lc2*m2*sin(q2)",
     "dq1**2*(2*l1*l2*m3*sin(q2) + l1*lc2*m2*sin(q2)", K.FACTOR, "2*l1*l2*m3*sin(q2)"),
])
def test_one_term_inside_a_velocity_products_coefficient_is_named(engine, tmp_path, old, new,
                                                                  kind, term):
    r"""One of the three terms of the three-link arm's h₂ coefficient of q̇₁² with its sign
    flipped, or doubled: that term is named (it was "the document lacks 2 l1 lc2 m2 sin q2":
    the coefficient is sampled on its own grid, where the numeric term trials do not run)."""
    for own in ("three_link_arm.toml", "three_link_arm.urdf"):
        (tmp_path / own).write_text((DATA / own).read_text())
    text = (DATA / "three_link_arm_divided.toml").read_text()
    assert old in text
    path = tmp_path / "planted.toml"
    path.write_text(text.replace(old, new))
    flagged = {r.element: r for r in engine.compare(load_derivation(path)).records
               if r.verdict != "agrees"}
    assert set(flagged) == {"h[2]:dq1*dq1"}, set(flagged)
    hit = flagged["h[2]:dq1*dq1"].diagnoses[0]
    assert hit.kind == kind and hit.term == term, flagged["h[2]:dq1*dq1"].texts


#: The differential-drive robot's (v, ω) equations (``data/published/dd_swivel_vw.toml``, on
#: the caster-free robot) solved for the accelerations, as simulation code integrates them.
DD_SOLVED = '''equations = [
  "dv = (m_c*d*omega**2 + (tau_R + tau_L)/R)/(m + 2*I_w/R**2)",
  "domega = (-m_c*d*omega*v + L*(tau_R - tau_L)/R)/(I + 2*L**2*I_w/R**2)",
]
'''


def _dd_solved(tmp_path: Path, old: str = "", new: str = "") -> Path:
    text = (DATA / "dd_swivel_vw.toml").read_text()
    text = text.replace('model = "dd_swivel.toml"', 'model = "dd_robot.toml"')
    text = text[:text.index("equations = [")] + DD_SOLVED.replace(old, new)
    for own in ("dd_robot.toml", "dd_robot.urdf"):
        (tmp_path / own).write_text((DATA / own).read_text())
    path = tmp_path / "solved.toml"
    path.write_text(text)
    return path


def test_rows_solved_for_a_diagonal_inertia_are_told_solved(engine, tmp_path):
    r"""Both rows solved (the robot's inertia is diagonal in (v, ω)): each is told "solved for
    the accelerations", the weights of its form, or divided by the sum it prints, where it was
    "times a function of the state and parameters (not identified)"."""
    result = engine.compare(load_derivation(_dd_solved(tmp_path)))
    assert result.equivalent is True
    frames = [e.frame for e in result.equations]
    assert frames[0] in ("solved for the accelerations (row of A⁻¹ × the true equations)",
                         "the true equation divided by 2*I_w/R**2 + m_c + 2*m_w"), frames
    assert frames[1].startswith("solved for the accelerations") or \
        frames[1].startswith("the true equation divided by"), frames
    assert not any("not identified" in f for f in frames), frames


def test_a_solved_row_whose_divisor_is_not_found_is_told_solved(engine, tmp_path,
                                                                 monkeypatch):
    r"""The same rows where the sums they divide by are not among the fits' bases (a divisor
    the search cannot name): "solved for the accelerations", not "times a function of the
    state and parameters (not identified)"."""
    from wheeled_dyn.compare.judge import fitting
    monkeypatch.setattr(fitting, "written_divisors", lambda d: [])
    result = engine.compare(load_derivation(_dd_solved(tmp_path)))
    assert result.equivalent is True
    for e in result.equations:
        assert e.frame.startswith("solved for the accelerations"), e.frame


def test_a_dropped_symbolic_factor_is_named(engine, tmp_path):
    r"""L dropped from L (τ_R − τ_L)/R in the solved yaw equation: both input elements "lack a
    factor L" (they had no diagnosis: the ratio is no number, and no term is missing)."""
    path = _dd_solved(tmp_path, "+ L*(tau_R - tau_L)/R", "+ (tau_R - tau_L)/R")
    flagged = {r.element: r for r in engine.compare(load_derivation(path)).records
               if r.verdict != "agrees"}
    assert set(flagged) == {"B[2,1]", "B[2,2]"}, set(flagged)
    for r in flagged.values():
        assert r.diagnoses[0].kind == K.FACTOR and r.diagnoses[0].factor == "1/L", r.texts


@pytest.mark.parametrize("error", [None, "sign"])
def test_a_row_divided_by_a_long_sum_it_prints_is_identified(engine, tmp_path, error):
    r"""The arm's first equation divided by its whole diagonal inertia d11 (five terms, one
    with cos q2), as printed: "the true equation divided by" that sum, where it was "times a
    function of the state and parameters (not identified)" (the sum search stops at two
    products); with the sign of h q̇₂² planted, that term is named in that frame."""
    path = P.write(tmp_path, "arm", "equations", error)
    text = path.read_text()
    D, c, phi = P.arm(error)
    first = (D[0, :] * sp.Matrix([P.ddq1, P.ddq2]))[0] + c[0] + phi[0]
    head, rest = text.split("equations = [\n")
    second = rest.splitlines()[1]
    path.write_text(f'{head}equations = [\n  "({P._s(first)})/({P._s(D[0, 0])}) = '
                    f'tau1/({P._s(D[0, 0])})",\n{second}\n]\n')
    result = engine.compare(load_derivation(path))
    assert result.equations[0].frame == (
        "the true equation divided by I1 + I2 + lc1**2*m1 + m2*(l1**2 + 2*l1*lc2*cos(q2) + "
        "lc2**2)"), result.equations[0].frame
    flagged = {r.element: r for r in result.records if r.verdict != "agrees"}
    if error is None:
        assert result.equivalent is True and not flagged
    else:
        assert set(flagged) == {"h[1]:dq2*dq2"}, set(flagged)
        assert flagged["h[1]:dq2*dq2"].diagnoses[0].kind == K.SIGN


FURUTA_TERM = "- 2*Jzz*dal*dth*sin(al)*cos(al)"


@pytest.mark.parametrize("planted", [False, True])
def test_a_term_of_a_velocity_products_coefficient_is_named(engine, tmp_path, planted):
    r"""A Furuta pendulum (``data/published/furuta_equations.toml``, written for the test with
    the pendulum's principal moments apart; it agrees with the truth): the coefficient of
    :math:`\dot\theta\dot\alpha`
    is :math:`2(J_{yy} - J_{zz} + m_2l_{c2}^2)\sin\alpha\cos\alpha`. With the sign of its
    :math:`J_{zz}` term flipped it was "1.02 × the truth if the pendulum is uniform": the
    products of h had no term diagnoses."""
    from wheeled_dyn.derivations import load_derivation
    for name in ("furuta.toml", "furuta.urdf"):
        (tmp_path / name).write_text((DATA / name).read_text())
    text = (DATA / "furuta_equations.toml").read_text()
    assert text.count(FURUTA_TERM) == 1
    if planted:
        text = text.replace(FURUTA_TERM, FURUTA_TERM.replace("- ", "+ ", 1))
    (tmp_path / "doc.toml").write_text(text)
    result = engine.compare(load_derivation(tmp_path / "doc.toml"))
    assert result.equivalent is (not planted), [c.explanation for c in result.causes]
    if planted:
        (record,) = [r for r in result.records if r.verdict != "agrees"]
        assert record.element == "h[1]:dth*dal", record.element
        assert record.texts[0] == "sign: the term 2*Jzz*sin(al)*cos(al) has the wrong sign", \
            record.texts


def test_inputs_left_undivided_are_the_odd_dimension_not_the_inertia(engine, tmp_path):
    r"""The WIP's heading equation divided by its inertia (``data/published/
    wip_heading_divided.toml``, written for the tests) with its inputs left undivided: the row
    is dimensionally inconsistent, and its velocity terms vote with its inertia terms for the
    row's dimension (an acceleration), so the two input terms are the odd ones. The inertia
    elements, right in the row's frame, were flagged "dimension: has dimensionless, expected
    kg; numerically equal here only because the inconsistent term vanishes" (two inertia
    votes against two input votes, the velocity terms not counted)."""
    source = DATA / "wip_heading_divided.toml"
    assert engine.compare(load_derivation(source)).equivalent is True
    old = "= ((-1/R)*T_l + (-1/R)*T_r)/(M_b + 2*m_w + 2*J/R**2)"
    path = tmp_path / source.name
    text = source.read_text()
    assert text.count(old) == 1
    path.write_text(text.replace(old, "= (-1/R)*T_l + (-1/R)*T_r"))
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    flagged = {r.element: r for r in result.records if r.verdict != "agrees"}
    assert set(flagged) == {"B[1,1]", "B[1,2]"}, {k: r.texts for k, r in flagged.items()}
    assert all(any(d.kind == K.DIMENSION for d in r.diagnoses) for r in flagged.values())


def test_a_right_equation_is_not_blamed_for_anothers_error(engine, tmp_path):
    r"""The cart and double pendulum of ``data/published/cart_double_pendulum_equations.toml``
    (written for the tests) with its first equation divided by the total mass and a1 written
    for L1 in one inertia term of the second (a1*L1 for a1**2): the second equation differs
    and is named. The document's det A then changes sign between robots of other masses, and
    the third equation, right and unchanged, was said "not defined for every robot of the
    model" (the rows of a null vector there); it agrees."""
    source = DATA / "cart_double_pendulum_equations.toml"
    for name in ("cart_double_pendulum.toml", "cart_double_pendulum.urdf"):
        (tmp_path / name).write_text((DATA / name).read_text())
    text = source.read_text()
    first = ('"L1*ddth1*m2*cos(th1) - L1*dth1**2*m2*sin(th1) + a1*ddth1*m1*cos(th1) - '
             'a1*dth1**2*m1*sin(th1) + a2*ddth2*m2*cos(th2) - a2*dth2**2*m2*sin(th2) + ddx*m1 + '
             'ddx*m2 + ddx*mc = u"')
    assert text.count(first) == 1 and text.count("a1**2*ddth1*m1") == 1
    text = text.replace(first, '"(' + first[1:-len(' = u"')] + ')/(m1 + m2 + mc) = '
                        'u/(m1 + m2 + mc)"').replace("a1**2*ddth1*m1", "L1*a1*ddth1*m1")
    path = tmp_path / source.name
    path.write_text(text)
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    assert [e.verdict for e in result.equations] == ["agrees", "differs", "agrees"], \
        [t for e in result.equations for t in e.texts]
    assert any(d.kind == K.SWAP for r in result.records if r.element == "A[2,2]"
               for d in r.diagnoses)


def test_wrong_declared_units_of_a_right_equation_are_said(engine, tmp_path):
    r"""The arm's equations, right, with the first link's inertia declared in kg: the
    equations agree (numbers), and the notes say the units as declared are inconsistent, in
    which term and element (it was silent)."""
    result = _arm_with_I1_in_kg(engine, tmp_path, None)
    assert result.equivalent is True
    said = [n for n in result.notes if n.startswith("units as declared:")]
    assert said and "term I1 is kg beside kg·m^2" in said[0] and "A[1,1]" in said[0], \
        result.notes


def test_a_long_summary_line_is_cut_on_the_terminal(engine, tmp_path, capsys):
    r"""A summary line of thousands of characters (an energy residual left unsimplified) is
    printed cut, saying how long it is; the reports hold it whole."""
    from dataclasses import replace

    from wheeled_dyn.cli.report_output import SUMMARY_WIDTH, print_summary
    from wheeled_dyn.compare.records import EnergyCheck
    result = engine.compare(load_derivation(P.write(tmp_path, "arm", "equations", None)))
    long = replace(result, energy=EnergyCheck(False, 1.0, "x*y + " * 2000))
    print_summary([long])
    out = capsys.readouterr().out
    assert max(len(line) for line in out.splitlines()) <= SUMMARY_WIDTH
    assert "(12041 characters: the reports hold it whole)" in out, out  # with its prefix


def _wip_with(tmp_path: Path, form: str, old: str, new: str):
    r"""``data/published/<form>.toml`` (a WIP form, the built-in model) with ``old`` planted as
    ``new``, compared."""
    text = (DATA / f"{form}.toml").read_text()
    assert text.count(old) == 1, old
    path = tmp_path / "doc.toml"
    path.write_text(text.replace(old, new))
    return ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(
        load_derivation(path))


def test_a_term_left_undivided_blames_no_unit_on_a_tie(tmp_path):
    r"""The planar WIP's pitch equation divided by its inertia, its gravity term left out of
    the division (``data/published/wip_planar_divided.toml``, positions without units): the
    input's coefficient implies the divided row's unit and the gravity term the undivided
    one, one vote each. The input's right coefficient was flagged "dimension ... numerically
    equal here only because the inconsistent term vanishes"; on such a tie no unit is blamed,
    and the gravity term is named as not divided."""
    result = _wip_with(tmp_path, "wip_planar_divided",
                       "(m*l*cos(theta)*ddx - m*g*l*sin(theta))/(I_b + m*l**2)",
                       "m*l*cos(theta)*ddx/(I_b + m*l**2) - m*g*l*sin(theta)")
    assert result.equivalent is False
    flagged = {r.element: r for r in result.records if r.verdict != "agrees"}
    assert set(flagged) == {"Q[2]"}, {e: r.texts for e, r in flagged.items()}
    assert "not divided" in flagged["Q[2]"].texts[0], flagged["Q[2]"].texts
    assert not any(K.DIMENSION in r.kinds for r in result.records)
    right = ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(
        load_derivation(DATA / "wip_planar_divided.toml"))
    assert right.equivalent is True and all(r.verdict == "agrees" for r in right.records)


def test_a_parallel_axis_term_equal_about_two_axes_names_both(tmp_path):
    r"""The planar WIP written out (``data/published/wip_planar_x.toml``) with the body's
    inertia about its centre where the one about the axle fits: its centre of mass lies on
    one of its axes, so its parallel-axis terms about the two others are the same number;
    the first was named ("about its x axis", the pitch axis is another), now both are."""
    result = _wip_with(tmp_path, "wip_planar_x", "(I_b + m*l**2)*ddtheta", "(I_b)*ddtheta")
    record = next(r for r in result.records if r.element == "A[2,2]")
    assert record.kinds[0] == K.PARALLEL_AXIS, record.texts
    assert "the parallel-axis term of body about its x or z axis" in record.texts[0], \
        record.texts


def test_a_plain_equation_is_not_said_to_be_divided(tmp_path):
    r"""A two-link arm whose elbow sits on a bracket turned by half a radian, its equations
    written out as if the bracket were not turned (``turned_bracket_arm_unturned.toml``,
    written for the tests): cos(q2) where cos(q2 + 1/2) fits. Its rows are the true
    equations themselves; the swap is named, and not "before the document divided its
    equation by its own quantity" (a row's factor of 1 was taken for a division)."""
    for name in ("turned_bracket_arm.toml", "turned_bracket_arm.urdf",
                 "turned_bracket_arm_unturned.toml"):
        (tmp_path / name).write_text((DATA / name).read_text())
    result = ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(
        load_derivation(tmp_path / "turned_bracket_arm_unturned.toml"))
    assert result.equivalent is False
    assert all(e.frame == "the true equation" for e in result.equations)
    flagged = [r for r in result.records if r.verdict != "agrees"]
    assert flagged
    assert not any("divided" in t for r in flagged for t in r.texts), \
        [(r.element, r.texts) for r in flagged]


def _arm_with_I1_in_kg(engine, folder: Path, error: str | None):
    r"""The arm's equations with ``error`` planted and the first link's inertia declared in kg
    (its units wrong, its terms right), compared."""
    path = P.write(folder, "arm", "equations", error)
    text = path.read_text()
    old = 'I1 = { value = "IYY(link1)", units = "kg*m**2" }'
    assert text.count(old) == 1
    path.write_text(text.replace(old, 'I1 = { value = "IYY(link1)", units = "kg" }'))
    result = engine.compare(load_derivation(path))
    return result


def test_wrong_units_beside_another_error_of_the_row_blame_no_right_element(engine, tmp_path):
    r"""The arm's equations with the first link's inertia declared in kg (its units wrong, its
    terms right) and, in the same first equation, the sign of a velocity term flipped: the
    equation differs and the flipped term is named, while A[1,1] — right, its values those of
    the truth on robots drawn at random — agrees, its units said. It had been "differs:
    numerically equal here only because the inconsistent term vanishes", a term that does not
    vanish (the rule is for a term the drawn parameters hide: :func:`_vanishing_term`)."""
    result = _arm_with_I1_in_kg(engine, tmp_path, "sign")
    assert result.equivalent is False
    a11 = next(r for r in result.records if r.element == "A[1,1]")
    assert a11.verdict == Verdict.AGREES, a11.texts
    assert K.DIMENSION in a11.kinds and K.COINCIDENCE not in a11.kinds
    flagged = [r for r in result.records if r.verdict != Verdict.AGREES]
    assert flagged and all(r.element.startswith("h[1]") for r in flagged), \
        {r.element: r.texts for r in flagged}


def test_a_squared_angle_inside_a_sine_is_a_difference_not_a_crash(engine, tmp_path):
    r"""sin(th1)² typed sin(th1**2) in the gravity of ``data/published/
    double_pendulum_springs.toml``: the first equation differs (the small-angle readings,
    tried for the angles the document takes sines and cosines of, had taken th1² for one and
    stopped the comparison with a traceback)."""
    text = (DATA / "double_pendulum_springs.toml").read_text()
    old = "m1*a1*g*sin(th1)"
    assert text.count(old) == 1
    for name in ("double_pendulum.toml", "double_pendulum.urdf"):
        (tmp_path / name).write_text((DATA / name).read_text())
    path = tmp_path / "doc.toml"
    path.write_text(text.replace(old, "m1*a1*g*sin(th1**2)"))
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    assert [r.element for r in result.records if r.verdict != Verdict.AGREES] == ["Q[1]"]


def _springs_with(tmp_path: Path, old: str, new: str):
    r"""``data/published/double_pendulum_springs.toml`` with ``old`` written as ``new``,
    compared."""
    text = (DATA / "double_pendulum_springs.toml").read_text()
    assert text.count(old) == 1, old
    for name in ("double_pendulum.toml", "double_pendulum.urdf"):
        (tmp_path / name).write_text((DATA / name).read_text())
    path = tmp_path / "doc.toml"
    path.write_text(text.replace(old, new))
    return ComparisonEngine(samples=1000, param_sets=5, seed=SEED).compare(
        load_derivation(path))


#: The double pendulum's second equation, as printed.
SECOND = ("m2*L1*a2*cos(th1 - th2)*ddth1 + (I2 + m2*a2**2)*ddth2 - m2*L1*a2*sin(th1 - th2)"
          "*dth1**2 + m2*a2*g*sin(th2) + k2*(th2 - th1 - r2) = T2")
#: A function of th1 at least 1, near 1 but about th1 = 1, finite everywhere.
BUMP = "(1 + exp(-10**4*(th1 - 1)**2))"


def test_a_row_times_a_narrow_exponential_bump_agrees(tmp_path):
    r"""The second equation, both sides, times 1 + exp(-10⁴(th1 - 1)²) (at least 1, finite
    everywhere): the same equation, and it agrees. Multiplied out, the exponential had been
    split into exp(-10⁴)·exp(2·10⁴ th1)·exp(-10⁴ th1²), which overflows: "not finite at half
    the samples", the system not decided; and factoring the row's common factor took 20 000
    as a power of exp(th1) and ran for minutes."""
    lhs, rhs = SECOND.split(" = ")
    result = _springs_with(tmp_path, SECOND, f"({lhs})*{BUMP} = {rhs}*{BUMP}")
    assert result.equivalent is True, [t for r in result.records for t in r.texts]
    assert all(r.verdict == Verdict.AGREES for r in result.records)


def test_an_error_near_one_state_is_no_familys_doing(tmp_path):
    r"""One gravity term times 1 + exp(-10⁶(th1 - 1)²): an error near th1 = 1 only, which the
    main grid sees and the family grids (80 samples) do not. Q[1] differs; it had been
    "agrees only if every link's products of inertia are zero", products that are zero."""
    result = _springs_with(tmp_path, "m1*a1*g*sin(th1)",
                           "m1*a1*g*sin(th1)*(1 + exp(-10**6*(th1 - 1)**2))")
    assert result.equivalent is False
    wrong = [r for r in result.records if r.verdict != Verdict.AGREES]
    assert [r.element for r in wrong] == ["Q[1]"], [r.texts for r in wrong]
    assert wrong[0].verdict == Verdict.DIFFERS
    assert K.CONDITION not in wrong[0].kinds, wrong[0].texts


#: The double pendulum's equations linearised about hanging rest (th1 = th2 = 0), with the
#: springs' constant terms, and the [assumes] that declares the point.
LINEARISED = [
    "(J1 + m2*L1**2)*ddth1 + m2*L1*a2*ddth2 + (m1*a1 + m2*L1)*g*th1 + k1*(th1 - r1) "
    "- k2*(th2 - th1 - r2) = T1 - T2",
    "m2*L1*a2*ddth1 + (I2 + m2*a2**2)*ddth2 + m2*a2*g*th2 + k2*(th2 - th1 - r2) = T2"]


def _linearised_springs(folder: Path, equations: list[str], declared: str):
    r"""``data/published/double_pendulum_springs.toml`` with ``equations`` for its own and
    ``declared`` added to its ``[assumes]``, compared."""
    text = (DATA / "double_pendulum_springs.toml").read_text()
    start = text.index("equations = [") + len("equations = [")
    text = text[:start] + "\n" + ",\n".join(f'  "{e}"' for e in equations) + "\n" + \
        text[text.index("]", start):]
    assumes = 'families = ["urdf_structure"]\n'
    assert text.count(assumes) == 1
    text = text.replace(assumes, assumes + declared)
    for name in ("double_pendulum.toml", "double_pendulum.urdf"):
        (folder / name).write_text((DATA / name).read_text())
    path = folder / "doc.toml"
    path.write_text(text)
    return ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(
        load_derivation(path))


@pytest.mark.parametrize("constants", [True, False])
def test_a_springs_preload_is_the_models_under_an_equilibrium_potential(tmp_path, constants):
    r"""The double pendulum with springs (rest angles drawn, not 0) linearised about 0, its
    potential declared measured from the equilibrium there: the declaration says springs the
    model lacks balance gravity at the point, not the model's own springs' preload. With the
    springs' constant terms the file agrees; without them it had agreed too (its Q at the
    point taken as zero whatever made it); now Q[1] and Q[2] differ, each lacking its
    spring's constant."""
    eqs = LINEARISED if constants else [e.replace("(th1 - r1)", "th1").replace(
        "(th2 - th1 - r2)", "(th2 - th1)") for e in LINEARISED]
    result = _linearised_springs(tmp_path, eqs, 'linearised_about = { th1 = 0.0, th2 = 0.0 }\n'
                                 'potential = "equilibrium"\n')
    wrong = {r.element: r for r in result.records if r.verdict != Verdict.AGREES}
    if constants:
        assert result.equivalent is True and not wrong, {e: r.texts for e, r in wrong.items()}
        return
    assert result.equivalent is False
    assert set(wrong) == {"Q[1]", "Q[2]"}, {e: r.texts for e, r in wrong.items()}
    assert "-k2*r2" in " ".join(wrong["Q[2]"].texts), wrong["Q[2]"].texts
    # named as the constants they are: cos(th1) is 1 at the point, no name of its own
    named = [t for t in wrong["Q[1]"].texts if "the document lacks" in t]
    assert named and "-k1*r1" in named[0] and "cos" not in named[0], wrong["Q[1]"].texts


def test_an_angle_wrapped_into_one_turn_differs_where_springs_pull(tmp_path):
    r"""The hip spring's angle written wrapped, atan2(sin th1, cos th1), as code that keeps
    angles in [−π, π] does: the same as th1 on one turn, not beyond, where the spring (linear
    in the joint's angle) pulls harder. Positions were drawn in [−π, π] only, and the file
    agreed; a model with springs draws them in two turns."""
    result = _springs_with(tmp_path, "k1*(th1 - r1)", "k1*(atan2(sin(th1), cos(th1)) - r1)")
    assert result.equivalent is False
    assert [r.element for r in result.records if r.verdict != Verdict.AGREES] == ["Q[1]"]


def test_a_dropped_inertia_is_named_beside_a_terms_wrong_units(engine, tmp_path):
    r"""The arm with link 2 taken as a point mass (I2 dropped from every element) and the
    first link's inertia declared in kg: A[1,1] has a term of inconsistent units (I1, right
    as a number) and lacks I2. The missing moment is named, and first; the units had been
    taken as the element's error and nothing else was named ("truth − document = I2")."""
    result = _arm_with_I1_in_kg(engine, tmp_path, "point_mass2")
    assert result.equivalent is False
    a11 = next(r for r in result.records if r.element == "A[1,1]")
    assert a11.verdict == Verdict.DIFFERS
    assert a11.diagnoses[0].kind == K.POINT_MASS, a11.texts
    assert K.DIMENSION in a11.kinds
    kinds = [c.kind for c in result.causes if "A[1,1]" in c.elements]
    assert kinds and kinds[0] == CauseKind.POINT_MASS, result.causes


def test_equations_linearised_about_rest_declared_about_another_point(tmp_path):
    r"""The double pendulum's equations linearised about rest, declared linearised about
    th1 = th2 = 0.5: they differ, and the first cause says they are the linearisation about
    0, where every equation is right. It had said "the document takes th1 as small … but
    declares no linearisation", of a file that declares one (positions drawn at the point,
    where th1 read as sin th1 holds by coincidence)."""
    result = _linearised_springs(tmp_path, LINEARISED,
                                 "linearised_about = { th1 = 0.5, th2 = 0.5 }\n")
    assert result.equivalent is False
    first = result.causes[0]
    assert first.kind == CauseKind.FILE_ERROR, result.causes
    assert "linearisation about th1 = 0, th2 = 0" in first.explanation, first.explanation
    assert not any(K.SMALL_ANGLE in r.kinds for r in result.records)


def test_a_symbol_mapped_to_another_links_parameter_is_the_cause(tmp_path):
    r"""The double pendulum with ``a2`` valued as the first link's centre of mass
    (``-CZ(link1)``, a slip of the link's name): the elements written with a2 differ, and the
    first cause says that with a2 = -CZ(link2) every equation is right. Only another
    parameter of the same link had been read."""
    old = 'a2 = { value = "-CZ(link2)"'
    result = _springs_with(tmp_path, old, old.replace("link2", "link1"))
    assert result.equivalent is False
    first = result.causes[0]
    assert first.kind == CauseKind.FILE_ERROR, result.causes
    assert "with a2 = -CZ(link2)" in first.explanation and "another link" in first.explanation


def test_a_deviations_term_of_inconsistent_units_is_no_hidden_term(tmp_path):
    r"""The linearised double pendulum with 9.81 written for g in its second equation's
    stiffness term: K[2,2] differs, named as the number for g; Q[2], right at the point (the
    term vanishes there as every deviation's does), agrees with a units note. It had been
    "differs: numerically equal only because the inconsistent term vanishes for this model's
    parameters" — a term in a deviation, which the point makes 0, is no parameter's zero."""
    eqs = [LINEARISED[0], LINEARISED[1].replace("m2*a2*g*th2", "m2*a2*9.81*th2")]
    assert eqs[1] != LINEARISED[1]
    result = _linearised_springs(tmp_path, eqs, "linearised_about = { th1 = 0.0, th2 = 0.0 }\n")
    assert result.equivalent is False
    wrong = [r for r in result.records if r.verdict != Verdict.AGREES]
    assert [r.element for r in wrong] == ["K[2,2]"], {r.element: r.texts for r in wrong}


def test_a_frame_constant_is_one_an_author_writes(tmp_path):
    r"""The Furuta pendulum's equations (``data/published/furuta_equations.toml``) on a URDF
    whose pendulum's centre of mass is 2 cm off its axis, which they leave out: they differ,
    and the missing parallel-axis part is named. Row 2 had been compared with "9869/10000 ×
    the equations of motion" (a ratio the model's proportions made its elements share), its
    A[2,2] said to hold "only if pend is uniform", and the document's own power identity,
    checked after that factor, said broken."""
    urdf = (DATA / "furuta.urdf").read_text()
    old = '<inertial><origin xyz="0 0 -0.15"/>'
    assert urdf.count(old) == 1
    (tmp_path / "furuta.urdf").write_text(urdf.replace(old, '<inertial><origin xyz="0 0.02 '
                                                            '-0.15"/>'))
    (tmp_path / "furuta.toml").write_text((DATA / "furuta.toml").read_text())
    path = tmp_path / "doc.toml"
    path.write_text((DATA / "furuta_equations.toml").read_text())
    result = ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(
        load_derivation(path))
    assert result.equivalent is False
    assert not any(c for c in result.row_factors), result.row_factors
    assert result.energy is not None and result.energy.conserves, result.energy
    a22 = next(r for r in result.records if r.element == "A[2,2]")
    assert a22.verdict == Verdict.DIFFERS and a22.diagnoses[0].kind == K.PARALLEL_AXIS, \
        a22.texts


@pytest.mark.parametrize("planted", [False, True], ids=["right", "K-dropped"])
def test_a_free_motor_constant_dropped_is_named(engine, tmp_path, planted):
    r"""The two-link arm's equations (``published_forms``, Spong's) driven through motors of
    one torque constant K, a parameter the model lacks (``free = true``, kept symbolic on
    both sides: ``tau1 = "K*i1"``), the currents the inputs: right as written; with K
    dropped from the second equation's input, B[2,2] differs, named as the factor K the
    document lacks (free symbols are parameters to name a term by; it was a difference with
    no name)."""
    path = P.write(tmp_path, "arm", "equations", None)
    text = path.read_text()
    for old, new in (('tau1 = "tau1"', 'tau1 = "K*i1"'), ('tau2 = "tau2"', 'tau2 = "K*i2"'),
                     ('tau1 = { input = true, units = "N*m" }',
                      'K = { free = true, units = "N*m/A" }\n'
                      'i1 = { input = true, units = "A" }'),
                     ('tau2 = { input = true, units = "N*m" }',
                      'i2 = { input = true, units = "A" }'),
                     ('= tau1"', '= K*i1"'), ('= tau2"', '= i2"' if planted else '= K*i2"')):
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    path.write_text(text)
    result = engine.compare(load_derivation(path))
    assert result.equivalent is not planted, result.equations
    wrong = {r.element: r for r in result.records if r.verdict != Verdict.AGREES}
    assert set(wrong) == ({"B[2,2]"} if planted else set()), wrong
    if planted:
        said = [(d.kind, d.factor) for d in wrong["B[2,2]"].diagnoses]
        assert said[0] == (K.FACTOR, "1/K") and {k for k, _ in said} <= {K.FACTOR, K.DIMENSION}, \
            wrong["B[2,2]"].texts
