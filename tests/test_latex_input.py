r"""LaTeX input in derivation files (:mod:`wheeled_dyn.derivations.latex`, issue 13 item 3)."""

from __future__ import annotations

import pickle
import re
from pathlib import Path

import pytest
import sympy

from wheeled_dyn.derivations import DerivationNameError, load_derivation
from wheeled_dyn.derivations.expressions import UndeclaredNameError, real_symbol
from wheeled_dyn.derivations.latex import (LatexError, LatexNames, is_printed_name,
                                           latex_to_sympy, parse_latex_expression,
                                           split_latex_matrix)
from wheeled_dyn.errors import DerivationError

ROOT = Path(__file__).resolve().parents[1]
SEED001 = ROOT / "src" / "wheeled_dyn" / "data" / "derivations" / "seed001"
TWINS = ROOT / "tests" / "data" / "latex_twins"
DOC = ROOT / "docs" / "derivation-format.md"
LATEX_DOC = ROOT / "docs" / "derivation-latex.md"
#: Seed 001's text: in shared/ beside the checkout (as CI has it), else where it is shared.
SEED_TEXT = next((p for p in (Path(__file__).resolve().parents[2] / "shared" / "seeds"
                              / "001_370b32d9732353a8.txt",
                              Path("/work/shared/seeds/001_370b32d9732353a8.txt"))
                  if p.is_file()), Path("/work/shared/seeds/001_370b32d9732353a8.txt"))

POSITIONS = ("x", "psi", "phi", "theta")
SYMBOLS = ("m_s", "m_c", "d", "R", "L", "g", "I_w3", "I_2", "M1", "Mw", "ZZw", "XX1", "YY1",
           "MZ1", "MY1", "alpha3", "a", "b")
NAMES = LatexNames(
    (*POSITIONS, *("d" + p for p in POSITIONS), *("dd" + p for p in POSITIONS), *SYMBOLS),
    {p: "d" + p for p in POSITIONS}, {p: "dd" + p for p in POSITIONS},
    {"a": r"\beta_{a}"},
    {r"s2\psi": "sin(2*psi)", r"c\psi": "cos(psi)"})
S = {n: real_symbol(n) for n in NAMES.names}


def read(latex: str, names: LatexNames = NAMES) -> sympy.Expr:
    return parse_latex_expression(latex, names, S)


def same(latex: str, sympy_text: str, names: LatexNames = NAMES) -> None:
    got = read(latex, names)
    expected = sympy.sympify(sympy_text, locals=S)
    assert sympy.simplify(got - expected) == 0, (latex, got, expected)


# -- constructs ------------------------------------------------------------------------------
@pytest.mark.parametrize("latex, expected", [
    (r"m_s", "m_s"), (r"m_{s}", "m_s"), (r"I_{w3}", "I_w3"), (r"I_2", "I_2"),
    (r"\mathbf{XX_1}", "XX1"), (r"\mathbf{MZ_1}", "MZ1"), (r"\mathbf{M}\mathbf{Y}_1", "MY1"),
    (r"M_1 + 2M_w", "M1 + 2*Mw"), (r"2M_wL^2", "2*Mw*L**2"), (r"\alpha_3", "alpha3"),
    (r"\beta_a", "a"),                                   # the symbol's printed form
    (r"m_s d \cos\phi", "m_s*d*cos(phi)"), (r"m_s\,d", "m_s*d"),
])
def test_names(latex, expected):
    same(latex, expected)


@pytest.mark.parametrize("latex, expected", [
    (r"\phi + \psi + \theta", "phi + psi + theta"), (r"\varphi", "phi"),
    (r"\dot{x}", "dx"), (r"\dot{\psi}", "dpsi"), (r"\dot\phi^2", "dphi**2"),
    (r"\ddot{x}", "ddx"), (r"\ddot{\psi}", "ddpsi"), (r"d\dot{x}", "d*dx"),
])
def test_greek_letters_and_derivatives(latex, expected):
    same(latex, expected)


@pytest.mark.parametrize("latex, expected", [
    (r"\sin\phi\cos\phi", "sin(phi)*cos(phi)"), (r"\sin^2\phi", "sin(phi)**2"),
    (r"\cos(2\psi)", "cos(2*psi)"), (r"\sin 2\phi", "sin(2*phi)"),
    (r"\cos\theta a", "cos(theta)*a"), (r"\sin(\phi)^2", "sin(phi)**2"),
    (r"\sqrt{R^2 + d^2}", "sqrt(R**2 + d**2)"), (r"\sqrt[3]{a}", "a**(1/3)"),
    # the radicand whole: a**3**(1/3) is a**(3**(1/3)) (a correct document differed)
    (r"\sqrt[3]{a^3}", "(a**3)**(1/3)"), (r"\sqrt[2]{a^2}", "sqrt(a**2)"),
    (r"\sqrt[3]{a^2 b}", "(a**2*b)**(1/3)"),
    (r"\exp\phi", "exp(phi)"),
    (r"\cos\left(\psi - \phi\right)", "cos(psi - phi)"),
])
def test_functions(latex, expected):
    same(latex, expected)


@pytest.mark.parametrize("latex, expected", [
    (r"I_{w3} s2\psi", "I_w3*sin(2*psi)"), (r"c\psi^2 m_s", "cos(psi)**2*m_s"),
    (r"\frac{s2\psi}{2}", "sin(2*psi)/2"),
])
def test_abbreviations(latex, expected):
    same(latex, expected)


@pytest.mark.parametrize("latex, expected", [
    (r"\frac{m_s}{R^2}", "m_s/R**2"), (r"\tfrac12 d", "d/2"), (r"\dfrac{a}{b}", "a/b"),
    (r"\left( m_s + m_c \right) d", "(m_s + m_c)*d"), (r"\left[a + b\right]^{2}", "(a + b)**2"),
    (r"a \cdot b", "a*b"), (r"a \times b", "a*b"), (r"a/b\,d", "a/b*d"),
    (r"R^{-1}", "1/R"), (r"R^{2}", "R**2"), (r"-a - -b", "-a + b"), (r"{d}{x}", "d*x"),
    (r"0.5 m_s", "m_s/2"), (r"2\pi R", "2*pi*R"),
    (r"-\frac{\dot{\phi}}{2}(2 a\cos(2\phi) + (a - b)\sin(2\phi))",
     "-dphi/2*(2*a*cos(2*phi) + (a - b)*sin(2*phi))"),
])
def test_operators(latex, expected):
    same(latex, expected)


def test_text_is_what_the_sympy_parser_accepts():
    assert latex_to_sympy(r"m_s d \cos\phi \ddot{x}", NAMES) == "m_s*d*cos(phi)*ddx"
    assert latex_to_sympy(r"m_s\ddot{x} = -\frac{a}{R}", NAMES, equation=True) \
        == "m_s*ddx = -(a/R)"


def test_matrix_cells():
    cells = split_latex_matrix(r"\mathbf{A} = \begin{bmatrix} a & \frac{1}{2} \\ c\psi & ?"
                               r" \\ \end{bmatrix}")
    assert cells == [["a", r"\frac{1}{2}"], [r"c\psi", "?"]]
    assert split_latex_matrix(r"\begin{pmatrix} 0 \\ 1 \end{pmatrix}") == [["0"], ["1"]]


def test_a_matrix_as_sympy_prints_it():
    r"""``sympy.latex(Matrix)`` prints ``\left[\begin{matrix} … \end{matrix}\right]``: read as a
    bmatrix (it was "expected one \begin{bmatrix} …"), also after ``A =`` and transposed."""
    theta = sympy.Symbol("theta")
    M = sympy.Matrix([[sympy.sin(theta), 1], [0, sympy.cos(theta) ** 2]])
    assert split_latex_matrix(sympy.latex(M)) == [
        [r"\sin{\left(\theta \right)}", "1"], ["0", r"\cos^{2}{\left(\theta \right)}"]]
    assert split_latex_matrix("A = " + sympy.latex(sympy.Matrix([[1, 2]])) + "^T") == \
        [["1"], ["2"]]


@pytest.mark.parametrize("latex, reason", [
    (r"\begin{bmatrix} a & b", "cannot read the LaTeX"),
    (r"a = \begin{bmatrix} a \end{bmatrix} + b", "expected one"),
    (r"\begin{cases} a \end{cases}", "expected one"),
    (r"\begin{bmatrix} a & \\ b & c \end{bmatrix}", "empty matrix cell"),
])
def test_bad_matrices(latex, reason):
    with pytest.raises(LatexError, match=reason):
        split_latex_matrix(latex)


# -- constructs of printed documents (the seed 001 twins) -------------------------------------
@pytest.mark.parametrize("latex, expected", [
    (r"sin^{2}\phi", "sin(phi)**2"), (r"cos^2\theta", "cos(theta)**2"), (r"sin\phi", "sin(phi)"),
    (r"tan\psi", "tan(psi)"), (r"m_{s}d^{2}sin^{2}\phi", "m_s*d**2*sin(phi)**2"),
    (r"m_s d cos \phi\ddot{x}", "m_s*d*cos(phi)*ddx"), (r"sin\phi cos\phi", "sin(phi)*cos(phi)"),
    (r"sin(2\phi) + cos 2\psi", "sin(2*phi) + cos(2*psi)"), (r"sinh\phi", "sinh(phi)"),
    (r"exp\frac{a}{b}", "exp(a/b)"), (r"a sin\dot{\phi}", "a*sin(dphi)"),
])
def test_functions_in_plain_letters(latex, expected):
    same(latex, expected)


def test_function_in_plain_letters_power_binds_like_a_macro():
    assert latex_to_sympy(r"m_{s}d^{2}sin^{2}\phi", NAMES) \
        == latex_to_sympy(r"m_{s}d^{2}\sin^{2}\phi", NAMES) == "m_s*d**2*sin(phi)**2"


def test_function_in_plain_letters_that_reads_as_names_is_ambiguous():
    names = LatexNames(("s", "i", "n", "phi", "a"))
    with pytest.raises(LatexError) as caught:
        latex_to_sympy(r"sin\phi", names)
    assert set(caught.value.readings) == {"s*i*n*phi", "sin(phi)"}
    assert "or as sin(phi)" in caught.value.reason
    with pytest.raises(LatexError) as caught:
        latex_to_sympy(r"a sin^{2}\phi", names)
    assert set(caught.value.readings) == {"a*s*i*n**2*phi", "a*sin(phi)**2"}
    assert "ambiguous: 'asin^2 " in caught.value.reason           # as printed, with the power
    # with no argument after it, the letters are only names
    assert latex_to_sympy("sin + a", names) == "s*i*n + a"
    # the macro is never a name
    assert latex_to_sympy(r"\sin\phi", names) == "sin(phi)"


def test_function_in_plain_letters_not_read_where_it_cannot_be():
    # a subscript spells no function; a function needs its argument
    with pytest.raises(UndeclaredNameError):
        latex_to_sympy(r"sin_1\phi", NAMES)
    with pytest.raises(UndeclaredNameError) as caught:
        latex_to_sympy(r"a sin + b", NAMES)
    assert caught.value.name == "sin"


def test_abbreviation_spelling_a_function_is_read_instead():
    names = LatexNames(("phi", "a"), abbreviations={r"sin\phi": "sin(phi)"})
    assert latex_to_sympy(r"a sin\phi", names) == "a*(sin(phi))"
    assert latex_to_sympy(r"a sin^{2}\phi", names) == "a*sin(phi)**2"
    assert latex_to_sympy(r"sin\phi cos\phi", names) == "(sin(phi))*cos(phi)"


BB = LatexNames(("Mbb", "Sbb1", "Sbb2", "psi", "a"),
                printed={"Mbb": r"\mathbb{M}", "Sbb1": r"\mathbb{S}_1", "Sbb2": r"\mathbb{S}_{2}"})


@pytest.mark.parametrize("latex, expected", [
    (r"\mathbb{M}\cos^2\psi", "Mbb*cos(psi)**2"), (r"\frac{1}{2}\mathbb{M}\sin2\psi",
                                                   "Mbb*sin(2*psi)/2"),
    (r"\mathbb{S}_1 - \mathbb{S}_{2}", "Sbb1 - Sbb2"), (r"-\mathbb{S}_{1}a", "-Sbb1*a"),
])
def test_blackboard_bold_names(latex, expected):
    assert sympy.simplify(parse_latex_expression(latex, BB, {n: real_symbol(n) for n in BB.names})
                          - sympy.sympify(expected, locals={n: real_symbol(n)
                                                            for n in BB.names})) == 0


RATES = LatexNames(("x0", "y0", "theta_l", "dx0", "dy0", "dtheta_l", "ddx0", "ddtheta_l", "a"),
                   {"x0": "dx0", "y0": "dy0", "theta_l": "dtheta_l"},
                   {"x0": "ddx0", "theta_l": "ddtheta_l"})


@pytest.mark.parametrize("latex, expected", [
    (r"\dot{x}_0", "dx0"), (r"\dot{y}_0", "dy0"), (r"\dot{\theta}_l", "dtheta_l"),
    (r"\ddot{x}_0", "ddx0"), (r"\ddot{\theta}_{l}", "ddtheta_l"), (r"\dot x_0", "dx0"),
    (r"\dot{x}_0^2", "dx0**2"), (r"\dot{x_0}", "dx0"),
    (r"\dot{x}_0 \sin\theta_l - a\dot{y}_0", "dx0*sin(theta_l) - a*dy0"),
])
def test_subscript_after_a_dot(latex, expected):
    assert latex_to_sympy(latex, RATES) == expected


def test_subscript_after_a_dot_errors():
    with pytest.raises(UndeclaredNameError) as caught:
        latex_to_sympy(r"\dot{x}_1", RATES)
    assert caught.value.name == r"\dot{x}_1" and caught.value.kind == "velocity"
    with pytest.raises(UndeclaredNameError) as caught:
        latex_to_sympy(r"\ddot{y}_0", RATES)
    assert caught.value.kind == "acceleration"
    with pytest.raises(LatexError, match="subscript _1 after"):
        latex_to_sympy(r"\dot{x_0}_1", RATES)


@pytest.mark.parametrize("latex, expected", [
    (r"\begin{bmatrix} 0 & 0 & -m g \sin\phi \end{bmatrix}^T",
     [["0"], ["0"], [r"-m g \sin\phi"]]),
    (r"\mathbf{Q} = \begin{bmatrix} a & b \end{bmatrix}^{T}", [["a"], ["b"]]),
    (r"\begin{bmatrix} a & b \end{bmatrix}^\top", [["a"], ["b"]]),
    (r"\begin{bmatrix} a & b \end{bmatrix}^{\top}", [["a"], ["b"]]),
    (r"\begin{bmatrix} a & b \end{bmatrix}^{\mathsf{T}}", [["a"], ["b"]]),
    (r"\begin{pmatrix} a & b \\ c & d \end{pmatrix}^T", [["a", "c"], ["b", "d"]]),
    (r"\begin{bmatrix} a \\ b \end{bmatrix}^T", [["a", "b"]]),
])
def test_transposed_matrix(latex, expected):
    assert split_latex_matrix(latex) == expected


@pytest.mark.parametrize("latex, reason", [
    (r"\begin{bmatrix} a & b \\ c \end{bmatrix}^T", "rows of one length"),
    (r"\begin{bmatrix} a & b \end{bmatrix}^2", "expected one"),
    (r"\begin{bmatrix} a & b \end{bmatrix}^T + c", "expected one"),
    (r"\begin{bmatrix} a & b \end{bmatrix}^{T", "cannot read the LaTeX"),
])
def test_bad_transposes(latex, reason):
    with pytest.raises(LatexError, match=reason):
        split_latex_matrix(latex)


@pytest.mark.parametrize("latex, expected", [
    (r"m_s\ddot{x} = a \tag{10}", "m_s*ddx = a"), (r"m_s\ddot{x} = a \tag*{(10)}", "m_s*ddx = a"),
    (r"m_s\ddot{x} = a \quad (9)", "m_s*ddx = a"), (r"m_s\ddot{x} = a\qquad(9)", "m_s*ddx = a"),
    (r"m_s\ddot{x} = a \quad\quad (4.2a)", "m_s*ddx = a"),
    (r"$m_s\ddot{x} = a \quad (9)$", "m_s*ddx = a"),
    # not after the last term: spacing and a factor
    (r"m_s\ddot{x} \quad (2) = a", "m_s*ddx*(2) = a"),
    (r"m_s\ddot{x} = a (9)", "m_s*ddx = a*(9)"), (r"m_s\ddot{x} = a \, (9)", "m_s*ddx = a*(9)"),
])
def test_equation_numbers(latex, expected):
    assert latex_to_sympy(latex, NAMES, equation=True) == expected


def test_equation_numbers_outside_equations():
    assert latex_to_sympy(r"a \tag{3}", NAMES) == "a"
    assert latex_to_sympy(r"a \quad (2)", NAMES) == "a*(2)"      # an expression: a factor
    with pytest.raises(LatexError, match="nothing where an expression is expected"):
        latex_to_sympy(r"a = \quad (2)", NAMES, equation=True)


@pytest.mark.parametrize("latex", [r"a^{} + b", r"\frac{}{2}", r"\sin{}"])
def test_an_empty_group_is_said_as_one(latex):
    r"""An exponent, a fraction's part or a function's argument left empty (``\ddot\alpha^{}``
    as a probe wrote it) is one error naming the empty group, not "empty expression"."""
    with pytest.raises(LatexError, match=r"a group \{\} .* left empty"):
        latex_to_sympy(latex, NAMES)
    assert split_latex_matrix(r"\begin{bmatrix} a & b \end{bmatrix}^T \quad (35)") \
        == split_latex_matrix(r"\begin{bmatrix} a & b \end{bmatrix}^T \tag{35}") == [["a"], ["b"]]


def test_loader_reads_the_printed_constructs(tmp_path):
    d = load(tmp_path, r"""I = { value = "I3", units = "kg*m**2" }

[latex]
names = { I = '\mathbb{I}' }

[definitions]
Ibb = { latex = 'd^2 sin^2 \phi + \mathbb{I}' }

[matrices]
A = "[[1, 0, 0], [0, 1, 0], [0, 0, 1]]"
C = "[[0, 0, 0], [0, 0, 0], [0, 0, 0]]"
Q = { latex = '\mathbf{Q} = \begin{bmatrix} 0 & 0 & -m_s d cos\phi \end{bmatrix}^T \quad (35)' }
""")
    phi, dd, m_s = (d.symbol(n) for n in ("phi", "d", "m_s"))
    assert d.Q.shape == (3, 1) and d.Q[2] == -m_s * dd * sympy.cos(phi)
    assert d.latex_input["definitions.Ibb"][1] == "d**2*sin(phi)**2 + I"
    with pytest.raises(DerivationError, match="shape") as caught:
        load(tmp_path, r"""
[matrices]
A = "[[1, 0, 0], [0, 1, 0], [0, 0, 1]]"
C = "[[0, 0, 0], [0, 0, 0], [0, 0, 0]]"
Q = { latex = '\begin{bmatrix} 0 & 0 \end{bmatrix}^T' }
""")
    assert caught.value.item == "Q"


def test_loader_plain_letter_function_ambiguity_names_the_item(tmp_path):
    with pytest.raises(DerivationError) as caught:
        load(tmp_path, r"""s = "1"
i = "1"
n = "1"

[definitions]
k = { latex = 'm_s sin\phi' }

[matrices]
equations = ['k*ddx = 0', 'ddpsi = 0', 'ddphi = 0']
""")
    err = caught.value
    assert err.item == "definitions.k" and err.path.name == "d.toml"
    assert "reads as m_s*s*i*n*phi or as m_s*sin(phi)" in str(err)


def test_loader_subscript_after_a_dot(tmp_path):
    head = HEAD.replace('use = "seed001"', 'positions = ["x_0", "theta_l", "phi"]\n'
                        'configuration = { x = "x_0", theta_l = "theta_l", phi = "phi" }')
    d = load(tmp_path, r"""
[constraints]
equations = { latex = ['\dot{x}_0 - d\dot{\theta}_l = 0'] }

[matrices]
equations = { latex = ['m_s\ddot{x}_0 = 0', '\ddot{\theta}_{l} = 0', '\ddot{\phi} = 0 \tag{3}'] }
""", head)
    assert d.latex_input["constraint 1"][1] == "dx_0 - d*dtheta_l = 0"
    assert d.latex_input["equation 1"][1] == "m_s*ddx_0 = 0"
    assert d.latex_input["equation 3"][1] == "ddphi = 0"


# -- errors ----------------------------------------------------------------------------------
@pytest.mark.parametrize("latex, reason", [
    (r"\frac{a}{b", "cannot read the LaTeX"), (r"a}", "cannot read the LaTeX"),
    (r"\foo{a}", r"unknown LaTeX macro \\foo"), (r"a & b", "outside a matrix"),
    (r"a = b", "only in an equation"), (r"\sin", "without an argument"),
    (r"a^", "without an argument"), (r"(a + b", "missing"), (r"a^2^3", "double superscript"),
    (r"\begin{bmatrix} a \end{bmatrix}", "where an expression is expected"),
    ("a" * 30000, "longer than"), (r"x_\mathbf\mathbf c", "not a name"),
])
def test_unreadable_latex_is_one_error(latex, reason):
    with pytest.raises(LatexError, match=reason):
        latex_to_sympy(latex, NAMES)


def test_ambiguous_run_shows_both_readings():
    names = LatexNames(("d", "x", "dx"))
    with pytest.raises(LatexError) as caught:
        latex_to_sympy("dx", names)
    assert set(caught.value.readings) == {"d*x", "dx"}
    assert "d*x" in caught.value.reason and "or as dx" in caught.value.reason
    # an undeclared run that splits two ways
    names = LatexNames(("a", "b", "c", "ab", "bc"))
    with pytest.raises(LatexError) as caught:
        latex_to_sympy("abc", names)
    assert len(caught.value.readings) == 2
    assert set(caught.value.readings) <= {"ab*c", "a*bc", "a*b*c"}
    # a variant letter when both letters are declared
    with pytest.raises(LatexError, match="phi or as varphi"):
        latex_to_sympy(r"\varphi", LatexNames(("phi", "varphi")))
    assert pickle.loads(pickle.dumps(caught.value)).readings == caught.value.readings


def test_script_ell_is_a_length_l():
    r"""``\ell``, a length's script l as papers print it, is ``ell`` where the file declares it,
    else ``l`` (as ``\varphi`` is ``phi``), and may be a declared symbol's printed form."""
    names = ("m", "l", "l1", "g", "theta", "dtheta", "ddtheta")
    got = latex_to_sympy(r"m \ell^2 \ddot{\theta} + \ell_1 m g",
                         LatexNames(names, {"theta": "dtheta"}, {"theta": "ddtheta"}))
    assert sympy.sympify(got) == sympy.sympify("m*l**2*ddtheta + l1*m*g")
    assert latex_to_sympy(r"\ell", LatexNames(("ell",))) == "ell"
    with pytest.raises(LatexError, match="l or as ell|ell or as l"):
        latex_to_sympy(r"\ell", LatexNames(("l", "ell")))
    assert is_printed_name(r"\ell") and is_printed_name(r"\ell_{c1}")


def test_unknown_names():
    with pytest.raises(UndeclaredNameError) as caught:
        latex_to_sympy(r"m_s q \cos\phi", NAMES)
    assert caught.value.name == "q"
    with pytest.raises(UndeclaredNameError) as caught:
        latex_to_sympy(r"\cos\vartheta_9", NAMES)
    assert caught.value.name == r"\vartheta_9"
    with pytest.raises(UndeclaredNameError) as caught:
        latex_to_sympy(r"\dot{m_s}", NAMES)
    assert caught.value.kind == "velocity"


# -- the loader ------------------------------------------------------------------------------
HEAD = """title = "t"
model = "wip"

[coordinates]
use = "seed001"

[symbols]
d = { value = "d", units = "m" }
m_s = { value = "m_S", units = "kg" }
MZ1 = { value = "MZ(body)", latex = '\\mathbf{MZ}_1' }
"""


def load(tmp_path, body: str, head: str = HEAD):
    path = tmp_path / "d.toml"
    path.write_text(head + body, encoding="utf-8")
    return load_derivation(path)


def test_loader_reads_every_kind_of_value(tmp_path):
    d = load(tmp_path, r"""u = { input = true }

[inputs]
tau_l = { latex = '-\frac{u}{2}' }
tau_r = { latex = '-\frac{u}{2}' }

[assume]
tau_f = { latex = '0' }

[rows]
scale = ["1", { latex = 'd^2' }, "1"]

[constraints]
equations = { latex = ['\dot{x} - d\,\dot{\phi} = 0'] }

[definitions]
k = { latex = '\frac{m_s d}{2}' }
w2 = { value = { latex = '2\dot{\phi}' } }

[latex]
abbreviations = { 's\phi' = "sin(phi)" }

[matrices]
equations = { latex = [
  '\mathbf{MZ}_1 \ddot{x} = 0',
  'k\ddot{\psi} = s\phi',
  'm_s d^2\ddot{\phi} - m_s d\sin\phi\cdot 0 = w_2 + u + \tau_f',
] }
""")
    u = d.symbol("u")
    assert d.inputs["tau_l"] == -u / 2 and d.assumptions["tau_f"] == 0
    assert d.row_scale[1] == d.symbol("d") ** 2
    assert d.constraint_matrix() == sympy.ImmutableMatrix([[1, 0, -d.symbol("d")]])
    assert d.latex_input["constraint 1"][1] == "dx - d*dphi = 0"
    phi, ddx, ddpsi, ddphi = (d.symbol(n) for n in ("phi", "ddx", "ddpsi", "ddphi"))
    m_s, dd, mz, dphi = (d.symbol(n) for n in ("m_s", "d", "MZ1", "dphi"))
    assert d.equations[0] == sympy.Eq(mz * ddx, 0, evaluate=False)
    assert sympy.simplify(d.equations[1].lhs - m_s * dd / 2 * ddpsi) == 0
    assert d.equations[1].rhs == sympy.sin(phi)
    assert d.equations[2].rhs == 2 * dphi + d.symbol("u") + d.symbol("tau_f")
    assert d.latex_input["equation 2"] == (r"k\ddot{\psi} = s\phi", "k*ddpsi = (sin(phi))")
    assert d.latex_input["definitions.k"][1] == "((m_s*d)/2)"


def test_loader_matrices_elementwise_and_missing(tmp_path):
    d = load(tmp_path, r"""
[matrices]
A = [["m_s", { latex = 'm_s d\cos\phi' }, "0"], ["0", "1", "0"], ["0", "0", "1"]]
Q = { latex = '\begin{bmatrix} 0 \\ ? \\ m_s d \sin\phi \end{bmatrix}' }
""")
    assert d.A[0, 1] == d.symbol("m_s") * d.symbol("d") * sympy.cos(d.symbol("phi"))
    assert d.missing == ("Q[2]",)
    assert d.latex_input["Q[3]"][1] == "m_s*d*sin(phi)"
    assert "A[1,1]" not in d.latex_input


def test_loader_ambiguity_names_item_and_both_readings(tmp_path):
    with pytest.raises(DerivationError) as caught:
        load(tmp_path, r"""
[matrices]
A = { latex = '\begin{bmatrix} m_s & 0 & 0 \\ 0 & m_s dx & 0 \\ 0 & 0 & 1 \end{bmatrix}' }
""")
    err = caught.value
    assert err.item == "A[2,2]" and err.path.name == "d.toml" and err.line is not None
    assert "'m_s dx' reads as m_s*d*x or as m_s*dx" in str(err)


def test_loader_unknown_name_lists_declared(tmp_path):
    with pytest.raises(DerivationNameError) as caught:
        load(tmp_path, "[matrices]\nequations = { latex = ['m_s\\ddot{x} = 0', "
                       "'\\ddot{\\psi} = 0', 'q_2 \\ddot{\\phi} = 0'] }\n")
    err = caught.value
    assert err.name == "q_2" and err.item == "equation 3"
    assert "m_s" in err.valid and "ddphi" in err.valid and "equation 3" in str(err)


@pytest.mark.parametrize("latex, reason", [
    (r"\frac{m_s}{d", "cannot read the LaTeX"), (r"\weird m_s", r"unknown LaTeX macro"),
])
def test_loader_bad_latex_is_one_derivation_error(tmp_path, latex, reason):
    with pytest.raises(DerivationError, match=reason) as caught:
        load(tmp_path, f"[definitions]\nk = {{ latex = '{latex}' }}\n"
                       "[matrices]\nequations = ['k*ddx = 0', 'ddpsi = 0', 'ddphi = 0']\n")
    assert caught.value.item == "definitions.k"
    assert "\n" not in str(caught.value)


def test_loader_checks_the_latex_table(tmp_path):
    eqs = "[matrices]\nequations = ['ddx = 0', 'ddpsi = 0', 'ddphi = 0']\n"
    with pytest.raises(DerivationError, match="unknown key") as caught:
        load(tmp_path, "[latex]\nabbrevs = {}\n" + eqs)
    assert caught.value.item == "latex.abbrevs"
    with pytest.raises(DerivationNameError) as caught:
        load(tmp_path, "[latex]\nabbreviations = { 'c\\phi' = \"cos(phy)\" }\n" + eqs)
    assert caught.value.name == "phy"
    with pytest.raises(DerivationNameError) as caught:
        load(tmp_path, "[latex]\nnames = { nope = '\\nu' }\n" + eqs)
    assert caught.value.item == "latex.names.nope"
    with pytest.raises(DerivationError, match="not a name") as caught:
        load(tmp_path, "[latex]\nnames = { phi = '\\frac{a}{b}' }\n" + eqs)
    assert caught.value.item == "latex.names.phi"
    with pytest.raises(DerivationError, match="an abbreviation is") as caught:
        load(tmp_path, "[latex]\nabbreviations = { '\\dot{x}' = \"dx\" }\n" + eqs)
    assert caught.value.item.startswith("latex.abbreviations")


def test_loader_keeps_the_expression_limits(tmp_path):
    with pytest.raises(DerivationError, match="exponent"):
        load(tmp_path, "[matrices]\nequations = { latex = ['m_s^{99}\\ddot{x} = 0', "
                       "'\\ddot{\\psi} = 0', '\\ddot{\\phi} = 0'] }\n")


# -- end to end: eq. (25) of seed 001 ----------------------------------------------------------
A25 = r"""\mathbf{A} = \begin{bmatrix} M_1 + 2M_w + 2\frac{\mathbf{ZZ_w}}{R^2} & \mathbf{MZ_1} - 2\frac{\mathbf{YZ_w}}{R} & -\mathbf{MY_1}\cos\phi - \mathbf{MX_1}\sin\phi \\ \mathbf{MZ_1} - 2\frac{\mathbf{YZ_w}}{R^2} & \mathbf{XX_1} + 2\mathbf{YY_w} + 2M_wL^2 - (\mathbf{XX_1} - \mathbf{YY_1})\cos^2\phi + \mathbf{XY_1}\sin(2\phi) + \frac{2L^2\mathbf{ZZ_w}}{R^2} & \mathbf{YZ_1}\cos\phi + \mathbf{XZ_1}\sin\phi \\ -\mathbf{MY_1}\cos\phi - \mathbf{MX_1}\sin\phi & \mathbf{YZ_1}\cos\phi + \mathbf{XZ_1}\sin\phi \end{bmatrix}"""  # noqa: E501
C25 = r"""\mathbf{C} = \begin{bmatrix} 0 & 0 & -\dot{\phi}(\mathbf{MX_1}\cos\phi - \mathbf{MY_1}\sin\phi) \\ 0 & \frac{\dot{\phi}}{2}(2\mathbf{XY_1}\cos(2\phi) + (\mathbf{XX_1} - \mathbf{YY_1})\sin(2\phi)) & \dot{\psi}(\mathbf{XY_1}\cos(2\phi) + (\mathbf{XX_1} - \mathbf{YY_1})\cos\phi\sin\phi) - \dot{\phi}(\mathbf{YZ_1}\sin\phi - \mathbf{XZ_1}\cos\phi) \\ 0 & -\frac{\dot{\phi}}{2}(2\mathbf{XY_1}\cos(2\phi) + (\mathbf{XX_1} - \mathbf{YY_1})\sin(2\phi)) & 0 \end{bmatrix}"""  # noqa: E501
Q25 = r"""\mathbf{Q} = \begin{bmatrix} 0 \\ 0 \\ \mathbf{MX_1}g\cos\phi - \mathbf{MY_1}g\sin\phi \end{bmatrix}"""  # noqa: E501
#: eq. (25) lost the last element of row 3 of A; the SymPy-syntax file restores it as ZZ1
#: under [reconstructed], and so does the twin
LOST = (r"\mathbf{XZ_1}\sin\phi \end{bmatrix}",
        r"\mathbf{XZ_1}\sin\phi & \mathbf{ZZ_1} \end{bmatrix}")


def assert_same_matrices(twin, sympy_file) -> None:
    for key in ("A", "C", "Q"):
        a, b = getattr(twin, key), getattr(sympy_file, key)
        assert a.shape == b.shape, key
        for i in range(a.rows):
            for j in range(a.cols):
                label = f"{key}[{i + 1},{j + 1}]" if key != "Q" else f"Q[{i + 1}]"
                if label in sympy_file.missing:
                    assert label in twin.missing
                else:
                    assert sympy.simplify(a[i, j] - b[i, j]) == 0, (label, a[i, j], b[i, j])
    assert dict(twin.reconstructed) == dict(sympy_file.reconstructed)
    assert twin.missing == sympy_file.missing


def test_eq25_latex_twin_gives_the_same_matrices(tmp_path):
    original = SEED001 / "eq25_lagrange.toml"
    text = original.read_text(encoding="utf-8")
    head, tail = text.split("[matrices]")
    reconstructed = tail[tail.index("[reconstructed]"):]
    A = A25.replace(*LOST)
    twin = tmp_path / "eq25_lagrange.tex.toml"
    twin.write_text(head + "[matrices]\n" + "\n".join(
        f"{k} = {{ latex = '''{v}''' }}" for k, v in (("A", A), ("C", C25), ("Q", Q25)))
        + "\n\n" + reconstructed, encoding="utf-8")
    d_twin, d_sympy = load_derivation(twin), load_derivation(original)
    assert_same_matrices(d_twin, d_sympy)
    # the typos of the print are kept: A[1,2] has /R, A[2,1] /R**2; C[3,2] has phi-dot
    R, YZw = d_twin.symbol("R"), d_twin.symbol("YZw")
    assert d_twin.A[0, 1].has(YZw / R) and d_twin.A[1, 0].has(YZw / R**2)
    assert d_twin.C[2, 1].has(d_twin.symbol("dphi"))
    assert len(d_twin.latex_input) == 9 + 9 + 3
    assert d_twin.latex_input["A[3,3]"] == (r"\mathbf{ZZ_1}", "ZZ1")


def test_shipped_twin_matches_and_is_pasted_verbatim():
    twin = TWINS / "eq25_lagrange.tex.toml"
    assert_same_matrices(load_derivation(twin), load_derivation(SEED001 / "eq25_lagrange.toml"))
    text = twin.read_text(encoding="utf-8")
    assert A25.replace(*LOST) in text and C25 in text and Q25 in text
    if SEED_TEXT.is_file():                 # the seed text is outside the repository
        seed = SEED_TEXT.read_text(encoding="utf-8")
        for latex in (A25, C25, Q25):
            assert f"$${latex}$$" in seed


# -- the documentation's example ---------------------------------------------------------------
def test_documented_example_matches_the_sympy_example(tmp_path):
    blocks = re.findall(r"```toml\n(.*?)```", DOC.read_text(encoding="utf-8")
                        + LATEX_DOC.read_text(encoding="utf-8"), flags=re.S)
    sympy_example = blocks[0]
    latex_example = next(b for b in blocks if "latex = '''" in b)
    latex_equations = next(b for b in blocks if "equations = { latex" in b)
    paths = {}
    for name, text in (("sympy", sympy_example), ("latex", latex_example),
                       ("equations", latex_example.split("[matrices]")[0] + latex_equations)):
        paths[name] = tmp_path / f"{name}.toml"
        paths[name].write_text(text, encoding="utf-8")
    ref, mat, eqs = (load_derivation(paths[k]) for k in ("sympy", "latex", "equations"))
    subs = {mat.symbol(n): ref.symbol(n) for n in mat.namespace}
    for key in ("A", "C", "Q", "B"):
        assert sympy.simplify(getattr(mat, key).xreplace(subs) - getattr(ref, key)) \
            == sympy.zeros(*getattr(ref, key).shape), key
    A, h, Q, B, _ = eqs.read_off()
    assert sympy.simplify(A - mat.A) == sympy.zeros(2, 2)
    assert sympy.simplify(mat.C * sympy.Matrix(mat.velocities) - h) == sympy.zeros(2, 1)
    assert sympy.simplify(Q - mat.Q) == sympy.zeros(2, 1) and B == mat.B
    assert mat.latex_input["A[1,2]"][1] == "m2*l*(cos(th))"


# -- no traceback ------------------------------------------------------------------------------
def test_random_latex_raises_only_expression_errors():
    r"""Random LaTeX soup: every failure is an ExpressionError (the loader turns it into a
    DerivationError naming the item), never an IndexError or a pylatexenc exception."""
    import random
    from wheeled_dyn.derivations.expressions import ExpressionError
    pieces = [r"\frac", "{", "}", "a", "b", "_", "^", r"\phi", r"\dot", r"\ddot", "(", ")",
              r"\left(", r"\right)", r"\sin", "2", "0.5", "+", "-", "=", r"\cdot", "&", r"\\",
              r"\begin{bmatrix}", r"\end{bmatrix}", r"\mathbf", "m_s", " ", "d", "x", r"\sqrt",
              "[", "]", r"\,", "$", "%", "~", "'", r"\foo", r"\left", "|", "\u03c6", r"\tfrac",
              r"\bm", r"c\psi", "\\", r"\begin", r"\end", r"\varphi", r"\mathbb", "sin", "cos^",
              "^T", r"^\top", r"\tag", r"\quad", "(9)", r"\dot{x}_", "_0"]
    rng = random.Random(13)
    for _ in range(3000):
        text = "".join(rng.choice(pieces) for _ in range(rng.randint(1, 12)))
        for read in (lambda: latex_to_sympy(text, NAMES),
                     lambda: latex_to_sympy(text, NAMES, equation=True),
                     lambda: split_latex_matrix(text)):
            try:
                read()
            except ExpressionError:
                pass


@pytest.mark.parametrize("latex", [r"\sin^{-1}\phi", r"\cos^{-1}(\psi)", r"\tan^{-1}\phi"])
def test_a_function_to_the_minus_one_is_ambiguous(latex):
    r"""``\sin^{-1}\theta`` is the arcsine in many texts and 1/sin θ in others: it was read
    as 1/sin θ without a word. One error says both readings and how to write either."""
    with pytest.raises(LatexError, match="ambiguous") as caught:
        latex_to_sympy(latex, NAMES)
    assert r"\arc" in caught.value.reason and "^{-1}" in caught.value.reason
    assert latex_to_sympy(r"(\sin\phi)^{-1}", NAMES) == "(sin(phi))**(-1)" or \
        sympy.simplify(read(r"(\sin\phi)^{-1}") - 1 / sympy.sin(S["phi"])) == 0
