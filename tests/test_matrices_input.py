r"""What a derivation's matrices and coordinate maps may hold, on the cart-pole of
:mod:`published_forms` (Florian 2007; its uniform pole of half-length l):

- an input (a force) inside A, C, Q or G, and a velocity inside Q, are one error naming the
  element (an input in Q ended in a ``NameError`` traceback; Q with the centripetal term and
  no C was "no combination of the true equations");
- a quasi-velocity mapped through a model length written as an identifier (``length_pole``)
  is compared (the power identity, which has no value for it, is left undecided: it ended in
  a ``TypeError`` traceback); in a configuration map such a name is unknown, and the error
  says how to name the length.
"""

from __future__ import annotations

from pathlib import Path

import pytest

import published_forms as P
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.derivations.errors import DerivationNameError
from wheeled_dyn.errors import DerivationError

#: The cart-pole's head with matrices instead of equations.
MATRICES = '''[matrices]
A = [["M + m", "m*l*cos(theta)"], ["m*l*cos(theta)", "4*m*l**2/3"]]
C = [["0", "-m*l*dtheta*sin(theta)"], ["0", "0"]]
Q = {Q}
B = {B}
'''
RIGHT_Q, RIGHT_B = '["0", "-m*g*l*sin(theta)"]', '[["1"], ["0"]]'


def _pole(tmp_path: Path, Q: str = RIGHT_Q, B: str = RIGHT_B, C: bool = True) -> Path:
    head = P.POLE_HEAD.format(form="matrices", error="", model=P.DATA / "cart_pole.toml",
                              eqs="")
    head = head[:head.index("[matrices]")]
    body = MATRICES.format(Q=Q, B=B)
    if not C:
        body = "\n".join(x for x in body.splitlines() if not x.startswith("C ="))
    path = tmp_path / "pole.toml"
    path.write_text(head + body)
    return path


def test_the_right_matrices_load_and_agree(tmp_path):
    engine = ComparisonEngine(samples=100, param_sets=2)
    assert engine.compare(load_derivation(_pole(tmp_path))).equivalent is True


@pytest.mark.parametrize("Q, B, C, said", [
    ('["-F", "-m*g*l*sin(theta)"]', '[["0"], ["0"]]', True,
     "Q[1]: the input F in Q: inputs enter through B"),
    ('["-m*l*dtheta**2*sin(theta)", "-m*g*l*sin(theta)"]', RIGHT_B, False,
     "Q[1]: the velocity or acceleration dtheta in Q"),
])
def test_an_input_or_a_velocity_in_q_is_one_error(tmp_path, Q, B, C, said):
    path = _pole(tmp_path, Q, B, C)
    with pytest.raises(DerivationError) as caught:
        load_derivation(path)
    assert said in str(caught.value) and caught.value.line is not None, str(caught.value)


def _kane_text() -> str:
    r"""The cart-pole in Kane's form with u2 = length_pole·θ̇ (the pole's length, 2l)."""
    text = P.POLE_HEAD.format(form="kane", error="", model=P.DATA / "cart_pole.toml", eqs=(
        '  "(M + m)*du1 + m*cos(theta)*du2/2 - m*u2**2*sin(theta)/(4*l) = F",\n'
        '  "m*cos(theta)*du1/2 + m*du2/3 - m*g*sin(theta)/2 = 0",'))
    text = text.replace('positions = ["x", "theta"]\nkind = "holonomic"\nrolling = "none"\n'
                        'configuration = { x = "x", theta = "theta" }\n'
                        'units = { x = "m", theta = "rad" }',
                        'positions = ["x", "theta"]\nvelocities = ["u1", "u2"]\n'
                        'accelerations = ["du1", "du2"]\nkind = "quasi"\n'
                        'configuration = { x = "x", theta = "theta" }\n'
                        'velocity_map = { u1 = "dx", u2 = "length_pole*dtheta" }')
    assert 'velocity_map = { u1 = "dx", u2 = "length_pole*dtheta" }' in text
    return text


def test_a_quasi_velocity_through_a_model_length_is_compared(tmp_path):
    r"""Kane's form with u2 = length_pole·θ̇ (the pole's length, 2l for the uniform pole, as
    the model's identifier): right (it ended in a traceback)."""
    path = tmp_path / "kane.toml"
    path.write_text(_kane_text())
    result = ComparisonEngine(samples=100, param_sets=2).compare(load_derivation(path))
    assert result.equivalent is True
    assert result.energy is None             # no value for length_pole: not decided


def test_a_symbol_of_no_length_in_a_velocity_map_is_named(tmp_path):
    r"""u2 = 2 l θ̇ with l the pole's centre (CZ(pole), a mass distribution's, not one of the
    model's lengths): the error names l and its value (it named 'CZ_pole', a name the file
    never wrote)."""
    text = tmp_path / "kane.toml"
    text.write_text(_kane_text().replace('u2 = "length_pole*dtheta"', 'u2 = "2*l*dtheta"'))
    with pytest.raises(DerivationError) as caught:
        ComparisonEngine(samples=100, param_sets=2).compare(load_derivation(text))
    said = str(caught.value)
    assert "coordinates.velocity_map.u2: the symbol l is CZ(pole), which a coordinate map " \
        "cannot use" in said and "CZ_pole" not in said, said


def test_a_model_length_in_a_configuration_map_says_how_to_name_it(tmp_path):
    eqs = ",\n".join(f'  "{e}"' for e in P.pole_forms()["equations"])
    text = P.POLE_HEAD.format(form="arc", error="", model=P.DATA / "cart_pole.toml", eqs=eqs)
    text = text.replace('configuration = { x = "x", theta = "theta" }',
                        'configuration = { x = "length_pole*x", theta = "theta" }')
    path = tmp_path / "arc.toml"
    path.write_text(text)
    with pytest.raises(DerivationNameError) as caught:
        load_derivation(path)
    said = str(caught.value)
    assert "unknown symbol 'length_pole'" in said and \
        'declare a symbol in [symbols] (x = { value = "length(pole)" })' in said, said
