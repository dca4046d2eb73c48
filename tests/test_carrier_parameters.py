r"""A document names a rigid body by the link that carries it (``M(base_link)``,
``CX(base_link)``, ``IZZ(base_link)``, about that link's frame); the closed forms name a body
whose carrying link is not at its joint frame after the joint (``M_psi``: a ROS ``base_link``
sits above the ``base_footprint`` a planar base moves). The link's parameters are the body's
moved to its frame (:func:`~wheeled_dyn.symbolic.parameter_modes.carrier_parameters`), so the
corrected equations and residuals of a differential-drive robot read in the document's own
symbols — before, ``(2*I_w/R**2 + M_psi + 2*m_w)*dv - MY_psi*domega - MX_psi*omega**2`` and a
residual ``2*I_w/R**2 - M_base_link + M_psi`` for one dropped term.

The moved parameters are checked against Pinocchio's own change of frame
(``frame.placement.actInv`` of the body's inertia, :mod:`wheeled_dyn.models.link_parameters`)
on every model that has such a body, rotated carriers among them (the platform of
``wip_platform``, Upkie's rotors)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.models.link_parameters import parameter_values
from wheeled_dyn.models.registry import load_model
from wheeled_dyn.symbolic.parameter_modes import carrier_parameters, standard_names
from wheeled_dyn.symbolic.parameters import PARAMETER_NAMES, numeric_parameters

DATA = Path(__file__).parent / "data"
#: Agreement of the moved parameters with Pinocchio's (Upkie's rotations are not exact).
MOVED_TOL = 1e-9
MODELS = ["tiago_base", "wip_platform", str(DATA / "published" / "dd_robot.toml"),
          str(DATA / "upkie_crouch" / "upkie_crouch.toml")]


@pytest.mark.parametrize("model", MODELS)
def test_moved_parameters_are_pinocchios(model):
    wm = load_model(model)
    carried = carrier_parameters(wm)
    assert carried, "a model with a carrying link away from its joint frame"
    names = standard_names(wm)
    numbers = {sp.Symbol(f"{k}_{names[j]}", real=True): x
               for j, pi in numeric_parameters(wm.model).items()
               for k, x in zip(PARAMETER_NAMES, pi)}
    expected = parameter_values(wm)
    for link, moved in carried.items():
        for key, expr in moved.items():
            value = float(expr.xreplace(numbers))
            scale = max(abs(expected[f"M({link})"]), 1.0)
            assert abs(value - expected[f"{key}({link})"]) <= MOVED_TOL * scale, (link, key)


def test_a_robots_corrected_equation_is_in_the_documents_symbols(tmp_path):
    text = (DATA / "published" / "dd_swivel_vw.toml").read_text()
    text = text.replace('model = "dd_swivel.toml"', 'model = "dd_robot.toml"')
    planted = text.replace("(m + 2*I_w/R**2)*dv", "m*dv")
    assert planted != text
    for own in ("dd_robot.toml", "dd_robot.urdf"):
        (tmp_path / own).write_text((DATA / "published" / own).read_text())
    (tmp_path / "doc.toml").write_text(planted)
    result = ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(
        load_derivation(tmp_path / "doc.toml"))
    a11 = next(r for r in result.records if r.element == "A[1,1]")
    assert sp.simplify(sp.sympify(a11.residual) - sp.sympify("2*I_w/R**2")) == 0
    corrected = " ".join(e.corrected for e in result.equations)
    assert "psi" not in corrected and "base_link" not in corrected, corrected
    assert "d*m_c*omega**2" in corrected
    np.testing.assert_equal(result.equivalent, False)
