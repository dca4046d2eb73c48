r"""Published equations of motion of two systems no shipped document covers, written by SymPy
in the forms authors publish them, with one planted error each (for the tests of
``test_published_forms.py``).

**A two-link planar arm** in a vertical plane (the "planar elbow manipulator"): M. W. Spong,
S. Hutchinson, M. Vidyasagar, *Robot Modeling and Control*, Wiley 2006, section 7.4: inertia
:math:`d_{11} = m_1l_{c1}^2 + m_2(l_1^2 + l_{c2}^2 + 2l_1l_{c2}\cos q_2) + I_1 + I_2`,
:math:`d_{12} = m_2(l_{c2}^2 + l_1l_{c2}\cos q_2) + I_2`, :math:`d_{22} = m_2l_{c2}^2 + I_2`;
:math:`h = -m_2l_1l_{c2}\sin q_2` with the velocity terms :math:`2h\dot q_1\dot q_2 + h\dot q_2^2`
and :math:`-h\dot q_1^2`; gravity :math:`\phi_1 = (m_1l_{c1} + m_2l_1)g\cos q_1 +
m_2l_{c2}g\cos(q_1 + q_2)`, :math:`\phi_2 = m_2l_{c2}g\cos(q_1 + q_2)` (angles from the
horizontal). Forms: the equations written out; as matrices; solved for the accelerations
(:math:`\ddot q = D^{-1}(\tau - c - \phi)`), and as simulation code solves them, second
acceleration first, then the first one from its own equation (:math:`\ddot q_1 = (\tau_1 -
d_{12}\ddot q_2 - c_1 - \phi_1)/d_{11}`); the second equation divided by its diagonal inertia
:math:`d_{22}`; the first replaced by the first step of an elimination,
:math:`\text{eq}_1 - (d_{12}/d_{22})\,\text{eq}_2`; Kane's :math:`F_r + F_r^* = 0`
(:math:`F_r = \tau_r - \phi_r`, :math:`F_r^* = -(D\ddot q + c)_r`).

**A cart-pole** with a uniform pole of half-length l hinged on the cart, its angle from the
upward vertical: the frictionless equations of R. V. Florian, *Correct equations for the
dynamics of the cart-pole system* (2007), and of A. G. Barto, R. S. Sutton, C. W. Anderson,
IEEE Trans. SMC 13 (1983): :math:`(M + m)\ddot x + ml\cos\theta\,\ddot\theta -
ml\dot\theta^2\sin\theta = F`, :math:`ml\cos\theta\,\ddot x + \tfrac43ml^2\ddot\theta -
mgl\sin\theta = 0`. Forms: those two; the pole's equation divided by :math:`ml` (as textbooks
print it, :math:`\ddot x\cos\theta + \tfrac43l\ddot\theta - g\sin\theta = 0`); solved as
Barto et al.'s simulation (and its many copies) computes it, :math:`\ddot\theta = (g\sin\theta
- \cos\theta\,T)/(l(\tfrac43 - m\cos^2\theta/(M + m)))`, :math:`T = (F + ml\dot\theta^2
\sin\theta)/(M + m)`, then :math:`\ddot x = T - ml\ddot\theta\cos\theta/(M + m)`; Kane's form.

The planted errors are made in the source equations before each form is derived from them:
a sign, a factor, a dropped term, one symbol written for another — and, for the pole, the
point-mass pendulum's :math:`ml^2` for the uniform pole's :math:`\tfrac43ml^2`.
"""

from __future__ import annotations

from pathlib import Path

import sympy as sp

DATA = Path(__file__).parent / "data" / "published"

q1, q2, dq1, dq2, ddq1, ddq2, tau1, tau2 = sp.symbols(
    "q1 q2 dq1 dq2 ddq1 ddq2 tau1 tau2", real=True)
m1, m2, l1, lc1, lc2, I1, I2, g = sp.symbols("m1 m2 l1 lc1 lc2 I1 I2 g", real=True)
x, th, dx, dth, ddx, ddth, F = sp.symbols("x theta dx dtheta ddx ddtheta F", real=True)
M, m, l = sp.symbols("M m l", real=True)

#: Planted errors of the arm (in its first equation and in d11) and of the cart-pole.
ARM_ERRORS = ("sign", "factor", "dropped", "swap", "gravity")
POLE_ERRORS = ("point_mass", "sign", "dropped", "trig")


def arm(error: str | None = None) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix]:
    r"""(D, c, φ) of the arm, with the planted ``error``: the sign of :math:`h\dot q_2^2`, the
    factor 2 of :math:`2h\dot q_1\dot q_2` lost, :math:`I_1` dropped from :math:`d_{11}`,
    :math:`l_{c1}` written for :math:`l_1` in :math:`m_2l_1^2`, link 2's gravity term left out
    of the second equation (``gravity``); ``point_mass2``: :math:`I_2`
    dropped from every element (link 2 taken as a point mass)."""
    l1_sq = lc1 ** 2 if error == "swap" else l1 ** 2
    own = 0 if error == "point_mass2" else I2          # link 2 a point mass: I2 everywhere
    d11 = m1 * lc1 ** 2 + m2 * (l1_sq + lc2 ** 2 + 2 * l1 * lc2 * sp.cos(q2)) + own
    d11 += 0 if error == "dropped" else I1
    d12 = m2 * (lc2 ** 2 + l1 * lc2 * sp.cos(q2)) + own
    d22 = m2 * lc2 ** 2 + own
    h = -m2 * l1 * lc2 * sp.sin(q2)
    c1 = (1 if error == "factor" else 2) * h * dq1 * dq2 + (-1 if error == "sign" else 1) * h \
        * dq2 ** 2
    c2 = -h * dq1 ** 2
    phi1 = (m1 * lc1 + m2 * l1) * g * sp.cos(q1) + m2 * lc2 * g * sp.cos(q1 + q2)
    phi2 = 0 if error == "gravity" else m2 * lc2 * g * sp.cos(q1 + q2)
    return sp.Matrix([[d11, d12], [d12, d22]]), sp.Matrix([c1, c2]), sp.Matrix([phi1, phi2])


def _s(e: sp.Expr) -> str:
    return sp.sstr(e)


def arm_forms(error: str | None = None) -> dict[str, list[str] | dict]:
    r"""Every form of the arm (module text): equations as text, or for ``matrices`` the
    tables of a matrix file."""
    D, c, phi = arm(error)
    acc, tau = sp.Matrix([ddq1, ddq2]), sp.Matrix([tau1, tau2])
    lhs = [(D[i, :] * acc)[0] + c[i] + phi[i] for i in range(2)]
    written = [f"{_s(lhs[i])} = {_s(tau[i])}" for i in range(2)]
    sol = D.LUsolve(tau - c - phi)
    k = D[0, 1] / D[1, 1]
    v = sp.Matrix([dq1, dq2])
    # C from the symmetric coefficients of c (Spong's C for the right equations)
    C = sp.Matrix(2, 2, lambda i, j: sum(sp.diff(c[i], v[j], v[kk]) / 2 * v[kk]
                                         for kk in range(2)))
    return {
        "matrices": {"A": [[_s(D[i, j]) for j in range(2)] for i in range(2)],
                     "C": [[_s(C[i, j]) for j in range(2)] for i in range(2)],
                     "Q": [_s(p) for p in phi], "B": [["1", "0"], ["0", "1"]]},
        "equations": written,
        "solved": [f"ddq1 = {_s(sol[0])}", f"ddq2 = {_s(sol[1])}"],
        "simulation": [f"ddq2 = {_s(sol[1])}",
                       f"ddq1 = (tau1 - ({_s(D[0, 1])})*ddq2 - ({_s(c[0])}) - ({_s(phi[0])}))"
                       f"/({_s(D[0, 0])})"],
        "divided": [written[0], f"({_s(lhs[1])})/({_s(D[1, 1])}) = tau2/({_s(D[1, 1])})"],
        "combined": [f"{_s(lhs[0])} - ({_s(k)})*({_s(lhs[1])}) = tau1 - ({_s(k)})*tau2",
                     written[1]],
        "kane": [f"tau{i + 1} - ({_s(phi[i])}) - ({_s((D[i, :] * acc)[0] + c[i])}) = 0"
                 for i in range(2)],
    }


def cart_pole(error: str | None = None) -> tuple[sp.Expr, sp.Expr]:
    r"""The cart-pole's two equations, left side minus right, with the planted ``error``:
    the point mass's :math:`ml^2` for :math:`\tfrac43ml^2`, the sign of the centripetal
    term, the coupling :math:`ml\cos\theta\,\ddot x` dropped from the pole's equation,
    :math:`\cos` written for :math:`\sin` in the gravity term."""
    inertia = m * l ** 2 if error == "point_mass" else sp.Rational(4, 3) * m * l ** 2
    centripetal = (1 if error == "sign" else -1) * m * l * dth ** 2 * sp.sin(th)
    gravity = m * g * l * (sp.cos(th) if error == "trig" else sp.sin(th))
    cart = (M + m) * ddx + m * l * sp.cos(th) * ddth + centripetal - F
    coupling = 0 if error == "dropped" else m * l * sp.cos(th) * ddx
    pole = coupling + inertia * ddth - gravity
    return cart, pole


def pole_forms(error: str | None = None) -> dict[str, list[str]]:
    r"""Every form of the cart-pole (module text)."""
    cart, pole = cart_pole(error)
    (sol,) = sp.solve([cart, pole], [ddx, ddth], dict=True)
    T = sp.Symbol("T")
    theta_acc = sp.simplify(sol[ddth])
    x_acc = sp.solve(cart.subs(ddth, T), ddx)[0]      # from the cart's equation, θ̈ given
    return {
        "equations": [f"{_s(cart)} = 0", f"{_s(pole)} = 0"],
        "divided": [f"{_s(cart)} = 0", f"({_s(pole)})/(m*l) = 0"],
        "solved": [f"ddx = {_s(x_acc.subs(T, ddth))}", f"ddtheta = {_s(theta_acc)}"],
        "kane": [f"{_s(-cart)} = 0", f"{_s(-pole)} = 0"],
        # the pole's reaction eliminated from the cart's equation, as for the cart's force
        "combined": [f"{_s(cart)} - (3*cos(theta)/(4*l))*({_s(pole)}) = 0", f"{_s(pole)} = 0"],
    }


ARM_HEAD = '''title = "Two-link arm ({form}{error})"
model = "{model}"
[coordinates]
positions = ["q1", "q2"]
kind = "holonomic"
rolling = "none"
configuration = {{ q1 = "q1", q2 = "q2" }}
units = {{ q1 = "rad", q2 = "rad" }}
[inputs]
tau1 = "tau1"
tau2 = "tau2"
[symbols]
m1 = {{ value = "M(link1)", units = "kg" }}
m2 = {{ value = "M(link2)", units = "kg" }}
lc1 = {{ value = "CX(link1)", units = "m" }}
lc2 = {{ value = "CX(link2)", units = "m" }}
I1 = {{ value = "IYY(link1)", units = "kg*m**2" }}
I2 = {{ value = "IYY(link2)", units = "kg*m**2" }}
l1 = {{ value = "l1", units = "m" }}
g = {{ value = "g", units = "m/s**2" }}
tau1 = {{ input = true, units = "N*m" }}
tau2 = {{ input = true, units = "N*m" }}
[assumes]
families = ["urdf_structure"]
[matrices]
equations = [
{eqs}
]
'''

POLE_HEAD = '''title = "Cart-pole ({form}{error})"
model = "{model}"
[coordinates]
positions = ["x", "theta"]
kind = "holonomic"
rolling = "none"
configuration = {{ x = "x", theta = "theta" }}
units = {{ x = "m", theta = "rad" }}
[inputs]
F = "F"
[symbols]
M = {{ value = "M(cart)", units = "kg" }}
m = {{ value = "M(pole)", units = "kg" }}
l = {{ value = "CZ(pole)", units = "m" }}
g = {{ value = "g", units = "m/s**2" }}
F = {{ input = true, units = "N" }}
[assumes]
families = ["urdf_proportions"]
[matrices]
equations = [
{eqs}
]
'''


#: A uniform rod pendulum (docs/derivation-format.md's example, model ``rod_pendulum``) with
#: its gravity term written as ``{gravity}`` (right: ``m*g*l/2*sin(theta)``).
ROD = """title = "Uniform rod pendulum"
model = "rod_pendulum"
[coordinates]
positions = ["theta"]
configuration = {{ theta = "theta" }}
units = {{ theta = "rad" }}
[symbols]
m = {{ value = "M(rod)", units = "kg" }}
l = {{ value = "length(rod)", units = "m" }}
g = {{ value = "g", units = "m/s**2" }}
[assumes]
uniform = ["rod"]
[matrices]
equations = ["1/3*m*l**2*ddtheta + {gravity} = 0"]
"""

def write(folder: Path, system: str, form: str, error: str | None) -> Path:
    r"""The derivation file of one form of ``system`` ("arm" or "pole") with ``error``."""
    eqs = (arm_forms if system == "arm" else pole_forms)(error)[form]
    head = ARM_HEAD if system == "arm" else POLE_HEAD
    model = DATA / ("two_link_arm.toml" if system == "arm" else "cart_pole.toml")
    path = folder / f"{system}_{form}_{error or 'right'}.toml"
    text = head.format(form=form, error=f", {error}" if error else "", model=model,
                       eqs=",\n".join(f'  "{e}"' for e in eqs) if isinstance(eqs, list)
                       else "")
    if isinstance(eqs, dict):                 # matrices
        text = text[:text.index("equations = [")] + "".join(
            f"{key} = {value!r}\n".replace("'", '"') for key, value in eqs.items())
    path.write_text(text)
    return path
