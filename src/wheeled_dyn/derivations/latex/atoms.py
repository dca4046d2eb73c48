r"""Atoms: the factors, functions and operators a LaTeX value is read into, and their grammar.

The reader (:mod:`.reader`) turns pylatexenc's nodes into atoms: a :class:`Letter` (a letter
or a Greek letter, with its subscript and power) waits to be resolved into a declared name;
a :class:`Value` is a factor already in SymPy syntax; a :class:`Func` a function; an
:class:`Op` an operator; a :class:`Rate` a ``\dot{x}``/``\ddot{x}``. Once the runs of
letters are resolved (:mod:`.runs`), :class:`Parser` reads the atoms as sums, products
(``\cdot``, ``\times`` and implicit), functions and powers: a function without parentheses
takes one factor (with a leading number: ``\sin 2\phi``), ``\sin^2\phi`` is
``sin(phi)**2``.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any, NamedTuple

from .nodes import LatexError


class Letter(NamedTuple):
    base: str                   # a letter or a Greek letter's name
    sub: str = ""
    sup: str | None = None
    alt: str | None = None      # the plain letter of a variant (varphi -> phi)

    @property
    def key(self) -> tuple[str, str]:
        return (self.base, self.sub)


class Value(NamedTuple):        # a factor already in SymPy syntax
    text: str
    sup: str | None = None
    number: bool = False


class Func(NamedTuple):
    name: str
    sup: str | None = None


class Op(NamedTuple):
    op: str
    sup: str | None = None


class Rate(NamedTuple):         # \dot{x}, \ddot{x}: named once its subscript is known
    macro: str                  # "dot" or "ddot"
    arg: tuple[Any, ...]        # the atoms under the dot
    sub: str = ""               # a subscript after the dot: \dot{x}_0
    sup: str | None = None


def wrap(text: str) -> str:
    r"""``text`` in parentheses unless it is one name or number (with a power)."""
    return text if re.fullmatch(r"[\w.]+(\*\*[\w.]+)?", text) else f"({text})"


def atom_key(atom: Any) -> tuple[str, str]:
    r"""What ``atom`` prints as a piece of a run: a letter's (base, subscript), a number's text."""
    return atom.key if isinstance(atom, Letter) else ("#", atom.text)


def power(text: str, sup: str | None) -> str:
    r"""``text`` raised to ``sup`` (SymPy syntax); ``text`` itself when ``sup`` is None."""
    if sup is None:
        return text
    return f"{text}**{sup}" if sup.isalnum() else f"{text}**({sup})"


class Parser:
    r"""Sums, products (explicit and implicit), functions and powers of resolved atoms;
    ``fail(reason)`` makes the error raised for atoms that do not parse."""

    def __init__(self, fail: Callable[[str], LatexError], tokens: list[Any]) -> None:
        self.fail, self.tokens, self.i = fail, tokens, 0

    def peek(self) -> Any:
        return self.tokens[self.i] if self.i < len(self.tokens) else None

    def take(self) -> Any:
        token = self.peek()
        if token is None:
            raise self.fail("expression ends too early")
        self.i += 1
        return token

    def close(self) -> Op:
        token = self.peek()
        if not (isinstance(token, Op) and token.op == ")"):
            raise self.fail("missing ')'")
        self.i += 1
        return token

    def parse(self) -> str:
        if not self.tokens:
            raise self.fail("nothing where an expression is expected (a side of an equation, "
                            "or a group {} — an exponent, a fraction's part, a function's "
                            "argument — left empty)")
        text = self.sum()
        if self.peek() is not None:
            raise self.fail(f"unexpected {self.peek()[0]!r}")
        return text

    def sum(self) -> str:
        out = ""
        while isinstance(self.peek(), Op) and self.peek().op in "+-":
            out += self.take().op
        out += self.product()
        while isinstance(self.peek(), Op) and self.peek().op in "+-":
            sign = self.take().op
            while isinstance(self.peek(), Op) and self.peek().op in "+-":
                sign = "-" if (sign == "-") != (self.take().op == "-") else "+"
            out += f" {sign} {self.product()}"
        return out

    def product(self) -> str:
        out = self.factor()
        while True:
            token = self.peek()
            if isinstance(token, Op) and token.op in "*/":
                self.i += 1
                out += f"{token.op}{self.factor()}"
            elif isinstance(token, (Value, Func)) or (isinstance(token, Op)
                                                      and token.op == "("):
                out += f"*{self.factor()}"
            else:
                return out

    def factor(self) -> str:
        token = self.take()
        if isinstance(token, Value):
            return power(token.text, token.sup)
        if isinstance(token, Func):
            if token.sup is not None and token.sup.replace(" ", "") in ("-1", "(-1)"):
                raise self.fail(f"\\{token.name}^{{-1}} is ambiguous (the inverse function, or "
                                f"1/\\{token.name}): write \\arc{token.name} or "
                                f"(\\{token.name} x)^{{-1}}")
            arg, sup = self.argument(token)
            return power(power(f"{token.name}({arg})", token.sup), sup)
        if isinstance(token, Op) and token.op == "(":
            inner, close = self.sum(), self.close()
            return power(f"({inner})", close.sup)
        if isinstance(token, Op) and token.op == "-":
            return f"(-{self.factor()})"
        raise self.fail(f"unexpected {token[0]!r}")

    def argument(self, func: Func) -> tuple[str, str | None]:
        r"""A function's argument: parenthesised, or one factor (with a leading number)."""
        token = self.peek()
        if isinstance(token, Op) and token.op == "(":
            self.i += 1
            inner, close = self.sum(), self.close()
            return inner, close.sup
        if isinstance(token, Func):
            return self.factor(), None
        if not isinstance(token, Value):
            raise self.fail(f"{func.name} without an argument")
        self.i += 1
        text = power(token.text, token.sup)
        after = self.peek()
        if token.number and token.sup is None and isinstance(after, Value) and not after.number:
            self.i += 1
            text += "*" + power(after.text, after.sup)
        return text, None
