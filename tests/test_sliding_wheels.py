r"""Wheels a document's map holds fixed while the robot moves. A newcomer's planar model of a
two-wheeled balancing robot (tests/data/ros_balancer) maps its forward position and pitch and
leaves the wheel angles out: with ``kind = "holonomic"`` and no rolling constraint the wheels
slide without turning, and a right derivation of the robot rolling was told "extra term …
2 I_w/r²" and "the wheels treated as point masses", the map's reason only in the notes. It is
now the first cause; a map that turns the wheels with the motion has none.
"""

from __future__ import annotations

from pathlib import Path

import pytest
from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import CauseKind
from wheeled_dyn.derivations import load_derivation

MODEL = Path(__file__).parent / "data" / "ros_balancer" / "ros_balancer.toml"
DOC = '''title = "Planar balancer, wheels {how}"
model = "{model}"
[coordinates]
positions = ["x", "theta"]
kind = "holonomic"
configuration = {{ x0 = "x", psi = "0", phi = "-theta"{wheels} }}
[symbols]
R = {{ value = "R", units = "m" }}
[matrices]
A = "[[1, 0], [0, 1]]"
Q = "[0, 0]"
'''


@pytest.mark.parametrize("wheels, said", [("", True),
                                          (', theta_l = "x/R + theta", theta_r = "x/R + theta"',
                                           False)])
def test_wheels_held_while_the_robot_moves_are_the_first_cause(tmp_path, wheels, said):
    path = tmp_path / "planar.toml"
    path.write_text(DOC.format(how="held" if said else "turning", model=MODEL, wheels=wheels))
    result = ComparisonEngine(samples=100, param_sets=2, seed=SEED).compare(
        load_derivation(path))
    found = [c for c in result.causes if "wheels sliding, not turning" in c.explanation]
    assert bool(found) is said, result.causes
    if said:
        assert result.causes[0] is found[0] and found[0].kind == CauseKind.FILE_ERROR
        assert "theta_l, theta_r" in found[0].explanation
