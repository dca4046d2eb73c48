r"""Runs of letters: how letters, subscripts and Greek letters next to each other split into
a file's declared names.

A run of letters, subscripts and Greek letters (``m_s d``, ``\mathbf{MZ_1}``, ``2M_wL^2``) is
split into the names, numbers and abbreviations of a symbol table
(:class:`~.names.LatexNames`); fonts (``\mathbf``, ``\mathbb`` ...) and spaces do not separate
names. A function spelled in plain letters (``sin^{2}\phi``, a print that lost its
backslash) is one more reading of a run: the function when the letters read as no declared
names, ambiguous when they also do; a ``[latex] abbreviation`` spelling it (``'sin\phi'``) is
read instead. A run that splits in two ways is an error showing both readings
(:func:`ambiguity`, a :class:`~.nodes.LatexError`); one that does not split an
:class:`~wheeled_dyn.derivations.expressions.UndeclaredNameError` naming the part no reading
gets past (:func:`unresolved`).
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable
from typing import TYPE_CHECKING, Any

from .atoms import Func, Letter, Value, atom_key, power
from .nodes import FUNCTIONS, GREEK

if TYPE_CHECKING:
    from .names import LatexNames

#: Readings of a run of letters collected before it is declared ambiguous.
MAX_READINGS = 2
#: Longest run or reading shown in an error message, in characters.
MAX_SHOWN = 80
_LONGEST_FUNCTION = max(map(len, FUNCTIONS))


def in_run(atom: Any) -> bool:
    r"""Whether ``atom`` is part of a run of letters: a letter or a number."""
    return isinstance(atom, Letter) or (isinstance(atom, Value) and atom.number)


def readings(names: LatexNames, atoms: list[Any], *, functions: bool = False,
             open_end: bool = False) -> list[list[Any]]:
    r"""Up to :data:`MAX_READINGS` ways to read ``atoms`` as declared names, numbers and
    abbreviations (each a list of SymPy factors) and, with ``functions``, functions
    spelled in plain letters (:class:`~.atoms.Func`; at the end of the run only if
    ``open_end``: its argument follows the run)."""
    memo: dict[int, list[list[Any]]] = {}

    def read(start: int) -> list[list[Any]]:
        if start == len(atoms):
            return [[]]
        if start not in memo:
            found: list[list[Any]] = []
            for end, piece in pieces(names, atoms, start, functions, open_end):
                for rest in read(end):
                    if len(found) < MAX_READINGS and [piece, *rest] not in found:
                        found.append([piece, *rest])
            memo[start] = found
        return memo[start]

    return read(0)


def pieces(names: LatexNames, atoms: list[Any], start: int, functions: bool = False,
           open_end: bool = False) -> Iterable[tuple[int, Any]]:
    r"""Pieces read from ``atoms[start]`` on: (end, SymPy text) for a number, each
    declared name and each abbreviation the atoms up to ``end`` print; with
    ``functions``, (end, :class:`~.atoms.Func`) for a function spelled in plain letters
    (``sin^2`` of ``sin^{2}\phi``) unless an abbreviation read from ``start`` spells it
    (``'sin\phi'`` declared: the file's own reading of the print)."""
    if isinstance(atoms[start], Value):
        yield start + 1, power(atoms[start].text, atoms[start].sup)
    forms, abbreviations, longest = (getattr(names, k)
                                     for k in ("_forms", "_abbrev", "_longest"))
    abbreviated = start
    for end in range(start + 1, min(len(atoms), start + longest) + 1):
        piece, last = atoms[start:end], atoms[end - 1]
        if any(a.sup for a in piece[:-1]):
            break
        value = abbreviations.get(tuple(atom_key(a) for a in piece))
        if value is not None:
            abbreviated = end
            yield end, power(value, last.sup)
        if not all(isinstance(a, Letter) for a in piece) or any(a.sub for a in piece[:-1]):
            continue
        found: set[str] = set()
        for spelled in itertools.product(*([a.base] + ([a.alt] if a.alt else [])
                                           for a in piece)):
            found |= forms.get(("".join(spelled), last.sub), set())
        for name in sorted(found):
            yield end, power(name, last.sup)
    if functions:
        for end, func in _spelled_functions(atoms, start):
            if end > abbreviated and (end < len(atoms) or open_end):
                yield end, func


def _spelled_functions(atoms: list[Any], start: int) -> Iterable[tuple[int, Func]]:
    r"""(end, function) for each of :data:`~.nodes.FUNCTIONS` the plain letters
    ``atoms[start:end]`` spell (``s i n^{2}``: ``sin`` squared); a subscript, or a power
    before the last letter, spells none."""
    letters = ""
    for k in range(start, min(len(atoms), start + _LONGEST_FUNCTION)):
        atom = atoms[k]
        if not (isinstance(atom, Letter) and len(atom.base) == 1 and not atom.sub):
            return
        letters += atom.base
        if letters in FUNCTIONS:
            yield k + 1, Func(FUNCTIONS[letters], atom.sup)
        if atom.sup is not None:
            return


def ambiguity(run: list[Any], found: list[list[Any]]) -> tuple[str, tuple[str, ...]]:
    r"""The reason and the readings shown for a ``run`` that reads as each of ``found``."""
    shown = tuple(_shown(r) for r in found)
    cut = [t if len(t) <= MAX_SHOWN else t[:MAX_SHOWN - 3] + "..."
           for t in (printed(run, powers=True), *shown)]
    return (f"ambiguous: {cut[0]!r} reads as {cut[1]} or as {cut[2]}; "
            "write it so that it reads one way (\\cdot or braces between factors, "
            "\\dot{x} for a velocity, \\sin for a function) or rename a symbol", shown)


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
    if not isinstance(piece, Func):
        return piece, k + 1
    arg, end = _shown_factor(reading, k + 1) if k + 1 < len(reading) else ("...", k + 1)
    return power(f"{piece.name}({arg})", piece.sup), end


def printed(run: list[Any], powers: bool = False) -> str:
    r"""``run`` as LaTeX, a space after a subscript or a Greek letter (``m_s dx``); with
    ``powers``, the powers too (``sin^2\phi``)."""
    out = ""
    for a in run:
        sup = "" if not powers or a.sup is None else (
            f"^{{{a.sup}}}" if len(a.sup) > 1 else f"^{a.sup}")
        if isinstance(a, Value):
            out += a.text + sup
            continue
        greek = a.base in GREEK or a.alt is not None
        out += ("\\" if greek else "") + a.base + (f"_{{{a.sub}}}" if len(a.sub) > 1 else
                                                    f"_{a.sub}" if a.sub else "") + sup
        out += " " if a.sub or greek or sup else ""
    return out.strip()


def unresolved(names: LatexNames, run: list[Any], open_end: bool) -> str:
    r"""The printed part of ``run`` no reading gets past: from the farthest point readings
    reach to the first point from which the rest reads."""
    reach = {0}
    for k in range(len(run)):
        if k in reach:
            reach |= {end for end, _ in pieces(names, run, k, True, open_end)}
    stop = max(reach)
    end = next(k for k in range(stop + 1, len(run) + 1)
               if k == len(run) or readings(names, run[k:], functions=True, open_end=open_end))
    return printed(run[stop:end])
