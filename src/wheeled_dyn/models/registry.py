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
from dataclasses import dataclass, replace
from functools import lru_cache
from pathlib import Path
from types import MappingProxyType

import numpy as np
import pinocchio as pin

from ..errors import ArgumentError, InputFileError, UnknownNameError
from ..paths import file_stamp, resolved
from .benchmarks import PYTHON_BENCHMARKS
from .builder import build_wheeled_model
from .listing import shipped_model_files
from .model_file import ModelFile, is_model_path, read_model_file
from .springs import spring_parameters
from .wheeled_model import ModelSpec, WheeledModel
from .wip_parameters import STANDARD_NAMES, WipParameters, standard_parameters


@dataclass(frozen=True)
class ModelEntry:
    name: str
    summary: str
    spec: Callable[[], ModelSpec]
    parameters: type | None = None          # physical-parameter record, if the model has one
    source: Path | None = None              # the model file, if the model is one


#: Models (and model files read) kept in memory, each per content of its files.
MODEL_CACHE = 128

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
#: The stamps of the shipped model files as they were read for :data:`MODELS`.
_READ: dict[str, tuple | None] = {str(e.source): file_stamp(e.source) for e in MODELS.values()
                                  if e.source is not None}
for _name, _summary, _spec in PYTHON_BENCHMARKS:
    if _name in MODELS:
        raise UnknownNameError("model", _name, (), where="models.benchmarks: defined twice")
    MODELS[_name] = ModelEntry(_name, _summary, _spec)


def register_model(name: str, summary: str, spec: Callable[[], ModelSpec],
                   parameters: type | None = None) -> ModelEntry:
    r"""Register a model written in Python (a :class:`ModelSpec` function) under ``name``."""
    MODELS[name] = ModelEntry(name, summary, spec, parameters)
    _built.cache_clear()
    _spec_of.cache_clear()
    return MODELS[name]


def model_names() -> tuple[str, ...]:
    return tuple(MODELS)


@lru_cache(maxsize=MODEL_CACHE)
def _path_entry(resolved: str, stamp: tuple | None) -> ModelEntry:
    return file_entry(read_model_file(resolved))


def model_key(reference: str | Path) -> str:
    r"""The registry key of a model reference: the name, or the model file's absolute path."""
    text = _reference(reference)
    if text in MODELS or not is_model_path(text):
        return text
    return str(resolved(Path(text).expanduser()))


def _reference(reference: object) -> str:
    r"""``reference`` as text, if it can name a model; else :class:`ArgumentError`."""
    if not isinstance(reference, (str, Path)) or isinstance(reference, bool):
        raise ArgumentError("load_model", "name", reference,
                            "a model name (see wheeled_dyn.model_names()) or a model file "
                            "path (str or Path)")
    text = str(reference)
    if not text or "\0" in text:
        raise ArgumentError("load_model", "name", reference,
                            "a model name or a model file path without NUL characters")
    return text


def model_entry(reference: str | Path) -> ModelEntry:
    r"""The entry of a model name or a model file path (see the module docstring); a model
    file is read again when it changed since it was read."""
    key = model_key(reference)
    entry = MODELS.get(key)
    if entry is not None:
        if entry.source is None:
            return entry
        stamp = file_stamp(entry.source)                     # a shipped model file
        return entry if _READ.get(str(entry.source)) == stamp else _path_entry(
            str(entry.source), stamp)
    if is_model_path(key):
        return _path_entry(key, file_stamp(key))
    if Path(str(reference)).is_dir():
        raise InputFileError(Path(str(reference)), "is a folder, expected a model file "
                             "(name.toml) or a shipped model's name")
    raise UnknownNameError("model", str(reference), (*MODELS, "a model file (name.toml)"))


def model_spec(reference: str | Path) -> ModelSpec:
    r"""The :class:`ModelSpec` of a model (made once per content of its model file)."""
    key = model_key(reference)
    entry = model_entry(key)
    return _spec_of(key, None if entry.source is None else file_stamp(entry.source))


@lru_cache(maxsize=MODEL_CACHE)
def _spec_of(key: str, stamp: tuple | None) -> ModelSpec:
    return model_entry(key).spec()


def model_files(reference: str | Path) -> tuple[Path, ...]:
    r"""The files a model is built from: its model file (when it has one) and its URDF."""
    entry = model_entry(reference)
    urdf = Path(model_spec(reference).urdf)
    return (Path(entry.source), urdf) if entry.source is not None else (urdf,)


def model_version(reference: str | Path) -> tuple:
    r"""What identifies the content a model is built from: the :func:`file_stamp` of each of
    its :func:`model_files`. A cached model, truth or result made under another version is
    stale."""
    return tuple((str(f), file_stamp(f)) for f in model_files(reference))


@lru_cache(maxsize=MODEL_CACHE)
def _built(key: str, version: tuple) -> WheeledModel:
    return build_wheeled_model(model_spec(key))


def load_model(name: str | Path, params: WipParameters | None = None) -> WheeledModel:
    r"""The model named ``name`` (or described by the model file at that path), with the given
    physical parameters if the model has a record. Built once per content of its files
    (:func:`model_version`): a model file or URDF saved since is read again."""
    key = model_key(name)
    base = _built(key, model_version(key))
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
    lengths = wm.lengths
    if lengths is not None:                 # the wheels' radius R and half track L
        radii = {f"radius({w.link})" for w in wm.wheels}
        lengths = type(lengths)(
            MappingProxyType({k: replace(d, value=p.R) if k in radii else d
                              for k, d in lengths.dimensions.items()}),
            MappingProxyType({k: replace(c, value={"R": p.R, "L": p.L}.get(k, c.value))
                              for k, c in lengths.constants.items()}))
    return WheeledModel(wm.name, wm.spec, model, wm.visual_model, tuple(wheels),
                        wm.coordinate_names, wm.input_names, {"R": p.R, "L": p.L}, body_jid,
                        lengths=lengths, readings=wm.readings)


def model_parameters(wm: WheeledModel) -> dict[str, float]:
    r"""Numeric values of the model's named parameters: its geometry (R, L for a wheeled
    model; the spec's named constants otherwise), its lengths keyed ``origin_x(joint)``,
    ``radius(link)`` etc. (:mod:`.geometry`), g, each spring's ``k_<name>``,
    ``rest_<name>`` and, per rigid body with mass, named by the link carrying it, Khalil's
    standard parameters keyed ``XX(link)`` (about the link origin) and the physical ones keyed
    ``IXX(link)``, ``CX(link)`` (about the centre of mass), both in the link frame
    (:mod:`.link_parameters`)."""
    from .link_parameters import parameter_values
    return {**{k: float(v) for k, v in wm.geometry.items()}, **wm.dimensions,
            "g": float(-wm.model.gravity.linear[2]), **spring_parameters(wm.springs),
            **parameter_values(wm)}
