r"""A family explains a difference by the parameters, never by where the states fell.

Grids under undeclared families have the states of the grid of the same size under the
declared families alone (:class:`wheeled_dyn.compare.grid.grid.Grids`): the control against
which a family is judged (:mod:`wheeled_dyn.compare.judge.families`) differs from the family's
grid in its parameter sets only. The case: ``data/published/wip_planar_divided.toml`` with
:math:`m g l\,e^{-10^4\theta^2}` added to the pitch equation's gravity term (an error near
θ = 0 only, whatever the parameters). The main grid and the control saw it; a family's grid,
drawn with states of its own, did not, and the pitch equation's Q[2] was "agrees only if the
wheels are uniform thin discs … and I1 = I2"."""

from __future__ import annotations

import numpy as np

from conftest import SEED
from shipped_copies import PUBLISHED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.engine.judgement import SPECIAL_SAMPLES, SPECIAL_SETS
from wheeled_dyn.compare.grid.assumptions import declared, undeclared_cases
from wheeled_dyn.compare.records import DiagnosisKind as K
from wheeled_dyn.compare.records import Verdict
from wheeled_dyn.derivations import load_derivation

GRAVITY = "- m*g*l*sin(theta))/(I_b + m*l**2)"


def test_an_error_near_one_state_is_no_familys_doing(tmp_path):
    text = (PUBLISHED / "wip_planar_divided.toml").read_text()     # model = "wip": shipped
    assert text.count(GRAVITY) == 1
    path = tmp_path / "doc.toml"
    path.write_text(text.replace(
        GRAVITY, "- m*g*l*sin(theta) + m*g*l*exp(-10000*theta**2))/(I_b + m*l**2)"))
    result = ComparisonEngine(samples=1000, param_sets=5, seed=2026).compare(   # the command's
        load_derivation(path))
    assert result.equivalent is False
    wrong = [r for r in result.records if r.verdict != Verdict.AGREES]
    assert [(r.element, r.verdict) for r in wrong] == [("Q[2]", Verdict.DIFFERS)], \
        [r.texts for r in wrong]
    assert K.CONDITION not in wrong[0].kinds, wrong[0].texts


def test_a_familys_grid_has_the_states_of_the_declared_families_grid():
    d = load_derivation(PUBLISHED / "wip_planar_divided.toml")
    engine = ComparisonEngine(samples=1000, param_sets=5, seed=SEED)
    assumed = declared(d)
    control = engine.grids.get(d, (), SPECIAL_SAMPLES, SPECIAL_SETS, assumed)
    cases = undeclared_cases(d, assumed)
    assert len(cases) >= 2
    for case in cases:
        grid = engine.grids.get(d, (case,), SPECIAL_SAMPLES, SPECIAL_SETS, assumed)
        assert np.array_equal(grid.q, control.q) and np.array_equal(grid.nu, control.nu)
        assert grid.sets != control.sets                   # the family's own parameters
