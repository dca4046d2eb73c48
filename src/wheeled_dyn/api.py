r"""Top-level conveniences of the Python API (exported lazily by :mod:`wheeled_dyn`).

Both check their arguments before any computing and raise the project's own, picklable
errors (:class:`~wheeled_dyn.errors.ArgumentError`, :class:`~wheeled_dyn.errors.LimitError`,
:class:`~wheeled_dyn.errors.DerivationError`), never a raw ``TypeError``.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any

from .constraints import CoordinateMap
from .coordinates import builtin_coordinate_set
from .dynamics import Terms
from .errors import ArgumentError, DerivationError, LimitError, StateError
from .models import WheeledModel
from .models.registry import load_model
from .models.urdf_values import MAX_MODEL_NUMBER, MAX_MODEL_TEXT


def matrices(model: WheeledModel | str, coords: str | None = None, **state: float) -> Terms:
    r"""A, C, Q, B, h of ``model`` in its built-in coordinate set ``coords`` at the state given
    by keyword (document names, e.g. ``phi=0.2, dx=1``; missing entries are 0)."""
    if not isinstance(model, (WheeledModel, str, Path)):
        raise ArgumentError("matrices", "model", model, "a model (wheeled_dyn.load_model) or "
                            "a model name or model file path")
    if coords is not None and not isinstance(coords, str):
        raise ArgumentError("matrices", "coords", coords, "the name of a coordinate set")
    for name, value in state.items():
        if not _real(value):
            raise StateError(name, value, "a finite real number of magnitude at most "
                                          f"{MAX_MODEL_TEXT}")
    wm = model if isinstance(model, WheeledModel) else load_model(model)
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, coords))
    q, nu = cmap.state_from(state)
    return finite_terms(cmap, q, nu)


def finite_terms(cmap: CoordinateMap, q: Any, nu: Any) -> Terms:
    r"""``cmap.terms(q, nu)`` if every entry of A, C, Q, B, h (and G) is finite; else
    :class:`LimitError` naming the first element that is not (numbers so large that a product
    overflows, without NumPy's warnings): a result is never given on NaN or infinity."""
    import numpy as np
    with np.errstate(over="ignore", invalid="ignore"):
        terms = cmap.terms(q, nu)
    model, coords = cmap.wm.name, cmap.cs.name
    for name in ("A", "C", "Q", "B", "h", "G"):
        value = getattr(terms, name)
        if value is None:
            continue
        bad = np.argwhere(~np.isfinite(np.atleast_1d(np.asarray(value, dtype=float))))
        if bad.size:
            index = ",".join(str(i + 1) for i in bad[0])
            raise LimitError(f"model {model}, coordinates {coords}: {name}[{index}]",
                             value[tuple(bad[0])], "a finite number", "the numbers of the "
                             "model or the state are too large: a product overflows floating "
                             "point; give smaller ones")
    return terms


def _real(value: object) -> bool:
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        return False
    try:
        number = float(value)
    except OverflowError:                     # an int of 400 digits
        return False
    return math.isfinite(number) and abs(number) <= MAX_MODEL_NUMBER


#: The tables :func:`compare` takes (as a derivation file has them).
TABLES = ("coordinates", "symbols", "inputs", "A", "C", "Q", "B", "G", "equations",
          "state_space", "assumes", "title", "source")
#: The tables that hold expressions (checked for non-finite numbers).
EXPRESSION_TABLES = ("A", "C", "Q", "B", "G", "equations")


def _entries(value: Any, label: str) -> Iterable[tuple[str, Any]]:
    r"""``(label, entry)`` of each entry of a matrix, nested list or list of equations, with
    1-based indices as the reports write them (``A[2,3]``)."""
    import sympy as sp
    if isinstance(value, sp.MatrixBase):
        for i in range(value.rows):
            for j in range(value.cols):
                yield f"{label}[{i + 1},{j + 1}]", value[i, j]
    elif isinstance(value, (list, tuple)):
        for i, item in enumerate(value):
            yield from _entries(item, f"{label}[{i + 1}]" if "[" not in label
                                else f"{label[:-1]},{i + 1}]")
    elif isinstance(value, sp.Equality):
        yield label, value.lhs
        yield label, value.rhs
    else:
        yield label, value


def _finite_tables(tables: dict[str, Any], title: str) -> None:
    r"""Raise :class:`DerivationError` naming the element where an expression holds NaN or an
    infinity (SymPy's ``nan``, ``oo``, ``zoo``, or a float that is not finite)."""
    import sympy as sp
    given = [(key, tables.get(key)) for key in EXPRESSION_TABLES]
    first_order = tables.get("state_space")
    if isinstance(first_order, Mapping):
        given += [(f"state_space.{k}", first_order.get(k)) for k in ("A", "B", "f")]
    for key, value in given:
        if value is None:
            continue
        for label, entry in _entries(value, key):
            if isinstance(entry, str):
                continue                        # text is parsed as a file's would be
            try:
                expr = sp.sympify(entry)
            except (sp.SympifyError, TypeError, ValueError):
                continue                        # reported by the parser, with its reason
            if isinstance(expr, sp.Basic) and expr.has(sp.nan, sp.oo, -sp.oo, sp.zoo):
                raise DerivationError(Path(f"<python: {title}>"), label,
                                      f"'{entry}' is not a finite expression (it holds NaN "
                                      "or an infinity); give the document's expression")


def compare(model: str | Path, *, samples: int = 1000, param_sets: int = 5, seed: int = 2026,
            reuse: bool = True, **tables: Any):
    r"""Compare a derivation given as SymPy objects with the truth; the same
    :class:`~wheeled_dyn.compare.records.DerivationResult` a file gives.

    ``tables``: ``coordinates`` (a built-in set's name or an inline table), ``symbols``
    (document name → value in the model), ``inputs``, ``A``, ``C``, ``Q``, ``B``, ``G`` or
    ``equations``, ``assumes``, ``title`` — see
    :func:`wheeled_dyn.derivations.from_python.derivation_from_sympy`. ``reuse=False`` uses
    nothing remembered on disk (no compiled code, printed form or closed form: as
    ``WHEELED_DYN_REUSE=0``). For a check in a test suite::

        result = wd.compare("wip", coordinates="seed001", A=A, C=C, Q=Q, symbols={...})
        assert not [r for r in result.records if r.verdict == "differs"]
    """
    from .cache_trust import without_reuse
    from .compare.grid.inputs import grid_size
    from .compare.engine import ComparisonEngine
    from .derivations.from_python import derivation_from_sympy
    from .models.registry import model_entry
    if not isinstance(model, (str, Path)):
        raise ArgumentError("compare", "model", model, "a model name or a model file path")
    samples, param_sets, seed = grid_size(samples, param_sets, seed, "compare")
    if not isinstance(reuse, bool):
        raise ArgumentError("compare", "reuse", reuse, "True or False")
    unknown = sorted(set(tables) - set(TABLES))
    if unknown:
        raise ArgumentError("compare", unknown[0], tables[unknown[0]],
                            "one of the tables " + ", ".join(TABLES))
    names = tables.get("symbols")
    if names is not None and (not isinstance(names, Mapping) or
                              not all(isinstance(k, str) for k in names)):
        bad = names if not isinstance(names, Mapping) else \
            next(k for k in names if not isinstance(k, str))
        raise ArgumentError("compare", "symbols", bad, "a mapping of the document's names "
                            "(strings, as a derivation file writes them) to their values")
    _finite_tables(tables, str(tables.get("title", "derivation from Python")))
    model_entry(str(model))                    # an unknown model: its own error, first
    with without_reuse(not reuse):
        d = derivation_from_sympy(model, **tables)     # its names checked by compare
        return ComparisonEngine(samples=samples, param_sets=param_sets, seed=seed).compare(d)


__all__ = ["EXPRESSION_TABLES", "TABLES", "compare", "finite_terms", "matrices"]
