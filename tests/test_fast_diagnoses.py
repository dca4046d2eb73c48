r"""The comparison's shortcuts decide what the plain computations decide: row factors voted
on stacked arrays against a per-element vote written out, and a swap diagnosis screened on a
few samples against the same diagnosis evaluated at every sample."""

from __future__ import annotations

import numpy as np
import sympy as sp

from conftest import SEED
from wheeled_dyn.compare.judge.diagnose import agrees, swap_diagnoses
from wheeled_dyn.compare.readings.row_factors import ROW_FACTOR_SPREAD, ROW_FACTORS, row_factors
from wheeled_dyn.compare.grid.arrays import Arrays

#: Samples, rows, inputs and random cases of the row-factor check.
N, ROWS, INPUTS, CASES = 40, 4, 2, 60


def _vote_one(D: np.ndarray, T: np.ndarray):
    r"""One element's vote, as the rule reads: the nearest candidate to its ratio within the
    spread, ``"none"`` when none is, no vote when not finite or a side is zero."""
    if not (np.isfinite(D).all() and np.isfinite(T).all()):
        return None
    if float(T @ T) <= 0 or float(D @ D) <= 0:
        return None
    c = float(D @ T) / float(T @ T)
    best = min(ROW_FACTORS, key=lambda f: abs(c - f))
    return best if abs(c - best) <= ROW_FACTOR_SPREAD * abs(best) else "none"


def _reference(doc: Arrays, truth: Arrays, B_true: np.ndarray) -> list:
    out = []
    for i in range(ROWS):
        a = [_vote_one(doc.A[:, i, j], truth.A[:, i, j]) for j in range(ROWS)]
        rest = [_vote_one(doc.Q[:, i], truth.Q[:, i])]
        rest += [_vote_one(doc.B[:, i, j], B_true[:, i, j]) for j in range(INPUTS)]
        a = [v for v in a if v is not None]
        every = a + [v for v in rest if v is not None]
        winner = None
        for f in ROW_FACTORS:
            if f != 1.0 and a and sum(v == f for v in a) * 2 > len(a) \
                    and sum(v == f for v in every) * 2 > len(every):
                winner = f
        out.append(winner)
    return out


def test_row_factors_vote_as_each_element_votes():
    rng = np.random.default_rng(SEED)
    found = set()
    for _ in range(CASES):
        truth = Arrays(A=rng.normal(size=(N, ROWS, ROWS)), Q=rng.normal(size=(N, ROWS)))
        B_true = rng.normal(size=(N, ROWS, INPUTS))
        factors = rng.choice(ROW_FACTORS, ROWS)
        doc = Arrays(A=truth.A * factors[None, :, None], Q=truth.Q * factors[None, :],
                     B=B_true * factors[None, :, None])
        for i in range(ROWS):                      # spoil some elements of some rows
            for j in rng.choice(ROWS, rng.integers(0, 4), replace=False):
                doc.A[:, i, j] = rng.choice([0.0, np.nan, 1.0]) * rng.normal(size=N) \
                    + rng.normal(size=N)
        expected = _reference(doc, truth, B_true)
        got = row_factors(doc, truth, B_true, ROWS)
        # the factor is then kept only where dividing by it makes an element agree: the
        # reference's winners are candidates, the engine's a subset of them
        assert all(g is None or g == e for g, e in zip(got, expected))
        assert all(g == e for g, e, f in zip(got, expected, factors) if e == f)
        found.update(g for g in got if g is not None)
    assert len(found) >= 3                         # factors other than 1 were found


def test_a_screened_swap_diagnosis_is_the_full_one():
    rng = np.random.default_rng(SEED)
    a, b, c = sp.symbols("a b c")
    values = {s: rng.uniform(0.5, 2.0, 500) for s in (a, b, c)}
    values[c][:250] = values[b][:250]              # b and c equal on half the samples
    expr = a * b ** 2 + c
    T = values[a] * values[c] ** 2 + values[c]     # the truth has c where expr has b
    scale = float(np.abs(T).max())
    calls = []

    def evaluate(x, y, rows=slice(None)):
        calls.append(rows)
        sub = {s: v[rows] for s, v in values.items()}
        sub[x] = sub[y]
        return sub[a] * sub[b] ** 2 + sub[c]

    rows = np.array([0, 100, 400])
    full = swap_diagnoses(expr, [[a, b, c]], evaluate, T, scale)
    assert [d.text for d in full] == ["swap: b where c fits"]
    assert (full[0].kind, full[0].written, full[0].fits) == ("swap", "b", "c")
    evaluated = len(calls)
    calls.clear()
    screened = swap_diagnoses(expr, [[a, b, c]], evaluate, T, scale,
                              lambda x, y: agrees(evaluate(x, y, rows), T[rows], scale))
    assert screened == full
    assert sum(r is not rows for r in calls) < evaluated     # fewer full evaluations
