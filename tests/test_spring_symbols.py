r"""A spring's stiffness and rest length declared as document symbols are read as the model's
parameters ``k_<name>``, ``rest_<name>`` (drawn in every parameter set, symbols in the closed
forms): the truth and truth − document are written in the document's K and l0, never with
the URDF's numbers. The particle on a table tied by a linear spring to a fixed point, polar
r, θ (seed 000's 4.6; Meriam & Kraige, *Engineering Mechanics: Dynamics*, polar coordinates):
m r̈ − m r θ̇² + K (r − l0) = 0, m r² θ̈ + 2 m r ṙ θ̇ = 0."""

from __future__ import annotations

import sympy as sp

import wheeled_dyn as wd
from wheeled_dyn.compare.records import DiagnosisKind as K, Verdict

m, k, l0, r, theta, dr, dtheta = sp.symbols("m K l0 r theta dr dtheta")


def _table(spring):
    return wd.compare(
        "spring_table",
        coordinates={"positions": ["r", "theta"], "configuration": {"r": "r", "theta": "theta"},
                     "ranges": {"r": [0.2, 1.5]}},
        A=sp.diag(m, m * r**2), C=sp.Matrix([[0, -m * r * dtheta], [m * r * dtheta, m * r * dr]]),
        Q=sp.Matrix([spring, 0]),
        symbols={"m": "M(ball)", "K": "k_radial", "l0": "rest_radial"},
        assumes={"families": ["urdf_proportions"]})


def test_the_spring_in_the_documents_symbols():
    result = _table(k * (r - l0))
    assert all(x.verdict == Verdict.AGREES for x in result.records)
    q = next(x for x in result.records if x.element == "Q[1]")
    assert sp.simplify(sp.sympify(q.truth) - k * (r - l0)) == 0


def test_a_wrong_rest_length_is_written_in_the_documents_symbols():
    result = _table(k * (r + l0))
    q = next(x for x in result.records if x.element == "Q[1]")
    assert q.verdict == Verdict.DIFFERS and any(d.kind == K.SIGN for d in q.diagnoses)
    assert sp.simplify(sp.sympify(q.residual) + 2 * k * l0) == 0


def test_the_rest_length_written_as_its_number_differs():
    r"""The rest length is a parameter like a length (drawn in every set, as the stiffness
    is): K (r − 1/2), with the model's own 0.5 m written as a number, is right for this model
    only, and differs; K (r − l0) agrees (above)."""
    result = _table(k * (r - sp.Rational(1, 2)))
    q = next(x for x in result.records if x.element == "Q[1]")
    assert q.verdict == Verdict.DIFFERS
    assert result.equivalent is False


def test_every_set_draws_its_own_rest_length_and_keeps_a_zero_one():
    from wheeled_dyn.compare.grid.samples import parameter_sets
    import numpy as np
    table = [ps.values["rest_radial"] for ps in
             parameter_sets("spring_table", 4, np.random.default_rng(0))]
    assert len(set(table)) == 4 and all(0.25 <= v <= 1.0 for v in table)   # 0.5 × [0.5, 2]
    block = parameter_sets("spring_block", 3, np.random.default_rng(0))
    assert all(v == 0.0 for ps in block for name, v in ps.values.items()
               if name.startswith("rest_"))
