r"""Time of the symbolic derivation of a WIP-sized model (planar base PX, PY, RZ; a pitching
body; two wheels: 6 joints), in Khalil's 60 standard parameters, against SymPy's own
``sympy.physics.mechanics.LagrangesMethod`` on the same system, in one run.

Ours: :func:`wheeled_dyn.symbolic.cached_symbolic_model` — cold (A, Q, Christoffel symbols,
C, h, energies, simplified) into an empty cache, then cached. SymPy: the Lagrangian of the six
rigid bodies (same kinematics, inertia about the joint-frame origin, first moments MS), then
``form_lagranges_equations``, ``mass_matrix`` and ``forcing`` (no simplification), and the
mass matrix simplified with ``trigsimp`` (what one does to read it). The two mass matrices and
generalized-force vectors are checked equal at a random state and parameter set.

Run: ``.venv/bin/python benchmarks/bench_symbolic.py``.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time

import numpy as np
import pinocchio as pin
import sympy as sp
from sympy.physics import mechanics as me

from wheeled_dyn.symbolic import (
    PARAMETER_NAMES, cached_symbolic_model, lambdify_terms, parameter_vector, symbolic_model)

SEED = 11
#: Geometry of the WIP-like model: pitch joint height, half track.
PITCH_HEIGHT = sp.Rational(3, 10)
HALF_TRACK = sp.Rational(1, 4)
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


def mechanics_lagrange(g: float = 9.81):
    """The same system with sympy.physics.mechanics; returns (q, qd, M, forcing, params)."""
    names = ("x", "y", "psi", "phi", "thl", "thr")
    q = me.dynamicsymbols(" ".join(names))
    qd = [me.dynamicsymbols(n, 1) for n in names]
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

    params = []
    T = 0
    V = 0
    for name in names:
        M, MX, MY, MZ, XX, XY, YY, XZ, YZ, ZZ = pis = sp.symbols(
            [f"{n}_{name}" for n in PARAMETER_NAMES])
        params += pis
        F, P = frames[name], points[name]
        # E = 1/2 (w^T J_O w + M v^T v + 2 MS^T (v x w)), U = -g^T (M p + R MS)
        v = P.vel(N)
        w = F.ang_vel_in(N)
        J = me.inertia(F, XX, YY, ZZ, XY, YZ, XZ)
        MS = MX * F.x + MY * F.y + MZ * F.z
        T += (w.dot(J.dot(w)) + M * v.dot(v) + 2 * MS.dot(v.cross(w))) / 2
        V += g * (M * P.pos_from(O) + MS).dot(N.z)
    L = T - V
    lm = me.LagrangesMethod(L, q)
    lm.form_lagranges_equations()
    return q, qd, lm.mass_matrix, lm.forcing, params


def timed(f, *args, **kw):
    t0 = time.perf_counter()
    out = f(*args, **kw)
    return out, time.perf_counter() - t0


def main() -> int:
    model = wip_model()
    warm = pin.Model()
    warm.addJoint(0, pin.JointModelRY(), pin.SE3.Identity(), "warm")
    symbolic_model(warm)  # imports warmed, not timed
    with tempfile.TemporaryDirectory() as root:
        os.environ.pop("WHEELED_DYN_CACHE", None)
        sym, t_cold = timed(cached_symbolic_model, model, root=root)
        _, t_cached = timed(cached_symbolic_model, model, root=root)
    _, t_nosimp = timed(symbolic_model, model, simplify=False)
    _, t_C = timed(sym.C, None, True)

    (q, qd, Mm, Fm, params), t_mech = timed(mechanics_lagrange)
    Ms, t_mech_simp = timed(lambda: Mm.applyfunc(sp.trigsimp))

    # the two derivations agree: mass matrix and generalized forces -h - Q
    rng = np.random.default_rng(SEED + 1)
    qv, vv = rng.uniform(-np.pi, np.pi, 6), rng.normal(size=6)
    p = parameter_vector(sym, model)
    f = lambdify_terms(sym, names=["A", "Q", "h"])
    qs, vs = sp.symbols("q0:6"), sp.symbols("v0:6")
    rename = dict(zip(qd, vs)) | dict(zip(q, qs))
    Mn = sp.lambdify([qs, params], Mm.xreplace(rename))(qv, p)
    Fn = sp.lambdify([qs, vs, params], Fm.xreplace(rename))(qv, vv, p)
    A, Q, h = f.A(qv, vv, p), f.Q(qv, vv, p), f.h(qv, vv, p)
    errs = (np.max(np.abs(np.asarray(Mn, float) - A)) / np.max(np.abs(A)),
            np.max(np.abs(np.asarray(Fn, float).ravel() + h + Q)) / np.max(np.abs(h + Q)))
    agree = max(errs) <= CHECK_RTOL

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
          f"{t_mech:7.3f} s")
    print(f"  + trigsimp of its 6x6 mass matrix:                                      "
          f"{t_mech_simp:7.3f} s")
    print(f"  ratio LagrangesMethod / ours cold: {t_mech / t_cold:6.1f}x"
          f"   (with its trigsimp: {(t_mech + t_mech_simp) / t_cold:6.1f}x);"
          f"   ours cold / cached: {t_cold / t_cached:6.0f}x")
    print(f"  agreement of the two derivations (relative): mass matrix {errs[0]:.1e}, "
          f"forces {errs[1]:.1e} -> {'OK' if agree else 'MISMATCH'}")
    return 0 if agree else 1


if __name__ == "__main__":
    sys.exit(main())
