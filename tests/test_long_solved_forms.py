r"""A 3×3 form solved for its accelerations with its abbreviations written out: the ROS
balancer in heading speed, heading rate and pitch solved by Cramer's rule
(:func:`balancer_solved.balancer_solved` with ``heading``), elements of hundreds of terms, each
over the written-out determinant (megabytes of text). It took 291 s to compare (the
determinant multiplied out in every term, the elements printed whole); held whole, 17–34 s,
with the same verdicts and names.

And the walks that make that possible (:mod:`wheeled_dyn.expression_size`) agree with
SymPy's own ``free_symbols``, ``atoms`` and ``count_ops`` on random expressions; the read-off
with the determinant held whole gives the same A, h, Q, B as one expanding everything.
"""

from __future__ import annotations

import random

import numpy as np
import pytest
import sympy as sp

from balancer_solved import balancer_solved
from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.compare.records import CauseKind
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.derivations.readoff import split_equation_terms
from wheeled_dyn.expression_size import atoms_of, free_symbols_of, node_count, ops_over

#: Relative tolerance of two readings of the same element at a random point.
RTOL = 1e-9


@pytest.mark.parametrize("planted", [False, True], ids=["right", "wheel-spin-dropped"])
def test_a_three_by_three_solved_form_is_judged_and_named(tmp_path, planted):
    r"""Right, it agrees; with the wheels' spin inertia :math:`2J_w/R^2` dropped from M11, it
    differs, named as the 2×2 form's is (a point mass, the wheels' own moment about their
    axles times :math:`R^{-2}`); the elements too long to print say so."""
    path = balancer_solved(tmp_path, *(("2*J_w/R**2", "0") if planted else ()), heading=True)
    result = ComparisonEngine(samples=200, param_sets=3, seed=SEED).compare(
        load_derivation(path))
    assert result.equivalent is not planted, [c.explanation for c in result.causes]
    long = [r for r in result.records if r.document.startswith("(not printed")]
    assert long and all(r.document_latex.startswith(r"\text{(not printed") for r in long)
    if not planted:
        return
    said = next(c.explanation for c in result.causes if c.kind == CauseKind.POINT_MASS)
    assert "A[1,1]: the moment of inertia Iyy(left_wheel) + Iyy(right_wheel) about its own " \
        "centre of mass × R**(-2) is missing, a point mass (truth − document = 2*J_w/R**2)" \
        in said, said


def _random_expr(rng: random.Random, symbols: list[sp.Symbol], depth: int) -> sp.Expr:
    r"""A random expression of sums, products, powers, sines and a shared subexpression."""
    if depth == 0:
        return rng.choice([*symbols, sp.Integer(rng.randint(-3, 3)), sp.Rational(1, 3)])
    a, b = (_random_expr(rng, symbols, depth - 1) for _ in range(2))
    return rng.choice([a + b, a * b, a ** 2, sp.sin(a) + b, a / (b + 7), (a + b) * (a - b)])


def test_the_walks_agree_with_sympys_own():
    rng = random.Random(SEED)
    symbols = list(sp.symbols("x y z dx"))
    for _ in range(60):
        e = _random_expr(rng, symbols, rng.randint(1, 5))
        assert free_symbols_of(e) == e.free_symbols, e
        assert atoms_of(e, sp.sin, sp.Number) == e.atoms(sp.sin, sp.Number), e
        ops = int(sp.count_ops(e))
        for limit in (0, ops - 1, ops, ops + 1, 10 * ops):
            assert ops_over(e, limit) is (ops > limit), (e, limit)
        nodes = sum(1 for _ in sp.preorder_traversal(e))
        assert node_count(e, 10 ** 6) == nodes and node_count(e, 2) == min(nodes, 3)
    M = sp.ImmutableMatrix([[symbols[0], sp.sin(symbols[1])]])
    assert free_symbols_of(M) == M.free_symbols and atoms_of(M, sp.sin) == {sp.sin(symbols[1])}


def test_a_determinant_held_whole_reads_off_the_same_equations():
    r"""A 3×3 system solved by Cramer's rule with a determinant of more than 200 nodes (held
    whole while the equations are expanded): at random accelerations, velocities, inputs and
    parameters, :math:`A\ddot q + h + Q - Bu` read off equals each equation evaluated as
    written (nothing multiplied out)."""
    q, dq, u = sp.symbols("q"), sp.symbols("dq1 dq2 dq3"), sp.symbols("u1 u2")
    a, b, c = sp.symbols("a b c", positive=True)
    Mx = sp.Matrix(3, 3, lambda i, j: ((i + 1) * a + (j + 1) ** 2 * b * sp.cos(q) ** (i + 1)
                                       + (i + 2) * c * sp.sin(q) ** j
                                       + (i * j % 2) * a * b * sp.cos(2 * q)))
    f = sp.Matrix([dq[0] * dq[i] * b * sp.sin(q) + u[i % 2] * (a + i) - c * sp.cos(q) * i
                   for i in range(3)])
    det = sp.expand(Mx.det())
    assert node_count(det, 200) > 200
    acc = sp.symbols("ddq1 ddq2 ddq3")
    eqs = [acc[i] - (Mx.adjugate() * f)[i] / det for i in range(3)]
    read = split_equation_terms(eqs, acc, dq, u)
    assert read.A == sp.eye(3)
    rng = np.random.default_rng(SEED)
    for _ in range(5):
        point = {s: rng.uniform(0.5, 2) for s in (q, a, b, c, *dq, *acc, *u)}
        left = (read.A * sp.Matrix(acc) + read.h + read.Q - read.B * sp.Matrix(u)).subs(point)
        written = [e.subs(point) for e in eqs]
        assert np.allclose(np.array(left, dtype=float).ravel(),
                           np.array(written, dtype=float), rtol=RTOL, atol=RTOL)
