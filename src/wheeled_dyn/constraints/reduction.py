r"""The equations of motion in a document's coordinates: projection and rolling reduction.

With the model's velocities written :math:`v = S(q)\,\nu` in the document's velocities
:math:`\nu`, and :math:`\dot v = S\dot\nu + \dot S\nu`, the model's equations
:math:`A\dot v + C v + Q = B u + J_c^T\lambda` projected on :math:`S` (which removes the
constraint forces, :math:`J_c S = 0`) give

.. math::

    A_\nu = S^TAS,\qquad C_\nu = S^TCS + S^TA\dot S,\qquad Q_\nu = S^TQ,\qquad B_\nu = S^TB .

:math:`S` comes from the coordinate set (:mod:`wheeled_dyn.coordinates`):

- holonomic map :math:`q = g(q_{doc})`: :math:`S = \partial g/\partial q_{doc}`, and
  :math:`C_\nu` is then the Christoffel-consistent matrix of the new coordinates;
- quasi-velocities :math:`\nu = T(q)v` with rolling eliminated: :math:`S` solves
  :math:`\begin{bmatrix}J_c\\T\end{bmatrix}S = \begin{bmatrix}0\\ \mathbb 1\end{bmatrix}`, and
  differentiating, :math:`\dot S = -\begin{bmatrix}J_c\\T\end{bmatrix}^{+}
  \begin{bmatrix}\dot J_c\\ \dot T\end{bmatrix} S`. Here :math:`C_\nu` has the
  :math:`S^TA\dot S` term that a Christoffel formula applied to quasi-velocities as if they were
  coordinates misses (Boltzmann–Hamel).

When the constraints are kept (``rolling = "multipliers"``) the document's equations read
:math:`A_\nu\dot\nu + C_\nu\nu + Q_\nu = B_\nu u + G^T\lambda` with :math:`G = J_c S`.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pinocchio as pin
import sympy as sp

from ..compiled import grouped_function
from ..coordinates.spec import CoordinateSet, CoordinateSpecError, model_symbols
from ..dynamics.terms import Terms, check_vector
from ..models.builder import WheeledModel
from .batch import lambdify_batch, reduce_batch
from .held import check_representatives, held_coordinates
from .linalg import pseudo_inverse
from .rolling import contact_jacobian, planar_drift, planar_rows

#: Largest residual of [J_c; T] S = [0; 1] for the velocities to parametrise the motions.
PARAMETRISATION_TOL = 1e-9


class CoordinateMap:
    r"""A coordinate set bound to a model: numbers in, document-coordinate terms out.

    Expressions are compiled once (as SymPy's ``lambdify`` does: :mod:`~wheeled_dyn.compiled`);
    the model's parameters enter as arguments, so the same map serves every parameter set of
    the same model structure.
    """

    def __init__(self, wm: WheeledModel, cs: CoordinateSet) -> None:
        from ..errors import ArgumentError
        if not isinstance(wm, WheeledModel):
            raise ArgumentError("CoordinateMap", "wm", wm, "a model (wheeled_dyn.load_model)")
        if not isinstance(cs, CoordinateSet):
            raise ArgumentError("CoordinateMap", "cs", cs, "a coordinate set "
                                "(wheeled_dyn.builtin_coordinate_set(model, name))")
        self.wm = wm
        self.cs = cs
        self.n = len(cs.positions)
        params = [sp.Symbol(p, real=True) for p in cs.parameters]
        self._param_names = cs.parameters
        doc_q = list(cs.position_symbols())
        doc_v = list(cs.velocity_symbols())
        config = sp.Matrix([cs.configuration[c] for c in wm.coordinate_names])
        self._config = grouped_function([doc_q, params], config)
        self._config_batch = lambdify_batch(config, [*doc_q, *params])
        if cs.kind == "holonomic":
            S = config.jacobian(doc_q)
            Sdot = sum((S.diff(s) * ds for s, ds in zip(doc_q, doc_v)), sp.zeros(*S.shape))
            self._S = grouped_function([doc_q, params], S)
            self._Sdot = grouped_function([doc_q, doc_v, params], Sdot)
            self._S_batch = lambdify_batch(S, [*doc_q, *params])
            self._Sdot_batch = lambdify_batch(Sdot, [*doc_q, *doc_v, *params])
        else:
            vmap = cs.velocity_map
            assert vmap is not None, "a set that is not holonomic maps its velocities"
            T = self._compile_velocity_map([vmap[v] for v in cs.velocities], params)
            if cs.rolling != "eliminate" and T.shape[0] != T.shape[1]:
                raise CoordinateSpecError(cs.name, "velocity_map",
                                          f"{T.shape[0]} velocities for {T.shape[1]} model "
                                          "velocities: without rolling elimination they must "
                                          "be as many")
        if cs.kind == "holonomic" and cs.rolling == "eliminate":
            raise CoordinateSpecError(cs.name, "rolling", "'eliminate' needs quasi-velocities "
                                      "(kind = 'quasi'); use 'multipliers' for a holonomic set")
        self.bind()
        #: The model coordinates the set holds (:mod:`.held`): their velocities are rows of T
        #: after the document's, each held at zero.
        self.held: tuple[str, ...] = ()
        if cs.kind == "quasi" and cs.rolling == "eliminate":
            self.held = held_coordinates(cs, wm.coordinate_names, self._stacked,
                                         [w.v_index for w in wm.wheels])
            if self.held:
                assert vmap is not None, "a quasi set maps its velocities"
                _, mv = model_symbols(wm.coordinate_names)
                index = {c: k for k, c in enumerate(wm.coordinate_names)}
                self._compile_velocity_map([*(vmap[v] for v in cs.velocities),
                                            *(mv[index[c]] for c in self.held)], params)
        if cs.kind == "quasi":
            check_representatives(cs, wm.coordinate_names, self._moved_at)

    def _compile_velocity_map(self, rows: list[sp.Expr], params: list[sp.Symbol]) -> sp.Matrix:
        r""":math:`T = \partial\nu/\partial v` of the velocities ``rows`` and its rate,
        compiled; returns T."""
        mq, mv = model_symbols(self.wm.coordinate_names)
        T = sp.Matrix(rows).jacobian(mv)
        Tdot = sum((T.diff(s) * ds for s, ds in zip(mq, mv)), sp.zeros(*T.shape))
        self._T = grouped_function([list(mq), params], T)
        self._Tdot = grouped_function([list(mq), list(mv), params], Tdot)
        self._T_batch = lambdify_batch(T, [*mq, *params])
        self._Tdot_batch = lambdify_batch(Tdot, [*mq, *mv, *params])
        return T

    def _stacked(self, q_doc: np.ndarray) -> np.ndarray:
        r""":math:`[J_c; T]` at the model configuration of the document positions ``q_doc``."""
        q = np.asarray(self._config(q_doc, self._p), dtype=float).reshape(-1)
        J, _ = contact_jacobian(self.wm, q, data=self._data)
        return np.vstack([J, np.asarray(self._T(q, self._p), dtype=float)])

    def _moved_at(self, k: int, step: float = 0.7) -> float:
        r"""The relative change of the truth in the document's velocities (:math:`A_\nu` and
        the gravity forces :math:`S^TQ`) when model coordinate ``k`` moves by ``step`` from the
        set's configuration at seeded positions."""
        q = np.asarray(self._config(np.random.default_rng(0).uniform(-1, 1, self.n), self._p),
                       dtype=float).ravel()
        dv = np.zeros(self.wm.model.nv)
        dv[k] = step
        zero = np.zeros(self.n)
        try:
            (A0, F0, _, _), (A1, F1, _, _) = (self.dynamics_at(x, zero) for x in (
                q, pin.integrate(self.wm.model, q, dv)))
        except (np.linalg.LinAlgError, ValueError):
            return 0.0                   # singular there: the comparison's own checks say so
        out, inertia = 0.0, float(np.abs(A0).max(initial=0.0))
        # (forces against gravity on that inertia, g ~ 10 per unit of it: a force that is 0 up
        # to rounding is not a scale)
        for x0, x1, floor in ((A0, A1, 1e-300), (F0, F1, 10.0 * inertia)):
            size = max(float(np.abs(x0).max(initial=0.0)), float(np.abs(x1).max(initial=0.0)),
                       floor)
            out = max(out, float(np.abs(x1 - x0).max(initial=0.0)) / size)
        return out

    def basis(self, Mp: np.ndarray, constraints: int) -> np.ndarray:
        r""":math:`S`: the columns of :math:`[J_c; T]^+` (``Mp``, N stacked or one) of the
        document's velocities, after the ``constraints`` rows of :math:`J_c` and before those
        of the held coordinates."""
        return Mp[..., constraints:constraints + self.n]

    def bind(self, wm: WheeledModel | None = None) -> "CoordinateMap":
        r"""Use the parameters (R, L, ...) and inertias of ``wm`` (same structure) from now on."""
        if wm is not None:
            self.wm = wm
        lengths = self.wm.named_lengths()
        self._p = [lengths[p] for p in self._param_names]
        self._data = self.wm.model.createData()
        self._lower = np.tril_indices(self.wm.model.nv, -1)   # lower triangle of A
        self._B = self.wm.input_matrix()
        return self

    # -- states -------------------------------------------------------------------------
    def model_configuration(self, q_doc: np.ndarray) -> np.ndarray:
        r"""The model configuration :math:`q = g(q_{doc})` (representative for quasi sets)."""
        q_doc = check_vector("q", q_doc, self.n, self.cs.positions)
        return np.asarray(self._config(q_doc, self._p), dtype=float).reshape(-1)

    def velocity_matrix(self, q: np.ndarray, q_doc: np.ndarray | None = None) -> np.ndarray:
        r""":math:`S` at model configuration ``q`` (holonomic sets use ``q_doc``)."""
        if self.cs.kind == "holonomic":
            return np.asarray(self._S(q_doc, self._p), dtype=float)
        T = np.asarray(self._T(q, self._p), dtype=float)
        if self.cs.rolling != "eliminate":
            return np.linalg.inv(T)
        J, _ = contact_jacobian(self.wm, q, data=self._data)
        M = np.vstack([J, T])
        E = np.vstack([np.zeros((J.shape[0], self.n)), np.eye(self.n),
                       np.zeros((len(self.held), self.n))])
        S = np.linalg.lstsq(M, E, rcond=None)[0]
        residual = np.abs(M @ S - E).max()
        if residual > PARAMETRISATION_TOL:
            raise CoordinateSpecError(self.cs.name, "velocity_map",
                                      "these velocities do not parametrise the rolling motions "
                                      f"(residual {residual:.2e} of [J_c; T] S = [0; 1])")
        return S

    def terms_at(self, q: np.ndarray, nu: np.ndarray, q_doc: np.ndarray | None = None) -> Terms:
        r"""The terms in document velocities at model configuration ``q`` and velocities
        :math:`\nu` (``q_doc`` is needed, and enough, for holonomic sets)."""
        return self.reduce_at(q, nu, q_doc)[0]

    def reduce_at(self, q: np.ndarray, nu: np.ndarray, q_doc: np.ndarray | None = None
                  ) -> tuple[Terms, np.ndarray, np.ndarray]:
        r"""(terms, :math:`S`, :math:`v = S\nu`) at model configuration ``q``."""
        nu = check_vector("velocity", nu, self.n, self.cs.velocities)
        model, data = self.wm.model, self._data
        if self.cs.kind == "holonomic":
            S = np.asarray(self._S(q_doc, self._p), dtype=float)
            v = S @ nu
            Sdot = np.asarray(self._Sdot(q_doc, nu, self._p), dtype=float)
            J = dJ = None
            if self.cs.rolling == "multipliers":
                J, _ = contact_jacobian(self.wm, q, data=data)
        else:
            T = np.asarray(self._T(q, self._p), dtype=float)
            if self.cs.rolling == "eliminate":
                J, _ = contact_jacobian(self.wm, q, data=data)
                M = np.vstack([J, T])
                Mp = np.linalg.pinv(M)
                S = self.basis(Mp, J.shape[0])
                v = S @ nu
                _, dJ = contact_jacobian(self.wm, q, v, data=data)
                Tdot = np.asarray(self._Tdot(q, v, self._p), dtype=float)
                Sdot = -Mp @ np.vstack([dJ, Tdot]) @ S
            else:
                S = np.linalg.inv(T)
                v = S @ nu
                Tdot = np.asarray(self._Tdot(q, v, self._p), dtype=float)
                Sdot = -S @ Tdot @ S
                J = contact_jacobian(self.wm, q, data=data)[0] if self.cs.rolling == "multipliers" else None
        A = pin.crba(model, data, q)
        A = np.triu(A) + np.triu(A, 1).T
        C = pin.computeCoriolisMatrix(model, data, q, v)
        Q = self.wm.potential_force(data, q)
        St = S.T
        AS = A @ S
        A_nu = St @ AS
        C_nu = St @ C @ S + St @ A @ Sdot
        G = J @ S if (self.cs.rolling == "multipliers" and J is not None) else None
        terms = Terms(self.cs.velocities, self.wm.input_names, 0.5 * (A_nu + A_nu.T), C_nu,
                      St @ Q, St @ self._B, C_nu @ nu, G)
        return terms, S, v

    def dynamics_at(self, q: np.ndarray, nu: np.ndarray, q_doc: np.ndarray | None = None
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        r"""What the equations of motion need and no more: :math:`(A_\nu,\ h_\nu + Q_\nu,
        B_\nu, S)` at model configuration ``q``, with

        .. math::

            h_\nu + Q_\nu = S^T\big(n(q, v) + A\,\dot S\nu\big),\qquad v = S\nu,

        :math:`n = C v + Q` from ``pin.nonLinearEffects`` and the springs (no Coriolis matrix), and
        :math:`\dot S\nu` as a vector (:meth:`reduce_at` gives the matrices C, Q apart)."""
        nu = np.asarray(nu, dtype=float).reshape(-1)
        wm, model, data = self.wm, self.wm.model, self._data
        A = pin.crba(model, data, q, pin.Convention.WORLD)     # leaves the joint Jacobians
        A = A.copy()
        A[self._lower] = A.T[self._lower]                      # crba fills the upper triangle
        if self.cs.kind == "holonomic":
            S = np.asarray(self._S(q_doc, self._p), dtype=float)
            Sdot_nu = np.asarray(self._Sdot(q_doc, nu, self._p), dtype=float) @ nu
            v = S @ nu
        else:
            T = np.asarray(self._T(q, self._p), dtype=float)
            if self.cs.rolling == "eliminate":
                planar = wm.contact is None and not wm.rolling_wheels
                J = planar_rows(wm, data) if planar else contact_jacobian(wm, q, data=data)[0]
                Mp = pseudo_inverse(np.vstack([J, T]))
                S = self.basis(Mp, J.shape[0])
                v = S @ nu
                drift = planar_drift(wm, data, q, v) if planar else \
                    contact_jacobian(wm, q, v, data=data)[1] @ v
                Tdot = np.asarray(self._Tdot(q, v, self._p), dtype=float)
                Sdot_nu = -Mp @ np.concatenate([drift, Tdot @ v])
            else:
                S = np.linalg.inv(T)
                v = S @ nu
                Sdot_nu = -S @ (np.asarray(self._Tdot(q, v, self._p), dtype=float) @ v)
        force = S.T @ (wm.nonlinear_effects(data, q, v) + A @ Sdot_nu)
        return S.T @ A @ S, force, S.T @ self._B, S

    def terms_batch(self, q_doc: np.ndarray, nu: np.ndarray) -> Terms:
        r"""The terms at N document states (``q_doc``: N × n positions, ``nu``: N × n
        velocities), as arrays with a leading axis N; the same numbers as :meth:`terms`."""
        q_doc = np.atleast_2d(np.asarray(q_doc, dtype=float))
        nu = np.atleast_2d(np.asarray(nu, dtype=float))
        for name, arr in (("q", q_doc), ("velocity", nu)):
            if arr.ndim != 2 or arr.shape[1] != self.n or not np.all(np.isfinite(arr)):
                from ..errors import StateError
                raise StateError(name, arr.shape, f"an N x {self.n} array of finite numbers")
        q = self._config_batch(len(q_doc), *q_doc.T, *self._p)[:, :, 0]
        return reduce_batch(self, q, nu, q_doc)

    def conditioning(self, q_doc: np.ndarray) -> np.ndarray:
        r"""The condition number, at N document positions, of the map between the document's
        velocities and the model's: :math:`S(q)` of a holonomic set, :math:`T(q)` of a
        quasi-velocity set. Near a singularity of the document's coordinates (the pitch
        :math:`\pm\pi/2` of ZYX angles) it grows without bound, and so do the rounding
        errors of :math:`S^TAS`, :math:`\dot S`, ..."""
        q_doc = np.atleast_2d(np.asarray(q_doc, dtype=float))
        N = len(q_doc)
        with np.errstate(all="ignore"):         # sqrt(theta) at theta < 0: NaN, redrawn
            if self.cs.kind == "holonomic":
                M = self._S_batch(N, *q_doc.T, *self._p)
            else:
                q = self._config_batch(N, *q_doc.T, *self._p)[:, :, 0]
                M = self._T_batch(N, *q.T, *self._p)[:, :self.n]   # the document's rows
        M = np.asarray(M, dtype=float)
        out = np.full(N, np.inf)
        finite = np.all(np.isfinite(M.reshape(N, -1)), axis=1)   # a map undefined there
        with np.errstate(all="ignore"):
            if finite.any():
                out[finite] = np.linalg.cond(M[finite])
        out[self.off_ground(q_doc)] = np.inf
        return np.where(np.isfinite(out), out, np.inf)

    def off_ground(self, q_doc: np.ndarray) -> np.ndarray:
        r"""Whether the map puts a tilting wheel off the ground or flat at each of N
        document positions (:func:`~.wheel_contact.off_ground`; all False for a model
        without tilting wheels)."""
        q_doc = np.atleast_2d(np.asarray(q_doc, dtype=float))
        if not self.wm.rolling_wheels:
            return np.zeros(len(q_doc), dtype=bool)
        from .wheel_contact import off_ground
        with np.errstate(all="ignore"):
            q = np.asarray(self._config_batch(len(q_doc), *q_doc.T, *self._p),
                           dtype=float)[:, :, 0]
        bad = ~np.isfinite(q).all(axis=1)
        bad[~bad] = off_ground(self.wm, q[~bad], self._data)
        return bad

    def terms(self, q_doc: np.ndarray, nu: np.ndarray) -> Terms:
        r"""The terms at a document state (positions ``q_doc``, velocities ``nu``)."""
        q_doc = check_vector("q", q_doc, self.n, self.cs.positions)
        return self.terms_at(self.model_configuration(q_doc), nu, q_doc)

    def state_from(self, values: Mapping[str, float]) -> tuple[np.ndarray, np.ndarray]:
        r"""(positions, velocities) from a mapping of document names (missing ones are 0);
        an unknown name raises :class:`UnknownNameError`."""
        from ..errors import UnknownNameError
        known = (*self.cs.positions, *self.cs.velocities)
        for key in values:
            if key not in known:
                raise UnknownNameError("state entry", key, known,
                                       where=f"coordinate set {self.cs.name}")
        q = np.array([float(values.get(p, 0.0)) for p in self.cs.positions])
        nu = np.array([float(values.get(v, 0.0)) for v in self.cs.velocities])
        check_vector("q", q, self.n, self.cs.positions)
        check_vector("velocity", nu, self.n, self.cs.velocities)
        return q, nu


def multipliers(wm: WheeledModel, q: np.ndarray, v: np.ndarray, u: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    r"""Contact forces :math:`\lambda` and accelerations :math:`\dot v` of the constrained
    model at a state satisfying :math:`J_c v = 0`, from the full equations

    .. math::

        \begin{bmatrix} A & -J_c^T\\ J_c & 0\end{bmatrix}
        \begin{bmatrix}\dot v\\ \lambda\end{bmatrix} =
        \begin{bmatrix} B u - h - Q\\ -\dot J_c v\end{bmatrix}.

    :math:`\lambda` stacks, per wheel, the world x and y ground force on the wheel, then, for
    a rolling ball, the three world components of the surface's force on it. Two wheels on
    one axle share the lateral force in a way rigid-body mechanics does not determine; the
    minimum-norm solution (equal shares) is returned.
    """
    model = wm.model
    data = model.createData()
    A = pin.crba(model, data, q)
    A = np.triu(A) + np.triu(A, 1).T
    nle = wm.nonlinear_effects(data, q, v)
    J, dJ = contact_jacobian(wm, q, v)
    m = J.shape[0]
    K = np.block([[A, -J.T], [J, np.zeros((m, m))]])
    rhs = np.concatenate([wm.input_matrix() @ u - nle, -dJ @ v])
    sol = np.linalg.lstsq(K, rhs, rcond=None)[0]
    return sol[model.nv:], sol[:model.nv]
