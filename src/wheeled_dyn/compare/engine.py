r"""The comparison engine: a document's derivation against the truth, element by element.

For a :class:`~wheeled_dyn.derivations.schema.Derivation`:

1. K random physically consistent parameter sets of its model and N random states each;
2. the truth in the document's coordinates (:mod:`.evaluate`), the document's numbers;
3. rows the document multiplied by a constant it did not declare (e.g. Kane's generalised
   inertia forces :math:`F^* = -(A\ddot q + h)`) are detected and divided out first;
4. a verdict per element of A, C, Q, B and per velocity product of h (:mod:`.diagnose`),
   "agrees only if ..." from special parameter families (:mod:`.samples`), the difference
   between "C differs" (factorisation only, when :math:`C\dot q` agrees) and "the equations
   differ", units term by term (:mod:`.units`);
5. checks of the document on its own (:mod:`.document_checks`): A symmetric, and the power
   identity :math:`\nu^T h = \tfrac12\nu^T\dot A\nu` (gyroscopic forces do no work) — a model
   that fails it does not conserve energy;
6. a better reading of the file's conventions when one exists (:mod:`.conventions`), and the
   root causes (:mod:`.causes`).

Data flows one way: derivation → evaluation (:mod:`.evaluate`) → elements (:mod:`.elements`,
:mod:`.diagnose`) → causes → :class:`~.result.DerivationResult`.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import replace

import numpy as np
import sympy as sp

from ..constraints.reduction import CoordinateMap
from ..derivations.schema import Derivation, equation_labels
from .causes import root as causes
from .presentation import closed_form
from .readings import signs as conventions, row_combinations, row_functions
from .judge.diagnose import (
    agrees,
    max_error,
    nice_number,
    swap_diagnoses,
    value_diagnoses,
)
from .judge.document_checks import asymmetry, constraint_rows, energy_check
from .judge.terms import element_term_diagnoses, trig_diagnoses
from .sides.elements import (
    apply_row_factors,
    element_expr,
    element_label,
    element_values,
    input_map,
    latex_names,
    row_factors,
    row_scales,
    swap_groups,
    truth_for,
)
from .sides.evaluate import (
    DocumentFunctions,
    derivation_coordinate_set,
    document_symbol_values,
)
from .presentation.printing import printed
from .records import Cause, Convention, ConventionSummary, DerivationResult, ElementRecord
from .readings.search import SearchEvaluation
from .grid.samples import (
    SpecialCase,
    parameter_sets,
    random_states,
    regular_states,
    special_cases,
)
from .grid.assumptions import Assumptions, apply_to_truth, declared, position_ranges
from .judge.units import DimensionChecker

#: Smaller grid used to test special parameter families.
SPECIAL_SAMPLES, SPECIAL_SETS = 40, 2
#: Samples a trial reading of a differing element (one symbol read as another) is first
#: evaluated on, spread over the parameter sets: only one that agrees there is evaluated on
#: every sample (it must agree at all of them), so the verdicts are those of the full grid.
SCREEN_SAMPLES = 64
#: The grid a row divided by a function, or a combination of rows, is identified on: states
#: per set, parameter sets.
ROW_FUNCTION_STATES, ROW_FUNCTION_SETS = 8, 16
#: The stages of one comparison as ``on_stage`` names them. The equations' stages start in this
#: order; "steps" comes first for the file's own ``[[step]]`` tables, last for the step files
#: that feed it.
STAGES: tuple[str, ...] = ("grid", "truth", "document", "judging", "readings", "causes", "steps")


class ComparisonEngine:
    r"""Compares derivations; caches the truth per (model, coordinate set, parameter family)
    so derivations sharing coordinates share the work. ``parallel_steps``: the step files
    feeding a derivation are compared in a forked process while the derivation itself is
    (the command line's ``compare``; :func:`~.steps.with_steps`). ``on_stage``: called with
    the derivation file's name and a stage's name (:data:`STAGES`) at the start of each stage
    of a comparison (a progress display; the stages of re-readings are not announced)."""

    def __init__(self, samples: int = 1000, param_sets: int = 5, seed: int = 2026,
                 parallel_steps: bool = False,
                 on_stage: Callable[[str, str], None] | None = None) -> None:
        self.samples = samples
        self.param_sets = param_sets
        self.seed = seed
        self.parallel_steps = parallel_steps
        self.on_stage = on_stage
        self._truth: dict[tuple, tuple] = {}      # (truth, sets, q, nu, coordinate set)
        self._maps: dict[tuple, CoordinateMap] = {}
        self._sets: dict[tuple, object] = {}
        self._results: dict[tuple, DerivationResult] = {}

    def _stage(self, d: Derivation, stage: str) -> None:
        if self.on_stage is not None:
            self.on_stage(d.path.name, stage)

    # -- the two sides -------------------------------------------------------------------
    def _grid(self, d: Derivation, special: tuple[SpecialCase, ...], n_states: int, k: int,
              assumed: Assumptions = Assumptions(), announce: bool = False):
        special = tuple(dict.fromkeys((*assumed.families, *special)))
        # the coordinates' identity: equations read in another order have the same truth
        raw = repr({name: value for name, value in d.coordinates.raw.items()
                    if name != conventions.ROWS_KEY})
        key = (d.model, raw, d.coordinates.use,
               tuple(c.name for c in special), n_states, k, assumed.key())
        if key not in self._truth:
            rng = np.random.default_rng([self.seed, len(special), n_states])
            sets = parameter_sets(d.model, k, rng, special)
            ckey = (d.model, raw, d.coordinates.use)
            if ckey not in self._sets:
                self._sets[ckey] = derivation_coordinate_set(d, sets[0])
            cs = self._sets[ckey]
            mkey = (d.model, repr(cs))
            if mkey not in self._maps:
                self._maps[mkey] = CoordinateMap(sets[0].model, cs)
            cmap = self._maps[mkey]
            n = len(cs.positions)
            ranges = position_ranges(d, cs.positions, assumed)
            q, nu = random_states(n, k * n_states, rng, ranges)
            q = regular_states(cmap, q, rng, ranges)
            q, nu = q.reshape(k, n_states, n), nu.reshape(k, n_states, n)
            if announce:
                self._stage(d, "truth")
            truth = truth_for(cmap, sets, q, nu)
            apply_to_truth(truth, assumed)
            self._truth[key] = (truth, sets, q, nu, cs)
        return self._truth[key]

    def _document(self, d: Derivation, funcs: DocumentFunctions, sets, q, nu, H_rows=None):
        r"""``(document arrays, symbol values per set, symbol values per sample)`` on a grid."""
        rng = np.random.default_rng(self.seed + 1)
        k, n_states, n = q.shape
        per_set = [document_symbol_values(d, ps, rng) for ps in sets]
        values = {s: np.repeat([v[s] for v in per_set], n_states) for s in funcs.params}
        doc = funcs.evaluate(q.reshape(-1, n), nu.reshape(-1, n), values)
        if doc.H is not None and H_rows is not None:
            doc.H = doc.H[H_rows]
        return doc, per_set, values

    def _identification(self, d: Derivation, ev: SearchEvaluation):
        r"""``(document, truth, positions, symbol values, true B)`` on the grid functions of
        the state are identified on: :data:`ROW_FUNCTION_SETS` parameter sets (a quantity of
        the parameters alone takes one value per set)."""
        truth, sets, q, nu, _ = self._grid(d, (), ROW_FUNCTION_STATES, ROW_FUNCTION_SETS,
                                           declared(d))
        doc, per_set, values = self._document(d, ev.funcs, sets, q, nu, truth.H_rows)
        B_true = input_map(d, truth, per_set, ROW_FUNCTION_STATES, [])
        return doc, truth, q.reshape(-1, d.n), values, B_true

    def _row_functions(self, d: Derivation, ev: SearchEvaluation) -> dict[int, sp.Expr]:
        r"""Rows the document divided by a function of the state or of the parameters
        (:mod:`.row_functions`)."""
        rows = row_functions.candidate_rows(ev.doc, ev.truth, ev.row_factor)
        if not rows:
            return {}
        doc, truth, q, values, _ = self._identification(d, ev)
        return row_functions.state_row_factors(d, doc, truth, q, values, rows)

    def _row_combination(self, d: Derivation, ev: SearchEvaluation
                         ) -> tuple[Derivation, sp.Matrix] | None:
        r"""``d`` with the combination of the true equations its rows are undone, and that
        combination :math:`W` (:mod:`.row_combinations`); None when its rows are no such
        combination (or declares, or was found to have, rows scaled: not combined here)."""
        if d.row_scale is not None or \
                row_combinations.combination(ev.doc, ev.truth, ev.B_true) is None:
            return None
        doc, truth, q, values, B_true = self._identification(d, ev)
        W = row_combinations.combination(doc, truth, B_true)
        if W is None:
            return None
        W = row_combinations.fit_combination(W, row_functions.bases(d, q, values))
        undone = None if W is None else row_combinations.separated(d, W)
        return None if undone is None else (undone, W)

    # -- main ----------------------------------------------------------------------------
    def compare(self, d: Derivation) -> DerivationResult:
        r"""The comparison of one derivation (memoised per file and content)."""
        key = (str(d.path), d.path.stat().st_mtime_ns if d.path.exists() else 0)
        if key not in self._results:
            from .steps.chain import with_steps          # earlier steps, upstream causes
            self._results[key] = with_steps(d, self._compare, self.seed, self.parallel_steps,
                                            lambda stage: self._stage(d, stage))
        return self._results[key]

    def _compare(self, d: Derivation) -> DerivationResult:
        r"""The comparison under the declared reading of the file's maps, or under a better
        sign convention when one explains :data:`conventions.MIN_GAIN` more elements
        (:mod:`.conventions`); then the root causes (:mod:`.causes`)."""
        result, ev = self._judge(d, announce=True)
        self._stage(d, "readings")
        first: list[Cause] = []
        rows = conventions.best_row_order(d, ev.doc_at, ev.score)
        if rows is not None:
            ordered = conventions.reordered(d, rows[0])
            again, ev2 = self._judge(ordered)
            if again.counts()["agrees"] > result.counts()["agrees"]:
                d = ordered
                first.append(Cause(kind="convention", elements=(), explanation=(
                    "the equations are printed in another order than the coordinates ("
                    f"{conventions.describe_rows(d, rows[0])}): compared in that order")))
                result, ev = again, ev2
        factors = self._row_functions(d, ev)
        if factors:
            scaled = row_functions.with_row_factors(d, factors)
            again, ev2 = self._judge(scaled)
            if again.counts()["agrees"] > result.counts()["agrees"]:
                first.append(Cause(kind="convention", elements=(), explanation=(
                    f"{row_functions.describe_factors(d, factors)}: compared so (an equation "
                    "divided by a quantity that does not vanish is as right as before)")))
                d, ev = scaled, ev2
                result = replace(again, row_functions=tuple(
                    sp.sstr(factors[i]) if i in factors else None for i in range(d.n)))
        combined = self._row_combination(d, ev) if result.counts()["differs"] else None
        if combined is not None:
            again, ev2 = self._judge(combined[0])
            if again.counts()["agrees"] > result.counts()["agrees"]:
                first.append(Cause(kind="convention", elements=(), explanation=(
                    f"{row_combinations.describe(combined[1])}: compared with the combination "
                    "undone (an equivalent system: the same motions)")))
                d, ev = combined[0], ev2
                result = replace(again, row_functions=result.row_functions,
                                 row_combination=row_combinations.as_text(combined[1]))
        declared_counts = result.counts()
        summary = None
        best = conventions.best_reading(d, ev.doc_at, ev.score, ev.score_readings)
        if best is not None:
            reading = best[0]
            flipped = conventions.flipped(d, *reading)
            better, ev2 = self._judge(flipped)
            if better.counts()["agrees"] > declared_counts["agrees"]:
                before = {r.element for r in result.records if r.verdict != "agrees"}
                now = {r.element for r in better.records if r.verdict == "agrees"}
                text = conventions.describe(d, *reading)
                summary = ConventionSummary(
                    declared=Convention("as declared: " + conventions.maps_text(d),
                                        declared_counts),
                    best=Convention(f"{text} ({conventions.maps_text(flipped)})",
                                    better.counts()),
                    finding=(f"read as {conventions.maps_text(flipped)} instead of the file's "
                             f"{conventions.maps_text(d)} ({text}), "
                             f"{better.counts()['agrees']} elements agree instead of "
                             f"{declared_counts['agrees']}"))
                kind = "swapped_inputs" if conventions.is_permutation_only(reading) \
                    else "convention"
                first.append(Cause(kind=kind, elements=tuple(sorted(before & now)),
                                   explanation=summary.finding + "; the elements below are "
                                   "compared under this reading"))
                result, ev, d = better, ev2, flipped
        if summary is None:
            summary = ConventionSummary(declared=Convention("as declared", declared_counts))
        self._stage(d, "causes")
        found = causes.root_causes(ev, d, result.records, result.energy, result.asymmetric,
                                   first)
        return replace(result, causes=found, conventions=summary)

    def _judge(self, d: Derivation, announce: bool = False
               ) -> tuple[DerivationResult, causes.Evaluation]:
        if announce:
            self._stage(d, "grid")
        terms = d.read_off(assume=True, unscale=True)
        n = d.n
        C = d.C
        if C is not None and d.row_scale is not None:
            C = sp.ImmutableMatrix([[e / d.row_scale[i] for e in C.row(i)]
                                    for i in range(C.rows)])      # row by row: keeps "?" local
        if C is not None and d.assumptions:
            C = sp.ImmutableMatrix(d.apply_assumptions(C))
        G = d.G if d.G is not None else d.constraint_matrix()
        funcs = DocumentFunctions(d, terms.A, C, terms.Q, terms.B, terms.h, G)
        read = d.read_off(assume=True, unscale=False)
        as_printed = {"A": read.A, "Q": read.Q, "B": read.B, "h": read.h, "C": d.C}
        assumed = declared(d)
        truth, sets, q, nu, cs = self._grid(d, (), self.samples, self.param_sets, assumed,
                                            announce)
        cs_name = cs.name
        if announce:
            self._stage(d, "document")
        doc, per_set, values = self._document(d, funcs, sets, q, nu, truth.H_rows)
        notes: list[str] = []
        B_true = input_map(d, truth, per_set, self.samples, notes)
        row_factor = row_factors(doc, truth, B_true, n)
        cases = tuple(c for c in special_cases(d.model) if c not in assumed.families)
        if cases:
            # a document usually omits what the special families remove (armature, products
            # of inertia ...): there its rows match the truth up to their factor exactly
            t2, sets2, q2, nu2, _ = self._grid(d, tuple(cases), SPECIAL_SAMPLES, SPECIAL_SETS,
                                               assumed)
            doc2, per2, _ = self._document(d, funcs, sets2, q2, nu2, t2.H_rows)
            special = row_factors(doc2, t2, input_map(d, t2, per2, SPECIAL_SAMPLES, []), n)
            row_factor = [f if f is not None else m for f, m in zip(special, row_factor)]
        apply_row_factors(doc, row_factor)
        if announce:
            self._stage(d, "judging")
        scales = row_scales(doc, truth, n)
        dims = DimensionChecker(d)
        mapped = closed_form.document_in_model(d, tuple(c.name for c in assumed.families))
        records = []
        label = equation_labels(str(d.source.get("equations", "")))
        groups = swap_groups(d)
        flat_q, flat_nu = q.reshape(-1, n), nu.reshape(-1, n)

        argv = [*flat_q.T, *flat_nu.T, *(values[p] for p in funcs.params)]
        position = {a: k for k, a in enumerate(funcs.args)}

        screen = np.linspace(0, len(flat_q) - 1, min(SCREEN_SAMPLES, len(flat_q))).astype(int)

        def swapped(key, index, a, b, rows: np.ndarray | None = None):
            r"""The element with symbol ``a`` read as ``b`` (argument arrays permuted), at
            every sample or at the samples ``rows``."""
            trial = list(argv)
            trial[position[a]] = argv[position[b]]
            if rows is not None:
                trial = [x[rows] if np.ndim(x) and len(x) == len(flat_q) else x for x in trial]
            out = np.broadcast_to(funcs.element_function(key, index)(*trial),
                                  (len(flat_q) if rows is None else len(rows),))
            c = row_factor[index[0]]
            return out.astype(float) / (c if c is not None else 1.0)

        arrays: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        exprs: list[sp.Expr | None] = []
        lost = set(d.missing)
        names = latex_names(d)
        for key, D, T, index, expr in element_values(funcs, doc, truth, B_true, n):
            i = index[0]
            h_row_lost = key == "h" and terms.h is not None and terms.h[i].has(sp.nan)
            if element_label(key, index, d.velocities) in lost or h_row_lost or (
                    expr is not None and expr.has(sp.nan)):
                if key != "h":
                    notes.append(f"{element_label(key, index, d.velocities)} was lost in the extracted "
                                 "text: not compared")
                continue
            scale = scales[i]
            problems = dims.check(key, index, expr) if key != "h" else []
            finite = np.isfinite(D) & np.isfinite(T)
            ok = agrees(D, T, scale) and bool(finite.all())
            diags: list[str] = [f"dimension: {p}" for p in problems]
            if not finite.all():
                side = "the document's" if not np.isfinite(D).all() else "the truth's"
                diags.insert(0, f"undecided: {side} values are not finite at "
                             f"{int((~finite).sum())} of {len(finite)} samples")
            if ok and problems:
                diags.append("numerically equal here only because the inconsistent term "
                             "vanishes for this model's parameters")
            if not ok and finite.all():
                diags += value_diagnoses(D, T, scale)
                if expr is not None and key != "h" and not any(
                        x.startswith(("sign", "extra", "missing")) for x in diags):
                    diags[:0] = element_term_diagnoses(expr, funcs, argv, row_factor[i], D, T, scale,
                                                any(x.startswith("factor") for x in diags))
                if expr is not None and key != "h" and not any(
                        x.startswith(("sign", "factor", "extra")) for x in diags):
                    diags += swap_diagnoses(
                        expr, groups, lambda a, b: swapped(key, index, a, b), T, scale,
                        lambda a, b: agrees(swapped(key, index, a, b, screen), T[screen], scale))
                if expr is not None and key == "h" and not diags:     # a velocity product's
                    diags += trig_diagnoses(expr, funcs, argv, row_factor[i], D, T, scale,
                                             check=True)
            verdict = ("undecided" if not finite.all() else
                       "agrees" if ok and not problems else "differs")
            shown = element_expr(as_printed, key, index, d.velocities)
            text, latex = ("", "") if shown is None else printed(shown, names)
            records.append(dict(element=element_label(key, index, d.velocities), key=key, index=index,
                                verdict=verdict, diagnoses=diags, document=text,
                                document_latex=latex,
                                **dict(zip(("document_model", "model_latex"), mapped(expr))),
                                truth=None, residual=None, max_error=max_error(D, T),
                                scale=float(scale), truth_sample=float(T[0]),
                                document_sample=float(D[0]), equation=label))
            arrays[id(records[-1])] = (D, T)
            exprs.append(expr)
        self._h_swaps(records, arrays)
        self._special(d, funcs, records, row_factor, assumed)
        self._factorization(records, n)
        closed_form.annotate(d, records, cs, {id(r): e for r, e in zip(records, exprs)},
                             tuple(row_factor), tuple(c.name for c in assumed.families))
        energy = energy_check(funcs, doc, row_factor, flat_q, flat_nu, values, d)
        asym = asymmetry(doc, scales, n)
        constraints = constraint_rows(doc, truth, scales)
        ev = SearchEvaluation(funcs=funcs, doc=doc, truth=truth, B_true=B_true, scales=scales,
                         q=flat_q, nu=flat_nu, values=values, row_factor=tuple(row_factor),
                         kind=cs.kind)
        return DerivationResult(
            path=d.path, title=d.title, model=d.model, source=dict(d.source), coordinates=cs_name,
            velocities=tuple(str(v) for v in d.velocities), form=d.form,
            records=tuple(ElementRecord(**r) for r in records),
            row_factors=tuple(None if c is None else nice_number(c) for c in row_factor),
            energy=energy, asymmetric=asym, constraints=constraints,
            reconstructed=dict(d.reconstructed), samples=self.samples,
            parameter_sets=self.param_sets, notes=tuple(notes), assumes=assumed.describe(),
            latex_input=dict(d.latex_input)), ev

    # -- refinements ---------------------------------------------------------------------
    @staticmethod
    def _factorization(records: list[dict], n: int) -> None:
        r"""C elements that differ while every h coefficient of their row agrees (or agrees
        only for special values) differ in factorisation only."""
        for i in range(n):
            h_row = [r for r in records if r["key"] == "h" and r["index"][0] == i]
            if not h_row or any(r["verdict"] not in ("agrees", "agrees_if") for r in h_row):
                continue
            special = any(r["verdict"] == "agrees_if" for r in h_row)
            for r in records:
                if r["key"] == "C" and r["index"][0] == i and r["verdict"] == "differs" \
                        and not any(x.startswith("dimension") for x in r["diagnoses"]):
                    r["verdict"] = "factorization"
                    r["diagnoses"] = [f"C q̇ agrees in row {i + 1}"
                                      + (" (for the special values its h terms need)" if special
                                         else "") + ": only the factorisation of C differs, "
                                      "not the equations"]

    def _special(self, d: Derivation, funcs: DocumentFunctions, records: list[dict],
                 row_factor: Sequence[float | None], assumed: Assumptions) -> None:
        r"""For elements that differ, the smallest combinations of special parameter families
        the document did not declare under which they agree."""
        cases = tuple(c for c in special_cases(d.model) if c not in assumed.families)
        todo = [r for r in records if r["verdict"] == "differs"
                and not any(x.startswith(("dimension", "sign", "factor", "swap")) for x in r["diagnoses"])]
        if not cases or not todo:
            return

        memo: dict[tuple[str, ...], set] = {}

        def agreeing(combo):
            key = tuple(c.name for c in combo)
            if key not in memo:
                memo[key] = _agreeing(combo)
            return memo[key]

        def _agreeing(combo):
            truth, sets, q, nu, _ = self._grid(d, combo, SPECIAL_SAMPLES, SPECIAL_SETS, assumed)
            doc, per_set, _ = self._document(d, funcs, sets, q, nu, truth.H_rows)
            B_true = input_map(d, truth, per_set, SPECIAL_SAMPLES, [])
            apply_row_factors(doc, row_factor)
            scales = row_scales(doc, truth, d.n)
            ok = set()
            h_values = {}
            for key, D, T, index, _ in element_values(funcs, doc, truth, B_true, d.n):
                if agrees(D, T, scales[index[0]]):
                    ok.add((key, index))
                else:                         # a constant factor that holds only here
                    found = value_diagnoses(D, T, scales[index[0]])
                    if found and found[0].startswith("factor"):
                        ok.add(("factor", key, index, found[0]))
                if key == "h":
                    h_values[index] = (D, T)
            # a document h term equal to another true h term of its row: a swapped product
            for a, (Da, Ta) in h_values.items():
                for b, (Db, Tb) in h_values.items():
                    if a != b and a[0] == b[0] and agrees(Da, Tb, scales[a[0]]) \
                            and not agrees(Da, Ta, scales[a[0]]) \
                            and not agrees(Da, 0 * Da, scales[a[0]]):
                        ok.add(("swap", a, b))
            return ok

        everything = agreeing(tuple(cases))
        by_index = {(r["key"], r["index"]): r for r in records}

        def minimal(item) -> list[SpecialCase]:
            r"""The first single family that suffices (weakest first), else a greedy
            minimal combination."""
            for case in cases:
                if item in agreeing((case,)):
                    return [case]
            needed = list(cases)
            for case in cases:
                trial = tuple(c for c in needed if c is not case)
                if item in agreeing(trial):
                    needed = list(trial)
            return needed

        for item in sorted((x for x in everything if x[0] == "swap"), key=str):
            _, a, b = item
            ra, rb = by_index.get(("h", a)), by_index.get(("h", b))
            if ra is None or rb is None or any(x.startswith("swap") for x in ra["diagnoses"]):
                continue
            if ra["verdict"] != "differs":
                continue
            text = " and ".join(c.description for c in minimal(item))
            pa, pb = ra["element"].split(":")[1], rb["element"].split(":")[1]
            ra["diagnoses"].append(f"swap: the document's {pa} term is the true {pb} term "
                                   f"(equal only if {text})")
            rb["diagnoses"].append(f"swap: written as {pa} in the document (equal only if {text})")
            for r in (ra, rb):
                if r in todo:
                    todo.remove(r)
        for r in todo:
            if (r["key"], r["index"]) not in everything:
                # no family makes it agree: a constant factor under the weakest that gives one
                for case in cases:
                    hit = next((x[3] for x in agreeing((case,))
                                if x[0] == "factor" and x[1:3] == (r["key"], r["index"])), None)
                    if hit is not None:
                        r["diagnoses"].insert(0, f"{hit} (if {case.description})")
                        break
                continue
            needed = minimal((r["key"], r["index"]))
            r["verdict"] = "agrees_if"
            text = " and ".join(c.description for c in needed) if needed else "always"
            r["diagnoses"] = [f"agrees only if {text}"] + [
                x for x in r["diagnoses"] if not x.startswith(("missing", "extra"))] + [
                x for x in r["diagnoses"] if x.startswith(("missing", "extra"))]

    @staticmethod
    def _h_swaps(records: list[dict], values: dict) -> None:
        r"""Within a row of h, an extra term equal to a missing one: the document wrote one
        velocity product for another (e.g. φ̇² where ψ̇² fits)."""
        for r_extra in records:
            if r_extra["key"] != "h" or not any(x.startswith("extra") for x in r_extra["diagnoses"]):
                continue
            for r_miss in records:
                if r_miss["key"] != "h" or r_miss["index"][0] != r_extra["index"][0] \
                        or not any(x.startswith("missing") for x in r_miss["diagnoses"]):
                    continue
                D, T = values[id(r_extra)][0], values[id(r_miss)][1]
                if agrees(D, T, r_extra["scale"]):
                    a = r_extra["element"].split(":")[1]
                    b = r_miss["element"].split(":")[1]
                    r_extra["diagnoses"].append(f"swap: the document's {a} term is the true {b} term")
                    r_miss["diagnoses"].append(f"swap: written as {a} in the document")
