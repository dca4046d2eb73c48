r"""What a document assumes, declared in its file (``[assumes]``), and how the comparison uses it.

A document usually simplifies the body: a symmetric body (products of inertia zero, centre of
mass above the axle), identical disc wheels, no motor inertia, equations linearised about a
state, a potential measured from an equilibrium. Declared, these are the document's own
assumptions: the comparison judges it under them first (the truth is computed on parameter sets
of the declared families, at the linearisation point), reports them once in one "assumes:" line,
and names as "agrees only if ..." only a condition the document did not state.

- ``families``: names of the model's special parameter families (:mod:`.samples`);
- ``uniform``: links that are uniform bodies (a disc, a ball, a rod): each is scaled as a whole
  with its lengths (:func:`.samples.uniform_family`), so its inertia stays :math:`m r^2/2`,
  :math:`\tfrac25 m r^2`, :math:`m l^2/12` of its drawn radius or length;
- ``linearised_about``: position = value. The linearised equations are compared at that state
  (positions drawn there, velocities random): A and B there, the velocity products of h zero
  (a linearisation about rest has none);
- ``potential = "equilibrium"``: the potential is measured from the equilibrium at that state
  (springs the model lacks balance gravity there): the gravity of the truth's Q at the state
  is subtracted, the model's own springs' force there kept (a spring's preload is the
  model's, and a document that drops it differs).
  The stiffness (Q's first-order terms) is compared as always: the springs' own constants are
  the document's to give (``[assume]``, 0 where the model has none);
- ``text``: other assumptions, in words (reported, not used).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from typing import Any
from dataclasses import dataclass, field

import numpy as np
import sympy as sp

from ...derivations.schema import Derivation
from ...errors import DerivationError, ParameterError, UnknownNameError
from ...expression_size import free_symbols_of
from ..records import Cause, CauseKind
from .round_wheels import implied_wheel_families, round_contradiction
from .samples import SpecialCase, family, massless_family, special_cases


#: Terms a cause lists where a linearised file's equations are not linear.
LISTED = 3
#: A declared range narrower than this share of the default span of a position is said
#: among the causes (:meth:`Assumptions.narrow_ranges`).
NARROW = 0.01


@dataclass(frozen=True)
class Assumptions:
    r"""The declared assumptions of one derivation, resolved against its model."""

    families: tuple[SpecialCase, ...] = ()
    linearised_about: tuple[tuple[str, float], ...] = ()
    equilibrium_potential: bool = False
    text: tuple[str, ...] = field(default=())
    #: ``[coordinates] ranges``: (position, low, high) — the states are drawn there only
    ranges: tuple[tuple[str, float, float], ...] = ()

    def describe(self) -> tuple[str, ...]:
        r"""The "assumes:" items, in words; a declared range among them (the comparison
        holds there only: a small angle's approximation agrees on a narrow one)."""
        out = [c.description for c in self.families]
        if self.linearised_about:
            point = ", ".join(f"{k} = {v:g}" for k, v in self.linearised_about)
            out.append(f"the equations are linearised about {point}")
        out += [f"{p} only in [{lo:.10g}, {hi:.10g}] (the file's ranges: compared there only)"
                for p, lo, hi in self.ranges]
        if self.equilibrium_potential:
            out.append("the potential is measured from the equilibrium at that state")
        return (*out, *self.text)

    def narrow_ranges(self, exprs: Iterable[sp.Basic | None]) -> tuple[Cause, ...]:
        r"""A cause for each declared range narrower than :data:`NARROW` (of the default span,
        2π) of a position the equations ``exprs`` are functions of: the comparison sees
        little of the motion there (a term wrong everywhere else agrees on it: cos for sin at
        θ = π/4)."""
        written = {str(x) for e in exprs if e is not None for x in free_symbols_of(e)}
        return tuple(Cause(CauseKind.ASSUMPTION, (), (
            f"{p} stays in [{lo:.10g}, {hi:.10g}], as the file's ranges declare (a span of "
            f"{hi - lo:.2g}): the comparison sees no other state of {p}, and a term wrong "
            "elsewhere may agree there")) for p, lo, hi in self.ranges
            if hi - lo < NARROW * 2 * np.pi and p in written)

    def not_linear(self, positions: Sequence[sp.Symbol],
                   exprs: Mapping[str, sp.Basic | None]) -> tuple[Cause, ...]:
        r"""For equations declared linearised, a ``file_error`` cause where they are not
        linear in the deviations from the point: a velocity product (C, h), an inertia or
        input coefficient that depends on a position (A, B), a Q whose second derivative
        in the positions is not zero. Such a term is compared at the point only, to first
        order: its sign or factor there is never seen (a centripetal term's, at θ = 0)."""
        if not self.linearised_about:
            return ()
        found: list[str] = []
        for key in ("C", "h", "A", "B", "Q"):
            M = exprs.get(key)
            if not isinstance(M, sp.MatrixBase):
                continue
            for (i, j), e in np.ndenumerate(np.array(M.tolist(), dtype=object)):
                e = sp.sympify(e)
                if e == 0 or not (key in "Ch" or e.free_symbols & set(positions)) or (
                        key == "Q" and all(sp.diff(e, p, r) == 0 for p in positions
                                           for r in positions)):
                    continue
                where = f"{key}[{i + 1}]" if M.shape[1] == 1 else f"{key}[{i + 1},{j + 1}]"
                found.append(f"{where} = {sp.sstr(e)}")
        if not found:
            return ()
        point = ", ".join(f"{k} = {v:g}" for k, v in self.linearised_about)
        shown = "; ".join(found[:LISTED]) + (f" and {len(found) - LISTED} more"
                                             if len(found) > LISTED else "")
        return (Cause(CauseKind.FILE_ERROR, (), (
            f"the file declares its equations linearised about {point}, but they are not "
            f"linear in the deviations from it: {shown}; they are compared at that state "
            "only, to first order (a term of higher order there, its sign or its factor, is "
            "not compared, but for velocity products, compared with the true ones in full: "
            "declare the linearisation only for equations that are linear)")),)

    def file_causes(self, d: Derivation, exprs: Mapping[str, sp.Basic | None]
                    ) -> tuple[Cause, ...]:
        r"""What the file's own declarations say first: a narrow range, equations declared
        linearised that are not linear, a declared ``round_wheels`` beside symbols of the
        wheels' asymmetry, a link declared uniform whose URDF inertia is no uniform body's."""
        return (*self.narrow_ranges(exprs.values()), *self.not_linear(d.positions, exprs),
                *round_contradiction(d, self.families), *_unlike_uniform(d, self.families))

    def key(self) -> tuple:
        r"""Hashable identity (cache key of the truth)."""
        return (tuple(c.name for c in self.families), self.linearised_about,
                self.equilibrium_potential)


def _unlike_uniform(d: Derivation, families: Sequence[SpecialCase]) -> tuple[Cause, ...]:
    r"""A ``file_error`` cause per link the file declares uniform whose URDF moments are no
    uniform body's of any cylinder, sphere or box it draws
    (:func:`~wheeled_dyn.models.uniform_reading.unlike_uniform`): the family keeps the
    URDF's inertia in its proportions, so a term the document writes as the uniform body's
    moment differs by that."""
    from ...models.registry import load_model, model_entry
    links = list(dict.fromkeys(link for c in families for link in (c.uniform or ())))
    if not links or model_entry(d.model).parameters is not None:
        return ()
    lengths = load_model(d.model).lengths
    unlike = {} if lengths is None else lengths.unlike_uniform
    return tuple(Cause(CauseKind.FILE_ERROR, (), (
        f"the file declares {link} uniform, but {unlike[link]}: the truth keeps the URDF's "
        "inertia (scaled as a whole), so a term written as the uniform body's moment "
        "differs by that (mend the URDF's inertia, or do not declare the link uniform)"))
        for link in links if link in unlike)


def declared(d: Derivation) -> Assumptions:
    r"""The assumptions ``d`` declares; an unknown family name is a
    :class:`~wheeled_dyn.errors.DerivationError` naming the file and the valid names."""
    raw: Mapping[str, Any] = d.assumes or {}          # as read from TOML
    families = [named_family(d, name, f"assumes.families.{name}")
                for name in raw.get("families", ())]
    uniform = raw.get("uniform", ())
    links = tuple(str(x) for x in uniform) if isinstance(uniform, (list, tuple)) else ()
    if links:             # the family uniform(link, ...) of a model without a physical record
        families.append(named_family(d, f"uniform({', '.join(links)})", "assumes.uniform"))
    _massless_named(d, families)
    point = tuple((k, float(v)) for k, v in dict(raw.get("linearised_about", {})).items())
    coordinates: Mapping[str, Any] = d.coordinates.raw           # as read from TOML
    drawn: Mapping[str, Any] = coordinates.get("ranges", {})
    ranges = tuple((str(p), float(r[0]), float(r[1])) for p, r in drawn.items()
                   if p not in dict(point))
    families += implied_wheel_families(d, tuple(families))
    return Assumptions(tuple(families), point, raw.get("potential") == "equilibrium",
                       tuple(raw.get("text", ())), ranges)


def _massless_named(d: Derivation, families: list[SpecialCase]) -> None:
    r"""A symbol whose value names the mass or inertia of a link a declared ``massless``
    family takes off is a :class:`~wheeled_dyn.errors.DerivationError` naming both (it was an
    unknown parameter, the file and the declaration unnamed)."""
    from sympy.core.function import AppliedUndef

    from ...models.link_parameters import FUNCTIONS
    gone = {link: c.name for c in families for link in c.massless}
    for name, spec in d.symbols.items():
        for call in () if spec.value is None else spec.value.atoms(AppliedUndef):
            link = str(call.args[0]) if call.args else ""
            if call.func.__name__ in FUNCTIONS and link in gone:
                raise DerivationError(d.path, f"symbols.{name}", (
                    f"{call} is the mass or inertia of link {link}, which assumes.families "
                    f"declares without mass ({gone[link]}): drop the link from the family, "
                    "or the symbol"))


def named_family(d: Derivation, name: str, where: str) -> SpecialCase:
    r"""The parameter family ``name`` of ``d``'s model (:func:`.samples.family`: one of its
    special cases, or ``uniform(link, ...)``); anything else is a
    :class:`~wheeled_dyn.errors.DerivationError` at ``where`` listing the valid names."""
    from ...models.registry import model_entry
    try:
        found = family(d.model, name)
    except (UnknownNameError, ParameterError) as exc:
        raise DerivationError(d.path, where, f"{name!r}: {exc}") from None
    if found is None:
        valid = [c.name for c in special_cases(d.model)]
        if model_entry(d.model).parameters is None:
            valid.append("uniform(link, ...)")
        raise DerivationError(d.path, where, f"{name!r} is not a parameter family of model "
                              f"{d.model!r}; valid: " + ", ".join(valid))
    return found


def undeclared_cases(d: Derivation, assumed: Assumptions) -> tuple[SpecialCase, ...]:
    r"""The parameter families ``d`` does not declare, weakest first: its model's special
    cases, then, for a model without a physical record, the links the document leaves out
    carrying no mass (:func:`left_out`)."""
    names = {c.name for c in assumed.families}
    cases = [c for c in special_cases(d.model) if c.name not in names]
    links = left_out(d)
    if links and not any(set(links) <= set(c.massless) for c in assumed.families):
        them = "it" if len(links) == 1 else "them"
        cases.append(massless_family(links, f"no symbol of the document names {them}"))
    return tuple(cases)


def left_out(d: Derivation) -> tuple[str, ...]:
    r"""The links with mass that nothing of ``d`` names, each the only link with mass of its
    rigid body: none of its symbols' values calls them (``M(link)``, ``radius(link)``) or
    the joint that carries them (``origin_x(joint)``), its coordinates do not move that joint,
    and they are not wheels or contacts of the model. Only where the document names some link
    by its mass or inertia (it names bodies by their links, so one it never names is one it
    leaves out: a caster of a differential-drive robot); none for a model with a physical
    record."""
    import pinocchio as pin
    from sympy.core.function import AppliedUndef

    from ...models.geometry_apply import bodies_of
    from ...models.link_parameters import FUNCTIONS
    from ...models.registry import load_model, model_entry
    if model_entry(d.model).parameters is not None or d.coordinates.use:
        return ()
    wm = load_model(d.model)
    if wm.lengths is None:
        return ()
    calls = [c for s in d.symbols.values() if s.value is not None
             for c in s.value.atoms(AppliedUndef) if c.args]
    if not any(c.func.__name__ in FUNCTIONS for c in calls):
        return ()
    joints = {alias: joint for joint, alias in wm.spec.aliases.items()}   # coordinate -> joint
    named = {str(c.args[0]) for c in calls} | {joints.get(k, k)
                                               for k in d.coordinates.configuration}
    kept = {w.link for w in wm.wheels} | {w.link for w in wm.rolling_wheels}
    if wm.contact is not None:
        kept.add(wm.contact.spec.link)
    model, masses = wm.model, wm.lengths.inertials
    out: list[str] = []
    for jid, links in bodies_of(wm).items():
        massive = [k for k in links if masses.get(k, (0.0,))[0] > 0]
        carriers = {model.frames[model.frames[model.getFrameId(k, pin.FrameType.BODY)]
                                 .parentFrame].name
                    for k in links}                       # the fixed joints that attach them
        if jid and massive and not (set(links) | carriers | {model.names[jid]}) & named \
                and not set(links) & kept:
            out += massive
    return tuple(out)


#: Half the range positions are drawn in where the file declares none: [−π, π], a turn, where
#: the truth is periodic in them; two turns where the model has springs (a spring's force
#: grows with its angle: a document writing the angle wrapped into [−π, π] differs beyond).
PERIOD, SPRUNG = np.pi, 2 * np.pi


def position_ranges(d: Derivation, positions: Sequence[str], assumptions: Assumptions,
                    sprung: bool = False) -> list[tuple[float, float]]:
    r"""Where each position is drawn: the linearisation point, else the file's declared
    range, else [−π, π] (``sprung``, a model with springs: [−2π, 2π])."""
    raw: Mapping[str, Any] = d.coordinates.raw            # as read from TOML
    ranges = dict(raw.get("ranges", {}))
    point = dict(assumptions.linearised_about)
    half = SPRUNG if sprung else PERIOD
    return [(point[p], point[p]) if p in point else tuple(ranges.get(p, (-half, half)))
            for p in positions]


def apply_to_truth(truth, assumptions: Assumptions, springs_Q: np.ndarray | None = None
                   ) -> None:
    r"""The truth as the document's assumptions read it (in place): linearised about rest, no
    velocity products; measured from the equilibrium, no gravity in Q at the equilibrium
    state (springs the model lacks balance it there): Q is ``springs_Q``, the model's own
    springs' force there (zero where it has none)."""
    if assumptions.linearised_about:
        for name in ("C", "h", "H"):
            M = getattr(truth, name)
            if M is not None:
                setattr(truth, name, np.zeros_like(M))
    if assumptions.equilibrium_potential and truth.Q is not None:
        truth.Q = np.zeros_like(truth.Q) if springs_Q is None else springs_Q
