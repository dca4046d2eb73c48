r"""Dimensional analysis of a document's elements, term by term.

Each symbol has units (``[symbols]``), each coordinate too (``[coordinates] units``; metres or
radians, radians counting as dimensionless). Row :math:`i` of the true equations is a
generalised force dual to :math:`q_i`, of dimension :math:`\mathrm{J}/[q_i]`; a document may
divide or multiply an equation by a dimensional factor (by :math:`m l`, by its inertia), which
is as right as before, so the row's dimension :math:`[F_i]` is the one most of its elements
imply (:meth:`DimensionChecker.row_dimension`; the declared row scale's, where the file
declares one). Then

.. math::

    [A_{ij}] = [F_i]\,\mathrm{s}^2/[q_j],\quad [C_{ij}] = [F_i]\,\mathrm{s}/[q_j],\quad
    [Q_i] = [h_i] = [F_i],\quad [B_{ij}] = [F_i]/[u_j],\quad
    [h_{i,jk}] = [F_i]\,\mathrm{s}^2/([q_j][q_k])

(:math:`h_{i,jk}` the coefficient of :math:`\nu_j\nu_k` in :math:`h_i`, a velocity term
voting as the others do), and every additive term of an element must have its element's
dimension; the argument of a
function (sin, cos, ...) must be dimensionless, except for functions homogeneous in their
arguments (``atan2(y, x)``, ``Abs``, ``Max``, ``Min``, ``sign``), whose arguments must share one
dimension. Dimensions are exponent vectors over
(kg, m, s).
"""

from __future__ import annotations

import functools
from collections.abc import Mapping

import sympy as sp
from sympy.core.function import AppliedUndef

from ...derivations.expressions import parse_units
from ...derivations.schema import Derivation

Dim = tuple[sp.Rational, sp.Rational, sp.Rational]
ZERO: Dim = (sp.Integer(0),) * 3
_BASE: Mapping[str, Dim] = {
    "kg": (1, 0, 0), "m": (0, 1, 0), "s": (0, 0, 1), "N": (1, 1, -2), "J": (1, 2, -2),
    "W": (1, 2, -3), "rad": (0, 0, 0), "A": (0, 0, 0), "V": (1, 2, -3), "K": (0, 0, 0),
    "mol": (0, 0, 0),
}


#: Functions homogeneous in their arguments, which must share one dimension: degree 0 (the
#: value is dimensionless, e.g. the angle atan2(y, x) of a point) or 1 (the value has the
#: arguments' dimension: |x|, max, min).
_HOMOGENEOUS: Mapping[type, int] = {sp.atan2: 0, sp.sign: 0, sp.Abs: 1, sp.Max: 1, sp.Min: 1}


def _add(a: Dim, b: Dim, k=1) -> Dim:
    k = sp.Rational(k)
    return tuple(sp.Rational(x) + k * sp.Rational(y) for x, y in zip(a, b))


@functools.lru_cache(maxsize=1024)
def units_dim(text: str | None) -> Dim | None:
    r"""The dimension of a units text, or None when not given (each text parsed once per
    process: a step file's symbols are looked up at every step)."""
    if text is None:
        return None
    expr = parse_units(str(text))
    dim = ZERO
    for base, exp in expr.as_powers_dict().items():
        if base.is_Number:
            continue
        dim = _add(dim, tuple(sp.Integer(v) for v in _BASE[str(base)]), exp)
    return dim


def format_dim(d: Dim) -> str:
    parts = [f"{n}" if e == 1 else f"{n}^{e}" for n, e in zip(("kg", "m", "s"), d) if e != 0]
    return "·".join(parts) if parts else "dimensionless"


#: The dimension of a model parameter a symbol's value names (``M(link)``, ``CZ(link)``,
#: ``IYY(link)``, Khalil's ``MX(link)`` and ``XX(link)``, lengths, ``g``), by its name.
_PARAMETER_DIMS: Mapping[str, Dim] = {
    **{k: (1, 0, 0) for k in ("M",)},
    **{k: (0, 1, 0) for k in ("CX", "CY", "CZ", "origin_x", "origin_y", "origin_z", "length",
                              "radius", "R", "L", "polar_radius", "surface_radius",
                              "vertex_radius", "tyre_radius")},
    **{k: (1, 1, 0) for k in ("MX", "MY", "MZ")},
    **{k: (1, 2, 0) for k in ("IXX", "IYY", "IZZ", "IXY", "IXZ", "IYZ", "XX", "YY", "ZZ",
                              "XY", "XZ", "YZ")},
    "g": (0, 1, -2)}


def value_dim(value: sp.Expr) -> Dim | None:
    r"""The dimension a symbol's ``value`` gives it from the model parameters it names
    (``CZ(base_link) + 13/200``: a length; a number added to one is taken in its units, as
    a file writes an offset), or None where it names none or they disagree."""
    value = sp.sympify(value)
    if value.is_Number:
        return None
    if value.is_Add:
        dims = {value_dim(t) for t in value.args if not t.is_Number}
        return dims.pop() if len(dims) == 1 else None
    if value.is_Mul:
        total: Dim = ZERO
        for f in value.args:
            if f.is_Number:
                continue
            fd = value_dim(f)
            if fd is None:
                return None
            total = _add(total, fd)
        return total
    if value.is_Pow and value.args[1].is_Number:
        bd = value_dim(value.args[0])
        return None if bd is None else tuple(sp.Rational(x) * sp.Rational(value.args[1])
                                             for x in bd)
    name = value.func.__name__ if isinstance(value, sp.Function) else str(value)
    found = _PARAMETER_DIMS.get(name)
    return None if found is None else tuple(sp.Integer(x) for x in found)


class DimensionChecker:
    r"""Dimensions of the document's names, and the check of an element's terms."""

    def __init__(self, d: Derivation, inferred: bool = False) -> None:
        self._memo: dict[sp.Expr, tuple[Dim | None, list[str]]] = {}
        self.known: dict[sp.Symbol, Dim] = {}
        for spec in d.symbols.values():
            dim = units_dim(spec.units)
            if dim is None and inferred and spec.value is not None:
                dim = value_dim(spec.value)
            if dim is not None:
                self.known[spec.symbol] = dim
        units = d.coordinates.units
        self.q_dims: list[Dim | None] = []
        for q, v, a in zip(d.positions, d.velocities, d.accelerations):
            dim = units_dim(units.get(str(q))) if str(q) in units else None
            self.q_dims.append(dim)
            if dim is not None:
                self.known[q] = dim
                self.known[v] = _add(dim, (0, 0, -1))
                self.known[a] = _add(dim, (0, 0, -2))
        self.input_dims = [self.known.get(u) for u in d.input_symbols]
        joule = tuple(sp.Integer(v) for v in _BASE["J"])
        self.row_dims: list[Dim | None] = [None if qd is None else _add(joule, qd, -1)
                                           for qd in self.q_dims]
        if d.row_scale is not None:            # a declared scale: the row as declared
            for i, factor in enumerate(d.row_scale):
                sd = self.dim(factor, [])
                row = self.row_dims[i]
                self.row_dims[i] = None if sd is None or row is None else _add(row, sd)
        self.declared = d.row_scale is not None

    def implied(self, key: str, index: tuple[int, ...], expr: sp.Expr) -> Dim | None:
        r"""The row dimension an element implies (its own dimension read back through the
        element's place: an inertia element times :math:`[q_j]/\mathrm{s}^2` ...), or None
        when unknown, the element is 0 or its own terms disagree."""
        if sp.sympify(expr) == 0:
            return None
        problems: list[str] = []
        got = self.dim(expr, problems)
        if got is None or problems:           # its own terms disagree: no vote
            return None
        if key == "h" and len(index) == 3:           # the coefficient of ν_j ν_k in h_i
            qj, qk = self.q_dims[index[1]], self.q_dims[index[2]]
            return None if qj is None or qk is None else _add(_add(_add(got, qj), qk),
                                                               (0, 0, -2))
        if key in ("Q", "h"):
            return got
        j = index[1]
        if key == "B":
            u = self.input_dims[j] if j < len(self.input_dims) else None
            return None if u is None else _add(got, u)
        qj = self.q_dims[j]
        if qj is None:
            return None
        return _add(_add(got, qj), (0, 0, {"A": -2, "C": -1, "K": 0}[key]))

    def row_dimension(self, i: int, elements: list[tuple[str, tuple[int, ...], sp.Expr]]
                      ) -> None:
        r"""Set row ``i``'s dimension to the one most of its ``elements`` (key, index,
        expression) imply, the unscaled one on a tie, none on a tie it is not in (a row
        divided by its inertia but for its gravity term, the positions without units: the
        input's vote against the gravity term's; a declared scale is kept). Where the
        positions have no units, the velocity, gravity and input terms vote alone (a torque
        row whose inputs are in N·m: its gravity element's term in N is the odd one, not its
        neighbour in N·m)."""
        if self.declared:
            return
        votes: dict[Dim, int] = {}
        for key, index, expr in elements:
            dim = self.implied(key, index, expr)
            if dim is not None:
                votes[dim] = votes.get(dim, 0) + 1
        if not votes:
            return
        unscaled = self.row_dims[i]
        ranked = sorted(votes.items(), key=lambda kv: (kv[1], kv[0] == unscaled), reverse=True)
        if len(ranked) > 1 and ranked[0][1] == ranked[1][1] and ranked[0][0] != unscaled:
            self.row_dims[i] = None        # a tie nothing breaks: no unit is blamed on either
            return
        self.row_dims[i] = ranked[0][0]

    def dim(self, expr: sp.Expr, problems: list[str]) -> Dim | None:
        r"""Dimension of ``expr``; inconsistent sums and dimensioned function arguments are
        appended to ``problems``. None where a name has no declared units. Remembered per
        subexpression (a solved form repeats its parts many times)."""
        expr = sp.sympify(expr)
        key = expr
        if key in self._memo:
            known, noted = self._memo[key]
            problems += noted
            return known
        said: list[str] = []
        found = self._dim(expr, said)
        self._memo[key] = (found, said)
        problems += said
        return found

    def _dim(self, expr: sp.Expr, problems: list[str]) -> Dim | None:
        if expr.is_Number or expr is sp.pi or expr.is_NumberSymbol:
            return ZERO
        if expr.is_Symbol:
            return self.known.get(expr)
        if expr.is_Add:
            return self._sum_dim(expr, problems)
        if expr.is_Mul:
            return self._product_dim(expr, problems)
        if expr.is_Pow:
            return self._power_dim(expr, problems)
        if expr.func in _HOMOGENEOUS:
            return self._homogeneous_dim(expr, problems)
        if isinstance(expr, sp.Function):
            for arg in expr.args:
                ad = self.dim(arg, problems)
                if ad is not None and ad != ZERO:
                    problems.append(f"argument of {expr.func.__name__}: {sp.sstr(arg)} is "
                                    f"{format_dim(ad)}")
            return ZERO
        return None

    def _sum_dim(self, expr: sp.Expr, problems: list[str]) -> Dim | None:
        r"""A sum's dimension: the one most of its terms have (the others are problems)."""
        dims = [(t, self.dim(t, problems)) for t in expr.args]
        known = [(t, dd) for t, dd in dims if dd is not None]
        if not known:
            return None
        ref = max(known, key=lambda td: sum(1 for t2, d2 in known if d2 == td[1]))[1]
        for t, dd in known:
            if dd != ref:
                problems.append(f"term {sp.sstr(t)} is {format_dim(dd)} beside "
                                f"{format_dim(ref)}")
        return ref

    def _product_dim(self, expr: sp.Expr, problems: list[str]) -> Dim | None:
        total = ZERO
        for f in expr.args:
            fd = self.dim(f, problems)
            if fd is None:
                return None
            total = _add(total, fd)
        return total

    def _power_dim(self, expr: sp.Expr, problems: list[str]) -> Dim | None:
        base, exp = expr.args
        bd = self.dim(base, problems)
        if bd is None:
            return None
        if not exp.is_Number:
            return ZERO if bd == ZERO else None
        return tuple(sp.Rational(x) * sp.Rational(exp) for x in bd)

    def _homogeneous_dim(self, expr: sp.Expr, problems: list[str]) -> Dim | None:
        r"""atan2(y, x), Max, Min: homogeneous of degree 0 or 1 in arguments of one
        dimension."""
        dims = [self.dim(a, problems) for a in expr.args]
        known = [(a, dd) for a, dd in zip(expr.args, dims) if dd is not None]
        for a, dd in known[1:]:
            if dd != known[0][1]:
                problems.append(f"arguments of {expr.func.__name__}: {sp.sstr(a)} is "
                                f"{format_dim(dd)} beside {format_dim(known[0][1])}")
        if _HOMOGENEOUS[expr.func] == 0:
            return ZERO
        return known[0][1] if len(known) == len(dims) else None

    def expected(self, key: str, index: tuple[int, ...]) -> Dim | None:
        i = index[0]
        row = self.row_dims[i]
        if row is None:
            return None
        if key in ("Q", "h"):
            return row
        j = index[1]
        if key == "B":
            u = self.input_dims[j] if j < len(self.input_dims) else None
            return None if u is None else _add(row, u, -1)
        qj = self.q_dims[j]
        if qj is None:
            return None
        return _add(_add(row, qj, -1), (0, 0, {"A": 2, "C": 1, "K": 0}[key]))

    def check(self, key: str, index: tuple[int, ...], expr: sp.Expr) -> list[str]:
        r"""Problems of one element: inconsistent terms, or a dimension other than expected.
        Where the row says what the element's dimension is and one of its terms has it, the
        terms named are those that do not (not those fewer than the others: in I2*L1 +
        L1*a2*m2, written for (I2 + a2²m2) L1/a2, the wrong one)."""
        problems: list[str] = []
        want = self.expected(key, index)
        e = sp.sympify(expr)
        if want is not None and isinstance(e, sp.Add):
            dims = [(t, self.dim(t, problems)) for t in e.args]
            if any(d == want for _, d in dims):
                return problems + [f"term {sp.sstr(t)} is {format_dim(d)} beside "
                                   f"{format_dim(want)}" for t, d in dims
                                   if d is not None and d != want]
        got = self.dim(expr, problems)
        if got is not None and want is not None and got != want and sp.sympify(expr) != 0:
            problems.append(f"has {format_dim(got)}, expected {format_dim(want)}")
        return problems


def contradicted_units(d: Derivation) -> list[tuple[str, str, Dim, Dim]]:
    r"""The symbols whose declared units contradict the link and joint parameters their value
    names (``I_b = { value = "IYY(body)", units = "kg*m" }``; a value with a plain name, R or
    a gear ratio a model calls L, is not judged: the model's ``[geometry]`` says what it is):
    (name, value as written, declared dimension, the value's), in the file's order. Both are
    the file's: the verdicts stand under the declared values, and the units are the file's to
    mend."""
    out = []
    for name, spec in d.symbols.items():
        declared = units_dim(spec.units) if spec.units else None
        if declared is None or spec.value is None:
            continue
        value = sp.sympify(spec.value)
        calls = value.atoms(AppliedUndef)
        if value.free_symbols - set().union(*(c.free_symbols for c in calls)):
            continue          # a plain name (R, L, G): what it is, the model's [geometry] says
        given = value_dim(value)
        if given is not None and tuple(map(sp.Rational, given)) != \
                tuple(map(sp.Rational, declared)):
            out.append((name, sp.sstr(spec.value), declared, given))
    return out


def geometric_symbols(d: Derivation) -> set[sp.Symbol]:
    r"""The document's positions and its symbols measured in metres (or dimensionless)."""
    out = set(d.positions)
    for spec in d.symbols.values():
        dim = units_dim(spec.units) if spec.units else None
        if dim is not None and dim[0] == 0 and dim[2] == 0:
            out.add(spec.symbol)
    return out
