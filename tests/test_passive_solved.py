r"""A passive body's equation solved for its acceleration (no inputs: a textbook's rolling
disk, a pendulum): an error in the inertia it divided by is named in that inertia, read back
from its gravity and velocity terms (:math:`W[Q\;H] = [Q_{doc}\;H_{doc}]`, :math:`M =
W^{-1}A_{doc}`).

Before, a form without inputs was never read back (the reading needed B), so a term dropped
from the denominator got "no single-term diagnosis"; and with one coordinate every inertia is
the truth's times a function, which was said as "the determinant … differs" rather than which
term of the inertia.

The eccentric disk rolling without slipping (seed 000's rolling disk: mass m, centre of mass
a from the axle, I about it, radius R), Greenwood, *Advanced Dynamics* (2003):
:math:`(I + m(R^2 - 2Ra\cos\theta + a^2))\ddot\theta + m a\sin\theta\,(R\dot\theta^2 + g) = 0`.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import DiagnosisKind, Verdict
from wheeled_dyn.derivations import load_derivation

SOLVED = '''
title = "Eccentric disk rolling, solved for its acceleration"
model = "rolling_disk"

[coordinates]
positions = ["theta"]
kind = "holonomic"
rolling = "none"
configuration = { x = "R*theta", theta = "theta" }
units = { theta = "rad" }

[symbols]
m = { value = "M(disk)", units = "kg" }
a = { value = "-CZ(disk)", units = "m" }
I = { value = "IYY(disk)", units = "kg*m**2" }
R = { value = "R", units = "m" }
g = { value = "g", units = "m/s**2" }

[assumes]
families = ["urdf_structure"]

[matrices]
equations = ["ddtheta = -m*a*sin(theta)*(R*dtheta**2 + g)/(I + m*(R**2 - 2*R*a*cos(theta) + a**2))"]
'''
DENOMINATOR = "(I + m*(R**2 - 2*R*a*cos(theta) + a**2))"


def _compare(tmp_path: Path, denominator: str = DENOMINATOR):
    path = tmp_path / "solved.toml"
    path.write_text(SOLVED.replace(DENOMINATOR, denominator))
    return ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(load_derivation(path))


def test_the_right_solved_form_agrees(tmp_path):
    assert _compare(tmp_path).equivalent is True


@pytest.mark.parametrize("denominator, kind, words", [
    ("(I + m*(R**2 - 2*R*a*cos(theta)))", DiagnosisKind.PARALLEL_AXIS, "a**2*m"),
    ("(I + m*(R**2 + 2*R*a*cos(theta) + a**2))", DiagnosisKind.SIGN, "A[1,1]"),
])
def test_an_error_in_the_inertia_divided_by_is_named_there(tmp_path, denominator, kind, words):
    result = _compare(tmp_path, denominator)
    assert result.equivalent is False
    differing = [r for r in result.records if r.verdict == Verdict.DIFFERS]
    said = " ".join(d.text for r in differing for d in r.diagnoses)
    kinds = {d.kind for r in differing for d in r.diagnoses}
    assert "A[1,1]:" in said and words in said, said
    assert kind in kinds and DiagnosisKind.COMMON_DIVISOR not in kinds, (kinds, said)
