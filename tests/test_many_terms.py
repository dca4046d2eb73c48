r"""One term wrong among many: a derivation written from a URDF whose joints and inertias are
turned by rpy rotations (``data/published/turned_arm*``, written for the tests: Lagrange's
equations of the arm in Khalil's parameters, the rotations' sines and cosines as the decimals
they are), whose elements have dozens of terms each. A sign or a factor of one term was "no
single-term diagnosis": the terms are tried one at a time only up to a few; all of them are
now fitted at once, and the term is named as the document writes it (its decimals, not the
fractions the parser reads them as)."""

from __future__ import annotations

from pathlib import Path

import pytest
import sympy as sp

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.judge.diagnose import MAX_TERMS
from wheeled_dyn.compare.records import DiagnosisKind as K
from wheeled_dyn.derivations import load_derivation

DATA = Path(__file__).parent / "data" / "published"


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=200, param_sets=3, seed=SEED)


def _compare(engine, tmp_path: Path, old: str = "", new: str = ""):
    for name in ("turned_arm.toml", "turned_arm.urdf"):
        (tmp_path / name).write_text((DATA / name).read_text())
    text = (DATA / "turned_arm_lagrange.toml").read_text()
    if old:
        assert text.count(old) == 1, old
        text = text.replace(old, new)
    path = tmp_path / "doc.toml"
    path.write_text(text)
    return engine.compare(load_derivation(path))


def test_the_turned_arm_agrees_and_its_elements_have_many_terms(engine, tmp_path):
    result = _compare(engine, tmp_path)
    assert result.equivalent is True
    assert all(r.verdict == "agrees" for r in result.records)
    d = load_derivation(tmp_path / "doc.toml")
    Q = d.read_off(assume=True, unscale=False).Q
    assert len(sp.Add.make_args(sp.expand(Q[0]))) > MAX_TERMS


@pytest.mark.parametrize("old, new, kind, text", [
    (" - 0.241704332108682*MZ_upper*g*sin(q1)", " + 0.241704332108682*MZ_upper*g*sin(q1)",
     K.SIGN, "the term 0.241704332108682*MZ_upper*g*sin(q1) has the wrong sign"),
    (" + 0.36*XX_upper*ddq1", " + 0.6*XX_upper*ddq1", K.FACTOR,
     "the term 3*XX_upper/5 is 5/3 × what fits"),
])
def test_one_term_wrong_among_many_is_named(engine, tmp_path, old, new, kind, text):
    result = _compare(engine, tmp_path, old, new)
    assert result.equivalent is False
    flagged = [r for r in result.records if r.verdict != "agrees"]
    assert len(flagged) == 1, [(r.element, r.texts) for r in flagged]
    assert flagged[0].kinds[0] == kind and text in flagged[0].texts[0], flagged[0].texts
