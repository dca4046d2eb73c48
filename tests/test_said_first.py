r"""What a cause line says first, for three errors people make (each with its planted file
from :mod:`published_forms`: Spong, Hutchinson & Vidyasagar's two-link arm; Florian's
cart-pole):

- the centripetal term of a two-link arm dropped from C (C[2,1] written 0): the cause "C was
  not derived from this A" now says the term h[2] lacks, as the element's record does;
- the pole's equation divided by m·l with its gravity term left outside the division: the
  cause is that term not divided as the rest of its row is (it was its units alone, which
  follow from it);
- the same with the whole gravity term of several additive terms left undivided: it was not
  named at all (only single additive terms were tried).
"""

from __future__ import annotations

import published_forms as P
from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import CauseKind
from wheeled_dyn.derivations import load_derivation

#: Engine grid.
SAMPLES, PARAM_SETS = 200, 3
CENTRIPETAL = '["dq1*l1*lc2*m2*sin(q2)", "0"]'
DIVIDED = "(4*ddtheta*l**2*m/3 + ddx*l*m*cos(theta) - g*l*m*sin(theta))/(m*l) = 0"


def _compare(path):
    engine = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)
    return engine.compare(load_derivation(path))


def _planted(folder, system: str, form: str, old: str, new: str):
    path = P.write(folder, system, form, None)
    text = path.read_text()
    assert text.count(old) == 1, (old, text)
    path.write_text(text.replace(old, new))
    return path


def test_a_dropped_centripetal_term_is_said_in_the_c_cause(tmp_path):
    result = _compare(_planted(tmp_path, "arm", "matrices", CENTRIPETAL, '["0", "0"]'))
    assert result.equivalent is False
    cause = result.causes[0]
    assert cause.kind == CauseKind.C_INCONSISTENT_WITH_A, [c.kind for c in result.causes]
    assert "h[2]:dq1*dq1 lacks l1*lc2*m2*sin(q2)" in cause.explanation, cause.explanation


def test_a_term_left_out_of_the_division_is_said_before_its_units(tmp_path):
    undivided = "(4*ddtheta*l**2*m/3 + ddx*l*m*cos(theta))/(m*l) - g*l*m*sin(theta) = 0"
    result = _compare(_planted(tmp_path, "pole", "divided", DIVIDED, undivided))
    assert result.equivalent is False
    kinds = [c.kind for c in result.causes if "Q[2]" in c.elements]
    assert kinds[0] == CauseKind.FACTOR, [(c.kind, c.explanation) for c in result.causes]
    first = next(c for c in result.causes if "Q[2]" in c.elements)
    assert "not divided as the rest of its row is" in first.explanation


def test_a_whole_term_of_several_left_undivided_is_named(tmp_path):
    row = P.arm_forms(None)["equations"][0]
    gravity = " + g*lc2*m2*cos(q1 + q2) + g*(l1*m2 + lc1*m1)*cos(q1) = tau1"
    assert row.endswith(gravity)
    inertia = "I1 + I2 + lc1**2*m1 + m2*(l1**2 + 2*l1*lc2*cos(q2) + lc2**2)"
    divided = (f"({row[:-len(gravity)]})/({inertia}) + g*lc2*m2*cos(q1 + q2) "
               f"+ g*(l1*m2 + lc1*m1)*cos(q1) = tau1/({inertia})")
    result = _compare(_planted(tmp_path, "arm", "equations", row, divided))
    assert result.equivalent is False
    q1 = next(r for r in result.records if r.element == "Q[1]")
    assert "not divided as the rest of its row is" in q1.diagnoses[0].text, q1.diagnoses


def test_a_row_that_differs_is_not_said_to_be_the_same_equations(tmp_path):
    r"""The cart-pole's x declared the other way round: the cart's row is compared times −1
    (most of its elements agree so), but it differs — it is not "−1 × the equations of
    motion (the same equations)"; a right row times −1 (Kane's form) still is."""
    from wheeled_dyn.report.summary import row_factor_line
    result = _compare(_planted(tmp_path, "pole", "equations", 'x = "x"', 'x = "-x"'))
    assert result.equivalent is False
    assert result.row_factors[0] == "-1" and result.equations[0].verdict.value == "differs"
    line = row_factor_line(result)
    assert "the same equations" not in line and "row 1 is compared with -1" in line, line
    kane = _compare(P.write(tmp_path, "pole", "kane", None))
    assert kane.equivalent is True and "the same equations" in row_factor_line(kane)


def test_units_of_a_linearisation_point_are_said_as_such():
    r"""A right document linearised about r = 0.2 m writes m2*(1/5)**2 for m2 r0²: its units
    look wrong (kg beside kg m²); the note says the point's numbers carry them, not only
    that a symbol's declared units are wrong."""
    import numpy as np
    from wheeled_dyn.compare.engine.equations import units_notes
    from wheeled_dyn.compare.judge.draft import ElementDraft
    from wheeled_dyn.compare.records import DiagnosisKind as K
    from wheeled_dyn.compare.records import Verdict, diagnosis
    draft = ElementDraft(element="A[1,1]", key="A", index=(0, 0), verdict=Verdict.AGREES,
                         diagnoses=[diagnosis(K.DIMENSION, "term m2/25 is kg beside kg·m^2")],
                         D=np.ones(3), T=np.ones(3), scale=1.0)
    plain, = units_notes([draft])
    linearised, = units_notes([draft], (("theta", 0.3), ("r", 0.2)))
    assert "declared units are probably wrong" in plain
    assert "linearisation point (theta = 0.3, r = 0.2)" in linearised, linearised
    assert units_notes([draft], (("theta", 0.0),)) == [plain]


def test_a_mass_left_out_is_no_point_mass(tmp_path):
    r"""The cart's inertia written M for M + m: under the cart-pole's declared proportions the
    pole's mass is 3 Ixx/l², and it was named "the moment Ixx(pole) × 3/l² is missing: a
    point mass". The term the entry lacks is one of the document's symbols: that is its
    name, and the cause says it."""
    from wheeled_dyn.compare.records import DiagnosisKind as K
    cart = "ddx*(M + m)"
    result = _compare(_planted(tmp_path, "pole", "equations", cart, "ddx*M"))
    a11 = next(r for r in result.records if r.element == "A[1,1]")
    assert not any(d.kind == K.POINT_MASS for d in a11.diagnoses), a11.diagnoses
    cause = next(c for c in result.causes if "A[1,1]" in c.elements)
    assert cause.kind == CauseKind.MISSING_PHYSICS and "A[1,1] lacks m" in cause.explanation
