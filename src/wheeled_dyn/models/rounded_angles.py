r"""Which angles a URDF prints are right angles rounded: ``1.5708`` and ``1.57`` are π/2 to
their digits, ``3.14`` is π; ``1.569`` and ``1.5700`` are within
:data:`~.conventions.RIGHT_ANGLE_TOL` of π/2 but are neither π/2 rounded nor cut at the digits
they print — an angle meant as written.

:func:`unrounded_joints` names the joints whose ``<origin rpy>`` has such an angle: those
angles are kept as written — and their other angles that are roundings made right angles —
where the comparisons turn the other joints by the right angles their roundings stand for
(:func:`~.conventions.right_angled_joints`).
"""

from __future__ import annotations

import functools
import math
import xml.etree.ElementTree as ET
from collections.abc import Mapping
from decimal import Decimal, InvalidOperation
from pathlib import Path
from types import MappingProxyType

from .conventions import ROUNDING
from ..paths import file_stamp

#: Relative slack of a comparison of two numbers printed to the same digits.
SAME_DIGITS = 1e-9


def is_rounding(text: str) -> bool:
    r"""Whether the number ``text`` is a multiple of π/2 rounded or cut to the decimals it
    prints (or that multiple to a float's precision)."""
    try:
        exponent = Decimal(text.strip()).as_tuple().exponent
        value = float(text)
    except (InvalidOperation, ValueError):
        return False
    exact = round(value / (math.pi / 2)) * (math.pi / 2)
    if abs(value - exact) <= ROUNDING or not isinstance(exponent, int):
        return abs(value - exact) <= ROUNDING
    digits = max(-exponent, 0)
    unit = 10.0 ** -digits
    cut = math.trunc(exact / unit) * unit
    return min(abs(value - round(exact, digits)), abs(value - cut)) <= SAME_DIGITS * unit


def unrounded_joints(urdf: Path, tolerance: float) -> Mapping[str, tuple[float, ...]]:
    r"""The joints of ``urdf`` whose ``<origin rpy>`` has an angle within ``tolerance`` of a
    multiple of π/2, off it, that is no rounding of it (:func:`is_rounding`), each with its
    roll, pitch and yaw as they are meant: those angles as printed, the ones that are
    roundings made the right angles they stand for (``rpy="1.5708 0 1.569"``: π/2, 0,
    1.569)."""
    stamp = file_stamp(urdf)
    if stamp is None:
        return {}
    return _unrounded(str(urdf), stamp, tolerance)


@functools.lru_cache(maxsize=32)
def _unrounded(path: str, stamp: tuple, tolerance: float) -> Mapping[str, tuple[float, ...]]:
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError):
        return {}
    out: dict[str, tuple[float, ...]] = {}
    for joint in root.iterfind("joint"):
        origin = joint.find("origin")
        texts = ("" if origin is None else origin.get("rpy", "")).split()
        try:
            values = [float(text) for text in texts]
        except ValueError:
            continue
        meant, unrounded = [], False
        for text, value in zip(texts, values):
            right = round(value / (math.pi / 2)) * (math.pi / 2)
            off = abs(value - right)
            rounding = off <= tolerance and is_rounding(text)
            unrounded |= ROUNDING < off <= tolerance and not rounding
            meant.append(right if rounding else value)
        if unrounded and len(meant) == 3:
            out[joint.get("name", "")] = tuple(meant)
    return MappingProxyType(out)


__all__ = ["is_rounding", "unrounded_joints"]
