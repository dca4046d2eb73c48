r"""The frame each equation of a document is explained in, chosen on the grids (the engine's
use of :mod:`..readings.frames`): per row, the simplest rule under which every element agrees
when the equation is right; else the rule under which most elements agree beyond the weights
it fits — the combinations that replace one inertia column only where the simple rules leave
more differing elements than a combination has weights. A factor the file declares is kept
(declarations bind), and where a right equation contradicts it, the row is listed: the
equation differs as declared (:func:`bind_declared`; a ``file_error`` cause).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import replace

import numpy as np
import sympy as sp

from ...derivations.schema import Derivation
from ..judge.fitting import RATIO_TOL, bases, fit_factor
from ..judge.units import DimensionChecker
from ..judge.unsolved import read_back_explains
from ..readings.describe import weight_expression
from ..readings.frame_choice import (choose, consensus, elements_of, score, solved_row,
                                     with_consensus)
from ..readings.frames import Frame, FrameKind, FrameRule, candidate_rules, evaluate_rule
from ..readings.variants import combination_variants
from ..records import Verdict
from ..sides.both import Sides
from ..sides.document import DocumentFunctions
from ..sides.framed import framed, row_of

#: Samples a ratio is fitted on to be taken as a simple expression (spread over the sets).
SIMPLE_SAMPLES = 64


def choose_frames(d: Derivation, funcs: DocumentFunctions, grids: list[Sides], decision
                  ) -> tuple[list[FrameRule], list[Frame], list[int], dict[int, Frame]]:
    r"""Every row's frame rule (chosen over ``grids``), its frame on the main grid, the rows
    whose declared scale the (right) equation contradicts, and the frames of the rows that
    differ whose elements contradict their declared scale too (:func:`_printed`)."""
    main = grids[0]
    rules, frames, wrong = [], [], []
    apart: dict[int, Frame] = {}
    rows = np.linspace(0, main.size - 1, min(SIMPLE_SAMPLES, main.size)).astype(int)
    found = bases(d, main.grid.flat_q[rows], {s: np.asarray(v)[rows] if np.ndim(v) else v
                                             for s, v in main.values.items()})

    def simple(ratio: np.ndarray) -> bool:
        r"""A ratio voted by one element of A alone is a simple expression of the document's
        names (on samples spread over the sets: a hint only, the frame is then scored on
        every sample)."""
        return fit_factor(ratio[rows], found) is not None
    declared_scale = None
    on = [(s.doc, s.truth, s.B_true) for s in grids]
    read_back = decision is not None and not decision.equivalent and \
        read_back_explains(main.doc, main.truth, main.B_true)
    for i in range(d.n):
        right = decision is not None and decision.equations[i].verdict == Verdict.AGREES
        has_declared = d.row_scale is not None
        declared_scale = declared_weights(d, main, i, funcs) if has_declared else None
        if decision is not None and not decision.told_row(i):
            # A alone does not tell how a row combines the true ones: as printed, or as
            # declared (the decision read it so)
            rule = FrameRule(FrameKind.DECLARED if has_declared else FrameKind.IDENTITY)
            rules.append(rule)
            frames.append(_always(i, rule, main, declared_scale))
            continue
        rules_i = candidate_rules(i, on, simple)
        if read_back:      # the equations read back name the error: A_doc,i A⁻¹ is the form's
            rules_i = [replace(r, identified=True) if r.kind == FrameKind.COMBINATION
                       and r.variant is None else r for r in rules_i]
        totals: dict[FrameRule, int] = {}
        rule = choose(i, rules_i, on, has_declared and not right, right, totals)
        if has_declared and not right and declared_scale is not None and \
                (printed := _printed(i, rules_i, on, main, declared_scale, totals)):
            apart[i] = printed
        differing = 0 if right or has_declared or solved_row(main.doc, i) else \
            _differing(i, rule, main)             # a solved row's form is its frame
        if differing > 1:
            variants = combination_variants(on, i, (rows, lambda w: fit_factor(w, found)
                                                    is not None))
            if differing <= d.n:       # no more than n weights fit: only numbers, or names
                variants = [v for v in variants if v.identified]
            if variants:
                rules_i = rules_i + variants
                rule = choose(i, rules_i, on, False, totals=totals)
        while _inhomogeneous(d, i, rule, main, rows, found):
            after = _next_ratio(i, rule, main, rows, found)
            rules_i = [r for r in rules_i if r != rule] + ([after] if after else [])
            rule = choose(i, rules_i, on, has_declared and not right, right, totals)
        evaluated = evaluate_rule(i, rule, main.doc, main.truth, main.doc.B, main.B_true,
                                  declared_scale)
        if evaluated is not None and solved_row(main.doc, i):
            rule, evaluated = _solved(i, rule, evaluated, main)
        if evaluated is None:
            rule = FrameRule(FrameKind.IDENTITY)
        frame = evaluated if evaluated is not None else _always(i, rule, main)
        if declared_scale is not None and rule.kind != FrameKind.DECLARED:
            if right and not _same(frame.weights, i, declared_scale):
                wrong.append(i)
            rule = FrameRule(FrameKind.DECLARED)      # binding: the row is read as declared
            frame = _always(i, rule, main, declared_scale)
        rules.append(rule)
        frames.append(frame)
    _as_the_others(d, rules, frames, on, main)
    for i in _shared_partners(rules):
        rules[i] = FrameRule(FrameKind.IDENTITY)
        frames[i] = _always(i, rules[i], main)
    return rules, frames, wrong, apart


def _printed(i: int, rules: Sequence[FrameRule], on, main: Sides, declared: np.ndarray,
             totals: dict[FrameRule, int]) -> Frame | None:
    r"""For row ``i`` that differs and has a declared scale: the frame it is printed in —
    the identity or a constant times the true row, not the declared one — where most of its
    elements agree in it and at least two more than as declared (a row declared twice the
    true one, printed as the true one with one term's sign wrong: every element differs as
    declared, one as printed); else None. It only explains: the row is read as declared."""
    found = choose(i, [r for r in rules if r.kind in (FrameKind.IDENTITY, FrameKind.CONSTANT)
                       and r.partner in (i, -1)], on, False, totals=totals)
    frame = evaluate_rule(i, found, main.doc, main.truth, main.doc.B, main.B_true)
    if frame is None or _same(frame.weights, i, declared):
        return None
    row = row_of(main.doc, i)
    as_printed = score(row, framed(frame.weights, main.truth, main.B_true, full=False))
    as_declared = score(row, framed(_always(i, FrameRule(FrameKind.DECLARED), main,
                                            declared).weights, main.truth, main.B_true,
                                    full=False))
    return frame if as_printed >= as_declared + 2 and 2 * as_printed >= elements_of(row) \
        else None


def _inhomogeneous(d: Derivation, i: int, rule: FrameRule, main: Sides, rows: np.ndarray,
                   found: list[tuple[sp.Expr, np.ndarray]]) -> bool:
    r"""Whether ``rule`` reads row ``i`` as the true equation times a factor no author
    writes: its expression in the document's names (fitted on the samples ``rows`` of the
    main grid with the bases ``found``) adds terms of different dimensions under the file's
    declared units (or, where it declares none, those its symbols' values give: M(link) a
    mass, CZ(link) a length), :math:`I_{yy} + m_b(x_b^2 + z_b)`. Such a ratio is the document's own
    wrongly written divisor shared by the elements that hold the error, not the frame the
    row was written in: the elements are explained in another frame, where they differ."""
    if rule.kind != FrameKind.FUNCTION:
        return False
    frame = evaluate_rule(i, rule, main.doc, main.truth, main.doc.B, main.B_true)
    if frame is None:
        return False
    factor = weight_expression(frame.weights[rows, rule.partner], found)
    if factor is None or factor.is_number:
        return False
    problems: list[str] = []
    DimensionChecker(d, inferred=True).dim(factor, problems)    # units from the values too
    return bool(problems)


def _next_ratio(i: int, rule: FrameRule, main: Sides, rows: np.ndarray,
                found: list[tuple[sp.Expr, np.ndarray]]) -> FrameRule | None:
    r"""The ``FUNCTION`` rule of the ratio the elements share after ``rule``'s (fewer of
    them), where it is one a frame is written with: the row's own diagonal inertia's (the
    true divisor :math:`I_{yy} + m_b(x_b^2 + z_b^2)` of the one element written right, a
    row divided by its inertia) or an expression of the document's names (a monomial, a
    short sum or its inverse: :func:`~..readings.describe.weight_expression`); None where
    there is none."""
    after = replace(rule, rank=rule.rank + 1, identified=True)
    frame = evaluate_rule(i, after, main.doc, main.truth, main.doc.B, main.B_true)
    if frame is None:
        return None
    ratio = frame.weights[:, rule.partner]
    with np.errstate(all="ignore"):
        own = rule.partner == i and main.doc.A is not None and bool(np.allclose(
            main.doc.A[:, i, i] / main.truth.need("A")[:, i, i], ratio, rtol=RATIO_TOL,
            atol=0.0))
    return after if own or weight_expression(ratio[rows], found) is not None else None


def _as_the_others(d: Derivation, rules: list[FrameRule], frames: list[Frame], on,
                   main: Sides) -> None:
    r"""Each row whose elements agree as well as chosen as in the constant most other rows
    are read in (:func:`~..readings.frame_choice.consensus`: Kane's −1) read in it, in place;
    none in a file that declares its rows' scales (they are binding)."""
    if d.row_scale is not None:
        return
    for i, rule in enumerate(list(rules)):
        value = consensus(rules, without=i)
        if value is None:
            continue
        better = rule if solved_row(main.doc, i) else with_consensus(i, rule, value, on)
        evaluated = None if better == rule else evaluate_rule(
            i, better, main.doc, main.truth, main.doc.B, main.B_true)
        if evaluated is not None:
            rules[i], frames[i] = better, evaluated


def _shared_partners(rules: Sequence[FrameRule]) -> list[int]:
    r"""The rows paired with another row's true equation (a constant or function frame)
    where another row is paired with it too: two equations of the document cannot both be
    multiples of one true equation in a system that is right, and a point-mass disk's
    heading row, its inertia row sin φ × its spin row, was "the true equation of theta
    times 2 sin(φ)/3" beside its spin row read as that true equation. They are explained
    as printed (the rows paired with their own equation keep their frames)."""
    def partner(i: int, rule: FrameRule) -> int | None:
        if rule.kind in (FrameKind.IDENTITY, FrameKind.DECLARED):
            return i
        return rule.partner if rule.kind in (FrameKind.CONSTANT, FrameKind.FUNCTION) else None
    partners = [partner(i, r) for i, r in enumerate(rules)]
    return [i for i, k in enumerate(partners) if k is not None and k != i
            and sum(p == k for p in partners) > 1]


def _solved(i: int, rule: FrameRule, frame: Frame, main: Sides) -> tuple[FrameRule, Frame]:
    r"""A row solved for its acceleration read as a function of the true row (not identified)
    whose weights are those of its solved form, row :math:`i` of :math:`A^{-1}` (a diagonal
    inertia): told as solved, which names it, with the same weights."""
    if rule.kind != FrameKind.FUNCTION or rule.identified:
        return rule, frame
    solved = FrameRule(FrameKind.COMBINATION)
    other = evaluate_rule(i, solved, main.doc, main.truth, main.doc.B, main.B_true)
    if other is None or not np.isfinite(other.weights).all() or \
            np.abs(other.weights - frame.weights).max() > \
            SAME_WEIGHTS * np.abs(frame.weights).max():
        return rule, frame
    return solved, other


#: Relative agreement of two frames' weights that are the same.
SAME_WEIGHTS = 1e-9


def _always(i: int, rule: FrameRule, main: Sides, declared: np.ndarray | None = None) -> Frame:
    r"""Row ``i``'s frame under a rule that always has one (the identity, the declared scale)
    on the main grid."""
    frame = evaluate_rule(i, rule, main.doc, main.truth, main.doc.B, main.B_true, declared)
    if frame is None:
        raise ValueError(f"row {i + 1}: the {rule.kind} frame is always defined")
    return frame


def _differing(i: int, rule: FrameRule, main: Sides) -> int:
    r"""How many of row ``i``'s elements differ under ``rule`` on the main grid."""
    frame = evaluate_rule(i, rule, main.doc, main.truth, main.doc.B, main.B_true)
    if frame is None:
        return 10 ** 6
    row = row_of(main.doc, i)
    return elements_of(row) - score(row, framed(frame.weights, main.truth, main.B_true,
                                                full=False))


def _same(w: np.ndarray, i: int, factor: np.ndarray) -> bool:
    r"""Weights ``w`` (S × n) that are ``factor`` × :math:`e_i` at every sample."""
    expected = np.zeros_like(w)
    expected[:, i] = factor
    scale = max(float(np.abs(expected).max(initial=0.0)), 1e-300)
    return bool(np.abs(w - expected).max(initial=0.0) <= 1e-7 * scale)


def declared_weights(d: Derivation, sides: Sides, i: int, funcs: DocumentFunctions
                      ) -> np.ndarray:
    r"""The factor the file declares for row ``i``, per sample."""
    if d.row_scale is None:
        raise ValueError(f"{d.path.name} declares no row scale")
    return np.broadcast_to(np.asarray(funcs.compiled(d.row_scale[i])(*sides.argv), dtype=float),
                           (sides.size,))


def row_factors(rules: list[FrameRule], frames: list[Frame | None]) -> dict[int, np.ndarray]:
    r"""Per row whose frame is the true equation times a factor, that factor per sample."""
    out = {}
    for i, (rule, frame) in enumerate(zip(rules, frames)):
        if frame is not None and rule.kind != FrameKind.COMBINATION:
            out[i] = frame.weights[:, i if rule.partner < 0 else rule.partner]
    return out


def id_frames(d: Derivation, funcs: DocumentFunctions, rules: list[FrameRule],
               id_sides: Sides) -> list[Frame | None]:
    r"""Every row's frame rule evaluated on the identification grid."""
    return [evaluate_rule(i, rule, id_sides.doc, id_sides.truth, id_sides.doc.B,
                          id_sides.B_true, declared_weights(d, id_sides, i, funcs)
                          if rule.kind == FrameKind.DECLARED else None)
            for i, rule in enumerate(rules)]


__all__ = ["SIMPLE_SAMPLES", "choose_frames", "declared_weights", "id_frames", "row_factors"]
