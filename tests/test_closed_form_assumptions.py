"""Closed-form truths read under what a document assumes: the symbolic substitution of each of
the WIP's parameter families equals the family applied to random parameter records, and seed
001's eq. (25), which assumes the centre of mass above the axle and no motor inertia, gets the
missing term of the seed's own table as its C[1,2] residual."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from wheeled_dyn.compare import ComparisonEngine
from wheeled_dyn.compare.presentation.closed_form import family_substitution
from wheeled_dyn.compare.grid.samples import WIP_SPECIAL_CASES
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.models.wip_parameters import random_wip_parameters

from conftest import SEED

SHIPPED = Path(__file__).parents[1] / "src" / "wheeled_dyn" / "data" / "derivations"
#: Relative tolerance of the family check (exact arithmetic up to rounding).
FAMILY_TOL = 1e-12


@pytest.mark.parametrize("case", WIP_SPECIAL_CASES, ids=lambda c: c.name)
def test_family_substitution_is_the_family(case):
    rng = np.random.default_rng(SEED)
    for _ in range(5):
        p = random_wip_parameters(rng)
        applied = case.apply(p).as_dict()
        subs = family_substitution((case.name,))
        values = {sp.Symbol(k, real=True): v for k, v in p.as_dict().items()}
        for name, value in applied.items():
            symbol = sp.Symbol(name, real=True)
            symbolic = float(sp.sympify(subs.get(symbol, symbol)).xreplace(values))
            assert symbolic == pytest.approx(value, rel=FAMILY_TOL, abs=FAMILY_TOL), (case.name,
                                                                                      name)


def test_eq25_residual_is_the_tables_missing_term():
    r"""Seed 001's eq. (25): C[1,2] is 0 where the truth has
    :math:`(MY_1\sin\phi - MX_1\cos\phi)\,\dot\psi` in the file's own symbols (its
    declarations ``MY1 = MY(body)``, ``MX1 = MX(body)``; the table's
    :math:`m_S d\sin\phi\,\dot\psi` where the centre of mass is above the axle, which the
    file no longer declares: eq. (25) writes MX1); under its family (no I_a)."""
    engine = ComparisonEngine(samples=200, param_sets=2, seed=SEED)
    result = engine.compare(load_derivation(SHIPPED / "seed001" / "eq25_lagrange.toml"))
    assert result.truth_in_document
    records = {r.element: r for r in result.records}
    MX1, MY1, phi, dpsi = sp.symbols("MX1 MY1 phi dpsi", real=True)
    names = {"MX1": MX1, "MY1": MY1, "phi": phi, "dpsi": dpsi}
    residual = sp.sympify(records["C[1,2]"].residual, locals=names)
    assert sp.simplify(residual - (MY1 * sp.sin(phi) - MX1 * sp.cos(phi)) * dpsi) == 0
    assert "d_x" not in records["C[1,2]"].truth and "I_a" not in records["A[1,1]"].truth
    assert "m_S" not in records["A[1,1]"].truth            # the model's symbols are gone
