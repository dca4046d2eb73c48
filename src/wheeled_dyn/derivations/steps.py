r"""Reading the ``[[step]]`` tables of a derivation file into :class:`Step` records.

A step table is checked key by key, then read by its ``kind`` (one reader per family of kinds:
frames, vectors, energies, stated results, relations, generalized forces; the fields they
share: :mod:`.step_fields`), then its printed components are parsed in the file's namespace:
a relation ``"lhs = rhs"`` as :math:`\mathrm{lhs} - \mathrm{rhs}` (both sides kept), a lost
component (``"?"``) as ``sympy.nan``, the word of a ``stability`` or ``steady motion`` claim as
1 (``"stable"``, ``"steady"``) or 0. The kinds and what each holds: :mod:`.step_records`,
whose names are importable from here as well.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from typing import Any

import sympy

from .latex.nodes import LatexSource
from .step_fields import (Expr, Fail, read_about, read_axes, read_balance, read_frame,
                          read_strings, read_texts)
from .step_records import (AXES, FORCE_KEYS, FRAME_KINDS, FRAMES, LOST, POINTS,
                           POTENTIAL_QUANTITIES, QUANTITIES, RELATION_KINDS, RESULT_KINDS,
                           STABILITY_CLAIMS, STEP_KEYS, STEP_KINDS, VECTOR_KINDS, Force, Step)

#: What the reader of one kind returns: the step's fields by name and its printed components.
Read = tuple[dict[str, Any], tuple[str, ...]]


def _header_lines(lines: list[str]) -> list[int]:
    return [i + 1 for i, text in enumerate(lines) if re.match(r"^\s*\[\[\s*step\s*\]\]", text)]


def read_steps(raw: Any, lines: list[str], n: int, expr: Expr,
               fail: Fail) -> tuple[Step, ...]:
    r"""Parse the ``[[step]]`` array. ``expr(text, item)`` parses one document expression,
    ``fail(item, reason, line)`` builds the error; ``n`` is the number of positions."""
    if raw is None:
        return ()
    if not isinstance(raw, list) or not all(isinstance(t, dict) for t in raw):
        raise fail("step", "expected [[step]] tables", None)
    headers = _header_lines(lines)
    return tuple(_step(t, k, headers[k] if k < len(headers) else None, n, expr, fail)
                 for k, t in enumerate(raw))


def _frame_step(t: dict, kind: str, item: str, line: int | None, n: int, expr: Expr,
                fail: Fail) -> Read:
    r"""``frame``, ``axes`` (and ``body``, ``body_axes``) and the printed components of an
    ``orientation`` or ``gravity`` step."""
    frame = read_frame(t, item, line, fail)
    axes = read_axes(t, "axes", item, line, fail)
    texts = read_texts(t, "components", item, line, fail)
    extra: dict[str, Any] = dict(frame=frame, axes=axes)
    if kind == "gravity":
        if len(texts) != len(axes):
            raise fail(f"{item}.components", f"{len(texts)} components for {len(axes)} axes",
                       line)
        return extra, texts
    body = t.get("body")
    if not isinstance(body, str) or not body or body == "world":
        raise fail(f"{item}.body", "an orientation names its body (a link, or \"heading\")",
                   line)
    body_axes = read_axes(t, "body_axes", item, line, fail)
    if len(axes) != 3 or len(body_axes) != 3 or len(texts) != 9:
        raise fail(f"{item}.components", "an orientation is a 3 x 3 matrix: nine components, "
                   "row by row, with three axes and three body axes", line)
    return dict(extra, body=body, body_axes=body_axes), texts


def _vector_step(t: dict, kind: str, item: str, line: int | None, n: int, expr: Expr,
                 fail: Fail) -> Read:
    r"""``body``, ``axes``, ``point`` and ``frame`` of a (angular) velocity or acceleration."""
    body = t.get("body")
    if not isinstance(body, str) or not body or body == "world":
        raise fail(f"{item}.body", "a vector step names its body (a link of the model, or "
                   "\"heading\": the heading frame)", line)
    axes = read_axes(t, "axes", item, line, fail)
    texts = read_texts(t, "components", item, line, fail)
    if len(texts) != len(axes):
        raise fail(f"{item}.components", f"{len(texts)} components for {len(axes)} axes", line)
    point = t.get("point", "origin")
    if isinstance(point, list):
        if len(point) != 3:
            raise fail(f"{item}.point", "a point is [x, y, z] in the body's frame", line)
        point = tuple(expr(p, f"{item}.point") for p in point)
    elif point not in POINTS:
        raise fail(f"{item}.point", f"{point!r}: expected one of {', '.join(POINTS)} or "
                   "[x, y, z] in the body's frame", line)
    if body == "heading" and point in ("com", "contact"):
        raise fail(f"{item}.point", "the heading frame's points are \"origin\" (on the "
                   "ground below the axle midpoint) or [x, y, z] in it", line)
    frame = read_frame(t, item, line, fail)
    return dict(body=body, axes=axes, point=point, frame=frame), texts


def _energy_step(t: dict, kind: str, item: str, line: int | None, n: int, expr: Expr,
                 fail: Fail) -> Read:
    r"""The ``value`` and ``bodies`` of an energy or a first integral (and a potential's
    ``quantity``)."""
    if "value" not in t:
        raise fail(f"{item}.value", f"a {kind} step gives value = \"...\"", line)
    texts = read_texts(t, "value", item, line, fail, single=True)
    bodies = read_strings(t, "bodies", item, line, fail)
    if any(b in FRAMES for b in bodies):
        raise fail(f"{item}.bodies", "an energy is of links of the model (world and heading "
                   "are frames)", line)
    extra: dict[str, Any] = dict(bodies=bodies)
    if kind == "potential energy":
        quantity = t.get("quantity", "potential")
        if quantity not in POTENTIAL_QUANTITIES:
            raise fail(f"{item}.quantity", "expected one of "
                       + ", ".join(POTENTIAL_QUANTITIES), line)
        extra["quantity"] = quantity
    return extra, texts


def _speed(t: dict, item: str, line: int | None, fail: Fail, reason: str) -> str:
    speed = t.get("speed")
    if not isinstance(speed, str) or not speed:
        raise fail(f"{item}.speed", reason, line)
    return speed


def _result_step(t: dict, kind: str, item: str, line: int | None, n: int, expr: Expr,
                 fail: Fail) -> Read:
    r"""The claimed ``value``, the state ``about`` (and the ``speed`` scanned) of a stated
    result: a frequency, a critical speed, a stability or a steady motion."""
    if kind == "steady motion":            # the claim is the state itself
        t = {**t, "value": t.get("value", "steady")}
    if "value" not in t:
        raise fail(f"{item}.value", f"a {kind} step gives value = \"...\"", line)
    texts = read_texts(t, "value", item, line, fail, single=True)
    extra: dict[str, Any] = dict(about=read_about(t, item, line, expr, fail))
    if kind == "steady motion" and texts[0] != "steady":
        raise fail(f"{item}.value", "a steady motion claims its state (about), no value",
                   line)
    if kind == "stability":
        if texts[0] not in STABILITY_CLAIMS:
            raise fail(f"{item}.value", "a stability step claims value = \"stable\" or "
                       "\"unstable\"", line)
        if "speed" in t:
            extra["speed"] = _speed(t, item, line, fail, "the document velocity the claim is "
                                    "for at every value: speed = \"dphi\"")
    if kind == "critical speed":
        extra["speed"] = _speed(t, item, line, fail, "a critical speed names the document "
                                "velocity it is of: speed = \"dphi\"")
    return extra, texts


def _relation_step(t: dict, kind: str, item: str, line: int | None, n: int, expr: Expr,
                   fail: Fail) -> Read:
    r"""The ``relations = ["lhs = rhs", ...]`` (and a balance's body and forces, or a
    linearisation's state ``about``)."""
    extra: dict[str, Any] = {}
    if kind == "newton-euler":
        extra = read_balance(t, item, line, expr, fail)
    if kind == "linearised equations":
        extra = dict(about=read_about(t, item, line, expr, fail))
    texts = read_texts(t, "relations", item, line, fail)
    if not texts or any(s.count("=") != 1 for s in texts):
        raise fail(f"{item}.relations", "expected relations = [\"lhs = rhs\", ...], one "
                   "'=' each", line)
    return extra, texts


def _force_step(t: dict, kind: str, item: str, line: int | None, n: int, expr: Expr,
                fail: Fail) -> Read:
    r"""The ``quantity`` and the ``rows`` (1 to ``n``, stored 0-based) of generalized forces."""
    quantity = t.get("quantity", "inertia")
    if quantity not in QUANTITIES:
        raise fail(f"{item}.quantity", f"expected one of {', '.join(QUANTITIES)}", line)
    texts = read_texts(t, "components", item, line, fail)
    rows = t.get("rows", list(range(1, len(texts) + 1)))
    if not isinstance(rows, list) or len(rows) != len(texts) or not all(
            isinstance(r, int) and not isinstance(r, bool) and 1 <= r <= n for r in rows):
        raise fail(f"{item}.rows", f"one row number (1 to {n}) per component", line)
    return dict(quantity=quantity, rows=tuple(r - 1 for r in rows)), texts


#: The reader of each kind of step.
_READERS: dict[str, Callable[..., Read]] = {
    **{k: _frame_step for k in FRAME_KINDS}, **{k: _vector_step for k in VECTOR_KINDS},
    **{k: _energy_step for k in ("kinetic energy", "potential energy", "first integral")},
    **{k: _result_step for k in RESULT_KINDS}, **{k: _relation_step for k in RELATION_KINDS},
    "generalized force": _force_step}


def _kind(t: dict, item: str, line: int | None, fail: Fail) -> str:
    r"""Check the table's keys and label; its kind."""
    for key in t:
        if key not in STEP_KEYS:
            raise fail(f"{item}.{key}", "unknown key; valid: " + ", ".join(STEP_KEYS), line)
    if not str(t.get("equation", "")).strip():
        raise fail(item, "every step needs its document label: equation = \"(57)\"", line)
    kind = t.get("kind")
    if kind not in STEP_KINDS:
        raise fail(f"{item}.kind", f"{kind!r} is not a step kind; valid: "
                   + ", ".join(STEP_KINDS), line)
    return kind


def _components(kind: str, texts: tuple[str, ...], item: str, expr: Expr) -> tuple[
        list[sympy.Expr], list[tuple[sympy.Expr, sympy.Expr]]]:
    r"""The parsed components (and, for relations, their two sides)."""
    def parse(text: Any, where: str) -> sympy.Expr:
        if isinstance(text, str) and text.strip() == LOST:
            return sympy.nan
        return expr(text, where)

    components: list[sympy.Expr] = []
    sides: list[tuple[sympy.Expr, sympy.Expr]] = []
    for i, text in enumerate(texts):
        where = f"{item} component {i + 1}"
        if kind in ("stability", "steady motion"):      # a word, not an expression
            components.append(sympy.Integer(int(text in ("stable", "steady"))))
        elif kind in RELATION_KINDS:
            wrap = LatexSource if isinstance(text, LatexSource) else str
            lhs, rhs = (parse(wrap(side), where) for side in text.split("="))
            sides.append((lhs, rhs))
            components.append(lhs - rhs)
        else:
            components.append(parse(text, where))
    return components, sides


def _step(t: dict, k: int, line: int | None, n: int, expr: Expr, fail: Fail) -> Step:
    label = str(t.get("equation", ""))
    item = f"step {k + 1}" + (f" {label}" if label else "")
    kind = _kind(t, item, line, fail)
    extra, texts = _READERS[kind](t, kind, item, line, n, expr, fail)
    names = read_strings(t, "names", item, line, fail)
    if names and len(names) != len(texts):
        raise fail(f"{item}.names", f"{len(names)} names for {len(texts)} components", line)
    components, sides = _components(kind, texts, item, expr)
    return Step(equation=label, kind=kind, components=tuple(components), printed=texts,
                label=str(t.get("label", "")), given=read_strings(t, "given", item, line, fail),
                note=str(t.get("note", "")), line=line, sides=tuple(sides), names=names, **extra)


__all__ = ["AXES", "FORCE_KEYS", "FRAME_KINDS", "FRAMES", "Force", "LOST", "POINTS",
           "POTENTIAL_QUANTITIES", "QUANTITIES", "RELATION_KINDS", "RESULT_KINDS",
           "STABILITY_CLAIMS", "STEP_KEYS", "STEP_KINDS", "Step", "VECTOR_KINDS", "read_steps"]
