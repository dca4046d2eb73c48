r"""Limits on the size of an expression of a derivation file, checked on the text before SymPy
(or NumPy) sees it, so that no expression can make the parser recurse without end, allocate a
number of billions of digits, or hang the comparison: at most :data:`MAX_TOKENS` tokens,
:data:`MAX_NESTING` levels of parentheses, every exponent a constant number of magnitude at most
:data:`MAX_EXPONENT`, every constant part (``9**9``, ``1e400``) of magnitude at most
:data:`MAX_CONSTANT` (:func:`check_limits`); once parsed, at most :data:`MAX_EXPANDED_TERMS`
terms multiplied out (:func:`check_expanded`). The largest expression of the shipped files has
about 300 tokens, 4 levels and exponents up to 4.
"""

from __future__ import annotations

import ast
import math
import operator
import tokenize
from collections.abc import Callable

import sympy

from .errors import ExpressionError, short_text

#: Most tokens (names, numbers, operators) in one expression (Python's compiler, which SymPy's
#: parser uses, recurses once per binary operator and fails near 3000 of them).
MAX_TOKENS = 2000
#: Most levels of parentheses in one expression.
MAX_NESTING = 32
#: Largest magnitude of an exponent: ``(1 + sin(phi))**2000`` overflows a float and makes
#: SymPy expand for minutes; ``9**9**9**9`` would be a number of billions of digits.
MAX_EXPONENT = 64
#: Largest magnitude of a number written in an expression, or of a constant part of one.
MAX_CONSTANT = 1e100
#: Most terms an expression may have once multiplied out (:func:`expanded_terms`): the
#: comparison expands every element (its time grows faster than the number of terms: 210 terms
#: take 9 s), and ``(a + b + c + d + e)**16`` has 4845 terms. Shipped elements have at most 8.
MAX_EXPANDED_TERMS = 100
#: The arithmetic of constant parts other than powers (a division by zero is left to SymPy).
_ARITHMETIC: dict[type[ast.operator], Callable[[float, float], float]] = {
    ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul,
    ast.Div: operator.truediv}


def check_limits(text: str, src: str, tokens: list[tokenize.TokenInfo]) -> None:
    r"""Raise :class:`ExpressionError` if the expression exceeds :data:`MAX_TOKENS`,
    :data:`MAX_NESTING`, :data:`MAX_EXPONENT` or :data:`MAX_CONSTANT` (``tokens`` are those of
    the normalised text ``src``, already checked to be allowed ones)."""
    if len(tokens) > MAX_TOKENS:
        raise ExpressionError(text, f"expression too long: {len(tokens)} tokens, at most "
                                    f"{MAX_TOKENS} (split it with [definitions])")
    depth = 0
    for tok in tokens:
        depth += tok.string == "("
        depth -= tok.string == ")"
        if depth > MAX_NESTING:
            raise ExpressionError(text, f"parentheses nested deeper than {MAX_NESTING} levels")
    try:
        tree = ast.parse(src.replace("^", "**"), mode="eval")
    except (SyntaxError, ValueError):
        return                                  # SymPy's parser reports it
    except (RecursionError, MemoryError):
        raise ExpressionError(text, "expression nested too deeply") from None
    _check_constants(text, tree.body)


def _check_constants(text: str, root: ast.AST) -> None:
    r"""Walk the syntax tree (without recursion: a sum of 2000 terms is 2000 levels deep),
    evaluating its constant parts in floating point with the bounds checked before each
    power; every exponent must be constant."""
    values: dict[int, float | None] = {}      # id(node) -> value, None if not constant
    stack: list[tuple[ast.AST, bool]] = [(root, False)]
    while stack:
        node, done = stack.pop()
        children = list(ast.iter_child_nodes(node))
        if not done:
            stack.append((node, True))
            stack.extend((c, False) for c in children)
            continue
        values[id(node)] = _constant_value(text, node, values)


def _constant_value(text: str, node: ast.AST, values: dict[int, float | None]) -> float | None:
    r"""The value of ``node`` if it is constant (its children's values in ``values``), else
    None; raises :class:`ExpressionError` for a number or constant out of bounds and for an
    exponent that is not a constant number."""
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)):
        if isinstance(node.value, int) and abs(node.value) > 10 ** 100:
            raise ExpressionError(text, f"number larger than {MAX_CONSTANT:g}")
        return _bounded(text, float(node.value), "number")
    if isinstance(node, ast.Name):
        return math.pi if node.id == "pi" else None
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.UAdd, ast.USub)):
        v = values.get(id(node.operand))
        return None if v is None else (-v if isinstance(node.op, ast.USub) else v)
    if not isinstance(node, ast.BinOp):
        return None
    a, b = values.get(id(node.left)), values.get(id(node.right))
    if isinstance(node.op, (ast.Pow, ast.BitXor)):
        return _power_value(text, node, a, b)
    arithmetic = _ARITHMETIC.get(type(node.op))
    if a is None or b is None or arithmetic is None:
        return None
    try:
        return _bounded(text, arithmetic(a, b), "constant")
    except ZeroDivisionError:
        return None                             # SymPy reports a division by zero


def _power_value(text: str, node: ast.BinOp, a: float | None, b: float | None) -> float | None:
    r"""The value of the power ``a ** b`` (``node``) if its base is constant; its exponent
    ``b`` must be a constant of magnitude at most :data:`MAX_EXPONENT`."""
    if b is None:
        raise ExpressionError(text, f"the exponent {short_text(ast.unparse(node.right), 40)!r} "
                                    "is not a constant number")
    if abs(b) > MAX_EXPONENT:
        raise ExpressionError(text, f"exponent {b:.6g} out of range: at most "
                                    f"{MAX_EXPONENT} in magnitude")
    if a is None:
        return None
    try:
        return _bounded(text, math.pow(a, b), "constant")
    except (OverflowError, ValueError, ZeroDivisionError):
        if a == 0 or a < 0:
            return None                     # 0**-1, (-1)**0.5: SymPy reports these
        raise ExpressionError(text, f"constant larger than {MAX_CONSTANT:g}") from None


def _bounded(text: str, value: float, what: str) -> float:
    if not math.isfinite(value) or abs(value) > MAX_CONSTANT:
        raise ExpressionError(text, f"{what} larger than {MAX_CONSTANT:g}")
    return value


def expanded_terms(expr: sympy.Basic) -> int:
    r"""How many terms ``sympy.expand(expr)`` has at most, counted without expanding: a sum
    adds its terms' counts, a product multiplies them, a power :math:`s^n` of a sum of
    :math:`t` terms (integer :math:`n > 0`) has :math:`\binom{n+t-1}{t-1}`; any other
    expression (a function, a quotient's denominator, a fractional power) counts 1."""
    memo: dict[sympy.Basic, int] = {}

    def count(e: sympy.Basic) -> int:
        if e in memo:
            return memo[e]
        if isinstance(e, sympy.Add):
            value = sum(count(a) for a in e.args)
        elif isinstance(e, sympy.Mul):
            value = math.prod(count(a) for a in e.args)
        elif isinstance(e, sympy.Pow) and e.exp.is_Integer and e.exp > 0:
            t = count(e.base)
            value = math.comb(int(e.exp) + t - 1, t - 1) if t > 1 else 1
        else:
            value = 1
        memo[e] = value = min(value, 10 ** 12)
        return value

    try:
        return count(expr)
    except RecursionError:
        return 10 ** 12


def check_expanded(text: str, expr: sympy.Basic) -> None:
    r"""Raise :class:`ExpressionError` if ``expr`` (parsed from ``text``, with any definitions
    substituted) has more than :data:`MAX_EXPANDED_TERMS` terms once multiplied out."""
    n = expanded_terms(expr)
    if n > MAX_EXPANDED_TERMS:
        size = f"{n}" if n < 10 ** 12 else "more than 10**12"
        raise ExpressionError(text, f"expression too large: {size} terms once multiplied out, "
                                    f"at most {MAX_EXPANDED_TERMS}")



__all__ = ["MAX_CONSTANT", "MAX_EXPANDED_TERMS", "MAX_EXPONENT", "MAX_NESTING", "MAX_TOKENS",
           "check_expanded", "check_limits", "expanded_terms"]
