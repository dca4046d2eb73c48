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
