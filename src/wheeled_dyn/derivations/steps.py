r"""Steps of a derivation before its equations of motion: the ``[[step]]`` tables of a file.

A hand derivation is a chain — kinematics, energies, constraints, generalized forces — and each
link is printed under an equation label. A ``[[step]]`` table records one such result as
printed, in the file's namespace (positions :math:`q`, velocities :math:`\nu`, accelerations
:math:`\dot\nu`, symbols, definitions):

=========================== ============================================================
``kind``                    what ``components`` (or ``value``, ``relations``) hold
=========================== ============================================================
``velocity``                velocity of a point of ``body`` (``point``: ``"origin"``,
                            ``"com"``, ``"contact"`` or ``[x, y, z]`` in the body's frame)
``acceleration``            its acceleration (inertial, :math:`\ddot{\mathbf r}`)
``angular velocity``        angular velocity :math:`\omega` of ``body``
``angular acceleration``    :math:`\dot\omega` (inertial derivative)
``kinetic energy``          ``value``: kinetic energy of ``bodies`` (default: all)
``potential energy``        ``value``: gravity potential of ``bodies`` (up to a constant), or
                            with ``quantity = "force function"`` the force function
                            :math:`U = -V` as some texts print it
``constraint``              ``relations``: velocity constraints ``"lhs = rhs"`` (linear in
                            :math:`\nu`) or configuration constraints (no velocities)
``claim``                   ``relations`` between coordinates or between parameters
``linearised equations``    ``relations`` linear in deviations (the document's positions,
                            velocities, accelerations read as deviations) about the state
                            ``about`` (velocities not named there are 0, positions random)
``first integral``          ``value``: a quantity the document says is constant in the
                            free motion (no inputs)
``frequency``               ``value``: an angular frequency of small oscillations about the
                            state ``about`` (a steady state)
``critical speed``          ``value``: the value of the velocity ``speed`` (the others as in
                            ``about``) at which the stability of ``about`` changes
``stability``               ``value``: ``"stable"`` or ``"unstable"``, claimed for the state
                            ``about`` (for every value of the velocity ``speed``, if named)
``steady motion``           the state ``about`` (positions, velocities: a steady precession's
                            rate, say) claimed to be a steady motion of the free motion
``orientation``             ``components``: the nine entries (row by row) of the matrix whose
                            columns are ``body``'s axes (``body_axes``) along ``frame``'s
                            ``axes`` (a rotation matrix such as :math:`{}^0A_1`)
``gravity``                 ``components``: the gravity vector along ``frame``'s ``axes``
``newton-euler``            ``relations``: force and moment balances of ``body`` (moments
                            about ``point``, components along ``frame``'s axes) with the
                            applied ``forces`` (document symbols, ``free = true``)
``generalized force``       ``components`` of Kane's generalized inertia forces
                            (``quantity = "inertia"``: :math:`F^* = -(A\dot\nu + h)`) or of
                            the inertial left side (``quantity = "inertial terms"``:
                            :math:`A\dot\nu + h`), for the document's ``rows``
=========================== ============================================================

A vector's ``body`` is a link of the model or ``"heading"``: the heading frame itself (the
model's :math:`\psi` joint frame, turning with the heading only; its origin is the point on the
ground below the axle midpoint, its points ``"origin"`` or ``[x, y, z]``, no ``"com"`` or
``"contact"``). Vectors are expressed in ``frame`` (``"world"``, ``"heading"`` — turning with
the heading angle only: x forward, y left, z up — or a link name) along the document's ``axes``
(default ``["x", "y", "z"]``; e.g. ``["x", "z", "-y"]`` for a frame with x forward, y up and z
to the right written over the heading frame). ``given`` names special parameter families of
the model under which the document states the step (``"no_products"``, ``"disc_wheels"`` ...).
Every step carries its document ``equation`` label as printed (``"(57)"``, ``"1.11"``).
"""

from __future__ import annotations

import re
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import sympy

from ..errors import DerivationError
from .latex.nodes import LatexSource, unwrap_latex

#: Kinds of steps a file can record (a subset of :data:`wheeled_dyn.compare.records.STEPS`).
STEP_KINDS: tuple[str, ...] = ("velocity", "angular velocity", "acceleration",
                               "angular acceleration", "kinetic energy", "potential energy",
                               "constraint", "claim", "generalized force",
                               "linearised equations", "first integral", "frequency",
                               "critical speed", "newton-euler", "orientation", "gravity",
                               "stability", "steady motion")
VECTOR_KINDS = STEP_KINDS[:4]
RELATION_KINDS = ("constraint", "claim", "linearised equations", "newton-euler")
#: A frame's orientation and the gravity vector: functions of the positions alone.
FRAME_KINDS = ("orientation", "gravity")
#: Stated results judged on the linearisation of the true motion (:mod:`~wheeled_dyn.compare.steps.stated`).
RESULT_KINDS = ("frequency", "critical speed", "stability", "steady motion")
#: What a ``stability`` step can claim.
STABILITY_CLAIMS = ("stable", "unstable")
#: Named points of a body.
POINTS: tuple[str, ...] = ("origin", "com", "contact")
#: Frames every model has; any link name is a frame too.
FRAMES: tuple[str, ...] = ("world", "heading")
AXES: tuple[str, ...] = ("x", "y", "z", "-x", "-y", "-z")
QUANTITIES: tuple[str, ...] = ("inertia", "inertial terms")
#: What a ``potential energy`` step's value is: the potential V, or the force function U = -V
#: (the work function some texts write instead).
POTENTIAL_QUANTITIES: tuple[str, ...] = ("potential", "force function")
STEP_KEYS: tuple[str, ...] = ("equation", "kind", "label", "body", "bodies", "point", "frame",
                              "axes", "components", "value", "relations", "quantity", "rows",
                              "given", "note", "names", "about", "speed",
                              "forces", "body_axes")
#: Keys of one applied force (or couple) of a ``newton-euler`` step.
FORCE_KEYS: tuple[str, ...] = ("point", "direction", "couple", "frame", "law")
#: An element the extracted text lost.
LOST = "?"


@dataclass(frozen=True)
class Force:
    r"""A force (or couple) of a ``newton-euler`` step: the document symbol ``name`` is its
    magnitude along ``direction`` (three expressions in ``frame``'s axes), applied at ``point``
    of the step's body (``"origin"``, ``"com"`` or three expressions in the body's frame);
    a couple (``couple = [x, y, z]``) is a pure moment about that direction. A force given
    by its ``law`` (a spring's :math:`K(x_{in} - x)`, a damper's :math:`-c\dot x`: an
    expression of the state and the symbols) is known, not an unknown of the balance."""

    name: str
    direction: tuple[sympy.Expr, ...]
    point: str | tuple[sympy.Expr, ...] = "com"
    frame: str = "world"
    couple: bool = False
    law: sympy.Expr | None = None


@dataclass(frozen=True)
class Step:
    r"""One printed step. ``components`` are document expressions (``sympy.nan`` where the
    text lost one): vector components along ``axes``, the energy (one), the relations as
    left side minus right side, or the generalized forces of ``rows`` (0-based).
    ``printed`` keeps the text of each component as written."""

    equation: str
    kind: str
    components: tuple[sympy.Expr, ...]
    printed: tuple[str, ...]
    label: str = ""
    body: str | None = None
    bodies: tuple[str, ...] = ()
    point: str | tuple[sympy.Expr, ...] = "origin"
    frame: str = "world"
    axes: tuple[str, ...] = ("x", "y", "z")
    quantity: str = "inertia"
    rows: tuple[int, ...] = ()
    given: tuple[str, ...] = ()
    note: str = ""
    line: int | None = None
    sides: tuple[tuple[sympy.Expr, sympy.Expr], ...] = ()    # relations: (lhs, rhs)
    names: tuple[str, ...] = ()          # the document's names of the components (i, j, k)
    about: tuple[tuple[str, sympy.Expr], ...] = ()   # linearised: (name, value) of the state
    speed: str = ""                      # critical speed: the document velocity scanned
    forces: tuple["Force", ...] = ()     # newton-euler: the applied forces and couples
    body_axes: tuple[str, ...] = ("x", "y", "z")   # orientation: the body's axes as labelled

    @property
    def name(self) -> str:
        r"""How reports name the step: its label, else its kind and equation."""
        return f"{self.equation} {self.label}".strip() if self.label else \
            f"{self.equation} {self.kind}".strip()

    def component_names(self) -> tuple[str, ...]:
        r"""Names of the components as reports print them (``x``, ``-z``, ``row 2``, ...)."""
        if self.names:
            return self.names
        if self.kind in VECTOR_KINDS:
            return self.axes
        if self.kind == "generalized force":
            return tuple(f"row {r + 1}" for r in self.rows)
        if self.kind == "orientation":
            return tuple(f"[{i},{j}]" for i in (1, 2, 3) for j in (1, 2, 3))
        if self.kind == "gravity":
            return self.axes
        if self.kind in RELATION_KINDS:
            return tuple(f"relation {i + 1}" for i in range(len(self.components)))
        return ("value",)


def _header_lines(lines: list[str]) -> list[int]:
    return [i + 1 for i, text in enumerate(lines) if re.match(r"^\s*\[\[\s*step\s*\]\]", text)]


def read_steps(raw: Any, lines: list[str], n: int, expr: Callable[[Any, str], sympy.Expr],
               fail: Callable[[str, str, int | None], DerivationError]) -> tuple[Step, ...]:
    r"""Parse the ``[[step]]`` array. ``expr(text, item)`` parses one document expression,
    ``fail(item, reason, line)`` builds the error; ``n`` is the number of positions."""
    if raw is None:
        return ()
    if not isinstance(raw, list) or not all(isinstance(t, dict) for t in raw):
        raise fail("step", "expected [[step]] tables", None)
    headers = _header_lines(lines)
    return tuple(_step(t, k, headers[k] if k < len(headers) else None, n, expr, fail)
                 for k, t in enumerate(raw))


def _strings(table: dict, key: str, item: str, line, fail) -> tuple[str, ...]:
    value = table.get(key, [])
    if isinstance(value, str):
        value = [value]
    if not isinstance(value, list) or not all(isinstance(v, (str, int, float)) and
                                              not isinstance(v, bool) for v in value):
        raise fail(f"{item}.{key}", "expected a list of strings", line)
    return tuple(str(v) for v in value)


def _texts(t: dict, key: str, item: str, line, fail, single: bool = False) -> tuple[str, ...]:
    r"""The printed texts of ``key``: strings, or LaTeX as written (``{ latex = '...' }`` for
    one, ``{ latex = ['...', ...] }`` for a list), kept as :class:`LatexSource` to be read by
    the file's LaTeX reader."""
    raw = unwrap_latex(t.get(key, None if single else []))
    items = [raw] if single or isinstance(raw, str) else raw
    if not isinstance(items, list):
        raise fail(f"{item}.{key}", "expected a list of strings or { latex = [...] }", line)
    out = []
    for value in items:
        value = unwrap_latex(value)
        if isinstance(value, LatexSource):
            out.append(value)
        elif isinstance(value, (str, int, float)) and not isinstance(value, bool):
            out.append(str(value))
        else:
            raise fail(f"{item}.{key}", "expected strings or { latex = '...' }", line)
    return tuple(out)


def _about(t: dict, item: str, line, expr, fail) -> tuple[tuple[str, sympy.Expr], ...]:
    about = t.get("about", {})
    if not isinstance(about, dict):
        raise fail(f"{item}.about", "expected a table: name = \"value\"", line)
    return tuple((str(k), expr(v, f"{item}.about.{k}")) for k, v in about.items())


def _point(value: Any, where: str, line, expr, fail) -> str | tuple[sympy.Expr, ...]:
    if isinstance(value, list):
        if len(value) != 3:
            raise fail(where, "a point is [x, y, z] in the body's frame", line)
        return tuple(expr(p, where) for p in value)
    if value not in ("origin", "com"):
        raise fail(where, f"{value!r}: expected origin, com or [x, y, z] in the body's frame",
                   line)
    return value


def _balance(t: dict, item: str, line, expr, fail) -> dict[str, Any]:
    r"""The ``body``, moment ``point``, ``frame`` and ``forces`` of a ``newton-euler`` step."""
    body = t.get("body")
    if not isinstance(body, str) or not body or body in FRAMES:
        raise fail(f"{item}.body", "a balance names its body (a link of the model)", line)
    frame = t.get("frame", "world")
    if not isinstance(frame, str) or not frame:
        raise fail(f"{item}.frame", "expected world, heading or a link name", line)
    table = t.get("forces", {})
    if not isinstance(table, dict) or not table:
        raise fail(f"{item}.forces", "a balance lists its forces: forces = { F = { point = "
                   "\"origin\", direction = [\"1\", \"0\", \"0\"] } }", line)
    forces = []
    for name, spec in table.items():
        where = f"{item}.forces.{name}"
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
        forces.append(Force(str(name), parsed,
                            _point(spec.get("point", "com"), f"{where}.point", line, expr, fail),
                            str(spec.get("frame", "world")), "couple" in spec, law))
    return dict(body=body, frame=frame, forces=tuple(forces),
                point=_point(t.get("point", "com"), f"{item}.point", line, expr, fail))


def _axes(t: dict, key: str, item: str, line, fail) -> tuple[str, ...]:
    axes = _strings(t, key, item, line, fail) or ("x", "y", "z")
    if any(a not in AXES for a in axes) or len(axes) != len(set(a.lstrip("-") for a in axes)):
        raise fail(f"{item}.{key}", f"axes are distinct among {', '.join(AXES)}", line)
    return axes


def _frame_step(t: dict, kind: str, item: str, line, fail) -> tuple[dict[str, Any],
                                                                    tuple[str, ...]]:
    r"""``frame``, ``axes`` (and ``body``, ``body_axes``) and the printed components of an
    ``orientation`` or ``gravity`` step."""
    frame = t.get("frame", "world")
    if not isinstance(frame, str) or not frame:
        raise fail(f"{item}.frame", "expected world, heading or a link name", line)
    axes = _axes(t, "axes", item, line, fail)
    texts = _texts(t, "components", item, line, fail)
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
    body_axes = _axes(t, "body_axes", item, line, fail)
    if len(axes) != 3 or len(body_axes) != 3 or len(texts) != 9:
        raise fail(f"{item}.components", "an orientation is a 3 x 3 matrix: nine components, "
                   "row by row, with three axes and three body axes", line)
    return dict(extra, body=body, body_axes=body_axes), texts


def _step(t: dict, k: int, line: int | None, n: int, expr, fail) -> Step:
    label = str(t.get("equation", ""))
    item = f"step {k + 1}" + (f" {label}" if label else "")
    for key in t:
        if key not in STEP_KEYS:
            raise fail(f"{item}.{key}", "unknown key; valid: " + ", ".join(STEP_KEYS), line)
    if not label.strip():
        raise fail(item, "every step needs its document label: equation = \"(57)\"", line)
    kind = t.get("kind")
    if kind not in STEP_KINDS:
        raise fail(f"{item}.kind", f"{kind!r} is not a step kind; valid: "
                   + ", ".join(STEP_KINDS), line)

    def parse(text: Any, where: str) -> sympy.Expr:
        if isinstance(text, str) and text.strip() == LOST:
            return sympy.nan
        return expr(text, where)

    extra: dict[str, Any] = {}
    if kind in FRAME_KINDS:
        extra, texts = _frame_step(t, kind, item, line, fail)
    elif kind in VECTOR_KINDS:
        body = t.get("body")
        if not isinstance(body, str) or not body or body == "world":
            raise fail(f"{item}.body", "a vector step names its body (a link of the model, or "
                       "\"heading\": the heading frame)", line)
        axes = _axes(t, "axes", item, line, fail)
        texts = _texts(t, "components", item, line, fail)
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
        frame = t.get("frame", "world")
        if not isinstance(frame, str) or not frame:
            raise fail(f"{item}.frame", "expected world, heading or a link name", line)
        extra = dict(body=body, axes=axes, point=point, frame=frame)
    elif kind in ("kinetic energy", "potential energy", "first integral"):
        if "value" not in t:
            raise fail(f"{item}.value", f"a {kind} step gives value = \"...\"", line)
        texts = _texts(t, "value", item, line, fail, single=True)
        bodies = _strings(t, "bodies", item, line, fail)
        if any(b in FRAMES for b in bodies):
            raise fail(f"{item}.bodies", "an energy is of links of the model (world and heading "
                       "are frames)", line)
        extra = dict(bodies=bodies)
        if kind == "potential energy":
            quantity = t.get("quantity", "potential")
            if quantity not in POTENTIAL_QUANTITIES:
                raise fail(f"{item}.quantity", "expected one of "
                           + ", ".join(POTENTIAL_QUANTITIES), line)
            extra["quantity"] = quantity
    elif kind in RESULT_KINDS:
        if kind == "steady motion":            # the claim is the state itself
            t = {**t, "value": t.get("value", "steady")}
        if "value" not in t:
            raise fail(f"{item}.value", f"a {kind} step gives value = \"...\"", line)
        texts = _texts(t, "value", item, line, fail, single=True)
        extra = dict(about=_about(t, item, line, expr, fail))
        if kind == "steady motion" and texts[0] != "steady":
            raise fail(f"{item}.value", "a steady motion claims its state (about), no value",
                       line)
        if kind == "stability":
            if texts[0] not in STABILITY_CLAIMS:
                raise fail(f"{item}.value", "a stability step claims value = \"stable\" or "
                           "\"unstable\"", line)
            if "speed" in t:
                if not isinstance(t["speed"], str) or not t["speed"]:
                    raise fail(f"{item}.speed", "the document velocity the claim is for at "
                               "every value: speed = \"dphi\"", line)
                extra["speed"] = t["speed"]
        if kind == "critical speed":
            speed = t.get("speed")
            if not isinstance(speed, str) or not speed:
                raise fail(f"{item}.speed", "a critical speed names the document velocity it "
                           "is of: speed = \"dphi\"", line)
            extra["speed"] = speed
    elif kind in RELATION_KINDS:
        if kind == "newton-euler":
            extra = _balance(t, item, line, expr, fail)
        if kind == "linearised equations":
            extra = dict(about=_about(t, item, line, expr, fail))
        texts = _texts(t, "relations", item, line, fail)
        if not texts or any(s.count("=") != 1 for s in texts):
            raise fail(f"{item}.relations", "expected relations = [\"lhs = rhs\", ...], one "
                       "'=' each", line)
    else:
        quantity = t.get("quantity", "inertia")
        if quantity not in QUANTITIES:
            raise fail(f"{item}.quantity", f"expected one of {', '.join(QUANTITIES)}", line)
        texts = _texts(t, "components", item, line, fail)
        rows = t.get("rows", list(range(1, len(texts) + 1)))
        if not isinstance(rows, list) or len(rows) != len(texts) or not all(
                isinstance(r, int) and not isinstance(r, bool) and 1 <= r <= n for r in rows):
            raise fail(f"{item}.rows", f"one row number (1 to {n}) per component", line)
        extra = dict(quantity=quantity, rows=tuple(r - 1 for r in rows))
    names = _strings(t, "names", item, line, fail)
    if names and len(names) != len(texts):
        raise fail(f"{item}.names", f"{len(names)} names for {len(texts)} components", line)
    components, sides = [], []
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
    return Step(equation=label, kind=kind, components=tuple(components), printed=texts,
                label=str(t.get("label", "")), given=_strings(t, "given", item, line, fail),
                note=str(t.get("note", "")), line=line, sides=tuple(sides), names=names, **extra)


__all__ = ["Force", "RELATION_KINDS", "RESULT_KINDS", "Step", "STEP_KINDS", "read_steps"]
