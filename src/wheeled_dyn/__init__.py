r"""wheeled_dyn: check hand-derived equations of motion of wheeled bodies against Pinocchio.

The Python API in four lines::

    import wheeled_dyn as wd
    wip = wd.load_model("wip")                                  # seed 001's pendulum
    terms = wd.matrices(wip, "seed001", phi=0.2, dx=1.0, dpsi=0.5)
    terms.A, terms.C, terms.Q, terms.B, terms.h                 # in (dx, dpsi, dphi)
"""

from __future__ import annotations

from .constraints import CoordinateMap, contact_jacobian, multipliers
from .coordinates import builtin_coordinate_set, coordinate_set_names
from .dynamics import Terms, christoffel_tensor, full_terms, h_coefficients
from .errors import WheeledDynError
from .models import WheeledModel
from .models.registry import load_model, model_names
from .models.wip_parameters import WipParameters, random_wip_parameters, standard_parameters
from .simulate import Trajectory, simulate

__version__ = "0.1.0"


def matrices(model: WheeledModel | str, coords: str | None = None, **state: float) -> Terms:
    r"""A, C, Q, B, h of ``model`` in its built-in coordinate set ``coords`` at the state given
    by keyword (document names, e.g. ``phi=0.2, dx=1``; missing entries are 0)."""
    wm = load_model(model) if isinstance(model, str) else model
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, coords))
    q, nu = cmap.state_from(state)
    return cmap.terms(q, nu)


__all__ = ["CoordinateMap", "Terms", "Trajectory", "WheeledDynError", "WheeledModel",
           "WipParameters", "builtin_coordinate_set", "christoffel_tensor", "contact_jacobian",
           "coordinate_set_names", "full_terms", "h_coefficients", "load_model", "matrices",
           "model_names", "multipliers", "random_wip_parameters", "simulate",
           "standard_parameters"]
