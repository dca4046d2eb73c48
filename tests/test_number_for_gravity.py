r"""A number written where the model's gravity fits: the cart-pole's equations (Florian 2007,
:func:`published_forms.cart_pole`) with Earth's 9.81 written for :math:`g` in the pole's
gravity term, as simulation code writes it. The comparison draws g as it draws every
parameter, so the document differs (it holds for g = 9.81 only); it was named by its units
alone ("has kg, expected kg·m·s⁻²"), and now as the number written where g fits. A number
near 9.81 that is not g's place (the term lacking l as well) is not so named."""

from __future__ import annotations

import published_forms as P
import pytest
import sympy as sp
from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import CauseKind
from wheeled_dyn.compare.records import DiagnosisKind as K
from wheeled_dyn.compare.records import Verdict
from wheeled_dyn.derivations import load_derivation

#: Engine grid.
SAMPLES, PARAM_SETS = 200, 3
GRAVITY = "g*l*m*sin(theta)"


@pytest.mark.parametrize("number", ["9.81", "9.8", "9.80665"])
def test_earths_gravity_written_for_g_is_named(tmp_path, number):
    result = _compare(tmp_path, f"{number}*l*m*sin(theta)")
    assert result.equivalent is False
    q2 = next(r for r in result.records if r.element == "Q[2]")
    assert q2.verdict == Verdict.DIFFERS
    first = q2.diagnoses[0]
    assert first.kind == K.SWAP, q2.diagnoses
    assert f"the number {float(number):g} is written where g fits" in first.text
    assert all(r.verdict == Verdict.AGREES for r in result.records if r.element != "Q[2]")


def test_a_number_that_is_not_gs_place_is_not_so_named(tmp_path):
    result = _compare(tmp_path, "9.81*m*sin(theta)")
    q2 = next(r for r in result.records if r.element == "Q[2]")
    assert q2.verdict == Verdict.DIFFERS
    assert not any("written where g fits" in d.text for d in q2.diagnoses), q2.diagnoses


def _compare(folder, gravity: str):
    path = P.write(folder, "pole", "equations", None)
    text = path.read_text()
    assert text.count(GRAVITY) == 1
    path.write_text(text.replace(GRAVITY, gravity))
    engine = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)
    return engine.compare(load_derivation(path))




def test_a_fraction_of_earths_gravity_is_named(tmp_path):
    r"""A rod pendulum (derivation-format.md's example) with 9.81/2 written where g/2 fits
    (read as 4.905): named as such, the equations holding for g = 9.81 only."""
    path = tmp_path / "rod.toml"
    path.write_text(P.ROD.format(gravity="9.81/2*m*l*sin(theta)"))
    engine = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)
    result = engine.compare(load_derivation(path))
    q1 = next(r for r in result.records if r.element == "Q[1]")
    first = q1.diagnoses[0]
    assert first.kind == K.SWAP, q1.diagnoses
    assert "the number 4.905 is written where g/2 fits" in first.text, first.text
    assert "hold for g = 9.81 only" in first.text


@pytest.mark.parametrize("units", [True, False])
def test_the_number_is_named_with_units_declared_or_not(tmp_path, units):
    r"""The arm of :mod:`published_forms` written out, 9.81 for g in its second equation's
    gravity term: named whether or not the file declares its symbols' units (it was named
    only where the units said "has kg·m², expected kg·m²·s⁻²" first)."""
    import re
    path = P.write(tmp_path, "arm", "equations", None)
    text = path.read_text()
    term = "g*lc2*m2*cos(q1 + q2) = tau2"
    assert text.count(term) == 1, text
    text = text.replace(term, term.replace("g*", "9.81*"))
    if not units:
        text = re.sub(r', units = "[^"]*"', "", text)
        assert "units" not in text.split("[symbols]")[1]
    path.write_text(text)
    engine = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    wrong = [r for r in result.records if r.verdict != Verdict.AGREES]
    assert [r.element for r in wrong] == ["Q[2]"], wrong
    first = wrong[0].diagnoses[0]
    assert first.kind == K.SWAP, wrong[0].diagnoses
    assert "the number 9.81 is written where g fits" in first.text, first.text


@pytest.mark.parametrize("error", [None, "sign"])
def test_a_symbol_valued_as_earths_gravity_is_the_cause(tmp_path, error):
    r"""The arm written out with ``g = 9.81`` in ``[symbols]``: its gravity terms differ (the
    model's g is drawn) and the first cause says that with g valued as the model's gravity
    every equation is right. With a planted sign besides, no such cause: it would not make
    every equation right."""
    path = P.write(tmp_path, "arm", "equations", error)
    text = path.read_text()
    line = 'g = { value = "g", units = "m/s**2" }'
    assert text.count(line) == 1
    path.write_text(text.replace(line, line.replace('"g"', '"9.81"')))
    engine = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    assert {r.element for r in result.records if r.verdict != Verdict.AGREES} >= {"Q[1]", "Q[2]"}
    said = [c for c in result.causes if "valued as the model's gravity" in c.explanation]
    if error is None:
        assert said and said[0] is result.causes[0], result.causes
        assert said[0].kind == CauseKind.FILE_ERROR
        assert "hold for g = 9.81 only" in said[0].explanation
    else:
        assert not said, said


@pytest.mark.parametrize("written, advice", [("-g", "-g"), ("g", "g")])
def test_a_symbol_valued_as_minus_earths_gravity_is_read_with_either_sign(tmp_path, written,
                                                                          advice):
    r"""``g = "-9.81"`` in ``[symbols]``, the equations writing ``written`` for the gravity:
    the cause names the value that makes every equation right — "-g" where they write -g
    (it advised "g", which flips both), "g" where they write g (no cause was said)."""
    path = P.write(tmp_path, "arm", "equations", None)
    text = path.read_text()
    line = 'g = { value = "g", units = "m/s**2" }'
    head, eqs = text.split("equations = [")
    eqs = eqs.replace("g*", f"({written})*")
    path.write_text(head.replace(line, line.replace('"g"', '"-9.81"')) + "equations = [" + eqs)
    engine = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)
    result = engine.compare(load_derivation(path))
    assert result.equivalent is False
    first = result.causes[0]
    assert first.kind == CauseKind.FILE_ERROR, result.causes
    assert f'(value g as "{advice}")' in first.explanation, first.explanation


def test_earths_gravity_in_a_solved_form_is_no_hundred_g(tmp_path):
    r"""A number a hundred times Earth's gravity (981, as SymPy writes 9.81 over a common
    denominator of 100) is no "100*g": only simple fractions of g are read as it."""
    from wheeled_dyn.compare.judge.numbers import _gravity_parts
    assert _gravity_parts(sp.Integer(981) * sp.Symbol("x")) == []
    assert _gravity_parts(sp.Rational(981, 200) * sp.Symbol("x")) == [
        (sp.Rational(981, 200), sp.Rational(1, 2))]
