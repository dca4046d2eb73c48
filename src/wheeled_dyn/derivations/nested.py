r"""A matrix written as text, ``[[a, b], [c, d]]``, split into nested lists of element texts
(:func:`split_nested`) before each element is parsed; commas inside parentheses
(``atan2(y, x)``) do not split, and a malformed list is an
:class:`~wheeled_dyn.derivations.errors.ExpressionError`.
"""

from __future__ import annotations

from typing import Union

from .errors import ExpressionError

Nested = Union[str, list["Nested"]]


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


__all__ = ["Nested", "split_nested"]
