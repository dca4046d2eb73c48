"""Seed 001's formula steps (15), (17), (55), (64), (66), (68) against the truth.

Before, the step files recorded only the components the document prints after these formulas.
Now they record each formula too, worked out into components as its
``[reconstructed]`` entry says. The expectations come from the document's geometry. Seed 001
section 4: frame 0 moves with the robot, x along the heading, y up, z along the axle from left
to right; frame 1 is the body's, a rotation by phi about z with its origin at the middle of the
axle. Section 7: i, j, k are the heading frame (x forward, y left, z up), the body turns by phi
about j, and its C.G. is at d (sin(phi) i + cos(phi) k). The expectations do not come from the
tool's output. Each formula is a correct rigid-body formula, so its worked-out components
agree. The printed components that follow them are where the errors enter:

- (61) alpha_B lacks the -phi-dot psi-dot i term of d(phi-dot j)/dt, because j turns with the
  heading;
- (65), (67), (69) take dv_xyz/dt = x-double-dot i and drop the x-dot psi-dot j from the
  turning of i. (65) also uses (61)'s alpha_B, which halves its psi-dot phi-dot j term.

Not compared, because no step kind can express them: in (15), 0g, 0T1, 1e1 and
q1-dot = phi-dot. 0w0 of (15), the angular velocity of frame 0, is compared with the heading
frame as its body (body = "heading"). U1 of (17) is compared as a potential energy, up to a
constant.

The wheels' energies E_L (18), E_R (19) are worked out from the printed wheel velocities. These
carry an L/2 where the geometry needs L: L is the half track, so the left wheel's centre moves at
x-dot - L psi-dot and the right one's at x-dot + L psi-dot. The energies inherit the L/2, so
they differ. With L for L/2 they agree.
"""

from __future__ import annotations

from pathlib import Path

import pytest
import sympy as sp

from wheeled_dyn.compare.steps.records import compare_steps
from wheeled_dyn.derivations import load_derivation

from conftest import SEED

FOLDER = Path(__file__).resolve().parents[1] / "src/wheeled_dyn/data/derivations/seed001"
S4 = FOLDER / "s4_energy_steps.toml"
S7 = FOLDER / "s7_newton_euler_steps.toml"


@pytest.fixture(scope="module")
def s4():
    d = load_derivation(S4)
    return d, compare_steps(d, SEED)


@pytest.fixture(scope="module")
def s7():
    d = load_derivation(S7)
    return d, compare_steps(d, SEED)


def _by_equation(records, equation: str) -> dict[str, object]:
    out = {r.element: r for r in records if r.equation == equation}
    assert out, f"no records for {equation}"
    return out


def _verdicts(records, equation: str) -> dict[str, str]:
    return {e: r.verdict for e, r in _by_equation(records, equation).items()}


def _step(d, equation: str):
    (s,) = [s for s in d.steps if s.equation == equation]
    return s


def _vec(d, equation: str) -> sp.Matrix:
    return sp.Matrix(_step(d, equation).components)


# -- section 4 ---------------------------------------------------------------------------------

def test_eq15_velocity_of_frame_0_agrees(s4):
    """0V0 = [x-dot 0 0]: the middle of the axle moves at the heading speed, along frame 0's x
    axis (forward). It is right. It is compared as the velocity of the body link's origin, which
    is frame 0's origin because 0P1 = 0."""
    _, records = s4
    got = {e: v for e, v in _verdicts(records, "(15)").items() if "0V0" in e}
    assert got == {"(15) 0V0 x0": "agrees", "(15) 0V0 y0": "agrees", "(15) 0V0 z0": "agrees"}
    assert {r.step for r in _by_equation(records, "(15)").values() if "0V0" in r.element} == \
        {"velocity"}


def test_eq17_kinetic_energy_of_the_body_agrees(s4):
    """E1 = 1/2 (w1^T J_G1 w1 + M1 V1^T V1 + 2 MS1^T (V1 x w1)) is Khalil's kinetic energy of a
    link. J_G1 is the inertia at frame 1's origin, the XX1 ... ZZ1 that (25) is written in. It
    is right, worked out with the (right) 1w1, 1V1 of (16). It is compared for the link 'body'
    alone."""
    d, records = s4
    r = _by_equation(records, "(17)")["(17) E1 value"]
    assert (r.element, r.step, r.verdict) == ("(17) E1 value", "kinetic energy", "agrees")
    assert all(s.bodies == ("body",) for s in d.steps if s.equation == "(17)")


def test_eq17_comparison_is_not_vacuous(tmp_path):
    """The same E1 with the first-moment term written 2 MS1^T (w1 x V1), the cross product
    reversed, differs. The terms it names are x-dot psi-dot and x-dot phi-dot."""
    text = S4.read_text()
    wrong = text.replace("2*(MZ1*dx*dpsi - (MX1*sin(phi) + MY1*cos(phi))*dx*dphi)",
                         "-2*(MZ1*dx*dpsi - (MX1*sin(phi) + MY1*cos(phi))*dx*dphi)")
    assert wrong != text
    path = tmp_path / "s4_planted_steps.toml"
    path.write_text(wrong)
    (r,) = [r for r in compare_steps(load_derivation(path), SEED)
            if r.equation == "(17)" and "E1" in r.element]
    assert r.verdict == "differs"
    assert any(x.startswith(("term dx*dpsi", "term dpsi*dx")) for x in r.texts)


def _u1_record(tmp_path, value: str):
    r"""The record of a step file with the s4 file's tables and one step: U1 = ``value``."""
    text = S4.read_text().split("[[step]]")[0]           # the file's tables, no step
    text += ('[[step]]\nequation = "(17)"\nlabel = "U1"\nkind = "potential energy"\n'
             f'bodies = ["body"]\nvalue = "{value}"\n')
    path = tmp_path / "s4_u1_steps.toml"
    path.write_text(text)
    (r,) = compare_steps(load_derivation(path), SEED)
    return r


def test_potential_energy_u1_agrees(tmp_path):
    """U1 = -[0g^T 0] 0T1 [MS1; M1] with 0g = [0 -g 0] and the printed 0T1 is
    g (MX1 sin(phi) + MY1 cos(phi)). That is right: the height of the point (X, Y) of frame 1
    is X sin(phi) + Y cos(phi) above the axle. A potential energy is compared as a value, up
    to a constant (the document measures it from the axle's height)."""
    assert _u1_record(tmp_path, "g*(MX1*sin(phi) + MY1*cos(phi))").verdict == "agrees"


def _copy_records(tmp_path, text: str, name: str = "s4_copy_steps.toml"):
    path = tmp_path / name
    path.write_text(text)
    return compare_steps(load_derivation(path), SEED)


def _with_L(text: str) -> str:
    r"""The s4 file with the wheels' L/2 read as L (in (18), (19) and in E_L, E_R)."""
    out = text.replace("L/(2*R)", "L/R").replace("dpsi*L/2", "dpsi*L")
    assert out != text and "L/2" not in out.split("[[step]]", 1)[1]
    return out


@pytest.mark.parametrize("equation, label, body, sign", [("(18)", "E_L", "wheel_left", -1),
                                                         ("(19)", "E_R", "wheel_right", 1)])
def test_wheel_energies_differ_by_the_printed_L_over_2(s4, equation, label, body, sign):
    r"""E_L (E_R) worked out from the printed w_L, V_L (w_R, V_R) is the kinetic energy of the
    link wheel_left (wheel_right) alone. The printed wheel-centre speed is
    x-dot -+ psi-dot L/2. L is the half track, so the true speed is x-dot -+ L psi-dot, and the
    spin follows by rolling, w_z = -V/R. The energy's x-dot psi-dot coefficient is
    2 V_x V_psi (M_w + ZZw/R**2)/2 with V_psi = -+L/2 printed and -+L true: half the truth.
    The velocity steps of the same equation differ by the same 1/2 on their psi-dot term."""
    d, records = s4
    s = next(x for x in d.steps if x.label == label)
    assert s.bodies == (body,) and s.kind == "kinetic energy"
    r = _by_equation(records, equation)[f"{equation} {label} value"]
    assert r.verdict == "differs"
    assert "term dx*dpsi: factor: the document is 1/2 × the truth" in r.texts
    assert any(x.startswith("term dpsi*dpsi") for x in r.texts)
    assert not any(x.startswith("term dx*dx") for x in r.texts)     # x-dot alone is right
    for e, rec in _by_equation(records, equation).items():
        if rec.step in ("velocity", "angular velocity") and rec.verdict == "differs":
            assert rec.texts == ("term dpsi: factor: the document is 1/2 × the truth",), e
    # by hand, in the document's symbols (wheel axisymmetric, centred: only YYw, ZZw, Mw)
    dx, dpsi, L, R, Mw, YYw, ZZw = (d.symbol(n) for n in ("dx", "dpsi", "L", "R", "Mw", "YYw",
                                                           "ZZw"))

    def energy(V):
        return sp.Rational(1, 2) * (YYw * dpsi**2 + ZZw * (V / R)**2 + Mw * V**2)

    printed, true = energy(dx + sign * L / 2 * dpsi), energy(dx + sign * L * dpsi)
    c = [sp.expand(e).coeff(dx, 1).coeff(dpsi, 1) for e in (printed, true)]
    assert sp.simplify(c[0] - c[1] / 2) == 0
    zero = {d.symbol(n): 0 for n in ("YZw", "MYw", "MZw")}
    assert sp.simplify(s.components[0].xreplace(zero) - printed) == 0


def test_wheel_energies_agree_with_L_for_L_over_2(tmp_path):
    r"""The same file with the wheels' L/2 read as L: the wheel velocities, angular velocities
    and energies of (18), (19) all agree. The wheel's spin sign, frame 0's axes and J_Gw at
    the wheel's centre are right; only the L/2 is wrong."""
    records = _copy_records(tmp_path, _with_L(S4.read_text()))
    for equation in ("(18)", "(19)"):
        got = _verdicts(records, equation)
        assert len(got) == 7 and set(got.values()) == {"agrees"}, got


def test_wheel_energy_without_its_translation_term_differs(tmp_path):
    r"""E_L (L read as L) without M_w V_L^T V_L: the translational energy of the wheel is lost,
    so the x-dot**2, x-dot psi-dot and psi-dot**2 terms all differ (each keeps its ZZw/R**2 and
    YYw part, so none is missing outright)."""
    text = _with_L(S4.read_text())
    wrong = text.replace("  + Mw*(dx - dpsi*L)**2\n", "")
    assert wrong != text
    records = _copy_records(tmp_path, wrong)
    r = _by_equation(records, "(18)")["(18) E_L value"]
    assert r.verdict == "differs"
    assert {x.split(":")[0] for x in r.texts if x.startswith("term ")} == \
        {"term dx*dx", "term dx*dpsi", "term dpsi*dpsi"}
    assert _by_equation(records, "(19)")["(19) E_R value"].verdict == "agrees"


def test_eq15_angular_velocity_of_frame_0_agrees(s4):
    r"""0w0 = [0 psi-dot 0]: frame 0 turns with the heading only, about its y axis (up). It is
    the angular velocity of the heading frame itself (body = "heading")."""
    d, records = s4
    s = next(x for x in d.steps if x.label == "0w0")
    assert (s.body, s.kind) == ("heading", "angular velocity")
    got = {e: v for e, v in _verdicts(records, "(15)").items() if "0w0" in e}
    assert got == {"(15) 0w0 x0": "agrees", "(15) 0w0 y0": "agrees", "(15) 0w0 z0": "agrees"}


def test_eq15_angular_velocity_with_the_pitch_rate_differs(tmp_path):
    r"""0w0 = [0 psi-dot phi-dot] (the body's pitch rate given to frame 0): its z component
    differs, and the extra phi-dot term is named."""
    text = S4.read_text()
    wrong = text.replace('components = ["0", "dpsi", "0"]', 'components = ["0", "dpsi", "dphi"]')
    assert wrong.count('"dpsi", "dphi"]') == 1
    got = _by_equation(_copy_records(tmp_path, wrong), "(15)")
    assert [got[f"(15) 0w0 {n}"].verdict for n in ("x0", "y0", "z0")] == \
        ["agrees", "agrees", "differs"]
    assert "term dphi: extra term: the truth is 0" in got["(15) 0w0 z0"].texts


_HEADING_STEPS = """
[[step]]
equation = "(h)"
label = "O"
kind = "velocity"
body = "heading"
frame = "heading"
components = ["{v}", "0", "0"]

[[step]]
equation = "(h)"
label = "axle"
kind = "acceleration"
body = "heading"
point = ["0", "0", "R"]
frame = "heading"
components = ["ddx", "{a}", "0"]
"""


def test_heading_frame_origin_and_points(tmp_path):
    r"""The heading frame's origin (on the ground below the axle midpoint) moves at x-dot
    forward; its point [0, 0, R] (the axle midpoint) accelerates at x-double-dot forward and
    x-dot psi-dot to the left (the turning heading). Planted: a sideways L psi-dot in the
    speed and the centripetal term dropped."""
    head = S4.read_text().split("[[step]]")[0]
    right = _copy_records(tmp_path, head + _HEADING_STEPS.format(v="dx", a="dx*dpsi"))
    assert {r.verdict for r in right} == {"agrees"} and len(right) == 6
    wrong = _copy_records(tmp_path, head + _HEADING_STEPS.format(v="dx + L*dpsi", a="0"),
                          "s4_heading_wrong_steps.toml")
    got = {r.element: r for r in wrong}
    assert got["(h) O x"].verdict == "differs"
    assert "term dpsi: extra term: the truth is 0" in got["(h) O x"].texts
    assert got["(h) axle y"].verdict == "differs"
    assert "term dx*dpsi: missing: the document has 0" in got["(h) axle y"].texts


@pytest.mark.parametrize("step, item", [
    ('kind = "velocity"\nbody = "heading"\npoint = "com"\ncomponents = ["dx", "0", "0"]',
     "step 1 (h).point"),
    ('kind = "velocity"\nbody = "world"\ncomponents = ["dx", "0", "0"]', "step 1 (h).body"),
    ('kind = "kinetic energy"\nbodies = ["heading"]\nvalue = "0"', "step 1 (h).bodies"),
])
def test_heading_is_a_frame_not_a_link(tmp_path, step, item):
    r"""The heading frame has no centre of mass or contact point, the world is no body, and
    an energy is of links only: each is an error naming the step."""
    from wheeled_dyn.errors import WheeledDynError
    path = tmp_path / "s4_bad_steps.toml"
    path.write_text(S4.read_text().split("[[step]]")[0] +
                    f'[[step]]\nequation = "(h)"\n{step}\n')
    with pytest.raises(WheeledDynError) as err:
        load_derivation(path)
    assert err.value.item == item


# -- section 7.1 -------------------------------------------------------------------------------

def test_eq55_velocity_formula_agrees_and_is_56(s7):
    """v_B = v_xyz + omega_B x d is right. Worked out, it is exactly the printed (56)."""
    d, records = s7
    assert set(_verdicts(records, "(55)").values()) == {"agrees"}
    assert len(_by_equation(records, "(55)")) == 3
    assert sp.simplify(_vec(d, "(55)") - _vec(d, "(56)")) == sp.zeros(3, 1)


def test_eq64_acceleration_formula_agrees_but_65_differs(s7):
    """a_B = dv_xyz/dt + alpha_B x d + omega_B x (omega_B x d) (label lost in the text) is the
    right rigid-body formula, so it agrees. The error enters when it is worked out into (65).
    (65) j lacks x-dot psi-dot (dv_xyz/dt taken as x-double-dot i, i held fixed), and it has
    half the true 2 psi-dot phi-dot d cos(phi): it uses (61)'s alpha_B, which lacks
    -phi-dot psi-dot i."""
    _, records = s7
    assert _verdicts(records, "(64)") == {"(64) a_B i": "agrees", "(64) a_B j": "agrees",
                                          "(64) a_B k": "agrees"}
    j = _by_equation(records, "(65)")["(65) a_B j"]
    assert j.verdict == "differs"
    assert "term dx*dpsi: missing: the document has 0" in j.texts
    assert "term dpsi*dphi: factor: the document is 1/2 × the truth" in j.texts
    alpha = _by_equation(records, "(61)")
    assert alpha["(61) alpha_B i"].verdict == "differs"
    assert "term dpsi*dphi: missing: the document has 0" in alpha["(61) alpha_B i"].texts


def test_65_is_64_worked_out_with_61_and_a_fixed_heading(s7):
    """The diagnosis, checked in the document's own symbols: (64) evaluated with the printed
    omega_B (54), alpha_B (61) and dv_xyz/dt = x-double-dot i gives the printed (65) exactly."""
    d, _ = s7
    phi, dist, ddx = (d.symbol(n) for n in ("phi", "d", "ddx"))
    vec_d = dist * sp.Matrix([sp.sin(phi), 0, sp.cos(phi)])
    omega, alpha = _vec(d, "(54)"), _vec(d, "(61)")
    a = sp.Matrix([ddx, 0, 0]) + alpha.cross(vec_d) + omega.cross(omega.cross(vec_d))
    assert sp.simplify(a - _vec(d, "(65)")) == sp.zeros(3, 1)


def test_eq64_comparison_is_not_vacuous(tmp_path):
    """(64) worked out with (61)'s alpha_B instead of d omega_B/dt loses one of its two
    psi-dot phi-dot d cos(phi) terms in j, and the comparison says so."""
    text = S7.read_text()
    wrong = text.replace("(ddpsi*d*sin(phi) + dphi*dpsi*d*cos(phi))", "(ddpsi*d*sin(phi))")
    assert wrong != text
    path = tmp_path / "s7_planted_steps.toml"
    path.write_text(wrong)
    got = _by_equation(compare_steps(load_derivation(path), SEED), "(64)")
    assert [got[f"(64) a_B {n}"].verdict for n in "ijk"] == ["agrees", "differs", "agrees"]
    assert ("term dpsi*dphi: factor: the document is 1/2 × the truth"
            in got["(64) a_B j"].texts)


@pytest.mark.parametrize("formula, result, wheel", [("(66)", "(67)", "a_L"),
                                                    ("(68)", "(69)", "a_R")])
def test_wheel_acceleration_formulas_agree_but_67_69_differ(s7, formula, result, wheel):
    """a_L = dv_xyz/dt + alpha_xyz x O_xyzL + omega_xyz x (omega_xyz x O_xyzL), and a_R likewise,
    are right: the wheel centre at +-L j, the frame turning at psi-dot k. Worked out, they
    agree. The printed (67), (69) drop the x-dot psi-dot j of dv_xyz/dt: the centripetal part
    of the turning heading speed."""
    _, records = s7
    assert _verdicts(records, formula) == {f"{formula} {wheel} {n}": "agrees" for n in "ijk"}
    printed = _by_equation(records, result)
    assert [printed[f"{result} {wheel} {n}"].verdict for n in "ijk"] == \
        ["agrees", "differs", "agrees"]
    assert printed[f"{result} {wheel} j"].texts == ("term dx*dpsi: missing: the document has 0",)


def test_potential_energy_with_a_wrong_term_differs(tmp_path):
    r"""The same U1 with cos and sin exchanged in its second term differs: the constant that
    is allowed cannot absorb a term that changes with the pitch."""
    assert _u1_record(tmp_path, "g*(MX1*sin(phi) + MY1*sin(phi))").verdict == "differs"


def test_a_swap_in_a_potential_energy_is_named(tmp_path):
    r"""U1 with sin and cos exchanged: the trial readings are levelled as the truth is (a
    potential is measured from any level), so the swap that fits is named."""
    r = _u1_record(tmp_path, "g*(MX1*cos(phi) + MY1*sin(phi))")
    assert r.verdict == "differs"
    assert any(x.startswith("swap:") and "sin(phi)" in x and "cos(phi)" in x
               for x in r.texts), r.texts


def test_shipped_u1_agrees():
    r"""The shipped step file compares U1 of (17) as well: it agrees up to a constant."""
    records = compare_steps(load_derivation(S4), SEED)
    (u1,) = [r for r in records if r.equation == "(17)" and "U1" in r.element]
    assert u1.verdict == "agrees", u1.texts


def test_eq15_gravity_and_orientation_of_frame_1_agree(s4):
    r"""(15)'s 0g = [0 -g 0] along frame 0's axes (y up) and the rotation part 0A1 of 0T1 (a
    rotation by phi about the axle z) agree: nine entries and three components."""
    _, records = s4
    got = {e: r.verdict for e, r in _by_equation(records, "(15)").items()
           if e.startswith(("(15) 0g", "(15) 0A1"))}
    assert len(got) == 12 and set(got.values()) == {"agrees"}, got


@pytest.mark.parametrize("old,new,element", [
    ('components = ["cos(phi)", "-sin(phi)", "0",', 'components = ["cos(phi)", "sin(phi)", "0",',
     "(15) 0A1 [1,2]"),
    ('components = ["0", "-g", "0"]', 'components = ["0", "g", "0"]', "(15) 0g y0"),
])
def test_eq15_planted_sign_in_0A1_or_0g_is_named(tmp_path, old, new, element):
    text = S4.read_text()
    assert text.count(old) == 1
    records = {r.element: r for r in _copy_records(tmp_path, text.replace(old, new))}
    r = records[element]
    assert r.verdict == "differs" and r.texts[0].startswith("sign"), r.texts
    others = [e for e, x in records.items() if e.startswith("(15)") and x.verdict != "agrees"]
    assert others == [element]


def test_an_orientation_is_nine_components(tmp_path):
    from wheeled_dyn.errors import DerivationError
    text = S4.read_text().replace('"0", "0", "1"]', '"0", "0"]', 1)
    path = tmp_path / "s4_bad_steps.toml"
    path.write_text(text)
    with pytest.raises(DerivationError) as err:
        load_derivation(path)
    assert "step 4 (15).components" in str(err.value) and "nine components" in str(err.value)
    assert err.value.line is not None
