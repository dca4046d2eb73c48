r"""What a table reproduction compares: the two documents the table names, the smallest
special parameter family under which its substitution holds, and both documents' and the
truth's A and C over that family's parameter sets × states, with each row's factor checked."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import sympy as sp

from ....compiled import numpy_function
from ....constraints.reduction import CoordinateMap
from ....derivations.parse import load_derivation
from ....derivations.schema import Derivation
from ....derivations.table import ComparisonTable
from ....errors import DerivationError
from ...grid.grid import derivation_coordinate_set
from ...grid.samples import ParameterSet, SpecialCase, parameter_sets, special_cases
from ...judge.diagnose import agrees
from ...readings.row_factors import ROW_FACTORS
from ...records import DerivationResult
from ...grid.values import model_value
from .text import CHECK_TOL


def table_documents(table: ComparisonTable, derived, reference) -> tuple[Derivation, Derivation]:
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
    per_set = [{s.symbol: model_value(s.value, ps.values) for s in table.symbols.values()
                if s.value is not None} for ps in sets]
    for symbol, expr in table.substitution.items():
        for values in per_set:
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


def found_row_factors(result: DerivationResult) -> list[float]:
    r"""The undeclared row factors the engine found (1 where none)."""
    return [float(sp.sympify(c or 1)) for c in result.row_factors]


def unscaled(d: Derivation, key: str) -> sp.Matrix:
    r"""Matrix ``key`` of ``d`` with a declared row scale divided out."""
    M = sp.Matrix(getattr(d, key))
    return M if d.row_scale is None else sp.diag(*[1 / s for s in d.row_scale]) * M


def matrices_at(d: Derivation | ComparisonTable, A: sp.Matrix, C: sp.Matrix, sets, q, nu
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


def checked_factors(A: np.ndarray, T: np.ndarray, engine_factors: Sequence[float]) -> list[float]:
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


def truth_at(d: Derivation, sets, q, nu) -> tuple[np.ndarray, np.ndarray]:
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


def table_assumptions(table: ComparisonTable, rng, also_assume) -> tuple[SpecialCase, ...]:
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


def table_cells(table: ComparisonTable) -> dict[str, dict[str, sp.Matrix]]:
    return {column: {key: table.matrix(key, column) for key in ("A", "C")}
            for column in ("derived", "reference")}
