r"""Which angles a URDF prints are right angles rounded: ``1.5708`` and ``1.57`` are π/2 to
their digits, ``3.14`` is π; ``1.569`` and ``1.5700`` are within
:data:`~.conventions.RIGHT_ANGLE_TOL` of π/2 but are neither π/2 rounded nor cut at the digits
they print — an angle meant as written.

:func:`unrounded_joints` names the joints whose ``<origin rpy>`` has such an angle: their
frames are kept as written where the comparisons turn the others by the right angles their
roundings stand for (:func:`~.conventions.right_angled_joints`).
"""

from __future__ import annotations

import functools
import math
import xml.etree.ElementTree as ET
from decimal import Decimal, InvalidOperation
from pathlib import Path

from .conventions import ROUNDING

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


def unrounded_joints(urdf: Path, tolerance: float) -> frozenset[str]:
    r"""The joints of ``urdf`` whose ``<origin rpy>`` has an angle within ``tolerance`` of a
    multiple of π/2, off it, that is no rounding of it (:func:`is_rounding`)."""
    try:
        stamp = urdf.stat().st_mtime_ns
    except OSError:
        return frozenset()
    return _unrounded(str(urdf), stamp, tolerance)


@functools.lru_cache(maxsize=32)
def _unrounded(path: str, stamp: int, tolerance: float) -> frozenset[str]:
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError):
        return frozenset()
    out = set()
    for joint in root.iterfind("joint"):
        origin = joint.find("origin")
        for text in ("" if origin is None else origin.get("rpy", "")).split():
            try:
                value = float(text)
            except ValueError:
                continue
            off = abs(value - round(value / (math.pi / 2)) * (math.pi / 2))
            if ROUNDING < off <= tolerance and not is_rounding(text):
                out.add(joint.get("name", ""))
    return frozenset(out)


__all__ = ["is_rounding", "unrounded_joints"]
