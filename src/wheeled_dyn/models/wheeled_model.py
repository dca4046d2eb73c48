r"""What to build and what is built: :class:`ModelSpec` (a URDF, its base, body, wheels and
conventions), :class:`WheeledModel` (the Pinocchio model with its coordinate names, wheels,
inputs and named lengths) and :class:`Wheel`.

A built model's dynamics are Pinocchio's plus the joint springs' (:mod:`.springs`):

.. math::

    Q(q) = \frac{\partial U}{\partial q},\qquad
    U(q) = U_{\text{gravity}}(q) + \sum_s \tfrac12 k_s (q_{j_s} - q_{j_s,0})^2,

and the motors enter through :math:`B` with :math:`B_{ik} = \delta_{i,j_k}` (motor :math:`k`
on joint :math:`j_k`). How a spec is built: :mod:`.builder`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np
import pinocchio as pin

from ..errors import UnknownNameError
from . import geometry as geo
from .contact import BallContact, SphereContact
from .rolling_wheel import BoundWheelContact, WheelContact
from .springs import BoundSpring, JointSpring, spring_energy, spring_force

#: Coordinate names of the six joints of a free base (ZYX angles: yaw, pitch, roll).
FREE_BASE = ("x0", "y0", "z0", "yaw", "pitch", "roll")


@dataclass(frozen=True)
class ModelSpec:
    r"""What to build: a URDF, its base, body and wheels, conventions. See the module docstring.

    ``body`` and ``wheels`` (left, right) are required for ``base = "planar"``; the other bases
    take no wheels. ``inputs`` names the motor inputs (default ``tau_l, tau_r`` for the wheels,
    ``tau_<coordinate>`` for each ``actuated`` joint)."""

    name: str
    urdf: Path
    body: str = ""
    wheels: tuple[str, ...] = ()                 # (left wheel link, right wheel link)
    up: tuple[float, float, float] = (0.0, 0.0, 1.0)
    pitch: bool = True
    lock: tuple[str, ...] = ()
    aliases: Mapping[str, str] = field(default_factory=dict)   # joint name -> coordinate name
    inputs: tuple[str, ...] | None = None
    radius: float | None = None
    package_dirs: tuple[str, ...] = ()
    description: str = ""
    base: str = "planar"
    actuated: tuple[str, ...] = ()               # joint names with a motor (beside the wheels')
    geometry: Mapping[str, object] = field(default_factory=dict)   # [geometry]: see .geometry
    contact: SphereContact | None = None
    rolling_wheels: tuple[WheelContact, ...] = ()   # tilting wheels on any link (fixed/free)
    locked: Mapping[str, float] = field(default_factory=dict)  # values of ``lock`` joints
    accept_inertia: tuple[str, ...] = ()         # links whose URDF inertia is not checked
    coordinate_sets: Mapping[str, Mapping] = field(default_factory=dict)  # declared sets
    default_coordinates: str | None = None       # the default coordinate set's name
    source: Path | None = None                   # the model file, if the spec came from one
    springs: tuple[JointSpring, ...] = ()        # linear springs along or about joints
    forward: tuple[float, float, float] | None = None   # body's forward, link axes (planar)
    fixed_geometry: tuple[str, ...] = ()         # [draw] fixed: names no parameter set draws


@dataclass(frozen=True)
class Wheel:
    r"""A drive wheel of a built model."""

    link: str
    side: str            # "left" or "right"
    joint_name: str
    joint_id: int
    v_index: int
    radius: float
    width: float


@dataclass(frozen=True)
class WheeledModel:
    r"""A Pinocchio model of a wheeled, fixed-base or free body with its conventions.

    ``coordinate_names[i]`` names ``q[i]`` (and ``v[i]``); ``wheels`` are the drive wheels
    (none for fixed and free bases); ``input_names`` the motor inputs: wheel torques (about each
    wheel joint axis, reaction on the wheel's parent), or one per joint of ``actuated``
    (velocity indices); ``geometry`` holds the named constants (``R`` wheel radius and ``L``
    half the distance between the wheel centres for a planar model, the spec's ``geometry``
    otherwise); ``contact`` the rolling ball, if any; ``lengths`` the named lengths and
    constants (:mod:`.geometry`: ``origin_x(joint)``, ``radius(link)`` ...); ``readings``
    what it reads otherwise than its URDF writes (:mod:`.readings`).
    """

    name: str
    spec: ModelSpec
    model: pin.Model
    visual_model: pin.GeometryModel | None
    wheels: tuple[Wheel, ...]
    coordinate_names: tuple[str, ...]
    input_names: tuple[str, ...]
    geometry: Mapping[str, float]
    body_joint_id: int
    actuated: tuple[int, ...] = ()
    contact: BallContact | None = None
    rolling_wheels: tuple[BoundWheelContact, ...] = ()
    springs: tuple[BoundSpring, ...] = ()
    lengths: geo.GeometryTable | None = None
    #: what the model reads otherwise than its URDF writes it (:mod:`.readings`), in words
    readings: tuple[str, ...] = ()

    @property
    def dimensions(self) -> dict[str, float]:
        r"""The named lengths (:mod:`.geometry`): ``{"origin_x(elbow)": 1.0, ...}``."""
        return {} if self.lengths is None else {k: d.value for k, d in
                                                self.lengths.dimensions.items()}

    def named_lengths(self) -> dict[str, float]:
        r"""The names a coordinate expression may use: the constants (``R``, ``L``, ...) and
        the lengths as identifiers (``radius_coin`` for ``radius(coin)``)."""
        out = {geo.identifier(k): v for k, v in self.dimensions.items()}
        out.update(self.geometry)
        return out

    @property
    def nv(self) -> int:
        return self.model.nv

    @property
    def base(self) -> str:
        return self.spec.base

    def index(self, coordinate: str) -> int:
        try:
            return self.coordinate_names.index(coordinate)
        except ValueError:
            raise UnknownNameError("coordinate", coordinate, self.coordinate_names,
                                   where=f"model {self.name}") from None

    def joint_id_of_link(self, link: str) -> int:
        r"""The joint that moves ``link`` (its body frame's parent joint); a name that is no
        link's (a joint's: its frame is no body's) is an unknown link."""
        if not self.model.existFrame(link, pin.FrameType.BODY):
            names = [f.name for f in self.model.frames if f.type == pin.FrameType.BODY]
            raise UnknownNameError("link", link, names, where=f"model {self.name}")
        return self.model.frames[self.model.getFrameId(link, pin.FrameType.BODY)].parentJoint

    def input_matrix(self) -> np.ndarray:
        r"""B (nv × number of motors): motor k acts on its joint, :math:`B_{ik}=\delta_{i,j_k}`
        (the wheel joints, then the ``actuated`` joints; nv × 0 for a body without
        motors)."""
        columns = [*(w.v_index for w in self.wheels), *self.actuated]
        B = np.zeros((self.nv, len(columns)))
        for k, i in enumerate(columns):
            B[i, k] = 1.0
        return B

    def with_model(self, model: pin.Model, springs: tuple[BoundSpring, ...] | None = None
                   ) -> "WheeledModel":
        r"""The same conventions on another Pinocchio model of identical structure (e.g. other
        inertial parameters), and other spring stiffnesses if ``springs`` is given."""
        return replace(self, model=model, springs=self.springs if springs is None else springs)

    def potential_force(self, data: pin.Data, q: np.ndarray) -> np.ndarray:
        r""":math:`Q(q) = \partial U/\partial q`: Pinocchio's generalised gravity plus the
        joint springs' :math:`k (q_j - q_{j,0})` (:mod:`.springs`)."""
        Q = pin.computeGeneralizedGravity(self.model, data, q).copy()
        return Q + spring_force(self.springs, q, self.nv) if self.springs else Q

    def potential_energy(self, data: pin.Data, q: np.ndarray) -> float:
        r""":math:`U(q)`: gravity (Pinocchio) plus the springs' :math:`\tfrac12 k (q_j -
        q_{j,0})^2`."""
        U = float(pin.computePotentialEnergy(self.model, data, q))
        # one configuration: spring_energy gives a float here (an array only for N of them)
        return U + float(spring_energy(self.springs, q)) if self.springs else U

    def nonlinear_effects(self, data: pin.Data, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        r""":math:`C(q, v) v + Q(q)` by ``pin.nonLinearEffects``, springs included."""
        n = pin.nonLinearEffects(self.model, data, q, v).copy()
        return n + spring_force(self.springs, q, self.nv) if self.springs else n



def coordinate_vector(wm: WheeledModel, values: Mapping[str, float] | Sequence[float]
                      ) -> np.ndarray:
    r"""A model vector from a mapping name → value (missing entries are 0) or a sequence."""
    if isinstance(values, Mapping):
        out = np.zeros(wm.nv)
        for key, val in values.items():
            out[wm.index(key)] = float(val)
        return out
    return np.asarray(values, dtype=float).reshape(wm.nv)
