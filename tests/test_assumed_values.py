r"""Terms a file sets in ``[assume]`` (terms the model lacks: friction, an external force) to a
value other than 0 (:mod:`wheeled_dyn.compare.engine.assumed_values`).

The acrobot's equations written out after R. Tedrake, *Underactuated Robotics*, ch. 3 (the
acrobot; I1, I2 about the joints), as ``data/published/acrobot_simulation.toml`` maps its
symbols. A friction torque F_d the model lacks is added to the shoulder's equation:

- set to 0, the file agrees (the control);
- the shoulder's gravity term doubled and F_d set to minus that term: the value cancels the
  error. The file is judged as it declares, but the shoulder's equation *agrees only if*
  F_d has that value (with F_d at 0, as the model has it, it differs), the system is not
  right, and the cause names F_d and its value; the "assumes:" line says the value too,
  beside the declared family;
- a constant F_d is a term the truth lacks: the equation differs.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import Verdict
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.report.summary import assumes_line

DATA = Path(__file__).parent / "data" / "published"
#: Engine grid (the planted terms are structural).
SAMPLES, PARAM_SETS = 200, 3
GRAVITY_1 = "g*lc1*m1*sin(q1) + g*m2*(l1*sin(q1) + lc2*sin(q1 + q2))"
SHOULDER = ("(I1 + I2 + l1**2*m2 + 2*l1*lc2*m2*cos(q2))*ddq1 + (I2 + l1*lc2*m2*cos(q2))*ddq2 "
            "- 2*l1*lc2*m2*sin(q2)*dq1*dq2 - l1*lc2*m2*sin(q2)*dq2**2 + {gravity} + F_d = 0")
ELBOW = ("(I2 + l1*lc2*m2*cos(q2))*ddq1 + I2*ddq2 + l1*lc2*m2*sin(q2)*dq1**2 "
         "+ g*lc2*m2*sin(q1 + q2) = u")


def _file(tmp_path: Path, gravity: str, value: str) -> Path:
    text = (DATA / "acrobot_simulation.toml").read_text()
    head = text[:text.index("[matrices]")]
    head = head.replace('[assumes]', f'[assume]\nF_d = {{ value = "{value}", units = "N*m", '
                        'meaning = "friction at the shoulder (not in the model)" }\n[assumes]')
    path = tmp_path / "acrobot_friction.toml"
    path.write_text(head + "[matrices]\nequations = [\n"
                    f'  "{SHOULDER.format(gravity=gravity)}",\n  "{ELBOW}",\n]\n')
    path.with_name("acrobot.toml").write_text((DATA / "acrobot.toml").read_text())
    path.with_name("acrobot.urdf").write_text((DATA / "acrobot.urdf").read_text())
    return path


@pytest.fixture(scope="module")
def engine() -> ComparisonEngine:
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)


def test_friction_at_zero_agrees(engine, tmp_path):
    result = engine.compare(load_derivation(_file(tmp_path, GRAVITY_1, "0")))
    assert result.equivalent is True, [(e.label, e.verdict) for e in result.equations]


def test_a_value_that_cancels_an_error_is_no_agreement(engine, tmp_path):
    doubled = "2*g*lc1*m1*sin(q1) + g*m2*(l1*sin(q1) + lc2*sin(q1 + q2))"
    result = engine.compare(load_derivation(_file(tmp_path, doubled, "-g*lc1*m1*sin(q1)")))
    assert result.equivalent is False
    shoulder, elbow = result.equations
    assert shoulder.verdict == Verdict.AGREES_IF and elbow.verdict == Verdict.AGREES
    assert "F_d = -g*lc1*m1*sin(q1)" in shoulder.diagnoses[0].condition
    said = [c for c in result.causes if c.kind == "assumption" and "F_d" in c.explanation]
    assert said and "equation 1" in said[0].explanation, result.causes
    line = assumes_line(result, {"F_d": "-g*lc1*m1*sin(q1)"})
    assert "the file sets F_d = -g*lc1*m1*sin(q1)" in line and result.assumes[0] in line


def test_a_constant_the_truth_lacks_differs(engine, tmp_path):
    result = engine.compare(load_derivation(_file(tmp_path, GRAVITY_1, "1/2")))
    assert result.equivalent is False
    assert result.equations[0].verdict == Verdict.DIFFERS
