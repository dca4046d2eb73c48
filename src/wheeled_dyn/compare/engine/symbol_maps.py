r"""A symbol mapped to another parameter of its link: a cause, never a verdict.

A newcomer maps the document's symbols to the model's parameters in the link's own axes, and
a CAD export turns those axes: the moment the derivation calls :math:`I_2` is ``IYY(forearm)``
where the file wrote ``IXX(forearm)``, the centre of mass's offset ``-CZ(link)`` where it wrote
``CX(link)``. Every element with the symbol then differs, and no term is wrong. The file's
``[symbols]`` are how the document is read (declarations are binding); where at most half the
equations are right, each symbol whose value is one link parameter is read, one at a time,
as another of its kind of the same link (a moment about another axis, a centre-of-mass
coordinate or a product of inertia along another, either sign) and as the same parameter
(or the mass) of each other link of the model, on the convention search's
samples (:class:`~..readings.search.SearchEvaluation`: the document's compiled functions, the
symbol's numbers changed, no new truth) — a symbol written in an element that agrees is
mapped right, and not read again (but for the elements of rows compared in a frame that
varies, divided or combined by the file's own values: they agree whatever the map gives).
One that makes every equation right is the first cause (``file_error``): "with I2 =
IYY(forearm_link) (the file maps it to IXX(forearm_link)), every equation is right (0 of 2 as
declared): the file probably maps I2 to another parameter of the link than the document means
…". A symbol valued as Earth's gravity (a number within
:data:`~..judge.numbers.GRAVITY_NUMBERS`) is read as the model's ``g``, which the comparison
draws as every parameter.
"""

from __future__ import annotations

import re
from collections.abc import Sequence
from dataclasses import replace

import numpy as np
import sympy as sp
from sympy.core.function import AppliedUndef

from ...expression_size import free_symbols_of
from ...derivations.schema import Derivation
from ...errors import UnknownNameError
from ..grid.values import model_value
from ..judge.numbers import GRAVITY_NUMBERS
from ..records import Cause, CauseKind, Verdict
from .conventions import search_evaluation

#: Link parameters of one kind: a symbol mapped to one is read as each other one.
GROUPS: tuple[tuple[str, ...], ...] = (("IXX", "IYY", "IZZ"), ("XX", "YY", "ZZ"),
                                       ("CX", "CY", "CZ"), ("MX", "MY", "MZ"),
                                       ("IXY", "IXZ", "IYZ"), ("XY", "XZ", "YZ"))
#: Of those, the kinds read with either sign (a coordinate along an axis turned the other way).
SIGNED: frozenset[str] = frozenset(("CX", "CY", "CZ", "MX", "MY", "MZ", "IXY", "IXZ", "IYZ",
                                    "XY", "XZ", "YZ"))


#: The model's gravity, as a symbol's value names it.
GRAVITY = sp.Symbol("g")


#: Why a reading is tried: the link's axes turned, another link meant, Earth's gravity, a
#: joint's length written where a centre of mass is meant.
AXES, LINK, EARTH, CENTRE = "axes", "link", "gravity", "centre"
#: The joints' lengths a symbol's value may name (:mod:`~wheeled_dyn.models.geometry`).
JOINT_LENGTHS = frozenset(("origin_x", "origin_y", "origin_z"))


def _alternatives(value: sp.Expr, links: Sequence[str] = ()) -> list[tuple[sp.Expr, str]]:
    r"""``value`` (one link parameter, times anything) with that parameter read as each other
    of its kind (:data:`GROUPS`, :data:`SIGNED` with either sign), and as the same parameter
    (or a mass) of each other of the model's ``links``; a number near Earth's gravity read as
    the model's :data:`GRAVITY`; a value of joints' lengths alone (:data:`JOINT_LENGTHS`) read
    as each link's centre-of-mass coordinate, either sign; none where it holds no link
    parameter or more than one. Each with why it is tried."""
    if value.is_Number and GRAVITY_NUMBERS[0] <= abs(float(value)) <= GRAVITY_NUMBERS[1]:
        return [(GRAVITY, EARTH), (-GRAVITY, EARTH)]       # either sign: g = -9.81 is one
    kinds = {k for g in GROUPS for k in g} | {"M"}
    calls = [c for c in value.atoms(AppliedUndef) if c.func.__name__ in kinds]
    if not calls and any(c.func.__name__ in JOINT_LENGTHS for c in value.atoms(AppliedUndef)):
        return [(s * sp.Function(axis)(sp.Symbol(link)), CENTRE) for link in links
                for axis in ("CX", "CY", "CZ") for s in (1, -1)]
    if len(calls) != 1:
        return []
    call = calls[0]
    name = call.func.__name__
    group = next((g for g in GROUPS if name in g), (name,))
    signs = (1, -1) if name in SIGNED else (1,)
    out = [(value.xreplace({call: s * sp.Function(other)(*call.args)}), AXES)
           for other in group for s in signs if (other, s) != (name, 1)]
    here = str(call.args[0]) if len(call.args) == 1 else None
    return out + [(value.xreplace({call: sp.Function(name)(sp.Symbol(link))}), LINK)
                  for link in links if here is not None and link != here]


def _in_any(name: str, texts: list[str]) -> bool:
    r"""Whether the symbol ``name`` is written in one of ``texts`` (an element that agrees
    with it as mapped: its map is right)."""
    word = re.compile(rf"(?<![A-Za-z0-9_]){re.escape(name)}(?![A-Za-z0-9_])")
    return any(word.search(t) for t in texts)


def _right(search, values) -> int:
    r"""How many of the document's equations are right with the symbols' ``values``."""
    ev = replace(search, values=values)
    return ev.equations_right(ev.doc_at((1,) * ev.q.shape[1]))


def _equations(j) -> list[sp.Expr]:
    r"""The document's expressions the judged derivation ``j`` compares (None left out)."""
    exprs = j.funcs.exprs
    return [e for e in exprs.values() if isinstance(e, sp.Basic)]


def symbol_map_finding(d: Derivation, j) -> Cause | None:
    r"""The first symbol whose value read as another parameter of its link makes every
    equation of the judged derivation ``j`` right (module text), as a cause; None where none
    does, or more than half the equations are right as declared."""
    if j.funcs.exprs.get("K") is not None:
        return None          # a linearised document: its stiffness is compared apart from the
        #                      samples a reading is judged on (a wrong K beside a wrong map)
    search = search_evaluation(j)
    agreeing = [r.document for r in j.result.records     # in a frame of the file's values:
                if r.verdict == Verdict.AGREES and r.document not in ("", "0")   # no voucher
                and not (r.index and r.index[0] in j.varying)]

    def mapped_right(symbol) -> bool:            # written, not 0, where an element agrees
        values = search.values.get(symbol)
        return values is not None and bool(np.any(np.asarray(values) != 0)) and \
            _in_any(str(symbol), agreeing)
    written = set().union(*(free_symbols_of(e) for e in _equations(j)))
    links = sorted(k[2:-1] for k in j.sides.grid.sets[0].values if k.startswith("M("))
    readings = [(spec, other, why) for spec in d.symbols.values()
                if not spec.is_input and spec.value is not None and spec.symbol in written
                and not mapped_right(spec.symbol)
                for other, why in _alternatives(spec.value, links)]
    if not readings:                    # no symbol is one link parameter (a physical record)
        return None
    n = search.q.shape[1]
    declared = sum(e.verdict == Verdict.AGREES for e in j.result.equations)   # as decided
    if declared > n // 2 or _right(search, search.values) != declared:
        return None          # the samples do not judge as the decision did (a linearised
        #                      document's stiffness is compared apart): no reading is said
    grid = j.sides.grid
    n_states = grid.q.shape[1]
    for spec, other, why in readings:
        if spec.symbol in search.values:
            try:
                per_set = [model_value(other, ps.values) for ps in grid.sets]
            except UnknownNameError:
                continue
            if not np.any(per_set):
                continue      # zero in every set (a centre of mass on the axis): the symbol's
                #               terms would vanish, not be read right
            values = dict(search.values)
            values[spec.symbol] = np.repeat(per_set, n_states)
            if _right(search, values) != n:
                continue
            value = sp.sympify(spec.value)
            if why == EARTH:
                return Cause(CauseKind.FILE_ERROR, (), (
                    f"with {spec.symbol} valued as the model's gravity (the file values "
                    f"it {float(value):g}), every equation is right ({declared} of {n} as "
                    "declared): the comparison draws gravity as every parameter of the "
                    f"model, and the equations as the file values them hold for g = "
                    f"{abs(float(value)):g} only (value {spec.symbol} as \"{sp.sstr(other)}\"); "
                    "the verdicts are under the file's declaration"))
            meant = "another parameter of the link than the document means (its axes " \
                "turned: declare the one that fits)" if why == AXES else \
                "a joint's length where the document means a link's centre of mass (the " \
                "comparison draws lengths and centres of mass as parameters of their own: " \
                "declare the centre of mass)" if why == CENTRE else \
                "a parameter of another link than the document means (declare the link)"
            return Cause(CauseKind.FILE_ERROR, (), (
                f"with {spec.symbol} = {sp.sstr(other)} (the file maps it to "
                f"{sp.sstr(value)}), every equation is right ({declared} of {n} as "
                f"declared): the file probably maps {spec.symbol} to {meant}; the verdicts "
                "are under the file's declaration"))
    return None


__all__ = ["GROUPS", "SIGNED", "symbol_map_finding"]
