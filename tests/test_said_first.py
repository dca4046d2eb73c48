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


def test_a_factor_is_said_only_where_an_author_could_have_written_it():
    r"""A term "c × what fits" for a c an author types or a simple ratio gives (2, 3/4, 0.999,
    1000 for a unit, 180/π); not for a coincidence of the numbers: 1.179e7 (a term a CAD
    export's rounding is all the truth has of) or 0.8083 (a ratio a family fixes) — a probe's
    differential drive was told "the term −m_w r²/2 is 1.179e+07 × what fits"."""
    import math

    from wheeled_dyn.compare.judge.diagnose import plausible_factor
    for c in (2, -1, 0.5, 0.75, 4 / 3, 16 / 9, 0.999, 1000, 1e-3, 180 / math.pi, 2 * math.pi):
        assert plausible_factor(c), c
    for c in (1.179e7, 0.8083001147348357, 0.0, math.inf, math.nan, 1 + 3.1e-7):
        assert not plausible_factor(c), c


def test_a_dropped_coupling_is_said_by_its_h_term_where_its_c_element_names_none(tmp_path):
    r"""TIAGo's (v, ω) equations as matrices (Fierro & Lewis's M v̇ + V v = B τ,
    :mod:`test_round_wheels`) with :math:`C_{21} = m_cd\omega` written 0: the truth's
    :math:`C_{21}` in the document's symbols carries terms of the wheels' rounding besides
    it, so only h[2]:v*omega names the term; the cause now says it (it said none, every
    record having to name one)."""
    from test_round_wheels import HEAD, V_OMEGA
    matrices = ('A = "[[m_c + 2*m_w + 2*I_w/r**2, -m_c*c], [-m_c*c, I_c + m_c*(d**2 + c**2) '
                '+ 2*m_w*(L + e)**2 + 2*I_m + 2*L**2*I_w/r**2]]"\n'
                'C = "[[0, -m_c*d*omega], [0, 0]]"\n'
                'B = "[[1/r, 1/r], [L/r, -L/r]]"\n')
    text = HEAD.format(form="matrices", coordinates=V_OMEGA, assumes="", eqs="")
    text = text[:text.index("equations = [")] + matrices
    path = tmp_path / "dropped.toml"
    path.write_text(text)
    result = _compare(path)
    cause = next(c for c in result.causes if c.kind == CauseKind.MISSING_PHYSICS)
    assert "h[2]:v*omega lacks d*m_c" in cause.explanation, cause.explanation
