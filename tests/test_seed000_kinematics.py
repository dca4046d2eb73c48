r"""Seed 000's 5.1: the acceleration of a body moving in the plane along its own axes,
a_x = U' - r V, a_y = V' + r U, from its body-axis velocity (U, V) and yaw rate r.

Written through the world coordinates, the components are functions of the positions and the
accelerations only (the r V and r U terms cancel the rates of the turning axes): a value to be
compared as it is, not a relation whose rate is taken. As printed both agree; a sign flipped
in r V names the velocity products it leaves.
"""

from __future__ import annotations

import pytest

from conftest import SEED
from wheeled_dyn.compare.steps.records import compare_steps
from wheeled_dyn.derivations import builtin_derivations, load_derivation

FILE = "p5_1_body_axes.toml"
PRINTED = 'components = ["dU - r*V", "dV + r*U"]'


def _records(tmp_path, new: str | None = None):
    folder = builtin_derivations("seed000")[0].parent
    text = (folder / FILE).read_text()
    assert text.count(PRINTED) == 1
    path = tmp_path / FILE
    path.write_text(text if new is None else text.replace(PRINTED, new))
    return {r.element: r for r in compare_steps(load_derivation(path), SEED)}


def test_body_axis_acceleration_agrees(tmp_path):
    records = _records(tmp_path)
    assert {e: r.verdict for e, r in records.items()} == {
        "5.1 acceleration a_x": "agrees", "5.1 acceleration a_y": "agrees"}


@pytest.mark.parametrize("new,element,terms", [
    ('components = ["dU + r*V", "dV + r*U"]', "5.1 acceleration a_x", {"dX*dtheta", "dY*dtheta"}),
    ('components = ["dU - r*V", "dV - r*U"]', "5.1 acceleration a_y", {"dX*dtheta", "dY*dtheta"}),
])
def test_a_flipped_rotation_term_names_its_products(tmp_path, new, element, terms):
    records = _records(tmp_path, new)
    r = records[element]
    assert r.verdict == "differs"
    named = {x.split(":")[0].removeprefix("term ") for x in r.texts}
    assert terms <= named, r.texts
    assert [e for e, x in records.items() if x.verdict != "agrees"] == [element]
