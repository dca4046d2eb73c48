r"""The search for a ratio's monomial in the bases (:func:`wheeled_dyn.compare.judge.fitting._search`),
which screens the products of two bases on a few samples first, against the plain search
written out here: every product of one or two bases with every pair of exponents, its spread
over all samples. The same candidates, in the same order, on seeded random cases — exact
products, products perturbed only away from the screened samples, and plain noise."""

from __future__ import annotations

import itertools

import numpy as np
import pytest
import sympy as sp

from wheeled_dyn.compare.judge.fitting import (EXPONENTS, RATIO_TOL, SEARCH_SCREEN, _search,
                                               fit_factor)


def _plain(ratio: np.ndarray, bases: list) -> list:
    y = np.log(np.abs(ratio))
    L = [np.log(np.abs(v)) for _, v in bases]
    out = []
    for p in EXPONENTS:
        out += [((a,), (p,)) for a in range(len(L)) if np.ptp(y - p * L[a]) <= RATIO_TOL]
    for p, q in itertools.product(EXPONENTS, EXPONENTS):
        out += [((a, b), (p, q)) for a, b in itertools.combinations(range(len(L)), 2)
                if np.ptp(y - p * L[a] - q * L[b]) <= RATIO_TOL]
    return out


def _case(rng: np.random.Generator, kind: str) -> tuple[np.ndarray, list]:
    S = int(rng.choice([5, 64, 128, 1000]))
    B = int(rng.integers(2, 10))
    vals = [rng.uniform(0.2, 3.0, S) * rng.choice([-1.0, 1.0]) for _ in range(B)]
    i, j = (int(x) for x in rng.choice(B, size=2, replace=False))
    p, q = (int(x) for x in rng.choice(EXPONENTS, size=2))
    ratio = 0.75 * vals[i] ** p * vals[j] ** q
    if kind == "off_screen":
        # the product exactly at the screened samples, 1e-6 off at one other sample
        rows = set(np.linspace(0, S - 1, min(S, SEARCH_SCREEN)).astype(int).tolist())
        other = next((k for k in range(S) if k not in rows), None)
        if other is not None:
            ratio[other] *= 1 + 1e-6
    elif kind == "noise":
        ratio = rng.uniform(0.5, 2.0, S)
    return ratio, [(sp.Symbol(f"b{k}"), v) for k, v in enumerate(vals)]


@pytest.mark.parametrize("kind", ["exact", "off_screen", "noise"])
def test_screened_search_is_the_plain_search(kind: str) -> None:
    rng = np.random.default_rng({"exact": 1, "off_screen": 2, "noise": 3}[kind])
    found = 0
    for _ in range(60):
        ratio, bases = _case(rng, kind)
        got = _search(ratio, bases)
        assert got == _plain(ratio, bases)
        found += len(got)
    if kind == "exact":
        assert found >= 60          # each exact product is found (with its equivalents)


def test_a_product_off_at_one_unscreened_sample_is_not_fitted() -> None:
    rng = np.random.default_rng(4)
    S = 64
    x, z = rng.uniform(0.5, 2.0, S), rng.uniform(0.5, 2.0, S)
    bases = [(sp.Symbol("x"), x), (sp.Symbol("z"), z)]
    ratio = 3 * x * z ** 2
    assert fit_factor(ratio, bases) == 3 * sp.Symbol("x") * sp.Symbol("z") ** 2
    ratio[10] *= 1 + 1e-6                     # not one of the screened samples (0, 21, 42, 63)
    assert fit_factor(ratio, bases) is None
