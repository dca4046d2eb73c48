r"""Links a document leaves out. A differential-drive robot as ROS users write it often has a
swivel caster (a continuous swivel joint carrying a fork, a continuous joint carrying the
caster wheel); a derivation of the robot in the (v, ω) form of Dhaouadi & Abu Hatab, *Dynamic
modelling of differential-drive mobile robots using Lagrange and Newton-Euler methodologies*,
Adv. Robot. Autom. 2:107 (2013), written for this file, leaves the caster out. Its
coordinates hold the caster's joints
(they name neither), so the truth carries the caster's mass with the chassis, and the document
names the chassis's mass, centre and inertia by ``base_link`` alone.

The elements the caster changes used to "differ" with no diagnosis. They now "agree only if
caster_fork, caster_wheel carry no mass" — a condition, never an agreement: the document is
not right as a system with the caster's mass. Declaring the family
(``massless(caster_fork, caster_wheel)``) binds: the truth is computed without it. A
planted error stays an error under either."""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.grid.assumptions import left_out
from wheeled_dyn.compare.records import CauseKind, Verdict
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.errors import DerivationError

DATA = Path(__file__).parent / "data" / "published"
SAMPLES, PARAM_SETS = 200, 3
DOC = "dd_swivel_vw.toml"
CASTER = "caster_fork, caster_wheel"
DECLARED = ('families = ["urdf_structure"]',
            f'families = ["urdf_structure", "massless({CASTER})"]')
#: A planted error: the wheels' spin inertia dropped from the forward equation's inertia.
DROPPED = ("(m + 2*I_w/R**2)*dv", "m*dv")


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)


def _doc(tmp_path: Path, *edits: tuple[str, str]):
    text = (DATA / DOC).read_text()
    for old, new in edits:
        assert old in text, old
        text = text.replace(old, new)
    for own in ("dd_swivel.toml", "dd_swivel.urdf"):
        (tmp_path / own).write_text((DATA / own).read_text())
    (tmp_path / DOC).write_text(text)
    return load_derivation(tmp_path / DOC)


def _elements(result) -> dict[str, object]:
    return {e.element: e for e in result.records}


def test_the_links_no_symbol_names_are_found(tmp_path):
    assert left_out(_doc(tmp_path)) == ("caster_fork", "caster_wheel")
    named = _doc(tmp_path, ('m_c = { value = "M(base_link)", units = "kg" }',
                            'm_c = { value = "M(base_link)", units = "kg" }\n'
                            'm_k = { value = "M(caster_wheel)", units = "kg" }'))
    assert left_out(named) == ("caster_fork",)


def test_a_left_out_caster_is_a_condition_not_an_agreement(engine, tmp_path):
    result = engine.compare(_doc(tmp_path))
    verdicts = {k: e.verdict for k, e in _elements(result).items()}
    assert Verdict.DIFFERS not in verdicts.values(), verdicts
    conditional = [e for e in result.records if e.verdict == Verdict.AGREES_IF]
    assert {e.element for e in conditional} >= {"A[1,1]", "A[2,2]"}
    assert all(CASTER in " ".join(e.texts) for e in conditional), [e.texts for e in conditional]
    assert result.equivalent is False          # the caster's mass is real


def test_the_declared_family_binds(engine, tmp_path):
    result = engine.compare(_doc(tmp_path, DECLARED))
    assert result.equivalent is True, [c.explanation for c in result.causes]
    assert all(e.verdict == Verdict.AGREES for e in result.records)


@pytest.mark.parametrize("declared", [False, True])
def test_a_planted_error_stays_an_error(engine, tmp_path, declared):
    edits = (DROPPED, DECLARED) if declared else (DROPPED,)
    result = engine.compare(_doc(tmp_path, *edits))
    a11 = _elements(result)["A[1,1]"]
    assert a11.verdict == Verdict.DIFFERS, a11.texts
    assert result.equivalent is False
    if declared:
        assert "2*I_w/R**2" in " ".join(a11.texts)
        # the truth under the declared family: the caster's mass terms are no part of it
        # (they were printed in the truth and in truth − document)
        assert a11.residual == "2*I_w/R**2", a11.residual
        assert "caster" not in (a11.truth or "") and "caster" not in result.equations[0].corrected


@pytest.mark.parametrize("name, expected", [
    ("massless(no_such_link)", "no_such_link"),
    ("massless(base_footprint)", "base_link"),       # it shares its body with base_link
    # a link whose mass a symbol names (m_w = M(left_wheel)): was "unknown model parameter
    # 'M(left_wheel)'", with neither the file nor the declaration named
    ("massless(left_wheel)", "symbols.m_w: M(left_wheel) is the mass or inertia of link "
                             "left_wheel, which assumes.families declares without mass"),
])
def test_a_wrong_declaration_is_one_clear_error(tmp_path, name, expected):
    d = _doc(tmp_path, ('families = ["urdf_structure"]', f'families = ["{name}"]'))
    with pytest.raises(DerivationError) as info:
        ComparisonEngine(samples=20, param_sets=1, seed=SEED).compare(d)
    assert DOC in str(info.value) and expected in str(info.value)


@pytest.mark.parametrize("unknown", [False, True])
def test_one_input_read_with_the_other_sign(engine, tmp_path, unknown):
    r"""The file maps the left torque as ``-tau_L`` where the document's is the model's: two
    elements (its column of B) differ and nothing else. The reading tau_L → −tau_L makes every
    element agree: a cause (the verdicts as declared), and the reading itself where the file
    says its convention is unknown. A gain of two elements was below the three a reading
    needed, so neither was found."""
    edits = [DECLARED, ('tau_l = "tau_L"', 'tau_l = "-tau_L"')]
    if unknown:
        edits.append(('title = "', 'convention = "unknown"\ntitle = "'))
    result = engine.compare(_doc(tmp_path, *edits))
    first = result.causes[0]
    assert first.kind == CauseKind.CONVENTION, result.causes
    if unknown:
        assert result.equivalent is True and "tau_L → −tau_L" in first.explanation
    else:
        assert result.equivalent is False and "tau_l = tau_L" in first.explanation
        assert {r.element for r in result.records if r.verdict == Verdict.DIFFERS} == \
            {"B[1,2]", "B[2,2]"}
