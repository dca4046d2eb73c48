r"""The ``[matrices]`` table: A, C, Q, B (or Gamma), G, or the equations as written.

Shapes, with n the number of the document's positions and k the number of its inputs:

======== ================= =====================================================
key      shape             meaning
======== ================= =====================================================
A        n×n               inertia matrix, coefficient of the accelerations
C        n×n               Coriolis/centrifugal matrix, :math:`h = C\dot q`
Q        n                 gravity vector (left side)
B        n×k               input matrix, columns in the order of the inputs
Gamma    n                 generalized forces as printed, linear in the inputs;
                           the loader derives :math:`B = \partial\Gamma/\partial u`
G        m×n               constraint matrix (multipliers side)
======== ================= =====================================================

A matrix is either text in SymPy list syntax (``"[[a, b], [c, d]]"``) or a TOML array of
arrays of strings or numbers. An element ``"?"`` marks a place the extracted text lost and
the file does not restore; it becomes ``sympy.nan`` and its label (``C[5,1]``) is recorded.
Labels are 1-based, as documents number their elements. ``{ latex = '\begin{bmatrix} ...
\end{bmatrix}' }`` gives a matrix as LaTeX (:mod:`.latex`), one element per cell.
"""

from __future__ import annotations

import re
from typing import TYPE_CHECKING, Any

import sympy

from .expressions import ExpressionError, split_nested
from .latex import LatexSource, split_latex_matrix, unwrap_latex

if TYPE_CHECKING:  # pragma: no cover
    from .loader import _Loader

#: Keys of ``[matrices]``.
MATRIX_KEYS: tuple[str, ...] = ("A", "C", "Q", "B", "Gamma", "G", "equations")
#: An element the text lost.
MISSING_ELEMENT = "?"
_LABEL = re.compile(r"^([A-Za-z]+)\[(\d+)(?:,\s*(\d+|:))?\]$")
_EQUATION_LABEL = re.compile(r"^equation (\d+)$")


class MatrixReader:
    r"""Reads the matrices of one file with the loader's namespace and error reporting."""

    def __init__(self, loader: "_Loader", n: int, inputs: tuple[sympy.Symbol, ...],
                 table: str = "matrices") -> None:
        self.ld = loader
        self.table = table
        #: what element labels start with (``state_space.`` outside ``[matrices]``)
        self.prefix = "" if table == "matrices" else f"{table}."
        self.n = n
        self.inputs = inputs
        self.missing: list[str] = []
        self.equations: tuple[sympy.Eq, ...] | None = None
        self.shapes: dict[str, tuple[int, int]] = {}

    def _nested(self, key: str, raw: Any, top: bool = True) -> Any:
        raw = unwrap_latex(raw)
        if isinstance(raw, LatexSource):        # a whole matrix, or one element of an array
            if not top:
                return raw
            try:
                return [[LatexSource(c) for c in row] for row in split_latex_matrix(raw)]
            except ExpressionError as exc:
                raise self.ld.fail(self.prefix + key, exc.reason,
                                   self.ld.line(self.table, key)) from exc
        if isinstance(raw, str):
            try:
                return split_nested(raw)
            except ExpressionError as exc:
                raise self.ld.fail(self.prefix + key, exc.reason,
                                   self.ld.line(self.table, key)) from exc
        if isinstance(raw, list):
            return [self._nested(key, r, top=False) for r in raw]
        if isinstance(raw, (int, float)) and not isinstance(raw, bool):
            return str(raw)
        raise self.ld.fail(self.prefix + key, f"expected a matrix (text or array), got "
                           f"{raw!r}", self.ld.line(self.table, key))

    def _element(self, key: str, label: str, text: Any) -> sympy.Expr:
        if not isinstance(text, str):
            raise self.ld.fail(label, "expected an element, got a list",
                               self.ld.line(self.table, key))
        if text.strip() == MISSING_ELEMENT:
            self.missing.append(label)
            return sympy.nan
        value = self.ld.expr(text, label, self.table, key)
        accelerations = sorted(str(s) for s in value.free_symbols
                               if self.ld.kinds.get(str(s)) == "acceleration")
        if accelerations:
            raise self.ld.fail(label, f"holds the acceleration {accelerations[0]}: the "
                               "matrices A, C, Q, B (Gamma) and G hold positions and "
                               "velocities only (the accelerations are what A multiplies)",
                               self.ld.line(self.table, key, accelerations[0]))
        return value

    def _shape_error(self, key: str, got: str, rows: int | None, cols: int) -> Exception:
        expected = f"{rows if rows is not None else 'm'}×{cols}"
        names = ", ".join(name for name, kind in self.ld.kinds.items() if kind == "position")
        what = f"n = {self.n} positions: {names}" if not self.prefix else \
            f"{self.n} entries of the state"
        return self.ld.fail(self.prefix + key, f"shape {got}, expected {expected} ({what}; "
                            f"k = {len(self.inputs)} inputs)", self.ld.line(self.table, key))

    def grid(self, key: str, raw: Any, rows: int | None, cols: int,
             vector: bool = False) -> sympy.ImmutableMatrix:
        r"""Parse ``raw`` as a rows×cols matrix (``rows=None``: any number of rows; ``vector``:
        an n-vector, written flat or as a column)."""
        nested = self._nested(key, raw)
        if isinstance(nested, str):
            raise self._shape_error(key, "a single element", rows, cols)
        flat = all(isinstance(x, str) for x in nested)
        if vector:
            if flat:
                nested = [[x] for x in nested]
            if len(nested) != rows or any(not isinstance(r, list) or len(r) != 1
                                          for r in nested):
                raise self._shape_error(key, f"{len(nested)} entries", rows, cols)
            return sympy.ImmutableMatrix([[self._element(key, f"{self.prefix}{key}[{i + 1}]",
                                                         r[0])] for i, r in enumerate(nested)])
        if flat:
            if cols == 1 and len(nested) == rows:
                nested = [[x] for x in nested]
            elif rows is None and len(nested) == cols:
                nested = [nested]
            else:
                raise self._shape_error(key, f"a flat list of {len(nested)}", rows, cols)
        if rows is not None and len(nested) != rows:
            raise self._shape_error(key, f"{len(nested)} rows", rows, cols)
        out = []
        for i, row in enumerate(nested):
            if not isinstance(row, list) or len(row) != cols:
                got = len(row) if isinstance(row, list) else 1
                raise self.ld.fail(f"{self.prefix}{key}[{i + 1},:]", f"row {i + 1} has {got} "
                                   f"elements, expected {cols}", self.ld.line(self.table, key))
            out.append([self._element(key, f"{self.prefix}{key}[{i + 1},{j + 1}]", x)
                        for j, x in enumerate(row)])
        return sympy.ImmutableMatrix(out)

    def equation(self, text: Any, item: str, table: str, key: str) -> sympy.Eq:
        r"""Parse ``"lhs = rhs"`` (exactly one ``=``), or a LaTeX equation."""
        text = unwrap_latex(text)
        if isinstance(text, LatexSource):
            text = self.ld.from_latex(text, item, table, key, equation=True)
        if not isinstance(text, str) or text.count("=") != 1:
            raise self.ld.fail(item, "expected \"left side = right side\" with one '='",
                               self.ld.line(table, key, str(text)[:30]))
        lhs, rhs = text.split("=")
        return sympy.Eq(self.ld.expr(lhs, item, table, key), self.ld.expr(rhs, item, table, key),
                        evaluate=False)

    def _check_keys(self, table: dict[str, Any]) -> None:
        r"""The keys of ``[matrices]`` are known and fit together: equations or matrices, B or
        Gamma (and document inputs for them), something besides G."""
        ld, k = self.ld, len(self.inputs)
        for key in table:
            if key not in MATRIX_KEYS:
                raise ld.fail(f"matrices.{key}", "unknown key; valid: " + ", ".join(MATRIX_KEYS),
                              ld.line("matrices", key))
        given = set(table)
        if "equations" in given and given & {"A", "C", "Q", "B", "Gamma"}:
            raise ld.fail("matrices", "give either equations or A, C, Q, B/Gamma, not both",
                          ld.line("matrices"))
        if "B" in given and "Gamma" in given:
            raise ld.fail("matrices", "give B or Gamma, not both", ld.line("matrices", "Gamma"))
        if not given - {"G"}:
            raise ld.fail("matrices", "no matrices and no equations", ld.line("matrices"))
        if given & {"B", "Gamma"} and k == 0:
            raise ld.fail("matrices", "B/Gamma need document inputs (symbols with input = true)",
                          ld.line("matrices", "B") or ld.line("matrices", "Gamma"))

    def _equations(self, raw: Any) -> tuple[sympy.Eq, ...]:
        r"""``equations = ["lhs = rhs", ...]``: one per position."""
        eqs = unwrap_latex(raw)
        if not isinstance(eqs, list):
            raise self.ld.fail("equations", "expected a list of \"lhs = rhs\"",
                               self.ld.line("matrices", "equations"))
        if len(eqs) != self.n:
            raise self.ld.fail("equations", f"{len(eqs)} equations for {self.n} positions",
                               self.ld.line("matrices", "equations"))
        return tuple(self.equation(t, f"equation {i + 1}", "matrices", "equations")
                     for i, t in enumerate(eqs))

    def read(self, table: dict[str, Any]) -> dict[str, sympy.ImmutableMatrix]:
        r"""All matrices of ``[matrices]`` (and :attr:`equations`), shapes checked."""
        n, k = self.n, len(self.inputs)
        self._check_keys(table)
        out: dict[str, sympy.ImmutableMatrix] = {}
        for key in ("A", "C"):
            if key in table:
                out[key] = self.grid(key, table[key], n, n)
        if "Q" in table:
            out["Q"] = self.grid("Q", table["Q"], n, 1, vector=True)
        if "B" in table:
            out["B"] = self.grid("B", table["B"], n, k)
        if "Gamma" in table:
            out["B"] = self._input_matrix(self.grid("Gamma", table["Gamma"], n, 1, vector=True))
        if "G" in table:
            out["G"] = self.grid("G", table["G"], None, n)
        if "equations" in table:
            self.equations = self._equations(table["equations"])
        for key in ("A", "C", "Q", "G"):
            self.without_inputs(key, out.get(key))
        self._without_rates(out.get("Q"))
        self.shapes = {key: M.shape for key, M in out.items()}
        return out

    def _without_rates(self, Q: sympy.ImmutableMatrix | None) -> None:
        r"""A velocity or an acceleration inside Q is an error naming the element: Q is the
        part of the equations free of them (velocity terms go in C, as C q̇; a document that
        keeps them together writes its equations)."""
        if Q is None:
            return
        names = {*self.ld.coordinates.get("velocities", ()),
                 *self.ld.coordinates.get("accelerations", ())}
        for i, e in enumerate(Q):
            found = sorted((s for s in e.free_symbols if s.name in names), key=str)
            if found:
                raise self.ld.fail(f"Q[{i + 1}]", f"the velocity or acceleration {found[0]} "
                                   "in Q: Q holds the terms free of them; velocity terms go in "
                                   "C (as C q̇), or write the equations",
                                   self.ld.line("matrices", "Q"))

    def without_inputs(self, key: str, M: sympy.ImmutableMatrix | None) -> None:
        r"""A document input (a torque) inside A, C, Q or G is an error naming the element:
        the inputs enter through B (or an equation's right side)."""
        if M is None or not self.inputs:
            return
        for idx, e in enumerate(M):
            found = sorted(e.free_symbols & set(self.inputs), key=str)
            if found:
                i, j = divmod(idx, M.cols)
                where = self.prefix + (f"{key}[{i + 1}]" if M.cols == 1 and key == "Q" else
                                       f"{key}[{i + 1},{j + 1}]")
                raise self.ld.fail(where, f"the input {found[0]} in {key}: inputs enter "
                                   "through B (or an equation's right side), A C Q G hold "
                                   "none", self.ld.line(self.table, key))

    def _input_matrix(self, gamma: sympy.ImmutableMatrix) -> sympy.ImmutableMatrix:
        B = gamma.jacobian(sympy.Matrix(self.inputs))
        for i in range(self.n):
            rest = sympy.expand(gamma[i] - sum(B[i, j] * u for j, u in enumerate(self.inputs)))
            if rest != 0 or B[i, :].has(*self.inputs):
                raise self.ld.fail(f"Gamma[{i + 1}]", "not linear and homogeneous in the "
                                   f"inputs {', '.join(map(str, self.inputs))}",
                                   self.ld.line("matrices", "Gamma"))
        return sympy.ImmutableMatrix(B)

    def check_label(self, label: str, line: int | None) -> None:
        r"""A ``[reconstructed]`` label that names an element (``A[3,3]``, ``Q[2]``,
        ``C[5,:]``, ``equation 2``) must exist; other labels are free text."""
        eq = _EQUATION_LABEL.match(label)
        if eq:
            if self.equations is None or not 1 <= int(eq.group(1)) <= len(self.equations):
                raise self.ld.fail(f"reconstructed.{label}", "no such equation", line)
            return
        found = _LABEL.match(label)
        if not found:
            return
        key, i, j = found.group(1), int(found.group(2)), found.group(3)
        if key == "Gamma":
            key = "B"
        if key not in self.shapes:
            raise self.ld.fail(f"reconstructed.{label}", f"the file gives no matrix {key}", line)
        rows, cols = self.shapes[key]
        bad = not 1 <= i <= rows or (j not in (None, ":") and not 1 <= int(j) <= cols)
        if bad:
            raise self.ld.fail(f"reconstructed.{label}", f"outside {key} ({rows}×{cols})", line)
