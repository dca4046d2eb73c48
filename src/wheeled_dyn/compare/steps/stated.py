r"""Stated results of a derivation — a natural frequency, a critical speed — against the
linearisation of the true free motion.

A document that has its equations of motion often goes on to a number: "for small θ,
:math:`\omega_n = \sqrt{3g/2l}`", "the hanging rod becomes unstable above
:math:`\omega_{crit} = \sqrt{3g/2L}`". Such a result is a ``[[step]]`` (``kind = "frequency"``
or ``"critical speed"``) with its printed ``value`` and the state ``about`` which it is stated
(document positions and velocities; velocities not named are 0, positions not named are drawn
at random). The truth comes from the model's reduced equations in the document's coordinates,
:math:`\dot\nu = f(q, \nu) = A^{-1}(-h - Q)`, with :math:`\dot q = \nu` (holonomic sets) or the
least-squares rates of the document's positions that give the model's velocity :math:`S\nu`
(quasi-velocities). The linearisation of the state field :math:`x = (q, \nu)` about the stated
state :math:`x^*`,

.. math::

    \Delta\dot x = J\,\Delta x ,\qquad J = \frac{\partial(\dot q, \dot\nu)}{\partial(q, \nu)}
    \Big|_{x^*}\quad\text{(central differences)},

has eigenvalues :math:`\lambda`:

- **frequency**: the document's value must equal :math:`|\operatorname{Im}\lambda|` of one
  oscillatory mode (:math:`|\operatorname{Re}\lambda|` negligible) at every parameter set;
- **critical speed**: the named velocity ``speed`` is scanned from 0 to :data:`SCAN_SPAN` × the
  document's value; the document's value must be where the largest real part of
  :math:`\lambda` changes sign (located by bisection);
- **steady motion**: the stated state itself must be steady (a steady precession whose rate
  the document gives);
- **stability** (``value = "stable"`` or ``"unstable"``): the claim must hold at the stated
  state — or, with a ``speed``, at every value of that velocity from 0 to :data:`SCAN_SPAN` ×
  the largest :math:`|\lambda|` of the state at rest (a claim "for any speed").

The stated state must be steady: :math:`\dot\nu(x^*) = 0`, and every position that moves there
(a flywheel's angle turning at :math:`\omega_0`) must be ignorable (:math:`f` does not depend on
it); otherwise the result is *undecided* with the reason.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import sympy as sp

from ...constraints.reduction import CoordinateMap
from ...derivations.schema import Derivation
from ...derivations.steps import RESULT_KINDS, Step
from ...errors import DerivationError
from ..judge.diagnose import nice_number
from ..grid.grid import derivation_coordinate_set
from ..sides.document import document_symbol_values, given_parameter_sets
from ..records import Diagnosis, DiagnosisKind as K, ElementRecord, Verdict, diagnosis
from ..records import Step as RecordStep
from ..judge.units import Dim, DimensionChecker, format_dim

#: Parameter sets a result is checked on.
RESULT_SETS = 3
#: Relative agreement of a stated number with the truth's (finite-difference linearisation).
RESULT_TOL = 1e-5
#: Real parts below this fraction of the largest |λ| count as zero (neutral stability).
NEUTRAL_TOL = 1e-6
#: Relative size of ν̇ (against the field's scale) under which the stated state is steady.
STEADY_TOL = 1e-8
#: Central-difference steps of the linearisation (positions, velocities).
FD_Q, FD_NU = 1e-5, 1e-4
#: A critical speed is looked for between 0 and this multiple of the document's value.
SCAN_SPAN = 3.0
#: Points of the first scan for a change of stability.
SCAN_POINTS = 60

StateField = Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]


def state_field(cmap: CoordinateMap, quasi: bool) -> StateField:
    r""":math:`(q, \nu) \mapsto (\dot q, \dot\nu)` of the free motion in the document's
    coordinates (see the module docstring)."""

    def field(q: np.ndarray, nu: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        terms, _, v = cmap.reduce_at(cmap.model_configuration(q), nu, q)
        nudot = np.linalg.solve(terms.A, -(terms.h + terms.Q))
        if not quasi:
            return nu.copy(), nudot
        G = np.stack([(cmap.model_configuration(q + 1e-6 * e) -
                       cmap.model_configuration(q - 1e-6 * e)) / 2e-6
                      for e in np.eye(len(q))], 1)
        return np.linalg.lstsq(G, v, rcond=None)[0], nudot
    return field


class NotSteady(str):
    r"""The reason a stated state is not steady (a text that says what it is by its type)."""

    def __add__(self, other: str) -> "NotSteady":
        return NotSteady(str(self) + other)


def _note(text: str) -> Diagnosis:
    return diagnosis(K.NOTE, text, prefix="")


def linearisation(field: StateField, q0: np.ndarray, nu0: np.ndarray) -> tuple[np.ndarray, str]:
    r"""The Jacobian :math:`J` of the state field at :math:`(q_0, \nu_0)` without the rows and
    columns of ignorable positions (the field does not depend on them: a flywheel's angle, a
    heading; their zero eigenvalues would pair up into a defective block that rounding splits
    into :math:`\pm\sqrt{\epsilon}`), and "" — or, if the state is not steady, no matrix and
    the reason."""
    n = len(q0)
    qdot, nudot = field(q0, nu0)
    cols = []
    for i in range(2 * n):
        e = np.zeros(2 * n)
        e[i] = FD_Q if i < n else FD_NU
        plus, minus = field(q0 + e[:n], nu0 + e[n:]), field(q0 - e[:n], nu0 - e[n:])
        cols.append(np.concatenate([plus[0] - minus[0], plus[1] - minus[1]]) / (2 * e[i]))
    J = np.stack(cols, 1)
    scale = max(float(np.abs(J).max()), 1e-300)
    if np.abs(nudot).max(initial=0.0) > STEADY_TOL * scale * (1 + np.abs(nu0).max(initial=0.0)):
        return np.zeros((0, 0)), NotSteady(f"the stated state is not steady: the true "
                                           f"accelerations there are "
                                           f"{np.round(nudot, 6).tolist()}")
    ignorable = [i for i in range(n) if np.abs(J[:, i]).max() <= np.sqrt(STEADY_TOL) * scale]
    moving = [i for i in range(n) if abs(qdot[i]) > STEADY_TOL * (1 + np.abs(nu0).max())]
    bound = [i for i in moving if i not in ignorable]
    if bound:
        return np.zeros((0, 0)), NotSteady(f"the stated state is not steady: position "
                                           f"{bound[0] + 1} moves and the motion depends on "
                                           "it")
    keep = [i for i in range(2 * n) if i not in ignorable]
    return J[np.ix_(keep, keep)], ""


def frequencies(J: np.ndarray) -> np.ndarray:
    r"""The angular frequencies :math:`\operatorname{Im}\lambda > 0` of the neutral modes."""
    lam = np.linalg.eigvals(J)
    size = max(float(np.abs(lam).max(initial=0.0)), 1e-300)
    keep = (np.abs(lam.real) <= NEUTRAL_TOL * size) & (lam.imag > NEUTRAL_TOL * size)
    return np.sort(lam.imag[keep])


def growth(J: np.ndarray) -> float:
    r"""The largest real part of :math:`\lambda` (1/s)."""
    return float(np.linalg.eigvals(J).real.max(initial=0.0))


def rate_scale(J: np.ndarray) -> float:
    r"""The largest :math:`|\lambda|`: the rate against which a growth counts as zero."""
    return float(np.abs(np.linalg.eigvals(J)).max(initial=0.0))


class _Setting:
    r"""The document's coordinates on one parameter set, and the stated state."""

    def __init__(self, d: Derivation, step: Step, ps, values: dict, rng) -> None:
        self.d, self.step = d, step
        cs = derivation_coordinate_set(d, ps)
        if cs.rolling == "multipliers":
            raise DerivationError(d.path, f"step {step.equation}", f"a {step.kind} needs "
                                  "coordinates with the rolling eliminated (or none)")
        self.cmap = CoordinateMap(ps.model, cs)
        self.field = state_field(self.cmap, cs.kind == "quasi")
        names = [str(p) for p in d.positions], [str(v) for v in d.velocities]
        self.q0 = rng.uniform(-np.pi, np.pi, len(names[0]))
        self.nu0 = np.zeros(len(names[1]))
        self.speed_index = None
        for name, value in step.about:
            x = float(value.xreplace(values))
            if name in names[0]:
                self.q0[names[0].index(name)] = x
            elif name in names[1]:
                self.nu0[names[1].index(name)] = x
            else:
                raise DerivationError(d.path, f"step {step.equation}.about.{name}", "not a "
                                      "position or velocity of the document")
        if step.speed:
            if step.speed not in names[1]:
                raise DerivationError(d.path, f"step {step.equation}.speed", f"{step.speed!r} "
                                      "is not a velocity of the document; valid: "
                                      + ", ".join(names[1]))
            if step.kind == "stability" and dict(step.about).get(step.speed) is not None:
                raise DerivationError(d.path, f"step {step.equation}.about.{step.speed}",
                                      "the velocity a stability claim is for at every value is "
                                      "scanned: it is not also given in about")
            self.speed_index = names[1].index(step.speed)

    def at_speed(self, s: float) -> tuple[np.ndarray, str]:
        nu = self.nu0.copy()
        nu[self.speed_index] = s
        return linearisation(self.field, self.q0, nu)


def _critical(setting: _Setting, stated: float) -> tuple[float | None, str]:
    r"""The speed in :math:`[0, \text{SCAN\_SPAN}\cdot\text{stated}]` where the stability
    changes nearest to the stated one, or None and why."""
    top = SCAN_SPAN * abs(stated)
    grid = np.linspace(0.0, top, SCAN_POINTS + 1)
    rates = []
    for s in grid:
        J, why = setting.at_speed(float(s))
        if why:
            return None, why + f" (at {setting.step.speed} = {s:.4g})"
        rates.append((growth(J), rate_scale(J)))
    # the modes pass through 0 at a change of stability: compare with the scan's largest rate
    floor = NEUTRAL_TOL * max(max(r[1] for r in rates), 1e-300)
    stable = [r[0] <= floor for r in rates]
    changes = [i for i in range(SCAN_POINTS) if stable[i] != stable[i + 1]]
    if not changes:
        return None, (f"the stability does not change for {setting.step.speed} between 0 and "
                      f"{top:.4g} ({'stable' if stable[0] else 'unstable'} throughout)")
    i = min(changes, key=lambda c: abs(grid[c] - abs(stated)))
    lo, hi = grid[i], grid[i + 1]
    while hi - lo > 0.01 * RESULT_TOL * max(abs(stated), 1e-300):
        mid = 0.5 * (lo + hi)
        if (growth(setting.at_speed(mid)[0]) <= floor) == stable[i]:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi), ""


def _dimension(d: Derivation, step: Step, expr: sp.Expr) -> list[Diagnosis]:
    r"""A mismatch between the value's dimension and the result's (1/s for a frequency, the
    scanned velocity's for a critical speed), as a diagnosis; none where units are unknown."""
    checker = DimensionChecker(d)
    problems: list[str] = []
    got = checker.dim(expr, problems)
    want: Dim | None
    if step.kind == "frequency":
        want = (sp.Integer(0), sp.Integer(0), sp.Integer(-1))
    else:
        names = [str(v) for v in d.velocities]
        want = checker.known.get(d.velocities[names.index(step.speed)]) \
            if step.speed in names else None
    out = [diagnosis(K.DIMENSION, x) for x in problems]
    if got is not None and want is not None and tuple(got) != tuple(want):
        out.append(diagnosis(K.DIMENSION, f"the value is {format_dim(got)}, a {step.kind} is "
                             f"{format_dim(want)}"))
    return out


def _stability(setting: _Setting, claim: str) -> str:
    r"""Where the truth contradicts the claimed stability of the stated state ("" if
    nowhere): the state itself, or — with a ``speed`` — the scan of that velocity from 0 to
    :data:`SCAN_SPAN` × the largest rate of the state at rest."""
    def stable(J: np.ndarray, floor: float) -> bool:
        return growth(J) <= floor

    if not setting.step.speed:
        J, why = linearisation(setting.field, setting.q0, setting.nu0)
        if why:
            return why
        ok = stable(J, NEUTRAL_TOL * max(rate_scale(J), 1e-300)) == (claim == "stable")
        return "" if ok else (f"{'un' if claim == 'stable' else ''}stable at the stated state "
                              f"(largest growth rate {growth(J):.3g}/s)")
    J0, why = setting.at_speed(0.0)
    if why:
        return why
    top = SCAN_SPAN * max(rate_scale(J0), 1.0)
    grid = np.linspace(0.0, top, SCAN_POINTS + 1)
    mats = []
    for s in grid:
        J, why = setting.at_speed(float(s))
        if why:
            return why + f" (at {setting.step.speed} = {s:.4g})"
        mats.append(J)
    floor = NEUTRAL_TOL * max(max(rate_scale(J) for J in mats), 1e-300)
    wrong = [s for s, J in zip(grid, mats) if stable(J, floor) != (claim == "stable")]
    if not wrong:
        return ""
    return (f"{'un' if claim == 'stable' else ''}stable for {setting.step.speed} from "
            f"{min(wrong):.4g} to {max(wrong):.4g} (scanned 0 to {top:.4g})")


def _claim_record(d: Derivation, step: Step, index: int, sets, rng) -> ElementRecord:
    r"""The record of a steady-motion or stability claim: where the truth first contradicts
    it over the parameter sets (a stability claim at a state that is not steady is
    undecided)."""
    claim = step.printed[0]
    found = ""
    for ps in sets:
        setting = _Setting(d, step, ps, document_symbol_values(d, ps, rng), rng)
        found = (linearisation(setting.field, setting.q0, setting.nu0)[1]
                 if step.kind == "steady motion" else _stability(setting, claim))
        if found:
            break
    verdict = (Verdict.UNDECIDED if step.kind == "stability" and isinstance(found, NotSteady)
               else Verdict.DIFFERS if found else Verdict.AGREES)
    return ElementRecord(element=f"{step.name} claim", key="step", index=(index, 0),
                         verdict=verdict, diagnoses=(_note(found),) if found else (),
                         document=claim,
                         document_model="", truth=None, residual=None,
                         max_error=float("nan") if found else 0.0, scale=1.0,
                         step=RecordStep(step.kind),
                         equation=step.equation,
                         document_latex="" if step.kind == "steady motion" else claim)


def compare_result(d: Derivation, step: Step, index: int, seed: int) -> ElementRecord:
    r"""The record of one stated result (see the module docstring)."""
    rng = np.random.default_rng([seed, 17, index])
    sets = given_parameter_sets(d, step.given, RESULT_SETS, rng)
    if step.kind in ("steady motion", "stability"):
        return _claim_record(d, step, index, sets, rng)
    expr = step.components[0]
    common = dict(element=f"{step.name} value", key="step", index=(index, 0),
                  document=step.printed[0], document_model="", truth=None, residual=None,
                  step=step.kind, equation=step.equation, document_latex=sp.latex(expr))
    D, T, notes = [], [], []
    dims = _dimension(d, step, expr)
    for ps in sets:
        values = document_symbol_values(d, ps, rng)
        stated = complex(expr.xreplace(values).evalf())
        if stated.imag != 0 or not np.isfinite(stated.real):
            return ElementRecord(verdict=Verdict.UNDECIDED, diagnoses=(diagnosis(
                K.UNDECIDED, f"the document's value is not a finite real number "
                f"({stated:.4g})", prefix=""),),
                max_error=float("nan"), scale=1.0, **common)
        setting = _Setting(d, step, ps, values, rng)
        if step.kind == "frequency":
            J, why = linearisation(setting.field, setting.q0, setting.nu0)
            if why:
                return ElementRecord(verdict=Verdict.UNDECIDED, diagnoses=(_note(why),),
                                     max_error=float("nan"), scale=1.0, **common)
            modes = frequencies(J)
            if not len(modes):
                return ElementRecord(verdict=Verdict.DIFFERS, diagnoses=(diagnosis(
                    K.NOTE, "the true motion about the stated state does not oscillate (no "
                    f"neutral mode; largest growth rate {growth(J):.3g}/s)", prefix=""),),
                    max_error=float("nan"), scale=abs(stated.real), **common)
            truth = float(modes[np.argmin(np.abs(modes - stated.real))])
            notes.append("true frequencies " + ", ".join(f"{w:.6g}" for w in modes))
        else:
            critical, why = _critical(setting, stated.real)
            if critical is None:              # a state that is not steady: undecided
                return ElementRecord(verdict=Verdict.UNDECIDED if isinstance(why, NotSteady)
                                     else Verdict.DIFFERS,
                                     diagnoses=(_note(why),), max_error=float("nan"),
                                     scale=abs(stated.real), **common)
            truth = critical
        D.append(stated.real)
        T.append(truth)
    D_arr, T_arr = np.array(D), np.array(T)
    scale = float(np.abs(T_arr).max(initial=0.0)) or 1.0
    ok = bool(np.all(np.abs(D_arr - T_arr) <= RESULT_TOL * np.abs(T_arr))) and not dims
    diags: list[Diagnosis] = list(dims)
    if not ok:
        ratios = D_arr / T_arr
        if np.ptp(ratios) <= RESULT_TOL * np.abs(ratios).max():
            c = nice_number(float(ratios[0]))
            diags.append(diagnosis(K.FACTOR, f"the document is {c} × the truth", factor=c))
            squared = float(ratios[0]) ** 2
            if abs(squared - round(squared)) > 1e-6 or round(squared) not in (0, 1):
                diags.append(_note(f"its square is {nice_number(squared)} × the truth's"))
        else:
            diags.append(_note("the ratio to the truth changes with the parameters "
                               f"({nice_number(float(ratios.min()))} to "
                               f"{nice_number(float(ratios.max()))})"))
        diags.append(_note(f"at the first parameter set: document {D[0]:.6g}, truth "
                           f"{T[0]:.6g}" + (f" ({notes[0]})" if notes else "")))
    return ElementRecord(verdict=Verdict.AGREES if ok else Verdict.DIFFERS,
                         diagnoses=tuple(diags),
                         max_error=float(np.abs(D_arr - T_arr).max()), scale=scale,
                         truth_sample=T[0], document_sample=D[0], **common)


__all__ = ["RESULT_KINDS", "compare_result", "frequencies", "growth", "linearisation",
           "state_field"]
