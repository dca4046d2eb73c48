"""Equations of motion that are combinations of the true ones (a Newton–Euler derivation's
moment balance about the centre of mass with the reaction eliminated) are judged right, the
combination named; an error in them is still found; the search itself on synthetic arrays.

The right equations are written by hand from seed 000's 2.19 balances (1A)-(3A) (block on a
pin riding a slider; its centre of mass H/2 above the pin), with the pin's normal force
eliminated by (2A): independent of the code under test.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.grid.arrays import Arrays
from wheeled_dyn.compare.readings.row_combinations import combination
from wheeled_dyn.derivations import load_derivation

#: Engine grid.
SAMPLES, PARAM_SETS = 60, 2

FILE = '''
title = "Block on springs: Newton-Euler equations of motion, N eliminated"
model = "spring_block"
[coordinates]
kind = "holonomic"
positions = ["x", "theta"]
rolling = "none"
configuration = { x = "x", theta = "theta" }
units = { x = "m", theta = "rad" }
[symbols]
m    = { value = "M(block)", units = "kg" }
H    = { value = "2*MZ(block)/M(block)", units = "m" }
I_cg = { value = "YY(block) - (MX(block)**2 + MZ(block)**2)/M(block)", units = "kg*m**2" }
g    = { value = "g", units = "m/s**2" }
K    = { value = "k_base", units = "N/m" }
x_in = { value = "rest_base", units = "m" }
K_T  = { value = "k_tilt", units = "N*m" }
[assumes]
families = ["urdf_structure"]
[matrices]
equations = [
  "K*(x_in - x) = m*(ddx + H/2*ddtheta*cos(theta) - H/2*dtheta**2*sin(theta))",
  "-K_T*theta + (m*g - m*H/2*ddtheta*sin(theta) - m*H/2*dtheta**2*cos(theta))*H/2*sin(theta) - K*(x_in - x)*H/2*cos(theta) = I_cg*ddtheta",
]
'''


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)


def _compare(engine, tmp_path: Path, text: str):
    path = tmp_path / "ne.toml"
    path.write_text(text)
    return engine.compare(load_derivation(path))


def test_moments_about_the_centre_of_mass_agree(engine, tmp_path):
    result = _compare(engine, tmp_path, FILE)
    differ = [(r.element, r.texts) for r in result.records if r.verdict != "agrees"]
    assert not differ, differ
    causes = [c.explanation for c in result.causes if c.kind == "convention"]
    assert any("equation 2 = H*eq1*cos(theta)/2 - eq2" in c for c in causes), causes


def test_an_error_in_a_combined_equation_is_not_explained_away(engine, tmp_path):
    planted = FILE.replace("*H/2*sin(theta) - K*(x_in", "*H/2*cos(theta) - K*(x_in")
    assert planted != FILE
    result = _compare(engine, tmp_path, planted)
    assert any(r.verdict == "differs" for r in result.records)
    assert not any("eq k: the true equation k" in c.explanation for c in result.causes)


def _arrays(rng, n=3, N=40):
    A = rng.normal(size=(N, n, n))
    A = A @ np.swapaxes(A, 1, 2) + n * np.eye(n)
    return Arrays(A=A, Q=rng.normal(size=(N, n)), h=rng.normal(size=(N, n)))


def test_the_combination_is_found_only_when_it_carries_every_part():
    rng = np.random.default_rng(SEED)
    truth = _arrays(rng)
    W = np.eye(3) + np.triu(rng.normal(size=(40, 3, 3)), 1)
    doc = Arrays(A=W @ truth.A, Q=np.einsum("nij,nj->ni", W, truth.Q),
                 h=np.einsum("nij,nj->ni", W, truth.h))
    assert np.allclose(combination(doc, truth, None), W)
    scaled = np.eye(3) * rng.uniform(1, 2, (40, 1, 3))           # rows scaled only
    diagonal = Arrays(A=scaled @ truth.A, Q=np.einsum("nij,nj->ni", scaled, truth.Q),
                      h=np.einsum("nij,nj->ni", scaled, truth.h))
    assert combination(diagonal, truth, None) is None
    wrong = Arrays(A=doc.A, Q=doc.Q, h=doc.h + 1e-3)              # h not carried
    assert combination(wrong, truth, None) is None


#: Relative energy drift of the document's own simulation over 1 s.
DOCUMENT_DRIFT_TOL = 1e-7


def test_the_documents_own_simulation_reads_the_equations_separated(engine, tmp_path):
    r"""Simulated from its own equations (with the combination undone, as compared), the
    Newton–Euler form conserves its own energy: its A is then symmetric."""
    import sympy as sp
    from wheeled_dyn.compare.readings.row_combinations import as_compared
    from wheeled_dyn.simulate.documented import side_by_side
    path = tmp_path / "ne.toml"
    path.write_text(FILE)
    d = load_derivation(path)
    result = engine.compare(d)
    assert result.row_combination
    A = as_compared(d, result).read_off().A
    assert sp.simplify(A - A.T) == sp.zeros(2, 2)
    s = side_by_side(d, {"x": 0.05, "theta": 0.2}, duration=1.0)
    energy = s.document.energy
    assert np.abs(energy - energy[0]).max() < DOCUMENT_DRIFT_TOL * abs(energy[0])
