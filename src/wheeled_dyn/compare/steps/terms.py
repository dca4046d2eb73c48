r"""A differing step component diagnosed term by term: the truth's coefficient of each
monomial of the velocities and accelerations (:func:`truth_coefficients`, from the truth at
unit velocities and accelerations, :math:`b_{jk} = F(e_j+e_k) - F(e_j) - F(e_k) + F(0)`)
against the document's, a relation's right side that is a constant times its left, and a
linearised relation's coefficients against the ones its residual needs."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import sympy as sp

from ...derivations.steps import VECTOR_KINDS, Step
from ..judge.diagnose import (agrees, nice_number, power_diagnoses, term_diagnoses,
                              value_diagnoses)
from ..records import Diagnosis, DiagnosisKind as K, diagnosis, in_product
from ..sides.kinematics import Motion
from .group import DECOMPOSE_STATES, StepGroup


#: Kinds whose components are polynomial in the velocities and accelerations (decomposable).
_TERMED = (*VECTOR_KINDS, "kinetic energy", "generalized force")


def _monomial_name(mono: tuple[int, ...], names: Sequence[sp.Symbol]) -> str:
    parts = [str(s) for s, e in zip(names, mono) for _ in range(e)]
    return "*".join(parts) if parts else "1"


#: A difference no single-term diagnosis names.
_DIFFERS = diagnosis(K.NOTE, "differs", prefix="")


def _terms(expr: sp.Expr, gens: Sequence[sp.Symbol]) -> dict[tuple[int, ...], sp.Expr] | None:
    try:
        return {m: c for m, c in sp.Poly(sp.expand(expr), *gens).terms()}
    except sp.PolynomialError:
        return None


def power_swaps(expr: sp.Expr, g: StepGroup, T: np.ndarray, scale: float
                ) -> list[Diagnosis]:
    return power_diagnoses(expr, g.params, g.document, T, scale)


def side_factor(g: StepGroup, sides: tuple[sp.Expr, sp.Expr], scale: float) -> list[Diagnosis]:
    r"""A relation whose right side is a constant c times what the left side is on the
    model's motions: the true relation has the right side divided by c."""
    L, R = (g.document(g.rate(x)) for x in sides)
    if float(L @ L) <= 0 or float(R @ R) <= 0:
        return []
    c = float(R @ L / (L @ L))
    if not agrees(R, c * L, scale):
        return []
    true = sp.nsimplify(sides[1] / sp.nsimplify(nice_number(c)))
    return [diagnosis(K.FACTOR, f"the right side is {nice_number(c)} × what the left side is "
                      f"on the model's motions; true: {sp.sstr(sides[0])} = {sp.sstr(true)}",
                      factor=nice_number(c))]


def linear_term_diagnoses(g: StepGroup, expr: sp.Expr) -> list[Diagnosis]:
    r"""A linearised relation :math:`\sum c_a\Delta\dot\nu_a + \sum c_x\Delta x` that does
    not hold: its residual on the true deviations is :math:`\sum\kappa_x\Delta x`
    (:math:`\kappa` fitted per parameter set over every deviation when the samples suffice,
    else over those the relation names); the document's :math:`c_x` (0 for a deviation it
    lacks) against the needed :math:`c_x - \kappa_x`."""
    d = g.d
    everything = [*d.positions, *d.velocities]
    # every deviation when the samples of a set determine the fit (a dropped term is named),
    # else those the relation names
    xs = everything if g.N >= len(everything) + 2 else [x for x in everything if expr.has(x)]
    if not xs:
        return []
    R = g.document(expr)
    X = np.stack(g.documents(xs), 1)
    kappa = np.zeros_like(X)
    for k in range(len(g.sets)):
        rows = slice(k * g.N, (k + 1) * g.N)
        fit = np.linalg.lstsq(X[rows], R[rows], rcond=None)[0]
        if not agrees(X[rows] @ fit, R[rows], float(np.abs(R).max(initial=0.0))):
            return []                   # the residual needs deviations the relation lacks
        kappa[rows] = fit
    out = []
    coefficients = g.documents([expr.diff(x) for x in xs])
    scale = max(max(float(np.abs(c).max(initial=0.0)),
                    float(np.abs(c - kappa[:, i]).max(initial=0.0)))
                for i, c in enumerate(coefficients))
    for i, (x, c) in enumerate(zip(xs, coefficients)):
        needed = c - kappa[:, i]
        if not agrees(c, needed, scale):
            why = value_diagnoses(c, needed, scale) or [_DIFFERS]
            out.append(in_product(str(x), why[0]))
    return out


def monomial_diagnoses(g: StepGroup, step: Step, j: int, expr: sp.Expr, scale: float
                    ) -> list[Diagnosis]:
    d = g.d
    gens = [*d.velocities, *d.accelerations]
    if step.kind not in _TERMED or (g.cs.kind == "holonomic" and g.cs.rolling == "multipliers"):
        return []
    doc = _terms(expr, gens)
    if doc is None:
        return []
    n = len(d.velocities)
    if step.kind in ("velocity", "angular velocity"):
        candidates = [tuple(int(i == j2) for i in range(2 * n)) for j2 in range(n)]
    else:
        candidates = [tuple(int(i == n + j2) for i in range(2 * n)) for j2 in range(n)]
        candidates += [tuple(int(i == a) + int(i == b) for i in range(2 * n))
                       for a in range(n) for b in range(a, n)]
    monos = list(dict.fromkeys([*candidates, *doc]))
    truth = truth_coefficients(g, step, monos)
    rows = sample_rows(g)
    docs = g.documents([doc.get(m, sp.Integer(0)) for m in monos], rows)
    values = {m: (D, truth[m][:, j]) for m, D in zip(monos, docs)}
    cscale = max([float(np.abs(v).max(initial=0.0)) for pair in values.values() for v in pair]
                 + [1e-300])
    out = []
    for m, (D, T) in values.items():
        if not np.all(np.isfinite(T)) or agrees(D, T, cscale):
            continue
        why = value_diagnoses(D, T, cscale) or term_diagnoses(
            doc.get(m, sp.Integer(0)), lambda e: g.documents([e], rows)[0], D, T, cscale) or \
            [_DIFFERS]
        out.append(in_product(_monomial_name(m, gens), why[0]))
    return out


def explained(diagnoses: Sequence[Diagnosis]) -> bool:
    r"""A diagnosis that names the error already (the whole component of the wrong sign or
    factor, a term of the wrong sign or factor, a swapped symbol, a power, a dimension): no
    special family is searched then. A missing or extra term is not enough: it may be what a
    special family removes (a centre of mass off the axis)."""
    return any(x.kind in (K.SIGN, K.FACTOR) or (not x.product and x.kind in (
        K.SWAP, K.POWER, K.DIMENSION)) for x in diagnoses)


def truth_coefficients(g: StepGroup, step: Step, monomials: Sequence[tuple[int, ...]]
                       ) -> dict:
    r"""The truth's coefficient of each monomial (exponents over velocities then
    accelerations) on the first :data:`DECOMPOSE_STATES` states of each set."""
    n = len(g.cs.positions)
    out: dict[tuple[int, ...], list[np.ndarray]] = {m: [] for m in monomials}
    for k, ps in enumerate(g.sets):
        g.cmap.bind(ps.model)
        data = ps.model.model.createData()
        for i in range(k * g.N, k * g.N + min(DECOMPOSE_STATES, g.N)):
            cache: dict[tuple, np.ndarray] = {}

            def F(nu, nudot):
                key = (*nu, *nudot)
                if key not in cache:
                    m = Motion(g.cmap, data, g.q[i], np.array(nu, float),
                               np.array(nudot, float), admissible=False)
                    cache[key] = g.true_value(step, m, k)
                return cache[key]

            zero = (0.0,) * n
            unit = [tuple(float(j == i2) for i2 in range(n)) for j in range(n)]
            c = F(zero, zero)
            for mono in monomials:
                vel, acc = mono[:n], mono[n:]
                idx = [j for j, e in enumerate(vel) for _ in range(e)]
                if sum(acc) == 1 and not idx:
                    val = F(zero, unit[acc.index(1)]) - c
                elif len(idx) == 1 and not sum(acc):
                    j = idx[0]
                    val = (F(unit[j], zero) - F(tuple(-x for x in unit[j]), zero)) / 2
                elif len(idx) == 2 and not sum(acc) and idx[0] == idx[1]:
                    j = idx[0]
                    val = (F(unit[j], zero) + F(tuple(-x for x in unit[j]), zero)) / 2 - c
                elif len(idx) == 2 and not sum(acc):
                    j, l = idx
                    both = tuple(a + b for a, b in zip(unit[j], unit[l]))
                    val = F(both, zero) - F(unit[j], zero) - F(unit[l], zero) + c
                elif not idx and not sum(acc):
                    val = c
                else:
                    val = np.full(len(c), np.nan)     # not a term the truth can have
                out[mono].append(val)
    return {m: np.array(v) for m, v in out.items()}


def sample_rows(g: StepGroup) -> np.ndarray:
    return np.concatenate([np.arange(k * g.N, k * g.N + min(DECOMPOSE_STATES, g.N))
                           for k in range(len(g.sets))])
