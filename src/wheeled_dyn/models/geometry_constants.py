r"""The constants of a model's ``[geometry]`` and the lengths a built model names.

:func:`constants` reads ``[geometry]`` (a number, an expression of lengths, a list of equal
lengths, ``{ value = x }``: :mod:`.geometry`), checked against the URDF's lengths; errors are
:class:`~wheeled_dyn.errors.ModelError` naming ``geometry.<name>``. :func:`planar_lengths` and
:func:`unwheeled_lengths` give the builder the model's :class:`~.geometry.GeometryTable`: its
lengths, the constants the builder names (a planar model's ``R``, ``L``; a ball's ``r``,
``R1``, ``a``; a spheroid's ``a``, ``c``) and those of ``[geometry]``.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from types import MappingProxyType
from typing import TYPE_CHECKING, Any

import sympy as sp
from sympy.core.function import AppliedUndef

from ..derivations.expressions import GEOMETRY_NAMES, ExpressionError, parse_model_expression
from ..errors import ModelError
from .geometry import (SAME_TOL, Constant, ConstantKind, Dimension, GeometryTable, monomial,
                       call_name, dimensions, evaluate, link_inertials, table, urdf_lengths)
from .uniform_reading import uniform_inertials, unlike_uniform

if TYPE_CHECKING:
    from .wheeled_model import ModelSpec
    from .urdf_source import UrdfSource


def constants(spec_name: str, raw: Mapping[str, Any], dims: Mapping[str, Dimension],
              given: Mapping[str, Constant] = MappingProxyType({}), fixed: Sequence[str] = ()
              ) -> dict[str, Constant]:
    r"""The constants of ``[geometry]`` (``raw``: name → number, expression, list of
    monomials or ``{ value = x }``) after the ones the builder ``given``; errors are
    :class:`~wheeled_dyn.errors.ModelError` naming ``geometry.<name>``."""
    out = dict(given)
    values = {k: d.value for k, d in dims.items()}
    for name, value in raw.items():
        item = f"geometry.{name}"
        if name in out:
            raise ModelError(spec_name, item, f"{name} is given by the model already "
                                              f"({out[name].meaning})")
        drawn = name not in fixed
        if isinstance(value, Mapping):
            out[name] = Constant(name, float(value["value"]), ConstantKind.FREE, drawn=drawn)
        elif isinstance(value, (int, float)) and not isinstance(value, bool):
            equal = [k for k, d in dims.items()
                     if d.value and abs(d.value - value) <= SAME_TOL * abs(value)]
            if equal:
                raise ModelError(spec_name, item, f"{value!r} is the value of {equal[0]}: write "
                                 f"{name} = \"{equal[0]}\" (or a list of the equal lengths) so "
                                 "that it is drawn with it, or { value = ... } if it is a "
                                 "constant of its own")
            out[name] = Constant(name, float(value), ConstantKind.FREE, drawn=drawn)
        elif isinstance(value, str):
            expr = _parse(spec_name, item, value, dims, out)
            out[name] = Constant(name, evaluate(expr, values, _numbers(out)),
                                 ConstantKind.DERIVED, expression=expr, drawn=drawn)
        else:
            out[name] = _same(spec_name, name, list(value), dims, out, drawn)
    return out


def _numbers(consts: Mapping[str, Constant]) -> dict[str, float]:
    return {k: c.value for k, c in consts.items()}


def _parse(spec_name: str, item: str, text: str, dims: Mapping[str, Dimension],
           consts: Mapping[str, Constant]) -> sp.Expr:
    try:
        expr = parse_model_expression(text, tuple(consts))
    except ExpressionError as exc:
        raise ModelError(spec_name, item, f"{text!r}: {exc.reason}") from None
    for call in expr.atoms(AppliedUndef):
        if call.func.__name__ not in GEOMETRY_NAMES or call_name(call) not in dims:
            raise ModelError(spec_name, item, f"{call_name(call)} is not a length of the model; "
                             "valid: " + ", ".join(dims))
    return expr


def _same(spec_name: str, name: str, entries: list, dims: Mapping[str, Dimension],
          consts: Mapping[str, Constant], drawn: bool) -> Constant:
    r"""A list of monomials ``c * dimension`` that are equal in the URDF."""
    item = f"geometry.{name}"
    members = []
    for text in entries:
        expr = _parse(spec_name, item, str(text), dims, consts)
        coef, rest = expr.as_coeff_Mul()
        if not (isinstance(rest, AppliedUndef) and coef != 0):
            raise ModelError(spec_name, item, f"{text!r}: expected a number times one length "
                             "(a list names equal lengths)")
        members.append((float(coef), call_name(rest)))
    values = [c * dims[d].value for c, d in members]
    for (c, d), v in zip(members, values):
        if abs(v - values[0]) > SAME_TOL * max(abs(values[0]), 1e-300):
            raise ModelError(spec_name, item, f"{monomial(c, d)} is {v:g} in the URDF, "
                             f"{monomial(*members[0])} is {values[0]:g}: the entries of a list "
                             "are equal lengths")
    if not math.isfinite(values[0]) or values[0] == 0:
        raise ModelError(spec_name, item, "equal lengths of value 0 (nothing to draw)")
    return Constant(name, values[0], ConstantKind.SAME, tuple(members),
                    drawn=drawn and all(dims[d].drawn for _, d in members))


def check_fixed(spec_name: str, fixed: Sequence[str], geometry: GeometryTable) -> None:
    r"""Every name of ``[draw] fixed`` is a dimension or a constant drawn on its own or with
    its equal lengths; a constant written as an expression of lengths is drawn with them (to
    keep it, keep them)."""
    for name in fixed:
        if name not in geometry.dimensions and name not in geometry.constants:
            raise ModelError(spec_name, "draw.fixed", f"{name} is not a length or constant of "
                             "the model; valid: " + ", ".join((*geometry.dimensions,
                                                               *geometry.constants)))
        c = geometry.constants.get(name)
        if c is not None and c.kind == ConstantKind.DERIVED:
            raise ModelError(spec_name, "draw.fixed", f"{name} = {c.expression} is drawn with "
                             "those lengths: keep them instead (list them in [draw] fixed)")




# -- the builder's tables -------------------------------------------------------------------
def _path_to_root(source: "UrdfSource", link: str) -> list:
    r"""The joints from the root down to ``link``."""
    out = []
    while link != source.root_link():
        joint = source.joint_to(link)
        out.append(joint)
        link = joint.parent
    return out


def _lengths(spec: "ModelSpec", source: "UrdfSource", dims: Mapping[str, Dimension],
             given: Mapping[str, Constant]) -> GeometryTable:
    r"""The model's lengths and constants (:mod:`.geometry`): the builder's ``given`` names
    where ``[geometry]`` does not name them, then ``[geometry]``'s; the links' own inertias."""
    kept = {k: c for k, c in given.items() if k not in spec.geometry}
    inertials = link_inertials(source.text, source.path)
    shapes = urdf_lengths(source.text)[1]
    out = table(dims, constants(spec.name, spec.geometry, dims, kept, spec.fixed_geometry),
                inertials, uniform_inertials(source.text, shapes, inertials),
                unlike_uniform(source.text, inertials))
    for name, c in given.items():                  # [geometry] says what it is drawn with
        value = out.constants[name].value if name in out.constants else c.value
        if abs(value - c.value) > SAME_TOL * max(1.0, abs(c.value)):
            raise ModelError(spec.name, f"geometry.{name}", f"{name} is {c.value:g} in the "
                             f"model ({c.meaning}), {value:g} as written: [geometry] may say "
                             "which lengths it is drawn with, not change it")
    check_fixed(spec.name, spec.fixed_geometry, out)
    return out


def _contact_lengths(spec: "ModelSpec") -> tuple[dict[str, dict[str, float]], dict[str, str]]:
    r"""The radii the contacts declare, per link (``radius``, ``polar_radius``,
    ``surface_radius``, ``vertex_radius``, ``tyre_radius``), and the names the builder gives
    them (``r``, ``R1``, ``a``, ``c``: name → length)."""
    rolling: dict[str, dict[str, float]] = {}
    given: dict[str, str] = {}
    sc = spec.contact
    if sc is not None:
        rolling[sc.link] = {"radius": float(sc.radius)}
        if sc.polar_radius is not None:             # a spheroid: equatorial and polar radii
            rolling[sc.link]["polar_radius"] = float(sc.polar_radius)
            given.update(a=f"radius({sc.link})", c=f"polar_radius({sc.link})")
        else:
            given["r"] = f"radius({sc.link})"
        if sc.surface == "sphere":
            rolling[sc.link]["surface_radius"] = float(sc.surface_radius)
            given["R1"] = f"surface_radius({sc.link})"
        elif sc.surface == "paraboloid":            # vertex radius of curvature
            rolling[sc.link]["vertex_radius"] = float(sc.vertex_radius)
            given["a"] = f"vertex_radius({sc.link})"
    for wc in spec.rolling_wheels:
        rolling[wc.link] = {"radius": float(wc.radius)}
        if wc.tyre_radius:
            rolling[wc.link]["tyre_radius"] = float(wc.tyre_radius)
    return rolling, given


def sp_call(name: str):
    r"""The SymPy call of a length's name (``radius(ball)``)."""
    from ..derivations.expressions import parse_model_expression
    return parse_model_expression(name)




def planar_lengths(spec: "ModelSpec", source: "UrdfSource", model: Any, radius: float,
                   half_track: float) -> GeometryTable:
    r"""A planar model's table: the joints from the root to the wheels named by ``R`` (both
    wheels' radius, the axle's height) and ``L`` (half the distance between the wheels)."""
    axle = [j.name for w in spec.wheels for j in _path_to_root(source, w)]
    dims = dimensions(model, source, {w: {"radius": radius} for w in spec.wheels}, axle,
                      spec.fixed_geometry)
    given = {"R": Constant("R", radius, ConstantKind.SAME,
                           tuple((1.0, f"radius({w})") for w in spec.wheels),
                           drawn="R" not in spec.fixed_geometry),
             "L": Constant("L", half_track, ConstantKind.TRACK,
                           drawn="L" not in spec.fixed_geometry)}
    return _lengths(spec, source, dims, given)


def unwheeled_lengths(spec: "ModelSpec", source: "UrdfSource", model: Any) -> GeometryTable:
    r"""A fixed or free model's table, its contacts' radii and their names included."""
    rolling, given = _contact_lengths(spec)
    dims = dimensions(model, source, rolling, (), spec.fixed_geometry)
    named = {k: Constant(k, dims[v].value, ConstantKind.DERIVED, expression=sp_call(v),
                         drawn=dims[v].drawn) for k, v in given.items()}
    return _lengths(spec, source, dims, named)
