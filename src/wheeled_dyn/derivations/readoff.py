r"""Reading A, h, Q and B off equations of motion written out term by term.

A document often prints its equations as sums (Kim et al.'s eq. (1):
:math:`3(m_c+m_s)\ddot x - m_s d\cos\phi\,\ddot\phi + m_s d\sin\phi(\dot\phi^2+\dot\psi^2)
= -(\alpha_3+\beta_3)/R`). With every term moved to the left,

.. math::

    \underbrace{\textstyle\sum_j A_{ij}\,\ddot q_j}_{\text{linear in } \ddot q}
    + \underbrace{h_i}_{\text{quadratic in } \dot q}
    + \underbrace{Q_i}_{\text{free of } \dot q,\ \ddot q,\ u}
    - \underbrace{\textstyle\sum_k B_{ik} u_k}_{\text{linear in } u} = 0 ,

each term of the expanded left side belongs to exactly one of the four groups, and
:math:`h = C\dot q` for any valid :math:`C`. A term that fits none of them (linear in a
velocity, like a viscous friction term; a product of an acceleration and a velocity; a
function of a velocity) is reported by name: the toolkit's form cannot hold it.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import NamedTuple

import sympy

from ..errors import DerivationError
from ..expression_size import free_symbols_of, node_count


class EquationTerms(NamedTuple):
    r"""The parts of :math:`A\ddot q + h + Q = B u` in the document's coordinates.

    ``A`` n×n, ``h`` n×1 (:math:`C\dot q`), ``Q`` n×1, ``B`` n×k with columns in the order of
    ``inputs``. In a matrix-form file a part the document does not give is None.
    """

    A: sympy.ImmutableMatrix | None
    h: sympy.ImmutableMatrix | None
    Q: sympy.ImmutableMatrix | None
    B: sympy.ImmutableMatrix | None
    inputs: tuple[sympy.Symbol, ...]


def _degrees(term: sympy.Expr, group: Sequence[sympy.Symbol]) -> dict[sympy.Symbol, int] | None:
    r"""Exponents of the symbols of ``group`` in the monomial ``term``; None if ``term`` is not a
    monomial in them (a symbol inside a function, a negative or symbolic power)."""
    members = set(group)
    found: dict[sympy.Symbol, int] = {}
    for factor in sympy.Mul.make_args(term):
        base, exp = factor.as_base_exp()
        if base in members:
            if not (exp.is_Integer and exp > 0):
                return None
            found[base] = found.get(base, 0) + int(exp)
        elif factor.has(*members):
            return None
    return found


def split_equation_terms(expressions: Sequence[sympy.Expr],
                         accelerations: Sequence[sympy.Symbol],
                         velocities: Sequence[sympy.Symbol],
                         inputs: Sequence[sympy.Symbol],
                         path: str | Path = "<equations>") -> EquationTerms:
    r"""Split each ``expressions[i]`` (left side minus right side of equation i+1) into A, h, Q
    and B as in the module docstring. Raises :class:`DerivationError` naming ``equation i``,
    the term and the velocity or input it is linear in when a term fits no group."""
    n, k = len(expressions), len(inputs)
    if len(accelerations) != n:
        raise DerivationError(path, "equations", f"{n} equations for {len(accelerations)} "
                                                 "coordinates")
    # each element's terms, summed once at the end (adding one term at a time to a SymPy sum
    # rebuilds it: quadratic in the terms of a solved form's element, minutes for thousands)
    A: list[list[list[sympy.Expr]]] = [[[] for _ in range(n)] for _ in range(n)]
    h: list[list[sympy.Expr]] = [[] for _ in range(n)]
    Q: list[list[sympy.Expr]] = [[] for _ in range(n)]
    B: list[list[list[sympy.Expr]]] = [[[] for _ in range(k)] for _ in range(n)]
    acc_index = {a: j for j, a in enumerate(accelerations)}
    inp_index = {u: j for j, u in enumerate(inputs)}
    everything = [*accelerations, *velocities, *inputs]
    vel_set = set(velocities)
    for i, expr in enumerate(expressions):
        item = f"equation {i + 1}"
        for term in sympy.Add.make_args(_expanded(expr, everything)):
            degrees = _degrees(term, everything)
            if degrees is None:
                raise DerivationError(path, item, f"term {term} is not a polynomial in the "
                                      "accelerations, velocities and inputs", _line(path, i))
            acc = {s: e for s, e in degrees.items() if s in acc_index}
            vel = {s: e for s, e in degrees.items() if s in vel_set}
            inp = {s: e for s, e in degrees.items() if s in inp_index}
            n_acc, n_vel, n_inp = sum(acc.values()), sum(vel.values()), sum(inp.values())
            if n_acc:
                if n_acc != 1 or n_vel or n_inp:
                    raise DerivationError(path, item, f"term {term} is not linear in the "
                                          "accelerations alone", _line(path, i))
                (a,) = acc
                A[i][acc_index[a]].append(term / a)
            elif n_inp:
                if n_inp != 1 or n_vel:
                    raise DerivationError(path, item, f"term {term} is not linear in the "
                                          "inputs alone", _line(path, i))
                (u,) = inp
                B[i][inp_index[u]].append(-term / u)
            elif n_vel == 2:
                h[i].append(term)
            elif n_vel == 0:
                Q[i].append(term)
            else:
                names = ", ".join(str(s) for s in vel)
                what = (f"linear in the velocity {names}" if n_vel == 1
                        else f"of degree {n_vel} in the velocities ({names})")
                raise DerivationError(path, item, f"term {term} is {what}: it is neither an "
                                      "inertia, Coriolis/centrifugal, gravity nor input term",
                                      _line(path, i))
    return EquationTerms(_summed(A, n, n), _summed([[t] for t in h], n, 1),
                         _summed([[t] for t in Q], n, 1), _summed(B, n, k), tuple(inputs))


#: Most nodes of a denominator multiplied out in every term of an expanded equation; a larger
#: one (the determinant of a solved form, its abbreviations written out) is held whole.
DENOMINATOR_NODES = 200


def _expanded(expr: sympy.Expr, generators: Sequence[sympy.Symbol]) -> sympy.Expr:
    r"""``expand(expr)``, an exponential of a sum kept whole (exp(-10⁴(q - 1)²) split
    overflows). A denominator of more than :data:`DENOMINATOR_NODES` nodes free of the
    ``generators`` (accelerations, velocities, inputs) — :math:`1/\det M` of a solved form,
    written out — is expanded once and held as one symbol while the rest is: expanded with the
    rest, it is multiplied out again in every term (10–21 s per equation of the ROS
    balancer solved in three coordinates, measured). The terms are the same products, each
    with its denominator beside it."""
    held = set(generators)
    denominators = {p for p in expr.atoms(sympy.Pow) if p.exp.is_negative and p.base.is_Add
                    and node_count(p.base, DENOMINATOR_NODES) > DENOMINATOR_NODES
                    and not free_symbols_of(p.base) & held}
    if not denominators:
        return sympy.expand(expr, power_exp=False)
    symbols = {p: sympy.Dummy() for p in denominators}
    back = {x: sympy.Pow(sympy.expand(p.base, power_exp=False), p.exp)
            for p, x in symbols.items()}
    return sympy.expand(expr.xreplace(symbols), power_exp=False).xreplace(back)


def _summed(terms: list[list[list[sympy.Expr]]], rows: int, cols: int) -> sympy.ImmutableMatrix:
    r"""The matrix whose element (i, j) is the sum of ``terms[i][j]``."""
    return sympy.ImmutableMatrix(rows, cols, [sympy.Add(*terms[i][j]) for i in range(rows)
                                              for j in range(cols)])


def _line(path: str | Path, i: int) -> int | None:
    r"""The line of equation ``i`` (from 0) in the file ``path``, where it can be found."""
    from .source import array_item_line
    return array_item_line(path, "matrices", "equations", i)

