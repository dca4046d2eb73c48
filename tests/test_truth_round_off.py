r"""The truth's own round-off never decides. Pinocchio computes every body's terms in one frame,
so each row of the truth carries the round-off of the model's largest terms: a two-link arm
whose upper arm is 10⁷ m long beside a forearm of 0.8 m (its inertia about the shoulder
~10¹⁴ kg m²) has 0.04 of round-off in the elbow's equation, 2e-7 of that row's size — a right
file was "not right as a system", with a condition it "agrees only if" (10⁷ m) or invented
causes (10¹⁰ m, 10²⁰ m: "not independent"). Now those differences are *undecided*, never
"agrees" and never a cause; at 1 m nothing changes, and a planted error larger than the
round-off still differs at 10⁷ m.

The arm and its right file are the course's two-link arm of ``tests/data/two_link_arm``
(uniform rods, Lagrange's equations); the long arm is the same URDF with the upper arm's
length, centre of mass and inertia scaled, as a user would write it.
"""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.judge.precision import ROUND_OFF_EPS, round_off
from wheeled_dyn.compare.records import Verdict
from wheeled_dyn.derivations import load_derivation

DATA = Path(__file__).parent / "data" / "two_link_arm"
#: Engine grid.
SAMPLES, PARAM_SETS = 200, 3
#: The forearm's gravity term as printed, and with a planted factor 3 (an error of m2 g l2,
#: about 12 N m: above the elbow row's round-off at 10⁷ m, about 0.04 N m measured).
GRAVITY = "m2*g*l2/2*cos(q1 + q2) = tau2"
PLANTED = "3*m2*g*l2/2*cos(q1 + q2) = tau2"


def _arm(folder: Path, length: float, planted: bool = False) -> Path:
    r"""The course's arm with the upper arm ``length`` long (a uniform rod of 2 kg) in
    ``folder``; its right file, or with the forearm's gravity term 3 × the truth's."""
    folder.mkdir()
    for name in ("two_link_arm.toml", "arm_lagrange.toml"):
        shutil.copy(DATA / name, folder / name)
    urdf = (DATA / "two_link_arm.urdf").read_text()
    inertia = 2.0 * length ** 2 / 12
    for old, new in (
            ('<origin xyz="0.5 0 0" rpy="0 0 0"/>', f'<origin xyz="{length / 2!r} 0 0" '
             'rpy="0 0 0"/>'),
            ('iyy="0.16666666666666666" iyz="0" izz="0.16666666666666666"',
             f'iyy="{inertia!r}" iyz="0" izz="{inertia!r}"'),
            ('<origin xyz="0.5 0 0" rpy="0 1.5707963267948966 0"/>',
             f'<origin xyz="{length / 2!r} 0 0" rpy="0 1.5707963267948966 0"/>'),
            ('<cylinder radius="0.02" length="1.0"/>',
             f'<cylinder radius="0.02" length="{length!r}"/>'),
            ('<origin xyz="1.0 0 0" rpy="0 0 0"/>', f'<origin xyz="{length!r} 0 0" '
             'rpy="0 0 0"/>')):
        assert old in urdf, old
        urdf = urdf.replace(old, new)
    (folder / "two_link_arm.urdf").write_text(urdf)
    doc = folder / "arm_lagrange.toml"
    if planted:
        text = doc.read_text()
        assert text.count(GRAVITY) == 1
        doc.write_text(text.replace(GRAVITY, PLANTED))
    return doc


def _compare(doc: Path):
    engine = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)
    return engine.compare(load_derivation(doc))


def test_at_a_metre_the_right_file_agrees(tmp_path):
    result = _compare(_arm(tmp_path / "arm", 1.0))
    assert result.equivalent is True
    assert all(r.verdict == Verdict.AGREES for r in result.records)


@pytest.mark.parametrize("length", [1e7, 1e10, 1e20])
def test_round_off_is_undecided_never_a_difference(tmp_path, length):
    result = _compare(_arm(tmp_path / "arm", length))
    verdicts = {r.element: r.verdict for r in result.records}
    assert result.equivalent is None, (result.equivalent, result.equations)
    assert not result.causes, [c.explanation for c in result.causes]
    assert Verdict.UNDECIDED in verdicts.values()
    assert set(verdicts.values()) <= {Verdict.AGREES, Verdict.UNDECIDED}, verdicts
    undecided = [r for r in result.records if r.verdict == Verdict.UNDECIDED]
    assert all("round-off" in r.diagnoses[0].text for r in undecided)
    assert all(r.element.startswith(("A[2,", "h[2]")) for r in undecided), verdicts


def test_an_error_larger_than_the_round_off_still_differs(tmp_path):
    result = _compare(_arm(tmp_path / "arm", 1e7, planted=True))
    assert result.equivalent is False
    gravity = next(r for r in result.records if r.element == "Q[2]")
    assert gravity.verdict == Verdict.DIFFERS, gravity
    assert "3" in " ".join(d.text for d in gravity.diagnoses), gravity.diagnoses


def test_the_round_off_of_a_combination_adds_its_weights():
    rng = np.random.default_rng(SEED)
    A = rng.uniform(-1, 1, (5, 2, 2))
    A[:, 0, 0] = 1e14                     # the largest term, row 1's
    n = rng.uniform(-1, 1, (5, 2))
    one = round_off(np.tile([0.0, 1.0], (5, 1)), A, n)
    both = round_off(np.tile([3.0, -1.0], (5, 1)), A, n)
    eps = float(np.finfo(float).eps)
    assert np.allclose(one, ROUND_OFF_EPS * eps * 1e14)
    assert np.allclose(both, 4 * one)


def test_the_report_says_not_decided(tmp_path):
    r"""The HTML section of an undecided system says so ("not decided", "cannot decide"),
    not "not equivalent" nor "values not finite"."""
    from wheeled_dyn.report.html import derivation_html
    html = derivation_html(_compare(_arm(tmp_path / "arm", 1e7)))
    assert "not decided" in html and "cannot decide" in html
    assert "not equivalent" not in html and "values not finite" not in html
