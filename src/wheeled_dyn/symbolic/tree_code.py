r"""Numeric code and operation counts of closed forms with intermediate variables.

:func:`compile_terms` turns the assignments of a :class:`~.tree.TreeDynamics` (or of a
reduction, :mod:`.tree_reduced`) into one straight-line Python function of
:math:`(q, \dot q, \text{parameters})` that returns :math:`A`, :math:`Q`, the Christoffel
symbols :math:`c_{i,jk}` (dense n×n×n) and :math:`C = \sum_k c_{\cdot,\cdot k}\dot q_k`; it is
what the tests check against Pinocchio at random states. :func:`operation_count` counts the
additions, multiplications and function calls of that code (SymPy's ``count_ops`` conventions:
a subtraction is an addition, a division a multiplication, an integer power :math:`x^k`
:math:`k-1` multiplications).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import sympy as sp
from sympy.printing.pycode import PythonCodePrinter


@dataclass(frozen=True)
class OperationCount:
    r"""Operations of straight-line code: ``additions``, ``multiplications``, ``functions``
    (sin, cos, sqrt ...), and the number of ``assignments`` (intermediate variables)."""

    additions: int
    multiplications: int
    functions: int
    assignments: int

    @property
    def total(self) -> int:
        return self.additions + self.multiplications + self.functions

    def __str__(self) -> str:
        return (f"{self.assignments} intermediate variables, {self.additions} additions, "
                f"{self.multiplications} multiplications, {self.functions} function calls")


def _count(e: sp.Expr, out: list[int]) -> None:
    if e.is_Atom:
        return
    if e.is_Add:
        out[0] += len(e.args) - 1
    elif e.is_Mul:
        args = [a for a in e.args if not (a.is_Number and abs(a) == 1)]
        out[1] += max(len(args) - 1, 0)
    elif e.is_Pow:
        if e.exp.is_Integer and e.exp > 0:
            out[1] += int(e.exp) - 1
        elif e.exp.is_Integer:
            out[1] += int(-e.exp)
        else:
            out[2] += 1
    elif isinstance(e, sp.Function):
        out[2] += 1
    for a in e.args:
        _count(a, out)


def operation_count(assignments: Sequence[tuple[sp.Symbol, sp.Expr]],
                    outputs: Sequence[sp.Expr] = ()) -> OperationCount:
    r"""Operations to evaluate ``assignments`` in order and then ``outputs``; each distinct
    :math:`\sin q_i`, :math:`\cos q_i` counted once (they are computed once)."""
    out = [0, 0, 0]
    trig: set[sp.Expr] = set()
    for e in [x for _, x in assignments] + list(outputs):
        e = sp.sympify(e)
        trig |= e.atoms(sp.sin, sp.cos)
        _count(e.xreplace({t: sp.Dummy() for t in e.atoms(sp.sin, sp.cos)}), out)
    return OperationCount(out[0], out[1], out[2] + len(trig), len(assignments))


class _Printer(PythonCodePrinter):
    def _print_Symbol(self, expr):  # names are valid identifiers or mapped by the caller
        return super()._print_Symbol(expr)


def _source(assignments, inputs: dict[sp.Symbol, str], results: Sequence[tuple[str, list]]
            ) -> str:
    printer = _Printer({"fully_qualified_modules": False, "standard": "python3"})
    lines = ["def _terms(_q, _v, _p):"]
    for sym, text in inputs.items():
        lines.append(f"    {printer.doprint(sym)} = {text}")
    trig: dict[sp.Expr, sp.Symbol] = {}
    body = []
    for w, e in assignments:
        for t in sorted(e.atoms(sp.sin, sp.cos), key=sp.default_sort_key):
            if t not in trig:
                trig[t] = sp.Symbol(f"_t{len(trig)}")
                body.append(f"    {trig[t]} = {printer.doprint(t)}")
        body.append(f"    {printer.doprint(w)} = {printer.doprint(e.xreplace(trig))}")
    lines += body
    for name, exprs in results:
        items = []
        for e in exprs:
            e = sp.sympify(e)
            for t in e.atoms(sp.sin, sp.cos):
                if t not in trig:
                    trig[t] = sp.Symbol(f"_t{len(trig)}")
                    lines.append(f"    {trig[t]} = {printer.doprint(t)}")
            items.append(printer.doprint(e.xreplace(trig)))
        lines.append(f"    {name} = [{', '.join(items)}]")
    lines.append("    return " + ", ".join(name for name, _ in results))
    return "\n".join(lines) + "\n"


def compile_assignments(assignments: Sequence[tuple[sp.Symbol, sp.Expr]],
                        q: Sequence[sp.Symbol], qd: Sequence[sp.Symbol],
                        parameters: Sequence[sp.Symbol],
                        results: Sequence[tuple[str, list]]) -> Callable:
    r"""A function ``f(q, qd, p)`` returning one flat list per ``results`` entry (name, list
    of expressions), the assignments evaluated once in order."""
    inputs = {s: f"_q[{i}]" for i, s in enumerate(q)}
    inputs |= {s: f"_v[{i}]" for i, s in enumerate(qd)}
    inputs |= {s: f"_p[{i}]" for i, s in enumerate(parameters)}
    src = _source(assignments, inputs, results)
    env: dict = {"math": __import__("math")}
    exec("from math import *\n" + src, env)      # straight-line code generated above
    return env["_terms"]


def compile_terms(td) -> Callable[[np.ndarray, np.ndarray, np.ndarray],
                                  tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]]:
    r"""``f(q, qd, p) -> (A, Q, c, C)`` for a :class:`~.tree.TreeDynamics` ``td``; ``p`` in
    the order of ``td.parameters``."""
    n = td.n
    c = [td.christoffel[i][j][k] for i in range(n) for j in range(n) for k in range(n)]
    f = compile_assignments(td.assignments, td.q, td.qd, td.parameters,
                            [("A", list(td.A)), ("Q", list(td.Q)), ("c", c)])

    def terms(q, qd, p):
        A, Q, cc = f(list(map(float, q)), list(map(float, qd)), list(map(float, p)))
        cc = np.array(cc, dtype=float).reshape(n, n, n)
        return (np.array(A, dtype=float).reshape(n, n), np.array(Q, dtype=float), cc,
                cc @ np.asarray(qd, dtype=float))

    return terms
