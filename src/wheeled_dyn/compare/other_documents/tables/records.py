r"""The records of a reproduced comparison table: one element (:class:`TableRow`), one
equation's difference (:class:`EquationDifference`) and the whole reproduction
(:class:`TableReproduction`, with its Markdown form)."""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path


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
