r"""The record of one step of a derivation (:class:`Step`, its applied :class:`Force`) and the
kinds of steps a ``[[step]]`` table of a file can record.

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

from dataclasses import dataclass

import sympy

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



__all__ = ["AXES", "FORCE_KEYS", "FRAME_KINDS", "FRAMES", "Force", "LOST", "POINTS",
           "POTENTIAL_QUANTITIES", "QUANTITIES", "RELATION_KINDS", "RESULT_KINDS",
           "STABILITY_CLAIMS", "STEP_KEYS", "STEP_KINDS", "Step", "VECTOR_KINDS"]
