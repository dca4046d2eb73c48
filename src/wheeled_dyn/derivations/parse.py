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
is checked by the comparison engine, or here when ``parameters``/``links`` are passed. The
file's namespace and its declaring sections: :mod:`.loader`; the matrices and equations:
:mod:`.matrices`; the steps: :mod:`.steps`.
"""

from __future__ import annotations

import math
import os
from collections.abc import Collection, Iterable, Mapping
from pathlib import Path
from types import MappingProxyType
from typing import Any

import sympy

from ..errors import ArgumentError
from .builtin import derivation_files
from .coordinates import (CoordinateNames, coordinate_names, coordinate_spec,
                          resolve_model_reference)
from .expressions import real_symbol
from .latex import unwrap_latex
from .limits import MAX_CONSTANT
from .loader import _Loader
from .matrices import MatrixReader
from .schema import Derivation
from .source import read_toml
from .state_space import StateSpace, read_state_space
from .steps import read_steps

TOP_LEVEL_KEYS: tuple[str, ...] = ("title", "model", "source", "coordinates", "inputs",
                                   "symbols", "assume", "definitions", "rows", "matrices",
                                   "constraints", "reconstructed", "step", "feeds",
                                   "assumes", "latex", "convention", "state_space")
#: Values of the top-level ``convention``: ``"declared"`` (the default: the file's maps are
#: how the document is read, binding) or ``"unknown"`` (the document's sign conventions are
#: not known: a better reading found by the comparison is applied, and said first).
CONVENTIONS: tuple[str, ...] = ("declared", "unknown")
#: Keys of ``[assumes]``: what the document assumes (see docs/derivation-format.md).
ASSUMES_KEYS: tuple[str, ...] = ("families", "uniform", "linearised_about", "potential", "text")


def _header(ld: _Loader) -> tuple[str, str, str, dict[str, Any]]:
    r"""Check the top-level keys; the ``title``, the ``model`` (resolved), the ``convention``
    and the ``[source]`` of the file."""
    for key in ld.data:
        if key not in TOP_LEVEL_KEYS:
            raise ld.fail(key, "unknown key or table; valid: " + ", ".join(TOP_LEVEL_KEYS),
                          ld.src.line_of(None, key) or ld.src.line_of(key))
    title, model = ld.text("title"), ld.text("model")
    model = resolve_model_reference(ld.path, model, ld.line(None, "model"))
    convention = ld.data.get("convention", "declared")
    if convention not in CONVENTIONS:
        raise ld.fail("convention", "expected one of " + ", ".join(f'"{c}"' for c in
                                                                    CONVENTIONS),
                      ld.line(None, "convention"))
    source = ld.table("source")
    if not all(isinstance(v, str) for v in source.values()):
        raise ld.fail("source", "values are strings", ld.line("source"))
    if source.get("convention") in CONVENTIONS:      # TOML puts a key after a table in it
        raise ld.fail("source.convention", "'convention' is a key of the file, not of "
                      "[source]: write it above the first table (a key after a [table] "
                      "header belongs to that table)", ld.line("source", "convention"))
    return title, model, convention, source


def _coordinates(ld: _Loader, coord_table: dict[str, Any], model: str) -> tuple[
        CoordinateNames, tuple[sympy.Symbol, ...], tuple[sympy.Symbol, ...],
        tuple[sympy.Symbol, ...]]:
    r"""The names of ``[coordinates]``, and the positions, velocities and accelerations
    declared."""
    names = coordinate_names(ld.path, coord_table, model,
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
    return names, positions, velocities, accelerations


def _inputs(ld: _Loader, input_symbols: tuple[sympy.Symbol, ...]) -> dict[str, sympy.Expr]:
    r"""``[inputs]``: each model input as an expression of the document inputs, every document
    input driving one."""
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
    return inputs


def _row_scale(ld: _Loader, n: int) -> tuple[sympy.Expr, ...] | None:
    r"""``[rows] scale``: one factor per row, or None."""
    rows = ld.table("rows")
    if not rows:
        return None
    extra = set(rows) - {"scale"}
    scale = rows.get("scale")
    if extra or not isinstance(scale, list):
        raise ld.fail("rows", "expected scale = [\"factor of row 1\", ...]", ld.line("rows"))
    if len(scale) != n:
        raise ld.fail("rows.scale", f"{len(scale)} factors for {n} rows",
                      ld.line("rows", "scale"))
    out = tuple(ld.expr(t, f"rows.scale[{i + 1}]", "rows", "scale")
                for i, t in enumerate(scale))
    for i, factor in enumerate(out):
        if factor.is_zero:
            raise ld.fail(f"rows.scale[{i + 1}]", f"{factor}: a row's factor must not be zero "
                          "(every equation times 0 is 0 = 0)", ld.line("rows", "scale"))
    return out


def _constraints(ld: _Loader, reader: MatrixReader) -> tuple[sympy.Eq, ...] | None:
    r"""``[constraints] equations``, or None."""
    ctable = ld.table("constraints")
    if not ctable:
        return None
    extra = set(ctable) - {"equations"}
    equations = unwrap_latex(ctable.get("equations"))
    if extra or not isinstance(equations, list):
        raise ld.fail("constraints", "expected equations = [\"lhs = rhs\", ...]",
                      ld.line("constraints"))
    return tuple(reader.equation(t, f"constraint {i + 1}", "constraints", "equations")
                 for i, t in enumerate(equations))


def _reconstructed(ld: _Loader, reader: MatrixReader) -> dict[str, Any]:
    r"""``[reconstructed]``: a note for each element or equation label the file restored."""
    reconstructed = ld.table("reconstructed")
    for label, note in reconstructed.items():
        if not isinstance(note, str):
            raise ld.fail(f"reconstructed.{label}", "expected a note (string)",
                          ld.line("reconstructed", label))
        reader.check_label(label, ld.line("reconstructed", label))
    return reconstructed


def load_derivation(path: str | Path, *, parameters: Collection[str] | None = None,
                    links: Collection[str] | None = None) -> Derivation:
    r"""Load one derivation file (format: ``docs/derivation-format.md``).

    ``parameters`` and ``links``, when given, are the model's valid parameter and link names:
    value expressions using others raise :class:`DerivationNameError`. Raises
    :class:`~wheeled_dyn.errors.InputFileError` for a missing file or malformed TOML (with
    line and column) and :class:`~wheeled_dyn.errors.DerivationError` for content that does
    not fit.
    """
    if not isinstance(path, (str, os.PathLike)):
        raise ArgumentError("load_derivation", "path", path, "the path of a derivation file "
                            "(str or pathlib.Path)")
    for argument, given in (("parameters", parameters), ("links", links)):
        if given is not None and (isinstance(given, str) or not isinstance(given, Iterable)
                                  or not all(isinstance(n, str) for n in given)):
            raise ArgumentError("load_derivation", argument, given, "a collection of names")
    p = Path(path)
    data, src = read_toml(p)
    ld = _Loader(p, data, src, parameters, links)
    title, model, convention, source = _header(ld)
    coord_table = ld.table("coordinates", required=True)
    names, positions, velocities, accelerations = _coordinates(ld, coord_table, model)
    symbols = ld.symbols()
    assumed_texts = ld.assume_names()
    definitions = ld.definitions()
    if "latex" in data:
        ld.latex_names()                          # check [latex] even if no value uses it
    assumptions = {name: ld.expr(text, f"assume.{name}", "assume", name)
                   for name, text in assumed_texts.items()}
    input_symbols = tuple(s.symbol for s in symbols.values() if s.is_input)
    inputs = _inputs(ld, input_symbols)
    n = len(positions)
    row_scale = _row_scale(ld, n)

    reader = MatrixReader(ld, n, input_symbols)
    assumes = _assumes(ld, positions)
    first_order = _state_space(ld, positions, velocities, accelerations, input_symbols,
                               assumes)
    mtable = ld.table("matrices", required="step" not in data and first_order is None)
    matrices = reader.read(mtable) if mtable else {}     # none: a file of steps only
    if first_order is not None:
        reader.equations = first_order.equations
        reader.missing.extend(first_order.missing)
    constraints = _constraints(ld, reader)
    reconstructed = _reconstructed(ld, reader)

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
        feeds=_feeds(ld), assumes=assumes,
        latex_input=MappingProxyType(dict(ld.latex_input)), convention=convention,
        state_space=first_order)


def _state_space(ld: "_Loader", positions, velocities, accelerations, inputs, assumes
                 ) -> StateSpace | None:
    r"""``[state_space]`` (:mod:`.state_space`), or None; a file gives it or ``[matrices]``."""
    table = ld.table("state_space")
    if not table:
        return None
    if "matrices" in ld.data:
        raise ld.fail("state_space", "give [state_space] or [matrices], not both",
                      ld.line("state_space"))
    rates = len(velocities) == len(positions) and all(
        str(v) == f"d{q}" for q, v in zip(positions, velocities))
    if ld.table("coordinates").get("kind", "holonomic") != "holonomic" and not rates:
        raise ld.fail("state_space", "a state-space form needs each velocity to be its "
                      "position's rate (a holonomic set, or velocities named d<position>: "
                      "dx the rate of x)", ld.line("state_space"))
    point = assumes["linearised_about"] if "linearised_about" in ld.table("assumes") else None
    return read_state_space(ld, table, tuple(zip(positions, velocities, accelerations)),
                            inputs, point)


def _feeds(ld: "_Loader") -> tuple[str, ...]:
    r"""``feeds``: the names (file stems) of the derivations a step file leads to, a list of
    strings (a single string is not read as its letters)."""
    feeds = ld.data.get("feeds", [])
    if not isinstance(feeds, list) or not all(isinstance(f, str) for f in feeds):
        raise ld.fail("feeds", "expected a list of derivation file names without .toml, "
                      'e.g. ["eq25_lagrange"]', ld.line(None, "feeds"))
    return tuple(feeds)


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
    for k, v in point.items():
        if not math.isfinite(v) or abs(v) > MAX_CONSTANT:
            raise ld.fail(f"assumes.linearised_about.{k}", f"{v} is not a finite number of "
                          f"magnitude at most {MAX_CONSTANT:g}",
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
