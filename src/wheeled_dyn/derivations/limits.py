r"""Limits on the size of an expression of a derivation file, checked on the text before SymPy
(or NumPy) sees it, so that no expression can make the parser recurse without end, allocate a
number of billions of digits, or hang the comparison: at most :data:`MAX_TOKENS` tokens,
:data:`MAX_NESTING` levels of parentheses, every exponent a constant number of magnitude at most
:data:`MAX_EXPONENT`, every constant part (``9**9``, ``1e400``, ``exp(1e99)``) of magnitude at
most :data:`MAX_CONSTANT` and, unless zero, at least its inverse, every number a function is
applied to at most :data:`MAX_FUNCTION_ARGUMENT` (:func:`check_limits`); once parsed, the same
for the numbers SymPy made, and at most :data:`MAX_EXPANDED_TERMS` terms multiplied out
(:func:`check_expanded`). The largest expression of the shipped files has
about 300 tokens, 4 levels and exponents up to 4.
"""

from __future__ import annotations

import ast
import decimal
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
#: Largest magnitude of a number given to a function (``sin(1e99)``): NumPy computes it on
#: floats, and beyond 2**53 a float does not hold it exactly (beyond 2**63, not at all).
MAX_FUNCTION_ARGUMENT = 1e15
#: Most terms an expression may have once multiplied out (:func:`expanded_terms`): the
#: comparison expands every element, and ``(a + b + c + d + e)**16`` has 4845 terms. Shipped
#: elements have at most 8; a three-coordinate robot's row replaced by a combination of its
#: equations, with a full body inertia, 186 (refused at 100). Four elements of 245 terms
#: each, all differing, are compared in 2.3 s.
MAX_EXPANDED_TERMS = 300
#: Most terms of one of a document's equations or matrix elements once multiplied out: an
#: equation solved for the accelerations as generated simulation code prints it (SymPy's solve
#: of a two-link arm with general centres of mass: 325 terms) is compared in seconds; three
#: equations of 2574 pathological terms each took about a minute.
MAX_DOCUMENT_TERMS = 3000
#: Most nodes of an expression written out as a tree, definitions substituted (19 levels of
#: ``k = sin(j + q2) + cos(j - q1)``, each two terms, is a tree of 3.4 million nodes: 553 s).
MAX_TREE_NODES = 100_000
#: Most terms of all of a document's expressions together (its cost is about their sum).
MAX_FILE_TERMS = 6000
#: Most levels of ``[definitions]`` used in one another (each level is a level of every
#: expression written with the outermost: 400 of them overflowed Python's stack, and 40 of
#: ``k = j*(j + 1)`` took minutes).
MAX_DEFINITION_DEPTH = 32
#: Most symbols a derivation declares (each one's value is parsed and checked against the
#: model: about 9 ms; a file of 20 000 unused symbols took three minutes). Shipped files
#: declare at most about 30.
MAX_SYMBOLS = 1000
#: The arithmetic of constant parts other than powers (a division by zero is left to SymPy).
_ARITHMETIC: dict[type[ast.operator], Callable[[float, float], float]] = {
    ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul,
    ast.Div: operator.truediv}
#: The standard functions computed on a constant argument, in floating point, so that a
#: value beyond :data:`MAX_CONSTANT` (``exp(1e99)``, ``cosh(1e50)``) is refused before SymPy
#: keeps it as an exact number NumPy cannot compute with.
_FUNCTIONS: dict[str, Callable[..., float]] = {
    "sin": math.sin, "cos": math.cos, "tan": math.tan, "cot": lambda x: 1 / math.tan(x),
    "sec": lambda x: 1 / math.cos(x), "csc": lambda x: 1 / math.sin(x), "asin": math.asin,
    "acos": math.acos, "atan": math.atan, "atan2": math.atan2, "sinh": math.sinh,
    "cosh": math.cosh, "tanh": math.tanh, "sqrt": math.sqrt, "exp": math.exp,
    "log": math.log, "Abs": abs, "sign": lambda x: math.copysign(1.0, x) if x else 0.0}


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
    for tok in tokens:
        if tok.type == tokenize.NUMBER:
            _check_literal(text, tok.string)
    try:
        tree = ast.parse(src.replace("^", "**"), mode="eval")
    except (SyntaxError, ValueError):
        return                                  # SymPy's parser reports it
    except (RecursionError, MemoryError):
        raise ExpressionError(text, "expression nested too deeply") from None
    _check_constants(text, tree.body)


def _check_literal(text: str, number: str) -> None:
    r"""A number as written: nonzero and below ``1/MAX_CONSTANT`` in magnitude (``1e-5000``,
    which a float reads as 0 but SymPy as a fraction of thousands of digits) is refused."""
    try:
        value = decimal.Decimal(number.replace("_", ""))
    except decimal.InvalidOperation:
        return                                  # 0x10, 0o7: the tokenizer's, no exponent
    if value and abs(value) < decimal.Decimal(1) / decimal.Decimal(MAX_CONSTANT):
        raise ExpressionError(text, f"number {number} smaller than {1 / MAX_CONSTANT:g} in "
                                    "magnitude (write 0, or scale the quantity)")
    if abs(value) > decimal.Decimal(MAX_CONSTANT):      # (Python reads no int of 4300 digits)
        raise ExpressionError(text, f"number larger than {MAX_CONSTANT:g} "
                                    f"({short_text(number, 40)})")


def _check_constants(text: str, root: ast.AST) -> None:
    r"""Walk the syntax tree (without recursion: a sum of 2000 terms is 2000 levels deep),
    evaluating its constant parts in floating point with the bounds checked before each
    power; every exponent must be constant."""
    values: dict[int, float | None] = {}      # id(node) -> value, None if not constant
    stack: list[tuple[ast.AST, bool]] = [(root, False)]
    while stack:
        node, done = stack.pop()
        if not done:
            stack.append((node, True))
            stack.extend((c, False) for c in ast.iter_child_nodes(node))
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
    if isinstance(node, ast.Call):
        return _call_value(text, node, values)
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


def _call_value(text: str, node: ast.Call, values: dict[int, float | None]) -> float | None:
    r"""The value of a standard function of constant arguments (``exp(1e99)``), None if an
    argument is not constant or outside the function's domain (SymPy reports that); a
    constant argument beyond :data:`MAX_FUNCTION_ARGUMENT` is refused."""
    name = node.func.id if isinstance(node.func, ast.Name) else ""
    args = [values.get(id(a)) for a in node.args]
    for a in args:
        if a is not None and abs(a) > MAX_FUNCTION_ARGUMENT:
            raise ExpressionError(text, f"{name}({a:.6g}): a function's argument is at most "
                                        f"{MAX_FUNCTION_ARGUMENT:g} in magnitude")
    function = _FUNCTIONS.get(name)
    if function is None or node.keywords or not args or any(a is None for a in args):
        return None
    try:
        value = function(*args)
    except OverflowError:
        raise ExpressionError(text, f"{name}(...) is a constant larger than "
                                    f"{MAX_CONSTANT:g}") from None
    except (ValueError, ZeroDivisionError, TypeError):
        return None
    return _bounded(text, value, "constant")


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
        value = math.pow(a, b)
    except (OverflowError, ValueError, ZeroDivisionError):
        if a == 0 or a < 0:
            return None                     # 0**-1, (-1)**0.5: SymPy reports these
        raise ExpressionError(text, f"constant larger than {MAX_CONSTANT:g}") from None
    if value == 0 and a != 0:                   # (1e100)**(-64): a fraction of 6400 digits
        raise ExpressionError(text, f"constant smaller than {1 / MAX_CONSTANT:g} in magnitude")
    return _bounded(text, value, "constant")


def _bounded(text: str, value: float, what: str) -> float:
    if not math.isfinite(value) or abs(value) > MAX_CONSTANT:
        raise ExpressionError(text, f"{what} larger than {MAX_CONSTANT:g}")
    if value and abs(value) < 1 / MAX_CONSTANT:
        raise ExpressionError(text, f"{what} smaller than {1 / MAX_CONSTANT:g} in magnitude")
    return value


def expanded_terms(expr: sympy.Basic, parts: list[sympy.Basic] | None = None) -> int:
    r"""How many terms ``sympy.expand(expr)`` has at most, counted without expanding: a sum
    adds its terms' counts, a product multiplies them, a power :math:`s^n` of a sum of
    :math:`t` terms (integer :math:`n > 0`) has :math:`\binom{n+t-1}{t-1}`; any other
    expression (a function, a quotient's denominator, a fractional power) counts 1. Then the
    largest of that and of what ``expand`` multiplies out inside: every denominator (a power
    :math:`s^{-n}`: :math:`s^n` expanded, ``1/(1 + (a + ... + h)**64)`` took all the memory)
    and every function's argument (``expand`` goes into ``sin((a + b)**40)``). ``parts``:
    the distinct subexpressions of ``expr`` (:func:`_parts`), where already found."""
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
        largest = count(expr)
        for part in _parts(expr) if parts is None else parts:
            if isinstance(part, sympy.Pow) and part.exp.is_Integer and part.exp < 0:
                largest = max(largest, count(sympy.Pow(part.base, -part.exp, evaluate=False)))
            elif isinstance(part, sympy.Function):
                largest = max(largest, *(count(a) for a in part.args))
        return largest
    except RecursionError:
        return 10 ** 12


def _parts(expr: sympy.Basic) -> list[sympy.Basic]:
    r"""Every distinct subexpression of ``expr``, each once (definitions substituted into one
    another share theirs: ``k1 = k0*(k0 + 1)``, ``k2 = k1*(k1 + 1)`` ... is a tree of
    :math:`2^n` nodes and :math:`n` distinct ones; SymPy's ``atoms`` visits the tree)."""
    seen: set[sympy.Basic] = set()
    stack = [expr]
    while stack:
        e = stack.pop()
        if e not in seen:
            seen.add(e)
            stack.extend(a for a in e.args if isinstance(a, sympy.Basic))
    return list(seen)


def _check_numbers(text: str, parts: list[sympy.Basic]) -> None:
    r"""The numbers of ``expr`` as SymPy simplified it: none with a numerator or denominator
    beyond :data:`MAX_CONSTANT` (``(x*1e100)**(-64)`` holds a fraction of 6400 digits, which
    no printer writes), no function of a number beyond :data:`MAX_FUNCTION_ARGUMENT`
    (``parts``: its distinct subexpressions, :func:`_parts`)."""
    bits = int(MAX_CONSTANT).bit_length()
    for part in parts:
        if isinstance(part, sympy.Rational) and \
                max(abs(int(part.p)), int(part.q)).bit_length() > bits:
            raise ExpressionError(text, f"a number larger than {MAX_CONSTANT:g} or smaller than "
                                        f"{1 / MAX_CONSTANT:g} in magnitude once simplified")
        if isinstance(part, sympy.Function) and any(
                a.is_Number and abs(a) > MAX_FUNCTION_ARGUMENT for a in part.args):
            raise ExpressionError(text, f"{part.func}(...): a function's argument is at "
                                        f"most {MAX_FUNCTION_ARGUMENT:g} in magnitude")


def tree_size(expr: sympy.Basic) -> int:
    r"""The number of nodes of ``expr`` as a tree (a subexpression used twice counted twice:
    what SymPy's printers and compilers walk), counted on its distinct subexpressions."""
    memo: dict[sympy.Basic, int] = {}
    stack: list[tuple[sympy.Basic, bool]] = [(expr, False)]
    while stack:
        e, done = stack.pop()
        if e in memo:
            continue
        kids = [a for a in e.args if isinstance(a, sympy.Basic)]
        if done:
            memo[e] = min(1 + sum(memo[a] for a in kids), 10 ** 12)
        else:
            stack.append((e, True))
            stack.extend((a, False) for a in kids if a not in memo)
    return memo[expr]


def check_expanded(text: str, expr: sympy.Basic, limit: int = MAX_EXPANDED_TERMS) -> int:
    r"""Raise :class:`ExpressionError` if ``expr`` (parsed from ``text``, with any definitions
    substituted) has more than ``limit`` terms once multiplied out (counted first: on the
    distinct subexpressions), an integer exponent beyond :data:`MAX_EXPONENT` (powers of
    definitions multiply), too many nodes or a number out of bounds; else return the
    count."""
    parts = _parts(expr)
    n = expanded_terms(expr, parts)
    if n > limit:
        size = f"{n}" if n < 10 ** 12 else "more than 10**12"
        raise ExpressionError(text, f"expression too large: {size} terms once multiplied out, "
                                    f"at most {limit}")
    power = next((p for p in parts if isinstance(p, sympy.Pow) and p.exp.is_Integer
                  and abs(p.exp) > MAX_EXPONENT), None)
    if power is not None:      # (c**64)**64 of definitions: SymPy makes it c**4096
        raise ExpressionError(text, f"exponent {power.exp} out of range (at most "
                                    f"{MAX_EXPONENT} in magnitude, definitions substituted)")
    nodes = tree_size(expr)
    if nodes > MAX_TREE_NODES:
        raise ExpressionError(text, f"expression too large: {nodes} nodes written out (its "
                                    f"definitions substituted), at most {MAX_TREE_NODES}")
    _check_numbers(text, parts)
    return n



__all__ = ["MAX_CONSTANT", "MAX_DEFINITION_DEPTH", "MAX_DOCUMENT_TERMS", "MAX_EXPANDED_TERMS", "MAX_FILE_TERMS", "MAX_TREE_NODES", "MAX_EXPONENT", "MAX_FUNCTION_ARGUMENT", "MAX_NESTING", "MAX_TOKENS",
           "check_expanded", "check_limits", "expanded_terms", "tree_size"]
