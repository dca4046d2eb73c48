r"""Loading derivation files: :func:`load_derivation`, :func:`load_derivations`.

The loader reads the TOML (``tomllib``), declares every document name (positions, velocities,
accelerations, ``[symbols]``, ``[assume]``, ``[definitions]``), parses every expression in
that namespace only (:mod:`.expressions`), expands the definitions, and checks the file's
internal consistency:

- every name used is declared (else :class:`DerivationNameError`, a
  :class:`~wheeled_dyn.errors.UnknownNameError` naming the file, line, element and the
  valid names);
- shapes fit the n positions: A, C n×n; Q, Gamma n; B n×k (k document inputs); G m×n;
  n equations; n row scales (else :class:`~wheeled_dyn.errors.DerivationError`);
- an unparseable element raises :class:`~wheeled_dyn.errors.DerivationError` naming it
  1-based (``A[2,3]``) with its line.

It does not import the models: whether the value expressions name real parameters of the model
is checked by the comparison engine, or here when ``parameters``/``links`` are passed.
"""

from __future__ import annotations

import math
from collections.abc import Collection, Iterable, Mapping
from pathlib import Path
from types import MappingProxyType
from typing import Any

import sympy

from ..errors import DerivationError
from .builtin import derivation_files
from .coordinates import coordinate_names, coordinate_spec, resolve_model_reference
from .errors import DerivationNameError
from .expressions import (RESERVED_NAMES, ExpressionError, UndeclaredNameError,
                          check_expanded, parse_expression, parse_model_expression, parse_units,
                          real_symbol, scan_names)
from .latex import (LATEX_KEYS, LatexNames, LatexSource, is_printed_name, latex_to_sympy,
                    unwrap_latex)
from .matrices import MatrixReader
from .schema import Derivation, SymbolSpec
from .source import SourceText, read_toml
from .steps import read_steps

TOP_LEVEL_KEYS: tuple[str, ...] = ("title", "model", "source", "coordinates", "inputs",
                                   "symbols", "assume", "definitions", "rows", "matrices",
                                   "constraints", "reconstructed", "step", "feeds",
                                   "assumes", "latex", "convention")
#: Values of the top-level ``convention``: ``"declared"`` (the default: the file's maps are
#: how the document is read, binding) or ``"unknown"`` (the document's sign conventions are
#: not known: a better reading found by the comparison is applied, and said first).
CONVENTIONS: tuple[str, ...] = ("declared", "unknown")
#: Names that stand for NaN or an infinity (in Python, SymPy or TOML): not finite numbers.
NON_FINITE_NAMES = frozenset({"nan", "inf", "infinity", "oo", "zoo"})
#: Keys of ``[assumes]``: what the document assumes (see docs/derivation-format.md).
ASSUMES_KEYS: tuple[str, ...] = ("families", "uniform", "linearised_about", "potential", "text")
SYMBOL_KEYS: tuple[str, ...] = ("value", "units", "meaning", "input", "free", "latex")


class _Loader:
    r"""One file's namespace and error reporting."""

    def __init__(self, path: Path, data: dict[str, Any], src: SourceText,
                 parameters: Collection[str] | None, links: Collection[str] | None) -> None:
        self.path, self.data, self.src = path, data, src
        self.parameters, self.links = parameters, links
        self.names: dict[str, sympy.Symbol] = {}
        self.kinds: dict[str, str] = {}
        self.expansion: dict[sympy.Symbol, sympy.Expr] = {}
        self.coordinates: dict[str, tuple[str, ...]] = {}     # positions, velocities, ...
        self.latex_input: dict[str, tuple[str, str]] = {}     # item -> (LaTeX, read as)
        self._latex: LatexNames | None = None

    # -- errors and lines ---------------------------------------------------------------
    def line(self, table: str | None, key: str | None = None,
             fragment: str | None = None) -> int | None:
        return self.src.line_of(table, key, fragment)

    def fail(self, item: str, reason: str, line: int | None = None) -> DerivationError:
        return DerivationError(self.path, item, reason, line)

    def table(self, key: str, required: bool = False) -> dict[str, Any]:
        value = self.data.get(key)
        if value is None:
            if required:
                raise self.fail(key, "missing table", None)
            return {}
        if not isinstance(value, dict):
            raise self.fail(key, "expected a table", self.line(None, key) or self.line(key))
        return value

    def text(self, key: str) -> str:
        value = self.data.get(key)
        if not isinstance(value, str) or not value.strip():
            raise self.fail(key, "expected a non-empty string", self.line(None, key))
        return value

    # -- names ----------------------------------------------------------------------------
    def declare(self, name: str, kind: str, item: str, line: int | None) -> sympy.Symbol:
        try:
            scanned = scan_names(name)
        except ExpressionError as exc:
            raise self.fail(item, exc.reason, line) from exc
        if len(scanned) != 1 or scanned[0][0] != name:
            raise self.fail(item, f"{name!r} is not a valid name", line)
        if name in RESERVED_NAMES:
            raise self.fail(item, f"{name!r} is a standard function or constant", line)
        if name in self.kinds:
            raise self.fail(item, f"{name!r} is already declared as a {self.kinds[name]}", line)
        symbol = real_symbol(name)
        self.names[name] = symbol
        self.kinds[name] = kind
        return symbol

    def expr(self, text: Any, item: str, table: str | None, key: str,
             names: Mapping[str, sympy.Basic] | None = None, expand: bool = True) -> sympy.Expr:
        r"""Parse a document expression; errors name the file, the line and ``item``."""
        names = self.names if names is None else names
        text = unwrap_latex(text)
        if isinstance(text, LatexSource):
            text = self.from_latex(text, item, table, key)
        if isinstance(text, bool) or not isinstance(text, (str, int, float)):
            raise self.fail(item, f"expected an expression, got {text!r}",
                            self.line(table, key))
        if isinstance(text, float) and not math.isfinite(text):
            raise self.fail(item, f"{text} is not a finite number (NaN or an infinity); give "
                            "the document's expression", self.line(table, key))
        source = str(text)
        try:
            value = parse_expression(source, names)
            value = value.xreplace(self.expansion) if expand and self.expansion else value
            check_expanded(source, value)
        except UndeclaredNameError as exc:
            if exc.name.lower() in NON_FINITE_NAMES:
                raise self.fail(item, f"{exc.name!r} is not a finite number (NaN or an "
                                "infinity) and not a declared symbol; give the document's "
                                "expression", self.line(table, key, exc.name)) from None
            raise DerivationNameError(self.path, item, "symbol", exc.name, names,
                                      self.line(table, key, exc.name)) from exc
        except ExpressionError as exc:
            raise self.fail(item, exc.reason, self.line(table, key, source)) from exc
        return value

    # -- LaTeX input (docs/derivation-latex.md) ----------------------------------------
    def latex_names(self) -> LatexNames:
        r"""The file's names for reading LaTeX: every declared name, the positions' velocities
        and accelerations, how the document prints names (``latex`` fields of ``[symbols]``,
        ``[latex] names``) and ``[latex] abbreviations``."""
        if self._latex is not None:
            return self._latex
        raw = self.table("latex")
        extra = sorted(set(raw) - set(LATEX_KEYS))
        if extra:
            raise self.fail(f"latex.{extra[0]}", "unknown key; valid: " + ", ".join(LATEX_KEYS),
                            self.line("latex", extra[0]))
        for key in LATEX_KEYS:
            if not isinstance(raw.get(key, {}), dict) or not all(
                    isinstance(v, str) for v in raw.get(key, {}).values()):
                raise self.fail(f"latex.{key}", "expected { 'LaTeX as printed' = \"SymPy "
                                "expression\", ... }" if key == "abbreviations" else
                                "expected { name = 'LaTeX as printed', ... }",
                                self.line("latex", key))
        abbreviations, printed = dict(raw.get("abbreviations", {})), {}
        for printed_text, value in abbreviations.items():
            self.expr(value, f"latex.abbreviations.{printed_text}", "latex", "abbreviations",
                      expand=False)
        for name, entry in self.table("symbols").items():
            if isinstance(entry, dict) and entry.get("latex") is not None:
                printed[name] = (f"symbols.{name}.latex", entry["latex"])
        for name, text in raw.get("names", {}).items():
            if name not in self.names:
                raise DerivationNameError(self.path, f"latex.names.{name}", "name", name,
                                          self.names, self.line("latex", "names"))
            printed[name] = (f"latex.names.{name}", text)
        for name, (item, text) in printed.items():
            if not isinstance(text, str) or not is_printed_name(text):
                raise self.fail(item, f"{text!r} is not a name as LaTeX prints it (letters, "
                                "Greek letters, one subscript)",
                                self.line("symbols", name) if item.startswith("symbols.")
                                else self.line("latex", "names"))
        pos, vel, acc = (self.coordinates.get(k, ()) for k in
                         ("positions", "velocities", "accelerations"))
        try:
            self._latex = LatexNames(tuple(self.names), dict(zip(pos, vel)), dict(zip(pos, acc)),
                                     {n: t for n, (_, t) in printed.items()}, abbreviations)
        except ExpressionError as exc:
            raise self.fail(f"latex.abbreviations.{exc.text}", exc.reason,
                            self.line("latex", "abbreviations")) from exc
        return self._latex

    def from_latex(self, source: LatexSource, item: str, table: str | None, key: str,
                   equation: bool = False) -> str:
        r"""The SymPy-syntax text of a LaTeX value (kept in :attr:`latex_input` under
        ``item``); errors name the file, the line and ``item``."""
        line = self.line(table, key, (source.strip().splitlines() or [""])[0][:40] or None)
        try:
            text = latex_to_sympy(source, self.latex_names(), equation=equation)
        except UndeclaredNameError as exc:
            raise DerivationNameError(self.path, item, exc.kind, exc.name, self.names,
                                      line) from exc
        except ExpressionError as exc:
            raise self.fail(item, exc.reason, line) from exc
        self.latex_input[item] = (str(source), text)
        return text

    # -- sections -------------------------------------------------------------------------
    def symbols(self) -> dict[str, SymbolSpec]:
        specs: dict[str, SymbolSpec] = {}
        for name, entry in self.table("symbols").items():
            item, line = f"symbols.{name}", self.line("symbols", name)
            if isinstance(entry, str):
                entry = {"value": entry}
            if not isinstance(entry, dict):
                raise self.fail(item, "expected \"value\" or { value = ..., units = ... }", line)
            for key in entry:
                if key not in SYMBOL_KEYS:
                    raise self.fail(f"{item}.{key}", "unknown key; valid: "
                                    + ", ".join(SYMBOL_KEYS), line)
            is_input, free = entry.get("input", False), entry.get("free", False)
            if not isinstance(is_input, bool) or not isinstance(free, bool):
                raise self.fail(item, "'input' and 'free' are true or false", line)
            has_value = "value" in entry
            if has_value + is_input + free != 1:
                raise self.fail(item, "give exactly one of: value = \"...\" (its meaning in the "
                                "model), input = true, free = true", line)
            symbol = self.declare(name, "input" if is_input else "symbol", item, line)
            value = None
            if has_value:
                value_text = entry["value"]
                if not isinstance(value_text, (str, int, float)) or isinstance(value_text, bool):
                    raise self.fail(f"{item}.value", "expected an expression", line)
                try:
                    value = parse_model_expression(str(value_text), self.parameters, self.links)
                except UndeclaredNameError as exc:
                    valid = self.links if exc.kind == "link" else self.parameters
                    raise DerivationNameError(self.path, f"{item}.value", exc.kind, exc.name,
                                              valid, line) from exc
                except ExpressionError as exc:
                    raise self.fail(f"{item}.value", exc.reason, line) from exc
            units = entry.get("units")
            if units is not None:
                try:
                    parse_units(str(units))
                except ExpressionError as exc:
                    raise self.fail(f"{item}.units", exc.reason, line) from exc
            specs[name] = SymbolSpec(name, symbol, None if value is None else str(entry["value"]),
                                     None if units is None else str(units),
                                     entry.get("meaning"), value, is_input, free,
                                     entry.get("latex"))
        return specs

    def assume_names(self) -> dict[str, Any]:
        raw = self.table("assume")
        texts = {}
        for name, entry in raw.items():
            item, line = f"assume.{name}", self.line("assume", name)
            if isinstance(entry, dict) and unwrap_latex(entry) is entry:
                extra = set(entry) - {"value", "units", "meaning"}
                if extra or "value" not in entry:
                    raise self.fail(item, "expected \"value\" or { value = ..., units = ..., "
                                    "meaning = ... }", line)
                if entry.get("units") is not None:
                    try:
                        parse_units(str(entry["units"]))
                    except ExpressionError as exc:
                        raise self.fail(f"{item}.units", exc.reason, line) from exc
                entry = entry["value"]
            self.declare(name, "term the model lacks", item, line)
            texts[name] = entry
        return texts

    def definitions(self) -> dict[str, sympy.Expr]:
        raw = self.table("definitions")
        for name in raw:
            self.declare(name, "definition", f"definitions.{name}", self.line("definitions", name))
        parsed = {}
        for name, entry in raw.items():
            text = (entry.get("value") if isinstance(entry, dict)
                    and unwrap_latex(entry) is entry else entry)
            parsed[name] = self.expr(text, f"definitions.{name}", "definitions", name,
                                     expand=False)
        symbols = {self.names[name]: name for name in raw}
        done: dict[sympy.Symbol, sympy.Expr] = {}

        def expand(name: str, chain: tuple[str, ...]) -> sympy.Expr:
            symbol = self.names[name]
            if symbol in done:
                return done[symbol]
            if name in chain:
                raise self.fail(f"definitions.{name}", "circular definition: "
                                + " -> ".join((*chain, name)), self.line("definitions", name))
            inner = {s: expand(symbols[s], (*chain, name))
                     for s in parsed[name].free_symbols if s in symbols}
            done[symbol] = parsed[name].xreplace(inner)
            return done[symbol]

        for name in raw:
            expand(name, ())
        self.expansion = done
        return {name: done[self.names[name]] for name in raw}


def load_derivation(path: str | Path, *, parameters: Collection[str] | None = None,
                    links: Collection[str] | None = None) -> Derivation:
    r"""Load one derivation file (format: ``docs/derivation-format.md``).

    ``parameters`` and ``links``, when given, are the model's valid parameter and link names:
    value expressions using others raise :class:`DerivationNameError`. Raises
    :class:`~wheeled_dyn.errors.InputFileError` for a missing file or malformed TOML (with
    line and column) and :class:`~wheeled_dyn.errors.DerivationError` for content that does
    not fit.
    """
    p = Path(path)
    data, src = read_toml(p)
    ld = _Loader(p, data, src, parameters, links)
    for key in data:
        if key not in TOP_LEVEL_KEYS:
            raise ld.fail(key, "unknown key or table; valid: " + ", ".join(TOP_LEVEL_KEYS),
                          src.line_of(None, key) or src.line_of(key))
    title, model = ld.text("title"), ld.text("model")
    model = resolve_model_reference(p, model, ld.line(None, "model"))
    convention = data.get("convention", "declared")
    if convention not in CONVENTIONS:
        raise ld.fail("convention", "expected one of " + ", ".join(f'"{c}"' for c in
                                                                    CONVENTIONS),
                      ld.line(None, "convention"))
    source = ld.table("source")
    if not all(isinstance(v, str) for v in source.values()):
        raise ld.fail("source", "values are strings", ld.line("source"))
    coord_table = ld.table("coordinates", required=True)
    names = coordinate_names(p, coord_table, model,
                             lambda key: ld.line("coordinates", key))
    ld.coordinates = {"positions": names.positions, "velocities": names.velocities,
                      "accelerations": names.accelerations}
    positions = tuple(ld.declare(n, "position", "coordinates.positions",
                                 ld.line("coordinates", "positions")) for n in names.positions)
    velocities = tuple(ld.declare(n, "velocity", "coordinates.velocities",
                                  ld.line("coordinates", "velocities")) for n in names.velocities)
    accelerations = tuple(ld.declare(n, "acceleration", "coordinates.accelerations",
                                     ld.line("coordinates", "accelerations"))
                          for n in names.accelerations)
    symbols = ld.symbols()
    assumed_texts = ld.assume_names()
    definitions = ld.definitions()
    if "latex" in data:
        ld.latex_names()                          # check [latex] even if no value uses it
    assumptions = {name: ld.expr(text, f"assume.{name}", "assume", name)
                   for name, text in assumed_texts.items()}
    input_symbols = tuple(s.symbol for s in symbols.values() if s.is_input)

    inputs = {}
    for model_input, text in ld.table("inputs").items():
        if not model_input.isidentifier():
            raise ld.fail(f"inputs.{model_input}", "not a model input name",
                          ld.line("inputs", model_input))
        inputs[model_input] = ld.expr(text, f"inputs.{model_input}", "inputs", model_input)
    used = set().union(*(e.free_symbols for e in inputs.values())) if inputs else set()
    for u in input_symbols:
        if u not in used:
            raise ld.fail("inputs", f"document input {u} drives no model input; map it in "
                          "[inputs] (model input = expression of document inputs)",
                          ld.line("inputs") or ld.line("symbols", str(u)))

    n = len(positions)
    row_scale = None
    rows = ld.table("rows")
    if rows:
        extra = set(rows) - {"scale"}
        scale = rows.get("scale")
        if extra or not isinstance(scale, list):
            raise ld.fail("rows", "expected scale = [\"factor of row 1\", ...]", ld.line("rows"))
        if len(scale) != n:
            raise ld.fail("rows.scale", f"{len(scale)} factors for {n} rows",
                          ld.line("rows", "scale"))
        row_scale = tuple(ld.expr(t, f"rows.scale[{i + 1}]", "rows", "scale")
                          for i, t in enumerate(scale))

    reader = MatrixReader(ld, n, input_symbols)
    mtable = ld.table("matrices", required="step" not in data)   # a file of steps only
    matrices = reader.read(mtable) if mtable else {}

    constraints = None
    ctable = ld.table("constraints")
    if ctable:
        extra = set(ctable) - {"equations"}
        equations = unwrap_latex(ctable.get("equations"))
        if extra or not isinstance(equations, list):
            raise ld.fail("constraints", "expected equations = [\"lhs = rhs\", ...]",
                          ld.line("constraints"))
        constraints = tuple(reader.equation(t, f"constraint {i + 1}", "constraints", "equations")
                            for i, t in enumerate(equations))

    reconstructed = ld.table("reconstructed")
    for label, note in reconstructed.items():
        if not isinstance(note, str):
            raise ld.fail(f"reconstructed.{label}", "expected a note (string)",
                          ld.line("reconstructed", label))
        reader.check_label(label, ld.line("reconstructed", label))

    assumes = _assumes(ld, positions)
    # in the steps, the rate of each acceleration (``ddq`` for ``dq``): second-order relations
    # a document derives from its linearised equations (q'' + k q = 0)
    jerks = {f"d{a}": real_symbol(f"d{a}") for a in accelerations if f"d{a}" not in ld.names}
    step_names = {**ld.names, **jerks}
    spec = coordinate_spec(p, coord_table, names,
                           lambda text, item, key: ld.expr(text, item, "coordinates", key),
                           lambda key: ld.line("coordinates", key))
    return Derivation(
        path=p, title=title, model=model, source=MappingProxyType(dict(source)),
        coordinates=spec, inputs=MappingProxyType(inputs), input_symbols=input_symbols,
        symbols=MappingProxyType(symbols), assumptions=MappingProxyType(assumptions),
        definitions=MappingProxyType(definitions), row_scale=row_scale,
        A=matrices.get("A"), C=matrices.get("C"), Q=matrices.get("Q"), B=matrices.get("B"),
        G=matrices.get("G"), equations=reader.equations, constraints=constraints,
        missing=tuple(reader.missing), reconstructed=MappingProxyType(dict(reconstructed)),
        positions=positions, velocities=velocities, accelerations=accelerations,
        namespace=MappingProxyType(dict(ld.names)),
        steps=read_steps(data.get("step"), src.lines, n,
                         lambda text, item: ld.expr(text, item, None, "step", step_names),
                         ld.fail),
        jerks=tuple(jerks.values()),
        feeds=tuple(str(f) for f in data.get("feeds", ())), assumes=assumes,
        latex_input=MappingProxyType(dict(ld.latex_input)), convention=convention)


def _assumes(ld: "_Loader", positions: tuple) -> Mapping[str, Any]:
    r"""``[assumes]``: ``families`` (names of the model's special parameter families),
    ``uniform`` (links that are uniform bodies), ``linearised_about`` (position = number),
    ``potential = "equilibrium"``, ``text`` (other assumptions in words). Family and link
    names are checked against the model by the comparison."""
    raw = ld.table("assumes")
    for key in raw:
        if key not in ASSUMES_KEYS:
            raise ld.fail(f"assumes.{key}", "unknown key; valid: " + ", ".join(ASSUMES_KEYS),
                          ld.line("assumes", key))
    for key in ("families", "uniform", "text"):
        if key in raw and not (isinstance(raw[key], list)
                               and all(isinstance(x, str) for x in raw[key])):
            raise ld.fail(f"assumes.{key}", "expected a list of strings", ld.line("assumes", key))
    point = raw.get("linearised_about", {})
    names = {str(q) for q in positions}
    if not isinstance(point, dict) or any(
            k not in names or isinstance(v, bool) or not isinstance(v, (int, float))
            for k, v in point.items()):
        raise ld.fail("assumes.linearised_about", "expected { position = number, ... } with "
                      "positions among " + ", ".join(sorted(names)),
                      ld.line("assumes", "linearised_about"))
    if raw.get("potential", "equilibrium") != "equilibrium" or (
            "potential" in raw and set(point) != names):
        raise ld.fail("assumes.potential", 'expected "equilibrium", with linearised_about '
                      "giving every position (the equilibrium state)",
                      ld.line("assumes", "potential"))
    return MappingProxyType({"families": tuple(raw.get("families", ())),
                             "uniform": tuple(raw.get("uniform", ())),
                             "linearised_about": MappingProxyType(
                                 {k: float(v) for k, v in point.items()}),
                             "potential": raw.get("potential"),
                             "text": tuple(raw.get("text", ()))})


def load_derivations(paths: Iterable[str | Path], *, parameters: Collection[str] | None = None,
                     links: Collection[str] | None = None) -> list[Derivation]:
    r"""Load several files; a folder stands for its ``*.toml`` derivation files (sorted,
    comparison tables ``*_table.toml`` left out)."""
    return [load_derivation(f, parameters=parameters, links=links) for f in derivation_files(paths)]
