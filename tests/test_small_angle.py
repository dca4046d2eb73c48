"""A small-angle approximation in equations compared as exact is named as such.

The planar balancing robot of ``examples/my_planar_robot.toml`` (right: it agrees) written
as a textbook linearises it without saying so — sin φ ≈ φ, cos φ ≈ 1, as in the linearised
inverted pendulum of Ogata, *Modern Control Engineering*, §3-5, or Franklin, Powell &
Emami-Naeini, *Feedback Control of Dynamic Systems*, §2.1 — every element it changes differs
and is named a small-angle approximation in φ, in one cause; a different error in the same
element (a factor 2, a sign) is not called one. On the same file, one wheel's spin inertia
left out is named by its term's factor, not also as a body treated as a point mass."""

from __future__ import annotations

from pathlib import Path

import pytest

from wheeled_dyn.compare import ComparisonEngine
from wheeled_dyn.compare.records import CauseKind, DiagnosisKind, Verdict
from wheeled_dyn.derivations import load_derivation

EXAMPLE = Path(__file__).parent.parent / "examples" / "my_planar_robot.toml"
#: Small grid: the approximations are structural.
SAMPLES, PARAM_SETS = 200, 2

A_EXACT = "-m_b*l*cos(phi)"
Q_EXACT = 'Q = "[0, -m_b*g*l*sin(phi)]"'
C_EXACT = "m_b*l*sin(phi)*dphi"


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=7)


def _compare(engine, tmp_path, replacements):
    text = EXAMPLE.read_text()
    for old, new in replacements:
        assert old in text
        text = text.replace(old, new)
    path = tmp_path / "doc.toml"
    path.write_text(text)
    result = engine.compare(load_derivation(path))
    return {r.element: r for r in result.records}, result.causes


def _small_angle(record):
    return [d for d in record.diagnoses if d.kind == DiagnosisKind.SMALL_ANGLE]


def test_the_exact_file_agrees_and_has_no_small_angle(engine, tmp_path):
    records, _ = _compare(engine, tmp_path, [])
    assert all(r.verdict == Verdict.AGREES for r in records.values())
    assert not any(_small_angle(r) for r in records.values())


def test_every_approximated_element_is_named_in_one_cause(engine, tmp_path):
    records, causes = _compare(engine, tmp_path, [
        (A_EXACT, "-m_b*l"), (Q_EXACT, 'Q = "[0, -m_b*g*l*phi]"'),
        (C_EXACT, "m_b*l*phi*dphi")])
    changed = {"A[1,2]", "A[2,1]", "Q[2]", "C[1,2]"}
    for element in changed:
        assert records[element].verdict == Verdict.DIFFERS, element
        (found,) = _small_angle(records[element])
        assert found.position == "phi"
    assert {d.fits for e in ("A[1,2]", "A[2,1]") for d in _small_angle(records[e])} \
        == {"cos(phi)"}
    assert _small_angle(records["Q[2]"])[0].written == "phi"
    assert _small_angle(records["Q[2]"])[0].fits == "sin(phi)"
    others = set(records) - changed - {e for e in records if e.startswith("h[")}
    assert all(records[e].verdict == Verdict.AGREES for e in others)
    (cause,) = [c for c in causes if c.kind == CauseKind.SMALL_ANGLE]
    assert changed <= set(cause.elements) and "phi" in cause.explanation


def test_one_term_of_a_sum_is_named(engine, tmp_path):
    r"""A[1,2] written as two halves, cos φ dropped from one: the approximation is named in
    the one term it is made in."""
    records, _ = _compare(engine, tmp_path, [
        ("[[m_b + 2*m_w + 2*J_w/r**2, " + A_EXACT + "]",
         "[[m_b + 2*m_w + 2*J_w/r**2, -m_b*l*cos(phi)/2 - m_b*l/2]")])
    (found,) = _small_angle(records["A[1,2]"])
    assert (found.written, found.fits, found.term) == ("1", "cos(phi)", "-l*m_b/2")
    assert records["A[2,1]"].verdict == Verdict.AGREES


@pytest.mark.parametrize("q,kind", [
    ('Q = "[0, -2*m_b*g*l*sin(phi)]"', DiagnosisKind.FACTOR),
    ('Q = "[0, m_b*g*l*sin(phi)]"', DiagnosisKind.SIGN)])
def test_other_errors_are_not_called_small_angles(engine, tmp_path, q, kind):
    records, causes = _compare(engine, tmp_path, [(Q_EXACT, q)])
    assert records["Q[2]"].verdict == Verdict.DIFFERS
    assert not _small_angle(records["Q[2]"])
    assert any(d.kind == kind for d in records["Q[2]"].diagnoses)
    assert not any(c.kind == CauseKind.SMALL_ANGLE for c in causes)


def test_one_terms_factor_is_not_also_called_a_point_mass(engine, tmp_path):
    r"""One wheel's spin inertia left out of A[1,1] (J_w/r² for 2 J_w/r²): the term's factor
    1/2 names it; the residual J_w/r² is not offered as a body treated as a point mass."""
    records, causes = _compare(engine, tmp_path, [("2*m_w + 2*J_w/r**2", "2*m_w + J_w/r**2")])
    a = records["A[1,1]"]
    assert [(d.term, d.factor) for d in a.diagnoses if d.kind == DiagnosisKind.FACTOR] == \
        [("J_w/r**2", "1/2")]
    assert not any(d.kind == DiagnosisKind.POINT_MASS for d in a.diagnoses)
    assert [c.kind for c in causes if "A[1,1]" in c.elements] == [CauseKind.FACTOR]
