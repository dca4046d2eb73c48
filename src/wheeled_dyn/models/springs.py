r"""Linear springs along or about one joint: what a model spec declares and what they add to
the equations of motion.

A spring on a prismatic joint (a translational spring, stiffness in N/m) or a revolute joint
(a torsional spring, N m/rad) with coordinate :math:`q_j` stores

.. math::

    U_s = \tfrac12\,k\,(q_j - q_{j,0})^2, \qquad
    Q_j \mathrel{+}= \frac{\partial U_s}{\partial q_j} = k\,(q_j - q_{j,0}),

where :math:`q_{j,0}` (``rest``) is the joint position at which the spring is relaxed (its free
length, for a spring whose length is the joint's coordinate). So the model's
:math:`Q = \partial U/\partial q` is Pinocchio's generalised gravity plus these terms, and its
potential :math:`U` is Pinocchio's plus :math:`\sum U_s` (:meth:`~.wheeled_model.WheeledModel.
potential_force`, :meth:`~.wheeled_model.WheeledModel.potential_energy`).

Each spring is named; derivation files refer to its stiffness and rest position as the model
parameters ``k_<name>`` and ``rest_<name>`` (``K = { value = "k_radial" }``). Random parameter
sets scale every stiffness and every rest position that is not 0
(:mod:`wheeled_dyn.compare.grid.samples`): a document writing the model's rest length as a
number is then right for that model only, and differs.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ..errors import ParameterError

#: Joint kinds a spring may act along or about (Pinocchio short names).
SPRING_JOINTS: tuple[str, ...] = ("JointModelPX", "JointModelPY", "JointModelPZ",
                                  "JointModelPrismaticUnaligned", "JointModelRX",
                                  "JointModelRY", "JointModelRZ",
                                  "JointModelRevoluteUnaligned")


@dataclass(frozen=True)
class JointSpring:
    r"""A linear spring on joint ``joint``: stiffness ``stiffness`` (> 0) and the joint
    position ``rest`` at which it is relaxed. Validated on construction."""

    name: str
    joint: str
    stiffness: float
    rest: float = 0.0

    def __post_init__(self) -> None:
        if not (isinstance(self.name, str) and self.name.isidentifier()):
            raise ParameterError("spring name", self.name, "a name (letters, digits, _)")
        for label, value, positive in (("stiffness", self.stiffness, True),
                                       ("rest", self.rest, False)):
            ok = (isinstance(value, (int, float)) and not isinstance(value, bool)
                  and math.isfinite(value))
            if not ok or (positive and value <= 0):
                raise ParameterError(f"{label} of spring {self.name}", value,
                                     "a positive number" if positive else "a finite number")

    @property
    def parameter_names(self) -> tuple[str, str]:
        r"""The names of its stiffness and rest position among the model's parameters."""
        return f"k_{self.name}", f"rest_{self.name}"


@dataclass(frozen=True)
class BoundSpring:
    r"""A :class:`JointSpring` bound to a built model: the joint's position index ``q_index``
    and velocity index ``v_index``; ``stiffness`` and the rest position may differ from the
    spec's (random parameter sets scale them: ``rest_value``, None for the spec's)."""

    spec: JointSpring
    q_index: int
    v_index: int
    stiffness: float
    rest_value: float | None = None

    @property
    def rest(self) -> float:
        return float(self.spec.rest if self.rest_value is None else self.rest_value)


def spring_force(springs: Sequence[BoundSpring], q: np.ndarray, nv: int) -> np.ndarray:
    r""":math:`\partial U_s/\partial q` (length ``nv``) at one configuration ``q``."""
    return spring_force_batch(springs, np.asarray(q, dtype=float)[None], nv)[0]


def spring_force_batch(springs: Sequence[BoundSpring], q: np.ndarray, nv: int) -> np.ndarray:
    r""":func:`spring_force` at N configurations (``q``: N × nq) at once: N × nv."""
    q = np.atleast_2d(q)
    out = np.zeros((q.shape[0], nv))
    for s in springs:
        out[:, s.v_index] += s.stiffness * (q[:, s.q_index] - s.rest)
    return out


def spring_energy(springs: Sequence[BoundSpring], q: np.ndarray) -> float | np.ndarray:
    r""":math:`\sum_s \tfrac12 k_s (q_{j_s} - q_{j_s,0})^2` at one configuration (a float) or at
    N configurations (``q``: N × nq; an array of N)."""
    q = np.asarray(q, dtype=float)
    total = np.zeros(q.shape[:-1])
    for s in springs:
        total = total + 0.5 * s.stiffness * (q[..., s.q_index] - s.rest) ** 2
    return float(total) if total.ndim == 0 else total


def spring_parameters(springs: Sequence[BoundSpring]) -> dict[str, float]:
    r"""``{k_<name>: stiffness, rest_<name>: rest}`` of each spring."""
    out: dict[str, float] = {}
    for s in springs:
        k_name, rest_name = s.spec.parameter_names
        out[k_name] = float(s.stiffness)
        out[rest_name] = s.rest
    return out


def with_stiffness(springs: Sequence[BoundSpring],
                   factors: Sequence[float] | np.ndarray | Mapping[str, float],
                   rest_factors: Sequence[float] | np.ndarray | None = None
                   ) -> tuple[BoundSpring, ...]:
    r"""The springs with each stiffness multiplied by its factor (one per spring, in order, or
    by name), and each rest position by its ``rest_factors`` entry (in order; a rest position
    0 stays 0)."""
    if isinstance(factors, Mapping):
        factors = [factors.get(s.spec.name, 1.0) for s in springs]
    rests = [None] * len(springs) if rest_factors is None else \
        [s.rest * float(f) for s, f in zip(springs, rest_factors, strict=True)]
    return tuple(BoundSpring(s.spec, s.q_index, s.v_index, s.stiffness * float(f),
                             s.rest_value if r is None else r)
                 for s, f, r in zip(springs, factors, rests, strict=True))


__all__ = ["BoundSpring", "JointSpring", "SPRING_JOINTS", "spring_energy", "spring_force",
           "spring_force_batch", "spring_parameters", "with_stiffness"]
