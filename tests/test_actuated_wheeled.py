r"""A wheeled robot with motors beside its wheels' (a torso on a motorised hip, an arm on a
mobile base): the model file's ``[joints] actuated`` adds B's columns after the two wheel
torques. It was ignored on a wheeled base (B had the wheels' columns only, and a derivation
naming the hip's torque was refused as an unknown input).

The robot (``data/torso_balancer``, written for the tests) in the form of Li, Yang & Fan,
*Advanced Control of Wheeled Inverted Pendulum Systems* (Springer 2013): Lagrange's equations
of the wheeled pendulum with a second link, the hip's torque on the torso with its reaction
on the leg. Pinocchio's truth (the hip's column of B from the joint's velocity index) against
the document's, and the hip torque's sign planted.
"""

from __future__ import annotations

import pickle
from pathlib import Path

import numpy as np
import pytest

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import DiagnosisKind, Verdict
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.errors import ModelError, UnknownNameError
from wheeled_dyn.models.registry import load_model

DATA = Path(__file__).parent / "data" / "torso_balancer"
MODEL, DOC = "torso_balancer.toml", "torso_balancer_hip.toml"


def _model_file(tmp_path: Path, old: str = "", new: str = "") -> Path:
    text = (DATA / MODEL).read_text()
    assert old in text, old
    (tmp_path / "torso_balancer.urdf").write_text((DATA / "torso_balancer.urdf").read_text())
    path = tmp_path / MODEL
    path.write_text(text.replace(old, new) if old else text)
    return path


def test_the_hip_motor_is_bs_third_column():
    wm = load_model(str(DATA / MODEL))
    assert wm.input_names == ("tau_l", "tau_r", "tau_hip")
    B = wm.input_matrix()
    hip = wm.model.joints[wm.model.getJointId("hip")].idx_v
    wheels = [w.v_index for w in wm.wheels]
    assert B.shape == (wm.nv, 3)
    assert np.array_equal(B[:, 2], np.eye(wm.nv)[hip])
    assert [int(np.argmax(B[:, k])) for k in range(2)] == wheels
    from wheeled_dyn.models.conventions import convention_table
    rows = {r.name: r for r in convention_table(wm).rows}
    assert rows["tau_hip"].kind == "input" and "hip" in rows["tau_hip"].axis


@pytest.mark.parametrize("planted", [None, "hip sign"])
def test_a_derivation_with_the_hip_torque_is_compared(tmp_path, planted):
    text = (DATA / DOC).read_text()
    if planted:
        old = 'B = "[[1/r, 0], [-1, -1], [0, 1]]"'
        assert old in text
        text = text.replace(old, 'B = "[[1/r, 0], [-1, 1], [0, 1]]"')
    _model_file(tmp_path)
    path = tmp_path / DOC
    path.write_text(text)
    result = ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(
        load_derivation(path))
    differing = {r.element: r for r in result.records if r.verdict != Verdict.AGREES}
    if planted is None:
        assert result.equivalent is True and not differing, list(differing)
        return
    assert result.equivalent is False
    assert set(differing) == {"B[2,2]"}
    assert any(d.kind == DiagnosisKind.SIGN for d in differing["B[2,2]"].diagnoses)


def test_the_actuated_joints_inputs_alone_follow_the_wheels(tmp_path):
    r"""``[joints] inputs`` naming the hip's torque only (no ``[wheels] inputs``): the
    wheels' torques keep their default names, first."""
    path = _model_file(tmp_path, 'inputs = ["tau_l", "tau_r"]\n', "")
    assert load_model(str(path)).input_names == ("tau_l", "tau_r", "tau_hip")


@pytest.mark.parametrize("old, new, message", [
    ('inputs = ["tau_hip"]', 'inputs = ["tau_hip", "tau_extra"]',
     "4 input names for two wheel motors and 1 actuated joints"),
    ('actuated = ["hip"]', 'actuated = ["left_wheel_joint"]', "no drive wheel's"),
])
def test_bad_actuated_joints_are_one_clear_error(tmp_path, old, new, message):
    path = _model_file(tmp_path, old, new)
    with pytest.raises(ModelError, match=message) as caught:
        load_model(str(path))
    again = pickle.loads(pickle.dumps(caught.value))
    assert str(again) == str(caught.value)


def test_an_actuated_joint_the_urdf_lacks_is_named(tmp_path):
    path = _model_file(tmp_path, 'actuated = ["hip"]', 'actuated = ["waist"]')
    with pytest.raises(UnknownNameError, match="waist"):
        load_model(str(path))


@pytest.mark.parametrize("alias", ["dtheta_l", "ddtheta_l"])
def test_an_alias_named_as_another_coordinates_velocity_is_one_clear_error(tmp_path, alias):
    r"""A joint's alias that is another coordinate's velocity (``dtheta_l``) or acceleration
    name: compiling the model's functions raised Python's "duplicate argument" SyntaxError."""
    path = _model_file(tmp_path, 'right_wheel_joint = "theta_r"', f'right_wheel_joint = "{alias}"')
    with pytest.raises(ModelError, match=f"'{alias}' is the name of the") as caught:
        load_model(str(path))
    assert "right_wheel_joint" in str(caught.value)
    assert str(pickle.loads(pickle.dumps(caught.value))) == str(caught.value)
