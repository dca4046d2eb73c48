r"""Top-level conveniences of the Python API (exported lazily by :mod:`wheeled_dyn`)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from .constraints import CoordinateMap
from .coordinates import builtin_coordinate_set
from .dynamics import Terms
from .models import WheeledModel
from .models.registry import load_model


def matrices(model: WheeledModel | str, coords: str | None = None, **state: float) -> Terms:
    r"""A, C, Q, B, h of ``model`` in its built-in coordinate set ``coords`` at the state given
    by keyword (document names, e.g. ``phi=0.2, dx=1``; missing entries are 0)."""
    wm = load_model(model) if isinstance(model, str) else model
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, coords))
    q, nu = cmap.state_from(state)
    return cmap.terms(q, nu)


def compare(model: str | Path, *, samples: int = 1000, param_sets: int = 5, seed: int = 2026,
            **tables: Any):
    r"""Compare a derivation given as SymPy objects with the truth; the same
    :class:`~wheeled_dyn.compare.records.DerivationResult` a file gives.

    ``tables``: ``coordinates`` (a built-in set's name or an inline table), ``symbols``
    (document name → value in the model), ``inputs``, ``A``, ``C``, ``Q``, ``B``, ``G`` or
    ``equations``, ``assumes``, ``title`` — see
    :func:`wheeled_dyn.derivations.from_python.derivation_from_sympy`. For a check in a test
    suite::

        result = wd.compare("wip", coordinates="seed001", A=A, C=C, Q=Q, symbols={...})
        assert not [r for r in result.records if r.verdict == "differs"]
    """
    from .cli.compare_cmd import check_model_names
    from .compare.engine import ComparisonEngine
    from .derivations.from_python import derivation_from_sympy
    from .models.registry import model_entry
    model_entry(str(model))                    # an unknown model: its own error, first
    d = derivation_from_sympy(model, **tables)
    check_model_names(d)
    return ComparisonEngine(samples=samples, param_sets=param_sets, seed=seed).compare(d)
