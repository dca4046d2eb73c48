r"""Documents that give part of the equations, and expressions that are no real equation
parts. A document gives only what it derives (a pendulum's gravity torque Q alone): it is
compared on that, where the frame search asked for its inertia and crashed
(``ValueError: A is needed here``). A row factor of 0 (``[rows] scale``) and an expression
holding the imaginary unit (``sqrt(-1)``) are one error naming the file and the item, where
the first crashed (``KeyError: 'ComplexInfinity'``) and the second was compared on its real
part with NumPy's warnings."""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import SEED
from test_bad_derivation_inputs import EQUATION, ROD
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import DiagnosisKind as K, Verdict
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.errors import DerivationError

#: A uniform rod pendulum's gravity torque about its pivot (m g l/2 sin θ), as a document
#: that derives only it writes it (the small valid file of the bad-input tests otherwise).
ONLY_Q = ROD.replace(EQUATION, 'Q = "[m*g*l/2*sin(theta)]"').replace(
    "Uniform rod pendulum", "rod pendulum, its gravity torque only")


def _write(tmp_path: Path, text: str) -> Path:
    path = tmp_path / "doc.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("printed, verdict", [("m*g*l/2*sin(theta)", Verdict.AGREES),
                                              ("m*g*l*sin(theta)", Verdict.DIFFERS)])
def test_a_document_giving_only_q_is_compared_on_it(tmp_path, printed, verdict):
    path = _write(tmp_path, ONLY_Q.replace("m*g*l/2*sin(theta)", printed))
    result = ComparisonEngine(samples=100, param_sets=2, seed=SEED).compare(
        load_derivation(path))
    assert [(r.element, r.verdict) for r in result.records] == [("Q[1]", verdict)]
    if verdict == Verdict.DIFFERS:
        assert result.records[0].diagnoses[0].kind == K.FACTOR


@pytest.mark.parametrize("old, new, where, words", [
    ('Q = "[m*g*l/2*sin(theta)]"', 'Q = "[m*g*l/2*sin(theta)]"\n[rows]\nscale = ["0"]',
     "rows.scale[1]", "must not be zero"),
    ("m*g*l/2*sin(theta)", "m*g*l/2*sin(theta)*sqrt(-1)", "Q", "imaginary unit"),
])
def test_no_real_factor_or_expression_is_one_error(tmp_path, old, new, where, words):
    path = _write(tmp_path, ONLY_Q.replace(old, new))
    with pytest.raises(DerivationError) as info:
        load_derivation(path)
    message = str(info.value)
    assert "doc.toml" in message and where in message and words in message, message
