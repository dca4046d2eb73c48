r"""A newcomer's own two-wheeled balancer (``data/newcomer_balancer``): a ROS URDF (base_footprint
root, base_link 0.065 m above the axle, a turned battery, wheel cylinders turned by
``rpy="1.5708 0 0"``) and its author's own Kane derivation in the quasi-velocities
:math:`(v, \omega, \dot\theta)`, its centre-of-mass height measured from the axle
(``z_b = CZ(base_link) + 0.065``). Right, it agrees; with the height measured from base_link
(``z_b = CZ(base_link)``) it differs, in the elements that hold the height."""

from __future__ import annotations

from pathlib import Path

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.derivations import load_derivation

DATA = Path(__file__).parent / "data" / "newcomer_balancer"
HEIGHT = 'z_b  = { value = "CZ(base_link) + 0.065", units = "m" }'


def _compare(tmp_path: Path, height: str):
    text = (DATA / "segbot2_kane.toml").read_text()
    assert text.count(HEIGHT) == 1
    for name in ("segbot2.toml", "segbot2.urdf"):
        (tmp_path / name).write_text((DATA / name).read_text())
    path = tmp_path / "doc.toml"
    path.write_text(text.replace(HEIGHT, height))
    return ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(
        load_derivation(path))


def test_the_newcomers_kane_derivation_agrees(tmp_path):
    result = _compare(tmp_path, HEIGHT)
    assert result.equivalent is True, [c.explanation for c in result.causes]


def test_a_height_from_the_wrong_point_differs(tmp_path):
    result = _compare(tmp_path, HEIGHT.replace(" + 0.065", ""))
    assert result.equivalent is False
    wrong = {r.element for r in result.records if r.verdict != "agrees"}
    assert {"A[1,3]", "A[3,3]"} <= wrong, wrong
