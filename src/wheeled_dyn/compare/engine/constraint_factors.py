r"""A constraint row the document states times a factor that vanishes: the rolling
constraint is lost where it does (the document lets the wheel slide there), though its rows
span the model's wherever the samples fall.

:func:`~..judge.document_checks.constraint_space` compares the document's rows
:math:`G_{doc}` with the model's at the samples, and sees a factor only where
:math:`\det P` (:math:`G_{doc} = PG`) changes sign within a parameter set — not a factor
that touches zero without changing sign (:math:`(\sin\varphi - 0.3)^2`, :math:`\cos^2\varphi`),
nor one of the parameters (:math:`m_c - 2m_w`), nor any where the model's rows are more
than its independent ones (a robot's two wheels: four rows of rank three). Here each stated
row's common factor is read symbolically (:func:`~.parameter_factors.row_factors`: the
greatest common divisor of its entries' numerators) and each factor in the positions and
parameters alone is tried:

- in the positions: the row is lost only where the stated rows then state fewer than the
  model's (:math:`\cos\theta\,g` beside :math:`\sin\theta\,g` loses nothing), at the
  factor's zeros (:func:`~.constraint_states.factor_zeros`; its base is tried, so a square's
  zeros show); a row divided by it is undefined where it takes both signs or is zero;
- in the parameters alone: at the other robots of the model (:mod:`.other_robots`,
  :mod:`.length_robots`), as an equation's factor is.

Rows with no such factor may still be
the model's mixed with weights that are singular somewhere (:math:`\cos\theta\,g_1 +
\sin\theta\,g_2` in place of :math:`g_2` is :math:`g_1` at :math:`\theta = 0`): their rank is
compared with the model's at the special states and where they are least independent
(:func:`~.constraint_states.weakest`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import sympy as sp

from ...compiled import numpy_function
from ..grid.grid import special_states
from ..sides.both import Sides
from ..sides.document import DocumentFunctions
from .constraint_states import StatedRows, factor_zeros, weakest
from .length_robots import vanishes_for_other_lengths
from .other_robots import scalable, scaled_values
from .parameter_factors import changes_sign, row_factors

#: A factor at most this fraction of its median magnitude over the samples is zero there.
ZERO = 1e-12


def _values_at(funcs: DocumentFunctions, sides: Sides, factor: sp.Expr
               ) -> list[np.ndarray]:
    r"""``factor`` per parameter set, at its samples and special states."""
    grid = sides.grid
    fn = funcs.compiled(factor)
    K, N, n = grid.q.shape
    with np.errstate(all="ignore"):
        at = np.broadcast_to(np.asarray(fn(*sides.argv), float), (K * N,)).reshape(K, N)
    q, owner = special_states(grid)
    out = [at[k] for k in range(K)]
    if len(q):
        values = [np.array([sides.per_set[k][p] for k in owner]) for p in funcs.params]
        with np.errstate(all="ignore"):
            special = np.broadcast_to(np.asarray(fn(*q.T, *np.zeros_like(q).T, *values),
                                                 float), (len(q),))
        out = [np.concatenate([out[k], special[owner == k]]) for k in range(K)]
    return out


def _vanishes_in_state(values: list[np.ndarray]) -> bool:
    r"""Whether a factor takes both signs within a parameter set, or is zero somewhere."""
    for v in values:
        v = v[np.isfinite(v)]
        if not v.size:
            continue
        typical = float(np.median(np.abs(v)))
        if (v.min() < 0 < v.max()) or np.abs(v).min() <= ZERO * typical:
            return True
    return False


def _vanishes(funcs: DocumentFunctions, sides: Sides, factor: sp.Expr,
              rng: np.random.Generator, seed: int) -> bool:
    r"""Whether a factor of the parameters alone vanishes for another robot of the model (of
    other masses and inertias, or other lengths)."""
    args = sorted(factor.free_symbols, key=sp.default_sort_key)
    fn = numpy_function(args, factor)
    return any(changes_sign(fn, args, scaled_values(funcs.d, ps, args, rng))
               for ps in sides.grid.sets) or vanishes_for_other_lengths(funcs.d, factor, seed)


@dataclass(frozen=True)
class Lost:
    r"""A constraint the document's rows lose: ``where`` the file states them (``G``,
    ``[constraints]``), the ``row`` (0-based) whose factor vanishes (None: the rows
    together), what is wrong (``text``) and the row's own line in the report (``row_text``)."""

    where: str
    row: int | None
    text: str
    row_text: str = ""

    def __str__(self) -> str:
        return f"{self.where}: {self.text}"


def lost_constraints(funcs: DocumentFunctions, sides: Sides, seed: int) -> tuple[Lost, ...]:
    r"""For the constraint rows the document states (its ``G``, its ``[constraints]``), what
    is wrong, named by where the file states them: a row times (or over) a factor of the
    parameters that vanishes for another robot of the model; a row times a factor of the
    positions that vanishes where the rows then state fewer constraints than the model's
    (:mod:`.constraint_states`); the rows together stating fewer at a special state or where
    they are least independent."""
    d = funcs.d
    stated = [("G", sp.Matrix(d.G))] if d.G is not None else []
    M = d.constraint_matrix()
    if M is not None:
        stated.append(("[constraints]", sp.Matrix(M)))
    positions = frozenset(d.positions)
    allowed = scalable(d, funcs.params) | set(positions)
    rng = np.random.default_rng([seed, 37])
    out: list[Lost] = []
    for where, G in stated:
        rows = StatedRows(funcs, sides, G)
        lost = next(filter(None, (_lost_row(funcs, sides, rows, where, r, f, e, divided,
                                            rng, seed)
                                  for r in range(G.rows) for divided in (False, True)
                                  for f, e in row_factors(list(G.row(r)), allowed, positions,
                                                          divided))), None)
        if lost is None:
            q, owner = special_states(sides.grid)
            bad = rows.fewer(q, owner)
            found = (q[bad:bad + 1], owner[bad:bad + 1]) if bad is not None else weakest(rows)
            if found is not None:
                lost = Lost(where, None, "its constraint rows state fewer independent "
                            f"constraints than the model's at {_state(d, found[0][0])}: a "
                            "constraint is lost there (rows mixed with weights that are "
                            "singular there, or stating it with factors that vanish "
                            "together)")
        if lost is not None:
            out.append(lost)
    return tuple(out)


def _state(d, q: np.ndarray) -> str:
    return ", ".join(f"{p} = {v:.4g}" for p, v in zip(d.positions, q))


def _lost_row(funcs: DocumentFunctions, sides: Sides, rows: StatedRows, where: str, r: int,
              f: sp.Expr, e: int, divided: bool, rng: np.random.Generator, seed: int
              ) -> Lost | None:
    r"""Row ``r`` written times (``divided``: over) ``f`` to the power ``e``: lost where
    ``f`` vanishes — for a factor of the positions, only where the rows then state fewer
    constraints than the model's (another row may state it there: cos θ·g and sin θ·g)."""
    how = f"{'divided by' if divided else 'times'} {sp.sstr(f ** e)}"
    state = "undefined" if divided else "lost"
    if f.free_symbols & set(funcs.d.positions):
        if divided:
            found = _vanishes_in_state(_values_at(funcs, sides, f))
            at = ""
        else:
            q, owner = factor_zeros(funcs, sides, f)
            bad = rows.fewer(q, owner)
            found, at = bad is not None, "" if bad is None else f" (at {_state(funcs.d, q[bad])})"
    else:
        found, at = _vanishes(funcs, sides, f, rng, seed), ""
    if not found:
        return None
    return Lost(where, r, f"its constraint row {r + 1} is written {how}, which vanishes for "
                f"some state or robot of the model{at}: the constraint is {state} there",
                f"a rolling constraint of the model {how}, which vanishes for some state or "
                f"robot: {state} there")


__all__ = ["ZERO", "Lost", "lost_constraints"]
