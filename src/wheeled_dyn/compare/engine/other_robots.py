r"""Other robots of a derivation's model, for the factors that may vanish for one of them
(:mod:`.parameter_factors`, :mod:`.constraint_factors`): each parameter set's robot with its
links' masses and inertias changed and its lengths kept, as physical as it is.

Per link (the drive wheels of a model together: the model declares them alike), at each of
:data:`DRAWS` robots:

- a mass :math:`\delta m = b\,m` added at its centre (:math:`b \in [0, 2]`: its inertia about
  the centre kept, its first moments and its inertias about its frame's origin grown by the
  parallel-axis terms);
- three thin rods along its axes added to its inertia about the centre, each of a moment up to
  twice its mean principal moment (a rod along x adds to the moments about y and z: each
  rod is a mass distribution, and so is the sum);
- all of it times a density factor :math:`a \in [10^{-2}, 10^{2}]`;

each joint spring's stiffness times such a factor and its rest position moved by up to
:data:`REST_SHIFT`. The first robot is the parameter set's own. The truth's
:math:`A = \sum_L J_L^T M_L J_L` stays positive definite at every such robot and at every
robot between two of them (the masses and inertias of valid bodies form a convex set;
:math:`J_L` depends on the lengths alone), and has no springs in it.

A link that the file declares uniform, massless or in its URDF's proportions keeps its shape
(its density alone changes): the robots are those its declaration allows. A model with a
parameter record (the WIP) changes its record's masses and inertias by its own groups
(:attr:`~wheeled_dyn.models.wip_parameters.WipParameters.DENSITY_OF`), density only.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import fields

import numpy as np
import sympy as sp
from sympy.core.function import AppliedUndef

from ...compiled import numpy_function
from ...derivations.namespace import GEOMETRY_NAMES, KHALIL_NAMES, PHYSICAL_NAMES
from ...derivations.schema import Derivation
from ..grid.samples import ParameterSet
from ..grid.values import model_value

#: A link's parameters that scale with its density: its mass, first moments and inertias
#: (Khalil's about its origin, and those about its centre).
DENSITY = frozenset({*KHALIL_NAMES, *PHYSICAL_NAMES[3:]})
#: A link's parameters its density leaves: its centre and the model's lengths.
LENGTHS = frozenset({*PHYSICAL_NAMES[:3], *GEOMETRY_NAMES})
#: Names of a model's namespace a density leaves: the gravity and the wheels' geometry.
KEPT_NAMES = frozenset({"g", "R", "L"})
#: Robots tried per parameter set, the range of each link's density factor (and each
#: spring's stiffness factor), and of the shift of a spring's rest position (rad or m).
DRAWS, DENSITY_RANGE, REST_SHIFT = 64, (1e-2, 1e2), 1.0
#: Largest mass added at a link's centre, and largest moment of each rod, relative to the
#: link's mass and mean principal moment.
SHAPE_RANGE = 2.0


def _record(d: Derivation) -> tuple[Mapping[str, str], Mapping[str, str], set[str]]:
    r"""The model's parameter record's masses and inertias by what scales them, its links'
    groups and the names it keeps (its lengths, the gravity); empty for a model without one."""
    from ...models.registry import model_entry
    record = model_entry(d.model).parameters
    density_of: Mapping[str, str] = getattr(record, "DENSITY_OF", {})
    if record is None or not density_of:
        return {}, {}, set()
    kept = {f.name for f in fields(record)} - set(density_of)
    return density_of, getattr(record, "LINK_GROUPS", {}), kept


def scalable(d: Derivation, params: tuple[sp.Symbol, ...]) -> set[sp.Symbol]:
    r"""The document's parameters whose values are link parameters, lengths, kept names or
    a parameter record's own masses and inertias. A model without a parameter record keeps
    every other name of its namespace (its gravity, its geometry's lengths, its springs):
    none of them changes with a link's mass."""
    density_of, _, kept = _record(d)
    from ...models.registry import model_entry
    named = None if model_entry(d.model).parameters is None else \
        KEPT_NAMES | set(density_of) | kept
    out = set()
    for spec in d.symbols.values():
        value = spec.value
        if spec.is_input or value is None or spec.symbol not in params:
            continue
        calls = value.atoms(AppliedUndef)
        plain = value.free_symbols - {a for c in calls for a in c.free_symbols}
        if all(c.func.__name__ in DENSITY | LENGTHS for c in calls) and \
                (named is None or all(s.name in named for s in plain)):
            out.add(spec.symbol)
    return out


def _fixed_shapes(d: Derivation, ps: ParameterSet) -> set[str]:
    r"""The links the file declares uniform, massless or in their URDF's proportions."""
    from ..grid.assumptions import declared
    from ..grid.samples import uniform_links
    cases = declared(d).families
    return uniform_links(ps.model, cases) | {link for c in cases for link in c.massless}


def _shaped(values: Mapping[str, float], link: str, b: np.ndarray,
            rods: np.ndarray) -> dict[str, np.ndarray]:
    r"""One link's mass parameters with a mass :math:`b\,m` added at its centre and rods of
    moments ``rods`` (DRAWS × 3, along x, y, z) added to its inertia about it."""
    def v(name: str) -> float:
        return float(values[f"{name}({link})"])
    m, c = v("M"), np.array([v("CX"), v("CY"), v("CZ")])
    mass = m * (1.0 + b)
    out = {"M": mass, **{f"M{a}": mass * c[i] for i, a in enumerate("XYZ")}}
    for i, a in enumerate("XYZ"):
        others = [k for k in range(3) if k != i]
        moment = v(f"I{a}{a}") + rods[:, others].sum(axis=1)
        out[f"I{a}{a}"] = moment
        out[f"{a}{a}"] = moment + mass * float(c[others[0]] ** 2 + c[others[1]] ** 2)
    for i, j in ((0, 1), (0, 2), (1, 2)):          # products: about the centre unchanged
        a, e = "XYZ"[i], "XYZ"[j]
        shift = (v(f"{a}{e}") - v(f"I{a}{e}")) / m if m else 0.0     # ±m cᵢcⱼ, per mass
        out[f"I{a}{e}"] = np.full(len(b), v(f"I{a}{e}"))
        out[f"{a}{e}"] = v(f"I{a}{e}") + mass * shift
    return {f"{k}({link})": np.broadcast_to(x, (len(b),)) for k, x in out.items()}


def scaled_values(d: Derivation, ps: ParameterSet, symbols: list[sp.Symbol],
                  rng: np.random.Generator) -> dict[sp.Symbol, np.ndarray]:
    r"""Each of ``symbols`` at :data:`DRAWS` robots of the model (module text)."""
    density_of, link_groups, _ = _record(d)
    names_of = [s.spec.parameter_names for s in ps.model.springs]
    springs = {k: f"spring {k}" for k, _ in names_of}
    rests = [rest for _, rest in names_of]
    wheels = {w: "drive wheels" for w in getattr(ps.model.spec, "wheels", ()) or ()}
    groups_of = {**wheels, **link_groups}

    def group(key: str) -> str | None:
        if "(" not in key:
            return density_of.get(key, springs.get(key))
        link = key[key.index("(") + 1:-1]
        return groups_of.get(link, link) if key[:key.index("(")] in DENSITY else None

    values = ps.values
    groups = {k: group(k) for k in values}
    names = sorted({g for g in groups.values() if g is not None})
    low, high = np.log(DENSITY_RANGE[0]), np.log(DENSITY_RANGE[1])
    factors = np.exp(rng.uniform(low, high, (DRAWS, len(names))))
    shifts = rng.uniform(-REST_SHIFT, REST_SHIFT, (DRAWS, len(rests)))
    factors[0], shifts[0] = 1.0, 0.0
    now: dict[str, np.ndarray | float] = dict(values)
    if not density_of:                            # a model without a parameter record
        fixed = _fixed_shapes(d, ps)
        links = sorted({k[k.index("(") + 1:-1] for k in values if k.startswith("M(")})
        shape = {g: (rng.uniform(0, SHAPE_RANGE, DRAWS), rng.uniform(0, SHAPE_RANGE, (DRAWS, 3)))
                 for g in sorted({groups_of.get(x, x) for x in links})}
        for link in links:
            g = groups_of.get(link, link)
            if link in fixed or g in {groups_of.get(x, x) for x in fixed} or \
                    not values[f"M({link})"] > 0:
                continue
            b, rods = shape[g][0].copy(), shape[g][1].copy()
            b[0], rods[0] = 0.0, 0.0
            mean = (values[f"IXX({link})"] + values[f"IYY({link})"] + values[f"IZZ({link})"]) / 3
            now.update(_shaped(values, link, b, rods * mean))
    column = dict(zip(names, factors.T))
    now = {k: v if groups[k] is None else v * column[str(groups[k])] for k, v in now.items()}
    now.update({k: values[k] + x for k, x in zip(rests, shifts.T) if k in values})
    specs = {s.symbol: s for s in d.symbols.values()}
    out = {}
    for s in symbols:
        value = specs[s].value
        assert value is not None
        out[s] = _at(value, now)
    return out


def _at(value: sp.Expr, namespace: Mapping[str, np.ndarray | float]) -> np.ndarray:
    r"""A model-namespace expression (``XX(link)`` calls, physical names) at arrays of the
    namespace's values (:data:`DRAWS` each), compiled once (the names checked first by
    :func:`~..sides.document.model_value` at the first draw)."""
    first = {k: float(np.atleast_1d(v)[0]) for k, v in namespace.items()}
    model_value(value, first)
    calls = sorted(value.atoms(AppliedUndef), key=sp.default_sort_key)
    places = [sp.Dummy() for _ in calls]
    plain = sorted(value.free_symbols - {a for c in calls for a in c.free_symbols},
                   key=sp.default_sort_key)
    fn = numpy_function([*places, *plain], value.xreplace(dict(zip(calls, places))))
    argv = [namespace[f"{c.func.__name__}({c.args[0]})"] for c in calls] + \
        [namespace[s.name] for s in plain]
    with np.errstate(all="ignore"):
        return np.broadcast_to(np.asarray(fn(*argv), float), (DRAWS,)).copy()


__all__ = ["DENSITY", "DENSITY_RANGE", "DRAWS", "KEPT_NAMES", "LENGTHS", "REST_SHIFT",
           "SHAPE_RANGE", "scalable", "scaled_values"]
