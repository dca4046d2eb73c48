r"""Sign conventions: the reading of a document's coordinates and inputs that fits it best.

A document rewritten "in the symbols of" another, or with an axis the other way round, differs
from the truth in many elements that share one reason: a coordinate or an input taken with the
opposite sign. With positions :math:`p = S p'` (:math:`S = \mathrm{diag}(s)`, :math:`s_i = \pm1`)
and inputs :math:`u = T u'`, the document's equations read in :math:`p'` are

.. math::

    A' = S\,A(Sp)\,S,\quad h'_i = s_i\,h_i(Sp, S\nu),\quad Q' = S\,Q(Sp),\quad
    B' = S\,B(Sp)\,T

(row :math:`i` times :math:`s_i` is the equation of :math:`p'_i`; whole-row factors are found
afterwards as for any document). Every :math:`(s, t)` is scored on the truth already computed
(the document's compiled functions evaluated at flipped states: no new truth), and the one with
the most agreeing elements wins; the declared reading is kept on a tie. The winner is applied
to the *file's maps* (:func:`flipped`) — the position :math:`p_i` read as :math:`s_i p_i` in
``configuration``, the velocity map of :math:`\nu_i` times :math:`s_i`, each input :math:`u_k`
read as :math:`t_k u_k` in ``[inputs]`` — which is the same comparison, so the records shown
are the ordinary ones under the better reading, and the convention is one cause.
"""

from __future__ import annotations

import itertools
from collections.abc import Callable, Sequence
from dataclasses import replace

import numpy as np
import sympy as sp

from ...derivations.schema import Derivation
from ..grid.arrays import Arrays
from .relative_angles import Sum, describe_sums, rates_of_positions, sum_velocity_map

#: Most signs searched (positions + inputs): 2**8 readings, each one evaluation of the document.
MAX_SIGNS = 8
#: Inputs permuted when there are at most this many (3! = 6 orders).
MAX_PERMUTED = 3
#: Equations reordered when there are at most this many (4! = 24 orders).
MAX_ROWS = 4
#: The key marking a derivation whose equations were reordered.
ROWS_KEY = "_row_order"
#: A reading replaces the declared one only if this many more elements agree under it ...
MIN_GAIN = 3
#: ... or this many, for a reading that only reorders the inputs (a swap of two symmetric
#: motors shows in the two elements of the turning row alone).
MIN_GAIN_ORDER = 2
#: A reading that moves a position (its sign, an angle from the opposite direction or from
#: another link) must make this many more elements agree, or equations right.
MIN_GAIN_OFFSET = 2
#: The key marking a derivation whose maps a convention has flipped (no search in it again).
FLIPPED_KEY = "_convention"


#: A reading :math:`(s, t, \pi, o, \sigma)`: the positions' signs, the inputs' signs, the
#: inputs' order, the positions (indices) measured from the opposite direction (:math:`+\pi`),
#: and the positions read as sums (:mod:`.relative_angles`: an angle measured from another
#: link).
Reading = tuple[tuple[int, ...], tuple[int, ...], tuple[int, ...], tuple[int, ...],
                tuple[Sum, ...]]


def _input_readings(d: Derivation) -> list[tuple[tuple[int, ...], tuple[int, ...]]]:
    r"""Every :math:`(t, \pi)` of ``d``'s inputs, the declared one first; inputs exchanged
    only where their declared units agree (a torque in N·m is no force in N: a document that
    writes the force where the torque fits is wrong, not in another convention)."""
    from ..judge.units import units_dim
    m = len(d.input_symbols) if d.inputs else 0
    dims = [units_dim(spec.units) if spec is not None else None
            for spec in (d.symbols.get(str(u)) for u in d.input_symbols[:m])]
    orders = [tuple(o) for o in itertools.permutations(range(m))
              if all(dims[k] == dims[j] for k, j in enumerate(o))] \
        if m <= MAX_PERMUTED else [tuple(range(m))]
    return [(tuple(t), order) for t in itertools.product((1, -1), repeat=m)
            for order in orders]


def readings(d: Derivation) -> list[Reading]:
    r"""Every reading :math:`(s, t, \pi)` of ``d``'s positions and inputs but the declared one
    (with a built-in coordinate set, of its inputs only; none when ``d`` was flipped already
    or has more than :data:`MAX_SIGNS` signs)."""
    n, m = d.n, len(d.input_symbols) if d.inputs else 0
    flips = 0 if d.coordinates.use else n        # a built-in set's positions are the model's
    if FLIPPED_KEY in d.coordinates.raw or flips + m > MAX_SIGNS or flips + m == 0:
        return []
    out: list[Reading] = []
    for s in itertools.product((1, -1), repeat=flips):
        for t, order in _input_readings(d):
            if any(x < 0 for x in (*s, *t)) or order != tuple(range(m)):
                out.append((tuple(s) if flips else (1,) * n, t, order, (), ()))
    return out


def offset_readings(d: Derivation, angles: Sequence[int]) -> list[Reading]:
    r"""The readings with one of the ``angles`` (position indices: those the document takes
    sines or cosines of) measured from the opposite direction, :math:`p_k \to p_k + \pi` or
    :math:`\pi - p_k` (a pendulum's angle from the upright where the file's map measures it
    from the hanging position), each with every reading of the inputs; none where
    :func:`readings` has none."""
    if not readings(d) or d.coordinates.use:
        return []
    n, inputs = d.n, _input_readings(d)
    out: list[Reading] = []
    for k in angles:
        for sign in (1, -1):
            s = tuple(sign if j == k else 1 for j in range(n))
            out += [(s, t, order, (k,), ()) for t, order in inputs]
    return out


def sum_readings(d: Derivation, angles: Sequence[int]) -> list[Reading]:
    r"""The readings with a position measured from one of the ``angles``, :math:`p_k \to
    p_k \pm p_j` (:mod:`.relative_angles`: absolute where the file's map takes it relative to
    the link before, or the reverse; a wheel's angle from the ground where the map takes it
    from the body), every other position in its units from that angle at once (both wheels'
    angles), and for three or more angles, all of them at once along the chain in their
    order (:math:`p_k \to p_k - p_{k-1}`, :math:`p_k \to \sum_{j\le k} p_j`), each with every
    reading of the inputs; only where the file's velocities are its positions' rates (a
    holonomic set, or a quasi one whose map says so:
    :func:`~.relative_angles.rates_of_positions`) and the positions are declared in the same
    units."""
    spec = d.coordinates
    if not readings(d) or spec.use or (spec.velocity_map and not rates_of_positions(
            d.positions, d.velocities, dict(spec.configuration), dict(spec.velocity_map))):
        return []
    n, units = d.n, [spec.units.get(str(p)) for p in d.positions]
    sums: list[tuple[Sum, ...]] = [((k, j, c),) for j in angles for k in range(n)
                                   if k != j and units[k] == units[j] for c in (1, -1)]
    for j in angles:                  # every other position from one angle: both wheels
        others = [k for k in range(n) if k != j and k not in angles and units[k] == units[j]]
        if len(others) > 1:
            sums += [tuple((k, j, c) for k in others) for c in (1, -1)]
    chain = sorted(angles)
    if len(chain) > 2 and len({units[k] for k in chain}) == 1:   # a serial chain, every angle
        sums += [tuple((k, j, 1) for i, k in enumerate(chain) for j in chain[:i]),
                 tuple((k, chain[i - 1], -1) for i, k in enumerate(chain) if i)]
    inputs = _input_readings(d)
    return [((1,) * n, t, order, (), x) for x in sums for t, order in inputs]


def _offset_gains(value: int, declared: int, weight: int | None) -> bool:
    r"""Whether a reading of score ``value`` makes :data:`MIN_GAIN_OFFSET` more elements
    agree, or equations right, than the declared one (scores of ``weight`` per equation)."""
    if weight is None:
        return value - declared >= MIN_GAIN_OFFSET
    return (value % weight - declared % weight >= MIN_GAIN_OFFSET
            or value // weight - declared // weight >= MIN_GAIN_OFFSET)


def _all_right(value: int, n: int, weight: int | None) -> bool:
    r"""Whether a score of ``value`` counts all ``n`` equations right (``weight`` each)."""
    return weight is not None and value // weight >= n


def flip_arrays(doc: Arrays, s: Sequence[int], t: Sequence[int],
                order: Sequence[int] = ()) -> Arrays:
    r"""The document's arrays (evaluated at flipped states :math:`Sp, S\nu`) read in
    :math:`p'`, its input columns in the ``order`` :math:`\pi`: the module's formulas."""
    s_, t_ = np.asarray(s, float), np.asarray(t, float)
    out = Arrays(H_rows=doc.H_rows)
    if doc.A is not None:
        out.A = doc.A * s_[None, :, None] * s_[None, None, :]
    if doc.C is not None:
        out.C = doc.C * s_[None, :, None] * s_[None, None, :]
    if doc.Q is not None:
        out.Q = doc.Q * s_[None, :]
    if doc.B is not None:
        B = doc.B[:, :, list(order)] if len(order) else doc.B
        out.B = B * s_[None, :, None] * (t_[None, None, :] if len(t_) else 1.0)
    if doc.h is not None:
        out.h = doc.h * s_[None, :]
    if doc.H is not None:
        out.H = doc.H * s_[None, :, None, None] * s_[None, None, :, None] * s_[None, None, None, :]
    if doc.G is not None:
        out.G = doc.G * s_[None, None, :]
    return out


def best_reading(d: Derivation,
                 evaluate: Callable[[Sequence[int], Sequence[int], Sequence[Sum]], Arrays],
                 score: Callable[[Arrays], int],
                 score_readings: Callable[[Arrays, Sequence[int], list], list[int]] | None = None,
                 total: int | None = None, complete_gain: int = MIN_GAIN_ORDER,
                 angles: Sequence[int] = (), offsets: Callable[[int], bool] | None = None,
                 weight: int | None = None) -> tuple[Reading, int, int] | None:
    r"""``((s, t, order), declared score, best score)`` when a reading beats the declared one
    by at least :data:`MIN_GAIN` agreeing elements — or by :data:`MIN_GAIN_ORDER` where every
    one of the ``total`` elements agrees under it (one input's sign in a robot's two rows:
    two elements, and nothing else left to explain; ``complete_gain`` for a file that declares
    its convention unknown, where one input's sign shows in one element) — else None.
    ``evaluate(s, o, σ)`` gives the document's arrays at the flipped states (the positions
    ``o`` shifted by π, those of ``σ`` read as sums), ``score(arrays)`` the number of
    agreeing elements;
    ``score_readings(arrays, s, [(t, order), ...])``, where given, the scores of several
    readings of the inputs at once (the same numbers). The ``angles`` are read from the
    opposite direction, or from another of them, too (:func:`offset_readings`,
    :func:`sum_readings`) where ``offsets(best score so far)`` says so (a reading that leaves
    most equations wrong: one that makes them right is no π away). A reading that moves a
    position (its sign, π, or a sum) is taken only where it makes
    at least :data:`MIN_GAIN_OFFSET` more elements agree or more equations right (a score is
    ``weight`` per equation right and one per element): one term's sign is a term's error,
    not a pendulum's angle measured from the upright — unless the file asks for its
    convention and every equation is right under it."""
    options = readings(d)
    if not options:
        return None
    declared = score(evaluate((1,) * d.n, (), ()))
    if score_readings is None:
        def score_readings(base, s, rest):
            return [score(flip_arrays(base, s, t, order)) for t, order in rest]
    best: tuple[Reading | None, int] = (None, declared)
    asked = complete_gain < MIN_GAIN_ORDER          # the file asks for its convention

    def search(options: list[Reading]) -> None:
        nonlocal best
        for (s, o, sums), group in itertools.groupby(options,
                                                     key=lambda r: (r[0], r[3], r[4])):
            members = list(group)                      # each (s, o, σ)'s consecutive
            values = score_readings(evaluate(s, o, sums), s, [(r[1], r[2]) for r in members])
            for reading, value in zip(members, values):
                moves = moves_position(reading)
                if value > best[1] and (not moves or _offset_gains(
                        value, declared, weight) or (asked and _all_right(value, d.n,
                                                                          weight))):
                    best = (reading, value)
    search(options)
    if angles and (offsets is None or offsets(best[1])):
        search(offset_readings(d, angles) + sum_readings(d, angles))
    complete = total is not None and best[1] == total
    if best[0] is None or best[1] < declared + (
            complete_gain if complete else
            MIN_GAIN_ORDER if is_permutation_only(best[0]) else MIN_GAIN):
        return None
    return best[0], declared, best[1]


def flipped(d: Derivation, s: Sequence[int], t: Sequence[int],
            order: Sequence[int] = (), offsets: Sequence[int] = (),
            sums: Sequence[Sum] = ()) -> Derivation:
    r"""``d`` with its maps read under :math:`(s, t, \pi, o, \sigma)` (see the module
    docstring): position :math:`p_k` read as :math:`s_kp_k`, or :math:`s_kp_k + \pi` for
    :math:`k` in ``offsets``, or :math:`p_k + c\,p_j` for :math:`(k, j, c)` in ``sums``."""
    spec = d.coordinates
    pos = {p: sign * p + (sp.pi if k in offsets else 0)
           for k, (p, sign) in enumerate(zip(d.positions, s)) if sign < 0 or k in offsets}
    for k, j, c in sums:
        pos[d.positions[k]] = pos.get(d.positions[k], d.positions[k]) + c * d.positions[j]
    configuration = {k: sp.sympify(v).xreplace(pos) for k, v in spec.configuration.items()}
    sign = dict(zip(spec.velocities, s))
    velocity_map = {v: (-sp.sympify(e) if sign.get(v, 1) < 0 else e)
                    for v, e in spec.velocity_map.items()}
    if sums and velocity_map:            # the velocities are the positions' rates: ν' = L⁻¹ν
        velocity_map = sum_velocity_map(d.velocities, velocity_map, d.n, sums)
    raw = dict(spec.raw)
    raw[FLIPPED_KEY] = describe(d, s, t, order, offsets, sums)
    new_spec = replace(spec, configuration=configuration, velocity_map=velocity_map, raw=raw)
    inputs = d.inputs
    u = list(d.input_symbols)
    order = tuple(order) or tuple(range(len(u)))
    if d.inputs and (any(x < 0 for x in t) or order != tuple(range(len(u)))):
        read = {u[k]: t[k] * u[order[k]] for k in range(len(u))}
        inputs = {k: sp.sympify(v).xreplace(read) for k, v in d.inputs.items()}
    return replace(d, coordinates=new_spec, inputs=inputs)


def describe(d: Derivation, s: Sequence[int], t: Sequence[int],
             order: Sequence[int] = (), offsets: Sequence[int] = (),
             sums: Sequence[Sum] = ()) -> str:
    r"""``"theta → −theta, u1 → −u1, u1 ↔ u2"``: the flipped names and the exchanged inputs,
    in the document's symbols; ``"theta → theta + π"`` (``"π − theta"``) for a position of
    the ``offsets``; ``"q2 → q2 − q1"`` for one of the ``sums``."""
    parts = [f"{p} → π − {p}" if x < 0 else f"{p} → {p} + π"
             for k, (p, x) in enumerate(zip(d.positions, s)) if k in offsets]
    names = [str(p) for k, (p, x) in enumerate(zip(d.positions, s))
             if x < 0 and k not in offsets]
    names += [str(u) for u, x in zip(d.input_symbols, t) if x < 0]
    parts += [f"{x} → −{x}" for x in names] + describe_sums(d.positions, sums)
    u = list(d.input_symbols)
    done: set[int] = set()
    for k, j in enumerate(order):
        if j != k and k not in done:
            if order[j] == k:
                parts.append(f"{u[k]} ↔ {u[j]}")
                done.update((k, j))
            else:
                parts.append(f"{u[k]} read as {u[j]}")
    return ", ".join(parts)


def is_permutation_only(reading: Reading) -> bool:
    r"""A reading that only reorders the inputs (no sign flipped, no position shifted)."""
    s, t, order, offsets, sums = reading
    return all(x > 0 for x in (*s, *t)) and not offsets and not sums and \
        tuple(order) != tuple(range(len(order)))


def moves_position(reading: Reading) -> bool:
    r"""A reading that moves a position: its sign, π, or a sum of positions."""
    return bool(reading[3] or reading[4] or any(x < 0 for x in reading[0]))


def row_orders(d: Derivation) -> list[tuple[int, ...]]:
    r"""The orders tried for the rows of a file of equations (none for matrices, for more
    than :data:`MAX_ROWS` rows, or once reordered)."""
    if d.equations is None or d.n > MAX_ROWS or ROWS_KEY in d.coordinates.raw:
        return []
    identity = tuple(range(d.n))
    return [o for o in itertools.permutations(range(d.n)) if o != identity]


def permute_rows(doc: Arrays, order: Sequence[int]) -> Arrays:
    r"""The document's arrays with row :math:`i` taken from its row ``order[i]``."""
    out = Arrays(H_rows=doc.H_rows, G=doc.G)
    for key in ("A", "C", "Q", "B", "h", "H"):
        M = getattr(doc, key)
        if M is not None:
            setattr(out, key, M[:, list(order)])
    return out


def best_row_order(d: Derivation, evaluate: Callable[[Sequence[int]], Arrays],
                   score: Callable[[Arrays], int]) -> tuple[tuple[int, ...], int, int] | None:
    r"""``(order, declared score, best score)`` when equations taken in another order agree
    in at least :data:`MIN_GAIN` more elements, else None."""
    options = row_orders(d)
    if not options:
        return None
    identity = (1,) * d.n
    declared = score(evaluate(identity))
    base = evaluate(identity)
    best: tuple[tuple[int, ...] | None, int] = (None, declared)
    for order in options:
        value = score(permute_rows(base, order))
        if value > best[1]:
            best = (order, value)
    if best[0] is None or best[1] < declared + MIN_GAIN:
        return None
    return best[0], declared, best[1]


def reordered(d: Derivation, order: Sequence[int]) -> Derivation:
    r"""``d`` with its equation :math:`i` taken from the file's equation ``order[i]``."""
    if d.equations is None:
        raise ValueError(f"{d.path.name}: only equations written out are reordered, not matrices")
    raw = dict(d.coordinates.raw)
    raw[ROWS_KEY] = describe_rows(d, order)
    scale = None if d.row_scale is None else tuple(d.row_scale[k] for k in order)
    return replace(d, equations=tuple(d.equations[k] for k in order), row_scale=scale,
                   coordinates=replace(d.coordinates, raw=raw))


def describe_rows(d: Derivation, order: Sequence[int]) -> str:
    r"""``"equation 1 is the one of phi, equation 3 the one of x"`` (1-based, as printed)."""
    parts = [f"equation {k + 1} is the one of {d.positions[i]}"
             for i, k in enumerate(order) if k != i]
    return ", ".join(parts)


def maps_text(d: Derivation) -> str:
    r"""The file's maps as declared, briefly (``phi = -theta; tau_l = -K_f*u1``)."""
    parts = [f"{k} = {sp.sstr(v)}" for k, v in d.coordinates.configuration.items()]
    parts += [f"{k} = {sp.sstr(v)}" for k, v in (d.inputs or {}).items()]
    return "; ".join(parts)


__all__ = ["MAX_PERMUTED", "MAX_SIGNS", "MIN_GAIN", "MIN_GAIN_ORDER", "Reading", "best_reading",
           "describe", "offset_readings",
           "best_row_order", "describe_rows", "flip_arrays", "flipped", "is_permutation_only",
           "maps_text", "moves_position", "permute_rows", "readings", "reordered", "row_orders",
           "sum_readings"]
