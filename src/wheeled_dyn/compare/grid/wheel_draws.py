r"""The two drive wheels of a wheeled model in a random parameter set: alike, as the model
declares them — each its URDF inertia scaled, axisymmetric (``round_wheels``), or one random
inertia for both (``free_wheels``): :mod:`.round_wheels` says which a comparison draws."""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from ...models.builder import WheeledModel
from ...models.round_wheels import made_round


def alike_wheels(wm: WheeledModel, model: pin.Model, rng: np.random.Generator,
                  rounded: bool = False, free: bool = False) -> None:
    r"""The two drive wheels of a wheeled model stay alike, as the model declares them: each
    is its URDF inertia scaled by one shared random mass factor and size factor (a centred,
    axisymmetric wheel stays so; the two stay equal; the size is not the drawn radius: a
    document's disc wheel, I = m R²/2, needs a family); ``rounded``: axisymmetric
    (:data:`~.samples.ROUND_WHEELS`, of the drawn one too); ``free``: one random inertia for
    both (:func:`_free_wheel`)."""
    wheels = tuple(getattr(wm.spec, "wheels", ()) or ())
    if len(wheels) != 2:
        return
    mass, size = rng.uniform(0.5, 2.0), rng.uniform(0.8, 1.25)
    axles = wheel_axles(wm) if rounded else {}
    drawn = _free_wheel(wm, rng) if free else None
    for link in wheels:
        jid = wm.joint_id_of_link(link)
        old = drawn if drawn is not None else wm.model.inertias[jid]
        old = made_round(old, axles[jid]) if jid in axles else old
        if old.mass > 0:
            model.inertias[jid] = pin.Inertia(old.mass * mass, old.lever * size,
                                              old.inertia * mass * size**2)


def _free_wheel(wm: WheeledModel, rng: np.random.Generator) -> pin.Inertia:
    r"""A random wheel inertia (about its joint's frame) for :data:`~.samples.FREE_WHEELS`: the
    first wheel's URDF mass, a centre of mass off its origin by up to a fifth of its radius, and
    moments about a randomly turned centre from second moments each up to twice the URDF's
    mean (valid: :math:`J_{ii} = \Sigma_{jj} + \Sigma_{kk}`)."""
    wheel = wm.wheels[0]
    old = wm.model.inertias[wheel.joint_id]
    second = np.mean(np.linalg.eigvalsh(np.asarray(old.inertia))) / 2 * rng.uniform(0.2, 2.0, 3)
    moments = np.array([second[1] + second[2], second[0] + second[2], second[0] + second[1]])
    turn, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    lever = np.asarray(old.lever) + rng.uniform(-0.2, 0.2, 3) * wheel.radius
    return pin.Inertia(old.mass, lever, turn @ np.diag(moments) @ turn.T)


def wheel_axles(wm: WheeledModel) -> dict[int, np.ndarray]:
    r"""The drive wheels' axles in their joints' frames, by joint."""
    from ...models.model_joints import joint_axis
    return {w.joint_id: joint_axis(wm.model.joints[w.joint_id]) for w in wm.wheels}


__all__ = ["alike_wheels", "wheel_axles"]
