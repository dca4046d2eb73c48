r"""The velocity basis :math:`\dot q = S(q)\,\nu` of a coordinate set, rolling included.

- rolling eliminated (``quasi`` sets): the contact point of each wheel (radius :math:`\rho`,
  centre velocity :math:`v_c`, angular velocity :math:`\omega`, both in world axes) moves with
  :math:`v_c + \rho\, e_z \times \omega`; its world x and y rows form :math:`J_c(q)`
  (:func:`contact_rows`). With :math:`T = \partial\nu/\partial v` from the set's
  ``velocity_map``, :math:`S` solves

  .. math::
     \begin{bmatrix} J_c' \\ T \end{bmatrix} S = \begin{bmatrix} 0 \\ \mathbb 1 \end{bmatrix},

  :math:`J_c'` a maximal set of independent rows of :math:`J_c` (:func:`independent_rows`:
  two wheels on one axle have the same lateral row); when the velocities are fewer than the
  rolling motions, the minimum-norm solution :math:`S = M^T(MM^T)^{-1}E`, which is what the
  pseudo-inverse of the numeric reduction gives. Solved exactly by
  :func:`~.trig_solve.trig_solve`; :math:`\dot S = \sum_k \partial S/\partial q_k\,\dot q_k`
  with :math:`\dot q = S\nu`;
- quasi-velocities with rolling kept: :math:`S = T^{-1}`;
- holonomic sets :math:`q = g(q_{doc})`: :math:`S = \partial g/\partial q_{doc}`,
  :math:`\dot S = \sum_k \partial S/\partial q_{doc,k}\,\dot q_{doc,k}`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
import sympy as sp

from ..coordinates.spec import CoordinateSet, CoordinateSpecError
from ..errors import ModelError
from ..models.wheeled_model import WheeledModel
from .model import SymbolicModel
from .simplify import canonical_trig
from .transform import time_derivative
from .trig_solve import reduce_fraction, trig_solve

#: Seed of the random point at which independent constraint rows are chosen.
ROW_SEED: int = 7
#: Smallest singular value ratio for a constraint row to count as independent.
RANK_TOL: float = 1e-9


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
    keep: list[int] = []
    for i in range(Jn.shape[0]):
        trial = np.vstack([chosen, Jn[i]])
        if trial.shape[0] > trial.shape[1]:
            break
        s = np.linalg.svd(trial, compute_uv=False)
        if s[-1] > RANK_TOL * s[0]:
            chosen, keep = trial, keep + [i]
    return keep


def _velocity_jacobian(cs: CoordinateSet, q: Sequence[sp.Symbol], qd: Sequence[sp.Symbol],
                       geometry: Mapping) -> sp.Matrix:
    r""":math:`T = \partial\nu/\partial v` of a quasi-velocity set in the model's coordinate
    and velocity symbols ``q, qd``."""
    from ..coordinates.spec import model_symbols
    if cs.velocity_map is None:
        raise CoordinateSpecError(cs.name, "velocity_map", "a quasi-velocity set needs one")
    mq, mv = model_symbols([str(s) for s in q])
    rename = dict(zip(mq, q)) | dict(zip(mv, qd)) | geometry_subs(cs, geometry)
    nu = sp.Matrix([cs.velocity_map[v] for v in cs.velocities]).xreplace(rename)
    return nu.jacobian(list(qd))


def geometry_subs(cs: CoordinateSet, geometry: Mapping) -> dict:
    r"""``{Symbol(p, real=True): value}`` for each parameter ``p`` of ``cs`` that ``geometry``
    names (a wheel radius, a half track, a drawn length)."""
    return {sp.Symbol(p, real=True): sp.sympify(geometry[p]) for p in cs.parameters
            if p in geometry}


#: How close a joint's rotation entry may come to 0, ±1/2, ±√2/2, ±√3/2 or ±1 without being
#: it: closer (but farther than :data:`ANGLE_NOISE`) it is an angle rounded from a right or
#: simple one (``rpy="-1.57 0 0"``: cos = 0.000796...; TIAGo's -1.57079632679: 4.9e-12, noise).
ROUNDED_ANGLE_TOL, ANGLE_NOISE = 1e-2, 1e-9
_SIMPLE = (0.0, 0.5, 2 ** -0.5, 3 ** 0.5 / 2, 1.0)


def rounded_rotation(wm: WheeledModel) -> tuple[str, float] | None:
    r"""The first joint or frame (name, rotation entry) the rolling constraints pass through
    — the joints from the root to each rolling link's joint, and that link's frame — whose
    rotation is near but not at a simple value (:data:`ROUNDED_ANGLE_TOL`); None when each
    is exact. A camera's optical frame turned by a rounded ``-1.5708`` is not on that path."""
    import pinocchio as pin

    model = wm.model
    links = [w.link for w in wm.wheels] + [w.link for w in wm.rolling_wheels]
    frames = [model.frames[model.getFrameId(link, pin.FrameType.BODY)] for link in links]
    chain = sorted({j for f in frames for j in model.supports[f.parentJoint] if j > 0})
    placements = [(model.names[j], model.jointPlacements[j]) for j in chain]
    placements += [(f.name, f.placement) for f in frames]
    for name, placement in placements:
        for x in np.abs(np.asarray(placement.rotation, dtype=float).ravel()):
            gap = min(abs(x - s) for s in _SIMPLE)
            if ANGLE_NOISE < gap < ROUNDED_ANGLE_TOL:
                return name, float(x)
    return None


def _held(wm: WheeledModel, cs: CoordinateSet, J: sp.Matrix, T: sp.Matrix,
          q: Sequence[sp.Symbol], config: Mapping, pos: Sequence[sp.Symbol]) -> list[int]:
    r"""The indices of the model coordinates ``cs`` holds (:mod:`~wheeled_dyn.constraints.held`,
    as the numeric reduction holds them), from :math:`[J_c; T]` at random parameters."""
    from ..constraints.held import held_coordinates
    M = J.col_join(T)
    drawn = _random_values([*M, *config.values()], np.random.default_rng(ROW_SEED))
    params = {k: sp.Float(v) for k, v in drawn.items()     # (SymPy numbers: xreplace gives
              if k not in set(q) | set(pos)}               # a lone symbol's value back)

    def stacked(q_doc):
        at = {p: sp.Float(float(x)) for p, x in zip(pos, q_doc)}
        sub = {qi: float(sp.sympify(config[qi]).xreplace(at).xreplace(params)) for qi in q}
        return np.array(M.xreplace(sub).xreplace(params).evalf(), dtype=float)
    names = held_coordinates(cs, wm.coordinate_names, stacked, [w.v_index for w in wm.wheels])
    return [wm.coordinate_names.index(c) for c in names]


def velocity_basis(wm: WheeledModel, cs: CoordinateSet, setup: Mapping, q: Sequence[sp.Symbol],
                   qd: Sequence[sp.Symbol], J: sp.Matrix | None
                   ) -> tuple[sp.Matrix, sp.Matrix, dict, tuple, tuple]:
    r"""``(S, Sdot, config, pos, nu)`` of the coordinate set ``cs`` (module docstring) for
    model coordinates ``q`` and velocities ``qd``: :math:`\dot q = S\nu`, ``Sdot`` in ``q, qd``;
    ``config`` maps each model coordinate to its expression in the document positions ``pos``
    (dummies, as ``nu``); ``J``: the contact rows (:func:`contact_rows`) or None."""
    q, qd = tuple(q), tuple(qd)
    geo = geometry_subs(cs, setup["geometry"])
    pos = tuple(sp.Dummy(p) for p in cs.positions)
    nu = tuple(sp.Dummy(v) for v in cs.velocities)
    doc = dict(zip(cs.position_symbols(), pos))
    config = {q[i]: sp.sympify(cs.configuration.get(name, 0)).xreplace(doc).xreplace(geo)
              for i, name in enumerate(wm.coordinate_names)}
    n, m = len(q), len(nu)
    if cs.kind == "holonomic":
        g = sp.Matrix([config[qi] for qi in q])
        S = g.jacobian(list(pos))
        Sdot = time_derivative(S, pos, nu)
    else:
        T = _velocity_jacobian(cs, q, qd, setup["geometry"])
        if cs.rolling == "eliminate":
            if J is None:
                raise ModelError(wm.name, cs.name, "rolling elimination needs the contact rows")
            if (rounded := rounded_rotation(wm)) is not None:   # the elimination would not end
                raise ModelError(wm.name, rounded[0], f"its rotation holds {rounded[1]:.15g}, "
                                 "near but not at a simple value: a rounded angle (rpy=\"-1.57 "
                                 "0 0\" for -pi/2; write -1.5707963267948966)? Closed forms "
                                 "of the rolling constraints need exact angles (the comparison, "
                                 "matrices and simulate use the numbers as written)")
            held = _held(wm, cs, J, T, q, config, pos)      # as the numbers hold them
            if held:
                T = T.col_join(sp.Matrix([[int(j == k) for j in range(n)] for k in held]))
            rows = independent_rows(J, T)
            M = J.extract(rows, list(range(n))).col_join(T)
            E = sp.zeros(len(rows), m).col_join(sp.eye(m)).col_join(sp.zeros(len(held), m))
            if M.shape[0] == n:
                S = trig_solve(M, E)
            else:  # fewer velocities than rolling motions: the minimum-norm S, as numerically
                S = M.T * trig_solve((M * M.T).applyfunc(canonical_trig), E)
                S = S.applyfunc(reduce_fraction)
        else:
            if T.shape[0] != n:
                raise ModelError(wm.name, cs.name, f"{T.shape[0]} velocities for {n} model "
                                 "velocities without rolling elimination")
            S = trig_solve(T, sp.eye(n))
        Sdot = time_derivative(S, q, qd)
    return S, Sdot, config, pos, nu
