r"""LaTeX as written: the ``{ latex = '...' }`` value, its vocabulary and its pylatexenc nodes.

A value written ``{ latex = '''...''' }`` in a derivation file is kept as a
:class:`LatexSource` until it is read. ``pylatexenc`` tokenises it in math mode
(:func:`parse_nodes`); any LaTeX it cannot tokenise is a :class:`LatexError`. The
vocabulary the reader knows (functions, Greek letters, fonts, operators, spacing) is named
here, as is the equation number a document prints: ``\tag{10}`` is dropped anywhere;
``\quad (9)`` only at the end of an equation or a matrix (elsewhere it is spacing and a
factor 9, :func:`drop_equation_number`).
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from typing import Any

from pylatexenc import macrospec
from pylatexenc.latexwalker import (LatexCharsNode, LatexCommentNode, LatexMacroNode,
                                    LatexMathNode, LatexWalker, LatexWalkerError,
                                    get_default_latex_context_db)

from ..expressions import ExpressionError

#: The key marking a value as LaTeX: ``A = { latex = '...' }``.
LATEX_KEY = "latex"
#: Keys of a file's ``[latex]`` table.
LATEX_KEYS: tuple[str, ...] = ("names", "abbreviations")
#: Longest LaTeX value read (the matrix A of seed 001's eq. (25) has about 900 characters).
MAX_LATEX_CHARS = 20_000
#: LaTeX functions and the SymPy function each is.
FUNCTIONS: Mapping[str, str] = {
    "sin": "sin", "cos": "cos", "tan": "tan", "cot": "cot", "sec": "sec", "csc": "csc",
    "arcsin": "asin", "arccos": "acos", "arctan": "atan", "sinh": "sinh", "cosh": "cosh",
    "tanh": "tanh", "exp": "exp", "log": "log", "ln": "log"}
GREEK: frozenset[str] = frozenset(
    "alpha beta gamma delta epsilon zeta eta theta iota kappa lambda mu nu xi omicron rho sigma "
    "tau upsilon phi chi psi omega Gamma Delta Theta Lambda Xi Pi Sigma Upsilon Phi Psi Omega"
    .split())
#: Variant letters: read as the plain letter when only that one is declared (``\ell`` a
#: length's script l).
VARIANTS: Mapping[str, str] = {"varphi": "phi", "vartheta": "theta", "varepsilon": "epsilon",
                               "varrho": "rho", "varsigma": "sigma", "ell": "l"}
#: Fonts: a name in any of them is the name (``\mathbb{M}``, ``\mathbf{MZ_1}``).
FONTS: frozenset[str] = frozenset({"mathbf", "mathrm", "mathit", "mathsf", "mathtt", "mathbb",
                                   "mathcal", "mathfrak", "mathscr", "boldsymbol", "bm"})
IGNORED: frozenset[str] = frozenset({",", ";", ":", "!", " ", "quad", "qquad", "big", "Big",
                                     "bigl", "bigr", "Bigl", "Bigr", "displaystyle"})
OPERATORS: Mapping[str, str] = {"cdot": "*", "times": "*", "div": "/", "{": "(", "}": ")",
                                "lbrack": "(", "rbrack": ")"}
#: An equation number: ``\tag{10}`` (dropped anywhere) and, after the last term of an
#: equation or a matrix, ``\quad (9)`` (one of :data:`NUMBER_SPACES`, then the number).
TAG = "tag"
NUMBER_SPACES: frozenset[str] = frozenset({"quad", "qquad"})
EQUATION_NUMBER = re.compile(r"\s*\(\s*\d+(?:\.\d+)*[a-z]?\s*\)\s*")

_CONTEXT = get_default_latex_context_db()
_CONTEXT.add_context_category("wheeled_dyn", prepend=True, macros=[
    macrospec.MacroSpec(m, "{{") for m in ("tfrac", "dfrac")] + [
    macrospec.MacroSpec(m, "{") for m in ("boldsymbol", "bm", "operatorname")] + [
    macrospec.MacroSpec(TAG, "*{"), macrospec.MacroSpec("top", ""),
    macrospec.MacroSpec("intercal", "")])


class LatexSource(str):
    r"""LaTeX text as written in a file (``{ latex = '...' }``), not yet read."""


def unwrap_latex(raw: Any) -> Any:
    r"""``{ latex = "..." }`` → :class:`LatexSource`; ``{ latex = ["...", ...] }`` → a list of
    them; any other value unchanged."""
    if not (isinstance(raw, dict) and set(raw) == {LATEX_KEY}):
        return raw
    value = raw[LATEX_KEY]
    if isinstance(value, list) and all(isinstance(v, str) for v in value):
        return [LatexSource(v) for v in value]
    return LatexSource(value) if isinstance(value, str) else raw


class LatexError(ExpressionError):
    r"""LaTeX that cannot be read; ``readings`` holds both readings of an ambiguous run."""

    def __init__(self, text: str, reason: str, readings: tuple[str, ...] = ()) -> None:
        self.readings = readings
        super().__init__(text, reason)

    def __reduce__(self):
        return type(self), (self.text, self.reason, self.readings)


def parse_nodes(source: str) -> list[Any]:
    r"""pylatexenc's nodes of ``source`` in math mode; any LaTeX error is a :class:`LatexError`."""
    if len(source) > MAX_LATEX_CHARS:
        raise LatexError(source[:80], f"LaTeX longer than {MAX_LATEX_CHARS} characters")
    walker = LatexWalker(source, latex_context=_CONTEXT, tolerant_parsing=False)
    try:
        nodes, _, _ = walker.get_latex_nodes(parsing_state=walker.make_parsing_state(
            in_math_mode=True))
    except LatexWalkerError as exc:
        raise LatexError(source, "cannot read the LaTeX: " + str(exc).split("\n")[0]) from None
    except RecursionError:
        raise LatexError(source, "LaTeX nested too deeply") from None
    return nodes


def _blank(node: Any) -> bool:
    return node is None or isinstance(node, LatexCommentNode) or (
        isinstance(node, LatexCharsNode) and not node.chars.strip())


def content(nodes: list[Any]) -> list[Any]:
    r"""The nodes of a value without blanks and comments; of one math group (``$...$``),
    the nodes inside it."""
    kept = [n for n in nodes if not _blank(n)]
    if len(kept) == 1 and isinstance(kept[0], LatexMathNode):
        kept = [n for n in kept[0].nodelist if not _blank(n)]
    return kept


def drop_equation_number(nodes: list[Any]) -> list[Any]:
    r"""``nodes`` without a final equation number ``\quad (9)``: spacing with at least one of
    :data:`NUMBER_SPACES`, then only :data:`EQUATION_NUMBER`, after a last term. Anywhere
    else ``\quad (9)`` is spacing and a factor 9."""
    kept = [n for n in nodes if not _blank(n)]
    if not (kept and isinstance(kept[-1], LatexCharsNode)
            and EQUATION_NUMBER.fullmatch(kept[-1].chars)):
        return nodes
    j, spaced = len(kept) - 1, False
    while j > 0 and isinstance(kept[j - 1], LatexMacroNode) and kept[j - 1].macroname in IGNORED:
        spaced = spaced or kept[j - 1].macroname in NUMBER_SPACES
        j -= 1
    return kept[:j] if spaced and j > 0 else nodes
