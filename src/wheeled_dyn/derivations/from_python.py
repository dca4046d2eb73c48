r"""Derivations built in Python: SymPy matrices or equations from a notebook, compared like a file.

A person who derives in SymPy has :math:`A`, :math:`C`, :math:`Q`, :math:`B` (or the equations
:math:`A\ddot q + C\dot q + Q = Bu` themselves) as SymPy objects. :func:`derivation_from_sympy`
turns them, with the same tables a derivation file has (coordinates, symbols and their meaning
in the model, inputs, assumptions), into a :class:`~.schema.Derivation` — by writing the TOML a
file would hold (``tomli_w``) and reading it with :func:`~.parse.load_derivation`, so every
check, limit and error of the file format applies unchanged. Errors name the derivation as
``<python: title>`` instead of the temporary file.
"""

from __future__ import annotations

import contextlib
import inspect
import re
import tempfile
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import replace
from pathlib import Path
from typing import Any

import sympy as sp
import tomli_w
from sympy.printing.str import StrPrinter

from ..paths import resolved
from ..errors import DerivationError, WheeledDynError
from .parse import load_derivation
from .schema import Derivation

#: Characters kept from a title in the temporary file's name.
#: What each table of :func:`derivation_from_sympy` is given as, for its errors.
EXPECTED: dict[str, str] = {
    "matrices": "SymPy matrices, nested lists of expressions, or sympy.Eq equations",
    "state_space": "a mapping as [state_space] of a file (state, A and B or f, inputs)",
    "symbols": "a mapping of names to model values (str, SymPy) or tables",
    "inputs": "a mapping of model inputs to expressions",
    "coordinates": "a coordinate set's name or a mapping as [coordinates] of a file",
    "assumes": "a mapping as [assumes] of a file", "source": "a mapping of str"}
_NAME = re.compile(r"[^A-Za-z0-9_-]+")


class _NumberPrinter(StrPrinter):
    r"""SymPy's text with its named numbers written as numbers: a file's ``E`` and ``I`` are
    the document's symbols, so Euler's number is written ``exp(1)`` and the other named
    constants but π as their digits; the imaginary unit is refused (equations of motion are
    real: a symbol of that name is ``sympy.Symbol("I")``)."""

    def _print_Exp1(self, expr: Any) -> str:
        return "exp(1)"

    def _print_ImaginaryUnit(self, expr: Any) -> str:
        raise ValueError("an expression holds SymPy's imaginary unit I (sympy.I): equations "
                         "of motion are real (a symbol named I is sympy.Symbol('I'))")

    def _print_NumberSymbol(self, expr: Any) -> str:
        return "pi" if expr == sp.pi else f"({sp.N(expr, 30)})"

    _print_EulerGamma = _print_GoldenRatio = _print_Catalan = _print_NumberSymbol
    _print_TribonacciConstant = _print_NumberSymbol


def _text(e: Any) -> str:
    return e if isinstance(e, str) else \
        _NumberPrinter().doprint(_without_time(sp.sympify(e)))


def _without_time(e: Any) -> Any:
    r"""``e`` with the functions of time of :mod:`sympy.physics.mechanics`
    (``dynamicsymbols``) read as a derivation's names: :math:`\theta(t)` as ``theta``, its
    first and second derivatives as ``dtheta`` and ``ddtheta`` (the names a file gives a
    position's velocity and acceleration), a generalized speed :math:`u(t)` as ``u`` and its
    derivative as ``du``."""
    if not isinstance(e, sp.Basic):
        return e
    from sympy.core.function import AppliedUndef
    timed = {f for f in e.atoms(AppliedUndef) if len(f.args) == 1 and f.args[0].is_Symbol}
    if not timed:
        return e
    names = {}
    for d in e.atoms(sp.Derivative):
        f, (t, k) = d.expr, d.variable_count[0]
        if f in timed and len(d.variable_count) == 1 and t == f.args[0] and k in (1, 2):
            names[d] = sp.Symbol("d" * int(k) + f.func.__name__, real=True)
    e = e.xreplace(names)
    return e.xreplace({f: sp.Symbol(f.func.__name__, real=True) for f in timed})


def _matrix(M: Any, column: bool = False) -> list:
    r"""Nested lists of SymPy-syntax strings (a column vector as a flat list)."""
    if isinstance(M, (list, tuple)):
        rows = [list(r) if isinstance(r, (list, tuple)) else [r] for r in M]
    else:
        rows = sp.Matrix(M).tolist()
    if column:
        return [_text(r[0]) for r in rows] if all(len(r) == 1 for r in rows) \
            else [_text(x) for x in rows[0]]
    return [[_text(x) for x in r] for r in rows]


def _equation(e: Any) -> str:
    if isinstance(e, str):
        return e
    if isinstance(e, (bool, sp.logic.boolalg.BooleanAtom)):
        raise ValueError(f"an equation SymPy already evaluated to {e} (sympy.Eq of identical "
                         "sides, or with a NaN in one): pass its sides as an expression "
                         "(left - right), or sympy.Eq(left, right, evaluate=False)")
    if isinstance(e, sp.Equality):
        return f"{_text(e.lhs)} = {_text(e.rhs)}"
    return f"{_text(e)} = 0"


class _TableError(Exception):
    r"""A table of :func:`derivation_data` that the arguments do not make: its name, why."""

    def __init__(self, table: str, reason: str) -> None:
        super().__init__(table, reason)
        self.table, self.reason = table, reason


@contextlib.contextmanager
def _table(name: str) -> Iterator[None]:
    r"""Errors of the arguments making table ``name`` (a ``None`` where a table is expected,
    an object that is no expression) as :class:`_TableError` naming it."""
    try:
        yield
    except (TypeError, ValueError, AttributeError, sp.SympifyError) as exc:
        raise _TableError(name, " ".join(str(exc).split())) from None


def derivation_data(model: str | Path, *, coordinates: str | Mapping[str, Any],
                    symbols: Mapping[str, Any] | None = None,
                    inputs: Mapping[str, Any] | None = None,
                    A: Any = None, C: Any = None, Q: Any = None, B: Any = None,
                    G: Any = None, equations: Sequence[Any] | None = None,
                    state_space: Mapping[str, Any] | None = None,
                    assumes: Mapping[str, Any] | None = None,
                    title: str = "derivation from Python",
                    source: Mapping[str, str] | None = None) -> dict[str, Any]:
    r"""The TOML tables of a derivation file for these SymPy objects (see
    :func:`derivation_from_sympy`)."""
    with _table("symbols"):
        symbols = {k: (_text(v) if not isinstance(v, Mapping) else dict(v))
                   for k, v in (symbols or {}).items()}
    with _table("inputs"):
        inputs = {k: _text(v) for k, v in (inputs or {}).items()}
        for text in inputs.values():
            for s in sorted(sp.sympify(text).free_symbols, key=str):
                symbols.setdefault(s.name, {"input": True})
    data: dict[str, Any] = {"title": title, "model": str(model)}
    with _table("source"):
        if source:
            data["source"] = dict(source)
    with _table("coordinates"):
        data["coordinates"] = {"use": coordinates} if isinstance(coordinates, str) \
            else dict(coordinates)
    if inputs:
        data["inputs"] = inputs
    data["symbols"] = symbols
    with _table("assumes"):
        if assumes:
            data["assumes"] = dict(assumes)
    matrices: dict[str, Any] = {}
    with _table("matrices"):
        if equations is not None:
            matrices["equations"] = [_equation(e) for e in equations]
        for key, M in (("A", A), ("C", C), ("B", B), ("G", G)):
            if M is not None:
                matrices[key] = _matrix(M)
        if Q is not None:
            matrices["Q"] = _matrix(Q, column=True)
    if matrices:
        data["matrices"] = matrices
    with _table("state_space"):
        if state_space is not None:
            data["state_space"] = _first_order(state_space)
    return data


def _first_order(table: Mapping[str, Any]) -> dict[str, Any]:
    r"""``[state_space]`` as a file writes it: the state and the inputs as names, A and B as
    matrices, f as a vector (other keys passed on, for the loader to name)."""
    out: dict[str, Any] = {}
    for key, value in dict(table).items():
        if key in ("state", "inputs"):
            out[key] = [v if isinstance(v, str) else _text(v) for v in value]
        elif key in ("A", "B"):
            out[key] = _matrix(value)
        elif key == "f":
            out[key] = _matrix(value, column=True)
        else:
            out[key] = value
    return out


def derivation_from_sympy(model: str | Path, **tables: Any) -> Derivation:
    r"""A :class:`~.schema.Derivation` from SymPy objects.

    ``model``: a model name or model file; ``coordinates``: a built-in coordinate set's name or
    an inline table (as ``[coordinates]`` of a file); ``symbols``: document name → its value in
    the model (``"m_S"``, ``"MX(body)"``) or a table ``{value, units, meaning}``; ``inputs``:
    model input → expression in the document's inputs (undeclared input symbols are declared);
    ``A``, ``C``, ``Q``, ``B``, ``G`` (SymPy matrices or nested lists) or ``equations``
    (``sympy.Eq`` or expressions equal to 0) or ``state_space`` (a mapping as
    ``[state_space]`` of a file: ``state``, ``A`` and ``B`` or ``f``, ``inputs``);
    ``assumes``, ``title``, ``source`` as in a file.
    Raises the errors a file would, naming ``<python: title>``."""
    title = str(tables.get("title", "derivation from Python"))
    name = f"<python: {title if len(title) <= 100 else title[:99] + '…'}>"   # a path's name
    if not any(tables.get(k) is not None
               for k in ("A", "C", "Q", "B", "G", "equations", "state_space")):
        raise DerivationError(Path(name), "matrices", "nothing to compare: give A, C, Q, B, G, "
                              "equations or state_space")
    try:
        data = derivation_data(model, **tables)
    except _TableError as exc:
        expected = EXPECTED.get(exc.table, "what a file's table holds")
        raise DerivationError(Path(name), exc.table, f"expected {expected} ({exc.reason})"
                              ) from None
    except (TypeError, ValueError, AttributeError, sp.SympifyError) as exc:
        raise DerivationError(Path(name), "arguments", " ".join(str(exc).split())) from None
    except RecursionError:
        raise DerivationError(Path(name), "matrices", "an expression nested too deeply to "
                              "print (a file's expressions are at most 32 levels deep)") from None
    model_path = Path(str(model))
    if model_path.suffix == ".toml" and not model_path.is_absolute():
        data["model"] = str(resolved(model_path))
    with tempfile.TemporaryDirectory(prefix="wheeled-dyn-") as folder:
        path = Path(folder) / ((_NAME.sub("_", title).strip("_")[:60] or "derivation")
                               + ".toml")        # (a file name has at most 255 bytes)
        path.write_text(tomli_w.dumps(data), encoding="utf-8")
        try:
            d = load_derivation(path)
        except WheeledDynError as exc:
            raise _renamed(exc, path, name) from None
    return replace(d, path=Path(name))


def _renamed(exc: WheeledDynError, path: Path, name: str) -> WheeledDynError:
    r"""``exc`` rebuilt with the temporary file's path replaced by ``name`` (and no line
    number: the lines are those of the generated file)."""
    args, kwargs = getattr(exc, "_ctor", (exc.args, {}))
    try:
        bound = inspect.signature(type(exc)).bind(*args, **kwargs)
    except TypeError:
        return exc
    for key, value in bound.arguments.items():
        if key in ("line", "column"):
            bound.arguments[key] = None
        elif isinstance(value, (str, Path)) and str(value) == str(path):
            bound.arguments[key] = Path(name)
    try:
        return type(exc)(*bound.args, **bound.kwargs)
    except TypeError:
        return exc


__all__ = ["derivation_data", "derivation_from_sympy"]
