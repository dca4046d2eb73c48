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
silently turned into a fresh parameter.

Limits, checked on the text before SymPy (or NumPy) sees it, so that no expression can make the
parser recurse without end, allocate a number of billions of digits, or hang the comparison:
at most :data:`MAX_TOKENS` tokens, :data:`MAX_NESTING` levels of parentheses, every exponent a
constant number of magnitude at most :data:`MAX_EXPONENT`, every constant part (``9**9``,
``1e400``) of magnitude at most :data:`MAX_CONSTANT`. The largest expression of the shipped
files has about 300 tokens, 4 levels and exponents up to 4.

Two namespaces exist. The *document* namespace holds what the document writes (its symbols,
coordinates, velocities, inputs). The *model* namespace (values of ``[symbols]``) holds the
model's physical parameters as real symbols and Khalil's standard inertial parameters as
undefined functions of a link name,

.. math::

    \mathrm{XX}(\text{body}),\ \mathrm{MY}(\text{body}),\ \mathrm{ZZ}(\text{wheel\_left}),\ \dots

written with :data:`KHALIL_FUNCTIONS` (real undefined functions) applied to
``sympy.Symbol(link)``, and the physical ones about the centre of mass, ``CX(link)``,
``IXX(link)`` ... (:data:`PHYSICAL_NAMES`; :func:`physical_in_standard` rewrites them in
Khalil's). The model namespace
is open (any identifier is a parameter) unless the caller passes the valid parameter and link
names: the parser does not import the models.

Every symbol made here is ``real=True``; fetch them from the :class:`Derivation` rather than
making new ones (``Symbol("phi")`` without assumptions is a different symbol).
"""

from __future__ import annotations

import ast
import io
import keyword
import math
import tokenize
from collections.abc import Collection, Mapping
from typing import Union

import sympy
from sympy.parsing.sympy_parser import auto_number, convert_xor, parse_expr, rationalize

#: Functions every expression may use, by the name it is written with.
STANDARD_FUNCTIONS: Mapping[str, object] = {
    "sin": sympy.sin, "cos": sympy.cos, "tan": sympy.tan, "cot": sympy.cot,
    "sec": sympy.sec, "csc": sympy.csc, "asin": sympy.asin, "acos": sympy.acos,
    "atan": sympy.atan, "atan2": sympy.atan2, "sinh": sympy.sinh, "cosh": sympy.cosh,
    "tanh": sympy.tanh, "sqrt": sympy.sqrt, "exp": sympy.exp, "log": sympy.log,
    "Abs": sympy.Abs, "sign": sympy.sign,
}
#: Constants every expression may use.
CONSTANTS: Mapping[str, sympy.Basic] = {"pi": sympy.pi}
#: Names a file may not declare (they are functions or constants).
RESERVED_NAMES: frozenset[str] = frozenset(STANDARD_FUNCTIONS) | frozenset(CONSTANTS)

#: Khalil's standard inertial parameters of a link, in the link frame, as written in value
#: expressions: ``M(link)`` mass, ``MX MY MZ`` first moments, ``XX XY XZ YY YZ ZZ`` inertia
#: tensor entries about the link frame origin.
KHALIL_NAMES: tuple[str, ...] = ("M", "MX", "MY", "MZ", "XX", "XY", "XZ", "YY", "YZ", "ZZ")
#: The model's lengths by name, as written in value expressions, with what names their argument
#: (a URDF joint or link): the origin of a joint in its parent link's frame, along x, y or z
#: (the URDF's ``<origin xyz>``), a link's radius (its rolling radius if it rolls, else its
#: first sphere or cylinder) and length (its first cylinder), a rolling wheel's tyre radius, a
#: spheroid's polar radius, and the radius of the fixed sphere or the vertex radius of the bowl
#: a ball rolls on (named by the ball's link). See ``docs/derivation-format.md``.
GEOMETRY_NAMES: Mapping[str, str] = {
    "origin_x": "joint", "origin_y": "joint", "origin_z": "joint", "radius": "link",
    "length": "link", "tyre_radius": "link", "polar_radius": "link", "surface_radius": "link",
    "vertex_radius": "link"}
KHALIL_FUNCTIONS: Mapping[str, sympy.FunctionClass] = {n: sympy.Function(n, real=True)
                                                       for n in KHALIL_NAMES}
#: The physical parameters of a link (:mod:`wheeled_dyn.models.link_parameters`): ``CX CY CZ``
#: the centre of mass in the link frame, ``IXX IXY IXZ IYY IYZ IZZ`` the inertia tensor entries
#: about the centre of mass in the link's axes (``M`` is shared with Khalil's).
PHYSICAL_NAMES: tuple[str, ...] = ("CX", "CY", "CZ", "IXX", "IXY", "IXZ", "IYY", "IYZ", "IZZ")
#: Every function a value expression may apply to a link (or, for a length, a joint) name.
LINK_FUNCTIONS: Mapping[str, sympy.FunctionClass] = {
    **KHALIL_FUNCTIONS, **{n: sympy.Function(n, real=True)
                           for n in (*PHYSICAL_NAMES, *GEOMETRY_NAMES)}}


def physical_in_standard(expr: sympy.Expr) -> sympy.Expr:
    r"""``expr`` with every physical link parameter written in Khalil's standard ones of the
    same link (parallel-axis theorem, :math:`J_G = J_O - M(|c|^2 I - c c^T)`, :math:`c = MS/M`):
    :math:`CX = MX/M`, :math:`IXX = XX - (MY^2 + MZ^2)/M`, :math:`IXY = XY + MX\,MY/M` ..."""
    f = LINK_FUNCTIONS
    out = {}
    for call in expr.atoms(sympy.core.function.AppliedUndef):
        name, link = call.func.__name__, call.args[0]
        if name not in PHYSICAL_NAMES:
            continue
        m = f["M"](link)
        ms = {"X": f["MX"](link), "Y": f["MY"](link), "Z": f["MZ"](link)}
        if name[0] == "C":
            out[call] = ms[name[1]] / m
        elif name[1] == name[2]:
            others = [ms[a] ** 2 for a in "XYZ" if a != name[1]]
            out[call] = f[name[1:]](link) - (others[0] + others[1]) / m
        else:
            out[call] = f[name[1:]](link) + ms[name[1]] * ms[name[2]] / m
    return expr.xreplace(out) if out else expr

#: Unit names accepted in ``units`` (SI base and derived units, radians; ``1`` = dimensionless).
UNIT_NAMES: tuple[str, ...] = ("kg", "m", "s", "rad", "N", "J", "W", "A", "V", "K", "mol")
_UNITS: Mapping[str, sympy.Symbol] = {u: sympy.Symbol(u, positive=True) for u in UNIT_NAMES}

_OPERATORS = frozenset({"+", "-", "*", "/", "**", "^", "(", ")", ","})
_TRANSFORMATIONS = (auto_number, rationalize, convert_xor)
_GLOBALS: dict[str, object] = {"Integer": sympy.Integer, "Float": sympy.Float,
                               "Rational": sympy.Rational}

Nested = Union[str, list["Nested"]]

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


class ExpressionError(ValueError):
    """An expression cannot be parsed; ``reason`` says why (internal: the loader adds the file,
    the line and the item)."""

    def __init__(self, text: str, reason: str) -> None:
        self.text = text
        self.reason = reason
        super().__init__(f"{reason} in {_short(text)!r}")

    def __reduce__(self):
        return type(self), (self.text, self.reason)


def _short(text: str, width: int = 120) -> str:
    text = str(text)
    return text if len(text) <= width else f"{text[:width - 20]} ... {text[-15:]}"


class UndeclaredNameError(ExpressionError):
    """An expression uses a name that is not declared; ``name`` and ``kind`` say which."""

    def __init__(self, text: str, name: str, kind: str = "symbol") -> None:
        self.name = name
        self.kind = kind
        super().__init__(text, f"undeclared {kind} {name!r}")

    def __reduce__(self):
        return type(self), (self.text, self.name, self.kind)


def real_symbol(name: str) -> sympy.Symbol:
    r"""The symbol of a document or model name: ``sympy.Symbol(name, real=True)``."""
    return sympy.Symbol(name, real=True)


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
                  if t.type not in (tokenize.NEWLINE, tokenize.NL, tokenize.ENDMARKER)]
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
        if b is None:
            raise ExpressionError(text, f"the exponent {_short(ast.unparse(node.right), 40)!r} "
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
    if a is None or b is None:
        return None
    try:
        if isinstance(node.op, ast.Add):
            return _bounded(text, a + b, "constant")
        if isinstance(node.op, ast.Sub):
            return _bounded(text, a - b, "constant")
        if isinstance(node.op, ast.Mult):
            return _bounded(text, a * b, "constant")
        if isinstance(node.op, ast.Div):
            return _bounded(text, a / b, "constant")
    except ZeroDivisionError:
        return None                             # SymPy reports a division by zero
    return None


def _bounded(text: str, value: float, what: str) -> float:
    if not math.isfinite(value) or abs(value) > MAX_CONSTANT:
        raise ExpressionError(text, f"{what} larger than {MAX_CONSTANT:g}")
    return value


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
    return expr


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
    ``origin_x(joint)`` is checked by the comparison, which knows the model).
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
    return expr


def parse_units(text: str) -> sympy.Expr:
    r"""Parse a units expression such as ``kg*m**2`` or ``N*m/A`` (``1`` = dimensionless) over
    :data:`UNIT_NAMES`; raises :class:`UndeclaredNameError` (kind ``"unit"``) otherwise."""
    for name, called in scan_names(text):
        if name not in _UNITS or called:
            raise UndeclaredNameError(text, name, "unit")
    return _evaluate(text, _UNITS)


def split_nested(text: str) -> Nested:
    r"""Split a matrix written as text, ``[[a, b], [c, d]]``, into nested lists of element
    strings. Commas inside parentheses (``atan2(y, x)``) do not split. A text without brackets
    is returned as one element."""
    s = str(text)
    pos, value = _item(s, _skip(s, 0))
    pos = _skip(s, pos)
    if pos != len(s):
        raise ExpressionError(text, f"unexpected {s[pos:pos + 10]!r} after the matrix")
    return value


def _skip(s: str, i: int) -> int:
    while i < len(s) and s[i].isspace():
        i += 1
    return i


def _item(s: str, i: int) -> tuple[int, Nested]:
    if i < len(s) and s[i] == "[":
        items: list[Nested] = []
        i = _skip(s, i + 1)
        if i < len(s) and s[i] == "]":
            raise ExpressionError(s, "empty list in a matrix")
        while True:
            i, value = _item(s, _skip(s, i))
            items.append(value)
            i = _skip(s, i)
            if i >= len(s):
                raise ExpressionError(s, "missing ']'")
            if s[i] == "]":
                return i + 1, items
            if s[i] != ",":
                raise ExpressionError(s, f"expected ',' or ']' at {s[i:i + 10]!r}")
            i += 1
    depth, start = 0, i
    while i < len(s):
        ch = s[i]
        if ch == "(":
            depth += 1
        elif ch == ")":
            depth -= 1
        elif ch == "[":
            raise ExpressionError(s, "unbalanced '(' in a matrix element" if depth > 0
                                  else "'[' inside a matrix element")
        elif depth == 0 and ch in ",]":
            break
        i += 1
    element = s[start:i].strip()
    if not element:
        raise ExpressionError(s, "empty matrix element")
    return i, element
