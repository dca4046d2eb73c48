r"""Time of the symbolic derivation of a WIP-sized model (planar base PX, PY, RZ; a pitching
body; two wheels: 6 joints), in Khalil's 60 standard parameters, against SymPy's own
``sympy.physics.mechanics.LagrangesMethod`` and ``KanesMethod`` on the same system, in one run.

Ours: :func:`wheeled_dyn.symbolic.cached_symbolic_model` — cold (A, Q, Christoffel symbols,
C, h, energies, simplified) into an empty cache, then cached. SymPy: the Lagrangian of the six
rigid bodies (same kinematics, inertia about the joint-frame origin, first moments MS), then
``form_lagranges_equations``, ``mass_matrix`` and ``forcing`` (no simplification), and the
mass matrix simplified with ``trigsimp`` (what one does to read it). ``KanesMethod`` on the
same bodies (generalized speeds :math:`u = \dot q`; each a ``RigidBody`` with inertia
:math:`J_O` about its joint-frame origin and mass centre :math:`O + MS/M`, gravity at the mass
centre), ``kanes_equations``, ``mass_matrix`` and ``forcing`` (no simplification). Every
derivation starts from an empty SymPy cache. Both SymPy mass matrices and generalized-force
vectors are checked equal to ours at a random state and parameter set (:data:`CHECK_RTOL`;
the script exits with 1 on a mismatch).

The closed forms with intermediate variables of larger trees (UR5, TIAGo) and SymPy on them:
``bench_symbolic_tree.py``.

Run: ``.venv/bin/python benchmarks/bench_symbolic.py``.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from dataclasses import dataclass

import numpy as np
import pinocchio as pin
import sympy as sp
from sympy.core.cache import clear_cache
from sympy.physics import mechanics as me

from wheeled_dyn.symbolic import (
    PARAMETER_NAMES, cached_symbolic_model, lambdify_terms, parameter_vector, symbolic_model)

SEED = 11
#: Geometry of the WIP-like model: pitch joint height, half track.
PITCH_HEIGHT = sp.Rational(3, 10)
HALF_TRACK = sp.Rational(1, 4)
#: Gravity of the SymPy systems (m/s^2, along -z), as Pinocchio's default.
GRAVITY = 9.81
#: Agreement required between the two derivations (relative).
CHECK_RTOL = 1e-9


def wip_model() -> pin.Model:
    m = pin.Model()
    m.name = "wip_like"
    rng = np.random.default_rng(SEED)

    def inertia() -> pin.Inertia:
        return pin.Inertia.FromLogCholeskyParameters(
            pin.LogCholeskyParameters(rng.normal(scale=0.5, size=10)))

    parent = 0
    for name, joint in (("x", pin.JointModelPX()), ("y", pin.JointModelPY()),
                        ("psi", pin.JointModelRZ())):
        parent = m.addJoint(parent, joint, pin.SE3.Identity(), name)
        m.appendBodyToJoint(parent, inertia(), pin.SE3.Identity())
    jphi = m.addJoint(parent, pin.JointModelRevoluteUnaligned(np.array([0.0, 1.0, 0.0])),
                      pin.SE3(np.eye(3), np.array([0.0, 0.0, float(PITCH_HEIGHT)])), "phi")
    m.appendBodyToJoint(jphi, inertia(), pin.SE3.Identity())
    for name, y in (("thl", HALF_TRACK), ("thr", -HALF_TRACK)):
        j = m.addJoint(jphi, pin.JointModelRY(), pin.SE3(np.eye(3), np.array([0, float(y), 0])),
                       name)
        m.appendBodyToJoint(j, inertia(), pin.SE3.Identity())
    return m


@dataclass(frozen=True)
class MechanicsSystem:
    r"""Rigid bodies for ``sympy.physics.mechanics``: coordinates ``q`` (dynamic symbols), the
    inertial frame ``N`` and origin ``O``, and per body its frame, the origin of its joint
    frame (velocity set) and its ten standard parameters (symbols, in ``params`` order)."""

    q: list
    N: me.ReferenceFrame
    O: me.Point
    bodies: list[tuple[me.ReferenceFrame, me.Point, tuple[sp.Symbol, ...]]]
    params: list[sp.Symbol]
    g: float


def body_parameters(name: str) -> tuple[sp.Symbol, ...]:
    return tuple(sp.symbols([f"{n}_{name}" for n in PARAMETER_NAMES]))


def wip_system(g: float = GRAVITY) -> MechanicsSystem:
    """The WIP-sized model of :func:`wip_model` as frames and points of sympy.mechanics."""
    names = ("x", "y", "psi", "phi", "thl", "thr")
    q = me.dynamicsymbols(" ".join(names))
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    frames, points = {}, {}
    frames["x"] = frames["y"] = N
    points["x"] = O.locatenew("Px", q[0] * N.x)
    points["y"] = points["x"].locatenew("Py", q[1] * N.y)
    frames["psi"] = N.orientnew("Fpsi", "Axis", (q[2], N.z))
    points["psi"] = points["y"]
    frames["phi"] = frames["psi"].orientnew("Fphi", "Axis", (q[3], frames["psi"].y))
    points["phi"] = points["psi"].locatenew("Pphi", PITCH_HEIGHT * frames["psi"].z)
    for k, (name, y) in enumerate((("thl", HALF_TRACK), ("thr", -HALF_TRACK))):
        frames[name] = frames["phi"].orientnew(f"F{name}", "Axis", (q[4 + k], frames["phi"].y))
        points[name] = points["phi"].locatenew(f"P{name}", y * frames["phi"].y)
    for pt in {id(p): p for p in points.values()}.values():
        pt.set_vel(N, pt.pos_from(O).dt(N))
    bodies = [(frames[n], points[n], body_parameters(n)) for n in names]
    return MechanicsSystem(q, N, O, bodies, [s for *_, pis in bodies for s in pis], g)


def _body_terms(F: me.ReferenceFrame, pis: tuple[sp.Symbol, ...]):
    M, MX, MY, MZ, XX, XY, YY, XZ, YZ, ZZ = pis
    J = me.inertia(F, XX, YY, ZZ, XY, YZ, XZ)       # about the joint-frame origin P
    MS = MX * F.x + MY * F.y + MZ * F.z
    return M, J, MS


def lagrange_equations(system: MechanicsSystem) -> tuple[sp.Matrix, sp.Matrix]:
    r"""``LagrangesMethod`` on ``system``: its ``mass_matrix`` and ``forcing`` (no
    simplification), from :math:`E = \tfrac12(\omega^TJ_O\omega + Mv^Tv + 2MS^T(v\times\omega))`,
    :math:`U = -g^T(Mp + R\,MS)` of every body."""
    N, O = system.N, system.O
    T = 0
    V = 0
    for F, P, pis in system.bodies:
        M, J, MS = _body_terms(F, pis)
        v = P.vel(N)
        w = F.ang_vel_in(N)
        T += (w.dot(J.dot(w)) + M * v.dot(v) + 2 * MS.dot(v.cross(w))) / 2
        V += system.g * (M * P.pos_from(O) + MS).dot(N.z)
    lm = me.LagrangesMethod(T - V, system.q)
    lm.form_lagranges_equations()
    return lm.mass_matrix, lm.forcing


def kane_equations(system: MechanicsSystem) -> tuple[sp.Matrix, sp.Matrix, list]:
    r"""``KanesMethod`` on ``system`` (generalized speeds :math:`u = \dot q`): its
    ``mass_matrix`` and ``forcing`` (no simplification) and the speeds. Each body a
    ``RigidBody`` with inertia :math:`J_O` about its joint-frame origin and mass centre
    :math:`O + MS/M`; gravity :math:`-Mg\,z` at the mass centre."""
    N, q = system.N, system.q
    u = me.dynamicsymbols(f"u0:{len(q)}")
    bodies, loads = [], []
    for k, (F, P, pis) in enumerate(system.bodies):
        M, J, MS = _body_terms(F, pis)
        G = P.locatenew(f"G{k}", MS / M)
        G.v2pt_theory(P, N, F)
        bodies.append(me.RigidBody(f"B{k}", G, F, M, (J, P)))
        loads.append((G, -M * system.g * N.z))
    km = me.KanesMethod(N, q_ind=list(q), u_ind=u,
                        kd_eqs=[qi.diff(me.dynamicsymbols._t) - ui for qi, ui in zip(q, u)])
    km.kanes_equations(bodies, loads)
    return km.mass_matrix, km.forcing, u


def timed(f, *args, **kw):
    """``(f(*args, **kw), seconds)``."""
    t0 = time.perf_counter()
    out = f(*args, **kw)
    return out, time.perf_counter() - t0


def numeric_equations(M: sp.Matrix, forcing: sp.Matrix, q: list, speeds: list,
                      params: list[sp.Symbol], qv: np.ndarray, vv: np.ndarray,
                      p: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    r"""SymPy's ``mass_matrix`` and ``forcing`` (in dynamic symbols ``q`` and ``speeds``)
    evaluated at ``(qv, vv)`` and parameters ``p``."""
    qs, vs = sp.symbols(f"q0:{len(q)}"), sp.symbols(f"v0:{len(q)}")
    t = me.dynamicsymbols._t
    rename = dict(zip(speeds, vs)) | {qi.diff(t): v for qi, v in zip(q, vs)} | dict(zip(q, qs))
    Mn = sp.lambdify([qs, params], M.xreplace(rename))(qv, p)
    Fn = sp.lambdify([qs, vs, params], forcing.xreplace(rename))(qv, vv, p)
    return np.asarray(Mn, dtype=float), np.asarray(Fn, dtype=float).ravel()


def relative_errors(Mn: np.ndarray, Fn: np.ndarray, A: np.ndarray, hq: np.ndarray
                    ) -> tuple[float, float]:
    r"""Largest differences of SymPy's mass matrix from :math:`A` and of its forcing from
    :math:`-(h + Q)`, relative to the largest entry of each."""
    return (float(np.max(np.abs(Mn - A)) / np.max(np.abs(A))),
            float(np.max(np.abs(Fn + hq)) / np.max(np.abs(hq))))


def main() -> int:
    model = wip_model()
    warm = pin.Model()
    warm.addJoint(0, pin.JointModelRY(), pin.SE3.Identity(), "warm")
    symbolic_model(warm)  # imports warmed, not timed
    # every derivation starts from an empty SymPy cache (none profits from another's work)
    with tempfile.TemporaryDirectory() as root:
        os.environ.pop("WHEELED_DYN_CACHE", None)
        clear_cache()
        sym, t_cold = timed(cached_symbolic_model, model, root=root)
        _, t_cached = timed(cached_symbolic_model, model, root=root)
    clear_cache()
    _, t_nosimp = timed(symbolic_model, model, simplify=False)
    _, t_C = timed(sym.C, None, True)

    # SymPy's two methods on the same bodies, each from the frames and points up
    clear_cache()
    lag_system, t_lag = timed(wip_system)
    (Mm, Fm), t = timed(lagrange_equations, lag_system)
    t_lag += t
    Ms, t_lag_simp = timed(lambda: Mm.applyfunc(sp.trigsimp))
    clear_cache()
    kane_system, t_kane = timed(wip_system)
    (Mk, Fk, uk), t = timed(kane_equations, kane_system)
    t_kane += t

    # the three derivations agree: mass matrix and generalized forces -h - Q
    rng = np.random.default_rng(SEED + 1)
    qv, vv = rng.uniform(-np.pi, np.pi, 6), rng.normal(size=6)
    p = parameter_vector(sym, model)
    f = lambdify_terms(sym, names=["A", "Q", "h"])
    A, Q, h = f.A(qv, vv, p), f.Q(qv, vv, p), f.h(qv, vv, p)
    q = lag_system.q
    errs_lag = relative_errors(*numeric_equations(Mm, Fm, q, [qi.diff() for qi in q],
                                                  lag_system.params, qv, vv, p), A, h + Q)
    errs_kane = relative_errors(*numeric_equations(Mk, Fk, kane_system.q, uk,
                                                   kane_system.params, qv, vv, p), A, h + Q)
    agree = max(errs_lag + errs_kane) <= CHECK_RTOL

    def verdict(errs: tuple[float, float]) -> str:
        return (f"mass matrix {errs[0]:.1e}, forces {errs[1]:.1e} -> "
                f"{'OK' if max(errs) <= CHECK_RTOL else 'MISMATCH'}")

    print(f"wheeled_dyn.symbolic on a WIP-sized model (6 joints, 60 standard parameters), "
          f"sympy {sp.__version__}, pinocchio {pin.__version__}, python {sys.version.split()[0]}")
    print(f"  ours, cold (A, Q, Christoffel, C, h, E, U; simplified; written to cache): "
          f"{t_cold:7.3f} s")
    print(f"  ours, cached (read from disk):                                          "
          f"{t_cached:7.3f} s")
    print(f"  ours, cold without the polish step:                                     "
          f"{t_nosimp:7.3f} s")
    print(f"  ours, C matrix collected and polished (extra):                          "
          f"{t_C:7.3f} s")
    print(f"  sympy.physics.mechanics LagrangesMethod (M, forcing; no simplification):"
          f"{t_lag:7.3f} s")
    print(f"  + trigsimp of its 6x6 mass matrix:                                      "
          f"{t_lag_simp:7.3f} s")
    print(f"  sympy.physics.mechanics KanesMethod (M, forcing; no simplification):    "
          f"{t_kane:7.3f} s")
    print(f"  ratio LagrangesMethod / ours cold: {t_lag / t_cold:6.1f}x"
          f"   (with its trigsimp: {(t_lag + t_lag_simp) / t_cold:6.1f}x);"
          f"   ours cold / cached: {t_cold / t_cached:6.0f}x")
    print(f"  ratio KanesMethod / ours cold:     {t_kane / t_cold:6.1f}x")
    print(f"  agreement with ours (relative), LagrangesMethod: {verdict(errs_lag)}")
    print(f"  agreement with ours (relative), KanesMethod:     {verdict(errs_kane)}")
    return 0 if agree else 1


if __name__ == "__main__":
    from doc_block import recorded
    with recorded(__file__):      # its block of docs/benchmarks.md
        code = main()
    sys.exit(code)
