r"""Wheels a document's map holds fixed while the robot moves: a file error said first.

A newcomer's planar model of a wheeled robot maps its own positions to the model's — the
forward position to ``x0``, the pitch to ``phi`` — and leaves the wheel angles out. A
holonomic map with ``rolling = "none"`` (the default for ``kind = "holonomic"``) then holds
them at 0: the wheels slide along the ground without turning, and the truth compared is that
robot's (its wheels' spin inertia is missing from the forward motion, their torques push the
body, not the ground). The equations of the robot rolling differ in every element the wheels
reach, with causes of terms, where the reason is the map: it is now the first cause.
"""

from __future__ import annotations

from ..records import Cause, CauseKind


def sliding_wheels(cs, wm) -> Cause | None:
    r"""A ``file_error`` cause where the coordinate set ``cs`` (holonomic, no rolling
    constraint) holds the drive wheels' joints of the wheeled model ``wm`` fixed while one of
    its positions moves the base along the ground (``x0``, ``y0``); None otherwise."""
    if cs.kind != "holonomic" or cs.rolling != "none" or not wm.wheels:
        return None
    positions = {str(p) for p in cs.positions}

    def moved(name: str) -> bool:
        e = cs.configuration.get(name)
        return e is not None and bool({str(x) for x in e.free_symbols} & positions)
    wheels = [wm.coordinate_names[wm.model.joints[w.joint_id].idx_q] for w in wm.wheels]
    if any(moved(w) for w in wheels) or not any(moved(b) for b in ("x0", "y0")):
        return None
    return Cause(CauseKind.FILE_ERROR, (), (
        f"the file's map holds the wheels' joints ({', '.join(wheels)}) fixed while the robot "
        "moves along the ground, with no rolling constraint (rolling = \"none\"): the truth "
        "compared is the robot with its wheels sliding, not turning; a derivation of the "
        "robot rolling maps its wheel angles to its positions (as the rolling constraint "
        "gives them) or declares a rolling coordinate set (kind = \"quasi\", rolling = "
        "\"eliminate\")"))


__all__ = ["sliding_wheels"]
