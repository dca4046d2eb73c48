r"""Errors of derivation files that carry the file, the line and the item.

The project's :class:`~wheeled_dyn.errors.UnknownNameError` names the unknown name and the valid
ones; in a derivation file the user also needs *where*: the file, the line (when it can be
found) and the item (``A[2,3]``, ``symbols.MX1.value``, ``equation 2``).
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
