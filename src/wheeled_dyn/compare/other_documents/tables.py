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

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import sympy as sp

from ...compiled import numpy_function
from ...constraints.reduction import CoordinateMap
from ...derivations.parse import load_derivation
from ...disk_cache import DiskMemo
from ...derivations.schema import Derivation
from ...derivations.table import ComparisonTable, TableEntry
from ...errors import DerivationError
from ..judge.diagnose import agrees
from ..records import Diagnosis, DiagnosisKind, first_of
from ..readings.row_factors import ROW_FACTORS
from ..engine import ComparisonEngine
from ..grid.grid import derivation_coordinate_set
from ..sides.document import model_value
from ..records import DerivationResult
from ..grid.samples import (
    ParameterSet,
    SpecialCase,
    parameter_sets,
    random_states,
    special_cases,
)

#: Special cases assumed beside the table's substitution (neither seed-001 document models the
#: motors, so the truth is taken without armature).
ALSO_ASSUMED: tuple[str, ...] = ("no_armature",)
#: Grid of the document comparison: parameter sets of the table's family × states each.
FAMILY_SETS, FAMILY_STATES = 3, 60
#: Random points of the identity checks of printed expressions, and their tolerance.
CHECK_POINTS, CHECK_TOL = 12, 1e-9

MACHINE_VERDICTS = ("match", "mismatch", "factorization")


@dataclass(frozen=True)
class TableRow:
    r"""One element of the reproduced table.

    ``derived``/``reference``: the documents' elements as printed, after the table's
    substitution. ``machine``: ``match``, ``mismatch`` or ``factorization`` (C differs, the
    row's :math:`C\dot q` does not). ``table``: ``mismatched`` or ``match`` (the printed list).
    ``truth``: which document agrees with the truth under the table's assumptions (``both``,
    ``derived``, ``reference``, ``neither``). ``disagreement``: where the machine and the
    printed table part ways ("" when they do not); ``explanation`` says why."""

    element: str
    derived: str
    reference: str
    machine: str
    table: str
    truth: str
    derived_engine: str
    reference_engine: str
    disagreement: str
    explanation: str


@dataclass(frozen=True)
class EquationDifference:
    r"""One equation's difference derived − reference (the reference row divided by its factor),
    after the substitution, beside the table's printed one. ``relation``: ``equal``,
    ``opposite sign``, ``differs`` or ``not printed``."""

    equation: int
    machine: str
    table: str
    relation: str
    explanation: str


@dataclass(frozen=True)
class TableReproduction:
    r"""The machine's version of a hand-made comparison table (:func:`reproduce_table`).

    ``row_factors`` / ``derived_row_factors``: the constants the reference's / derived
    document's rows were divided by (the engine's, checked under the table's assumptions);
    ``engine_row_factors``: what the engine found in general parameters (derived, reference)."""

    table: Path
    derived: Path
    reference: Path
    assumptions: tuple[str, ...]
    row_factors: tuple[str, ...]
    derived_row_factors: tuple[str, ...]
    engine_row_factors: tuple[tuple[str | None, ...], tuple[str | None, ...]]
    rows: tuple[TableRow, ...]
    equations: tuple[EquationDifference, ...]
    notes: tuple[str, ...]

    @property
    def machine_mismatched(self) -> tuple[str, ...]:
        r"""Elements whose equations differ between the two documents (factorisation-only
        differences left out)."""
        return tuple(r.element for r in self.rows if r.machine == "mismatch")

    @property
    def table_mismatched(self) -> tuple[str, ...]:
        return tuple(r.element for r in self.rows if r.table == "mismatched")

    @property
    def disagreements(self) -> tuple[TableRow, ...]:
        return tuple(r for r in self.rows if r.disagreement)

    def row(self, element: str) -> TableRow:
        for r in self.rows:
            if r.element == element:
                return r
        raise KeyError(element)

    def markdown(self) -> str:
        r"""The reproduction as a Markdown document: the element table, the differences per
        equation, the notes."""
        def factors(fs):
            return "(" + ", ".join(fs) + ")"

        lines = [f"# Comparison table reproduced: {self.table.name}", "",
                 f"- derived: `{self.derived.name}`, rows {factors(self.derived_row_factors)} "
                 f"× the truth's; reference: `{self.reference.name}`, rows "
                 f"{factors(self.row_factors)} × the truth's (divided out before comparing)",
                 "- assumptions (the table's substitution): " + "; ".join(self.assumptions),
                 "- mismatched, table: " + (", ".join(self.table_mismatched) or "none"),
                 "- mismatched, machine: " + (", ".join(self.machine_mismatched) or "none"),
                 "", "| element | derived | reference | machine | table | right (vs truth) "
                 "| explanation |",
                 "|---|---|---|---|---|---|---|"]
        for r in self.rows:
            mark = " **≠ table**" if r.disagreement else ""
            lines.append(f"| {r.element} | {_code(r.derived)} | {_code(r.reference)} | "
                         f"{r.machine}{mark} | {r.table} | {r.truth} | {_cell(r.explanation)} |")
        lines += ["", "## Resulting differences (derived − reference)", "",
                  "| equation | machine | table | relation | explanation |",
                  "|---|---|---|---|---|"]
        for e in self.equations:
            lines.append(f"| {e.equation} | {_code(e.machine)} | {_code(e.table)} | {e.relation} "
                         f"| {_cell(e.explanation)} |")
        if self.notes:
            lines += ["", "## Notes", ""] + [f"- {n}" for n in self.notes]
        return "\n".join(lines) + "\n"


def _cell(text: str) -> str:
    return text.replace("|", "\\|").replace("\n", " ")


def _code(text: str) -> str:
    return f"`{_cell(text)}`" if text else ""


# -- helpers ------------------------------------------------------------------------------

def _documents(table: ComparisonTable, derived, reference) -> tuple[Derivation, Derivation]:
    if derived is None or reference is None:
        names = table.documents
        if not names:
            raise DerivationError(table.path, "documents", "the table names no documents; "
                                  "add [documents] derived = \"...\", reference = \"...\" or "
                                  "pass derived= and reference= (derivation files)")
        derived = derived if derived is not None else table.path.parent / names[0]
        reference = reference if reference is not None else table.path.parent / names[1]
    docs = tuple(x if isinstance(x, Derivation) else load_derivation(x)
                 for x in (derived, reference))
    for d in docs:
        same = tuple(map(str, d.positions)) == tuple(map(str, table.positions))
        if d.model != table.model or not same:
            raise DerivationError(d.path, "coordinates", f"the table {table.path.name} compares "
                                  f"model {table.model} in {[str(p) for p in table.positions]}; "
                                  f"this file has {d.model} in {[str(p) for p in d.positions]}")
        if d.A is None or d.C is None:
            raise DerivationError(d.path, "matrices", "the table compares A and C: give both")
    return docs  # type: ignore[return-value]


def _substitution_failures(table: ComparisonTable, sets: Sequence[ParameterSet]) -> list[str]:
    r"""Substituted symbols whose model value differs from their substitution at some set."""
    failing = []
    for symbol, expr in table.substitution.items():
        for ps in sets:
            values = {s.symbol: model_value(s.value, ps.values) for s in table.symbols.values()
                      if s.value is not None}
            lhs = values[symbol]
            rhs = float(expr.xreplace(values))
            if abs(lhs - rhs) > CHECK_TOL * max(1.0, abs(lhs), abs(rhs)):
                failing.append(str(symbol))
                break
    return failing


def _family(table: ComparisonTable, rng: np.random.Generator) -> tuple[SpecialCase, ...]:
    r"""The smallest combination of special cases under which the substitution holds."""
    cases = special_cases(table.model)

    def holds(combo):
        return not _substitution_failures(table, parameter_sets(table.model, 2, rng, combo))

    if not holds(cases):
        failing = _substitution_failures(table, parameter_sets(table.model, 2, rng, cases))
        raise DerivationError(table.path, "substitution", "does not hold for the model even with "
                              "every special parameter family ("
                              + ", ".join(c.name for c in cases) + "): " + ", ".join(failing))
    needed = list(cases)
    for case in cases:
        trial = tuple(c for c in needed if c is not case)
        if holds(trial):
            needed = list(trial)
    return tuple(needed)


def _factors(result: DerivationResult) -> list[float]:
    r"""The undeclared row factors the engine found (1 where none)."""
    return [float(sp.sympify(c or 1)) for c in result.row_factors]


def _unscaled(d: Derivation, key: str) -> sp.Matrix:
    r"""Matrix ``key`` of ``d`` with a declared row scale divided out."""
    M = sp.Matrix(getattr(d, key))
    return M if d.row_scale is None else sp.diag(*[1 / s for s in d.row_scale]) * M


def _numbers(d: Derivation | ComparisonTable, A: sp.Matrix, C: sp.Matrix, sets, q, nu
             ) -> tuple[np.ndarray, np.ndarray]:
    r"""A and C in the namespace of ``d`` (a document or the table) over sets × states."""
    params = [s for s in d.symbols.values() if not s.is_input and s.value is not None]
    args = [*d.positions, *d.velocities, *(s.symbol for s in params)]
    fA, fC = numpy_function(args, A), numpy_function(args, C)
    n = len(d.positions)
    out: dict[str, list[np.ndarray]] = {"A": [], "C": []}
    for k, ps in enumerate(sets):
        vals = [model_value(s.value, ps.values) for s in params]
        for s in range(q.shape[1]):
            argv = [*q[k, s], *nu[k, s], *vals]
            out["A"].append(np.asarray(fA(*argv), dtype=float).reshape(n, n))
            out["C"].append(np.asarray(fC(*argv), dtype=float).reshape(n, n))
    return np.array(out["A"]), np.array(out["C"])


def _checked_factors(A: np.ndarray, T: np.ndarray, engine_factors: Sequence[float]) -> list[float]:
    r"""Row factors under the table's assumptions: the candidate (:data:`ROW_FACTORS`) with
    which a strict majority of the row's nonzero A entries equal c × the truth exactly; the
    engine's factor where no candidate has one."""
    out = []
    for i, engine_f in enumerate(engine_factors):
        scale = max(float(np.abs(A[:, i]).max()), float(np.abs(T[:, i]).max()), 1e-300)
        entries = [j for j in range(A.shape[2]) if np.abs(A[:, i, j]).max() > 1e-12 * scale]
        best = engine_f
        for c in ROW_FACTORS:
            hits = sum(agrees(A[:, i, j], c * T[:, i, j], scale) for j in entries)
            if entries and 2 * hits > len(entries):
                best = c
        out.append(float(best))
    return out


def _truth(d: Derivation, sets, q, nu) -> tuple[np.ndarray, np.ndarray]:
    cmap = None
    A, C = [], []
    for k, ps in enumerate(sets):
        if cmap is None:
            cmap = CoordinateMap(ps.model, derivation_coordinate_set(d, ps))
        cmap.bind(ps.model)
        t = cmap.terms_batch(q[k], nu[k])
        A.append(t.A)
        C.append(t.C)
    return np.concatenate(A), np.concatenate(C)


def _in_table(expr: sp.Expr, d: Derivation, table: ComparisonTable, notes: list[str]) -> sp.Expr:
    r"""A document expression in the table's namespace: each document symbol becomes the table
    symbol of the same name and model value, or else the one of the same model value."""
    rename = {}
    by_value = {s.value: s.symbol for s in table.symbols.values() if s.value is not None}
    for spec in d.symbols.values():
        if spec.symbol not in expr.free_symbols or spec.value is None:
            continue
        mine = table.symbols.get(spec.name)
        if mine is not None and mine.value == spec.value:
            continue
        if spec.value in by_value:
            rename[spec.symbol] = by_value[spec.value]
        else:
            note = (f"{d.path.name}: symbol {spec.name} = {spec.value_expr_text} has no "
                    f"counterpart in the table; kept as is")
            if note not in notes:
                notes.append(note)
    rename.update(zip(d.velocities, table.velocities))
    rename.update(zip(d.accelerations, table.accelerations))
    rename.update(zip(d.positions, table.positions))
    return sp.sympify(expr).xreplace(rename)


def _simplest(expr: sp.Expr) -> sp.Expr:
    trig = sp.trigsimp(sp.expand(expr))
    powers = [a for a in trig.atoms(sp.Pow) if a.base.func in (sp.sin, sp.cos)]
    candidates = [trig, sp.factor_terms(trig),
                  sp.collect(sp.expand(trig), powers or list(trig.atoms(sp.sin, sp.cos)))]
    return min(candidates, key=lambda e: (sp.count_ops(e), len(sp.sstr(e))))


#: The short texts of :func:`_show`, remembered across runs (the disk cache's
#: ``compare/table-text-<code>.pickle``): simplifying a cell again gives the same text.
SHOWN = DiskMemo("compare", "table-text", lambda: [Path(__file__)])


def _show(expr: sp.Expr, gens: Sequence[sp.Symbol] = ()) -> str:
    r"""Short text of ``expr``: grouped by the monomials in ``gens`` (velocities,
    accelerations), each coefficient in its simplest form (remembered: :data:`SHOWN`)."""
    expr = sp.sympify(expr)
    return SHOWN.get((expr, tuple(gens)), lambda: _shown(expr, gens))


def _shown(expr: sp.Expr, gens: Sequence[sp.Symbol]) -> str:
    expr = sp.expand(expr)
    gens = [g for g in gens if expr.has(g)]
    if not gens:
        return sp.sstr(_simplest(expr))
    try:
        monomials = sp.Poly(expr, *gens).terms()
    except sp.PolynomialError:
        return sp.sstr(_simplest(expr))
    return sp.sstr(sp.Add(*[_simplest(c) * sp.Mul(*[g**k for g, k in zip(gens, mon)])
                            for mon, c in monomials]))


def _same(a: sp.Expr, b: sp.Expr, rng: np.random.Generator) -> bool:
    r"""``a`` equals ``b`` identically (checked at random values of every symbol)."""
    a, b = sp.sympify(a), sp.sympify(b)
    symbols = sorted(a.free_symbols | b.free_symbols, key=str)
    if not symbols:
        return abs(float(a - b)) <= CHECK_TOL * max(1.0, abs(float(a)), abs(float(b)))
    fa, fb = numpy_function(symbols, a), numpy_function(symbols, b)
    for _ in range(CHECK_POINTS):
        x = rng.uniform(0.3, 1.7, len(symbols))
        va, vb = float(fa(*x)), float(fb(*x))
        if abs(va - vb) > CHECK_TOL * max(1.0, abs(va), abs(vb)):
            return False
    return True


def _engine_text(result: DerivationResult, label: str) -> str:
    for r in result.records:
        if r.element == label:
            return r.verdict.value + (": " + "; ".join(d.text for d in r.diagnoses)
                                      if r.diagnoses else "")
    return "not compared"


# -- the reproduction ---------------------------------------------------------------------

def reproduce_table(table: ComparisonTable, engine: ComparisonEngine, *,
                    derived: Derivation | str | Path | None = None,
                    reference: Derivation | str | Path | None = None,
                    also_assume: Sequence[str] = ALSO_ASSUMED) -> TableReproduction:
    r"""The machine's version of ``table`` (see the module docstring). ``derived`` and
    ``reference`` default to the documents the table file names in ``[documents]``;
    ``engine`` compares each against the truth (its row factors and verdicts are used)."""
    der, ref = _documents(table, derived, reference)
    rng = np.random.default_rng([engine.seed, 1])
    notes: list[str] = []
    family = _assumptions(table, rng, also_assume)
    results = {"derived": engine.compare(der), "reference": engine.compare(ref)}
    n = der.n
    sets = parameter_sets(table.model, FAMILY_SETS, rng, family)
    q, nu = random_states(n, FAMILY_SETS * FAMILY_STATES, rng)
    q, nu = q.reshape(FAMILY_SETS, FAMILY_STATES, n), nu.reshape(FAMILY_SETS, FAMILY_STATES, n)
    cells = _table_cells(table)
    numbers = {"derived": _numbers(der, _unscaled(der, "A"), _unscaled(der, "C"), sets, q, nu),
               "reference": _numbers(ref, _unscaled(ref, "A"), _unscaled(ref, "C"), sets, q, nu),
               "derived cell": _numbers(table, cells["derived"]["A"], cells["derived"]["C"],
                                        sets, q, nu),
               "reference cell": _numbers(table, cells["reference"]["A"],
                                          cells["reference"]["C"], sets, q, nu),
               "truth": _truth(der, sets, q, nu)}
    factors = {}
    for which in ("derived", "reference"):
        engine_f = _factors(results[which])
        factors[which] = _checked_factors(numbers[which][0], numbers["truth"][0], engine_f)
        for i, (e, f) in enumerate(zip(engine_f, factors[which])):
            if e != f:
                notes.append(
                    f"the engine finds row factor {_num(e)} for row {i + 1} of the {which} "
                    f"document in general parameters, but under the table's assumptions the "
                    f"row's A is exactly {_num(f)} × the truth's: {_num(f)} is used, and the "
                    f"engine's verdicts on that row are quoted as they are")
        for key in (which, f"{which} cell"):
            f = np.asarray(factors[which])[None, :, None]
            numbers[key] = (numbers[key][0] / f, numbers[key][1] / f)
    flat_nu = nu.reshape(-1, n)
    numbers_h = {k: np.einsum("sij,sj->si", v[1], flat_nu) for k, v in numbers.items()}
    scale = np.ones(n)
    for A, C in numbers.values():
        scale = np.maximum(scale, np.abs(np.concatenate([A, C], axis=2)).max(axis=(0, 2)))
    raw = {which: {key: _unscaled(d, key).applyfunc(lambda e, d=d: _in_table(e, d, table, notes))
                   for key in ("A", "C")} for which, d in (("derived", der), ("reference", ref))}
    ctx = _Context(table, numbers, numbers_h, scale, raw, cells, factors, results,
                   tuple(c.description for c in family), rng)
    rows = tuple(_row(entry, ctx) for entry in table.entries)
    sign_only = [r.element for r in rows
                 if r.machine == "match" and "(in sign only)" in r.explanation]
    if sign_only:
        notes.append("the printed cells of " + ", ".join(sign_only) + " differ in sign only and "
                     "the table rightly does not list them: the reference's rows are ("
                     + ", ".join(_num(c) for c in factors["reference"]) + ") × the truth's "
                     "(Kane's generalised inertia forces F* = -(A q̈ + h))")
    notes += _step_notes(table, rng)
    return TableReproduction(
        table=table.path, derived=der.path, reference=ref.path, assumptions=ctx.assumed,
        row_factors=tuple(_num(c) for c in factors["reference"]),
        derived_row_factors=tuple(_num(c) for c in factors["derived"]),
        engine_row_factors=(tuple(results["derived"].row_factors),
                            tuple(results["reference"].row_factors)), rows=rows,
        equations=tuple(_equations(ctx, rows)), notes=tuple(notes))


@dataclass(frozen=True)
class _Context:
    table: ComparisonTable
    numbers: Mapping[str, tuple[np.ndarray, np.ndarray]]
    h: Mapping[str, np.ndarray]
    scale: np.ndarray
    raw: Mapping[str, Mapping[str, sp.Matrix]]
    cells: Mapping[str, Mapping[str, sp.Matrix]]
    factors: Mapping[str, list[float]]
    results: Mapping[str, DerivationResult]
    assumed: tuple[str, ...]
    rng: np.random.Generator

    def subst(self, expr: sp.Expr) -> sp.Expr:
        return sp.sympify(expr).xreplace(dict(self.table.substitution))

    def factor(self, which: str, i: int) -> sp.Expr:
        return sp.nsimplify(self.factors[which][i])


def _assumptions(table: ComparisonTable, rng, also_assume) -> tuple[SpecialCase, ...]:
    family = list(_family(table, rng))
    for name in also_assume:
        case = next((c for c in special_cases(table.model) if c.name == name), None)
        if case is None:
            raise DerivationError(table.path, "also_assume", f"{name!r} is not a special case "
                                  f"of {table.model}: " + ", ".join(
                                      c.name for c in special_cases(table.model)))
        if case not in family:
            family.append(case)
    return tuple(family)


def _table_cells(table: ComparisonTable) -> dict[str, dict[str, sp.Matrix]]:
    return {column: {key: table.matrix(key, column) for key in ("A", "C")}
            for column in ("derived", "reference")}


def _num(c: float) -> str:
    return sp.sstr(sp.nsimplify(c))


def _within(diagnoses: Sequence[Diagnosis], model: str, assumed: Sequence[str]) -> bool:
    r"""An "agrees only if ..." diagnosis whose conditions are all among ``assumed``
    (descriptions of the model's special cases, as the engine quotes them)."""
    hit = first_of(diagnoses, DiagnosisKind.CONDITION)
    if hit is None:
        return False
    text = hit.condition
    return all(c.description not in text or c.description in assumed
               for c in special_cases(model))


def _h_both_wrong(ctx: _Context, i: int) -> list[str]:
    r"""h coefficients of row ``i`` that the engine finds wrong in both documents, beyond the
    table's assumptions."""
    wrong = None
    for result in ctx.results.values():
        bad = {r.element for r in result.records if r.key == "h" and r.index[0] == i
               and r.verdict != "agrees"
               and not (r.verdict == "agrees_if"
                        and _within(r.diagnoses, ctx.table.model, ctx.assumed))}
        wrong = bad if wrong is None else wrong & bad
    return sorted(wrong or ())


def _row(entry: TableEntry, ctx: _Context) -> TableRow:
    key, i, j = entry.matrix, entry.row - 1, entry.col - 1
    idx = 0 if key == "A" else 1
    D, R, T = (ctx.numbers[k][idx][:, i, j] for k in ("derived", "reference", "truth"))
    tol = ctx.scale[i]
    match = agrees(D, R, tol)
    same_h = agrees(ctx.h["derived"][:, i], ctx.h["reference"][:, i], tol)
    machine = "match" if match else ("factorization" if key == "C" and same_h else "mismatch")
    right = {"derived": agrees(D, T, tol), "reference": agrees(R, T, tol)}
    truth = ("both" if all(right.values()) else "derived" if right["derived"] else
             "reference" if right["reference"] else "neither")
    d_printed = ctx.subst(ctx.raw["derived"][key][i, j])
    r_printed = ctx.subst(ctx.raw["reference"][key][i, j])
    d_expr = d_printed / ctx.factor("derived", i)
    r_expr = r_printed / ctx.factor("reference", i)
    label = f"{key}[{entry.row},{entry.col}]"
    engine = {w: _engine_text(ctx.results[w], label) for w in ("derived", "reference")}
    listed = entry.name in ctx.table.mismatched
    gens = (*ctx.table.velocities, *ctx.table.accelerations)
    parts, kinds = [], []

    if machine == "match":
        f_d, f_r = ctx.factors["derived"][i], ctx.factors["reference"][i]
        if f_d != f_r and not _same(d_printed, r_printed, ctx.rng):
            parts.append(f"equal once row {entry.row} is divided by its factor (derived "
                         f"{_num(f_d)}, reference {_num(f_r)}); the printed cells differ by "
                         f"the factor {_num(f_r / f_d)}"
                         + (" (in sign only)" if f_r == -f_d else ""))
        else:
            parts.append("equal after the substitution")
    else:
        parts.append(f"derived − reference = {_show(d_expr - r_expr, gens)}")
        if machine == "factorization":
            parts.append(f"but C q̇ of row {entry.row} is the same in both: only the "
                         "factorisation of C differs, not the equations")
    verdict = {True: "agrees with the truth", False: "differs from the truth"}
    parts.append(f"under the table's assumptions the derived {verdict[right['derived']]} "
                 f"(engine, general parameters: {engine['derived']}), the reference "
                 f"{verdict[right['reference']]} (engine: {engine['reference']})")
    if machine == "mismatch" and not listed:
        kinds.append("missed by the table")
        parts.append("the table does not list it")
    elif machine != "mismatch" and listed:
        kinds.append("factorisation only" if machine == "factorization" else "not a mismatch")
        parts.append("the table lists it as mismatched, but the equations agree here")
    elif listed:
        parts.append("the table lists it: agreed")
    if machine == "match" and truth == "neither":
        kinds.append("both documents wrong")
        hidden = _h_both_wrong(ctx, i)
        parts.append("the two documents agree with each other here, so a table comparing them "
                     "cannot see it, but both differ from the truth"
                     + (f" (the engine finds {', '.join(hidden)} wrong in both)" if hidden else ""))
    cell_parts, cell_kinds = _cell_checks(entry, ctx, (d_printed, r_printed), T, tol)
    return TableRow(element=entry.name, derived=_show(d_printed, gens),
                    reference=_show(r_printed, gens), machine=machine,
                    table="mismatched" if listed else "match", truth=truth,
                    derived_engine=engine["derived"], reference_engine=engine["reference"],
                    disagreement="; ".join(dict.fromkeys(kinds + cell_kinds)),
                    explanation="; ".join(parts + cell_parts))


def _cell_checks(entry: TableEntry, ctx: _Context, docs, T, tol):
    r"""Are the table's derived and reference cells the documents as printed? When they are
    not, is the cell the truth?"""
    notes, kinds = [], []
    key, i, j = entry.matrix, entry.row - 1, entry.col - 1
    for column, cell, doc in (("derived", entry.derived, docs[0]),
                              ("reference", entry.reference, docs[1])):
        printed = ctx.raw[column][key][i, j]
        if _same(ctx.subst(cell), doc, ctx.rng):
            if not _same(cell, printed, ctx.rng):
                notes.append(f"the table's {column} cell {sp.sstr(cell)} is not the document as "
                             f"printed, {sp.sstr(printed)}, but equal to it after the "
                             "substitution")
            continue
        values = ctx.numbers[f"{column} cell"][0 if key == "A" else 1][:, i, j]
        kinds.append("cells differ from the documents")
        notes.append(f"the table's {column} cell {sp.sstr(cell)} is not the {column} document as "
                     f"printed, {sp.sstr(printed)}, even after the substitution; the cell "
                     + ("agrees with the truth" if agrees(values, T, tol) else
                        "differs from the truth too") + " under the table's assumptions")
    return notes, kinds


def _step_notes(table: ComparisonTable, rng) -> list[str]:
    r"""Printed steps of the "equivalent form" column that do not equal the derived cell after
    the substitution."""
    out = []
    subst = dict(table.substitution)
    for e in table.entries:
        target = e.derived.xreplace(subst)
        for k, step in enumerate(e.equivalent, start=1):
            if not _same(step, target, rng):
                out.append(f"{e.name}: step {k} of the table's equivalent form, {sp.sstr(step)}, "
                           f"is not the derived cell after the substitution, {_show(target)}")
    return out


def _equations(ctx: _Context, rows: Sequence[TableRow]) -> list[EquationDifference]:
    table = ctx.table
    acc, vel = sp.Matrix(table.accelerations), sp.Matrix(table.velocities)
    gens = (*table.velocities, *table.accelerations)

    def lhs(M: Mapping[str, sp.Matrix], i: int) -> sp.Expr:
        return ctx.subst((M["A"] * acc)[i] + (M["C"] * vel)[i])

    out = []
    for i in range(len(table.positions)):
        label = f"equation {i + 1}"
        fd, fr = ctx.factor("derived", i), ctx.factor("reference", i)
        machine = lhs(ctx.raw["derived"], i) / fd - lhs(ctx.raw["reference"], i) / fr
        from_cells = lhs(ctx.cells["derived"], i) / fd - lhs(ctx.cells["reference"], i) / fr
        printed = table.differences.get(label)
        mine = [r for r in rows if r.element[1] == str(i + 1)]
        if printed is None:
            relation, why = "not printed", "the table gives no difference for this equation"
        elif _same(printed, machine, ctx.rng):
            relation, why = "equal", "the table's difference is derived − reference"
        elif _same(printed, -machine, ctx.rng):
            relation, why = "opposite sign", ("the table gives reference − derived here, "
                                              "derived − reference in the other equations")
        elif _same(printed, from_cells, ctx.rng) or _same(printed, -from_cells, ctx.rng):
            relation = "differs"
            why = ("the table's difference follows its own cells, which are not the documents "
                   "as printed at " + ", ".join(r.element for r in mine
                                                if "cells differ" in r.disagreement)
                   + f"; from its cells: {_show(from_cells, gens)}")
        else:
            relation = "differs"
            why = ("neither derived − reference nor its negative; from the table's cells: "
                   + _show(from_cells, gens))
        hidden = [r.element for r in mine if r.truth == "neither" and r.machine == "match"]
        neither = [r.element for r in mine if r.truth == "neither" and r.machine != "match"]
        if hidden:
            why += (f"; both documents differ from the truth at {', '.join(hidden)} in the same "
                    "way, which no difference between them shows")
        if neither:
            why += f"; neither document is right at {', '.join(neither)}"
        out.append(EquationDifference(i + 1, _show(machine, gens),
                                      "" if printed is None else _show(printed, gens),
                                      relation, why))
    return out
