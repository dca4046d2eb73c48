r"""A symbol mapped to another parameter of its link. A newcomer maps the document's symbols to
the model's parameters in the link's own axes, which a CAD export turns: the moment the
derivation calls I2 is IYY(link) where the file wrote IXX(link), the centre of mass's offset
CX where it wrote CY. Every element with the symbol differs and no term is wrong: a probe's
UR5 so mapped had "no single-term diagnosis" only. The file's map stays binding (it differs);
the first cause now says the parameter under which every equation is right.

Spong, Hutchinson & Vidyasagar's two-link arm (:mod:`published_forms`: written out, solved for
the accelerations), its symbols mapped to the wrong axis of their links.
"""

from __future__ import annotations

import published_forms as P
import pytest
from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import CauseKind
from wheeled_dyn.derivations import load_derivation

#: Engine grid.
SAMPLES, PARAM_SETS = 200, 3
#: (the file's map as written for the arm, the wrong one, the cause's reading).
WRONG = {"moment": ('I2 = { value = "IYY(link2)"', 'I2 = { value = "IXX(link2)"',
                    "with I2 = IYY(link2)"),
         "offset": ('lc2 = { value = "CX(link2)"', 'lc2 = { value = "-CZ(link2)"',
                    "with lc2 = CX(link2)")}


def _compare(path):
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED).compare(
        load_derivation(path))


@pytest.mark.parametrize("form", ["equations", "solved", "divided", "combined"])
@pytest.mark.parametrize("which", sorted(WRONG))
def test_a_symbol_mapped_to_another_axis_is_the_first_cause(tmp_path, which, form):
    r"""In every form: the divided and combined ones too, whose rows agree where they are
    divided by the symbol as the file maps it (those elements do not vouch for its map)."""
    right, wrong, said = WRONG[which]
    path = P.write(tmp_path, "arm", form, None)
    text = path.read_text()
    assert right in text
    path.write_text(text.replace(right, wrong))
    result = _compare(path)
    assert result.equivalent is False
    mapped = [c for c in result.causes if said in c.explanation]
    assert mapped and mapped[0].kind == CauseKind.FILE_ERROR, result.causes
    assert all(c.kind == CauseKind.FILE_ERROR for c in result.causes[:result.causes.index(
        mapped[0])]), result.causes           # after the file's other errors only


@pytest.mark.parametrize("error", ["sign", "dropped"])
def test_a_terms_error_is_no_map(tmp_path, error):
    r"""One term wrong under a right map: no symbol read as another parameter makes every
    equation right, and none is said."""
    result = _compare(P.write(tmp_path, "arm", "equations", error))
    assert result.equivalent is False
    assert not any("the file probably maps" in c.explanation for c in result.causes)


@pytest.mark.parametrize("form", ["equations", "solved"])
def test_a_joints_length_for_a_centre_of_mass_is_the_first_cause(tmp_path, form):
    r"""The arm's URDF with link 1's centre of mass half way along it (x = 0.4 of 0.8 m), and
    the file mapping lc1 to half the joint's length, ``origin_x(q2)/2``: equal at the URDF's
    numbers, apart in the geometry the comparison draws (lengths are parameters). Every
    element with lc1 differs (it had no cause); the first cause says that with
    lc1 = CX(link1) every equation is right, a joint's length written where a centre of mass
    is meant. The same file mapping lc1 = CX(link1) is right."""
    from shipped_copies import PUBLISHED
    urdf = (PUBLISHED / "two_link_arm.urdf").read_text()
    old = '<origin xyz="0.35 0 0" rpy="0 0 0"/>'
    assert urdf.count(old) == 1
    (tmp_path / "two_link_arm.urdf").write_text(urdf.replace(old, '<origin xyz="0.4 0 0" rpy="0 0 0"/>'))
    (tmp_path / "two_link_arm.toml").write_text((PUBLISHED / "two_link_arm.toml").read_text())
    for mapped, right in (('lc1 = { value = "origin_x(q2)/2"', False),
                          ('lc1 = { value = "CX(link1)"', True)):
        path = P.write(tmp_path, "arm", form, None)
        text = path.read_text().replace(str(PUBLISHED / "two_link_arm.toml"),
                                        str(tmp_path / "two_link_arm.toml"))
        assert 'lc1 = { value = "CX(link1)"' in text
        path.write_text(text.replace('lc1 = { value = "CX(link1)"', mapped))
        result = _compare(path)
        assert result.equivalent is right, result.equations
        if right:
            continue
        mapped_cause = [c for c in result.causes if "with lc1 = CX(link1)" in c.explanation]
        assert mapped_cause and mapped_cause[0].kind == CauseKind.FILE_ERROR, result.causes
        assert "a joint's length where the document means a link's centre of mass" in \
            mapped_cause[0].explanation
