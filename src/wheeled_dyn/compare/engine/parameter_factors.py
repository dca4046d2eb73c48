r"""An equation multiplied by a factor of the parameters that vanishes for a robot the model
may be, though not for the parameter sets drawn: :math:`(M - m)^2` times a true equation of
a cart-pole is lost where the cart weighs what the pole does, a robot as real as any other.

The equivalence decision (:func:`~..judge.equivalence.decide`) sees :math:`W = A_{doc}A^{-1}`
at the samples only, and a square never changes sign. Here the common factor of a row of the
document's own :math:`A` is read symbolically — the greatest common divisor of its
elements' numerators, factored — and each factor that depends on the parameters alone and is
not a single symbol is tried at other robots of the model (:mod:`.other_robots`: its
links' masses and inertias changed, its lengths kept, its springs changed). The truth's A
stays positive definite at every one of them and between two, so where a factor takes both
signs among them it vanishes between two with the truth regular: there the row of
:math:`A_{doc}` is zero and :math:`W` singular — the equation is not equivalent. The common
factor of the row's denominators is tried alike (a row divided by it: :math:`W` unbounded
there), and each factor also at robots of other lengths (:mod:`.length_robots`).

Only symbols :func:`~.other_robots.scalable` says follow the model are tried; a factor in
any other symbol (a free symbol) is not.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass
from enum import Enum

import numpy as np
import sympy as sp

from ...compiled import numpy_function
from ..judge import equivalence
from ..sides.both import Sides
from ..sides.document import DocumentFunctions
from .length_robots import vanishes_for_other_lengths
from .other_robots import DRAWS, scalable, scaled_values

class Robots(Enum):
    r"""The robots of the model a factor vanishes for: of other masses and inertias
    (:mod:`.other_robots`), of other lengths (:mod:`.length_robots`), or between two of the
    parameter sets drawn (a single symbol, a centre-of-mass coordinate, that takes both signs
    among them)."""

    MASSES = "masses"
    LENGTHS = "lengths"
    DRAWN = "drawn"


@dataclass(frozen=True)
class Vanishing:
    r"""A factor of a row that vanishes for a robot of the model: the row is ``divided`` by it
    (else multiplied), and which ``robots``."""

    factor: sp.Expr
    divided: bool
    robots: Robots


def row_factors(row: list[sp.Expr], allowed: set[sp.Symbol],
                bare: frozenset[sp.Symbol] = frozenset(), divided: bool = False
                ) -> list[tuple[sp.Expr, int]]:
    r"""The factors of the common divisor of ``row``'s numerators (with ``divided``: of its
    denominators, what the row is divided by) that depend on ``allowed`` symbols alone and
    are sums or a symbol of ``bare`` (a position, or with :func:`vanishing_factors`'
    ``drawn`` a parameter whose sign the drawn sets may change; a mass never vanishes):
    (base, power), the base the one that changes sign ((cos θ − 1/3)² has the base
    3 cos θ − 1)."""
    # an exponential never vanishes, and SymPy's polynomials take exp(2·10⁴q) as the power
    # 20000 of exp(q) (factoring it ran for minutes): each one a generator of its own
    exps = {x: sp.Dummy() for e in row for x in e.atoms(sp.exp)}
    row = [e.xreplace(exps) for e in row]
    try:
        numerators = [sp.fraction(sp.together(e))[int(divided)] for e in row if e != 0]
        if not numerators:
            return []
        common = functools.reduce(sp.gcd, numerators)
        _, found = sp.factor_list(common)
    except (sp.PolynomialError, sp.CoercionFailed, NotImplementedError):
        return []
    return [(-b if b.could_extract_minus_sign() else b, int(e)) for b, e in found
            if b.free_symbols and b.free_symbols <= allowed and not b.is_number
            and (not b.is_Symbol or b in bare)]


def changes_sign(fn, args: list[sp.Symbol], values: dict[sp.Symbol, np.ndarray]) -> bool:
    r"""Whether ``fn`` of ``args`` takes both signs (or zero) among one parameter set's
    robots: its lengths are the same for all of them, so the truth stays regular between."""
    with np.errstate(all="ignore"):
        found = np.broadcast_to(np.asarray(fn(*(values[s] for s in args)), float), (DRAWS,))
    found = found[np.isfinite(found)]
    return bool(found.size) and found.min() <= 0.0 <= found.max()


def vanishing_factors(funcs: DocumentFunctions, sides: Sides, rows: list[int],
                      seed: int, drawn: bool = False) -> dict[int, Vanishing]:
    r"""For each of ``rows``, a factor of the parameters common to its elements of the
    document's :math:`A`, or to their denominators, that vanishes for a robot of the model
    (module text; of other lengths: :mod:`.length_robots`), where one does. With ``drawn``
    (where :math:`\det W` changes sign between the drawn sets: the decision is made, this
    names the equation), a single symbol is a factor too where its value takes both signs
    among the drawn sets (a row times a centre-of-mass coordinate)."""
    A = funcs.exprs["A"]
    if A is None or not rows:
        return {}
    d = funcs.d
    allowed = scalable(d, funcs.params)
    single = frozenset(allowed) if drawn else frozenset()
    candidates = {i: [(f, e, divided) for divided in (False, True)
                      for f, e in row_factors(list(sp.Matrix(A).row(i)), allowed, single,
                                              divided=divided)] for i in rows}
    if not any(candidates.values()):
        return {}
    rng = np.random.default_rng([seed, 29])
    needed = sorted({s for fs in candidates.values() for f, _, _ in fs
                     for s in f.free_symbols}, key=sp.default_sort_key)
    draws = [scaled_values(d, ps, needed, rng) for ps in sides.grid.sets]
    out: dict[int, Vanishing] = {}
    for i, found in candidates.items():
        for f, e, divided in found:
            args = sorted(f.free_symbols, key=sp.default_sort_key)
            fn = numpy_function(args, f)
            if f.is_Symbol:
                if not _changes_sign_between_sets(f, sides):
                    continue
                out[i] = Vanishing(f ** e, divided, Robots.DRAWN)
            elif any(changes_sign(fn, args, v) for v in draws):
                out[i] = Vanishing(f ** e, divided, Robots.MASSES)
            elif vanishes_for_other_lengths(d, f, seed):
                out[i] = Vanishing(f ** e, divided, Robots.LENGTHS)
            else:
                continue
            break
    return out


def _changes_sign_between_sets(s: sp.Symbol, sides: Sides) -> bool:
    values = np.array([float(ps[s]) for ps in sides.per_set if s in ps])
    return bool(values.size) and values.min() < 0.0 < values.max()


#: States of each parameter set at which :func:`robot_sign_changes` tries the robots.
STATES = 8


def robot_sign_changes(funcs: DocumentFunctions, sides: Sides, seed: int
                       ) -> tuple[tuple[int, ...], bool] | None:
    r"""Where :math:`\det A_{doc}` takes both signs among the other robots of the model at one
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


__all__ = ["STATES", "Robots", "Vanishing", "changes_sign", "robot_sign_changes", "row_factors",
           "vanishing_factors"]
