r"""A wrong term named as the document has it, and no reading that only makes it vanish.

- A term the document has too much is named with the document's sign (a probe's
  :math:`+m_1h_1^2` was "too much :math:`-h_1^2m_1`"), and a small length's term is extra, not
  "to another power" (:math:`h_1^2` where :math:`h_1^4` fits only made it negligible).
- A term the document lacks is lacking even where the element writes another term of the same
  function of the positions with the other sign (a probe's balancer lacking
  :math:`I_{xz}\cos 2\theta` beside :math:`-m_bx_bz_b\cos 2\theta` was "too much").
- A symbol read as another parameter of its link is a cause only where the equations are
  judged as the decision judged them (a linearised document's wrong stiffness was "right with
  J2yy = IYY(pend)", a symbol its equations do not write), and never as a parameter that is 0
  in every parameter set (its terms vanish; they are not read right).

The rod is seed 000's 4.4 (the shipped ``rod_pendulum``: :math:`\tfrac13ml^2\ddot\theta +
\tfrac12mgl\sin\theta = 0`, its radius 0.01 m); the balancer, the project's ROS balancer
(``tests/data/ros_balancer``, its matrices from Kane's equations: ``tests/ros_kane.py``).
"""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import CauseKind, DiagnosisKind as K
from wheeled_dyn.derivations import load_derivation

from test_equivalence import ROD as EQUIVALENCE_ROD

SAMPLES, PARAM_SETS = 200, 3
DATA = Path(__file__).parent / "data"

#: test_equivalence's rod file, with the rod's radius and room for more symbols.
ROD = EQUIVALENCE_ROD.replace('g = {{ value = "g", units = "m/s**2" }}\n',
                              'g = {{ value = "g", units = "m/s**2" }}\n'
                              'r = {{ value = "radius(rod)", units = "m" }}\n{symbols}\n')
assert "{symbols}" in ROD


def _compare(tmp_path, name, equation, symbols="", assumes=""):
    path = tmp_path / f"{name}.toml"
    path.write_text(ROD.format(name=name, equation=equation, symbols=symbols, assumes=assumes))
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED).compare(
        load_derivation(path))


def _record(result, element):
    return next(r for r in result.records if r.element == element)


@pytest.mark.parametrize("sign", ["+", "-"])
def test_a_small_terms_extra_not_to_another_power(tmp_path, sign):
    result = _compare(tmp_path, "extra", f"(1/3*m*l**2 {sign} m*r**2)*ddtheta "
                                         "+ m*g*l/2*sin(theta) = 0")
    record = _record(result, "A[1,1]")
    assert record.verdict == "differs"
    kinds = [x.kind for x in record.diagnoses]
    assert K.POWER not in kinds, record.diagnoses
    extra = next(x for x in record.diagnoses if x.kind == K.EXTRA)
    assert extra.terms == ((f"{'-' if sign == '-' else ''}m*r**2",)), extra


def test_a_dropped_term_lacks_beside_another_of_its_function(tmp_path):
    text = (DATA / "ros_balancer" / "ros_balancer_heading.toml").read_text()
    right = "(I_xz*cos(2*theta) - (I_xx - I_zz)*sin(2*theta)/2"
    assert text.count(right) == 1
    path = tmp_path / "ros_balancer_heading.toml"
    path.write_text(text.replace(right, "(-(I_xx - I_zz)*sin(2*theta)/2"))
    (tmp_path / "ros_balancer.toml").write_text(
        (DATA / "ros_balancer" / "ros_balancer.toml").read_text().replace(
            'path = "ros_balancer.urdf"', f'path = "{DATA / "ros_balancer" / "ros_balancer.urdf"}"'))
    result = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED).compare(
        load_derivation(path))
    record = _record(result, "h[3]:dpsi*dpsi")
    named = next(x for x in record.diagnoses if x.kind in (K.MISSING, K.EXTRA))
    assert named.kind == K.MISSING and named.terms == ("I_xz*cos(2*theta)",), named


LINEAR = "linearised_about = { theta = 0.0 }"


@pytest.mark.parametrize("symbol, equation", [
    # a symbol the equation writes, whose other axis (XX = YY on the rod) keeps its A right
    ('I = { value = "YY(rod)", units = "kg*m**2" }', "I*ddtheta + 5*m*g*l*theta = 0"),
    # a symbol it does not write
    ('J = { value = "XX(rod)", units = "kg*m**2" }', "1/3*m*l**2*ddtheta + 5*m*g*l*theta = 0"),
    # a symbol mapped wrong as well: read right, its A is right and its K still not
    ('I = { value = "ZZ(rod)", units = "kg*m**2" }', "I*ddtheta + 5*m*g*l*theta = 0"),
])
def test_a_wrong_stiffness_is_no_symbol_map(tmp_path, symbol, equation):
    result = _compare(tmp_path, "stiff", equation, symbol, LINEAR)
    assert result.equivalent is False
    assert _record(result, "K[1,1]").verdict == "differs"
    assert not any(c.kind == CauseKind.FILE_ERROR and "probably maps" in c.explanation
                   for c in result.causes), result.causes


def test_a_parameter_zero_in_every_set_is_no_symbol_map(tmp_path):
    # c = CZ(rod) (l/2) in a term the truth does not have: read as CX(rod) or CY(rod), both
    # 0 in every set (urdf_structure), the term would vanish
    result = _compare(tmp_path, "zero", "(1/3*m*l**2 + m*c**2)*ddtheta + m*g*l/2*sin(theta) = 0",
                      'c = { value = "CZ(rod)", units = "m" }')
    assert result.equivalent is False
    assert not any(c.kind == CauseKind.FILE_ERROR for c in result.causes), result.causes


def test_an_element_that_is_one_wrong_symbol_is_judged(tmp_path):
    r"""An element written as one symbol, the wrong one (half the rod's moment about its
    pivot, XX(rod) in Khalil's parameters): judged, differing by its factor (trying it "left
    out" crashed: SymPy gives the replacement itself back, a Python 0, for a lone symbol)."""
    result = _compare(tmp_path, "lone", "J*ddtheta + m*g*l/2*sin(theta) = 0",
                      'J = { value = "XX(rod)/2", units = "kg*m**2" }')
    assert result.equivalent is False
    record = _record(result, "A[1,1]")
    assert record.verdict == "differs"
    assert any(x.kind == K.FACTOR and x.factor == "1/2" for x in record.diagnoses), record


ARM_LINEAR = '''title = "Spong's two-link arm linearised about upright, I2 mapped to another axis"
model = "{model}"
[coordinates]
positions = ["a1", "a2"]
configuration = {{ q1 = "pi/2 + a1", q2 = "a2" }}
[inputs]
tau1 = "tau1"
tau2 = "tau2"
[symbols]
m1 = "M(link1)"
m2 = "M(link2)"
lc1 = "CX(link1)"
lc2 = "CX(link2)"
I1 = "IYY(link1)"
I2 = "IXX(link2)"
l1 = "l1"
g = "g"
tau1 = {{ input = true }}
tau2 = {{ input = true }}
[assumes]
families = ["urdf_structure"]
linearised_about = {{ a1 = 0, a2 = 0 }}
[matrices]
equations = [
 "(m1*lc1**2 + I1 + m2*(l1**2 + lc2**2 + 2*l1*lc2) + I2)*dda1 + (m2*(lc2**2 + l1*lc2) + I2)*dda2 - (m1*lc1 + m2*lc2)*g*a1 - m2*lc2*g*a2 = tau1",
 "(m2*(lc2**2 + l1*lc2) + I2)*dda1 + (m2*lc2**2 + I2)*dda2 - m2*lc2*g*(a1 + a2) = tau2",
]
'''


def test_a_wrong_map_beside_a_wrong_stiffness_is_no_symbol_map(tmp_path):
    r"""A probe's linearised two-link arm (Spong, Hutchinson & Vidyasagar's) with I2 mapped
    to IXX(link2) and K[1,1] lacking -g l1 m2: "with I2 = IYY(link2) ... every equation is
    right" was said, though K stays wrong (the samples a reading is judged on hold no K)."""
    path = tmp_path / "arm_linear.toml"
    path.write_text(ARM_LINEAR.format(model=DATA / "published" / "two_link_arm.toml"))
    result = ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED).compare(
        load_derivation(path))
    assert result.equivalent is False
    assert not any(c.kind == CauseKind.FILE_ERROR and "probably maps" in c.explanation
                   for c in result.causes), result.causes
