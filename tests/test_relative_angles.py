r"""Angles measured from another link. The two-link arm of Spong, Hutchinson and Vidyasagar
(:mod:`published_forms`: joint angles, the elbow's relative to the upper arm) written in
absolute angles, each link's from the horizontal, as double-pendulum derivations take them
(T. W. B. Kibble, F. H. Berkshire, *Classical Mechanics*, 5th ed., ch. 11, the
double pendulum's θ and φ, each from the vertical): the document's :math:`q_2` is the
model's :math:`q_1 + q_2`, its equations those of the absolute angles (the relative ones
combined by :math:`L^{-T}`).

The reading's formulas are checked against the truth computed through two maps; a file
whose map does not say how the document measures its angles differs (declarations are
binding) with the reading as its first cause; with ``convention = "unknown"`` it is compared
under the reading, and a planted error still differs.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import published_forms as P
import pytest
import sympy as sp
from conftest import SEED
from wheeled_dyn import CoordinateMap, load_model
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.readings.relative_angles import document_state, sum_arrays
from wheeled_dyn.compare.grid.arrays import Arrays
from wheeled_dyn.compare.records import CauseKind, Verdict
from wheeled_dyn.coordinates.spec import parse_coordinate_set
from wheeled_dyn.derivations import load_derivation

#: Engine grid.
SAMPLES, PARAM_SETS = 300, 3
#: The reading's transform against the truth computed directly (relative to its size).
FORMULA_TOL = 1e-10
#: The document's angle (absolute, a2) in the model's relative ones, its rates too.
ABSOLUTE = {P.q2: sp.Symbol("a2") - P.q1, P.dq2: sp.Symbol("da2") - P.dq1,
            P.ddq2: sp.Symbol("dda2") - P.ddq1}


def _absolute_equations(error: str | None) -> list[str]:
    r"""The arm's equations in absolute angles, the planted ``error`` made in the source
    equations: the rows of the absolute angles are (eq₁ − eq₂, eq₂) of the joint angles,
    each written in :math:`(q_1, q_2 = q_1 + q_2^{joint})`."""
    D, c, phi = P.arm(error)
    acc, tau = sp.Matrix([P.ddq1, P.ddq2]), sp.Matrix([P.tau1, P.tau2])
    lhs = [(D[i, :] * acc)[0] + c[i] + phi[i] - tau[i] for i in range(2)]
    back = {sp.Symbol("a2"): P.q2, sp.Symbol("da2"): P.dq2, sp.Symbol("dda2"): P.ddq2}
    rows = [sp.expand(sp.expand_trig(r.subs(ABSOLUTE, simultaneous=True))).subs(back)
            for r in (lhs[0] - lhs[1], lhs[1])]
    return [f"{sp.sstr(r)} = 0" for r in rows]


def _write(folder: Path, error: str | None, elbow: str, unknown: bool = False,
           relative: bool = False) -> Path:
    r"""The arm's file (absolute angles, or the joint angles' equations where ``relative``)
    whose map reads the elbow as ``elbow``."""
    eqs = P.arm_forms(error)["equations"] if relative else _absolute_equations(error)
    text = P.ARM_HEAD.format(form="absolute", error=f", {error}" if error else "",
                             model=P.DATA / "two_link_arm.toml",
                             eqs=",\n".join(f'  "{e}"' for e in eqs))
    text = text.replace('q2 = "q2" }', f'q2 = "{elbow}" }}')
    if unknown:
        text = text.replace("[coordinates]", 'convention = "unknown"\n[coordinates]')
    path = folder / f"arm_{error or 'right'}_{'rel' if relative else 'abs'}_{unknown}.toml"
    path.write_text(text)
    return path


def _compare(path: Path):
    return ComparisonEngine(samples=SAMPLES, param_sets=PARAM_SETS, seed=SEED).compare(
        load_derivation(path))


def test_the_reading_gives_the_truth_of_the_other_map():
    r"""The truth in absolute angles, read with :math:`q_2 \to q_2 - q_1` and its equations
    combined by :math:`L^{-T}` (:func:`sum_arrays`), is the truth in joint angles: Pinocchio
    through two coordinate maps against the module's formulas."""
    wm = load_model(str(P.DATA / "two_link_arm.toml"))

    def truth(configuration: dict) -> CoordinateMap:
        return CoordinateMap(wm, parse_coordinate_set(
            {"positions": ["q1", "q2"], "kind": "holonomic", "rolling": "none",
             "configuration": configuration}, "arm", wm.coordinate_names, list(wm.geometry)))
    relative = truth({"q1": "q1", "q2": "q2"})          # the model's joints are q1, q2
    absolute = truth({"q1": "q1", "q2": "q2 - q1"})
    rng = np.random.default_rng(SEED)
    q, nu = rng.uniform(-3, 3, (50, 2)), rng.normal(size=(50, 2))
    sums = ((1, 0, -1),)             # the file's q2 (joint) → q2 − q1: the document's absolute
    qa, nua = document_state(q, nu, sums)
    assert np.allclose(qa[:, 1], q[:, 0] + q[:, 1]) and np.allclose(nua[:, 1], nu.sum(axis=1))
    t_abs = absolute.terms_batch(qa, nua)
    read = sum_arrays(Arrays(A=t_abs.A, C=t_abs.C, Q=t_abs.Q, B=t_abs.B, h=t_abs.h), sums)
    t_rel = relative.terms_batch(q, nu)
    for key in "ACQBh":
        mine, true = getattr(read, key), getattr(t_rel, key)
        scale = max(1.0, float(np.abs(true).max()))
        assert np.abs(mine - true).max() <= FORMULA_TOL * scale, key


@pytest.mark.parametrize("relative", [False, True])
def test_declared_the_reading_is_the_first_cause(tmp_path, relative):
    r"""Absolute angles under the joint angles' map (the reading :math:`q_2 \to q_2 - q_1`),
    and joint angles under the absolute angles' map (:math:`q_2 \to q_2 + q_1`): the file
    differs as declared, and the first cause is the reading."""
    path = _write(tmp_path, None, "q2 - q1" if relative else "q2", relative=relative)
    result = _compare(path)
    assert result.equivalent is False
    first = result.causes[0]
    assert first.kind == CauseKind.CONVENTION, [c.explanation for c in result.causes]
    said = "q2 → q2 + q1" if relative else "q2 → q2 − q1"
    assert said in first.explanation and "measured from another link" in first.explanation
    assert "2 of 2 equations are right instead of 0" in first.explanation


def test_declared_as_the_document_measures_them_it_agrees(tmp_path):
    result = _compare(_write(tmp_path, None, "q2 - q1"))
    assert result.equivalent is True, result.equations
    assert not any(c.kind == CauseKind.CONVENTION for c in result.causes), result.causes


def test_unknown_it_is_compared_under_the_reading(tmp_path):
    result = _compare(_write(tmp_path, None, "q2", unknown=True))
    assert result.equivalent is True, result.equations
    assert "q2 → q2 − q1" in result.causes[0].explanation


def test_a_real_error_beside_the_reading_still_differs(tmp_path):
    r"""The sign of :math:`h\dot q_2^2` planted in the source equations: in absolute angles it
    is in the first equation's three velocity products; compared under the reading, those
    differ and nothing else."""
    result = _compare(_write(tmp_path, "sign", "q2", unknown=True))
    assert result.equivalent is False
    assert "q2 → q2 − q1" in result.causes[0].explanation
    wrong = {r.element for r in result.records if r.verdict == Verdict.DIFFERS}
    assert wrong and all(e.startswith("h[1]:") for e in wrong), wrong


@pytest.mark.parametrize("error", ["sign", "dropped", "gravity"])
def test_one_terms_error_is_no_reading(tmp_path, error):
    r"""The joint angles' equations with one planted error, under their own map: no angle is
    read from another link (the causes are the terms')."""
    result = _compare(_write(tmp_path, error, "q2", relative=True))
    assert result.equivalent is False
    assert not any(c.kind == CauseKind.CONVENTION for c in result.causes), \
        [c.explanation for c in result.causes]


@pytest.mark.parametrize("unknown", [False, True])
def test_a_chain_of_three_read_along_it(tmp_path, unknown):
    r"""A three-link arm's joint-angle equations (``data/published/three_link_arm_divided``:
    Spong's notation, the third divided by its diagonal inertia) under a map that takes the
    angles absolute (j2 = q2 − q1, j3 = q3 − q2): read along the chain, q2 → q2 + q1 and
    q3 → q3 + q1 + q2, every equation is right — the cause, or with ``convention =
    "unknown"`` the reading compared under (one angle at a time left the third blamed on
    terms)."""
    import shutil
    data = P.DATA
    for own in ("three_link_arm.toml", "three_link_arm.urdf"):
        shutil.copy(data / own, tmp_path / own)
    text = (data / "three_link_arm_divided.toml").read_text()
    old = 'configuration = { j1 = "q1", j2 = "q2", j3 = "q3" }'
    assert old in text
    text = text.replace(old, 'configuration = { j1 = "q1", j2 = "q2 - q1", j3 = "q3 - q2" }')
    if unknown:                                    # a key of the file: above its tables
        text = text.replace("model = ", 'convention = "unknown"\nmodel = ', 1)
    path = tmp_path / "chain.toml"
    path.write_text(text)
    result = _compare(path)
    assert result.equivalent is (True if unknown else False), result.equations
    first = result.causes[0]
    assert "q2 → q2 + q1, q3 → q3 + q1 + q2" in first.explanation, first.explanation


def test_the_velocity_products_are_combined_as_h_is():
    r"""The tensor of velocity products H (:math:`h_i = H_{ijk}\nu_j\nu_k`) read as the
    module says: the document's h at its velocities :math:`\nu'`, combined by
    :math:`L^{-T}`, is the transformed H at the file's :math:`\nu = L\nu'`."""
    from wheeled_dyn.compare.readings.relative_angles import sum_matrix
    rng = np.random.default_rng(SEED)
    H = rng.normal(size=(7, 3, 3, 3))
    H = H + np.swapaxes(H, 2, 3)
    nu = rng.normal(size=(7, 3))                       # the document's velocities
    h = np.einsum("sijk,sj,sk->si", H, nu, nu)
    sums = ((2, 0, 1), (2, 1, 1))
    read = sum_arrays(Arrays(H=H, h=h, Q=np.zeros((7, 3))), sums)
    file_nu = nu @ sum_matrix(3, sums).T
    assert np.allclose(np.einsum("sijk,sj,sk->si", read.H, file_nu, file_nu), read.h,
                       atol=1e-12)
