r"""The coordinate sets every wheeled model offers, and the WIP's seed-001 names.

- ``full``: the model's own coordinates (x0, y0, psi, [phi], ..., theta_l, theta_r), rolling
  constraints kept with multipliers;
- ``heading``: the heading speed :math:`\dot x = \cos\psi\,\dot x_0 + \sin\psi\,\dot y_0`, the
  heading rate :math:`\dot\psi`, then every coordinate that is neither the base's nor a wheel's
  (the pitch :math:`\varphi` of the WIP); rolling eliminated. For ``wip`` this is seed 001's
  eq. (25) set and is also called ``seed001`` (states x, psi, phi, dx, dpsi, dphi);
- ``absolute_wheels`` (``wip`` only): seed 001 section 5's coordinates
  :math:`(x_0, y_0, \theta_l, \theta_r, \varphi)` with absolute, forward-positive wheel
  angles and the holonomic map :math:`\psi = R(\theta_r - \theta_l)/(2L)`, constraints kept;
- ``wheels``: the wheel angle rates :math:`\dot\theta_l, \dot\theta_r` then the same others;
  rolling eliminated.
"""

from __future__ import annotations

from typing import Any

from ..errors import UnknownNameError
from ..models.builder import WheeledModel
from .spec import CoordinateSet, parse_coordinate_set

BASE = ("x0", "y0", "psi")
#: The default set of each model (the first of its list otherwise).
DEFAULTS = {"wip": "seed001"}


def _others(wm: WheeledModel) -> list[str]:
    wheel_names = {wm.coordinate_names[w.v_index] for w in wm.wheels}
    return [n for n in wm.coordinate_names if n not in BASE and n not in wheel_names]


def builtin_specs(wm: WheeledModel) -> dict[str, dict[str, Any]]:
    r"""The raw specs (dicts, as a derivation file would write them) of the model's sets."""
    others = _others(wm)
    wl, wr = (wm.coordinate_names[w.v_index] for w in wm.wheels)
    heading = {
        "description": "heading speed, heading rate and the body coordinates; rolling eliminated",
        "kind": "quasi", "rolling": "eliminate",
        "positions": ["x", "psi", *others],
        "configuration": {"x0": "x", "psi": "psi", **{n: n for n in others}},
        "velocity_map": {"dx": "cos(psi)*dx0 + sin(psi)*dy0", "dpsi": "dpsi",
                         **{"d" + n: "d" + n for n in others}},
    }
    wheels = {
        "description": "wheel angle rates and the body coordinates; rolling eliminated",
        "kind": "quasi", "rolling": "eliminate",
        "positions": [wl, wr, *others],
        "configuration": {wl: wl, wr: wr, **{n: n for n in others}},
        "velocity_map": {"d" + n: "d" + n for n in (wl, wr, *others)},
    }
    full = {
        "description": "the model's own coordinates; rolling constraints kept as multipliers",
        "kind": "holonomic", "rolling": "multipliers",
        "positions": list(wm.coordinate_names),
    }
    specs = {"heading": heading, "wheels": wheels, "full": full}
    if wm.name == "wip":
        specs = {"seed001": {**heading, "description": "seed 001 eq. (25): " +
                             heading["description"]}, **specs}
        specs["absolute_wheels"] = {
            "description": "seed 001 section 5's coordinates done right: x0, y0, absolute wheel "
                           "angles (forward-positive), pitch; psi = R(theta_r - theta_l)/(2L); "
                           "rolling kept as multipliers",
            "kind": "holonomic", "rolling": "multipliers",
            "positions": ["x0", "y0", "theta_l", "theta_r", "phi"],
            "configuration": {"x0": "x0", "y0": "y0", "psi": "R*(theta_r - theta_l)/(2*L)",
                              "phi": "phi", "theta_l": "-theta_l - phi",
                              "theta_r": "-theta_r - phi"},
        }
    return specs


def coordinate_set_names(wm: WheeledModel) -> tuple[str, ...]:
    return tuple(builtin_specs(wm))


def default_coordinate_set(wm: WheeledModel) -> str:
    return DEFAULTS.get(wm.name, "heading")


def builtin_coordinate_set(wm: WheeledModel, name: str | None = None) -> CoordinateSet:
    r"""A built-in set of the model by name (default: the model's default set)."""
    name = name or default_coordinate_set(wm)
    specs = builtin_specs(wm)
    if name not in specs:
        raise UnknownNameError("coordinate set", name, specs, where=f"model {wm.name}")
    return parse_coordinate_set(specs[name], name, wm.coordinate_names,
                                tuple(parameter_names(wm)), where=f"model {wm.name}")


def parameter_names(wm: WheeledModel) -> tuple[str, ...]:
    r"""Parameters a coordinate expression may use: the wheel radius R, half track L."""
    return tuple(wm.geometry)
