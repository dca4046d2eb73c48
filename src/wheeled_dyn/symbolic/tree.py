r"""Closed forms of any tree of 1-DoF joints with intermediate variables (SYMORO's way).

Expanding :math:`A(q)` of a 15-joint robot into a sum of trigonometric monomials does not
finish; Khalil's customised symbolic Newton–Euler instead names every non-trivial intermediate
quantity and gets the dynamic model of a tree in time linear in the number of links. Here, with
joint :math:`j`, parent :math:`\lambda(j)`, placement :math:`{}^{\lambda}T_j(q_j) = (R_j, p_j)`
(exact geometry, :mod:`.exact`), motion subspace :math:`s_j = (a_j, 0)` (revolute) or
:math:`(0, a_j)` (prismatic) in frame :math:`j`, and the ten standard parameters
:math:`(m, h = m c, I_O)` of each link in its joint frame:

- **composite bodies** (leaves to root): :math:`K_j = \pi_j + \sum_{\lambda(k)=j}
  {}^{j}X_k^{*}K_k`, with :math:`m' = m`, :math:`h' = Rh + m p`,
  :math:`I' = RIR^T + 2(p\cdot Rh)\mathbb 1 - Rh\,p^T - p\,(Rh)^T + m(|p|^2\mathbb 1 - pp^T)`;
- **inertia matrix** (composite-rigid-body algorithm): :math:`F_j = K_j s_j`, carried to each
  ancestor :math:`i` (:math:`f \mapsto Rf`, :math:`n \mapsto Rn + p \times Rf`),
  :math:`A_{ij} = s_i \cdot F_j^{(i)}` (:math:`A_{ij} = 0` for joints on different branches),
  plus the armature on the diagonal;
- **gravity**: :math:`g_j = R_j^T g_{\lambda(j)}`, :math:`Q_j = -a_j\cdot(h^K_j\times g_j)`
  (revolute) or :math:`-a_j\cdot m^K_j g_j` (prismatic);
- **Christoffel symbols** from the derivatives of :math:`A` in spatial algebra
  (:math:`\partial S_j/\partial q_k = S_k \times S_j` for :math:`k \preceq j`): for
  :math:`i \preceq j`,

  .. math::
     \frac{\partial A_{ij}}{\partial q_k} = \begin{cases}
       0 & k \preceq i \\
       -(s_k \times s_i^{(k)})\cdot F_j^{(k)} & i \prec k \preceq j \\
       -(s_k \times s_i^{(k)})\cdot K_k s_j^{(k)} - K_k s_i^{(k)}\cdot(s_k \times s_j^{(k)})
         & j \prec k \\
       0 & \text{otherwise,} \end{cases}

  with :math:`s_i^{(k)}` the motion vector :math:`s_i` expressed in frame :math:`k`, and
  :math:`c_{i,jk} = \tfrac12(\partial_k A_{ij} + \partial_j A_{ik} - \partial_i A_{jk})`.

Every quantity that is not a number or a single symbol becomes a new symbol with its defining
expression recorded (:class:`TreeDynamics` ``.assignments``, in order); an element is expanded on
demand (:meth:`TreeDynamics.expand`). Numeric evaluation and operation counts:
:mod:`.tree_code`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np
import pinocchio as pin
import sympy as sp

from ..errors import ModelError
from .exact import GEOMETRY_TOLERANCE, exact_length, exact_rotation, exact_translation
from .kinematics import joint_kind, rodrigues
from .parameters import resolve_parameters
from .tree_algebra import Body, Namer, Vec, cross, dot, inliner, motion_cross, mtv, mv, sym3


@dataclass(frozen=True, eq=False)
class TreeDynamics:
    r"""Closed forms of :math:`A\ddot q + C(q,\dot q)\dot q + Q = \tau` with intermediate
    variables: ``assignments`` ``((w, expression), ...)`` in evaluation order (each expression
    in the coordinates ``q``, parameters and earlier ``w``); ``A`` (n×n), ``Q`` (n),
    ``christoffel[i][j][k]`` (:math:`c_{i,jk}`) in those variables; ``parameters``: the free
    symbols other than ``q``, ``qd`` and the intermediates."""

    q: tuple[sp.Symbol, ...]
    qd: tuple[sp.Symbol, ...]
    parameters: tuple[sp.Symbol, ...]
    assignments: tuple[tuple[sp.Symbol, sp.Expr], ...]
    A: sp.Matrix
    Q: sp.Matrix
    christoffel: tuple[tuple[tuple[sp.Expr, ...], ...], ...]

    @property
    def n(self) -> int:
        return len(self.q)

    def C(self, qdot: Sequence[sp.Expr] | None = None) -> sp.Matrix:
        r""":math:`C_{ij} = \sum_k c_{i,jk}\dot q_k` (in the intermediate variables)."""
        qdot = self.qd if qdot is None else tuple(qdot)
        c, n = self.christoffel, self.n
        return sp.Matrix(n, n, lambda i, j: sp.Add(*[c[i][j][k] * qdot[k] for k in range(n)]))

    def expand(self, expr: sp.Expr, simplify: bool = True) -> sp.Expr:
        r"""``expr`` with every intermediate variable replaced by its definition; collected by
        parameter and polished (:func:`~.simplify.simplify_expr`) with ``simplify``."""
        out = sp.expand(inliner(self.assignments)(sp.sympify(expr)))
        if simplify:
            from .simplify import simplify_expr
            out = simplify_expr(out, self.parameters + self.qd)
        return out


def _placement(model: pin.Model, j: int, tolerance: float) -> tuple[sp.Matrix, sp.Matrix]:
    P = model.jointPlacements[j]
    return exact_rotation(P.rotation, tolerance), exact_translation(P.translation, tolerance)


@dataclass(frozen=True)
class _Tree:
    r"""The joints of a tree in exact geometry: parent :math:`\lambda(j)`, velocity index,
    kind, :math:`{}^{\lambda}T_j(q_j) = (R_j, p_j)`, motion subspace :math:`s_j` (frame
    :math:`j`) and the chain of ancestors (root first, :math:`j` last) of each joint."""

    parent: list[int]
    vidx: dict[int, int]
    kinds: dict[int, str]
    R: dict[int, sp.Matrix]
    p: dict[int, Vec]
    s: dict[int, Vec]
    ancestors: dict[int, list[int]]


def _coordinates(model: pin.Model, coordinate_names: Sequence[str] | None
                 ) -> tuple[tuple[sp.Symbol, ...], tuple[sp.Symbol, ...]]:
    r"""``(q, qd)``: real symbols named after the coordinates and ``"d" + name``; a
    :class:`ModelError` unless every joint has one coordinate, each named."""
    n = model.nv
    coords = list(coordinate_names) if coordinate_names is not None else \
        [model.names[j] for j in range(1, model.njoints)]
    if len(coords) != n or any(model.joints[j].nv != 1 for j in range(1, model.njoints)):
        raise ModelError(model.name or "<pinocchio>", None,
                         f"{len(coords)} coordinate names for nv={n}, or a joint that is not "
                         "1-DoF: the tree closed forms need one coordinate per joint")
    return (tuple(sp.Symbol(c, real=True) for c in coords),
            tuple(sp.Symbol("d" + c, real=True) for c in coords))


def _tree(model: pin.Model, q: Sequence[sp.Symbol], translations: Mapping | None,
          tolerance: float) -> _Tree:
    r"""The joints of ``model`` (:class:`_Tree`): a revolute joint about :math:`a` turns by
    :math:`R_j = R^0_j\,\mathrm{rot}(a, q_j)`, a prismatic one moves :math:`p_j = p^0_j +
    R^0_j a\,q_j`; ``translations`` replace placement translations."""
    N = model.njoints
    parent = [model.parents[j] for j in range(N)]
    vidx = {j: model.joints[j].idx_v for j in range(1, N)}
    kinds: dict[int, str] = {}
    R: dict[int, sp.Matrix] = {}
    p: dict[int, Vec] = {}
    s: dict[int, Vec] = {}
    for j in range(1, N):
        kind, axis = joint_kind(model, j)
        Rp, pp = _placement(model, j, tolerance)
        if translations and j in translations:
            pp = sp.Matrix([sp.sympify(x) for x in translations[j]])
        qj = q[vidx[j]]
        a = [sp.sympify(x) for x in axis]
        if kind == "revolute":
            R[j], p[j] = (Rp * rodrigues(sp.Matrix(a), qj)).applyfunc(sp.expand), list(pp)
            s[j] = a + [0, 0, 0]
        else:
            R[j], p[j] = Rp, [pp[i] + (Rp * sp.Matrix(a))[i] * qj for i in range(3)]
            s[j] = [0, 0, 0] + a
        kinds[j] = kind
    ancestors: dict[int, list[int]] = {0: []}
    for j in range(1, N):
        ancestors[j] = ancestors[parent[j]] + [j]          # root first, j last
    return _Tree(parent, vidx, kinds, R, p, s, ancestors)


def _composite_bodies(tree: _Tree, pis: Mapping[int, Sequence], name: Namer
                      ) -> dict[int, Body]:
    r""":math:`K_j` of every joint, leaves to root (module docstring)."""
    N = len(tree.parent)
    K: dict[int, Body] = {}
    acc = {j: Body(*(lambda pi: (pi[0], list(pi[1:4]), list(pi[4:10])))(
        [sp.sympify(x) for x in pis.get(j, (0,) * 10)])) for j in range(1, N)}
    for j in range(N - 1, 0, -1):
        b = acc[j]
        K[j] = Body(name(b.m, "m"), name.vec(b.h, "h"), name.vec(b.I, "K"))
        lam = tree.parent[j]
        if lam == 0:
            continue
        k, Rj, pj = K[j], tree.R[j], tree.p[j]
        Rh = name.vec(mv(Rj, k.h), "u")
        I = sym3(k.I)
        RI = [[sp.Add(*[Rj[r, c] * I[c][t] for c in range(3)]) for t in range(3)]
              for r in range(3)]
        RI = [name.vec(row, "u") for row in RI]
        RIRt = [[sp.Add(*[RI[r][c] * Rj[t, c] for c in range(3)]) for t in range(3)]
                for r in range(3)]
        ph = dot(pj, Rh)
        pp2 = dot(pj, pj)
        Inew = [[RIRt[r][t] + (2 * ph + k.m * pp2 if r == t else 0) - Rh[r] * pj[t]
                 - pj[r] * Rh[t] - k.m * pj[r] * pj[t] for t in range(3)] for r in range(3)]
        add = [Inew[0][0], Inew[0][1], Inew[1][1], Inew[0][2], Inew[1][2], Inew[2][2]]
        pa = acc[lam]
        acc[lam] = Body(pa.m + k.m, [pa.h[i] + Rh[i] + k.m * pj[i] for i in range(3)],
                         [pa.I[i] + add[i] for i in range(6)])
    return K


def _inertia_matrix(tree: _Tree, K: Mapping[int, Body], arm: Sequence[sp.Expr],
                    name: Namer) -> tuple[sp.Matrix, dict[tuple[int, int], Vec]]:
    r"""``(A, F)``: :math:`A` by the composite-rigid-body algorithm, armature on the diagonal,
    and :math:`F_j^{(i)}` (``F[(j, i)]``) for every joint and each of its ancestors."""
    n = len(arm)

    def up(F: Vec, j: int) -> Vec:
        f = mv(tree.R[j], F[3:])
        nn = mv(tree.R[j], F[:3])
        pf = cross(tree.p[j], f)
        return name.vec([nn[i] + pf[i] for i in range(3)] + f, "f")

    A = sp.zeros(n, n)
    Fin: dict[tuple[int, int], Vec] = {}
    vidx = tree.vidx
    for j in range(1, len(tree.parent)):
        F = name.vec(K[j].apply(tree.s[j]), "f")
        Fin[(j, j)] = F
        chain = tree.ancestors[j]
        for i in reversed(chain[:-1]):
            F = up(F, chain[chain.index(i) + 1])
            Fin[(j, i)] = F
        for i in chain:
            a = name(dot(tree.s[i], Fin[(j, i)]), "A")
            A[vidx[i], vidx[j]] = A[vidx[j], vidx[i]] = a
    for i in range(n):
        if arm[i] != 0:
            A[i, i] = name(A[i, i] + arm[i], "A")
    return A, Fin


def _gravity_forces(tree: _Tree, K: Mapping[int, Body], g0: Vec, name: Namer, n: int
                    ) -> list[sp.Expr]:
    r""":math:`Q` (module docstring), gravity carried down the tree."""
    Qv: list[sp.Expr] = [sp.Integer(0)] * n
    gj: dict[int, Vec] = {0: g0}
    for j in range(1, len(tree.parent)):
        gj[j] = name.vec(mtv(tree.R[j], gj[tree.parent[j]]), "g")
        revolute = tree.kinds[j] == "revolute"
        a = tree.s[j][:3] if revolute else tree.s[j][3:]
        force = cross(K[j].h, gj[j]) if revolute else [K[j].m * x for x in gj[j]]
        Qv[tree.vidx[j]] = name(-dot(a, force), "Q")
    return Qv


def _christoffel(tree: _Tree, K: Mapping[int, Body], Fin: Mapping[tuple[int, int], Vec],
                 name: Namer, n: int) -> list[list[list[sp.Expr]]]:
    r""":math:`c_{i,jk}` (velocity indices) from :math:`\partial A_{ij}/\partial q_k` (module
    docstring)."""
    s, ancestors, parent = tree.s, tree.ancestors, tree.parent

    def down(m: Vec, j: int) -> Vec:
        w, v = m[:3], m[3:]
        wp = cross(w, tree.p[j])
        return name.vec(mtv(tree.R[j], w) + mtv(tree.R[j], [v[i] + wp[i] for i in range(3)]),
                        "s")

    # motion vectors of ancestors in descendant frames
    sin_: dict[tuple[int, int], Vec] = {}
    for k in range(1, len(parent)):
        sin_[(k, k)] = s[k]
        for i in ancestors[k][:-1]:
            sin_[(i, k)] = down(sin_[(i, parent[k])] if parent[k] != i else s[i], k)

    def dA(i: int, j: int, k: int) -> sp.Expr:
        r""":math:`\partial A_{ij}/\partial q_k` (joint indices)."""
        if i not in ancestors[j]:
            if j not in ancestors[i]:
                return sp.Integer(0)
            i, j = j, i
        if k in ancestors[i]:
            return sp.Integer(0)
        if k in ancestors[j]:                                   # i < k <= j
            return name(-dot(motion_cross(s[k], sin_[(i, k)]), Fin[(j, k)]), "D")
        if j in ancestors[k]:                                   # j < k
            w, u = sin_[(i, k)], sin_[(j, k)]
            Ku, Kw = K[k].apply(u), K[k].apply(w)
            return name(-dot(motion_cross(s[k], w), Ku)
                        - dot(Kw, motion_cross(s[k], u)), "D")
        return sp.Integer(0)

    joint_of = {v: j for j, v in tree.vidx.items()}
    D: dict[tuple[int, int, int], sp.Expr] = {}

    def d(a: int, b: int, k: int) -> sp.Expr:
        key = (min(a, b), max(a, b), k)
        if key not in D:
            D[key] = dA(joint_of[key[0]], joint_of[key[1]], joint_of[k])
        return D[key]

    c = [[[sp.Integer(0)] * n for _ in range(n)] for _ in range(n)]
    for i in range(n):
        for j in range(n):
            for k in range(j, n):
                val = (d(i, j, k) + d(i, k, j) - d(j, k, i)) / 2
                c[i][j][k] = c[i][k][j] = name(val, "c") if val != 0 else sp.Integer(0)
    return c


def tree_dynamics(model: pin.Model, params: Mapping[int, Sequence] | None = None,
                  coordinate_names: Sequence[str] | None = None, gravity=None,
                  armature: Sequence | None = None, translations: Mapping | None = None,
                  tolerance: float = GEOMETRY_TOLERANCE) -> TreeDynamics:
    r""":class:`TreeDynamics` of ``model`` (every joint revolute or prismatic, 1 DoF).

    ``params``: ``{joint index: 10 standard parameters}`` as for
    :func:`~.model.symbolic_model` (default: symbols ``M_<joint>, MX_<joint> ...``);
    ``gravity``: a 3-vector (default ``model.gravity``, exact); ``armature``: one expression per
    velocity (default ``model.armature``); ``translations``: ``{joint index: (x, y, z)}``
    expressions replacing joint placement translations (symbolic geometry such as ``R``,
    ``L``); geometry made exact within ``tolerance``
    (:mod:`.exact`). Coordinates and velocities are real symbols named after
    ``coordinate_names`` (default the joint names) and ``"d" + name``.
    """
    q, qd = _coordinates(model, coordinate_names)
    n = model.nv
    pis = resolve_parameters(model, params)
    g0 = list(exact_translation(model.gravity.linear, tolerance)) if gravity is None \
        else [sp.sympify(x) for x in gravity]
    arm = [exact_length(a, tolerance) for a in model.armature] if armature is None \
        else [sp.sympify(a) for a in armature]
    name = Namer()
    tree = _tree(model, q, translations, tolerance)
    K = _composite_bodies(tree, pis, name)
    A, Fin = _inertia_matrix(tree, K, arm, name)
    Qv = _gravity_forces(tree, K, g0, name, n)
    c = _christoffel(tree, K, Fin, name, n)

    special = set(q) | set(qd) | {w for w, _ in name.assignments}
    free: dict[sp.Symbol, None] = {}
    for _, e in name.assignments:
        for sym in sorted(e.free_symbols - special, key=sp.default_sort_key):
            free.setdefault(sym, None)
    return TreeDynamics(q=q, qd=qd, parameters=tuple(free),
                        assignments=tuple(name.assignments), A=A, Q=sp.Matrix(Qv),
                        christoffel=tuple(tuple(tuple(r) for r in m) for m in c))


def random_state(td: TreeDynamics, rng: np.random.Generator) -> tuple[np.ndarray, np.ndarray]:
    """A random ``(q, qd)`` (uniform in [-π, π] and [-1, 1]) for checks."""
    return rng.uniform(-np.pi, np.pi, td.n), rng.uniform(-1.0, 1.0, td.n)
