r"""Each step of a derivation against the truth, component by component and term by term.

For the ``[[step]]`` tables of a derivation file (:mod:`wheeled_dyn.derivations.steps`): the
truth on :data:`STEP_SETS` random parameter sets (of the families a step is ``given``) ×
:data:`STEP_STATES` random states (:mod:`.kinematics_truth`), the document's components on the
same samples, and one :class:`~.result.ElementRecord` per component (``step`` = the step's
kind, ``equation`` = its label as printed) with the verdicts and diagnoses of :mod:`.diagnose`
(sign, factor, missing, extra, a swapped symbol), plus:

- its *terms*, when the component differs: each monomial of the velocities and accelerations
  (:math:`\dot x\dot\psi`, :math:`\ddot\phi`) against the truth's coefficient, obtained by
  evaluating the truth at unit velocities and accelerations
  (:math:`b_{jk} = F(e_j+e_k) - F(e_j) - F(e_k) + F(0)`);
- for a relation (constraint, claim): it is checked on the model's admissible motions (a
  configuration relation through its rate, a claim between parameters on the parameter sets);
  a right side that is a constant times the truth, sin written for cos, a power of a symbol
  (R⁻² for R²), mismatched dimensions;
- "agrees only if": the smallest combination of the model's special parameter families under
  which a differing component agrees.
"""

from __future__ import annotations

from dataclasses import replace
from typing import Any

import numpy as np
import sympy as sp

from ...derivations.schema import Derivation
from ...derivations.steps import RELATION_KINDS, RESULT_KINDS, Step
from ..grid.assumptions import declared
from ..grid.samples import special_cases
from ..judge.diagnose import (agrees, max_error, swap_diagnoses, trig_swap_diagnoses,
                              value_diagnoses)
from ..judge.consistency import vanishing
from ..judge.units import DimensionChecker, format_dim
from ..records import Diagnosis, DiagnosisKind as K, ElementRecord, Verdict, diagnosis
from ..sides.elements import swap_groups
from .balances import compare_balance
from .group import STEP_SETS, STEP_STATES, StepGroup
from .stated import compare_result
from .terms import (explained, linear_term_diagnoses, monomial_diagnoses, power_swaps,
                    side_factor)


#: Smaller grid on which special parameter families are tried.
SPECIAL_SETS, SPECIAL_STATES = 2, 6
#: A relation whose every term stays below this (relative to the sampled velocities) on the
#: admissible motions has nothing to check.
VACUOUS_TOL = 1e-9


def _compiled(g: StepGroup, step: Step) -> list[sp.Expr]:
    r"""The step's components (rates of relations) that the text did not lose, in order."""
    return [g.rate(e, step.kind) for e in step.components if not e.has(sp.nan)]


def _document_values(g: StepGroup, step: Step, T: np.ndarray):
    r"""The document's values of each component (None where lost) and the step's scale: the
    largest value on either side (for a relation, of either side's rate; for a vector, at
    least the size of the body origin's vector of the same kind, so that a vector that is 0
    (a contact point's velocity) is judged against the motion's size)."""
    kept = [j for j, expr in enumerate(step.components) if not expr.has(sp.nan)]
    exprs = _compiled(g, step)
    if step.kind in RELATION_KINDS:        # the size of each side's terms: a side may be 0
        exprs += [g.rate(t) for j in kept for side in step.sides[j]
                  for t in sp.Add.make_args(sp.expand(side))]
    reference = g.reference.get(id(step), 0.0)
    if step.kind == "first integral":
        # the size its rate would have were it not an integral: |dI/dq| |q'| + |dI/dnu| |nu'|
        d = g.d
        for j in kept:
            e = step.components[j]
            grads = g.documents([e.diff(x) for x in (*d.positions, *d.velocities)])
            n = len(d.positions)
            size = (sum(np.abs(x) for x in grads[:n]) * np.linalg.norm(g.qdot, axis=1)
                    + sum(np.abs(x) for x in grads[n:]) * np.linalg.norm(g.nudot, axis=1))
            reference = max(reference, float(np.max(size, initial=0.0)))
    values = g.documents(exprs)
    D_all: list[np.ndarray | None] = [None] * len(step.components)
    for j, v in zip(kept, values):
        D_all[j] = v
    parts = values[len(kept):]
    scale = max([float(np.abs(a).max(initial=0.0))
                 for a in (*[x for x in D_all if x is not None], T, *parts)
                 if np.all(np.isfinite(a))] + [reference, 1e-300])
    return D_all, scale


def _level(g: StepGroup, step: Step, x: np.ndarray) -> np.ndarray:
    r"""A potential energy is measured from any level: its values (every sample of the
    group) taken from their mean per parameter set; other steps' values as they are."""
    if step.kind != "potential energy":
        return x
    k = len(g.sets)
    return (x.reshape(k, -1) - x.reshape(k, -1).mean(axis=1, keepdims=True)).ravel()


def _levelled(g: StepGroup, step: Step, D: np.ndarray, T: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray]:
    r"""Both sides levelled (:func:`_level`: a wrong sign or factor still shows as such)."""
    return _level(g, step, D), _level(g, step, T)


def _special(d: Derivation, step: Step, seed: int) -> dict[int, str]:
    r"""For the components that differ, the smallest combination of the model's special
    parameter families (beyond the step's ``given``) under which they agree; none that makes
    a symbol the step writes vanish (:mod:`..judge.consistency`: a potential energy with the
    wrong sign of its :math:`MX_1` term is not "right if :math:`MX_1 = 0`")."""
    given = [c for c in special_cases(d.model) if c.name in step.given]
    written = set().union(*(sp.sympify(e).free_symbols for e in step.components)) & {
        spec.symbol for spec in d.symbols.values() if not spec.is_input}
    cases = [c for c in special_cases(d.model) if c.name not in step.given
             and not vanishing(d, written, given, c, seed)]
    memo: dict[tuple[str, ...], set[int]] = {}

    def agreeing(names: tuple[str, ...]) -> set[int]:
        if names not in memo:
            g = StepGroup(d, step.given + names, seed, SPECIAL_SETS, SPECIAL_STATES)
            T = g.truth([step])[0]
            D_all, scale = _document_values(g, step, T)
            memo[names] = {j for j, D in enumerate(D_all) if D is not None
                           and np.all(np.isfinite(D))
                           and agrees(*_levelled(g, step, D, T[:, j]), scale)}
        return memo[names]

    full = tuple(c.name for c in cases)
    out = {}
    for j in (agreeing(full) if cases else ()):
        needed = list(full)
        for name in full:
            trial = tuple(x for x in needed if x != name)
            if j in agreeing(trial):
                needed = list(trial)
        out[j] = " and ".join(c.description for c in cases if c.name in needed) or "always"
    return out


def _records(g: StepGroup, step: Step, index: int, T: np.ndarray) -> list[ElementRecord]:
    d = g.d
    names = step.component_names()
    groups = swap_groups(d)
    dims = DimensionChecker(d)
    recs = []
    D_all, scale = _document_values(g, step, T)
    for j, expr in enumerate(step.components):
        D, Tj = D_all[j], T[:, j]
        element = f"{step.name} {names[j]}"
        common: dict[str, Any] = dict(                   # ElementRecord's fields
            element=element, key="step", index=(index, j), document=step.printed[j],
            document_model="", truth=None, residual=None,
            step="claim" if step.kind == "first integral" else step.kind, equation=step.equation)
        if D is None or not np.all(np.isfinite(D)) or not np.all(np.isfinite(Tj)):
            why = "lost in the extracted text: not compared" if D is None else \
                "not finite at some samples"
            recs.append(ElementRecord(verdict=Verdict.UNDECIDED, diagnoses=(
                diagnosis(K.UNDECIDED, why, prefix=""),), max_error=float("nan"), scale=scale,
                **common))
            continue
        size = 1.0 + float(np.abs(g.nu).max(initial=0.0))
        if step.kind == "constraint" and scale <= VACUOUS_TOL * size:
            recs.append(ElementRecord(verdict=Verdict.UNDECIDED, diagnoses=(diagnosis(
                K.UNDECIDED, "every term of the relation vanishes on the model's admissible "
                "motions: nothing to check", prefix=""),),
                max_error=float("nan"), scale=scale, **common))
            continue
        diags: list[Diagnosis] = []
        expr = g.rate(step.components[j], step.kind)
        D, Tj = _levelled(g, step, D, Tj)
        relation = step.kind in RELATION_KINDS
        if relation:
            lhs, rhs = step.sides[j]
            dl, dr = dims.dim(lhs, []), dims.dim(rhs, [])
            if dl is not None and dr is not None and dl != dr and lhs != 0 and rhs != 0:
                diags.append(diagnosis(K.DIMENSION, f"the left side is {format_dim(dl)}, the "
                                       f"right side {format_dim(dr)}"))
        else:
            problems: list[str] = []
            dims.dim(step.components[j], problems)
            diags += [diagnosis(K.DIMENSION, x) for x in problems]
        ok = agrees(D, Tj, scale) and not diags
        if not ok:
            if step.kind == "first integral":
                diags.append(diagnosis(K.NOTE, "its rate along the model's free motion is "
                                       "not 0", prefix=""))
            elif step.kind == "linearised equations":
                diags += linear_term_diagnoses(g, step.components[j])
            elif relation:
                diags += side_factor(g, step.sides[j], scale)
            else:
                diags += value_diagnoses(D, Tj, scale)
                diags += monomial_diagnoses(g, step, j, expr, scale)
            together, at = _compiled(g, step), sum(1 for e in step.components[:j]
                                                    if not e.has(sp.nan))
            diags += swap_diagnoses(
                expr, groups,
                lambda a, b: _level(g, step, g.documents(together, read=(a, b))[at]), Tj, scale)
            if not explained(diags):                 # trials levelled as the truth is
                diags += trig_swap_diagnoses(
                    expr, lambda es: [_level(g, step, v) for v in g.documents(es)], Tj, scale)
            if step.kind == "first integral" or (
                    step.kind == "claim" and not expr.has(*d.positions, *d.velocities)):
                diags += power_swaps(expr, g, Tj, scale)
        recs.append(ElementRecord(verdict=Verdict.AGREES if ok else Verdict.DIFFERS,
                                  diagnoses=tuple(diags),
                                  max_error=max_error(D, Tj), scale=scale,
                                  document_latex=sp.latex(expr), truth_sample=float(Tj[0]),
                                  document_sample=float(D[0]), **common))
    return recs


def compare_steps(d: Derivation, seed: int = 2026) -> list[ElementRecord]:
    r"""Records of every ``[[step]]`` of ``d``, in the file's order. A step is read under the
    parameter families the file ``[assumes]`` as well as its own ``given``."""
    by_given: dict[tuple, list[int]] = {}
    out: dict[int, list[ElementRecord]] = {}
    assumed = tuple(c.name for c in declared(d).families)
    steps = [replace(s, given=tuple(dict.fromkeys((*assumed, *s.given)))) for s in d.steps]
    for i, s in enumerate(steps):
        if s.kind in RESULT_KINDS:
            out[i] = [compare_result(d, s, i, seed)]
            continue
        if s.kind == "newton-euler":
            out[i] = compare_balance(d, s, i, seed)
            continue
        alone = (i,) if s.kind in ("linearised equations", "first integral") else ()
        by_given.setdefault((s.given, alone), []).append(i)
    for (given, _), idx in by_given.items():
        g = StepGroup(d, given, seed)
        truths = g.truth([steps[i] for i in idx])
        for i, T in zip(idx, truths):
            out[i] = _records(g, steps[i], i, T)
            todo = [r for r in out[i] if r.verdict == "differs" and not explained(r.diagnoses)]
            special = _special(d, steps[i], seed) if todo else {}
            out[i] = [replace(r, verdict=Verdict.AGREES_IF, diagnoses=(
                Diagnosis(K.CONDITION, f"agrees only if {special[r.index[1]]}",
                          special[r.index[1]], condition=special[r.index[1]]), *r.diagnoses))
                if r in todo and r.index[1] in special else r for r in out[i]]
    return [r for i in sorted(out) for r in out[i]]


__all__ = ["STEP_SETS", "STEP_STATES", "compare_steps"]
