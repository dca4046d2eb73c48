r"""What a model reads otherwise than its URDF writes is said in every comparison's notes
(:mod:`wheeled_dyn.models.readings`): an ``<inertial>`` orientation read as the right angles it
rounds (``tests/test_right_angles.py`` checks the comparison's notes), a joint's
``<dynamics>`` damping and friction and a ``<transmission>``, which the truth
:math:`A\ddot q + C\dot q + Q = \Gamma` does not have (a derivation's damping terms are terms
it does not have, and a report said nothing of the file's damping). Locked and fixed joints
are part of their bodies: their damping is no term of anything."""

from __future__ import annotations

from wheeled_dyn.models.readings import urdf_readings
from wheeled_dyn.models.registry import load_model

URDF = """<robot name="r">
  <link name="a"><inertial><origin xyz="0 0 0" rpy="0 3.1416 0.3"/><mass value="1"/>
    <inertia ixx="1" ixy="0" ixz="0" iyy="2" iyz="0" izz="3"/></inertial></link>
  <link name="b"><inertial><origin xyz="0 0 0" rpy="0 0 0"/><mass value="1"/>
    <inertia ixx="1" ixy="0" ixz="0" iyy="1" iyz="0" izz="1"/></inertial></link>
  <link name="c"/><link name="d"/>
  <joint name="hinge" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <dynamics damping="0.7"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="held" type="revolute"><parent link="b"/><child link="c"/><axis xyz="0 0 1"/>
    <dynamics friction="0.2"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="glued" type="fixed"><parent link="c"/><child link="d"/>
    <dynamics damping="5"/></joint>
  <transmission name="t_hinge"><joint name="hinge"/></transmission>
  <transmission name="t_held"><joint name="held"/></transmission>
</robot>"""


def test_each_reading_is_named_once():
    readings = urdf_readings(URDF)
    assert readings[0].startswith('link a: its inertial origin rpy="0 3.1416 0.3" is read as '
                                  "(0, π, 0.3)"), readings
    assert "joints hinge, held: the damping and friction of their dynamics element" in readings[1]
    assert "transmissions t_hinge, t_held: not applied" in readings[2]
    assert len(readings) == 3 and not any("glued" in r or "link b" in r for r in readings)


def test_a_locked_joint_is_part_of_its_body():
    readings = urdf_readings(URDF, locked=("held",))
    assert "joint hinge: the damping" in readings[1] and "transmission t_hinge:" in readings[2]
    assert not any("held" in r for r in readings), readings


def test_a_robot_as_published_says_what_it_leaves_out():
    r"""PAL's TIAGo (example-robot-data): its arm joints are damped and its motors have
    transmissions; TIAGo with its arm locked keeps only the wheels' transmissions, and its
    wheels are round to their rounding (:mod:`test_round_wheels`)."""
    full = load_model("tiago").readings
    assert full[0].startswith("joints torso_lift_joint, head_1_joint, head_2_joint and 7 "
                              "more: the damping and friction of their dynamics element"), full
    base = load_model("tiago_base").readings
    assert base[0] == ("transmissions wheel_right_trans, wheel_left_trans: not applied; the "
                       "model's inputs are its joints' torques (a reduction between motor and "
                       "joint is the document's to state)"), base
    assert len(base) == 2 and base[1].startswith("wheels wheel_left_link, wheel_right_link: "
                                                 "axisymmetric about their axles"), base


def test_a_footprint_off_the_ground_is_said(tmp_path):
    r"""A ROS robot whose ``base_footprint`` (REP 120: on the ground) is 0.1 m below its axle
    while its wheels' radius is 0.08: the model's R is the radius, and the reading says the
    footprint is 0.02 m below the ground (the file's numbers do not agree)."""
    from pathlib import Path
    data = Path(__file__).parent / "data" / "published"
    text = (data / "dd_robot.urdf").read_text()
    assert text.count('<origin xyz="0 0 0.08" rpy="0 0 0"/>') == 1
    (tmp_path / "dd_robot.urdf").write_text(text.replace('<origin xyz="0 0 0.08" rpy="0 0 0"/>',
                                                         '<origin xyz="0 0 0.1" rpy="0 0 0"/>'))
    (tmp_path / "dd_robot.toml").write_text((data / "dd_robot.toml").read_text())
    readings = load_model(str(tmp_path / "dd_robot.toml")).readings
    assert readings == ("link base_footprint (a frame only, the root) is 0.02 m below the "
                        "ground the wheels' radius 0.08 puts under their axle: the model's R "
                        "is that radius (if the root is meant on the ground, its joints' "
                        "origins and the wheels' radius do not agree)",), readings
    assert load_model(str(data / "dd_robot.toml")).readings == ()


def test_matrices_prints_the_readings(capsys):
    r"""``wheeled-dyn matrices`` says them too, as notes (and ``--json`` as ``notes``)."""
    import json

    from wheeled_dyn.cli.main import main
    assert main(["matrices", "tiago_base"]) == 0
    out = capsys.readouterr().out
    assert "note: transmissions wheel_right_trans, wheel_left_trans: not applied" in out
    assert main(["matrices", "tiago_base", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["notes"] == list(load_model("tiago_base").readings)


def test_an_axis_not_of_unit_length_is_said_and_read_as_its_direction():
    r"""``<axis xyz="0 0 2">`` is read as its direction (the joint's angle about the unit axis,
    as Pinocchio reads it): said once, and the model's inertia equals the one of the same URDF
    with the unit axis, at seeded configurations."""
    import numpy as np
    import pinocchio as pin

    from conftest import SEED
    scaled = URDF.replace('<child link="b"/><axis xyz="0 0 1"/>',
                          '<child link="b"/><axis xyz="0 0 2"/>')
    said = [r for r in urdf_readings(scaled) if "axis not of unit length" in r]
    assert len(said) == 1 and said[0].startswith("joint hinge (0 0 2)"), said
    assert not any("axis not of unit length" in r for r in urdf_readings(URDF))
    models = [pin.buildModelFromXML(text) for text in (scaled, URDF)]
    rng = np.random.default_rng(SEED)
    for _ in range(4):
        q = rng.uniform(-1.0, 1.0, models[1].nq)
        a, b = (pin.crba(m, m.createData(), q) for m in models)
        assert np.abs(a - b).max() <= 1e-12 * np.abs(b).max()
