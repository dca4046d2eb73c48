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
  document inverted differs", an inverse of the true one); every input of the wrong sign or
  doubled (a cart-pole with both joints driven, written for the tests): the true inertia
  times one number, which nothing tells from an inertia so scaled — nothing said either.

And a factor of two names the document lacks is that factor, not one name written for the
other, unless writing the one for the other (or exchanging them) makes the truth (two
differential-drive robots of ``data/published``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import sympy as sp

import published_forms as P
from balancer_solved import balancer_solved
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


DATA = Path(__file__).parent / "data" / "published"


def _planted(tmp_path: Path, model: str, form: str, old: str, new: str) -> Path:
    r"""``data/published/<form>.toml`` (model ``<model>``) with ``old`` planted as ``new``."""
    for name in (model + ".toml", model + ".urdf"):
        if (DATA / name).exists():
            (tmp_path / name).write_text((DATA / name).read_text())
    text = (DATA / (form + ".toml")).read_text()
    assert text.count(old) == 1, old
    path = tmp_path / "doc.toml"
    path.write_text(text.replace(old, new))
    return path


@pytest.mark.parametrize("c", [-1, 2])
def test_every_input_of_the_wrong_sign_or_scaled_is_no_inverted_inertia(engine, tmp_path, c):
    r"""The cart-pole with both joints driven, solved (``cart_pole_driven_solved.toml``), its
    inputs all negated or doubled: the inertia read back from them is the true one times -1
    or 1/2, symmetric — and an inertia so scaled, with every other term, reads the same.
    It was "the inertia matrix the document inverted differs: A[1,1] opposite sign ...;
    Q[2] ...; h[1] ..."; now only the inputs' elements are named."""
    for name in ("cart_pole_driven.toml", "cart_pole.urdf"):
        (tmp_path / name).write_text((DATA / name).read_text())
    text = (DATA / "cart_pole_driven_solved.toml").read_text()
    F, tau = sp.symbols("F tau")
    lines = []
    for line in text.split("\n"):
        if line.strip().startswith('"dd'):
            left, right = line.strip().strip('",').split(" = ")
            right = sp.sstr(sp.sympify(right).xreplace({F: c * F, tau: c * tau}))
            line = f'  "{left} = {right}",'
        lines.append(line)
    path = tmp_path / "doc.toml"
    path.write_text("\n".join(lines))
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    assert "the inertia matrix the document inverted" not in _said(result), _said(result)
    flagged = {r.element for r in result.records if r.verdict != "agrees"}
    assert flagged and all(e.startswith("B[") for e in flagged), flagged


def test_a_factor_dropped_is_no_symbol_written_for_another(engine, tmp_path):
    r"""A differential-drive robot's first equation (``dd_offset_wheels.toml``) with a
    factor R/L dropped from one term, R³/L² → R²/L: the element is the truth times L/R; L
    for R in that term would not make the truth (it holds L elsewhere). It was "L where R
    fits", and is the factor the document lacks."""
    path = _planted(tmp_path, "dd_offset", "dd_offset_wheels",
                    "- R**3*a*dphi_L**2*m_b/(4*L**2)", "- R**2*a*dphi_L**2*m_b/(4*L)")
    result = engine.compare(load_derivation(path))
    record = next(r for r in result.records if r.element == "h[1]:dphi_L*dphi_L")
    assert record.verdict == "differs"
    assert not any(k == "swap" for k in record.kinds), record.texts
    assert "lacks a factor R/L" in record.texts[0], record.texts


def test_two_names_exchanged_are_named_as_exchanged(engine, tmp_path):
    r"""The differential-drive robot in (v, ω) (``dd_swivel_vw.toml``) with its yaw input
    written R(τR − τL)/L where L(τR − τL)/R fits: the two exchanged ("R**2 where L**2 fits"
    named a square the document does not write)."""
    path = _planted(tmp_path, "dd_swivel", "dd_swivel_vw", "= L*(tau_R - tau_L)/R",
                    "= R*(tau_R - tau_L)/L")
    result = engine.compare(load_derivation(path))
    flagged = {r.element: r for r in result.records if r.verdict == "differs"}
    assert set(flagged) == {"B[2,1]", "B[2,2]"}, {e: r.texts for e, r in flagged.items()}
    assert all(r.texts[0].startswith("swap: L and R exchanged") for r in flagged.values()), \
        {e: r.texts for e, r in flagged.items()}


def test_a_plain_inertia_error_is_not_read_back_as_a_combination():
    r""":func:`~wheeled_dyn.compare.judge.unsolved.read_back_explains` on arrays: two
    uncoupled equations, an input on the second, the document plain but for its first
    inertia (a + ε for a). Read back (rows times A A_doc⁻¹) its inputs are the truth's and
    its first gravity term differs — one entry, as many as the document as printed differs
    in: that is no better reading, and its first row is not to be explained as a
    combination (its inertia's error would be hidden in the frame)."""
    from wheeled_dyn.compare.grid.arrays import Arrays
    from wheeled_dyn.compare.judge.unsolved import read_back_explains
    rng = np.random.default_rng(SEED)
    S = 50
    a, c, g1, g2 = (rng.uniform(1.0, 2.0, S) for _ in range(4))
    A = np.zeros((S, 2, 2))
    A[:, 0, 0], A[:, 1, 1] = a, c
    A_doc = A.copy()
    A_doc[:, 0, 0] = 1.3 * a
    B = np.zeros((S, 2, 1))
    B[:, 1, 0] = 1.0
    Q = np.stack([g1, g2], axis=1)
    truth, doc = Arrays(A=A, Q=Q), Arrays(A=A_doc, Q=Q.copy(), B=B.copy())
    assert not read_back_explains(doc, truth, B)
    # solved for its accelerations, the same document is read back: one entry, where as
    # printed every entry of A, B and Q differs
    inv = np.linalg.inv(A_doc)
    solved = Arrays(A=np.broadcast_to(np.eye(2), A.shape).copy(),
                    Q=np.einsum("sij,sj->si", inv, Q), B=inv @ B)
    assert read_back_explains(solved, truth, B)


@pytest.mark.parametrize("changed, cause, named", [
    # the m1 lc1 g cos q1 gravity term doubled: no term the document leaves out
    (lambda c, phi: (c, phi + sp.Matrix([P.m1 * P.lc1 * P.g * sp.cos(P.q1), 0])),
     "a constant factor", "Q[1]: the term g*lc1*m1*cos(q1) is 2 × what fits"),
    # a term the truth does not have, m2 g l1 sin q2 in the second equation
    (lambda c, phi: (c, phi + sp.Matrix([0, P.m2 * P.g * P.l1 * sp.sin(P.q2)])),
     "a term the truth does not have", "Q[2]: the document has g*l1*m2*sin(q2) too much"),
    # half of the m2 lc2 g cos(q1 + q2) gravity term of the first equation dropped
    (lambda c, phi: (c, phi - sp.Matrix([P.m2 * P.lc2 * P.g * sp.cos(P.q1 + P.q2) / 2, 0])),
     "a constant factor", "Q[1]: the term g*lc2*m2*cos(q1 + q2) is 1/2 × what fits"),
])
def test_a_term_read_back_is_named_against_the_truths_entry(engine, tmp_path, changed, cause,
                                                            named):
    r"""An entry read back before solving that differs by a term is named against the
    truth's entry in the document's symbols: a term twice (it was "truth − document =
    −g·lc1·m1·cos q1", and the cause a term the document leaves out), a term the truth does
    not have, a term halved."""
    D, c, phi = P.arm(None)
    c, phi = changed(c, phi)
    result = engine.compare(load_derivation(_solved(tmp_path, D, c, phi)))
    assert result.equivalent is False
    said = _said(result)
    assert named in said, said
    explained = [c.explanation for c in result.causes]
    assert any(named in e or cause in e for e in explained), explained
    assert not any("leaves out" in e for e in explained), explained


@pytest.mark.parametrize("tau, q1, reading", [
    ([P.tau2, P.tau1], P.q1, "tau1 ↔ tau2"),          # the inputs exchanged
    ([-P.tau1, P.tau2], P.q1, "tau1 → −tau1"),        # one input's sign
    ([P.tau1, P.tau2], -P.q1, "q1 → −q1"),            # the first angle the other way
])
@pytest.mark.parametrize("convention", ["unknown", "declared"])
def test_a_solved_form_in_another_convention_is_read_so(engine, tmp_path, tau, q1, reading,
                                                         convention):
    r"""A form solved for the accelerations, right but for its convention: its inputs
    exchanged, one input's sign, or q1 measured the other way (the solved equations of
    :math:`q_1' = -q_1`, whose acceleration is :math:`-\ddot q_1`). No element of a solved row
    agrees under any reading, so the search counts the equations each reading makes right:
    a file that declares its convention unknown is compared under the reading and agrees (it
    was "not right as a system", with a term's sign named where there is none); one that
    declares the convention has the reading as its cause."""
    D, c, phi = P.arm(None)
    flip = {P.q1: q1, P.dq1: P.dq1 * (1 if q1 == P.q1 else -1)}
    D, c, phi = (M.xreplace(flip) for M in (D, c, phi))
    path = _solved(tmp_path, D, c, phi, sp.Matrix(tau))
    if q1 != P.q1:                                     # row 1 is the equation of q1' = -q1
        lines = path.read_text().splitlines()
        at = next(i for i, x in enumerate(lines) if x.strip().startswith('"ddq1 ='))
        lines[at] = lines[at].replace('"ddq1 = ', '"ddq1 = -(') [:-2] + ')",'
        path.write_text("\n".join(lines) + "\n")
    if convention == "unknown":
        path.write_text('convention = "unknown"\n' + path.read_text())
    result = engine.compare(load_derivation(path))
    explained = " ".join(c.explanation for c in result.causes)
    assert reading in explained, explained
    assert result.equivalent is (convention == "unknown")


@pytest.mark.parametrize("planted", [False, True], ids=["right", "wheel-spin-dropped"])
def test_a_solved_form_names_a_wheels_spin_inertia_dropped_as_a_point_mass(engine, tmp_path,
                                                                          planted):
    r"""The ROS balancer in heading speed and pitch solved for its accelerations
    (:func:`balancer_solved.balancer_solved`): right, it agrees; with the wheels' spin inertia
    :math:`2J_w/R^2` dropped from M11, the inertia read back names it as the matrix form's
    element does — the wheels' own moment about their axles, times :math:`R^{-2}` in heading
    coordinates: a point mass (it was "a term the document leaves out",
    ``missing_physics``)."""
    from wheeled_dyn.compare.records import CauseKind
    path = balancer_solved(tmp_path, *(("2*J_w/R**2", "0") if planted else ()))
    result = engine.compare(load_derivation(path))
    assert result.equivalent is not planted, result.equations
    if not planted:
        return
    kinds = [c.kind for c in result.causes]
    assert CauseKind.POINT_MASS in kinds and CauseKind.MISSING_PHYSICS not in kinds, \
        result.causes
    said = next(c.explanation for c in result.causes if c.kind == CauseKind.POINT_MASS)
    assert "A[1,1]: the moment of inertia Iyy(left_wheel) + Iyy(right_wheel) about its own " \
        "centre of mass × R**(-2) is missing, a point mass (truth − document = 2*J_w/R**2)" \
        in said, said


@pytest.mark.parametrize("old, new, divisor", [
    ("", "", False),
    ("Det = \"M11*M22*M33 - M11*M23*M32", "Det = \"M11*M22*M33", True),
    ("f2 = \"-L1*a2*dth2**2*m2*sin(th1 - th2) - L1*g*m2*sin(th1)",
     "f2 = \"-L1*a2*dth2**2*m2*sin(th1 - th2) + L1*g*m2*sin(th1)", False),
], ids=["right", "determinant-term-dropped", "one-gravity-sign"])
def test_a_wrong_determinant_is_named_as_the_divisor_every_solved_equation_shares(
        engine, tmp_path, old, new, divisor):
    r"""The double pendulum on a cart solved by Cramer's rule
    (``data/published/cart_double_pendulum_solved.toml``) with the term
    :math:`-M_{11}M_{23}M_{32}` dropped from its determinant: every differing element of the
    three solved equations is the truth's times one function (det M / Det), and that is named
    on each, with an ``upstream_step`` cause (the elements had no diagnosis). Right, nothing
    differs; with one gravity term's sign wrong in the equations solved, the elements' ratios
    are no one function and the divisor is not named."""
    from wheeled_dyn.compare.records import CauseKind, DiagnosisKind
    data = Path(__file__).parent / "data" / "published"
    for name in ("cart_double_pendulum.toml", "cart_double_pendulum.urdf"):
        (tmp_path / name).write_text((data / name).read_text())
    text = (data / "cart_double_pendulum_solved.toml").read_text()
    assert text.count(old) == 1 or not old, old
    path = tmp_path / "doc.toml"
    path.write_text(text.replace(old, new) if old else text)
    result = engine.compare(load_derivation(path))
    assert result.equivalent is (not old), result.equations
    wrong = [r for r in result.records if r.verdict != "agrees"]
    named = [r for r in wrong if r.diagnoses and r.diagnoses[0].kind ==
             DiagnosisKind.COMMON_DIVISOR]
    if divisor:
        assert len(wrong) >= 6 and named == wrong, [(r.element, r.texts) for r in wrong]
        assert {int(r.element[2]) for r in wrong} == {1, 2, 3}
        assert any(c.kind == CauseKind.UPSTREAM_STEP for c in result.causes), result.causes
    else:
        assert not named, [(r.element, r.texts) for r in named]


def test_the_default_grid_judges_a_solved_form_with_a_number_in_its_velocity_terms(tmp_path):
    r"""The arm solved for its accelerations with link 1's own inertia dropped
    (``published_forms``' ``dropped``), on the engine's default grid, where h's velocity
    products are compared on a subset of the samples: it differs, named as the point mass. A
    gravity number trial of an h element was evaluated on every sample against h's subset
    (a probe's "operands could not be broadcast together with shapes (5000,) (1000,)":
    a traceback; the tests' smaller grids compare h on every sample)."""
    from wheeled_dyn.compare.records import CauseKind
    result = ComparisonEngine(seed=SEED).compare(
        load_derivation(P.write(tmp_path, "arm", "solved", "dropped")))
    assert result.equivalent is False
    assert any(c.kind == CauseKind.POINT_MASS for c in result.causes), result.causes
