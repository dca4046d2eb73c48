"""How the reports write names: multi-letter symbols are one symbol, quasi-velocities keep the
document's letter, velocities that are rates are dotted, differences are shown simplified."""

from __future__ import annotations

import sympy as sp
from latex2mathml.converter import convert

from wheeled_dyn.report.symbols import (
    Notation,
    difference_latex,
    name_latex,
    notation,
    parse,
    simplified,
    text_latex,
)


def test_multi_letter_names_are_one_symbol_with_a_subscript():
    assert name_latex("Ixy") == "I_{xy}"
    assert name_latex("XX1") == "{XX}_{1}"
    assert name_latex("I_w2") == "I_{w2}"
    assert name_latex("Iw3") == "I_{w3}"
    assert name_latex("m_S") == "m_{S}"
    assert name_latex("theta_l") == r"\theta_{l}"
    assert name_latex("Omega") == r"\Omega"
    # in MathML the subscript belongs to the whole name: XX_1 is not X times X_1
    mathml = convert(name_latex("XX1"))
    assert "<msub><mrow><mi>X</mi><mi>X</mi></mrow>" in mathml


def test_product_of_letters_is_not_read_into_a_name():
    expr = parse("Ixy*sin(2*phi) + I*x*y")
    assert {s.name for s in expr.free_symbols} == {"Ixy", "phi", "I", "x", "y"}
    latex = text_latex("Ixy*sin(2*phi)", Notation(("phi",)))
    assert "I_{xy}" in latex and r"\sin" in latex


def test_capital_i_and_e_stay_symbols_of_the_document():
    expr = parse("I*dphi**2 + E")
    assert expr.free_symbols == {sp.Symbol("I"), sp.Symbol("dphi"), sp.Symbol("E")}
    assert not expr.has(sp.I) and not expr.has(sp.E)


def test_quasi_velocities_keep_the_document_letter():
    # seed 000's 7.2: p, q, r are body rates, not rates of yaw, pitch, roll
    euler = notation(("x0", "yaw", "pitch"), ("dx0", "q", "r"), ("ddx0", "dq", "dr"), quasi=True)
    assert euler.latex("q") == "q" and euler.latex("dq") == r"\dot{q}"
    assert euler.latex("dx0") == r"\dot{x}_{0}"          # a rate of a position: dotted
    # seed 002's (3.12): n is a spin, not the rate of the file's third position chi
    sphere = notation(("u1", "v1", "chi"), ("xi", "eta", "n"), ("dxi", "deta", "dn"), quasi=True)
    assert sphere.latex("n") == "n" and sphere.latex("xi") == r"\xi"
    assert sphere.latex("dv1") == r"\dot{v}_{1}"           # a definition dv1 = eta/sin(u1)
    assert "chi" not in text_latex("A*n*xi", sphere)


def test_holonomic_velocities_and_rates_are_dotted():
    wip = notation(("x", "psi", "phi"), ("dx", "dpsi", "dphi"), ("ddx", "ddpsi", "ddphi"),
                   quasi=False)
    assert wip.latex("dpsi") == r"\dot{\psi}" and wip.latex("ddphi") == r"\ddot{\phi}"
    latex = text_latex("dpsi*(XY1*cos(2*phi))", wip)
    assert r"\dot{\psi}" in latex and "d \\psi" not in latex
    assert wip.label("h[2]:dx*dpsi") == "h[2] x\u0307\u03c8\u0307"      # ẋψ̇


def test_displayed_difference_is_simplified_and_equal():
    # seed 001 eq. (25), A[2,2]: an unsimplified residual whose value is 2 I_a L**2 / R**2
    raw = ("I1*sin(phi)**2 - I1 + I2*cos(phi)**2 + 2*I_a*L**2/R**2 + Ixy*sin(2*phi) "
           "- (Ixy)*sin(2*phi) + I1*cos(phi)**2 - I2*cos(phi)**2")
    expr = parse(raw)
    short = simplified(expr)
    assert sp.simplify(short - expr) == 0
    assert short == 2 * sp.Symbol("I_a") * sp.Symbol("L") ** 2 / sp.Symbol("R") ** 2
    assert difference_latex(raw, Notation(("phi",))) == r"\frac{2 I_{a} L^{2}}{R^{2}}"
    assert difference_latex("0", Notation()) == ""


def test_a_printed_relation_is_rendered_side_by_side():
    r"""A step's printed relation "lhs = rhs" renders each side in the document's notation
    (accelerations with two dots), joined by "="."""
    from wheeled_dyn.report.symbols import notation, text_latex
    names = notation(("theta",), ("dtheta",), ("ddtheta",), quasi=False)
    latex = text_latex("-F*a*cos(theta) = I_g*ddtheta", names, "fallback")
    assert latex.count("=") == 1 and r"\ddot" in latex and "ddtheta" not in latex
    assert text_latex("a = b = c", names, "fallback") == "fallback"


def test_printed_names_read_back_as_symbols_not_sympy_constants():
    r"""A residual printed in the document's names and read back for its LaTeX keeps them:
    the rolling disk's I and J (not the imaginary unit), E, Q, gamma as plain symbols."""
    from pathlib import Path

    import sympy as sp

    from wheeled_dyn.compare.causes.root import _power_latex
    from wheeled_dyn.derivations import load_derivation
    from wheeled_dyn.sympy_text import parse
    expr = parse("I*E + Q*gamma + sin(I)")
    assert expr is not None and not expr.has(sp.I) and not expr.has(sp.E)
    assert {s.name for s in expr.free_symbols} == {"I", "E", "Q", "gamma"}
    d = load_derivation(Path(__file__).parent / "data" / "published"
                        / "rolling_disk_multipliers.toml")
    latex = _power_latex("dphi*dtheta*(I - J)", d)
    import re
    assert r"\left(I - J\right)" in latex, latex
    assert not re.search(r"(?<![A-Za-z\\])i(?![A-Za-z])", latex), latex   # no imaginary unit
