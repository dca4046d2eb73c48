r"""A model from any URDF on one of three bases: ``planar`` (wheeled), ``fixed`` or ``free``.

Every joint of a built model has one degree of freedom (so that q and v have the same size and
Christoffel symbols exist). ``ModelSpec.base`` chooses what carries the URDF's root link:

- ``"planar"`` (the default; a wheeled body): given the link that carries the axle (the *body*)
  and the two drive wheels,

  .. math::

      q = (x_0,\ y_0,\ \psi,\ [\varphi],\ \text{the URDF's own joints}\ \dots)

  * :math:`x_0, y_0` (prismatic along the world x and y): the point on the ground plane
    :math:`z = 0` below the axle midpoint;
  * :math:`\psi` (revolute about the world z, up): the heading, the body's forward direction;
  * :math:`\varphi` (optional, revolute about the axle, oriented from the left wheel to the right
    wheel): the pitch of the body; the axle midpoint is at height :math:`R` (wheel radius);
  * then the URDF's tree as written, hanging from the body, with ``continuous`` joints as
    unlimited revolute joints (each wheel angle is one coordinate, measured relative to the body).

  The body's *up* direction (in its link frame, at zero pitch) is declared; *forward* is
  up × axle. The wheel radius comes from the wheel link's cylinder geometry unless given.
- ``"fixed"``: the URDF as written, its root link fixed to the world (world z up, gravity −z);
  no wheels. ``q`` is the URDF's joints.
- ``"free"``: the root link on six 1-DoF joints, ``q = (x0, y0, z0, yaw, pitch, roll, ...)``:
  translations along the world axes, then :math:`R = R_z(\text{yaw})\,R_y(\text{pitch})\,
  R_x(\text{roll})` (ZYX angles). The body's angular velocity in its own frame is

  .. math::

      \omega_B = \begin{bmatrix}\dot\phi - \sin\theta\,\dot\psi\\
      \cos\phi\,\dot\theta + \sin\phi\cos\theta\,\dot\psi\\
      -\sin\phi\,\dot\theta + \cos\phi\cos\theta\,\dot\psi\end{bmatrix}
      \quad(\psi, \theta, \phi = \text{yaw, pitch, roll}),

  singular at :math:`\text{pitch} = \pm\pi/2` (yaw and roll turn about the same axis there:
  keep motions away from it, or use body angular velocities as quasi-velocities, which are
  regular everywhere the angles are).

Joints listed in ``lock`` are frozen, at the values of ``locked`` (0 for a joint not given
there); their bodies' inertia is merged into their parents. A wheel link may hang from its spin
joint through fixed joints (a tyre on a hub on a motor rotor): its link origin is the wheel
centre, which must lie on the spin axis; the joint's origin is moved along its axis to that
centre (an exact change of frame: a rotation about an axis commutes with a translation along
it), so the rolling constraint acts at the tyre. Motors: the wheel joints of a planar model;
on the other bases, the joints listed in ``actuated`` (a torque or force along each joint
axis, reaction on the parent). ``geometry`` names constants that coordinate sets and
derivation files may use (a rolling radius, a gear ratio); a ball rolling without slip on the ground, on a fixed sphere or inside a paraboloid
bowl, or a spheroid on the ground, is declared by ``contact``
(:class:`~wheeled_dyn.models.contact.SphereContact`); a linear spring along or about a joint by
``springs`` (:mod:`.springs`: :math:`Q` and :math:`U` then include it).

The records are in :mod:`.wheeled_model`, the planar base in :mod:`.planar_base`, the fixed
and free bases in :mod:`.unwheeled_base`, the joint operations shared by both in
:mod:`.model_joints`; this module reads the URDF, locks joints and dispatches on the base.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import replace

import numpy as np
import pinocchio as pin

from ..errors import InputFileError, ModelError, UnknownNameError
from .model_joints import DIRECTION_TOL, GRAVITY
from .readings import urdf_readings
from .planar_base import AXIS_TOL, HORIZONTAL_TOL, RADIUS_TOL, build_planar
from .unwheeled_base import build_unwheeled
from .urdf_checks import check_mimic
from .urdf_source import UrdfSource, read_urdf
from .visual_geometry import visual_geometry
from .model_file import BASES
from .wheeled_model import FREE_BASE, ModelSpec, Wheel, WheeledModel, coordinate_vector

#: Names importable from here, where the model was built before its parts had modules.
__all__ = ["AXIS_TOL", "BASES", "DIRECTION_TOL", "FREE_BASE", "GRAVITY", "HORIZONTAL_TOL",
           "RADIUS_TOL", "ModelSpec", "Wheel", "WheeledModel", "build_wheeled_model",
           "coordinate_vector"]


def _urdf_models(source: UrdfSource, spec: ModelSpec) -> tuple[pin.Model, pin.GeometryModel]:
    r"""The URDF's Pinocchio model and visual geometry, mimic joints checked, the ``lock``
    joints frozen at their ``locked`` values (their inertia merged into their parents)."""
    check_mimic(source.path, source.text, ET.fromstring(source.text), spec.locked, spec.lock)
    text = source.pinocchio_text()
    try:
        model = pin.buildModelFromXML(text)
    except (ValueError, RuntimeError) as exc:   # what the checks before did not foresee
        raise InputFileError(source.path, f"Pinocchio cannot read this URDF ({exc}); its "
                                          "reader's 'Error:' lines above say where") from None
    geom = visual_geometry(source, spec.name, spec.package_dirs, model, text)
    for name in spec.locked:
        if name not in spec.lock:
            raise ModelError(spec.name, name, "a value is given for a joint that is not locked")
    if spec.lock:
        ids = []
        q_ref = pin.neutral(model)
        for name in spec.lock:
            if not model.existJointName(name):
                raise UnknownNameError("joint", name, list(model.names)[1:],
                                       where=str(source.path))
            jid = model.getJointId(name)
            ids.append(jid)
            value = float(spec.locked.get(name, 0.0))
            if model.joints[jid].nq != 1:          # a URDF's floating or planar joint
                raise ModelError(spec.name, name, f"a joint of {model.joints[jid].nq} "
                                 "coordinates (floating or planar) cannot be locked at one "
                                 "value: make it fixed in the URDF (the model's base gives "
                                 "the body its motion)")
            if not np.isfinite(value):
                raise ModelError(spec.name, name, f"locked value {value!r}: expected a finite "
                                                  "number")
            k = model.joints[jid].idx_q
            low, high = float(model.lowerPositionLimit[k]), float(model.upperPositionLimit[k])
            if low < high and not low <= value <= high:    # limits the URDF gives (not 0, 0)
                raise ModelError(spec.name, name, f"locked at {value:g}, outside the joint's "
                                 f"limits [{low:g}, {high:g}] in the URDF (a pose the robot "
                                 "cannot take: a value in radians, or metres, within them)")
            q_ref[k] = value
        model, geom = pin.buildReducedModel(model, geom, ids, q_ref)
    return model, geom


def _check_names(spec: ModelSpec, source: UrdfSource) -> None:
    r"""The links and joints the spec names only to describe them (``[joints] aliases``,
    ``[checks] accept_inertia``) exist in the URDF: a misspelt one would change nothing,
    silently. :class:`UnknownNameError` names the model file (or model), the key and the
    valid names."""
    where = str(spec.source) if spec.source is not None else f"model {spec.name}"
    for key, links in (("[base] body", (spec.body,) if spec.body else ()),
                       ("[wheels] links", spec.wheels)):
        for link in links:
            if link not in source.link_names:
                raise UnknownNameError("link", link, source.link_names, where=f"{where}: {key}")
    for joint in spec.aliases:
        if joint not in source.joint_names:
            raise UnknownNameError("joint", joint, source.joint_names,
                                   where=f"{where}: [joints] aliases")
    for link in spec.accept_inertia:
        if link not in source.link_names:
            raise UnknownNameError("link", link, source.link_names,
                                   where=f"{where}: [checks] accept_inertia")


def build_wheeled_model(spec: ModelSpec) -> WheeledModel:
    r"""Build the model described by ``spec`` (see the module docstring)."""
    if spec.base not in BASES:
        raise ModelError(spec.name, None, f"base {spec.base!r}; expected one of {BASES}")
    if spec.rolling_wheels and spec.base == "planar":
        raise ModelError(spec.name, spec.rolling_wheels[0].link, "tilting wheels need base "
                                                                  "'free' or 'fixed', not 'planar'")
    if spec.contact is not None and spec.base == "planar":
        raise ModelError(spec.name, spec.contact.link, "a rolling ball needs base 'free' or "
                                                       "'fixed', not 'planar'")
    source = read_urdf(spec.urdf, tuple(spec.lock), tuple(spec.accept_inertia))
    _check_names(spec, source)
    urdf_model, urdf_geom = _urdf_models(source, spec)
    built = (build_planar if spec.base == "planar" else build_unwheeled)(
        spec, source, urdf_model, urdf_geom)
    return replace(built, readings=urdf_readings(source.text, tuple(spec.lock)) + built.readings)
