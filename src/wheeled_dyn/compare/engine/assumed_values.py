r"""The terms a file sets in ``[assume]`` to a value other than zero: what the equations owe them.

``[assume]`` gives a value to a term of the document the model lacks (a friction torque, an
external force, a spring): the truth has no such term, so for the model its value is 0. A
file that sets one to another value is judged as it declares (declarations are binding), but
that value can make any difference agree: :math:`2\,m g l\cos q_1 + F_d` with
:math:`F_d = -m g l\cos q_1` is the truth's term. So each equation is decided once more with
those terms at 0 (:func:`~.deciding.decide` on the same grid): one that agrees only with the
file's values *agrees only if* they hold, and the cause says which values and which
equations; an equation that agrees either way owes them nothing.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import replace
from types import MappingProxyType

import sympy as sp

from ...derivations.schema import Derivation
from ..records import Cause, CauseKind, Verdict
from ..sides.both import Sides, both_sides
from ..sides.document import DocumentFunctions


def nonzero_assumed(d: Derivation) -> dict[str, sp.Expr]:
    r"""The ``[assume]`` terms the file sets to a value other than 0."""
    return {k: v for k, v in d.assumptions.items() if sp.sympify(v) != 0}


def assumed_text(values: Mapping[str, sp.Expr]) -> str:
    r"""The condition said for an equation that owes its agreement to ``values``."""
    return ", ".join(f"{k} = {sp.sstr(v)}" for k, v in values.items()) + \
        " (the file's [assume]: a term the model lacks, 0 in its truth)"


def owed_equations(d: Derivation, grids: Sequence[Sides], seed: int, decision,
                   funcs: DocumentFunctions) -> frozenset[int]:
    r"""The equations (0-based) that agree as declared and not with the file's nonzero
    ``[assume]`` terms at 0 (module text), on the main grid (``decision``) or on the
    undeclared families' grid (where an equation *agrees only if* a family); empty where the
    file sets none to another value."""
    values = nonzero_assumed(d)
    if not values or decision is None:
        return frozenset()
    from .deciding import decide
    from .judgement import document_functions
    zeroed = replace(d, assumptions=MappingProxyType(
        {k: (sp.Integer(0) if k in values else v) for k, v in d.assumptions.items()}))
    zero_funcs = document_functions(zeroed)
    owed: set[int] = set()
    for k, sides in enumerate(grids):
        declared = decision if k == 0 else decide(d, funcs, sides, seed)
        without = decide(zeroed, zero_funcs, both_sides(zeroed, zero_funcs, sides.grid, seed),
                         seed)
        if declared is None or without is None:
            continue
        owed |= {i for i, (e, e0) in enumerate(zip(declared.equations, without.equations))
                 if e.verdict in (Verdict.AGREES, Verdict.AGREES_IF)
                 and e0.verdict == Verdict.DIFFERS}
    return frozenset(owed)


def assumed_cause(d: Derivation, owed: frozenset[int]) -> tuple[Cause, ...]:
    r"""The cause of the equations that owe their agreement to the file's nonzero
    ``[assume]`` values (none where none does)."""
    if not owed:
        return ()
    which = ", ".join(f"equation {i + 1}" for i in sorted(owed))
    return (Cause(CauseKind.ASSUMPTION, (), (
        f"{which} agree{'s' if len(owed) == 1 else ''} only with "
        f"{assumed_text(nonzero_assumed(d))}: with those terms at 0, as the model has them, "
        f"{'it differs' if len(owed) == 1 else 'they differ'} — the values stand for terms "
        "of the equations themselves")),)


__all__ = ["assumed_cause", "assumed_text", "nonzero_assumed", "owed_equations"]
