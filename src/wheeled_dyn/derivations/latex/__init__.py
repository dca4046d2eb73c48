r"""LaTeX input: expressions, equations and matrices copied from a document.

A value written ``{ latex = '''...''' }`` in a derivation file is read here and turned into the
SymPy-syntax text the rest of the loader parses (:mod:`~wheeled_dyn.derivations.expressions`,
with all its limits). ``pylatexenc`` tokenises the LaTeX; the file's symbol table
(:class:`LatexNames`) resolves it. One concept a module, each used only by those after it:

- :mod:`.nodes`: the value as written (:class:`LatexSource`), the vocabulary, pylatexenc's
  nodes, :class:`LatexError` and equation numbers (``\tag{10}``, a final ``\quad (9)``);
- :mod:`.atoms`: the atoms the nodes are read into and the grammar of sums, products,
  functions and powers over them;
- :mod:`.runs`: a run of letters, subscripts and Greek letters split into declared names,
  numbers, abbreviations and functions spelled in plain letters; an ambiguous run is an
  error showing both readings;
- :mod:`.reader`: an expression or equation to SymPy text (:func:`latex_to_sympy`,
  :func:`parse_latex_expression`), ``\dot{p}``/``\ddot{p}`` as velocities and accelerations;
- :mod:`.names`: the symbol table (:class:`LatexNames`), whose printed forms and
  abbreviations are themselves read with the reader (so the reader and the runs refer to it
  in type annotations only);
- :mod:`.matrices`: ``bmatrix``/``pmatrix`` cells (:func:`split_latex_matrix`), transposed
  by ``^T``.
"""

from .matrices import MATRICES, TRANSPOSE, split_latex_matrix
from .names import LatexNames, is_printed_name
from .nodes import (EQUATION_NUMBER, FONTS, FUNCTIONS, GREEK, IGNORED, LATEX_KEY, LATEX_KEYS,
                    MAX_LATEX_CHARS, NUMBER_SPACES, OPERATORS, TAG, VARIANTS, LatexError,
                    LatexSource, unwrap_latex)
from .reader import latex_to_sympy, parse_latex_expression
from .runs import MAX_READINGS, MAX_SHOWN

__all__ = [
    "EQUATION_NUMBER", "FONTS", "FUNCTIONS", "GREEK", "IGNORED", "LATEX_KEY", "LATEX_KEYS",
    "LatexError", "LatexNames", "LatexSource", "MATRICES", "MAX_LATEX_CHARS", "MAX_READINGS",
    "MAX_SHOWN", "NUMBER_SPACES", "OPERATORS", "TAG", "TRANSPOSE", "VARIANTS",
    "is_printed_name", "latex_to_sympy", "parse_latex_expression", "split_latex_matrix",
    "unwrap_latex",
]
