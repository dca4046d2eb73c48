r"""A newcomer's own two-wheeled balancer (``data/newcomer_balancer``): a ROS URDF (base_footprint
root, base_link 0.065 m above the axle, a turned battery, wheel cylinders turned by
``rpy="1.5708 0 0"``) and its author's own Kane derivation in the quasi-velocities
:math:`(v, \omega, \dot\theta)`, its centre-of-mass height measured from the axle
(``z_b = CZ(base_link) + 0.065``). Right, it agrees; with the height measured from base_link
(``z_b = CZ(base_link)``) it differs, in the elements that hold the height."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from conftest import SEED
from shipped_copies import published_copy
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import CauseKind, DiagnosisKind
from wheeled_dyn.derivations import load_derivation

DATA = Path(__file__).parent / "data" / "newcomer_balancer"
HEIGHT = 'z_b  = { value = "CZ(base_link) + 0.065", units = "m" }'


def _compare(tmp_path: Path, height: str):
    path = published_copy(tmp_path, "segbot2", "segbot2_kane", (HEIGHT, height), data=DATA)
    return ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(
        load_derivation(path))


def test_the_newcomers_kane_derivation_agrees(tmp_path):
    result = _compare(tmp_path, HEIGHT)
    assert result.equivalent is True, [c.explanation for c in result.causes]


def test_a_height_from_the_wrong_point_differs(tmp_path):
    result = _compare(tmp_path, HEIGHT.replace(" + 0.065", ""))
    assert result.equivalent is False
    wrong = {r.element for r in result.records if r.verdict != "agrees"}
    assert {"A[1,3]", "A[3,3]"} <= wrong, wrong


#: The pitch row's inertia, the quantity the newcomer divides the row by, and the same
#: written with z_b for z_b**2 (kg·m beside kg·m²) — everywhere but the acceleration's own
#: coefficient, which the author writes as 1 (D/D).
INERTIA = "I_yy + m_b*x_b**2 + m_b*z_b**2"
NO_SQUARE = "I_yy + m_b*x_b**2 + m_b*z_b"


def _divided(divisor: str) -> str:
    r"""The newcomer's file with the pitch row (the third) of A, C, Q and B divided by
    ``divisor``, its A[3,3] written 1."""
    import tomllib

    import sympy as sp
    text = (DATA / "segbot2_kane.toml").read_text()
    matrices = tomllib.loads(text)["matrices"]
    lines = []
    for key in "ACQB":
        M = sp.Matrix(sp.sympify(matrices[key]))
        rows = [list(M.row(i)) for i in range(M.rows)] if M.cols > 1 else [[x] for x in M]
        rows[2] = [sp.Symbol("DIV_") if x == 0 else sp.sympify(
            f"({sp.sstr(x)})/({divisor})", evaluate=False) for x in rows[2]]
        if key == "A":
            rows[2][2] = sp.Integer(1)
        rows[2] = [0 if x == sp.Symbol("DIV_") else x for x in rows[2]]
        body = ", ".join("[" + ", ".join(sp.sstr(x) for x in r) + "]" for r in rows) \
            if M.cols > 1 else ", ".join(sp.sstr(r[0]) for r in rows)
        lines.append(f'{key} = "[{body}]"')
    return text[:text.index("[matrices]")] + "[matrices]\n" + "\n".join(lines) + "\n"


def _compare_text(tmp_path: Path, text: str):
    path = published_copy(tmp_path, "segbot2", "segbot2_kane", data=DATA)
    path.write_text(text)                     # the model beside it, the document as given
    return ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(
        load_derivation(path))


def test_the_pitch_row_divided_by_its_inertia_agrees(tmp_path):
    result = _compare_text(tmp_path, _divided(INERTIA))
    assert result.equivalent is True, [c.explanation for c in result.causes]


@pytest.mark.parametrize("units", [True, False], ids=["declared", "from-values"])
def test_a_divisor_with_wrong_units_is_flagged_where_it_is_written(tmp_path, units):
    r"""z_b for z_b² in the divisor: the elements that hold it differ, each with the term's
    units where the file declares them; A[3,3] = 1, written right, agrees (a ratio adding
    kg·m to kg·m² is no frame the row was written in, though four elements share it) — also
    where the file declares no units: its symbols' values give them (M(link) a mass,
    CZ(link) a length)."""
    text = _divided(NO_SQUARE)
    if not units:
        text = re.sub(r',\s*units = "[^"]*"', "", text)
        assert "units" not in text.split("[symbols]")[1].split("[matrices]")[0]
    result = _compare_text(tmp_path, text)
    assert result.equivalent is False
    by = {r.element: r for r in result.records}
    assert by["A[3,3]"].verdict == "agrees", by["A[3,3]"].diagnoses
    for element in ("A[3,1]", "Q[3]", "B[3,1]", "B[3,2]"):
        r = by[element]
        assert r.verdict == "differs", (element, r.diagnoses)
        assert not units or any(x.kind == DiagnosisKind.DIMENSION and "m_b*z_b is kg·m beside "
                                "kg·m^2" in x.text for x in r.diagnoses), (element, r.diagnoses)


#: The newcomer's derivation in its wheel angles (``segbot2_wheels.toml``): each relative to
#: the body, as its map declares; and the map of wheel angles measured from the ground
#: (the body's pitch added), with their rates.
RELATIVE = ('configuration = { theta_l = "phi_l", theta_r = "-phi_r", '
            'psi = "R*(phi_r - phi_l)/(2*L)", phi = "-theta" }\n'
            'velocity_map = { dphi_l = "dtheta_l", dphi_r = "-dtheta_r", dtheta = "-dphi" }')
ABSOLUTE = ('configuration = { theta_l = "phi_l + theta", theta_r = "-phi_r - theta", '
            'psi = "R*(phi_r - phi_l)/(2*L)", phi = "-theta" }\n'
            'velocity_map = { dphi_l = "dtheta_l + dphi", dphi_r = "-dtheta_r + dphi", '
            'dtheta = "-dphi" }')


@pytest.mark.parametrize("declared", ["relative", "absolute"])
def test_wheel_angles_declared_from_the_ground_are_read_from_the_body(tmp_path, declared):
    r"""The wheel-angle derivation is right with the wheels' angles relative to the body. A
    file declaring them from the ground (its equations unchanged) differs, and its first
    cause reads each wheel's angle from the body, φ → φ − θ for both at once — velocities
    that are their positions' rates read along (the rolling constraints eliminated, x and y
    no functions of them); it was "at least one is a quasi-velocity"."""
    text = (DATA / "segbot2_wheels.toml").read_text()
    assert text.count(RELATIVE) == 1
    if declared == "absolute":
        text = text.replace(RELATIVE, ABSOLUTE)
    result = _compare_text(tmp_path, text)
    if declared == "relative":
        assert result.equivalent is True, [c.explanation for c in result.causes]
        return
    assert result.equivalent is False
    first = result.causes[0]
    assert first.kind == CauseKind.CONVENTION, result.causes
    assert "phi_l → phi_l − theta" in first.explanation, first.explanation
    assert "phi_r → phi_r − theta" in first.explanation, first.explanation


def test_boltzmann_hamel_terms_missing_beside_a_wrong_inertia_are_said(tmp_path):
    r"""A[1,2] = A[2,1] written −m_b y_b cos ψ (wrong along ψ) and C taken as the Christoffel
    matrix of that A in (v, ω, θ̇) as if they were rates of coordinates: the products of h
    the Christoffel terms of the wrong A do not give, ω² in row 1 and vω in row 2 (the
    Boltzmann–Hamel terms; in vω the ψ-derivatives cancel), keep their quasi-coordinate
    cause (they were said to "follow from A[1,2]")."""
    import tomllib

    import sympy as sp

    from wheeled_dyn.compare.causes.methods import christoffel_tensor
    text = (DATA / "segbot2_kane.toml").read_text()
    matrices = tomllib.loads(text)["matrices"]
    names = {n: sp.Symbol(n) for n in ("x", "psi", "theta", "v", "omega", "dtheta")}
    A = sp.Matrix(sp.sympify(matrices["A"], locals=names))
    assert A[0, 1] == -sp.Symbol("m_b") * sp.Symbol("y_b")
    A[0, 1] = A[1, 0] = A[0, 1] * sp.cos(names["psi"])
    H = christoffel_tensor(A, [names["x"], names["psi"], names["theta"]])
    nu = [names["v"], names["omega"], names["dtheta"]]
    C = sp.Matrix(3, 3, lambda i, j: sp.Add(*(H[i][j][k] * nu[k] for k in range(3))))

    def rows(M: sp.Matrix) -> str:
        return "[" + ", ".join("[" + ", ".join(sp.sstr(x) for x in M.row(i)) + "]"
                               for i in range(M.rows)) + "]"
    body = (f'A = "{rows(A)}"\nC = "{rows(C)}"\nQ = "{matrices["Q"]}"\n'
            f'B = """{matrices["B"]}"""\n')
    result = _compare_text(tmp_path, text[:text.index("[matrices]")] + "[matrices]\n" + body)
    assert result.equivalent is False
    (quasi,) = [c for c in result.causes if c.kind == CauseKind.QUASI_COORDINATE_CHRISTOFFEL]
    assert {"h[1]:omega*omega", "h[2]:v*omega"} <= set(quasi.elements), result.causes


def test_two_lengths_exchanged_in_a_long_element_are_named(tmp_path):
    r"""R and L exchanged in the wheels' yaw term of the heading inertia, an element of
    thirteen terms: named as the exchange (the trials of one symbol for another in its
    earlier terms had used up the search, "no single-term diagnosis")."""
    text = (DATA / "segbot2_kane.toml").read_text()
    old = "2*J_w*L**2/R**2"
    assert text.count(old) == 1
    result = _compare_text(tmp_path, text.replace(old, "2*J_w*R**2/L**2"))
    assert result.equivalent is False
    (a22,) = [r for r in result.records if r.element == "A[2,2]"]
    assert any(x.kind == DiagnosisKind.SWAP and x.written == "2*J_w*R**2/L**2"
               for x in a22.diagnoses), a22.diagnoses
