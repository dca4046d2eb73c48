r"""How big an expression is, and which symbols it holds, without walking a huge one whole.

A document solved for its accelerations by Cramer's rule, with its abbreviations expanded,
has elements of a few hundred terms of thousands of characters each: every term carries
:math:`1/\det M` written out. SymPy's ``count_ops`` and ``free_symbols`` visit every node of
such a tree each time they are asked (seconds per element), although the tree is mostly the
same few subexpressions repeated. The size limits of the reports ask only whether an
expression is over a limit, and the symbols are the same for every repetition of a
subexpression; both are answered here by walks that stop early or visit each distinct
object once.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator

import sympy as sp
from sympy.tensor.array import NDimArray

#: Nodes per operation beyond which a tree is over any operation limit without counting:
#: every SymPy node but a leaf adds an operation (``a + b``, ``a*b``, ``a**b``, ``sin(a)``),
#: and a node has a few leaves of its own (at most 4.5 nodes per operation + 1 on 3000 random
#: expressions measured; tests/test_long_solved_forms.py checks ``ops_over`` against
#: ``count_ops``), so a tree of more nodes than this per operation of the limit is over it.
NODES_PER_OP = 8


def node_count(expr: sp.Basic, cap: int) -> int:
    r"""The number of nodes of ``expr``'s tree, counted up to ``cap + 1`` (the walk stops
    there: a huge tree costs no more than a small one); a matrix counts its elements'."""
    count, stack = 0, _roots(expr)
    while stack:
        node = stack.pop()
        count += 1
        if count > cap:
            return count
        stack.extend(node.args)
    return count


def ops_over(expr: sp.Basic, limit: int) -> bool:
    r"""``sympy.count_ops(expr) > limit``, with ``count_ops`` called only on trees of at most
    :data:`NODES_PER_OP` × (``limit`` + 1) nodes; a larger tree is over the limit."""
    cap = NODES_PER_OP * (limit + 1)
    if node_count(expr, cap) > cap:
        return True
    return bool(sp.count_ops(expr) > limit)


def free_symbols_of(expr: sp.Basic) -> set[sp.Basic]:
    r"""``expr.free_symbols``, each distinct subexpression object visited once (a
    subexpression repeated in every term, :math:`1/\det M`, is read once). A node that binds
    symbols of its own (an integral, a ``Lambda``, a derivative) answers for itself."""
    found: set[sp.Basic] = set()
    for node in _distinct(expr, lambda n: not n.is_Symbol and _generic(type(n))):
        if node.is_Symbol:
            found.add(node)
        elif not _generic(type(node)):
            found |= node.free_symbols
    return found


def atoms_of(expr: sp.Basic, *types: type) -> set[sp.Basic]:
    r"""``expr.atoms(*types)`` — its subexpressions of the given ``types`` —, each distinct
    subexpression object visited once."""
    return {node for node in _distinct(expr, lambda n: True) if isinstance(node, types)}


def _distinct(expr: sp.Basic, inside: Callable[[sp.Basic], bool]) -> Iterator[sp.Basic]:
    r"""Each distinct subexpression object of ``expr`` (of each element of a matrix or
    array) once, the arguments of those for which ``inside`` holds read too."""
    seen: set[int] = set()
    stack = _roots(expr)
    while stack:
        node = stack.pop()
        if id(node) in seen:
            continue
        seen.add(id(node))
        yield node
        if inside(node):
            stack.extend(node.args)


def _roots(expr: sp.Basic) -> list[sp.Basic]:
    r"""The trees a walk of ``expr`` starts from: a matrix's or array's elements, else itself."""
    return list(expr) if isinstance(expr, (sp.MatrixBase, NDimArray)) else [expr]


_GENERIC: dict[type, bool] = {}


def _generic(cls: type) -> bool:
    r"""Whether ``cls`` takes ``free_symbols`` from :class:`sympy.Basic` (its args' union)."""
    if cls not in _GENERIC:
        owner = next(c for c in cls.__mro__ if "free_symbols" in c.__dict__)
        _GENERIC[cls] = owner is sp.Basic
    return _GENERIC[cls]


#: Largest multiple of an angle whose sine, cosine (or hyperbolic) is expanded into powers of
#: the angle's own: sin 2θ = 2 sin θ cos θ, cos(q1 + q2); cosh 1000θ would be a polynomial of
#: degree 1000 (seconds per term, then a recursion too deep).
EXPANDED_MULTIPLE = 4
_TRIG = (sp.sin, sp.cos, sp.tan, sp.cot, sp.sinh, sp.cosh, sp.tanh, sp.coth)


def trig_expandable(expr: sp.Basic) -> bool:
    r"""Whether every trigonometric or hyperbolic function in ``expr`` takes angles of at most
    :data:`EXPANDED_MULTIPLE` times a symbol (each term of its argument)."""
    for f in atoms_of(expr, *_TRIG):
        for term in sp.Add.make_args(f.args[0]):
            c = term.as_coeff_Mul()[0]
            if c.is_Number and abs(c) > EXPANDED_MULTIPLE:
                return False
    return True


def expand_trig_small(expr: sp.Basic) -> sp.Basic:
    r"""``sp.expand_trig(expr)`` where :func:`trig_expandable`, else ``expr`` as it is."""
    return sp.expand_trig(expr) if trig_expandable(expr) else expr


__all__ = ["EXPANDED_MULTIPLE", "NODES_PER_OP", "atoms_of", "expand_trig_small",
           "free_symbols_of", "node_count", "ops_over", "trig_expandable"]
