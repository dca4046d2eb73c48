r"""The models: the shipped model files (``data/models/*.toml``), models written in Python,
and model files named by path; physical parameters applied to them.

``load_model("wip")`` builds the seed-001 wheeled pendulum described by ``data/models/wip.toml``;
``load_model("wip", WipParameters(...))`` the same body with other physical parameters (masses,
inertias, centre of mass, wheel radius R, half track L, gravity, motor armature).
``load_model("path/to/robot.toml")`` builds the model a user's file describes (any reference
ending in ``.toml`` or containing a path separator is a file; format: ``docs/model-format.md``).
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

from ..errors import UnknownNameError
from .benchmarks import PYTHON_BENCHMARKS
from .builder import ModelSpec, WheeledModel, build_wheeled_model
from .listing import shipped_model_files
from .model_file import ModelFile, is_model_path, read_model_file
from .springs import spring_parameters
from .wip_parameters import STANDARD_NAMES, WipParameters, standard_parameters


@dataclass(frozen=True)
class ModelEntry:
    name: str
    summary: str
    spec: Callable[[], ModelSpec]
    parameters: type | None = None          # physical-parameter record, if the model has one
    source: Path | None = None              # the model file, if the model is one


#: Physical-parameter records by the name a model file gives (``parameters = "wip"``).
PARAMETER_RECORDS: dict[str, type] = {"wip": WipParameters}

#: Rolling radius of Upkie's wheels (m): the distance from ``left_wheel_tire`` to the
#: ``left_contact`` frame in upkie_description's URDF (``data/models/upkie.toml``).
UPKIE_WHEEL_RADIUS = 0.047


def file_entry(mf: ModelFile) -> ModelEntry:
    r"""The registry entry of a model file."""
    return ModelEntry(mf.name, mf.summary, mf.spec,
                      PARAMETER_RECORDS[mf.parameters] if mf.parameters else None, mf.path)


MODELS: dict[str, ModelEntry] = {name: file_entry(mf)
                                 for name, mf in shipped_model_files().items()}
for _name, _summary, _spec in PYTHON_BENCHMARKS:
    if _name in MODELS:
        raise UnknownNameError("model", _name, (), where="models.benchmarks: defined twice")
    MODELS[_name] = ModelEntry(_name, _summary, _spec)


def register_model(name: str, summary: str, spec: Callable[[], ModelSpec],
                   parameters: type | None = None) -> ModelEntry:
    r"""Register a model written in Python (a :class:`ModelSpec` function) under ``name``."""
    MODELS[name] = ModelEntry(name, summary, spec, parameters)
    _built.cache_clear()
    return MODELS[name]


def model_names() -> tuple[str, ...]:
    return tuple(MODELS)


@lru_cache(maxsize=None)
def _path_entry(resolved: str) -> ModelEntry:
    return file_entry(read_model_file(resolved))


def model_key(reference: str | Path) -> str:
    r"""The registry key of a model reference: the name, or the model file's absolute path."""
    text = str(reference)
    if text in MODELS or not is_model_path(text):
        return text
    return str(Path(text).expanduser().resolve())


def model_entry(reference: str | Path) -> ModelEntry:
    r"""The entry of a model name or a model file path (see the module docstring)."""
    key = model_key(reference)
    if key in MODELS:
        return MODELS[key]
    if is_model_path(key):
        return _path_entry(key)
    raise UnknownNameError("model", str(reference), MODELS,
                           where="names, or a model file path (name.toml)")


@lru_cache(maxsize=None)
def _built(key: str) -> WheeledModel:
    return build_wheeled_model(model_entry(key).spec())


def load_model(name: str | Path, params: WipParameters | None = None) -> WheeledModel:
    r"""The model named ``name`` (or described by the model file at that path), with the given
    physical parameters if the model has a record."""
    base = _built(model_key(name))
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
    model; the spec's named constants otherwise), g, each spring's ``k_<name>``,
    ``rest_<name>`` and, per rigid body with mass, named by the link carrying it, Khalil's
    standard parameters keyed ``XX(link)`` (about the link origin) and the physical ones keyed
    ``IXX(link)``, ``CX(link)`` (about the centre of mass), both in the link frame
    (:mod:`.link_parameters`)."""
    from .link_parameters import parameter_values
    return {**{k: float(v) for k, v in wm.geometry.items()},
            "g": float(-wm.model.gravity.linear[2]), **spring_parameters(wm.springs),
            **parameter_values(wm)}
