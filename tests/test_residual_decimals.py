r"""Truth − document printed where the truth holds decimals (a rotation by a rounded angle)
and the document the same numbers written out: the pairs that cancel to round-off are gone,
and what is left is the term that differs (a residual of 2 kB hid one term before); and a
short residual with :math:`\sin^2 + \cos^2 = 1` used where that shortens it."""

from __future__ import annotations

import sympy as sp

from wheeled_dyn.compare.presentation.residuals import TRIG_EXPAND_LIMIT, _residual_text

x, y, q, g = sp.symbols("x y q g", real=True)
NAMES = {"x": x, "y": y, "q": q, "g": g}


def _read(text: str) -> sp.Expr:
    return sp.sympify(text, locals=NAMES)


def test_decimal_pairs_cancel_and_the_wrong_term_is_left():
    r"""Eight parameters in brackets of decimals (too long to be expanded with the
    trigonometric identities), the document's the same fractions, one term's sign flipped."""
    params = sp.symbols("p1:9", real=True)
    decimals = [0.0978433950072557 * (k + 1) ** 0.5 for k in range(8)]
    truth = sum((sp.Float(c) * p * (sp.sin(q) + 2 * sp.cos(q)) for c, p in zip(decimals, params)),
                sp.Integer(0)) + sp.Float(0.241704332108682) * g * y
    doc = sp.expand(sum((sp.nsimplify(sp.Float(c), rational=True) * p * (sp.sin(q) + 2 *
                                                                        sp.cos(q))
                         for c, p in zip(decimals, params)), sp.Integer(0))) \
        - sp.Rational(241704332108682, 10 ** 15) * g * y          # written out, as printed
    assert sp.count_ops(truth - doc) > TRIG_EXPAND_LIMIT
    text = _residual_text(truth, doc, physical=True)
    assert _read(text).free_symbols == {g, y}, text
    assert abs(float(_read(text).coeff(g * y)) - 2 * 0.241704332108682) < 1e-12, text


def test_a_residual_without_decimals_is_kept_whole():
    text = _residual_text(x * sp.sin(q) + y, x * sp.sin(q) - y, physical=True)
    assert _read(text) == 2 * y, text


def test_a_decimal_against_an_exact_sine_is_round_off():
    r"""A bracket turned by half a radian: the truth's decimal 2 sin(1/2), the document's
    exact ``2*sin(1/2)`` — they cancel; the term that differs is left."""
    params = sp.symbols("p1:9", real=True)
    truth = sum((sp.Float(2 * float(sp.sin(sp.Rational(1, 2)))) * p * sp.sin(q) for p in params),
                sp.Integer(0)) + g * y
    doc = sum((2 * sp.sin(sp.Rational(1, 2)) * p * sp.sin(q) for p in params), sp.Integer(0))
    text = _residual_text(truth, doc, physical=True)
    assert _read(text).free_symbols == {g, y}, text


def test_sin_squared_plus_cos_squared_is_one_in_a_residual():
    r"""Truth − document of a body's yaw inertia written :math:`I_2` where
    :math:`I_1\sin^2\phi + I_2\cos^2\phi` fits (seed 001's eq. 25): shown as
    :math:`I_1\sin^2\phi - I_2\sin^2\phi`, not :math:`I_1\sin^2\phi + I_2\cos^2\phi - I_2`;
    no other identity is used (:math:`2\sin\phi\cos\phi` stays, the document's monomial)."""
    import sympy as sp
    from wheeled_dyn.compare.presentation.residuals import _residual_text
    I1, I2, phi, m = sp.symbols("I1 I_2 phi m")
    s, c = sp.sin(phi), sp.cos(phi)
    said = _residual_text(I1 * s ** 2 + I2 * c ** 2, I2, True)
    assert sp.sympify(said) == sp.expand(I1 * s ** 2 - I2 * s ** 2) and "cos" not in said
    kept = _residual_text(2 * I1 * s * c + m * c ** 2 + m * s ** 2, sp.Integer(0), True)
    assert sp.sympify(kept) == sp.expand(2 * I1 * s * c + m) and "sin(2*phi)" not in kept
