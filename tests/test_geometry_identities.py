"""The truth on drawn geometry against independent computations.

A random parameter set draws the model's lengths (joint origins, wheel and contact radii, the
track, the constants of ``[geometry]``) and updates Pinocchio's model in place
(``models/geometry_apply.py``). The same numbers written into a URDF and read again by
Pinocchio's parser through the builder (``tests/drawn_urdf.py``) must give the same dynamics:
A, n = C q̇ + Q, the rolling constraints and the reduced terms in the model's coordinates; and
MuJoCo, loading that URDF, the same mass matrix and bias forces.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from conftest import SEED
from drawn_urdf import drawn_urdf_text, rebuilt
from wheeled_dyn import CoordinateMap, builtin_coordinate_set, load_model
from wheeled_dyn.compare.grid.samples import (URDF_PROPORTIONS, URDF_STRUCTURE, parameter_sets,
                                              special_cases, uniform_family)
from wheeled_dyn.constraints.rolling import contact_jacobian
from wheeled_dyn.models.registry import model_parameters


#: Agreement of two computations of the same quantity (relative to its size).
EXACT_TOL = 1e-9
#: Parameter sets and states per model.
SETS, STATES = 3, 4
ARM = str(Path(__file__).parent / "data" / "two_link_arm" / "two_link_arm.toml")

MODELS = ["rod_pendulum", ARM, "rolling_disk", "differential", "car4", "sphere_paraboloid",
          "sphere_sphere", "spheroid_plane", "wip_platform", "rolling_coin", "gyroscope"]
FAMILIES = {"generic": (), "structure": (URDF_STRUCTURE,), "uniform": (URDF_PROPORTIONS,)}


def _close(a: np.ndarray, b: np.ndarray, what: str) -> None:
    assert a.shape == b.shape, what
    if not b.size:
        return
    scale = max(1.0, float(np.abs(b).max()))
    assert np.abs(a - b).max() <= EXACT_TOL * scale, (what, np.abs(a - b).max())


def _states(wm, rng):
    for _ in range(STATES):
        q = rng.uniform(-1.0, 1.0, wm.nv)
        yield q, rng.normal(size=wm.nv)


@pytest.mark.parametrize("family", FAMILIES)
@pytest.mark.parametrize("name", MODELS)
def test_drawn_model_equals_the_urdf_written_with_its_numbers(name, family, tmp_path):
    rng = np.random.default_rng(SEED)
    base = load_model(name)
    for k, ps in enumerate(parameter_sets(name, SETS, rng, FAMILIES[family])):
        drawn = ps.model
        assert drawn.dimensions != base.dimensions or not base.dimensions
        other = rebuilt(base, drawn, tmp_path)
        assert other.coordinate_names == drawn.coordinate_names
        for key, value in drawn.geometry.items():
            assert abs(other.geometry[key] - value) <= EXACT_TOL * max(1, abs(value)), key
        mine, theirs = model_parameters(drawn), model_parameters(other)
        for key, value in mine.items():
            assert abs(theirs[key] - value) <= EXACT_TOL * max(1, abs(value)), (k, key)
        d1, d2 = drawn.model.createData(), other.model.createData()
        for q, v in _states(drawn, rng):
            _close(pin.crba(drawn.model, d1, q), pin.crba(other.model, d2, q), "A")
            _close(drawn.nonlinear_effects(d1, q, v), other.nonlinear_effects(d2, q, v), "n")
            if drawn.wheels or drawn.contact is not None or drawn.rolling_wheels:
                J1, dJ1 = contact_jacobian(drawn, q, v)
                J2, dJ2 = contact_jacobian(other, q, v)
                _close(J1, J2, "J_c")
                _close(dJ1 @ v, dJ2 @ v, "dJ_c v")
        cs = builtin_coordinate_set(drawn)
        m1, m2 = CoordinateMap(drawn, cs), CoordinateMap(other, cs)
        for _ in range(STATES):
            qd = rng.uniform(-0.5, 0.5, len(cs.positions))
            nu = rng.normal(size=len(cs.positions))
            t1, t2 = m1.terms(qd, nu), m2.terms(qd, nu)
            for key in ("A", "Q", "h", "B"):
                _close(getattr(t1, key), getattr(t2, key), f"reduced {key}")


@pytest.mark.parametrize("name", ["rolling_coin", "sphere_paraboloid", ARM])
def test_a_uniform_body_keeps_its_shape_with_its_lengths(name):
    r"""Under the uniform family the body's inertia is its URDF inertia scaled by its drawn
    length: the coin's I = m r²/4, m r²/2, the ball's 2/5 m r², the arm's m l²/12."""
    rng = np.random.default_rng(SEED)
    base = load_model(name)
    for ps in parameter_sets(name, SETS, rng, (URDF_PROPORTIONS,)):
        wm, values = ps.model, ps.values
        if name == "rolling_coin":
            m, r = values["M(coin)"], values["radius(coin)"]
            I = wm.model.inertias[wm.joint_id_of_link("coin")].inertia
            assert abs(I[1, 1] - m * r**2 / 2) <= EXACT_TOL * m * r**2
            assert abs(I[0, 0] - m * r**2 / 4) <= EXACT_TOL * m * r**2
            assert abs(values["R"] - r) <= EXACT_TOL
        elif name == "sphere_paraboloid":
            m, r = values["M(ball)"], values["radius(ball)"]
            I = wm.model.inertias[wm.joint_id_of_link("ball")].inertia
            assert np.abs(I - 0.4 * m * r**2 * np.eye(3)).max() <= 1e-6 * m * r**2
            assert values["a"] == values["vertex_radius(ball)"] and values["r"] == r
        else:
            for link, length in (("upper_arm", "l1"), ("forearm", "length(forearm)")):
                m, l = values[f"M({link})"], values[length]
                assert abs(values[f"YY({link})"] - m * l**2 / 3) <= EXACT_TOL * m * l**2
                assert abs(values[f"MX({link})"] - m * l / 2) <= EXACT_TOL * m * l
            assert values["length(upper_arm)"] == values["origin_x(elbow)"] == values["l1"]
    assert base.dimensions == load_model(name).dimensions          # the base is not changed


def test_lengths_drawn_apart_are_independent_and_listed_equal_ones_stay_equal():
    r"""car4's [geometry] lists the wheel radii and the body's height as one length R, the
    track W from four origins: they stay equal; the model's own lengths change."""
    rng = np.random.default_rng(SEED)
    base = load_model("car4")
    radii = set()
    for ps in parameter_sets("car4", 4, rng):
        v = ps.values
        assert {v[f"radius(wheel_{w})"] for w in ("rl", "rr", "fl", "fr")} == {v["R"]}
        assert v["origin_z(theta)"] == v["R"]
        assert v["origin_y(spin_rl)"] == -v["origin_y(spin_rr)"] == v["W"] / 2
        assert v["origin_x(steer_fl)"] == v["a"] and v["origin_x(spin_rr)"] == -v["b"]
        radii.add(v["R"])
    assert len(radii) == 4 and base.geometry["R"] not in radii


def test_a_uniform_family_per_link():
    r"""``uniform(link)``: that link scaled as a whole, the others drawn freely."""
    rng = np.random.default_rng(SEED)
    for ps in parameter_sets(ARM, SETS, rng, (uniform_family(("forearm",)),)):
        v = ps.values
        m, l = v["M(forearm)"], v["length(forearm)"]
        assert abs(v["YY(forearm)"] - m * l**2 / 3) <= EXACT_TOL * m * l**2
        m1, l1 = v["M(upper_arm)"], v["l1"]
        assert abs(v["YY(upper_arm)"] - m1 * l1**2 / 3) > 1e-3 * m1 * l1**2


# -- MuJoCo ---------------------------------------------------------------------------------
#: Models for MuJoCo (every moving link has mass: MuJoCo rejects a massless moving body), with
#: whether their URDF inertias are positive definite (MuJoCo rejects a slender rod's zero
#: moment about its axis, which the uniform family keeps).
MUJOCO_MODELS = {"rod_pendulum": False, ARM: False, "compound_pendulum": True,
                 "differential": True, "flywheel_rod": False}


@pytest.mark.parametrize("name", MUJOCO_MODELS)
def test_mujoco_agrees_on_the_drawn_urdf(name):
    r"""MuJoCo loads the URDF written with a drawn set's numbers: its mass matrix and bias
    forces equal Pinocchio's on the drawn model (joints matched by name)."""
    mujoco = pytest.importorskip("mujoco", reason="MuJoCo is an optional test dependency "
                                                  "(pip install mujoco)")
    rng = np.random.default_rng(SEED)
    base = load_model(name)
    uniform = parameter_sets(name, SETS, rng, (URDF_PROPORTIONS,)) if MUJOCO_MODELS[name] \
        else []
    for ps in uniform + parameter_sets(name, SETS, rng):
        wm = ps.model
        m = mujoco.MjModel.from_xml_string(drawn_urdf_text(base, wm))
        m.opt.gravity[:] = wm.model.gravity.linear
        d = mujoco.MjData(m)
        index = [m.jnt_dofadr[mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, n)]
                 for n in (wm.model.names[j] for j in range(1, wm.model.njoints))]
        data = wm.model.createData()
        for q, v in _states(wm, rng):
            d.qpos[index], d.qvel[index] = q, v
            mujoco.mj_forward(m, d)
            M = np.zeros((m.nv, m.nv))
            mujoco.mj_fullM(m, d, M)
            _close(M[np.ix_(index, index)], pin.crba(wm.model, data, q), "mass matrix")
            _close(d.qfrc_bias[index], wm.nonlinear_effects(data, q, v), "bias forces")


@pytest.mark.parametrize("name", ["free_body", "rolling_coin"])
def test_each_set_has_its_own_model_and_its_values_are_that_model_s(name):
    r"""A model with no length to draw (free_body) and one with: every set is a model of its
    own, its namespace values read from that model, and the registry's model is not changed."""
    rng = np.random.default_rng(SEED)
    before = model_parameters(load_model(name))
    for family in FAMILIES.values():
        sets = parameter_sets(name, SETS, rng, family)
        assert len({id(ps.model.model) for ps in sets}) == len(sets)
        for ps in sets:
            assert ps.values == model_parameters(ps.model)
    assert model_parameters(load_model(name)) == before


def _model_copy(tmp_path, model: str, extra: str, name: str) -> str:
    from wheeled_dyn.models.listing import shipped_model_files
    text = shipped_model_files()[model].path.read_text()
    path = tmp_path / f"{name}.toml"
    path.write_text(text.replace(f'name = "{model}"', f'name = "{name}"') + extra)
    return str(path)


def test_geometry_may_not_change_a_length_the_model_has(tmp_path):
    r"""``[geometry] R = 0.31`` on a model whose R (its wheels' radius) is 0.25: the model
    loaded with R = 0.31 as its named value while Pinocchio's wheels kept 0.25. Saying what R
    is drawn with (``R = "radius(wheel_left)"``-like entries of the shipped models) stays."""
    from wheeled_dyn.errors import ModelError
    with pytest.raises(ModelError, match=r"\(geometry.R\): R is 0.25 in the model"):
        load_model(_model_copy(tmp_path, "wip_platform", "\n[geometry]\nR = 0.31\n", "r031"))


def test_a_constant_drawn_with_lengths_is_not_kept_alone(tmp_path):
    r"""``[draw] fixed = ["R"]`` where ``R = "radius(coin)"``: the closed forms wrote R as a
    number while every parameter set drew the coin's radius (and R with it)."""
    from wheeled_dyn.errors import ModelError
    with pytest.raises(ModelError, match=r"\(draw.fixed\): R = radius"):
        load_model(_model_copy(tmp_path, "rolling_coin", '\n[draw]\nfixed = ["R"]\n', "coinR"))
    wm = load_model(_model_copy(tmp_path, "rolling_coin",
                                '\n[draw]\nfixed = ["radius(coin)"]\n', "coinr"))
    assert not wm.lengths.dimensions["radius(coin)"].drawn


@pytest.mark.parametrize("family", ["uniform(wheel_left)", "uniform(wheel_right)"])
def test_the_drive_wheels_stay_alike_when_one_is_uniform(family):
    r"""``uniform(wheel_left)`` on the platform: the right wheel was drawn a random inertia of
    its own (masses 9.86 and 1.93), so the two wheels the model declares alike were not, and a
    truth written with ``M_wheel_right = M_wheel_left`` did not hold on the sets."""
    case = next(c for c in special_cases("wip_platform") if c.name == family)
    for ps in parameter_sets("wip_platform", 4, np.random.default_rng(SEED), (case,)):
        left, right = (ps.model.model.inertias[ps.model.joint_id_of_link(w.link)]
                       for w in ps.model.wheels)
        assert left.mass == pytest.approx(right.mass, rel=1e-12)
        np.testing.assert_allclose(left.inertia, right.inertia, rtol=1e-12, atol=1e-15)


def _shipped() -> list[str]:
    from wheeled_dyn.models.listing import shipped_model_files
    return sorted(shipped_model_files())


@pytest.mark.parametrize("name", _shipped())
def test_every_shipped_model_draws_finite_parameter_sets(name):
    r"""Every shipped model draws its parameter sets under each family: finite inertias, a
    body of several links composed again from its links. TIAGo's base carries a massless
    base_footprint, as ROS writes it: its zero mass made the composed inertia NaN (Pinocchio:
    "The 3d inertia should be symmetric") and every comparison on it failed."""
    rng = np.random.default_rng(SEED)
    for family in FAMILIES.values():
        for ps in parameter_sets(name, 2, rng, family):
            for inertia in ps.model.model.inertias:
                assert np.all(np.isfinite(inertia.toDynamicParameters())), (name, family)
