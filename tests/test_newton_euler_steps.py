r"""Newton–Euler balances as derivation steps (``kind = "newton-euler"``, compare/balances.py).

Seed 000 prints three sets: 2.6 (a) the compound pendulum with the pivot force (F_x, F_y) and
(c) its moments about the pivot, 2.7 (c) a vehicle in the plane with four tyre forces, and
2.13 (c) a four-wheeled vehicle with steered front wheels in body axes. As printed the first
two are balances of the body and must agree; 2.13's moment equation puts the front wheels'
a sin(delta) arm on the rear wheels' forces, and the four forces involved must be named; planted errors — a wrong moment arm, a
flipped force, an inertia written as a mass, two arms swapped — must be named, and correct
rewrites (a relation multiplied through, moments about another point declared, a balance along
the body's axes declared) must still agree. The residual rows themselves are checked against
the pendulum's closed form.
"""

from __future__ import annotations


import numpy as np
import pytest

from conftest import SEED
from shipped_copies import rewritten_copy, shipped
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.errors import DerivationError

#: Engine grid (verdicts, not statistics).
SAMPLES, PARAM_SETS = 20, 1

PENDULUM = "p2_6_compound_pendulum.toml"
VEHICLE = "p2_7_vehicle.toml"
CAR = "p2_13_vehicle.toml"
PARTICLE = "p1_15_particle.toml"
DISK = "p2_2b_eccentric_disk.toml"
ARM_3 = "-F_x*a*cos(theta) - F_y*a*sin(theta) = I_g*ddtheta"
PIVOT = '"-m*g*a*sin(theta) = (I_g + m*a**2)*ddtheta"'


def _copy(tmp_path, name, *replacements):
    return rewritten_copy(shipped("seed000", name), tmp_path, *replacements)


def _balances(path) -> dict[str, object]:
    result = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED).compare(
        load_derivation(path))
    return {r.element: r for r in result.records if r.key == "step"}


def test_printed_pendulum_balances_agree(tmp_path):
    records = _balances(_copy(tmp_path, PENDULUM))
    balances = {e: r for e, r in records.items() if r.step == "newton-euler"}
    assert len(balances) == 4
    assert all(r.verdict == "agrees" for r in balances.values()), balances


def test_printed_vehicle_balances_agree_and_v_hl_differs(tmp_path):
    records = _balances(_copy(tmp_path, VEHICLE))
    verdicts = {e: r.verdict for e, r in records.items()}
    assert verdicts.pop("2.7 (b) left wheel v_hl") == "differs"
    # v_hl is printed with v_hr's -(w/2) theta' sin(theta): the left wheel's is +
    assert records["2.7 (b) left wheel v_hl"].texts == (
        "term dtheta: sign: the term -w*sin(theta)/2 has the wrong sign",)
    assert len(verdicts) == 6 and set(verdicts.values()) == {"agrees"}, verdicts


@pytest.mark.parametrize("old,new,element,expected", [
    ("F_hr*(h*cos(theta) - w/2*sin(theta))", "F_hr*(h*cos(theta) + w/2*sin(theta))",
     "2.7 (c) newton-euler (3)", "term F_hr: its coefficient"),
    ("F_vl - F_vr = m*ddy_g", "F_vl + F_vr = m*ddy_g",
     "2.7 (c) newton-euler (2)", "term F_vr: sign"),
    ('= I_g*ddtheta"]', '= m*ddtheta"]', "2.7 (c) newton-euler (3)", "dimension"),
    ("-F_hr - F_hl = m*ddx_g", "-F_hr - F_hl = 2*m*ddx_g",
     "2.7 (c) newton-euler (1)", "term ddx_g: factor: the document is 2"),
])
def test_planted_vehicle_errors_are_named(tmp_path, old, new, element, expected):
    records = _balances(_copy(tmp_path, VEHICLE, (old, new)))
    r = records[element]
    assert r.verdict == "differs"
    assert any(x.startswith(expected) for x in r.texts), r.texts
    others = [e for e, x in records.items() if x.verdict != "agrees"]
    assert sorted(others) == sorted({element, "2.7 (b) left wheel v_hl"})


def test_swapped_moment_arms_are_named_together(tmp_path):
    r = _balances(_copy(tmp_path, PENDULUM, (
        ARM_3, "-F_x*a*sin(theta) - F_y*a*cos(theta) = I_g*ddtheta")))["2.6 (a) newton-euler (3)"]
    assert r.verdict == "differs"
    assert any(x.startswith("term F_x and term F_y") for x in r.texts), r.texts


def test_a_dropped_velocity_term_is_named(tmp_path):
    r = _balances(_copy(tmp_path, PENDULUM, (
        "a*ddtheta*cos(theta) - a*dtheta**2*sin(theta))", "a*ddtheta*cos(theta))"
    )))["2.6 (a) newton-euler (1)"]
    assert r.verdict == "differs"
    assert any("without accelerations or forces" in x for x in r.texts), r.texts


def test_correct_rewrites_agree(tmp_path):
    r"""(3) multiplied by -2 and rearranged; the moment equation about the pivot (declared)
    with the pivot forces' (zero) moments written out."""
    path = _copy(tmp_path, PENDULUM,
                 (ARM_3, "2*I_g*ddtheta + 2*a*(F_x*cos(theta) + F_y*sin(theta)) = 0"),
                 (PIVOT, '"0*F_x - m*g*a*sin(theta) - (I_g + m*a**2)*ddtheta = 0*F_y"'))
    records = _balances(path)
    assert {e: r.verdict for e, r in records.items() if r.step == "newton-euler"} == {
        "2.6 (a) newton-euler (1)": "agrees", "2.6 (a) newton-euler (2)": "agrees",
        "2.6 (a) newton-euler (3)": "agrees", "2.6 (c) newton-euler relation 1": "agrees"}


def test_the_moment_point_matters(tmp_path):
    r"""The pivot's moment equation read about G is not a balance: the pivot force has a moment
    about G."""
    path = _copy(tmp_path, PENDULUM, ('point = "origin"               # moments about the pivot',
                                      'point = "com"                  # moments about G'))
    assert _balances(path)["2.6 (c) newton-euler relation 1"].verdict == "differs"


def test_a_balance_along_the_body_axes(tmp_path):
    r"""(1) and (2) rotated into the body's axes (the rod's, turning with theta): the
    centripetal a theta'^2 along the rod, a theta'' across it. Declared frame = "body" it
    agrees; declared in world axes it differs and the other frame is named."""
    along_rod = ('"F_x*sin(theta) - F_y*cos(theta) + m*g*cos(theta) = -m*a*dtheta**2"')
    forces = ('[step.forces]\nF_x = { point = "origin", direction = ["1", "0", "0"] }\n'
              'F_y = { point = "origin", direction = ["0", "0", "1"] }\n')
    for frame, verdict in (("body", "agrees"), ("world", "differs")):
        text = (f'\n[[step]]\nequation = "rotated"\nkind = "newton-euler"\nbody = "body"\n'
                f'frame = "{frame}"\nrelations = [{along_rod}]\n' + forces)
        path = _copy(tmp_path, PENDULUM)
        path.write_text(path.read_text() + text)
        r = _balances(path)["rotated newton-euler relation 1"]
        assert r.verdict == verdict, (frame, r.texts)
        if verdict == "differs":
            assert r.texts[0].startswith("frame: it is a balance along the axes of body")


@pytest.mark.parametrize("old,new,item", [
    ('F_x = { free = true, units = "N", meaning = "horizontal force of the pivot on the body (to the right)" }',
     'F_x = { value = "1", units = "N" }', "forces.F_x"),
    (ARM_3, "-F_x**2*a*cos(theta) - F_y*a*sin(theta) = I_g*ddtheta", "relation 3"),
])
def test_bad_balances_name_the_place(tmp_path, old, new, item):
    with pytest.raises(DerivationError) as err:
        ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED).compare(
            load_derivation(_copy(tmp_path, PENDULUM, (old, new))))
    assert item in str(err.value)


@pytest.mark.parametrize("old,new,item", [
    ('forces = { F_x = { point = "origin", direction = ["1", "0", "0"] }, F_y = { point = "origin", direction = ["0", "0", "1"] } }\nnames',
     'names', "forces"),
    ('F_y = { point = "origin", direction = ["0", "0", "1"] } }\nnames',
     'F_y = { point = "origin" } }\nnames', "forces.F_y"),
    ('F_y = { point = "origin", direction = ["0", "0", "1"] } }\nnames',
     'F_y = { point = "origin", direction = ["0", "0", "0"] } }\nnames', "forces.F_y"),
])
def test_bad_force_tables_are_refused_on_load(tmp_path, old, new, item):
    with pytest.raises(DerivationError) as err:
        load_derivation(_copy(tmp_path, PENDULUM, (old, new)))
    assert item in str(err.value) and err.value.line is not None


def test_residual_rows_against_the_pendulum():
    r"""The rows E of compare/balances.py for the compound pendulum at one state, against the
    closed form: about the pivot, with no force, the moment row is
    I_O theta'' + m g a sin(theta) (I_O = I_g + m a^2) and the force rows m a_G - m g."""
    from wheeled_dyn import builtin_coordinate_set, load_model
    from wheeled_dyn.compare.steps.balances import residual_rows
    from wheeled_dyn.compare.sides.kinematics import Motion
    from wheeled_dyn.constraints.reduction import CoordinateMap
    wm = load_model("compound_pendulum")
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "full"))
    inertia = wm.model.inertias[wm.joint_id_of_link("body")]
    m, a = inertia.mass, float(np.linalg.norm(inertia.lever))
    I_O = float(inertia.inertia[1, 1]) + m * a * a
    g = float(-wm.model.gravity.linear[2])
    th, dth, ddth = 0.7, -1.3, 2.1
    motion = Motion(cmap, wm.model.createData(), np.array([th]), np.array([dth]),
                    np.array([ddth]))
    rows = residual_rows(motion, "body", "origin", "world", (), ())
    moment = rows[3:, 0]
    assert abs(abs(moment[1]) - abs(I_O * ddth + m * g * a * np.sin(th))) < 1e-9
    a_G = np.array([a * (ddth * np.cos(th) - dth**2 * np.sin(th)), 0.0,
                    a * (ddth * np.sin(th) + dth**2 * np.cos(th))])
    assert np.allclose(rows[:3, 0], m * a_G + m * g * np.array([0.0, 0.0, 1.0]), atol=1e-9)


def test_car_moment_equation_names_the_moved_arm(tmp_path):
    r"""2.13 (c): the force equations agree; the moment equation's (F_xrr + F_xlr) a sin(delta)
    belongs to the front wheels. Its motion side (I_g omega-dot) fixes the combination, so the
    four forces whose coefficients change are named; with the front wheels' forces there the
    relation agrees."""
    records = _balances(_copy(tmp_path, CAR))
    assert records["2.13 (c) newton-euler x"].verdict == "agrees"
    assert records["2.13 (c) newton-euler y"].verdict == "agrees"
    moment = records["2.13 (c) newton-euler moment"]
    assert moment.verdict == "differs"
    named = {x.split(":")[0] for x in moment.texts}
    assert named == {"term F_xrf", "term F_xlf", "term F_xrr", "term F_xlr"}, moment.texts
    fixed = _balances(_copy(tmp_path, CAR, ("(F_xrr + F_xlr)*a*sin(delta)",
                                            "(F_xrf + F_xlf)*a*sin(delta)")))
    assert fixed["2.13 (c) newton-euler moment"].verdict == "agrees"


def test_particle_on_a_string_through_a_hole(tmp_path):
    r"""1.15: the balance across the string (b), the angular momentum about the hole as a first
    integral and its rate as the moment balance about the hole (c) agree as printed; a lost
    factor 2 in (b), m r theta' for m r^2 theta', and the moments taken about the ball instead
    of the hole each differ."""
    records = _balances(_copy(tmp_path, PARTICLE))
    assert len(records) == 4 and all(r.verdict == "agrees" for r in records.values()), records
    for old, new, element in (
            ('["r*ddtheta + 2*dr*dtheta = 0"]', '["r*ddtheta + dr*dtheta = 0"]',
             "1.15 (b) newton-euler relation 1"),
            ('value = "m*r**2*dtheta"', 'value = "m*r*dtheta"', "1.15 (c) |r x p| value"),
            ('point = ["-r", "0", "0"]           # the hole', 'point = "com"',
             "1.15 (c) its rate boxed")):
        wrong = {e for e, r in _balances(_copy(tmp_path, PARTICLE, (old, new))).items()
                 if r.verdict != "agrees"}
        assert element in wrong, (old, wrong)


def test_rolling_eccentric_disk_with_contact_forces(tmp_path):
    r"""The second 2.2: a rolling disk with its centre of mass off its centre, pushed by F, with
    the friction H and normal force N at the contact point (a point of the disk given by
    document expressions). (1)-(3) agree as printed; a cos written for the sin of H's moment
    arm is named as that swap, and a flipped weight as the force-free terms."""
    records = _balances(_copy(tmp_path, DISK))
    assert [r.verdict for r in records.values()] == ["agrees"] * 3
    moment = _balances(_copy(tmp_path, DISK, ("H*(R + a*sin(theta))", "H*(R + a*cos(theta))")))[
        "(1)-(3) newton-euler (3)"]
    assert moment.verdict == "differs"
    assert "swap: cos(theta) where sin(theta) fits in the term H*(R + a*cos(theta))" in \
        moment.texts, moment.texts
    weight = _balances(_copy(tmp_path, DISK, ("N - m*g =", "N + m*g =")))["(1)-(3) newton-euler (2)"]
    assert weight.verdict == "differs"
    assert weight.texts[0].startswith("the terms without accelerations or forces")


def test_a_balance_not_finite_somewhere_is_undecided(tmp_path):
    r"""A force applied at a point the document writes with a logarithm of a negative number
    (not finite at the samples): no verdict is computed, the record says why."""
    path = _copy(tmp_path, PENDULUM, (
        'F_x = { point = "origin", direction = ["1", "0", "0"] }, F_y = { point = "origin", direction = ["0", "0", "1"] } }\nnames',
        'F_x = { point = ["log(-1 - theta**2)", "0", "0"], direction = ["1", "0", "0"] }, F_y = { point = "origin", direction = ["0", "0", "1"] } }\nnames'))
    records = _balances(path)
    bad = [r for e, r in records.items() if e.startswith("2.6 (a)")]
    assert bad and all(r.verdict == "undecided" for r in bad)
    assert all(r.texts == ("not finite at some samples",) for r in bad)
