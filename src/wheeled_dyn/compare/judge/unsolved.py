r"""Equations solved for the accelerations, read back before solving.

A document that writes :math:`\ddot q = M_{doc}^{-1}(B u - n_{doc})` (simulation code does),
or solves part of its equations, hides its inertia matrix in every element; an error in it (a
dropped inertia, a symbol for another in :math:`M_{doc}`) changes all of them. When the inputs
act on every coordinate (B square and invertible), the document's own inertia matrix, in the
true equations' frame, is read back from its inputs' coefficients: its equations
:math:`A_{doc}\ddot q + n_{doc} = B_{doc}u` are :math:`BB_{doc}^{-1}` times a system whose
inputs enter as the truth's, with the inertia matrix

.. math:: M_{doc} = B\,B_{doc}^{-1}A_{doc}

and compared with the truth's A element by element; a differing element is named in the
document's symbols (:mod:`.fitting`: "A[1,1] lacks I1"). With fewer inputs than coordinates,
the weights :math:`W` are fitted to the inputs', gravity and velocity terms' coefficients
together, :math:`W[B\;Q\;H] = [B_{doc}\;Q_{doc}\;H_{doc}]` (more columns than coordinates:
where a term of those is wrong no W fits them all, and the inertia is not blamed), and
:math:`M_{doc} = W^{-1}A_{doc}`. This only explains: the equations' verdicts are decided by
their equivalence.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import sympy as sp

from ..records import Diagnosis, DiagnosisKind as K, Verdict, has_kind
from .diagnose import AGREE_TOL
from .common_divisor import divisor_diagnosis, function_factor
from .draft import ElementDraft
from .entry_terms import Part, entry_part, read_back_diagnosis
from .named import NAMED
from .own_inertia import grid_inertia


def solved_for(row: np.ndarray) -> tuple[int, float] | None:
    r"""Where one row of a document's A (S × n) has one constant nonzero entry,
    :math:`c\,e_k` at every sample (the row solved for acceleration k, its own or another's):
    ``(k, c)``; else None."""
    size = np.abs(row).max(axis=0)
    nonzero = np.flatnonzero(size > 1e-12 * max(float(size.max(initial=0.0)), 1e-300))
    if len(nonzero) == 1 and np.ptp(row[:, nonzero[0]]) <= 1e-12 * size[nonzero[0]]:
        return int(nonzero[0]), float(row[0, nonzero[0]])
    return None


def implied_inertia(doc_B: np.ndarray, true_B: np.ndarray) -> np.ndarray | None:
    r""":math:`M_{doc} = B B_{doc}^{-1}` per sample, or None (B not square, or singular)."""
    if doc_B.shape[1] != doc_B.shape[2] or true_B.shape != doc_B.shape:
        return None
    if not (np.isfinite(doc_B).all() and np.isfinite(true_B).all()):
        return None
    if (np.abs(np.linalg.det(doc_B)) <= 1e-12 * np.abs(doc_B).max(axis=(1, 2)) ** doc_B.shape[1]
            ).any():
        return None
    return true_B @ np.linalg.inv(doc_B)


def term_columns(arrays, B: np.ndarray | None, rows: np.ndarray) -> np.ndarray | None:
    r"""The coefficients of the inputs, the gravity terms and each velocity product
    (:math:`H_{jl} + H_{lj}`) of every equation on the samples ``rows``, then a linearised
    document's stiffness K (its columns, where given): samples × n × columns; None where one
    of them is not given (H: on those samples)."""
    if arrays.Q is None or arrays.H is None or len(arrays.H) != len(rows):
        return None
    H = arrays.H
    n = H.shape[1]
    # no inputs (a passive body): none of their columns
    inputs = B[rows] if B is not None else np.zeros((len(rows), n, 0))
    products = [H[:, :, j, j] if j == m else H[:, :, j, m] + H[:, :, m, j]
                for j in range(n) for m in range(j, n)]
    stiffness = [] if arrays.K is None else [arrays.K[rows]]
    return np.concatenate([inputs, arrays.Q[rows][:, :, None],
                           np.stack(products, axis=2), *stiffness], axis=2)


def _spans(C: np.ndarray) -> bool:
    r"""Whether the columns of ``C`` (samples × n × columns) span :math:`\mathbb{R}^n` at every
    sample."""
    n = C.shape[1]
    if C.shape[2] < n:
        return False
    sv = np.linalg.svd(C, compute_uv=False)
    return bool((sv[:, n - 1] > 1e-9 * sv[:, 0]).all())


def source_weights(doc, truth, true_B: np.ndarray | None) -> tuple[np.ndarray, np.ndarray] | None:
    r"""(W, samples): the weights :math:`W` with which the document's equations are
    :math:`W` times equations whose inputs, gravity and velocity terms are the truth's
    (:math:`W[B\;Q\;H] = [B_{doc}\;Q_{doc}\;H_{doc}]` per sample, by least squares), on the
    samples where H is known; None where they do not determine W with every column left
    out in turn (the cart-pole's gravity term alone carries its pole's row: a sin written
    for a cos there was read as a wrong inertia) or no W fits every column (a term of those
    is wrong itself: then it is not the inertia)."""
    rows = truth.H_rows if truth.H_rows is not None else np.arange(len(truth.need("A")))
    if doc.H is None or doc.H.shape[0] != len(rows):
        return None
    C_true, C_doc = term_columns(truth, true_B, rows), term_columns(doc, doc.B, rows)
    if C_true is None or C_doc is None or C_true.shape != C_doc.shape:
        return None
    if not (np.isfinite(C_true).all() and np.isfinite(C_doc).all()):
        return None
    if not all(_spans(np.delete(C_true, k, axis=2)) for k in range(C_true.shape[2])):
        return None                    # a column W rests on alone: an error in it is not seen
    W = np.swapaxes(np.linalg.pinv(np.swapaxes(C_true, 1, 2)) @ np.swapaxes(C_doc, 1, 2), 1, 2)
    scale = max(float(np.abs(C_doc).max()), 1e-300)
    if np.abs(W @ C_true - C_doc).max() > AGREE_TOL * scale:
        return None
    return W, rows


def inertia_diagnoses(sides, bases: Sequence[tuple[sp.Expr, np.ndarray]],
                      velocities: Sequence[sp.Symbol] = (),
                      truths: Mapping[str, sp.Expr] | None = None,
                      lengths: Sequence[tuple[sp.Expr, np.ndarray]] = (),
                      groups: Sequence[Sequence[sp.Symbol]] = ()) -> Diagnosis | None:
    r"""The elements of the document's own inertia matrix (read back from its inputs,
    module text; where its inputs are fewer than its coordinates, from its inputs, gravity
    and velocity terms, :func:`source_weights`) that differ from the truth's, named (a
    link's own moment missing: a point mass); None when all agree or it cannot be read back.
    Read back from its inputs, the inertia must be symmetric (an input exchanged, of the
    wrong sign or scaled reads back as none), and not the truth's times one number (every
    input of the wrong sign, or scaled: nothing tells that from an inertia so scaled with
    every term too); the equations' other entries so read back are named beside it where at
    most :data:`MAX_UNSOLVED` differ (a term wrong beside the inertia), else nothing is said.
    ``sides``: both sides on a grid (:class:`~..sides.both.Sides`), ``lengths`` the bases of
    the document's lengths (:func:`~.own_inertia.length_bases`), ``groups`` the symbols of
    one kind (:func:`~.entry_terms.entry_part`)."""
    doc, truth, true_B = sides.doc, sides.truth, sides.B_true
    doc_A, true_A = doc.A, truth.need("A")
    own = grid_inertia([ps.values for ps in sides.grid.sets], len(true_A), lengths)
    n = doc_A.shape[1]
    if not np.isfinite(doc_A).all():
        return None
    # a passive body (no inputs on either side): from its gravity and velocity terms alone
    T = None if doc.B is None or true_B is None else implied_inertia(doc.B, true_B)
    how = "its inputs' coefficients, M = B B_doc⁻¹ A_doc"
    extra: list[tuple[str, np.ndarray, np.ndarray, float, bool]] = []
    if T is not None:
        M = T @ doc_A
        size = max(float(np.abs(M).max(initial=0.0)), 1e-300)
        if np.abs(M - np.swapaxes(M, 1, 2)).max() > AGREE_TOL * size or _scaled(M, true_A):
            return None                     # no inertia matrix: the inputs are not the truth's
        extra = _entries(doc, truth, true_B, velocities, T) or []
        if len(extra) > MAX_UNSOLVED:
            return None
    elif (found := source_weights(doc, truth, true_B)) is not None:
        W, rows = found
        try:
            M = np.linalg.inv(W) @ doc_A[rows]
        except np.linalg.LinAlgError:
            return None
        true_A, bases = true_A[rows], [(e, v[rows]) for e, v in bases]
        own = own.at(rows)
        how = ("its inputs', gravity and velocity terms' coefficients: W [B Q H] = "
               "[B_doc Q_doc H_doc], M = W⁻¹ A_doc")
    else:
        return None
    # one divisor of every solved row: its determinant (of one coordinate, the inertia itself:
    # its terms are named below)
    k = function_factor(M, true_A) if n > 1 else None
    if k is not None:
        return divisor_diagnosis(k, f"the inertia matrix the document inverted (read back "
                                    f"from {how}) is the truth's")
    scale = float(np.abs(true_A).max())
    parts = [entry_part(f"A[{i + 1},{j + 1}]", true_A[:, i, j], M[:, i, j], scale, bases,
                        own, truths, groups)
             for i in range(n) for j in range(n)
             if np.abs(true_A[:, i, j] - M[:, i, j]).max() > AGREE_TOL * scale]
    if not parts:
        return None
    return read_back_diagnosis(
        f"the inertia matrix the document inverted (read back from {how}) differs from the "
        "truth's: ", parts + _named(extra, truth, bases, truths, groups))


def whole_factor(T: np.ndarray, D: np.ndarray) -> float | None:
    r"""The number :math:`c` with ``D`` = c ``T`` wherever ``T`` is not negligible (every
    entry of an array of any shape: the same one number), or None."""
    big = np.abs(T) > 1e-9 * float(np.abs(T).max(initial=0.0))
    if not big.any():
        return None
    ratio = D[big] / T[big]
    c = float(np.median(ratio))
    return c if c != 0.0 and float(np.abs(ratio - c).max()) <= AGREE_TOL * abs(c) else None


def _scaled(M: np.ndarray, true_A: np.ndarray) -> bool:
    r"""Whether ``M`` is the true inertia times one number other than 1 (the inputs of the
    wrong sign or scaled, all of them: an inertia c A inverted and inputs and terms c × the
    truth's read the same, and nothing tells them apart)."""
    c = whole_factor(true_A, M)
    return c is not None and abs(c - 1.0) > AGREE_TOL


def _named(entries, truth, bases: Sequence[tuple[sp.Expr, np.ndarray]],
           truths: Mapping[str, sp.Expr] | None = None,
           groups: Sequence[Sequence[sp.Symbol]] = ()) -> list[Part]:
    r"""The differing ``entries`` of :func:`_entries`, named in the document's symbols."""
    rows = truth.H_rows
    at = [(e, v[rows]) for e, v in bases] if rows is not None else []
    return [entry_part(where, t, v, scale, at if on_rows else bases, None, truths, groups)
            for where, t, v, scale, on_rows in entries]


#: Most differing entries of the equations read back before solving for them to be named
#: (one term wrong in the source equations changes one or two; an inertia matrix the document
#: inverted wrong changes every one, and the true one does not undo it).
MAX_UNSOLVED = 3




def _undo(true_A: np.ndarray, doc_A: np.ndarray) -> np.ndarray | None:
    r""":math:`A A_{doc}^{-1}` per sample (the document's rows back to the true equations'
    frame), or None where the document's A is singular somewhere."""
    try:
        return true_A @ np.linalg.inv(doc_A)
    except np.linalg.LinAlgError:
        return None


def _entries(doc, truth, true_B: np.ndarray | None, velocities: Sequence[sp.Symbol] = (),
             T: np.ndarray | None = None
             ) -> list[tuple[str, np.ndarray, np.ndarray, float, bool]] | None:
    r"""The entries of the document's equations read back before it solved or combined them
    (its rows times :math:`AA_{doc}^{-1}`, or ``T`` given) that differ from the truth's:
    (where, truth, document, scale, on ``H_rows``) — of its gravity and velocity terms and a
    linearised document's stiffness; None
    where it cannot be read back or its inputs' coefficients then differ from the truth's
    (the inertia it inverted is not the truth's)."""
    if doc.A is None or truth.A is None or not np.isfinite(doc.A).all():
        return None
    given = T is not None
    T = T if T is not None else _undo(truth.A, doc.A)
    if T is None:
        return None
    n = doc.A.shape[1]
    out = []
    if doc.B is not None and true_B is not None and not given:
        B = np.einsum("ski,sij->skj", T, doc.B)
        if np.abs(true_B - B).max() > AGREE_TOL * max(float(np.abs(true_B).max()), 1e-300):
            return None
    if doc.Q is not None and truth.Q is not None:
        Q = np.einsum("ski,si->sk", T, doc.Q)
        scale = float(np.abs(truth.Q).max())
        out += [(f"Q[{k + 1}]", truth.Q[:, k], Q[:, k], scale, False) for k in range(n)
                if np.abs(truth.Q[:, k] - Q[:, k]).max() > AGREE_TOL * scale]
    if doc.K is not None and truth.K is not None:     # a linearised document's stiffness
        K = np.einsum("ski,sij->skj", T, doc.K)
        scale = float(np.abs(truth.K).max())
        out += [(f"K[{k + 1},{j + 1}]", truth.K[:, k, j], K[:, k, j], scale, False)
                for k in range(n) for j in range(n)
                if np.abs(truth.K[:, k, j] - K[:, k, j]).max() > AGREE_TOL * scale]
    rows = truth.H_rows
    if doc.H is not None and truth.H is not None and rows is not None:
        H = np.einsum("ski,sijl->skjl", T[rows], doc.H)
        scale = float(np.abs(truth.H).max())
        for k in range(n):
            for j in range(n):
                for m in range(j, n):
                    both = 1 if j == m else 2
                    t, v = truth.H[:, k, j, m] * both, H[:, k, j, m] * both
                    if np.abs(t - v).max() > AGREE_TOL * scale:
                        product = (f"{velocities[j]}*{velocities[m]}" if velocities
                                   else f"{j},{m}")
                        out.append((f"h[{k + 1}]:{product}", t, v, scale, True))
    return out


def unsolved_terms(doc, truth, true_B: np.ndarray | None, velocities: Sequence[sp.Symbol],
                   bases: Sequence[tuple[sp.Expr, np.ndarray]],
                   truths: Mapping[str, sp.Expr] | None = None,
                   groups: Sequence[Sequence[sp.Symbol]] = ()) -> Diagnosis | None:
    r"""A document solved for its accelerations (or its rows combined), read back before it
    was: its rows times :math:`AA_{doc}^{-1}` (``doc``, ``truth``: arrays on the same
    samples, A, Q, B and the products' tensor H on ``H_rows``). Where that undoes it — its
    inputs' coefficients are then the truth's — the few terms of the velocity products,
    gravity terms and inputs of the equations it solved that differ are named in its
    symbols (a sign in one h term changed all three solved rows, and none was named); where
    its inputs' coefficients differ too or more than :data:`MAX_UNSOLVED` entries do, the
    inertia it inverted is not the truth's and nothing is said here."""
    entries = _entries(doc, truth, true_B, velocities)
    if not entries or len(entries) > MAX_UNSOLVED:
        return None
    return read_back_diagnosis(
        "read back before it was solved or combined (its rows times A A_doc⁻¹: its inputs' "
        "coefficients are then the truth's), the equations differ: ",
        _named(entries, truth, bases, truths, groups))


def read_back_explains(doc, truth, true_B: np.ndarray | None) -> bool:
    r"""Whether the document's equations, read back before it solved or combined them
    (:func:`unsolved_terms`), have the truth's inputs' coefficients and differ from the truth
    in one to :data:`MAX_UNSOLVED` other entries, fewer than the equations as printed do:
    then each row is :math:`A_{doc,i}A^{-1}` times such equations, a combination the form
    says (its inputs, stated, confirm it). A document written plainly with one inertia wrong
    differs as printed in that entry alone, and read back in its gravity or velocity terms
    instead: it is not read back (its rows' frames would hide the inertia's error)."""
    if doc.B is None or true_B is None or not np.abs(true_B).max(initial=0.0) > 0:
        return False
    entries = _entries(doc, truth, true_B)
    return entries is not None and 0 < len(entries) <= MAX_UNSOLVED and \
        len(entries) < _as_printed(doc, truth, true_B)


def _as_printed(doc, truth, true_B: np.ndarray) -> int:
    r"""The entries of the document's A, B, gravity and velocity terms that differ from the
    truth's as printed (each row read as the true one)."""
    assert doc.A is not None and doc.B is not None
    same = np.broadcast_to(np.eye(doc.A.shape[1]), doc.A.shape)
    out = len(_entries(doc, truth, true_B, T=same) or [])
    for mine, theirs in ((doc.A, truth.need("A")), (doc.B, true_B)):
        if mine.shape != theirs.shape:
            return 10 ** 9                  # no entry-wise reading: anything is fewer
        scale = max(float(np.abs(theirs).max(initial=0.0)), 1e-300)
        out += int((np.abs(mine - theirs).max(axis=0) > AGREE_TOL * scale).sum())
    return out


#: An element's own diagnoses that name its error where the document solved or combined its
#: equations (its terms "too much" or missing in that frame do not: a term dropped before
#: solving shows there as terms the document has too much).
STRONG = tuple(k for k in (*NAMED, K.FACTOR) if k != K.EXTRA)


def read_back(drafts: Sequence[ElementDraft], rows: set[int], found: Diagnosis | None,
              varying: set[int] | frozenset[int] = frozenset(),
              alone: set[int] | frozenset[int] = frozenset(),
              first: set[int] | frozenset[int] = frozenset()) -> None:
    r"""``found`` (:func:`inertia_diagnoses` or :func:`unsolved_terms`: the document's
    equations read back before it solved or combined them) said first on each element of
    those ``rows`` (divided by a function or combined) that differs and that no diagnosis
    names yet (none of :data:`STRONG`) — in the rows ``varying`` (their weights functions of
    the state: solved) in place of its own terms missing or too much there: one wrong term
    of the source equations lands in every solved element it reaches, in a rational function
    of every parameter, and is named where the author wrote it (a row combined with numbers,
    eq1 − eq2, keeps its own: its terms are the author's); in the rows ``alone`` (their
    frames not the author's combination) in place of every name of its own; in the rows
    ``first`` (solved, the inertia the document inverted read back wrong) before every name of
    its own, which stay after it (a12's sign before solving is each solved element's "opposite
    sign"). An explanation only: no verdict changes."""
    if found is None:
        return
    for r in drafts:
        if r.row in alone and r.verdict == Verdict.DIFFERS and r.key != "C":
            r.diagnoses[:] = [found, *(x for x in r.diagnoses if x.kind not in (*STRONG, K.EXTRA,
                                                                                K.MISSING))]
        elif r.row in first and r.verdict == Verdict.DIFFERS and r.key != "C":
            r.diagnoses[:] = [found, *r.diagnoses]
        elif r.row in rows and r.verdict == Verdict.DIFFERS and r.key != "C" \
                and not has_kind(r.diagnoses, *STRONG):
            # its own terms missing or too much in the solved frame are what the source's
            # error became there, not its name (a term too much before solving was "lacks −t")
            weak = (K.MISSING, K.EXTRA) if r.row in varying else ()
            r.diagnoses[:] = [found, *(x for x in r.diagnoses if x.kind not in weak)]


__all__ = ["MAX_UNSOLVED", "STRONG", "term_columns", "implied_inertia", "inertia_diagnoses",
           "read_back", "read_back_explains", "solved_for",
           "unsolved_terms", "whole_factor"]
