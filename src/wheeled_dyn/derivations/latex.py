r"""LaTeX input: expressions, equations and matrices copied from a document.

A value written ``{ latex = '''...''' }`` in a derivation file is read here and turned into the
SymPy-syntax text the rest of the loader parses (:mod:`.expressions`, with all its limits).
``pylatexenc`` tokenises the LaTeX; the file's symbol table (:class:`LatexNames`) resolves it:

- a run of letters, subscripts and Greek letters (``m_s d``, ``\mathbf{MZ_1}``, ``2M_wL^2``) is
  split into declared names; a name is printed as written (``m_s``, ``I_w3`` as ``I_{w3}``), as
  its letters with the trailing digits or the lower-case rest subscripted (``XX1`` as
  ``XX_1``, ``Mw`` as ``M_w``), or as its ``latex`` field in ``[symbols]``. Fonts
  (``\mathbf``, ``\mathbb`` ...) and spaces do not separate names. A run that splits in two
  ways is an error showing both readings (:class:`LatexError`); one that does not split an
  :class:`~.expressions.UndeclaredNameError`;
- ``\dot{p}``, ``\ddot{p}`` of a position are its velocity and acceleration (of another name
  ``n``: the declared ``dn``, ``ddn``); a subscript after the dot joins the dotted letters
  as in a name: ``\dot{x}_0`` is the velocity of ``x_0`` (``x0``);
- ``\sin\phi\cos\phi``: a function without parentheses takes one name (with a leading number:
  ``\sin 2\phi``); ``\sin^2\phi`` is ``sin(phi)**2``. A function spelled in plain letters
  (``sin^{2}\phi``, a print that lost its backslash) is one more reading of a run of letters:
  the function when the letters read as no declared names, ambiguous when they also do; a
  ``[latex] abbreviation`` spelling it (``'sin\phi'``) is read instead;
- abbreviations declared in ``[latex] abbreviations`` (``'s2\psi' = "sin(2*psi)"``) are
  pieces of a run like names;
- ``\frac``, ``\sqrt``, ``\left( \right)``, ``\cdot``, ``\times``, powers, implicit products;
  ``bmatrix``/``pmatrix`` cells (:func:`split_latex_matrix`), transposed by ``^T``;
  ``=`` in equations;
- equation numbers: ``\tag{10}`` is dropped anywhere; ``\quad (9)`` only at the end of an
  equation or a matrix (elsewhere it is spacing and a factor 9).
"""

from __future__ import annotations

import itertools
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from typing import Any, NamedTuple

import sympy
from pylatexenc import macrospec
from pylatexenc.latexwalker import (LatexCharsNode, LatexCommentNode, LatexEnvironmentNode,
                                    LatexGroupNode, LatexMacroNode, LatexMathNode,
                                    LatexSpecialsNode, LatexWalker, LatexWalkerError,
                                    get_default_latex_context_db)

from .expressions import ExpressionError, UndeclaredNameError, parse_expression

#: The key marking a value as LaTeX: ``A = { latex = '...' }``.
LATEX_KEY = "latex"
#: Keys of a file's ``[latex]`` table.
LATEX_KEYS: tuple[str, ...] = ("names", "abbreviations")
#: Longest LaTeX value read (the matrix A of seed 001's eq. (25) has about 900 characters).
MAX_LATEX_CHARS = 20_000
#: Readings of a run of letters collected before it is declared ambiguous.
MAX_READINGS = 2
#: Longest run or reading shown in an error message, in characters.
MAX_SHOWN = 80
#: LaTeX functions and the SymPy function each is.
FUNCTIONS: Mapping[str, str] = {
    "sin": "sin", "cos": "cos", "tan": "tan", "cot": "cot", "sec": "sec", "csc": "csc",
    "arcsin": "asin", "arccos": "acos", "arctan": "atan", "sinh": "sinh", "cosh": "cosh",
    "tanh": "tanh", "exp": "exp", "log": "log", "ln": "log"}
GREEK: frozenset[str] = frozenset(
    "alpha beta gamma delta epsilon zeta eta theta iota kappa lambda mu nu xi omicron rho sigma "
    "tau upsilon phi chi psi omega Gamma Delta Theta Lambda Xi Pi Sigma Upsilon Phi Psi Omega"
    .split())
#: Variant letters: read as the plain letter when only that one is declared.
VARIANTS: Mapping[str, str] = {"varphi": "phi", "vartheta": "theta", "varepsilon": "epsilon",
                               "varrho": "rho", "varsigma": "sigma"}
#: Fonts: a name in any of them is the name (``\mathbb{M}``, ``\mathbf{MZ_1}``).
FONTS: frozenset[str] = frozenset({"mathbf", "mathrm", "mathit", "mathsf", "mathtt", "mathbb",
                                   "mathcal", "mathfrak", "mathscr", "boldsymbol", "bm"})
IGNORED: frozenset[str] = frozenset({",", ";", ":", "!", " ", "quad", "qquad", "big", "Big",
                                     "bigl", "bigr", "Bigl", "Bigr", "displaystyle"})
OPERATORS: Mapping[str, str] = {"cdot": "*", "times": "*", "div": "/", "{": "(", "}": ")",
                                "lbrack": "(", "rbrack": ")"}
MATRICES: frozenset[str] = frozenset({"bmatrix", "pmatrix", "matrix", "Bmatrix"})
#: An equation number: ``\tag{10}`` (dropped anywhere) and, after the last term of an
#: equation or a matrix, ``\quad (9)`` (one of :data:`NUMBER_SPACES`, then the number).
TAG = "tag"
NUMBER_SPACES: frozenset[str] = frozenset({"quad", "qquad"})
EQUATION_NUMBER = re.compile(r"\s*\(\s*\d+(?:\.\d+)*[a-z]?\s*\)\s*")
#: A transposed matrix: ``\end{bmatrix}^T`` (``^{T}``, ``^\top``, ``^{\mathsf{T}}``, ...).
_T_MARK = r"(?:T|\\top|\\intercal|\\(?:mathsf|mathrm|mathit|mathbf)\s*\{\s*T\s*\})"
TRANSPOSE = re.compile(rf"\^\s*(?:{_T_MARK}|\{{\s*{_T_MARK}\s*\}})\s*")
_ARGUMENTS = {"frac": 2, "tfrac": 2, "dfrac": 2, "sqrt": 1, "dot": 1, "ddot": 1,
              **{font: 1 for font in FONTS}}
_CHAR_OPS = {"+": "+", "-": "-", "*": "*", "/": "/", "=": "=", "(": "(", ")": ")", "[": "(",
             "]": ")"}
_LONGEST_FUNCTION = max(map(len, FUNCTIONS))
_NUMBER = re.compile(r"\d+(?:\.\d*)?|\.\d+")
_SPLITS = (re.compile(r"^([A-Za-z]+?)(\d+)$"), re.compile(r"^([A-Z]+)([a-z0-9]+)$"))

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


@dataclass(frozen=True)
class LatexNames:
    r"""A file's names as LaTeX sees them. ``names``: every declared name; ``velocity`` and
    ``acceleration``: position → its velocity/acceleration name; ``printed``: name → its
    ``latex`` field; ``abbreviations``: LaTeX as printed → SymPy text."""

    names: tuple[str, ...]
    velocity: Mapping[str, str] = field(default_factory=dict)
    acceleration: Mapping[str, str] = field(default_factory=dict)
    printed: Mapping[str, str] = field(default_factory=dict)
    abbreviations: Mapping[str, str] = field(default_factory=dict)

    def __post_init__(self) -> None:
        forms: dict[tuple[str, str], set[str]] = {}
        for name in self.names:
            for key in _name_forms(name):
                forms.setdefault(key, set()).add(name)
        for name, text in self.printed.items():
            key = _printed_key(text)
            if key is None:
                raise LatexError(text, f"the printed form of {name} is not a name")
            forms.setdefault(key, set()).add(name)
        object.__setattr__(self, "_forms", forms)       # read by the abbreviations' \dot{}
        object.__setattr__(self, "_abbrev", {})
        object.__setattr__(self, "_longest", max([len(b) for b, _ in forms] + [1]))
        abbrev = {}
        for text, value in self.abbreviations.items():
            atoms = _Reader(self, text).atoms(_parse(text))
            if not atoms or any(a.sup or not (isinstance(a, _Letter) or getattr(a, "number", 0))
                                for a in atoms):
                raise LatexError(text, "an abbreviation is letters, digits and subscripts")
            abbrev[tuple(_atom_key(a) for a in atoms)] = f"({value})"
        object.__setattr__(self, "_abbrev", abbrev)
        # no piece is longer (in atoms) than the longest name (in letters) or abbreviation
        object.__setattr__(self, "_longest", max([len(b) for b, _ in forms]
                                                 + [len(k) for k in abbrev] + [1]))


def _name_forms(name: str) -> list[tuple[str, str]]:
    if "_" in name:
        base, sub = name.split("_", 1)
        return [(base, sub)] if base else []
    found = [(name, "")]
    found += [(m.group(1), m.group(2)) for m in (r.match(name) for r in _SPLITS) if m]
    return found


def is_printed_name(text: str) -> bool:
    r"""Whether ``text`` prints one name: letters and Greek letters, the last subscripted
    (``\mathbf{MZ_1}``, ``m_{s}``, ``\alpha_3``)."""
    return _printed_key(text) is not None


def _printed_key(text: str) -> tuple[str, str] | None:
    try:
        atoms = _Reader(LatexNames(()), text).atoms(_parse(text))
    except ExpressionError:
        return None
    if not atoms or any(not isinstance(a, _Letter) or a.sup or a.sub for a in atoms[:-1]):
        return None
    last = atoms[-1]
    return None if not isinstance(last, _Letter) or last.sup else (
        "".join(a.base for a in atoms), last.sub)


def _parse(source: str) -> list[Any]:
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


class _Letter(NamedTuple):
    base: str                   # a letter or a Greek letter's name
    sub: str = ""
    sup: str | None = None
    alt: str | None = None      # the plain letter of a variant (varphi -> phi)

    @property
    def key(self) -> tuple[str, str]:
        return (self.base, self.sub)


class _Value(NamedTuple):       # a factor already in SymPy syntax
    text: str
    sup: str | None = None
    number: bool = False


class _Func(NamedTuple):
    name: str
    sup: str | None = None


class _Op(NamedTuple):
    op: str
    sup: str | None = None


class _Rate(NamedTuple):        # \dot{x}, \ddot{x}: named once its subscript is known
    macro: str                  # "dot" or "ddot"
    arg: tuple[Any, ...]        # the atoms under the dot
    sub: str = ""               # a subscript after the dot: \dot{x}_0
    sup: str | None = None


def _wrap(text: str) -> str:
    return text if re.fullmatch(r"[\w.]+(\*\*[\w.]+)?", text) else f"({text})"


def _atom_key(atom: Any) -> tuple[str, str]:
    return atom.key if isinstance(atom, _Letter) else ("#", atom.text)


def _pow(text: str, sup: str | None) -> str:
    if sup is None:
        return text
    return f"{text}**{sup}" if sup.isalnum() else f"{text}**({sup})"


class _Reader:
    r"""Converts pylatexenc nodes of one value to SymPy text."""

    def __init__(self, names: LatexNames, source: str) -> None:
        self.names, self.source = names, source

    def fail(self, reason: str, readings: tuple[str, ...] = ()) -> LatexError:
        return LatexError(self.source, reason, readings)

    # -- nodes -> atoms ---------------------------------------------------------------
    def atoms(self, nodes: Iterable[Any]) -> list[Any]:
        out: list[Any] = []
        pending: str | None = None          # "_" or "^" waiting for its argument
        for node in nodes:
            if isinstance(node, LatexCharsNode):
                chars, i = node.chars, 0
                while i < len(chars):
                    c = chars[i]
                    number = _NUMBER.match(chars, i)
                    if c.isspace():
                        i += 1
                        continue
                    if pending:
                        self._attach(out, pending, c, c)
                        pending, i = None, i + 1
                    elif c in "_^":
                        pending, i = c, i + 1
                    elif number:
                        out.append(_Value(number.group(0), number=True))
                        i = number.end()
                    elif c.isalpha() and c.isascii():
                        out.append(_Letter(c))
                        i += 1
                    elif c in _CHAR_OPS:
                        out.append(_Op(_CHAR_OPS[c]))
                        i += 1
                    else:
                        raise self.fail(f"unexpected {c!r}")
            elif isinstance(node, LatexCommentNode) or node is None:
                continue
            elif pending:
                self._attach(out, pending, node,
                             self._key_text([node]) if pending == "_" else None)
                pending = None
            else:
                out.extend(self._node(node))
        if pending:
            raise self.fail(f"{pending!r} without an argument")
        return [_Value(self._derivative(a), a.sup) if isinstance(a, _Rate) else a for a in out]

    def _attach(self, out: list[Any], marker: str, arg: Any, key: str | None) -> None:
        last = out[-1] if out else None
        if marker == "_":
            if not isinstance(last, (_Letter, _Rate)) or last.sub or last.sup:
                raise self.fail(f"subscript _{key} after no letter")
            out[-1] = last._replace(sub=key)
            return
        if isinstance(last, (_Letter, _Value, _Func, _Rate)) or (isinstance(last, _Op)
                                                          and last.op == ")"):
            if last.sup is not None:
                raise self.fail("double superscript")
            if isinstance(arg, str):        # one character: ^2, ^n
                text = self.text([_Letter(arg) if arg.isalpha()
                                  else _Value(arg, number=arg.isdigit())])
            else:
                text = self.expression(arg.nodelist if isinstance(arg, LatexGroupNode)
                                       else [arg])
            out[-1] = last._replace(sup=text)
        else:
            raise self.fail("superscript ^ after no factor")

    def _key_text(self, nodes: Iterable[Any]) -> str:
        parts = []
        for node in nodes:
            if isinstance(node, LatexCharsNode):
                parts.append("".join(node.chars.split()))
            elif isinstance(node, LatexGroupNode):
                parts.append(self._key_text(node.nodelist))
            elif isinstance(node, LatexMacroNode) and node.macroname in FONTS:
                parts.append(self._key_text([a for a in (node.nodeargd.argnlist if node.nodeargd
                                                         else []) if a]))
            elif isinstance(node, LatexMacroNode) and node.macroname in GREEK | set(VARIANTS):
                parts.append(node.macroname)
            elif not (isinstance(node, LatexMacroNode) and node.macroname in IGNORED):
                raise self.fail("a subscript is letters, digits and Greek letters")
        key = "".join(parts)
        if not re.fullmatch(r"[A-Za-z0-9,]+", key):
            raise self.fail(f"subscript {key!r} is not a name")
        return key

    def _node(self, node: Any) -> list[Any]:
        if isinstance(node, LatexGroupNode):
            return [_Value(f"({self.expression(node.nodelist)})")]
        if isinstance(node, LatexMathNode):
            return self.atoms(node.nodelist)
        if isinstance(node, LatexEnvironmentNode):
            raise self.fail(f"\\begin{{{node.environmentname}}} where an expression is expected "
                            "(a matrix is a whole value: A = { latex = '...' })")
        if isinstance(node, LatexSpecialsNode):
            raise self.fail(f"{node.specials_chars!r} outside a matrix")
        name = node.macroname
        args = [a for a in (node.nodeargd.argnlist if node.nodeargd else []) if a is not None]
        if len(args) < _ARGUMENTS.get(name, 0):
            raise self.fail(f"\\{name} needs {_ARGUMENTS[name]} argument(s)")
        if name in GREEK or name in VARIANTS:
            return [_Letter(name, alt=VARIANTS.get(name))]
        if name == "pi":
            return [_Value("pi")]
        if name in FONTS:
            return self.atoms(args[-1].nodelist if isinstance(args[-1], LatexGroupNode)
                              else args[-1:])
        if name in FUNCTIONS:
            return [_Func(FUNCTIONS[name])]
        if name in ("frac", "tfrac", "dfrac"):
            num, den = (self.expression(a.nodelist if isinstance(a, LatexGroupNode) else [a])
                        for a in args)
            return [_Value(f"({_wrap(num)}/{_wrap(den)})")]
        if name == "sqrt":
            inner = self.expression(args[-1].nodelist if isinstance(args[-1], LatexGroupNode)
                                    else args[-1:])
            if len(args) == 2:
                root = _wrap(self.expression(args[0].nodelist))
                return [_Value(f"({_wrap(inner)}**(1/{root}))")]
            return [_Value(f"sqrt({inner})")]
        if name in ("dot", "ddot"):
            arg = args[0].nodelist if isinstance(args[0], LatexGroupNode) else [args[0]]
            return [_Rate(name, tuple(self.atoms(arg)))]
        if name == TAG:                     # an equation number
            return []
        if name in OPERATORS:
            return [_Op(OPERATORS[name])]
        if name in IGNORED or name in ("left", "right"):
            return []
        if name == "\\":
            raise self.fail("'\\\\' outside a matrix")
        raise self.fail(f"unknown LaTeX macro \\{name}")

    def _derivative(self, rate: _Rate) -> str:
        r"""The velocity (``\dot``) or acceleration (``\ddot``) name of ``rate``; a subscript
        after the dot joins the dotted letters (``\dot{x}_0`` is the rate of ``x_0``)."""
        atoms = list(rate.arg)
        letters = bool(atoms) and all(isinstance(a, _Letter) for a in atoms)
        if rate.sub:
            if not letters or atoms[-1].sub or atoms[-1].sup:
                raise self.fail(f"subscript _{rate.sub} after \\{rate.macro}{{...}} of no letter")
            atoms[-1] = atoms[-1]._replace(sub=rate.sub)
        readings = self._readings(atoms) if letters else []
        if len(readings) > 1:
            raise self._ambiguous(atoms, readings)
        table, prefix = ((self.names.velocity, "d") if rate.macro == "dot"
                         else (self.names.acceleration, "dd"))
        if readings and len(readings[0]) == 1:
            found = table.get(readings[0][0], prefix + readings[0][0])
            if found in self.names.names:
                return found
        what = _printed(list(rate.arg)) if letters else "?"
        sub = (f"_{{{rate.sub}}}" if len(rate.sub) > 1 else f"_{rate.sub}") if rate.sub else ""
        raise UndeclaredNameError(self.source, f"\\{rate.macro}{{{what}}}{sub}", "velocity"
                                  if rate.macro == "dot" else "acceleration")

    # -- runs of letters -> names ----------------------------------------------------
    def _readings(self, atoms: list[Any], *, functions: bool = False,
                  open_end: bool = False) -> list[list[Any]]:
        r"""Up to :data:`MAX_READINGS` ways to read ``atoms`` as declared names, numbers and
        abbreviations (each a list of SymPy factors) and, with ``functions``, functions
        spelled in plain letters (:class:`_Func`; at the end of the run only if
        ``open_end``: its argument follows the run)."""
        memo: dict[int, list[list[Any]]] = {}

        def read(start: int) -> list[list[Any]]:
            if start == len(atoms):
                return [[]]
            if start not in memo:
                found: list[list[Any]] = []
                for end, piece in self._pieces(atoms, start, functions, open_end):
                    for rest in read(end):
                        if len(found) < MAX_READINGS and [piece, *rest] not in found:
                            found.append([piece, *rest])
                memo[start] = found
            return memo[start]

        return read(0)

    def _pieces(self, atoms: list[Any], start: int, functions: bool = False,
                open_end: bool = False) -> Iterable[tuple[int, Any]]:
        r"""Pieces read from ``atoms[start]`` on: (end, SymPy text) for a number, each
        declared name and each abbreviation the atoms up to ``end`` print; with
        ``functions``, (end, :class:`_Func`) for a function spelled in plain letters
        (``sin^2`` of ``sin^{2}\phi``) unless an abbreviation read from ``start`` spells it
        (``'sin\phi'`` declared: the file's own reading of the print)."""
        if isinstance(atoms[start], _Value):
            yield start + 1, _pow(atoms[start].text, atoms[start].sup)
        forms, abbreviations, longest = (getattr(self.names, k)
                                         for k in ("_forms", "_abbrev", "_longest"))
        abbreviated = start
        for end in range(start + 1, min(len(atoms), start + longest) + 1):
            piece, last = atoms[start:end], atoms[end - 1]
            if any(a.sup for a in piece[:-1]):
                break
            value = abbreviations.get(tuple(_atom_key(a) for a in piece))
            if value is not None:
                abbreviated = end
                yield end, _pow(value, last.sup)
            if not all(isinstance(a, _Letter) for a in piece) or any(a.sub for a in piece[:-1]):
                continue
            names: set[str] = set()
            for spelled in itertools.product(*([a.base] + ([a.alt] if a.alt else [])
                                               for a in piece)):
                names |= forms.get(("".join(spelled), last.sub), set())
            for name in sorted(names):
                yield end, _pow(name, last.sup)
        if functions:
            for end, func in _spelled_functions(atoms, start):
                if end > abbreviated and (end < len(atoms) or open_end):
                    yield end, func

    def _resolve(self, atoms: list[Any]) -> list[Any]:
        r"""Replace each run of letters (and the numbers in it) by its one reading: names,
        numbers, abbreviations and functions spelled in plain letters (a function ends the
        run only before what can be its argument: a factor or ``(``)."""
        out: list[Any] = []
        i = 0
        while i < len(atoms):
            j = i
            while j < len(atoms) and _in_run(atoms[j]):
                j += 1
            if j == i:
                out.append(atoms[i])
                i += 1
                continue
            run, after = atoms[i:j], atoms[j] if j < len(atoms) else None
            open_end = isinstance(after, (_Value, _Func)) or (isinstance(after, _Op)
                                                              and after.op == "(")
            readings = self._readings(run, functions=True, open_end=open_end)
            if len(readings) > 1:
                raise self._ambiguous(run, readings)
            if not readings:
                raise UndeclaredNameError(self.source, _unresolved(self, run, open_end))
            out.extend(t if isinstance(t, _Func) else
                       _Value(t, number=_NUMBER.fullmatch(t) is not None) for t in readings[0])
            i = j
        return out

    def _ambiguous(self, run: list[Any], readings: list[list[Any]]) -> LatexError:
        shown = tuple(_shown(r) for r in readings)
        cut = [t if len(t) <= MAX_SHOWN else t[:MAX_SHOWN - 3] + "..."
               for t in (_printed(run, powers=True), *shown)]
        return self.fail(f"ambiguous: {cut[0]!r} reads as {cut[1]} or as {cut[2]}; "
                         "write it so that it reads one way (\\cdot or braces between factors, "
                         "\\dot{x} for a velocity, \\sin for a function) or rename a symbol",
                         shown)

    # -- atoms -> SymPy text ---------------------------------------------------------
    def expression(self, nodes: Iterable[Any], equation: bool = False) -> str:
        return self.text(self.atoms(nodes), equation)

    def text(self, atoms: list[Any], equation: bool = False) -> str:
        tokens = self._resolve(atoms)
        sides = [[]]
        for t in tokens:
            if isinstance(t, _Op) and t.op == "=":
                sides.append([])
            else:
                sides[-1].append(t)
        if len(sides) > 1 and not equation:
            raise self.fail("'=' is allowed only in an equation")
        if equation and len(sides) != 2:
            raise self.fail("an equation has one '=' between its sides")
        return " = ".join(_Parser(self, side).parse() for side in sides)


def _in_run(atom: Any) -> bool:
    return isinstance(atom, _Letter) or (isinstance(atom, _Value) and atom.number)


def _spelled_functions(atoms: list[Any], start: int) -> Iterable[tuple[int, _Func]]:
    r"""(end, function) for each of :data:`FUNCTIONS` the plain letters ``atoms[start:end]``
    spell (``s i n^{2}``: ``sin`` squared); a subscript, or a power before the last
    letter, spells none."""
    letters = ""
    for k in range(start, min(len(atoms), start + _LONGEST_FUNCTION)):
        atom = atoms[k]
        if not (isinstance(atom, _Letter) and len(atom.base) == 1 and not atom.sub):
            return
        letters += atom.base
        if letters in FUNCTIONS:
            yield k + 1, _Func(FUNCTIONS[letters], atom.sup)
        if atom.sup is not None:
            return


def _shown(reading: list[Any]) -> str:
    r"""A reading as SymPy-like text: factors joined by ``*``, a function applied to the
    factor after it (``m_s*sin(phi)**2``)."""
    out: list[str] = []
    k = 0
    while k < len(reading):
        text, k = _shown_factor(reading, k)
        out.append(text)
    return "*".join(out)


def _shown_factor(reading: list[Any], k: int) -> tuple[str, int]:
    piece = reading[k]
    if not isinstance(piece, _Func):
        return piece, k + 1
    arg, end = _shown_factor(reading, k + 1) if k + 1 < len(reading) else ("...", k + 1)
    return _pow(f"{piece.name}({arg})", piece.sup), end


def _printed(run: list[Any], powers: bool = False) -> str:
    r"""``run`` as LaTeX, a space after a subscript or a Greek letter (``m_s dx``); with
    ``powers``, the powers too (``sin^2\phi``)."""
    out = ""
    for a in run:
        sup = "" if not powers or a.sup is None else (
            f"^{{{a.sup}}}" if len(a.sup) > 1 else f"^{a.sup}")
        if isinstance(a, _Value):
            out += a.text + sup
            continue
        greek = a.base in GREEK or a.alt is not None
        out += ("\\" if greek else "") + a.base + (f"_{{{a.sub}}}" if len(a.sub) > 1 else
                                                    f"_{a.sub}" if a.sub else "") + sup
        out += " " if a.sub or greek or sup else ""
    return out.strip()


def _unresolved(reader: _Reader, run: list[Any], open_end: bool) -> str:
    r"""The printed part of ``run`` no reading gets past: from the farthest point readings
    reach to the first point from which the rest reads."""
    reach = {0}
    for k in range(len(run)):
        if k in reach:
            reach |= {end for end, _ in reader._pieces(run, k, True, open_end)}
    stop = max(reach)
    end = next(k for k in range(stop + 1, len(run) + 1)
               if k == len(run) or reader._readings(run[k:], functions=True, open_end=open_end))
    return _printed(run[stop:end])


class _Parser:
    r"""Sums, products (explicit and implicit), functions and powers of resolved atoms."""

    def __init__(self, reader: _Reader, tokens: list[Any]) -> None:
        self.reader, self.tokens, self.i = reader, tokens, 0

    def peek(self) -> Any:
        return self.tokens[self.i] if self.i < len(self.tokens) else None

    def take(self) -> Any:
        token = self.peek()
        if token is None:
            raise self.reader.fail("expression ends too early")
        self.i += 1
        return token

    def close(self) -> _Op:
        token = self.peek()
        if not (isinstance(token, _Op) and token.op == ")"):
            raise self.reader.fail("missing ')'")
        self.i += 1
        return token

    def parse(self) -> str:
        if not self.tokens:
            raise self.reader.fail("empty expression")
        text = self.sum()
        if self.peek() is not None:
            raise self.reader.fail(f"unexpected {self.peek()[0]!r}")
        return text

    def sum(self) -> str:
        out = ""
        while isinstance(self.peek(), _Op) and self.peek().op in "+-":
            out += self.take().op
        out += self.product()
        while isinstance(self.peek(), _Op) and self.peek().op in "+-":
            sign = self.take().op
            while isinstance(self.peek(), _Op) and self.peek().op in "+-":
                sign = "-" if (sign == "-") != (self.take().op == "-") else "+"
            out += f" {sign} {self.product()}"
        return out

    def product(self) -> str:
        out = self.factor()
        while True:
            token = self.peek()
            if isinstance(token, _Op) and token.op in "*/":
                self.i += 1
                out += f"{token.op}{self.factor()}"
            elif isinstance(token, (_Value, _Func)) or (isinstance(token, _Op)
                                                        and token.op == "("):
                out += f"*{self.factor()}"
            else:
                return out

    def factor(self) -> str:
        token = self.take()
        if isinstance(token, _Value):
            return _pow(token.text, token.sup)
        if isinstance(token, _Func):
            arg, sup = self.argument(token)
            return _pow(_pow(f"{token.name}({arg})", token.sup), sup)
        if isinstance(token, _Op) and token.op == "(":
            inner, close = self.sum(), self.close()
            return _pow(f"({inner})", close.sup)
        if isinstance(token, _Op) and token.op == "-":
            return f"(-{self.factor()})"
        raise self.reader.fail(f"unexpected {token[0]!r}")

    def argument(self, func: _Func) -> tuple[str, str | None]:
        r"""A function's argument: parenthesised, or one factor (with a leading number)."""
        token = self.peek()
        if isinstance(token, _Op) and token.op == "(":
            self.i += 1
            inner, close = self.sum(), self.close()
            return inner, close.sup
        if isinstance(token, _Func):
            return self.factor(), None
        if not isinstance(token, _Value):
            raise self.reader.fail(f"{func.name} without an argument")
        self.i += 1
        text = _pow(token.text, token.sup)
        after = self.peek()
        if token.number and token.sup is None and isinstance(after, _Value) and not after.number:
            self.i += 1
            text += "*" + _pow(after.text, after.sup)
        return text, None


def latex_to_sympy(source: str, names: LatexNames, *, equation: bool = False) -> str:
    r"""The SymPy-syntax text of the LaTeX expression ``source`` (with ``equation=True``,
    ``"lhs = rhs"``). Raises :class:`LatexError` for LaTeX that cannot be read or reads two
    ways, :class:`~.expressions.UndeclaredNameError` for a name ``names`` lacks."""
    reader = _Reader(names, source)
    try:
        nodes = _content(_parse(source))
        return reader.expression(_drop_equation_number(nodes) if equation else nodes,
                                 equation=equation)
    except RecursionError:
        raise LatexError(source, "LaTeX nested too deeply") from None


def _blank(node: Any) -> bool:
    return node is None or isinstance(node, LatexCommentNode) or (
        isinstance(node, LatexCharsNode) and not node.chars.strip())


def _content(nodes: list[Any]) -> list[Any]:
    r"""The nodes of a value without blanks and comments; of one math group (``$...$``),
    the nodes inside it."""
    kept = [n for n in nodes if not _blank(n)]
    if len(kept) == 1 and isinstance(kept[0], LatexMathNode):
        kept = [n for n in kept[0].nodelist if not _blank(n)]
    return kept


def _drop_equation_number(nodes: list[Any]) -> list[Any]:
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


def split_latex_matrix(source: str) -> list[list[str]]:
    r"""The cells (LaTeX text) of the one ``bmatrix``/``pmatrix`` in ``source``, row by row.
    Text before the matrix ending in ``=`` (its printed name, ``\mathbf{A} =``) is skipped;
    a matrix followed by a transpose (:data:`TRANSPOSE`: ``^T``, ``^{T}``, ``^\top``,
    ``^{\mathsf{T}}``) gives its columns as rows (a printed row vector ``[a & b]^T`` is the
    column ``[[a], [b]]``); ``\tag{...}`` and a final ``\quad (35)`` are dropped."""
    nodes = _drop_equation_number([n for n in _content(_parse(source)) if not (
        isinstance(n, LatexMacroNode) and n.macroname == TAG)])
    envs = [k for k, n in enumerate(nodes) if isinstance(n, LatexEnvironmentNode)]
    prefix = source[nodes[0].pos:nodes[envs[0]].pos].strip() if envs else ""
    tail = "".join(source[n.pos:n.pos + n.len] for n in nodes[envs[0] + 1:]) if envs else ""
    transposed = bool(tail) and TRANSPOSE.fullmatch(tail) is not None
    if (len(envs) != 1 or (tail and not transposed)
            or nodes[envs[0]].environmentname not in MATRICES
            or (prefix and not prefix.endswith("="))):
        raise LatexError(source, "expected one \\begin{bmatrix} ... \\end{bmatrix} "
                                 "(or pmatrix), optionally after 'A =', optionally "
                                 "transposed (^T)")
    rows: list[list[str]] = [[]]
    cell: list[Any] = []

    def close_cell() -> None:
        text = source[cell[0].pos:cell[-1].pos + cell[-1].len].strip() if cell else ""
        rows[-1].append(text)
        cell.clear()

    for node in nodes[envs[0]].nodelist:
        if isinstance(node, LatexSpecialsNode) and node.specials_chars == "&":
            close_cell()
        elif isinstance(node, LatexMacroNode) and node.macroname == "\\":
            close_cell()
            rows.append([])
        elif node is not None and not isinstance(node, LatexCommentNode):
            cell.append(node)
    close_cell()
    if rows[-1] == [""] and len(rows) > 1:
        rows.pop()                              # a trailing \\ ends the last row
    if any(c == "" for row in rows for c in row):
        raise LatexError(source, "empty matrix cell")
    if transposed:
        if len({len(row) for row in rows}) != 1:
            raise LatexError(source, "a transposed matrix needs rows of one length, got "
                                     + ", ".join(str(len(row)) for row in rows))
        rows = [list(column) for column in zip(*rows)]
    return rows


def parse_latex_expression(source: str, names: LatexNames,
                           namespace: Mapping[str, sympy.Basic]) -> sympy.Expr:
    r"""The SymPy expression of ``source``: :func:`latex_to_sympy`, then
    :func:`~.expressions.parse_expression` in ``namespace`` (its limits included)."""
    return parse_expression(latex_to_sympy(source, names), namespace)
