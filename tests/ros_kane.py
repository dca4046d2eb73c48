"""An independent derivation of the ROS balancer's reduced equations (tests/data/ros_balancer):
SymPy's KanesMethod on the same bodies, written from the URDF's description, not from the
project's symbolic engine or Pinocchio.

Bodies: the body B (base_link with the torso fixed on it; origin at the axle midpoint, axes x
forward, y left, z up), its centre of mass (x_b, y_b, z_b) and inertia about it (I_xx ... I_zz)
in B's axes; two wheels at +-L along B's y, mass m_w, inertia J_w about the axle and K_w about
a diameter. Coordinates: psi (heading about the vertical), theta (pitch about +y, REP 103:
positive tilts the top forward); speeds u1 (forward speed of the axle midpoint), u2 = psi',
u3 = theta'; wheel angles a_l about +y of B (left joint axis), a_r about -y (right joint axis),
their rates dependent through the rolling constraints (contact points at rest). Inputs: torques
u_l about +y on the left wheel and u_r about +y on the right wheel, reactions on B.
"""

from __future__ import annotations

import sympy as sp
from sympy.physics.mechanics import (KanesMethod, Point, ReferenceFrame, RigidBody, dynamicsymbols,
                                     inertia)

PARAMETERS = ("m_b", "x_b", "y_b", "z_b", "I_xx", "I_xy", "I_xz", "I_yy", "I_yz", "I_zz",
              "m_w", "J_w", "K_w", "R", "L", "g")


def kane_terms():
    r"""(symbols, positions, speeds, inputs, A, h, Q, B) with A u' + h + Q = B (u_l, u_r),
    in u = (u1, psi', theta'): A the mass matrix of the independent speeds, and
    h, Q, B read off Kane's forcing (velocity terms, gravity, inputs)."""
    p = {n: sp.Symbol(n, real=True) for n in PARAMETERS}
    psi, theta, a_l, a_r = dynamicsymbols("psi theta a_l a_r")
    u1, u2, u3, w_l, w_r = dynamicsymbols("u1 u2 u3 w_l w_r")
    tl, tr = sp.symbols("u_l u_r", real=True)
    N = ReferenceFrame("N")
    H = N.orientnew("H", "Axis", [psi, N.z])
    B = H.orientnew("B", "Axis", [theta, H.y])
    Wl = B.orientnew("Wl", "Axis", [a_l, B.y])
    Wr = B.orientnew("Wr", "Axis", [a_r, -B.y])
    B.set_ang_vel(N, u2 * N.z + u3 * H.y)
    Wl.set_ang_vel(B, w_l * B.y)
    Wr.set_ang_vel(B, -w_r * B.y)
    O = Point("O")
    O.set_vel(N, u1 * H.x)
    G = O.locatenew("G", p["x_b"] * B.x + p["y_b"] * B.y + p["z_b"] * B.z)
    G.v2pt_theory(O, N, B)
    Cl = O.locatenew("Cl", p["L"] * B.y)
    Cr = O.locatenew("Cr", -p["L"] * B.y)
    for c in (Cl, Cr):
        c.v2pt_theory(O, N, B)
    Pl = Cl.locatenew("Pl", -p["R"] * H.z)
    Pr = Cr.locatenew("Pr", -p["R"] * H.z)
    Pl.v2pt_theory(Cl, N, Wl)
    Pr.v2pt_theory(Cr, N, Wr)
    rolling = [Pl.vel(N).dot(H.x), Pr.vel(N).dot(H.x)]
    body = RigidBody("body", G, B, p["m_b"],
                     (inertia(B, p["I_xx"], p["I_yy"], p["I_zz"], p["I_xy"], p["I_yz"],
                              p["I_xz"]), G))
    wheels = [RigidBody(f"wheel_{s}", c, f, p["m_w"],
                        (inertia(f, p["K_w"], p["J_w"], p["K_w"]), c))
              for s, c, f in (("l", Cl, Wl), ("r", Cr, Wr))]
    loads = [(G, -p["m_b"] * p["g"] * N.z), (Cl, -p["m_w"] * p["g"] * N.z),
             (Cr, -p["m_w"] * p["g"] * N.z),
             (Wl, tl * B.y), (Wr, tr * B.y), (B, -(tl + tr) * B.y)]
    kane = KanesMethod(N, q_ind=[psi, theta, a_l, a_r], u_ind=[u1, u2, u3],
                       u_dependent=[w_l, w_r], velocity_constraints=rolling,
                       kd_eqs=[psi.diff() - u2, theta.diff() - u3, a_l.diff() - w_l,
                               a_r.diff() - w_r])
    kane.kanes_equations([body, *wheels], loads)
    # mass_matrix and forcing hold the 3 dynamic equations in all 5 speed derivatives, then the
    # 2 differentiated constraints: eliminate the dependent accelerations.
    M, F = kane.mass_matrix, kane.forcing.subs(kane.kindiffdict())
    Mi, Md, Ci, Cd = M[:3, :3], M[:3, 3:], M[3:, :3], M[3:, 3:]
    solve = Md * Cd.inv()
    A = sp.simplify(Mi - solve * Ci)
    F = F[:3, :] - solve * F[3:, :]             # = B tau - h - Q
    speeds = {u1: 0, u2: 0, u3: 0}
    inputs = {tl: 0, tr: 0}
    Bm = F.jacobian([tl, tr])
    Q = -F.subs(inputs).subs(speeds)
    h = -F.subs(inputs) - Q
    plain = {psi: sp.Symbol("psi", real=True), theta: sp.Symbol("theta", real=True),
             u1: sp.Symbol("dx", real=True), u2: sp.Symbol("dpsi", real=True),
             u3: sp.Symbol("dtheta", real=True)}

    def clean(M):
        return sp.Matrix(M).xreplace(plain).applyfunc(lambda e: sp.simplify(sp.expand(e)))

    return p, clean(A), clean(h), clean(Q), clean(Bm), (tl, tr)
