r"""Every step of a derivation against the truth, and where an error enters.

For each ``[[step]]`` of a derivation file (:mod:`wheeled_dyn.derivations.steps`), and of the
``*_steps.toml`` files in its folder that name it under ``feeds``:

1. the truth on :data:`STEP_SETS` random parameter sets (of the families the step is ``given``)
   × :data:`STEP_STATES` random states (:mod:`.kinematics_truth`); the document's components
   on the same samples;
2. one :class:`~.result.ElementRecord` per component, ``step`` = the step's kind and
   ``equation`` = its label as printed, with the verdict vocabulary and diagnoses of
   :mod:`.diagnose` (sign, factor, missing, extra, swapped symbols), and, when the component
   differs, its terms: each monomial of the velocities and accelerations
   (:math:`\dot x\dot\psi`, :math:`\ddot\phi`) compared with the truth's coefficient,
   obtained by evaluating the truth at unit velocities and accelerations;
   relations are checked on the model's admissible motions (a configuration relation through
   its rate), a claim between parameters on the parameter sets;
3. internal consistency, without the truth: the fed derivation's :math:`A` against the Hessian
   :math:`\partial^2T/\partial\nu\partial\nu` of the document's own kinetic energy, its
   :math:`Q` against :math:`\partial U/\partial q`;
4. an ``upstream_step`` :class:`~.result.Cause` for each differing term of the equations of
   motion (:math:`h_i`'s product :math:`\nu_j\nu_k`, :math:`A_{ij}`'s acceleration) that an
   earlier step gets wrong too: the first such step of the chain (kinematics before energies
   before generalized forces, then in the document's order).
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Callable, Sequence
from dataclasses import replace
from pathlib import Path

import numpy as np
import sympy as sp

from ..constraints.reduction import CoordinateMap
from ..derivations.builtin import STEPS_SUFFIX
from ..derivations.schema import Derivation
from ..derivations.steps import STEP_KINDS, VECTOR_KINDS, Step
from ..errors import DerivationError
from .diagnose import agrees, max_error, nice_number, swap_diagnoses, value_diagnoses
from .evaluate import derivation_coordinate_set, document_symbol_values
from .kinematics_truth import Motion, along, check_links
from .result import Cause, DerivationResult, ElementRecord
from .samples import parameter_sets, random_states, special_cases
from .units import DimensionChecker, format_dim

#: Parameter sets and states per set on which the steps are compared.
STEP_SETS, STEP_STATES = 3, 40
#: States per set on which the truth's coefficients are computed (only for differing components).
DECOMPOSE_STATES = 8
#: Kinds whose components are polynomial in the velocities and accelerations (decomposable).
_TERMED = (*VECTOR_KINDS, "kinetic energy", "generalized force")
_TRIG_SWAP = {sp.sin: sp.cos, sp.cos: sp.sin}


class _Group:
    r"""The samples, truth and document values of the steps sharing one parameter family."""

    def __init__(self, d: Derivation, given: tuple[str, ...], seed: int) -> None:
        self.d = d
        cases = {c.name: c for c in special_cases(d.model)}
        for name in given:
            if name not in cases:
                raise DerivationError(d.path, "step.given", f"{name!r} is not a parameter family "
                                      f"of model {d.model}; valid: " + ", ".join(cases))
        rng = np.random.default_rng([seed, 11, len(given)])
        self.sets = parameter_sets(d.model, STEP_SETS, rng, tuple(cases[g] for g in given))
        self.cs = derivation_coordinate_set(d, self.sets[0])
        self.cmap = CoordinateMap(self.sets[0].model, self.cs)
        n = len(self.cs.positions)
        declared = dict(d.coordinates.raw.get("ranges", {}))
        ranges = [tuple(declared.get(p, (-np.pi, np.pi))) for p in self.cs.positions]
        q, nu = random_states(n, STEP_SETS * STEP_STATES, rng, ranges)
        self.q, self.nu, self.nudot = q, nu, rng.normal(size=nu.shape)
        self.params = tuple(s.symbol for s in d.symbols.values() if not s.is_input)
        self.values = [document_symbol_values(d, ps, rng) for ps in self.sets]
        self.args = [*d.positions, *d.velocities, *d.accelerations, *self.params]

    def truth(self, steps: Sequence[Step]) -> list[np.ndarray]:
        r"""The truth of every step at every sample; the states are made admissible first."""
        out = [np.zeros((len(self.q), len(s.components))) for s in steps]
        for k, ps in enumerate(self.sets):
            self.cmap.bind(ps.model)
            check_links(ps.model, [b for s in steps for b in (*([s.body] if s.body else []),
                                                              *s.bodies)])
            data = ps.model.model.createData()
            for i in range(k * STEP_STATES, (k + 1) * STEP_STATES):
                m = Motion(self.cmap, data, self.q[i], self.nu[i], self.nudot[i])
                self.nu[i], self.nudot[i] = m.nu, m.nudot
                for s, arr in zip(steps, out):
                    arr[i] = self._true(s, m, k)
        return out

    def coefficients(self, step: Step, monomials: Sequence[tuple[int, ...]]) -> dict:
        r"""The truth's coefficient of each monomial (exponents over velocities then
        accelerations) on the first :data:`DECOMPOSE_STATES` states of each set."""
        n = len(self.cs.positions)
        out = {m: [] for m in monomials}
        for k, ps in enumerate(self.sets):
            self.cmap.bind(ps.model)
            data = ps.model.model.createData()
            for i in range(k * STEP_STATES, k * STEP_STATES + DECOMPOSE_STATES):
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
        return np.concatenate([np.arange(k * STEP_STATES, k * STEP_STATES + DECOMPOSE_STATES)
                               for k in range(len(self.sets))])

    def _true(self, s: Step, m: Motion, k: int) -> np.ndarray:
        if s.kind in VECTOR_KINDS:
            point = s.point
            if isinstance(point, tuple):
                point = np.array([float(sp.sympify(p).xreplace(self.values[k])) for p in point])
            return along(m.vector(s.kind, s.body, point, s.frame), s.axes)
        if s.kind == "kinetic energy":
            return np.array([m.kinetic_energy(s.bodies)])
        if s.kind == "potential energy":
            return np.array([m.potential_energy(s.bodies)])
        if s.kind == "generalized force":
            f = m.inertial_terms()[list(s.rows)]
            return -f if s.quantity == "inertia" else f
        return np.zeros(len(s.components))      # a relation holds on the model's motions

    def _rate(self, expr: sp.Expr) -> sp.Expr:
        r"""A configuration relation's rate :math:`\sum_i \partial f/\partial q_i\,\dot q_i`
        (holonomic sets); velocity relations and parameter claims as they are."""
        d = self.d
        if expr.has(*d.velocities) or not expr.has(*d.positions):
            return expr
        if self.cs.kind != "holonomic":
            raise DerivationError(d.path, "step", "a relation between coordinates is checked "
                                  "through its rate: it needs a holonomic coordinate set")
        return sum((expr.diff(p) * v for p, v in zip(d.positions, d.velocities)), sp.Integer(0))

    _fns: dict = {}

    def _fn(self, expr: sp.Expr) -> Callable:
        key = (tuple(self.args), expr)
        if key not in _Group._fns:
            _Group._fns[key] = sp.lambdify(self.args, expr, "numpy")
        return _Group._fns[key]

    def argv(self, rows: np.ndarray | None = None) -> list[np.ndarray]:
        rows = np.arange(len(self.q)) if rows is None else rows
        per = np.repeat(np.arange(len(self.sets)), STEP_STATES)[rows]
        return [*self.q[rows].T, *self.nu[rows].T, *self.nudot[rows].T,
                *(np.array([self.values[k][p] for k in per]) for p in self.params)]

    def document(self, expr: sp.Expr, rows: np.ndarray | None = None) -> np.ndarray:
        argv = self.argv(rows)
        return np.broadcast_to(np.asarray(self._fn(expr)(*argv), dtype=float),
                               (len(argv[0]),)).copy()


def _monomial_name(mono: tuple[int, ...], names: Sequence[sp.Symbol]) -> str:
    parts = [str(s) for s, e in zip(names, mono) for _ in range(e)]
    return "*".join(parts) if parts else "1"


def _terms(expr: sp.Expr, gens: Sequence[sp.Symbol]) -> dict[tuple[int, ...], sp.Expr] | None:
    try:
        return {m: c for m, c in sp.Poly(sp.expand(expr), *gens).terms()}
    except sp.PolynomialError:
        return None


def _trig_swaps(expr: sp.Expr, g: _Group, T: np.ndarray, scale: float) -> list[str]:
    found = []
    for f in sorted(expr.atoms(sp.sin, sp.cos), key=sp.default_sort_key):
        other = _TRIG_SWAP[f.func](*f.args)
        if agrees(g.document(expr.xreplace({f: other})), T, scale):
            found.append(f"swap: {sp.sstr(f)} where {sp.sstr(other)} fits")
    return found


def _power_swaps(expr: sp.Expr, g: _Group, T: np.ndarray, scale: float) -> list[str]:
    found = []
    powers = sp.Mul.make_args(expr)
    for s in sorted(expr.free_symbols & set(g.params), key=str):
        e = sum((sp.Pow.make_args(f)[0].as_base_exp()[1] for f in powers
                 if f.as_base_exp()[0] == s), sp.Integer(0))
        for p in (-1, 2, sp.Rational(1, 2)):
            if e != 0 and agrees(g.document(expr.xreplace({s: s ** p})), T, scale):
                found.append(f"power: {sp.sstr(s ** e)} where {sp.sstr(s ** (e * p))} fits")
    return found


def _side_factor(g: _Group, sides: tuple[sp.Expr, sp.Expr], scale: float) -> list[str]:
    r"""A relation whose right side is a constant c times what the left side is on the
    model's motions: the true relation has the right side divided by c."""
    L, R = (g.document(g._rate(x)) for x in sides)
    if float(L @ L) <= 0 or float(R @ R) <= 0:
        return []
    c = float(R @ L / (L @ L))
    if not agrees(R, c * L, scale):
        return []
    true = sp.nsimplify(sides[1] / sp.nsimplify(nice_number(c)))
    return [f"factor: the right side is {nice_number(c)} × what the left side is on the "
            f"model's motions; true: {sp.sstr(sides[0])} = {sp.sstr(true)}"]


def _swap_groups(d: Derivation) -> list[list[sp.Symbol]]:
    by_units: dict[str, list[sp.Symbol]] = {}
    for spec in d.symbols.values():
        if not spec.is_input and spec.units:
            by_units.setdefault(spec.units.replace(" ", ""), []).append(spec.symbol)
    return [list(d.velocities), list(d.positions), *[v for v in by_units.values() if len(v) > 1]]


def _term_diagnoses(g: _Group, step: Step, j: int, expr: sp.Expr, scale: float) -> list[str]:
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
    values = {m: (g.document(doc.get(m, sp.Integer(0)), rows), truth[m][:, j]) for m in monos}
    cscale = max([float(np.abs(v).max(initial=0.0)) for pair in values.values() for v in pair]
                 + [1e-300])
    out = []
    for m, (D, T) in values.items():
        if not np.all(np.isfinite(T)) or agrees(D, T, cscale):
            continue
        why = value_diagnoses(D, T, cscale) or ["differs"]
        out.append(f"term {_monomial_name(m, gens)}: {why[0]}")
    return out


def _records(g: _Group, step: Step, index: int, T: np.ndarray) -> list[ElementRecord]:
    d = g.d
    names = step.component_names()
    groups = _swap_groups(d)
    dims = DimensionChecker(d)
    recs = []
    D_all, parts = [], []
    for j, expr in enumerate(step.components):
        lost = expr.has(sp.nan)
        D_all.append(None if lost else g.document(g._rate(expr)))
        if step.kind in ("constraint", "claim") and not lost:
            parts += [g.document(g._rate(side)) for side in step.sides[j]]
    scale = max([float(np.abs(a).max(initial=0.0))
                 for a in (*[x for x in D_all if x is not None], T, *parts)
                 if np.all(np.isfinite(a))] + [1e-300])
    for j, expr in enumerate(step.components):
        D, Tj = D_all[j], T[:, j]
        element = f"{step.name} {names[j]}"
        common = dict(element=element, key="step", index=(index, j), document=step.printed[j],
                      document_model="", truth=None, residual=None, step=step.kind,
                      equation=step.equation)
        if D is None or not np.all(np.isfinite(D)) or not np.all(np.isfinite(Tj)):
            why = "lost in the extracted text: not compared" if D is None else \
                "not finite at some samples"
            recs.append(ElementRecord(verdict="undecided", diagnoses=(why,), max_error=float("nan"),
                                      scale=scale, **common))
            continue
        diags: list[str] = []
        expr = g._rate(step.components[j])
        relation = step.kind in ("constraint", "claim")
        if relation:
            lhs, rhs = step.sides[j]
            dl, dr = dims.dim(lhs, []), dims.dim(rhs, [])
            if dl is not None and dr is not None and dl != dr:
                diags.append(f"dimension: the left side is {format_dim(dl)}, the right side "
                             f"{format_dim(dr)}")
        ok = agrees(D, Tj, scale) and not diags
        if not ok:
            if relation:
                diags += _side_factor(g, step.sides[j], scale)
            else:
                diags += value_diagnoses(D, Tj, scale)
                diags += _term_diagnoses(g, step, j, expr, scale)
            diags += swap_diagnoses(expr, groups, lambda a, b: g.document(expr.xreplace({a: b})),
                                    Tj, scale)
            diags += _trig_swaps(expr, g, Tj, scale)
            if step.kind == "claim" and not expr.has(*d.positions, *d.velocities):
                diags += _power_swaps(expr, g, Tj, scale)
        recs.append(ElementRecord(verdict="agrees" if ok else "differs", diagnoses=tuple(diags),
                                  max_error=max_error(D, Tj), scale=scale,
                                  document_latex=sp.latex(expr), truth_sample=float(Tj[0]),
                                  document_sample=float(D[0]), **common))
    return recs


def compare_steps(d: Derivation, seed: int = 2026) -> list[ElementRecord]:
    r"""Records of every ``[[step]]`` of ``d``, in the file's order."""
    by_given: dict[tuple[str, ...], list[int]] = {}
    for i, s in enumerate(d.steps):
        by_given.setdefault(s.given, []).append(i)
    out: dict[int, list[ElementRecord]] = {}
    for given, idx in by_given.items():
        g = _Group(d, given, seed)
        truths = g.truth([d.steps[i] for i in idx])
        for i, T in zip(idx, truths):
            out[i] = _records(g, d.steps[i], i, T)
    return [r for i in sorted(out) for r in out[i]]


def _hessian_records(steps_d: Derivation, eom: Derivation, seed: int) -> list[ElementRecord]:
    r"""The fed derivation's A against the Hessian of the document's own total kinetic energy,
    and its Q against the gradient of its own total potential energy (names matched)."""
    out: list[ElementRecord] = []
    names = [str(v) for v in eom.velocities]
    if [str(v) for v in steps_d.velocities] != names or \
            [str(p) for p in steps_d.positions] != [str(p) for p in eom.positions]:
        return out
    terms = eom.read_off(assume=True, unscale=True)
    rng = np.random.default_rng([seed, 13])
    sets = parameter_sets(eom.model, 2, rng)
    for s in steps_d.steps:
        if s.bodies or s.given or s.kind not in ("kinetic energy", "potential energy"):
            continue
        expr = s.components[0].xreplace(dict(zip(steps_d.positions, eom.positions)))
        expr = expr.xreplace(dict(zip(steps_d.velocities, eom.velocities)))
        if s.kind == "kinetic energy" and terms.A is not None:
            own = sp.hessian(expr, eom.velocities)
            pairs = [(f"A[{i + 1},{j + 1}]", terms.A[i, j], own[i, j], f"∂²T/∂{names[i]}∂{names[j]}")
                     for i in range(eom.n) for j in range(eom.n)]
        elif s.kind == "potential energy" and terms.Q is not None:
            pairs = [(f"Q[{i + 1}]", terms.Q[i], expr.diff(p), f"∂U/∂{p}")
                     for i, p in enumerate(eom.positions)]
        else:
            continue
        states = rng.uniform(-np.pi, np.pi, (20, eom.n))
        for label, a, b, what in pairs:
            if a.has(sp.nan):
                continue
            fa = sp.lambdify(eom.positions, a.xreplace(_values(eom, sets, 0)), "numpy")
            Da, Db = [], []
            for k in range(len(sets)):
                va, vb = _values(eom, sets, k), _values(steps_d, sets, k)
                fa = sp.lambdify(eom.positions, a.xreplace(va), "numpy")
                fb = sp.lambdify(eom.positions, b.xreplace(vb), "numpy")
                Da.append(np.broadcast_to(fa(*states.T), (len(states),)))
                Db.append(np.broadcast_to(fb(*states.T), (len(states),)))
            Da, Db = np.concatenate(Da).astype(float), np.concatenate(Db).astype(float)
            scale = max(float(np.abs(Da).max()), float(np.abs(Db).max()), 1e-300)
            ok = agrees(Da, Db, scale)
            diags = () if ok else (f"{label} of {eom.path.stem} is not {what} of the document's "
                                   f"own energy {s.equation}", *value_diagnoses(Da, Db, scale))
            out.append(ElementRecord(
                element=f"{label} vs {what} {s.equation}", key="consistency", index=(),
                verdict="agrees" if ok else "differs", diagnoses=diags, document=sp.sstr(a),
                document_model=sp.sstr(b), truth=None, residual=None,
                max_error=max_error(Da, Db), scale=scale, step=s.kind, equation=s.equation))
    return out


def _values(d: Derivation, sets, k: int) -> dict:
    rng = np.random.default_rng(k)
    return {s: sp.Float(v) for s, v in document_symbol_values(d, sets[k], rng).items()}


def _mono(r: ElementRecord, eom: Derivation) -> Counter | None:
    if r.key == "h":
        return Counter(r.element.split(":", 1)[1].split("*"))
    if r.key == "A":
        return Counter([str(eom.accelerations[r.index[1]])])
    return None


def upstream_causes(steps: Sequence[ElementRecord], eom_records: Sequence[ElementRecord],
                    eom: Derivation) -> list[Cause]:
    r"""For each differing term of the equations of motion, the first step (of the chain,
    :data:`STEP_KINDS` order, then the document's) whose same term differs."""
    level = {k: i for i, k in enumerate(STEP_KINDS)}
    chain = sorted((r for r in steps if r.verdict == "differs" and r.key == "step"),
                   key=lambda r: level.get(r.step, len(level)))
    found: dict[tuple[str, str], list[str]] = {}
    for r in eom_records:
        mono = _mono(r, eom) if r.verdict == "differs" else None
        if not mono:
            continue
        for s in chain:
            hit = next((x for x in s.diagnoses if x.startswith("term ")
                        and Counter(x[5:].split(":", 1)[0].split("*")) == mono), None)
            if hit:
                found.setdefault((s.element, hit), []).append(r.element)
                break
    out = []
    for (element, hit), labels in found.items():
        s = next(x for x in chain if x.element == element)
        term = hit[5:].split(":", 1)[0]
        rows = sorted({lab.split("[")[1].split("]")[0].split(",")[0] for lab in labels})
        out.append(Cause(kind="upstream_step", elements=tuple(labels),
                         explanation=f"{element} differs ({hit[5:]}); the {term} term of "
                         f"equation{'s' if len(rows) > 1 else ''} {', '.join(rows)} "
                         f"({', '.join(labels)}) follows from it",
                         step=s.step, equation=s.equation))
    return out


_STEP_CACHE: dict[tuple, tuple[Derivation, list[ElementRecord]]] = {}


def _step_file(path: Path, seed: int):
    from ..derivations.parse import load_derivation
    key = (str(path), path.stat().st_mtime_ns, seed)
    if key not in _STEP_CACHE:
        sd = load_derivation(path)
        _STEP_CACHE[key] = (sd, compare_steps(sd, seed))
    return _STEP_CACHE[key]


def feeding_files(d: Derivation) -> list[Path]:
    r"""The ``*_steps.toml`` files beside ``d`` whose ``feeds`` name it (sorted)."""
    from ..derivations.parse import load_derivation
    folder = d.path.parent
    if not folder.is_dir():
        return []
    return [p for p in sorted(folder.glob("*" + STEPS_SUFFIX))
            if p != d.path and d.path.stem in load_derivation(p).feeds]


def has_equations(d: Derivation) -> bool:
    return d.equations is not None or any(getattr(d, k) is not None for k in "ACQBG")


def with_steps(d: Derivation, compare: Callable[[Derivation], DerivationResult],
               seed: int = 2026) -> DerivationResult:
    r"""``compare(d)`` (the equations of motion, when the file has them) with the records of
    its steps and of the step files that feed it, the consistency of its A and Q with the
    document's own energies, and the ``upstream_step`` causes."""
    own = compare_steps(d, seed) if d.steps else []
    fed = [_step_file(p, seed) for p in feeding_files(d)]
    if not has_equations(d):
        return DerivationResult(
            path=d.path, title=d.title, model=d.model, source=dict(d.source),
            coordinates=d.coordinates.use or "inline",
            velocities=tuple(str(v) for v in d.velocities), form="steps", records=tuple(own),
            row_factors=(), energy=None, asymmetric=(), constraints=(),
            reconstructed=dict(d.reconstructed), samples=STEP_STATES, parameter_sets=STEP_SETS)
    base = compare(d)
    if not own and not fed:
        return base
    steps = own + [r for _, recs in fed for r in recs]
    consistency = _hessian_records(d, d, seed) + [r for sd, _ in fed
                                                   for r in _hessian_records(sd, d, seed)]
    causes = upstream_causes(steps, base.records, d)
    return replace(base, records=tuple(base.records) + tuple(steps) + tuple(consistency),
                   causes=tuple(base.causes) + tuple(causes))


__all__ = ["STEP_SETS", "STEP_STATES", "compare_steps", "feeding_files", "upstream_causes",
           "with_steps"]
