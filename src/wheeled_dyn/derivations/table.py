r"""Hand-made comparison tables, as data: :func:`load_comparison_table`.

Seed 001 ends with a table comparing its eq. (25) with Kim et al. element by element: for each
element :math:`A_{11} \dots C_{33}` the *derived expression* (Khalil's notation), its
*equivalent form in [1]* (after the substitution :math:`M_1 = m_S`, :math:`MY_1 = m_S d`, ...
printed above the table) and the *expression in [1]*; then the list of mismatched elements and
the resulting differences in each equation. The comparison engine reproduces such a table
automatically and says where it disagrees with the hand-made one; this module gives it the
hand-made one.

The file has ``title``, ``model``, ``[source]``, ``[coordinates]`` and ``[symbols]`` as a
derivation file, and

- ``[substitution]``: document symbol = expression in the other symbols (the table's
  "equivalent form" substitution);
- ``[[element]]``: ``name`` (``"A11"``), ``derived``, ``equivalent`` (one expression or a list
  of the printed steps), ``reference``, each with a ``*_latex`` twin holding the text as
  printed;
- ``[mismatch]``: ``elements`` (list of names) and ``[mismatch.differences]``
  (``"equation 1" = "expression"``);
- ``[reconstructed]``: label = what was restored from garbled text.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from types import MappingProxyType
from typing import Any

import sympy

from .coordinates import coordinate_names, resolve_model_reference
from .loader import _Loader
from .schema import SymbolSpec
from .source import read_toml

TABLE_KEYS: tuple[str, ...] = ("title", "model", "source", "documents", "coordinates",
                               "symbols", "substitution", "element", "mismatch",
                               "reconstructed")
#: Keys of ``[documents]``: the derivation files (beside the table) whose matrices it compares.
DOCUMENT_KEYS: tuple[str, str] = ("derived", "reference")
ELEMENT_KEYS: tuple[str, ...] = ("name", "derived", "derived_latex", "equivalent",
                                 "equivalent_latex", "reference", "reference_latex")
_ELEMENT_NAME = re.compile(r"^([A-Z])(\d)(\d)$")


@dataclass(frozen=True)
class TableEntry:
    r"""One row of a comparison table: element ``name`` (``"A22"``, 1-based ``row``/``col``),
    the three columns as SymPy expressions and as the printed LaTeX text."""

    name: str
    matrix: str
    row: int
    col: int
    derived: sympy.Expr
    equivalent: tuple[sympy.Expr, ...]
    reference: sympy.Expr
    derived_latex: str
    equivalent_latex: str
    reference_latex: str


@dataclass(frozen=True)
class ComparisonTable:
    r"""A hand-made comparison table (see the module docstring)."""

    path: Path
    title: str
    model: str
    source: Mapping[str, str]
    symbols: Mapping[str, SymbolSpec]
    substitution: Mapping[sympy.Symbol, sympy.Expr]
    entries: tuple[TableEntry, ...]
    mismatched: tuple[str, ...]
    differences: Mapping[str, sympy.Expr]
    reconstructed: Mapping[str, str]
    positions: tuple[sympy.Symbol, ...]
    velocities: tuple[sympy.Symbol, ...]
    accelerations: tuple[sympy.Symbol, ...]
    namespace: Mapping[str, sympy.Symbol]
    #: ``[documents]``: the derived and the reference derivation files, beside the table
    documents: tuple[str, ...] = ()

    def entry(self, name: str) -> TableEntry:
        r"""The entry of element ``name`` (``"C23"``)."""
        for e in self.entries:
            if e.name == name:
                return e
        from ..errors import UnknownNameError
        raise UnknownNameError("table element", name, [e.name for e in self.entries],
                               where=str(self.path))

    def matrix(self, which: str, column: str = "derived") -> sympy.ImmutableMatrix:
        r"""Matrix ``which`` (``"A"``/``"C"``) assembled from one column (``"derived"``,
        ``"equivalent"`` (last printed step) or ``"reference"``)."""
        entries = [e for e in self.entries if e.matrix == which]
        size = max(max(e.row, e.col) for e in entries)
        M = sympy.zeros(size, size)
        for e in entries:
            value = getattr(e, column)
            M[e.row - 1, e.col - 1] = value[-1] if column == "equivalent" else value
        return sympy.ImmutableMatrix(M)


def load_comparison_table(path: str | Path) -> ComparisonTable:
    r"""Load a comparison table file; errors as :func:`load_derivation` (file, line, item)."""
    p = Path(path)
    data, src = read_toml(p)
    ld = _Loader(p, data, src, None, None)
    for key in data:
        if key not in TABLE_KEYS:
            raise ld.fail(key, "unknown key or table; valid: " + ", ".join(TABLE_KEYS),
                          src.line_of(None, key) or src.line_of(key))
    title, model = ld.text("title"), ld.text("model")
    model = resolve_model_reference(p, model, ld.line(None, "model"))
    documents = _documents(ld, ld.table("documents"))
    names = coordinate_names(p, ld.table("coordinates", required=True), model,
                             lambda key: ld.line("coordinates", key))
    positions = tuple(ld.declare(n, "position", "coordinates", None) for n in names.positions)
    velocities = tuple(ld.declare(n, "velocity", "coordinates", None) for n in names.velocities)
    accelerations = tuple(ld.declare(n, "acceleration", "coordinates", None)
                          for n in names.accelerations)
    symbols = ld.symbols()
    substitution = {}
    for name, text in ld.table("substitution").items():
        if name not in ld.names:
            raise ld.fail(f"substitution.{name}", "not a declared symbol",
                          ld.line("substitution", name))
        substitution[ld.names[name]] = ld.expr(text, f"substitution.{name}", "substitution", name)
    raw_entries = data.get("element", [])
    if not isinstance(raw_entries, list) or not raw_entries:
        raise ld.fail("element", "expected [[element]] tables", ld.line("element"))
    entries = []
    for raw in raw_entries:
        entries.append(_entry(ld, raw))
    if len({e.name for e in entries}) != len(entries):
        raise ld.fail("element", "an element is listed twice", ld.line("element"))
    mismatch = ld.table("mismatch")
    listed = mismatch.get("elements", [])
    known = {e.name for e in entries}
    for name in listed:
        if name not in known:
            raise ld.fail("mismatch.elements", f"{name!r} is not an element of the table",
                          ld.line("mismatch", "elements"))
    differences = {label: ld.expr(text, f"mismatch.differences.{label}",
                                  "mismatch.differences", label)
                   for label, text in mismatch.get("differences", {}).items()}
    return ComparisonTable(
        path=p, title=title, model=model, source=MappingProxyType(dict(ld.table("source"))),
        symbols=MappingProxyType(symbols), substitution=MappingProxyType(substitution),
        entries=tuple(entries), mismatched=tuple(listed),
        differences=MappingProxyType(differences),
        reconstructed=MappingProxyType(dict(ld.table("reconstructed"))),
        positions=positions, velocities=velocities, accelerations=accelerations,
        namespace=MappingProxyType(dict(ld.names)), documents=documents)


def _documents(ld: _Loader, raw: dict[str, Any]) -> tuple[str, ...]:
    r"""``[documents] derived = "...", reference = "..."`` as (derived, reference), or ()."""
    if not raw:
        return ()
    for key in raw:
        if key not in DOCUMENT_KEYS:
            raise ld.fail(f"documents.{key}", "unknown key; valid: " + ", ".join(DOCUMENT_KEYS),
                          ld.line("documents", key))
    out = []
    for key in DOCUMENT_KEYS:
        value = raw.get(key)
        if not isinstance(value, str) or not value.endswith(".toml"):
            raise ld.fail(f"documents.{key}", "expected the name of a derivation file (.toml) "
                          "beside the table", ld.line("documents", key) or ld.line("documents"))
        out.append(value)
    return tuple(out)


def _entry(ld: _Loader, raw: Any) -> TableEntry:
    if not isinstance(raw, dict) or not isinstance(raw.get("name"), str):
        raise ld.fail("element", "each [[element]] needs name = \"A11\"", ld.line("element"))
    name = raw["name"]
    found = _ELEMENT_NAME.match(name)
    if not found:
        raise ld.fail(f"element {name}", "name is a matrix letter and two digits, e.g. A11",
                      ld.line("element", "name", name))
    for key in raw:
        if key not in ELEMENT_KEYS:
            raise ld.fail(f"element {name}.{key}", "unknown key; valid: "
                          + ", ".join(ELEMENT_KEYS), ld.line("element", "name", name))
    for key in ("derived", "equivalent", "reference"):
        if key not in raw:
            raise ld.fail(f"element {name}", f"missing {key}", ld.line("element", "name", name))
    steps = raw["equivalent"] if isinstance(raw["equivalent"], list) else [raw["equivalent"]]

    def parse(text: Any, column: str) -> sympy.Expr:
        return ld.expr(text, f"element {name}.{column}", "element", column)

    return TableEntry(
        name=name, matrix=found.group(1), row=int(found.group(2)), col=int(found.group(3)),
        derived=parse(raw["derived"], "derived"),
        equivalent=tuple(parse(t, "equivalent") for t in steps),
        reference=parse(raw["reference"], "reference"),
        derived_latex=str(raw.get("derived_latex", "")),
        equivalent_latex=str(raw.get("equivalent_latex", "")),
        reference_latex=str(raw.get("reference_latex", "")))
