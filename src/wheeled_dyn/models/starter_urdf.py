r"""The URDF a starting model file is made from (:mod:`.starter`): read and checked
(:mod:`.urdf_checks`, :mod:`.urdf_values`), every link whose inertia fails the checks named in
one error with the option that writes the file anyway, and its yourdfpy model."""

from __future__ import annotations

import io
from pathlib import Path

import numpy as np

from ..errors import InertiaError, InputFileError, ModelError
from .urdf_checks import ACCEPT_HINT
from .urdf_source import check_link_names, read_urdf

#: How to write a starting file for a URDF whose link inertia is known to be wrong.
STARTER_ACCEPT_HINT = ("; fix the URDF, or give 'wheeled-dyn model --accept-inertia {link}' to "
                       "write the model file anyway (it lists the link in [checks] "
                       "accept_inertia)")


def read_checked(path: str | Path, accept: tuple[str, ...] = ()):
    r"""The URDF's source and its yourdfpy model. A link whose inertia fails the checks is an
    error unless ``accept`` lists it (``--accept-inertia``: the file then lists it in
    ``[checks] accept_inertia``); a link of ``accept`` that the URDF does not have is an
    error too."""
    import yourdfpy
    failing: list[InertiaError] = []
    while True:                        # every link that fails, named in one error
        try:
            source = read_urdf(path, accept_inertia=accept + tuple(e.item or "" for e in failing))
            break
        except InertiaError as exc:
            if exc.item is None or exc.item in accept or any(e.item == exc.item for e in failing):
                raise
            failing.append(exc)
        except ModelError:
            if not failing:
                raise
            break        # accepting the links found does not build either: name those first
    check_link_names(Path(path), accept, "--accept-inertia")     # a misspelt name first
    if failing:
        first, links = failing[0], ",".join(e.item or "" for e in failing)
        others = f" (and {', '.join(e.item or '' for e in failing[1:])}, likewise)" \
            if len(failing) > 1 else ""
        raise ModelError(first.model, first.item, first.reason.replace(
            ACCEPT_HINT, others + STARTER_ACCEPT_HINT.format(link=links)))
    try:
        urdf = yourdfpy.URDF.load(io.BytesIO(source.text.encode("utf-8")),
                                  build_scene_graph=True, load_meshes=False,
                                  load_collision_meshes=False)
    except Exception as exc:  # yourdfpy raises assorted types for what the checks let through
        raise InputFileError(source.path, f"invalid URDF (yourdfpy: {type(exc).__name__}: "
                                          f"{exc})") from None
    return source, urdf, accept


__all__ = ["STARTER_ACCEPT_HINT", "read_checked"]


def caster_links(urdf, pair, free: tuple[str, ...], up: np.ndarray, root: str
                 ) -> tuple[str, ...]:
    r"""The links that look like casters of a robot whose drive wheels are ``pair`` (wheel
    candidates): a link with a sphere (a caster ball), or one a moving joint of ``free`` turns
    (a swivel caster, another wheel), whose origin lies no higher than the drive wheels' tops
    (``up``: the up direction in the ``root`` frame, zero configuration) — an arm's links
    above the body were taken for casters, and a balancing robot carrying one was read as
    kept level; and a link whose collision box reaches the ground (within
    :data:`SKID_TOL` of a wheel radius) away from the axle (a TurtleBot3's caster, a box on a
    fixed joint, was not seen); sorted. They keep a wheeled body level (its model's
    ``pitch = false``)."""
    wheels = {w.link for w in pair}
    top = max(float(np.dot(w.position, up)) + w.radius for w in pair)
    ground = min(float(np.dot(w.position, up)) - w.radius for w in pair)
    axle = np.mean([w.position for w in pair], axis=0)

    def low(link: str) -> bool:
        return float(np.dot(urdf.get_transform(link, root)[:3, 3], up)) <= top

    out = {link.name for link in urdf.robot.links if link.name not in wheels and any(
        shape.geometry is not None and shape.geometry.sphere is not None
        for shape in (*link.collisions, *link.visuals))}
    out |= {j.child for j in urdf.robot.joints if j.name in free}
    radius = min(w.radius for w in pair)
    for link in urdf.robot.links:
        if link.name in wheels:
            continue
        for corner in _box_corners(urdf, link, root):
            off = corner - axle
            if abs(float(np.dot(corner, up)) - ground) <= SKID_TOL * radius and \
                    np.linalg.norm(off - np.dot(off, up) * up) > radius:
                out.add(link.name)
    return tuple(sorted(link for link in out if low(link)))


#: A collision box of a link other than the wheels whose lowest corner is within this fraction
#: of the wheel radius of the ground, away from the axle, is a skid or a fixed caster.
SKID_TOL = 0.25


def _box_corners(urdf, link, root: str) -> list[np.ndarray]:
    r"""The corners of ``link``'s collision boxes in the ``root`` frame (zero configuration)."""
    out = []
    for shape in link.collisions:
        box = None if shape.geometry is None else shape.geometry.box
        if box is None:
            continue
        pose = urdf.get_transform(link.name, root) @ (np.eye(4) if shape.origin is None
                                                       else np.asarray(shape.origin))
        half = 0.5 * np.asarray(box.size, dtype=float)
        for sx in (-1, 1):
            for sy in (-1, 1):
                for sz in (-1, 1):
                    out.append(pose[:3, :3] @ (half * (sx, sy, sz)) + pose[:3, 3])
    return out

