r"""A tyre touches the ground in its own mid-plane. A ROS URDF may set a wheel's cylinder off
its link's origin along the axle (``<collision><origin xyz="0 0.03 0">``): the contact is
then at the cylinder's centre, not at the link's origin, and the track is measured between
the tyres.

Checked as an identity between two URDFs of one robot (tests/data/ros_balancer): the tyres
set off by :data:`SHIFT` outward in their links, and the wheel joints moved outward by
:data:`SHIFT` with the tyres centred and each wheel's mass put back where it was. The truth of
both, in the heading coordinates, is the same. A cylinder centred off the spin axis is no
wheel: the model is refused, naming the link, and ``wheeled-dyn model`` says why.
"""

from __future__ import annotations

import re
import shutil
from pathlib import Path

import numpy as np
import pytest
from conftest import SEED
from wheeled_dyn.constraints import CoordinateMap
from wheeled_dyn.coordinates import builtin_coordinate_set
from wheeled_dyn.errors import ModelError
from wheeled_dyn.models.registry import load_model
from wheeled_dyn.models.starter import inspect_urdf

DATA = Path(__file__).parent / "data" / "ros_balancer"
#: How far each tyre is set off outward along the axle (m).
SHIFT = 0.03
#: The two models' terms against each other, relative to each matrix's largest entry.
SAME_TOL = 1e-12
#: Random states compared.
N_STATES = 12


def _wheel(text: str, side: str, cylinder_xyz: str | None = None, joint_y: float | None = None,
           inertial_xyz: str | None = None) -> str:
    r"""``text`` with the ``side`` wheel's cylinders (visual and collision) centred at
    ``cylinder_xyz``, its joint at ``y = joint_y`` and its inertial at ``inertial_xyz``."""
    link = re.search(rf'<link name="{side}_wheel">.*?</link>', text, re.S)
    assert link is not None
    body = link.group(0)
    if cylinder_xyz is not None:
        body = body.replace('<origin xyz="0 0 0" rpy="1.5', f'<origin xyz="{cylinder_xyz}" rpy="1.5')
    if inertial_xyz is not None:
        body = body.replace('<origin xyz="0 0 0" rpy="0 0 0"/>\n      <mass',
                            f'<origin xyz="{inertial_xyz}" rpy="0 0 0"/>\n      <mass')
    text = text.replace(link.group(0), body)
    if joint_y is not None:
        sign = 1 if side == "left" else -1
        text = text.replace(f'<origin xyz="0 {sign * 0.22:g} 0" rpy="0 0 0"/>',
                            f'<origin xyz="0 {joint_y:g} 0" rpy="0 0 0"/>')
    return text


def _model(folder: Path, name: str, urdf: str):
    folder.mkdir()
    (folder / "ros_balancer.urdf").write_text(urdf)
    shutil.copy(DATA / "ros_balancer.toml", folder / "ros_balancer.toml")
    return load_model(str(folder / "ros_balancer.toml"))


def _urdfs() -> tuple[str, str]:
    r"""(tyres set off in their links, joints moved to the tyres)."""
    text = (DATA / "ros_balancer.urdf").read_text()
    shifted = _wheel(_wheel(text, "left", cylinder_xyz=f"0 {SHIFT:g} 0"),
                     "right", cylinder_xyz=f"0 {-SHIFT:g} 0")
    moved = _wheel(_wheel(text, "left", joint_y=0.22 + SHIFT, inertial_xyz=f"0 {-SHIFT:g} 0"),
                   "right", joint_y=-0.22 - SHIFT, inertial_xyz=f"0 {SHIFT:g} 0")
    assert shifted != text and moved != text
    return shifted, moved


def test_the_contact_is_in_the_tyres_mid_plane(tmp_path):
    shifted, moved = _urdfs()
    models = [_model(tmp_path / name, name, urdf)
              for name, urdf in (("shifted", shifted), ("moved", moved))]
    rng = np.random.default_rng(SEED)
    q, nu = rng.uniform(-1, 1, (N_STATES, 3)), rng.normal(size=(N_STATES, 3))
    terms = [CoordinateMap(wm, builtin_coordinate_set(wm, "heading")).terms_batch(q, nu)
             for wm in models]
    for key in "AQBh":
        a, b = (getattr(t, key) for t in terms)
        assert np.abs(a - b).max() <= SAME_TOL * np.abs(b).max(), key
    plain = load_model(str(DATA / "ros_balancer.toml"))
    a = CoordinateMap(plain, builtin_coordinate_set(plain, "heading")).terms_batch(q, nu).A
    turning = np.abs(a[:, 1, 1] - terms[0].A[:, 1, 1])      # the tyres' place counts: the
    assert (turning > 0.01 * np.abs(a[:, 1, 1])).all()      # wheels' share of the turning


def test_the_tyres_place_is_a_reading(tmp_path):
    shifted, _ = _urdfs()
    wm = _model(tmp_path / "said", "said", shifted)
    said = [x for x in wm.readings if "tyre's mid-plane" in x]
    assert len(said) == 2 and all(f"{SHIFT:g} m from the link's origin" in x for x in said)


def test_the_starter_measures_the_track_between_the_tyres(tmp_path):
    urdf = tmp_path / "shifted.urdf"
    urdf.write_text(_urdfs()[0])
    pair = inspect_urdf(urdf).pair
    assert pair is not None
    assert sorted(round(c.position[1], 12) for c in pair) == [-0.22 - SHIFT, 0.22 + SHIFT]


@pytest.mark.parametrize("xyz", ["0.02 0 0", "0 0 -0.01"])
def test_a_tyre_off_its_axis_is_no_wheel(tmp_path, xyz):
    text = _wheel((DATA / "ros_balancer.urdf").read_text(), "left", cylinder_xyz=xyz)
    with pytest.raises(ModelError) as error:
        _model(tmp_path / "eccentric", "eccentric", text)
    assert "left_wheel" in str(error.value) and "off the spin axis" in str(error.value)
    urdf = tmp_path / "eccentric.urdf"
    urdf.write_text(text)
    found = inspect_urdf(urdf)
    assert found.pair is None
    assert any("off the joint axis" in why for _, why in found.rejected), found.rejected
