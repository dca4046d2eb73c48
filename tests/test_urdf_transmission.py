r"""A ROS URDF with ``<transmission>`` blocks (ros_control's, as robot descriptions carry
them): each names its joint in a ``<joint name="...">`` element of its own, with no origin.
The model's lengths are read from the robot's own joints only: the transmission's ``<joint>``
had been read as the joint itself, its origin 0, and the two-link arm of ``data/published``
(Spong, Hutchinson, Vidyasagar's planar elbow arm, ``published_forms.py``) with a transmission
on its elbow was "not right as a system" in the forms that name the first link's length."""

from __future__ import annotations

from pathlib import Path

import pytest

import published_forms as P
from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.models.registry import load_model

DATA = Path(__file__).parent / "data" / "published"

TRANSMISSIONS = """  <transmission name="{joint}_trans">
    <type>transmission_interface/SimpleTransmission</type>
    <joint name="{joint}"><hardwareInterface>hardware_interface/EffortJointInterface</hardwareInterface></joint>
    <actuator name="{joint}_motor"><mechanicalReduction>1</mechanicalReduction></actuator>
  </transmission>
"""


def _arm_with_transmissions(tmp_path: Path) -> Path:
    urdf = (DATA / "two_link_arm.urdf").read_text()
    blocks = "".join(TRANSMISSIONS.format(joint=j) for j in ("q1", "q2"))
    (tmp_path / "two_link_arm.urdf").write_text(urdf.replace("</robot>", blocks + "</robot>"))
    model = tmp_path / "two_link_arm.toml"
    model.write_text((DATA / "two_link_arm.toml").read_text())
    return model


def test_the_lengths_are_the_joints_own(tmp_path: Path) -> None:
    plain = load_model(str(DATA / "two_link_arm.toml")).lengths
    ros = load_model(str(_arm_with_transmissions(tmp_path))).lengths
    assert plain is not None and ros is not None
    assert {k: d.value for k, d in ros.dimensions.items()} == \
        {k: d.value for k, d in plain.dimensions.items()}


@pytest.mark.parametrize("form", ["equations", "solved", "matrices"])
def test_every_form_agrees_with_transmissions(tmp_path: Path, form: str) -> None:
    model = _arm_with_transmissions(tmp_path)
    path = P.write(tmp_path, "arm", form, None)
    path.write_text(path.read_text().replace(str(DATA / "two_link_arm.toml"), str(model)))
    result = ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(
        load_derivation(path))
    assert result.equivalent is True, [t for e in result.equations for t in e.texts]


def test_a_urdf_given_as_the_model_is_told_how_to_make_one(tmp_path: Path) -> None:
    r"""``compare robot.urdf doc.toml``: one error naming the derivation and saying how a model
    file is made of the URDF (it said only that the file describes another model)."""
    from wheeled_dyn.cli.running import run_comparison
    from wheeled_dyn.errors import DerivationError
    model = _arm_with_transmissions(tmp_path)
    path = P.write(tmp_path, "arm", "equations", None)
    path.write_text(path.read_text().replace(str(DATA / "two_link_arm.toml"), str(model)))
    urdf = str(tmp_path / "two_link_arm.urdf")
    with pytest.raises(DerivationError) as err:
        run_comparison([path], 20, 1, model=urdf)
    text = str(err.value)
    assert path.name in text and f"wheeled-dyn model {urdf} --out MODEL.toml" in text, text
