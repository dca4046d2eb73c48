r"""Products of inertia a derivation leaves out. URDFs exported from CAD give every link small
products of inertia (a probe's TurtleBot-like wheel: ixz of 6e-9 kg m²; here 3e-6, 3e-3 of the
wheel's moments: more than the rounding below which a wheel is drawn round,
:mod:`test_round_wheels`); a
derivation in Dhaouadi & Abu Hatab's (v, ω) form of a differential-drive robot (2013) takes the
axes as principal.
The truth carries them (``urdf_structure`` keeps what the URDF has), and the elements they
change differed with terms in strange rational numbers. The family ``principal_axes`` (every
link's inertia about its centre diagonal in its joint's axes) now says why: they "agree only
if" it holds — never "agree": the document is not right as a system — and declared, it binds.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import Verdict
from wheeled_dyn.derivations import load_derivation

DATA = Path(__file__).parent / "data" / "published"
WHEEL = 'ixx="0.0009" ixy="0" ixz="0" iyy="0.0009"'
FAMILY = "every link's products of inertia are zero"


def _doc(tmp_path: Path, declared: bool) -> Path:
    urdf = (DATA / "dd_robot.urdf").read_text()
    assert urdf.count(WHEEL) == 2
    (tmp_path / "dd_robot.urdf").write_text(urdf.replace(WHEEL, WHEEL.replace(
        'ixz="0"', 'ixz="3e-6"')))
    (tmp_path / "dd_robot.toml").write_text((DATA / "dd_robot.toml").read_text())
    text = (DATA / "dd_swivel_vw.toml").read_text().replace('model = "dd_swivel.toml"',
                                                             'model = "dd_robot.toml"')
    if declared:
        text = text.replace('families = ["urdf_structure"]',
                            'families = ["urdf_structure", "principal_axes"]')
    (tmp_path / "doc.toml").write_text(text)
    return tmp_path / "doc.toml"


@pytest.mark.parametrize("declared", [False, True])
def test_products_of_inertia_left_out_are_a_condition(tmp_path, declared):
    result = ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(
        load_derivation(_doc(tmp_path, declared)))
    if declared:
        assert result.equivalent is True, [c.explanation for c in result.causes]
        return
    assert result.equivalent is False
    verdicts = {r.element: r.verdict for r in result.records}
    assert Verdict.DIFFERS not in verdicts.values(), verdicts
    conditional = [r for r in result.records if r.verdict == Verdict.AGREES_IF]
    assert conditional and all(FAMILY in " ".join(r.texts) for r in conditional)



def test_a_declared_family_zeroes_the_products_in_the_corrected_equation(tmp_path):
    r"""The rotary pendulum (``data/published/furuta_products*``, ``furuta_principal``:
    products of inertia in its URDF) in principal axes, declared, with the arm's Coriolis
    term's sign planted wrong: the corrected equation reads in the document's symbols only
    — no product of inertia about a joint's axes (``XZ_pendulum``...), which the family
    makes −MX·MZ/M (zero about the centre) and the file names no symbol for."""
    from shipped_copies import published_copy
    path = published_copy(tmp_path, "furuta_products", "furuta_principal",
                          ("*sin(2*al)*dth*dal", "*sin(2*al)*dth*dal*(-1)"))
    result = ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(
        load_derivation(path))
    (wrong,) = [e for e in result.equations if e.verdict == Verdict.DIFFERS]
    assert wrong.corrected, wrong
    assert not any(f"{k}_" in wrong.corrected for k in ("XY", "XZ", "YZ")), wrong.corrected
