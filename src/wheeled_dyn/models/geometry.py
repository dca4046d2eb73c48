r"""The model's lengths by name, and the constants of its ``[geometry]``.

Agreement at one set of numbers hides errors: :math:`l_1^2` written for :math:`l_1` is invisible
on a URDF whose :math:`l_1` is 1 m, and a disc's :math:`I = m r^2/2` breaks when its mass and
inertia are drawn but not its radius. So every length of a model has a name, a derivation may
use it (``l1 = "origin_x(elbow)"`` as ``m = "M(link)"``), and the random parameter sets draw
it (:mod:`.geometry_apply`).

**Dimensions** (:class:`Dimension`), named by a function of a URDF joint or link
(:data:`~wheeled_dyn.derivations.expressions.GEOMETRY_NAMES`):

- ``origin_x(joint)``, ``origin_y(joint)``, ``origin_z(joint)``: the joint's origin in its
  parent link's frame, as the URDF's ``<origin xyz>`` writes it, for every joint, moving,
  fixed or locked (a zero stays zero; rotations are kept). The joints on the path from a
  planar model's root to its wheels are named by ``R`` and ``L`` instead;
- ``radius(link)``: the rolling radius of a wheel or ball, else the link's first sphere or
  cylinder (collision, then visual); ``length(link)``: its first cylinder's length;
- ``tyre_radius(link)`` of a rolling wheel with a tyre, ``polar_radius(link)`` of a spheroid,
  ``surface_radius(link)`` (the fixed sphere a ball rolls on) and ``vertex_radius(link)`` (the
  bowl's radius of curvature at its vertex), both named by the ball's link.

A link's radii and lengths are its *shape*: a uniform link (a family of the comparison) keeps
them in proportion to its inertia. Where a joint sits on a link is not its shape (a point
mass anywhere on a disc): a model that has a joint at the end of a rod says so in
``[geometry]`` (``l1 = ["origin_x(elbow)", "length(upper_arm)"]``).

**Constants** (:class:`Constant`), the names of ``[geometry]`` (and the ones the builder gives:
``R``, ``L`` of a planar model, ``r``, ``R1``, ``a``, ``c`` of a rolling ball or spheroid):

- a number (``G = 3.5``): a constant of the model (a gear ratio), drawn on its own;
- an expression of dimensions and constants (``R = "radius(coin)"``): it follows them;
- a list of monomials ``c * dimension``
  (``W = ["2*origin_y(spin_rl)", "-2*origin_y(spin_rr)"]``): lengths the body has equal by
  design, drawn as one (each entry equals the constant);
- ``{ value = x }``: a number that is a constant of its own although a length of the URDF has
  the same value (a plain number equal to one is an error: it would be drawn apart from it).

They are read by :mod:`.geometry_constants`. ``[draw] fixed`` lists names kept at their values
in every parameter set (a published body whose wheels must touch the ground at its reference
state).
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from enum import Enum
from pathlib import Path
from types import MappingProxyType
from typing import Any

import numpy as np
import sympy as sp
from sympy.core.function import AppliedUndef

from ..errors import InputFileError
from .conventions import inertia_tensor, inertial_rotation


#: Relative agreement of the entries of a ``[geometry]`` list (and of a number with a length
#: of the URDF, which makes it an error to write it as a plain number).
SAME_TOL = 1e-9
_AXES = ("x", "y", "z")


class ConstantKind(str, Enum):
    r"""How a constant of ``[geometry]`` is drawn (see the module docstring)."""

    FREE = "free"          # a number of its own: drawn by a random factor
    SAME = "same"          # equal lengths of the URDF: drawn as one
    DERIVED = "derived"    # an expression of the dimensions: follows them
    TRACK = "track"        # a planar model's half track L: the wheels moved along the axle


@dataclass(frozen=True)
class Dimension:
    r"""A named length of the model: ``name`` as written (``origin_x(elbow)``), its value,
    what it is, the link whose shape it is (``shape_of``: its radii and lengths; None for a
    joint's origin and a fixed surface), whether a parameter set draws it (``drawn``: not a
    length kept by ``[draw] fixed``)."""

    name: str
    value: float
    meaning: str
    shape_of: str | None = None
    drawn: bool = True

    @property
    def kept(self) -> bool:
        return not self.drawn


@dataclass(frozen=True)
class Constant:
    r"""A named constant: a number, equal lengths (``members``: (c, dimension), the constant
    is c × the dimension) or an ``expression`` of dimensions and constants."""

    name: str
    value: float
    kind: ConstantKind
    members: tuple[tuple[float, str], ...] = ()
    expression: sp.Expr | None = None
    drawn: bool = True

    @property
    def meaning(self) -> str:
        if self.kind is ConstantKind.SAME:
            return "= " + " = ".join(monomial(c, d) for c, d in self.members)
        if self.kind is ConstantKind.DERIVED:
            return f"= {self.expression}"
        if self.kind is ConstantKind.TRACK:
            return "half the distance between the wheels (their tyres' mid-planes)"
        return "a constant of the model"


def monomial(c: float, name: str) -> str:
    return name if c == 1 else f"-{name}" if c == -1 else f"{c:g}*{name}"


@dataclass(frozen=True)
class GeometryTable:
    r"""The dimensions and constants of a built model (names in the file's order), and each
    link's own inertia as the URDF gives it (``inertials``: link → Pinocchio's ten dynamic
    parameters in the link frame), from which a body of several links is put together again
    when its lengths change."""

    dimensions: Mapping[str, Dimension]
    constants: Mapping[str, Constant]
    inertials: Mapping[str, tuple[float, ...]] = field(default_factory=dict)
    #: link → (its inertials read as the uniform body's, the reading in words), for the links
    #: whose printed moments are a uniform body's to their digits (:mod:`.uniform_reading`)
    uniform: Mapping[str, tuple[tuple[float, ...], str]] = field(default_factory=dict)
    #: link → in words, for the links whose printed moments are no uniform body's of any
    #: cylinder, sphere or box they draw (:func:`~.uniform_reading.unlike_uniform`)
    unlike_uniform: Mapping[str, str] = field(default_factory=dict)

    def values(self) -> dict[str, float]:
        r"""Every name → its value (dimensions, then constants)."""
        return {**{k: d.value for k, d in self.dimensions.items()},
                **{k: c.value for k, c in self.constants.items()}}

    def constant_values(self, dims: Mapping[str, float],
                        free: Mapping[str, float] | None = None) -> dict[str, float]:
        r"""The constants at the dimensions ``dims`` (the numbers of ``free`` constants as
        given, else as in the table)."""
        out: dict[str, float] = {}
        for name, c in self.constants.items():
            if c.kind is ConstantKind.SAME:
                coef, member = c.members[0]
                out[name] = coef * dims[member]
            elif c.kind is ConstantKind.DERIVED:
                out[name] = evaluate(c.expression, dims, out)
            else:
                out[name] = float((free or {}).get(name, c.value))
        return out


def evaluate(expr: sp.Expr, dims: Mapping[str, float], constants: Mapping[str, float]) -> float:
    r"""An expression of dimension calls and constant names at these values."""
    calls = {call: sp.Float(dims[call_name(call)]) for call in expr.atoms(AppliedUndef)}
    out = expr.xreplace(calls)
    return float(out.xreplace({s: constants[s.name] for s in out.free_symbols}))


def identifier(name: str) -> str:
    r"""The name of a length as one identifier, as coordinate expressions and closed forms
    write it: ``radius_coin`` for ``radius(coin)``."""
    return name.replace("(", "_").rstrip(")")


def call_name(call: sp.Expr) -> str:
    r"""``origin_x(elbow)`` of the SymPy call ``origin_x(elbow)``."""
    return f"{call.func.__name__}({call.args[0]})"


# -- reading the URDF --------------------------------------------------------------------
def urdf_lengths(text: str) -> tuple[dict[str, tuple[float, float, float]],
                                     dict[str, tuple[float | None, float | None]]]:
    r"""Each joint's ``<origin xyz>`` and each link's (radius, length) of its first sphere or
    cylinder (collision, then visual; None where absent)."""
    root = ET.fromstring(text)
    origins: dict[str, tuple[float, float, float]] = {}
    for joint in root.findall("joint"):      # not a <transmission>'s <joint>
        origin = joint.find("origin")
        xyz = (origin.get("xyz", "0 0 0") if origin is not None else "0 0 0").split()
        origins[joint.get("name", "")] = tuple(float(x) for x in xyz)  # type: ignore[assignment]
    shapes: dict[str, tuple[float | None, float | None]] = {}
    for link in root.findall("link"):
        found: tuple[float | None, float | None] = (None, None)
        for group in ("collision", "visual"):
            for item in link.findall(group):
                geometry = item.find("geometry")
                shape = None if geometry is None else (geometry.find("cylinder")
                                                       if geometry.find("cylinder") is not None
                                                       else geometry.find("sphere"))
                if shape is not None and found == (None, None):
                    length = shape.get("length")
                    found = (float(shape.get("radius", "nan")),
                             None if length is None else float(length))
        shapes[link.get("name", "")] = found
    return origins, shapes


def urdf_length_names(text: str) -> list[tuple[str, float, str]]:
    r"""The lengths a URDF names (name, value, what it is), as a model built on it lists them
    before its contacts are declared: each joint's nonzero origin components, each link's first
    sphere or cylinder (the starting model file lists them)."""
    origins, shapes = urdf_lengths(text)
    out = []
    for joint, xyz in origins.items():
        for axis, value in zip(_AXES, xyz):
            if value:
                out.append((f"origin_{axis}({joint})", value, f"{axis} of joint {joint}'s "
                            "origin"))
    for link, (radius, length) in shapes.items():
        if radius is not None:
            out.append((f"radius({link})", radius, f"{link}'s first sphere or cylinder"))
        if length is not None:
            out.append((f"length({link})", length, f"{link}'s first cylinder"))
    return out


def link_inertials(text: str, path: Path | None = None) -> dict[str, tuple[float, ...]]:
    r"""Each link's own ``<inertial>`` in its link frame, as Pinocchio's dynamic parameters
    :math:`(m, mc, I_O)` (links without one are left out). An inertia Pinocchio refuses (a
    negative moment about an axis, listed in ``accept_inertia``) raises
    :class:`~wheeled_dyn.errors.InputFileError` naming the URDF ``path`` and the link."""
    import pinocchio as pin
    out: dict[str, tuple[float, ...]] = {}
    for link in ET.fromstring(text).findall("link"):
        inertial = link.find("inertial")
        mass = None if inertial is None else inertial.find("mass")
        if inertial is None or mass is None:
            continue
        origin = inertial.find("origin")
        xyz = np.array([float(x) for x in (origin.get("xyz", "0 0 0") if origin is not None
                                           else "0 0 0").split()])
        rpy = np.array([float(x) for x in (origin.get("rpy", "0 0 0") if origin is not None
                                           else "0 0 0").split()])
        tensor_matrix = inertia_tensor(inertial.find("inertia"))
        R = inertial_rotation(rpy)
        try:
            inertia = pin.Inertia(float(mass.get("value", "0")), xyz, R @ tensor_matrix @ R.T)
        except (RuntimeError, ValueError) as exc:
            raise InputFileError(path or Path("<URDF>"), f"link {link.get('name')!r}: "
                                 f"Pinocchio cannot take its inertia ({exc})") from None
        out[link.get("name", "")] = tuple(float(x) for x in inertia.toDynamicParameters())
    return out


def dimensions(model: Any, source: Any, rolling: Mapping[str, dict[str, float]],
               skip_joints: Sequence[str] = (), fixed: Sequence[str] = ()
               ) -> dict[str, Dimension]:
    r"""The named lengths of a built model (module docstring). ``rolling``: per link, the
    radii its contact declares (``radius``, ``tyre_radius`` ...; these replace its shape's
    radius); ``skip_joints``: joints named otherwise (a planar model's axle); ``fixed``:
    names kept in every parameter set."""
    origins, shapes = urdf_lengths(source.text)
    out: dict[str, Dimension] = {}
    for info in source.outline.joints:
        if info.name in skip_joints or not model.existFrame(info.parent):
            continue
        kind = "" if model.existJointName(info.name) else f" ({info.type} joint)"
        for axis, value in zip(_AXES, origins.get(info.name, (0.0, 0.0, 0.0))):
            name = f"origin_{axis}({info.name})"
            out[name] = Dimension(name, float(value), f"{axis} of joint {info.name}'s origin in "
                                  f"link {info.parent}'s frame{kind}", None, name not in fixed)
    for link in source.link_names:
        if not model.existFrame(link):
            continue
        radius, length = shapes.get(link, (None, None))
        declared = rolling.get(link, {})
        if "radius" in declared:
            radius = None
        for key, value in declared.items():
            name = f"{key}({link})"
            surface = key in ("surface_radius", "vertex_radius")
            out[name] = Dimension(name, float(value), f"{key.replace('_', ' ')} of {link} "
                                  "(its contact)", None if surface else link, name not in fixed)
        if radius is not None:
            name = f"radius({link})"
            out[name] = Dimension(name, radius, f"radius of {link}'s first sphere or cylinder",
                                  link, name not in fixed)
        if length is not None:
            name = f"length({link})"
            out[name] = Dimension(name, length, f"length of {link}'s first cylinder", link,
                                  name not in fixed)
    return out


def symbols(geometry: GeometryTable, exact=None) -> dict[str, sp.Expr]:
    r"""Every name of ``geometry`` as the closed forms write it: the lengths a parameter set
    draws as symbols, one per group of equal lengths (its constant's name:
    ``origin_y(spin_rl) → W/2``, ``radius(coin) → R`` where ``R = "radius(coin)"``), the others
    (``origin_x(elbow) → origin_x_elbow``); a constant that follows them as their expression;
    what is kept (a fixed joint's origin, ``[draw] fixed``) as its number (``exact``: the
    function making a float exact, default ``sympy.nsimplify``)."""
    exact = exact or (lambda x: sp.nsimplify(x, rational=True))
    out: dict[str, sp.Expr] = {}
    for name, c in geometry.constants.items():
        single = c.kind is ConstantKind.DERIVED and isinstance(c.expression, AppliedUndef)
        if c.kind is ConstantKind.SAME or single:
            members = c.members or ((1.0, call_name(c.expression)),)
            drawn = c.drawn and all(geometry.dimensions[d].drawn for _, d in members)
            symbol = sp.Symbol(name, real=True) if drawn else exact(c.value)
            for coef, dim in members:
                out.setdefault(dim, symbol / sp.nsimplify(coef, rational=True))
            out[name] = symbol
    for name, d in geometry.dimensions.items():
        if name not in out:
            out[name] = sp.Symbol(identifier(name), real=True) if d.drawn and d.value else \
                exact(d.value)
    for name, c in geometry.constants.items():
        if name in out:
            continue
        if c.kind is ConstantKind.DERIVED and c.expression is not None:
            expr = c.expression
            calls = {call: out[call_name(call)] for call in expr.atoms(AppliedUndef)}
            out[name] = expr.xreplace(calls).xreplace(
                {s: out[s.name] for s in expr.free_symbols if s.name in out})
        else:
            out[name] = sp.Symbol(name, real=True) if c.drawn else exact(c.value)
    return out


def table(dims: Mapping[str, Dimension], consts: Mapping[str, Constant],
          inertials: Mapping[str, tuple[float, ...]],
          uniform: Mapping[str, tuple[tuple[float, ...], str]] | None = None,
          unlike_uniform: Mapping[str, str] | None = None) -> GeometryTable:
    return GeometryTable(MappingProxyType(dict(dims)), MappingProxyType(dict(consts)),
                         MappingProxyType(dict(inertials)), MappingProxyType(dict(uniform or {})),
                         MappingProxyType(dict(unlike_uniform or {})))
