r"""What ``wheeled-dyn model robot.urdf`` decided, in a few lines a person reads: the body and
the links merged into it, the wheels (left and right, and how that was decided), the radius and
track, which way is forward, then the convention table (:mod:`.conventions`) and the
parameters a derivation may name (:mod:`.link_parameters`) of the model the file describes.

When no wheel pair was found, or the URDF's root is the world (a fixed base whatever its
wheels), it says so first, with each moving joint and why it is not a wheel.
"""

from __future__ import annotations

from .starter import UrdfInventory


def starter_spec(inv: UrdfInventory):
    r"""The :class:`~.wheeled_model.ModelSpec` the starting file describes: its text, written to a
    temporary folder and read back as any model file is (the URDF by its absolute path or its
    package, so that package meshes resolve)."""
    import tempfile
    from pathlib import Path

    from .model_file import read_model_file
    from .starter_file import starter_text
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "starter.toml"
        path.write_text(starter_text(inv, path), encoding="utf-8")
        return read_model_file(path).spec()


def summary(inv: UrdfInventory) -> tuple[list[str], bool]:
    r"""The summary lines (see the module docstring), and whether the suggested model builds:
    one that does not is reported in one line with the reason, not raised."""
    from ..errors import WheeledDynError
    from .builder import build_wheeled_model
    from .conventions import convention_table
    from .link_parameters import parameter_listing
    lines: list[str] = []
    if inv.pair is None and inv.world_root:
        lines.append(f"{inv.path.name} is fixed to the world (its root link is "
                     f"{inv.root!r}): the model is a fixed base, not a wheeled robot")
        lines += [f"  {joint}: {reason}" for joint, reason in inv.rejected]
    elif inv.pair is None:
        lines.append(f"no wheel pair found in {inv.path.name}: the model is a fixed base "
                     "(the root link held in the air), not a wheeled robot")
        lines += [f"  {joint}: {reason}" for joint, reason in inv.rejected]
    else:
        left, right = inv.pair
        track = sum((a - b) ** 2 for a, b in zip(left.position, right.position)) ** 0.5
        lines += [f"wheel pair found: left {left.link} (joint {left.joint}), right "
                  f"{right.link} (joint {right.joint})",
                  f"  radius {left.radius:g} m (from {left.link}'s {left.geometry} cylinder), "
                  f"track {track:g} m (L = {track / 2:g} m, half the track)",
                  f"  body {inv.body}; up {_axis(inv.up)} of {inv.body}, forward = up x "
                  "(left -> right)"]
        lines += [f"  {note}" for note in inv.notes]
        if inv.path_joints:
            lines.append(f"  locked at 0 (CHECK): {', '.join(inv.path_joints)}")
    try:
        wm = build_wheeled_model(starter_spec(inv))
    except WheeledDynError as exc:
        return lines + [f"the suggested model does not build: {exc}"], False
    lines += convention_table(wm).lines()
    lines.append("parameters a derivation may name (per rigid body, by the link carrying it):")
    lines += parameter_listing(wm)
    return lines, True


def _axis(v: tuple[float, float, float]) -> str:
    for i, name in enumerate("xyz"):
        if abs(v[i]) == 1.0:
            return ("+" if v[i] > 0 else "-") + name
    return str(v)
