r"""Closed forms of a wheeled model in a document's coordinates, rolling included.

:func:`wheeled_symbolic` builds the symbolic model of a :class:`~wheeled_dyn.models.WheeledModel`
(:func:`~.model.symbolic_model`) and transforms it to a coordinate set
(:func:`~.transform.transform`) with :math:`\dot q = S(q)\,\nu`:

- rolling eliminated (``quasi`` sets): the contact point of each wheel (radius :math:`\rho`,
  centre velocity :math:`v_c`, angular velocity :math:`\omega`, both in world axes) moves with
  :math:`v_c + \rho\, e_z \times \omega`; its world x and y rows form :math:`J_c(q)`. With
  :math:`T = \partial\nu/\partial v` from the set's ``velocity_map``, :math:`S` solves

  .. math::
     \begin{bmatrix} J_c' \\ T \end{bmatrix} S = \begin{bmatrix} 0 \\ \mathbb 1 \end{bmatrix},

  :math:`J_c'` a maximal set of independent rows of :math:`J_c` (two wheels on one axle have
  the same lateral row); when the velocities are fewer than the rolling motions (a document
  that leaves the heading out), the minimum-norm solution
  :math:`S = M^T(MM^T)^{-1}E`, which is what the pseudo-inverse of the numeric reduction
  gives. The solve is exact (fraction field of the parameters and of
  :math:`\sin, \cos` of the angles), each entry reduced modulo :math:`\sin^2 + \cos^2 = 1`;
  :math:`\dot S = \sum_k \partial S/\partial q_k\,\dot q_k` with :math:`\dot q = S\nu`;
- holonomic sets :math:`q = g(q_{doc})`: :math:`S = \partial g/\partial q_{doc}`,
  :math:`\dot S = \sum_k \partial S/\partial q_{doc,k}\,\dot q_{doc,k}`; with rolling kept as
  multipliers also :math:`G = J_c S`;

then every model coordinate is replaced by its ``configuration`` expression in the document's
positions. Symbols: the document's positions and velocities are ``Symbol(name, real=True)``
named as in the set (as the derivation parser makes them).

Parameters (``parameters=``):

- ``"physical"`` (models with a physical-parameter record: the WIP): Khalil's standard
  parameters of ``body`` and the wheels from
  :func:`~wheeled_dyn.models.wip_parameters.standard_parameters` of the real symbols
  ``m_S, m_C, d, I1, ...``, the armature ``I_a`` on both wheel joints, gravity ``g``, and the
  geometry as symbols: the axle at height ``R`` (the pitch joint's placement, also the wheel
  radius) and the wheels at :math:`z = \mp L` on the axle;
- ``"numbers"``: every number from the Pinocchio model (inertias, placements, armature,
  gravity, wheel radius);
- ``"standard"``: Khalil symbols ``M_<link>, MX_<link>, ..., ZZ_<link>`` (link frame = joint
  frame where a joint carries one link at its origin, else named after the joint) for every
  joint that carries mass; numbers for the rest.

:func:`true_expressions` gives the elements of the WIP's terms, labelled as the comparison
engine labels them, cached in memory and on disk.
"""

from __future__ import annotations

import hashlib
from collections.abc import Mapping, Sequence
from dataclasses import fields, replace
from typing import TYPE_CHECKING

import numpy as np
import pinocchio as pin
import sympy as sp
from sympy.polys.matrices import DomainMatrix

from ..coordinates.spec import CoordinateSet
from ..errors import ModelError, UnknownNameError
from ..models.wheeled_model import WheeledModel
from ..models.geometry import identifier
from .lengths import length_symbols, planar_translations, translations
from .exact import exact_length, exact_model
from ..disk_cache import load, store
from .cache import _code_digest, cache_dir, cached_symbolic_model, model_fingerprint
from .kinematics import exact_number
from .model import SymbolicModel
from .parameters import PARAMETER_NAMES, numeric_parameters
from .simplify import canonical_trig, simplify_expr
from .springs import spring_terms, with_springs
from .transform import ReducedSymbolic, time_derivative, transform

if TYPE_CHECKING:
    from .tree_wheeled import ReducedTree

#: Parameter modes of :func:`wheeled_symbolic`.
PARAMETER_MODES: tuple[str, ...] = ("physical", "numbers", "standard")
#: Seed of the random point at which independent constraint rows are chosen.
ROW_SEED: int = 7
#: Smallest singular value ratio for a constraint row to count as independent.
RANK_TOL: float = 1e-9
#: Largest distance between a model's joint placement and the symbolic one at its numbers.
PLACEMENT_TOL: float = 1e-12


# -- parameters ---------------------------------------------------------------------------
def physical_symbols() -> dict[str, sp.Symbol]:
    r"""``{name: Symbol(name, real=True)}`` for every field of
    :class:`~wheeled_dyn.models.wip_parameters.WipParameters` (``m_S, m_C, R, L, d, g, ...``)."""
    from ..models.wip_parameters import WipParameters
    return {f.name: sp.Symbol(f.name, real=True) for f in fields(WipParameters)}


#: LaTeX of the physical symbols (seed 001's notation).
PHYSICAL_LATEX: dict[str, str] = {
    "m_S": "m_S", "m_C": "m_C", "I1": "I_1", "I2": "I_2", "I3": "I_3", "Ixy": "I_{xy}",
    "Ixz": "I_{xz}", "Iyz": "I_{yz}", "Iw2": "I_{w2}", "Iw3": "I_{w3}", "d_x": "d_x",
    "d_z": "d_z", "I_a": "I_a"}


def physical_latex() -> dict[sp.Symbol, str]:
    """``{symbol: LaTeX}`` for :func:`~.printing.to_latex`'s ``names``."""
    P = physical_symbols()
    return {P[k]: v for k, v in PHYSICAL_LATEX.items() if k in P}


def _has_physical_record(wm: WheeledModel) -> bool:
    from ..models.registry import MODELS
    from ..models.wip_parameters import WipParameters
    entry = MODELS.get(wm.name)
    return entry is not None and entry.parameters is WipParameters


def _link_at_joint(wm: WheeledModel, link: str) -> int:
    """The joint of ``link``, checking that the link frame is the joint frame."""
    model = wm.model
    if not model.existFrame(link):
        raise UnknownNameError("link", link, [f.name for f in model.frames],
                               where=f"model {wm.name}")
    frame = model.frames[model.getFrameId(link)]
    if not frame.placement.isIdentity(PLACEMENT_TOL):
        raise ModelError(wm.name, link, "the link frame is not its joint frame: the physical "
                                        "parameters are given in the link frame")
    return frame.parentJoint


def _physical_setup(wm: WheeledModel) -> dict:
    r"""Arguments of :func:`~.model.symbolic_model` for the WIP in physical symbols."""
    from ..models.wip_parameters import standard_parameters
    if not _has_physical_record(wm):
        raise ModelError(wm.name, None, "no physical-parameter record: use parameters="
                                        "'numbers' or 'standard'")
    P = physical_symbols()
    std = standard_parameters(P)
    model = wm.model
    params: dict[int, list] = {j: [0] * 10 for j in range(1, model.njoints)}
    body = _link_at_joint(wm, "body")
    if body != wm.body_joint_id:
        raise ModelError(wm.name, "body", "the body link is not on the pitch joint")
    params[body] = [std["body"][k] for k in PARAMETER_NAMES]
    translations = {body: (0, 0, P["R"])}
    armature = [0] * model.nv
    for wheel, sign in zip(wm.wheels, (-1, 1)):
        j = _link_at_joint(wm, wheel.link)
        params[j] = [std[wheel.link][k] for k in PARAMETER_NAMES]
        translations[j] = (0, 0, sign * P["L"])
        armature[wheel.v_index] = P["I_a"]
    numbers = {P["R"]: wm.geometry["R"], P["L"]: wm.geometry["L"]}
    for j, t in translations.items():
        want = np.array([float(sp.sympify(x).xreplace(numbers)) for x in t])
        if np.abs(model.jointPlacements[j].translation - want).max() > PLACEMENT_TOL:
            raise ModelError(wm.name, model.names[j], "the joint placement is not the WIP's "
                             f"(0, 0, R) / (0, 0, -+L): {model.jointPlacements[j].translation}")
    return dict(params=params, gravity=P["g"], translations=translations, armature=armature,
                radius=[P["R"]] * len(wm.wheels), geometry={"R": P["R"], "L": P["L"]})


def _standard_names(wm: WheeledModel) -> dict[int, str]:
    r"""The name of each joint body's standard parameters (in the joint frame): the link that
    carries the rigid body (:mod:`~wheeled_dyn.models.link_parameters`) when its frame is the
    joint frame, so that ``XX_link`` is what a derivation's ``XX(link)`` names; else the
    joint's name (a merged link such as ``base_footprint`` never names the whole body)."""
    from ..models.link_parameters import rigid_bodies
    model = wm.model
    names = {j: model.names[j] for j in range(1, model.njoints)}
    for body in rigid_bodies(wm):
        frame = model.frames[model.getFrameId(body.carrier, pin.FrameType.BODY)]
        if frame.placement.isIdentity(PLACEMENT_TOL):
            names[frame.parentJoint] = body.carrier
    return names


def _numeric_setup(wm: WheeledModel, mode: str, axle: bool = False) -> dict:
    r"""Standard or numeric parameters; with ``mode == "standard"`` the drawn lengths as
    symbols (a planar wheeled model's ``R`` and ``L`` only with ``axle``: the tree's closed
    forms, where the rolling rows stay polynomial in them)."""
    model = wm.model
    nums = numeric_parameters(model)
    names = _standard_names(wm)
    params: dict[int, list] = {}
    for j, pi in nums.items():
        if mode == "standard" and any(abs(x) > 0 for x in pi):
            params[j] = [sp.Symbol(f"{k}_{names[j]}", real=True) for k in PARAMETER_NAMES]
        else:
            params[j] = [exact_number(x) for x in pi]
    geometry = {k: exact_length(v) for k, v in wm.named_lengths().items()}
    moved, radius = None, [exact_length(w.radius) for w in wm.wheels]
    planar = axle and bool(wm.wheels) and wm.spec.base == "planar"
    if mode == "standard" and wm.lengths is not None and (planar or not wm.wheels):
        lengths = length_symbols(wm)
        geometry.update({identifier(k): v for k, v in lengths.items()})
        geometry.update({k: v for k, v in lengths.items() if k in wm.geometry})
        if planar:
            moved = planar_translations(wm, lengths)
            radius = [lengths.get("R", r) for r in radius]
        else:
            moved = translations(wm, lengths)
    return dict(params=params, gravity=None, translations=moved, armature=None,
                radius=radius, geometry=geometry)


def _setup(wm: WheeledModel, parameters: str, axle: bool = False) -> dict:
    if parameters not in PARAMETER_MODES:
        raise UnknownNameError("parameter mode", parameters, PARAMETER_MODES)
    if parameters == "physical":
        return _physical_setup(wm)
    return _numeric_setup(wm, parameters, axle)


# -- rolling ------------------------------------------------------------------------------
def contact_rows(sym: SymbolicModel, wm: WheeledModel, radius: Sequence[sp.Expr]) -> sp.Matrix:
    r"""The symbolic :math:`J_c(q)` (2·wheels × nv): per wheel the world x and y components of
    :math:`v_c + \rho\,e_z\times\omega` (:math:`v_c`, :math:`\omega` of the wheel joint frame
    in world axes), differentiated by the velocities; canonical trigonometric form."""
    if getattr(wm, "contact", None) is not None:
        raise ModelError(wm.name, None, "the closed forms cover wheels, not a rolling ball")
    kin = {k.index: k for k in sym.kinematics}
    rows = []
    for wheel, rho in zip(wm.wheels, radius):
        k = kin[wheel.joint_id]
        v, w = k.R * k.v, k.R * k.omega
        rows += [v[0] - rho * w[1], v[1] + rho * w[0]]
    if not rows:
        return sp.zeros(0, sym.n)
    return sp.Matrix(rows).jacobian(list(sym.qd)).applyfunc(canonical_trig)


def _angles(exprs: Sequence[sp.Expr]) -> dict[sp.Expr, sp.Dummy]:
    fwd = {}
    for e in exprs:
        for a in sp.sympify(e).atoms(sp.sin, sp.cos):
            fwd.setdefault(a, sp.Dummy(f"{type(a).__name__}"))
    return fwd


def _reduce_fraction(e: sp.Expr) -> sp.Expr:
    """A rational function of sines and cosines with numerator and denominator each in
    canonical form (exact: both are reduced modulo :math:`\\sin^2 + \\cos^2 = 1`)."""
    num, den = sp.fraction(sp.cancel(sp.together(e)))
    num, den = canonical_trig(num), canonical_trig(den)
    return sp.cancel(num / den) if not den.has(sp.sin, sp.cos) else num / den


#: Floats below this size in a matrix to invert are rounding noise of composed rotations
#: (a locked joint's 1e-16): taken as 0. Other floats become the rationals they print as, so
#: the elimination runs over exact numbers (over floats it is slow and loses digits).
FLOAT_NOISE = 1e-12


def _exact_numbers(M: sp.Matrix) -> sp.Matrix:
    r"""``M`` with its floats exact: noise (:data:`FLOAT_NOISE`) as 0, others as rationals."""
    floats = M.atoms(sp.Float)
    if not floats:
        return M
    return M.xreplace({f: sp.Integer(0) if abs(f) < FLOAT_NOISE
                       else sp.nsimplify(f, rational=True) for f in floats})


def trig_solve(M: sp.Matrix, E: sp.Matrix) -> sp.Matrix:
    r""":math:`X = M^{-1}E` for a square ``M`` whose entries are polynomials in parameters and
    in sines and cosines: exact Gaussian elimination over the fraction field with
    :math:`\sin x, \cos x` as indeterminates, then each entry reduced (:func:`_reduce_fraction`)."""
    M, E = _exact_numbers(M), _exact_numbers(E)
    fwd = _angles(list(M) + list(E))
    back = {d: a for a, d in fwd.items()}
    Md, Ed = M.xreplace(fwd), E.xreplace(fwd)
    dm = DomainMatrix.from_Matrix(Md).to_field()
    de = DomainMatrix.from_Matrix(Ed)
    K = dm.domain.unify(de.domain)
    X = dm.convert_to(K).lu_solve(de.convert_to(K)).to_Matrix()
    return X.applyfunc(lambda e: _reduce_fraction(sp.sympify(e).xreplace(back)))


def _random_values(exprs: Sequence[sp.Expr], rng: np.random.Generator) -> dict:
    free = set().union(*[sp.sympify(e).free_symbols for e in exprs])
    return {s: float(rng.uniform(0.3, 1.3)) for s in free}


def independent_rows(J: sp.Matrix, T: sp.Matrix) -> list[int]:
    r"""Indices of rows of ``J`` that, with all of ``T``, are linearly independent at a random
    point (a generic configuration and parameter set)."""
    rng = np.random.default_rng(ROW_SEED)
    vals = _random_values(list(J) + list(T), rng)
    f = lambda M: np.array(M.xreplace(vals).evalf(), dtype=float).reshape(M.shape)  # noqa: E731
    Jn, chosen = f(J), f(T)
    keep = []
    for i in range(Jn.shape[0]):
        trial = np.vstack([chosen, Jn[i]])
        if trial.shape[0] > trial.shape[1]:
            break
        s = np.linalg.svd(trial, compute_uv=False)
        if s[-1] > RANK_TOL * s[0]:
            chosen, keep = trial, keep + [i]
    return keep


# -- coordinate sets ----------------------------------------------------------------------
def _velocity_jacobian(cs: CoordinateSet, sym: SymbolicModel, geometry: Mapping) -> sp.Matrix:
    from ..coordinates.spec import model_symbols
    mq, mv = model_symbols([str(s) for s in sym.q])
    rename = dict(zip(mq, sym.q)) | dict(zip(mv, sym.qd)) | _geometry_subs(cs, geometry)
    nu = sp.Matrix([cs.velocity_map[v] for v in cs.velocities]).xreplace(rename)
    return nu.jacobian(list(sym.qd))


def _geometry_subs(cs: CoordinateSet, geometry: Mapping) -> dict:
    return {sp.Symbol(p, real=True): sp.sympify(geometry[p]) for p in cs.parameters
            if p in geometry}


def wheeled_symbolic(wm: WheeledModel, cs: CoordinateSet, parameters: str = "physical",
                     simplify: bool = True, model_coordinates: bool = False) -> ReducedSymbolic:
    r"""The terms :math:`A_\nu, C_\nu, Q_\nu, h_\nu, B_\nu` (and :math:`G = J_cS` when rolling
    is kept with multipliers) of ``wm`` in the coordinate set ``cs``, in closed form.

    ``parameters``: ``"physical"`` (the WIP's physical symbols, geometry ``R, L`` symbolic),
    ``"numbers"`` or ``"standard"`` (see the module docstring). The model part is read from
    the disk cache (:func:`~.cache.cached_symbolic_model`). ``q`` and ``nu`` of the result are
    the set's positions and velocities as real symbols; with ``model_coordinates`` (quasi sets
    only) the terms and :math:`S` stay functions of the model's coordinates (``q`` = the
    model's coordinate symbols), as a simulation of the full configuration needs them.
    ``simplify``: polish for reading (off: canonical forms only, faster).
    Raises :class:`ModelError` for a model the mode does not fit or a holonomic set with
    ``model_coordinates``; :class:`UnknownNameError` for an unknown mode.
    """
    return symbolic_parts(wm, cs, parameters, simplify, model_coordinates)[1]


def velocity_basis(wm: WheeledModel, cs: CoordinateSet, setup: Mapping, q: Sequence[sp.Symbol],
                   qd: Sequence[sp.Symbol], J: sp.Matrix | None
                   ) -> tuple[sp.Matrix, sp.Matrix, dict, tuple, tuple]:
    r"""``(S, Sdot, config, pos, nu)`` of the coordinate set ``cs`` (module docstring) for
    model coordinates ``q`` and velocities ``qd``: :math:`\dot q = S\nu`, ``Sdot`` in ``q, qd``;
    ``config`` maps each model coordinate to its expression in the document positions ``pos``
    (dummies, as ``nu``); ``J``: the contact rows (:func:`contact_rows`) or None."""
    sym = type("_Coordinates", (), {"q": tuple(q), "qd": tuple(qd)})
    geo = _geometry_subs(cs, setup["geometry"])
    pos = tuple(sp.Dummy(p) for p in cs.positions)
    nu = tuple(sp.Dummy(v) for v in cs.velocities)
    doc = dict(zip(cs.position_symbols(), pos))
    config = {sym.q[i]: sp.sympify(cs.configuration.get(name, 0)).xreplace(doc).xreplace(geo)
              for i, name in enumerate(wm.coordinate_names)}
    n, m = len(sym.q), len(nu)
    if cs.kind == "holonomic":
        g = sp.Matrix([config[qi] for qi in sym.q])
        S = g.jacobian(list(pos))
        Sdot = time_derivative(S, pos, nu)
    else:
        T = _velocity_jacobian(cs, sym, setup["geometry"])
        if cs.rolling == "eliminate":
            rows = independent_rows(J, T)
            M = J.extract(rows, list(range(n))).col_join(T)
            E = sp.zeros(len(rows), m).col_join(sp.eye(m))
            if M.shape[0] == n:
                S = trig_solve(M, E)
            else:  # fewer velocities than rolling motions: the minimum-norm S, as numerically
                S = M.T * trig_solve((M * M.T).applyfunc(canonical_trig), E)
                S = S.applyfunc(_reduce_fraction)
        else:
            if T.shape[0] != n:
                raise ModelError(wm.name, cs.name, f"{T.shape[0]} velocities for {n} model "
                                 "velocities without rolling elimination")
            S = trig_solve(T, sp.eye(n))
        Sdot = time_derivative(S, sym.q, sym.qd)
    return S, Sdot, config, pos, nu


def symbolic_parts(wm: WheeledModel, cs: CoordinateSet, parameters: str = "physical",
                   simplify: bool = True, model_coordinates: bool = False
                   ) -> tuple[SymbolicModel, ReducedSymbolic]:
    r"""(the model's :class:`~.model.SymbolicModel`, :func:`wheeled_symbolic`'s result)."""
    setup = _setup(wm, parameters)
    sym = cached_symbolic_model(exact_model(wm.model), setup["params"], wm.coordinate_names,
                                setup["gravity"], simplify, translations=setup["translations"],
                                armature=setup["armature"], real=True)
    sym = with_springs(sym, spring_terms(wm, parameters))
    if model_coordinates and cs.kind != "quasi":
        raise ModelError(wm.name, cs.name, "terms in model coordinates need a quasi-velocity "
                                           "set (kind = 'quasi')")
    J = contact_rows(sym, wm, setup["radius"]) if cs.rolling != "none" else None
    S, Sdot, config, pos, nu = velocity_basis(wm, cs, setup, sym.q, sym.qd, J)
    B = sp.Matrix(wm.input_matrix().astype(int)) if wm.input_matrix().size else None
    if model_coordinates:
        subs, coords = {}, sym.q
    else:
        subs, coords = config, pos
    red = transform(sym, S, Sdot, nu, subs=subs, B=B, coordinates=coords, simplify=simplify)
    G, parameters_ = None, red.parameters
    if cs.rolling == "multipliers" and J is not None and J.shape[0]:
        Gx = J.xreplace(subs) * red.S
        G = Gx.applyfunc(lambda e: simplify_expr(sp.expand(e), red.parameters, trig=simplify))
        extra = G.free_symbols - set(parameters_) - set(coords) - set(nu)
        parameters_ += tuple(sorted(extra, key=sp.default_sort_key))
    back = dict(zip(pos, cs.position_symbols())) | dict(zip(nu, cs.velocity_symbols()))

    def ren(M):
        return None if M is None else M.xreplace(back)

    red = replace(red, q=tuple(back.get(p, p) for p in red.q), nu=cs.velocity_symbols(),
                  parameters=parameters_,
                  params={j: tuple(sp.sympify(x).xreplace(back) for x in pi)
                          for j, pi in red.params.items()},
                  A=ren(red.A), C=ren(red.C), Q=ren(red.Q), h=ren(red.h), B=ren(red.B),
                  S=ren(red.S), Sdot=ren(red.Sdot), G=ren(G))
    return sym, red


# -- elements for the reports -------------------------------------------------------------
def velocity_products(h: sp.Expr, nu: Sequence[sp.Symbol]) -> dict[tuple[int, int], sp.Expr]:
    r"""``{(j, k): coefficient of}`` :math:`\nu_j\nu_k` (``j <= k``; for ``j < k`` the whole
    coefficient of the product) in a quadratic form ``h`` of the velocities ``nu``."""
    out: dict[tuple[int, int], sp.Expr] = {}
    expanded = sp.expand(h)
    if expanded == 0:
        return out
    poly = sp.Poly(expanded, *nu)
    for mon, coef in poly.terms():
        idx = [i for i, e in enumerate(mon) for _ in range(e)]
        if len(idx) != 2:
            raise ModelError("<symbolic>", None, f"h is not quadratic in {nu}: {mon}")
        out[(idx[0], idx[1])] = out.get((idx[0], idx[1]), 0) + coef
    return out


def element_expressions(red: ReducedSymbolic | ReducedTree, inputs: Sequence[str] = ()) -> dict[str, sp.Expr]:
    r"""The elements of ``red`` labelled as the comparison engine labels them (1-based):
    ``"A[i,j]"``, ``"C[i,j]"``, ``"Q[i]"``, ``"B[i,j]"``, ``"G[i,j]"`` and ``"h[i]:a*b"`` (the
    coefficient of the velocity product ``a*b``, ``a`` not after ``b`` in the velocity
    order; products with a zero coefficient are listed as 0). Each is collected by parameter
    (:func:`~.simplify.simplify_expr`)."""
    nu, m = red.nu, len(red.nu)
    pars = tuple(red.parameters)
    out: dict[str, sp.Expr] = {}
    for key in ("A", "C", "B", "G"):
        M = getattr(red, key, None)
        if M is None:
            continue
        for i in range(M.shape[0]):
            for j in range(M.shape[1]):
                out[f"{key}[{i + 1},{j + 1}]"] = M[i, j]
    for i in range(m):
        out[f"Q[{i + 1}]"] = red.Q[i]
    for i in range(m):
        coeffs = velocity_products(red.h[i], nu)
        for j in range(m):
            for k in range(j, m):
                c = coeffs.get((j, k), sp.Integer(0))
                out[f"h[{i + 1}]:{nu[j]}*{nu[k]}"] = simplify_expr(c, pars) if c != 0 else c
    return out


def coordinate_set_key(cs: CoordinateSet) -> str:
    """A text that changes with anything of ``cs`` the closed forms depend on (not its name or
    description)."""
    def text(e):
        return sp.srepr(sp.sympify(e))
    parts = [cs.kind, cs.rolling, repr(cs.positions), repr(cs.velocities), repr(cs.parameters),
             repr(sorted((k, text(v)) for k, v in cs.configuration.items())),
             repr(None if cs.velocity_map is None else
                  sorted((k, text(v)) for k, v in cs.velocity_map.items()))]
    return "\x00".join(parts)


_MEMORY: dict[str, dict[str, sp.Expr] | None] = {}
#: Models without a physical record get closed forms in standard parameters for the reports
#: when they have a fixed base and at most this many joints (the benchmark bodies of seed 000
#: take a tenth of a second; a free body in body rates takes minutes).
STANDARD_MAX_DOF = 4


def _true_key(model: str, cs: CoordinateSet, wm: WheeledModel) -> str:
    h = hashlib.sha256()
    for part in ("true_expressions", model, sp.__version__, _code_digest(),
                 model_fingerprint(wm.model, coordinate_names=wm.coordinate_names),
                 repr(wm.geometry), repr(wm.input_names), repr(wm.springs),
                 coordinate_set_key(cs)):
        h.update(str(part).encode())
        h.update(b"\x00")
    return h.hexdigest()


def true_expressions(model: str, cs: CoordinateSet, refresh: bool = False
                     ) -> dict[str, sp.Expr] | None:
    r"""The true elements of model ``model`` (a registry name) in the coordinate set ``cs``,
    in the model's physical parameters (:func:`wheeled_symbolic` with ``"physical"``) or, for a
    model without a physical-parameter record, in Khalil's standard parameters of its links
    (``"standard"``: symbols ``XX_link`` ..., geometry as exact numbers), labelled as
    :func:`element_expressions` does; ``"B[i,j]"`` in the model's inputs. None where the
    symbolic engine does not fit the model.

    Cached in memory and on disk (:func:`~.cache.cache_dir`, ``true-<key>.pickle``), keyed by
    the model, the content of ``cs`` and the code version; ``refresh`` re-derives.
    """
    from ..models.registry import load_model, model_entry
    from .expanded import expanded_tree
    model_entry(model)  # unknown names raise here
    wm = load_model(model)
    mode = "physical" if _has_physical_record(wm) else "standard"
    tree = mode == "standard" and (wm.spec.base != "fixed" or wm.model.nv > STANDARD_MAX_DOF)
    key = _true_key(model, cs, wm) + mode
    if key in _MEMORY and not refresh:
        return _MEMORY[key]
    path = cache_dir() / f"true-{key}.pickle"
    if not refresh and (found := load(path, dict)) is not None:
        _MEMORY[key] = found
        return found
    try:            # free bodies and contacts: minutes in one piece, seconds as a tree
        red = expanded_tree(wm, cs) if tree else wheeled_symbolic(wm, cs, mode)
    except ModelError:                        # a model the standard mode does not fit
        red = None
    if red is None:
        _MEMORY[key] = None
        return None
    out = element_expressions(red, wm.input_names)
    store(path, out)
    _MEMORY[key] = out
    return out
