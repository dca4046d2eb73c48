r"""A body's own inertia: every link's moments about its centre of mass (and their
parallel-axis parts), and a residual fitted as one of them times a multiplier — the
document treating the body as a point mass (:mod:`.named`, :mod:`.unsolved`)."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import sympy as sp

from .fitting import RATIO_TOL, fit_factor

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


def bodies(name: str) -> str:
    r"""``"link1 as a point mass"``, ``"wheel_left and wheel_right as point masses"`` for
    the moments ``name`` (``Izz(wheel_left) + Izz(wheel_right)``) of :func:`own_moments`."""
    links = list(dict.fromkeys(one[one.index("(") + 1:-1] for one in name.split(" + ")))
    return f"{links[0]} as a point mass" if len(links) == 1 else \
        f"{' and '.join(links)} as point masses"


__all__ = ["AXES", "bodies", "own_moments", "point_mass_fit"]
