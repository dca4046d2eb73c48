"""Models without wheels: fixed and free bases, motors on declared joints, built-in coordinate
sets, the benchmark URDFs' stated numbers, and the errors of a spec that does not fit."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from conftest import N_STATES, SEED
from wheeled_dyn import CoordinateMap, builtin_coordinate_set, coordinate_set_names, load_model
from wheeled_dyn.cli.main import main
from wheeled_dyn.errors import ModelError, ParameterError, UnknownNameError
from wheeled_dyn.models import ModelSpec, build_wheeled_model
from wheeled_dyn.models.benchmarks import BENCHMARKS
from wheeled_dyn.models.contact import SphereContact
from wheeled_dyn.models.registry import MODELS, model_parameters
from wheeled_dyn.paths import urdf_dir

#: Tolerance of identities exact to rounding.
EXACT_TOL = 1e-9
#: Slack on inertia values written with 4-6 significant digits in the URDFs.
VALUE_TOL = 1e-4

NAMES = [name for name, _, _ in BENCHMARKS]


def test_every_benchmark_is_listed(capsys):
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    for name in NAMES:
        assert name in MODELS
        line = next(l for l in out.splitlines() if l.split()[0] == name)
        assert MODELS[name].summary in line


@pytest.mark.parametrize("name", NAMES)
def test_builds_with_one_coordinate_per_joint(name):
    wm = load_model(name)
    assert wm.wheels == ()
    assert wm.model.nq == wm.model.nv == len(wm.coordinate_names)
    assert wm.input_matrix().shape == (wm.nv, len(wm.input_names))
    sets = coordinate_set_names(wm)
    assert "full" in sets
    full = builtin_coordinate_set(wm, "full")
    assert full.kind == "holonomic" and full.positions == wm.coordinate_names
    assert full.rolling == ("multipliers" if wm.contact is not None else "none")
    if wm.base == "free":
        assert {"body_rates", "world_rates"} <= set(sets)
    params = model_parameters(wm)
    assert params["g"] == pytest.approx(9.81)
    assert all(params[k] == v for k, v in wm.geometry.items())


def test_motors_on_declared_joints():
    wm = load_model("differential")
    B = wm.input_matrix()
    assert wm.input_names == ("tau_1", "tau_2", "tau_3")
    for k, joint in enumerate(("theta1", "theta2", "pinion")):
        assert B[:, k].tolist() == [1.0 if c == joint else 0.0 for c in wm.coordinate_names]
    assert load_model("rod_pendulum").input_matrix().shape == (1, 0)
    assert load_model("flywheel_rod").input_names == ("tau_phi",)


@pytest.mark.parametrize("name", ["free_body", "sphere_plane"])
def test_free_base_angular_velocity_sets(name):
    r"""body_rates are Pinocchio's angular velocity of the root link in its own frame,
    world_rates in world axes, at random states."""
    rng = np.random.default_rng(SEED)
    wm = load_model(name)
    link = "block" if name == "free_body" else "ball"
    fid = wm.model.getFrameId(link)
    body = CoordinateMap(wm, builtin_coordinate_set(wm, "body_rates"))
    world = CoordinateMap(wm, builtin_coordinate_set(wm, "world_rates"))
    data = wm.model.createData()
    for _ in range(N_STATES):
        q = rng.uniform(-1.2, 1.2, wm.nv)
        v = rng.normal(size=wm.nv)
        pin.forwardKinematics(wm.model, data, q, v)
        local = pin.getFrameVelocity(wm.model, data, fid, pin.LOCAL).angular
        aligned = pin.getFrameVelocity(wm.model, data, fid, pin.LOCAL_WORLD_ALIGNED).angular
        k = body.n - 3
        assert np.abs(body._T(q, body._p) @ v - np.r_[v[:3], local][-body.n:]).max() < EXACT_TOL
        assert np.abs((world._T(q, world._p) @ v)[k:] - aligned).max() < EXACT_TOL


@pytest.mark.parametrize("name", ["differential", "rolling_disk", "free_body", "sphere_sphere"])
def test_batch_equals_single(name):
    rng = np.random.default_rng(SEED)
    wm = load_model(name)
    for coords in coordinate_set_names(wm):
        cmap = CoordinateMap(wm, builtin_coordinate_set(wm, coords))
        q, nu = rng.uniform(-1, 1, (N_STATES, cmap.n)), rng.normal(size=(N_STATES, cmap.n))
        batch = cmap.terms_batch(q, nu)
        for i in range(N_STATES):
            one = cmap.terms(q[i], nu[i])
            for key in ("A", "C", "Q", "B", "h"):
                diff = np.abs(getattr(batch, key)[i] - getattr(one, key))
                assert np.max(diff, initial=0.0) < EXACT_TOL, (coords, key)


# central inertia (about the centre of mass, link axes) the URDF comments state, from the
# formulas they give
def _stated():
    rod = 1.5 * 1.0**2 / 12
    return {
        ("rod_pendulum", "rod"): (1.5, [0, 0, -0.5], [rod, rod, 0.0]),
        ("compound_pendulum", "body"): (1.555, [0, 0, -0.3],
                                        [1.555 * (0.8**2 + 0.012**2) / 12,
                                         1.555 * (0.8**2 + 0.06**2) / 12,
                                         1.555 * (0.06**2 + 0.012**2) / 12]),
        ("flywheel_rod", "rod"): (0.6, [0, 0, -0.25], [0.6 * 0.25 / 12, 0.6 * 0.25 / 12, 0.0]),
        ("free_body", "block"): (1.0, [0, 0, 0], [(0.03**2 + 0.23**2) / 12,
                                                  (0.15**2 + 0.23**2) / 12,
                                                  (0.15**2 + 0.03**2) / 12]),
        ("sphere_plane", "ball"): (7.0, [0, 0, 0], [0.4 * 7.0 * 0.109**2] * 3),
        ("gyroscope", "rotor"): (1.5, [0, 0.12, 0], [1.5 * 0.08**2 / 4 + 1.5 * 0.02**2 / 12,
                                                     1.5 * 0.08**2 / 2,
                                                     1.5 * 0.08**2 / 4 + 1.5 * 0.02**2 / 12]),
    }


@pytest.mark.parametrize("key", list(_stated()))
def test_urdf_numbers_are_the_stated_ones(key):
    name, link = key
    mass, com, moments = _stated()[key]
    wm = load_model(name)
    inertia = wm.model.inertias[wm.joint_id_of_link(link)]
    assert inertia.mass == pytest.approx(mass)
    assert np.allclose(inertia.lever, com, atol=1e-12)
    assert np.allclose(np.diag(inertia.inertia), moments, rtol=VALUE_TOL, atol=1e-12)


def test_the_point_mass_is_part_of_the_rolling_disk():
    params = model_parameters(load_model("rolling_disk"))
    assert params["M(disk)"] == pytest.approx(5.0)
    assert params["MZ(disk)"] == pytest.approx(-0.2)
    assert params["YY(disk)"] == pytest.approx(0.18 + 0.04 + 0.00016)
    assert params["R"] == 0.30


def _spec(**changes):
    base = dict(name="bad", urdf=urdf_dir() / "rod_pendulum.urdf", base="fixed")
    return ModelSpec(**{**base, **changes})


def test_spec_errors():
    with pytest.raises(ModelError, match="base 'wobbly'"):
        build_wheeled_model(_spec(base="wobbly"))
    with pytest.raises(ModelError, match="wheels need base 'planar'"):
        build_wheeled_model(_spec(wheels=("rod", "rod")))
    with pytest.raises(ModelError, match="needs its body"):
        build_wheeled_model(_spec(base="planar"))
    with pytest.raises(UnknownNameError, match="unknown joint 'elbow'"):
        build_wheeled_model(_spec(actuated=("elbow",)))
    with pytest.raises(ModelError, match="2 input names for 1 actuated"):
        build_wheeled_model(_spec(actuated=("theta",), inputs=("a", "b")))
    with pytest.raises(ModelError, match="rolling ball needs base"):
        build_wheeled_model(_spec(base="planar", contact=SphereContact("rod", 0.1)))
    with pytest.raises(ParameterError):
        SphereContact("ball", -0.1)
    with pytest.raises(ParameterError):
        SphereContact("ball", 0.1, "sphere")           # no fixed-sphere radius
    with pytest.raises(ParameterError):
        SphereContact("ball", 0.1, "cone")
