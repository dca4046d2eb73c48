r"""The names an expression of a derivation file may use, beyond the file's own.

Two namespaces exist. The *document* namespace holds what the document writes (its symbols,
coordinates, velocities, inputs), plus the standard functions :data:`STANDARD_FUNCTIONS` and
the :data:`CONSTANTS`. The *model* namespace (values of ``[symbols]``) holds the model's
physical parameters as real symbols and Khalil's standard inertial parameters as undefined
functions of a link name,

.. math::

    \mathrm{XX}(\text{body}),\ \mathrm{MY}(\text{body}),\ \mathrm{ZZ}(\text{wheel\_left}),\ \dots

written with :data:`KHALIL_FUNCTIONS` (real undefined functions) applied to
``sympy.Symbol(link)``, and the physical ones about the centre of mass, ``CX(link)``,
``IXX(link)`` ... (:data:`PHYSICAL_NAMES`; :func:`physical_in_standard` rewrites them in
Khalil's), and the model's lengths (:data:`GEOMETRY_NAMES`). Units are written over
:data:`UNIT_NAMES`.

Every symbol made here is ``real=True`` (:func:`real_symbol`); fetch them from the
:class:`~wheeled_dyn.derivations.schema.Derivation` rather than making new ones
(``Symbol("phi")`` without assumptions is a different symbol).
"""

from __future__ import annotations

from collections.abc import Mapping

import sympy

#: Functions every expression may use, by the name it is written with.
STANDARD_FUNCTIONS: Mapping[str, object] = {
    "sin": sympy.sin, "cos": sympy.cos, "tan": sympy.tan, "cot": sympy.cot,
    "sec": sympy.sec, "csc": sympy.csc, "asin": sympy.asin, "acos": sympy.acos,
    "atan": sympy.atan, "atan2": sympy.atan2, "sinh": sympy.sinh, "cosh": sympy.cosh,
    "tanh": sympy.tanh, "sqrt": sympy.sqrt, "exp": sympy.exp, "log": sympy.log,
    "Abs": sympy.Abs, "sign": sympy.sign,
}
#: Constants every expression may use.
CONSTANTS: Mapping[str, sympy.Basic] = {"pi": sympy.pi}
#: Names a file may not declare (they are functions or constants).
RESERVED_NAMES: frozenset[str] = frozenset(STANDARD_FUNCTIONS) | frozenset(CONSTANTS)

#: Khalil's standard inertial parameters of a link, in the link frame, as written in value
#: expressions: ``M(link)`` mass, ``MX MY MZ`` first moments, ``XX XY XZ YY YZ ZZ`` inertia
#: tensor entries about the link frame origin.
KHALIL_NAMES: tuple[str, ...] = ("M", "MX", "MY", "MZ", "XX", "XY", "XZ", "YY", "YZ", "ZZ")
#: The model's lengths by name, as written in value expressions, with what names their argument
#: (a URDF joint or link): the origin of a joint in its parent link's frame, along x, y or z
#: (the URDF's ``<origin xyz>``), a link's radius (its rolling radius if it rolls, else its
#: first sphere or cylinder) and length (its first cylinder), a rolling wheel's tyre radius, a
#: spheroid's polar radius, and the radius of the fixed sphere or the vertex radius of the bowl
#: a ball rolls on (named by the ball's link). See ``docs/derivation-format.md``.
GEOMETRY_NAMES: Mapping[str, str] = {
    "origin_x": "joint", "origin_y": "joint", "origin_z": "joint", "radius": "link",
    "length": "link", "tyre_radius": "link", "polar_radius": "link", "surface_radius": "link",
    "vertex_radius": "link"}
KHALIL_FUNCTIONS: Mapping[str, sympy.FunctionClass] = {n: sympy.Function(n, real=True)
                                                       for n in KHALIL_NAMES}
#: The physical parameters of a link (:mod:`wheeled_dyn.models.link_parameters`): ``CX CY CZ``
#: the centre of mass in the link frame, ``IXX IXY IXZ IYY IYZ IZZ`` the inertia tensor entries
#: about the centre of mass in the link's axes (``M`` is shared with Khalil's).
PHYSICAL_NAMES: tuple[str, ...] = ("CX", "CY", "CZ", "IXX", "IXY", "IXZ", "IYY", "IYZ", "IZZ")
#: Every function a value expression may apply to a link (or, for a length, a joint) name.
LINK_FUNCTIONS: Mapping[str, sympy.FunctionClass] = {
    **KHALIL_FUNCTIONS, **{n: sympy.Function(n, real=True)
                           for n in (*PHYSICAL_NAMES, *GEOMETRY_NAMES)}}


def physical_in_standard(expr: sympy.Expr) -> sympy.Expr:
    r"""``expr`` with every physical link parameter written in Khalil's standard ones of the
    same link (parallel-axis theorem, :math:`J_G = J_O - M(|c|^2 I - c c^T)`, :math:`c = MS/M`):
    :math:`CX = MX/M`, :math:`IXX = XX - (MY^2 + MZ^2)/M`, :math:`IXY = XY + MX\,MY/M` ..."""
    f = LINK_FUNCTIONS
    out = {}
    for call in expr.atoms(sympy.core.function.AppliedUndef):
        name, link = call.func.__name__, call.args[0]
        if name not in PHYSICAL_NAMES:
            continue
        m = f["M"](link)
        ms = {"X": f["MX"](link), "Y": f["MY"](link), "Z": f["MZ"](link)}
        if name[0] == "C":
            out[call] = ms[name[1]] / m
        elif name[1] == name[2]:
            others = [ms[a] ** 2 for a in "XYZ" if a != name[1]]
            out[call] = f[name[1:]](link) - (others[0] + others[1]) / m
        else:
            out[call] = f[name[1:]](link) + ms[name[1]] * ms[name[2]] / m
    return expr.xreplace(out) if out else expr


#: Unit names accepted in ``units`` (SI base and derived units, radians; ``1`` = dimensionless).
UNIT_NAMES: tuple[str, ...] = ("kg", "m", "s", "rad", "N", "J", "W", "A", "V", "K", "mol")
#: The unit symbols by name (positive).
UNITS: Mapping[str, sympy.Symbol] = {u: sympy.Symbol(u, positive=True) for u in UNIT_NAMES}


def real_symbol(name: str) -> sympy.Symbol:
    r"""The symbol of a document or model name: ``sympy.Symbol(name, real=True)``."""
    return sympy.Symbol(name, real=True)


__all__ = ["CONSTANTS", "GEOMETRY_NAMES", "KHALIL_FUNCTIONS", "KHALIL_NAMES", "LINK_FUNCTIONS",
           "PHYSICAL_NAMES", "RESERVED_NAMES", "STANDARD_FUNCTIONS", "UNIT_NAMES", "UNITS",
           "physical_in_standard", "real_symbol"]
