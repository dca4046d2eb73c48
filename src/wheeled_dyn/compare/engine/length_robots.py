r"""Robots of a derivation's model with other lengths, for a row's factor that vanishes for
one of them (:mod:`.parameter_factors`, :mod:`.constraint_factors`).

The parameter sets a comparison draws change each length by a factor in :math:`[1/1.6, 1.6]`
(:mod:`~wheeled_dyn.models.geometry_apply`), and the other robots of :mod:`.other_robots`
keep the lengths: a row times :math:`h - 2R` (a centre of mass twice the wheel's radius above
the axle) or :math:`L - R` (a wheel as large as half the track), or a square of one, keeps
its sign among them, though it vanishes for a robot as real as any. Here :data:`SETS` robots
of the model are drawn as the comparison draws its parameter sets (the file's families kept)
with each length's factor in :math:`[1/\text{SPREAD}, \text{SPREAD}]`, and the factor is read
at each: where it takes both signs (or is zero), it vanishes between two of them.

There the truth stays regular: its :math:`A` is positive definite for every robot with
positive lengths, masses and valid inertias, and the document's coordinates are taken to be
regular for every such robot (a rolling map :math:`v = R\dot\varphi` for :math:`R > 0`).
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from ...compiled import numpy_function
from ...derivations.schema import Derivation
from ..grid.samples import ParameterSet
from ..grid.values import model_value

#: Robots drawn, and the largest factor of each of their lengths (the smallest: its inverse).
SETS, SPREAD = 16, 10.0

_ROBOTS: dict[tuple, list[ParameterSet]] = {}


def _robots(d: Derivation, seed: int) -> list[ParameterSet]:
    r"""The :data:`SETS` robots of ``d``'s model with its declared families, made once per
    model, version, families and seed."""
    from ...models.registry import model_version
    from ..grid.assumptions import declared
    from ..grid.samples import parameter_sets
    families = declared(d).families
    key = (d.model, model_version(d.model), tuple(c.name for c in families), seed)
    if key not in _ROBOTS:
        rng = np.random.default_rng([seed, 41])
        _ROBOTS[key] = parameter_sets(d.model, SETS, rng, tuple(families), SPREAD)
    return _ROBOTS[key]


def vanishes_for_other_lengths(d: Derivation, factor: sp.Expr, seed: int) -> bool:
    r"""Whether ``factor`` (of ``d``'s symbols that have model values) takes both signs, or
    zero, among the robots of other lengths (module text)."""
    values_of = {s.symbol: s.value for s in d.symbols.values()}
    args = sorted(factor.free_symbols, key=sp.default_sort_key)
    exprs = [values_of.get(s) for s in args]
    if not args or any(e is None for e in exprs):
        return False
    fn = numpy_function(args, factor)
    found = []
    for ps in _robots(d, seed):
        point = [model_value(e, ps.values) for e in exprs if e is not None]
        with np.errstate(all="ignore"):
            found.append(float(np.asarray(fn(*point), float)))
    values = np.array(found)
    values = values[np.isfinite(values)]
    return bool(values.size) and values.min() <= 0.0 <= values.max()


__all__ = ["SETS", "SPREAD", "vanishes_for_other_lengths"]
