"""The convention search counts a reading's agreeing elements matrix by matrix: the same count
as judging every element on its own (:func:`wheeled_dyn.compare.judge.diagnose.agrees`); and
its equations right, as many as the decision finds."""

from __future__ import annotations

import itertools

import numpy as np
import pytest

from conftest import SEED
from wheeled_dyn.compare.readings.signs import flip_arrays, readings
from wheeled_dyn.compare.judge.diagnose import agrees
from wheeled_dyn.compare.readings.row_factors import apply_row_factors, row_factors, row_scales
from wheeled_dyn.compare.sides.elements import element_values
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.engine.conventions import search_evaluation
from wheeled_dyn.derivations import builtin_derivations, load_derivation

#: Readings (sign patterns) scored per file.
READINGS = 8


@pytest.mark.parametrize("group, stem", [("seed001", "eq25_lagrange"),
                                         ("seed001", "sec5_nonholonomic"),
                                         ("seed000", "p4_9_pendulum_support")])
def test_score_counts_what_element_by_element_counts(group, stem):
    d = load_derivation(next(p for p in builtin_derivations(group) if p.stem == stem))
    ev = search_evaluation(ComparisonEngine(samples=60, param_sets=2, seed=SEED).judge(d))
    n = ev.q.shape[1]
    _, truth, B_true = ev._subset()
    counts = set()
    for signs in itertools.islice(itertools.product((1, -1), repeat=n), READINGS):
        one = ev.doc_at(signs)
        apply_row_factors(one, row_factors(one, truth, B_true, n))
        scales = row_scales(one, truth, n)
        expected = sum(bool(np.isfinite(D).all()) and agrees(D, T, scales[index[0]])
                       for _, D, T, index, _ in element_values(ev.funcs, one, truth, B_true, n))
        assert ev.agreeing(ev.doc_at(signs)) == expected, signs
        counts.add(expected)
    assert len(counts) > 1                      # the readings do differ


@pytest.mark.parametrize("group, stem", [("seed001", "sec5_nonholonomic"),
                                         ("seed001", "kim_eq6_8"),
                                         ("seed001", "book_eq9_11"),
                                         ("seed000", "p4_9_pendulum_support")])
def test_readings_scored_together_score_as_each_alone(group, stem):
    r"""The convention search scores the readings of the inputs at one sign pattern of the
    positions together (what they share found once): the same numbers as scoring each
    reading's arrays on their own."""
    d = load_derivation(next(p for p in builtin_derivations(group) if p.stem == stem))
    ev = search_evaluation(ComparisonEngine(samples=60, param_sets=2, seed=SEED).judge(d))
    options = readings(d)
    if not options:
        pytest.skip(f"{stem}: no readings to search")
    values = set()
    for s, group_ in itertools.islice(itertools.groupby(options, key=lambda o: o[0]),
                                      READINGS):
        group_ = list(group_)
        together = ev.score_readings(ev.doc_at(s), s, [(t, o) for _, t, o, _, _ in group_])
        alone = [ev.score(flip_arrays(ev.doc_at(s), s, t, o)) for _, t, o, _, _ in group_]
        assert together == alone, s
        values.update(alone)
    assert len(values) > 1                      # the readings do differ


@pytest.mark.parametrize("group, stem", [("seed001", "eq25_lagrange"),
                                         ("seed001", "book_eq9_11"),
                                         ("seed000", "p4_9_pendulum_support")])
def test_score_counts_the_equations_the_decision_finds_right(group, stem):
    r"""Beyond its elements, a reading's score counts :meth:`weight` for each equation that is
    a combination of the true ones on the search's samples: as declared, as many as the
    judged derivation's equations that agree (decided on every sample)."""
    from wheeled_dyn.compare.records import Verdict
    d = load_derivation(next(p for p in builtin_derivations(group) if p.stem == stem))
    j = ComparisonEngine(samples=60, param_sets=2, seed=SEED).judge(d)
    ev = search_evaluation(j)
    declared = ev.doc_at((1,) * ev.q.shape[1])
    right = sum(e.verdict == Verdict.AGREES for e in j.result.equations)
    score, agreeing = ev.score(declared), ev.agreeing(ev.doc_at((1,) * ev.q.shape[1]))
    assert (score - agreeing) == ev.weight() * right, (score, agreeing, right)
    assert ev.weight() > ev.elements(declared)
