"""Joint springs (``[[spring]]`` in a model file): their Q and U in every path.

Identities between independent computations: Q against finite differences of U; the numeric
terms (one state, batched, reduced) against each other and against the closed forms; the
simulated radial oscillation of the particle on its spring against the closed form
r(t) = l0 + a cos(sqrt(k/m) t); energy conservation. Then seed 000's 4.6, transcribed as
printed, agrees, and planted errors in its spring term are named.
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from conftest import SEED
from shipped_copies import rewritten_copy
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.grid.samples import parameter_sets
from wheeled_dyn.constraints import CoordinateMap
from wheeled_dyn.constraints.batch import reduce_batch
from wheeled_dyn.coordinates.builtin import builtin_coordinate_set
from wheeled_dyn.derivations import builtin_derivations, load_derivation
from wheeled_dyn.dynamics.terms import full_terms
from wheeled_dyn.errors import (DerivationError, InputFileError, ModelError, ParameterError,
                                 UnknownNameError)
from wheeled_dyn.models.builder import build_wheeled_model
from wheeled_dyn.models.model_file import read_model_file
from wheeled_dyn.models.registry import load_model, model_parameters
from wheeled_dyn.models.springs import JointSpring
from wheeled_dyn.simulate.reduced import simulate

#: Central-difference step (m or rad) and the agreement of Q with the difference quotient.
FD_STEP, FD_TOL = 1e-6, 1e-6
#: Agreement of two exact computations of the same numbers (relative).
EXACT_TOL = 1e-9
#: Agreement of the simulated radius with the closed form (m) and energy drift (relative).
SIM_TOL, DRIFT_TOL = 1e-6, 1e-7
#: Engine grid.
SAMPLES, PARAM_SETS = 60, 2


def _torsional_pendulum():
    r"""The rod pendulum with a torsional spring at its hinge (revolute joint)."""
    spec = load_model("rod_pendulum").spec
    return build_wheeled_model(replace(spec, springs=(JointSpring("hinge", "theta", 3.0, 0.2),)))


@pytest.fixture(scope="module", params=["spring_table", "torsion"])
def sprung(request):
    return load_model("spring_table") if request.param == "spring_table" else _torsional_pendulum()


def test_Q_is_the_gradient_of_U(sprung):
    rng = np.random.default_rng(SEED)
    data = sprung.model.createData()
    for _ in range(5):
        q = rng.uniform(0.2, 1.5, sprung.nv)
        Q = full_terms(sprung, q, np.zeros(sprung.nv)).Q
        fd = np.array([(sprung.potential_energy(data, q + FD_STEP * e)
                        - sprung.potential_energy(data, q - FD_STEP * e)) / (2 * FD_STEP)
                       for e in np.eye(sprung.nv)])
        np.testing.assert_allclose(Q, fd, atol=FD_TOL * (1 + np.abs(Q).max()))


def test_spring_term_is_k_times_stretch():
    wm = load_model("spring_table")
    spring = wm.springs[0]
    q = np.array([0.3, 0.9])
    Q = full_terms(wm, q, np.zeros(2)).Q
    bare = full_terms(replace(wm, springs=()), q, np.zeros(2)).Q
    assert Q[spring.v_index] - bare[spring.v_index] == pytest.approx(
        spring.stiffness * (q[spring.q_index] - spring.rest), rel=EXACT_TOL)
    params = model_parameters(wm)
    assert (params["k_radial"], params["rest_radial"]) == (40.0, 0.5)


def test_one_state_batch_and_reduced_agree(sprung):
    rng = np.random.default_rng(SEED)
    cmap = CoordinateMap(sprung, builtin_coordinate_set(sprung, "full"))
    q = rng.uniform(0.2, 1.5, (6, sprung.nv))
    nu = rng.normal(size=(6, sprung.nv))
    batch = reduce_batch(cmap, q, nu, q)
    for i in range(len(q)):
        one = full_terms(sprung, q[i], nu[i])
        np.testing.assert_allclose(batch.Q[i], one.Q, rtol=EXACT_TOL, atol=EXACT_TOL)
        A_nu, force, _, _ = cmap.dynamics_at(q[i], nu[i], q[i])
        np.testing.assert_allclose(force, one.h + one.Q, rtol=EXACT_TOL, atol=EXACT_TOL)


def test_closed_forms_include_the_spring(sprung):
    from wheeled_dyn.symbolic.tree_wheeled import tree_wheeled
    from wheeled_dyn.symbolic.wheeled import symbolic_parts
    cs = builtin_coordinate_set(sprung, "full")
    _, numbers = symbolic_parts(sprung, cs, "numbers", simplify=False)
    _, symbols = symbolic_parts(sprung, cs, "standard", simplify=False)
    name = sprung.springs[0].spec.name
    assert sp.Symbol(f"k_{name}", real=True) in symbols.Q.free_symbols
    tree = tree_wheeled(sprung, cs, "standard")            # the intermediate-variable form
    assert sp.Symbol(f"k_{name}", real=True) in set().union(
        *(tree.expand(e, simplify=False).free_symbols for e in tree.Q))
    fn = sp.lambdify([numbers.q], numbers.Q)
    rng = np.random.default_rng(SEED)
    for _ in range(4):
        q = rng.uniform(0.2, 1.5, sprung.nv)
        np.testing.assert_allclose(np.array(fn(q), dtype=float).ravel(),
                                   full_terms(sprung, q, np.zeros(sprung.nv)).Q,
                                   rtol=EXACT_TOL, atol=EXACT_TOL)


def test_radial_oscillation_matches_the_closed_form():
    r"""With no turning, the particle oscillates about the free length at
    :math:`\omega = \sqrt{k/m}`: :math:`r(t) = l_0 + a\cos\omega t`."""
    wm = load_model("spring_table")
    k, rest, m = wm.springs[0].stiffness, wm.springs[0].rest, model_parameters(wm)["M(ball)"]
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "full"))
    a = 0.2
    traj = simulate(cmap, np.array([0.0, rest + a]), np.zeros(2), 1.0, rate=200.0,
                    rtol=1e-11, atol=1e-12)
    r = traj.q[:, wm.index("r")]
    expected = rest + a * np.cos(np.sqrt(k / m) * traj.t)
    assert np.abs(r - expected).max() < SIM_TOL


def test_energy_is_conserved_with_the_spring(sprung):
    cmap = CoordinateMap(sprung, builtin_coordinate_set(sprung, "full"))
    q0 = np.full(sprung.nv, 0.7)
    traj = simulate(cmap, q0, np.full(sprung.nv, 0.8), 1.0, rate=200.0, rtol=1e-11, atol=1e-12)
    assert traj.relative_energy_drift() < DRIFT_TOL


def test_random_parameter_sets_scale_the_stiffness():
    sets = parameter_sets("spring_table", 4, np.random.default_rng(SEED))
    stiffness = [ps.model.springs[0].stiffness for ps in sets]
    assert len(set(stiffness)) == 4 and all(20.0 <= k <= 80.0 for k in stiffness)
    assert all(ps.values["k_radial"] == ps.model.springs[0].stiffness for ps in sets)


def _seed_file(stem: str = "p4_6_spring_particle") -> Path:
    return next(p for p in builtin_derivations("seed000") if p.stem == stem)


def _rewritten(tmp_path: Path, stem: str, printed: str, replacement: str) -> Path:
    return rewritten_copy(_seed_file(stem), tmp_path, (printed, replacement))


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)


def test_seed000_4_6_agrees(engine):
    r"""Every element agrees (the boxed theta equation is the printed one divided by m r^2,
    a factor the comparison finds: tests/test_row_functions.py)."""
    result = engine.compare(load_derivation(_seed_file()))
    assert result.records and all(r.verdict == "agrees" for r in result.records), \
        [(r.element, r.verdict, r.texts) for r in result.records if r.verdict != "agrees"]


@pytest.mark.parametrize("printed, planted, named", [
    ("K*(r - l0) = 0", "K*(r + l0) = 0", "Q[2]"),
    ("K*(r - l0) = 0", "K*(l0 - r) = 0", "Q[2]"),
    ("K*(r - l0) = 0", "K/2*(r - l0) = 0", "Q[2]"),
    ("1/2*K*(r - l0)**2", "K*(r - l0)**2", "V value"),
])
def test_planted_spring_errors_are_named(engine, tmp_path, printed, planted, named):
    result = engine.compare(load_derivation(_rewritten(tmp_path, "p4_6_spring_particle",
                                                       printed, planted)))
    differ = {r.element for r in result.records if r.verdict == "differs"}
    assert any(named in e for e in differ), differ
    assert all(("Q[" in e or "V" in e) for e in differ), differ


def _verdicts(engine, path: Path) -> dict[str, tuple[str, tuple[str, ...]]]:
    result = engine.compare(load_derivation(path))
    return {r.element: (r.verdict, r.texts) for r in result.records}


def test_seed000_2_19_small_motions(engine):
    r"""(1C), (3C) and the first-order form's x'' agree; the first-order form's theta'' has
    K H/I_g where (3C) gives K H/(2 I_g); the matrix form's rows are not the equations."""
    verdicts = _verdicts(engine, _seed_file("p2_19_spring_block"))
    by_name = {e.rsplit(" equations ", 1)[-1]: v for e, v in verdicts.items()}
    assert by_name["(1C)"][0] == by_name["(3C)"][0] == by_name["x4' = x''"][0] == "agrees"
    verdict, diagnoses = by_name["x2' = theta''"]
    assert verdict == "differs" and diagnoses == ("term x: factor: the document is 2 × the truth",)
    assert by_name["row 1"][0] == by_name["row 2"][0] == "differs"


def test_seed000_2_19_balances_with_the_springs_laws_agree(engine):
    r"""(1A)-(3A): the pin's spring force and the torsional spring's moment are given by their
    laws, the normal force N is unknown; all three balances agree."""
    verdicts = _verdicts(engine, _seed_file("p2_19_spring_block"))
    balances = {e: v for e, v in verdicts.items() if e.startswith("(1A)-(3A)")}
    assert len(balances) == 3 and all(v[0] == "agrees" for v in balances.values()), balances


@pytest.mark.parametrize("printed, planted, named", [
    ("-K*l*theta + N*H/2*sin(theta)", "K*l*theta + N*H/2*sin(theta)",
     "sign: the term K*l*theta has the wrong sign"),               # the spring's moment
    ("- K*(x_in - x)*H/2*cos(theta) = I_cg", "- K*(x_in - x)*H/2*sin(theta) = I_cg",
     "swap: sin(theta) where cos(theta) fits"),
    ("-K*l*theta + N*H/2*sin(theta)", "-K*l*theta + N*H*sin(theta)", "term N"),   # arm of N
])
def test_planted_errors_in_a_balance_with_laws_are_named(engine, tmp_path, printed, planted,
                                                         named):
    path = _rewritten(tmp_path, "p2_19_spring_block", printed, planted)
    verdict, diagnoses = _verdicts(engine, path)["(1A)-(3A) newton-euler (3A)"]
    assert verdict == "differs" and any(named in x for x in diagnoses), diagnoses


def test_a_law_with_an_acceleration_is_refused(engine, tmp_path):
    path = _rewritten(tmp_path, "p2_19_spring_block", 'law = "K*(x_in - x)"',
                      'law = "K*(x_in - x) + m*ddx"')
    with pytest.raises(DerivationError, match="not of the accelerations"):
        engine.compare(load_derivation(path))


def test_a_law_named_as_a_parameter_is_refused(engine, tmp_path):
    path = _rewritten(tmp_path, "p2_19_spring_block", 'F_s = { point = "origin"',
                      'K = { point = "origin"')
    with pytest.raises(DerivationError, match="not by one of the file's parameters"):
        engine.compare(load_derivation(path))


def test_seed000_2_19_rewritten_rows_agree(engine, tmp_path):
    r"""The first-order form's theta'' row, corrected and written as (3C) solved otherwise,
    agrees: the relation holds on the true small motions whatever its arrangement."""
    path = _rewritten(tmp_path, "p2_19_spring_block",
                      '"ddtheta = -(K_T/I_g - m*g/I_g*H/2)*theta + K*H/I_g*x",',
                      '"2*I_g*ddtheta + (2*K_T - m*g*H)*theta = K*H*x",')
    verdicts = {e.rsplit(" equations ", 1)[-1]: v for e, v in _verdicts(engine, path).items()}
    assert verdicts["x2' = theta''"][0] == "agrees", verdicts["x2' = theta''"]


def _model_file(tmp_path, spring: str) -> Path:
    urdf = Path(load_model("spring_table").spec.urdf)
    path = tmp_path / "m.toml"
    path.write_text(f'name = "m"\n[urdf]\npath = "{urdf}"\n[base]\ntype = "fixed"\n'
                    f"[[spring]]\n{spring}\n")
    return path


@pytest.mark.parametrize("spring, error, fragment", [
    ('name = "s"\njoint = "r"\nstiffness = -1.0', InputFileError, "positive stiffness"),
    ('name = "s"\njoint = "r"', InputFileError, "give its stiffness"),
    ('name = "s"\njoint = "r"\nstiffness = 1.0\ndamping = 2.0', InputFileError, "unknown key"),
    ('name = "s"\njoint = "nope"\nstiffness = 1.0', UnknownNameError, "nope"),
])
def test_bad_springs_get_one_clear_error(tmp_path, spring, error, fragment):
    path = _model_file(tmp_path, spring)
    with pytest.raises(error) as info:
        build_wheeled_model(read_model_file(path).spec())
    assert fragment in str(info.value)


def test_a_second_spring_on_one_joint_is_refused():
    spec = load_model("spring_table").spec
    two = (JointSpring("a", "r", 1.0), JointSpring("b", "r", 2.0))
    with pytest.raises(ModelError, match="second spring"):
        build_wheeled_model(replace(spec, springs=two))
    with pytest.raises(ParameterError):
        JointSpring("c", "r", float("nan"))
