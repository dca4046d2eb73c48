r"""Named models shipped with the toolkit, and physical parameters applied to them.

``load_model("wip")`` builds the seed-001 wheeled pendulum from ``urdf/wip.urdf``;
``load_model("wip", WipParameters(...))`` the same body with other physical parameters (masses,
inertias, centre of mass, wheel radius R, half track L, gravity, motor armature).
``load_model("tiago")`` is PAL's TIAGo from example-robot-data (its casters are fixed joints in
the URDF: their mass is part of the base, their contact is what keeps the base level, so the
base does not pitch; their rolling is not modelled).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np
import pinocchio as pin

from ..errors import OptionalDependencyError, UnknownNameError
from ..paths import example_robot_data_share, urdf_dir
from .benchmarks import BENCHMARKS
from .builder import ModelSpec, WheeledModel, build_wheeled_model
from .wip_parameters import STANDARD_NAMES, WipParameters, standard_parameters


@dataclass(frozen=True)
class ModelEntry:
    name: str
    summary: str
    spec: Callable[[], ModelSpec]
    parameters: type | None = None          # physical-parameter record, if the model has one


def _wip_spec() -> ModelSpec:
    return ModelSpec(
        name="wip", urdf=urdf_dir() / "wip.urdf", body="body",
        wheels=("wheel_left", "wheel_right"), up=(0.0, 1.0, 0.0), pitch=True,
        aliases={"wheel_left_joint": "theta_l", "wheel_right_joint": "theta_r"},
        description="two-wheeled inverted pendulum of seed 001 (body pitching on its axle)")


def _wip_platform_spec() -> ModelSpec:
    return ModelSpec(
        name="wip_platform", urdf=urdf_dir() / "wip_platform.urdf", body="platform",
        wheels=("wheel_left", "wheel_right"), up=(0.0, 1.0, 0.0), pitch=False,
        aliases={"wheel_left_joint": "theta_l", "wheel_right_joint": "theta_r",
                 "hinge": "alpha", "pendulum_joint": "alpha", "alpha": "alpha"},
        description="level platform on two wheels carrying a pendulum on a passive hinge "
                    "(seed 001's book equations (9)-(14))")


def _tiago_spec() -> ModelSpec:
    share = example_robot_data_share()
    if share is None:
        raise OptionalDependencyError("model tiago", "example-robot-data",
                                      "pip install example-robot-data")
    return ModelSpec(
        name="tiago", urdf=share / "example-robot-data/robots/tiago_description/robots/"
        "tiago_no_hand.urdf", body="base_link", wheels=("wheel_left_link", "wheel_right_link"),
        up=(0.0, 0.0, 1.0), pitch=False, package_dirs=(str(share),),
        aliases={"wheel_left_joint": "theta_l", "wheel_right_joint": "theta_r"},
        description="PAL TIAGo (differential drive, torso, 7-DoF arm, head); casters fixed")


def _tiago_base_spec() -> ModelSpec:
    spec = _tiago_spec()
    upper = ("torso_lift_joint", *(f"arm_{i}_joint" for i in range(1, 8)), "head_1_joint",
             "head_2_joint")
    return ModelSpec(**{**spec.__dict__, "name": "tiago_base", "lock": upper,
                        "description": "TIAGo with torso, arm and head locked: a "
                                       "differential-drive base carrying a rigid upper body"})


#: Rolling radius of Upkie's wheels (m): the distance from ``left_wheel_tire`` to the
#: ``left_contact`` frame in upkie_description's URDF.
UPKIE_WHEEL_RADIUS = 0.047


def _upkie_spec() -> ModelSpec:
    try:
        import upkie_description
    except ImportError:
        raise OptionalDependencyError("model upkie", "upkie-description",
                                      "pip install upkie-description") from None
    from .rolling_wheel import WheelContact
    wheels = tuple(WheelContact(f"{side}_wheel_tire", UPKIE_WHEEL_RADIUS, axis=(0.0, 0.0, 1.0))
                   for side in ("left", "right"))
    return ModelSpec(
        name="upkie", urdf=Path(upkie_description.URDF_PATH), base="free", body="base",
        actuated=tuple(f"{side}_{joint}" for side in ("left", "right")
                       for joint in ("hip", "knee", "wheel")),
        package_dirs=(str(Path(upkie_description.__file__).parent.parent),),
        rolling_wheels=wheels, geometry={"R": UPKIE_WHEEL_RADIUS},
        description="Upkie wheel-legged robot (upkie-description): free base, hips and knees "
                    "free, both wheels rolling (knife edges, radius from the URDF's contact "
                    "frames)")


MODELS: dict[str, ModelEntry] = {
    "wip": ModelEntry("wip", "two-wheeled inverted pendulum (seed 001), 6 coordinates",
                      _wip_spec, WipParameters),
    "wip_platform": ModelEntry("wip_platform", "platform on two wheels with a hinged pendulum "
                               "(seed 001 eqs (9)-(14))", _wip_platform_spec),
    "tiago": ModelEntry("tiago", "PAL TIAGo from example-robot-data, differential drive + arm",
                        _tiago_spec),
    "tiago_base": ModelEntry("tiago_base", "TIAGo with torso, arm and head locked "
                             "(differential drive, 5 coordinates)", _tiago_base_spec),
    "upkie": ModelEntry("upkie", "Upkie wheel-legged robot, legs free, both wheels rolling "
                        "(upkie-description)", _upkie_spec),
}


MODELS.update({name: ModelEntry(name, summary, spec) for name, summary, spec in BENCHMARKS})


def model_names() -> tuple[str, ...]:
    return tuple(MODELS)


def model_entry(name: str) -> ModelEntry:
    try:
        return MODELS[name]
    except KeyError:
        raise UnknownNameError("model", name, MODELS) from None


@lru_cache(maxsize=None)
def _built(name: str) -> WheeledModel:
    return build_wheeled_model(model_entry(name).spec())


def load_model(name: str, params: WipParameters | None = None) -> WheeledModel:
    r"""The named model, with the given physical parameters if the model has a record."""
    base = _built(name)
    if params is None:
        return base.with_model(pin.Model(base.model))
    entry = model_entry(name)
    if entry.parameters is None or not isinstance(params, entry.parameters):
        raise UnknownNameError("parameter record", type(params).__name__,
                               [entry.parameters.__name__] if entry.parameters else [],
                               where=f"model {name}")
    return apply_wip_parameters(base, params)


def _link_inertia(wm: WheeledModel, model: pin.Model, link: str, values: dict) -> pin.Inertia:
    """The link's inertia, given in its link frame, expressed in its joint's frame."""
    frame = model.frames[model.getFrameId(link)]
    vec = np.array([float(values[k]) for k in STANDARD_NAMES])
    return frame.placement.act(pin.Inertia.FromDynamicParameters(vec))


def apply_wip_parameters(wm: WheeledModel, p: WipParameters) -> WheeledModel:
    r"""A copy of the WIP model ``wm`` with parameters ``p``: inertias of body and wheels,
    axle height R, wheel positions :math:`z = \mp L`, armature, gravity."""
    model = pin.Model(wm.model)
    std = standard_parameters(p.as_dict())
    body_jid = wm.body_joint_id
    model.inertias[body_jid] = _link_inertia(wm, model, "body", std["body"])
    placement = model.jointPlacements[body_jid]
    model.jointPlacements[body_jid] = pin.SE3(placement.rotation, np.array([0.0, 0.0, p.R]))
    wheels = []
    for wheel, sign in zip(wm.wheels, (-1.0, 1.0)):
        model.inertias[wheel.joint_id] = _link_inertia(wm, model, wheel.link, std[wheel.link])
        jp = model.jointPlacements[wheel.joint_id]
        model.jointPlacements[wheel.joint_id] = pin.SE3(jp.rotation, np.array([0.0, 0.0, sign * p.L]))
        model.armature[wheel.v_index] = p.I_a
        wheels.append(type(wheel)(wheel.link, wheel.side, wheel.joint_name, wheel.joint_id,
                                  wheel.v_index, p.R, wheel.width))
    model.gravity = pin.Motion(np.array([0.0, 0.0, -p.g]), np.zeros(3))
    return WheeledModel(wm.name, wm.spec, model, wm.visual_model, tuple(wheels),
                        wm.coordinate_names, wm.input_names, {"R": p.R, "L": p.L}, body_jid)


def model_parameters(wm: WheeledModel) -> dict[str, float]:
    r"""Numeric values of the model's named parameters: its geometry (R, L for a wheeled
    model; the spec's named constants otherwise), g and, per link with mass, Khalil's standard
    parameters keyed ``XX(link)`` etc. (in the link frame)."""
    out = {**{k: float(v) for k, v in wm.geometry.items()},
           "g": float(-wm.model.gravity.linear[2])}
    for frame in wm.model.frames:
        if frame.type != pin.FrameType.BODY:
            continue
        inertia = frame.placement.actInv(wm.model.inertias[frame.parentJoint])
        if inertia.mass <= 0:
            continue
        # only links that are alone on their joint have their own parameters
        for key, value in zip(STANDARD_NAMES, inertia.toDynamicParameters()):
            out[f"{key}({frame.name})"] = float(value)
    return out
