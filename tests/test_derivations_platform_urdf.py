r"""urdf/wip_platform.urdf, the body of the book's equations (9)-(14): links, joints, frames and
values as its comment states."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

URDF = Path(__file__).resolve().parents[1] / "urdf" / "wip_platform.urdf"
#: Numeric slack on values written with 5 decimals in the URDF.
VALUE_TOL = 1e-4


def test_structure_and_frames():
    robot = ET.parse(URDF).getroot()
    links = {link.get("name"): link for link in robot.findall("link")}
    assert set(links) == {"platform", "pendulum", "wheel_left", "wheel_right"}
    joints = {j.get("name"): j for j in robot.findall("joint")}
    hinge = joints["pendulum_joint"]
    assert hinge.get("type") == "revolute"
    assert hinge.find("parent").get("link") == "platform"
    assert hinge.find("axis").get("xyz") == "0 0 1"
    assert float(hinge.find("limit").get("effort")) == 0.0       # passive
    for side, z in (("left", -0.35), ("right", 0.35)):
        j = joints[f"wheel_{side}_joint"]
        assert j.get("type") == "continuous" and j.find("axis").get("xyz") == "0 0 1"
        assert [float(v) for v in j.find("origin").get("xyz").split()] == [0.0, 0.0, z]
        cyl = links[f"wheel_{side}"].find("collision/geometry/cylinder")
        assert float(cyl.get("radius")) == 0.25
    pendulum = links["pendulum"].find("inertial")
    assert float(pendulum.find("mass").get("value")) == 50.0
    assert [float(v) for v in pendulum.find("origin").get("xyz").split()] == [0.0, 0.5, 0.0]
    assert float(links["platform"].find("inertial/mass").get("value")) == 20.0


def test_pinocchio_reads_it():
    pin = pytest.importorskip("pinocchio")
    model = pin.buildModelFromUrdf(str(URDF))
    assert model.nv == 3
    data = model.createData()
    M = pin.crba(model, data, pin.neutral(model))
    hinge = model.getJointId("pendulum_joint")
    # pendulum about the hinge: I_zz(COM) + m l**2
    assert abs(M[model.joints[hinge].idx_v, model.joints[hinge].idx_v]
               - (4.54167 + 50.0 * 0.5**2)) < VALUE_TOL
    assert np.allclose(model.inertias[hinge].lever, [0.0, 0.5, 0.0])
