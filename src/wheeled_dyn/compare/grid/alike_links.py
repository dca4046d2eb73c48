r"""Links a URDF writes alike: the same mass, centre of mass and inertia in their joints' frames
(the two wheels of a cart on continuous joints, the twin legs of a robot), which a derivation
names with one symbol (:math:`2J_w` for the wheels' :math:`J_l + J_r`).

Random parameter sets draw every body's inertia on its own, so such a document differs where
the links are drawn apart; it holds for the URDF's numbers because the links are alike. The
family ``alike_links`` (:func:`~.samples.special_cases` offers it where a model has such
links, and a derivation may declare it) draws each group alike: the first link's random
inertia copied to the others, in their joints' frames. A wheeled model's two drive wheels are
drawn alike already (:mod:`.wheel_draws`) and are not grouped here.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from ...models.builder import WheeledModel
from ...models.geometry_apply import bodies_of

#: The family's name (a derivation's ``families`` entry).
ALIKE_LINKS = "alike_links"
#: Relative tolerance of "the same number" between two links' URDF inertial values.
ALIKE_TOL = 1e-9


def _alike(a: pin.Inertia, b: pin.Inertia) -> bool:
    r"""Whether two bodies' inertias (mass, centre of mass, inertia about it, in their joints'
    frames) are the same numbers to :data:`ALIKE_TOL`."""
    pairs = ((a.mass, b.mass), (np.asarray(a.lever), np.asarray(b.lever)),
             (np.asarray(a.inertia), np.asarray(b.inertia)))
    size = max(float(np.max(np.abs(x))) for x, _ in pairs)
    return all(np.allclose(x, y, rtol=ALIKE_TOL, atol=ALIKE_TOL * size) for x, y in pairs)


def alike_groups(wm: WheeledModel) -> list[tuple[int, ...]]:
    r"""The joints (Pinocchio ids) whose bodies carry mass and are alike (module text), in
    groups of at least two, each in joint order; a wheeled model's drive wheels left out."""
    wheels = {w.joint_id for w in wm.wheels}
    groups: list[list[int]] = []
    for jid in range(1, wm.model.njoints):
        inertia = wm.model.inertias[jid]
        if inertia.mass <= 0 or jid in wheels:
            continue
        home = next((g for g in groups if _alike(wm.model.inertias[g[0]], inertia)), None)
        if home is None:
            groups.append([jid])
        else:
            home.append(jid)
    return [tuple(g) for g in groups if len(g) > 1]


def alike_description(wm: WheeledModel) -> str | None:
    r"""The family's description for ``wm`` (its groups of links by name), None where it has
    no links alike."""
    groups = alike_groups(wm)
    if not groups:
        return None
    bodies = bodies_of(wm)
    named = "; ".join(" and ".join(bodies[jid][0] for jid in g) for g in groups)
    return f"the links the URDF writes alike stay alike ({named}: the same mass, centre of " \
        "mass and inertia in their joints' frames)"


def draw_alike(wm: WheeledModel, model: pin.Model) -> None:
    r"""Each group's first drawn inertia given to the others of ``model`` (drawn from
    ``wm``), in place — also where a family draws a link with its lengths (a uniform link):
    under both, the others take the first's inertia, drawn so."""
    for group in alike_groups(wm):
        for jid in group[1:]:
            model.inertias[jid] = pin.Inertia(model.inertias[group[0]])


__all__ = ["ALIKE_LINKS", "alike_description", "alike_groups", "draw_alike"]
