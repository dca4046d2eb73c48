r"""Diagnoses of one element that differs, from its printed expression: a parameter to the
wrong power, one additive term with the wrong sign or factor, a sin written for a cos
(:mod:`.diagnose`), evaluated with the document's compiled functions on the engine's samples.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
import sympy as sp

from ..records import Diagnosis, DiagnosisKind as K, diagnosis
from .diagnose import (AGREE_TOL, MAX_TERMS, agrees, nice_number, plausible_factor,
                       expanded_terms, power_diagnoses, term_diagnoses, term_text,
                       trig_swap_diagnoses)
from .small_angle import small_angle_diagnoses
from ..sides.document import DocumentFunctions


#: Samples the readings of :func:`trig_diagnoses` are first tried on (spread over the
#: parameter sets): a reading that agrees at every sample agrees there, so where none does,
#: none is tried on every sample (most elements that differ have none).
TRIG_SCREEN = 128


def trig_diagnoses(expr: sp.Expr, funcs: DocumentFunctions, argv: Sequence[np.ndarray],
                    factor: float | None, D: np.ndarray, T: np.ndarray, scale: float,
                    check: bool = False) -> list[Diagnosis]:
    r"""A sin written for a cos in ``expr`` (:func:`.diagnose.trig_swap_diagnoses`), else a
    small-angle approximation (:func:`.small_angle.small_angle_diagnoses`), the document's
    values divided by its row ``factor``. ``check``: only when ``expr`` evaluated on ``argv``
    gives the element's own values ``D`` (a velocity product's coefficient is sampled on its
    own grid). Tried on :data:`TRIG_SCREEN` samples first, on every sample only where a
    reading agrees there."""
    size = len(D)

    def reader(rows: np.ndarray | None) -> Callable[[list], list[np.ndarray]]:
        at = argv if rows is None else [x[rows] if np.ndim(x) and len(x) == size else x
                                         for x in argv]
        c = 1.0 if factor is None else factor if rows is None or not np.ndim(factor) \
            else np.asarray(factor)[rows]
        shape = np.shape(at[0])

        def evaluate_many(exprs: list) -> list[np.ndarray]:
            return [np.broadcast_to(np.asarray(v, float), shape) / c
                    for v in funcs.compiled(tuple(exprs))(*at)]
        return evaluate_many

    def readings(rows: np.ndarray | None) -> list[Diagnosis]:
        few, target = reader(rows), T if rows is None else T[rows]
        return trig_swap_diagnoses(expr, few, target, scale) or small_angle_diagnoses(
            expr, funcs.angles(), few, target, scale)
    if len(np.shape(argv[0])) != 1 or np.shape(argv[0])[0] != size:
        return []
    if check and not agrees(reader(None)([expr])[0], D, scale):
        return []
    screen = np.linspace(0, size - 1, min(size, TRIG_SCREEN)).astype(int)
    if len(screen) < size and not readings(screen):
        return []
    return readings(None)


def element_term_diagnoses(expr: sp.Expr, funcs: DocumentFunctions, argv: Sequence[np.ndarray],
                    factor: float | None, D: np.ndarray, T: np.ndarray, scale: float,
                    has_factor: bool) -> list[Diagnosis]:
    r"""A parameter to the wrong power (also where a constant factor fits: with a geometry
    constant the sets do not vary, G for G² *is* a factor), then, when the element has no
    diagnosis yet, one additive term with the wrong sign or factor, then a sin written for a
    cos (:mod:`.diagnose`) or a small angle (:mod:`.small_angle`)."""
    c = 1.0 if factor is None else factor

    def evaluate(e: sp.Expr) -> np.ndarray:
        with np.errstate(all="ignore"):           # a trial power may leave the reals: NaN
            out = funcs.compiled(e)(*argv)
        return np.broadcast_to(np.asarray(out, float), D.shape) / c

    compiled, position = funcs.compiled(expr), funcs.args.index

    def powered(s: sp.Symbol, k) -> np.ndarray:
        trial = list(argv)
        with np.errstate(all="ignore"):           # a trial power may leave the reals: NaN
            trial[position(s)] = np.asarray(trial[position(s)], float) ** float(k)
            out = compiled(*trial)
        return np.broadcast_to(np.asarray(out, float), D.shape) / c

    def at_zero(s: sp.Symbol) -> np.ndarray:
        trial = list(argv)
        with np.errstate(all="ignore"):           # a term divided by s: not finite
            trial[position(s)] = np.zeros_like(np.asarray(trial[position(s)], float))
            out = compiled(*trial)
        return np.broadcast_to(np.asarray(out, float), D.shape) / c

    found = power_diagnoses(expr, funcs.params, evaluate, T, scale, powered, at_zero)
    if not found and not has_factor:
        found = term_diagnoses(expr, evaluate, D, T, scale) or \
            many_term_diagnoses(expr, funcs, argv, c, D, T, scale)
    if not found and not has_factor:
        found = trig_diagnoses(expr, funcs, argv, factor, D, T, scale)
    return found


#: Most terms of an element (expanded) among which one with the wrong sign or factor is
#: looked for all at once (a derivation written from a URDF with rotated frames: a hundred
#: terms with decimal coefficients).
MAX_MANY_TERMS = 600


def many_term_diagnoses(expr: sp.Expr, funcs: DocumentFunctions, argv: Sequence[np.ndarray],
                        c: float, D: np.ndarray, T: np.ndarray, scale: float
                        ) -> list[Diagnosis]:
    r"""One additive term :math:`t` of an element of more than :data:`~.diagnose.MAX_TERMS`
    terms with the wrong sign or a constant factor (:math:`T = D + k\,t`: :math:`k = -2` a
    sign, else the term is :math:`1/(1 + k)` × what fits), every term evaluated in one
    compiled function and :math:`k` fitted to each by least squares; only where exactly one
    term fits at every sample (two equal terms: nothing is said). ``c``: the row's factor."""
    from ...compiled import numpy_function
    expanded = expanded_terms(expr)
    if not MAX_TERMS < len(expanded) <= MAX_MANY_TERMS:
        return []
    with np.errstate(all="ignore"):
        V = np.stack([np.broadcast_to(np.asarray(v, float), D.shape)
                      for v in numpy_function(funcs.args, list(expanded))(*argv)]) / c
    if not np.isfinite(V).all():
        return []
    tt = np.einsum("ks,ks->k", V, V)
    usable = np.sqrt(tt) > AGREE_TOL * scale * np.sqrt(len(D))   # (scale² overflowed)
    k = V @ (T - D) / np.where(usable, tt, 1.0)
    off = np.abs(D[None, :] + k[:, None] * V - T[None, :]).max(axis=1)
    hits = np.flatnonzero(usable & (off <= AGREE_TOL * scale) & (np.abs(1 + k) > 1e-12))
    if len(hits) != 1:
        return []
    term, fit = term_text(expanded[hits[0]]), float(k[hits[0]])
    if abs(fit + 2) <= 1e-9:
        return [diagnosis(K.SIGN, f"the term {term} has the wrong sign", term=term,
                          factor="-1")]
    if not plausible_factor(1 / (1 + fit)):
        return []
    times = nice_number(1 / (1 + fit))
    return [diagnosis(K.FACTOR, f"the term {term} is {times} × what fits", term=term,
                      factor=times)]


def product_diagnoses(expr: sp.Expr, funcs: DocumentFunctions, argv: Sequence[np.ndarray],
                      D: np.ndarray, T: np.ndarray, scale: float) -> list[Diagnosis]:
    r"""A velocity product's coefficient in h that differs: one of its terms with the wrong
    sign or factor (:func:`.diagnose.term_diagnoses`: a term :math:`2J_{zz}\sin\alpha\cos\alpha`
    with the wrong sign was "1.02 × the truth if the pendulum is uniform"), else a sin for a
    cos or a small angle; only where ``expr`` evaluated on ``argv`` gives ``D`` (a product's
    coefficient is sampled on its own grid)."""
    if len(np.shape(argv[0])) != 1 or np.shape(argv[0])[0] != len(D):
        return []

    def evaluate(e: sp.Expr) -> np.ndarray:
        return np.broadcast_to(np.asarray(funcs.compiled(e)(*argv), float), D.shape)
    if not agrees(evaluate(expr), D, scale):
        return []
    return term_diagnoses(expr, evaluate, D, T, scale) or trig_diagnoses(
        expr, funcs, argv, None, D, T, scale)


def undivided_term_diagnoses(expr: sp.Expr, evaluate: Callable[[sp.Expr], np.ndarray],
                             D: np.ndarray, T: np.ndarray, scale: float,
                             factor: np.ndarray) -> list[Diagnosis]:
    r"""One additive term :math:`t` of an element (or the element, one term) of a row that is
    the true equation times a ``factor`` :math:`f` varying from sample to sample (a row
    divided by its inertia) left out of it: :math:`D + (f - 1)\,t = T` (the document divided
    the rest of the row and not this term), or given it twice, :math:`D + (1/f - 1)\,t = T`."""
    if np.ptp(factor) <= 1e-9 * float(np.abs(factor).max(initial=0.0)) or \
            not np.all(np.isfinite(factor)) or not np.all(factor != 0):
        return []
    expanded = expanded_terms(expr)
    if len(expanded) > MAX_TERMS:
        return []
    for t in dict.fromkeys((*expanded, *sp.Add.make_args(expr), expr)):   # or all of it
        tv = np.broadcast_to(np.asarray(evaluate(t), float), D.shape)
        if agrees(D + (factor - 1) * tv, T, scale):
            return [diagnosis(K.FACTOR, f"the term {sp.sstr(t)} is not divided as the rest of "
                              "its row is (the row is the true equation times a factor; this "
                              "term is the true one's without it)", term=sp.sstr(t))]
        if agrees(D + (1 / factor - 1) * tv, T, scale):
            return [diagnosis(K.FACTOR, f"the term {sp.sstr(t)} is divided twice (the row is "
                              "the true equation times a factor; this term is the true one's "
                              "times it twice)", term=sp.sstr(t))]
    return []


__all__ = ["element_term_diagnoses", "product_diagnoses", "trig_diagnoses",
           "undivided_term_diagnoses"]
