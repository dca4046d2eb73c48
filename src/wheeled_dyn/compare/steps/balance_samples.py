r"""The samples of one Newton–Euler balance (:class:`BalanceSamples`): random parameter sets
and states of a ``newton-euler`` step, at each state the columns of the body's true residuals
:math:`E(\dot\nu, F)` (:func:`residual_rows`: the constant, each acceleration, each force,
from Pinocchio's motion of the body) along a frame's axes, and the document's coefficients of
the same unknowns (see :mod:`.balances`)."""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import sympy as sp

from ...compiled import numpy_function
from ...constraints.reduction import CoordinateMap
from ...derivations.schema import Derivation
from ...derivations.steps import Force, Step
from ...errors import DerivationError
from ..grid.assumptions import Assumptions, position_ranges
from ..grid.grid import derivation_coordinate_set
from ..grid.samples import random_states, regular_states
from ..sides.document import document_symbol_values, given_parameter_sets
from ..sides.kinematics import Motion, check_links, step_body


#: Parameter sets and states per set on which a balance is checked.
BALANCE_SETS, BALANCE_STATES = 2, 8


def _world_point(m: Motion, body: str, point) -> np.ndarray:
    fid = m.frame_id(body)
    local = m.point_in_link(body, np.array([float(x) for x in point])
                            if isinstance(point, np.ndarray) else point)
    return m.data.oMf[fid].act(local)


def residual_rows(m: Motion, body: str, point, frame: str, forces: Sequence[Force],
                  geometry: Sequence[tuple[np.ndarray, np.ndarray]]) -> np.ndarray:
    r"""Columns of :math:`E` at the motion ``m`` along ``frame``'s axes: the residual at the
    motion's accelerations with no force, then :math:`\partial E/\partial F_k` for each force
    (``geometry``: its application point and direction in the world, evaluated)."""
    wm, data = m.wm, m.data
    j = wm.model.frames[m.frame_id(body)].parentJoint
    inertia = wm.model.inertias[j]
    rot = data.oMi[j].rotation
    mass, G = inertia.mass, data.oMi[j].act(inertia.lever)
    I_G = rot @ np.asarray(inertia.inertia) @ rot.T
    w = m.vector("angular velocity", body, "origin", "world")
    dw = m.vector("angular acceleration", body, "origin", "world")
    a_G = m.vector("acceleration", body, "com", "world")
    P = _world_point(m, body, point)
    lin = mass * a_G - mass * wm.model.gravity.linear
    ang = I_G @ dw + np.cross(w, I_G @ w) + np.cross(G - P, lin)
    cols = [np.concatenate([lin, ang])]
    for force, (p, d) in zip(forces, geometry):
        cols.append(-np.concatenate([np.zeros(3), d]) if force.couple
                    else -np.concatenate([d, np.cross(p - P, d)]))
    R_f = m.rotation(frame)
    return np.kron(np.eye(2), R_f.T) @ np.stack(cols, 1)


class BalanceSamples:
    r"""Samples of one ``newton-euler`` step: for every state the truth's coefficient columns
    (constant, each acceleration, each force) and the document's."""

    def __init__(self, d: Derivation, step: Step, index: int, seed: int) -> None:
        self.d, self.step = d, step
        rng = np.random.default_rng([seed, 23, index])
        self.sets = given_parameter_sets(d, step.given, BALANCE_SETS, rng)
        symbols = {str(s.symbol): s for s in d.symbols.values()}
        self.free = [f for f in step.forces if f.law is None]
        for f in step.forces:
            where = f"step {step.equation}.forces.{f.name}"
            if f.law is not None and f.law.has(*d.accelerations):
                raise DerivationError(d.path, f"{where}.law", "a force's law is a function of "
                                      "the positions, velocities and symbols, not of the "
                                      "accelerations")
            if f.law is not None and f.name in symbols and not symbols[f.name].free:
                raise DerivationError(d.path, where, "a force given by its law is named by a "
                                      "label, or by a symbol declared free = true, not by one "
                                      "of the file's parameters")
            if f.law is None and (f.name not in symbols or not symbols[f.name].free):
                raise DerivationError(d.path, where, "a force is a symbol of the file declared "
                                      "free = true (with units = \"N\", or \"N*m\" for a "
                                      "couple), or is given by its law = \"...\"")
        self.F = [symbols[f.name].symbol for f in self.free]
        #: a known force's symbol, where the file declares one, stands for its law
        self.laws = {symbols[f.name].symbol: f.law for f in step.forces
                     if f.law is not None and f.name in symbols}
        self.unknowns = [*d.accelerations, *self.F]
        for j, expr in enumerate(step.components):
            expr = expr.xreplace(self.laws)
            try:
                degree = sp.Poly(sp.expand(expr), *self.unknowns).total_degree()
            except sp.PolynomialError:
                degree = 2
            if degree > 1:
                raise DerivationError(d.path, f"step {step.equation} relation {j + 1}",
                                      "a balance is linear in the accelerations and forces")
        ranges = position_ranges(d, [str(p) for p in d.positions], Assumptions())
        #: the coordinate map, compiled once and bound to each parameter set in turn
        self._map = CoordinateMap(self.sets[0].model, derivation_coordinate_set(d, self.sets[0]))
        q, self.nu = random_states(len(d.positions), BALANCE_SETS * BALANCE_STATES, rng, ranges)
        self.q = regular_states(self._map, q, rng, ranges)   # not where coordinates are singular
        self.params = [s.symbol for s in d.symbols.values() if not s.is_input]
        self.args = [*d.positions, *d.velocities, *self.params]
        self.values = [document_symbol_values(d, ps, rng) for ps in self.sets]
        self._world: list[np.ndarray] | None = None        # residual columns, world axes
        self._rotations: dict[str, list[np.ndarray]] = {}  # frame -> per set, states x 3 x 3

    def _argv(self, k: int, i: int) -> list[float]:
        return [*self.q[i], *self.nu[i], *(self.values[k][p] for p in self.params)]

    def document(self, exprs: Sequence[sp.Expr]) -> list[np.ndarray]:
        r"""Per parameter set, the coefficients of ``exprs`` (states × relations × columns:
        the constant, each acceleration, each force)."""
        zero = {u: 0 for u in self.unknowns}
        exprs = [e.xreplace(self.laws) for e in exprs]
        fn = numpy_function(self.args, [[e.xreplace(zero)] + [e.diff(u) for u in self.unknowns]
                                         for e in exprs])
        out = []
        with np.errstate(all="ignore"):          # a value that is not finite is a verdict's
            for k in range(len(self.sets)):     # business (undecided), not a warning
                rows = range(k * BALANCE_STATES, (k + 1) * BALANCE_STATES)
                out.append(np.array([np.array(fn(*self._argv(k, i)), dtype=float)
                                     for i in rows]))
        return out

    def truth(self, frame: str) -> list[np.ndarray]:
        r"""Per parameter set, the columns of the residuals along ``frame``'s axes (states ×
        6 × columns): the world's residuals, computed once (the sampled velocities made
        admissible on the way, before the document is evaluated at them), turned into the
        frame's axes (``frame``: the step's, the world, or the body)."""
        if self._world is None:
            self._world = self._residuals()
        return [np.einsum("sij,sjc->sic", _blocks(R), W)
                for R, W in zip(self._rotations[frame], self._world)]

    def _residuals(self) -> list[np.ndarray]:
        d, step = self.d, self.step
        body = step_body(step)
        n = len(d.velocities)
        geo = numpy_function(self.args, [[*f.direction,
                                          *(f.point if isinstance(f.point, tuple) else ())]
                                         for f in step.forces])
        about = numpy_function(self.args, list(step.point)) \
            if isinstance(step.point, tuple) else None
        known = [k for k, f in enumerate(step.forces) if f.law is not None]
        unknown = [k for k, f in enumerate(step.forces) if f.law is None]
        law = numpy_function(self.args, [step.forces[k].law for k in known])
        truth = []
        frames = tuple(dict.fromkeys((step.frame, "world", body)))
        self._rotations = {f: [] for f in frames}
        for k, ps in enumerate(self.sets):
            cmap = self._map.bind(ps.model)
            check_links(ps.model, [body, *(f for f in frames
                                                if f not in ("world", "heading"))])
            data = ps.model.model.createData()
            T_k: list[np.ndarray] = []
            R_k: dict[str, list[np.ndarray]] = {f: [] for f in frames}
            for i in range(k * BALANCE_STATES, (k + 1) * BALANCE_STATES):
                argv = self._argv(k, i)
                with np.errstate(all="ignore"):
                    raw = geo(*argv)
                    point = np.array(about(*argv), dtype=float) if about else step.point
                rows: list[np.ndarray] = []
                for nudot in (np.zeros(n), *np.eye(n)):
                    m = Motion(cmap, data, self.q[i], self.nu[i], nudot)
                    self.nu[i] = m.nu      # made admissible (rolling kept): the document too
                    if rows:               # an acceleration's column: no force columns again
                        rows.append(residual_rows(m, body, point, "world", (), ()))
                        continue
                    geometry = [(_world_point(m, body, np.array(r[3:], dtype=float)
                                              if isinstance(f.point, tuple) else f.point),
                                 m.rotation(f.frame) @ np.array(r[:3], dtype=float))
                                for f, r in zip(step.forces, raw)]
                    rows.append(residual_rows(m, body, point, "world", step.forces,
                                              geometry))
                    for f in frames:                   # the frames' rotations: q only
                        R_k[f].append(np.array(m.rotation(f)))       # a copy: data is reused
                accel = [r[:, 0] - rows[0][:, 0] for r in rows[1:]]
                with np.errstate(all="ignore"):          # the velocities made admissible
                    values = np.array(law(*self._argv(k, i)), dtype=float).reshape(-1)
                forces = rows[0][:, 1:]
                constant = rows[0][:, 0] + forces[:, known] @ values   # known forces' share
                T_k.append(np.column_stack([constant, *accel, forces[:, unknown]]))
            truth.append(np.array(T_k))
            for f in frames:
                self._rotations[f].append(np.array(R_k[f]))
        return truth


def _blocks(R: np.ndarray) -> np.ndarray:
    r"""Per state, :math:`\mathrm{blockdiag}(R^T, R^T)` (states × 6 × 6): world components to
    a frame's."""
    out = np.zeros((len(R), 6, 6))
    out[:, :3, :3] = out[:, 3:, 3:] = np.transpose(R, (0, 2, 1))
    return out
