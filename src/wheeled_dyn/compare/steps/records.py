r"""Each step of a derivation against the truth, component by component and term by term.

For the ``[[step]]`` tables of a derivation file (:mod:`wheeled_dyn.derivations.steps`): the
truth on :data:`STEP_SETS` random parameter sets (of the families a step is ``given``) ×
:data:`STEP_STATES` random states (:mod:`.kinematics_truth`), the document's components on the
same samples, and one :class:`~.result.ElementRecord` per component (``step`` = the step's
kind, ``equation`` = its label as printed) with the verdicts and diagnoses of :mod:`.diagnose`
(sign, factor, missing, extra, a swapped symbol), plus:

- its *terms*, when the component differs: each monomial of the velocities and accelerations
  (:math:`\dot x\dot\psi`, :math:`\ddot\phi`) against the truth's coefficient, obtained by
  evaluating the truth at unit velocities and accelerations
  (:math:`b_{jk} = F(e_j+e_k) - F(e_j) - F(e_k) + F(0)`);
- for a relation (constraint, claim): it is checked on the model's admissible motions (a
  configuration relation through its rate, a claim between parameters on the parameter sets);
  a right side that is a constant times the truth, sin written for cos, a power of a symbol
  (R⁻² for R²), mismatched dimensions;
- "agrees only if": the smallest combination of the model's special parameter families under
  which a differing component agrees.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import replace

import numpy as np
import sympy as sp

from ...constraints.reduction import CoordinateMap
from ...derivations.schema import Derivation
from ...derivations.steps import RELATION_KINDS, RESULT_KINDS, VECTOR_KINDS, Step
from ...errors import DerivationError
from ...models.registry import model_version
from ..judge.diagnose import (agrees, max_error, nice_number, power_diagnoses, swap_diagnoses,
                       term_diagnoses, trig_swap_diagnoses, value_diagnoses)
from ..sides.elements import swap_groups
from ..grid.grid import derivation_coordinate_set
from ..sides.document import document_symbol_values, given_parameter_sets
from ..sides.kinematics import Motion, along, check_links
from ..records import (Diagnosis, DiagnosisKind as K, ElementRecord, Verdict, diagnosis,
                       in_product)
from ..grid.assumptions import Assumptions, declared, position_ranges
from .balances import compare_balance
from ...compiled import numpy_function
from .stated import compare_result
from ..grid.samples import random_states, regular_states, special_cases
from ..judge.units import DimensionChecker, format_dim

#: Parameter sets and states per set on which the steps are compared.
STEP_SETS, STEP_STATES = 2, 10
#: States per set on which the truth's coefficients are computed (only for differing components).
DECOMPOSE_STATES = 3
#: Smaller grid on which special parameter families are tried.
SPECIAL_SETS, SPECIAL_STATES = 2, 6
#: A relation whose every term stays below this (relative to the sampled velocities) on the
#: admissible motions has nothing to check.
VACUOUS_TOL = 1e-9
#: Kinds whose components are polynomial in the velocities and accelerations (decomposable).
_TERMED = (*VECTOR_KINDS, "kinetic energy", "generalized force")


_MAPS: dict[tuple[str, str], CoordinateMap] = {}
_SETS: dict[tuple, object] = {}


class _Group:
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
                    arr[i] = self._true(s, m, k)
                    if s.kind in VECTOR_KINDS:       # the size of the body's motion
                        size = float(np.linalg.norm(m.vector(s.kind, s.body, "origin", "world")))
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

    def coefficients(self, step: Step, monomials: Sequence[tuple[int, ...]]) -> dict:
        r"""The truth's coefficient of each monomial (exponents over velocities then
        accelerations) on the first :data:`DECOMPOSE_STATES` states of each set."""
        n = len(self.cs.positions)
        out = {m: [] for m in monomials}
        for k, ps in enumerate(self.sets):
            self.cmap.bind(ps.model)
            data = ps.model.model.createData()
            for i in range(k * self.N, k * self.N + min(DECOMPOSE_STATES, self.N)):
                cache: dict[tuple, np.ndarray] = {}

                def F(nu, nudot):
                    key = (*nu, *nudot)
                    if key not in cache:
                        m = Motion(self.cmap, data, self.q[i], np.array(nu, float),
                                   np.array(nudot, float), admissible=False)
                        cache[key] = self._true(step, m, k)
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

    def sample_rows(self) -> np.ndarray:
        return np.concatenate([np.arange(k * self.N, k * self.N + min(DECOMPOSE_STATES, self.N))
                               for k in range(len(self.sets))])

    def _true(self, s: Step, m: Motion, k: int) -> np.ndarray:
        if s.kind in VECTOR_KINDS:
            point = s.point
            if isinstance(point, tuple):
                point = np.array([float(sp.sympify(p).xreplace(self.values[k])) for p in point])
            return along(m.vector(s.kind, s.body, point, s.frame), s.axes)
        if s.kind == "orientation":
            return m.orientation(s.body, s.frame, s.axes, s.body_axes).ravel()
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

    def _rate(self, expr: sp.Expr, kind: str | None = None) -> sp.Expr:
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
        if key not in _Group._fns:
            _Group._fns[key] = numpy_function(self.args, expr)
        return _Group._fns[key]

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


def _power_swaps(expr: sp.Expr, g: _Group, T: np.ndarray, scale: float) -> list[str]:
    return power_diagnoses(expr, g.params, g.document, T, scale)


def _side_factor(g: _Group, sides: tuple[sp.Expr, sp.Expr], scale: float) -> list[Diagnosis]:
    r"""A relation whose right side is a constant c times what the left side is on the
    model's motions: the true relation has the right side divided by c."""
    L, R = (g.document(g._rate(x)) for x in sides)
    if float(L @ L) <= 0 or float(R @ R) <= 0:
        return []
    c = float(R @ L / (L @ L))
    if not agrees(R, c * L, scale):
        return []
    true = sp.nsimplify(sides[1] / sp.nsimplify(nice_number(c)))
    return [diagnosis(K.FACTOR, f"the right side is {nice_number(c)} × what the left side is "
                      f"on the model's motions; true: {sp.sstr(sides[0])} = {sp.sstr(true)}",
                      factor=nice_number(c))]


def _linear_terms(g: _Group, expr: sp.Expr) -> list[str]:
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


def _term_diagnoses(g: _Group, step: Step, j: int, expr: sp.Expr, scale: float
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
    truth = g.coefficients(step, monos)
    rows = g.sample_rows()
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


def _explained(diagnoses: Sequence[Diagnosis]) -> bool:
    r"""A diagnosis that names the error already (the whole component of the wrong sign or
    factor, a term of the wrong sign or factor, a swapped symbol, a power, a dimension): no
    special family is searched then. A missing or extra term is not enough: it may be what a
    special family removes (a centre of mass off the axis)."""
    return any(x.kind in (K.SIGN, K.FACTOR) or (not x.product and x.kind in (
        K.SWAP, K.POWER, K.DIMENSION)) for x in diagnoses)


def _compiled(g: _Group, step: Step) -> list[sp.Expr]:
    r"""The step's components (rates of relations) that the text did not lose, in order."""
    return [g._rate(e, step.kind) for e in step.components if not e.has(sp.nan)]


def _document_values(g: _Group, step: Step, T: np.ndarray):
    r"""The document's values of each component (None where lost) and the step's scale: the
    largest value on either side (for a relation, of either side's rate; for a vector, at
    least the size of the body origin's vector of the same kind, so that a vector that is 0
    (a contact point's velocity) is judged against the motion's size)."""
    kept = [j for j, expr in enumerate(step.components) if not expr.has(sp.nan)]
    exprs = _compiled(g, step)
    if step.kind in RELATION_KINDS:        # the size of each side's terms: a side may be 0
        exprs += [g._rate(t) for j in kept for side in step.sides[j]
                  for t in sp.Add.make_args(sp.expand(side))]
    reference = g.reference.get(id(step), 0.0)
    if step.kind == "first integral":
        # the size its rate would have were it not an integral: |dI/dq| |q'| + |dI/dnu| |nu'|
        d = g.d
        for j in kept:
            e = step.components[j]
            grads = g.documents([e.diff(x) for x in (*d.positions, *d.velocities)])
            n = len(d.positions)
            size = (sum(np.abs(x) for x in grads[:n]) * np.linalg.norm(g.qdot, axis=1)
                    + sum(np.abs(x) for x in grads[n:]) * np.linalg.norm(g.nudot, axis=1))
            reference = max(reference, float(np.max(size, initial=0.0)))
    values = g.documents(exprs)
    D_all = [None] * len(step.components)
    for j, v in zip(kept, values):
        D_all[j] = v
    parts = values[len(kept):]
    scale = max([float(np.abs(a).max(initial=0.0))
                 for a in (*[x for x in D_all if x is not None], T, *parts)
                 if np.all(np.isfinite(a))] + [reference, 1e-300])
    return D_all, scale


def _level(g: _Group, step: Step, x: np.ndarray) -> np.ndarray:
    r"""A potential energy is measured from any level: its values (every sample of the
    group) taken from their mean per parameter set; other steps' values as they are."""
    if step.kind != "potential energy":
        return x
    k = len(g.sets)
    return (x.reshape(k, -1) - x.reshape(k, -1).mean(axis=1, keepdims=True)).ravel()


def _levelled(g: _Group, step: Step, D: np.ndarray, T: np.ndarray
              ) -> tuple[np.ndarray, np.ndarray]:
    r"""Both sides levelled (:func:`_level`: a wrong sign or factor still shows as such)."""
    return _level(g, step, D), _level(g, step, T)


def _special(d: Derivation, step: Step, seed: int) -> dict[int, str]:
    r"""For the components that differ, the smallest combination of the model's special
    parameter families (beyond the step's ``given``) under which they agree."""
    cases = [c for c in special_cases(d.model) if c.name not in step.given]
    memo: dict[tuple[str, ...], set[int]] = {}

    def agreeing(names: tuple[str, ...]) -> set[int]:
        if names not in memo:
            g = _Group(d, step.given + names, seed, SPECIAL_SETS, SPECIAL_STATES)
            T = g.truth([step])[0]
            D_all, scale = _document_values(g, step, T)
            memo[names] = {j for j, D in enumerate(D_all) if D is not None
                           and np.all(np.isfinite(D))
                           and agrees(*_levelled(g, step, D, T[:, j]), scale)}
        return memo[names]

    full = tuple(c.name for c in cases)
    out = {}
    for j in (agreeing(full) if cases else ()):
        needed = list(full)
        for name in full:
            trial = tuple(x for x in needed if x != name)
            if j in agreeing(trial):
                needed = list(trial)
        out[j] = " and ".join(c.description for c in cases if c.name in needed) or "always"
    return out


def _records(g: _Group, step: Step, index: int, T: np.ndarray) -> list[ElementRecord]:
    d = g.d
    names = step.component_names()
    groups = swap_groups(d)
    dims = DimensionChecker(d)
    recs = []
    D_all, scale = _document_values(g, step, T)
    for j, expr in enumerate(step.components):
        D, Tj = D_all[j], T[:, j]
        element = f"{step.name} {names[j]}"
        common = dict(element=element, key="step", index=(index, j), document=step.printed[j],
                      document_model="", truth=None, residual=None,
                      step="claim" if step.kind == "first integral" else step.kind,
                      equation=step.equation)
        if D is None or not np.all(np.isfinite(D)) or not np.all(np.isfinite(Tj)):
            why = "lost in the extracted text: not compared" if D is None else \
                "not finite at some samples"
            recs.append(ElementRecord(verdict=Verdict.UNDECIDED, diagnoses=(
                diagnosis(K.UNDECIDED, why, prefix=""),), max_error=float("nan"), scale=scale,
                **common))
            continue
        size = 1.0 + float(np.abs(g.nu).max(initial=0.0))
        if step.kind == "constraint" and scale <= VACUOUS_TOL * size:
            recs.append(ElementRecord(verdict=Verdict.UNDECIDED, diagnoses=(diagnosis(
                K.UNDECIDED, "every term of the relation vanishes on the model's admissible "
                "motions: nothing to check", prefix=""),),
                max_error=float("nan"), scale=scale, **common))
            continue
        diags: list[Diagnosis] = []
        expr = g._rate(step.components[j], step.kind)
        D, Tj = _levelled(g, step, D, Tj)
        relation = step.kind in RELATION_KINDS
        if relation:
            lhs, rhs = step.sides[j]
            dl, dr = dims.dim(lhs, []), dims.dim(rhs, [])
            if dl is not None and dr is not None and dl != dr and lhs != 0 and rhs != 0:
                diags.append(diagnosis(K.DIMENSION, f"the left side is {format_dim(dl)}, the "
                                       f"right side {format_dim(dr)}"))
        else:
            problems: list[str] = []
            dims.dim(step.components[j], problems)
            diags += [diagnosis(K.DIMENSION, x) for x in problems]
        ok = agrees(D, Tj, scale) and not diags
        if not ok:
            if step.kind == "first integral":
                diags.append(diagnosis(K.NOTE, "its rate along the model's free motion is "
                                       "not 0", prefix=""))
            elif step.kind == "linearised equations":
                diags += _linear_terms(g, step.components[j])
            elif relation:
                diags += _side_factor(g, step.sides[j], scale)
            else:
                diags += value_diagnoses(D, Tj, scale)
                diags += _term_diagnoses(g, step, j, expr, scale)
            together, at = _compiled(g, step), sum(1 for e in step.components[:j]
                                                    if not e.has(sp.nan))
            diags += swap_diagnoses(
                expr, groups,
                lambda a, b: _level(g, step, g.documents(together, read=(a, b))[at]), Tj, scale)
            if not _explained(diags):                 # trials levelled as the truth is
                diags += trig_swap_diagnoses(
                    expr, lambda es: [_level(g, step, v) for v in g.documents(es)], Tj, scale)
            if step.kind == "first integral" or (
                    step.kind == "claim" and not expr.has(*d.positions, *d.velocities)):
                diags += _power_swaps(expr, g, Tj, scale)
        recs.append(ElementRecord(verdict=Verdict.AGREES if ok else Verdict.DIFFERS,
                                  diagnoses=tuple(diags),
                                  max_error=max_error(D, Tj), scale=scale,
                                  document_latex=sp.latex(expr), truth_sample=float(Tj[0]),
                                  document_sample=float(D[0]), **common))
    return recs


def compare_steps(d: Derivation, seed: int = 2026) -> list[ElementRecord]:
    r"""Records of every ``[[step]]`` of ``d``, in the file's order. A step is read under the
    parameter families the file ``[assumes]`` as well as its own ``given``."""
    by_given: dict[tuple, list[int]] = {}
    out: dict[int, list[ElementRecord]] = {}
    assumed = tuple(c.name for c in declared(d).families)
    steps = [replace(s, given=tuple(dict.fromkeys((*assumed, *s.given)))) for s in d.steps]
    for i, s in enumerate(steps):
        if s.kind in RESULT_KINDS:
            out[i] = [compare_result(d, s, i, seed)]
            continue
        if s.kind == "newton-euler":
            out[i] = compare_balance(d, s, i, seed)
            continue
        alone = (i,) if s.kind in ("linearised equations", "first integral") else ()
        by_given.setdefault((s.given, alone), []).append(i)
    for (given, _), idx in by_given.items():
        g = _Group(d, given, seed)
        truths = g.truth([steps[i] for i in idx])
        for i, T in zip(idx, truths):
            out[i] = _records(g, steps[i], i, T)
            todo = [r for r in out[i] if r.verdict == "differs" and not _explained(r.diagnoses)]
            special = _special(d, steps[i], seed) if todo else {}
            out[i] = [replace(r, verdict=Verdict.AGREES_IF, diagnoses=(
                Diagnosis(K.CONDITION, f"agrees only if {special[r.index[1]]}",
                          special[r.index[1]], condition=special[r.index[1]]), *r.diagnoses))
                if r in todo and r.index[1] in special else r for r in out[i]]
    return [r for i in sorted(out) for r in out[i]]


__all__ = ["STEP_SETS", "STEP_STATES", "compare_steps"]
