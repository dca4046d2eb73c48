r"""A body's own inertia: every link's moments about its centre of mass (and their
parallel-axis parts), and a residual fitted as one of them times a multiplier — the
document treating the body as a point mass (:mod:`.named`, :mod:`.unsolved`)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np
import sympy as sp

from ...expression_size import ops_over
from ..records import DiagnosisKind as K
from .fitting import RATIO_TOL, evaluated, fit_factor, symbol_values

#: Axes of a link's own moments of inertia.
AXES = ("x", "y", "z")


def own_moments(values: Sequence[Mapping[str, float]], states: int, parallel: bool = False
                ) -> dict[str, np.ndarray]:
    r"""Every link's moments about its centre of mass along its own axes, per sample of a grid
    (``values``: each parameter set's namespace values; ``states`` per set):
    :math:`I_{xx,c} = XX - (MY^2 + MZ^2)/M` and likewise; with ``parallel`` their
    parallel-axis parts instead, :math:`(MY^2 + MZ^2)/M = M (c_y^2 + c_z^2)` (keys
    ``Pxx(link)``), and each part :math:`M c_y^2` (``P:y(link)``, once for both axes it
    belongs to)."""
    links = sorted({k[2:-1] for k in values[0] if k.startswith("M(")})
    out: dict[str, np.ndarray] = {}
    for link in links:
        for a, axis in enumerate(AXES):
            others = [x for x in AXES if x != axis]
            vals = []
            parts: dict[str, list[float]] = {}
            for v in values:
                m = v.get(f"M({link})", 0.0)
                first = [v.get(f"M{o.upper()}({link})", 0.0) for o in others]
                moment = v.get(f"{axis.upper() * 2}({link})", 0.0)
                shift = sum(f * f for f in first) / m if m > 0 else 0.0
                vals.append(shift if parallel else moment - shift if m > 0 else 0.0)
                for o, f in zip(others, first):
                    parts.setdefault(o, []).append(f * f / m if m > 0 else 0.0)
            arr = np.repeat(np.asarray(vals, float), states)
            if np.abs(arr).max(initial=0.0) > 0:
                out[f"{'P' if parallel else 'I'}{axis}{axis}({link})"] = arr
            for o, part in parts.items() if parallel else ():
                arr = np.repeat(np.asarray(part, float), states)
                if np.abs(arr).max(initial=0.0) > 0:
                    out[f"P:{o}({link})"] = arr
    return out


def point_mass_fit(residual: np.ndarray, moments: Mapping[str, np.ndarray],
                   bases: Sequence[tuple[sp.Expr, np.ndarray]]) -> tuple[str, sp.Expr] | None:
    r"""``(moment name(s), multiplier)`` with :math:`\Delta` = multiplier × moment(s); the
    multiplier a simple rational, or a monomial in ``bases`` (the document's lengths and
    positions: geometry, never another inertia)."""
    items = list(moments.items())
    trials = [(name, v) for name, v in items]
    trials += [(f"{a} + {b}", va + vb) for k, (a, va) in enumerate(items)
               for b, vb in items[k + 1:] if a[:3] == b[:3]]
    found: list[tuple[str, sp.Expr]] = []
    for name, v in trials:
        if np.abs(v).min() <= 0:
            continue
        ratio = residual / v
        if np.ptp(ratio) <= RATIO_TOL * np.abs(ratio).max():
            c = sp.nsimplify(float(np.median(ratio)), rational=True, tolerance=1e-9)
            if c != 0 and abs(float(c) - float(np.median(ratio))) <= 1e-9 * abs(float(c)) \
                    and _plausible(sp.Rational(c)):
                found.append((name, c))
                continue
        fitted = fit_factor(ratio, bases)
        if fitted is not None and not fitted.is_number:   # a number: the plausible ones above
            found.append((name, fitted))
    # a moment the document lacks (never one it has too much: that is no point mass); where
    # several fit (a family keeps a body's moments proportional), the simplest multiplier
    lacking = [(name, c) for name, c in found if not c.could_extract_minus_sign()]
    return min(lacking, key=lambda f: _plainness(f[1]), default=None)


def _plausible(c: sp.Rational) -> bool:
    r"""A number a body's own moment is missing times: a whole one up to four (two wheels'
    alike, a rod's :math:`ml^2/4` = 3 × its own), or a part of one (:math:`mr^2/4`, half a
    cylinder's axial moment); not 253/6 (a moment of another axis that a link's proportions,
    kept in every draw, make any residual a multiple of)."""
    return (c.q == 1 and 1 <= abs(c.p) <= 4) or (abs(c) < 1 and c.q <= 12)


def _plainness(c: sp.Expr) -> tuple[int, int]:
    r"""How plain a multiplier is: its operations, then its rational coefficient's size."""
    coeff = c.as_coeff_Mul()[0]
    size = int(abs(coeff.p) + coeff.q) if isinstance(coeff, sp.Rational) else 10 ** 6
    return int(sp.count_ops(c)), size


@dataclass(frozen=True)
class OwnInertia:
    r"""What a residual is compared with as a body's own inertia, on one grid: every link's
    moments about its centre of mass and its parallel-axis parts (:func:`own_moments`), and
    the document's lengths a multiplier may be a monomial of (:func:`length_bases`), and
    the parameter set of each sample (``sets``, its index; None: not known)."""

    moments: Mapping[str, np.ndarray]
    parallel: Mapping[str, np.ndarray]
    lengths: Sequence[tuple[sp.Expr, np.ndarray]]
    sets: np.ndarray | None = None

    def at(self, rows: np.ndarray) -> "OwnInertia":
        r"""The same at the samples ``rows``."""
        return OwnInertia({k: v[rows] for k, v in self.moments.items()},
                          {k: v[rows] for k, v in self.parallel.items()},
                          [(e, v[rows]) for e, v in self.lengths],
                          None if self.sets is None else self.sets[rows])


def grid_inertia(values: Sequence[Mapping[str, float]], samples: int,
                 lengths: Sequence[tuple[sp.Expr, np.ndarray]] = ()) -> OwnInertia:
    r""":class:`OwnInertia` on a grid of ``samples`` states spread over the parameter sets of
    ``values`` (each set's namespace values)."""
    states = samples // max(len(values), 1)
    return OwnInertia(own_moments(values, states), own_moments(values, states, True),
                      list(lengths), set_indices(len(values), states))


def length_bases(bases: Sequence[tuple[sp.Expr, np.ndarray]], geometric: set[sp.Symbol],
                 positions: Sequence[sp.Symbol] = ()) -> list[tuple[sp.Expr, np.ndarray]]:
    r"""The ``bases`` (:func:`~.fitting.bases`) of the document's lengths alone (``geometric``;
    no position: a body's own inertia enters the inertia matrix as a constant times lengths)."""
    return [(e, v) for e, v in bases if e.free_symbols <= geometric and not e.has(*positions)]


def _whole(multiplier: sp.Expr) -> bool:
    r"""Whether a moment's ``multiplier`` is 1 or a monomial of lengths with coefficient 1
    (:math:`R^{-2}` in heading coordinates): the whole moment, never a part of it."""
    return multiplier == 1 or (not multiplier.is_number and multiplier.as_coeff_Mul()[0] == 1)


def own_reading(residual: np.ndarray, own: OwnInertia) -> tuple[K, str, sp.Expr] | None:
    r"""What truth − document ``residual`` (an entry of an inertia matrix) is as a body's own
    inertia: ``(POINT_MASS, moment name(s), multiplier)`` where it is a moment times 1 or
    times a monomial of lengths with coefficient 1 (:math:`2J_w/r^2` in heading coordinates);
    else ``(PARALLEL_AXIS, name, 1)`` where it is a parallel-axis term; else None (a
    number other than 1 times a moment is said by the element's own naming, which weighs it
    against the document's symbols)."""
    hit = point_mass_fit(residual, own.moments, own.lengths) if own.moments else None
    if hit is not None and _whole(hit[1]):
        return K.POINT_MASS, hit[0], hit[1]
    steiner = point_mass_fit(residual, own.parallel, own.lengths) if own.parallel else None
    if steiner is not None and steiner[1] == 1:
        return K.PARALLEL_AXIS, steiner[0], steiner[1]
    return None


#: Parts of a written term tried as the one written for a body's own moment: p/q, q at most
#: this (the m_w of 3 m_w, a wheel's m r²/2 counted with the body's mass).
FORMULA_PARTS = 6


@dataclass(frozen=True)
class FormulaReading:
    r"""A part of a written term found where a body's own moment fits: truth − document
    :math:`= \lambda I - c\,t` at every sample, ``written`` = :math:`c\,t` in the
    document's symbols, ``term`` = :math:`t` as written, ``name`` the moment(s) :math:`I`
    (:func:`own_moments`) and ``multiplier`` :math:`\lambda` (1, or a monomial of lengths
    with coefficient 1)."""

    written: sp.Expr
    term: sp.Expr
    name: str
    multiplier: sp.Expr
    #: :math:`\lambda I` at each sample (what fits where :attr:`written` stands)
    fit_values: np.ndarray = field(default_factory=lambda: np.zeros(0), compare=False,
                                   repr=False)

    @property
    def times(self) -> str:
        r"""The multiplier as said after the moment: ``" × R**(-2)"``, ``""`` for 1."""
        return "" if self.multiplier == 1 else f" × {sp.sstr(self.multiplier)}"

    @property
    def fits(self) -> str:
        r"""What fits where :attr:`written` stands: ``"Iyy(left_wheel) × R**(-2)"``."""
        return f"{self.name}{self.times}"


def formula_reading(residual: np.ndarray, terms: Sequence[tuple[sp.Expr, np.ndarray]],
                    moments: Mapping[str, np.ndarray],
                    lengths: Sequence[tuple[sp.Expr, np.ndarray]],
                    sets: np.ndarray | None) -> FormulaReading | None:
    r"""The written term (or the part :math:`c = p/q`, :math:`q \le` :data:`FORMULA_PARTS`,
    of one) that truth − document ``residual`` says stands where a body's own moment
    belongs: :math:`\Delta + c\,t` is a moment times 1 or a coefficient-1 monomial of
    ``lengths`` (:func:`point_mass_fit`) — a formula for the moment (a uniform body's,
    :math:`m r^2/2`) written for one that does not follow it. ``terms``: the document's
    element's terms with their values (none 0 at a sample); ``sets`` the parameter set of
    each sample (None: no reading). A moment and lengths are the same at every state of a
    set, and so is a formula for it: a residual or a term that is not is none. The first
    term and the largest part found, or None; never a term the residual is a multiple of,
    nor one that is itself a moment times lengths (``Th_k`` written where ``Th_k/r**2``
    fits: the moment, not a formula for it; its lengths are what is wrong)."""
    if sets is None or not _per_set(residual, sets):
        return None
    parts = sorted({sp.Rational(p, q) for q in range(1, FORMULA_PARTS + 1)
                    for p in range(1, q + 1)}, reverse=True)
    for term, values in terms:
        if not _per_set(values, sets) or point_mass_fit(values, moments, lengths) is not None:
            continue             # (the moment itself, with other lengths: no formula for it)
        ratio = residual / values
        if np.ptp(ratio) <= RATIO_TOL * np.abs(ratio).max():
            continue             # the term times a number: a factor (or moments a family
        for c in parts:          # keeps proportional to it, which no values can tell)
            combined = residual + float(c) * values
            if combined.min() <= 0:
                continue         # a moment times lengths is positive
            hit = point_mass_fit(combined, moments, lengths)
            if hit is not None and _whole(hit[1]):
                return FormulaReading(c * term, term, hit[0], hit[1], combined)
    return None


#: Largest expressions (operations) whose terms are evaluated one by one.
MAX_TERM_OPS = 200


def term_values(expr: sp.Expr, bases: Sequence[tuple[sp.Expr, np.ndarray]]
                    ) -> list[tuple[sp.Expr, np.ndarray]]:
    r"""The terms of ``expr`` (multiplied out; none of more than :data:`MAX_TERM_OPS`
    operations) with their values on the grid of ``bases`` — those
    whose symbols all have values there, and which are 0 at no sample."""
    values = symbol_values(bases)
    if ops_over(expr, MAX_TERM_OPS) or not values:
        return []
    shape = next(iter(values.values())).shape
    out = []
    for term in sp.Add.make_args(sp.expand(expr)):
        v = None if term.is_number else evaluated(term, values, shape)
        if v is not None and np.isfinite(v).all() and np.abs(v).min() > 0:
            out.append((term, v))
    return out


def formula_phrase(f: FormulaReading, of: str = "", symbols: sp.Expr | None = None) -> str:
    r"""``"m_w (of its 3*m_w) where the moment of inertia … fits: …"``: what the document has
    (``of``: the term it is a part of, as written) where a body's own moment fits
    (``symbols``: that moment in the document's symbols, where it has them)."""
    own = f" ({sp.sstr(symbols)} in the document's symbols)" if symbols is not None else ""
    return (f"{sp.sstr(f.written)}{of} where the moment of inertia {f.name} about its own "
            f"centre of mass{f.times}{own} fits: a formula for it (as for a uniform body) that "
            "the model's parameter sets do not keep")


def set_indices(sets: int, states: int) -> np.ndarray:
    r"""The parameter set of each sample of a grid of ``states`` samples per set, a set's
    together (as :func:`own_moments` repeats a set's moments)."""
    return np.repeat(np.arange(sets), states)


def _per_set(values: np.ndarray, sets: np.ndarray) -> bool:
    r"""Whether ``values`` are the same at every sample of each parameter set (``sets``: the
    set of each sample), to :data:`~.fitting.RATIO_TOL` of their largest."""
    tol = RATIO_TOL * float(np.abs(values).max(initial=0.0))
    return len(values) == len(sets) and all(
        np.ptp(values[sets == k]) <= tol for k in np.unique(sets))


def same_parts(name: str, parallel: Mapping[str, np.ndarray]) -> str:
    r"""The axes (letters) of the link's other parallel-axis terms equal to ``name``'s at every
    sample (a centre of mass on one axis: the terms about the two others are the same
    number, and which one the element needs its values cannot tell)."""
    if " + " in name or name[1] == ":" or name not in parallel:
        return ""
    link = name[name.index("("):]
    return "".join(a for a in AXES if a != name[1] and f"P{a}{a}{link}" in parallel
                   and np.allclose(parallel[f"P{a}{a}{link}"], parallel[name], rtol=1e-12,
                                   atol=0.0))


def parallel_phrase(name: str, also: str = "") -> str:
    r"""``"the parallel-axis term of bob about its y axis"`` for the parallel-axis part(s)
    ``name`` of :func:`own_moments` (``Pyy(bob)``; ``P:z(bob)``: the part :math:`Mc_z^2`;
    ``also``: other axes whose terms are the same number)."""
    parts = []
    for one in name.split(" + "):
        link = one[one.index("(") + 1:-1]
        axes = " or ".join((one[1], *also)) if one[1] != ":" else ""
        parts.append(f"the part M c_{one[2]}² of {link}'s parallel-axis term" if one[1] == ":"
                     else f"the parallel-axis term of {link} about its {axes} axis")
    return " and ".join(parts)


def bodies(name: str) -> str:
    r"""``"link1 as a point mass"``, ``"wheel_left and wheel_right as point masses"`` for
    the moments ``name`` (``Izz(wheel_left) + Izz(wheel_right)``) of :func:`own_moments`."""
    links = list(dict.fromkeys(one[one.index("(") + 1:-1] for one in name.split(" + ")))
    return f"{links[0]} as a point mass" if len(links) == 1 else \
        f"{' and '.join(links)} as point masses"


__all__ = ["AXES", "FORMULA_PARTS", "MAX_TERM_OPS", "FormulaReading", "OwnInertia", "bodies",
           "formula_phrase", "formula_reading", "grid_inertia", "length_bases", "own_moments",
           "own_reading", "parallel_phrase", "point_mass_fit", "same_parts", "set_indices",
           "term_values"]
