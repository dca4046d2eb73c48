"""Seed 000, problems 1.11 and 1.12: the four-wheeled car with both front wheels steered by the
same angle (model ``car4``, file ``seed000/p1_11_car_constraints.toml``).

The expected verdicts come from the side slip written by hand: a wheel at (x_i, y_i) in the
body frame (x forward, y left), steered by delta_i (positive to the left), slips sideways at

    s_i = -(v_x - y_i theta') sin(delta_i) + (v_y + x_i theta') cos(delta_i),

with (v_x, v_y) = (cos theta X' + sin theta Y', -sin theta X' + cos theta Y') the reference
point's velocity in body axes; rear wheels at x = -b, y = +-W/2, delta = 0, front wheels at
x = a, y = +-W/2 (wheel 3 left, wheel 4 right), delta. Against it, as printed: 1.11's wheels
1, 2, 4 are right and its wheel 3 has (v_x + W/2 theta') where (v_y + a theta') belongs;
1.12's wheel 4 is right, its wheels 1 and 2 have +b theta' for -b theta', its wheel 2's
second form is X' + b theta', and its wheel 3 (printed as wheel 4) has the sign of the
W/2 theta' sin(delta) term of the right wheel.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

from conftest import N_STATES, SEED
from wheeled_dyn import load_model
from wheeled_dyn.compare.steps.records import compare_steps
from wheeled_dyn.constraints.rolling import contact_jacobian, contact_velocities
from wheeled_dyn.constraints.wheel_contact import wheel_heights
from wheeled_dyn.derivations import load_derivation

FILE = (Path(__file__).resolve().parents[1] / "src" / "wheeled_dyn" / "data" / "derivations"
        / "seed000" / "p1_11_car_constraints.toml")
MODEL = "car4"
#: The model's geometry (car4.toml, urdf/car4.urdf): front axle ahead of and rear axle behind
#: the reference point, track, wheel radius (m).
A, B, W, R = 1.2, 1.5, 1.6, 0.3
#: Rolling wheels in the model's order, with their centres in the body frame and whether they
#: steer (by the same-named joint's angle).
WHEELS = {"wheel_rl": ((-B, W / 2), None), "wheel_rr": ((-B, -W / 2), None),
          "wheel_fl": ((A, W / 2), "steer_fl"), "wheel_fr": ((A, -W / 2), "steer_fr")}
#: Identities exact up to rounding.
EXACT_TOL = 1e-9
#: Singular values below this count as zero (the contact Jacobian's entries are O(1)).
RANK_TOL = 1e-9
#: Steering angles drawn in the tests (rad), inside the URDF's joint limits.
STEER = 0.6

#: The verdict of every printed relation (element as the report names it), by the hand check.
EXPECTED = {
    "1.11 wheel 1 side slip": "agrees",
    "1.11 wheel 2 side slip": "agrees",
    "1.11 wheel 4 side slip": "agrees",
    "1.11 wheel 3 side slip": "differs",             # (v_x + W/2 theta') for (v_y + a theta')
    "1.12 v_x, v_y of 1.11 replaced v_x": "agrees",
    "1.12 v_x, v_y of 1.11 replaced v_y": "agrees",
    "1.12 wheel 1 side slip": "differs",             # + b theta' for - b theta'
    "1.12 wheel 2 side slip": "differs",             # the same
    "1.12 wheel 2, second form side slip": "differs",
    "1.12 wheel 3 side slip": "differs",             # wheel 4's relation: sign of W/2 term
    "1.12 wheel 4 side slip": "agrees",
}

#: Two printed relations of the file, as they appear in it (for the planted copies).
WHEEL1 = 'components = ["v_y - b*dtheta"]'
WHEEL4 = 'components = ["(v_y + a*dtheta)*cos(delta) - (v_x + W/2*dtheta)*sin(delta)"]'


def _records(path: Path) -> dict:
    return {r.element: r for r in compare_steps(load_derivation(path), SEED)}


@pytest.fixture(scope="module")
def shipped() -> dict:
    return _records(FILE)


def _planted(tmp_path: Path, old: str, new: str) -> dict:
    text = FILE.read_text()
    assert text.count(old) >= 1
    path = tmp_path / FILE.name
    path.write_text(text.replace(old, new, 1))
    return _records(path)


# -- the model ----------------------------------------------------------------------------------

def _state(wm, rng, steer_fl: float, steer_fr: float) -> np.ndarray:
    q = np.zeros(wm.model.nq)
    for name in wm.coordinate_names:
        q[wm.index(name)] = rng.uniform(-np.pi, np.pi)
    q[wm.index("steer_fl")], q[wm.index("steer_fr")] = steer_fl, steer_fr
    return q


def _ackermann(delta_left: float) -> float:
    r"""The right front wheel's angle turning about the same point of the rear axle line as the
    left front wheel at ``delta_left``: cot(delta_r) - cot(delta_l) = W / (a + b)."""
    t = np.tan(delta_left)
    return float(np.arctan((A + B) * t / ((A + B) + W * t)))


def test_model_geometry_and_contacts():
    wm = load_model(MODEL)
    assert [w.link for w in wm.rolling_wheels] == list(WHEELS)
    assert wm.coordinate_names == ("X", "Y", "theta", "spin_rl", "spin_rr", "steer_fl",
                                   "spin_fl", "steer_fr", "spin_fr")
    assert wm.geometry == {"a": A, "b": B, "W": W, "R": R}
    rng = np.random.default_rng(SEED)
    data = wm.model.createData()
    for _ in range(N_STATES):
        q = _state(wm, rng, *rng.uniform(-STEER, STEER, 2))
        pin.framesForwardKinematics(wm.model, data, q)
        assert np.abs(wheel_heights(wm, q)).max() < EXACT_TOL
        body = data.oMf[wm.model.getFrameId("body")]
        for link, ((x, y), _) in WHEELS.items():
            centre = data.oMf[wm.model.getFrameId(link)].translation
            assert np.allclose(body.actInv(centre), [x, y, 0.0], atol=EXACT_TOL)
            assert centre[2] == pytest.approx(R)


#: The URDF's stated inertial numbers (header comment of urdf/car4.urdf): mass, centre of mass in
#: the link frame, principal moments about it.
BODY = (1200.0, [-0.15, 0.0, 0.35], [1200.0 * (1.7**2 + 0.5**2) / 12,
                                      1200.0 * (4.0**2 + 0.5**2) / 12,
                                      1200.0 * (4.0**2 + 1.7**2) / 12])
WHEEL = (20.0, [0.0, 0.0, 0.0], [20.0 * (3 * R**2 + 0.2**2) / 12, 20.0 * R**2 / 2,
                                 20.0 * (3 * R**2 + 0.2**2) / 12])
#: Slack on inertia values written with 6 significant digits in the URDF.
VALUE_TOL = 1e-5


@pytest.mark.parametrize("link", ["body", *WHEELS])
def test_urdf_numbers_are_the_stated_ones(link):
    mass, com, moments = BODY if link == "body" else WHEEL
    wm = load_model(MODEL)
    inertia = wm.model.inertias[wm.joint_id_of_link(link)]     # each joint carries one link
    assert inertia.mass == pytest.approx(mass)
    assert np.allclose(inertia.lever, com, atol=EXACT_TOL)
    assert np.allclose(inertia.inertia, np.diag(moments), rtol=VALUE_TOL, atol=EXACT_TOL)


def test_side_slip_rows_are_the_hand_formula():
    r"""For any velocities, each wheel's contact point moves along its axle at s_i (module
    docstring): the lateral rows of the model are the hand-written conditions."""
    wm = load_model(MODEL)
    rng = np.random.default_rng(SEED + 1)
    for _ in range(N_STATES):
        q = _state(wm, rng, *rng.uniform(-STEER, STEER, 2))
        v = rng.normal(size=wm.nv)
        theta, dX, dY, dtheta = q[wm.index("theta")], *v[[wm.index(n) for n in ("X", "Y", "theta")]]
        vx = np.cos(theta) * dX + np.sin(theta) * dY
        vy = -np.sin(theta) * dX + np.cos(theta) * dY
        J, _ = contact_jacobian(wm, q)
        moving = contact_velocities(wm, q, v)
        assert np.allclose(J @ v, moving.ravel(), atol=EXACT_TOL)
        for k, ((x, y), steer) in enumerate(WHEELS.values()):
            delta = q[wm.index(steer)] if steer else 0.0
            axle = np.array([-np.sin(theta + delta), np.cos(theta + delta), 0.0])
            slip = -(vx - y * dtheta) * np.sin(delta) + (vy + x * dtheta) * np.cos(delta)
            assert moving[k] @ axle == pytest.approx(slip, abs=EXACT_TOL)


def test_rolling_motions_leave_the_contacts_at_rest():
    r"""Steered as Ackermann (both front wheels about one point of the rear axle line), the
    car can move: the rolling motions are the body turning about that point and the two
    steering rates; on each, every contact point is at rest (computed from the wheels' frame
    velocities, independently of the Jacobian)."""
    wm = load_model(MODEL)
    rng = np.random.default_rng(SEED + 2)
    for _ in range(N_STATES):
        left = rng.uniform(0.1, STEER) * rng.choice([-1.0, 1.0])
        q = _state(wm, rng, left, _ackermann(left))
        J, _ = contact_jacobian(wm, q)
        _, s, vt = np.linalg.svd(J)
        null = vt[np.sum(s > RANK_TOL):]
        assert len(null) == 3
        base = [wm.index(n) for n in ("X", "Y", "theta")]
        assert np.linalg.matrix_rank(null[:, base], tol=RANK_TOL) == 1   # one way to move
        for v in null:
            assert np.abs(contact_velocities(wm, q, v)).max() < EXACT_TOL
        v = null.T @ rng.normal(size=3)
        assert np.abs(contact_velocities(wm, q, v)).max() < EXACT_TOL


def test_the_same_steering_angle_on_both_front_wheels_admits_no_motion():
    r"""With both front wheels at one angle delta != 0 (the document's car), the four wheels'
    rolling leaves only the steering rates: the body cannot move. This is why the file
    compares each relation with its wheel's side slip (velocity steps) rather than as a
    constraint on the model's rolling motions."""
    wm = load_model(MODEL)
    rng = np.random.default_rng(SEED + 3)
    for _ in range(N_STATES):
        delta = rng.uniform(0.1, STEER) * rng.choice([-1.0, 1.0])
        q = _state(wm, rng, delta, delta)
        J, _ = contact_jacobian(wm, q)
        _, s, vt = np.linalg.svd(J)
        null = vt[np.sum(s > RANK_TOL):]
        assert len(null) == 2
        moving = [wm.index(n) for n in ("X", "Y", "theta", "spin_rl", "spin_rr", "spin_fl",
                                        "spin_fr")]
        assert np.abs(null[:, moving]).max() < EXACT_TOL


# -- the printed relations ------------------------------------------------------------------------

def test_every_printed_relation_is_judged_as_the_hand_check_says(shipped):
    assert {k: r.verdict for k, r in shipped.items()} == EXPECTED


def test_diagnoses_name_the_wrong_terms(shipped):
    for element in ("1.12 wheel 1 side slip", "1.12 wheel 2 side slip"):
        assert "term dtheta: sign: the document has the opposite sign" in \
            shipped[element].texts
    # printed "- W/2 theta' sin(delta)" where the wheel at y = +W/2 has "+": that part's sign
    assert shipped["1.12 wheel 3 side slip"].texts == (
        "term dtheta: sign: the term -W*sin(delta)/2 has the wrong sign",)
    assert {d.split(":")[0] for d in shipped["1.11 wheel 3 side slip"].texts} == \
        {"term dX", "term dY", "term dtheta"}
    second = shipped["1.12 wheel 2, second form side slip"].texts
    assert "term dY: missing: the document has 0" in second
    for r in shipped.values():
        assert r.step == "velocity" and r.equation in ("1.11", "1.12")


def test_file_records_the_reading():
    d = load_derivation(FILE)
    assert d.model == MODEL
    assert {"wheel numbering", "steering angle", "reference point", "1.12 wheel 2"} <= \
        set(d.reconstructed)
    config = {k: str(v) for k, v in d.coordinates.raw["configuration"].items()}
    assert config["steer_fl"] == config["steer_fr"] == "delta"


# -- planted errors and right relations rewritten -------------------------------------------------

def test_sin_written_for_cos_in_a_right_relation_differs(tmp_path):
    planted = WHEEL4.replace("*cos(delta)", "*sin(delta)", 1)
    records = _planted(tmp_path, WHEEL4, planted)
    r = records["1.11 wheel 4 side slip"]
    assert r.verdict == "differs"
    assert any(x.startswith("swap: sin(delta) where cos(delta) fits in the term")
               for x in r.texts), r.texts
    assert records["1.11 wheel 1 side slip"].verdict == "agrees"


def test_wrong_moment_arm_differs_and_is_named(tmp_path):
    records = _planted(tmp_path, WHEEL1, WHEEL1.replace("b*dtheta", "a*dtheta"))
    r = records["1.11 wheel 1 side slip"]
    assert r.verdict == "differs"
    assert "swap: a where b fits" in r.texts
    # a and b are drawn apart (the car's lengths are parameters): a/b is no constant factor
    assert not any(x.startswith("term dtheta: factor") for x in r.texts), r.texts


def test_right_relation_reordered_agrees(tmp_path):
    reordered = 'components = ["-sin(delta)*(W/2*dtheta + v_x) + cos(delta)*(a*dtheta + v_y)"]'
    records = _planted(tmp_path, WHEEL4, reordered)
    assert records["1.11 wheel 4 side slip"].verdict == "agrees"


def test_right_relation_multiplied_through_is_named_as_a_factor(tmp_path):
    r"""Compared as its wheel's side slip, a right relation multiplied through by -2 is that
    side slip times -2: reported as the factor and nothing else (as a constraint it would be
    right; see the next test for why the file cannot use constraint steps)."""
    scaled = ('components = ["-2*((v_y + a*dtheta)*cos(delta) - (v_x + W/2*dtheta)'
              '*sin(delta))"]')
    r = _planted(tmp_path, WHEEL4, scaled)["1.11 wheel 4 side slip"]
    assert r.verdict == "differs"
    assert r.texts[0] == "factor: the document is -2 × the truth"
    assert all("factor" in x for x in r.texts)


def _as_constraints(tmp_path):
    r"""The file's side-slip relations as printed, as ``constraint`` steps ("s = 0") in the
    coordinates with the rolling kept (multipliers)."""
    text = FILE.read_text().replace('rolling = "none"', 'rolling = "multipliers"')
    head, *steps = text.split("[[step]]")
    relations = []
    for step in steps:
        if 'names = ["side slip"]' not in step:
            continue
        component = step.split('components = ["', 1)[1].split('"]', 1)[0]
        label = step.split('label = "', 1)[1].split('"', 1)[0]
        equation = step.split('equation = "', 1)[1].split('"', 1)[0]
        relations.append(f'[[step]]\nequation = "{equation}"\nlabel = "{label}"\n'
                         f'kind = "constraint"\nrelations = ["{component} = 0"]\n')
    tail = "[reconstructed]" + steps[-1].split("[reconstructed]", 1)[1]
    path = tmp_path / "constraints.toml"
    path.write_text(head + "".join(relations) + tail)
    return {r.element.replace(" relation 1", " side slip"): r
            for r in compare_steps(load_derivation(path), SEED)}


def test_all_four_wheels_at_once_leave_nothing_to_check(tmp_path):
    r"""With both front wheels at one angle, the four wheels' conditions together admit no
    motion of the body: every term of every relation vanishes there, and the verdict is
    "undecided" (with the reason), not one computed on rounding noise."""
    records = _as_constraints(tmp_path)
    assert records and all(r.verdict == "undecided" for r in records.values())
    assert all("nothing to check" in r.texts[0] for r in records.values())
