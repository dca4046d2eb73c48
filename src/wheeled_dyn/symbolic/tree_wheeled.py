r"""A wheeled model of any size in a document's coordinates, with intermediate variables.

:func:`tree_wheeled` is :func:`~.wheeled.wheeled_symbolic` for robots whose expanded closed
forms do not finish (TIAGo with its arm): the model's :math:`A`, :math:`c_{i,jk}`, :math:`Q` come
from :func:`~.tree.tree_dynamics`, :math:`S(q)` and :math:`\dot S` from the same rolling
reduction (:func:`~.basis.velocity_basis`; the contact rows need only the joints that carry
the wheels), and the projection

.. math::
   A_\nu = S^TAS, \quad C_\nu = S^T C(q, S\nu) S + S^T A\dot S, \quad Q_\nu = S^TQ, \quad
   B_\nu = S^TB, \quad h_\nu = C_\nu\nu, \qquad C(q,\dot q)_{ij} = \sum_k c_{i,jk}\dot q_k,

adds its own intermediate variables. Model coordinates are then replaced by their
expressions in the document's positions (``configuration`` of the set).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import pinocchio as pin
import sympy as sp

from ..coordinates.spec import CoordinateSet
from ..models.wheeled_model import WheeledModel
from .basis import velocity_basis
from .exact import exact_model
from .kinematics import forward_kinematics
from .model import _gravity
from .parameter_modes import parameter_setup
from .springs import spring_terms, with_springs
from .tree import TreeDynamics, tree_dynamics
from .tree_algebra import Namer


@dataclass(frozen=True, eq=False)
class ReducedTree:
    r"""Terms in quasi-velocities with intermediate variables (as :class:`~.tree.TreeDynamics`):
    ``A``, ``C``, ``Q``, ``h``, ``B`` (None without inputs) in the document positions ``q``,
    velocities ``nu``, ``parameters`` and the ``assignments``' variables."""

    q: tuple[sp.Symbol, ...]
    nu: tuple[sp.Symbol, ...]
    parameters: tuple[sp.Symbol, ...]
    assignments: tuple[tuple[sp.Symbol, sp.Expr], ...]
    A: sp.Matrix
    C: sp.Matrix
    Q: sp.Matrix
    h: sp.Matrix
    B: sp.Matrix | None

    def expand(self, expr: sp.Expr, simplify: bool = True) -> sp.Expr:
        """``expr`` with the intermediate variables replaced (:meth:`.TreeDynamics.expand`)."""
        return TreeDynamics.expand(self, expr, simplify)  # type: ignore[arg-type]

    @property
    def qd(self) -> tuple[sp.Symbol, ...]:
        return self.nu


def _wheel_rows(wm: WheeledModel, model: pin.Model, td: TreeDynamics, radius,
                translations=None) -> sp.Matrix:
    r""":math:`J_c` (2 rows per wheel, as :func:`~.basis.contact_rows`) from the kinematics
    of the joints that carry the wheels only (a reduced model)."""
    keep = set()
    for w in wm.wheels:
        j = w.joint_id
        while j:
            keep.add(j)
            j = model.parents[j]
    lock = [j for j in range(1, model.njoints) if j not in keep]
    sub = pin.buildReducedModel(model, lock, pin.neutral(model)) if lock else model
    index = {model.names[j]: model.joints[j].idx_v for j in range(1, model.njoints)}
    cols = [index[sub.names[j]] for j in range(1, sub.njoints)]
    q = [td.q[c] for c in cols]
    qd = [td.qd[c] for c in cols]
    moved = {sub.getJointId(model.names[j]): t for j, t in (translations or {}).items()
             if sub.existJointName(model.names[j])}
    kin = {k.name: k for k in forward_kinematics(sub, q, qd, translations=moved)}
    rows = []
    for wheel, rho in zip(wm.wheels, radius):
        k = kin[wheel.joint_name]
        v, w = k.R * k.v, k.R * k.omega
        rows += [v[0] - rho * w[1], v[1] + rho * w[0]]
    Jsub = sp.Matrix(rows).jacobian(qd).applyfunc(sp.expand)
    J = sp.zeros(len(rows), td.n)
    for a, c in enumerate(cols):
        J[:, c] = Jsub[:, a]
    return J


def reduce_tree(td: TreeDynamics, S: sp.Matrix, Sdot: sp.Matrix, nu: Sequence[sp.Symbol],
                B: sp.Matrix | None = None) -> tuple[list, sp.Matrix, sp.Matrix, sp.Matrix,
                                                    sp.Matrix, sp.Matrix | None]:
    r"""``(new assignments, A_ν, C_ν, Q_ν, h_ν, B_ν)`` with :math:`\dot q = S\nu`; ``Sdot`` in
    the model velocities ``td.qd`` (replaced by :math:`S\nu`)."""
    name = Namer()
    name.count = len(td.assignments)
    n, m = td.n, len(nu)
    Snu = [name(sp.Add(*[S[a, b] * nu[b] for b in range(m)]), "v") for a in range(n)]
    Sd = Sdot.xreplace(dict(zip(td.qd, Snu)))
    c = td.christoffel
    Cq = [[name(sp.Add(*[c[i][j][k] * Snu[k] for k in range(n) if c[i][j][k] != 0]), "C")
           for j in range(n)] for i in range(n)]

    def left(M, cols):          # S^T M for M n×cols
        return [[name(sp.Add(*[S[a, i] * M[a][j] for a in range(n) if S[a, i] != 0]), "r")
                 for j in range(cols)] for i in range(m)]

    def right(M, X, rows):      # M X for M rows×n, X n×m (SymPy matrix)
        return [[name(sp.Add(*[M[i][a] * X[a, j] for a in range(n) if X[a, j] != 0]), "r")
                 for j in range(m)] for i in range(rows)]

    Al = [[td.A[i, j] for j in range(n)] for i in range(n)]
    AS = right(Al, S, n)
    ASd = right(Al, Sd, n)
    CS = right(Cq, S, n)
    An = left(AS, m)
    C1, C2 = left(CS, m), left(ASd, m)
    Cn = [[name(C1[i][j] + C2[i][j], "C") for j in range(m)] for i in range(m)]
    Qn = left([[x] for x in td.Q], 1)
    hn = [name(sp.Add(*[Cn[i][j] * nu[j] for j in range(m)]), "h") for i in range(m)]
    Bn = None
    if B is not None:
        Bn = sp.Matrix(left([[B[a, k] for k in range(B.shape[1])] for a in range(n)],
                            B.shape[1]))
    return (name.assignments, sp.Matrix(An), sp.Matrix(Cn), sp.Matrix([r[0] for r in Qn]),
            sp.Matrix(hn), Bn)


def tree_wheeled(wm: WheeledModel, cs: CoordinateSet, parameters: str = "standard"
                 ) -> ReducedTree:
    r""":class:`ReducedTree` of ``wm`` in the coordinate set ``cs`` (parameters as in
    :func:`~.wheeled.wheeled_symbolic`: ``"physical"``, ``"numbers"``, ``"standard"``)."""
    setup = parameter_setup(wm, parameters, axle=True)
    model = exact_model(wm.model)
    g = _gravity(model, setup["gravity"])
    td = tree_dynamics(model, setup["params"], wm.coordinate_names, gravity=list(g),
                       armature=setup["armature"], translations=setup["translations"])
    td = with_springs(td, spring_terms(wm, parameters))
    J = _wheel_rows(wm, model, td, setup["radius"], setup["translations"]) \
        if cs.rolling != "none" else None
    S, Sdot, config, pos, nu = velocity_basis(wm, cs, setup, td.q, td.qd, J)
    B = sp.Matrix(wm.input_matrix().astype(int)) if wm.input_matrix().size else None
    new, A, C, Q, h, Bn = reduce_tree(td, S, Sdot, nu, B)
    back = dict(zip(pos, cs.position_symbols())) | dict(zip(nu, cs.velocity_symbols()))
    subs = {k: sp.sympify(v).xreplace(back) for k, v in config.items()} | back
    assignments = tuple((w, e.xreplace(subs)) for w, e in (*td.assignments, *new))

    def ren(M):
        return None if M is None else M.xreplace(subs)

    special = set(cs.position_symbols()) | set(cs.velocity_symbols()) | \
        {w for w, _ in assignments}
    free: dict[sp.Symbol, None] = dict.fromkeys(p for p in td.parameters)
    for _, e in assignments:
        for s_ in sorted(e.free_symbols - special, key=sp.default_sort_key):
            free.setdefault(s_, None)
    params = tuple(p for p in free if p not in special)
    return ReducedTree(q=cs.position_symbols(), nu=cs.velocity_symbols(), parameters=params,
                       assignments=assignments, A=ren(A), C=ren(C), Q=ren(Q), h=ren(h),
                       B=ren(Bn))
