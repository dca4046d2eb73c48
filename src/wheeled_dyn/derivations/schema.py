r"""What a derivation file says, as frozen records: :class:`Derivation`, :class:`SymbolSpec`,
:class:`CoordinateSpec`.

A derivation is a document's equations of motion

.. math::

    A(q)\,\ddot q + C(q,\dot q)\,\dot q + Q(q) = B\,u \;[+\ G^{\mathsf T}\lambda]

in the document's own coordinates and symbols, transcribed as printed (typos included), with
the declarations needed to relate them to a model of the toolkit: how the document's
coordinates map to the model's (:class:`CoordinateSpec`), what each document symbol is in the
model's parameters (:class:`SymbolSpec`), which model input each document input drives.
Matrices are :class:`sympy.ImmutableMatrix`; elements the extracted text lost and the file
marks ``"?"`` are ``sympy.nan`` and listed in :attr:`Derivation.missing`.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import MappingProxyType

import sympy

from ..errors import DerivationError, UnknownNameError
from .readoff import EquationTerms, split_equation_terms
from .state_space import StateSpace


@dataclass(frozen=True)
class SymbolSpec:
    r"""One document symbol.

    ``value`` is its meaning in the model namespace (parsed from ``value_expr_text``; Khalil
    parameters as ``KHALIL_FUNCTIONS[...](Symbol(link))``), or None for a document input
    (``is_input``) or a free symbol (``free``: a parameter the model lacks, kept symbolic on
    both sides, e.g. a motor constant multiplying an input). ``units`` is the text as written
    (checked by :func:`~wheeled_dyn.derivations.expressions.parse_units`).
    """

    name: str
    symbol: sympy.Symbol
    value_expr_text: str | None
    units: str | None
    meaning: str | None
    value: sympy.Expr | None = None
    is_input: bool = False
    free: bool = False
    latex: str | None = None


@dataclass(frozen=True)
class CoordinateSpec:
    r"""How the document's coordinates relate to the model's.

    ``use`` names a built-in coordinate set of the model (then ``configuration`` and
    ``velocity_map`` are empty: the model defines them), or is None for an inline set.
    ``configuration`` maps a *model* coordinate name to an expression of the document's
    positions and symbols; ``velocity_map`` (quasi-velocity sets) maps a *document* velocity
    name to an expression in the model namespace (model coordinates and velocities
    ``d<coordinate>``), linear in the model velocities. ``rolling`` is ``"eliminate"``,
    ``"multipliers"`` or ``"none"``. ``raw`` is the TOML table as read.
    """

    use: str | None
    kind: str
    positions: tuple[str, ...]
    velocities: tuple[str, ...]
    accelerations: tuple[str, ...]
    configuration: Mapping[str, sympy.Expr]
    velocity_map: Mapping[str, sympy.Expr]
    rolling: str
    units: Mapping[str, str]
    raw: Mapping[str, object]


#: Longest equation text kept as a label when the source names no numbered equation.
LABEL_CHARS = 40
_LABELS = re.compile(r"\s*(\([^)]*\)(?:\s*(?:,|-|–|and)\s*\([^)]*\))*)")


def equation_labels(text: str) -> str:
    r"""The equation labels a ``[source] equations`` text starts with: ``(7.24) dq' + ...`` →
    ``(7.24)``; ``(1)-(3)``, ``(33), (35)`` as they are; a text without labels up to its first
    colon, at most :data:`LABEL_CHARS` characters."""
    m = _LABELS.match(text)
    if m:
        return m.group(1)
    head = text.split(":")[0].strip()
    return head if len(head) <= LABEL_CHARS else head[:LABEL_CHARS - 1] + "…"


@dataclass(frozen=True)
class Derivation:
    r"""A parsed derivation file. See ``docs/derivation-format.md`` for every key.

    Matrix form: ``A`` (n×n), ``C`` (n×n), ``Q`` (n×1), ``B`` (n×k, columns in the order of
    ``input_symbols``; also derived from a ``Gamma`` vector), ``G`` (m×n), each None when the
    document does not give it. Equation form: ``equations`` (n :class:`sympy.Eq`) and
    :meth:`read_off`. All expressions are in the document namespace with ``[definitions]``
    expanded; ``row_scale[i]`` is the factor the document multiplied true row i by.
    """

    path: Path
    title: str
    model: str
    source: Mapping[str, str]
    coordinates: CoordinateSpec
    inputs: Mapping[str, sympy.Expr]
    input_symbols: tuple[sympy.Symbol, ...]
    symbols: Mapping[str, SymbolSpec]
    assumptions: Mapping[str, sympy.Expr]
    definitions: Mapping[str, sympy.Expr]
    row_scale: tuple[sympy.Expr, ...] | None
    A: sympy.ImmutableMatrix | None
    C: sympy.ImmutableMatrix | None
    Q: sympy.ImmutableMatrix | None
    B: sympy.ImmutableMatrix | None
    G: sympy.ImmutableMatrix | None
    equations: tuple[sympy.Eq, ...] | None
    constraints: tuple[sympy.Eq, ...] | None
    missing: tuple[str, ...]
    reconstructed: Mapping[str, str]
    positions: tuple[sympy.Symbol, ...]
    velocities: tuple[sympy.Symbol, ...]
    accelerations: tuple[sympy.Symbol, ...]
    namespace: Mapping[str, sympy.Symbol]
    steps: tuple = ()               # earlier steps as printed (:class:`.steps.Step`)
    feeds: tuple[str, ...] = ()     # stems of the derivation files these steps lead to
    #: ``[assumes]``: families, linearised_about, potential, text (what the document assumes)
    assumes: Mapping[str, object] = field(default_factory=lambda: MappingProxyType({}))
    #: values given as LaTeX: item (``A[2,3]``, ``equation 1``, ``definitions.Mbb``) →
    #: (the LaTeX as written, the SymPy text it was parsed as), for a report to echo
    latex_input: Mapping[str, tuple[str, str]] = field(
        default_factory=lambda: MappingProxyType({}))
    #: ``"declared"``: the file's maps are binding; ``"unknown"``: the document's sign
    #: conventions are not known, a better reading found by the comparison is applied
    convention: str = "declared"
    #: the rates of the accelerations (``ddq`` for ``dq``), names a step may use: a
    #: second-order relation derived from linearised equations
    jerks: tuple[sympy.Symbol, ...] = ()
    #: what a ``[state_space]`` file says besides its equations
    #: (:class:`~.state_space.StateSpace`: the rows stating a position's rate, checked on the
    #: document alone; the row each equation is), None for other files
    state_space: StateSpace | None = None

    @property
    def form(self) -> str:
        r"""``"equations"`` or ``"matrices"``."""
        return "equations" if self.equations is not None else "matrices"

    @property
    def n(self) -> int:
        r"""Number of the document's coordinates."""
        return len(self.positions)

    @property
    def model_values(self) -> dict[sympy.Symbol, sympy.Expr]:
        r"""Document symbol → its value in the model namespace, for symbols that have one."""
        return {s.symbol: s.value for s in self.symbols.values() if s.value is not None}

    def symbol(self, name: str) -> sympy.Symbol:
        r"""The SymPy symbol of a document name (coordinate, velocity, symbol, input ...)."""
        try:
            return self.namespace[name]
        except KeyError:
            raise UnknownNameError("document name", name, self.namespace,
                                   where=str(self.path)) from None

    def apply_assumptions(self, expr: sympy.Basic) -> sympy.Basic:
        r"""``expr`` with the ``[assume]`` names replaced by their values (usually 0)."""
        if not self.assumptions:
            return expr
        return expr.xreplace({self.namespace[k]: v for k, v in self.assumptions.items()})

    def _assumed(self, expr: sympy.Basic, assume: bool) -> sympy.Basic:
        return self.apply_assumptions(expr) if assume else expr

    def read_off(self, *, assume: bool = True, unscale: bool = False) -> EquationTerms:
        r"""A, h = C q̇, Q and B of the document.

        Equation form: read off term by term (:func:`split_equation_terms`); a term linear in
        a velocity raises :class:`DerivationError` naming it. Matrix form: the matrices as
        given, ``h = C q̇`` (None where the document gives no C). ``assume=True`` substitutes
        the ``[assume]`` values (terms the model lacks, usually 0); with ``assume=False`` the
        assumed names are extra inputs, appended after ``input_symbols``. ``unscale=True``
        divides row i by ``row_scale[i]``.
        """
        inputs = tuple(self.input_symbols)
        if not assume:
            inputs += tuple(self.namespace[k] for k in self.assumptions)
        if self.equations is not None:
            exprs = [self._assumed(eq.lhs - eq.rhs, assume) for eq in self.equations]
            terms = split_equation_terms(exprs, self.accelerations, self.velocities, inputs,
                                         self.path)
        else:
            qd = sympy.Matrix(self.velocities)
            A, h, Q, B = (None if M is None else sympy.ImmutableMatrix(self._assumed(M, assume))
                          for M in (self.A, None if self.C is None else self.C * qd, self.Q,
                                    self.B))
            if not assume and B is not None and self.assumptions:
                B = B.row_join(sympy.zeros(self.n, len(self.assumptions)))
            terms = EquationTerms(A, h, Q, B, inputs)
        scale = self.row_scale
        if unscale and scale is not None:
            # row by row, not diag(1/s) * M: a lost element ("?", nan) must stay in its row
            # (0 * nan is nan in a matrix product)
            def unscaled(M: sympy.ImmutableMatrix | None) -> sympy.ImmutableMatrix | None:
                return None if M is None else sympy.ImmutableMatrix(
                    M.rows, M.cols, lambda i, j: M[i, j] / scale[i])

            terms = EquationTerms(unscaled(terms.A), unscaled(terms.h), unscaled(terms.Q),
                                  unscaled(terms.B), inputs)
        return terms

    def constraint_matrix(self) -> sympy.ImmutableMatrix | None:
        r"""The m×n matrix :math:`G` of the ``[constraints]`` equations :math:`G\dot q = 0`
        as printed (left side minus right side), or None when the file has none. Raises
        :class:`DerivationError` if a constraint is not linear and homogeneous in the
        velocities."""
        if self.constraints is None:
            return None
        rows = []
        for i, eq in enumerate(self.constraints):
            expr = eq.lhs - eq.rhs
            row = [sympy.diff(expr, v) for v in self.velocities]
            rest = sympy.expand(expr - sum(c * v for c, v in zip(row, self.velocities)))
            if rest != 0 or any(c.has(*self.velocities, *self.accelerations) for c in row):
                raise DerivationError(self.path, f"constraint {i + 1}",
                                      "not linear and homogeneous in the velocities")
            rows.append(row)
        return sympy.ImmutableMatrix(rows)
