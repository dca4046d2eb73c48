r"""Newton–Euler balances of a document (``kind = "newton-euler"`` steps) against the body's
true motion.

A balance is printed as a relation between the applied forces (document symbols, ``free =
true``: tyre forces, a hinge's reaction) and the body's accelerations: "−F_hr − F_hl = m ẍ_g",
"−F_x a cos θ − F_y a sin θ = I_g θ̈". Of a rigid body of mass :math:`m`, centre of mass
:math:`G`, central inertia :math:`I_G`, angular velocity :math:`\omega`, with forces
:math:`F_k d_k` at points :math:`p_k` and couples :math:`C_k c_k`, the six Newton–Euler
residuals, moments about a point :math:`P` of the body, are

.. math::

    E(\dot\nu, F) = \begin{bmatrix} m a_G - m g - \sum_k F_k d_k \\
      I_G\dot\omega + \omega\times I_G\omega + (G - P)\times(m a_G - m g)
      - \sum_k (p_k - P)\times F_k d_k - \sum_k C_k c_k \end{bmatrix} ,

affine in the accelerations :math:`\dot\nu` (through :math:`a_G, \dot\omega`) and in the
forces, with :math:`a_G, \omega, \dot\omega` from Pinocchio at the document's state
(:class:`~.kinematics_truth.Motion`). A printed relation :math:`R(\dot\nu, F) = 0`, affine in
the same unknowns, is right when it is one fixed combination of the residuals written along the
axes of the step's ``frame``:

.. math::

    R = \mu^T\,\mathrm{blockdiag}(R_f^T, R_f^T)\,E \quad\text{for one } \mu\in\mathbb R^6
    \text{ per parameter set, at every state,}

which is checked coefficient by coefficient (the constant term, each acceleration, each
force) by least squares over the states. When it fails, each coefficient is left out in turn:
if the others then fit, that term is named, with the sign or factor it is off by, or as a
wrong moment arm or direction. A relation that fits in other axes (the body's, the world's)
says so.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence

import numpy as np
import sympy as sp

from ...derivations.schema import Derivation
from ...derivations.steps import Force, Step
from ..judge.diagnose import AGREE_TOL, nice_number
from ..judge.units import DimensionChecker, format_dim
from ..records import Diagnosis, DiagnosisKind as K, ElementRecord, Verdict, diagnosis
from ..sides.kinematics import step_body
from .balance_samples import BALANCE_SETS, BALANCE_STATES, BalanceSamples, residual_rows


def _fit(T: np.ndarray, D: np.ndarray, keep: np.ndarray) -> tuple[np.ndarray, float]:
    r"""Least-squares :math:`\mu` with :math:`\mu^T T_i[:, c] = D_i[c]` over states i and kept
    columns c; its largest residual."""
    A = np.concatenate([T[i][:, keep].T for i in range(len(T))])
    b = np.concatenate([D[i][keep] for i in range(len(D))])
    mu = np.linalg.lstsq(A, b, rcond=None)[0]
    return mu, float(np.abs(A @ mu - b).max(initial=0.0))


def _off_balance(truth: list[np.ndarray], doc: list[np.ndarray], j: int) -> float:
    r"""How far relation ``j`` is, at the first state, from the nearest combination of the
    balances (0 when it is one): the report's "document" number beside the truth's 0."""
    everything = np.arange(truth[0].shape[2])
    mu, _ = _fit(truth[0], doc[0][:, j, :], everything)
    return float(np.abs(truth[0][0].T @ mu - doc[0][0, j, :]).max())


def _term_names(d: Derivation, step: Step, free: Sequence[Force]) -> list[str]:
    known = ", the forces given by their laws" if len(free) < len(step.forces) else ""
    return [f"the terms without accelerations or forces (gravity, velocity products{known})",
            *(f"term {a}" for a in d.accelerations), *(f"term {f.name}" for f in free)]


def _suspects(truth: list[np.ndarray], doc: list[np.ndarray], j: int,
              scale: float) -> list[tuple[int, ...]]:
    r"""The smallest sets of coefficient columns (one, else two) without which relation ``j``
    fits the balances."""
    cols = truth[0].shape[2]
    everything = np.arange(cols)
    for size in (1, 2):
        found = []
        for group in (itertools.combinations(range(cols), size)):
            keep = np.array([c for c in everything if c not in group])
            if len(keep) and max(_fit(T, D[:, j, :], keep)[1]
                                 for T, D in zip(truth, doc)) <= AGREE_TOL * scale:
                found.append(group)
        if found:
            return found
    return []


def _note(text: str) -> Diagnosis:
    return diagnosis(K.NOTE, text, prefix="")


def _judge(truth: list[np.ndarray], doc: list[np.ndarray], j: int, names: list[str],
           n_forces: int) -> tuple[bool, list[Diagnosis], float, float]:
    r"""Verdict and diagnoses of relation ``j``: one fit per parameter set."""
    cols = truth[0].shape[2]
    scale = max(max(float(np.abs(D[:, j, :]).max()) for D in doc), 1e-300)
    everything = np.arange(cols)
    fits = [_fit(T, D[:, j, :], everything) for T, D in zip(truth, doc)]
    worst = max(r for _, r in fits)
    if worst <= AGREE_TOL * scale:
        return True, [], worst, scale
    diags: list[Diagnosis] = []
    for group in _suspects(truth, doc, j, scale):
        keep = np.array([c for c in everything if c not in group])
        partial = [_fit(T, D[:, j, :], keep) for T, D in zip(truth, doc)]
        c = group[0] if len(group) == 1 else None
        if c is None:
            diags.append(_note(" and ".join(names[g] for g in group) + ": their coefficients "
                               "are not the balance's (moment arms, directions, masses or "
                               "inertias)"))
            continue
        implied = np.concatenate([np.einsum("r,sr->s", mu, T[:, :, c])
                                  for (mu, _), T in zip(partial, truth)])
        printed = np.concatenate([D[:, j, c] for D in doc])
        if np.abs(implied).max() <= AGREE_TOL * scale:
            diags.append(diagnosis(K.EXTRA, "the balance has none", prefix=f"{names[c]}: extra",
                                   term=names[c]))
            continue
        if np.abs(printed).max() <= AGREE_TOL * scale:
            diags.append(diagnosis(K.MISSING, "the document has none",
                                   prefix=f"{names[c]}: missing", term=names[c]))
            continue
        ratio = printed / np.where(implied == 0, np.nan, implied)
        if np.nanmax(ratio) - np.nanmin(ratio) <= 1e-6 * np.nanmax(np.abs(ratio)):
            r = float(np.nanmean(ratio))
            diags.append(diagnosis(K.SIGN, "the document has the opposite sign",
                                   prefix=f"{names[c]}: sign", term=names[c], factor="-1")
                         if abs(r + 1) < 1e-6 else
                         diagnosis(K.FACTOR, f"the document is {nice_number(r)} × the balance",
                                   prefix=f"{names[c]}: factor", term=names[c],
                                   factor=nice_number(r)))
        else:
            diags.append(_note(f"{names[c]}: its coefficient is not the balance's (a moment "
                               "arm, a direction, a mass or an inertia)"))
    if not diags:
        diags += _forces_against_the_motion(truth, doc, j, names, n_forces, scale)
    if not diags:
        diags.append(_note("not a combination of the body's force and moment balances"))
    return False, diags, worst, scale


def _forces_against_the_motion(truth: list[np.ndarray], doc: list[np.ndarray], j: int,
                               names: list[str], n_forces: int, scale: float
                               ) -> list[Diagnosis]:
    r"""When the relation's motion side (the terms without forces and the accelerations)
    fixes the combination :math:`\mu` on its own, the forces whose coefficients differ from
    what that combination gives — several at once (an arm moved from one force to another)."""
    cols = len(names)
    forces = list(range(cols - n_forces, cols))
    motion = np.arange(cols - n_forces)
    fits = [_fit(T, D[:, j, :], motion) for T, D in zip(truth, doc)]
    if max(r for _, r in fits) > AGREE_TOL * scale:
        return []
    out = []
    for c in forces:
        implied = np.concatenate([np.einsum("r,sr->s", mu, T[:, :, c])
                                  for (mu, _), T in zip(fits, truth)])
        printed = np.concatenate([D[:, j, c] for D in doc])
        if np.abs(printed - implied).max() > AGREE_TOL * scale:
            out.append(_note(f"{names[c]}: its coefficient is not what the motion side gives "
                             f"(document {printed[0]:.6g}, balance {implied[0]:.6g} at the "
                             "first state)"))
    return out


def _term_fixes(b: BalanceSamples, j: int, names: list[str]) -> list[Diagnosis]:
    r"""One printed term of relation ``j`` with the wrong sign, or a sin written for a cos
    (or the reverse) in it: the edits that make the relation a balance."""
    expr = b.step.components[j]
    truth = b.truth(b.step.frame)

    def fits(trial: sp.Expr) -> bool:
        return _judge(truth, b.document([trial]), 0, names, len(b.free))[0]

    for terms in (sp.Add.make_args(expr), sp.Add.make_args(sp.expand(expr))):
        found = [diagnosis(K.SIGN, f"the term {sp.sstr(term)} has the wrong sign",
                           term=sp.sstr(term), factor="-1") for k, term in
                 enumerate(terms) if len(terms) > 1
                 and fits(sp.Add(*terms[:k], -term, *terms[k + 1:]))]
        for k, term in enumerate(terms):
            for f in sorted(term.atoms(sp.sin, sp.cos), key=sp.default_sort_key):
                other = (sp.cos if f.func == sp.sin else sp.sin)(*f.args)
                if fits(sp.Add(*terms[:k], term.xreplace({f: other}), *terms[k + 1:])):
                    found.append(diagnosis(K.SWAP, f"{sp.sstr(f)} where {sp.sstr(other)} fits "
                                           f"in the term {sp.sstr(term)}", written=sp.sstr(f),
                                           fits=sp.sstr(other), term=sp.sstr(term)))
        if found:
            return found
    return []


def compare_balance(d: Derivation, step: Step, index: int, seed: int) -> list[ElementRecord]:
    r"""One record per relation of a ``newton-euler`` step (see the module docstring)."""
    b = BalanceSamples(d, step, index, seed)
    truth, doc = b.truth(step.frame), b.document(step.components)
    names = _term_names(d, step, b.free)
    labels = step.component_names()
    out = []
    dims = DimensionChecker(d)
    for j in range(len(step.components)):
        common = dict(element=f"{step.name} {labels[j]}", key="step", index=(index, j),
                      document=step.printed[j], document_model="", truth=None, residual=None,
                      step=step.kind, equation=step.equation,
                      document_latex=sp.latex(step.components[j]))
        if not all(np.all(np.isfinite(D[:, j, :])) for D in doc) or \
                not all(np.all(np.isfinite(T)) for T in truth):
            out.append(ElementRecord(verdict=Verdict.UNDECIDED, diagnoses=(diagnosis(
                K.UNDECIDED, "not finite at some samples", prefix=""),), max_error=float("nan"),
                scale=float("nan"),
                **common))
            continue
        ok, diags, worst, scale = _judge(truth, doc, j, names, len(b.free))
        lhs, rhs = (dims.dim(side, []) for side in step.sides[j])
        if lhs is not None and rhs is not None and lhs != rhs and 0 not in step.sides[j]:
            ok = False
            diags.insert(0, diagnosis(K.DIMENSION, f"the left side is {format_dim(lhs)}, the "
                                      f"right side {format_dim(rhs)}"))
        if not ok:
            diags += _term_fixes(b, j, names)
            for frame in dict.fromkeys(("world", step_body(step))):
                if frame != step.frame and _judge(b.truth(frame), doc, j, names,
                                                  len(b.free))[0]:
                    diags.insert(0, diagnosis(K.NOTE, f"it is a balance along the axes of "
                                              f"{frame}, not {step.frame}", prefix="frame"))
        out.append(ElementRecord(verdict=Verdict.AGREES if ok else Verdict.DIFFERS,
                                 diagnoses=tuple(diags),
                                 max_error=worst, scale=scale, truth_sample=0.0,
                                 document_sample=_off_balance(truth, doc, j), **common))
    return out


__all__ = ["BALANCE_SETS", "BALANCE_STATES", "compare_balance", "residual_rows"]
