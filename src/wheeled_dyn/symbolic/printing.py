r"""Printers for closed forms: LaTeX, MathML, SymPy ``srepr`` and plain text.

Symbol names follow Khalil's notation: ``XX_thl`` prints as :math:`\mathrm{XX}_{\mathrm{thl}}`,
Greek names as letters (``psi`` :math:`\to \psi`), and a velocity symbol whose coordinate is
known (``dots={dpsi: psi}``, see :func:`velocity_dots`) as :math:`\dot\psi`. MathML is
``latex2mathml``'s rendering of the LaTeX text (cleaner than SymPy's own MathML printer).
``srepr`` text round-trips exactly through :func:`from_srepr`.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping

import sympy as sp

from ..errors import OptionalDependencyError


def _name_latex(name: str) -> str:
    text = sp.latex(sp.Symbol(name))
    if len(name) > 1 and text == name and name.isalnum():
        return rf"\mathrm{{{name}}}"
    return text


def symbol_latex(symbol: sp.Symbol) -> str:
    r"""LaTeX of one symbol: ``base_sub`` as ``base_{sub}``, multi-letter parts upright,
    Greek names as letters."""
    base, sep, sub = symbol.name.partition("_")
    if not base or not sep or not sub:
        return _name_latex(symbol.name)
    return f"{_name_latex(base)}_{{{_name_latex(sub)}}}"


def velocity_dots(sym) -> dict[sp.Symbol, sp.Symbol]:
    """``{velocity symbol: coordinate symbol}`` of a :class:`~.model.SymbolicModel`
    (``qd`` ↔ ``q``), for printing velocities with a dot."""
    return dict(zip(sym.qd, sym.q))


def latex_names(symbols: Iterable[sp.Symbol],
                dots: Mapping[sp.Symbol, sp.Symbol] | None = None) -> dict[sp.Symbol, str]:
    """The ``symbol_names`` table SymPy's LaTeX printer takes, for ``symbols``."""
    dots = dict(dots or {})
    out = {}
    for s in symbols:
        if not isinstance(s, sp.Symbol):
            continue
        out[s] = rf"\dot{{{symbol_latex(dots[s])}}}" if s in dots else symbol_latex(s)
    return out


def to_latex(M: sp.Basic, dots: Mapping[sp.Symbol, sp.Symbol] | None = None,
             names: Mapping[sp.Symbol, str] | None = None) -> str:
    """LaTeX text of an expression or matrix (``dots``: velocity → coordinate; ``names``:
    explicit LaTeX per symbol, winning over the defaults)."""
    M = sp.sympify(M)
    table = latex_names(M.free_symbols, dots)
    table.update(names or {})
    return sp.latex(M, symbol_names=table)


def to_mathml(M: sp.Basic, dots: Mapping[sp.Symbol, sp.Symbol] | None = None,
              names: Mapping[sp.Symbol, str] | None = None, display: str = "block") -> str:
    """Presentation MathML (``<math>`` element) of :func:`to_latex`'s text."""
    try:
        from latex2mathml.converter import convert
    except ImportError as exc:  # pragma: no cover - a declared dependency
        raise OptionalDependencyError("MathML output", "latex2mathml",
                                      "pip install latex2mathml") from exc
    return convert(to_latex(M, dots, names), display=display)


def to_srepr(M: sp.Basic) -> str:
    """Exact, re-readable text (``sympy.srepr``)."""
    return sp.srepr(sp.sympify(M))


def from_srepr(text: str) -> sp.Basic:
    """Inverse of :func:`to_srepr` (expressions and matrices)."""
    return sp.parse_expr(text)


def to_text(M: sp.Basic) -> str:
    """Plain SymPy text (``str``), readable and parseable by ``sympy.sympify``."""
    return str(sp.sympify(M))
