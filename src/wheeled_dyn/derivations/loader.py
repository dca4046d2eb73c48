r"""One derivation file's namespace while it is loaded (:class:`_Loader`): the names it
declares, its expressions parsed in that namespace only (:mod:`.expressions`, with the
``[definitions]`` expanded), its LaTeX values read (:mod:`.latex`), and its errors, which
name the file, the line and the item.

The declaring sections are read here: ``[symbols]`` (each a value in the model's namespace,
a document input or a free symbol), ``[assume]`` (terms the model lacks) and
``[definitions]`` (expanded into one another, a circular definition refused). The whole file:
:mod:`.parse`; the comparison tables, which share the namespace: :mod:`.table`.
"""

from __future__ import annotations

import math
import unicodedata
from collections.abc import Collection, Mapping
from pathlib import Path
from typing import Any

import sympy

from ..errors import DerivationError
from .errors import DerivationNameError
from .expressions import (RESERVED_NAMES, ExpressionError, UndeclaredNameError,
                          check_expanded, parse_expression, parse_model_expression, parse_units,
                          real_symbol, scan_names)
from .latex import (LATEX_KEYS, LatexNames, LatexSource, is_printed_name, latex_to_sympy,
                    unwrap_latex)
from .limits import (MAX_DEFINITION_DEPTH, MAX_DOCUMENT_TERMS, MAX_FILE_TERMS, MAX_SYMBOLS,
                     MAX_TREE_NODES, tree_size)
from .schema import SymbolSpec
from .source import SourceText

#: Names that stand for NaN or an infinity (in Python, SymPy or TOML): not finite numbers.
NON_FINITE_NAMES = frozenset({"nan", "inf", "infinity", "oo", "zoo"})
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
        self.terms = 0                  # of the expressions read so far, multiplied out
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
        kept = unicodedata.normalize("NFKC", name)
        if kept != name:             # Python reads ℓ as l, ϑ as θ, ﬁ as fi in compiled code
            raise self.fail(item, f"{name!r} is read as {kept!r} by Python (Unicode NFKC): "
                            f"name it {kept!r} or otherwise", line)
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
            self.terms += check_expanded(source, value, MAX_DOCUMENT_TERMS)
            if self.terms > MAX_FILE_TERMS:
                raise ExpressionError(source, f"the file's expressions have more than "
                                      f"{MAX_FILE_TERMS} terms once multiplied out together")
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
        table = self.table("symbols")
        if len(table) > MAX_SYMBOLS:
            raise self.fail("symbols", f"{len(table)} symbols declared; at most {MAX_SYMBOLS}",
                            self.line("symbols"))
        for name, entry in table.items():
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
        depth: dict[sympy.Symbol, int] = {}

        def expand(name: str, chain: tuple[str, ...]) -> sympy.Expr:
            symbol = self.names[name]
            if symbol in done:
                return done[symbol]
            if name in chain:
                raise self.fail(f"definitions.{name}", "circular definition: "
                                + " -> ".join((*chain, name)), self.line("definitions", name))
            if len(chain) >= MAX_DEFINITION_DEPTH:        # (declared outermost first)
                raise self.fail(f"definitions.{chain[0]}", "definitions nested more than "
                                f"{MAX_DEFINITION_DEPTH} deep (each used in the next)",
                                self.line("definitions", chain[0]))
            inner = {s: expand(symbols[s], (*chain, name))
                     for s in parsed[name].free_symbols if s in symbols}
            depth[symbol] = 1 + max((depth[s] for s in inner), default=0)
            if depth[symbol] > MAX_DEFINITION_DEPTH:
                raise self.fail(f"definitions.{name}", "definitions nested more than "
                                f"{MAX_DEFINITION_DEPTH} deep (each used in the next)",
                                self.line("definitions", name))
            done[symbol] = parsed[name].xreplace(inner)
            nodes = tree_size(done[symbol])
            if nodes > MAX_TREE_NODES:      # each use copies the one before: a tree of 2**k
                raise self.fail(f"definitions.{name}", f"definition too large: {nodes} "
                                "nodes written out (the definitions it uses substituted), at "
                                f"most {MAX_TREE_NODES}", self.line("definitions", name))
            return done[symbol]

        for name in raw:
            expand(name, ())
        self.expansion = done
        return {name: done[self.names[name]] for name in raw}
