r"""The grid a comparison is decided on: K parameter sets of the document's model and N states
each, and the truth there in the document's coordinates.

A :class:`Grid` holds the truth's arrays (:class:`~.arrays.Arrays`, samples
:math:`S = K N` in set order), the parameter sets, the states :math:`q, \nu` (K × N × n), the
document's coordinate set and its coordinate map. :class:`Grids` makes them and remembers them
per (model, coordinates, special families, size, assumptions), so derivations sharing
coordinates share the truth. States are drawn where the document's assumptions put them
(:func:`.assumptions.position_ranges`) and away from the coordinates' singular positions
(:func:`.samples.regular_states`). A grid under undeclared families has the states of the
grid of the same size under the declared families alone (only its parameter sets differ): an
element that agrees under a family and differs without it differs there for the parameters,
never for where the states fell (a term that differs only near one state is seen at both or
neither).

:func:`special_states` adds the states at which an equation multiplied by a function of the
positions would read :math:`0 = 0`: each position in turn at :math:`0, \pm\pi/2, \pi` (inside
its range), the others as drawn.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import sympy as sp

from ...constraints.reduction import CoordinateMap
from ...coordinates import CoordinateSet, CoordinateSpecError
from ...coordinates import builtin_coordinate_set, parse_coordinate_set
from ...derivations.schema import Derivation
from ...derivations.source import key_line
from ...errors import DerivationError, UnknownNameError
from ...models.registry import model_version
from .arrays import Arrays
from .assumptions import Assumptions, apply_to_truth, position_ranges
from .samples import ParameterSet, SpecialCase, parameter_sets, random_states, regular_states

#: The key marking a derivation whose equations were reordered (the coordinates' identity
#: leaves it out: equations read in another order have the same truth).
ROWS_KEY = "_row_order"
#: Positions tried by :func:`special_states`, and how many of each set's states are used.
SPECIAL_VALUES = (0.0, np.pi / 2, -np.pi / 2, np.pi)
SPECIAL_STATES_PER_SET = 6


@dataclass(frozen=True)
class Grid:
    r"""The truth on K parameter sets × N states (see the module text)."""

    truth: Arrays
    sets: tuple[ParameterSet, ...]
    q: np.ndarray
    nu: np.ndarray
    cs: CoordinateSet
    cmap: CoordinateMap
    ranges: tuple[tuple[float, float], ...]
    #: states first drawn where the map put a tilting wheel off the ground, drawn again
    off_ground: int = 0

    @property
    def flat_q(self) -> np.ndarray:
        return self.q.reshape(-1, self.q.shape[2])

    @property
    def flat_nu(self) -> np.ndarray:
        return self.nu.reshape(-1, self.nu.shape[2])


#: Computes the truth on a grid: ``(coordinate map, parameter sets, q, nu) -> Arrays``
#: (:func:`~..sides.truth.truth_for`, given by the engine: the truth is a side's business).
TruthFunction = Callable[[CoordinateMap, Sequence[ParameterSet], np.ndarray, np.ndarray], Arrays]


def derivation_coordinate_set(d: Derivation, ps: ParameterSet) -> CoordinateSet:
    r"""The document's coordinate set, built-in or inline; document symbols in inline
    expressions are replaced by their model values' names (R, L ...)."""
    wm = ps.model
    spec = d.coordinates
    if spec.use:
        cs = builtin_coordinate_set(wm, spec.use)
        if tuple(cs.velocities) != tuple(str(v) for v in d.velocities):
            raise DerivationError(d.path, "coordinates", f"built-in set {spec.use!r} has "
                                  f"velocities {cs.velocities}, the file {d.velocities}")
        return cs
    to_model = {s.symbol: _identifiers(s.value) for s in d.symbols.values()
                if s.value is not None}
    raw = {"kind": spec.kind, "rolling": spec.rolling, "positions": list(spec.positions),
           "velocities": list(spec.velocities),
           "configuration": {k: str(sp.sympify(v).xreplace(to_model))
                             for k, v in spec.configuration.items()}}
    if spec.velocity_map:
        raw["velocity_map"] = {k: str(sp.sympify(v).xreplace(to_model))
                               for k, v in spec.velocity_map.items()}
    try:
        return parse_coordinate_set(raw, "inline", wm.coordinate_names,
                                    tuple(wm.named_lengths()), where=str(d.path))
    except UnknownNameError as exc:          # the file, its line and key; not the path glued
        if exc.kind == "model coordinate":   # to "configuration" with no line
            raise DerivationError(d.path, f"coordinates.configuration.{exc.name}",
                                  f"unknown model coordinate {exc.name!r}; valid: "
                                  + ", ".join(exc.valid or ()),
                                  key_line(d.path, "coordinates", "configuration")) from None
        raise _not_a_length(d, raw, to_model, exc) from None
    except CoordinateSpecError as exc:       # the file, its line and the map's key
        table = exc.item.split(".")[0]
        raise DerivationError(d.path, f"coordinates.{exc.item}", exc.reason,
                              key_line(d.path, "coordinates", table)) from None


def _not_a_length(d: Derivation, raw: dict, to_model: dict, exc: UnknownNameError
                  ) -> Exception:
    r"""A name of an inline map the model does not have, where it is a document symbol's
    value (``l`` for ``CZ(pole)``: a centre of mass, not one of the model's lengths): an
    error naming the symbol and the map's key; else ``exc``."""
    written = [s for s, v in to_model.items() if exc.name in {str(x) for x in v.free_symbols}]
    if not written:
        return exc
    spec = d.coordinates
    for table in ("configuration", "velocity_map"):
        for key, text in raw.get(table, {}).items():
            if exc.name in {str(x) for x in sp.sympify(text).free_symbols}:
                own = getattr(spec, table).get(key)        # the entry as the file writes it
                used = [s for s in written if own is not None
                        and str(s) in {str(x) for x in sp.sympify(own).free_symbols}]
                symbol = (used or written)[0]
                return DerivationError(
                    d.path, f"coordinates.{table}.{key}", f"the symbol {symbol} is "
                    f"{d.symbols[str(symbol)].value}, which a coordinate map cannot use: "
                    "it may use the positions and the model's lengths (" +
                    ", ".join(exc.valid or ()) + "), or symbols whose values they are",
                    key_line(d.path, "coordinates", table))
    return exc


def _identifiers(expr: sp.Expr) -> sp.Expr:
    r"""A model expression with its lengths as identifiers (``radius(coin)`` → ``radius_coin``,
    as coordinate expressions write them)."""
    from sympy.core.function import AppliedUndef

    from ...models.geometry import call_name, identifier
    calls = {c: sp.Symbol(identifier(call_name(c)), real=True) for c in expr.atoms(AppliedUndef)}
    return expr.xreplace(calls) if calls else expr


class Grids:
    r"""Grids made once per key (module text); ``seed`` seeds every draw, ``truth`` computes
    the truth on each."""

    def __init__(self, seed: int, truth: TruthFunction) -> None:
        self.seed = seed
        self.truth = truth
        self._grids: dict[tuple, Grid] = {}
        self._maps: dict[tuple, CoordinateMap] = {}
        self._sets: dict[tuple, CoordinateSet] = {}

    def get(self, d: Derivation, special: tuple[SpecialCase, ...], n_states: int, k: int,
            assumed: Assumptions = Assumptions(), on_truth: Callable[[], None] | None = None
            ) -> Grid:
        r"""The grid of ``d`` under the ``special`` families and its ``assumed``
        assumptions, made once; ``on_truth`` is called before its truth is computed."""
        special = tuple(dict.fromkeys((*assumed.families, *special)))
        raw = repr({name: value for name, value in d.coordinates.raw.items()
                    if name != ROWS_KEY})
        # the model as its files are now: a model file or URDF saved since is another truth
        key = (d.model, model_version(d.model), raw, d.coordinates.use,
               tuple(c.name for c in special), n_states, k, assumed.key())
        if key not in self._grids:
            self._grids[key] = self._make(d, special, n_states, k, assumed, raw, on_truth)
        return self._grids[key]

    def _make(self, d: Derivation, special: tuple[SpecialCase, ...], n_states: int, k: int,
              assumed: Assumptions, raw: str, on_truth: Callable[[], None] | None) -> Grid:
        rng = np.random.default_rng([self.seed, len(special), n_states])
        sets = parameter_sets(d.model, k, rng, special)
        version = model_version(d.model)
        ckey = (d.model, version, raw, d.coordinates.use)
        if ckey not in self._sets:
            self._sets[ckey] = derivation_coordinate_set(d, sets[0])
        cs = self._sets[ckey]
        mkey = (d.model, version, repr(cs))
        if mkey not in self._maps:
            try:
                self._maps[mkey] = CoordinateMap(sets[0].model, cs)
            except CoordinateSpecError as exc:   # a set of the file: its path and line
                if d.coordinates.use:
                    raise
                raise DerivationError(d.path, f"coordinates.{exc.item}", exc.reason, key_line(
                    d.path, "coordinates", exc.item.split(".")[0])) from None
        cmap = self._maps[mkey]
        n = len(cs.positions)
        ranges = position_ranges(d, cs.positions, assumed,
                                 sprung=any(ps.model.springs for ps in sets))
        if len(special) > len(assumed.families):        # the declared families' states
            control = self.get(d, (), n_states, k, assumed)
            q, nu, off = control.q, control.nu, control.off_ground
        else:
            q, nu = random_states(n, k * n_states, rng, ranges)
            off = int(cmap.off_ground(q).sum())
            q = regular_states(cmap, q, rng, ranges)
            check_finite_map(d, cmap, q)
            q, nu = q.reshape(k, n_states, n), nu.reshape(k, n_states, n)
        if on_truth is not None:
            on_truth()
        truth = self.truth(cmap, sets, q, nu)
        springs = self._springs_only(cmap, sets, q, nu) if assumed.equilibrium_potential \
            else None
        apply_to_truth(truth, assumed, springs)
        return Grid(truth, tuple(sets), q, nu, cs, cmap, tuple((lo, hi) for lo, hi in ranges),
                    off)

    def _springs_only(self, cmap: CoordinateMap, sets: Sequence[ParameterSet], q: np.ndarray,
                      nu: np.ndarray) -> np.ndarray | None:
        r"""The truth's Q with gravity off in every set (the model's springs' force alone),
        where the model has springs; None where it has none."""
        if not any(ps.model.springs for ps in sets):
            return None
        saved = [ps.model.model.gravity.copy() for ps in sets]
        try:
            for ps in sets:
                ps.model.model.gravity.setZero()
            return self.truth(cmap, sets, q, nu).Q
        finally:
            for ps, g in zip(sets, saved):
                ps.model.model.gravity = g


def check_finite_map(d: Derivation, cmap: CoordinateMap, q: np.ndarray) -> None:
    r"""Raise :class:`DerivationError` if the document's coordinate map (its configuration
    map, and for a holonomic set its Jacobian) is not finite at one of the states ``q`` left
    after :func:`.samples.regular_states` redrew those where it was not: ``sqrt(theta)``,
    ``asin(theta)``, ``log(theta)`` outside their domain on much of the drawn range."""
    N = len(q)
    params = cmap._p
    with np.errstate(all="ignore"):
        bad = ~np.isfinite(np.asarray(cmap._config_batch(N, *q.T, *params),
                                      dtype=float)[:, :, 0])
        if cmap.cs.kind == "holonomic":
            S = np.asarray(cmap._S_batch(N, *q.T, *params), dtype=float)
            bad |= ~np.all(np.isfinite(S), axis=2)
    rows, cols = np.nonzero(bad)
    if not rows.size:
        _check_on_ground(d, cmap, q)
        return
    name = cmap.wm.coordinate_names[cols[0]]
    state = ", ".join(f"{p} = {v:.4g}" for p, v in zip(cmap.cs.positions, q[rows[0]]))
    item = "coordinates.use" if d.coordinates.use else f"coordinates.configuration.{name}"
    raise DerivationError(d.path, item, f"the map to model coordinate {name!r} or its "
                          f"derivative is not finite at {state} (a square root, logarithm or "
                          "inverse sine outside its domain?); say where the comparison draws "
                          "the positions: [coordinates] ranges = { position = [low, high] }")


def _check_on_ground(d: Derivation, cmap: CoordinateMap, q: np.ndarray) -> None:
    r"""Raise :class:`DerivationError` if the map puts a tilting wheel off the ground or flat
    at one of the states ``q`` that :func:`.samples.regular_states` could not draw again
    (:meth:`~wheeled_dyn.constraints.CoordinateMap.off_ground`)."""
    off = np.flatnonzero(cmap.off_ground(q))
    if not off.size:
        return
    state = ", ".join(f"{p} = {v:.4g}" for p, v in zip(cmap.cs.positions, q[off[0]]))
    wheels = ", ".join(wc.link for wc in cmap.wm.rolling_wheels)
    item = "coordinates.use" if d.coordinates.use else "coordinates.configuration"
    if off.size == len(q):
        raise DerivationError(d.path, item, f"the map puts the wheel ({wheels}) off the "
                              f"ground or lying flat at every drawn state ({state}, ...): "
                              "the height it gives the wheel's centre is not its rim's lowest "
                              "point above the ground (R*|cos(lean)| for a disk of radius R)")
    raise DerivationError(d.path, item, f"the map puts the wheel ({wheels}) off the ground "
                          f"or lying flat at {state} and at {off.size - 1} more of the drawn "
                          "states (a centre height of R*cos(lean) sinks a disk leaning beyond "
                          "a right angle); say where the comparison draws the positions: "
                          "[coordinates] ranges = { position = [low, high] }")


def special_states(grid: Grid) -> tuple[np.ndarray, np.ndarray]:
    r"""``(q, set index)`` of the special states (module text): for each parameter set, its
    first :data:`SPECIAL_STATES_PER_SET` states with one position at a time moved to each of
    :data:`SPECIAL_VALUES` inside its range."""
    K, N, n = grid.q.shape
    m = min(N, SPECIAL_STATES_PER_SET)
    qs, owner = [], []
    for a, (low, high) in enumerate(grid.ranges):
        for value in SPECIAL_VALUES:
            if low == high or not low <= value <= high:
                continue
            for k in range(K):
                q = grid.q[k, :m].copy()
                q[:, a] = value
                qs.append(q)
                owner.append(np.full(m, k))
    if not qs:
        return np.empty((0, n)), np.empty(0, dtype=int)
    return np.concatenate(qs), np.concatenate(owner)


__all__ = ["Grid", "Grids", "ROWS_KEY", "check_finite_map", "SPECIAL_STATES_PER_SET", "SPECIAL_VALUES",
           "TruthFunction", "derivation_coordinate_set", "special_states"]
