r"""Simulation of a documented model (a derivation file) beside the true one.

The document's equations, with its symbols at the values of one parameter set,

.. math::

    A_{doc}(q)\,\dot\nu + h_{doc}(q,\nu) + Q_{doc}(q) = B_{doc}\,u,\qquad \dot q = \nu ,

(the document treats its positions as coordinates whose derivatives are its velocities) are
integrated from the same start with the same input as the true reduced equations
(:mod:`.reduced`). Each side's energy: the truth's :math:`\tfrac12\nu^TA_\nu\nu + U`; the
document's :math:`\tfrac12\nu^TA_{doc}\nu + U_{doc}` with :math:`U_{doc} = \sum_i\int Q_i\,dq_i`
when its Q is a gradient (otherwise the document has no potential and only its kinetic energy
is shown). A missing gyroscopic term shows as a drifting energy and a diverging trajectory.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp

from ..compare.grid.grid import derivation_coordinate_set
from ..compare.sides.document import document_symbol_values
from ..compare.grid.samples import ParameterSet, namespace_values
from ..constraints.reduction import CoordinateMap
from ..derivations.schema import Derivation
from ..errors import DerivationError, StateError
from ..models.registry import load_model, model_entry
from .reduced import RTOL, ATOL, Trajectory, simulate


@dataclass(frozen=True)
class DocumentTrajectory:
    r"""Samples of the documented model: times, positions, velocities, energy (NaN where the
    document has no potential), and whether that energy includes a potential."""

    t: np.ndarray
    q: np.ndarray
    nu: np.ndarray
    energy: np.ndarray
    has_potential: bool


def _potential(d: Derivation, Q: sp.Matrix) -> sp.Expr | None:
    q = d.positions
    for i in range(d.n):
        for j in range(i + 1, d.n):
            if sp.simplify(sp.diff(Q[i], q[j]) - sp.diff(Q[j], q[i])) != 0:
                return None
    U = sp.Integer(0)
    for i, qi in enumerate(q):
        rest = sp.simplify(Q[i] - sp.diff(U, qi))
        U += sp.integrate(rest, qi)
    return U


def simulate_document(d: Derivation, params: ParameterSet, q0: np.ndarray, nu0: np.ndarray,
                      duration: float, rate: float = 200.0, u: np.ndarray | None = None,
                      seed: int = 0, row_factors: tuple[float | None, ...] | None = None
                      ) -> DocumentTrajectory:
    r"""Integrate the document's own equations (constant input ``u`` in its inputs); rows are
    first divided by ``row_factors`` (undeclared constant factors the comparison found, e.g.
    −1 for a row written as Kane's generalised inertia force), so that its energy is read
    from a consistently signed A."""
    terms = d.read_off(assume=True, unscale=True)
    if terms.A is None or terms.Q is None:
        raise StateError(None, d.path.name, "a derivation with A and Q to simulate")
    values = document_symbol_values(d, params, np.random.default_rng(seed))
    h = terms.h if terms.h is not None else sp.zeros(d.n, 1)
    scale = sp.diag(*[1 if not c else sp.nsimplify(1 / float(c)) for c in
                      (row_factors or (None,) * d.n)])
    A, Q, h = (scale * sp.Matrix(M).xreplace(values) for M in (terms.A, terms.Q, h))
    B = scale * sp.Matrix(terms.B).xreplace(values) if terms.B is not None else sp.zeros(d.n, 0)
    args = [*d.positions, *d.velocities]
    fA, fh, fQ = (sp.lambdify(args, M, "numpy") for M in (A, h, Q))
    u = np.zeros(B.shape[1]) if u is None else np.asarray(u, dtype=float)
    Bu = np.array(B, dtype=float) @ u if B.shape[1] else np.zeros(d.n)
    n = d.n

    def rhs(t, y):
        a = [*y]
        with np.errstate(all="ignore"):
            force = Bu - _real(fh(*a), d, t, y) - _real(fQ(*a), d, t, y)
            mass = _real(fA(*a), d, t, y).reshape(n, n)
            try:
                acc = np.linalg.solve(mass, force)
            except np.linalg.LinAlgError:
                raise _unusable(d, t, y, "A is singular") from None
        if not np.all(np.isfinite(acc)):
            raise _unusable(d, t, y, "the accelerations are not finite")
        return np.concatenate([y[n:], acc])

    t_eval = np.linspace(0.0, duration, int(round(duration * rate)) + 1)
    y0 = np.concatenate([q0, nu0]).astype(float)
    sol = solve_ivp(rhs, (0.0, duration), y0, method="DOP853", t_eval=t_eval, rtol=RTOL, atol=ATOL)
    U = _potential(d, Q)
    v = sp.Matrix(d.velocities)
    E = (v.T * A * v)[0] / 2 + (U if U is not None else 0)
    fE = sp.lambdify(args, E, "numpy")
    energy = np.array([float(fE(*y)) for y in sol.y.T])
    # the document's model may blow up: where the integrator gives up first, what was
    # integrated is kept (sol.t ends early); accelerations that are not finite raise above
    return DocumentTrajectory(sol.t, sol.y[:n].T, sol.y[n:].T, energy, U is not None)


def _unusable(d: Derivation, t: float, y: np.ndarray, why: str) -> DerivationError:
    r"""The error for a document whose equations cannot be integrated at time ``t``,
    state ``y`` (its positions, then its velocities)."""
    names = [*d.positions, *d.velocities]
    state = ", ".join(f"{s} = {v:.4g}" for s, v in zip(names, np.real(y)))
    return DerivationError(d.path, "equations" if d.equations else "matrices",
                           f"{why} at t = {t:.4g} s ({state}): the document's equations "
                           "cannot be integrated there")


def _real(value: object, d: Derivation, t: float, y: np.ndarray) -> np.ndarray:
    r"""``value`` (a term of the document at time ``t``, state ``y``) as a flat array of
    finite real numbers; else :func:`_unusable` (``sqrt(-1 - theta**2)`` is imaginary,
    ``exp(exp(exp(10)))`` does not fit a float)."""
    try:
        arr = np.asarray(value, dtype=complex).ravel()
    except (TypeError, ValueError, OverflowError):
        raise _unusable(d, t, y, "a term is not a number") from None
    if not np.all(np.isfinite(arr)):
        raise _unusable(d, t, y, "a term is not finite (a square root or logarithm of a "
                        "negative number, a division by zero?)")
    if np.any(arr.imag != 0):
        raise _unusable(d, t, y, "a term is not real (a square root or logarithm of a "
                        "negative number?)")
    return arr.real


@dataclass(frozen=True)
class SideBySide:
    r"""The true and the documented trajectory from one start."""

    derivation: Derivation
    truth: Trajectory
    truth_doc_q: np.ndarray          # true motion in the document's positions (integrated ν)
    document: DocumentTrajectory


def side_by_side(d: Derivation, q0: dict[str, float], duration: float = 5.0,
                 rate: float = 200.0, row_factors: tuple[float | None, ...] | None = None
                 ) -> SideBySide:
    r"""Both models from the document state ``q0`` (names of the document's positions and
    velocities; missing are 0), zero input, the model's default parameters. ``row_factors``:
    see :func:`simulate_document` (default: found by a quick comparison, with the equations
    read as it read them: :func:`~wheeled_dyn.compare.readings.row_combinations.as_compared`)."""
    if row_factors is None:
        from ..compare.engine import ComparisonEngine
        from ..compare.readings.row_combinations import as_compared
        found = ComparisonEngine(samples=50, param_sets=2).compare(d)
        row_factors = tuple(None if c is None else float(sp.Rational(c))
                            for c in found.row_factors)
        d = as_compared(d, found)
    wm = load_model(d.model)
    entry = model_entry(d.model)
    physical = entry.parameters() if entry.parameters else None
    params = ParameterSet(wm, namespace_values(wm, physical), physical)
    cs = derivation_coordinate_set(d, params)
    cmap = CoordinateMap(wm, cs)
    pos, vel = cmap.state_from(q0)
    start = pos if cs.kind == "holonomic" else cmap.model_configuration(pos)
    truth = simulate(cmap, start, vel, duration, rate=rate)
    # the true motion in the document's positions: integrate its velocities
    dt = np.diff(truth.t)
    doc_q = pos + np.vstack([np.zeros(len(pos)), np.cumsum(0.5 * (truth.nu[1:] + truth.nu[:-1])
                                                           * dt[:, None], axis=0)])
    doc = simulate_document(d, params, pos, vel, duration, rate, row_factors=row_factors)
    return SideBySide(d, truth, doc_q, doc)
