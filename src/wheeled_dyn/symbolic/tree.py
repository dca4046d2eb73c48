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

Vec = list  # three (or six) SymPy expressions


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
        definitions = dict(self.assignments)
        memo: dict[sp.Symbol, sp.Expr] = {}

        def full(e: sp.Expr) -> sp.Expr:
            subs = {}
            for s in e.free_symbols:
                if s in definitions:
                    if s not in memo:
                        memo[s] = full(definitions[s])
                    subs[s] = memo[s]
            return e.xreplace(subs) if subs else e

        out = sp.expand(full(sp.sympify(expr)))
        if simplify:
            from .simplify import simplify_expr
            out = simplify_expr(out, self.parameters + self.qd)
        return out


class _Namer:
    r"""Records intermediate variables ``<prefix><n>``; numbers, symbols and their negatives
    are kept as they are, an expression met before gets its earlier name."""

    def __init__(self) -> None:
        self.assignments: list[tuple[sp.Symbol, sp.Expr]] = []
        self.seen: dict[sp.Expr, sp.Expr] = {}
        self.count = 0

    def __call__(self, e: sp.Expr, prefix: str) -> sp.Expr:
        e = sp.expand(e) if e.is_Add or e.is_Mul else e
        if e.is_Number or e.is_Symbol or (e.is_Mul and len(e.args) == 2 and e.args[0].is_Number
                                          and e.args[1].is_Symbol):
            return e
        if e in self.seen:
            return self.seen[e]
        neg = -e
        if neg in self.seen:
            return -self.seen[neg]
        self.count += 1
        w = sp.Symbol(f"{prefix}{self.count}", real=True)
        self.assignments.append((w, e))
        self.seen[e] = w
        return w

    def vec(self, v: Vec, prefix: str) -> Vec:
        return [self(x, prefix) for x in v]


def _cross(a: Vec, b: Vec) -> Vec:
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _dot(a: Vec, b: Vec) -> sp.Expr:
    return sp.Add(*[x * y for x, y in zip(a, b)])


def _mv(R: sp.Matrix, v: Vec) -> Vec:
    return [sp.Add(*[R[i, k] * v[k] for k in range(3)]) for i in range(3)]


def _mtv(R: sp.Matrix, v: Vec) -> Vec:
    return [sp.Add(*[R[k, i] * v[k] for k in range(3)]) for i in range(3)]


def _sym3(I6: Vec) -> list[list[sp.Expr]]:
    xx, xy, yy, xz, yz, zz = I6
    return [[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]


@dataclass
class _Body:
    m: sp.Expr
    h: Vec
    I: Vec  # xx, xy, yy, xz, yz, zz (Pinocchio's order)

    def apply(self, motion: Vec) -> Vec:
        r"""The momentum :math:`K m` of the motion ``(ω, v)``: ``(n, f)`` with
        :math:`n = I\omega + h\times v`, :math:`f = m v + \omega\times h`."""
        w, v = motion[:3], motion[3:]
        M = _sym3(self.I)
        n = [sp.Add(*[M[i][k] * w[k] for k in range(3)]) for i in range(3)]
        hv = _cross(self.h, v)
        wh = _cross(w, self.h)
        return [n[i] + hv[i] for i in range(3)] + [self.m * v[i] + wh[i] for i in range(3)]


def _motion_cross(a: Vec, b: Vec) -> Vec:
    w1, v1, w2, v2 = a[:3], a[3:], b[:3], b[3:]
    x, y, z = _cross(w1, w2), _cross(w1, v2), _cross(v1, w2)
    return x + [y[i] + z[i] for i in range(3)]


def _placement(model: pin.Model, j: int, tolerance: float) -> tuple[sp.Matrix, sp.Matrix]:
    P = model.jointPlacements[j]
    return exact_rotation(P.rotation, tolerance), exact_translation(P.translation, tolerance)


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
    n = model.nv
    coords = list(coordinate_names) if coordinate_names is not None else \
        [model.names[j] for j in range(1, model.njoints)]
    if len(coords) != n or any(model.joints[j].nv != 1 for j in range(1, model.njoints)):
        raise ModelError(model.name or "<pinocchio>", None,
                         f"{len(coords)} coordinate names for nv={n}, or a joint that is not "
                         "1-DoF: the tree closed forms need one coordinate per joint")
    q = tuple(sp.Symbol(c, real=True) for c in coords)
    qd = tuple(sp.Symbol("d" + c, real=True) for c in coords)
    pis = resolve_parameters(model, params)
    g0 = list(exact_translation(model.gravity.linear, tolerance)) if gravity is None \
        else [sp.sympify(x) for x in gravity]
    arm = [exact_length(a, tolerance) for a in model.armature] if armature is None \
        else [sp.sympify(a) for a in armature]
    name = _Namer()
    N = model.njoints
    parent = [model.parents[j] for j in range(N)]
    vidx = {j: model.joints[j].idx_v for j in range(1, N)}
    kinds, R, p, s = {}, {}, {}, {}
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
    ancestors = {0: []}
    for j in range(1, N):
        ancestors[j] = ancestors[parent[j]] + [j]          # root first, j last

    # composite bodies, leaves to root
    K: dict[int, _Body] = {}
    acc = {j: _Body(*(lambda pi: (pi[0], list(pi[1:4]), list(pi[4:10])))(
        [sp.sympify(x) for x in pis.get(j, (0,) * 10)])) for j in range(1, N)}
    for j in range(N - 1, 0, -1):
        b = acc[j]
        K[j] = _Body(name(b.m, "m"), name.vec(b.h, "h"), name.vec(b.I, "K"))
        lam = parent[j]
        if lam == 0:
            continue
        k, Rj, pj = K[j], R[j], p[j]
        Rh = name.vec(_mv(Rj, k.h), "u")
        I = _sym3(k.I)
        RI = [[sp.Add(*[Rj[r, c] * I[c][t] for c in range(3)]) for t in range(3)]
              for r in range(3)]
        RI = [name.vec(row, "u") for row in RI]
        RIRt = [[sp.Add(*[RI[r][c] * Rj[t, c] for c in range(3)]) for t in range(3)]
                for r in range(3)]
        ph = _dot(pj, Rh)
        pp2 = _dot(pj, pj)
        Inew = [[RIRt[r][t] + (2 * ph + k.m * pp2 if r == t else 0) - Rh[r] * pj[t]
                 - pj[r] * Rh[t] - k.m * pj[r] * pj[t] for t in range(3)] for r in range(3)]
        add = [Inew[0][0], Inew[0][1], Inew[1][1], Inew[0][2], Inew[1][2], Inew[2][2]]
        pa = acc[lam]
        acc[lam] = _Body(pa.m + k.m, [pa.h[i] + Rh[i] + k.m * pj[i] for i in range(3)],
                         [pa.I[i] + add[i] for i in range(6)])

    def up(F: Vec, j: int) -> Vec:
        f = _mv(R[j], F[3:])
        nn = _mv(R[j], F[:3])
        pf = _cross(p[j], f)
        return name.vec([nn[i] + pf[i] for i in range(3)] + f, "f")

    def down(m: Vec, j: int) -> Vec:
        w, v = m[:3], m[3:]
        wp = _cross(w, p[j])
        return name.vec(_mtv(R[j], w) + _mtv(R[j], [v[i] + wp[i] for i in range(3)]), "s")

    # inertia matrix: F_j carried to every ancestor
    A = sp.zeros(n, n)
    Fin: dict[tuple[int, int], Vec] = {}
    for j in range(1, N):
        F = name.vec(K[j].apply(s[j]), "f")
        Fin[(j, j)] = F
        chain = ancestors[j]
        for i in reversed(chain[:-1]):
            F = up(F, chain[chain.index(i) + 1])
            Fin[(j, i)] = F
        for i in chain:
            a = name(_dot(s[i], Fin[(j, i)]), "A")
            A[vidx[i], vidx[j]] = A[vidx[j], vidx[i]] = a
    for i in range(n):
        if arm[i] != 0:
            A[i, i] = name(A[i, i] + arm[i], "A")

    # gravity
    Qv = [sp.Integer(0)] * n
    gj: dict[int, Vec] = {0: g0}
    for j in range(1, N):
        gj[j] = name.vec(_mtv(R[j], gj[parent[j]]), "g")
        a = s[j][:3] if kinds[j] == "revolute" else s[j][3:]
        force = _cross(K[j].h, gj[j]) if kinds[j] == "revolute" else \
            [K[j].m * x for x in gj[j]]
        Qv[vidx[j]] = name(-_dot(a, force), "Q")

    # motion vectors of ancestors in descendant frames
    sin_: dict[tuple[int, int], Vec] = {}
    for k in range(1, N):
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
            return name(-_dot(_motion_cross(s[k], sin_[(i, k)]), Fin[(j, k)]), "D")
        if j in ancestors[k]:                                   # j < k
            w, u = sin_[(i, k)], sin_[(j, k)]
            Ku, Kw = K[k].apply(u), K[k].apply(w)
            return name(-_dot(_motion_cross(s[k], w), Ku)
                        - _dot(Kw, _motion_cross(s[k], u)), "D")
        return sp.Integer(0)

    joint_of = {vidx[j]: j for j in range(1, N)}
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
