r"""The joint springs of a model in the closed forms.

A spring of stiffness :math:`k` on coordinate :math:`q_i`, relaxed at :math:`q_{i,0}`
(:mod:`wheeled_dyn.models.springs`), adds

.. math::

    Q_i \mathrel{+}= k\,(q_i - q_{i,0}),\qquad U \mathrel{+}= \tfrac12\,k\,(q_i - q_{i,0})^2

to the closed forms of :mod:`.model` and :mod:`.tree` (both are linear in the springs, so
they are added after the rigid-body terms are derived, and the cached rigid-body forms stay
valid). With numbers (``"numbers"`` mode) :math:`k` and :math:`q_{i,0}` are the model's exact
values; otherwise they are the symbols ``k_<name>`` and ``rest_<name>`` of the model's
parameters.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace
from typing import TYPE_CHECKING, TypeVar

import sympy as sp

from ..models.wheeled_model import WheeledModel
from .kinematics import exact_number

if TYPE_CHECKING:
    from .model import SymbolicModel
    from .tree import TreeDynamics

SpringTerm = tuple[int, sp.Expr, sp.Expr]       # (velocity index, stiffness, rest position)
#: The closed forms springs are added to (both frozen dataclasses with ``q``, ``Q`` and
#: ``parameters``).
T = TypeVar("T", "SymbolicModel", "TreeDynamics")


def spring_terms(wm: WheeledModel, mode: str) -> tuple[SpringTerm, ...]:
    r"""``(index, k, rest)`` of each spring of ``wm``: exact numbers for ``mode ==
    "numbers"``, else the parameter symbols ``k_<name>``, ``rest_<name>``."""
    out = []
    for s in wm.springs:
        if mode == "numbers":
            k, rest = exact_number(s.stiffness), exact_number(s.rest)
        else:
            k, rest = (sp.Symbol(n, real=True) for n in s.spec.parameter_names)
        out.append((s.v_index, k, rest))
    return tuple(out)


def spring_potential(q: Sequence[sp.Symbol], springs: Sequence[SpringTerm]) -> sp.Expr:
    r""":math:`\sum \tfrac12 k (q_i - q_{i,0})^2`."""
    return sp.Add(*(k * (q[i] - rest) ** 2 / 2 for i, k, rest in springs))


def _with_spring_forces(Q: sp.Matrix, q: Sequence[sp.Symbol], springs: Sequence[SpringTerm]
                        ) -> sp.Matrix:
    Q = sp.Matrix(Q)
    for i, k, rest in springs:
        Q[i] = Q[i] + k * q[i] - k * rest
    return Q


def _new_parameters(old: Sequence[sp.Symbol], springs: Sequence[SpringTerm]
                    ) -> tuple[sp.Symbol, ...]:
    seen = dict.fromkeys(old)
    for _, k, rest in springs:
        for s in sorted((k + rest).free_symbols, key=sp.default_sort_key):
            seen.setdefault(s, None)
    return tuple(seen)


def with_springs(closed: T, springs: Sequence[SpringTerm]) -> T:
    r"""A :class:`~.model.SymbolicModel` or :class:`~.tree.TreeDynamics` with the springs'
    terms added to ``Q`` (and, for the former, to the potential energy)."""
    if not springs:
        return closed
    changes: dict = {"Q": _with_spring_forces(closed.Q, closed.q, springs),
                     "parameters": _new_parameters(closed.parameters, springs)}
    if hasattr(closed, "potential_energy"):
        changes["potential_energy"] = closed.potential_energy + spring_potential(closed.q,
                                                                                 springs)
    return replace(closed, **changes)


__all__ = ["SpringTerm", "spring_potential", "spring_terms", "with_springs"]
