r"""Equations that keep the rolling constraints with their multipliers,
:math:`A\ddot q + n = Bu + G^T\lambda`, :math:`G\dot q = 0`: a document is right only if its
constraints are the model's and its equations are combinations of the true ones *with their
multipliers' terms*. Before, the multipliers' coefficients were never compared: a sign flipped
in G, a constraint left out, a wrong ``[constraints]`` equation, and even a wrong inertia (the
yaw inertia without its wheels' 2 I_m, absorbed into W = A_doc A⁻¹) all "agreed".

Two documents no shipped file covers, both derived independently with SymPy's Lagrange
equations of the first kind (``data/published``):

- the rolling disk (the shipped ``rolling_coin``) in the contact point's (x, y) and Euler
  angles 3-1-3, after Neimark & Fufaev, *Dynamics of Nonholonomic Systems* (1972);
- a differential-drive robot written as ROS tutorials write it (two driven wheels, a caster
  ball fixed to the chassis), in (x, y, θ, φ_R, φ_L) with three multipliers, after Sarkar,
  Yun & Kumar (IJRR 1994) and Fierro & Lewis (1997).

Each correct file is right as a system; each planted error (in G, in ``[constraints]``, in one
inertia element) makes it wrong, the constraint errors named where the file states them and
the inertia error in its own equation only.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.judge.equivalence import Side, decide
from wheeled_dyn.compare.judge.multipliers import multiplier_terms
from wheeled_dyn.compare.records import CauseKind, Verdict
from wheeled_dyn.derivations import load_derivation

DATA = Path(__file__).parent / "data" / "published"
SAMPLES, PARAM_SETS = 200, 3
DISK, ROBOT = "rolling_disk_multipliers.toml", "dd_multipliers.toml"
DISK_G = 'G = "[[1, 0, 0, 0, r*cos(phi)], [0, 1, 0, 0, r*sin(phi)]]"'
#: Planted errors: (file, what the file prints, what is planted, where it is named).
PLANTED = {
    "G sign": (DISK, DISK_G, DISK_G.replace("r*cos(phi)", "-r*cos(phi)"),
               "G: its constraint row 1"),
    "G row left out": (DISK, DISK_G, 'G = "[[1, 0, 0, 0, r*cos(phi)]]"',
                       "1 rolling constraint missing"),
    "G row wrong": (DISK, DISK_G, DISK_G.replace("r*sin(phi)", "r*cos(phi)"),
                    "G: its constraint row 2"),
    "[constraints] sign": (DISK, '"dx + r*cos(phi)*dpsi = 0"', '"dx - r*cos(phi)*dpsi = 0"',
                           "[constraints]: its constraint row 1"),
    "robot G sign": (ROBOT, "[0, 0, 1, -R/(2*L), R/(2*L)]]", "[0, 0, 1, R/(2*L), R/(2*L)]]",
                     "G: its constraint row 3"),
    "no constraints stated": (DISK, DISK_G + "\n\n[constraints]\nequations = "
                              '["dx + r*cos(phi)*dpsi = 0", "dy + r*sin(phi)*dpsi = 0"]', "",
                              "it states no constraints"),
    "G zero row": (DISK, DISK_G, 'G = "[[1, 0, 0, 0, r*cos(phi)], [0, 0, 0, 0, 0]]"',
                   "1 rolling constraint missing"),
}


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)


def _compare(engine, tmp_path: Path, name: str, old: str = "", new: str = ""):
    text = (DATA / name).read_text()
    if old:
        assert old in text, old
        text = text.replace(old, new)
    for own in ("dd_robot.toml", "dd_robot.urdf"):          # the robot's model beside it
        (tmp_path / own).write_text((DATA / own).read_text())
    path = tmp_path / name
    path.write_text(text)
    return engine.compare(load_derivation(path))


@pytest.mark.parametrize("name", [DISK, ROBOT])
def test_the_correct_documents_are_right_with_their_constraints(engine, tmp_path, name):
    result = _compare(engine, tmp_path, name)
    assert result.equivalent is True, [c.explanation for c in result.causes]
    assert result.constraints_agree is True
    assert all(e.verdict == "agrees" for e in result.equations)


@pytest.mark.parametrize("error", sorted(PLANTED))
def test_a_wrong_constraint_makes_the_document_wrong_and_is_named(engine, tmp_path, error):
    name, old, new, named = PLANTED[error]
    result = _compare(engine, tmp_path, name, old, new)
    assert result.equivalent is False
    assert result.constraints_agree is False
    causes = [c.explanation for c in result.causes if c.kind == CauseKind.NOT_EQUIVALENT]
    assert any(named in c for c in causes), causes


def test_a_wrong_inertia_is_not_absorbed_into_the_combination(engine, tmp_path):
    r"""The robot's yaw inertia without its wheels' 2 I_m: with the constraints, the robot
    turns otherwise under the same torques. W = A_doc A⁻¹ takes the wrong row as a combination
    of the true ones; its multipliers' terms are then not that combination's, so equation 3
    differs — and only it (the multipliers' mixing is fitted without the wrong equation)."""
    result = _compare(engine, tmp_path, ROBOT, 'I = "I_c + m_c*d**2 + 2*m_w*L**2 + 2*I_m"',
                      'I = "I_c + m_c*d**2 + 2*m_w*L**2"')
    assert result.equivalent is False
    assert [e.verdict for e in result.equations] == ["agrees", "agrees", "differs", "agrees",
                                                     "agrees"]
    assert result.constraints_agree is True
    # named in the document's symbols with the plainest coefficient: its wheels' two moments
    # are in a fixed ratio (I_m = 9 I_w/16), and 9*I_w/8 was written for 2*I_m
    a33 = next(r for r in result.records if r.element == "A[3,3]")
    assert "(2*I_m in the document's symbols)" in " ".join(a33.texts), a33.texts


def test_a_term_too_much_is_said_before_a_factor_under_an_unstated_family(engine, tmp_path):
    r"""The wheels' rows with the wheel's mass counted twice, :math:`I_w + m_w R^2` (a probe's
    plant): it is "3 × the truth if the wheel is a uniform body", a family the document does
    not state, and exactly :math:`m_w R^2` too much. The cause says the term, not the
    factor (it said the factor)."""
    rows = "[0, 0, 0, I_w, 0],\n        [0, 0, 0, 0, I_w]]"
    text = (DATA / ROBOT).read_text()
    assert rows in text
    result = _compare(engine, tmp_path, ROBOT, rows, rows.replace("I_w", "I_w + m_w*R**2"))
    assert result.equivalent is False
    wrong = {r.element for r in result.records if r.verdict == Verdict.DIFFERS}
    assert wrong == {"A[4,4]", "A[5,5]"}, wrong
    cause = next(c for c in result.causes if "A[4,4]" in c.elements)
    assert cause.kind == CauseKind.EXTRA_TERM and "R**2*m_w too much" in cause.explanation, \
        result.causes


def test_multiplier_terms_allow_any_mixing_of_the_multipliers():
    r"""An identity: a document whose multipliers are an invertible mixing M of the true ones
    (λ = M λ_doc), its equations a combination W of the true ones, has its multipliers'
    coefficients W G^T M recovered exactly; one equation's coefficients disturbed leave the
    others' recovered (they fit without it)."""
    rng = np.random.default_rng(SEED)
    S, n, m = 50, 5, 2
    W = rng.normal(size=(S, n, n)) + 3 * np.eye(n)
    true_L = rng.normal(size=(S, n, m))
    M = rng.normal(size=(S, m, m)) + 2 * np.eye(m)
    doc_L = W @ true_L @ M
    assert np.allclose(np.einsum("sij,sjk->sik", W, multiplier_terms(doc_L, true_L, W)), doc_L)
    doc_L[:, 2, :] += 0.5
    fitted = np.einsum("sij,sjk->sik", W, multiplier_terms(doc_L, true_L, W))
    rest = [0, 1, 3, 4]
    assert np.allclose(fitted[:, rest], doc_L[:, rest])
    assert not np.allclose(fitted[:, 2], doc_L[:, 2])


def test_a_multiplier_coefficient_is_measured_at_its_own_size():
    r"""A row whose inertia is 1e9 times its multipliers' coefficients (a document in other
    units): one coefficient wrong by a tenth of the largest differs (measured against the
    row's inertia it was 1e-10 of it, below the tolerance, and agreed); a row with no
    multiplier term whose true terms are round-off agrees. Identities on arrays: the truth is
    a random positive definite A with n and G, the document W times it."""
    rng = np.random.default_rng(SEED)
    S, n, m = 40, 5, 2
    true_A = np.einsum("sij,skj->sik", *(2 * [rng.normal(size=(S, n, n))])) + n * np.eye(n)
    true = Side(true_A, rng.normal(size=(S, n)), None, rng.normal(size=(S, n, m)))
    W = np.broadcast_to(np.diag([1e9, 1.0, 1.0, 1.0, 1.0]), (S, n, n)).copy()
    doc_L = W @ true.L
    doc_L[:, 1, :] = 0.0                          # row 2 has no multiplier term ...
    true.L[:, 1, :] = 1e-17 * rng.normal(size=(S, m))      # ... the truth's is round-off
    doc = Side(W @ true.A, np.einsum("sij,sj->si", W, true.n), None, doc_L)
    assert [e.verdict for e in decide(doc, true, 1).equations] == [Verdict.AGREES] * n
    doc.L[:, 0, 0] += 0.1 * np.abs(doc.L).max()
    verdicts = [e.verdict for e in decide(doc, true, 1).equations]
    assert verdicts == [Verdict.DIFFERS] + [Verdict.AGREES] * (n - 1), verdicts


def test_only_constraints_stated_wrong_is_named_so(engine, tmp_path):
    r"""A file with ``[constraints]`` and no G: its multiplier terms are those rows', and a
    wrong one is named where the file states it, not as "G"."""
    text = (DATA / DISK).read_text().replace(DISK_G + "\n", "")
    text = text.replace('"dx + r*cos(phi)*dpsi = 0"', '"dx - r*cos(phi)*dpsi = 0"')
    path = tmp_path / "only_constraints.toml"
    path.write_text(text)
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False and result.constraints_agree is False
    causes = [c.explanation for c in result.causes if c.kind == CauseKind.NOT_EQUIVALENT]
    assert any("[constraints]: its constraint row 1" in c for c in causes), causes
    assert not any("G:" in c for c in causes), causes


@pytest.mark.parametrize("factor", ["r*1000000", "(2 + cos(theta))", "100000000"])
def test_a_constraint_row_scaled_is_the_same_constraint(engine, tmp_path, factor):
    r"""A row of G times a factor that does not vanish is the same constraint, its multiplier
    another name: 1e8 too (its multiplier's terms were 6e-7 of the row off, round-off)."""
    result = _compare(engine, tmp_path, DISK, DISK_G,
                      DISK_G.replace("[1, 0, 0, 0, r*cos(phi)]",
                                     f"[{factor}, 0, 0, 0, {factor}*r*cos(phi)]"))
    assert result.constraints_agree is True
    assert result.equivalent is True, [c.explanation for c in result.causes]


def test_the_equation_wrong_with_its_multipliers_is_the_one_named(engine, tmp_path):
    r"""The disk's first equation doubled (A and velocity terms) with its multiplier term as
    G states it: either the first or the fifth equation could be left out of the
    multipliers' fit; the mixing nearest the one G gives names the first."""
    text = (DATA / DISK).read_text()
    first = text.split("equations = [\n")[1].splitlines()[0].strip().strip('",')
    lhs = first.split(" = ")[0]
    result = _compare(engine, tmp_path, DISK, first, f"2*({lhs}) = 0")
    assert [e.verdict for e in result.equations] == ["differs", "agrees", "agrees", "agrees",
                                                     "agrees"]
    # its elements agree in its frame (the equation times 2): the multiplier terms are the
    # difference, and a cause says so (a verdict is never left without one)
    causes = [c for c in result.causes if c.kind == CauseKind.NOT_EQUIVALENT]
    assert any(result.equations[0].label in c.elements for c in causes), result.causes


@pytest.mark.parametrize("factor", ["sin(phi)", "1/cos(theta)"])
def test_a_constraint_row_times_a_vanishing_factor_is_not_the_same(engine, tmp_path, factor):
    r"""G's first row times sin φ (lost where φ = 0) or divided by cos θ (undefined where
    θ = π/2, inside the file's range): not the model's constraints, as an equation so scaled
    is not the true one."""
    result = _compare(engine, tmp_path, DISK, DISK_G,
                      DISK_G.replace("[1, 0, 0, 0, r*cos(phi)]",
                                     f"[{factor}, 0, 0, 0, {factor}*r*cos(phi)]"))
    assert result.constraints_agree is False and result.equivalent is False
    causes = [c.explanation for c in result.causes if c.kind == CauseKind.NOT_EQUIVALENT]
    assert any("vanishes or is unbounded" in c for c in causes), causes


@pytest.mark.parametrize("name, old, new, lost", [
    (DISK, "[1, 0, 0, 0, r*cos(phi)]", "[(sin(phi) - 3/10)**2, 0, 0, 0, "
     "(sin(phi) - 3/10)**2*r*cos(phi)]", True),
    (DISK, "[1, 0, 0, 0, r*cos(phi)]", "[cos(phi)**2, 0, 0, 0, cos(phi)**2*r*cos(phi)]", True),
    (ROBOT, "[0, 0, 1, -R/(2*L), R/(2*L)]]", "[0, 0, cos(theta), -R*cos(theta)/(2*L), "
     "R*cos(theta)/(2*L)]]", True),
    (ROBOT, "[0, 0, 1, -R/(2*L), R/(2*L)]]", "[0, 0, m_c - 2*m_w, -R*(m_c - 2*m_w)/(2*L), "
     "R*(m_c - 2*m_w)/(2*L)]]", True),
    (ROBOT, "[0, 0, 1, -R/(2*L), R/(2*L)]]", "[0, 0, 2 + cos(theta), -R*(2 + cos(theta))/(2*L), "
     "R*(2 + cos(theta))/(2*L)]]", False)])
def test_a_constraint_row_times_a_factor_that_touches_zero_is_lost(engine, tmp_path, name, old,
                                                                   new, lost):
    r"""A stated constraint row times a factor that vanishes without changing sign
    ((sin φ − 0.3)², cos² φ), or whose sign change the samples cannot see for a robot whose
    four true rows have rank three (cos θ), or of the parameters (m_c − 2m_w, zero for a
    robot of other densities): the constraint is lost there (all agreed); 2 + cos θ never
    vanishes."""
    result = _compare(engine, tmp_path, name, old, new)
    assert result.constraints_agree is (not lost), [c.explanation for c in result.causes]
    assert result.equivalent is (not lost)
    if lost:
        assert any("is written times" in c.explanation for c in result.causes
                   if c.kind == CauseKind.NOT_EQUIVALENT), result.causes
        # the row's own line says so too (it read "a rolling constraint of the model")
        if name == ROBOT:
            assert result.constraints[2].startswith("G row 3: a rolling constraint of the "
                                                    "model times "), result.constraints
            assert result.constraints[2].endswith(": lost there"), result.constraints



def test_constraint_rows_mixed_with_weights_singular_at_a_state_lose_a_constraint(engine,
                                                                                  tmp_path):
    r"""The robot's second row replaced by cos θ·row 1 + sin θ·row 2 (no common factor in
    any row; the weights' determinant sin θ changes sign, but the model's four rows of rank
    three have no determinant to compare with): at θ = 0 it is row 1, and the rolling
    constraint is lost there (it agreed)."""
    old = "[cos(theta), sin(theta), 0, -R/2, -R/2]"
    result = _compare(engine, tmp_path, ROBOT, old,
                      "[-sin(theta)*cos(theta) + sin(theta)*cos(theta), cos(theta)**2 + "
                      "sin(theta)**2, 0, -R/2*sin(theta), -R/2*sin(theta)]")
    assert result.constraints_agree is False and result.equivalent is False
    causes = [c.explanation for c in result.causes if c.kind == CauseKind.NOT_EQUIVALENT]
    assert any("fewer independent constraints than the model's at" in c and "theta = 0" in c
               for c in causes), causes

#: The robot's three rows as its file prints them: sideways, rolling forward, yaw.
LATERAL, FORWARD, YAW = ("[-sin(theta), cos(theta), 0, 0, 0]",
                         "[cos(theta), sin(theta), 0, -R/2, -R/2]",
                         "[0, 0, 1, -R/(2*L), R/(2*L)]")


def _robot_rows(engine, tmp_path, *rows: str):
    old = f"[{LATERAL},\n        {FORWARD},\n        {YAW}]"
    text = (DATA / ROBOT).read_text()
    assert text.count(old) == 1
    return _compare(engine, tmp_path, ROBOT, old, "[" + ",\n        ".join(rows) + "]")


def test_rows_whose_factors_vanish_apart_still_state_the_constraints(engine, tmp_path):
    r"""The forward-rolling row written twice, times cos θ and times sin θ, beside the others:
    each row's factor vanishes somewhere, but never both, so the four rows state the three
    constraints everywhere (it was said lost where cos θ = 0); with factors that vanish
    together, the constraint is lost where they do."""
    def times(f: str, row: str) -> str:
        return "[" + ", ".join(f"{f}*({x.strip()})" for x in row[1:-1].split(",")) + "]"
    result = _robot_rows(engine, tmp_path, times("cos(theta)", FORWARD),
                         times("sin(theta)", FORWARD), LATERAL, YAW)
    assert result.constraints_agree is True, [c.explanation for c in result.causes]
    assert result.equivalent is True
    # ... but times cos θ and times sin φ_R, both zero at θ = π/2, φ_R = 0: lost there (it
    # agreed once each factor's zeros were found covered by the other row)
    result = _robot_rows(engine, tmp_path, times("cos(theta)", FORWARD),
                         times("sin(phi_R)", FORWARD), LATERAL, YAW)
    said = [c.explanation for c in result.causes if c.kind == CauseKind.NOT_EQUIVALENT]
    assert result.constraints_agree is False and result.equivalent is False, said
    assert any("fewer independent constraints than the model's at" in c for c in said), said


@pytest.mark.parametrize("weight", ["(cos(theta) - 1/3)", "(cos(theta) - 1/3)**2"])
def test_rows_mixed_with_weights_singular_away_from_special_positions_lose_one(
        engine, tmp_path, weight):
    r"""The yaw row replaced by the forward row plus a weight times the yaw row: where
    cos θ = 1/3 (no special position) it is the forward row again, and the yaw constraint is
    lost there, whether the weights' determinant changes sign or only touches zero (both
    agreed: no row has a factor, and the model's four rows of rank three have no determinant
    to compare with). The rows' least independence is searched for."""
    def plus(a: str, w: str, b: str) -> str:
        return "[" + ", ".join(f"({x.strip()}) + {w}*({y.strip()})" for x, y in
                               zip(a[1:-1].split(","), b[1:-1].split(","))) + "]"
    result = _robot_rows(engine, tmp_path, LATERAL, FORWARD, plus(FORWARD, weight, YAW))
    assert result.constraints_agree is False and result.equivalent is False
    said = [c.explanation for c in result.causes if c.kind == CauseKind.NOT_EQUIVALENT]
    assert any("fewer independent constraints than the model's at" in c and
               ("theta = 1.231" in c or "theta = -1.231" in c) for c in said), said

def test_a_constraint_stated_twice_is_still_the_models(engine, tmp_path):
    r"""The robot's G with a fourth row, the sum of its first two (a dependent row, four
    multipliers): the same constraints. The model's own rows are four of rank three here; a
    determinant taken between three of each changed sign through the states where those three
    are dependent, and the rows were said to be "times a factor that vanishes"."""
    old = "[0, 0, 1, -R/(2*L), R/(2*L)]]"
    result = _compare(engine, tmp_path, ROBOT, old,
                      "[0, 0, 1, -R/(2*L), R/(2*L)],\n"
                      "        [cos(theta) - sin(theta), sin(theta) + cos(theta), 0, -R/2, "
                      "-R/2]]")
    assert result.constraints_agree is True
    assert result.equivalent is True, [c.explanation for c in result.causes]


def test_constraints_stated_where_the_file_drops_the_rolling_say_so(engine, tmp_path):
    r"""The disk's file with ``rolling = "none"`` and its G: not the model's constraints, and
    the cause says it is the file's setting that drops them (it said only "constraints the
    model does not have", though the body rolls)."""
    result = _compare(engine, tmp_path, DISK, 'rolling = "multipliers"', 'rolling = "none"')
    assert result.equivalent is False
    causes = [c.explanation for c in result.causes if c.kind == CauseKind.NOT_EQUIVALENT]
    assert any('rolling = "none"' in c for c in causes), causes


def test_two_wrong_equations_leave_the_right_ones_right(engine, tmp_path):
    r"""The robot's two wheel equations each with a wrong inertia (2 I_w and 3 I_w): those
    two differ, the other three are right. Its G has four rows of rank three (two per wheel);
    its four columns were counted as multipliers, so two equations of five were never left
    out of the multipliers' fit and all five were "no combination of the true equations"."""
    result = _compare(engine, tmp_path, ROBOT, "[0, 0, 0, I_w, 0],\n        [0, 0, 0, 0, I_w]]",
                      "[0, 0, 0, 2*I_w, 0],\n        [0, 0, 0, 0, 3*I_w]]")
    assert [e.verdict for e in result.equations] == ["agrees", "agrees", "agrees", "differs",
                                                     "differs"]
    assert result.equivalent is False


def test_three_equations_wrong_leave_the_wheels_right(tmp_path):
    r"""The robot's file with no family declared (its base's centre of mass is then drawn off
    the x axis its equations assume: the three base equations differ for those parameters,
    agreeing only if the URDF's structure holds). Three wrong equations are more than the
    multipliers' fit can leave out (two of five, three multipliers), so each fit took a wrong
    one's weights and the left wheel's equation, right, was "no combination of the true
    equations". The document's multiplier terms are the truth's mixed as its constraint rows
    mix them; with that mixing both wheel equations are right."""
    engine = ComparisonEngine(samples=1000, param_sets=5, seed=2026)
    result = _compare(engine, tmp_path, ROBOT, 'families = ["urdf_structure"]', "families = []")
    assert [e.verdict for e in result.equations] == ["agrees_if", "agrees_if", "agrees_if",
                                                     "agrees", "agrees"]
    assert result.equivalent is False


#: The seed's eccentric rolling disk (seed 000, 4.8: its model has no rolling constraint, the
#: rolling is the holonomic map x = R θ) written in (x, θ) with x' = R θ' kept by a multiplier
#: (Goldstein, *Classical Mechanics*, 3rd ed., sec. 2.4, undetermined multipliers).
FREE_X = '''
title = "Rolling disk, x kept with a multiplier"
model = "rolling_disk"

[coordinates]
positions = ["x", "theta"]
kind = "holonomic"
rolling = "multipliers"
configuration = { x = "x", theta = "theta" }

[symbols]
M = { value = "M(disk)", units = "kg" }
MZ = { value = "MZ(disk)", units = "kg*m" }
J = { value = "YY(disk)", units = "kg*m**2" }
R = { value = "R", units = "m" }
g = { value = "g", units = "m/s**2" }

[matrices]
A = "[[M, MZ*cos(theta)], [MZ*cos(theta), J]]"
C = "[[0, -MZ*sin(theta)*dtheta], [0, 0]]"
Q = "[0, -MZ*g*sin(theta)]"
G = "[[1, -R]]"
'''


def test_constraint_rows_on_a_model_without_rolling_constraints_are_not_its(engine, tmp_path):
    r"""A model whose coordinates leave it no rolling constraint (its G has no rows): the
    file's G is no constraint of the model, said as such (it raised NumPy's "zero-size array
    to reduction operation maximum" from the constraint check)."""
    path = tmp_path / "free_x.toml"
    path.write_text(FREE_X)
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    causes = [c.explanation for c in result.causes if c.kind == CauseKind.NOT_EQUIVALENT]
    assert any("no rolling constraint" in c for c in causes), causes
