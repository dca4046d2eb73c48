r"""A body's inertia about its centre of mass written where the one about the joint's axis fits
is named as the missing parallel-axis term, not as a point mass.

The uniform rod hinged at one end (seed 000's 4.4; its mass and length drawn): about the hinge
I = m l²/3 = m l²/12 (about its centre) + m (l/2)² (the parallel-axis theorem; Meriam &
Kraige, *Engineering Mechanics: Dynamics*, §B/1). A document writing m l²/12 lacks m l²/4,
which for a uniform rod is also 3 × its own moment: the exact fit, the parallel-axis term, is
named. A document writing the rod as a point mass at its centre, m l²/4, lacks its own
moment m l²/12: a point mass. The compound pendulum (a bar whose centre is off its axis in two
directions, a along it and b across) written with I_G + m b² lacks the part m a² of its
parallel-axis term."""

from __future__ import annotations

import sympy as sp

import wheeled_dyn as wd
from wheeled_dyn.compare.records import CauseKind, DiagnosisKind as K, Verdict

m, l, g, theta = sp.symbols("m l g theta")
ROD = {"m": "M(rod)", "l": "length(rod)", "g": "g"}
Q_ROD = sp.Matrix([m * g * l / 2 * sp.sin(theta)])
COORDS = {"positions": ["theta"], "configuration": {"theta": "theta"}}


def _rod(inertia):
    result = wd.compare("rod_pendulum", coordinates=COORDS, A=sp.Matrix([[inertia]]),
                        C=sp.zeros(1, 1), Q=Q_ROD, symbols=ROD, assumes={"uniform": ["rod"]})
    (a,) = [r for r in result.records if r.element == "A[1,1]"]
    return a, result


def test_the_rod_about_its_hinge_agrees():
    a, _ = _rod(m * l**2 / 3)
    assert a.verdict == Verdict.AGREES


def test_the_rod_about_its_centre_lacks_the_parallel_axis_term():
    a, result = _rod(m * l**2 / 12)
    assert a.verdict == Verdict.DIFFERS
    assert a.diagnoses[0].kind == K.PARALLEL_AXIS
    assert sp.sympify(a.diagnoses[0].terms[0]) - m * l**2 / 4 == 0
    assert not any(d.kind in (K.POINT_MASS, K.FACTOR) for d in a.diagnoses)
    assert [c.kind for c in result.causes if "A[1,1]" in c.elements] == \
        [CauseKind.PARALLEL_AXIS]


def test_the_rod_as_a_point_mass_lacks_its_own_moment():
    a, _ = _rod(m * l**2 / 4)
    assert a.verdict == Verdict.DIFFERS
    assert a.diagnoses[0].kind == K.POINT_MASS
    assert not any(d.kind == K.PARALLEL_AXIS for d in a.diagnoses)


def test_the_compound_pendulum_lacks_one_part_of_its_parallel_axis_term():
    mm, a, b, ig = sp.symbols("m a b I_g")
    result = wd.compare(
        "compound_pendulum", coordinates=COORDS,
        A=sp.Matrix([[ig + mm * b**2]]), C=sp.zeros(1, 1),
        Q=sp.Matrix([mm * g * (a * sp.sin(theta) + b * sp.cos(theta))]),
        symbols={"m": "M(body)", "a": "-CZ(body)", "b": "CX(body)", "I_g": "IYY(body)",
                 "g": "g"}, assumes={"families": ["urdf_structure"]})
    (r,) = [r for r in result.records if r.element == "A[1,1]"]
    assert r.verdict == Verdict.DIFFERS and r.diagnoses[0].kind == K.PARALLEL_AXIS
    assert sp.sympify(r.diagnoses[0].terms[0]) - mm * a**2 == 0
    assert all(x.verdict == Verdict.AGREES for x in result.records if x is not r)
