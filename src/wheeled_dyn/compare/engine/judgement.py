r"""One derivation judged as its file declares it: the equations decided by equivalence, then
every element explained in its row's frame.

The stages (see :mod:`..engine`): the grid and both sides on it; the equations' verdicts
(:func:`~..judge.equivalence.decide`, with the special states at which a factor may vanish);
the frame of every row (:func:`~..readings.frames.choose`, scored on the main grid and on the
grid of the special families the document did not declare); the elements judged in their frames
(:mod:`..judge.element`), the family search, C by its products, the differing terms named; the
equation records, consistent with the elements (:func:`equation_records`); the document's own
checks (energy, symmetry, constraint rows); the printed forms for the reports.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
import sympy as sp

from ...derivations.schema import Derivation, equation_labels
from ..causes.frames import frame_causes
from ..grid.assumptions import Assumptions, declared, undeclared_cases
from ..judge import families
from ..judge.consistency import consistent_cases, contradiction_causes
from ..judge.document_checks import constraint_problems, constraint_rows
from ..judge.draft import ElementDraft
from ..judge.element import Trials, judge
from ..judge.factorization import factorization
from ..judge.diagnose import nice_number
from ..judge.fitting import bases
from ..judge.named import NAMED, name_terms
from ..judge.own_inertia import own_moments
from ..judge.precision import largest_terms, row_round_off
from ..judge.rows import drafts_of_row, row_values
from ..judge.units import DimensionChecker, geometric_symbols
from ..readings.describe import describe
from ..readings.frames import Frame, FrameKind, FrameRule, constant_weights, evaluate_rule
from .declared_rows import (apart_causes, bind_declared, declared_apart, declared_only,
                            printed_factors)
from .frames import choose_frames, declared_weights, id_frames, row_factors
from ..records import Cause, CauseKind, DerivationResult, Verdict, has_kind
from ..sides.both import Sides, both_sides
from ..sides.document import DocumentFunctions
from ..sides.elements import swap_groups
from ..sides.evaluation import Evaluation
from ..sides.framed import framed, row_of, row_scale
from .assumed_values import assumed_cause, owed_equations
from .equations import equation_records, state_rates, units_notes
from .printing import corrected, document_truth, print_drafts
from .constraint_factors import lost_constraints
from .deciding import decide
from .own_checks import own_checks
from .read_back import read_back_said

#: Smaller grid used to test special parameter families: states per set, sets.
SPECIAL_SAMPLES, SPECIAL_SETS = 40, 2
#: The grid functions of the state are identified on (the frames' descriptions, the named
#: terms): states per set, parameter sets (a quantity of the parameters alone takes one value
#: per set, so many sets).
ID_STATES, ID_SETS = 8, 16


@dataclass(frozen=True)
class Judgement:
    r"""A derivation judged as declared: the result (no causes yet), the numbers it was
    decided on, the causes found while judging (frames, declarations), and the sides."""

    result: DerivationResult
    evaluation: Evaluation
    causes: tuple[Cause, ...]
    sides: Sides
    funcs: DocumentFunctions
    #: the rows (0-based) compared in a frame whose weights vary with the state or the
    #: parameters (divided by a function of them, or combined): their elements agree with
    #: the document's divisors as the file maps them, right or not
    varying: frozenset[int] = frozenset()


def document_functions(d: Derivation) -> DocumentFunctions:
    r"""The document's elements as printed (declared row scales not divided out: the truth is
    brought into the document's frame), assumptions applied, compiled."""
    terms = d.read_off(assume=True, unscale=False)
    C = d.C
    if C is not None and d.assumptions:
        C = sp.ImmutableMatrix(d.apply_assumptions(C))
    G = d.G if d.G is not None else d.constraint_matrix()
    return DocumentFunctions(d, terms.A, C, terms.Q, terms.B, terms.h, G, _stiffness(d, terms))


def _stiffness(d: Derivation, terms) -> sp.ImmutableMatrix | None:
    r"""A linearised document's stiffness :math:`K = \partial Q/\partial q`, compared with
    the truth's — also where it declares its potential from an equilibrium (Q zero at the
    point, never K: a declaration that hid K passed either sign); None for others."""
    assumed = declared(d)
    if not assumed.linearised_about or terms.Q is None or terms.Q.has(sp.nan):
        return None
    return sp.ImmutableMatrix(terms.Q.jacobian(sp.Matrix(d.positions)))


def _grids(engine, d: Derivation, funcs: DocumentFunctions, sides: Sides,
           cases: tuple, assumed: Assumptions) -> list[Sides]:
    r"""The main sides and, where the model has undeclared special families, the sides on
    their grid (a document usually omits what they remove: there its rows match the truth in
    their frame exactly)."""
    out = [sides]
    if cases:
        grid = engine.grids.get(d, tuple(cases), SPECIAL_SAMPLES, SPECIAL_SETS, assumed)
        out.append(both_sides(d, funcs, grid, engine.seed))
    return out


def _row_drafts(d: Derivation, funcs: DocumentFunctions, sides: Sides, frames: list[Frame],
                rules: list[FrameRule], dims: DimensionChecker, label: str,
                only: set[int] | None = None) -> tuple[list[ElementDraft], dict]:
    r"""Every element (of the rows ``only``, where given) judged in its row's frame
    (``rules``: how each was found); per row the document's and the framed truth's
    :math:`\Gamma` (for C by its products)."""
    trials = Trials(funcs, sides.argv, sides.size, sides.truth.H_rows)
    groups = swap_groups(d, sides.values)
    lost = set(d.missing)
    drafts: list[ElementDraft] = []
    gammas = {}
    h, Q = sides.truth.h, sides.truth.Q
    largest = largest_terms(sides.truth.need("A"), h if Q is None else Q if h is None else h + Q)
    for i, (frame, rule) in enumerate(zip(frames, rules)):
        if only is not None and i not in only:
            continue
        doc_row, true_row = row_of(sides.doc, i), framed(frame.weights, sides.truth,
                                                          sides.B_true)
        factor = None if rule.kind == FrameKind.COMBINATION else \
            frame.weights[:, i if rule.partner < 0 else rule.partner]
        scale = row_scale(doc_row, true_row)
        row = drafts_of_row(doc_row, true_row, i, funcs.exprs, d.velocities, scale, lost,
                            label)
        rho = row_round_off(frame.weights, largest)
        for r in row:
            r.round_off = rho
        dims.row_dimension(i, [(r.key, r.index, r.expr) for r in row
                               if r.expr is not None])
        for r in row:
            problems = dims.check(r.key, r.index, r.expr) if r.key != "h" and \
                r.expr is not None else []
            judge(r, problems, trials, groups, factor)
        drafts += row
        if doc_row.Gamma is not None and true_row.Gamma is not None:
            gammas[i] = (doc_row.Gamma[:, 0], true_row.Gamma[:, 0])
    return drafts, gammas


def _agreeing(engine, d, funcs, rules, assumed):
    r"""The family search's callback (:data:`~..judge.families.Agreeing`)."""
    def on(combo):
        grid = engine.grids.get(d, combo, SPECIAL_SAMPLES, SPECIAL_SETS, assumed)
        s = both_sides(d, funcs, grid, engine.seed)
        elements = []
        for i, rule in enumerate(rules):
            frame = evaluate_rule(i, rule, s.doc, s.truth, s.doc.B, s.B_true,
                                  declared_weights(d, s, i, funcs)
                                  if rule.kind == FrameKind.DECLARED
                                  else None)
            if frame is None:
                continue
            doc_row, true_row = row_of(s.doc, i), framed(frame.weights, s.truth, s.B_true)
            scale = row_scale(doc_row, true_row)
            elements += [(key, index, D, T, scale) for key, index, D, T, _ in
                         row_values(doc_row, true_row, i, funcs.exprs, d.velocities)]
        return families.items(elements)
    return on


def _held(cs) -> list[str]:
    r"""A note for each model coordinate a document's holonomic map holds fixed (left out of
    it, held at 0, or mapped to a constant): the equations compared are the model's with
    that joint locked there."""
    if cs.kind != "holonomic":
        return []
    positions = {str(p) for p in cs.positions}
    return [f"model coordinate {name} is held at {sp.sstr(e)} by the document's "
            "configuration map (none of its positions moves it): the equations compared are "
            "the model's with that joint locked there"
            for name, e in cs.configuration.items()
            if not {str(x) for x in e.free_symbols} & positions]


def judge_derivation(engine, d: Derivation, announce: bool = False) -> Judgement:
    r"""``d`` judged as declared (module text); ``announce``: the stages are told to the
    engine's ``on_stage``."""
    def stage(name: str) -> None:
        if announce:
            engine.stage(d, name)
    stage("grid")
    assumed = declared(d)
    funcs = document_functions(d)
    grid = engine.grids.get(d, (), engine.samples, engine.param_sets, assumed,
                            lambda: stage("truth"))
    stage("document")
    sides = both_sides(d, funcs, grid, engine.seed, with_gamma=True)
    stage("equivalence")
    decision = decide(d, funcs, sides, engine.seed)
    cases = consistent_cases(d, funcs, undeclared_cases(d, assumed), assumed, engine.seed)
    grids = _grids(engine, d, funcs, sides, cases, assumed)
    stage("frames")
    rules, frames, wrong, apart = choose_frames(d, funcs, grids, decision)
    # the rows right as printed that contradict their declared scale, by their printed factor
    declared_wrong = {} if decision is None else printed_factors(decision, wrong)
    if decision is not None:
        decision = bind_declared(d, decision, declared_wrong)
    stage("judging")
    label = equation_labels(str(d.source.get("equations", "")))
    drafts, gammas = _row_drafts(d, funcs, sides, frames, rules, DimensionChecker(d), label)
    if apart:                         # the rows whose elements contradict their declared scale
        declared_apart(d, drafts, _row_drafts(d, funcs, sides, [apart.get(i, f) for i, f in enumerate(
            frames)], rules, DimensionChecker(d), label, set(apart))[0])
    from ..judge.swaps import h_swaps
    h_swaps(drafts)
    declared_only(d, drafts, declared_wrong)
    families.search(cases, drafts, _agreeing(engine, d, funcs, rules, assumed))
    factorization(drafts, gammas, d.velocities)
    combined = any(r.kind == FrameKind.COMBINATION for r in rules)
    unnamed = any(r.verdict != Verdict.AGREES and r.key != "C" and not has_kind(r.diagnoses, *NAMED)
                  for r in drafts)
    solved, found, id_sides = None, [], None
    frames_on_id: list[Frame | None] = [None] * d.n
    if unnamed or combined or any(r.kind == FrameKind.FUNCTION for r in rules):
        # the identification grid (many parameter sets), only where something is identified
        id_sides = both_sides(d, funcs, engine.grids.get(d, (), ID_STATES, ID_SETS, assumed),
                              engine.seed)
        frames_on_id = id_frames(d, funcs, rules, id_sides)
        found = bases(d, id_sides.grid.flat_q, id_sides.values)
    texts = [describe(i, frame, None if on_id is None else on_id.weights, found, d.positions,
                      sides.doc.A[:, i, :] if sides.doc.A is not None else None,
                      None if d.row_scale is None else d.row_scale[i])
             for i, (frame, on_id) in enumerate(zip(frames, frames_on_id))]
    if unnamed and id_sides is not None:
        name_terms(drafts, _id_values(d, funcs, id_sides, frames_on_id), found,
                   own_moments([ps.values for ps in id_sides.grid.sets], ID_STATES),
                   geometric_symbols(d), d.positions, row_factors(rules, frames_on_id),
                   own_moments([ps.values for ps in id_sides.grid.sets], ID_STATES, True),
                   ID_STATES, swap_groups(d, id_sides.values))
    if decision is not None and not decision.equivalent and id_sides is not None \
            and id_sides.doc.A is not None:
        solved = read_back_said(d, drafts, rules, frames, frames_on_id, id_sides, found, combined,
                                lambda: document_truth(d, sides.grid.cs, assumed),
                                sides.truth.H_rows)
    owed = owed_equations(d, grids, engine.seed, decision, funcs)
    equations = equation_records(d, decision, drafts, texts, label, grids, funcs, rules, solved,
                                 owed)
    fixes = print_drafts(d, drafts, sides.grid.cs, texts, assumed, funcs.exprs)
    equations = corrected(d, equations, fixes)
    j = _judgement(d, funcs, sides, drafts, equations, texts, rules, frames, assumed,
                   declared_wrong, fixes.truth is not None, engine.seed, {**declared_wrong, **{
                       i: sp.nsimplify(nice_number(f.constant)) if f.constant is not None
                       else None for i, f in apart.items()}})
    return replace(j, causes=(*assumed.file_causes(d, funcs.exprs), *apart_causes(d, apart, drafts),
                              *contradiction_causes(d, funcs, assumed, engine.seed),
                              *assumed_cause(d, owed), *j.causes))


def _id_values(d: Derivation, funcs: DocumentFunctions, id_sides: Sides,
               id_frames: list[Frame | None]) -> dict:
    r"""Each element's (document, truth in frame) values on the identification grid."""
    out = {}
    for i, frame in enumerate(id_frames):
        if frame is None:
            continue
        doc_row = row_of(id_sides.doc, i)
        true_row = framed(frame.weights, id_sides.truth, id_sides.B_true)
        for key, index, D, T, _ in row_values(doc_row, true_row, i, funcs.exprs, d.velocities):
            out[(key, index)] = (D, T)
    return out


def _judgement(d, funcs, sides, drafts, equations, texts, rules, frames, assumed,
               declared_wrong, in_document: bool, seed: int = 2026, printed=None) -> Judgement:
    grid = sides.grid
    scales = np.array([r.scale for r in [next((x for x in drafts if x.row == i), None)
                                          for i in range(d.n)] if r is not None] or [1.0])
    if len(scales) != d.n:
        scales = np.ones(d.n)
    no_factor = (None,) * d.n
    energy, asymmetric = own_checks(d, funcs, sides, texts, rules, frames, printed)
    ev = Evaluation(funcs=funcs, doc=sides.doc, truth=sides.truth, B_true=sides.B_true,
                    scales=scales, q=grid.flat_q, nu=grid.flat_nu, values=sides.values,
                    row_factor=no_factor, kind=grid.cs.kind)
    constants = tuple(None if t.factor is None or not t.factor.is_number or t.factor == 1
                      or f.rule.partner not in (i, -1) or f.rule.kind == FrameKind.DECLARED
                      else sp.sstr(t.factor)
                      for i, (t, f) in enumerate(zip(texts, frames)))
    functions = tuple(None if f.rule.kind != FrameKind.FUNCTION or t.factor is None
                      or f.rule.partner != i else sp.sstr(t.factor)
                      for i, (t, f) in enumerate(zip(texts, frames)))
    combination = _combination(texts, rules, frames, d.n)
    if combination:                      # the combination carries the rows' factors too
        functions = constants = (None,) * d.n
    notes = list(sides.notes) + [f"{e} was lost in the extracted text: not compared"
                                 for e in d.missing] + _held(grid.cs) + _off_ground(grid) \
        + _uniform_read(grid, assumed) + units_notes(drafts, assumed.linearised_about) \
        + ([] if d.state_space is None else [d.state_space.note()])
    result = DerivationResult(
        path=d.path, title=d.title, model=d.model, source=dict(d.source),
        coordinates=grid.cs.name, velocities=tuple(str(v) for v in d.velocities),
        form=d.form, records=tuple(r.freeze() for r in drafts), row_factors=constants,
        energy=energy, asymmetric=asymmetric,
        constraints=constraint_rows(sides.doc, sides.truth, scales),
        reconstructed=dict(d.reconstructed), samples=grid.q.shape[1],
        parameter_sets=len(grid.sets), notes=tuple(notes), assumes=assumed.describe(),
        latex_input=dict(d.latex_input), row_functions=functions, row_combination=combination,
        equations=tuple(equations), truth_in_document=in_document,
        model_readings=sides.readings)
    causes = frame_causes(d, texts, rules, result.equations, declared_wrong, result.records)
    wrong = constraint_problems(d, funcs, sides)
    if wrong is not None and sides.truth.G is not None and not wrong:
        lost = lost_constraints(funcs, sides, seed)
        wrong = tuple(map(str, lost))
        rows = list(result.constraints)          # a G row lost says so on its own line too
        for x in lost:
            if x.where == "G" and x.row is not None and x.row < len(rows):
                rows[x.row] = f"G row {x.row + 1}: {x.row_text}"
        result = replace(result, constraints=tuple(rows))
    if wrong:
        causes.append(Cause(CauseKind.NOT_EQUIVALENT, (), "the document's constraints are "
                            "not the model's rolling constraints: " + "; ".join(wrong)))
    result = replace(result, constraints_agree=None if wrong is None else not wrong)
    rates, rates_agree = state_rates(d)
    if rates:
        causes.append(Cause(CauseKind.NOT_EQUIVALENT, (), "the state-space form's rates of "
                            "the positions are not their velocities: " + "; ".join(rates)))
    result = replace(result, state_rates=rates, state_rates_agree=rates_agree)
    varying = frozenset(i for i, f in enumerate(frames) if not constant_weights(f.weights))
    return Judgement(result, ev, tuple(causes), sides, funcs, varying)


def _uniform_read(grid, assumed: Assumptions) -> list[str]:
    r"""The readings of the links the document declares uniform whose URDF inertia is the
    uniform body's to its printed digits (:mod:`~wheeled_dyn.models.uniform_reading`)."""
    from ..grid.samples import uniform_links
    wm = grid.sets[0].model
    table = wm.lengths
    if table is None or not table.uniform or not assumed.families:
        return []
    return [table.uniform[link][1] for link in sorted(uniform_links(wm, assumed.families))
            if link in table.uniform]


def _off_ground(grid) -> list[str]:
    r"""A note where the map put a tilting wheel off the ground at states first drawn (they
    were drawn again: the model has no motion there)."""
    if not grid.off_ground:
        return []
    return [f"{grid.off_ground} of the {grid.q.shape[0] * grid.q.shape[1]} states first "
            "drawn were drawn again: the coordinate map puts the wheel off the ground or "
            "flat there (its centre's height is the rim's lowest point above the ground only "
            "within a part of the positions' range; [coordinates] ranges says where the "
            "document's coordinates hold)"]


def _combination(texts, rules, frames, n: int) -> tuple[tuple[str, ...], ...]:
    r"""The combination :math:`W` of the true equations the document's are (rows of SymPy
    text), when some row is not the true one times a factor and every row's weights were
    identified; () otherwise."""
    if all(r.kind != FrameKind.COMBINATION and r.partner in (i, -1)
           for i, r in enumerate(rules)):
        return ()
    rows = []
    for i, (t, r, f) in enumerate(zip(texts, rules, frames)):
        if t.weights is not None:
            rows.append(tuple(sp.sstr(w) for w in t.weights))
        elif t.factor is not None and r.partner >= 0:
            rows.append(tuple(sp.sstr(t.factor) if k == r.partner else "0" for k in range(n)))
        elif r.kind == FrameKind.DECLARED or t.text == "":
            rows.append(tuple("1" if k == i else "0" for k in range(n)))
        else:
            return ()
    return tuple(rows)


__all__ = ["ID_SETS", "ID_STATES", "Judgement", "SPECIAL_SAMPLES", "SPECIAL_SETS",
           "decide", "document_functions", "judge_derivation"]
