r"""Top-level conveniences of the Python API (exported lazily by :mod:`wheeled_dyn`)."""

from __future__ import annotations

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
