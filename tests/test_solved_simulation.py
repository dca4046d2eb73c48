r"""Equations solved for the accelerations as simulation code writes them.

- Bogdanov's double inverted pendulum on a cart (``data/published/dipc_simulation.toml``: the
  inertia matrix's entries, the right-hand sides and the determinant in ``[definitions]``,
  each acceleration a ratio of cofactors): it agrees, and a sign, a point mass, are named
  where the author wrote them (in the frame where the solve is undone).
- SymPy's own solve of Spong's two-link arm with its centres of mass off the links' axes, the
  numerators multiplied out (``data/published/two_link_arm_solved_com.toml``): 325 terms in
  an equation, refused at 300 before; it agrees.
- A file whose expressions are too large together is still refused when it is read.
"""

from __future__ import annotations

from pathlib import Path

import pytest

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import CauseKind, DiagnosisKind as K, Verdict
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.errors import DerivationError

DATA = Path(__file__).parent / "data" / "published"
SAMPLES, PARAM_SETS = 300, 3
#: (the file as written, the planted error, the element named, its diagnosis kind)
PLANTED = {
    "sign": ('f2 = "-L1*dth2**2*l2*m2*sin(th1 - th2)', 'f2 = "L1*dth2**2*l2*m2*sin(th1 - th2)',
             "h[2]:dth2*dth2", K.SIGN),
    "point_mass": ('M33 = "I2 + l2**2*m2"', 'M33 = "l2**2*m2"', None, CauseKind.POINT_MASS),
}


def _compare(tmp_path: Path, old: str = "", new: str = ""):
    text = (DATA / "dipc_simulation.toml").read_text()
    assert old in text
    path = tmp_path / "dipc_simulation.toml"
    path.write_text(text.replace(old, new).replace('model = "dipc.toml"',
                                                   f'model = "{DATA / "dipc.toml"}"'))
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED).compare(
        load_derivation(path))


def test_the_solved_file_agrees(tmp_path):
    result = _compare(tmp_path)
    assert result.equivalent is True
    assert all(r.verdict == Verdict.AGREES for r in result.records)


@pytest.mark.parametrize("error", sorted(PLANTED))
def test_a_planted_error_is_named(tmp_path, error):
    old, new, element, kind = PLANTED[error]
    result = _compare(tmp_path, old, new)
    assert result.equivalent is False
    if isinstance(kind, CauseKind):
        assert result.causes and any(c.kind == kind for c in result.causes[:3]), result.causes
    else:
        record = next(r for r in result.records if r.element == element)
        assert record.verdict == Verdict.DIFFERS and record.diagnoses[0].kind == kind


def test_expressions_too_large_together_are_refused_when_read(tmp_path, monkeypatch):
    r"""Each expression within :data:`MAX_DOCUMENT_TERMS`, all of them together not (the
    comparison's cost is about their sum): refused when the file is read, naming the
    expression that went past it. Shown with the limit lowered to the arm's size."""
    from wheeled_dyn.derivations import loader
    monkeypatch.setattr(loader, "MAX_FILE_TERMS", 400)
    path = tmp_path / ARM.name
    path.write_text(ARM.read_text().replace('model = "two_link_arm.toml"',
                                            f'model = "{DATA / "two_link_arm.toml"}"'))
    with pytest.raises(DerivationError, match="more than 400 terms once multiplied out "
                                              "together"):
        load_derivation(path)


ARM = DATA / "two_link_arm_solved_com.toml"


def _arm(tmp_path: Path, old: str = "", new: str = ""):
    text = ARM.read_text()
    assert old in text
    path = tmp_path / ARM.name
    path.write_text(text.replace(old, new).replace('model = "two_link_arm.toml"',
                                                   f'model = "{DATA / "two_link_arm.toml"}"'))
    return ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(load_derivation(path))


def test_a_generated_solved_arm_of_hundreds_of_terms_agrees(tmp_path):
    r"""Spong's two-link arm with its centres of mass off the links' axes, solved by SymPy
    with the numerators multiplied out (325 terms in the first): refused at 300 terms before;
    it agrees, and a centre of mass mapped across the wrong axis is said as the file's map."""
    result = _arm(tmp_path)
    assert result.equivalent is True
    wrong = _arm(tmp_path, 'b2 = { value = "CZ(link2)"', 'b2 = { value = "-CZ(link2)"')
    assert wrong.equivalent is False
    assert wrong.causes[0].kind == CauseKind.FILE_ERROR, wrong.causes
    assert "with b2 = CZ(link2)" in wrong.causes[0].explanation
