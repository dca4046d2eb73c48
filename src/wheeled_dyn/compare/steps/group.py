r"""The samples of a derivation's steps that share one parameter family (:class:`StepGroup`):
random parameter sets and states (made admissible, away from singular coordinates), the truth
of each step there (:mod:`~wheeled_dyn.compare.sides.kinematics`; a linearised step on deviations from its point, a
first integral along the free motion), and the document's expressions compiled and evaluated
on the same samples."""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
import sympy as sp

from ...compiled import numpy_function
from ...constraints.reduction import CoordinateMap, CoordinateSet
from ...derivations.schema import Derivation
from ...derivations.steps import RELATION_KINDS, VECTOR_KINDS, Step
from ...errors import DerivationError
from ...models.registry import model_version
from ..grid.assumptions import Assumptions, position_ranges
from ..grid.grid import derivation_coordinate_set
from ..grid.samples import random_states, regular_states
from ..sides.document import document_symbol_values, given_parameter_sets
from ..sides.kinematics import Motion, along, check_links, step_body


#: Parameter sets and states per set on which the steps are compared.
STEP_SETS, STEP_STATES = 2, 10
#: States per set on which the truth's coefficients are computed (only for differing components).
DECOMPOSE_STATES = 3


_MAPS: dict[tuple, CoordinateMap] = {}
_SETS: dict[tuple, CoordinateSet] = {}


class StepGroup:
    r"""The samples, truth and document values of the steps sharing one parameter family."""

    def __init__(self, d: Derivation, given: tuple[str, ...], seed: int,
                 sets: int = STEP_SETS, states: int = STEP_STATES) -> None:
        self.d, self.N = d, states
        self.reference: dict[int, float] = {}
        self.linearised = False
        self.integral = False
        self._argv: list[np.ndarray] | None = None
        rng = np.random.default_rng([seed, 11, len(given)])
        self.sets = given_parameter_sets(d, given, sets, rng)
        version = model_version(d.model)          # the model's files as they are now
        ckey = (str(d.path), repr(d.coordinates.raw), d.coordinates.use, version)
        if ckey not in _SETS:
            _SETS[ckey] = derivation_coordinate_set(d, self.sets[0])
        self.cs = _SETS[ckey]
        key = (d.model, version, repr(self.cs))
        if key not in _MAPS:                      # compiled once, rebound per parameter set
            _MAPS[key] = CoordinateMap(self.sets[0].model, self.cs)
        self.cmap = _MAPS[key]
        n = len(self.cs.positions)
        ranges = position_ranges(d, self.cs.positions, Assumptions())
        q, nu = random_states(n, sets * states, rng, ranges)
        q = regular_states(self.cmap, q, rng, ranges)    # not where the coordinates are singular
        self.q, self.nu, self.nudot = q, nu, rng.normal(size=nu.shape)
        self.rng = rng
        self.params = tuple(s.symbol for s in d.symbols.values() if not s.is_input)
        self.values = [document_symbol_values(d, ps, rng) for ps in self.sets]
        #: the rates of the positions along the free motion (first integrals; else 0)
        self.rates = [sp.Symbol("_rate_" + str(p), real=True) for p in d.positions]
        self.qdot = np.zeros_like(q)
        #: the rates of the accelerations on a linearised step's deviations (else NaN: a
        #: second-order relation means nothing elsewhere)
        self.jerk = np.full_like(nu, np.nan)
        self.args = [*d.positions, *d.velocities, *d.accelerations, *self.params, *self.rates,
                     *d.jerks]

    def truth(self, steps: Sequence[Step]) -> list[np.ndarray]:
        r"""The truth of every step at every sample; the states are made admissible first (a
        linearised step, alone in its group: replaced by deviations, see :meth:`_deviations`)."""
        self.linearised = steps[0].kind == "linearised equations"
        self.integral = steps[0].kind == "first integral"
        self._argv = None
        out = [np.zeros((len(self.q), len(s.components))) for s in steps]
        for k, ps in enumerate(self.sets):
            self.cmap.bind(ps.model)
            check_links(ps.model, [b for s in steps for b in (*([s.body] if s.body else []),
                                                              *s.bodies)])
            data = ps.model.model.createData()
            for i in range(k * self.N, (k + 1) * self.N):
                if steps[0].kind == "linearised equations":      # alone in its group
                    self._deviations(steps[0], k, i)
                    continue
                if steps[0].kind == "first integral":            # alone in its group
                    self._free_rates(steps[0], i)
                    continue
                m = Motion(self.cmap, data, self.q[i], self.nu[i], self.nudot[i])
                self.nu[i], self.nudot[i] = m.nu, m.nudot
                for s, arr in zip(steps, out):
                    arr[i] = self.true_value(s, m, k)
                    if s.kind in VECTOR_KINDS:       # the size of the body's motion
                        size = float(np.linalg.norm(m.vector(s.kind, step_body(s), "origin",
                                                             "world")))
                        self.reference[id(s)] = max(self.reference.get(id(s), 0.0), size)
        return out

    def _deviations(self, step: Step, k: int, i: int) -> None:
        r"""Sample ``i`` of a linearised step: the state :math:`x^*` (``about``; positions not
        named there as drawn), the true free motion's Jacobians :math:`J_q, J_\nu` of
        :math:`\dot\nu = A^{-1}(-h - Q)` there (central differences; exact in :math:`\nu`,
        where it is quadratic), and random deviations :math:`\Delta q, \Delta\nu` with
        :math:`\Delta\dot\nu = J_q\Delta q + J_\nu\Delta\nu` in place of the sample; their
        rates :math:`\Delta\ddot\nu = J_q\Delta\dot q + J_\nu\Delta\dot\nu`, with
        :math:`\Delta\dot q = R_q\Delta q + R_\nu\Delta\nu` from the positions' rates
        :math:`\dot q = r(q, \nu)` (:math:`r = \nu` in holonomic coordinates)."""
        d, cmap = self.d, self.cmap
        if self.cs.rolling == "multipliers":
            raise DerivationError(d.path, f"step {step.equation}", "linearised equations need "
                                  "coordinates with the rolling eliminated (or none)")
        q0, nu0 = self.q[i].copy(), np.zeros(len(self.nu[i]))
        names = [str(p) for p in d.positions], [str(v) for v in d.velocities]
        for name, value in step.about:
            x = float(value.xreplace(self.values[k]))
            if name in names[0]:
                q0[names[0].index(name)] = x
            elif name in names[1]:
                nu0[names[1].index(name)] = x
            else:
                raise DerivationError(d.path, f"step {step.equation}.about.{name}", "not a "
                                      "position or velocity of the document")

        def f(q, nu):
            t = cmap.terms_at(cmap.model_configuration(q), nu, q)
            return np.linalg.solve(t.A, -(t.h + t.Q))

        n = len(nu0)
        eye = np.eye(n)
        J_nu = np.stack([(f(q0, nu0 + 1e-3 * e) - f(q0, nu0 - 1e-3 * e)) / 2e-3 for e in eye], 1)
        J_q = np.stack([(f(q0 + 1e-4 * e, nu0) - f(q0 - 1e-4 * e, nu0)) / 2e-4 for e in eye], 1)
        dq, dnu = self.rng.normal(size=n), self.rng.normal(size=n)
        self.q[i], self.nu[i], self.nudot[i] = dq, dnu, J_q @ dq + J_nu @ dnu
        if self.d.jerks:
            if self.cs.kind == "holonomic":
                dqdot = dnu
            else:
                R_nu = np.stack([(self._position_rates(q0, nu0 + 1e-6 * e)
                                  - self._position_rates(q0, nu0 - 1e-6 * e)) / 2e-6
                                 for e in eye], 1)
                R_q = np.stack([(self._position_rates(q0 + 1e-6 * e, nu0)
                                 - self._position_rates(q0 - 1e-6 * e, nu0)) / 2e-6
                                for e in eye], 1)
                dqdot = R_q @ dq + R_nu @ dnu
            self.jerk[i] = J_q @ dqdot + J_nu @ self.nudot[i]

    def _position_rates(self, q0: np.ndarray, nu: np.ndarray) -> np.ndarray:
        r"""The rates of the document's positions at ``(q0, nu)``: the least-squares solution
        of :math:`\partial g/\partial q_d\,\dot q_d = v`, :math:`v = S\nu` the model's
        velocity (:math:`\partial g/\partial q_d` by central differences)."""
        cmap = self.cmap
        q = cmap.model_configuration(q0)
        _, _, v = cmap.reduce_at(q, nu, q0)
        G = np.stack([(cmap.model_configuration(q0 + 1e-6 * e) -
                       cmap.model_configuration(q0 - 1e-6 * e)) / 2e-6
                      for e in np.eye(len(q0))], 1)
        return np.linalg.lstsq(G, v, rcond=None)[0]

    def _free_rates(self, step: Step, i: int) -> None:
        r"""Sample ``i`` of a first integral: the true accelerations of the free motion,
        :math:`\dot\nu = A^{-1}(-h - Q)`, and the rates of the document's positions
        (:math:`\dot q_d = \nu` for holonomic sets; else the least-squares solution of
        :math:`\partial g/\partial q_d\,\dot q_d = v` with the model's velocity
        :math:`v = S\nu`, :math:`\partial g/\partial q_d` by central differences)."""
        cmap = self.cmap
        if self.cs.rolling == "multipliers":
            raise DerivationError(self.d.path, f"step {step.equation}", "first integrals need "
                                  "coordinates with the rolling eliminated (or none)")
        q0, nu = self.q[i], self.nu[i]
        terms, _, _ = cmap.reduce_at(cmap.model_configuration(q0), nu, q0)
        self.nudot[i] = np.linalg.solve(terms.A, -(terms.h + terms.Q))
        self.qdot[i] = nu if self.cs.kind == "holonomic" else self._position_rates(q0, nu)

    def true_value(self, s: Step, m: Motion, k: int) -> np.ndarray:
        if s.kind in VECTOR_KINDS:
            point = s.point if not isinstance(s.point, tuple) else np.array(
                [float(sp.sympify(p).xreplace(self.values[k])) for p in s.point])
            return along(m.vector(s.kind, step_body(s), point, s.frame), s.axes)
        if s.kind == "orientation":
            return m.orientation(step_body(s), s.frame, s.axes, s.body_axes).ravel()
        if s.kind == "gravity":
            g = self.cmap.wm.model.gravity.linear
            return along(m.rotation(s.frame).T @ g, s.axes)
        if s.kind == "kinetic energy":
            return np.array([m.kinetic_energy(s.bodies)])
        if s.kind == "potential energy":
            sign = -1.0 if s.quantity == "force function" else 1.0      # U = -V
            return np.array([sign * m.potential_energy(s.bodies)])
        if s.kind == "generalized force":
            f = m.inertial_terms()[list(s.rows)]
            return -f if s.quantity == "inertia" else f
        return np.zeros(len(s.components))      # a relation holds on the model's motions

    def rate(self, expr: sp.Expr, kind: str | None = None) -> sp.Expr:
        r"""A configuration relation's rate :math:`\sum_i \partial f/\partial q_i\,\dot q_i`
        (holonomic sets); velocity relations and parameter claims as they are. A value of a
        step that is not a relation (``kind``: a vector, even one without velocities such as
        :math:`\ddot x\cos\theta`, an energy, an orientation) is compared as it is."""
        d = self.d
        if kind is not None and kind not in (*RELATION_KINDS, "first integral"):
            return expr                   # a value (a vector, an energy, a force), not a relation
        if self.integral:                 # its rate along the free motion
            return sum((expr.diff(p) * r for p, r in zip(d.positions, self.rates)),
                       sp.Integer(0)) + sum((expr.diff(v) * a for v, a in
                                             zip(d.velocities, d.accelerations)), sp.Integer(0))
        if self.linearised or expr.has(*d.velocities) or not expr.has(*d.positions):
            return expr
        if self.cs.kind != "holonomic":
            raise DerivationError(d.path, "step", "a relation between coordinates is checked "
                                  "through its rate: it needs a holonomic coordinate set")
        return sum((expr.diff(p) * v for p, v in zip(d.positions, d.velocities)), sp.Integer(0))

    _fns: dict = {}

    def _fn(self, expr: sp.Expr) -> Callable:
        key = (tuple(self.args), expr)
        if key not in StepGroup._fns:
            StepGroup._fns[key] = numpy_function(self.args, expr)
        return StepGroup._fns[key]

    def argv(self, rows: np.ndarray | None = None) -> list[np.ndarray]:
        r"""The arguments of the document's functions at the samples ``rows`` (all: cached;
        call after :meth:`truth`, which makes the states admissible)."""
        if rows is None and self._argv is not None:
            return list(self._argv)
        every = np.arange(len(self.q)) if rows is None else rows
        per = np.repeat(np.arange(len(self.sets)), self.N)[every]
        out = [*self.q[every].T, *self.nu[every].T, *self.nudot[every].T,
               *(np.array([self.values[k][p] for k in per]) for p in self.params),
               *self.qdot[every].T, *self.jerk[every][:, :len(self.d.jerks)].T]
        if rows is None:
            self._argv = out
        return list(out)

    def documents(self, exprs: Sequence[sp.Expr], rows: np.ndarray | None = None,
                  read: tuple[sp.Symbol, sp.Symbol] | None = None) -> list[np.ndarray]:
        r"""Several expressions at the samples, compiled together (one function);
        ``read`` as in :meth:`document`."""
        if not exprs:
            return []
        argv = self.argv(rows)
        if read is not None:
            argv[self.args.index(read[0])] = argv[self.args.index(read[1])]
        with np.errstate(all="ignore"):       # inf/NaN: the records call it undecided
            values = self._fn(tuple(exprs))(*argv)
        return [np.broadcast_to(np.asarray(v, dtype=float), (len(argv[0]),)).copy()
                for v in values]

    def document(self, expr: sp.Expr, rows: np.ndarray | None = None,
                 read: tuple[sp.Symbol, sp.Symbol] | None = None) -> np.ndarray:
        r"""The document's ``expr`` at the samples (``rows``); ``read = (a, b)``: with the
        symbol ``a`` read as ``b`` (its argument array replaced, nothing recompiled)."""
        argv = self.argv(rows)
        if read is not None:
            argv[self.args.index(read[0])] = argv[self.args.index(read[1])]
        with np.errstate(all="ignore"):       # inf/NaN: the records call it undecided
            value = self._fn(expr)(*argv)
        return np.broadcast_to(np.asarray(value, dtype=float), (len(argv[0]),)).copy()
