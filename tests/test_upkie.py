r"""Upkie with its legs locked at a crouch, from a model file a user writes (no Python), against
an independent Lagrangian of the same two-wheeled pendulum.

The independent computation does not use Pinocchio or the toolkit's builder: the URDF's links
are summed with yourdfpy's forward kinematics at the crouch into one rigid body (base, legs,
stators) and two wheels (rotor, hub, tyre and the frames on them), each with its mass, centre
of mass and inertia. SymPy then writes the kinetic and potential energy in the coordinates
:math:`q = (x_0, y_0, \psi, \varphi, \theta_l, \theta_r)` (axle midpoint on the ground, heading,
pitch about the axle from the left wheel to the right, wheel angles relative to the body),

.. math::

    T = \sum_k \tfrac12 m_k \lVert \dot p_k\rVert^2 + \tfrac12 \omega_k^{\mathsf T} I_k \omega_k,
    \qquad V = g \sum_k m_k z_k ,

the mass matrix as the Hessian of :math:`T`, :math:`C` from its Christoffel symbols and
:math:`Q = \partial V/\partial q`. Rolling without slip, :math:`\dot q = S(q)\,\nu` with
:math:`\nu = (\dot x, \dot\psi, \dot\varphi)` (heading speed, heading rate, pitch rate), gives
the reduced terms :math:`A_\nu = S^{\mathsf T} A S`,
:math:`C_\nu = S^{\mathsf T} C S + S^{\mathsf T} A \dot S`, :math:`Q_\nu = S^{\mathsf T} Q`.
:math:`S` is written by hand (each wheel turns at (speed of its centre)/R relative to the
ground) and checked against the contact points' velocities.
"""

from __future__ import annotations

import json
import subprocess
import sys
from functools import lru_cache
from pathlib import Path

import numpy as np
import pytest

sp = pytest.importorskip("sympy")
upkie_description = pytest.importorskip("upkie_description",
                                        reason="upkie-description is not installed")
yourdfpy = pytest.importorskip("yourdfpy")

from wheeled_dyn.constraints import CoordinateMap  # noqa: E402
from wheeled_dyn.coordinates import builtin_coordinate_set  # noqa: E402
from wheeled_dyn.models.model_file import read_model_file  # noqa: E402
from wheeled_dyn.models.registry import load_model  # noqa: E402

DATA = Path(__file__).parent / "data" / "upkie_crouch"
MODEL_FILE = DATA / "upkie_crouch.toml"
#: Relative tolerance of the reduced terms (both sides exact to rounding).
TERMS_TOL = 1e-9
#: Largest contact-point speed (m/s per unit of nu) the hand-written S may leave.
ROLLING_TOL = 1e-12
#: Random states compared.
N_STATES = 6
G = 9.81


def _rigid_sum(urdf, links, frame):
    r"""Mass, centre of mass and inertia about it (all in ``frame``) of ``links``."""
    m_tot, first, second = 0.0, np.zeros(3), np.zeros((3, 3))
    for name in links:
        inertial = urdf.link_map[name].inertial
        if inertial is None or inertial.mass is None or inertial.mass == 0:
            continue
        T = urdf.get_transform(name, frame) @ (inertial.origin if inertial.origin is not None
                                               else np.eye(4))
        m, c, Rot = float(inertial.mass), T[:3, 3], T[:3, :3]
        I_c = Rot @ np.asarray(inertial.inertia, dtype=float) @ Rot.T
        m_tot += m
        first += m * c
        second += I_c + m * (c @ c * np.eye(3) - np.outer(c, c))
    com = first / m_tot
    return m_tot, com, second - m_tot * (com @ com * np.eye(3) - np.outer(com, com))


def _subtree(urdf, joint_name):
    child = urdf.joint_map[joint_name].child
    out, stack = [], [child]
    while stack:
        link = stack.pop()
        out.append(link)
        stack += [j.child for j in urdf.robot.joints if j.parent == link]
    return out


def _rot(axis, angle):
    a = sp.Matrix(axis) / sp.sqrt(sum(x**2 for x in axis))
    K = sp.Matrix([[0, -a[2], a[1]], [a[2], 0, -a[0]], [-a[1], a[0], 0]])
    return sp.eye(3) + sp.sin(angle) * K + (1 - sp.cos(angle)) * K * K


def _unskew(W):
    return sp.Matrix([W[2, 1], W[0, 2], W[1, 0]])


@lru_cache(maxsize=1)
def independent():
    r"""Lambdified A(q), Christoffel C(q, qd), Q(q), contact velocity rows, S(q, ...), R."""
    mf = read_model_file(MODEL_FILE)
    locked = {k: np.float64(v) for k, v in mf.data["joints"]["locked"].items()}
    R = float(mf.data["wheels"]["radius"])
    urdf = yourdfpy.URDF.load(upkie_description.URDF_PATH, build_scene_graph=True,
                              load_meshes=False, load_collision_meshes=False)
    urdf.update_cfg(locked)
    wheels = {"l": ("left_wheel", "left_wheel_tire"), "r": ("right_wheel", "right_wheel_tire")}
    wheel_links = {k: _subtree(urdf, j) for k, (j, _) in wheels.items()}
    body_links = [l.name for l in urdf.robot.links
                  if not any(l.name in ls for ls in wheel_links.values())]
    mb, cb, Ib = _rigid_sum(urdf, body_links, "base")
    centres = {k: urdf.get_transform(t, "base")[:3, 3] for k, (_, t) in wheels.items()}
    axle_mid = 0.5 * (centres["l"] + centres["r"])

    x0, y0, psi, phi, thl, thr = q = sp.symbols("x0 y0 psi phi theta_l theta_r")
    qd = sp.symbols("dx0 dy0 dpsi dphi dtheta_l dtheta_r")
    t = sp.Symbol("t")
    as_t = {s: sp.Function(s.name)(t) for s in q}
    Rb = _rot((0, 0, 1), psi) * _rot((0, -1, 0), phi)   # pitch about the axle, left -> right
    origin = sp.Matrix([x0, y0, R]) - Rb * sp.Matrix(axle_mid)   # base origin, world

    def velocity(p):
        return p.jacobian(q) * sp.Matrix(qd)

    def omega_body(Rot):
        Rt = Rot.subs(as_t)
        W = (Rt.T * Rt.diff(t)).subs({f.diff(t): d for f, d in zip(as_t.values(), qd)})
        return _unskew(W.subs({f: s for s, f in as_t.items()}))

    parts = [(mb, origin + Rb * sp.Matrix(cb), Rb, Ib)]
    rows = []
    for k, theta in (("l", thl), ("r", thr)):
        joint_name, tyre = wheels[k]
        joint = urdf.joint_map[joint_name]
        mw, cw, Iw = _rigid_sum(urdf, wheel_links[k], tyre)
        child_in_base = urdf.get_transform(joint.child, "base")[:3, :3]
        tyre_in_child = urdf.get_transform(tyre, joint.child)[:3, :3]
        Rw = Rb * sp.Matrix(child_in_base) * _rot(tuple(joint.axis), theta) * \
            sp.Matrix(tyre_in_child)
        centre = origin + Rb * sp.Matrix(centres[k])
        parts.append((mw, centre + Rw * sp.Matrix(cw), Rw, Iw))
        w_world = Rw * omega_body(Rw)
        v_contact = velocity(centre) + w_world.cross(sp.Matrix([0, 0, -R]))
        rows.append(v_contact[:2, :].jacobian(qd))
    T = sp.S(0)
    V = sp.S(0)
    for m, p, Rot, I in parts:
        v = velocity(p)
        w = omega_body(Rot)
        T += sp.Rational(1, 2) * m * (v.T * v)[0] + sp.Rational(1, 2) * (w.T * sp.Matrix(I) * w)[0]
        V += G * m * p[2]
    A = sp.hessian(T, qd)
    Q = sp.Matrix([V]).jacobian(q).T
    lam = lambda e: sp.lambdify((q, qd), e, "numpy")  # noqa: E731
    dA = lam([A.diff(s) for s in q])

    def christoffel(qv, qdv):
        r""":math:`C_{ij} = \tfrac12\sum_k (\partial_k A_{ij} + \partial_j A_{ik}
        - \partial_i A_{jk})\,\dot q_k`."""
        D = np.asarray(dA(qv, qdv), dtype=float)          # D[k, i, j] = dA_ij/dq_k
        return 0.5 * (np.einsum("kij,k->ij", D, qdv) + np.einsum("jik,k->ij", D, qdv)
                      - np.einsum("ijk,k->ij", D, qdv))

    return lam(A), christoffel, lam(Q), lam(sp.Matrix.vstack(*rows)), R, \
        float(axle_mid @ [0, 1, 0]), float(np.linalg.norm(centres["l"] - centres["r"]) / 2)


def _S(q, signs, R, L):
    psi = q[2]
    sl, sr, pl, pr = signs
    return np.array([[np.cos(psi), 0, 0], [np.sin(psi), 0, 0], [0, 1, 0], [0, 0, 1],
                     [sl / R, -sl * L / R, pl], [sr / R, sr * L / R, pr]])


def _S_dot(q, qdot):
    Sd = np.zeros((6, 3))
    Sd[0, 0], Sd[1, 0] = -np.sin(q[2]) * qdot[2], np.cos(q[2]) * qdot[2]
    return Sd


def _signs(rows, R, L):
    r"""The wheel-rate signs of S (forward speed, pitch) that make the contact points still."""
    rng = np.random.default_rng(3)
    q = np.r_[0.0, 0.0, rng.uniform(-1, 1, 4)]
    best = None
    for signs in np.array(np.meshgrid(*[[-1.0, 1.0]] * 4)).T.reshape(-1, 4):
        err = np.abs(rows(q, np.zeros(6)) @ _S(q, signs, R, L)).max()
        if best is None or err < best[0]:
            best = (err, signs)
    return best


def test_model_file_builds_a_pendulum_on_two_wheels():
    wm = load_model(str(MODEL_FILE))
    assert wm.coordinate_names == ("x0", "y0", "psi", "phi", "theta_l", "theta_r")
    A_f, C_f, Q_f, rows, R, y_mid, L = independent()
    assert wm.geometry["R"] == pytest.approx(R, rel=TERMS_TOL)
    assert wm.geometry["L"] == pytest.approx(L, rel=TERMS_TOL)
    assert abs(y_mid) < TERMS_TOL          # a symmetric crouch: the axle midpoint on the x-z plane


def test_reduced_terms_match_an_independent_lagrangian():
    A_f, C_f, Q_f, rows, R, _, L = independent()
    err, signs = _signs(rows, R, L)
    assert err < ROLLING_TOL, f"no sign choice makes S roll without slip ({err:.3g})"
    wm = load_model(str(MODEL_FILE))
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "heading"))
    rng = np.random.default_rng(2026)
    for _ in range(N_STATES):
        psi, phi = rng.uniform(-1.0, 1.0, 2)
        nu = rng.uniform(-1.0, 1.0, 3)
        state = {"x": 0.0, "psi": psi, "phi": phi, "dx": nu[0], "dpsi": nu[1], "dphi": nu[2]}
        q_doc, nu_doc = cmap.state_from(state)
        terms = cmap.terms(q_doc, nu_doc)
        q = np.array([0.0, 0.0, psi, phi, 0.0, 0.0])
        S = _S(q, signs, R, L)
        qdot = S @ nu
        assert np.abs(rows(q, qdot) @ S).max() < ROLLING_TOL
        A = np.asarray(A_f(q, qdot), dtype=float)
        C = np.asarray(C_f(q, qdot), dtype=float)
        Q = np.asarray(Q_f(q, qdot), dtype=float).ravel()
        A_nu = S.T @ A @ S
        C_nu = S.T @ C @ S + S.T @ A @ _S_dot(q, qdot)
        Q_nu = S.T @ Q
        for name, mine, theirs in (("A", A_nu, terms.A), ("C", C_nu, terms.C),
                                   ("Q", Q_nu, terms.Q), ("h", C_nu @ nu, terms.h)):
            scale = max(np.abs(mine).max(), 1.0)
            assert np.abs(np.asarray(theirs) - mine).max() < TERMS_TOL * scale, \
                f"{name} at {state}:\n{np.asarray(theirs)}\nindependent:\n{mine}"


def _cli(*args: str) -> subprocess.CompletedProcess:
    r"""Run the installed ``wheeled-dyn`` command, as a user would."""
    exe = Path(sys.executable).with_name("wheeled-dyn")
    if not exe.is_file():
        pytest.skip("the wheeled-dyn command is not installed next to this Python")
    return subprocess.run([str(exe), *args], capture_output=True, text=True, timeout=600)


def test_matrices_command_on_the_model_file():
    out = _cli("matrices", str(MODEL_FILE), "--state", "phi=0.1,dx=0.5", "--json")
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    wm = load_model(str(MODEL_FILE))
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "heading"))
    terms = cmap.terms(*cmap.state_from({"phi": 0.1, "dx": 0.5}))
    assert data["coordinates"] == ["dx", "dpsi", "dphi"]
    assert np.allclose(data["A"], terms.A, rtol=TERMS_TOL, atol=0.0)
