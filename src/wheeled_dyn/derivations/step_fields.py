r"""The fields of one ``[[step]]`` table, each read and checked alone: lists of strings, the
printed texts (strings or LaTeX as written), the state ``about`` which a result is stated, a
point of a body, a frame and its axes, and the applied forces of a ``newton-euler`` balance.

Every reader takes the table ``t``, the ``item`` that names the step in errors (``step 3
(57)``), its ``line`` and ``fail(item, reason, line)``, which builds the
:class:`~wheeled_dyn.errors.DerivationError` raised; those that read expressions take
``expr(text, item)`` too. The kinds of steps and what they hold: :mod:`.step_records`.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

import sympy

from ..errors import DerivationError
from .latex.nodes import LatexSource, unwrap_latex
from .step_records import AXES, FORCE_KEYS, FRAMES, Force

#: Builds the error of one item: ``fail(item, reason, line)``.
Fail = Callable[[str, str, int | None], DerivationError]
#: Parses one document expression: ``expr(text, item)``.
Expr = Callable[[Any, str], sympy.Expr]


def read_strings(table: dict, key: str, item: str, line: int | None,
                 fail: Fail) -> tuple[str, ...]:
    r"""``key`` as a list of strings (one string, or numbers, read as such; none: ``()``)."""
    value = table.get(key, [])
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, list) or not all(isinstance(v, (str, int, float)) and
                                              not isinstance(v, bool) for v in value):
        raise fail(f"{item}.{key}", "expected a list of strings", line)
    return tuple(str(v) for v in value)


def read_texts(t: dict, key: str, item: str, line: int | None, fail: Fail,
               single: bool = False) -> tuple[str, ...]:
    r"""The printed texts of ``key``: strings, or LaTeX as written (``{ latex = '...' }`` for
    one, ``{ latex = ['...', ...] }`` for a list), kept as :class:`LatexSource` to be read by
    the file's LaTeX reader."""
    raw = unwrap_latex(t.get(key, None if single else []))
    items = [raw] if single or isinstance(raw, str) else raw
    if not isinstance(items, list):
        raise fail(f"{item}.{key}", "expected a list of strings or { latex = [...] }", line)
    out: list[str] = []
    for value in items:
        value = unwrap_latex(value)
        if isinstance(value, LatexSource):
            out.append(value)
        elif isinstance(value, (str, int, float)) and not isinstance(value, bool):
            out.append(str(value))
        else:
            raise fail(f"{item}.{key}", "expected strings or { latex = '...' }", line)
    return tuple(out)


def read_about(t: dict, item: str, line: int | None, expr: Expr,
               fail: Fail) -> tuple[tuple[str, sympy.Expr], ...]:
    r"""The state ``about = { name = "value", ... }`` of a linearisation or a stated result."""
    about = t.get("about", {})
    if not isinstance(about, dict):
        raise fail(f"{item}.about", "expected a table: name = \"value\"", line)
    return tuple((str(k), expr(v, f"{item}.about.{k}")) for k, v in about.items())


def read_point(value: Any, where: str, line: int | None, expr: Expr,
               fail: Fail) -> str | tuple[sympy.Expr, ...]:
    r"""A point of a balance's body or of a force on it: ``"origin"``, ``"com"`` or three
    expressions in the body's frame."""
    if isinstance(value, list):
        if len(value) != 3:
            raise fail(where, "a point is [x, y, z] in the body's frame", line)
        return tuple(expr(p, where) for p in value)
    if value not in ("origin", "com"):
        raise fail(where, f"{value!r}: expected origin, com or [x, y, z] in the body's frame",
                   line)
    return value


def read_frame(t: dict, item: str, line: int | None, fail: Fail) -> str:
    r"""``frame`` (default ``"world"``): a frame's name, checked against the model later."""
    frame = t.get("frame", "world")
    if not isinstance(frame, str) or not frame:
        raise fail(f"{item}.frame", "expected world, heading or a link name", line)
    return frame


def read_axes(t: dict, key: str, item: str, line: int | None, fail: Fail) -> tuple[str, ...]:
    r"""Distinct axes among :data:`~.step_records.AXES` (default ``x, y, z``)."""
    axes = read_strings(t, key, item, line, fail) or ("x", "y", "z")
    if any(a not in AXES for a in axes) or len(axes) != len(set(a.lstrip("-") for a in axes)):
        raise fail(f"{item}.{key}", f"axes are distinct among {', '.join(AXES)}", line)
    return axes


def read_balance(t: dict, item: str, line: int | None, expr: Expr,
                 fail: Fail) -> dict[str, Any]:
    r"""The ``body``, moment ``point``, ``frame`` and ``forces`` of a ``newton-euler`` step."""
    body = t.get("body")
    if not isinstance(body, str) or not body or body in FRAMES:
        raise fail(f"{item}.body", "a balance names its body (a link of the model)", line)
    frame = read_frame(t, item, line, fail)
    table = t.get("forces", {})
    if not isinstance(table, dict) or not table:
        raise fail(f"{item}.forces", "a balance lists its forces: forces = { F = { point = "
                   "\"origin\", direction = [\"1\", \"0\", \"0\"] } }", line)
    forces = tuple(_force(str(name), spec, f"{item}.forces.{name}", line, expr, fail)
                   for name, spec in table.items())
    return dict(body=body, frame=frame, forces=forces,
                point=read_point(t.get("point", "com"), f"{item}.point", line, expr, fail))


def _force(name: str, spec: Any, where: str, line: int | None, expr: Expr,
           fail: Fail) -> Force:
    r"""One force or couple ``name = { direction | couple = [x, y, z], point, frame, law }``."""
    if not isinstance(spec, dict) or any(k not in FORCE_KEYS for k in spec):
        raise fail(where, "expected a table with keys " + ", ".join(FORCE_KEYS), line)
    if ("direction" in spec) == ("couple" in spec):
        raise fail(where, "give its direction = [x, y, z] (a force) or couple = [x, y, z] "
                   "(a pure moment)", line)
    axis = spec.get("direction", spec.get("couple"))
    if not isinstance(axis, list) or len(axis) != 3:
        raise fail(where, "a direction is three expressions [x, y, z]", line)
    parsed = tuple(expr(a, where) for a in axis)
    if all(x == 0 for x in parsed):
        raise fail(where, "a direction is not the zero vector", line)
    law = expr(spec["law"], f"{where}.law") if "law" in spec else None
    return Force(name, parsed, read_point(spec.get("point", "com"), f"{where}.point", line,
                                          expr, fail),
                 str(spec.get("frame", "world")), "couple" in spec, law)
