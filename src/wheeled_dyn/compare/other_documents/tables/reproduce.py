r"""The reproduction of a hand-made comparison table (:func:`reproduce_table`): both documents
compared with the truth by the engine, then with each other under the table's assumptions."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

from ....derivations.schema import Derivation
from ....derivations.table import ComparisonTable
from ...engine import ComparisonEngine
from ...grid.samples import parameter_sets, random_states
from .inputs import (checked_factors, found_row_factors, matrices_at, table_assumptions,
                     table_cells, table_documents, truth_at, unscaled)
from .records import TableReproduction
from .rows import Context, equation_differences, step_notes, table_row
from .text import in_table, num


#: Special cases assumed beside the table's substitution (neither seed-001 document models the
#: motors, so the truth is taken without armature).
ALSO_ASSUMED: tuple[str, ...] = ("no_armature",)
#: Grid of the document comparison: parameter sets of the table's family × states each.
FAMILY_SETS, FAMILY_STATES = 3, 60


def reproduce_table(table: ComparisonTable, engine: ComparisonEngine, *,
                    derived: Derivation | str | Path | None = None,
                    reference: Derivation | str | Path | None = None,
                    also_assume: Sequence[str] = ALSO_ASSUMED) -> TableReproduction:
    r"""The machine's version of ``table`` (see :mod:`wheeled_dyn.compare.other_documents.tables`). ``derived`` and
    ``reference`` default to the documents the table file names in ``[documents]``;
    ``engine`` compares each against the truth (its row factors and verdicts are used)."""
    der, ref = table_documents(table, derived, reference)
    rng = np.random.default_rng([engine.seed, 1])
    notes: list[str] = []
    family = table_assumptions(table, rng, also_assume)
    results = {"derived": engine.compare(der), "reference": engine.compare(ref)}
    n = der.n
    sets = parameter_sets(table.model, FAMILY_SETS, rng, family)
    q, nu = random_states(n, FAMILY_SETS * FAMILY_STATES, rng)
    q, nu = q.reshape(FAMILY_SETS, FAMILY_STATES, n), nu.reshape(FAMILY_SETS, FAMILY_STATES, n)
    cells = table_cells(table)
    numbers = {"derived": matrices_at(der, unscaled(der, "A"), unscaled(der, "C"), sets, q, nu),
               "reference": matrices_at(ref, unscaled(ref, "A"), unscaled(ref, "C"), sets, q, nu),
               "derived cell": matrices_at(table, cells["derived"]["A"], cells["derived"]["C"],
                                        sets, q, nu),
               "reference cell": matrices_at(table, cells["reference"]["A"],
                                          cells["reference"]["C"], sets, q, nu),
               "truth": truth_at(der, sets, q, nu)}
    factors = {}
    for which in ("derived", "reference"):
        engine_f = found_row_factors(results[which])
        factors[which] = checked_factors(numbers[which][0], numbers["truth"][0], engine_f)
        for i, (e, f) in enumerate(zip(engine_f, factors[which])):
            if e != f:
                notes.append(
                    f"the engine finds row factor {num(e)} for row {i + 1} of the {which} "
                    f"document in general parameters, but under the table's assumptions the "
                    f"row's A is exactly {num(f)} × the truth's: {num(f)} is used, and the "
                    f"engine's verdicts on that row are quoted as they are")
        per_row = np.asarray(factors[which])[None, :, None]
        for key in (which, f"{which} cell"):
            numbers[key] = (numbers[key][0] / per_row, numbers[key][1] / per_row)
    flat_nu = nu.reshape(-1, n)
    numbers_h = {k: np.einsum("sij,sj->si", v[1], flat_nu) for k, v in numbers.items()}
    scale = np.ones(n)
    for A, C in numbers.values():
        scale = np.maximum(scale, np.abs(np.concatenate([A, C], axis=2)).max(axis=(0, 2)))
    raw = {which: {key: unscaled(d, key).applyfunc(lambda e, d=d: in_table(e, d, table, notes))
                   for key in ("A", "C")} for which, d in (("derived", der), ("reference", ref))}
    ctx = Context(table, numbers, numbers_h, scale, raw, cells, factors, results,
                   tuple(c.description for c in family), rng)
    rows = tuple(table_row(entry, ctx) for entry in table.entries)
    sign_only = [r.element for r in rows
                 if r.machine == "match" and "(in sign only)" in r.explanation]
    if sign_only:
        notes.append("the printed cells of " + ", ".join(sign_only) + " differ in sign only and "
                     "the table rightly does not list them: the reference's rows are ("
                     + ", ".join(num(c) for c in factors["reference"]) + ") × the truth's "
                     "(Kane's generalised inertia forces F* = -(A q̈ + h))")
    notes += step_notes(table, rng)
    return TableReproduction(
        table=table.path, derived=der.path, reference=ref.path, assumptions=ctx.assumed,
        row_factors=tuple(num(c) for c in factors["reference"]),
        derived_row_factors=tuple(num(c) for c in factors["derived"]),
        engine_row_factors=(tuple(results["derived"].row_factors),
                            tuple(results["reference"].row_factors)), rows=rows,
        equations=tuple(equation_differences(ctx, rows)), notes=tuple(notes))
