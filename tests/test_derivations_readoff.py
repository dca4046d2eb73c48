r"""Reading A, h, Q, B off equations written term by term, against the matrix form of the same
system (a cart carrying a pendulum)."""

from __future__ import annotations

import numpy as np
import pytest
import sympy

from wheeled_dyn.derivations import load_derivation, split_equation_terms
from wheeled_dyn.errors import DerivationError

SEED = 7
N_SAMPLES = 20
#: Largest |difference| between the two forms evaluated at random numbers.
NUMERIC_TOL = 1e-10

HEAD = """
title = "cart with a pendulum"
model = "cart"

[coordinates]
positions = ["x", "th"]
configuration = { x = "x", th = "th" }

[inputs]
force = "F"

[symbols]
m1 = { value = "M(cart)", units = "kg" }
m2 = { value = "M(bob)", units = "kg" }
l = { value = "MY(bob)/M(bob)", units = "m" }
g = "g"
c = { free = true, units = "N*s/m" }
F = { input = true, units = "N" }
"""

MATRIX_FORM = HEAD + """
[matrices]
A = "[[m1 + m2, m2*l*cos(th)], [m2*l*cos(th), m2*l**2]]"
C = [["0", "-m2*l*sin(th)*dth"], ["0", "0"]]
Q = ["0", "m2*g*l*sin(th)"]
B = "[[1], [0]]"
"""

EQUATION_FORM = HEAD + """
[matrices]
equations = [
  "(m1 + m2)*ddx + m2*l*cos(th)*ddth - m2*l*sin(th)*dth**2 = F",
  "m2*l*cos(th)*ddx + m2*l**2*ddth + m2*g*l*sin(th) = 0",
]
"""


def _write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text, encoding="utf-8")
    return path


def test_equation_form_equals_matrix_form(tmp_path):
    mat = load_derivation(_write(tmp_path, "m.toml", MATRIX_FORM))
    eqs = load_derivation(_write(tmp_path, "e.toml", EQUATION_FORM))
    assert mat.form == "matrices" and eqs.form == "equations"
    A, h, Q, B, inputs = eqs.read_off()
    assert sympy.simplify(A - mat.A) == sympy.zeros(2, 2)
    assert sympy.simplify(Q - mat.Q) == sympy.zeros(2, 1)
    assert sympy.simplify(B - mat.B) == sympy.zeros(2, 1)
    qd = sympy.Matrix(mat.velocities)
    assert sympy.simplify(mat.C * qd - h) == sympy.zeros(2, 1)
    assert inputs == mat.input_symbols == (mat.symbol("F"),)
    # the matrix form's read_off gives the same four parts
    mA, mh, mQ, mB, _ = mat.read_off()
    assert (mA, mQ, mB) == (mat.A, mat.Q, mat.B)
    assert sympy.simplify(mh - h) == sympy.zeros(2, 1)


def test_read_off_numerically_reproduces_the_equations(tmp_path):
    d = load_derivation(_write(tmp_path, "e.toml", EQUATION_FORM))
    A, h, Q, B, inputs = d.read_off()
    qdd = sympy.Matrix(d.accelerations)
    rebuilt = A * qdd + h + Q - B * sympy.Matrix(inputs)
    original = sympy.Matrix([eq.lhs - eq.rhs for eq in d.equations])
    names = sorted((rebuilt.free_symbols | original.free_symbols), key=str)
    f = sympy.lambdify(names, rebuilt - original, "numpy")
    rng = np.random.default_rng(SEED)
    for _ in range(N_SAMPLES):
        assert np.max(np.abs(f(*rng.uniform(-2, 2, len(names))))) < NUMERIC_TOL


def test_known_parts_of_the_split():
    x, v, a, u, k, m = sympy.symbols("x v a u k m", real=True)
    terms = split_equation_terms([m * a + k * v**2 + 3 * sympy.sin(x) - 2 * u],
                                 [a], [v], [u])
    assert terms.A == sympy.Matrix([[m]])
    assert terms.h == sympy.Matrix([k * v**2])
    assert terms.Q == sympy.Matrix([3 * sympy.sin(x)])
    assert terms.B == sympy.Matrix([[2]])


@pytest.mark.parametrize("term, words", [
    ("c*dx", "linear in the velocity dx"),
    ("c*dx*dth**2", "of degree 3"),
    ("c*ddx*dth", "not linear in the accelerations"),
    ("c*F*dth", "not linear in the inputs"),
    ("c*sin(dth)", "not a polynomial"),
])
def test_terms_of_no_group_are_named(tmp_path, term, words):
    text = EQUATION_FORM.replace("- m2*l*sin(th)*dth**2 = F", f"+ {term} = F")
    d = load_derivation(_write(tmp_path, "bad.toml", text))
    with pytest.raises(DerivationError) as err:
        d.read_off()
    assert err.value.item == "equation 1"
    assert words in str(err.value)
    assert "bad.toml" in str(err.value)


def test_gamma_gives_B(tmp_path):
    text = MATRIX_FORM.replace('B = "[[1], [0]]"', 'Gamma = "[F, 0]"')
    d = load_derivation(_write(tmp_path, "g.toml", text))
    assert d.B == sympy.Matrix([[1], [0]])
    bad = MATRIX_FORM.replace('B = "[[1], [0]]"', 'Gamma = "[F + m1, 0]"')
    with pytest.raises(DerivationError, match=r"Gamma\[1\]"):
        load_derivation(_write(tmp_path, "g2.toml", bad))


def test_rows_scale_and_unscale(tmp_path):
    text = EQUATION_FORM.replace("[matrices]", '[rows]\nscale = ["l", "1"]\n\n[matrices]')
    d = load_derivation(_write(tmp_path, "s.toml", text))
    assert d.row_scale == (d.symbol("l"), 1)
    scaled, plain = d.read_off(), d.read_off(unscale=True)
    assert sympy.simplify(plain.A[0, 1] * d.symbol("l") - scaled.A[0, 1]) == 0
    assert plain.A[1, 1] == scaled.A[1, 1]
