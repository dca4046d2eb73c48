r"""A document in Kane's form :math:`F_r + F_r^* = 0`: every row is −1 × the equation of motion
(:math:`F_r^* = -(M\dot u + \dots)`), a factor the file need not declare.

The rolling disc of SymPy's mechanics documentation ("A rolling disc, with Kane's method",
``data/geometry/rolling_disc_kane.toml`` gives its solved form), written as
:math:`F_r + F_r^* = 0` with its generalized speeds :math:`u_1, u_2, u_3`. Its second row has
two terms, :math:`-(\tfrac32 m r^2\dot u_2 + m r^2 u_1u_3)`. With the sign of the second flipped,
the row reads as well as printed (+1: its inertia's sign wrong) as in −1 (the term's sign
wrong): read as the other rows are, the term's sign is named (it was the inertia's, and the
inertia the document inverts "not positive definite at 5000 of 5000 samples")."""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.derivations import load_derivation

SOLVED = Path(__file__).parent / "data" / "geometry" / "rolling_disc_kane.toml"
KANE = [
    "m*g*r*sin(q2) - (5*m*r**2/4*du1 - 3*m*r**2/2*u2*u3 + m*r**2/4*u3**2*tan(q2)) = 0",
    "-(3*m*r**2/2*du2 + m*r**2*u1*u3) = 0",
    "-(m*r**2/4*du3 + m*r**2/2*u1*u2 - m*r**2/4*u1*u3*tan(q2)) = 0",
]


@pytest.fixture(scope="module")
def engine() -> ComparisonEngine:
    return ComparisonEngine(samples=300, param_sets=3, seed=SEED)


def _file(tmp_path: Path, rows: list[str]) -> Path:
    text = SOLVED.read_text()
    text = text[:text.index("[matrices]")].replace("solved for the speed rates", "F_r + F_r* = 0")
    path = tmp_path / "rolling_disc_kane_form.toml"
    path.write_text(text + "[matrices]\nequations = [\n" + "".join(f'  "{r}",\n' for r in rows)
                    + "]\n")
    return path


def test_kanes_form_agrees(engine, tmp_path):
    result = engine.compare(load_derivation(_file(tmp_path, KANE)))
    assert result.equivalent is True, [c.explanation for c in result.causes]


def test_a_terms_sign_in_a_two_term_row_is_the_terms(engine, tmp_path):
    rows = [KANE[0], KANE[1].replace("+ m*r**2*u1*u3", "- m*r**2*u1*u3"), KANE[2]]
    result = engine.compare(load_derivation(_file(tmp_path, rows)))
    assert result.equivalent is False
    wrong = {r.element for r in result.records if r.verdict == "differs"}
    assert wrong == {"h[2]:u1*u3"}, wrong
    assert any(c.kind == "sign" and c.elements == ("h[2]:u1*u3",) for c in result.causes)
    assert not any(c.kind == "not_positive_definite" for c in result.causes), result.causes


#: The reaction-wheel pendulum of D. J. Block, K. J. Åström, M. W. Spong, *The Reaction Wheel
#: Pendulum* (2007), ch. 2, with the wheel's absolute angle q2 (model
#: ``data/published/reaction_wheel.toml``), as F_r + F_r* = 0: the pendulum's row, then the
#: wheel's, :math:`\tau - I_2\ddot q_2 = 0`, a row of two terms.
WHEEL_HEAD = f"""title = "Reaction-wheel pendulum, F_r + F_r* = 0"
model = "{Path(__file__).parent / 'data' / 'published' / 'reaction_wheel.toml'}"
[coordinates]
positions = ["q1", "q2"]
configuration = {{ pivot = "q1", wheel_joint = "q2 - q1" }}
units = {{ q1 = "rad", q2 = "rad" }}
[inputs]
tau_w = "tau"
[symbols]
m1 = {{ value = "M(pendulum)", units = "kg" }}
m2 = {{ value = "M(wheel)", units = "kg" }}
l1 = {{ value = "l1", units = "m" }}
lc1 = {{ value = "CZ(pendulum)", units = "m" }}
I1 = {{ value = "IYY(pendulum)", units = "kg*m**2" }}
I2 = {{ value = "IYY(wheel)", units = "kg*m**2" }}
g = {{ value = "g", units = "m/s**2" }}
tau = {{ input = true, units = "N*m" }}
[assumes]
families = ["urdf_structure"]
[matrices]
equations = [
  "(m1*lc1 + m2*l1)*g*sin(q1) - tau - (m1*lc1**2 + m2*l1**2 + I1)*ddq1 = 0",
"""


@pytest.mark.parametrize("row, named", [("tau - I2*ddq2", None), ("-tau - I2*ddq2", "B[2,1]"),
                                         ("tau + I2*ddq2", "A[2,2]")])
def test_a_two_row_documents_tie_is_read_as_its_other_row(engine, tmp_path, row, named):
    r"""Two rows: the pendulum's read in −1 beside the wheel's two-term row, where one term's
    sign is wrong and the row reads as well in +1 as in −1. Read as the other row is, the
    term planted is named — the torque's sign, or the inertia's — not its right neighbour
    (a consensus of more than half of all rows never formed with two)."""
    path = tmp_path / "wheel.toml"
    path.write_text(WHEEL_HEAD + f'  "{row} = 0",\n]\n')
    result = engine.compare(load_derivation(path))
    wrong = [r.element for r in result.records if r.verdict != "agrees"]
    assert wrong == ([] if named is None else [named]), wrong
    if named is not None:
        (r,) = [r for r in result.records if r.element == named]
        assert "sign" in r.kinds, r.texts
