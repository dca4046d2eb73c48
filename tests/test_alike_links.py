r"""Links a URDF writes alike, named by one symbol (:mod:`wheeled_dyn.compare.grid.alike_links`).

A newcomer's wheeled cart-pole (``data/wheeled_cart_pole``: a cart on a prismatic joint, two
wheels on continuous joints whose spin the derivation ties to the cart's travel, a pole),
Lagrange's equations with :math:`T = \tfrac12(M + 2J_w/R^2)\dot x^2 + \tfrac12 m(\dot x^2 +
2l\cos\theta\,\dot x\dot\theta + l^2\dot\theta^2) + \tfrac12 I\dot\theta^2`, one wheel's
``IZZ`` as :math:`J_w` for both. The wheels are alike in the URDF, and random parameter sets
drew them apart: A[1,1] "differed", said as "a formula for it (as for a uniform body)". It
agrees only if the links stay alike; declared (``alike_links``), it agrees; written as the two
wheels' mean, it agrees with no family; on a URDF whose wheels differ, it differs."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from conftest import SEED
from shipped_copies import published_copy
from wheeled_dyn import load_model
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.grid.alike_links import ALIKE_LINKS, alike_groups
from wheeled_dyn.compare.grid.samples import parameter_sets, special_cases
from wheeled_dyn.compare.records import DiagnosisKind as K
from wheeled_dyn.compare.records import Verdict
from wheeled_dyn.derivations import load_derivation

DATA = Path(__file__).parent / "data" / "wheeled_cart_pole"
FAMILIES = 'families = ["urdf_structure"]'
J_W = 'J_w = { value = "IZZ(left_wheel)"'
RIGHT_IZZ = ('<inertia ixx="0.0021" ixy="0" ixz="0" iyy="0.0021" iyz="0" izz="0.0040"/>', 2)


def _copy(folder: Path, *replacements: tuple[str, str], urdf: str | None = None) -> Path:
    path = published_copy(folder, "wheeled_cart_pole", "wheeled_cart_pole_matrices",
                          *replacements, data=DATA)
    if urdf is not None:
        (folder / "wheeled_cart_pole.urdf").write_text(urdf)
    return path


def _compare(path: Path):
    return ComparisonEngine(samples=300, param_sets=4, seed=SEED).compare(load_derivation(path))


def test_one_wheels_symbol_for_both_agrees_only_if_the_links_stay_alike(tmp_path):
    result = _compare(_copy(tmp_path))
    flagged = [r for r in result.records if r.verdict != Verdict.AGREES]
    assert [(r.element, r.verdict) for r in flagged] == [("A[1,1]", Verdict.AGREES_IF)], \
        [r.texts for r in flagged]
    said = flagged[0].diagnoses[0]
    assert said.kind == K.CONDITION and "left_wheel and right_wheel" in said.condition, said


@pytest.mark.parametrize("change", [(FAMILIES, 'families = ["urdf_structure", "alike_links"]'),
                                    (J_W, 'J_w = { value = "(IZZ(left_wheel) + '
                                          'IZZ(right_wheel))/2"')],
                         ids=["declared", "mean-of-both"])
def test_declared_or_written_as_both_it_agrees(tmp_path, change):
    result = _compare(_copy(tmp_path, change))
    assert result.equivalent is True
    assert all(r.verdict == Verdict.AGREES for r in result.records)


def test_wheels_the_urdf_writes_apart_are_no_family(tmp_path):
    urdf = (DATA / "wheeled_cart_pole.urdf").read_text()
    line, count = RIGHT_IZZ
    assert urdf.count(line) == count
    at = urdf.rindex(line)                                     # the right wheel's
    urdf = urdf[:at] + line.replace("0.0040", "0.0038") + urdf[at + len(line):]
    path = _copy(tmp_path, urdf=urdf)
    assert not alike_groups(load_model(str(tmp_path / "wheeled_cart_pole.toml")))
    result = _compare(path)
    flagged = [r for r in result.records if r.verdict != Verdict.AGREES]
    assert [(r.element, r.verdict) for r in flagged] == [("A[1,1]", Verdict.DIFFERS)]


def test_the_family_draws_the_alike_links_equal_and_only_then():
    model = str(DATA / "wheeled_cart_pole.toml")
    wm = load_model(model)
    (group,) = alike_groups(wm)
    assert [wm.model.names[j] for j in group] == ["left_wheel_joint", "right_wheel_joint"]
    alike = next(c for c in special_cases(model) if c.name == ALIKE_LINKS)
    for special, equal in (((), False), ((alike,), True)):
        for ps in parameter_sets(model, 3, np.random.default_rng(SEED), special):
            a, b = (ps.model.model.inertias[j] for j in group)
            same = np.allclose(a.toDynamicParameters(), b.toDynamicParameters(), rtol=1e-12)
            assert same is equal
