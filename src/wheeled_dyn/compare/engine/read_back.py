r"""The document's equations read back before it solved or combined them, named on the elements
of the rows its frames show divided or combined (:func:`read_back_said`): its inverted inertia
matrix (:func:`~..judge.unsolved.inertia_diagnoses`), the terms of the equations it solved
(:func:`~..judge.unsolved.unsolved_terms`), or the one wrong entry of the equations it combined
(:func:`~..judge.source_entry.source_entry`), or, none of these, the determinant it solved
with (:func:`~..judge.common_divisor.common_divisor`). An explanation only: the equations'
verdicts are decided by their equivalence.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping

import numpy as np
import sympy as sp

from ...derivations.schema import Derivation
from ..judge.common_divisor import common_divisor
from ..judge.draft import ElementDraft
from ..judge.own_inertia import length_bases
from ..judge.source_entry import source_entry
from ..judge.units import geometric_symbols
from ..judge.unsolved import inertia_diagnoses, read_back, unsolved_terms
from ..readings.frames import Frame, FrameKind, FrameRule, constant_weights
from ..records import Diagnosis
from ..sides.both import Sides
from ..sides.elements import swap_groups


def read_back_said(d: Derivation, drafts: list[ElementDraft], rules: list[FrameRule],
                   frames: list[Frame], on_id: list[Frame | None], id_sides: Sides, found,
                   combined: bool, truths: Callable[[], Mapping[str, sp.Expr] | None],
                   h_rows: np.ndarray | None = None) -> Diagnosis | None:
    r"""The document's equations read back before it solved or combined them, said on the
    elements of its rows that the frames show divided or combined (:func:`read_back`), and
    returned (None where none is found); ``truths()`` the truth's entries in the document's
    symbols, ``on_id`` the frames on the identification grid, ``found`` the names' values
    on it (:func:`~..judge.fitting.bases`; a body's own moment missing is named times a
    monomial of the document's lengths among them, as the elements of a form not solved
    are), ``h_rows`` the samples of the main grid h's velocity products are compared on.
    Where the frames show no combination, only a wrong entry of the source equations is looked for
    (:func:`source_entry`); the rows it shows combined in another way than their frames (the
    wrong entry in a combination's weight, eq1 − (d₁₂/d₂₂)·eq2, left every frame worse
    than the row as printed, or was taken into the frame's weights) are named by it alone."""
    solved, entry, inverted = None, None, None
    lengths = length_bases(found, geometric_symbols(d), d.positions)
    groups = swap_groups(d, id_sides.values)
    if combined:
        said = truths()
        inverted = inertia_diagnoses(id_sides, found, d.velocities, said, lengths, groups)
        solved = inverted or unsolved_terms(id_sides.doc, id_sides.truth, id_sides.B_true,
                                            d.velocities, found, said, groups)
        entry = None if solved is not None else source_entry(id_sides, found, d.velocities,
                                                              said, lengths, groups)
    else:                  # as printed but for rows it shows combined: else none read back
        entry = source_entry(id_sides, found, d.velocities, truths, lengths, groups)
        entry = entry if entry is not None and entry.combined else None
    if entry is not None:
        solved = entry.diagnosis
    shown = {i for i, r in enumerate(rules)
             if r.kind in (FrameKind.FUNCTION, FrameKind.COMBINATION)} if combined else set()
    if solved is None and combined:
        solved = common_divisor(drafts, shown, h_rows)
    if solved is None:
        return None
    varying = {i for i, f in enumerate(frames) if not constant_weights(f.weights)} \
        if combined else set()
    other = set() if entry is None else set(entry.other_frames(
        [None if f is None else f.weights for f in on_id]))
    # rows whose weights vary (solved): one wrong entry of the source equations (it alone
    # gives the document at every sample) is said in place of each element's own names —
    # those are what it became there (a term's sign in a solved row is the source's input
    # sign: one cause, not two); the inverted inertia read back wrong before them
    alone = other | (varying if entry is not None else set())
    read_back(drafts, shown | other, solved, varying | other, alone,
              varying if inverted is not None else set())
    return solved


__all__ = ["read_back_said"]
