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
5. checks of the document on its own: A symmetric, and the power identity
   :math:`\nu^T h = \tfrac12\nu^T\dot A\nu` (gyroscopic forces do no work) — a model that fails
   it does not conserve energy.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import replace

import numpy as np
import sympy as sp

from ..constraints.reduction import CoordinateMap
from ..derivations.schema import Derivation
from . import causes, closed_form, conventions
from .diagnose import (
    AGREE_TOL,
    agrees,
    max_error,
    nice_number,
    power_diagnoses,
    swap_diagnoses,
    term_diagnoses,
    value_diagnoses,
)
from .evaluate import (
    Arrays,
    DocumentFunctions,
    derivation_coordinate_set,
    document_symbol_values,
    truth_arrays,
)
from .result import (Cause, Convention, ConventionSummary, DerivationResult, ElementRecord,
                     EnergyCheck)
from .samples import (
    SpecialCase,
    parameter_sets,
    random_states,
    special_cases,
)
from .assumptions import Assumptions, apply_to_truth, declared, position_ranges
from .units import DimensionChecker

#: Smaller grid used to test special parameter families.
SPECIAL_SAMPLES, SPECIAL_SETS = 40, 2
#: Power residuals up to this many operations are factorised for display.
FACTOR_LIMIT = 120
#: Samples the convention search scores each reading on (spread over the parameter sets).
SEARCH_SAMPLES = 400
#: Candidate undeclared row factors, and how far an element's own ratio may be from one.
ROW_FACTORS = (1.0, -1.0, 2.0, -2.0, 0.5, -0.5)
ROW_FACTOR_SPREAD = 0.35


def _latex_names(d: Derivation) -> dict[sp.Symbol, str]:
    r"""LaTeX of velocities and accelerations as dotted coordinates (:math:`\dot\psi`)."""
    out = {}
    for q, v, a in zip(d.positions, d.velocities, d.accelerations):
        base = sp.latex(q)
        out[v] = rf"\dot{{{base}}}"
        out[a] = rf"\ddot{{{base}}}"
    return out


def _text(expr: sp.Expr | None) -> str:
    return "" if expr is None else sp.sstr(expr)


def _label(key: str, index: tuple[int, ...], velocities: Sequence[sp.Symbol]) -> str:
    if key in ("Q",):
        return f"Q[{index[0] + 1}]"
    if key == "h":
        i, j, k = index
        return f"h[{i + 1}]:{velocities[j]}*{velocities[k]}"
    return f"{key}[{index[0] + 1},{index[1] + 1}]"


class ComparisonEngine:
    r"""Compares derivations; caches the truth per (model, coordinate set, parameter family)
    so derivations sharing coordinates share the work."""

    def __init__(self, samples: int = 1000, param_sets: int = 5, seed: int = 2026) -> None:
        self.samples = samples
        self.param_sets = param_sets
        self.seed = seed
        self._truth: dict[tuple, tuple] = {}      # (truth, sets, q, nu, coordinate set)
        self._maps: dict[tuple, CoordinateMap] = {}
        self._sets: dict[tuple, object] = {}
        self._results: dict[tuple, DerivationResult] = {}

    # -- the two sides -------------------------------------------------------------------
    def _grid(self, d: Derivation, special: tuple[SpecialCase, ...], n_states: int, k: int,
              assumed: Assumptions = Assumptions()):
        special = tuple(dict.fromkeys((*assumed.families, *special)))
        key = (d.model, repr(d.coordinates.raw), d.coordinates.use,
               tuple(c.name for c in special), n_states, k, assumed.key())
        if key not in self._truth:
            rng = np.random.default_rng([self.seed, len(special), n_states])
            sets = parameter_sets(d.model, k, rng, special)
            ckey = (d.model, repr(d.coordinates.raw), d.coordinates.use)
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
            q, nu = q.reshape(k, n_states, n), nu.reshape(k, n_states, n)
            truth = _truth_for(cmap, sets, q, nu)
            apply_to_truth(truth, assumed)
            self._truth[key] = (truth, sets, q, nu, cs)
        return self._truth[key]

    def _document(self, d: Derivation, funcs: DocumentFunctions, sets, q, nu, H_rows=None):
        rng = np.random.default_rng(self.seed + 1)
        k, n_states, n = q.shape
        per_set = [document_symbol_values(d, ps, rng) for ps in sets]
        values = {s: np.repeat([v[s] for v in per_set], n_states) for s in funcs.params}
        doc = funcs.evaluate(q.reshape(-1, n), nu.reshape(-1, n), values)
        if doc.H is not None and H_rows is not None:
            doc.H = doc.H[H_rows]
        return doc, per_set

    # -- main ----------------------------------------------------------------------------
    def compare(self, d: Derivation) -> DerivationResult:
        r"""The comparison of one derivation (memoised per file and content)."""
        key = (str(d.path), d.path.stat().st_mtime_ns if d.path.exists() else 0)
        if key not in self._results:
            from .steps import with_steps          # earlier steps, upstream causes
            self._results[key] = with_steps(d, self._compare, self.seed)
        return self._results[key]

    def _compare(self, d: Derivation) -> DerivationResult:
        r"""The comparison under the declared reading of the file's maps, or under a better
        sign convention when one explains :data:`conventions.MIN_GAIN` more elements
        (:mod:`.conventions`); then the root causes (:mod:`.causes`)."""
        result, ev = self._judge(d)
        first: list[Cause] = []
        rows = conventions.best_row_order(d, ev.doc_at, ev.score)
        if rows is not None:
            again, ev2 = self._judge(conventions.reordered(d, rows[0]))
            if again.counts()["agrees"] > result.counts()["agrees"]:
                d = conventions.reordered(d, rows[0])
                first.append(Cause(kind="convention", elements=(), explanation=(
                    "the equations are printed in another order than the coordinates ("
                    f"{conventions.describe_rows(d, rows[0])}): compared in that order")))
                result, ev = again, ev2
        declared_counts = result.counts()
        summary = None
        best = conventions.best_reading(d, ev.doc_at, ev.score) if conventions.readings(d) \
            else None
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
        found = causes.root_causes(ev, d, result.records, result.energy, result.asymmetric,
                                   first)
        return replace(result, causes=found, conventions=summary)

    def _judge(self, d: Derivation) -> tuple[DerivationResult, causes.Evaluation]:
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
        as_printed = d.read_off(assume=True, unscale=False)
        printed = {"A": as_printed.A, "Q": as_printed.Q, "B": as_printed.B, "h": as_printed.h,
                   "C": d.C}
        assumed = declared(d)
        truth, sets, q, nu, cs = self._grid(d, (), self.samples, self.param_sets, assumed)
        cs_name = cs.name
        doc, per_set = self._document(d, funcs, sets, q, nu, truth.H_rows)
        notes: list[str] = []
        B_true = _input_map(d, truth, per_set, self.samples, notes)
        row_factor = _row_factors(doc, truth, B_true, n)
        cases = tuple(c for c in special_cases(d.model) if c not in assumed.families)
        if cases:
            # a document usually omits what the special families remove (armature, products
            # of inertia ...): there its rows match the truth up to their factor exactly
            t2, sets2, q2, nu2, _ = self._grid(d, tuple(cases), SPECIAL_SAMPLES, SPECIAL_SETS,
                                               assumed)
            doc2, per2 = self._document(d, funcs, sets2, q2, nu2, t2.H_rows)
            special = _row_factors(doc2, t2, _input_map(d, t2, per2, SPECIAL_SAMPLES, []), n)
            row_factor = [f if f is not None else m for f, m in zip(special, row_factor)]
        _apply_row_factors(doc, row_factor)
        scales = _row_scales(doc, truth, n)
        dims = DimensionChecker(d)
        mapped = closed_form.document_in_model(d)
        records = []
        groups = _swap_groups(d)
        flat_q, flat_nu = q.reshape(-1, n), nu.reshape(-1, n)
        values = {s: np.repeat([v[s] for v in per_set], self.samples) for s in funcs.params}

        argv = [*flat_q.T, *flat_nu.T, *(values[p] for p in funcs.params)]
        position = {a: k for k, a in enumerate(funcs.args)}

        def swapped(key, index, a, b):
            r"""The element with symbol ``a`` read as ``b`` (argument arrays permuted)."""
            trial = list(argv)
            trial[position[a]] = argv[position[b]]
            out = np.broadcast_to(funcs.element_function(key, index)(*trial), (len(flat_q),))
            c = row_factor[index[0]]
            return out.astype(float) / (c if c is not None else 1.0)

        arrays: dict[int, tuple[np.ndarray, np.ndarray]] = {}
        exprs: list[sp.Expr | None] = []
        lost = set(d.missing)
        names = _latex_names(d)
        for key, D, T, index, expr in _elements(funcs, doc, truth, B_true, n):
            i = index[0]
            h_row_lost = key == "h" and terms.h is not None and terms.h[i].has(sp.nan)
            if _label(key, index, d.velocities) in lost or h_row_lost or (
                    expr is not None and expr.has(sp.nan)):
                if key != "h":
                    notes.append(f"{_label(key, index, d.velocities)} was lost in the extracted "
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
                    diags[:0] = _term_diagnoses(expr, funcs, argv, row_factor[i], D, T, scale,
                                                any(x.startswith("factor") for x in diags))
                if expr is not None and key != "h" and not any(
                        x.startswith(("sign", "factor", "extra")) for x in diags):
                    diags += swap_diagnoses(expr, groups, lambda a, b: swapped(key, index, a, b),
                                            T, scale)
            verdict = ("undecided" if not finite.all() else
                       "agrees" if ok and not problems else "differs")
            records.append(dict(element=_label(key, index, d.velocities), key=key, index=index,
                                verdict=verdict, diagnoses=diags,
                                document=_text(shown := _element_expr(printed, key, index, d.velocities)),
                                document_latex="" if shown is None else sp.latex(shown, symbol_names=names),
                                **dict(zip(("document_model", "model_latex"), mapped(expr))),
                                truth=None, residual=None, max_error=max_error(D, T),
                                scale=float(scale), truth_sample=float(T[0]),
                                document_sample=float(D[0])))
            arrays[id(records[-1])] = (D, T)
            exprs.append(expr)
        self._h_swaps(records, arrays)
        self._special(d, funcs, records, row_factor, assumed)
        self._factorization(records, n)
        closed_form.annotate(d, records, cs, {id(r): e for r, e in zip(records, exprs)},
                             tuple(row_factor))
        energy = _energy(funcs, doc, row_factor, flat_q, flat_nu, values, d)
        asym = _asymmetric(doc, scales, n)
        constraints = _constraints(doc, truth, scales)
        ev = _Evaluation(funcs=funcs, doc=doc, truth=truth, B_true=B_true, scales=scales,
                         q=flat_q, nu=flat_nu, values=values, row_factor=tuple(row_factor),
                         kind=cs.kind)
        return DerivationResult(
            path=d.path, title=d.title, model=d.model, source=dict(d.source), coordinates=cs_name,
            velocities=tuple(str(v) for v in d.velocities), form=d.form,
            records=tuple(ElementRecord(**r) for r in records),
            row_factors=tuple(None if c is None else nice_number(c) for c in row_factor),
            energy=energy, asymmetric=asym, constraints=constraints,
            reconstructed=dict(d.reconstructed), samples=self.samples,
            parameter_sets=self.param_sets, notes=tuple(notes), assumes=assumed.describe()), ev

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
            doc, per_set = self._document(d, funcs, sets, q, nu, truth.H_rows)
            B_true = _input_map(d, truth, per_set, SPECIAL_SAMPLES, [])
            _apply_row_factors(doc, row_factor)
            scales = _row_scales(doc, truth, d.n)
            ok = set()
            h_values = {}
            for key, D, T, index, _ in _elements(funcs, doc, truth, B_true, d.n):
                if agrees(D, T, scales[index[0]]):
                    ok.add((key, index))
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


class _Evaluation(causes.Evaluation):
    r"""The engine's evaluation, with what the convention search needs: the document at
    sign-flipped states and the number of elements agreeing in a set of arrays."""

    def _subset(self) -> tuple[np.ndarray, Arrays, np.ndarray | None]:
        r"""The samples the search scores on: those where the truth has H (the first
        :data:`~.evaluate.H_SAMPLES` states of every parameter set), at most
        :data:`SEARCH_SAMPLES`; the truth and its B there."""
        if not hasattr(self, "_sub"):
            rows = self.truth.H_rows if self.truth.H_rows is not None \
                else np.arange(len(self.q))
            keep = np.arange(len(rows))
            if len(rows) > SEARCH_SAMPLES:
                keep = np.linspace(0, len(rows) - 1, SEARCH_SAMPLES).astype(int)
            rows = rows[keep]
            sub = Arrays(**{k: (None if getattr(self.truth, k) is None
                                else getattr(self.truth, k)[rows]) for k in "ACQBhG"})
            sub.H = None if self.truth.H is None else self.truth.H[keep]
            B = None if self.B_true is None else self.B_true[rows]
            self._sub = (rows, sub, B)
        return self._sub

    def doc_at(self, s: Sequence[int]) -> Arrays:
        r"""The document's arrays at :math:`(Sp, S\nu)` on the search's samples (rows not
        yet divided by factors)."""
        rows, _, _ = self._subset()
        S = np.asarray(s, float)
        values = {p: np.asarray(v)[rows] if np.ndim(v) else v for p, v in self.values.items()}
        return self.funcs.evaluate(self.q[rows] * S, self.nu[rows] * S, values)

    def score(self, doc: Arrays) -> int:
        r"""Elements of ``doc`` (on the search's samples) that agree with the truth, after
        its own row factors."""
        n = self.q.shape[1]
        _, truth, B_true = self._subset()
        factors = _row_factors(doc, truth, B_true, n)
        _apply_row_factors(doc, factors)
        scales = _row_scales(doc, truth, n)
        return sum(bool(np.isfinite(D).all()) and agrees(D, T, scales[index[0]])
                   for _, D, T, index, _ in _elements(self.funcs, doc, truth, B_true, n,
                                                      expressions=False))


def _term_diagnoses(expr: sp.Expr, funcs: DocumentFunctions, argv: Sequence[np.ndarray],
                    factor: float | None, D: np.ndarray, T: np.ndarray, scale: float,
                    has_factor: bool) -> list[str]:
    r"""A parameter to the wrong power (also where a constant factor fits: with a geometry
    constant the sets do not vary, G for G² *is* a factor), then, when the element has no
    diagnosis yet, one additive term with the wrong sign or factor (:mod:`.diagnose`)."""
    c = 1.0 if factor is None else factor

    def evaluate(e: sp.Expr) -> np.ndarray:
        with np.errstate(all="ignore"):           # a trial power may leave the reals: NaN
            out = funcs.compiled(e)(*argv)
        return np.broadcast_to(np.asarray(out, float), D.shape) / c

    found = power_diagnoses(expr, funcs.params, evaluate, T, scale)
    if not found and not has_factor:
        found = term_diagnoses(expr, evaluate, D, T, scale)
    return found


def _truth_for(cmap: CoordinateMap, sets, q, nu) -> Arrays:
    r"""The truth at every parameter set (B in the model's inputs)."""
    parts = []
    for k, ps in enumerate(sets):
        cmap.bind(ps.model)
        parts.append(truth_arrays([cmap], q[k:k + 1], nu[k:k + 1], None))
    out = Arrays()
    for name in ("A", "C", "Q", "B", "h", "H", "G"):
        vals = [getattr(p, name) for p in parts]
        setattr(out, name, None if vals[0] is None else np.concatenate(vals))
    n_states = q.shape[1]
    out.H_rows = np.concatenate([k * n_states + p.H_rows for k, p in enumerate(parts)])
    return out


def _input_map(d: Derivation, truth: Arrays, per_set, n_states: int, notes: list[str]):
    r"""The truth's B in the document's inputs: :math:`B\,\partial\tau/\partial u_{doc}`."""
    if not d.input_symbols or not d.inputs:
        if d.input_symbols:
            notes.append("the file maps no model input to the document's inputs: B not compared")
        return None
    from ..models.registry import load_model
    names = load_model(d.model).input_names
    f = sp.Matrix([d.inputs.get(name, 0) for name in names])
    P = f.jacobian(sp.Matrix(d.input_symbols))
    Ps = np.stack([np.array(P.xreplace(v), dtype=float) for v in per_set])
    Ps = np.repeat(Ps, n_states, axis=0)
    return truth.B @ Ps


def _element_expr(exprs: Mapping[str, object], key: str, index: tuple[int, ...],
                  velocities: Sequence[sp.Symbol]) -> sp.Expr | None:
    r"""The expression of one element (for h: the coefficient of a velocity product)."""
    M = exprs.get(key if key != "h" else "h")
    if M is None:
        return None
    if key == "Q":
        return M[index[0]]
    if key == "h":
        i, j, k = index
        h = _expanded(M[i])
        if j == k:
            return h.coeff(velocities[j], 2)
        return h.coeff(velocities[j], 1).coeff(velocities[k], 1)
    return M[index]


_EXPANDED: dict[sp.Expr, sp.Expr] = {}


def _expanded(expr: sp.Expr) -> sp.Expr:
    if expr not in _EXPANDED:
        _EXPANDED[expr] = sp.expand(expr)
    return _EXPANDED[expr]


def _elements(funcs: DocumentFunctions, doc: Arrays, truth: Arrays, B_true, n: int,
              expressions: bool = True):
    r"""(key, document values, true values, index, document expression) of every element
    (the expression None without ``expressions``)."""
    ex, vel = funcs.exprs, funcs.d.velocities
    if not expressions:
        ex = {k: (None if v is None else _Nones()) for k, v in ex.items()}
    if doc.A is not None:
        for i in range(n):
            for j in range(n):
                yield "A", doc.A[:, i, j], truth.A[:, i, j], (i, j), ex["A"][i, j]
    if doc.C is not None:
        for i in range(n):
            for j in range(n):
                yield "C", doc.C[:, i, j], truth.C[:, i, j], (i, j), ex["C"][i, j]
    if doc.Q is not None:
        for i in range(n):
            yield "Q", doc.Q[:, i], truth.Q[:, i], (i,), ex["Q"][i]
    if doc.B is not None and B_true is not None:
        for i in range(n):
            for j in range(doc.B.shape[2]):
                yield "B", doc.B[:, i, j], B_true[:, i, j], (i, j), ex["B"][i, j]
    if doc.H is not None:
        for i in range(n):
            for j in range(n):
                for k in range(j, n):
                    w = 1.0 if j == k else 2.0
                    yield ("h", w * doc.H[:, i, j, k], w * truth.H[:, i, j, k], (i, j, k),
                           _element_expr(ex, "h", (i, j, k), vel) if expressions else None)


class _Nones:
    r"""Stands for a matrix of expressions that are not needed: every element is None."""

    def __getitem__(self, index) -> None:
        return None


def _row_factors(doc: Arrays, truth: Arrays, B_true, n: int) -> list[float | None]:
    r"""A constant :math:`c_i` with document row i = :math:`c_i` × true row i that the file did
    not declare (e.g. −1 for Kane's generalised inertia forces :math:`F^* = -(A\ddot q + h)`).

    Each nonzero element of the row votes for the candidate of :data:`ROW_FACTORS` nearest its
    own least-squares ratio (within :data:`ROW_FACTOR_SPREAD`); a candidate other than 1 needs
    a strict majority among A's entries and among all of the row's (A, Q, B). Voting keeps a
    single wrong coefficient (e.g. 3(m_c + m_s)) from scaling a row."""
    out: list[float | None] = []
    for i in range(n):
        a_pairs, other_pairs = [], []
        if doc.A is not None:
            a_pairs = [(doc.A[:, i, j], truth.A[:, i, j]) for j in range(doc.A.shape[2])]
        if doc.Q is not None:
            other_pairs.append((doc.Q[:, i], truth.Q[:, i]))
        if doc.B is not None and B_true is not None:
            other_pairs += [(doc.B[:, i, j], B_true[:, i, j]) for j in range(doc.B.shape[2])]

        def vote(pairs):
            votes = []
            for D, T in pairs:
                tt = float(T @ T)
                if tt <= 0 or float(D @ D) <= 0:
                    continue
                c = float(D @ T / tt)
                best = min(ROW_FACTORS, key=lambda f: abs(c - f))
                votes.append(best if abs(c - best) <= ROW_FACTOR_SPREAD * abs(best) else None)
            return votes

        # A's entries decide; Q and B only confirm (a wrong input map must not scale a row)
        votes_a, votes_all = vote(a_pairs), vote(a_pairs + other_pairs)
        winner = None
        for f in ROW_FACTORS:
            if f == 1.0 or not votes_a:
                continue
            if sum(v == f for v in votes_a) * 2 > len(votes_a) and \
                    sum(v == f for v in votes_all) * 2 > len(votes_all):
                winner = f
        out.append(winner)
    return out


def _apply_row_factors(doc: Arrays, factors) -> None:
    for i, c in enumerate(factors):
        if c is None:
            continue
        for name in ("A", "C", "Q", "B", "h", "H"):
            M = getattr(doc, name)
            if M is not None:
                M[:, i] = M[:, i] / c


def _row_scales(doc: Arrays, truth: Arrays, n: int) -> np.ndarray:
    s = np.zeros(n)
    for arrays in (doc, truth):
        for name in ("A", "C", "Q", "H"):
            M = getattr(arrays, name)
            if M is not None:
                s = np.maximum(s, np.abs(M.reshape(M.shape[0], n, -1)).max(axis=(0, 2)))
    return np.where(s > 0, s, 1.0)


def _swap_groups(d: Derivation) -> list[list[sp.Symbol]]:
    by_units: dict[str, list[sp.Symbol]] = {}
    for spec in d.symbols.values():
        if not spec.is_input and spec.units:
            by_units.setdefault(spec.units.replace(" ", ""), []).append(spec.symbol)
    return [list(d.velocities), list(d.positions), *[g for g in by_units.values() if len(g) > 1]]


def _energy(funcs: DocumentFunctions, doc: Arrays, row_factor, q, nu, values, d: Derivation):
    r"""Power identity of the document on its own (rows divided by their detected factors)."""
    A, h = funcs.exprs["A"], funcs.exprs["h"]
    if A is None or h is None or A.has(sp.nan) or h.has(sp.nan):
        return None
    scale = sp.diag(*[1 if c is None else sp.nsimplify(1 / c) for c in row_factor])
    A = scale * sp.Matrix(A)
    h = scale * sp.Matrix(h)
    v = sp.Matrix(d.velocities)
    rates = position_rates(d)
    if any(rates[p] is None for p in d.positions if A.diff(p) != sp.zeros(d.n, d.n)):
        return None                       # A depends on a position whose rate is not known
    Adot = sum((A.diff(p) * rates[p] for p in d.positions if rates[p] is not None),
               sp.zeros(d.n, d.n))
    power = (v.T * h)[0] - (v.T * Adot * v)[0] / 2
    fn = sp.lambdify(funcs.args, power, "numpy")
    fh = sp.lambdify(funcs.args, (v.T * h)[0], "numpy")
    argv = [*q.T, *nu.T, *(values[p] for p in funcs.params)]
    P = np.broadcast_to(fn(*argv), (len(q),))
    # scale: the power's parts, and (when both vanish, e.g. Euler's gyroscopic terms) the
    # kinetic-energy rate scale |A| |nu|^2 |nu|
    kinetic = sp.lambdify(funcs.args, (v.T * A * v)[0], "numpy")
    speed = np.linalg.norm(nu, axis=1)
    ref = max(float(np.abs(np.broadcast_to(fh(*argv), (len(q),))).max()),
              float(np.abs(np.broadcast_to(kinetic(*argv), (len(q),)) * speed).max()), 1e-300)
    conserves = bool(np.abs(P).max() <= AGREE_TOL * ref * 10)
    residual = "0"
    if not conserves:
        expr = sp.expand(sp.expand_trig(power))
        residual = sp.sstr(sp.factor(expr) if sp.count_ops(expr) <= FACTOR_LIMIT else expr)
    return EnergyCheck(conserves, float(np.abs(P).max()), residual)


def position_rates(d: Derivation) -> dict[sp.Symbol, sp.Expr | None]:
    r"""The rate of each document position along the motion, in the document's velocities.

    Holonomic sets: :math:`\dot q_k` is the k-th velocity. Quasi-velocity sets: with the
    configuration :math:`c = e(p)` (model coordinates of the document's positions) and the
    velocity map :math:`\nu = V(c)\,\dot c`, the rates solve
    :math:`\nu_i = \sum_c V_{ic}\,\sum_k \partial e_c/\partial p_k\,\dot p_k` for the
    velocities whose map involves configured coordinates only. A position no equation fixes
    (the distance x travelled along the heading) gets None. Built-in sets: the velocity
    ``d<position>`` is the position's rate when the set has it (the built-in quasi set's
    heading speed ``dx`` is not the rate of any coordinate the matrices depend on)."""
    spec = d.coordinates
    if spec.kind != "quasi" or spec.use:
        return dict(zip(d.positions, d.velocities))
    rates = sp.symbols(f"rate_0:{d.n}")
    model_rate = {}
    for name, e in spec.configuration.items():
        e = sp.sympify(e).xreplace(d.model_values)
        model_rate[f"d{name}"] = sum((e.diff(p) * r for p, r in zip(d.positions, rates)),
                                     sp.Integer(0))
    eqs = []
    for vel in d.velocities:
        expr = spec.velocity_map.get(str(vel))
        if expr is None:
            continue
        if any(s.name.startswith("d") and s.name not in model_rate
               and s.name not in spec.configuration for s in expr.free_symbols):
            continue                      # involves a model velocity no position fixes
        sub = {s: model_rate[s.name] for s in expr.free_symbols if s.name in model_rate}
        sub.update({s: sp.sympify(spec.configuration[s.name]).xreplace(d.model_values)
                    for s in expr.free_symbols if s.name in spec.configuration})
        eqs.append(expr.xreplace(sub) - vel)
    found = _solve_rates(eqs, rates, d) if eqs else {}
    return {p: found.get(r) for p, r in zip(d.positions, rates)}


#: Seed of the generic point at which the rank of the rate equations is read.
RATE_POINT_SEED = 4099
#: Relative size below which a singular value of the rate equations counts as zero.
RATE_RANK_TOL = 1e-9


def _solve_rates(eqs: Sequence[sp.Expr], rates: Sequence[sp.Symbol], d: Derivation
                 ) -> dict[sp.Symbol, sp.Expr]:
    r"""The rates the linear equations :math:`M(p)\,r = b` fix, as expressions.

    A rate :math:`r_k` is fixed when :math:`e_k` lies in the row space of :math:`M`, read at
    a generic point (numbers for every symbol). Independent rows and pivot columns found
    there give a square system solved by LU without simplification (``sp.solve`` on
    trigonometric coefficients can run for hours); rates outside the pivots are set to 0."""
    M = sp.Matrix(eqs).jacobian(list(rates))
    b = -sp.Matrix(eqs).xreplace({r: 0 for r in rates})
    symbols = sorted(M.free_symbols | b.free_symbols, key=str)
    rng = np.random.default_rng(RATE_POINT_SEED)
    point = dict(zip(symbols, rng.uniform(0.3, 1.2, len(symbols))))
    try:
        Mn = np.array(M.xreplace(point).evalf(), dtype=float)
    except (TypeError, ValueError):
        return {}
    if not np.all(np.isfinite(Mn)) or not Mn.size:
        return {}
    _, s, vt = np.linalg.svd(Mn)
    rank = int((s > RATE_RANK_TOL * max(s[0], 1e-300)).sum())
    if rank == 0:
        return {}
    null = vt[rank:]
    fixed = [k for k in range(len(rates)) if not null.size or
             np.abs(null[:, k]).max() <= RATE_RANK_TOL]
    rows = _independent(Mn, rank)
    cols = _independent(Mn[rows].T, rank)
    sol = M.extract(rows, cols).LUsolve(b.extract(rows, [0]))
    value = dict(zip((rates[c] for c in cols), sol))
    return {rates[k]: value.get(rates[k], sp.Integer(0)) for k in fixed}


def _independent(Mn: np.ndarray, rank: int) -> list[int]:
    r"""``rank`` linearly independent rows of ``Mn`` (greedy, in order)."""
    chosen: list[int] = []
    for i in range(Mn.shape[0]):
        trial = Mn[chosen + [i]]
        if np.linalg.matrix_rank(trial, tol=RATE_RANK_TOL * max(np.abs(Mn).max(), 1e-300)) \
                > len(chosen):
            chosen.append(i)
        if len(chosen) == rank:
            break
    return chosen


def _asymmetric(doc: Arrays, scales, n: int) -> tuple[str, ...]:
    r"""Pairs A[i,j] ≠ A[j,i], and whether A is positive definite (elements lost in the
    extracted text, NaN, are left out; A with a lost element is not tested for definiteness)."""
    if doc.A is None:
        return ()
    out = []
    lost = ~np.isfinite(doc.A).all(axis=0)
    for i in range(n):
        for j in range(i + 1, n):
            if lost[i, j] or lost[j, i]:
                continue
            if not agrees(doc.A[:, i, j], doc.A[:, j, i], max(scales[i], scales[j])):
                out.append(f"A[{i + 1},{j + 1}] ≠ A[{j + 1},{i + 1}]")
    if lost.any():
        return tuple(out)
    sym = 0.5 * (doc.A + np.swapaxes(doc.A, 1, 2))
    lowest = np.linalg.eigvalsh(sym)[:, 0] / np.maximum(np.abs(sym).max(axis=(1, 2)), 1e-300)
    if (lowest <= AGREE_TOL).any():
        out.append(f"A is not positive definite at {int((lowest <= AGREE_TOL).sum())} of "
                   f"{len(lowest)} samples (smallest eigenvalue {lowest.min():.2g} × its largest entry)")
    return tuple(out)


def _constraints(doc: Arrays, truth: Arrays, scales) -> tuple[str, ...]:
    r"""Is each row of the document's G a combination of the true constraint rows?"""
    if doc.G is None:
        return ()
    if truth.G is None:
        return ("the document keeps constraints the coordinate set eliminates: G not compared",)
    out = []
    Gt = truth.G
    proj = np.linalg.pinv(Gt) @ Gt                      # projector on the true row space
    for r in range(doc.G.shape[1]):
        row = doc.G[:, r, :]
        off = np.einsum("si,sij->sj", row, proj) - row
        worst = float((np.abs(off).max(axis=1) / np.maximum(np.abs(row).max(axis=1), 1e-12)).max())
        out.append(f"G row {r + 1}: " + ("a rolling constraint of the model" if worst < 1e-6 else
                                          f"not a rolling constraint of the model (off by {worst:.2g})"))
    return tuple(out)
