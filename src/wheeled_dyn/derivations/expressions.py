r"""Safe parsing of the expressions written in derivation files.

A derivation file holds expressions in SymPy syntax (``m_s*d*cos(phi)*ddphi``, ``x^2`` is
accepted for ``x**2``). They are parsed with :func:`sympy.parsing.sympy_parser.parse_expr`, but
only after a token check that admits

- names from an explicit table (the file's declared symbols, coordinates, velocities, ...),
  plus the standard functions :data:`STANDARD_FUNCTIONS` and the constant ``pi``;
- numbers (decimals become exact rationals: ``0.5`` is :math:`\tfrac12`);
- the operators ``+ - * / ** ^`` and the parentheses and commas of function calls.

Anything else (attribute access, strings, brackets, keywords, ``=``, names starting with ``_``)
is an :class:`ExpressionError`; an undeclared name is an :class:`UndeclaredNameError` carrying
the name. Unknown names are errors, never new symbols: a typo in a file is reported, not
silently turned into a fresh parameter. Every expression is held to the limits of
:mod:`.limits` (:data:`MAX_TOKENS`, :data:`MAX_NESTING`, :data:`MAX_EXPONENT`,
:data:`MAX_CONSTANT`); the document expressions of a derivation file (elements, equations,
definitions, inputs, steps: read by its loader, with its definitions substituted) and every
model expression (:func:`parse_model_expression`) also to :data:`MAX_EXPANDED_TERMS`.

Two namespaces exist (:mod:`.namespace`): the *document* namespace (:func:`parse_expression`:
what the document writes) and the *model* namespace (:func:`parse_model_expression`: values of
``[symbols]``, Khalil's and the physical parameters of a link, the model's lengths). The model
namespace is open (any identifier is a parameter) unless the caller passes the valid parameter
and link names: the parser does not import the models. Units: :func:`parse_units`.

The names of :mod:`.namespace`, :mod:`.limits`, :mod:`.nested` and the expression errors
(:mod:`.errors`) are importable from here as well.
"""

from __future__ import annotations

import io
import keyword
import tokenize
from collections.abc import Collection, Mapping

import sympy
from sympy.parsing.sympy_parser import auto_number, convert_xor, parse_expr, rationalize

from .errors import ExpressionError, UndeclaredNameError
from .limits import (MAX_CONSTANT, MAX_EXPANDED_TERMS, MAX_EXPONENT, MAX_NESTING, MAX_TOKENS,
                     check_expanded, check_limits, expanded_terms)
from .namespace import (CONSTANTS, GEOMETRY_NAMES, KHALIL_FUNCTIONS, KHALIL_NAMES,
                        LINK_FUNCTIONS, PHYSICAL_NAMES, RESERVED_NAMES, STANDARD_FUNCTIONS,
                        UNIT_NAMES, UNITS, physical_in_standard, real_symbol)
from .nested import Nested, split_nested

_OPERATORS = frozenset({"+", "-", "*", "/", "**", "^", "(", ")", ","})
_TRANSFORMATIONS = (auto_number, rationalize, convert_xor)
_GLOBALS: dict[str, object] = {"Integer": sympy.Integer, "Float": sympy.Float,
                               "Rational": sympy.Rational}


def _normalise(text: str) -> str:
    return " ".join(str(text).split())


def scan_names(text: str) -> list[tuple[str, bool]]:
    r"""Check the tokens of ``text`` and return its names in order, each with whether it is
    called (followed by ``(``). Raises :class:`ExpressionError` for a disallowed token."""
    src = _normalise(text)
    if not src:
        raise ExpressionError(text, "empty expression")
    try:
        tokens = [t for t in tokenize.generate_tokens(io.StringIO(src).readline)
                  if t.type not in (tokenize.NEWLINE, tokenize.NL, tokenize.ENDMARKER)
                  and not (t.type == tokenize.ERRORTOKEN and t.string.isspace())]
    except (tokenize.TokenError, IndentationError, SyntaxError) as exc:
        raise ExpressionError(text, f"cannot tokenize ({exc.args[0]})") from exc
    names: list[tuple[str, bool]] = []
    for k, tok in enumerate(tokens):
        if tok.type == tokenize.NAME:
            if keyword.iskeyword(tok.string) or keyword.issoftkeyword(tok.string):
                raise ExpressionError(text, f"{tok.string!r} is a Python keyword; rename it")
            if tok.string.startswith("_"):
                raise ExpressionError(text, f"names may not start with '_' ({tok.string!r})")
            called = k + 1 < len(tokens) and tokens[k + 1].string == "("
            names.append((tok.string, called))
        elif tok.type == tokenize.NUMBER:
            if tok.string[-1] in "jJ":
                raise ExpressionError(text, f"imaginary number {tok.string!r}")
        elif tok.type == tokenize.OP and tok.string in _OPERATORS:
            continue
        elif tok.string == "=":
            raise ExpressionError(text, "'=' is allowed only once, in an equation")
        else:
            raise ExpressionError(text, f"token {tok.string!r} is not allowed")
    check_limits(text, src, tokens)
    return names


def _evaluate(text: str, local: Mapping[str, object]) -> sympy.Expr:
    try:
        expr = parse_expr(_normalise(text), local_dict=dict(local), global_dict=dict(_GLOBALS),
                          transformations=_TRANSFORMATIONS, evaluate=True)
    except (SyntaxError, TypeError, ValueError, AttributeError, ZeroDivisionError) as exc:
        raise ExpressionError(text, f"not a valid expression ({exc})") from exc
    except (RecursionError, MemoryError, OverflowError):
        raise ExpressionError(text, "expression too large or nested too deeply") from None
    if not isinstance(expr, sympy.Expr):
        raise ExpressionError(text, f"not a scalar expression (got {type(expr).__name__})")
    if expr.has(sympy.zoo, sympy.nan, sympy.oo, -sympy.oo):
        raise ExpressionError(text, "evaluates to infinity or an undefined value")
    if expr.has(sympy.I):
        raise ExpressionError(text, "not a real expression: it holds the imaginary unit (the "
                                    "square root or logarithm of a negative number?)")
    return expr


def parse_expression(text: str, names: Mapping[str, sympy.Basic]) -> sympy.Expr:
    r"""Parse ``text`` in a document namespace ``names`` (name → SymPy object).

    Only ``names``, :data:`STANDARD_FUNCTIONS` and :data:`CONSTANTS` may appear; an undeclared
    name raises :class:`UndeclaredNameError`, a function call of a non-function name or a bad
    token :class:`ExpressionError`.
    """
    for name, called in scan_names(text):
        if name in STANDARD_FUNCTIONS:
            if not called:
                raise ExpressionError(text, f"{name!r} is a function; write {name}(...)")
        elif name in names or name in CONSTANTS:
            if called:
                raise ExpressionError(text, f"{name!r} is not a function")
        else:
            raise UndeclaredNameError(text, name)
    return _evaluate(text, {**STANDARD_FUNCTIONS, **CONSTANTS, **names})


def parse_model_expression(text: str, parameters: Collection[str] | None = None,
                           links: Collection[str] | None = None) -> sympy.Expr:
    r"""Parse a value expression in the model namespace.

    Khalil parameters are written ``XX(body)`` (one link name as argument), the model's lengths
    ``origin_x(joint)``, ``radius(link)`` ... (:data:`GEOMETRY_NAMES`); every other name is
    a model parameter, a real symbol. With ``parameters``/``links`` given, names outside them
    raise :class:`UndeclaredNameError` (kind ``"model parameter"``/``"link"``; the joint of
    ``origin_x(joint)`` is checked by the comparison, which knows the model). Held to
    :data:`MAX_EXPANDED_TERMS` like a document's expressions: a value is substituted and
    solved for.
    """
    scanned = scan_names(text)
    local: dict[str, object] = {**STANDARD_FUNCTIONS, **CONSTANTS}
    previous_khalil: str | None = None
    for name, called in scanned:
        if previous_khalil:          # the argument of M(...), XX(...): a link name
            function, previous_khalil = previous_khalil, None
            kind = GEOMETRY_NAMES.get(function, "link")
            if called:
                raise ExpressionError(text, f"the argument of {function}(...) must be a {kind} "
                                            f"name, not a call of {name!r}")
            if links is not None and kind == "link" and name not in links:
                raise UndeclaredNameError(text, name, "link")
            local[name] = sympy.Symbol(name)
            continue
        if name in STANDARD_FUNCTIONS:
            if not called:
                raise ExpressionError(text, f"{name!r} is a function; write {name}(...)")
        elif name in LINK_FUNCTIONS and called:
            local[name] = LINK_FUNCTIONS[name]
            previous_khalil = name
        elif name in CONSTANTS:
            continue
        else:
            if called:
                raise ExpressionError(text, f"{name!r} is not a function; link parameters are "
                                            f"{', '.join(LINK_FUNCTIONS)}")
            if parameters is not None and name not in parameters:
                raise UndeclaredNameError(text, name, "model parameter")
            local[name] = real_symbol(name)
    expr = _evaluate(text, local)
    for call in expr.atoms(sympy.core.function.AppliedUndef):
        if len(call.args) != 1 or not isinstance(call.args[0], sympy.Symbol):
            raise ExpressionError(text, f"{call} must have exactly one link or joint name as "
                                        "argument")
    check_expanded(text, expr)
    return expr


def parse_units(text: str) -> sympy.Expr:
    r"""Parse a units expression such as ``kg*m**2`` or ``N*m/A`` (``1`` = dimensionless) over
    :data:`UNIT_NAMES`; raises :class:`UndeclaredNameError` (kind ``"unit"``) otherwise."""
    for name, called in scan_names(text):
        if name not in UNITS or called:
            raise UndeclaredNameError(text, name, "unit")
    return _evaluate(text, UNITS)


__all__ = ["CONSTANTS", "GEOMETRY_NAMES", "KHALIL_FUNCTIONS", "KHALIL_NAMES", "LINK_FUNCTIONS",
           "MAX_CONSTANT", "MAX_EXPANDED_TERMS", "MAX_EXPONENT", "MAX_NESTING", "MAX_TOKENS",
           "PHYSICAL_NAMES", "RESERVED_NAMES", "STANDARD_FUNCTIONS", "UNIT_NAMES", "UNITS",
           "ExpressionError", "Nested", "UndeclaredNameError", "check_expanded",
           "check_limits", "expanded_terms", "parse_expression", "parse_model_expression",
           "parse_units", "physical_in_standard", "real_symbol", "scan_names",
           "split_nested"]
