r"""An element is judged at its own size, not at its row's: the sprung double pendulum
(``data/published/double_pendulum*``, Meirovitch's Lagrange equations) with every length
scaled — to millimetres, its inertias are 1e-4 of its gravity terms (accelerations of 1 in SI
units are small there); to 1e8 m, its gravity terms 1e-8 of its inertias — and one term of an
inertia or of a gravity term doubled: the typo agreed at the row's scale ("16 agree" beside
"not right as a system"), it is now named. A term that overflows somewhere (1e299 where it is
finite) no longer sets its row's scale either: a typo beside it agreed. The correct file agrees
at every size."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import DiagnosisKind as K, Verdict
from wheeled_dyn.derivations import load_derivation

DATA = Path(__file__).parent / "data" / "published"
#: Planted typos: (what the file prints, what is planted, the element flagged, the term
#: doubled: named whole, or by the truth − document it leaves).
TYPOS = {
    "A": ("(I2 + m2*a2**2)*ddth2", "(I2 + 2*m2*a2**2)*ddth2", "A[2,2]", "2*a2**2*m2"),
    "Q": ("m1*a1*g*sin(th1) + m2*L1*g*sin(th1)", "m1*a1*g*sin(th1) + 2*m2*L1*g*sin(th1)",
          "Q[1]", "2*L1*g*m2*sin(th1)"),
}


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=200, param_sets=3, seed=SEED)


def _scaled(folder: Path, factor: float, old: str = "", new: str = "") -> Path:
    r"""The pendulum with every length times ``factor`` (inertias times its square)."""
    def lengths(m: re.Match) -> str:
        return m.group(1) + " ".join(repr(float(x) * factor) for x in m.group(2).split()) + '"'

    def moments(m: re.Match) -> str:
        return m.group(1) + repr(float(m.group(2)) * factor ** 2) + '"'
    urdf = (DATA / "double_pendulum.urdf").read_text()
    urdf = re.sub(r'((?:xyz|length|radius)=")([^"]*)"', lengths, urdf)
    urdf = re.sub(r'(i[xyz][xyz]=")([^"]*)"', moments, urdf)
    (folder / "double_pendulum.urdf").write_text(urdf)
    (folder / "double_pendulum.toml").write_text((DATA / "double_pendulum.toml").read_text())
    text = (DATA / "double_pendulum_springs.toml").read_text()
    assert old in text
    (folder / "doc.toml").write_text(text.replace(old, new))
    return folder / "doc.toml"


@pytest.mark.parametrize("factor, typo", [(1e-3, "A"), (1e8, "Q"), (1e-3, None)])
def test_a_typo_is_found_whatever_the_units(engine, tmp_path, factor, typo):
    old, new, element, term = TYPOS[typo] if typo else ("", "", "", "")
    result = engine.compare(load_derivation(_scaled(tmp_path, factor, old, new)))
    flagged = {r.element: r for r in result.records if r.verdict != Verdict.AGREES}
    if typo is None:
        assert result.equivalent is True and not flagged, set(flagged)
        return
    assert set(flagged) == {element}, set(flagged)
    assert flagged[element].diagnoses[0].kind == K.FACTOR, flagged[element].texts
    assert term.removeprefix("2*") in " ".join(flagged[element].texts), flagged[element].texts


def test_an_overflowing_term_does_not_hide_a_typo_beside_it(engine, tmp_path):
    old = "m1*a1*g*sin(th1)"
    path = _scaled(tmp_path, 1.0, "(J1 + m2*L1**2)*ddth1", "(2*J1 + m2*L1**2)*ddth1")
    text = path.read_text()
    path.write_text(text.replace(old, f"{old} + exp(exp(exp(3 + th1)))/10000000", 1))
    flagged = {r.element for r in engine.compare(load_derivation(path)).records
               if r.verdict != Verdict.AGREES}
    assert "A[1,1]" in flagged, flagged
