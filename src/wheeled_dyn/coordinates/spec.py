r"""Coordinate sets: how a document's coordinates and velocities relate to the model's.

A coordinate set is data (a dict, e.g. a TOML table) with

- ``positions``: the document's coordinate names, ``velocities`` (default ``d`` + name);
- ``configuration``: each model coordinate as an expression of the document's positions and
  the model's parameters (``R``, ``L``, ..., and its lengths as identifiers: ``radius_coin``
  for ``radius(coin)``); model coordinates not listed are 0. For a
  ``quasi`` set this is a *representative* configuration: the reduced dynamics do not depend on
  the coordinates it leaves out (x0, y0, and wheel angles for a body on flat ground);
- ``kind``:

  * ``holonomic``: :math:`q = g(q_{doc})`, so :math:`\dot q = S\,\dot q_{doc}` with
    :math:`S = \partial g/\partial q_{doc}` and :math:`\dot S = \sum_k \partial S/\partial
    q_{doc,k}\,\dot q_{doc,k}`;
  * ``quasi``: document velocities are linear in the model velocities,
    :math:`\nu = T(q)\,v` (``velocity_map``: document velocity = expression in model
    coordinates and model velocities ``d<name>``), e.g. the heading speed
    :math:`\dot x = \cos\psi\,\dot x_0 + \sin\psi\,\dot y_0`, which is the derivative of no
    coordinate;

- ``rolling``: ``eliminate`` (rolling constraints :math:`J_c v = 0` are solved with the
  velocity map: :math:`v = S\nu` spans their null space), ``multipliers`` (kept, with the
  constraint matrix :math:`G = J_c S`), or ``none``.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

import sympy as sp
from sympy.parsing.sympy_parser import parse_expr, standard_transformations

from ..errors import DerivationError, UnknownNameError, WheeledDynError

KINDS = ("holonomic", "quasi")
ROLLING = ("eliminate", "multipliers", "none")
#: The functions a coordinate set's expressions may call: a derivation's standard functions
#: (any other name called is an unknown function, refused).
_FUNCTIONS: dict[str, Any] = {name: getattr(sp, name) for name in
                              ("sin", "cos", "tan", "cot", "sec", "csc", "asin", "acos", "atan",
                               "atan2", "sinh", "cosh", "tanh", "sqrt", "exp", "log")}
_FUNCTIONS["pi"] = sp.pi


class CoordinateSpecError(WheeledDynError):
    """A coordinate set does not fit its model. Attributes: ``name``, ``item``, ``reason``."""

    def __init__(self, name: str, item: str, reason: str) -> None:
        self.name, self.item, self.reason = name, item, reason
        super().__init__(f"coordinate set {name!r}, {item}: {reason}")


def parse_expression(text: str | int | float, names: Mapping[str, sp.Basic], *, where: str,
                     item: str) -> sp.Expr:
    r"""Parse SymPy syntax with only ``names`` (and sin, cos, ..., pi) known.

    An unknown name raises :class:`UnknownNameError` naming ``where`` and ``item``; a syntax
    error, a token a derivation's expression may not hold (attribute access, a string, a
    keyword, ...) or an expression over the limits of :mod:`~wheeled_dyn.derivations.limits`
    raises :class:`DerivationError`: the text is checked by the derivations' token scan before
    SymPy reads it, as a model file's coordinate sets are the user's text too.
    """
    from ..derivations.expressions import ExpressionError, check_expanded, scan_names
    if isinstance(text, (int, float)):
        return sp.nsimplify(text) if float(text).is_integer() else sp.Float(text)
    try:
        scan_names(str(text))
    except ExpressionError as exc:
        raise DerivationError(where, item, exc.reason) from None
    local = {**_FUNCTIONS, **names}
    try:
        expr = parse_expr(str(text), local_dict=local, global_dict={"Integer": sp.Integer,
                          "Float": sp.Float, "Rational": sp.Rational, "Symbol": sp.Symbol,
                          "Function": sp.Function}, transformations=standard_transformations,
                          evaluate=True)
    except (SyntaxError, TypeError, ValueError, AttributeError) as exc:
        raise DerivationError(where, item, f"cannot parse {text!r}: {exc}") from None
    unknown = {s.name for s in expr.free_symbols} - set(names)
    if unknown:
        raise UnknownNameError("symbol", sorted(unknown)[0], names, where=f"{where}, {item}")
    calls = sorted(str(c.func) for c in expr.atoms(sp.core.function.AppliedUndef))
    if calls or expr.has(sp.Abs, sp.sign):
        called = calls[0] if calls else "Abs" if expr.has(sp.Abs) else "sign"
        raise DerivationError(where, item, f"{called}(...): a coordinate map is differentiated "
                              "and may call only the smooth functions "
                              + ", ".join(sorted(f for f in _FUNCTIONS if f != "pi")))
    try:
        check_expanded(str(text), expr)
    except ExpressionError as exc:
        raise DerivationError(where, item, exc.reason) from None
    return expr


@dataclass(frozen=True)
class CoordinateSet:
    r"""A parsed coordinate set (see the module docstring). Expressions are SymPy."""

    name: str
    kind: str
    positions: tuple[str, ...]
    velocities: tuple[str, ...]
    rolling: str
    configuration: Mapping[str, sp.Expr]          # model coordinate -> expr(doc positions, params)
    velocity_map: Mapping[str, sp.Expr] | None    # doc velocity -> expr(model q, model v, params)
    description: str = ""
    parameters: tuple[str, ...] = field(default=())

    @property
    def accelerations(self) -> tuple[str, ...]:
        return tuple("d" + v for v in self.velocities)

    def position_symbols(self) -> tuple[sp.Symbol, ...]:
        return tuple(sp.Symbol(n, real=True) for n in self.positions)

    def velocity_symbols(self) -> tuple[sp.Symbol, ...]:
        return tuple(sp.Symbol(n, real=True) for n in self.velocities)


def model_symbols(coordinate_names: Sequence[str]) -> tuple[tuple[sp.Symbol, ...], tuple[sp.Symbol, ...]]:
    r"""SymPy symbols of the model coordinates and velocities (``d`` + name)."""
    q = tuple(sp.Symbol(n, real=True) for n in coordinate_names)
    v = tuple(sp.Symbol("d" + n, real=True) for n in coordinate_names)
    return q, v


def parse_coordinate_set(spec: Mapping[str, Any], name: str, coordinate_names: Sequence[str],
                         parameter_names: Sequence[str], where: str = "coordinates") -> CoordinateSet:
    r"""Build a :class:`CoordinateSet` from a dict, checking every name against the model's
    coordinates and parameters."""
    kind = spec.get("kind", "holonomic")
    if kind not in KINDS:
        raise CoordinateSpecError(name, "kind", f"{kind!r}; expected one of {KINDS}")
    rolling = spec.get("rolling", "eliminate" if kind == "quasi" else "none")
    if rolling not in ROLLING:
        raise CoordinateSpecError(name, "rolling", f"{rolling!r}; expected one of {ROLLING}")
    positions = tuple(spec.get("positions", ()))
    if not positions:
        raise CoordinateSpecError(name, "positions", "expected a non-empty list of names")
    velocities = tuple(spec.get("velocities", ["d" + p for p in positions]))
    if len(velocities) != len(positions):
        raise CoordinateSpecError(name, "velocities", f"{len(velocities)} names for "
                                  f"{len(positions)} positions")
    params = {p: sp.Symbol(p, real=True) for p in parameter_names}
    doc_q = {p: sp.Symbol(p, real=True) for p in positions}
    clash = set(doc_q) & set(params)
    if clash:
        raise CoordinateSpecError(name, "positions", f"{sorted(clash)} are also parameter names")
    raw_config = dict(spec.get("configuration", {p: p for p in positions if p in coordinate_names}))
    configuration = {}
    for key, text in raw_config.items():
        if key not in coordinate_names:
            raise UnknownNameError("model coordinate", key, coordinate_names,
                                   where=f"{where}.configuration")
        configuration[key] = parse_expression(text, {**params, **doc_q}, where=where,
                                              item=f"configuration.{key}")
    for key in coordinate_names:
        configuration.setdefault(key, sp.Integer(0))
    velocity_map = None
    if kind == "quasi":
        raw = spec.get("velocity_map")
        if not raw:
            raise CoordinateSpecError(name, "velocity_map", "a quasi-velocity set needs one")
        mq, mv = model_symbols(coordinate_names)
        names = {**params, **{s.name: s for s in mq}, **{s.name: s for s in mv}}
        velocity_map = {}
        for vel in velocities:
            if vel not in raw:
                raise CoordinateSpecError(name, "velocity_map", f"no entry for {vel!r}")
            expr = parse_expression(raw[vel], names, where=where, item=f"velocity_map.{vel}")
            scale = sp.Dummy("scale")
            if sp.expand(expr.xreplace({s: scale * s for s in mv}) - scale * expr) != 0:
                raise CoordinateSpecError(name, f"velocity_map.{vel}",
                                          "must be linear in the model velocities")
            velocity_map[vel] = expr
        extra = set(raw) - set(velocities)
        if extra:
            raise UnknownNameError("velocity", sorted(extra)[0], velocities,
                                   where=f"{where}.velocity_map")
    used = set().union(*(e.free_symbols for e in (*configuration.values(),
                                                  *(velocity_map or {}).values())))
    return CoordinateSet(name=name, kind=kind, positions=positions, velocities=velocities,
                         rolling=rolling, configuration=configuration, velocity_map=velocity_map,
                         description=str(spec.get("description", "")),
                         parameters=tuple(p for p in parameter_names if params[p] in used))
