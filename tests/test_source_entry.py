r"""One wrong entry of the equations a document solved, found where its inertia cannot be read
back from its inputs (:mod:`wheeled_dyn.compare.judge.source_entry`): fewer inputs than
coordinates, and a column of :math:`[B\;Q\;H]` that alone carries a row.

- The identity itself, on random numbers: rows :math:`D = W(T + \delta e_re_c^T)` give back
  the planted :math:`\delta` at :math:`(r, c)` and no other entry; errors in two rows give
  none.
- A cart-pole solved for the accelerations as a textbook does (:mod:`published_forms`), the
  pole taken as a point mass (:math:`ml^2` for :math:`\tfrac43ml^2`): every element of the
  pole's solved equation differed with "truth − document = …" of eleven factors, or with
  nothing; now each names :math:`A_{22}` and the pole's own moment. Two errors planted at
  once: no one entry is claimed.
- A reaction-wheel pendulum after M. W. Spong, P. Corke, R. Lozano, *Nonlinear control of the
  reaction wheel pendulum*, Automatica 37 (2001) (``data/published/rwp*``), its two equations
  :math:`d_{11}\ddot q_1 + d_{12}\ddot q_2 + \phi_1 = 0`, :math:`d_{21}\ddot q_1 +
  d_{22}\ddot q_2 = \tau` solved by SymPy, with one error planted in :math:`d_{11}` before
  solving: the pendulum's own moment dropped, the wheel's dropped, :math:`l_{c1}` written for
  :math:`l_1` — each named where it was made.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import sympy as sp

import published_forms as P
from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.judge.source_entry import _entry_values, _explains, _pair_values
from wheeled_dyn.compare.records import DiagnosisKind as K
from wheeled_dyn.derivations import load_derivation

DATA = Path(__file__).parent / "data" / "published"
#: Engine grid.
SAMPLES, PARAM_SETS = 200, 3
#: Agreement of the recovered entry with the planted one (well-conditioned random systems).
TOL = 1e-8
HEAD = "one entry differs"


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)


def _system(rng: np.random.Generator, S: int = 50, n: int = 3, m: int = 8):
    T = rng.normal(size=(S, n, m))
    W = rng.normal(size=(S, n, n)) + 3.0 * np.eye(n)
    return T, W


@pytest.mark.parametrize("r, c", [(0, 0), (1, 4), (2, 7)])
def test_the_planted_entry_and_no_other_is_found(r: int, c: int) -> None:
    T, W = _system(np.random.default_rng(SEED + r))
    delta = np.random.default_rng(SEED).uniform(0.5, 2.0, len(T))
    V = T.copy()
    V[:, r, c] += delta
    D = W @ V
    found = []
    for row in range(T.shape[1]):
        values = _entry_values(T, D, row)
        if values is None:
            continue
        found += [(row, col) for col in range(T.shape[2])
                  if _explains(T, D, [(row, col)], values[:, col]) is not None]
        if row == r:
            assert np.abs(values[:, c] - delta).max() <= TOL * np.abs(delta).max()
    assert found == [(r, c)]


def test_a_symmetric_pair_of_the_inertia_is_found_with_its_combination() -> None:
    r"""The coupling :math:`A_{12} = A_{21}` wrong by the same amount in both source
    equations (module :mod:`~wheeled_dyn.compare.judge.source_entry`): no one entry explains
    the document; the pair's :math:`\delta` is the planted one, and the :math:`W` found is the
    combination planted."""
    T, W = _system(np.random.default_rng(SEED + 7))
    delta = np.random.default_rng(SEED).uniform(0.5, 2.0, len(T))
    V = T.copy()
    V[:, 0, 1] += delta
    V[:, 1, 0] += delta
    D = W @ V
    singles = [(row, col) for row in range(T.shape[1])
               if (values := _entry_values(T, D, row)) is not None
               for col in range(T.shape[2])
               if _explains(T, D, [(row, col)], values[:, col]) is not None]
    assert singles == []
    found = _pair_values(T, D, 0, 1)
    assert found is not None and np.abs(found - delta).max() <= TOL * np.abs(delta).max()
    weights = _explains(T, D, [(0, 1), (1, 0)], found)
    assert weights is not None and np.abs(weights - W).max() <= TOL * np.abs(W).max()
    assert _pair_values(T, D, 0, 2) is None or _explains(
        T, D, [(0, 2), (2, 0)], _pair_values(T, D, 0, 2)) is None


def test_errors_in_two_rows_are_no_one_entry() -> None:
    T, W = _system(np.random.default_rng(SEED))
    V = T.copy()
    V[:, 0, 1] += 1.0
    V[:, 2, 5] -= 0.5
    D = W @ V
    assert all(_entry_values(T, D, row) is None for row in range(T.shape[1]))


def _texts(result, row: int) -> list[str]:
    return [x.text for r in result.records if r.verdict != "agrees" and r.index[0] == row
            for x in r.diagnoses[:1]]


def test_cart_pole_solved_with_a_point_mass_names_the_pole(engine, tmp_path):
    result = engine.compare(load_derivation(P.write(tmp_path, "pole", "solved", "point_mass")))
    assert result.equivalent is False
    texts = _texts(result, 1)
    assert texts and all(HEAD in t and "A[2,2]" in t and "Ixx(pole)" in t and "point mass"
                         in t for t in texts), texts
    assert any(c.kind == K.POINT_MASS for c in result.causes)


def test_two_errors_before_solving_are_no_one_entry(engine, tmp_path):
    path = P.write(tmp_path, "pole", "solved", "point_mass")
    cart, pole = P.cart_pole("point_mass")
    pole = pole + 2 * P.m * P.g * P.l * sp.sin(P.th)              # and gravity's sign
    (sol,) = sp.solve([cart, pole], [P.ddx, P.ddth], dict=True)
    lines = path.read_text().splitlines()
    at = next(i for i, line in enumerate(lines) if line.strip().startswith('"ddtheta ='))
    lines[at] = f'  "ddtheta = {sp.sstr(sp.simplify(sol[P.ddth]))}"'
    path.write_text("\n".join(lines) + "\n")
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    assert not any(HEAD in x.text for r in result.records for x in r.diagnoses)


q1, q2, dq1, dq2, ddq1, ddq2 = sp.symbols("q1 q2 dq1 dq2 ddq1 ddq2", real=True)
m1, m2, l1, lc1, I1, I2, g, tau = sp.symbols("m1 m2 l1 lc1 I1 I2 g tau", real=True)


def _rwp_solved(tmp_path: Path, d11: sp.Expr) -> Path:
    r"""``data/published/rwp_combined.toml`` with its equations replaced by Spong, Corke &
    Lozano's, :math:`d_{11}` as given, solved for the accelerations."""
    for name in ("rwp.toml", "rwp.urdf"):
        (tmp_path / name).write_text((DATA / name).read_text())
    phi1 = -(m1 * lc1 + m2 * l1) * g * sp.sin(q1)
    eqs = [d11 * ddq1 + I2 * ddq2 + phi1, I2 * ddq1 + I2 * ddq2 - tau]
    sol = sp.solve(eqs, [ddq1, ddq2], dict=True)[0]
    text = (DATA / "rwp_combined.toml").read_text()
    text = text[:text.index("equations = [")] + "equations = [\n" + ",\n".join(
        f'  "{a} = {sp.sstr(sp.simplify(sol[a]))}"' for a in (ddq1, ddq2)) + "\n]\n"
    path = tmp_path / "rwp_solved.toml"
    path.write_text(text)
    return path


D11 = m1 * lc1 ** 2 + m2 * l1 ** 2 + I1 + I2


def test_rwp_solved_right_agrees(engine, tmp_path):
    result = engine.compare(load_derivation(_rwp_solved(tmp_path, D11)))
    assert result.equivalent is True


@pytest.mark.parametrize("d11, kind, said", [
    (D11 - I1, K.POINT_MASS, "Iyy(pend)"),          # the pendulum's own moment dropped
    (D11 - I2, K.POINT_MASS, "Iyy(wheel)"),         # the wheel's dropped from d11
    (D11.subs(l1, lc1), K.SWAP, "l1 and lc1"),      # lc1 written for l1 in m2 l1²
])
def test_rwp_solved_error_in_d11_is_named(engine, tmp_path, d11, kind, said):
    result = engine.compare(load_derivation(_rwp_solved(tmp_path, d11)))
    assert result.equivalent is False
    texts = _texts(result, 0) + _texts(result, 1)
    assert texts and all(HEAD in t and "A[1,1]" in t and said in t for t in texts), texts
    assert any(c.kind == kind and "A[1,1]" in c.explanation for c in result.causes)


def test_a_factor_of_one_entry_is_said_with_its_equal(engine, tmp_path):
    r"""One entry of a source row a factor of the truth's — the cart's coupling
    :math:`ml\cos\theta\,\ddot\theta` written twice, then solved — is the same equations as
    every other entry of that row the inverse factor × the truth's (a row's common factor
    goes into its weight): both are said, not the one as a fact."""
    path = P.write(tmp_path, "pole", "solved", None)
    cart, pole = P.cart_pole(None)
    cart = cart + P.m * P.l * sp.cos(P.th) * P.ddth
    (sol,) = sp.solve([cart, pole], [P.ddx, P.ddth], dict=True)
    lines = path.read_text().splitlines()
    for name, acc in (("ddx", P.ddx), ("ddtheta", P.ddth)):
        at = next(i for i, x in enumerate(lines) if x.strip().startswith(f'"{name} ='))
        end = "," if lines[at].rstrip().endswith(",") else ""
        lines[at] = f'  "{name} = {sp.sstr(sp.simplify(sol[acc]))}"{end}'
    path.write_text("\n".join(lines) + "\n")
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    said = [t for r in result.records if r.verdict != "agrees" for t in r.texts[:1]]
    assert said and all("A[1,2]: the document is 2 × the truth" in t and "or, the same "
                        "equations: every other entry of equation 1 is 1/2 × the truth's" in t
                        for t in said), said


def test_a_residual_read_back_claims_no_term_missing():
    r"""An entry read back whose truth − document no single or double term reads (φ₂ of
    the arm with cos(q1 + q2) written cos q1 + cos q2: terms too much and terms missing at
    once) is said as truth − document, of no kind that claims a term missing."""
    from wheeled_dyn.compare.judge.unsolved import entry_part
    rng = np.random.default_rng(SEED)
    a, b = rng.uniform(-3, 3, 200), rng.uniform(-3, 3, 200)
    T = np.cos(a + b)
    D = np.cos(a) + np.cos(b)
    part = entry_part("Q[2]", T, D, float(np.abs(T).max()), [], None, {"Q[2]": sp.cos(q1 + q2)})
    assert part.kind == K.RESIDUAL, part


def test_a_term_read_back_as_too_much_is_named_as_the_document_writes_it():
    r"""An entry read back with a term the truth's entry does not have (the cart's row with the
    pole's equation eliminated, its :math:`\ddot\theta` coefficient written 0 where the true
    combination leaves :math:`-I\cos\theta/l`: the source entry has :math:`I\cos\theta/l`
    too much) carries that term as the document has it, as a record's extra terms are; its
    cause says "has too much I*cos(theta)/l", not the negative."""
    from wheeled_dyn.compare.judge.entry_terms import read_back_diagnosis
    from wheeled_dyn.compare.judge.unsolved import entry_part
    rng = np.random.default_rng(SEED)
    I_, l_, th = rng.uniform(0.5, 2.0, 200), rng.uniform(0.5, 2.0, 200), rng.uniform(-3, 3, 200)
    I, l, theta = sp.symbols("I l theta")
    T = l_ * np.cos(th)                                   # the truth's entry: m l cos(theta)
    D = T + I_ * np.cos(th) / l_                          # the document's: I cos(theta)/l more
    bases = [(I, I_), (l, l_), (sp.cos(theta), np.cos(th))]
    part = entry_part("A[1,2]", T, D, float(np.abs(T).max()), bases, None,
                      {"A[1,2]": l * sp.cos(theta)})
    assert part.kind == K.EXTRA, part
    said = read_back_diagnosis("read back: ", [part])
    assert said.terms == (sp.sstr(I * sp.cos(theta) / l),), said


def test_a_cause_of_missing_terms_says_the_terms_said_missing():
    r"""An element read back with a term too much in the source equations (the frame's entry
    lacking it: the same difference said in two frames) gets the cause of its first term
    kind, a term missing; that cause says the term as missing ("lacks"), never the read-back's
    "has too much" beside "a term the document leaves out"."""
    from wheeled_dyn.compare.causes.root import term_causes
    from wheeled_dyn.compare.records import Diagnosis, ElementRecord, Verdict
    back = Diagnosis(K.EXTRA, "read back …: A[1,2]: the document has I*cos(theta)/l too much",
                     "", terms=("I*cos(theta)/l",))
    frame = Diagnosis(K.MISSING, "terms: the document lacks -I*cos(theta)/l", "",
                      terms=("-I*cos(theta)/l",))
    record = ElementRecord("A[1,2]", "A", (0, 1), Verdict.DIFFERS,
                           (back, Diagnosis(K.MISSING, "missing: the document has 0"), frame),
                           "0", "0", "-I*cos(theta)/l", "-I*cos(theta)/l", 1.0, 1.0)
    (cause,) = term_causes([record], set())
    assert cause.kind == "missing_physics"
    assert cause.explanation.endswith("A[1,2] lacks -I*cos(theta)/l"), cause.explanation


def test_an_input_sign_before_solving_is_one_cause(engine, tmp_path):
    r"""The planar WIP (``data/published/wip_planar_x.toml``: the wheel torque T drives the
    cart's equation as T/r and the body's as −T) solved for the accelerations with the
    body's −T written +T before solving: one wrong entry of the source equations, B[2,1],
    gives the document at every sample. Every solved element it reaches says it first, also
    where a term of the solved expression reads as a sign of its own, so the report has one
    sign cause naming them all, not a second for that term (a probe's ballbot, its motor's
    sign in the tilt equation)."""
    text = (DATA / "wip_planar_x.toml").read_text()
    head = text[:text.index("[matrices]")]
    eqs = [sp.sympify(e.replace("=", "-(", 1) + ")") for e in (
        "(m + 2*m_w + 2*J_w/r**2)*ddx + m*l*cos(theta)*ddtheta - m*l*sin(theta)*dtheta**2 = T/r",
        "m*l*cos(theta)*ddx + (I_b + m*l**2)*ddtheta - m*g*l*sin(theta) = T")]
    ddx, ddtheta = sp.symbols("ddx ddtheta")
    (sol,) = sp.solve(eqs, [ddx, ddtheta], dict=True)
    path = tmp_path / "wip_solved.toml"
    path.write_text(head + "[matrices]\nequations = [\n" + "".join(
        f'  "{name} = {sp.sstr(sp.simplify(sol[acc]))}",\n'
        for name, acc in (("ddx", ddx), ("ddtheta", ddtheta))) + "]\n")
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    wrong = {r.element for r in result.records if r.verdict != "agrees"}
    signs = [c for c in result.causes if c.kind == "sign"]
    assert len(signs) == 1 and set(signs[0].elements) == wrong, (wrong, result.causes)
    assert "B[2,1]" in signs[0].explanation
