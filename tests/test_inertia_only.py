"""A document that states its inertia matrix A alone is read as the mass matrix.

The equivalence decision finds each equation's weights :math:`w_i = A_{doc,i}A^{-1}` from A
and checks them on the document's other terms (velocity, gravity, input, multiplier terms).
With A alone there is nothing to check them on: every A is :math:`WA` for some W, and a
diagonal A for a two-link arm "agreed" (found by a probe with Spong's acrobot). Such a
document's A is now compared as printed (each row scaled as the file declares), and the
frames it is explained in are the identity. The arm is Spong, Hutchinson and Vidyasagar's
planar elbow manipulator (``published_forms.py``); its correct A agrees, A with a planted
error (link 1's own inertia dropped: a point mass; the matrix diagonal; a row doubled)
differs and names what it can; a row doubled and declared so agrees.
"""

from __future__ import annotations

import numpy as np
import pytest

import published_forms as P
from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.judge.equivalence import Side, weights_told
from wheeled_dyn.compare.records import DiagnosisKind as K, Verdict
from wheeled_dyn.derivations import load_derivation

#: Engine grid.
SAMPLES, PARAM_SETS = 200, 3


@pytest.fixture(scope="module")
def engine():
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED)


def _inertia_only(folder, error: str | None = None, A: list | None = None,
                  scale: list[str] | None = None):
    r"""The arm's matrices form with only its A kept (``A`` replacing it where given) and,
    with ``scale``, a ``[rows]`` declaration."""
    path = P.write(folder, "arm", "matrices", error)
    text = path.read_text()
    head = text[:text.index("A = ")]
    matrix = A if A is not None else P.arm_forms(error)["matrices"]["A"]
    text = head + f"A = {matrix!r}\n".replace("'", '"')
    if scale is not None:
        text += f"[rows]\nscale = {scale!r}\n".replace("'", '"')
    path.write_text(text)
    return load_derivation(path)


def _verdicts(result) -> dict[str, Verdict]:
    return {r.element: r.verdict for r in result.records}


def test_the_right_inertia_alone_agrees(engine, tmp_path):
    result = engine.compare(_inertia_only(tmp_path))
    assert set(_verdicts(result).values()) == {Verdict.AGREES}
    assert result.equivalent


def test_an_inertia_with_link_1_a_point_mass_differs_and_is_named(engine, tmp_path):
    result = engine.compare(_inertia_only(tmp_path, "dropped"))
    verdicts = _verdicts(result)
    assert verdicts["A[1,1]"] == Verdict.DIFFERS
    assert {k for k, v in verdicts.items() if v != Verdict.AGREES} == {"A[1,1]"}
    assert not result.equivalent
    record = next(r for r in result.records if r.element == "A[1,1]")
    assert any(x.kind == K.POINT_MASS for x in record.diagnoses)


def test_a_diagonal_inertia_differs(engine, tmp_path):
    A = [["m1*lc1**2 + I1", "0"], ["0", "m2*lc2**2 + I2"]]
    result = engine.compare(_inertia_only(tmp_path, A=A))
    verdicts = _verdicts(result)
    assert all(verdicts[e] == Verdict.DIFFERS for e in ("A[1,1]", "A[1,2]", "A[2,1]"))
    assert not result.equivalent


def test_a_row_doubled_differs_unless_it_is_declared(engine, tmp_path):
    A = P.arm_forms(None)["matrices"]["A"]
    doubled = [A[0], [f"2*({x})" for x in A[1]]]
    result = engine.compare(_inertia_only(tmp_path, A=doubled))
    assert not result.equivalent
    assert _verdicts(result)["A[2,2]"] == Verdict.DIFFERS
    declared = engine.compare(_inertia_only(tmp_path, A=doubled, scale=["1", "2"]))
    assert declared.equivalent
    assert set(_verdicts(declared).values()) == {Verdict.AGREES}


def test_terms_the_truth_has_none_of_do_not_tell_the_weights():
    rng = np.random.default_rng(SEED)
    A = rng.normal(size=(50, 2, 2))
    A = A @ np.swapaxes(A, 1, 2) + 2 * np.eye(2)
    zero = np.zeros((50, 2))
    assert weights_told(Side(A, None, None), Side(A, None, None)) == (False, False)
    assert weights_told(Side(A, zero, None), Side(A, zero, None)) == (False, False)
    assert weights_told(Side(A, zero, None), Side(A, rng.normal(size=(50, 2)), None)) == \
        (True, True)
    lost = zero.copy()
    lost[:, 1] = np.nan                       # the second equation's term lost: not stated
    assert weights_told(Side(A, lost, None), Side(A, rng.normal(size=(50, 2)), None)) == \
        (True, False)


def _one_joint(folder, A: str, Q: str | None = None):
    r"""The arm with only its shoulder in the document's map (the elbow held at 0)."""
    text = P.ARM_HEAD.format(form="shoulder only", error="", model=P.DATA / "two_link_arm.toml",
                             eqs="")
    text = text.replace('positions = ["q1", "q2"]', 'positions = ["q1"]')
    text = text.replace('configuration = { q1 = "q1", q2 = "q2" }', 'configuration = { q1 = "q1" }')
    text = text.replace('units = { q1 = "rad", q2 = "rad" }', 'units = { q1 = "rad" }')
    text = text.replace('tau2 = "tau2"\n', "").replace(
        'tau2 = { input = true, units = "N*m" }\n', "")
    text = text[:text.index("equations = [")] + f'A = [["{A}"]]\n' + (
        f'Q = ["{Q}"]\nB = [["1"]]\n' if Q else "")
    path = folder / "shoulder.toml"
    path.write_text(text)
    return load_derivation(path)


def test_a_joint_left_out_of_the_map_is_held_and_said(engine, tmp_path):
    r"""The probe's one-coordinate file for a two-joint arm: the elbow is held at 0 and the
    report says so; the arm's own d11 and φ1 at q2 = 0 agree, a unit inertia alone differs."""
    D, _, phi = P.arm()
    locked = engine.compare(_one_joint(tmp_path, P._s(D[0, 0].subs(P.q2, 0)),
                                       P._s(phi[0].subs(P.q2, 0))))
    assert locked.equivalent
    assert any("q2 is held at 0 by the document's configuration map" in n
               for n in locked.notes)
    assert not engine.compare(_one_joint(tmp_path, "1")).equivalent


@pytest.mark.parametrize("scale", ["sin(q2)", "m1 - m2", "(cos(q1) - 1/2)**2"])
def test_a_declared_scale_that_vanishes_is_not_equivalent(engine, tmp_path, scale):
    r"""A alone, row 1 times a factor that vanishes (at q2 = 0; for a robot with m1 = m2;
    at q1 = π/3), the factor declared (a probe): it agreed, the singular checks being skipped
    for an A read as the mass matrix. The equation is lost where the factor vanishes."""
    A = P.arm_forms(None)["matrices"]["A"]
    scaled = [[f"({scale})*({x})" for x in A[0]], A[1]]
    result = engine.compare(_inertia_only(tmp_path, A=scaled, scale=[scale, "1"]))
    assert not result.equivalent
    assert result.equations[0].verdict == Verdict.DIFFERS
    assert any(x.kind == K.SINGULAR for x in result.equations[0].diagnoses)


def test_an_equation_whose_other_terms_are_lost_is_read_as_printed(engine, tmp_path):
    r"""A and Q given, Q's second element lost in the extracted text: equation 2 states
    nothing beyond A, so its weights are not told and its A row is compared as printed
    (doubled, it differs; as printed, its elements agree); equation 1's are told by Q."""
    D, _, phi = P.arm()
    Q = [P._s(phi[0]), "?"]
    A = P.arm_forms(None)["matrices"]["A"]
    for row2, verdict in ((A[1], Verdict.AGREES), ([f"2*({x})" for x in A[1]],
                                                   Verdict.DIFFERS)):
        d = _inertia_only(tmp_path, A=[A[0], row2])
        text = d.path.read_text() + f"Q = {Q!r}\n".replace("'", '"')
        d.path.write_text(text)
        result = engine.compare(load_derivation(d.path))
        verdicts = _verdicts(result)
        assert verdicts["A[2,1]"] == verdicts["A[2,2]"] == verdict
        assert verdicts["A[1,1]"] == verdicts["Q[1]"] == Verdict.AGREES
