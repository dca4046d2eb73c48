r"""Derivations made with :mod:`sympy.physics.mechanics` passed to ``wd.compare`` as they come
out of it: functions of time (``dynamicsymbols``) and their derivatives, not plain symbols.

The uniform rod of seed 000's pendulum (the README's example: length l, mass m, hinged at one
end, its angle θ from hanging straight down) derived twice, independently of the tool, by
Kane's method (``KanesMethod.mass_matrix`` and ``forcing``: :math:`M\dot u = f`,
:math:`\dot\theta = u`) and by Lagrange's (``LagrangesMethod.form_lagranges_equations``, in
:math:`\ddot\theta(t)`): both agree with the truth; the same rod taken as a point mass at its
centre (inertia :math:`ml^2/4`, Kane's) differs in A only.
"""

from __future__ import annotations

import pytest

me = pytest.importorskip("sympy.physics.mechanics", reason="sympy.physics.mechanics is "
                         "SymPy's own (installed with it)")
import sympy as sp  # noqa: E402

import wheeled_dyn as wd  # noqa: E402

#: The rod's names in the model (seed 000's pendulum: the README's example).
SYMBOLS = {"m": "4*MZ(rod)**2/(3*YY(rod))", "l": "-3*YY(rod)/(2*MZ(rod))", "g": "g"}
COORDINATES = {"positions": ["theta"], "configuration": {"theta": "theta"}}
ASSUMES = {"families": ["urdf_structure"]}


def _rod(point_mass: bool = False):
    r"""(theta(t), the rod's rigid body, its centre, the frame N, the hinge O): down is +N.x."""
    theta = me.dynamicsymbols("theta")
    m, l = sp.symbols("m l", positive=True)
    N = me.ReferenceFrame("N")
    B = N.orientnew("B", "Axis", [theta, N.z])
    O = me.Point("O")
    O.set_vel(N, 0)
    P = O.locatenew("P", l / 2 * B.x)
    P.v2pt_theory(O, N, B)
    inertia = me.inertia(B, 0, 0, 0 if point_mass else m * l**2 / 12)
    return theta, me.RigidBody("rod", P, B, m, (inertia, P)), P, N, O


def _compare(**tables):
    return wd.compare("rod_pendulum", coordinates=COORDINATES, symbols=SYMBOLS,
                      assumes=ASSUMES, samples=200, param_sets=3, **tables)


@pytest.mark.parametrize("point_mass", [False, True])
def test_kanes_mass_matrix_and_forcing(point_mass):
    theta, rod, P, N, _ = _rod(point_mass)
    u = me.dynamicsymbols("u")
    rod.frame.set_ang_vel(N, u * N.z)
    m, g = rod.mass, sp.Symbol("g", positive=True)
    kane = me.KanesMethod(N, q_ind=[theta], u_ind=[u], kd_eqs=[theta.diff() - u])
    kane.kanes_equations([rod], [(P, m * g * N.x)])
    # M u' = f with u = theta': A = M, Q = -f (f holds theta(t), u(t))
    result = _compare(A=kane.mass_matrix, C=sp.zeros(1, 1),
                      Q=(-kane.forcing).subs(u, theta.diff()))
    differs = {r.element for r in result.records if r.verdict != "agrees"}
    assert differs == ({"A[1,1]"} if point_mass else set()), differs
    assert result.equivalent is (not point_mass)


def test_lagranges_equations_in_derivatives_of_time():
    theta, rod, P, N, O = _rod()
    m, g = rod.mass, sp.Symbol("g", positive=True)
    rod.potential_energy = -m * g * P.pos_from(O).dot(N.x)
    (eq,) = me.LagrangesMethod(me.Lagrangian(N, rod), [theta]).form_lagranges_equations()
    assert eq.has(sp.Derivative(theta, (sp.Symbol("t"), 2)))
    result = _compare(equations=[sp.Eq(eq, 0)])
    assert result.equivalent is True, [(r.element, r.texts) for r in result.records]
    assert {r.verdict for r in result.records} == {"agrees"}
