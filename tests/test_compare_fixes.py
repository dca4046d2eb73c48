"""Correctness of the comparison on derivations that are right but written unusually, and on
values it cannot decide.

- ``atan2(y, x)`` of two lengths is dimensionless: a phase form of Q (the amplitude and
  phase of :math:`MX_1\\cos\\varphi - MY_1\\sin\\varphi`) agrees, with no dimension finding;
- an element that is not finite at some samples is *undecided*, never *agrees*;
- the power identity of quasi-velocity files differentiates A along the motion: the rate of
  each position follows from the file's configuration and velocity map (Euler angles' rates
  from body rates), checked against the closed form.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from wheeled_dyn.compare.judge.document_checks import position_rates
from wheeled_dyn.derivations import builtin_derivations, load_derivation

from test_compare_planted import _others_agree, _planted, _records, engine  # noqa: F401

#: Phase form of the true Q[3] = g (MX1 cos φ − MY1 sin φ) = g r cos(φ + atan2(MY1, MX1)).
PHASE_Q3 = "g*sqrt(MX1**2 + MY1**2)*cos(phi + atan2(MY1, MX1))"
#: The true A[3,3] plus a term that is 0 where it is defined and NaN for φ < 0.
NAN_A33 = "ZZ1 + 2*I_a + log(2*phi) - log(phi) - log(2)"


def test_atan2_phase_form_agrees_without_dimension_finding(engine, tmp_path):  # noqa: F811
    result = engine.compare(load_derivation(_planted(tmp_path, {("Q", 2): PHASE_Q3})))
    r = _records(result)["Q[3]"]
    assert r.verdict == "agrees", r.texts
    assert not any(x.startswith("dimension") for x in r.texts), r.texts
    _others_agree(result, set())


def test_non_finite_element_is_undecided(engine, tmp_path):  # noqa: F811
    result = engine.compare(load_derivation(_planted(tmp_path, {("A", 2, 2): NAN_A33})))
    r = _records(result)["A[3,3]"]
    assert r.verdict == "undecided", (r.verdict, r.texts)
    assert r.texts[0].startswith("undecided: the document's values are not finite")
    assert result.counts()["undecided"] >= 1 and result.counts()["agrees"] < len(result.records)


def test_position_rates_of_euler_angles_from_body_rates():
    r"""ZYX Euler angles with body rates (p, q, r): the rates solved from the file's
    configuration and velocity map equal the textbook kinematics
    :math:`\dot\psi = (q\sin\phi + r\cos\phi)/\cos\theta`,
    :math:`\dot\theta = q\cos\phi - r\sin\phi`,
    :math:`\dot\phi = p + (q\sin\phi + r\cos\phi)\tan\theta`."""
    path = next(p for p in builtin_derivations("seed000") if p.name.startswith("p7_2"))
    d = load_derivation(path)
    rates = position_rates(d)
    yaw, pitch, roll = (d.symbol(n) for n in ("yaw", "pitch", "roll"))
    p, q, r = (d.symbol(n) for n in ("p", "q", "r"))
    expected = {yaw: (q * sp.sin(roll) + r * sp.cos(roll)) / sp.cos(pitch),
                pitch: q * sp.cos(roll) - r * sp.sin(roll),
                roll: p + (q * sp.sin(roll) + r * sp.cos(roll)) * sp.tan(pitch)}
    rng = np.random.default_rng(7)
    for _ in range(5):
        point = dict(zip((yaw, pitch, roll, p, q, r), rng.uniform(-1.2, 1.2, 6)))
        for k, want in expected.items():
            assert abs(float(rates[k].xreplace(point)) - float(want.xreplace(point))) < 1e-12


def test_position_rates_of_a_quasi_heading_speed_file():
    r"""Kim's rewritten equations: ψ̇ and θ̇ are velocities of the file; x (distance along the
    heading) has no rate of its own (None)."""
    path = next(p for p in builtin_derivations("seed001") if p.name == "kim_eq6_8.toml")
    d = load_derivation(path)
    rates = position_rates(d)
    assert rates[d.symbol("psi")] == d.symbol("dpsi")
    assert rates[d.symbol("theta")] == d.symbol("dtheta")
    assert rates[d.symbol("x")] is None
