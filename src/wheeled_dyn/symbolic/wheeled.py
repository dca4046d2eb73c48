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
  joint that carries mass, gravity's magnitude ``g``, and the lengths the parameter sets draw
  as symbols where :func:`lengths_are_symbols` says so; numbers for the rest.

:func:`true_expressions` gives the elements of the WIP's terms, labelled as the comparison
engine labels them, cached in memory and on disk.

The parts: :mod:`.parameter_modes` (what each mode gives the symbolic model),
:mod:`.basis` (:math:`S`, :math:`\dot S`, the contact rows), :mod:`.trig_solve` (the exact
solve), :mod:`.elements` (the labelled elements).
"""

from __future__ import annotations

import hashlib
from pathlib import Path
from dataclasses import replace

import sympy as sp

from ..coordinates.spec import CoordinateSet
from ..disk_cache import load, store
from ..errors import ModelError
from ..models.wheeled_model import WheeledModel
from .basis import RANK_TOL, ROW_SEED, contact_rows, independent_rows, velocity_basis
from .cache import _code_digest, cache_dir, cached_symbolic_model, model_fingerprint
from .elements import coordinate_set_key, element_expressions, velocity_products
from .exact import exact_model
from .lengths import axle_symbols
from .model import SymbolicModel
from .parameter_modes import (PARAMETER_MODES, PHYSICAL_LATEX, PLACEMENT_TOL,
                              _numeric_setup, has_physical_record, parameter_setup,
                              physical_latex, physical_symbols)
from .simplify import simplify_expr
from .springs import spring_terms, with_springs
from .transform import ReducedSymbolic, transform
from .trig_solve import FLOAT_NOISE, trig_solve

#: Names importable from here, where every part of the closed forms lived before it had a
#: module of its own.
__all__ = ["FLOAT_NOISE", "lengths_are_symbols", "PARAMETER_MODES", "PHYSICAL_LATEX", "PLACEMENT_TOL", "RANK_TOL",
           "ROW_SEED", "STANDARD_MAX_DOF", "_numeric_setup",
           "contact_rows", "coordinate_set_key", "element_expressions", "independent_rows",
           "physical_latex", "physical_symbols", "symbolic_parts", "trig_solve",
           "true_expressions", "velocity_basis", "velocity_products", "wheeled_symbolic"]


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


def symbolic_parts(wm: WheeledModel, cs: CoordinateSet, parameters: str = "physical",
                   simplify: bool = True, model_coordinates: bool = False
                   ) -> tuple[SymbolicModel, ReducedSymbolic]:
    r"""(the model's :class:`~.model.SymbolicModel`, :func:`wheeled_symbolic`'s result)."""
    setup = parameter_setup(wm, parameters)
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


_MEMORY: dict[str, dict[str, sp.Expr] | None] = {}
#: Models without a physical record get closed forms in standard parameters from the
#: Lagrangian when they have a fixed base and at most this many joints (the benchmark bodies
#: of seed 000 take a tenth of a second); the others from the tree's forms written out
#: (:func:`~.expanded.expanded_tree`; a free body in body rates took minutes the other way).
STANDARD_MAX_DOF = 4


def _true_key(model: str, cs: CoordinateSet, wm: WheeledModel) -> str:
    r"""The key of ``model``'s closed forms in ``cs``: the code, the numeric model, and its
    lengths — which are drawn, which kept, how they are grouped (``wm.lengths`` and the code
    that names them as symbols, :mod:`~wheeled_dyn.models.geometry`), which joint each input
    drives and the whole model file's record: a model file whose ``[draw] fixed``,
    ``[geometry]`` or ``[joints] actuated`` changed gets closed forms of its own (its inputs
    swapped between two joints, the corrected equations read the old ones back)."""
    from ..models import geometry, geometry_constants
    h = hashlib.sha256()
    for part in ("true_expressions", model, sp.__version__, _code_digest(),
                 model_fingerprint(wm.model, coordinate_names=wm.coordinate_names),
                 repr(wm.geometry), repr(wm.lengths), repr(wm.input_names), repr(wm.springs),
                 repr(wm.input_matrix().tolist()), repr(wm.spec),
                 coordinate_set_key(cs), Path(geometry.__file__).read_text(),
                 Path(geometry_constants.__file__).read_text()):
        h.update(str(part).encode())
        h.update(b"\x00")
    return h.hexdigest()


def _tree(wm: WheeledModel, mode: str) -> bool:
    return mode == "standard" and (wm.spec.base != "fixed" or wm.model.nv > STANDARD_MAX_DOF)


def lengths_are_symbols(model: str) -> bool:
    r"""Whether :func:`true_expressions` of ``model`` writes every length the parameter sets
    draw as a symbol (the WIP's ``R, L``; a model without wheels; a planar wheeled model's
    ``R, L`` in the tree's forms). Where not, its closed forms hold at the URDF's lengths
    only: fit to print, not to be solved for a document's symbols or pasted back."""
    from ..models.registry import load_model
    wm = load_model(model)
    if has_physical_record(wm) or wm.lengths is None or not wm.wheels:
        return True
    return _tree(wm, "standard") and axle_symbols(wm)


def trig_polynomial_map(cs: CoordinateSet) -> bool:
    r"""Whether the configuration map of ``cs`` is a polynomial in its positions' sines and
    cosines (and in other symbols): the closed forms are derived for such maps only. A
    spherical pendulum's (θ, φ) through ``atan2`` and ``asin`` gave terms ``trigsimp`` did
    not finish in 11 minutes (with ``trigsimp`` given short expressions only, the forms took
    39 s, one run); its numbers are compared all the same."""
    from .trigpoly import NotPolynomial, TrigRing
    exprs = [sp.sympify(e) for e in cs.configuration.values()]
    try:
        TrigRing.from_exprs(exprs)
    except NotPolynomial:
        return False
    return True


def derivation_joints(wm: WheeledModel, mode: str) -> None:
    r"""Turn ``wm``'s joint frames rounded to right angles by the right angles they stand for,
    in place, as the comparisons draw them and a derivation takes them
    (:func:`~..models.conventions.right_angled_joints`), in Khalil's standard parameters
    (``mode`` ``"standard"``; a physical-parameter record is written for the model as it
    is). ``wm`` must be a copy of its own (:func:`~..models.registry.load_model` gives one)."""
    from ..models.conventions import RIGHT_ANGLE_TOL, base_joints, right_angled_joints
    from ..models.rounded_angles import unrounded_joints
    if mode == "standard":
        right_angled_joints(wm.model, base_joints(wm),
                            unrounded_joints(wm.spec.urdf, RIGHT_ANGLE_TOL))


def true_expressions(model: str, cs: CoordinateSet, refresh: bool = False
                     ) -> dict[str, sp.Expr] | None:
    r"""The true elements of model ``model`` (a registry name) in the coordinate set ``cs``,
    in the model's physical parameters (:func:`wheeled_symbolic` with ``"physical"``) or, for a
    model without a physical-parameter record, in Khalil's standard parameters of its links
    (``"standard"``: symbols ``XX_link`` ..., ``g``, the drawn lengths as symbols where
:func:`lengths_are_symbols`, other geometry as exact numbers), labelled as
    :func:`element_expressions` does; ``"B[i,j]"`` in the model's inputs. None where the
    symbolic engine does not fit the model.

    Cached in memory and on disk (:func:`~.cache.cache_dir`, ``true-<key>.pickle``), keyed by
    the model, the content of ``cs`` and the code version; ``refresh`` re-derives.
    """
    from ..models.registry import load_model, model_entry
    from .expanded import expanded_tree
    model_entry(model)  # unknown names raise here
    wm = load_model(model)                               # a copy: its joints may be turned
    mode = "physical" if has_physical_record(wm) else "standard"
    derivation_joints(wm, mode)
    tree = _tree(wm, mode)
    key = _true_key(model, cs, wm) + mode
    if key in _MEMORY and not refresh:
        return _MEMORY[key]
    path = cache_dir() / f"true-{key}.pickle"
    if not refresh and (found := load(path, dict)) is not None:
        _MEMORY[key] = found
        return found
    if not trig_polynomial_map(cs):
        _MEMORY[key] = None
        return None
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
