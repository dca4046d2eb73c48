r"""Models the viewer tests draw, and tests of the stand-in shapes built for models without
meshes.

``cart_model()`` follows the wheeled-model contract: joints x0 (PX), y0 (PY), psi (RZ) put the
body on the ground plane, then a body with mass and two wheels (revolute about the axle y),
no visual model. ``tiago_models()`` is PAL's TIAGo from example-robot-data, with its meshes.
"""

from __future__ import annotations

import site
from dataclasses import dataclass
from pathlib import Path

import coal
import numpy as np
import pinocchio as pin
import pytest

from wheeled_dyn.viewer import equivalent_box, fallback_visual_model
from wheeled_dyn.viewer.shapes import MIN_SIDE, joint_axis

RADIUS = 0.1
WIDTH = 0.04
HALF_TRACK = 0.2
BODY_SIDES = (0.3, 0.25, 0.5)      # a, b, c of the uniform box body
BODY_MASS = 4.0
TOL = 1e-12


@dataclass(frozen=True)
class CartWheel:
    joint_id: int
    radius: float
    width: float


@dataclass(frozen=True)
class Cart:
    name: str
    model: pin.Model
    visual_model: pin.GeometryModel | None
    wheels: tuple[CartWheel, ...]


def box_inertia(mass: float, sides: tuple[float, float, float]) -> np.ndarray:
    a, b, c = sides
    return mass / 12.0 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])


def cart_model() -> Cart:
    r"""A two-wheeled cart on the ground-plane base (x0, y0, psi), no meshes."""
    model = pin.Model()
    model.name = "cart"
    parent = 0
    for name, joint in (("x0", pin.JointModelPX()), ("y0", pin.JointModelPY()),
                        ("psi", pin.JointModelRZ())):
        parent = model.addJoint(parent, joint, pin.SE3.Identity(), name)
    body = parent
    com = np.array([0.0, 0.0, RADIUS + 0.5 * BODY_SIDES[2]])
    model.appendBodyToJoint(body, pin.Inertia(BODY_MASS, com, box_inertia(BODY_MASS, BODY_SIDES)),
                            pin.SE3.Identity())
    wheels = []
    for side, y in (("left", HALF_TRACK), ("right", -HALF_TRACK)):
        jid = model.addJoint(body, pin.JointModelRY(), pin.SE3(np.eye(3), np.array([0, y, RADIUS])),
                             f"wheel_{side}")
        model.appendBodyToJoint(jid, pin.Inertia.FromCylinder(0.5, RADIUS, WIDTH),
                                pin.SE3.Identity())
        wheels.append(CartWheel(jid, RADIUS, WIDTH))
    return Cart("cart", model, None, tuple(wheels))


def cart_circle(duration: float = 2.0, n: int = 201) -> tuple[np.ndarray, np.ndarray]:
    r"""The cart driving a quarter circle of radius 1 m, wheels turning."""
    t = np.linspace(0.0, duration, n)
    s = 0.5 * np.pi * t / duration
    qs = np.zeros((n, 5))
    qs[:, 0], qs[:, 1], qs[:, 2] = np.sin(s), 1.0 - np.cos(s), s
    qs[:, 3] = (1.0 + HALF_TRACK) * s / RADIUS
    qs[:, 4] = (1.0 - HALF_TRACK) * s / RADIUS
    return t, qs


def example_robot_data_share() -> Path:
    import cmeel

    for root in site.getsitepackages():
        share = Path(root) / cmeel.consts.CMEEL_PREFIX / "share"
        if (share / "example-robot-data" / "robots").is_dir():
            return share
    pytest.skip("example-robot-data robots not found under site-packages")


def tiago_models() -> tuple[pin.Model, pin.GeometryModel]:
    share = example_robot_data_share()
    urdf = share / "example-robot-data/robots/tiago_description/robots/tiago.urdf"
    model, _, visual = pin.buildModelsFromUrdf(str(urdf), package_dirs=[str(share)])
    return model, visual


# -- tests of the stand-in shapes --------------------------------------------------------------
def test_equivalent_box_of_a_box_is_that_box() -> None:
    rng = np.random.default_rng(5)
    for _ in range(20):
        sides = tuple(rng.uniform(0.05, 2.0, 3))
        mass = rng.uniform(0.1, 10.0)
        R = pin.Quaternion(rng.normal(size=4)).normalized().toRotationMatrix()
        inertia = pin.Inertia(mass, rng.normal(size=3), R @ box_inertia(mass, sides) @ R.T)
        got, axes = equivalent_box(inertia)
        # the box's inertia, rebuilt in the body frame, is the body's
        rebuilt = axes @ box_inertia(mass, tuple(got)) @ axes.T
        np.testing.assert_allclose(rebuilt, inertia.inertia, atol=1e-10,
                                   err_msg=f"sides {sides}, mass {mass}")
        np.testing.assert_allclose(sorted(got), sorted(sides), rtol=1e-9)
        assert np.linalg.det(axes) == pytest.approx(1.0, abs=TOL)


def test_equivalent_box_of_a_rod_keeps_a_visible_thickness() -> None:
    rod = pin.Inertia(1.0, np.zeros(3), np.diag([1.0 / 12, 1.0 / 12, 0.0]))   # 1 m along z
    sides, _ = equivalent_box(rod)
    assert sorted(sides)[:2] == pytest.approx([MIN_SIDE, MIN_SIDE])
    assert max(sides) == pytest.approx(1.0)


def test_fallback_visual_model_has_a_box_per_body_and_a_cylinder_per_wheel() -> None:
    cart = cart_model()
    geom = fallback_visual_model(cart.model, cart.wheels)
    kinds = {g.name: type(g.geometry) for g in geom.geometryObjects}
    assert kinds == {"wheel_left_wheel": coal.Cylinder, "wheel_right_wheel": coal.Cylinder,
                     "psi_body": coal.Box}
    box = geom.geometryObjects[geom.getGeometryId("psi_body")]
    np.testing.assert_allclose(sorted(2 * box.geometry.halfSide), sorted(BODY_SIDES), rtol=1e-9)
    np.testing.assert_allclose(box.placement.translation, [0, 0, RADIUS + 0.25], atol=TOL)
    for w in cart.wheels:
        cyl = geom.geometryObjects[geom.getGeometryId(f"{cart.model.names[w.joint_id]}_wheel")]
        assert cyl.parentJoint == w.joint_id
        assert cyl.geometry.radius == pytest.approx(RADIUS)
        assert 2 * cyl.geometry.halfLength == pytest.approx(WIDTH)
        # the cylinder's axis (its z) is the wheel's spin axis (the joint's y)
        np.testing.assert_allclose(cyl.placement.rotation[:, 2], [0, 1, 0], atol=1e-12)


def test_joint_axis_of_an_unaligned_revolute_joint() -> None:
    model = pin.Model()
    axis = np.array([1.0, 2.0, 2.0]) / 3.0
    model.addJoint(0, pin.JointModelRevoluteUnaligned(axis), pin.SE3.Identity(), "a")
    model.addJoint(1, pin.JointModelPX(), pin.SE3.Identity(), "b")
    np.testing.assert_allclose(joint_axis(model, 1), axis, atol=TOL)
    with pytest.raises(ValueError, match="not a 1-DoF revolute"):
        joint_axis(model, 2)
