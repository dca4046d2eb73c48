r"""The frame a wrong equation is explained in is the one its author wrote, so that the planted
term is named and the right elements agree.

- The compound pendulum solved for its one acceleration, θ̈ = −m g a sin θ/(I_G + m a²)
  (Meriam & Kraige, *Engineering Mechanics: Dynamics*, the compound pendulum; the
  parallel-axis theorem gives the pivot's inertia I_G + m a²), with a factor 2, a sign or a
  power planted on its right side: the solved form's frame (row of A⁻¹, read from the form,
  nothing fitted) is taken, A[1,1] = 1 agrees and the planted error is named on Q[1]. Before,
  the identity frame tied with it and A[1,1] was flagged with no diagnosis.
- The WIP's yaw equation (seed 001's model in its coordinates, no products of inertia, the
  centre of mass on the axis) with its left side multiplied by r/L and its input side not:
  the row's inertia and velocity terms agree in the r/L frame (a simple ratio, as good as a
  constant however many elements share it) and only the inputs differ. Before, the identity
  frame tied with it and a Boltzmann–Hamel cause was invented for the scaled terms.
"""

from __future__ import annotations

import pytest

from wheeled_dyn.compare import ComparisonEngine
from wheeled_dyn.compare.records import CauseKind, DiagnosisKind as K, Verdict
from wheeled_dyn.derivations import load_derivation

from conftest import SEED

#: Small grid: the frames are structural.
SAMPLES, PARAM_SETS = 200, 2

PENDULUM = """title = "compound pendulum, solved for its acceleration"
model = "compound_pendulum"
[coordinates]
positions = ["theta"]
configuration = {{ theta = "theta" }}
units = {{ theta = "rad" }}
[symbols]
m = {{ value = "M(body)", units = "kg" }}
a = {{ value = "-CZ(body)", units = "m" }}
I_g = {{ value = "IYY(body)", units = "kg*m**2" }}
g = {{ value = "g", units = "m/s**2" }}
[assumes]
families = ["urdf_structure"]
[matrices]
equations = ["ddtheta = {rhs}"]
"""

WIP = """title = "WIP, the yaw equation multiplied by r/L"
model = "wip"
[coordinates]
use = "seed001"
[inputs]
tau_l = "u_l"
tau_r = "u_r"
[symbols]
m = {{ value = "m_S", units = "kg" }}
m_w = {{ value = "m_C", units = "kg" }}
r = {{ value = "R", units = "m" }}
L = {{ value = "L", units = "m" }}
d = {{ value = "d", units = "m" }}
I1 = {{ value = "I1", units = "kg*m**2" }}
I2 = {{ value = "I2", units = "kg*m**2" }}
I3 = {{ value = "I3", units = "kg*m**2" }}
J = {{ value = "Iw3", units = "kg*m**2" }}
K = {{ value = "Iw2", units = "kg*m**2" }}
g = {{ value = "g", units = "m/s**2" }}
u_l = {{ input = true, units = "N*m" }}
u_r = {{ input = true, units = "N*m" }}
[assumes]
families = ["no_products", "com_on_axis", "no_armature"]
[matrices]
equations = [
  "(m + 2*m_w + 2*J/r**2)*ddx - m*d*cos(phi)*ddphi + m*d*sin(phi)*(dpsi**2 + dphi**2) = -(u_l + u_r)/r",
  "r/L*(I1*sin(phi)**2 + I2*cos(phi)**2 + 2*K + 2*J*L**2/r**2 + 2*m_w*L**2 + m*d**2*sin(phi)**2)*ddpsi - r/L*m*d*sin(phi)*dx*dpsi + 2*r/L*(I1 - I2 + m*d**2)*sin(phi)*cos(phi)*dpsi*dphi = {yaw_input}",
  "-m*d*cos(phi)*ddx + (I3 + m*d**2)*ddphi - (I1 - I2 + m*d**2)*sin(phi)*cos(phi)*dpsi**2 - m*g*d*sin(phi) = -(u_l + u_r)"]
"""


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)


def _records(engine, tmp_path, text):
    path = tmp_path / "doc.toml"
    path.write_text(text)
    result = engine.compare(load_derivation(path))
    return {r.element: r for r in result.records}, result


def test_the_solved_pendulum_agrees(engine, tmp_path):
    records, _ = _records(engine, tmp_path, PENDULUM.format(
        rhs="-m*g*a*sin(theta)/(I_g + m*a**2)"))
    assert all(r.verdict == Verdict.AGREES for r in records.values())


@pytest.mark.parametrize("rhs,kind", [
    ("-2*m*g*a*sin(theta)/(I_g + m*a**2)", K.FACTOR),
    ("m*g*a*sin(theta)/(I_g + m*a**2)", K.SIGN),
    ("-m*g*a*sin(theta)/(I_g + m*a)", K.DIMENSION)])
def test_an_error_in_the_solved_pendulum_is_named_where_it_is(engine, tmp_path, rhs, kind):
    records, result = _records(engine, tmp_path, PENDULUM.format(rhs=rhs))
    assert records["A[1,1]"].verdict == Verdict.AGREES
    assert records["Q[1]"].verdict == Verdict.DIFFERS
    assert any(d.kind == kind for d in records["Q[1]"].diagnoses)
    if kind == K.FACTOR:
        assert [d.factor for d in records["Q[1]"].diagnoses if d.kind == K.FACTOR] == ["2"]


def test_the_scaled_yaw_row_agrees_with_its_inputs_scaled(engine, tmp_path):
    records, _ = _records(engine, tmp_path, WIP.format(yaw_input="u_l - u_r"))
    assert all(r.verdict == Verdict.AGREES for r in records.values())


def test_a_yaw_row_scaled_on_its_left_side_only_flags_its_inputs(engine, tmp_path):
    records, result = _records(engine, tmp_path, WIP.format(yaw_input="L*(u_l - u_r)/r"))
    differing = {e for e, r in records.items() if r.verdict != Verdict.AGREES}
    assert differing == {"B[2,1]", "B[2,2]"}
    assert not any(c.kind == CauseKind.QUASI_COORDINATE_CHRISTOFFEL for c in result.causes)
