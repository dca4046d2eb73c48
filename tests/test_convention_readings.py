r"""Readings of a file whose convention is unknown or declared wrongly. An angle measured from
the opposite direction: the cart-pole's equations (Florian 2007,
:mod:`published_forms`) written for :math:`\theta' = \theta + \pi` or :math:`\pi - \theta` —
the pole's angle from the upright where the model's joint measures it from the hanging
position, or the other way — while the file's map says ``theta = "theta"``.

Declared, the equations are not the model's (declarations are binding), and the cause now
says the reading that makes them right, θ → θ + π (it named the sign of every term that
changes: the gravity, the coupling, the centripetal term). With ``convention = "unknown"``
they are compared under that reading and agree; a real error planted beside the offset still
differs under it.
"""

from __future__ import annotations

from pathlib import Path

import published_forms as P
import pytest
import sympy as sp
from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import CauseKind, Verdict
from wheeled_dyn.derivations import load_derivation

#: Engine grid.
SAMPLES, PARAM_SETS = 300, 3
#: The document's angle in the model's: (the substitution that writes the equations in it —
#: its rates too —, how the reading is said).
OFFSETS = {"plus": ({P.th: P.th + sp.pi}, "theta → theta + π"),
           "minus": ({P.th: sp.pi - P.th, P.dth: -P.dth, P.ddth: -P.ddth},
                     "theta → π − theta")}


def _write(folder: Path, form: str, offset: str, unknown: bool, error: str | None = None
           ) -> Path:
    r"""The cart-pole's ``form`` (with the planted ``error``) written in the document's angle
    of ``offset``, the file's map unchanged."""
    path = P.write(folder, "pole", form, error)
    head, body = path.read_text().split("equations = [")
    angle, _ = OFFSETS[offset]
    written = []
    for line in (x.strip().rstrip(",").strip('"') for x in body.splitlines()
                 if x.strip().startswith('"')):
        names = {"theta": P.th, "dtheta": P.dth, "ddtheta": P.ddth, "M": P.M}
        sides = [sp.sympify(x, locals=names) for x in line.split(" = ")]
        written.append(" = ".join(sp.sstr(sp.simplify(x.subs(angle, simultaneous=True)))
                                  for x in sides))
    if unknown:
        head = head.replace("[coordinates]", 'convention = "unknown"\n[coordinates]')
    path.write_text(head + "equations = [\n" + ",\n".join(f'  "{e}"' for e in written)
                    + "\n]\n")
    return path


def _compare(path: Path):
    engine = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)
    return engine.compare(load_derivation(path))


@pytest.mark.parametrize("form", ["equations", "solved"])
def test_declared_the_reading_is_the_cause(tmp_path, form):
    result = _compare(_write(tmp_path, form, "plus", unknown=False))
    assert result.equivalent is False
    first = result.causes[0]
    assert first.kind == CauseKind.CONVENTION, [c.explanation for c in result.causes]
    assert OFFSETS["plus"][1] in first.explanation
    assert "measured from the opposite direction" in first.explanation


def test_declared_pi_minus_theta_is_one_terms_sign(tmp_path):
    r"""Written for π − θ, the cart-pole's cart equation is unchanged and its pole equation
    is the true one times −1 but for its gravity term's sign: one element, as a sign error
    would be; declared, that is its cause (the simpler reading)."""
    result = _compare(_write(tmp_path, "equations", "minus", unknown=False))
    assert result.equivalent is False
    assert [r.element for r in result.records if r.verdict == Verdict.DIFFERS] == ["Q[2]"]
    assert result.causes[0].kind == CauseKind.SIGN, result.causes


@pytest.mark.parametrize("offset", sorted(OFFSETS))
@pytest.mark.parametrize("form", ["equations", "solved"])
def test_unknown_it_is_compared_under_the_reading(tmp_path, form, offset):
    result = _compare(_write(tmp_path, form, offset, unknown=True))
    assert result.equivalent is True, result.equations
    assert OFFSETS[offset][1] in result.causes[0].explanation


def test_a_real_error_beside_the_offset_still_differs(tmp_path):
    result = _compare(_write(tmp_path, "equations", "plus", unknown=True, error="sign"))
    assert result.equivalent is False
    assert OFFSETS["plus"][1] in result.causes[0].explanation
    wrong = [r.element for r in result.records if r.verdict == Verdict.DIFFERS]
    assert wrong == ["h[1]:dtheta*dtheta"], wrong


def test_inputs_of_other_units_are_never_read_as_exchanged(tmp_path):
    r"""A cart-pole with a force on the cart (N) and a torque at the hinge (N·m), its
    equations written with the torque in the cart's equation and the force in the pole's:
    wrong, whatever the convention — a torque is no force. With ``convention = "unknown"`` the
    search had read it as "tau ↔ F" and it agreed (with its units blamed on the file)."""
    import shutil
    from pathlib import Path
    from wheeled_dyn.compare.engine import ComparisonEngine
    from wheeled_dyn.derivations import load_derivation
    data = Path(__file__).parent / "data" / "published"
    for name in ("cart_pole_driven.toml", "cart_pole.urdf"):
        shutil.copy(data / name, tmp_path / name)
    text = (data / "cart_pole_driven_solved.toml").read_text()
    head = text[:text.index("equations = [")]
    swapped = ('equations = [\n'
               '  "(M + m)*ddx + m*l*cos(theta)*ddtheta - m*l*sin(theta)*dtheta**2 = tau",\n'
               '  "m*l*cos(theta)*ddx + 4*m*l**2/3*ddtheta - m*g*l*sin(theta) = F"\n]\n')
    right = swapped.replace("= tau", "= TAU").replace("= F", "= tau").replace("= TAU", "= F")
    for equations, agrees in ((right, True), (swapped, False)):
        doc = tmp_path / "driven.toml"
        doc.write_text(head.replace("[coordinates]", 'convention = "unknown"\n[coordinates]')
                       + equations)
        result = ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(
            load_derivation(doc))
        assert result.equivalent is agrees, (equations, result.equations)
        assert not any("↔" in c.explanation for c in result.causes), result.causes


def test_one_terms_sign_is_not_an_angle_from_the_other_side(tmp_path):
    r"""A rod pendulum (derivation-format.md's example) with its gravity term's sign wrong:
    θ → θ + π would make it right too, but one element is one term's error: the cause is
    its sign, not the angle measured from the upright."""
    doc = tmp_path / "rod.toml"
    doc.write_text(P.ROD.format(gravity="- m*g*l/2*sin(theta)"))
    result = _compare(doc)
    assert result.equivalent is False
    assert [c.kind for c in result.causes] == [CauseKind.SIGN], result.causes


def _planted_forms(tmp_path: Path, name: str, coupling: sp.Expr, gravity: sp.Expr,
                   form: str) -> Path:
    r"""The cart-pole (Florian's equations) with the coupling and the pole's gravity term
    given, written ``solved`` or ``combined`` (the cart's equation less 3 cos θ/(4l) × the
    pole's)."""
    cart = (P.M + P.m) * P.ddx + coupling * P.ddth - P.m * P.l * P.dth ** 2 * sp.sin(P.th) - P.F
    pole = coupling * P.ddx + sp.Rational(4, 3) * P.m * P.l ** 2 * P.ddth - gravity
    if form == "solved":
        (sol,) = sp.solve([cart, pole], [P.ddx, P.ddth], dict=True)
        eqs = [f"ddx = {P._s(sp.simplify(sol[P.ddx]))}",
               f"ddtheta = {P._s(sp.simplify(sol[P.ddth]))}"]
    else:
        eqs = [f"{P._s(cart)} - (3*cos(theta)/(4*l))*({P._s(pole)}) = 0", f"{P._s(pole)} = 0"]
    path = tmp_path / f"{name}_{form}.toml"
    path.write_text(P.POLE_HEAD.format(form=form, error=f", {name}",
                                       model=P.DATA / "cart_pole.toml",
                                       eqs=",\n".join(f'  "{e}"' for e in eqs)))
    return path


@pytest.mark.parametrize("form", ["solved", "combined"])
@pytest.mark.parametrize("error", ["gravity_sign", "coupling_sign"])
def test_one_wrong_entry_is_no_reading_of_the_positions(tmp_path, form, error):
    r"""One term wrong in the equations before they were solved or combined — the pole's
    gravity sign, or the coupling's sign in both equations — reads as π − θ, or −θ, too: it
    is said as the term's error, not as the file's angles measured from the other side."""
    coupling = P.m * P.l * sp.cos(P.th) * (-1 if error == "coupling_sign" else 1)
    gravity = P.m * P.g * P.l * sp.sin(P.th) * (-1 if error == "gravity_sign" else 1)
    result = _compare(_planted_forms(tmp_path, error, coupling, gravity, form))
    assert result.equivalent is False
    assert not any("→" in c.explanation for c in result.causes), \
        [c.explanation for c in result.causes]
    assert any(c.kind == CauseKind.SIGN for c in result.causes), result.causes
