r"""Fast simulation of a wheeled model on its reduced equations in closed form.

The same equations as :mod:`.reduced` (state: the full model configuration :math:`q` and the
document velocities :math:`\nu`),

.. math::

    \dot q = S(q)\,\nu,\qquad A_\nu(q)\,\dot\nu = B_\nu(q)\,u - h_\nu(q,\nu) - Q_\nu(q),

but with :math:`S, A_\nu, h_\nu, Q_\nu, B_\nu` from
:func:`~wheeled_dyn.symbolic.wheeled.wheeled_symbolic` (``"numbers"``: the model's own numbers
substituted once, terms as functions of the model coordinates) compiled into one scalar Python
function: common subexpressions shared (``sympy.cse``), ``math`` functions on Python floats,
and the symmetric positive definite :math:`A_\nu` solved by an unrolled
:math:`LDL^T` factorisation (no NumPy call, no array allocation but the returned list).
Integration by :func:`scipy.integrate.solve_ivp` (DOP853). The energy
:math:`E = \tfrac12\nu^TA_\nu\nu + U(q)` is evaluated on the samples in one vectorised call.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import sympy as sp
from scipy.integrate import solve_ivp
from sympy.printing.pycode import PythonCodePrinter

from ..coordinates.spec import CoordinateSet
from ..errors import StateError
from ..models.builder import WheeledModel
from .reduced import Input, Trajectory

#: Default tolerances (relative, absolute): energy drift below 1e-9 over 10 s for the WIP.
FAST_RTOL, FAST_ATOL = 1e-9, 1e-11


class _Printer(PythonCodePrinter):
    """Python code with bare ``sin``/``cos``/``sqrt`` and floats at full precision."""

    def __init__(self) -> None:
        super().__init__({"fully_qualified_modules": False})

    def _print_Float(self, expr: sp.Float) -> str:
        return repr(float(expr))

    def _print_Rational(self, expr: sp.Rational) -> str:
        return repr(float(expr))

    def _print_Integer(self, expr: sp.Integer) -> str:
        return str(int(expr))


_NAMESPACE = {"sin": math.sin, "cos": math.cos, "tan": math.tan, "sqrt": math.sqrt,
              "exp": math.exp, "math": math}


def _ldlt_lines(n: int, a: Callable[[int, int], str], b: Callable[[int], str],
                x: Callable[[int], str]) -> list[str]:
    r"""Unrolled :math:`A x = b` for a symmetric positive definite ``A`` by
    :math:`A = LDL^T` (lines of Python, names from ``a(i, j)`` (``i >= j``), ``b(i)``;
    the solution is assigned to ``x(i)``)."""
    lines = []
    for j in range(n):
        terms = "".join(f" - _L{j}_{k}*_L{j}_{k}*_D{k}" for k in range(j))
        lines.append(f"_D{j} = {a(j, j)}{terms}")
        for i in range(j + 1, n):
            terms = "".join(f" - _L{i}_{k}*_L{j}_{k}*_D{k}" for k in range(j))
            lines.append(f"_L{i}_{j} = ({a(i, j)}{terms})/_D{j}")
    for i in range(n):
        terms = "".join(f" - _L{i}_{k}*_z{k}" for k in range(i))
        lines.append(f"_z{i} = {b(i)}{terms}")
    for i in reversed(range(n)):
        terms = "".join(f" - _L{k}_{i}*{x(k)}" for k in range(i + 1, n))
        lines.append(f"{x(i)} = _z{i}/_D{i}{terms}")
    return lines


def compile_rhs(S: sp.Matrix, A: sp.Matrix, force: sp.Matrix, q: Sequence[sp.Symbol],
                nu: Sequence[sp.Symbol], u: Sequence[sp.Symbol] = ()) -> Callable:
    r"""A Python function ``f(Y, U) -> list`` of :math:`[\dot q;\ \dot\nu]` with
    :math:`\dot q = S\nu` and :math:`A\dot\nu = \text{force}`, ``Y`` the list
    :math:`[q;\ \nu]`, ``U`` the list of inputs (symbols ``u`` in ``force``)."""
    nq, n = len(q), len(nu)
    ys = sp.symbols(f"_y0:{nq + n}")
    us = sp.symbols(f"_u0:{len(u)}") if u else ()
    rename = dict(zip(q, ys[:nq])) | dict(zip(nu, ys[nq:])) | dict(zip(u, us))
    qdot = list(S * sp.Matrix(nu))
    a_idx = [(i, j) for i in range(n) for j in range(i + 1)]
    exprs = [sp.sympify(e).xreplace(rename) for e in
             qdot + [A[i, j] for i, j in a_idx] + list(force)]
    reps, reduced = sp.cse(exprs, symbols=sp.numbered_symbols("_c"), order="none")
    pr = _Printer()
    lines = ["def _rhs(Y, U):"]
    body = [f"{', '.join(str(s) for s in ys)}, = Y"]
    if us:
        body.append(f"{', '.join(str(s) for s in us)}, = U")
    body += [f"{s} = {pr.doprint(e)}" for s, e in reps]
    body += [f"_qd{i} = {pr.doprint(e)}" for i, e in enumerate(reduced[:nq])]
    for (i, j), e in zip(a_idx, reduced[nq:nq + len(a_idx)]):
        body.append(f"_a{i}_{j} = {pr.doprint(e)}")
    for i, e in enumerate(reduced[nq + len(a_idx):]):
        body.append(f"_b{i} = {pr.doprint(e)}")
    body += _ldlt_lines(n, lambda i, j: f"_a{i}_{j}", lambda i: f"_b{i}", lambda i: f"_x{i}")
    out = [f"_qd{i}" for i in range(nq)] + [f"_x{i}" for i in range(n)]
    body.append(f"return [{', '.join(out)}]")
    source = "\n".join(lines + ["    " + line for line in body])
    namespace = dict(_NAMESPACE)
    exec(compile(source, "<wheeled_dyn fast rhs>", "exec"), namespace)  # noqa: S102
    fn: Any = namespace["_rhs"]            # made by exec: a function with its source
    fn.source = source
    return fn


@dataclass(frozen=True)
class FastModel:
    r"""Compiled reduced equations of one model and coordinate set: ``rhs(Y, U)`` (lists),
    ``energy(q, nu)`` (arrays N × nq, N × n → N), sizes and names."""

    rhs: Callable
    energy_batch: Callable
    nq: int
    n: int
    n_inputs: int
    velocities: tuple[str, ...]
    coordinate_names: tuple[str, ...]

    def energy(self, q: np.ndarray, nu: np.ndarray) -> np.ndarray:
        q, nu = np.atleast_2d(q), np.atleast_2d(nu)
        return np.broadcast_to(self.energy_batch(*q.T, *nu.T), (len(q),)).astype(float)


_COMPILED: dict[tuple, FastModel] = {}


def _model_key(wm: WheeledModel, cs: CoordinateSet) -> tuple:
    from ..symbolic.cache import model_fingerprint
    from ..symbolic.parameters import numeric_parameters
    from ..symbolic.wheeled import coordinate_set_key
    inertias = tuple(x for pi in numeric_parameters(wm.model).values() for x in pi)
    return (wm.name, model_fingerprint(wm.model), inertias, tuple(wm.model.armature),
            tuple(wm.model.gravity.linear), tuple(w.radius for w in wm.wheels), wm.springs,
            coordinate_set_key(cs))


def fast_model(wm: WheeledModel, cs: CoordinateSet) -> FastModel:
    r"""The compiled equations of ``wm`` (its numbers) in ``cs`` (kind ``quasi``, rolling
    eliminated); cached in memory per model numbers and coordinate set."""
    if cs.kind != "quasi" or cs.rolling != "eliminate":
        raise StateError(None, cs.name, "a quasi-velocity coordinate set with rolling "
                                        "eliminated (e.g. 'seed001', 'heading', 'wheels')")
    key = _model_key(wm, cs)
    if key in _COMPILED:
        return _COMPILED[key]
    from ..symbolic.wheeled import symbolic_parts
    sym, red = symbolic_parts(wm, cs, "numbers", simplify=False, model_coordinates=True)
    q, nu = tuple(red.q), tuple(red.nu)
    k = 0 if red.B is None else red.B.shape[1]
    us = sp.symbols(f"_input0:{k}") if k else ()
    force = -red.h - red.Q
    if k:
        force += red.B * sp.Matrix(us)
    rhs = compile_rhs(red.S, red.A, force, q, nu, us)
    nu_col = sp.Matrix(nu)
    E = (nu_col.T * red.A * nu_col)[0, 0] / 2 + sym.potential_energy
    energy = sp.lambdify([*q, *nu], E, modules="numpy", cse=True)
    fm = FastModel(rhs, energy, len(q), len(nu), k, tuple(cs.velocities),
                   tuple(wm.coordinate_names))
    _COMPILED[key] = fm
    return fm


#: Most samples of a trajectory (duration × rate): 10**9 of them took all the memory.
MAX_SAMPLES = 10 ** 6


def simulate_fast(wm: WheeledModel, cs: CoordinateSet, q0: np.ndarray, nu0: np.ndarray,
                  duration: float, rate: float = 1000.0, u: Input | None = None,
                  rtol: float = FAST_RTOL, atol: float = FAST_ATOL) -> Trajectory:
    r"""Integrate the closed-form reduced equations of ``wm`` in ``cs`` from model
    configuration ``q0`` and document velocities ``nu0`` for ``duration`` seconds, sampled at
    ``rate`` Hz; ``u(t, q, nu)`` gives the motor torques (default zero). Same result type as
    :func:`~wheeled_dyn.simulate.reduced.simulate`; the energy is evaluated on every sample
    (constant only without input)."""
    fm = fast_model(wm, cs)
    nq, n = fm.nq, fm.n
    y0 = np.concatenate([np.asarray(q0, float).reshape(-1), np.asarray(nu0, float).reshape(-1)])
    if y0.shape != (nq + n,) or not np.all(np.isfinite(y0)):
        raise StateError(None, y0.tolist(), f"{nq} finite coordinates and {n} velocities")
    if not (duration > 0 and rate > 0):
        raise StateError("duration", duration, "a positive duration and rate")
    if duration * rate > MAX_SAMPLES:
        raise StateError("duration", duration, f"at most {MAX_SAMPLES:g} samples "
                         f"(duration × rate; the rate is {rate:g} Hz)")
    core = fm.rhs
    zero = [0.0] * fm.n_inputs
    if u is None:
        def rhs(t: float, y: np.ndarray) -> list:
            return core(y.tolist(), zero)
    else:
        def rhs(t: float, y: np.ndarray) -> list:
            return core(y.tolist(), np.asarray(u(t, y[:nq], y[nq:]), float).tolist())
    t_eval = np.linspace(0.0, duration, int(round(duration * rate)) + 1)
    try:
        with np.errstate(over="raise", invalid="raise"):
            sol = solve_ivp(rhs, (0.0, duration), y0, method="DOP853", t_eval=t_eval,
                            rtol=rtol, atol=atol)
    except (OverflowError, FloatingPointError, ValueError) as exc:
        raise StateError(None, y0.tolist(), f"a motion the integration can follow ({exc}: "
                         "the state overflows)") from None
    if not sol.success:
        raise StateError(None, float(sol.t[-1]), f"integration to {duration} s ({sol.message})")
    qs, nus = sol.y[:nq].T, sol.y[nq:].T
    if u is None:
        us = np.zeros((len(sol.t), fm.n_inputs))
    else:
        us = np.array([np.asarray(u(t, q, v), float) for t, q, v in zip(sol.t, qs, nus)])
        us = us.reshape(len(sol.t), fm.n_inputs)
    return Trajectory(sol.t, qs, nus, us, fm.energy(qs, nus), fm.velocities,
                      fm.coordinate_names)
