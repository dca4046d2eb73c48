r"""A linearised document whose equations are those about another point: a cause, never a
verdict.

A file declaring ``linearised_about`` a point with a position not 0 (a pendulum about
:math:`\theta = 0.5`) whose equations differ is judged again, as a reading, linearised about
every position 0: the most common slip, small angles taken about rest when the point is
another. Where every equation is right there, the first cause (``file_error``) says so —
"the equations are the linearisation about th1 = 0, th2 = 0, where every equation is right
(0 of 2 about the declared point)" — and the verdicts stay as declared. Small-angle readings
(x written where sin x fits) are not tried on a linearised document: its positions are drawn
at the point, where such a reading holds by coincidence.
"""

from __future__ import annotations

from dataclasses import replace
from types import MappingProxyType

from ...derivations.schema import Derivation
from ..grid.assumptions import declared
from ..records import Cause, CauseKind, Verdict


def point_finding(engine, d: Derivation, j) -> Cause | None:
    r"""The cause where ``d`` (judged as ``j``, not right) declares a linearisation point
    with a position not 0 and its equations are all right linearised about 0; else None."""
    point = declared(d).linearised_about
    if not point or all(value == 0.0 for _, value in point):
        return None
    zero = {name: 0.0 for name, _ in point}
    about_zero = replace(d, assumes=MappingProxyType({**dict(d.assumes),
                                                      "linearised_about": zero}))
    better = engine.judge(about_zero).result
    if not better.equivalent:
        return None
    n = len(j.result.equations)
    right = sum(e.verdict == Verdict.AGREES for e in j.result.equations)
    declared_text = ", ".join(f"{name} = {value:g}" for name, value in point)
    zero_text = ", ".join(f"{name} = 0" for name in zero)
    return Cause(CauseKind.FILE_ERROR, (), (
        f"the file declares its equations linearised about {declared_text}, but they are the "
        f"linearisation about {zero_text}: there every equation is right ({right} of {n} "
        "about the declared point); the verdicts are under the file's declaration (declare "
        "the point the document linearises about)"))


__all__ = ["point_finding"]
