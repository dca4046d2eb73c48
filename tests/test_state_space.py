r"""A derivation printed as a first-order system, as control papers print it
(``[state_space]``, docs/derivation-format.md).

The cart-pole of :mod:`published_forms` (R. V. Florian, *Correct equations for the dynamics of
the cart-pole system*, 2007; Barto, Sutton & Anderson 1983): its two equations solved for the
accelerations, then written as :math:`\dot x = f(x, F)` with the state interleaved as control
texts order it, :math:`x = (x, \dot x, \theta, \dot\theta)`, and linearised about the upright
pole, :math:`\dot x = A_s x + B_s F` with :math:`A_s = \partial f/\partial x`,
:math:`B_s = \partial f/\partial F` at :math:`x = 0, F = 0` (Ogata, *Modern Control
Engineering*, the inverted pendulum on a cart). The forms are derived here from the source
equations with SymPy, with the planted errors of :mod:`published_forms` made in the source
equations first; a rate row and a state-space entry are planted in the printed matrices.
"""

from __future__ import annotations

import pickle
from pathlib import Path

import pytest
import sympy as sp

import wheeled_dyn as wd
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import CauseKind, DiagnosisKind as K, Verdict
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.errors import DerivationError

from published_forms import DATA, F, POLE_HEAD, cart_pole, ddth, ddx, dth, dx, th, x

STATE = (x, dx, th, dth)
#: Grid of the comparisons here (states per parameter set, parameter sets), and its seed.
SAMPLES, PARAM_SETS, SEED = 200, 3, 2026


def _first_order(error: str | None = None) -> tuple[sp.Matrix, sp.Matrix, sp.Matrix]:
    r"""(f, A_s, B_s) of the cart-pole with the planted ``error``, state :data:`STATE`."""
    cart, pole = cart_pole(error)
    (sol,) = sp.solve([cart, pole], [ddx, ddth], dict=True)
    f = sp.Matrix([dx, sp.simplify(sol[ddx]), dth, sp.simplify(sol[ddth])])
    at = {s: 0 for s in (*STATE, F)}
    A = f.jacobian(sp.Matrix(STATE)).subs(at).applyfunc(sp.simplify)
    B = f.jacobian(sp.Matrix([F])).subs(at).applyfunc(sp.simplify)
    return f, A, B


def _text(M: sp.Matrix) -> str:
    return str([[sp.sstr(e) for e in M.row(i)] for i in range(M.rows)]).replace("'", "")


def _file(folder: Path, name: str, table: str, linear: bool = True) -> Path:
    head = POLE_HEAD.format(form=name, error="", model=DATA / "cart_pole.toml", eqs="")
    head = head.split("[matrices]")[0]
    if linear:
        head = head.replace("[assumes]\n", "[assumes]\nlinearised_about = { x = 0.0, "
                            "theta = 0.0 }\n")
    path = folder / f"{name}.toml"
    path.write_text(head + "[state_space]\n" + table, encoding="utf-8")
    return path


def _linear(folder: Path, name: str, A: sp.Matrix, B: sp.Matrix) -> Path:
    return _file(folder, name, f'state = ["x", "dx", "theta", "dtheta"]\nA = "{_text(A)}"\n'
                 f'B = "{_text(B)}"\n')


def _nonlinear(folder: Path, name: str, f: sp.Matrix) -> Path:
    rows = ", ".join(f'"{sp.sstr(e)}"' for e in f)
    return _file(folder, name, f'state = ["x", "dx", "theta", "dtheta"]\nf = [{rows}]\n',
                 linear=False)


def _compare(path: Path):
    engine = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)
    return engine.compare(load_derivation(path))


def test_the_right_forms_agree(tmp_path):
    f, A, B = _first_order()
    for path in (_linear(tmp_path, "linear", A, B), _nonlinear(tmp_path, "nonlinear", f)):
        result = _compare(path)
        assert result.equivalent is True, [(r.element, r.texts) for r in result.records
                                           if r.verdict != Verdict.AGREES]
        assert result.state_rates_agree is True and not result.state_rates


@pytest.mark.parametrize("error", ["point_mass", "dropped", "trig"])
def test_a_planted_error_in_the_source_equations_is_found_in_the_linear_form(tmp_path, error):
    r"""The point mass's m l² for 4/3 m l², the coupling dropped, cos for sin in gravity: each
    changes A_s (the centripetal sign does not: it vanishes in the linearisation)."""
    _, A, B = _first_order(error)
    result = _compare(_linear(tmp_path, error, A, B))
    assert result.equivalent is False
    assert any(r.verdict == Verdict.DIFFERS for r in result.records)


@pytest.mark.parametrize("error", ["sign", "point_mass", "dropped", "trig"])
def test_a_planted_error_is_found_in_the_nonlinear_form(tmp_path, error):
    f, _, _ = _first_order(error)
    result = _compare(_nonlinear(tmp_path, error, f))
    assert result.equivalent is False
    assert any(r.verdict == Verdict.DIFFERS for r in result.records)


def test_a_stiffness_of_the_wrong_sign_is_named_in_the_equation_of_its_row(tmp_path):
    r"""A_s[4,3] (the pole's θ̈ from θ) with its sign reversed — the hanging pole's
    stiffness for the upright one's: the stiffness K[2,2] of the equation the row is, sign."""
    _, A, B = _first_order()
    A[3, 2] = -A[3, 2]
    result = _compare(_linear(tmp_path, "stiffness", A, B))
    assert result.equivalent is False
    k = next(r for r in result.records if r.element == "K[2,2]")
    assert k.verdict == Verdict.DIFFERS and any(d.kind == K.SIGN for d in k.diagnoses)
    assert any("equation 2 is row 4" in n for n in result.notes)


def test_a_rate_that_is_not_the_velocity_makes_the_system_wrong(tmp_path):
    r"""Row 1 gives x's rate as 2 dx: every equation may agree, the system does not."""
    _, A, B = _first_order()
    A[0, 1] = 2
    result = _compare(_linear(tmp_path, "rate", A, B))
    assert result.equivalent is False and result.state_rates_agree is False
    (said,) = result.state_rates
    assert "state row 1 (the rate of x)" in said and "2*dx" in said
    assert any(c.kind == CauseKind.NOT_EQUIVALENT and "2*dx" in c.explanation
               for c in result.causes)


def test_the_python_api_takes_a_state_space_form():
    _, A, B = _first_order()
    common = dict(
        coordinates={"positions": ["x", "theta"], "configuration": {"x": "x", "theta": "theta"}},
        symbols={"M": "M(cart)", "m": "M(pole)", "l": "CZ(pole)", "g": "g"}, inputs={"F": "F"},
        assumes={"families": ["urdf_proportions"],
                 "linearised_about": {"x": 0.0, "theta": 0.0}},
        samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)
    model = str(DATA / "cart_pole.toml")
    right = wd.compare(model, state_space={"state": list(STATE), "A": A, "B": B}, **common)
    assert right.equivalent is True
    A[3, 2] = 2 * A[3, 2]
    wrong = wd.compare(model, state_space={"state": list(STATE), "A": A, "B": B}, **common)
    assert wrong.equivalent is False


@pytest.mark.parametrize("table, item, words", [
    ('state = ["x", "dx", "theta"]\nf = ["dx", "0", "dtheta"]\n', "state_space.state",
     "appears 0 times"),
    ('state = ["x", "dx", "theta", "dtheta", "y"]\nf = ["dx"]\n', "state_space.state",
     "neither a position nor a velocity"),
    ('state = ["x", "dx", "theta", "dtheta"]\nf = ["dx", "0", "dtheta"]\n', "state_space.f",
     "shape"),
    ('state = ["x", "dx", "theta", "dtheta"]\nA = "[[0]]"\n', "state_space.A",
     "linearised_about"),
    ('state = ["x", "dx", "theta", "dtheta"]\nf = ["dx", "0", "dtheta", "0"]\nA = "[[0]]"\n',
     "state_space", "one of them"),
    ('state = ["x", "dx", "theta", "dtheta"]\nf = ["dx", "ddx", "dtheta", "0"]\n',
     "state_space.f[2]", "acceleration"),
    ('state = ["x", "dx", "theta", "dtheta"]\nf = ["dx", "0", "dtheta", "0"]\nD = 1\n',
     "state_space.D", "unknown key"),
])
def test_a_bad_table_is_one_clear_error(tmp_path, table, item, words):
    path = _file(tmp_path, "bad", table, linear=False)
    with pytest.raises(DerivationError) as info:
        _compare(path)
    err = pickle.loads(pickle.dumps(info.value))
    assert err.item == item and words in str(err) and str(path) in str(err)


def test_a_dropped_coupling_is_named_missing_not_a_point_mass(tmp_path):
    r"""The pole's coupling m l cos θ ẍ dropped before solving: the solved ẍ row lacks its
    θ̈ term, m l/(M + m) in its frame. Under the uniform pole's proportions m l is also
    3 I_xx/l, which was named "the pole treated as a point mass"; no body's own moment
    enters the cart's row (its multiplier is no 1 or 2 × lengths): the term is named missing."""
    _, A, B = _first_order("dropped")
    result = _compare(_linear(tmp_path, "dropped", A, B))
    assert result.equivalent is False
    assert not any(c.kind == CauseKind.POINT_MASS for c in result.causes), result.causes
    coupling = next(r for r in result.records if r.element == "A[1,2]")
    assert coupling.verdict == Verdict.DIFFERS and K.MISSING in coupling.kinds
    assert not any(d.kind == K.POINT_MASS for d in coupling.diagnoses), coupling.texts


def test_matrices_given_as_latex_agree(tmp_path):
    r"""A_s and B_s as the paper's LaTeX (here SymPy's printing of them, ``\left[\begin{matrix}
    …\right]``) read as the text form: the right system agrees, a stiffness doubled does not."""
    _, A, B = _first_order()
    for factor, right in ((1, True), (2, False)):
        A2 = A.copy()
        A2[3, 2] = factor * A2[3, 2]
        path = _file(tmp_path, f"latex{factor}", 'state = ["x", "dx", "theta", "dtheta"]\n'
                     f"A = {{ latex = '{sp.latex(A2)}' }}\nB = {{ latex = '{sp.latex(B)}' }}\n")
        assert _compare(path).equivalent is right


def _planar_robot(tmp_path: Path, flip: bool) -> Path:
    r"""``examples/my_planar_robot.toml`` (the planar balancing robot by Lagrange, velocities
    dx, dphi in a quasi set) linearised about the upright body and written x' = A x + B τ,
    x = (x, φ, ẋ, φ̇), as a wheeled pendulum's control paper prints it; ``flip``: the sign of
    A_s[4,2] (the body's stiffness) reversed."""
    m_b, m_w, J_w, r, l, J_b, g = sp.symbols("m_b m_w J_w r l J_b g")
    inertia = sp.Matrix([[m_b + 2 * m_w + 2 * J_w / r**2, -m_b * l], [-m_b * l, J_b + m_b * l**2]])
    inverse = inertia.inv()
    A, B = sp.zeros(4, 4), sp.zeros(4, 1)
    A[0, 2] = A[1, 3] = 1
    A[2:, :2] = (-inverse * sp.Matrix([[0, 0], [0, -m_b * g * l]])).applyfunc(sp.simplify)
    B[2:, :] = (inverse * sp.Matrix([[1 / r], [1]])).applyfunc(sp.simplify)
    if flip:
        A[3, 1] = -A[3, 1]
    text = (Path(__file__).parents[1] / "examples" / "my_planar_robot.toml").read_text()
    text = text[:text.index("[matrices]")].replace(
        "[assumes]\n", "[assumes]\nlinearised_about = { x = 0.0, phi = 0.0 }\n")
    path = tmp_path / f"planar{int(flip)}.toml"
    path.write_text(text + f'[state_space]\nstate = ["x", "phi", "dx", "dphi"]\n'
                    f'A = "{_text(A)}"\nB = "{_text(B)}"\n')
    return path


@pytest.mark.parametrize("flip", [False, True])
def test_a_wheeled_pendulum_in_state_space(tmp_path, flip):
    r"""Velocities named as their positions' rates in a quasi set (the heading speed dx of
    x): the state-space form is read; right it agrees, its stiffness's sign reversed is
    named K[2,2]."""
    result = _compare(_planar_robot(tmp_path, flip))
    assert result.equivalent is (not flip)
    if flip:
        k = next(r for r in result.records if r.element == "K[2,2]")
        assert k.verdict == Verdict.DIFFERS and K.SIGN in k.kinds, k.texts


@pytest.mark.parametrize("entry, item, words", [
    ((3, 3), "state_space.A[4,4]", "linear in the velocity dtheta"),
    ((0, 3), None, None)])
def test_a_velocity_term_in_a_velocity_row_is_one_clear_error(tmp_path, entry, item, words):
    r"""A damping (a motor's back-EMF) in A_s: dθ̇/dt linear in θ̇ is no term of the equations
    of motion — one error naming the entry, where the equations' reader named "equation 2"
    and a term the file never wrote; in a position's row it is that row's rate, said so."""
    _, A, B = _first_order()
    A[entry] = sp.Symbol("g")
    path = _linear(tmp_path, "damped", A, B)
    if item is None:
        result = _compare(path)
        assert result.state_rates_agree is False, result.state_rates
        return
    with pytest.raises(DerivationError) as info:
        _compare(path)
    err = pickle.loads(pickle.dumps(info.value))
    assert err.item == item and words in str(err), str(err)
