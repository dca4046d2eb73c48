r"""Errors of derivation files that carry the file, the line and the item.

The project's :class:`~wheeled_dyn.errors.UnknownNameError` names the unknown name and the valid
ones; in a derivation file the user also needs *where*: the file, the line (when it can be
found) and the item (``A[2,3]``, ``symbols.MX1.value``, ``equation 2``).

An expression that cannot be read raises :class:`ExpressionError` (or
:class:`UndeclaredNameError`, naming the name) before anyone knows where it stands: the loader
catches it and raises the project's error with the file, the line and the item.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

from ..errors import UnknownNameError


class DerivationNameError(UnknownNameError):
    r"""A name used in a derivation file is not declared.

    Attributes as :class:`UnknownNameError` (``kind``, ``name``, ``valid``, ``where``) plus
    ``path`` (the file), ``item`` (the key or matrix element, 1-based like ``A[2,3]``) and
    ``line`` (1-based, or None).
    """

    def __init__(self, path: str | Path, item: str, kind: str, name: str,
                 valid: Iterable[str] | None = None, line: int | None = None) -> None:
        self.path = Path(path)
        self.item = item
        self.line = line
        where = f"{self.path}:{line}" if line is not None else str(self.path)
        super().__init__(kind, name, valid, where=f"{where}: {item}")
        from .namespace import GEOMETRY_NAMES
        call = next((f"{g}({name[len(g) + 1:]})" for g in sorted(GEOMETRY_NAMES, key=len,
                                                                  reverse=True)
                     if kind == "symbol" and name.startswith(g + "_")), None)
        if call is not None:               # a model length as a coordinate map writes it
            self.args = (self.args[0] + f"; for the model length {call}, declare a symbol "
                         f"in [symbols] (x = {{ value = \"{call}\" }}) and write it here",)
        if kind == "model input":          # a starter model file lists no motors
            self.args = (self.args[0] + "; a model's inputs are the motors its model file "
                         "names: [joints] actuated = [the joints], inputs = [their names]",)


class ExpressionError(ValueError):
    """An expression cannot be parsed; ``reason`` says why (internal: the loader adds the file,
    the line and the item)."""

    def __init__(self, text: str, reason: str) -> None:
        self.text = text
        self.reason = reason
        super().__init__(f"{reason} in {short_text(text)!r}")

    def __reduce__(self):
        return type(self), (self.text, self.reason)


def short_text(text: str, width: int = 120) -> str:
    r"""``text`` cut in the middle to at most about ``width`` characters, for a message."""
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
