"""The convention table (``models/conventions.py``) says what ``matrices`` computes.

For the WIP (seed 001's body frame: y up, z along the axle) and for a REP 103 robot
(tests/data/ros_balancer: base_link x forward, y left, z up, a base_footprint root, a torso fixed
on top, wheel joints about +y and -y), every claim of the table is checked against the built
model and the terms ``wheeled-dyn matrices`` prints: the point 1 m above the axle at a positive
pitch, the heading at a positive psi, the wheel rates of a forward rolling motion (the velocity
matrix of the heading coordinates), and the acceleration from rest of each wheel torque
(A^-1 B). The table ``matrices`` prints is this record's; the docs show the WIP's and the ROS
robot's tables as printed.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from wheeled_dyn.cli.main import main
from wheeled_dyn.constraints import CoordinateMap
from wheeled_dyn.coordinates import builtin_coordinate_set
from wheeled_dyn.models.conventions import Positive, convention_table
from wheeled_dyn.models.registry import load_model

HERE = Path(__file__).parent
ROS = HERE / "data" / "ros_balancer" / "ros_balancer.toml"
DOCS = HERE.parent / "docs"
#: Small pitch and heading (rad) at which the geometric claims are read.
ANGLE = 0.1
#: Smallest displacement (m) or rate counted as a sign (the claims are first-order effects).
SIGNIFICANT = 1e-6

MODELS = ["wip", str(ROS)]


def _frame_pose(wm, q: np.ndarray) -> pin.SE3:
    data = wm.model.createData()
    pin.forwardKinematics(wm.model, data, q)
    pin.updateFramePlacements(wm.model, data)
    return data.oMf[wm.model.getFrameId(wm.spec.body, pin.FrameType.BODY)]


def _q(wm, **values) -> np.ndarray:
    q = pin.neutral(wm.model)
    for name, value in values.items():
        q[wm.index(name)] = value
    return q


@pytest.mark.parametrize("model", MODELS)
def test_pitch_and_heading_claims_hold(model):
    wm = load_model(model)
    table = convention_table(wm)
    rest = _frame_pose(wm, _q(wm))
    up_in_body = rest.rotation.T @ np.array([0.0, 0.0, 1.0])
    above_axle = rest.actInv(np.array([0.0, 0.0, wm.geometry["R"]])) + up_in_body  # 1 m above
    pitched = _frame_pose(wm, _q(wm, phi=ANGLE))
    moved = pitched.act(above_axle)[0] - rest.act(above_axle)[0]
    claim = table.row("phi").positive
    assert claim in (Positive.TOP_BACKWARD, Positive.TOP_FORWARD)
    assert abs(moved) > SIGNIFICANT
    assert (moved < 0) == (claim is Positive.TOP_BACKWARD), (model, moved)
    forward_in_body = rest.rotation.T @ np.array([1.0, 0.0, 0.0])
    turned = _frame_pose(wm, _q(wm, psi=ANGLE)).rotation @ forward_in_body
    assert table.row("psi").positive is Positive.TURNS_LEFT and turned[1] > SIGNIFICANT


@pytest.mark.parametrize("model", MODELS)
def test_wheel_and_input_claims_hold_in_the_terms_matrices_prints(model):
    wm = load_model(model)
    table = convention_table(wm)
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "heading"))
    q, nu = cmap.state_from({})
    S = cmap.velocity_matrix(cmap.model_configuration(q))
    rolling = S @ np.eye(len(nu))[0]                    # dx = 1: rolling forward, body level
    terms = cmap.terms(q, nu)                           # at rest, upright
    accel = np.linalg.solve(terms.A, terms.B)           # each input's acceleration from rest
    for wheel, name in zip(wm.wheels, wm.input_names):
        coordinate = wm.coordinate_names[wheel.v_index]
        rate = rolling[wheel.v_index]
        sign = table.row(coordinate).positive
        assert abs(rate) > SIGNIFICANT
        assert (rate > 0) == (sign is Positive.INCREASES_ROLLING_FORWARD), (coordinate, rate)
        forward = accel[0, wm.input_names.index(name)]
        claim = table.row(name).positive
        assert abs(forward) > SIGNIFICANT
        assert (forward > 0) == (claim is Positive.DRIVES_FORWARD), (name, forward)


def test_the_ros_robot_table_reads_as_rep_103():
    table = convention_table(load_model(str(ROS)))
    assert table.row("phi").vector == pytest.approx((0.0, -1.0, 0.0))
    assert "REP 103" in table.row("phi").note
    assert table.row("theta_l").positive is Positive.INCREASES_ROLLING_FORWARD   # axis +y
    assert table.row("theta_r").positive is Positive.DECREASES_ROLLING_FORWARD   # axis -y
    assert table.row("tau_r").positive is Positive.DRIVES_BACKWARD


@pytest.mark.parametrize("model", MODELS)
def test_matrices_prints_the_table(model, capsys):
    assert main(["matrices", model]) == 0
    out = capsys.readouterr().out
    for line in convention_table(load_model(model)).lines():
        assert line in out


def _block(text: str, name: str) -> list[str]:
    found = re.search(rf"<!-- conventions {re.escape(name)} -->\n```\n(.*?)```", text, re.S)
    assert found, f"no conventions block for {name}"
    return found.group(1).rstrip("\n").split("\n")


@pytest.mark.parametrize("doc,name,model", [
    ("derivation-format.md", "wip", "wip"),
    ("model-format.md", "ros_balancer", str(ROS)),
])
def test_the_docs_show_the_tables_as_printed(doc, name, model):
    text = (DOCS / doc).read_text(encoding="utf-8")
    assert _block(text, name) == convention_table(load_model(model)).lines()
