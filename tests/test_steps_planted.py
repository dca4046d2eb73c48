"""Steps of a derivation (``[[step]]``): right steps written in other forms are judged right,
steps with one planted error are caught and the error is named.

The truth is Pinocchio's (frame velocities and accelerations, energies, rolling constraints);
the right steps below are written by hand from the geometry of the two-wheeled pendulum
(heading frame x forward, y left, z up; left wheel at +L y; the body's centre of mass at
(-d sin φ, d cos φ) in the (forward, up) plane for the model's pitch φ), independently of the
code under test.
"""

from __future__ import annotations

from pathlib import Path

import pytest
import sympy as sp

from wheeled_dyn.compare.steps.records import compare_steps
from wheeled_dyn.compare.steps.chain import energy_consistency
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.errors import WheeledDynError

from conftest import SEED

HEADER = """
title = "planted steps"
model = "wip"
[coordinates]
use = "seed001"
[symbols]
d = { value = "d", units = "m" }
R = { value = "R", units = "m" }
L = { value = "L", units = "m" }
m_C = { value = "m_C", units = "kg" }
I_w2 = { value = "Iw2", units = "kg*m**2" }
I_w3 = { value = "Iw3", units = "kg*m**2" }
"""

WHEELS = """
title = "planted constraints"
model = "wip"
[coordinates]
kind = "holonomic"
positions = ["x0", "y0", "psi", "theta_l", "theta_r", "phi"]
rolling = "multipliers"
configuration = { x0 = "x0", y0 = "y0", psi = "psi", phi = "phi", theta_l = "-theta_l - phi", theta_r = "-theta_r - phi" }
[symbols]
R = { value = "R", units = "m" }
L = { value = "L", units = "m" }
"""


def _step(kind: str, components, **keys) -> str:
    lines = ["[[step]]", 'equation = "(1)"', f'kind = "{kind}"']
    for k, v in keys.items():
        v = [v] if isinstance(v, bool) else v
        lines.append(f"{k} = " + (f'"{v}"' if isinstance(v, str) else repr(list(v)).replace("'", '"')))
    key = "relations" if kind in ("constraint", "claim", "linearised equations") else (
        "value" if "energy" in kind else "components")
    text = f'"{components}"' if key == "value" else repr(list(components)).replace("'", '"')
    lines.append(f"{key} = {text}")
    return "\n".join(lines) + "\n"


def _records(tmp_path: Path, body: str, header: str = HEADER):
    path = tmp_path / "steps.toml"
    path.write_text(header + body)
    return compare_steps(load_derivation(path), SEED)


def _verdicts(records) -> list[str]:
    return [r.verdict for r in records]


# -- kinematics -------------------------------------------------------------------------------

V_LEFT = ["dx - L*dpsi", "0", "0"]
OMEGA_LEFT = ["0", "(dx - L*dpsi)/R", "dpsi"]           # about left: rolling forward is +
A_COM = ["ddx - d*cos(phi)*ddphi + d*sin(phi)*(dphi**2 + dpsi**2)",
         "dx*dpsi - d*sin(phi)*ddpsi - 2*d*cos(phi)*dpsi*dphi",
         "-d*sin(phi)*ddphi - d*cos(phi)*dphi**2"]


def test_right_kinematics_in_other_forms_agree(tmp_path):
    body = (_step("velocity", V_LEFT, body="wheel_left", frame="heading")
            # the same vector in the world frame
            + _step("velocity", ["(dx - L*dpsi)*cos(psi)", "(dx - L*dpsi)*sin(psi)", "0"],
                    body="wheel_left", frame="world")
            # other order of the axes, other sign of an axis
            + _step("angular velocity", ["dpsi", "-(dx - L*dpsi)/R", "0"],
                    body="wheel_left", frame="heading", axes=["z", "-y", "x"])
            + _step("angular velocity", OMEGA_LEFT, body="wheel_left", frame="heading")
            # other trigonometric forms: sin(2 phi)/2, cos written as a shifted sine
            + _step("acceleration", [A_COM[0].replace("cos(phi)", "sin(phi + pi/2)"),
                                     "dx*dpsi - d*sin(phi)*ddpsi - d*sin(2*phi)/sin(phi)*dpsi*dphi",
                                     A_COM[2]],
                    body="body", point="com", frame="heading", given=["com_on_axis"])
            # the centre of mass as a point given in the body's frame
            + _step("acceleration", A_COM, body="body", point=["0", "d", "0"], frame="heading",
                    given=["com_on_axis"])
            + _step("velocity", ["0", "0", "0"], body="wheel_right", point="contact",
                    frame="world"))
    records = _records(tmp_path, body)
    assert len(records) == 7 * 3
    assert set(_verdicts(records)) == {"agrees"}, [(r.element, r.texts) for r in records
                                                   if r.verdict != "agrees"]
    assert {r.step for r in records} == {"velocity", "angular velocity", "acceleration"}
    assert {r.equation for r in records} == {"(1)"}


def test_wrong_velocity_component_is_named(tmp_path):
    wrong = ["dx + L*dpsi", "0", "0"]                      # the right wheel's, for the left
    records = _records(tmp_path, _step("velocity", wrong, body="wheel_left", frame="heading"))
    assert _verdicts(records) == ["differs", "agrees", "agrees"]
    assert "term dpsi: sign: the document has the opposite sign" in records[0].texts


def test_missing_acceleration_term_is_named(tmp_path):
    wrong = [A_COM[0], A_COM[1].replace("dx*dpsi - ", "-"), A_COM[2]]
    records = _records(tmp_path, _step("acceleration", wrong, body="body", point="com",
                                       frame="heading", given=["com_on_axis"]))
    assert _verdicts(records) == ["agrees", "differs", "agrees"]
    assert "term dx*dpsi: missing: the document has 0" in records[1].texts


def test_wrong_moment_arm_is_named(tmp_path):
    right = ["dx - dphi*d*cos(phi)", "-dpsi*d*sin(phi)", "-dphi*d*sin(phi)"]
    wrong = [c.replace("d*", "L*") for c in right]          # the arm L for d
    records = _records(tmp_path,
                       _step("velocity", right, body="body", point="com", frame="heading",
                             given=["com_on_axis"])
                       + _step("velocity", wrong, body="body", point="com", frame="heading",
                               given=["com_on_axis"]))
    assert _verdicts(records[:3]) == ["agrees"] * 3
    assert _verdicts(records[3:]) == ["differs"] * 3
    assert all("swap: L where d fits" in r.texts for r in records[3:])


def test_agrees_only_if_a_special_family(tmp_path):
    # the centre-of-mass velocity of a body whose centre is on the axis, stated without saying so
    right = ["dx - dphi*d*cos(phi)", "-dpsi*d*sin(phi)", "-dphi*d*sin(phi)"]
    records = _records(tmp_path, _step("velocity", right, body="body", point="com",
                                       frame="heading"))
    assert all(r.verdict == "agrees_if" for r in records[:2])
    assert "centre of mass is straight above the axle" in records[0].texts[0]


# -- energies -----------------------------------------------------------------------------------

T_WHEEL = "m_C/2*(dx - L*dpsi)**2 + I_w3/(2*R**2)*(dx - L*dpsi)**2 + I_w2/2*dpsi**2"


def test_energy_right_rewritten_and_dropped_term(tmp_path):
    rewritten = "(m_C + I_w3/R**2)*(dx**2 - 2*L*dx*dpsi + L**2*dpsi**2)/2 + I_w2*dpsi**2/2"
    dropped = "m_C/2*(dx - L*dpsi)**2 + I_w3/(2*R**2)*(dx - L*dpsi)**2"
    body = "".join(_step("kinetic energy", t, bodies=["wheel_left"])
                   for t in (T_WHEEL, rewritten, dropped))
    records = _records(tmp_path, body)
    assert _verdicts(records) == ["agrees", "agrees", "differs"]
    assert any(x.startswith("term dpsi*dpsi") for x in records[2].texts)
    assert not any(x.startswith(("term dx*dx", "term dx*dpsi")) for x in records[2].texts)


def test_a_against_the_hessian_of_its_own_energy(tmp_path):
    energy = "M/2*dx**2 + J/2*sin(phi)**2*dpsi**2 + K/2*dphi**2 + N*cos(phi)*dx*dphi"
    header = HEADER + 'M = { value = "m_S", units = "kg" }\nJ = { value = "I1", units = "kg*m**2" }\n' \
        'K = { value = "I3", units = "kg*m**2" }\nN = { value = "m_S*d", units = "kg*m" }\n'
    right = 'A = "[[M, 0, N*cos(phi)], [0, J*sin(phi)**2, 0], [N*cos(phi), 0, K]]"'
    wrong = 'A = "[[M, 0, N*cos(phi)], [0, J*cos(phi)**2, 0], [N*cos(phi), 0, K]]"'
    out = {}
    for name, A in (("right", right), ("wrong", wrong)):
        path = tmp_path / f"{name}.toml"
        path.write_text(header + f"[matrices]\n{A}\n" + _step("kinetic energy", energy))
        d = load_derivation(path)
        out[name] = {r.element.split(" ")[0]: r for r in energy_consistency(d, d, SEED)}
    assert {r.verdict for r in out["right"].values()} == {"agrees"}
    assert len(out["right"]) == 9
    assert [k for k, r in out["wrong"].items() if r.verdict == "differs"] == ["A[2,2]"]
    assert out["wrong"]["A[2,2]"].step == "kinetic energy"


# -- constraints and claims ------------------------------------------------------------------

RIGHT_CONSTRAINTS = ["dx0*sin(psi) - dy0*cos(psi) = 0",
                     "dx0*cos(psi) + dy0*sin(psi) = R/2*(dtheta_l + dtheta_r)"]


def test_constraints_right_rewritten_and_sin_for_cos(tmp_path):
    rewritten = ["2*dy0*cos(psi) = 2*dx0*sin(psi)",       # scaled, sides exchanged
                 # a combination of both rows
                 "dx0*(cos(psi) + sin(psi)) + dy0*(sin(psi) - cos(psi)) = R*(dtheta_l + dtheta_r)/2"]
    wrong = ["dx0*sin(psi) - dy0*cos(psi) = 0",
             "dx0*sin(psi) + dy0*cos(psi) = R/2*(dtheta_l + dtheta_r)"]   # as seed 001 prints
    body = "".join(_step("constraint", c) for c in (RIGHT_CONSTRAINTS, rewritten, wrong))
    records = _records(tmp_path, body, WHEELS)
    assert _verdicts(records) == ["agrees"] * 5 + ["differs"]
    assert any("sin(psi) and cos(psi) exchanged" in x for x in records[5].texts)
    assert records[5].step == "constraint"


def test_claimed_relation_between_coordinates(tmp_path):
    body = (_step("claim", ["psi = R*(theta_r - theta_l)/(2*L)"])
            + _step("claim", ["psi = R/L*(theta_l - theta_r)"]))       # seed 001, section 5
    records = _records(tmp_path, body, WHEELS)
    assert _verdicts(records) == ["agrees", "differs"]
    (why,) = records[1].texts
    assert "-2 ×" in why and "true: psi = -R*(theta_l - theta_r)/(2*L)" in why


def test_claim_between_parameters_power_and_dimension(tmp_path):
    body = _step("claim", ["I_w3 = m_C*R**2/2", "I_w2 = m_C*R**2/4", "I_w2 = m_C/(4*R**2)"],
                 given=["disc_wheels"])
    records = _records(tmp_path, body)
    assert _verdicts(records) == ["agrees", "agrees", "differs"]
    assert "power: R**(-2) where R**2 fits" in records[2].texts
    assert any(x.startswith("dimension") for x in records[2].texts)


def test_generalized_inertia_forces_planted_factor(tmp_path):
    # Kane's F1* = -(A u-dot + h)[1] for identical disc-free wheels, centre of mass on the axis
    header = HEADER + 'm_S = { value = "m_S", units = "kg" }\n'
    right = ("-(m_S + 2*m_C + 2*I_w3/R**2)*ddx + m_S*d*cos(phi)*ddphi "
             "- m_S*d*sin(phi)*(dphi**2 + dpsi**2)")
    halved = right.replace("(dphi**2 + dpsi**2)", "(dphi**2 + dpsi**2/2)")
    body = "".join(_step("generalized force", [f], rows=[1],
                         given=["com_on_axis", "no_armature"]) for f in (right, halved))
    records = _records(tmp_path, body, header)
    assert _verdicts(records) == ["agrees", "differs"]
    assert "term dpsi*dpsi: factor: the document is 1/2 × the truth" in records[1].texts


# -- the seed: where Kim et al.'s missing and halved terms enter -------------------------------

def test_seed001_upstream_causes():
    from wheeled_dyn.compare import ComparisonEngine
    from wheeled_dyn.derivations import builtin_derivations
    path = next(p for p in builtin_derivations("seed001") if p.stem == "kim_eq1_3")
    result = ComparisonEngine(samples=100, param_sets=2).compare(load_derivation(path))
    causes = {c.elements: c for c in result.causes if c.kind == "upstream_step"}
    assert causes[("h[2]:dx*dpsi",)].equation == "(65)"
    assert "missing" in causes[("h[2]:dx*dpsi",)].explanation
    assert causes[("h[2]:dpsi*dphi",)].equation == "(65)"
    assert "1/2" in causes[("h[2]:dpsi*dphi",)].explanation
    steps = {r.equation for r in result.records if r.key == "step"}
    assert {"(54)", "(65)", "(69)", "F1", "F3", "after F3"} <= steps


# -- bad input -------------------------------------------------------------------------------------

@pytest.mark.parametrize("body, item", [
    ('[[step]]\nkind = "velocity"\nbody = "body"\ncomponents = ["0", "0", "0"]\n', "step 1"),
    ('[[step]]\nequation = "(9)"\nkind = "speed"\ncomponents = ["0"]\n', "step 1 (9).kind"),
    ('[[step]]\nequation = "(9)"\nkind = "velocity"\nbody = "body"\ncomponents = ["0", "0"]\n',
     "step 1 (9).components"),
    ('[[step]]\nequation = "(9)"\nkind = "claim"\nrelations = ["psi"]\n', "step 1 (9).relations"),
    ('[[step]]\nequation = "(9)"\nkind = "velocity"\nbody = "body"\ncomponents = ["0", "0", "q"]\n',
     "step 1 (9) component 3"),
])
def test_bad_steps_name_the_step_and_line(tmp_path, body, item):
    path = tmp_path / "bad.toml"
    path.write_text(HEADER + body)
    with pytest.raises(WheeledDynError) as err:
        load_derivation(path)
    assert err.value.item == item
    assert err.value.line == HEADER.count("\n") + 1 or "component" in item


def test_unknown_link_is_an_error(tmp_path):
    from wheeled_dyn.errors import UnknownNameError
    with pytest.raises(UnknownNameError):
        _records(tmp_path, _step("velocity", ["0", "0", "0"], body="wheel_middle",
                                 frame="heading"))


def test_step_expressions_are_sympy():
    path = next(Path(__file__).parents[1].glob(
        "src/wheeled_dyn/data/derivations/seed001/s7_newton_euler_steps.toml"))
    d = load_derivation(path)
    assert d.feeds == ("kim_eq1_3", "appendix_kim_A_C")
    assert d.A is None and d.equations is None
    (a_b,) = [s for s in d.steps if s.equation == "(65)"]
    assert a_b.components[1] == sp.sympify("ddpsi*d*sin(phi) + dpsi*dphi*d*cos(phi)",
                                           locals={n: d.symbol(n) for n in
                                                   ("ddpsi", "d", "phi", "dpsi", "dphi")})


def test_the_documented_step_examples_load_and_say_what_the_text_says(tmp_path):
    import re
    doc = (Path(__file__).resolve().parents[1] / "docs" / "derivation-steps.md").read_text()
    blocks = [b for b in re.findall(r"```toml\n(.*?)```", doc, flags=re.S) if "[[step]]" in b
              and 'model = "wip"' in b]     # the flywheel example: test_derivations_docs.py
    assert len(blocks) == 2
    verdicts = {}
    for k, block in enumerate(blocks):
        path = tmp_path / f"example{k}_steps.toml"
        path.write_text(block)
        for r in compare_steps(load_derivation(path), SEED):
            verdicts.setdefault(r.equation, []).append(r.verdict)
    assert verdicts["(56)"] == ["agrees"] * 3
    assert verdicts["(65)"] == ["agrees", "differs", "agrees"]
    assert verdicts["(18)"] == ["agrees"]
    assert verdicts["F2"] == ["differs"]                      # Kim's F2 lacks the x-dot psi-dot term
    assert verdicts["after F3"] == ["differs"]
    assert verdicts["(33)"] == ["agrees", "differs"]
    assert verdicts["before (35)"] == ["differs"]


def test_linearised_equations_right_rewritten_and_planted_sign(tmp_path):
    path = Path(__file__).resolve().parents[1] / \
        "src/wheeled_dyn/data/derivations/seed000/p7_2_linearised_steps.toml"
    text = path.read_text()
    head = text.split("[[step]]")[0]
    body = "".join(_step("linearised equations", rel, about_table=True)
                   for rel in (["dq + (I1 - I3)*Omega/I2*r = 0"],                 # (7.24)
                               ["I2*dq = (I3 - I1)*Omega*r"],                     # rewritten
                               ["dr - (I2 - I1)*Omega/I3*q = 0"]))               # planted sign
    body = body.replace("about_table = [True]", 'about = { p = "Omega" }\ngiven = ["urdf_structure"]')
    records = _records(tmp_path, body, head)
    assert _verdicts(records) == ["agrees", "agrees", "differs"]
    assert "term q: sign: the document has the opposite sign" in records[2].texts
    assert records[2].step == "linearised equations"


def test_steps_are_not_sampled_where_the_coordinates_are_singular(monkeypatch):
    r"""A step file's samples avoid the positions where its coordinate map is singular (as
    the equations' grid does): seed 002's paraboloid, with the seed 2028, draws a sample of
    condition number above the bound, which is drawn again."""
    from wheeled_dyn.compare.steps import group as step_group
    from wheeled_dyn.compare.grid.samples import MAX_CONDITION
    from wheeled_dyn.derivations import builtin_derivations
    drawn = []
    plain = step_group.regular_states

    def recorded(cmap, q, rng, ranges=None):
        out = plain(cmap, q, rng, ranges)
        drawn.append((cmap.conditioning(q).max(), cmap.conditioning(out).max()))
        return out

    monkeypatch.setattr(step_group, "regular_states", recorded)
    path = next(p for p in builtin_derivations("seed002") if p.name == "s3_8_paraboloid.toml")
    compare_steps(load_derivation(path), 2028)
    assert drawn and max(before for before, _ in drawn) > MAX_CONDITION
    assert all(after <= MAX_CONDITION for _, after in drawn)


def test_balances_are_sampled_away_from_singular_coordinates(monkeypatch):
    r"""A balance's samples go through the same redraw of singular positions (seed 000's
    2.19: one grid per balance, every position left regular)."""
    from wheeled_dyn.compare.steps import balance_samples
    from wheeled_dyn.compare.grid.samples import MAX_CONDITION
    from wheeled_dyn.derivations import builtin_derivations
    drawn = []
    plain = balance_samples.regular_states

    def recorded(cmap, q, rng, ranges=None):
        out = plain(cmap, q, rng, ranges)
        drawn.append((q.shape, cmap.conditioning(out).max()))
        return out

    monkeypatch.setattr(balance_samples, "regular_states", recorded)
    path = next(p for p in builtin_derivations("seed000") if p.name == "p2_19_spring_block.toml")
    d = load_derivation(path)
    compare_steps(d, 2026)
    kinds = [s.kind for s in d.steps]
    assert len(drawn) == kinds.count("newton-euler") > 0, kinds
    assert all(shape[1] == len(d.positions) and c <= MAX_CONDITION for shape, c in drawn)
