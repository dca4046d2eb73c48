r"""Random, physically consistent parameter sets and the values of a model's parameter names.

A comparison evaluates the document and the truth over K parameter sets × N states. Agreement
at one set of numbers can hide errors (a product of inertia that happens to be 0 hides every
term it multiplies; :math:`l^2` written for :math:`l` is invisible where :math:`l = 1`), so the
sets are random: every product of inertia and centre-of-mass offset nonzero, and every length
of the model drawn too (joint origins, wheel, ball and contact radii, track, the constants of
its ``[geometry]``: :mod:`~wheeled_dyn.models.geometry_apply`; for a model with a physical
parameter record, the record's lengths — its links' shapes stay the URDF's), except where the
model declares a symmetry: the two drive wheels of a wheeled model stay alike (one shared
random scaling of the URDF's wheels), lengths its ``[geometry]`` lists as equal stay equal.
*Special cases* restrict them (e.g. products of inertia zero, a uniform body): an element that
agrees under a special case only is reported as "agrees only if ...".

The model namespace a derivation's symbols are written in: the physical parameters of the
model's record (``m_S, d, I1, ...`` for the WIP), the geometric ``R`` (wheel radius), ``L``
(half track), ``g``, Khalil's standard parameters of each link, keyed ``XX(body)``, and the
model's lengths, keyed ``origin_x(joint)``, ``radius(link)`` ...
(:mod:`~wheeled_dyn.models.geometry`).
"""

from __future__ import annotations

from collections.abc import Callable, Collection, Sequence
from dataclasses import dataclass, replace

import numpy as np
import pinocchio as pin

from ...errors import ParameterError
from ...models.builder import WheeledModel
from ...models.geometry_apply import FACTOR, apply_geometry, bodies_of, draw_geometry
from ...models.conventions import RIGHT_ANGLE_TOL, base_joints, right_angled_joints
from ...models.rounded_angles import unrounded_joints
from ...models.round_wheels import made_round
from .alike_links import ALIKE_LINKS, alike_description, draw_alike
from .wheel_draws import alike_wheels, wheel_axles
from ...models.registry import load_model, model_entry, model_parameters
from ...models.springs import with_stiffness
from ...models.wip_parameters import WipParameters, random_wip_parameters


@dataclass(frozen=True)
class SpecialCase:
    r"""A named restriction of the parameters (applied to a random set). ``uniform``: for a
    model without a physical record, the links that stay uniform bodies (scaled as a whole,
    their lengths with them); ``()``: every link; None: not such a family."""

    name: str
    description: str
    apply: Callable[[WipParameters], WipParameters]
    uniform: tuple[str, ...] | None = None
    massless: tuple[str, ...] = ()


WIP_SPECIAL_CASES: tuple[SpecialCase, ...] = (
    SpecialCase("no_products", "the body's products of inertia are zero (Ixy = Ixz = Iyz = 0)",
                lambda p: p.replace(Ixy=0.0, Ixz=0.0, Iyz=0.0)),
    SpecialCase("com_on_axis", "the body's centre of mass is straight above the axle midpoint "
                "(d_x = d_z = 0)", lambda p: p.replace(d_x=0.0, d_z=0.0)),
    SpecialCase("disc_wheels", "the wheels are uniform thin discs (Iw3 = m_C R²/2, "
                "Iw2 = m_C R²/4)", lambda p: p.replace(Iw3=p.m_C * p.R**2 / 2,
                                                        Iw2=p.m_C * p.R**2 / 4)),
    SpecialCase("I1_eq_I2", "the body's moments about the forward and vertical axes are equal "
                "(I1 = I2)", lambda p: p.replace(I2=p.I1)),
    SpecialCase("no_armature", "the motors add no rotor inertia (I_a = 0)",
                lambda p: p.replace(I_a=0.0)),
)


#: Generic models (no physical record): random inertias keeping the URDF's inertial structure.
URDF_STRUCTURE = SpecialCase(
    "urdf_structure", "every link's centre of mass and principal axes are as in the URDF "
    "(coordinates and products of inertia that are zero there stay zero)", lambda p: p)


#: Generic models: every body's inertia about its centre of mass diagonal in its joint's axes
#: (no products of inertia: the tiny ones a CAD export writes, or a rounded angle leaves).
NO_PRODUCTS = SpecialCase(
    "principal_axes", "every link's products of inertia are zero (its principal axes along its "
    "joint's axes)", lambda p: p)


#: Generic models: each link scaled as a whole (mass by one factor, lengths by another, its radii,
#: shapes and the origins of the joints it carries with them), so its shape stays the URDF's
#: (a uniform ball stays uniform with its radius, a rod stays a uniform rod of its length).
URDF_PROPORTIONS = SpecialCase(
    "urdf_proportions", "every link keeps the URDF's proportions (its mass and size scaled "
    "as a whole, its lengths with it: a uniform body stays uniform)", lambda p: p, ())


#: Wheeled models: the two drive wheels axisymmetric about their axles, as a derivation takes
#: a wheel (:mod:`~wheeled_dyn.models.round_wheels`): declared, offered as an explanation, and
#: implied where the URDF's are so to its rounding (:mod:`.round_wheels`).
ROUND_WHEELS = SpecialCase(
    "round_wheels", "the drive wheels are axisymmetric about their axles (one moment about "
    "every diameter, no products of inertia, the centres of mass on the axles)", lambda p: p)


#: Wheeled models: the two drive wheels alike but with a random inertia and centre of mass
#: (the same in their joints' frames), where a document names their asymmetry (a product of
#: inertia, the centre of mass off the axle): implied (:mod:`.round_wheels`).
FREE_WHEELS = SpecialCase(
    "free_wheels", "the drive wheels are drawn alike with a random inertia and centre of mass "
    "(implied: the document names parameters of their asymmetry, compared as drawn)",
    lambda p: p)


def uniform_family(links: Sequence[str]) -> SpecialCase:
    r"""The family in which ``links`` stay uniform bodies (declared in a derivation's
    ``[assumes] uniform``)."""
    names = ", ".join(links)
    verb = "is a uniform body" if len(links) == 1 else "are uniform bodies"
    return SpecialCase(f"uniform({names})", f"{names} {verb} (mass and size scaled as a whole, "
                       "its lengths with it)", lambda p: p, tuple(links))


def massless_family(links: Sequence[str], why: str = "") -> SpecialCase:
    r"""The family in which ``links`` carry no mass (each the only link with mass of its rigid
    body): a body a document leaves out (a caster it does not model: ``why`` says how it was
    found), or declares left out (``[assumes] families = ["massless(link, ...)"]``)."""
    names = ", ".join(links)
    verb = "carries no mass" if len(links) == 1 else "carry no mass"
    return SpecialCase(f"massless({names})", f"{names} {verb}" + (f" ({why})" if why else ""),
                       lambda p: p, massless=tuple(links))


def _massless_bodies(wm: WheeledModel, links: Collection[str]) -> list[int]:
    r"""The rigid bodies of ``links`` (their joint ids); a
    :class:`~wheeled_dyn.errors.ParameterError` where one of them shares its body with a link
    with mass that is not among them (its mass cannot be taken out alone)."""
    inertials = wm.lengths.inertials if wm.lengths is not None else {}
    out = []
    for jid, members in bodies_of(wm).items():
        named = set(members) & set(links)
        if not named or not jid:
            continue
        others = [m for m in members if m not in named and inertials.get(m, (0.0,))[0] > 0]
        if others:
            raise ParameterError(f"massless({', '.join(sorted(named))})", others[0],
                                 f"among the links named: {others[0]} is in the same rigid "
                                 "body and has mass")
        out.append(jid)
    return out


@dataclass(frozen=True)
class ParameterSet:
    r"""A model with its parameters, and the values of every name of its namespace."""

    model: WheeledModel
    values: dict[str, float]
    physical: WipParameters | None = None


def namespace_values(wm: WheeledModel, physical: WipParameters | None) -> dict[str, float]:
    values = model_parameters(wm)
    if physical is not None:
        values.update(physical.as_dict())
    return values


#: Times a draw of the lengths that makes a contact invalid (a ball as large as its bowl) is
#: made again.
GEOMETRY_REDRAWS = 50


def _with_geometry(wm: WheeledModel, rng: np.random.Generator, uniform: Collection[str],
                   spread: float = FACTOR) -> WheeledModel:
    r"""``wm`` with random lengths (:func:`~wheeled_dyn.models.geometry_apply.draw_geometry`),
    drawn again where a contact would be invalid."""
    for _ in range(GEOMETRY_REDRAWS):
        try:
            return apply_geometry(wm, draw_geometry(wm, rng, uniform, spread))
        except ParameterError:
            continue
    return wm


def uniform_links(wm: WheeledModel, special: Sequence[SpecialCase]) -> set[str]:
    r"""The links the ``special`` families keep uniform (every link with mass for
    ``urdf_proportions``); a drive wheel with the others (the model declares them alike: one
    uniform and the other drawn freely would not be)."""
    out: set[str] = set()
    masses = {link for jid, links in bodies_of(wm).items() for link in links
              if jid and wm.lengths is not None and wm.lengths.inertials.get(link, (0.0,))[0] > 0}
    for case in special:
        if case.uniform == ():
            out |= masses
        elif case.uniform:
            out |= set(case.uniform)
    wheels = {w.link for w in wm.wheels}
    return out | wheels if out & wheels else out


def _random_link_inertias(wm: WheeledModel, rng: np.random.Generator,
                          keep_structure: bool = False,
                          uniform: frozenset[str] | set[str] = frozenset(),
                          massless: Collection[str] = (), principal: bool = False,
                          spread: float = FACTOR, rounded: bool = False,
                          free: bool = False, alike: bool = False) -> WheeledModel:
    r"""Random lengths (the ``uniform`` links scaled as a whole with a random mass factor
    each, and their bodies put together again from their links:
    :mod:`~wheeled_dyn.models.geometry_apply`), and random, physically consistent inertias
    (log-Cholesky parameters) for every other joint that carries mass; a random gravity. With
    ``keep_structure`` the URDF's inertias are rescaled instead: mass and each centre-of-mass
    coordinate by random factors, the principal moments by random factors keeping the triangle
    inequality, the principal axes unchanged. Each spring's stiffness and rest position are
    scaled by random factors in [0.5, 2]. The bodies of the ``massless`` links carry none;
    with ``principal`` every body's inertia about its centre is made diagonal in its joint's
    axes (the diagonal of a valid one is valid: :math:`J_{ii} = \Sigma_{jj} + \Sigma_{kk}` of
    the second moments' diagonal). ``spread``: each length's factor is drawn in
    :math:`[1/s, s]` (and with ``keep_structure`` each centre-of-mass coordinate's too).
    ``rounded``: the drive wheels axisymmetric (:data:`ROUND_WHEELS`); ``free``: drawn
    alike from a random inertia (:data:`FREE_WHEELS`); ``alike``: the links the URDF writes
    alike drawn alike (:mod:`.alike_links`)."""
    drawn = _with_geometry(wm, rng, uniform, spread)
    model = pin.Model(drawn.model)               # never the model of ``wm`` itself
    right_angled_joints(model, base_joints(drawn),
                        unrounded_joints(drawn.spec.urdf, RIGHT_ANGLE_TOL))
    composed = {jid for jid, links in bodies_of(wm).items() if uniform & set(links)}
    for jid in range(1, model.njoints):
        if model.inertias[jid].mass > 0 and jid in composed:
            continue                              # its links drawn with the lengths
        elif model.inertias[jid].mass > 0 and keep_structure:
            old = model.inertias[jid]
            eig, axes = np.linalg.eigh(old.inertia)
            second = 0.5 * (eig.sum() - 2 * eig)           # second moments along the axes
            second = np.maximum(second, 0.0) * rng.uniform(0.5, 2.0, 3)
            moments = np.array([second[1] + second[2], second[0] + second[2],
                                second[0] + second[1]])
            mass = old.mass * rng.uniform(0.5, 2.0)       # drawn before the centre, as ever
            lever = old.lever * (rng.uniform(0.5, 2.0, 3) if spread == FACTOR else
                                 np.exp(rng.uniform(-np.log(spread), np.log(spread), 3)))
            model.inertias[jid] = pin.Inertia(mass, lever, axes @ np.diag(moments) @ axes.T)
        elif model.inertias[jid].mass > 0:
            base = model.inertias[jid].toDynamicParameters()
            scale = np.log(max(base[0], 1e-3))
            theta = rng.normal(size=10) * 0.3
            theta[0] += 0.5 * scale / 3
            model.inertias[jid] = pin.Inertia.FromLogCholeskyParameters(
                pin.LogCholeskyParameters(theta))
    if alike:
        draw_alike(wm, model)
    if not composed & {w.joint_id for w in wm.wheels}:
        alike_wheels(wm, model, rng, rounded, free)
    elif rounded:                         # uniform wheels, drawn with the lengths: as round
        for jid, axis in wheel_axles(wm).items():
            model.inertias[jid] = made_round(model.inertias[jid], axis)
    for jid in _massless_bodies(wm, massless):
        model.inertias[jid] = pin.Inertia.Zero()
    if principal:
        for jid in range(1, model.njoints):
            old = model.inertias[jid]
            model.inertias[jid] = pin.Inertia(old.mass, old.lever, np.diag(np.diag(old.inertia)))
    model.gravity = pin.Motion(np.array([0.0, 0.0, -rng.uniform(5.0, 15.0)]), np.zeros(3))
    springs = with_stiffness(wm.springs, rng.uniform(0.5, 2.0, len(wm.springs)),
                             rng.uniform(0.5, 2.0, len(wm.springs))) \
        if wm.springs else None
    return drawn.with_model(model, springs)


def parameter_sets(model_name: str, k: int, rng: np.random.Generator,
                   special: tuple[SpecialCase, ...] = (), spread: float = FACTOR
                   ) -> list[ParameterSet]:
    r"""``k`` random parameter sets of the model, restricted by the ``special`` cases; each
    length's factor in :math:`[1/s, s]` for the ``spread`` s (the WIP's record: its own
    ranges, and with a wider spread its lengths each times such a factor)."""
    entry = model_entry(model_name)
    out: list[ParameterSet] = []
    if entry.parameters is WipParameters:
        while len(out) < k:
            p = random_wip_parameters(rng)
            if spread != FACTOR:
                p = replace(p, **{name: getattr(p, name) * float(np.exp(rng.uniform(
                    -np.log(spread), np.log(spread)))) for name in WipParameters.LENGTHS})
            try:
                for case in special:
                    p = case.apply(p)
            except ParameterError:
                continue                      # the restriction made it non-physical: redraw
            wm = load_model(model_name, p)
            out.append(ParameterSet(wm, namespace_values(wm, p), p))
        return out
    base = load_model(model_name)
    keep = URDF_STRUCTURE in special
    uniform = uniform_links(base, special)
    massless = {link for case in special for link in case.massless}
    principal = NO_PRODUCTS in special
    rounded = any(c.name == ROUND_WHEELS.name for c in special)   # declared or implied
    free = any(c.name == FREE_WHEELS.name for c in special)       # implied
    alike = any(c.name == ALIKE_LINKS for c in special)
    for _ in range(k):
        wm = _random_link_inertias(base, rng, keep, uniform, massless, principal, spread,
                                   rounded, free, alike)
        out.append(ParameterSet(wm, namespace_values(wm, None)))
    return out


def family(model_name: str, name: str) -> SpecialCase | None:
    r"""The model's special family called ``name``: one of :func:`special_cases`, or
    ``uniform(link, ...)`` (:func:`uniform_family`) or ``massless(link, ...)``
    (:func:`massless_family`) for links of a model without a physical record; None for
    another name (an unknown link is an :class:`~wheeled_dyn.errors.UnknownNameError`)."""
    found = next((c for c in special_cases(model_name) if c.name == name), None)
    head = next((h for h in ("uniform(", "massless(") if name.startswith(h)), None)
    if found is not None or head is None or not name.endswith(")"):
        return found
    if model_entry(model_name).parameters is not None:
        return None
    links = tuple(x.strip() for x in name[len(head):-1].split(","))
    wm = load_model(model_name)
    for link in links:
        wm.joint_id_of_link(link)
    if head == "massless(":
        _massless_bodies(wm, links)
        return massless_family(links)
    return uniform_family(links)


#: A model without a physical record whose links with mass are at least two and at most this
#: many also offers each of them uniform alone as a family (a per-link "agrees only if").
UNIFORM_LINK_FAMILIES = 4


def special_cases(model_name: str) -> tuple[SpecialCase, ...]:
    r"""The special families of a model, weakest first: the WIP's
    (:data:`WIP_SPECIAL_CASES`); for the others ``urdf_structure``, ``principal_axes``
    (:data:`NO_PRODUCTS`), for a wheeled model ``round_wheels`` (:data:`ROUND_WHEELS`),
    for a model with links the URDF writes alike ``alike_links`` (:mod:`.alike_links`),
    each link with mass uniform alone (:func:`uniform_family`, two to
    :data:`UNIFORM_LINK_FAMILIES` such links) and every link uniform
    (``urdf_proportions``)."""
    if model_entry(model_name).parameters is WipParameters:
        return WIP_SPECIAL_CASES
    wm = load_model(model_name)
    links = sorted(uniform_links(wm, (URDF_PROPORTIONS,)))
    each = tuple(uniform_family((link,)) for link in links) \
        if 2 <= len(links) <= UNIFORM_LINK_FAMILIES else ()
    wheels = (ROUND_WHEELS,) if len(wm.wheels) == 2 else ()
    said = alike_description(wm)
    alike = (SpecialCase(ALIKE_LINKS, said, lambda p: p),) if said is not None else ()
    return (URDF_STRUCTURE, NO_PRODUCTS, *wheels, *alike, *each, URDF_PROPORTIONS)


def regular_states(cmap, q: np.ndarray, rng: np.random.Generator,
                   ranges: Sequence[tuple[float, float]] | None = None) -> np.ndarray:
    r"""``q`` (N × n document positions) with every position where the coordinate map's
    condition number exceeds :data:`MAX_CONDITION` drawn again (at most
    :data:`REDRAWS` times): the truth there is rounding. Positions that stay singular are
    kept (a document whose coordinates are singular everywhere is judged as it is)."""
    q = np.array(q, dtype=float)
    for _ in range(REDRAWS):
        bad = np.flatnonzero(cmap.conditioning(q) > MAX_CONDITION)
        if not bad.size:
            break
        q[bad] = random_states(q.shape[1], len(bad), rng, ranges)[0]
    return q


def random_states(n_positions: int, n: int, rng: np.random.Generator,
                  ranges: Sequence[tuple[float, float]] | None = None) -> tuple[np.ndarray, np.ndarray]:
    r"""``n`` states: positions uniform in [-π, π] (or in the document's declared ``ranges``,
    one (low, high) per position), velocities standard normal."""
    low, high = (np.array(r, dtype=float) for r in zip(*ranges)) if ranges else (-np.pi, np.pi)
    return rng.uniform(low, high, (n, n_positions)), rng.normal(size=(n, n_positions))


#: Largest condition number of the coordinate map at a sampled state: near a singularity of
#: the document's coordinates the reduced terms carry errors of order cond³ × rounding.
MAX_CONDITION = 100.0
#: Times a singular sample is drawn again (a map singular on much of the range, undefined
#: there or sinking a disk beyond a lean of ±π/2, keeps some: the file is asked for its
#: ranges, :func:`~.grid.check_finite_map`).
REDRAWS = 5

__all__ = ["MAX_CONDITION", "ParameterSet", "SpecialCase", "WIP_SPECIAL_CASES",
           "namespace_values", "parameter_sets", "random_states", "regular_states",
           "special_cases", "family", "massless_family", "uniform_family", "uniform_links", "replace"]
