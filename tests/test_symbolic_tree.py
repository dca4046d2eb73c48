"""Closed forms with intermediate variables (symbolic.tree) against Pinocchio on robots of
example-robot-data (UR5, TIAGo with its arm) at random states, the rolling reduction of TIAGo
against the numeric reduction, the tree form against the expanded Lagrange form on the WIP, and
exact geometry (no float coefficients from URDF angles)."""

from __future__ import annotations

import json

import numpy as np
import pinocchio as pin
import pytest
import sympy as sp

import wheeled_dyn as wd
from wheeled_dyn.cli.main import main
from wheeled_dyn.coordinates import builtin_coordinate_set
from wheeled_dyn.dynamics import christoffel_tensor
from wheeled_dyn.models.registry import model_parameters
from wheeled_dyn.paths import example_robot_data_share
from wheeled_dyn.symbolic.exact import exact_length, exact_rotation
from wheeled_dyn.symbolic.parameters import named_parameters
from wheeled_dyn.symbolic.tree import tree_dynamics
from wheeled_dyn.symbolic.tree_code import compile_assignments, compile_terms, operation_count
from wheeled_dyn.symbolic.tree_wheeled import tree_wheeled

#: Largest difference from Pinocchio, relative to the largest entry of the term (or 1).
TOLERANCE = 1e-9
SEED = 20261124
STATES = 5

SHARE = example_robot_data_share()
needs_erd = pytest.mark.skipif(SHARE is None, reason="example-robot-data is not installed")


def _close(a, b, what):
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    scale = max(1.0, float(np.abs(b).max()))
    err = float(np.abs(a - b).max())
    assert err <= TOLERANCE * scale, f"{what}: max difference {err:.3e} (scale {scale:.3g})"


def _check_tree(model: pin.Model, names=None):
    td = tree_dynamics(model, coordinate_names=names)
    values = named_parameters(model)
    p = [values[str(s)] for s in td.parameters]
    f = compile_terms(td)
    rng = np.random.default_rng(SEED)
    data = model.createData()
    for _ in range(STATES):
        q = rng.uniform(-np.pi, np.pi, model.nv)
        v = rng.uniform(-1.0, 1.0, model.nv)
        A, Q, c, C = f(q, v, p)
        M = pin.crba(model, data, q)
        _close(A, np.triu(M) + np.triu(M, 1).T, "A")
        _close(Q, pin.computeGeneralizedGravity(model, data, q), "Q")
        _close(C, pin.computeCoriolisMatrix(model, data, q, v), "C")
        _close(c, christoffel_tensor(model, q), "Christoffel symbols")
    return td


@needs_erd
def test_ur5_closed_forms_match_pinocchio():
    model = pin.buildModelFromUrdf(
        str(SHARE / "example-robot-data/robots/ur_description/urdf/ur5_robot.urdf"))
    td = _check_tree(model)
    assert not any(e.has(sp.Float) for _, e in td.assignments), "float left in UR5 geometry"


@pytest.fixture(scope="module")
def tiago():
    if SHARE is None:
        pytest.skip("example-robot-data is not installed")
    return wd.load_model("tiago")


def test_tiago_full_tree_matches_pinocchio(tiago):
    td = _check_tree(tiago.model, tiago.coordinate_names)
    assert td.n == 15
    assert not any(e.has(sp.Float) for _, e in td.assignments), "float left in TIAGo geometry"
    ops = operation_count(td.assignments)
    assert ops.assignments == len(td.assignments) and ops.multiplications > 0


def _reduced_check(wm, cs, red, parameter_values):
    m = len(red.nu)
    f = compile_assignments(red.assignments, red.q, red.nu, red.parameters,
                            [("A", list(red.A)), ("C", list(red.C)), ("Q", list(red.Q)),
                             ("h", list(red.h))])
    p = [parameter_values[str(s)] for s in red.parameters]
    cmap = wd.CoordinateMap(wm, cs)
    rng = np.random.default_rng(SEED)
    for _ in range(STATES):
        qd = rng.uniform(-np.pi, np.pi, len(red.q))
        nu = rng.uniform(-1.0, 1.0, m)
        A, C, Q, h = (np.array(x, dtype=float) for x in f(qd, nu, p))
        q, v = cmap.state_from(dict(zip(cs.positions, qd)) | dict(zip(cs.velocities, nu)))
        t = cmap.terms(q, v)
        _close(A.reshape(m, m), t.A, "reduced A")
        _close(C.reshape(m, m), t.C, "reduced C")
        _close(Q, t.Q, "reduced Q")
        _close(h, t.h, "reduced h")


def test_tiago_rolling_reduction_matches_numeric(tiago):
    cs = builtin_coordinate_set(tiago, None)
    red = tree_wheeled(tiago, cs, "standard")
    values = {k.replace("(", "_").rstrip(")"): v for k, v in model_parameters(tiago).items()}
    values |= named_parameters(tiago.model)      # joint bodies named by their joints (M_psi)
    _reduced_check(tiago, cs, red, values)
    # one element expanded on demand: the heading-speed mass is the total mass plus wheel terms
    a11 = red.expand(red.A[0, 0])
    assert not a11.has(sp.Float) and a11.has(sp.Symbol("M_arm_7_link", real=True))


def test_tree_form_matches_expanded_form_on_the_wip():
    wm = wd.load_model("wip")
    cs = builtin_coordinate_set(wm, "seed001")
    red = tree_wheeled(wm, cs, "physical")
    values = {k: float(v) for k, v in wd.WipParameters().as_dict().items()}
    _reduced_check(wm, cs, red, values)
    from wheeled_dyn.symbolic.wheeled import wheeled_symbolic
    full = wheeled_symbolic(wm, cs, "physical")
    for i in range(len(red.nu)):
        for j in range(len(red.nu)):
            diff = sp.simplify(red.expand(red.A[i, j], simplify=False) - sp.expand(full.A[i, j]))
            assert diff == 0, f"A[{i + 1},{j + 1}]: tree and Lagrange forms differ by {diff}"


def test_exact_geometry():
    R = pin.rpy.rpyToMatrix(1.57079632679, 0.0, -1.57079632679)   # as URDFs write pi/2
    E = exact_rotation(R)
    assert not E.has(sp.Float), E
    assert np.abs(np.array(E, dtype=float) - R).max() < 1e-8
    assert set(E) <= {0, 1, -1}
    # 2.7e-8 from pi/2 is beyond the tolerance: kept as it is, not silently rounded
    assert exact_rotation(pin.rpy.rpyToMatrix(0.0, 0.0, 1.5707963)).has(sp.Float)
    assert exact_length(0.2022) == sp.Rational(1011, 5000)
    assert exact_length(0.1 + 1e-12) == sp.Rational(1, 10)
    assert exact_length(0.123456789123).is_Float          # not simple within the tolerance
    R30 = pin.rpy.rpyToMatrix(0.0, 0.0, np.pi / 6 + 1e-11)
    assert exact_rotation(R30)[0, 0] == sp.sqrt(3) / 2


@needs_erd
def test_tiago_base_closed_forms_have_no_float_coefficients():
    from wheeled_dyn.symbolic.wheeled import wheeled_symbolic
    wm = wd.load_model("tiago_base")
    red = wheeled_symbolic(wm, builtin_coordinate_set(wm, None), "standard")
    for key, M in red.terms().items():
        assert not any(sp.sympify(e).has(sp.Float) for e in M), f"float in {key}"


@needs_erd
def test_symbolic_command_intermediate_form(capsys):
    assert main(["symbolic", "tiago_base", "--form", "intermediate", "--json",
                 "--expand", "A[1,1],Q[2]"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["form"] == "intermediate" and out["assignments"]
    assert out["operations"]["multiplications"] > 0
    assert set(out["expanded"]) == {"A[1,1]", "Q[2]"}
    assert main(["symbolic", "tiago_base", "--form", "intermediate", "--expand", "A[9,9]"]) == 2


def test_the_lengths_column_is_what_the_printed_forms_write(capsys):
    r"""``symbolic wip_platform --form intermediate --parameters standard``: the tree's forms
    write the wheels' radius and half track as ``R`` and ``L`` (they are free symbols of A),
    and the lengths table says so; it printed no symbol for any wheeled model."""
    import sympy as sp
    assert main(["symbolic", "wip_platform", "--form", "intermediate", "--parameters",
                 "standard", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    symbols = {name: entry["symbol"] for name, entry in out["lengths"].items()}
    assert symbols["R"] == "R" and symbols["L"] == "L"
    assert symbols["radius(wheel_left)"] == "R"
    written = set().union(*(sp.sympify(e).free_symbols for _, e in out["assignments"]))
    assert {"R", "L"} <= {str(s) for s in written}
