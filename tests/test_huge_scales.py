r"""Terms of huge size (a length of 1e99 in a URDF, within the inputs' bound of 1e100): a
term's sign error is found as at any scale, and nothing overflows — the squared tolerance,
:math:`(10^{-7}\cdot 10^{160})^2`, had raised Python's ``OverflowError`` at comparison time.
The element :math:`a + b\cos q` with :math:`b` of the wrong sign, at the scale 1e160."""

from __future__ import annotations

import numpy as np
import pytest
import sympy as sp

from conftest import SEED
from wheeled_dyn.compare.judge.diagnose import term_diagnoses
from wheeled_dyn.compare.records import DiagnosisKind as K

#: The scale of the element's values.
SCALE = 1e160

q, a, b = sp.symbols("q a b", real=True)


@pytest.mark.parametrize("scale", [1.0, SCALE])
def test_a_terms_sign_is_found_at_any_scale(scale: float) -> None:
    rng = np.random.default_rng(SEED)
    values = {q: rng.uniform(-3, 3, 200), a: scale * rng.uniform(1, 2, 200),
              b: scale * rng.uniform(1, 2, 200)}

    def evaluate(e: sp.Expr) -> np.ndarray:
        return sp.lambdify([q, a, b], e, "numpy")(values[q], values[a], values[b])
    T = evaluate(a + b * sp.cos(q))
    D = evaluate(a - b * sp.cos(q))
    with np.errstate(all="ignore"):             # as the engine judges (a sum of squares: inf)
        found = term_diagnoses(a - b * sp.cos(q), evaluate, D, T, float(np.abs(T).max()))
    assert [x.kind for x in found] == [K.SIGN] and "b*cos(q)" in found[0].text, found
