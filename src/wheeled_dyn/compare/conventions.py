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

from ..derivations.schema import Derivation
from .evaluate import Arrays

#: Most signs searched (positions + inputs): 2**8 readings, each one evaluation of the document.
MAX_SIGNS = 8
#: A reading replaces the declared one only if this many more elements agree under it.
MIN_GAIN = 3
#: The key marking a derivation whose maps a convention has flipped (no search in it again).
FLIPPED_KEY = "_convention"


def readings(d: Derivation) -> list[tuple[tuple[int, ...], tuple[int, ...]]]:
    r"""Every sign reading :math:`(s, t)` of ``d``'s positions and inputs but the declared one
    (none when ``d`` uses a built-in coordinate set, was flipped already, or has more than
    :data:`MAX_SIGNS` signs)."""
    n, m = d.n, len(d.input_symbols) if d.inputs else 0
    if d.coordinates.use or FLIPPED_KEY in d.coordinates.raw or n + m > MAX_SIGNS:
        return []
    out = []
    for signs in itertools.product((1, -1), repeat=n + m):
        if any(x < 0 for x in signs):
            out.append((tuple(signs[:n]), tuple(signs[n:])))
    return out


def flip_arrays(doc: Arrays, s: Sequence[int], t: Sequence[int]) -> Arrays:
    r"""The document's arrays (evaluated at flipped states :math:`Sp, S\nu`) read in
    :math:`p'`: the formulas of the module docstring."""
    s_, t_ = np.asarray(s, float), np.asarray(t, float)
    out = Arrays(H_rows=doc.H_rows)
    if doc.A is not None:
        out.A = doc.A * s_[None, :, None] * s_[None, None, :]
    if doc.C is not None:
        out.C = doc.C * s_[None, :, None] * s_[None, None, :]
    if doc.Q is not None:
        out.Q = doc.Q * s_[None, :]
    if doc.B is not None:
        out.B = doc.B * s_[None, :, None] * (t_[None, None, :] if len(t_) else 1.0)
    if doc.h is not None:
        out.h = doc.h * s_[None, :]
    if doc.H is not None:
        out.H = doc.H * s_[None, :, None, None] * s_[None, None, :, None] * s_[None, None, None, :]
    if doc.G is not None:
        out.G = doc.G * s_[None, None, :]
    return out


def best_reading(d: Derivation, evaluate: Callable[[Sequence[int]], Arrays],
                 score: Callable[[Arrays], int]) -> tuple[tuple, tuple, int, int] | None:
    r"""``(s, t, declared score, best score)`` when a reading beats the declared one by at
    least :data:`MIN_GAIN` agreeing elements, else None. ``evaluate(s)`` gives the document's
    arrays at the flipped states, ``score(arrays)`` the number of agreeing elements."""
    options = readings(d)
    if not options:
        return None
    n = d.n
    declared = score(evaluate((1,) * n))
    cache: dict[tuple[int, ...], Arrays] = {}
    best = (None, None, declared)
    for s, t in options:
        if s not in cache:
            cache[s] = evaluate(s)
        value = score(flip_arrays(cache[s], s, t))
        if value > best[2]:
            best = (s, t, value)
    if best[0] is None or best[2] < declared + MIN_GAIN:
        return None
    return best[0], best[1], declared, best[2]


def flipped(d: Derivation, s: Sequence[int], t: Sequence[int]) -> Derivation:
    r"""``d`` with its maps read under :math:`(s, t)` (see the module docstring)."""
    spec = d.coordinates
    pos = {p: sign * p for p, sign in zip(d.positions, s) if sign < 0}
    configuration = {k: sp.sympify(v).xreplace(pos) for k, v in spec.configuration.items()}
    velocity_map = {v: (-sp.sympify(e) if s[i] < 0 else e)
                    for i, v in enumerate(spec.velocities)
                    for e in [spec.velocity_map[v]] if v in spec.velocity_map}
    raw = dict(spec.raw)
    raw[FLIPPED_KEY] = describe(d, s, t)
    new_spec = replace(spec, configuration=configuration, velocity_map=velocity_map, raw=raw)
    inputs = d.inputs
    if d.inputs and any(x < 0 for x in t):
        flip = {u: -u for u, sign in zip(d.input_symbols, t) if sign < 0}
        inputs = {k: sp.sympify(v).xreplace(flip) for k, v in d.inputs.items()}
    return replace(d, coordinates=new_spec, inputs=inputs)


def describe(d: Derivation, s: Sequence[int], t: Sequence[int]) -> str:
    r"""``"theta → −theta, u1 → −u1"``: the flipped names, in the document's symbols."""
    names = [str(p) for p, x in zip(d.positions, s) if x < 0]
    names += [str(u) for u, x in zip(d.input_symbols, t) if x < 0]
    return ", ".join(f"{x} → −{x}" for x in names)


def maps_text(d: Derivation) -> str:
    r"""The file's maps as declared, briefly (``phi = -theta; tau_l = -K_f*u1``)."""
    parts = [f"{k} = {sp.sstr(v)}" for k, v in d.coordinates.configuration.items()]
    parts += [f"{k} = {sp.sstr(v)}" for k, v in (d.inputs or {}).items()]
    return "; ".join(parts)


__all__ = ["MAX_SIGNS", "MIN_GAIN", "best_reading", "describe", "flip_arrays", "flipped",
           "maps_text", "readings"]
