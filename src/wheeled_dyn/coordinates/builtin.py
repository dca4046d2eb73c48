r"""The coordinate sets every model offers, and those its model file declares.

- ``full``: the model's own coordinates (x0, y0, psi, [phi], ..., theta_l, theta_r), rolling
  constraints kept with multipliers;
- ``heading``: the heading speed :math:`\dot x = \cos\psi\,\dot x_0 + \sin\psi\,\dot y_0`, the
  heading rate :math:`\dot\psi`, then every coordinate that is neither the base's nor a wheel's
  (the pitch :math:`\varphi` of the WIP); rolling eliminated. ``wip.toml`` declares the same
  set as ``seed001`` (seed 001's eq. (25): states x, psi, phi, dx, dpsi, dphi) and
  ``absolute_wheels``: seed 001 section 5's coordinates
  :math:`(x_0, y_0, \theta_l, \theta_r, \varphi)` with absolute, forward-positive wheel
  angles and the holonomic map :math:`\psi = R(\theta_r - \theta_l)/(2L)`, constraints kept;
- ``wheels``: the wheel angle rates :math:`\dot\theta_l, \dot\theta_r` then the same others;
  rolling eliminated.

Models without wheels (``fixed`` and ``free`` bases) offer

- ``full``: the model's own coordinates; no rolling (``none``), or, for a model with a rolling
  ball, the ball's contact constraints kept with multipliers;
- ``body_rates`` (``free`` base): the components :math:`\omega_x, \omega_y, \omega_z` of the
  body's angular velocity in its own frame (velocities ``wx, wy, wz``) as quasi-velocities,
  with the yaw, pitch and roll angles as positions, and the other joints' coordinates.
  Without a contact the velocities of the origin ``dx0, dy0, dz0`` come first (rolling
  ``none``); with a rolling ball they are eliminated by the contact (rolling ``eliminate``)
  and the representative configuration puts the ball on the ground at the origin, on top
  of the fixed sphere, or at the bottom of the paraboloid bowl (a spheroid: on the ground at
  the origin, its centre at the height of :data:`SPHEROID_HEIGHT` for the given angles, so
  that the representative configuration touches the ground at every orientation);
- ``world_rates`` (``free`` base): the same with the angular velocity's components in world
  axes (velocities ``wX, wY, wZ``). For a ball whose inertia is isotropic the reduced
  equations in these velocities do not depend on the ball's orientation, so a spinning ball
  on top of the fixed sphere is an equilibrium of (centre, angular velocity).

A model file's ``[coordinates.<name>]`` tables (:attr:`ModelSpec.coordinate_sets
<wheeled_dyn.models.builder.ModelSpec.coordinate_sets>`) add sets, or replace the generated
set of the same name; ``default_coordinates`` names the default.
"""

from __future__ import annotations

from typing import Any

from ..errors import UnknownNameError
from ..models.builder import FREE_BASE, WheeledModel
from .spec import CoordinateSet, parse_coordinate_set

BASE = ("x0", "y0", "psi")


def _others(wm: WheeledModel) -> list[str]:
    wheel_names = {wm.coordinate_names[w.v_index] for w in wm.wheels}
    return [n for n in wm.coordinate_names if n not in BASE and n not in wheel_names]


#: Body angular velocity (own frame) in the ZYX angles of a free base.
BODY_RATES = {"wx": "droll - sin(pitch)*dyaw",
              "wy": "cos(roll)*dpitch + sin(roll)*cos(pitch)*dyaw",
              "wz": "-sin(roll)*dpitch + cos(roll)*cos(pitch)*dyaw"}


#: Angular velocity in world axes in the ZYX angles of a free base.
WORLD_RATES = {"wX": "-sin(yaw)*dpitch + cos(yaw)*cos(pitch)*droll",
               "wY": "cos(yaw)*dpitch + sin(yaw)*cos(pitch)*droll",
               "wZ": "dyaw - sin(pitch)*droll"}


#: Height of the centre of a spheroid (radii a, c, axis the body's z) touching the ground in the
#: ZYX angles of a free base: s = sqrt(a^2 - (a^2 - c^2) (e_3.e_z)^2) with
#: e_3.e_z = cos(pitch) cos(roll) (constraints/spheroid_contact.py).
SPHEROID_HEIGHT = "sqrt(a**2 - (a**2 - c**2)*cos(pitch)**2*cos(roll)**2)"


def _unwheeled_specs(wm: WheeledModel) -> dict[str, dict[str, Any]]:
    contact = wm.contact is not None
    specs: dict[str, dict[str, Any]] = {"full": {
        "description": "the model's own coordinates" + ("; the ball's rolling constraints kept "
                                                        "as multipliers" if contact else ""),
        "kind": "holonomic", "rolling": "multipliers" if contact else "none",
        "positions": list(wm.coordinate_names)}}
    if wm.base != "free":
        return specs
    others = [n for n in wm.coordinate_names if n not in FREE_BASE]
    angles = ["yaw", "pitch", "roll"]
    config = {n: n for n in (*angles, *others)}
    vmap = {**BODY_RATES, **{"d" + n: "d" + n for n in others}}
    velocities = ["wx", "wy", "wz", *("d" + n for n in others)]
    if wm.contact is not None:
        spec = wm.contact.spec
        cx, cy, cz = (str(float(c)) for c in spec.centre)
        if spec.spheroid:                       # centre at the height s of the lowest point
            config["z0"] = SPHEROID_HEIGHT
            place = "on the ground at the origin"
        elif spec.surface == "plane":
            config["z0"], place = "r", "on the ground at the origin"
        elif spec.surface == "sphere":
            config.update(x0=cx, y0=cy, z0=f"{cz} + R1 + r")
            place = "on top of the fixed sphere"
        else:                                   # a bowl whose vertex is the centre
            config.update(x0=cx, y0=cy, z0=f"{cz} + r")
            place = f"at the bottom of the {spec.surface} bowl"
        body = "spheroid" if spec.spheroid else "ball"
        description = (f"body angular velocity components in the body frame; the {body}'s "
                       f"rolling eliminated (representative configuration: the {body} {place})")
        positions = [*angles, *others]
    else:
        config.update({"x0": "x0", "y0": "y0", "z0": "z0"})
        vmap.update({"dx0": "dx0", "dy0": "dy0", "dz0": "dz0"})
        velocities = ["dx0", "dy0", "dz0", *velocities]
        positions = ["x0", "y0", "z0", *angles, *others]
        description = ("velocity of the body frame origin (world axes), then the body angular "
                       "velocity components in the body frame")
    specs["body_rates"] = {"description": description, "kind": "quasi",
                           "rolling": "eliminate" if contact else "none",
                           "positions": positions, "velocities": velocities,
                           "configuration": config, "velocity_map": vmap}
    world = {**{k: v for k, v in vmap.items() if k not in BODY_RATES}, **WORLD_RATES}
    specs["world_rates"] = {**specs["body_rates"],
                            "description": description.replace("body angular velocity "
                                                               "components in the body frame",
                                                               "angular velocity in world axes"),
                            "velocities": [{"wx": "wX", "wy": "wY", "wz": "wZ"}.get(v, v)
                                           for v in velocities],
                            "velocity_map": world}
    return specs


def _generated_specs(wm: WheeledModel) -> dict[str, dict[str, Any]]:
    r"""The sets every model of this kind offers (see the module docstring)."""
    if not wm.wheels:
        return _unwheeled_specs(wm)
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
    return {"heading": heading, "wheels": wheels, "full": full}


def builtin_specs(wm: WheeledModel) -> dict[str, dict[str, Any]]:
    r"""The raw specs (dicts, as a derivation file would write them) of the model's sets: the
    generated ones, then those its model file declares (replacing a generated one of the same
    name)."""
    specs = _generated_specs(wm)
    for name, raw in wm.spec.coordinate_sets.items():
        specs[name] = {k: (dict(v) if isinstance(v, dict) else v) for k, v in raw.items()}
    return specs


def coordinate_set_names(wm: WheeledModel) -> tuple[str, ...]:
    return tuple(builtin_specs(wm))


def default_coordinate_set(wm: WheeledModel) -> str:
    if wm.spec.default_coordinates:
        return wm.spec.default_coordinates
    if wm.wheels:
        return "heading"
    return "body_rates" if wm.contact is not None else "full"


def builtin_coordinate_set(wm: WheeledModel, name: str | None = None) -> CoordinateSet:
    r"""A built-in set of the model by name (default: the model's default set)."""
    if wm.nv == 0:              # every joint fixed or locked: no coordinate to take
        from ..errors import ModelError
        raise ModelError(wm.name, "joints", "the model has no moving joint (every joint is "
                         "fixed or locked): it has no coordinates, no equations of motion")
    name = name or default_coordinate_set(wm)
    specs = builtin_specs(wm)
    if name not in specs:
        raise UnknownNameError("coordinate set", name, specs, where=f"model {wm.name}")
    return parse_coordinate_set(specs[name], name, wm.coordinate_names,
                                tuple(parameter_names(wm)), where=f"model {wm.name}")


def parameter_names(wm: WheeledModel) -> tuple[str, ...]:
    r"""Parameters a coordinate expression may use: the model's geometry (the wheel radius R,
    half track L of a wheeled model; the named constants of the others) and its lengths as
    identifiers (``radius_coin`` for ``radius(coin)``: :meth:`~.WheeledModel.named_lengths`)."""
    return tuple(wm.named_lengths())
