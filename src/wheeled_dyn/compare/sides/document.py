r"""The document's numbers over K parameter sets × N states.

Each element of its A, C, Q, B (matrix form) or of the read-off A, h, Q, B (equation
form) is compiled as ``sympy.lambdify`` compiles it (:mod:`.compiled`) in its coordinates,
velocities and symbols; every symbol takes the value its declaration gives in the model
namespace, at each parameter set.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import sympy as sp

from ...derivations.schema import Derivation
from ...compiled import numpy_function
from ...expression_size import node_count
from ..grid.arrays import Arrays
from ..grid.samples import ParameterSet, parameter_sets
from ..grid.values import model_value

#: Range of the random values of a document's free symbols (present on both sides).
FREE_RANGE = (0.5, 2.0)


def document_arrays(d: Derivation, funcs: "DocumentFunctions", sets, q: np.ndarray,
                    nu: np.ndarray, seed: int, H_rows: np.ndarray | None = None
                    ) -> tuple[Arrays, list[dict[sp.Symbol, float]], dict[sp.Symbol, np.ndarray]]:
    r"""``(document arrays, symbol values per set, symbol values per sample)`` at the states
    ``q, nu`` (K × N × n) of the parameter ``sets``; H kept at the samples ``H_rows`` (the
    truth's)."""
    rng = np.random.default_rng(seed + 1)
    k, n_states, n = q.shape
    per_set = [document_symbol_values(d, ps, rng) for ps in sets]
    values = {s: np.repeat([v[s] for v in per_set], n_states) for s in funcs.params}
    doc = funcs.evaluate(q.reshape(-1, n), nu.reshape(-1, n), values)
    if doc.H is not None and H_rows is not None:
        doc.H = doc.H[H_rows]
    return doc, per_set, values


def document_symbol_values(d: Derivation, ps: ParameterSet, rng: np.random.Generator) -> dict[sp.Symbol, float]:
    r"""Each non-input document symbol's number at this parameter set."""
    out = {}
    for spec in d.symbols.values():
        if spec.is_input:
            continue
        if spec.value is not None:
            out[spec.symbol] = model_value(spec.value, ps.values)
        else:
            out[spec.symbol] = rng.uniform(*FREE_RANGE)
    return out


_EXPANDED: dict[sp.Expr, sp.Expr] = {}


def expanded(expr: sp.Expr) -> sp.Expr:
    r"""``sympy.expand(expr)`` (an exponential of a sum kept whole: split, exp(-10⁴(q - 1)²)
    is exp(-10⁴)·exp(2·10⁴q)·exp(-10⁴q²), which overflows), once per expression in this
    process (a row of h is expanded for its tensor and for each velocity product's
    coefficient)."""
    if expr not in _EXPANDED:
        _EXPANDED[expr] = sp.expand(expr, power_exp=False)
    return _EXPANDED[expr]


def _h_tensor(h: sp.MatrixBase, velocities: Sequence[sp.Symbol]) -> sp.Array:
    r""":math:`H_{i,jk}` with :math:`h_i = \sum_{jk} H_{i,jk}\nu_j\nu_k`, symmetric, from the
    polynomial coefficients of h in the velocities."""
    n = len(velocities)
    H = [[[sp.Integer(0)] * n for _ in range(n)] for _ in range(h.shape[0])]
    for i in range(h.shape[0]):
        if h[i] == 0:
            continue
        if h[i].has(sp.nan):                  # a lost element: the whole row is unknown
            for j in range(n):
                for k in range(n):
                    H[i][j][k] = sp.nan
            continue
        for (j, k), coeff in _coefficients(h[i], velocities).items():
            if j == k:
                H[i][j][j] = coeff
            else:
                H[i][j][k] = H[i][k][j] = coeff / 2
    return sp.Array(H)


#: Most nodes of a row of h expanded before its coefficients are read.
EXPAND_NODES = 5000
_LARGE: dict[tuple[sp.Expr, tuple[sp.Symbol, ...]], dict[tuple[int, int], sp.Expr] | None] = {}


def large_coefficients(expr: sp.Expr, velocities: Sequence[sp.Symbol]
                       ) -> dict[tuple[int, int], sp.Expr] | None:
    r"""The coefficient of each product :math:`\nu_j\nu_k` (:math:`j \le k`) of a row of h
    of more than :data:`EXPAND_NODES` nodes whose terms are each a coefficient times a
    product of velocities (as ``read_off`` splits a solved form's row: every term over the same
    written-out determinant), its terms grouped as they are, not expanded again (52 s for
    a 3×3 solved form, under a profiler); None for any other row, which is expanded first.
    Once per row in this process."""
    key = (expr, tuple(velocities))
    if key not in _LARGE:
        _LARGE[key] = _monomial_coefficients(expr, velocities) \
            if node_count(expr, EXPAND_NODES) > EXPAND_NODES else None
    return _LARGE[key]


def _coefficients(expr: sp.Expr, velocities: Sequence[sp.Symbol]) -> dict[tuple[int, int], sp.Expr]:
    r""":func:`_quadratic_coefficients` of ``expr`` expanded, or its
    :func:`large_coefficients`."""
    parts = large_coefficients(expr, velocities)
    return _quadratic_coefficients(expanded(expr), velocities) if parts is None else parts


def _quadratic_coefficients(expr: sp.Expr, velocities: Sequence[sp.Symbol]
                            ) -> dict[tuple[int, int], sp.Expr]:
    r"""The coefficient of each product :math:`\nu_j\nu_k` (:math:`j \le k`) in the expanded
    ``expr``: its terms grouped by their velocity factor (a term of another degree in the
    velocities is left out: ``read_off`` has rejected such documents). A term whose velocity
    factor is not a monomial (a velocity inside a function) is read by ``Poly``, as before."""
    parts = _monomial_coefficients(expr, velocities)
    return _poly_coefficients(expr, velocities) if parts is None else parts


def _monomial_coefficients(expr: sp.Expr, velocities: Sequence[sp.Symbol]
                           ) -> dict[tuple[int, int], sp.Expr] | None:
    r"""The coefficient of each product :math:`\nu_j\nu_k` in ``expr`` as it is written, its
    terms grouped by their velocity factor; None where a term's velocity factor is not a
    monomial."""
    index = {v: j for j, v in enumerate(velocities)}
    parts: dict[tuple[int, int], list[sp.Expr]] = {}
    for term in sp.Add.make_args(expr):
        coeff, product = term.as_independent(*velocities, as_Add=False)
        powers = product.as_powers_dict()
        if not all(v in index and e.is_Integer and e > 0 for v, e in powers.items()
                   if v != 1):
            return None
        idx = sorted(index[v] for v, e in powers.items() if v in index for _ in range(int(e)))
        if len(idx) == 2:
            parts.setdefault((idx[0], idx[1]), []).append(coeff)
    return {jk: sp.Add(*terms) for jk, terms in parts.items()}


def _poly_coefficients(expr: sp.Expr, velocities: Sequence[sp.Symbol]
                       ) -> dict[tuple[int, int], sp.Expr]:
    r""":func:`_quadratic_coefficients` read by ``sympy.Poly`` in the velocities."""
    out: dict[tuple[int, int], sp.Expr] = {}
    for monomial, coeff in sp.Poly(expr, *velocities, expand=False).terms():
        idx = [j for j, e in enumerate(monomial) for _ in range(e)]
        if len(idx) == 2:
            out[(idx[0], idx[1])] = out.get((idx[0], idx[1]), sp.Integer(0)) + coeff
    return out


def _printed(d: Derivation) -> list:
    r"""The document's matrices and equations as printed (those it gives)."""
    return [M for M in (d.A, d.C, d.Q, d.B, *(d.equations or ())) if M is not None]


def compound_trig(d: Derivation) -> list[sp.Expr]:
    r"""The sines, cosines and tangents the document writes (its matrices or equations as
    printed) of a combination of its positions that is not one position alone
    (:math:`\cos(q_1 + q_2)` of a two-link arm), sorted: bases of the fits
    (:func:`~..judge.fitting.bases`) and angles of the small-angle readings
    (:meth:`DocumentFunctions.angles`)."""
    found = set().union(*(M.atoms(sp.sin, sp.cos, sp.tan) for M in _printed(d)))
    positions = set(d.positions)
    return sorted((f for f in found if f.args[0] not in positions and f.args[0].free_symbols
                   and f.args[0].free_symbols <= positions), key=sp.default_sort_key)


def _linear(x: sp.Expr, positions: list[sp.Symbol]) -> bool:
    r"""Whether ``x`` is :math:`c_0 + \sum_k c_k q_k` in the ``positions``."""
    try:
        return sp.Poly(x, *positions).total_degree() == 1
    except sp.PolynomialError:
        return False


def written_divisors(d: Derivation) -> list[sp.Expr]:
    r"""The sums of parameters and positions the document divides by as printed
    (:math:`(\ldots)/(m_c + 2 m_w + 2 I_w/R^2)` of a row divided by, or solved with, its
    inertia), sorted: bases of the fits (:func:`~..judge.fitting.bases`), so that a row
    divided by one is named however many terms it has."""
    found = {p.base for M in _printed(d) for p in M.atoms(sp.Pow)
             if p.exp.is_negative and isinstance(p.base, sp.Add)}
    moving = {*d.velocities, *d.accelerations, *d.input_symbols}
    return sorted((x for x in found if not x.free_symbols & moving), key=sp.default_sort_key)


class DocumentFunctions:
    r"""The document's elements compiled once (one function per matrix); evaluated at any
    samples."""

    def __init__(self, d: Derivation, A, C, Q, B, h, G, K=None) -> None:
        self.d = d
        self.params = tuple(s.symbol for s in d.symbols.values() if not s.is_input)
        self.args = [*d.positions, *d.velocities, *self.params]
        self.exprs = {"A": A, "C": C, "Q": Q, "B": B, "h": h, "G": G, "K": K}
        self.exprs["H"] = None if h is None else _h_tensor(h, d.velocities)
        self._fns = {}
        self._element_fns: dict[tuple, object] = {}
        self._compiled: dict[sp.Expr, object] = {}
        self._angles: list[sp.Expr] | None = None
        for key, M in self.exprs.items():
            if M is None:
                continue
            arr = sp.Array(M) if not isinstance(M, sp.Array) else M
            flat = sp.flatten(arr.tolist())
            self._fns[key] = (arr.shape, flat, numpy_function(self.args, flat, cse=True))

    def evaluate(self, q: np.ndarray, nu: np.ndarray, values: Mapping[sp.Symbol, np.ndarray],
                 keys: tuple[str, ...] | None = None) -> Arrays:
        r"""Arrays over samples: positions ``q`` (S × n), velocities ``nu``, symbol values
        (arrays of length S); ``keys``: only those (``("A",)``), else all. An element that
        overflows or leaves the reals is inf or NaN there, silently (the comparison calls it
        undecided)."""
        S = len(q)
        argv = [*q.T, *nu.T, *(values[p] for p in self.params)]
        out = Arrays()
        for key, (shape, flat, fn) in self._fns.items():
            if keys is not None and key not in keys:
                continue
            arr = np.empty((S, len(flat)))
            with np.errstate(all="ignore"):
                vals = fn(*argv)
                for j, v in enumerate(vals):
                    arr[:, j] = v
            arr = arr.reshape((S, *shape))
            if key in ("Q", "h") and arr.ndim == 3:
                arr = arr[..., 0]
            setattr(out, key, arr)
        return out

    def angles(self) -> list[sp.Expr]:
        r"""The angles a small-angle reading is tried for: the positions, and the linear
        combinations of them the document takes sines or cosines of (:func:`compound_trig`;
        q1 + q2 written where sin(q1 + q2) fits; not sin(q1²), a typo's argument), found
        once; none for a linearised document (:mod:`..engine.linear_point`)."""
        if self._angles is None and self.d.assumes.get("linearised_about"):
            self._angles = []        # positions drawn at the point: a reading holds by chance
        if self._angles is None:
            positions = list(self.d.positions)
            compound = dict.fromkeys(f.args[0] for f in compound_trig(self.d)
                                     if _linear(f.args[0], positions))
            self._angles = [*positions, *compound]
        return self._angles

    def compiled(self, expr: sp.Expr):
        r"""``expr`` (in the document's positions, velocities and symbols) compiled once;
        the function returned evaluates without floating-point warnings (an overflow gives
        inf, a value outside the reals NaN)."""
        if expr not in self._compiled:
            fn = numpy_function(self.args, expr)

            def quiet(*argv: np.ndarray, _fn=fn) -> np.ndarray:
                with np.errstate(all="ignore"):
                    return _fn(*argv)

            self._compiled[expr] = quiet
        return self._compiled[expr]

    def element_function(self, key: str, index: tuple[int, ...]):
        r"""The compiled function of one element (for ``h``: of :math:`H_{i,jk}`)."""
        key = "H" if key == "h" else key
        shape, flat, _ = self._fns[key]
        index = tuple(index) + (0,) * (len(shape) - len(index))
        pos = int(np.ravel_multi_index(index, shape))
        if (key, pos) not in self._element_fns:
            self._element_fns[(key, pos)] = numpy_function(self.args, flat[pos])
        return self._element_fns[(key, pos)]


def given_parameter_sets(d: Derivation, given: Sequence[str], k: int,
                         rng: np.random.Generator) -> list[ParameterSet]:
    r"""``k`` random parameter sets of ``d``'s model restricted by the special families named
    in a step's ``given`` (the model's families, or ``uniform(link, ...)``); an unknown name
    is a :class:`DerivationError` listing the model's."""
    from ..grid.assumptions import named_family
    cases = [named_family(d, name, "step.given") for name in given]
    return parameter_sets(d.model, k, rng, tuple(cases))
