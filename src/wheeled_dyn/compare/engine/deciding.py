r"""The equivalence decision of a document's equations on the main grid
(:func:`~..judge.equivalence.decide`): its sides as arrays (:math:`n = h + Q`, a linearised
document's stiffness beside its inputs, the multipliers' coefficients of a form that keeps the
rolling constraints) and, where an equation's weights :math:`W = A_{doc}A^{-1}` vary, the
states (:mod:`.special`) and the robots (:mod:`.parameter_factors`) at which a factor of them
may vanish.
"""

from __future__ import annotations

import copy

import numpy as np
import sympy as sp

from ...derivations.schema import Derivation
from ..judge import equivalence
from ..records import DiagnosisKind, Verdict, has_kind
from ..sides.both import Sides
from ..sides.document import DocumentFunctions
from .frames import declared_weights
from .parameter_factors import Robots, Vanishing, robot_sign_changes, vanishing_factors
from .special import special_sides


def _n(a, B, multipliers: bool = False) -> equivalence.Side | None:
    r"""An :class:`~..judge.equivalence.Side` of arrays ``a`` (n = h + Q where given; a
    linearised document's stiffness K compared with its inputs' columns; with
    ``multipliers``, the coefficients :math:`G^T` of the multipliers)."""
    if a.A is None:
        return None
    parts = [x for x in (a.h, a.Q) if x is not None]
    n = None if not parts else sum(parts[1:], parts[0])
    L = np.swapaxes(a.G, 1, 2) if multipliers and a.G is not None else None
    return equivalence.Side(a.A, n, _with_stiffness(a.K, B), L)


def _with_stiffness(K: np.ndarray | None, B: np.ndarray | None) -> np.ndarray | None:
    if K is None:
        return B
    return K if B is None else np.concatenate([K, B], axis=2)


def _lost(i: int, v: Vanishing) -> str:
    r"""Why equation ``i`` is lost (or undefined) where its factor ``v`` vanishes."""
    robots = {Robots.LENGTHS: "lengths the robot may have (each of its lengths between a "
              "tenth and ten times the model's)", Robots.MASSES: "masses and inertias the "
              "robot may have (its links' masses and inertias changed, its lengths kept)",
              Robots.DRAWN: "a robot between two of the parameter sets drawn (it takes both "
              "signs among them)"}[v.robots]
    return (f"equation {i + 1} is not {'defined' if v.divided else 'independent'} for every "
            f"robot of the model: its inertia terms "
            f"{'are divided by' if v.divided else 'share the factor'} {sp.sstr(v.factor)}, "
            f"which vanishes for {robots}, where W = A_doc A⁻¹ is "
            f"{'unbounded' if v.divided else 'singular'} (an equation "
            f"{'divided' if v.divided else 'multiplied'} by a factor that vanishes)")


def _without(side: equivalence.Side, funcs: DocumentFunctions, sides: Sides,
             found: dict[int, Vanishing]) -> tuple[equivalence.Side, np.ndarray]:
    r"""``side`` with each row of ``found`` divided by its factor (multiplied, where the row
    is divided by it), at every sample; and what each row was multiplied by (S × n)."""
    scale = np.ones((len(side.A), side.A.shape[1]))
    for i, v in found.items():
        with np.errstate(all="ignore"):
            f = np.broadcast_to(np.asarray(funcs.compiled(v.factor)(*sides.argv), float),
                                (len(side.A),))
        scale[:, i] = f if v.divided else 1.0 / f

    def rows(M: np.ndarray | None) -> np.ndarray | None:
        return None if M is None else M * scale.reshape(scale.shape + (1,) * (M.ndim - 2))
    return equivalence.Side(side.A * scale[:, :, None], rows(side.n), rows(side.B),
                            rows(side.L)), scale


def decide(d: Derivation, funcs: DocumentFunctions, sides: Sides, seed: int = 2026
           ) -> equivalence.SystemDecision | None:
    r"""The equations' verdicts on the main grid (None where the document gives no A); where
    an equation's weights vary, with the special states and the robots at which a factor of
    them may vanish (:mod:`.special`, :mod:`.parameter_factors`; ``seed``: their draws)."""
    doc, truth = sides.doc, sides.truth
    both_n = doc.h is not None or doc.Q is not None
    kept = truth.G is not None          # the coordinates keep the rolling constraints
    if kept and doc.G is None:          # a document stating none: no multiplier terms
        doc = copy.copy(doc)
        doc.G = np.zeros_like(truth.G)
    doc_side = _n(doc, doc.B if sides.B_true is not None else None, kept)
    if doc_side is None or truth.A is None:
        return None
    parts = [truth.need(k) for k, y in (("h", doc.h), ("Q", doc.Q)) if y is not None]
    true_n = sum(parts[1:], parts[0]) if both_n else None
    true_side = equivalence.Side(truth.A, true_n, _with_stiffness(
        truth.K if doc.K is not None else None, sides.B_true),
        np.swapaxes(truth.G, 1, 2) if kept and truth.G is not None else None)
    # an equation whose terms beyond A do not tell its weights: its A read as the mass
    # matrix's row, as printed or scaled as declared (the singular checks below as for any)
    given = None if all(equivalence.weights_told(doc_side, true_side)) else \
        _given(d, funcs, sides)
    first = equivalence.decide(doc_side, true_side, len(sides.grid.sets), given=given)
    if any(has_kind(e.diagnoses, DiagnosisKind.SINGULAR) for e in first.equations) and \
            equivalence.singular_everywhere(doc_side.A, true_side.A, first.W) is None:
        # W singular or unbounded somewhere (not everywhere: an equation repeated or lost is
        # said as it is): a row's own factor, where one vanishes, says which equation and
        # how (det W alone tells a zero from a pole by magnitude only)
        found = vanishing_factors(funcs, sides, list(range(d.n)), seed, drawn=True)
        if found:
            # decided on with those factors divided out (another row lost elsewhere, a row
            # times sin θ beside one times L - R, is still said), their rows marked at the end
            doc_side, scale = _without(doc_side, funcs, sides, found)
            given = None if given is None else given * scale[:, :, None]
            first = equivalence.decide(doc_side, true_side, len(sides.grid.sets), given=given)
            decision = _further(funcs, sides, doc_side, true_side, first, seed,
                                frozenset(found), given)
            for i, v in found.items():
                decision = equivalence.mark_lost(decision, (i,), _lost(i, v))
            return decision
    return _further(funcs, sides, doc_side, true_side, first, seed, given=given)


def _given(d: Derivation, funcs: DocumentFunctions, sides: Sides) -> np.ndarray:
    r"""The rows of :math:`W` for the equations whose terms do not tell theirs (A alone):
    each its own unit row, times the scale the file declares for it (declarations bind)."""
    W = np.zeros((sides.size, d.n, d.n))
    for i in range(d.n):
        W[:, i, i] = 1.0 if d.row_scale is None else declared_weights(d, sides, i, funcs)
    return W


def _further(funcs: DocumentFunctions, sides: Sides, doc_side: equivalence.Side,
             true_side: equivalence.Side, first: equivalence.SystemDecision, seed: int,
             named: frozenset[int] = frozenset(), given: np.ndarray | None = None
             ) -> equivalence.SystemDecision:
    r"""``first`` with where an equation whose weights vary is lost: at the special states,
    for a factor of its row, for another robot of the model; the rows ``named`` (their
    factor found and divided out) are left to the caller; ``given`` as
    :func:`~..judge.equivalence.decide`'s."""
    # the special positions matter where an equation is otherwise a combination of the true
    # ones with weights that vary (a factor that may vanish there: sin θ)
    W = first.W
    varies = [i for i, e in enumerate(first.equations) if e.verdict == Verdict.AGREES and
              i not in named and
              np.nanmax(np.ptp(np.nan_to_num(W[:, i]), axis=0), initial=0.0) > 1e-9 * max(
                  float(np.nanmax(np.abs(W[:, i]), initial=0.0)), 1e-300)]
    if not varies:
        return first
    second = equivalence.decide(doc_side, true_side, len(sides.grid.sets),
                                special_sides(funcs, sides, sides.doc.need("A"),
                                              sides.truth.need("A"), W), given)
    # every row that still agrees is tried for its own factor, also where another is lost at
    # a special state (a row times a length factor beside one times (cos θ - 1/2)²)
    agreeing = [i for i in varies if second.equations[i].verdict == Verdict.AGREES]
    for i, v in vanishing_factors(funcs, sides, agreeing, seed).items():
        second = equivalence.mark_lost(second, (i,), _lost(i, v))
    if any(has_kind(e.diagnoses, DiagnosisKind.SINGULAR) for e in second.equations):
        return second
    changes = robot_sign_changes(funcs, sides, seed)
    if changes is None or not set(changes[0]) - named:
        return second
    rows, pole = changes
    wrong = tuple(k for k in rows if second.equations[k].verdict == Verdict.DIFFERS)
    if not wrong and any(e.verdict == Verdict.DIFFERS for e in second.equations):
        return second    # det A_doc changing sign may be the equation that differs already
        #                  (a symbol for another in one inertia): a right one is not blamed
    wrong = wrong or rows
    names = ", ".join(str(k + 1) for k in wrong)
    which = f"equations {names} are" if len(wrong) > 1 else f"equation {names} is"
    return equivalence.mark_lost(second, wrong, (
        f"{which} not {'defined' if pole else 'independent'} for every robot of the model: "
        "det A_doc changes sign between robots whose links' masses and inertias differ "
        "(lengths kept), where the truth's A stays positive definite, so W = A_doc A⁻¹ is "
        f"{'unbounded' if pole else 'singular'} for one between them (an equation "
        f"{'divided' if pole else 'multiplied'} by a factor of the masses that vanishes, "
        "alone or in a combination of the equations)"))


__all__ = ["decide"]
