"""Canonical trigonometric form, polish, collection by parameter, exact numbers, printers and
numeric functions: identities checked against SymPy and numerically."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from wheeled_dyn.errors import StateError, UnknownNameError
from wheeled_dyn.symbolic import (
    TrigRing, canonical_trig, energy_terms, exact_number, is_zero, lambdify_terms, polish_trig,
    simplify_expr, simplify_matrix)
from wheeled_dyn.symbolic.printing import (
    from_srepr, symbol_latex, to_latex, to_mathml, to_srepr, to_text)
from wheeled_dyn.symbolic.trigpoly import NotPolynomial

SEED = 7
#: Absolute tolerance of numeric checks of symbolic rewrites.
NUM_TOL = 1e-12
N_POINTS = 20

a, b, c, x, m, R = sp.symbols("a b c x m R")


def numerically_equal(e1: sp.Expr, e2: sp.Expr, symbols=(a, b, c, x, m, R)) -> bool:
    f1 = sp.lambdify(symbols, e1)
    f2 = sp.lambdify(symbols, e2)
    rng = np.random.default_rng(SEED)
    for _ in range(N_POINTS):
        v = rng.uniform(0.2, 2.0, len(symbols))
        if abs(f1(*v) - f2(*v)) > NUM_TOL * max(1.0, abs(f2(*v))):
            return False
    return True


# --------------------------------------------------------------------------- canonical form
@pytest.mark.parametrize("expr", [
    sp.sin(a) ** 2 + sp.cos(a) ** 2 - 1,
    sp.sin(a + b) - sp.sin(a) * sp.cos(b) - sp.cos(a) * sp.sin(b),
    sp.cos(2 * a) - 1 + 2 * sp.sin(a) ** 2,
    m * (sp.sin(a) ** 4 - sp.cos(a) ** 4) + m * sp.cos(2 * a),
    sp.sin(a - b) ** 2 + sp.cos(b - a) ** 2 - 1,
    x / R * (sp.sin(c) ** 2 - 1) + x / R * sp.cos(c) ** 2,
])
def test_identities_are_zero(expr):
    assert canonical_trig(expr) == 0
    assert is_zero(expr)


def test_nonzero_is_not_zero():
    e = sp.sin(a) ** 2 - sp.cos(a) ** 2
    assert not is_zero(e)
    assert canonical_trig(e) != 0
    assert numerically_equal(canonical_trig(e), e)


def test_canonical_form_is_unique():
    """Two spellings of one function give the identical canonical expression."""
    e1 = sp.sin(2 * a) * sp.cos(b) * m
    e2 = 2 * m * sp.sin(a) * sp.cos(a) * sp.cos(b) * (sp.sin(b) ** 2 + sp.cos(b) ** 2)
    assert canonical_trig(e1) == canonical_trig(e2)
    assert simplify_expr(e1, trig=False) == simplify_expr(e2, trig=False)


def test_float_round_off_is_chopped_and_atol():
    e = 2.0 * m * sp.cos(a) + 1e-17 * m * sp.sin(a)
    assert canonical_trig(e) == 2 * m * sp.cos(a)
    assert not is_zero(1e-17 * m * sp.sin(a))
    assert is_zero(1e-17 * m * sp.sin(a), atol=1e-15)


def test_non_polynomial_falls_back():
    e = sp.sin(a) / sp.cos(a) - sp.tan(a)
    with pytest.raises(NotPolynomial):
        TrigRing.from_exprs([sp.sqrt(sp.sin(a))])
    assert is_zero(e)
    assert simplify_expr(sp.sqrt(sp.sin(a) ** 2 + sp.cos(a) ** 2)) == 1


# ----------------------------------------------------------------------------------- the ring
def test_ring_derivative_matches_sympy():
    exprs = [sp.sin(a) ** 3 * sp.cos(b) * m + x ** 2 * sp.cos(a - b), sp.sin(a + 2 * b) * x / R]
    ring, els = TrigRing.from_exprs(exprs, extra=(a, b, x))
    for e, p in zip(exprs, els):
        for s in (a, b, x):
            assert is_zero(ring.to_expr(ring.diff(p, s)) - sp.diff(e, s)), (e, s)


def test_ring_rejects_nonlinear_angles():
    ring, (p,) = TrigRing.from_exprs([sp.sin(a * b)], extra=(a, b))
    with pytest.raises(NotPolynomial):
        ring.diff(p, a)


def test_energy_terms_of_a_pendulum_on_a_cart():
    r"""Lagrange from energies: cart x, pendulum angle a (mass m, length l, from the
    vertical): A = [[M+m, m l cos a], [m l cos a, m l^2]], h = [-m l sin a da^2, 0],
    Q = [0, -m g l sin a]."""
    M, l, g = sp.symbols("M l g")
    dx, da = sp.symbols("dx da")
    vx = dx + l * sp.cos(a) * da
    vy = l * sp.sin(a) * da
    E = M * dx ** 2 / 2 + m * (vx ** 2 + vy ** 2) / 2
    U = -m * g * l * sp.cos(a)
    t = energy_terms(E, U, (x, a), (dx, da))
    ring = t.ring
    A = sp.Matrix(2, 2, lambda i, j: ring.to_expr(t.A[i][j]))
    assert all(is_zero(e) for e in A - sp.Matrix([[M + m, m * l * sp.cos(a)],
                                                  [m * l * sp.cos(a), m * l ** 2]]))
    assert is_zero(ring.to_expr(t.h[0]) + m * l * sp.sin(a) * da ** 2)
    assert is_zero(ring.to_expr(t.h[1]))
    assert is_zero(ring.to_expr(t.Q[1]) - m * g * l * sp.sin(a))


# --------------------------------------------------------------------------- polish / collect
def test_polish_shortens_and_keeps_the_value():
    cases = [1 - sp.cos(a) ** 2,
             sp.cos(a) * sp.cos(b) - sp.sin(a) * sp.sin(b),
             2 * sp.sin(a) * sp.cos(a) * sp.cos(b) ** 2 - sp.sin(a) * sp.cos(a)]
    for e in cases:
        p = polish_trig(e)
        assert sp.count_ops(p) <= sp.count_ops(e)
        assert numerically_equal(p, e)
    assert polish_trig(cases[0]) == sp.sin(a) ** 2
    assert polish_trig(cases[1]) == sp.cos(a + b)


def test_simplify_matrix_collects_by_parameter():
    XX, YY = sp.symbols("XX YY")
    M = sp.Matrix([[XX * sp.cos(a) ** 2 + XX * sp.sin(a) ** 2 + YY * sp.sin(a) * sp.cos(a),
                    0], [0, (XX - YY) * (1 - sp.cos(a) ** 2)]])
    S = simplify_matrix(M, parameters=[XX, YY])
    assert S[0, 0] in (XX + YY * sp.sin(2 * a) / 2, XX + YY * sp.sin(a) * sp.cos(a))
    assert set(sp.Add.make_args(S[1, 1])) == {XX * sp.sin(a) ** 2, -YY * sp.sin(a) ** 2}
    assert numerically_equal(S[0, 0], M[0, 0], (a, XX, YY))


# ------------------------------------------------------------------------------ exact numbers
@pytest.mark.parametrize(("value", "expected"), [
    (0.0, sp.Integer(0)), (-1.0, sp.Integer(-1)), (1e-17, sp.Integer(0)),
    (0.2, sp.Rational(1, 5)), (0.7071067811865476, sp.sqrt(2) / 2),
    (-0.8660254037844386, -sp.sqrt(3) / 2), (1 / 3, sp.Rational(1, 3)),
])
def test_exact_numbers(value, expected):
    assert exact_number(value) == expected


@pytest.mark.parametrize("value", [9.81, 0.123456, 0.3333, 1.5707963267948966])
def test_floats_that_stay_floats(value):
    e = exact_number(value)
    assert e.is_Float and float(e) == value


# ---------------------------------------------------------------------------------- printers
def test_latex_names_and_dots():
    XX_thl, psi, dpsi, theta_l = sp.symbols("XX_thl psi dpsi theta_l")
    assert symbol_latex(XX_thl) == r"\mathrm{XX}_{\mathrm{thl}}"
    assert symbol_latex(theta_l) == r"\theta_{l}"
    text = to_latex(XX_thl * dpsi ** 2 * sp.sin(psi), dots={dpsi: psi})
    assert r"\dot{\psi}^{2}" in text and r"\mathrm{XX}_{\mathrm{thl}}" in text
    mathml = to_mathml(sp.Matrix([[XX_thl, 0], [0, dpsi]]), dots={dpsi: psi})
    assert mathml.startswith("<math") and "<mtable>" in mathml and "&#x002D9;" in mathml


def test_srepr_round_trip_and_text():
    M = sp.Matrix([[m * sp.cos(a) ** 2, sp.Float(9.81) * x], [sp.Rational(1, 3), 0]])
    assert from_srepr(to_srepr(M)) == M
    assert from_srepr(to_srepr(M[0, 0])) == M[0, 0]
    assert sp.sympify(to_text(M[0, 0])) == M[0, 0]


# ----------------------------------------------------------------------------- lambdify errors
def test_lambdify_errors():
    class Tiny:
        q = (a,)
        parameters = (m,)
        velocities = (x,)

        def terms(self):
            return {"A": sp.Matrix([[m * sp.cos(a) + R]])}

    with pytest.raises(UnknownNameError) as info:
        lambdify_terms(Tiny())
    assert info.value.name == "R"
    Tiny.terms = lambda self: {"A": sp.Matrix([[m * sp.cos(a)]])}
    f = lambdify_terms(Tiny())
    assert f.A([0.0], [0.0], [2.0]).shape == (1, 1)
    assert f("A", [0.0], None, [2.0])[0, 0] == pytest.approx(2.0)
    with pytest.raises(StateError):
        f.A([0.0, 1.0], None, [2.0])
    with pytest.raises(UnknownNameError):
        f("B", [0.0])
