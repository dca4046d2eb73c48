r"""One symbol written for another in a part of an element (:mod:`wheeled_dyn.compare.judge.
part_swap`): a printed product the multiplying out spread over several terms or merged with
another's. The double pendulum with torsional springs (``data/published/double_pendulum*``,
Lagrange's equations as in Meirovitch, *Methods of Analytical Dynamics*, ch. 2) with the hip
spring's constant written for the knee's in :math:`-k_2(\theta_2 - \theta_1 - r_2)` of the
first equation: its :math:`k_1\theta_1` merges with :math:`k_1(\theta_1 - r_1)`'s, and the
element had "no single-term diagnosis" (written out) or "Q[1] differs" (solved). Named in
the equations written out and solved for the accelerations (read back before solving); on
numbers, :math:`k_2 + k_2` for :math:`k_1 + k_2` (a linearised stiffness) as the part of
:math:`2k_2` it is; a typo of another kind in the same place is no swap."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from conftest import SEED
from shipped_copies import published_copy
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.judge.part_swap import part_swap
from wheeled_dyn.compare.records import DiagnosisKind as K
from wheeled_dyn.compare.records import Verdict
from wheeled_dyn.derivations import load_derivation

KNEE = "k1*(th1 - r1) - k2*(th2 - th1 - r2)"


def _compare(path: Path):
    return ComparisonEngine(samples=1000, param_sets=5, seed=SEED).compare(
        load_derivation(path))


def _wrong(result) -> dict:
    return {r.element: r for r in result.records if r.verdict != Verdict.AGREES}


def test_written_out_the_hip_constant_for_the_knees_is_named(tmp_path):
    result = _compare(published_copy(tmp_path, "double_pendulum", "double_pendulum_springs",
                                     (KNEE, "k1*(th1 - r1) - k1*(th2 - th1 - r2)")))
    wrong = _wrong(result)
    assert result.equivalent is False and list(wrong) == ["Q[1]"], wrong
    first = wrong["Q[1]"].diagnoses[0]
    assert first.kind == K.SWAP and (first.written, first.fits) == ("k1", "k2"), first
    assert first.text.endswith("k1 where k2 fits in k1*(r2 + th1 - th2)"), first.text


def test_solved_for_the_accelerations_it_is_named_in_the_equations_read_back(tmp_path):
    result = _compare(published_copy(
        tmp_path, "double_pendulum", "double_pendulum_solved",
        ("- k2*(th2 - th1 - r2))\"", "- k1*(th2 - th1 - r2))\"")))
    wrong = _wrong(result)
    assert result.equivalent is False and set(wrong) == {"Q[1]", "Q[2]"}, wrong
    said = " ".join(x.text for x in wrong["Q[1]"].diagnoses)
    assert "Q[1]: k1 where k2 fits in k1*(r2 + th1 - th2)" in said, said


def test_a_symbol_merged_into_a_multiple_is_named_as_the_part_it_is():
    r"""The linearised hip row's stiffness :math:`k_1 + k_2` written :math:`k_2 + k_2`: truth
    − document :math:`k_1 - k_2` is half of the document's :math:`2k_2` read with
    :math:`k_1`, at random values of both (the function itself, on numbers)."""
    rng = np.random.default_rng(SEED)
    k1, k2, g = sp.symbols("k1 k2 g")
    values = {k1: rng.uniform(1, 5, 50), k2: rng.uniform(1, 5, 50), g: rng.uniform(9, 10, 50)}
    document = 2 * k2 + g
    truth_minus_document = values[k1] - values[k2]
    found = part_swap(document, truth_minus_document, values, [[k1, k2]])
    assert found is not None and found.text == "k2 (of its 2*k2) where k1 fits", found
    assert part_swap(document, truth_minus_document + 0.01 * values[g], values,
                     [[k1, k2]]) is None                  # another error: no swap


@pytest.mark.parametrize("typo", ["k1*(th1 - r1) - 2*k2*(th2 - th1 - r2)",
                                  "k1*(th1 - r1) - k2*(th2 - r2)"], ids=["factor", "dropped"])
def test_other_errors_in_the_same_product_are_no_swap(tmp_path, typo):
    result = _compare(published_copy(tmp_path, "double_pendulum", "double_pendulum_springs",
                                     (KNEE, typo)))
    wrong = _wrong(result)
    assert result.equivalent is False and "Q[1]" in wrong, wrong
    assert not any(x.kind == K.SWAP for x in wrong["Q[1]"].diagnoses), wrong["Q[1]"].texts
