r"""The truth a linearised document is compared with, in closed form for the reports.

A document that declares ``linearised_about`` (positions :math:`q^*`) is judged against the
truth's linearisation there (:mod:`..grid.assumptions`): A and B at :math:`q^*`, no velocity
products, Q at :math:`q^*` and its stiffness :math:`K = \partial Q/\partial q` there. Its report
shows the same: every true element at :math:`q^*`, C and h zero, and

.. math::

    Q_{lin} = Q(q^*) + \sum_j K_{ij}(q^*)\,(q_j - q_j^*), \qquad
    K_{ij} = \frac{\partial Q_i}{\partial q_j}\Big|_{q^*},

so that truth − document names the stiffness a document got wrong. With a potential measured
from the equilibrium (``potential = "equilibrium"``) the gravity of :math:`Q(q^*)` is left out
(springs the model lacks balance it there), the model's own springs' force there kept; K is
compared and shown as always (the springs' own stiffness is the document's to give in
``[assume]``: 0 where the model has none).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import sympy as sp

from ...derivations.state_space import point_value


def linearised_truth(truth: Mapping[str, sp.Expr], positions: Sequence[sp.Symbol],
                     point: Sequence[tuple[str, float]], equilibrium: bool = False,
                     gravity: frozenset[str] = frozenset()) -> dict[str, sp.Expr]:
    r"""The true elements (labels as the engine's: ``A[1,2]``, ``h[1]:dx*dpsi``, ``Q[3]``)
    linearised about ``point`` (module text), with ``K[i,j]`` added; ``equilibrium``: no
    gravity in :math:`Q(q^*)` (the symbols named in ``gravity`` taken 0 there)."""
    values = dict(point)
    at = {p: point_value(values[p.name]) for p in positions if p.name in values}
    out: dict[str, sp.Expr] = {}
    for label, expr in truth.items():
        key = label.partition("[")[0]
        e = sp.sympify(expr)
        if key in ("C", "h"):
            out[label] = sp.Integer(0)
            continue
        if key != "Q":
            out[label] = e.xreplace(at)
            continue
        row = label.partition("[")[2].partition("]")[0]
        slopes = [sp.diff(e, p).xreplace(at) for p in positions]
        base = e.xreplace(at)
        if equilibrium:                  # the model's springs' force at the point stays
            base = base.xreplace({x: 0 for x in base.free_symbols if x.name in gravity})
        out[label] = base + sp.Add(*(k * (p - at[p]) for k, p in zip(slopes, positions)
                                     if p in at))
        for j, k in enumerate(slopes):
            out[f"K[{row},{j + 1}]"] = k
    return out


__all__ = ["linearised_truth"]
