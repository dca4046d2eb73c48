r"""The symbol table as LaTeX sees it: a file's names, how each is printed, and abbreviations.

A name is printed as written (``m_s``, ``I_w3`` as ``I_{w3}``), as its letters with the
trailing digits or the lower-case rest subscripted (``XX1`` as ``XX_1``, ``Mw`` as
``M_w``), or as its ``latex`` field in ``[symbols]`` (:func:`is_printed_name`). Abbreviations
declared in ``[latex] abbreviations`` (``'s2\psi' = "sin(2*psi)"``) are pieces of a run like
names. :class:`LatexNames` reads the printed forms and abbreviations once, with the reader
(:mod:`.reader`), into the keys a run of letters is split by (:mod:`.runs`).
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field

from ..expressions import ExpressionError
from .atoms import Letter, atom_key
from .nodes import LatexError, parse_nodes
from .reader import Reader

_SPLITS = (re.compile(r"^([A-Za-z]+?)(\d+)$"), re.compile(r"^([A-Z]+)([a-z0-9]+)$"))


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
            printed_key = _printed_key(text)
            if printed_key is None:
                raise LatexError(text, f"the printed form of {name} is not a name")
            forms.setdefault(printed_key, set()).add(name)
        object.__setattr__(self, "_forms", forms)       # read by the abbreviations' \dot{}
        object.__setattr__(self, "_abbrev", {})
        object.__setattr__(self, "_longest", max([len(b) for b, _ in forms] + [1]))
        abbrev = {}
        for text, value in self.abbreviations.items():
            atoms = Reader(self, text).atoms(parse_nodes(text))
            if not atoms or any(a.sup or not (isinstance(a, Letter) or getattr(a, "number", False))
                                for a in atoms):
                raise LatexError(text, "an abbreviation is letters, digits and subscripts")
            abbrev[tuple(atom_key(a) for a in atoms)] = f"({value})"
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
        atoms = Reader(LatexNames(()), text).atoms(parse_nodes(text))
    except ExpressionError:
        return None
    if not atoms or any(not isinstance(a, Letter) or a.sup or a.sub for a in atoms[:-1]):
        return None
    last = atoms[-1]
    return None if not isinstance(last, Letter) or last.sup else (
        "".join(a.base for a in atoms), last.sub)
