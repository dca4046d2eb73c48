r"""Linearised equations solved for the accelerations, :math:`\ddot q = -M^{-1}K q + M^{-1}B u`
(the form a controller's design starts from, and the velocity rows of :math:`\dot x = A x +
B u`): an error made before solving spreads over a whole column of the solved stiffness or
inputs, and is named where it was made, in the equations read back before solving
(:math:`M` times the document's rows).

Before, the stiffness was not among the entries read back: a symbol written for another in
one stiffness made the three solved entries of its column differ by one ratio, and the report
blamed "the divisor the solved equations share — the determinant" (which was right); an
input's sign or a dropped reaction got "no single-term diagnosis".

The balancer with a motorised torso (``data/torso_balancer``), linearised about upright, in
the form of Li, Yang & Fan (Springer 2013): its inertia, stiffness and inputs at the point,
and the inverse written with the adjugate over the determinant, as the document does.
"""

from __future__ import annotations

import re
from pathlib import Path

import pytest

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import DiagnosisKind, Verdict
from wheeled_dyn.derivations import load_derivation

DATA = Path(__file__).parent / "data" / "torso_balancer"

SOLVED = '''
[definitions]
a11 = "2*J_w/r**2 + m_1 + m_2 + 2*m_w"
a12 = "l_1*m_2 + l_c1*m_1"
a13 = "l_c2*m_2"
a22 = "I_1 + l_1**2*m_2 + l_c1**2*m_1"
a23 = "l_1*l_c2*m_2"
a33 = "I_2 + l_c2**2*m_2"
k2 = "-g*(l_1*m_2 + l_c1*m_1)"
k3 = "-g*l_c2*m_2"
b2 = "-1"
det = "a11*(a22*a33 - a23**2) - a12*(a12*a33 - a23*a13) + a13*(a12*a23 - a22*a13)"
i11 = "(a22*a33 - a23**2)/det"
i12 = "(a13*a23 - a12*a33)/det"
i13 = "(a12*a23 - a13*a22)/det"
i22 = "(a11*a33 - a13**2)/det"
i23 = "(a12*a13 - a11*a23)/det"
i33 = "(a11*a22 - a12**2)/det"

[matrices]
equations = [
  "ddx = -i12*k2*th1 - i13*k3*th2 + (i11/r + i12*b2)*tau + (i13 - i12)*tau_h",
  "ddth1 = -i22*k2*th1 - i23*k3*th2 + (i12/r + i22*b2)*tau + (i23 - i22)*tau_h",
  "ddth2 = -i23*k2*th1 - i33*k3*th2 + (i13/r + i23*b2)*tau + (i33 - i23)*tau_h",
]
'''

#: Planted errors, each made before solving: the text replaced, the element the read-back
#: names, the kind it says (None: the reaction's sign, said on B[2,1]).
PLANTED = {
    "l_c2 for l_1 in k2": ('k2 = "-g*(l_1*m_2', 'k2 = "-g*(l_c2*m_2', "K[2,2]",
                           DiagnosisKind.SWAP),
    "wheel reaction's sign": ('b2 = "-1"', 'b2 = "1"', None, None),
    "l_c1 for l_c2 in a13": ('a13 = "l_c2*m_2"', 'a13 = "l_c1*m_2"', "A[1,3]",
                             DiagnosisKind.SWAP),
}


def _file(tmp_path: Path, old: str = "", new: str = "", hip: bool = True) -> Path:
    r"""The solved linearisation; without ``hip``, the hip motor idle (its torque 0): the
    wheels' torque alone, one input for three coordinates, as a controller of the wheels
    alone reads the robot."""
    head = (DATA / "torso_balancer_hip.toml").read_text().split("[matrices]")[0]
    head = head.replace("[assumes]\n", "[assumes]\nlinearised_about = "
                        "{ x = 0.0, th1 = 0.0, th2 = 0.0 }\n")
    text = head + SOLVED
    if not hip:
        text = re.sub(r" \+ \([^()]*\)\*tau_h", "", text.replace('tau_hip = "tau_h"',
                                                                   'tau_hip = "0"'))
        text = "\n".join(line for line in text.splitlines() if not line.startswith("tau_h "))
        assert "*tau_h" not in text and "tau_h =" not in text
    if old:
        assert old in text, old
        text = text.replace(old, new)
    for name in ("torso_balancer.toml", "torso_balancer.urdf"):
        (tmp_path / name).write_text((DATA / name).read_text())
    path = tmp_path / "solved.toml"
    path.write_text(text)
    return path


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=200, param_sets=3, seed=SEED)


@pytest.mark.parametrize("hip", [True, False])
def test_the_right_solved_linearisation_agrees(engine, tmp_path, hip):
    result = engine.compare(load_derivation(_file(tmp_path, hip=hip)))
    assert result.equivalent is True, [c.explanation for c in result.causes]


@pytest.mark.parametrize("hip", [True, False])
@pytest.mark.parametrize("error", sorted(PLANTED))
def test_an_error_made_before_solving_is_named_where_it_was_made(engine, tmp_path, error, hip):
    old, new, where, kind = PLANTED[error]
    result = engine.compare(load_derivation(_file(tmp_path, old, new, hip)))
    assert result.equivalent is False
    differing = [r for r in result.records if r.verdict == Verdict.DIFFERS]
    assert differing
    kinds = {d.kind for r in differing for d in r.diagnoses}
    assert DiagnosisKind.COMMON_DIVISOR not in kinds          # the determinant is right
    said = " ".join(d.text for r in differing for d in r.diagnoses)
    assert "no single-term diagnosis" not in said, said
    if where is not None:
        assert f"{where}:" in said, said
        assert kind in kinds, said
    else:                                  # the reaction's sign: B[2,1] read back
        assert "B[2,1]:" in said and DiagnosisKind.SIGN in kinds, said
