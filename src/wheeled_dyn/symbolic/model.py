r"""Closed-form equations of motion of a Pinocchio tree of 1-DoF joints.

With the kinematics of :mod:`.kinematics` and the standard parameters of :mod:`.parameters`,

.. math::
   E = \sum_j E_j + \tfrac12 \sum_i \mathrm{armature}_i\,\dot q_i^2, \qquad
   U = \sum_j -g^T (M_j\,{}^0p_j + {}^0R_j\, MS_j),

and (seed 001, eqs. (21)–(24))

.. math::
   A = \frac{\partial^2 E}{\partial \dot q^2}
     = \sum_j J_j^T \mathcal{I}_j J_j + \mathrm{diag}(\mathrm{armature}), \qquad
   Q = \frac{\partial U}{\partial q},

   c_{i,jk} = \tfrac12\left(\frac{\partial A_{ij}}{\partial q_k}
     + \frac{\partial A_{ik}}{\partial q_j} - \frac{\partial A_{jk}}{\partial q_i}\right),
   \qquad C_{ij} = \sum_k c_{i,jk}\,\dot q_k, \qquad h = C\dot q,

so that :math:`A\ddot q + C\dot q + Q = \tau` (Pinocchio's ``rnea``). Kinematics, energies and
all derivatives are computed on elements of one :class:`~.trigpoly.TrigRing`
(:func:`~.kinematics.kinematics_in_ring`, :func:`~.lagrange.lagrange_terms`): exact, canonical
modulo :math:`\sin^2+\cos^2=1`, and fast; SymPy expressions are made only at the end.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import pinocchio as pin
import sympy as sp

from ..errors import ModelError
from .exact import exact_length, exact_translation
from .kinematics import JointKinematics, exact_matrix, joint_kinematics, \
    kinematics_in_ring
from .lagrange import lagrange_terms
from .parameters import kinetic_energy_body, potential_energy_body, resolve_parameters
from .simplify import collect_terms, simplify_matrix


@dataclass(frozen=True, eq=False)
class SymbolicModel:
    r"""Closed forms of a model's equations of motion :math:`A\ddot q + C\dot q + Q = \tau`.

    ``q``, ``qd``: coordinate and velocity symbols (velocity index order); ``params``: the ten
    standard parameters per joint index; ``parameters``: every other free symbol, inertial ones
    first in joint order, then the rest (e.g. ``g``) by name; ``kinematics``: per-joint
    placements and velocities; ``gravity``: the 3-vector :math:`g` used in :math:`U`.
    ``A``, ``Q``, ``h``: polished for reading when ``simplified``; ``A_canonical``,
    ``Adot``, ``christoffel_symbols``: canonical trigonometric form
    (:func:`~.simplify.canonical_trig`), collected by parameter.
    """

    q: tuple[sp.Symbol, ...]
    qd: tuple[sp.Symbol, ...]
    joint_names: tuple[str, ...]
    params: Mapping[int, tuple[sp.Expr, ...]]
    parameters: tuple[sp.Symbol, ...]
    gravity: sp.Matrix
    kinematics: tuple[JointKinematics, ...]
    A: sp.Matrix
    Q: sp.Matrix
    h_vector: sp.Matrix
    A_canonical: sp.Matrix
    Adot: sp.Matrix
    christoffel_symbols: tuple[tuple[tuple[sp.Expr, ...], ...], ...]
    kinetic_energy: sp.Expr
    potential_energy: sp.Expr
    simplified: bool = True

    @property
    def n(self) -> int:
        """Number of coordinates."""
        return len(self.q)

    @property
    def velocities(self) -> tuple[sp.Symbol, ...]:
        """Same as ``qd`` (the name shared with :class:`~.transform.ReducedSymbolic`)."""
        return self.qd

    def christoffel(self) -> tuple[tuple[tuple[sp.Expr, ...], ...], ...]:
        r"""``c[i][j][k]`` :math:`= c_{i,jk} = \tfrac12(\partial_k A_{ij} + \partial_j A_{ik}
        - \partial_i A_{jk})`; symmetric in ``j, k``."""
        return self.christoffel_symbols

    def C(self, qdot: Sequence[sp.Expr] | None = None, simplify: bool = False) -> sp.Matrix:
        r"""The Christoffel-consistent :math:`C_{ij} = \sum_k c_{i,jk}\,\dot q_k`, with
        :math:`\dot q` = ``qdot`` (default: the symbols ``qd``); ``simplify``: collected by
        parameter and velocity and polished for reading (:func:`~.simplify.simplify_matrix`)."""
        qdot = self.qd if qdot is None else tuple(qdot)
        c, n = self.christoffel_symbols, self.n
        C = sp.Matrix(n, n, lambda i, j: sp.Add(*[c[i][j][k] * qdot[k] for k in range(n)]))
        if simplify:
            C = simplify_matrix(C, parameters=self.parameters + tuple(
                s for s in qdot if isinstance(s, sp.Symbol)))
        return C

    def h(self, qdot: Sequence[sp.Expr] | None = None) -> sp.Matrix:
        r"""Coriolis and centrifugal vector :math:`h = C(q,\dot q)\,\dot q` (quadratic in
        :math:`\dot q`; ``qdot`` substitutes the velocity symbols)."""
        if qdot is None:
            return self.h_vector
        return self.h_vector.xreplace(dict(zip(self.qd, qdot)))

    def terms(self) -> dict[str, sp.Matrix]:
        """``{"A": A, "C": C, "Q": Q, "h": h}`` (the matrices a derivation is compared on)."""
        return {"A": self.A, "C": self.C(), "Q": self.Q, "h": self.h_vector}


def _gravity(model: pin.Model, gravity) -> sp.Matrix:
    where = model.name or "<pinocchio>"
    if gravity is None:
        return exact_translation(model.gravity.linear)
    if isinstance(gravity, (str, int, float, sp.Expr)):
        mag = sp.Symbol(gravity) if isinstance(gravity, str) else sp.sympify(gravity)
        g0 = np.asarray(model.gravity.linear, dtype=float)
        norm = float(np.linalg.norm(g0))
        if norm == 0.0:
            raise ModelError(where, None,
                             "a gravity magnitude needs a nonzero model.gravity direction")
        return exact_matrix(g0 / norm) * mag
    g = sp.Matrix(gravity)
    if g.shape not in ((3, 1), (1, 3)):
        raise ModelError(where, None,
                         f"gravity must be a 3-vector or a magnitude, got shape {g.shape}")
    return g.reshape(3, 1)


def symbolic_model(model: pin.Model, params: Mapping[int, Sequence] | None = None,
                   coordinate_names: Sequence[str] | None = None, gravity=None,
                   simplify: bool = True, translations: Mapping | None = None,
                   armature: Sequence | None = None, real: bool = False) -> SymbolicModel:
    r"""Symbolic :math:`A, Q, c_{i,jk}, C, h, \dot A, E, U` of ``model``.

    ``params``: ``{joint index or name: 10 numbers or expressions}`` in Pinocchio's
    ``toDynamicParameters()`` order (default: symbols ``M_<joint>, MX_<joint>, ...``; use
    :func:`~.parameters.numeric_parameters` for the model's own numbers). ``coordinate_names``:
    one name per coordinate (default: the joint names); velocities are ``"d" + name``.
    ``gravity``: None (``model.gravity``), a magnitude (symbol, name or number) along
    ``model.gravity``, or a 3-vector. ``translations``: ``{joint: (x, y, z)}`` expressions
    replacing joint placement translations (symbolic geometry,
    :func:`~.kinematics.kinematics_in_ring`); ``armature``: one expression per velocity
    (default ``model.armature``); ``real``: coordinate and velocity symbols with
    ``real=True``. All results are in canonical trigonometric form collected
    by parameter (and velocity); ``simplify`` also polishes ``A``, ``Q``, ``h`` and ``U`` for
    reading (:func:`~.simplify.polish_trig`).
    Raises :class:`ModelError` for joints other than 1-DoF revolute/prismatic.
    """
    names = tuple(model.names[j] for j in range(1, model.njoints))
    coords = [""] * model.nv
    for j in range(1, model.njoints):
        if model.joints[j].nv == 1:
            coords[model.joints[j].idx_v] = model.names[j]
    if coordinate_names is not None:
        coords = list(coordinate_names)
        if len(coords) != model.nv:
            raise ModelError(model.name or "<pinocchio>", None,
                             f"{len(coords)} coordinate names for nv={model.nv}")
    q = tuple(sp.Symbol(c, real=True) if real else sp.Symbol(c) for c in coords)
    qd = tuple(sp.Symbol("d" + c, real=True) if real else sp.Symbol("d" + c) for c in coords)
    pis = resolve_parameters(model, params)
    g = _gravity(model, gravity)
    n = model.nv
    if armature is None:
        arm = [exact_length(a) for a in model.armature]
    else:
        arm = [sp.sympify(a) for a in armature]
        if len(arm) != n:
            raise ModelError(model.name or "<pinocchio>", None,
                             f"{len(arm)} armature values for nv={n}")
    flat_pi = [x for j in sorted(pis) for x in pis[j]]
    inertial = [s for x in flat_pi for s in sorted(x.free_symbols, key=sp.default_sort_key)]
    rk = kinematics_in_ring(model, q, qd, extra_exprs=list(g) + arm + flat_pi,
                            extra_symbols=tuple(dict.fromkeys(inertial)),
                            translations=translations)
    ring = rk.ring
    gp, armp, pip = rk.extra[:3], rk.extra[3:3 + n], rk.extra[3 + n:]
    pi_of = {j: pip[10 * i:10 * (i + 1)] for i, j in enumerate(sorted(pis))}

    seen: dict[sp.Symbol, None] = dict.fromkeys(inertial)
    others = {s for g_ in ring.symbols() for s in g_.free_symbols}
    for s in sorted(others - set(q) - set(qd) - set(seen), key=sp.default_sort_key):
        seen.setdefault(s, None)
    parameters = tuple(seen)

    E = ring.ring.zero
    U = ring.ring.zero
    for j, f in rk.frames.items():
        E += kinetic_energy_body(pi_of[j], f["v"], f["omega"])
        U += potential_energy_body(pi_of[j], f["R"], f["p"], gp)
    for i in range(n):
        E += armp[i] * ring.gen(qd[i]) ** 2 / 2
    t = lagrange_terms(ring, E, U, q, qd)

    by_velocity = parameters + qd
    memo: dict = {}

    def expr(p, polish=False):
        key = (id(p), polish)
        if key not in memo:
            memo[key] = (p, collect_terms(ring, p, by_velocity, trig=polish))
        return memo[key][1]

    def matrix(m, polish=False):
        out = sp.zeros(n, n)
        for a in range(n):
            for b in range(a, n):
                out[a, b] = expr(m[a][b], polish)
                out[b, a] = out[a, b] if m[b][a] is m[a][b] else expr(m[b][a], polish)
        return out

    A_can = matrix(t.A)
    christ = tuple(tuple(tuple(expr(t.c[i][j][k]) for k in range(n)) for j in range(n))
                   for i in range(n))
    return SymbolicModel(
        q=q, qd=qd, joint_names=names, params=pis, parameters=parameters, gravity=g,
        kinematics=joint_kinematics(model, rk),
        A=matrix(t.A, simplify) if simplify else A_can,
        Q=sp.Matrix([expr(p, simplify) for p in t.Q]),
        h_vector=sp.Matrix([expr(p, simplify) for p in t.h]),
        A_canonical=A_can, Adot=matrix(t.Adot), christoffel_symbols=christ,
        kinetic_energy=expr(t.E), potential_energy=expr(t.U, simplify), simplified=simplify)
