r"""An equation multiplied by a factor of the parameters that vanishes for a robot the model
may be, though not for the parameter sets drawn: :math:`(M - m)^2` times a true equation of
a cart-pole is lost where the cart weighs what the pole does, a robot as real as any other.

The equivalence decision (:func:`~..judge.equivalence.decide`) sees :math:`W = A_{doc}A^{-1}`
at the samples only, and a square never changes sign. Here the common factor of a row of the
document's own :math:`A` is read symbolically — the greatest common divisor of its
elements' numerators, factored — and each factor that depends on the parameters alone and is
not a single symbol is tried at robots the model may be without being another: each link's
density scaled by its own factor :math:`a_L \in [10^{-2}, 10^{2}]` (its mass, first moments
and inertias times :math:`a_L`; its lengths, the gravity and the wheels' geometry kept), each
joint spring's stiffness scaled so and its rest position moved (the truth's A has neither). The
truth's :math:`A = \sum_L a_L J_L^T M_L J_L` stays positive definite for every positive
:math:`a`, so where a factor takes both signs among the draws it vanishes between two of them
(the segment between two draws stays positive) with the truth regular: there the row of
:math:`A_{doc}` is zero and :math:`W` singular — the equation is not equivalent.

Only symbols whose value is such a link parameter, a length of a link, another name of a
model without a parameter record (its gravity, lengths and springs), or a name of a
parameter record that says what scales it (the WIP's ``DENSITY_OF``, its lengths kept) are
scaled or kept; a factor in any other symbol (a free symbol) is not tried.
"""

from __future__ import annotations

import functools
from collections.abc import Mapping
from dataclasses import fields

import numpy as np
import sympy as sp
from sympy.core.function import AppliedUndef

from ...compiled import numpy_function
from ...derivations.schema import Derivation
from ..judge import equivalence
from ..grid.samples import ParameterSet
from ..sides.both import Sides
from ..sides.document import DocumentFunctions, model_value

#: A link's parameters that scale with its density.
DENSITY = frozenset({"M", "MX", "MY", "MZ", "XX", "XY", "XZ", "YY", "YZ", "ZZ",
                     "IXX", "IXY", "IXZ", "IYY", "IYZ", "IZZ"})
#: A link's parameters its density leaves (its lengths).
LENGTHS = frozenset({"CX", "CY", "CZ", "length", "radius", "width", "origin_x", "origin_y",
                     "origin_z"})
#: Names of a model's namespace a density leaves: the gravity and the wheels' geometry.
KEPT_NAMES = frozenset({"g", "R", "L"})
#: Robots tried per parameter set, the range of each link's density factor (and each
#: spring's stiffness factor), and of the shift of a spring's rest position (rad or m).
DRAWS, DENSITY_RANGE, REST_SHIFT = 64, (1e-2, 1e2), 1.0


def _record(d: Derivation) -> tuple[Mapping[str, str], Mapping[str, str], set[str]]:
    r"""The model's parameter record's masses and inertias by what scales them, its links'
    groups (:attr:`~wheeled_dyn.models.wip_parameters.WipParameters.DENSITY_OF`) and the
    names it keeps (its lengths, the gravity); empty for a model without one."""
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
    none of them changes with a link's density."""
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


def row_factors(row: list[sp.Expr], allowed: set[sp.Symbol],
                bare: frozenset[sp.Symbol] = frozenset()) -> list[sp.Expr]:
    r"""The factors of the common divisor of ``row``'s numerators that depend on ``allowed``
    symbols alone and are sums or a symbol of ``bare`` (a position; a single symbol of a
    mass never vanishes)."""
    try:
        numerators = [sp.fraction(sp.together(e))[0] for e in row if e != 0]
        if not numerators:
            return []
        common = functools.reduce(sp.gcd, numerators)
        _, found = sp.factor_list(common)
    except (sp.PolynomialError, sp.CoercionFailed, NotImplementedError):
        return []
    return [-b if b.could_extract_minus_sign() else b for b, _ in found
            if b.free_symbols and b.free_symbols <= allowed and not b.is_number
            and (not b.is_Symbol or b in bare)]


def scaled_values(d: Derivation, ps: ParameterSet, symbols: list[sp.Symbol],
                   rng: np.random.Generator) -> dict[sp.Symbol, np.ndarray]:
    r"""Each of ``symbols`` at :data:`DRAWS` robots: the namespace values of ``ps`` with each
    link's density scaled, each joint spring's stiffness scaled and its rest position moved
    (none of which the truth's A depends on; the first draw: as drawn)."""
    density_of, link_groups, _ = _record(d)
    names_of = [s.spec.parameter_names for s in ps.model.springs]
    springs = {k: f"spring {k}" for k, _ in names_of}
    rests = [rest for _, rest in names_of]

    def group(key: str) -> str | None:
        if "(" not in key:
            return density_of.get(key, springs.get(key))
        link = key[key.index("(") + 1:-1]
        return link_groups.get(link, link) if key[:key.index("(")] in DENSITY else None

    values = ps.values
    groups = {k: group(k) for k in values}
    names = sorted({g for g in groups.values() if g is not None})
    low, high = np.log(DENSITY_RANGE[0]), np.log(DENSITY_RANGE[1])
    factors = np.exp(rng.uniform(low, high, (DRAWS, len(names))))
    shifts = rng.uniform(-REST_SHIFT, REST_SHIFT, (DRAWS, len(rests)))
    factors[0], shifts[0] = 1.0, 0.0
    column = dict(zip(names, factors.T))
    now = {k: v if groups[k] is None else v * column[str(groups[k])]
           for k, v in values.items()}
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


def changes_sign(fn, args: list[sp.Symbol], values: dict[sp.Symbol, np.ndarray]) -> bool:
    r"""Whether ``fn`` of ``args`` takes both signs (or zero) among one parameter set's
    robots: its lengths are the same for all of them, so the truth stays regular between."""
    with np.errstate(all="ignore"):
        found = np.broadcast_to(np.asarray(fn(*(values[s] for s in args)), float), (DRAWS,))
    found = found[np.isfinite(found)]
    return bool(found.size) and found.min() <= 0.0 <= found.max()


def vanishing_factors(funcs: DocumentFunctions, sides: Sides, rows: list[int],
                      seed: int) -> dict[int, sp.Expr]:
    r"""For each of ``rows``, a factor of the parameters common to its elements of the
    document's :math:`A` that vanishes for a robot of the model (module text), where one
    does."""
    A = funcs.exprs["A"]
    if A is None or not rows:
        return {}
    d = funcs.d
    allowed = scalable(d, funcs.params)
    candidates = {i: row_factors(list(sp.Matrix(A).row(i)), allowed) for i in rows}
    if not any(candidates.values()):
        return {}
    rng = np.random.default_rng([seed, 29])
    needed = sorted({s for fs in candidates.values() for f in fs for s in f.free_symbols},
                    key=sp.default_sort_key)
    draws = [scaled_values(d, ps, needed, rng) for ps in sides.grid.sets]
    out: dict[int, sp.Expr] = {}
    for i, found in candidates.items():
        for f in found:
            args = sorted(f.free_symbols, key=sp.default_sort_key)
            fn = numpy_function(args, f)
            if any(changes_sign(fn, args, v) for v in draws):
                out[i] = f
                break
    return out


#: States of each parameter set at which :func:`robot_sign_changes` tries the robots.
STATES = 8


def robot_sign_changes(funcs: DocumentFunctions, sides: Sides, seed: int
                       ) -> tuple[tuple[int, ...], bool] | None:
    r"""Where :math:`\det A_{doc}` takes both signs among the robots of other densities at one
    state (module text: :math:`\det A` does not, so :math:`\det W` vanishes or has a pole
    between them — an equation times, or divided by, a factor of the masses that vanishes,
    alone or in a combination of the equations): the equations involved and whether it is a
    pole (:func:`~..judge.equivalence.sign_changes`, on :math:`A_{doc}`, whose left null
    vector is :math:`W`'s), else None. Not tried where the document's A has a symbol that
    cannot be scaled (module text)."""
    A = funcs.exprs["A"]
    if A is None:
        return None
    d = funcs.d
    used = sp.Matrix(A).free_symbols & set(funcs.params)
    free = {s.symbol for s in d.symbols.values() if s.value is None and not s.is_input}
    scaled = sorted(used & scalable(d, funcs.params), key=sp.default_sort_key)
    if not scaled or not used <= set(scaled) | free:
        return None
    rng = np.random.default_rng([seed, 31])
    n = len(d.positions)
    for k, ps in enumerate(sides.grid.sets):
        q = np.repeat(sides.grid.q[k, :STATES], DRAWS, axis=0)
        draws = scaled_values(d, ps, scaled, rng)
        values = {s: np.tile(draws[s], STATES) if s in draws else
                  np.full(len(q), sides.per_set[k][s]) for s in funcs.params}
        doc_A = funcs.evaluate(q, np.zeros((len(q), n)), values, ("A",)).need("A")
        found = equivalence.sign_changes(doc_A, len(q) // DRAWS)
        if found is not None:
            return found
    return None


__all__ = ["DENSITY", "DRAWS", "KEPT_NAMES", "LENGTHS", "STATES", "changes_sign",
           "robot_sign_changes", "row_factors", "scalable", "scaled_values",
           "vanishing_factors"]
