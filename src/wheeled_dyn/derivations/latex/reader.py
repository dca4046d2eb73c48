r"""The reader: a LaTeX expression or equation, as pylatexenc's nodes, to SymPy text.

:func:`latex_to_sympy` gives the SymPy-syntax text the rest of the loader parses
(:mod:`~wheeled_dyn.derivations.expressions`, with all its limits);
:func:`parse_latex_expression` parses it too. The nodes become atoms (:mod:`.atoms`), the
runs of letters in them the file's names (:mod:`.runs`), and the atoms a sum of products:

- ``\dot{p}``, ``\ddot{p}`` of a position are its velocity and acceleration (of another name
  ``n``: the declared ``dn``, ``ddn``); a subscript after the dot joins the dotted letters
  as in a name: ``\dot{x}_0`` is the velocity of ``x_0`` (``x0``);
- ``\sin\phi\cos\phi``: a function without parentheses takes one name (with a leading number:
  ``\sin 2\phi``); ``\sin^2\phi`` is ``sin(phi)**2``;
- ``\frac``, ``\sqrt``, ``\left( \right)``, ``\cdot``, ``\times``, powers, implicit products;
  ``=`` in equations; an equation's final number ``\quad (9)`` and any ``\tag{10}`` are
  dropped.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from typing import TYPE_CHECKING, Any

import sympy
from pylatexenc.latexwalker import (LatexCharsNode, LatexCommentNode, LatexEnvironmentNode,
                                    LatexGroupNode, LatexMacroNode, LatexMathNode,
                                    LatexSpecialsNode)

from ..expressions import UndeclaredNameError, parse_expression
from .atoms import Func, Letter, Op, Parser, Rate, Value, wrap
from .nodes import (FONTS, FUNCTIONS, GREEK, IGNORED, OPERATORS, TAG, VARIANTS, LatexError,
                    content, drop_equation_number, parse_nodes)
from .runs import ambiguity, in_run, printed, readings, unresolved

if TYPE_CHECKING:
    from .names import LatexNames

_ARGUMENTS = {"frac": 2, "tfrac": 2, "dfrac": 2, "sqrt": 1, "dot": 1, "ddot": 1,
              **{font: 1 for font in FONTS}}
_CHAR_OPS = {"+": "+", "-": "-", "*": "*", "/": "/", "=": "=", "(": "(", ")": ")", "[": "(",
             "]": ")"}
_NUMBER = re.compile(r"\d+(?:\.\d*)?|\.\d+")


class Reader:
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
                        self._attach(out, pending, c)
                        pending, i = None, i + 1
                    elif c in "_^":
                        pending, i = c, i + 1
                    elif number:
                        out.append(Value(number.group(0), number=True))
                        i = number.end()
                    elif c.isalpha() and c.isascii():
                        out.append(Letter(c))
                        i += 1
                    elif c in _CHAR_OPS:
                        out.append(Op(_CHAR_OPS[c]))
                        i += 1
                    else:
                        raise self.fail(f"unexpected {c!r}")
            elif isinstance(node, LatexCommentNode) or node is None:
                continue
            elif pending:
                self._attach(out, pending, node)
                pending = None
            else:
                out.extend(self._node(node))
        if pending:
            raise self.fail(f"{pending!r} without an argument")
        return [Value(self._derivative(a), a.sup) if isinstance(a, Rate) else a for a in out]

    def _attach(self, out: list[Any], marker: str, arg: Any) -> None:
        r"""Attach the subscript (``marker`` ``"_"``) or superscript (``"^"``) ``arg`` (one
        character or a node) to the last atom of ``out``."""
        last = out[-1] if out else None
        if marker == "_":
            key = arg if isinstance(arg, str) else self._key_text([arg])
            if not isinstance(last, (Letter, Rate)) or last.sub or last.sup:
                raise self.fail(f"subscript _{key} after no letter")
            out[-1] = last._replace(sub=key)
            return
        if isinstance(last, (Letter, Value, Func, Rate)) or (isinstance(last, Op)
                                                             and last.op == ")"):
            if last.sup is not None:
                raise self.fail("double superscript")
            if isinstance(arg, str):        # one character: ^2, ^n
                text = self.text([Letter(arg) if arg.isalpha()
                                  else Value(arg, number=arg.isdigit())])
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
        r"""The atoms of one node other than characters and comments."""
        if isinstance(node, LatexGroupNode):
            return [Value(f"({self.expression(node.nodelist)})")]
        if isinstance(node, LatexMathNode):
            return self.atoms(node.nodelist)
        if isinstance(node, LatexEnvironmentNode):
            raise self.fail(f"\\begin{{{node.environmentname}}} where an expression is expected "
                            "(a matrix is a whole value: A = { latex = '...' })")
        if isinstance(node, LatexSpecialsNode):
            raise self.fail(f"{node.specials_chars!r} outside a matrix")
        return self._macro(node)

    def _macro(self, node: Any) -> list[Any]:
        r"""The atoms of a macro: a letter, ``\pi``, a font's content, a function, or (with
        :meth:`_built`) a fraction, a root, a rate, an operator, nothing."""
        name = node.macroname
        args = [a for a in (node.nodeargd.argnlist if node.nodeargd else []) if a is not None]
        if len(args) < _ARGUMENTS.get(name, 0):
            raise self.fail(f"\\{name} needs {_ARGUMENTS[name]} argument(s)")
        if name in GREEK or name in VARIANTS:
            return [Letter(name, alt=VARIANTS.get(name))]
        if name == "pi":
            return [Value("pi")]
        if name in FONTS:
            return self.atoms(args[-1].nodelist if isinstance(args[-1], LatexGroupNode)
                              else args[-1:])
        if name in FUNCTIONS:
            return [Func(FUNCTIONS[name])]
        return self._built(name, args)

    def _built(self, name: str, args: list[Any]) -> list[Any]:
        r"""The atoms of ``\frac``, ``\sqrt``, ``\dot``, ``\ddot``, an equation number, an
        operator macro or an ignored one; any other macro is an error."""
        if name in ("frac", "tfrac", "dfrac"):
            num, den = (self.expression(a.nodelist if isinstance(a, LatexGroupNode) else [a])
                        for a in args)
            return [Value(f"({wrap(num)}/{wrap(den)})")]
        if name == "sqrt":
            return [self._root(args)]
        if name in ("dot", "ddot"):
            arg = args[0].nodelist if isinstance(args[0], LatexGroupNode) else [args[0]]
            return [Rate(name, tuple(self.atoms(arg)))]
        if name == TAG:                     # an equation number
            return []
        if name in OPERATORS:
            return [Op(OPERATORS[name])]
        if name in IGNORED or name in ("left", "right"):
            return []
        if name == "\\":
            raise self.fail("'\\\\' outside a matrix")
        raise self.fail(f"unknown LaTeX macro \\{name}")

    def _root(self, args: list[Any]) -> Value:
        r"""``\sqrt{x}``, or ``\sqrt[n]{x}`` as a power ``1/n``."""
        inner = self.expression(args[-1].nodelist if isinstance(args[-1], LatexGroupNode)
                                else args[-1:])
        if len(args) == 2:
            root = wrap(self.expression(args[0].nodelist))
            # the base whole: m**3**(1/3) is m**(3**(1/3))
            return Value(f"(({inner})**(1/{root}))")
        return Value(f"sqrt({inner})")

    def _derivative(self, rate: Rate) -> str:
        r"""The velocity (``\dot``) or acceleration (``\ddot``) name of ``rate``; a subscript
        after the dot joins the dotted letters (``\dot{x}_0`` is the rate of ``x_0``)."""
        atoms = list(rate.arg)
        letters = bool(atoms) and all(isinstance(a, Letter) for a in atoms)
        if rate.sub:
            if not letters or atoms[-1].sub or atoms[-1].sup:
                raise self.fail(f"subscript _{rate.sub} after \\{rate.macro}{{...}} of no letter")
            atoms[-1] = atoms[-1]._replace(sub=rate.sub)
        found = readings(self.names, atoms) if letters else []
        if len(found) > 1:
            raise self._ambiguous(atoms, found)
        table, prefix = ((self.names.velocity, "d") if rate.macro == "dot"
                         else (self.names.acceleration, "dd"))
        if found and len(found[0]) == 1:
            name = table.get(found[0][0], prefix + found[0][0])
            if name in self.names.names:
                return name
        what = printed(list(rate.arg)) if letters else "?"
        sub = (f"_{{{rate.sub}}}" if len(rate.sub) > 1 else f"_{rate.sub}") if rate.sub else ""
        raise UndeclaredNameError(self.source, f"\\{rate.macro}{{{what}}}{sub}", "velocity"
                                  if rate.macro == "dot" else "acceleration")

    # -- runs of letters -> names ----------------------------------------------------
    def _resolve(self, atoms: list[Any]) -> list[Any]:
        r"""Replace each run of letters (and the numbers in it) by its one reading: names,
        numbers, abbreviations and functions spelled in plain letters (a function ends the
        run only before what can be its argument: a factor or ``(``)."""
        out: list[Any] = []
        i = 0
        while i < len(atoms):
            j = i
            while j < len(atoms) and in_run(atoms[j]):
                j += 1
            if j == i:
                out.append(atoms[i])
                i += 1
                continue
            run, after = atoms[i:j], atoms[j] if j < len(atoms) else None
            open_end = isinstance(after, (Value, Func)) or (isinstance(after, Op)
                                                            and after.op == "(")
            found = readings(self.names, run, functions=True, open_end=open_end)
            if len(found) > 1:
                raise self._ambiguous(run, found)
            if not found:
                raise UndeclaredNameError(self.source, unresolved(self.names, run, open_end))
            out.extend(t if isinstance(t, Func) else
                       Value(t, number=_NUMBER.fullmatch(t) is not None) for t in found[0])
            i = j
        return out

    def _ambiguous(self, run: list[Any], found: list[list[Any]]) -> LatexError:
        return self.fail(*ambiguity(run, found))

    # -- atoms -> SymPy text ---------------------------------------------------------
    def expression(self, nodes: Iterable[Any], equation: bool = False) -> str:
        return self.text(self.atoms(nodes), equation)

    def text(self, atoms: list[Any], equation: bool = False) -> str:
        tokens = self._resolve(atoms)
        sides: list[list[Any]] = [[]]
        for t in tokens:
            if isinstance(t, Op) and t.op == "=":
                sides.append([])
            else:
                sides[-1].append(t)
        if len(sides) > 1 and not equation:
            raise self.fail("'=' is allowed only in an equation")
        if equation and len(sides) != 2:
            raise self.fail("an equation has one '=' between its sides")
        return " = ".join(Parser(self.fail, side).parse() for side in sides)


def latex_to_sympy(source: str, names: LatexNames, *, equation: bool = False) -> str:
    r"""The SymPy-syntax text of the LaTeX expression ``source`` (with ``equation=True``,
    ``"lhs = rhs"``). Raises :class:`~.nodes.LatexError` for LaTeX that cannot be read or
    reads two ways, :class:`~wheeled_dyn.derivations.expressions.UndeclaredNameError` for a
    name ``names`` lacks."""
    reader = Reader(names, source)
    try:
        nodes = content(parse_nodes(source))
        return reader.expression(drop_equation_number(nodes) if equation else nodes,
                                 equation=equation)
    except RecursionError:
        raise LatexError(source, "LaTeX nested too deeply") from None


def parse_latex_expression(source: str, names: LatexNames,
                           namespace: Mapping[str, sympy.Basic]) -> sympy.Expr:
    r"""The SymPy expression of ``source``: :func:`latex_to_sympy`, then
    :func:`~wheeled_dyn.derivations.expressions.parse_expression` in ``namespace`` (its
    limits included)."""
    return parse_expression(latex_to_sympy(source, names), namespace)
