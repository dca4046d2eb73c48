r"""A URDF whose wheel joints are turned by a rounded angle, as ROS users write them
(``<origin rpy="-1.57 0 0"/>`` with ``<axis xyz="0 0 1"/>``, the turtlebot3 style): a planar
model's wheels are turned onto their axle (their spin axes 8e-4 rad off it before, so the
rolling constraints held cos(1.57) = 0.000796..., the exact elimination ran for more than five
minutes and the ``symbolic`` command refused the model), so the comparison and the closed forms
run on the robot as meant. A rounded rotation left on the rolling constraints' path is still
found. A factor near 1 that is not 1 is printed with the digits that show it (0.9999997, not
"1")."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from wheeled_dyn.compare.judge.diagnose import nice_number

ROS = Path(__file__).parent / "data" / "ros_balancer"
#: Seconds a command may take here (it took more than 300 before).
LIMIT = 240


def _rounded_model(tmp_path: Path) -> Path:
    text = (ROS / "ros_balancer.urdf").read_text()
    for side, y, rpy, axis in (("left", "0.22", "-1.57", "0 1 0"), ("right", "-0.22", "1.57",
                                                                     "0 -1 0")):
        old = (f'<origin xyz="0 {y} 0" rpy="0 0 0"/>\n    <axis xyz="{axis}"/>')
        assert old in text, side
        text = text.replace(old, f'<origin xyz="0 {y} 0" rpy="{rpy} 0 0"/>\n'
                                 '    <axis xyz="0 0 1"/>')
    (tmp_path / "rounded.urdf").write_text(text)
    model = (ROS / "ros_balancer.toml").read_text().replace(
        'path = "ros_balancer.urdf"', 'path = "rounded.urdf"').replace(
        'name = "ros_balancer"', 'name = "ros_rounded"')
    (tmp_path / "rounded.toml").write_text(model)
    derivation = (ROS / "ros_balancer_heading.toml").read_text().replace(
        'model = "ros_balancer.toml"', 'model = "rounded.toml"')
    (tmp_path / "doc.toml").write_text(derivation)
    return tmp_path


def _command(*args: str, cwd: Path) -> subprocess.CompletedProcess:
    exe = Path(sys.executable).with_name("wheeled-dyn")
    env = {**os.environ, "WHEELED_DYN_CACHE": str(cwd / "cache")}
    return subprocess.run([str(exe), *args], cwd=cwd, capture_output=True, text=True,
                          timeout=LIMIT, env=env)


def test_the_comparison_runs_on_the_numbers_as_written(tmp_path):
    folder = _rounded_model(tmp_path)
    done = _command("compare", "rounded.toml", "doc.toml", "--out", "out", "--samples", "200",
                    "--param-sets", "2", cwd=folder)
    assert done.returncode == 0, done.stderr[-2000:]
    assert (folder / "out" / "report.json").is_file()


def test_the_symbolic_command_gives_the_robot_as_meant(tmp_path):
    folder = _rounded_model(tmp_path)
    done = _command("symbolic", "rounded.toml", cwd=folder)
    assert done.returncode == 0, done.stderr[-2000:]
    assert "B[3,2] = -1" in done.stdout


def test_a_rounded_rotation_is_found_and_an_exact_or_generic_one_is_not(tmp_path):
    import numpy as np
    import pinocchio as pin

    from wheeled_dyn.models.registry import load_model
    from wheeled_dyn.symbolic.basis import rounded_rotation
    rounded = load_model(str(_rounded_model(tmp_path) / "rounded.toml"))
    assert rounded_rotation(rounded) is None            # its wheels turned onto the axle
    assert rounded_rotation(load_model(str(ROS / "ros_balancer.toml"))) is None   # rpy 0 0 0.4
    model = pin.Model(rounded.model)                    # a rounded turn left on the path
    jid = rounded.wheels[0].joint_id
    placement = model.jointPlacements[jid]
    model.jointPlacements[jid] = pin.SE3(placement.rotation @ pin.rpy.rpyToMatrix(
        np.array([0.0, 0.0, 1.57])), placement.translation)
    found = rounded_rotation(rounded.with_model(model, rounded.springs))
    assert found is not None and found[0] == rounded.wheels[0].joint_name


def test_a_rounded_angle_off_the_wheels_path_keeps_the_closed_forms(tmp_path):
    r"""A camera's optical frame turned by a rounded angle (``rpy="-1.5708 0 -1.5708"``, as
    ROS writes it) is not on the rolling constraints' path: it does not cost the model its
    closed forms."""
    from wheeled_dyn.models.registry import load_model
    from wheeled_dyn.symbolic.basis import rounded_rotation
    text = (ROS / "ros_balancer.urdf").read_text().replace("</robot>", (
        '  <link name="camera_optical"/>\n  <joint name="camera_optical_joint" type="fixed">\n'
        '    <parent link="torso"/>\n    <child link="camera_optical"/>\n'
        '    <origin xyz="0 0 0.3" rpy="-1.5708 0 -1.5708"/>\n  </joint>\n</robot>'))
    (tmp_path / "camera.urdf").write_text(text)
    (tmp_path / "camera.toml").write_text((ROS / "ros_balancer.toml").read_text().replace(
        'path = "ros_balancer.urdf"', 'path = "camera.urdf"').replace(
        'name = "ros_balancer"', 'name = "ros_camera"'))
    assert rounded_rotation(load_model(str(tmp_path / "camera.toml"))) is None


@pytest.mark.parametrize("c,text", [(0.9999997, "0.9999997"), (-1.0000004, "-1.0000004"),
                                    (0.5, "1/2"), (0.75000000001, "3/4"), (0.3734, "0.3734"),
                                    (2.00004, "2.00004")])
def test_a_factor_near_a_simple_one_shows_its_digits(c, text):
    assert nice_number(c) == text
