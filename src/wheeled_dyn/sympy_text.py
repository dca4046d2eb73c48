r"""Expressions read back from SymPy's text form (``sstr``) with every name a plain symbol:
``I`` is a symbol, not :math:`\sqrt{-1}`, ``E`` not Euler's number, ``Q`` not SymPy's
assumptions, ``gamma`` not the Gamma function — the names of a document or a model, as the
comparison printed them. Used wherever a printed residual or truth is turned back into an
expression (its LaTeX, its terms)."""

from __future__ import annotations

import functools
import keyword
import re
from collections.abc import Mapping

import sympy as sp

#: Function names kept as SymPy functions when expressions are re-read.
FUNCTIONS: Mapping[str, object] = {
    name: getattr(sp, name) for name in (
        "sin", "cos", "tan", "cot", "sec", "csc", "asin", "acos", "atan", "atan2", "sinh",
        "cosh", "tanh", "exp", "log", "sqrt", "Abs", "sign", "Min", "Max", "Piecewise",
        "Heaviside", "re", "im")}
#: Constants kept as SymPy constants (``pi``); everything else is a symbol.
CONSTANTS: Mapping[str, object] = {"pi": sp.pi, "oo": sp.oo, "nan": sp.nan, "zoo": sp.zoo}
#: Expressions longer than this (characters of text) are not re-read (shown as text).
MAX_TEXT = 6000

_IDENT = re.compile(r"[A-Za-z_][A-Za-z_0-9]*")


@functools.lru_cache(maxsize=8192)
def parse(text: str) -> sp.Expr | None:
    r"""An expression from SymPy's text form with every name a plain symbol (``I`` is a
    symbol, not :math:`\sqrt{-1}`); None when the text cannot be read."""
    if not text or len(text) > MAX_TEXT:
        return None
    local: dict[str, object] = {}
    for name in set(_IDENT.findall(text)):
        if name in FUNCTIONS:
            local[name] = FUNCTIONS[name]
        elif name in CONSTANTS:
            local[name] = CONSTANTS[name]
        elif re.search(rf"\b{re.escape(name)}\s*\(", text):
            local[name] = sp.Function(name)
        else:
            local[name] = sp.Symbol(name)
    if any(keyword.iskeyword(n) for n in local):
        return None
    try:
        return sp.sympify(text, locals=local, rational=False)
    except (sp.SympifyError, SyntaxError, TypeError, ValueError, AttributeError):
        return None


__all__ = ["CONSTANTS", "FUNCTIONS", "MAX_TEXT", "parse"]
