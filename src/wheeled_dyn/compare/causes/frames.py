r"""Causes from the equations as a whole: the frames the equations were explained in, the
equations that are not equivalent because :math:`W` is singular, and declarations the
equations contradict.

- a row that is not the true equation itself (divided by a function, reordered, combined,
  solved for the accelerations) is one ``convention`` cause naming the frames: it explains
  how the elements are compared, it changes no verdict (an equivalent form is as right as
  the true one, :mod:`..judge.equivalence`);
- equations multiplied by a factor that vanishes somewhere, lost or repeated: a
  ``not_equivalent`` cause naming them;
- a row scale the file declares that the equation contradicts, although the equation as
  printed is right: the equation differs as declared (declarations bind), and a
  ``file_error`` cause says the declaration is probably wrong.
"""

from __future__ import annotations

from collections.abc import Sequence


from ...derivations.schema import Derivation
from ..readings.describe import FrameText
from ..readings.frames import FrameKind, FrameRule
from ..records import (Cause, CauseKind, DiagnosisKind as K, ElementRecord, EquationRecord,
                       Verdict, first_of)


def frame_causes(d: Derivation, texts: Sequence[FrameText], rules: Sequence[FrameRule],
                 equations: Sequence[EquationRecord], declared_wrong: Sequence[int] = (),
                 records: Sequence[ElementRecord] = ()) -> list[Cause]:
    r"""The causes of the module text; and an equation that is no combination of the true
    ones while every element of its row agrees in its frame (its multiplier terms, a
    difference below each element's tolerance) is its own ``not_equivalent`` cause: a verdict
    is never left without one."""
    out: list[Cause] = []
    for e in equations:
        why = first_of(e.diagnoses, K.NOT_EQUIVALENT)
        if why is not None and not any(r.index[0] == e.index and r.verdict != Verdict.AGREES
                                       for r in records if r.key in "ACQBhK"):
            out.append(Cause(CauseKind.NOT_EQUIVALENT, (e.label,), why.detail))
    shown = [f"equation {i + 1} is {t.text}" if not t.text.startswith("=") else
             f"equation {i + 1} {t.text}"
             for i, (t, r) in enumerate(zip(texts, rules))
             if t.text and r.kind not in (FrameKind.IDENTITY, FrameKind.DECLARED)
             and not (r.kind == FrameKind.CONSTANT and r.partner == i)]
    # singular W is its own cause only where the equations are otherwise combinations of the
    # true ones (scaled by a vanishing factor, lost, repeated); where an equation is no
    # combination, its terms say why (a singular A_doc follows from them)
    singular = [e for e in equations if first_of(e.diagnoses, K.SINGULAR) is not None
                and first_of(e.diagnoses, K.NOT_EQUIVALENT) is None]
    if shown:
        out.append(Cause(CauseKind.CONVENTION, (), "; ".join(shown) + ": its elements are "
                         "compared in that frame" + ("" if singular else (
                             " (an equation divided by a quantity that does not vanish, or "
                             "replaced by an invertible combination of the equations, has the "
                             "same solutions)"))))
    if singular:
        why = first_of(singular[0].diagnoses, K.SINGULAR)
        out.append(Cause(CauseKind.NOT_EQUIVALENT, tuple(e.label for e in singular),
                         why.detail if why is not None else ""))
    for i in declared_wrong:
        found = first_of(equations[i].diagnoses, K.DECLARED) if i < len(equations) else None
        if found is not None:        # its elements differ for it alone (declared_only)
            elements = tuple(r.element for r in records if r.key in "ACQBhK"
                             and r.index[0] == i and r.verdict != Verdict.AGREES)
            out.append(Cause(CauseKind.FILE_ERROR, (equations[i].label, *elements),
                             found.detail))
    return out


__all__ = ["frame_causes"]
