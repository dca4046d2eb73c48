"""The derivation files of seed 000 and seed 002: they load against their models, they agree
with the truth at the URDFs' own parameters except where the documents are wrong, and the
comparison engine says where they are wrong.

At the URDFs' parameters the documents' idealisations (uniform rod, point mass, uniform
sphere) hold, so a correct equation must agree there exactly; that check does not depend on
the engine's random parameter families."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.grid.grid import derivation_coordinate_set
from wheeled_dyn.compare.sides.document import model_value
from wheeled_dyn.compare.readings.row_functions import with_row_functions
from wheeled_dyn.compare.grid.samples import ParameterSet, namespace_values
from wheeled_dyn.constraints import CoordinateMap
from wheeled_dyn.derivations import builtin_derivations, load_derivation
from wheeled_dyn.models.registry import load_model, model_parameters

#: Relative agreement of a document element with the truth at the URDF's parameters.
AGREE_TOL = 1e-9
#: A document element that is wrong differs from the truth by at least this (relative).
DIFFER_MIN = 1e-3
#: States per file.
N_STATES = 12
#: Engine grid (small: verdicts, not statistics).
SAMPLES, PARAM_SETS = 60, 2

SEED000 = {"p2_2b_eccentric_disk", "p2_6_compound_pendulum", "p4_4_rod_pendulum", "p4_8_rolling_disk",
           "p4_6_spring_particle",
           "p4_9_pendulum_support", "p4_12_bounce_pitch", "p4_13_differential",
           "p4_13_differential_theta1", "p4_17_flywheel_rod", "p7_2_euler_equations"}
SEED002 = {"s3_3_sphere_plane", "s3_12_sphere_sphere"}
#: Seed 000 files of steps only (kinematics, constraints, balances; no equations of motion):
#: tests/test_seed000_car_constraints.py, tests/test_newton_euler_steps.py,
#: tests/test_springs.py (seed 002's
#: s3_8_paraboloid: tests/test_ball_surface.py).
STEPS_ONLY = {"p1_11_car_constraints", "p1_15_particle", "p2_7_vehicle", "p2_13_vehicle",
              "p2_19_spring_block", "p5_1_body_axes", "p7_7_gyroscope"}

#: Elements each document gets wrong (1-based labels); every other element agrees.
WRONG = {
    "p4_8_rolling_disk": {"A[1,1]"},                      # -m r^2 for +m r^2
    "p4_12_bounce_pitch": {"A[1,2]", "A[2,1]",            # linearised: M d for M d cos(theta)
                           "Q[1]", "Q[2]"},               # springs only, no gravity
    "p4_13_differential_theta1": {"A[1,1]", "A[1,2]", "A[2,1]", "A[2,2]"},   # G/4 for G^2/4
}
#: Elements of WRONG a file's [assumes] table makes right (4.12 (c): linearised about
#: theta = 0, potential measured from the static equilibrium, as the document says).
ASSUMED = {"p4_12_bounce_pitch": {"A[1,2]", "A[2,1]", "Q[1]", "Q[2]"}}
#: Equations a document printed divided by a function of the state (its boxed forms), as the
#: engine finds them (tests/test_row_functions.py): compared after multiplying back.
DIVIDED = {"p4_6_spring_particle": ("1/(m*r**2)", None)}
#: Position ranges where a document's coordinates are valid (default [-pi, pi]).
RANGES = {"s3_3_sphere_plane": [(0.2, np.pi - 0.2), (-np.pi, np.pi), (-np.pi, np.pi)],
          "s3_12_sphere_sphere": [(0.2, np.pi - 0.2), (-np.pi, np.pi), (-np.pi, np.pi)]}


def _paths():
    return {p.stem: p for group in ("seed000", "seed002") for p in builtin_derivations(group)}


def test_shipped_files():
    paths = _paths()
    assert {p.stem for p in builtin_derivations("seed000")} == SEED000 | STEPS_ONLY
    assert {p.stem for p in builtin_derivations("seed002")} == SEED002 | {"s3_8_paraboloid"}
    assert set(WRONG) <= set(paths)


@pytest.mark.parametrize("stem", sorted(SEED000 | SEED002 | STEPS_ONLY))
def test_loads_against_its_model(stem):
    path = _paths()[stem]
    model = load_derivation(path).model
    params = model_parameters(load_model(model))
    names = {k for k in params if "(" not in k}
    links = {k.split("(")[1].rstrip(")") for k in params if "(" in k}
    d = load_derivation(path, parameters=names, links=links)
    assert d.n >= 1 and d.title


def _elements(d, wm, rng, ranges):
    r"""Per element label of A, Q, h: the largest |document - truth| / (1 + |truth row|) over
    states (B, an input map, is left to the engine's test)."""
    ps = ParameterSet(wm, namespace_values(wm, None))
    cmap = CoordinateMap(wm, derivation_coordinate_set(d, ps))
    values = {s.symbol: model_value(s.value, ps.values) for s in d.symbols.values()
              if s.value is not None}
    doc = d.read_off(unscale=True)
    given = {k: sp.Matrix(M) for k, M in (("A", doc.A), ("Q", doc.Q), ("h", doc.h))
             if M is not None}
    parts = {k: sp.lambdify([d.positions, d.velocities], M.xreplace(values))
             for k, M in given.items()}
    errors: dict[str, float] = {}
    for _ in range(N_STATES):
        q = np.array([rng.uniform(*r) for r in ranges])
        nu = rng.normal(size=d.n)
        truth = cmap.terms(q, nu)
        for key, fn in parts.items():
            D = np.array(fn(q, nu), dtype=float)
            T = getattr(truth, key)
            D = D.reshape(T.shape)
            flat = list(given[key])                     # row-major, as np.ndindex
            for k, index in enumerate(np.ndindex(T.shape)):
                if flat[k].has(sp.nan):
                    continue                            # lost in the document ("?")
                row = np.abs(T[index[0]]).max() if T.ndim > 1 else np.abs(T).max()
                label = f"{key}[{','.join(str(i + 1) for i in index)}]"
                err = abs(D[index] - T[index]) / (1 + row)
                errors[label] = max(errors.get(label, 0.0), np.inf if np.isnan(err) else err)
    return errors


@pytest.mark.parametrize("stem", sorted(SEED000 | SEED002))
def test_document_against_truth_at_urdf_parameters(stem):
    d = with_row_functions(load_derivation(_paths()[stem]), DIVIDED.get(stem, ()))
    ranges = RANGES.get(stem, [(-np.pi, np.pi)] * d.n)
    errors = _elements(d, load_model(d.model), np.random.default_rng(SEED), ranges)
    wrong = WRONG.get(stem, set())
    for label, err in errors.items():
        if label in wrong:
            assert err > DIFFER_MIN, (label, err)
        else:
            assert err < AGREE_TOL, (label, err)
    assert wrong <= set(errors)


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)


@pytest.mark.parametrize("stem", sorted(SEED000))
def test_engine_verdicts(stem, engine):
    r"""The engine says 'differs' on every element a document gets wrong, and never on an
    element of A, Q, B of a document that is right (it may say 'agrees only if ...': the
    documents assume uniform rods, point masses, principal axes)."""
    result = engine.compare(load_derivation(_paths()[stem]))
    records = {r.element: r for r in result.records if r.key in ("A", "Q", "B")}
    wrong = WRONG.get(stem, set()) - ASSUMED.get(stem, set())
    for label in wrong:
        assert records[label].verdict == "differs", (label, records[label].verdict)
    for label, r in records.items():
        if label not in wrong:
            assert r.verdict in ("agrees", "agrees_if"), (label, r.verdict, r.texts)


def test_engine_judges_bounce_pitch_under_its_declared_assumptions(engine):
    r"""4.12 (c) is linearised about θ = 0 with the potential measured from the static
    equilibrium ([assumes]): under them its A and Q agree and the result says what was
    assumed."""
    result = engine.compare(load_derivation(_paths()["p4_12_bounce_pitch"]))
    said = " ".join(result.assumes)
    assert "linearised about" in said and "equilibrium" in said, result.assumes
    records = {r.element: r for r in result.records}
    for label in ASSUMED["p4_12_bounce_pitch"]:
        assert records[label].verdict == "agrees", (label, records[label].texts)


def test_engine_without_the_assumptions_names_the_missing_gravity(engine, tmp_path):
    r"""The same file without its [assumes] table is compared with the full equations at any
    θ: A[1,2] differs (the factor cos θ the linearisation drops) and Q misses gravity."""
    text = _paths()["p4_12_bounce_pitch"].read_text()
    start = text.index("[assumes]")
    end = text.index("\n[", start + 1)
    path = tmp_path / "p4_12_bounce_pitch.toml"
    path.write_text(text[:start] + text[end + 1:])
    result = engine.compare(load_derivation(path))
    assert not result.assumes
    records = {r.element: r for r in result.records}
    assert records["A[1,2]"].verdict == "differs"
    assert all(any("missing" in x for x in records[k].texts) for k in ("Q[1]", "Q[2]"))


def test_engine_skips_h_of_a_lost_row(engine):
    result = engine.compare(load_derivation(_paths()["p4_9_pendulum_support"]))
    assert not [r.element for r in result.records if r.element.startswith("h[1]")]


def test_engine_power_identity_of_euler_equations(engine):
    result = engine.compare(load_derivation(_paths()["p7_2_euler_equations"]))
    assert result.energy is not None and result.energy.conserves


def test_engine_on_the_uniform_sphere(engine):
    r"""Seed 002's (3.3), true for a uniform sphere: every element agrees, at most "only if"
    the ball keeps the URDF's proportions (a uniform ball stays uniform), its polar angle u
    drawn in the file's declared range (0.2, pi - 0.2)."""
    result = engine.compare(load_derivation(_paths()["s3_3_sphere_plane"]))
    assert all(r.verdict in ("agrees", "agrees_if") for r in result.records if r.key != "C")


def test_engine_runs_with_a_lost_row_of_A(engine):
    engine.compare(load_derivation(_paths()["s3_12_sphere_sphere"]))


def test_row_scale_keeps_lost_elements_in_their_row():
    r"""read_off(unscale=True) divides row by row: the lost first row of (3.12)'s file does
    not spread nan into the rows the paper prints."""
    d = load_derivation(_paths()["s3_12_sphere_sphere"])
    terms = d.read_off(unscale=True)
    assert all(terms.A[0, j].has(sp.nan) for j in range(3))
    assert not any(terms.A[i, j].has(sp.nan) for i in (1, 2) for j in range(3))
    assert not terms.h[1].has(sp.nan) and terms.h[0].has(sp.nan)
