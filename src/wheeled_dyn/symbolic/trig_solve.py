r"""Exact solution of linear systems whose entries are polynomials in parameters and in the
sines and cosines of angles.

:math:`X = M^{-1}E` by Gaussian elimination over the fraction field
:math:`\mathbb Q(p_1, \dots, s_1, c_1, \dots)` with :math:`s_k = \sin x_k`,
:math:`c_k = \cos x_k` as independent indeterminates (SymPy's ``DomainMatrix``), floats made
exact first (:data:`FLOAT_NOISE`); each entry's numerator and denominator are then reduced
modulo :math:`s_k^2 + c_k^2 = 1` (:func:`~.simplify.canonical_trig`), which is exact because
the identity holds on the whole domain.
"""

from __future__ import annotations

from collections.abc import Sequence

import sympy as sp
from sympy.polys.matrices import DomainMatrix

from .simplify import canonical_trig


def _angles(exprs: Sequence[sp.Expr]) -> dict[sp.Expr, sp.Dummy]:
    fwd: dict[sp.Expr, sp.Dummy] = {}
    for e in exprs:
        for a in sp.sympify(e).atoms(sp.sin, sp.cos):
            fwd.setdefault(a, sp.Dummy(f"{type(a).__name__}"))
    return fwd


def reduce_fraction(e: sp.Expr) -> sp.Expr:
    """A rational function of sines and cosines with numerator and denominator each in
    canonical form (exact: both are reduced modulo :math:`\\sin^2 + \\cos^2 = 1`)."""
    num, den = sp.fraction(sp.cancel(sp.together(e)))
    num, den = canonical_trig(num), canonical_trig(den)
    return sp.cancel(num / den) if not den.has(sp.sin, sp.cos) else num / den


#: Floats below this size in a matrix to invert are rounding noise of composed rotations
#: (a locked joint's 1e-16): taken as 0. Other floats become the rationals they print as, so
#: the elimination runs over exact numbers (over floats it is slow and loses digits).
FLOAT_NOISE = 1e-12


def _exact_numbers(M: sp.Matrix) -> sp.Matrix:
    r"""``M`` with its floats exact: noise (:data:`FLOAT_NOISE`) as 0, others as rationals."""
    floats = M.atoms(sp.Float)
    if not floats:
        return M
    return M.xreplace({f: sp.Integer(0) if abs(f) < FLOAT_NOISE
                       else sp.nsimplify(f, rational=True) for f in floats})


def trig_solve(M: sp.Matrix, E: sp.Matrix) -> sp.Matrix:
    r""":math:`X = M^{-1}E` for a square ``M`` whose entries are polynomials in parameters and
    in sines and cosines: exact Gaussian elimination over the fraction field with
    :math:`\sin x, \cos x` as indeterminates, then each entry reduced (:func:`reduce_fraction`)."""
    M, E = _exact_numbers(M), _exact_numbers(E)
    fwd = _angles(list(M) + list(E))
    back = {d: a for a, d in fwd.items()}
    Md, Ed = M.xreplace(fwd), E.xreplace(fwd)
    dm = DomainMatrix.from_Matrix(Md).to_field()
    de = DomainMatrix.from_Matrix(Ed)
    K = dm.domain.unify(de.domain)
    X = dm.convert_to(K).lu_solve(de.convert_to(K)).to_Matrix()
    return X.applyfunc(lambda e: reduce_fraction(sp.sympify(e).xreplace(back)))
