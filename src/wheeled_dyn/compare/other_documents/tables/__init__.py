r"""Reproducing a hand-made comparison table: :func:`reproduce_table`.

Seed 001 ends with a table comparing its eq. (25) (the *derived* document) with the appendix's
A and C of Kim et al. (the *reference*, "[1]") element by element, after a substitution printed
above the table (a body symmetric about its mid-plane, centre of mass straight above the axle:
:math:`MX_1 = MZ_1 = XY_1 = XZ_1 = YZ_1 = 0`, :math:`MY_1 = m_S d`, ...), and lists the
mismatched elements and the resulting differences in each equation. This module does the same by
machine and sets the two side by side:

1. **The table's assumptions.** The substitution is turned into the smallest combination of the
   model's special parameter families (:func:`~wheeled_dyn.compare.grid.samples.special_cases`) under
   which every substituted symbol's model value equals its substitution, checked on random
   parameter sets (a substitution no family satisfies is an error of the table file). Cases in
   ``also_assume`` are added (by default no motor armature: neither document models the motors).
2. **Document against document.** Both documents' A and C, as printed, at random states and
   parameter sets of that family; each document's rows divided by the constant the engine
   finds (:attr:`DerivationResult.row_factors`: −1 for Kane's generalised inertia forces
   :math:`F^* = -(A\ddot q + h)`), checked under the family, where the row's A must be exactly
   that constant times the truth's (the engine decides in general parameters, where a document
   lacking an effect the model has, e.g. the motor armature, can blur the vote; a factor found
   only under the family is used and noted). An element *matches* or is a *mismatch*; a C
   element whose row has the same :math:`C\dot q` in both is a *factorisation* difference
   only.
3. **Against the truth.** Each document's element against the truth at the same samples
   (:class:`~wheeled_dyn.constraints.CoordinateMap`): which of the two is right under the
   table's assumptions; the engine's verdict in general parameters is quoted beside it.
4. **Against the printed table.** The table's mismatched list, its cells (are they the documents
   as printed?) and its "resulting differences", equation by equation; every place where the
   machine and the table part ways comes with an explanation.

Expressions shown are in the table's namespace after its substitution (the "equivalent form").
"""

from __future__ import annotations

from .records import MACHINE_VERDICTS, EquationDifference, TableReproduction, TableRow
from .reproduce import ALSO_ASSUMED, FAMILY_SETS, FAMILY_STATES, reproduce_table
from .text import CHECK_POINTS, CHECK_TOL, SHOWN

__all__ = ["ALSO_ASSUMED", "CHECK_POINTS", "CHECK_TOL", "FAMILY_SETS", "FAMILY_STATES",
           "MACHINE_VERDICTS", "SHOWN", "EquationDifference", "TableReproduction", "TableRow",
           "reproduce_table"]
