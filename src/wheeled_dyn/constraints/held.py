r"""The model coordinates a quasi-velocity set holds, and the motions it leaves free.

With rolling eliminated, a document's velocities :math:`\nu = T(q)\,v` and the rolling
constraints :math:`J_c v = 0` must determine the model's velocities: :math:`v = S\nu` with
:math:`\begin{bmatrix}J_c\\T\end{bmatrix}S = \begin{bmatrix}0\\ \mathbb 1\end{bmatrix}` has one
solution only when :math:`\begin{bmatrix}J_c\\T\end{bmatrix}` has full column rank. A planar
derivation :math:`(x, \theta)` of a robot that can also turn, or a level-body derivation
:math:`(v, \omega)` of a model whose body pitches, leaves a motion free: a pseudo-inverse
would fill it in with a made-up rate (the smallest velocity norm: a pitch rate of
:math:`2v/3r`), and the truth would be of no robot.

Such a file holds a coordinate where it says so: a model coordinate whose configuration is a
constant (written, or left out: 0), whose velocity no ``velocity_map`` entry uses and that is
not a drive wheel's angle is held at that constant, :math:`\dot c = 0` joining the
constraints, as a locked joint or a guide would hold it — but only where the document's
velocities and the rolling constraints leave it free (a representative configuration
:math:`x_0 = 0` of a coordinate the map moves is not held). A motion still free then is
refused, naming the coordinates it moves
(:class:`~wheeled_dyn.coordinates.spec.CoordinateSpecError`).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np
import sympy as sp

from ..coordinates.spec import CoordinateSet, CoordinateSpecError, model_symbols

#: Singular values below this fraction of the largest count as zero (the rank of [J_c; T]).
RANK_TOL = 1e-9
#: Document configurations the rank is taken at (the largest rank of them: a configuration
#: where the map is singular by chance does not hold a coordinate).
DRAWS = 3
#: Components of a free motion above this fraction of its largest name the coordinates it moves.
NAMED_FRACTION = 0.1


def _rank(M: np.ndarray) -> int:
    s = np.linalg.svd(M, compute_uv=False)
    return int((s > RANK_TOL * max(float(s.max(initial=0.0)), 1e-300)).sum())


def _constants(cs: CoordinateSet, coordinates: Sequence[str]
               ) -> list[tuple[int, str, sp.Expr, bool]]:
    r"""The model coordinates whose configuration in ``cs`` is a constant (no document
    position in it): (index, name, the constant, whether the velocity map uses its rate)."""
    _, mv = model_symbols(coordinates)
    mapped = set().union(*(e.free_symbols for e in (cs.velocity_map or {}).values()))
    doc_q = set(cs.position_symbols())
    out = []
    for k, name in enumerate(coordinates):
        config = sp.sympify(cs.configuration.get(name, 0))
        if not config.free_symbols & doc_q:
            out.append((k, name, config, mv[k] in mapped))
    return out


def held_coordinates(cs: CoordinateSet, coordinates: Sequence[str],
                     stacked: Callable[[np.ndarray], np.ndarray], wheels: Sequence[int] = (),
                     seed: int = 0) -> tuple[str, ...]:
    r"""The model ``coordinates`` ``cs`` holds (module docstring), in the model's order.

    ``stacked(q_doc)`` is :math:`[J_c; T]` at the model configuration of the document
    positions ``q_doc`` (one column per model velocity, in the order of ``coordinates``).
    The drive wheels' angles (indices ``wheels``) are never held: their configuration is a
    representative one, and holding a wheel on its axle would make up a constraint (a
    free pitch held through a locked wheel). Raises :class:`CoordinateSpecError` when a
    motion is free even with the coordinates held."""
    rng = np.random.default_rng(seed)
    draws = [stacked(rng.uniform(-1.0, 1.0, len(cs.positions))) for _ in range(DRAWS)]
    draws = [M for M in draws if np.all(np.isfinite(M))] or draws[:1]
    nv = draws[0].shape[1]
    if max(_rank(M) for M in draws) >= nv:
        return ()
    held: list[int] = []

    def rank(rows: list[int]) -> int:
        return max(_rank(np.vstack([M, np.eye(nv)[rows]])) for M in draws)

    for k, _name, _config, mapped in _constants(cs, coordinates):
        if k in wheels or mapped:
            continue
        if rank([*held, k]) > rank(held):
            held.append(k)
            if rank(held) >= nv:
                return tuple(coordinates[i] for i in held)
    M = np.vstack([draws[0], np.eye(nv)[held]])
    free = np.linalg.svd(M)[2][-1]
    named = [coordinates[int(i)] for i in np.flatnonzero(np.abs(free) > NAMED_FRACTION
                                                    * np.abs(free).max())]
    raise CoordinateSpecError(
        cs.name, "velocity_map",
        f"the file's velocities and the rolling constraints leave a motion of the model free "
        f"(it moves {', '.join(named)}): map its velocity in velocity_map, or hold a coordinate "
        "it moves by a constant configuration whose velocity the map does not use")


def check_representatives(cs: CoordinateSet, coordinates: Sequence[str],
                          moved_at: Callable[[int], float]) -> None:
    r"""A model coordinate whose rate the velocity map uses while its configuration is a
    constant is a *representative* value: right only where the truth does not depend on it
    (:math:`x_0, y_0`, the heading of a body on flat ground). ``moved_at(k)`` is how much the
    truth (its inertia matrix and gravity forces, relative to their size) changes when model
    coordinate ``k`` moves from the set's configuration. One on which it depends is refused
    naming it: a file mapping the pitch rate (``dtheta = "dphi"``) but leaving ``phi`` out of
    its configuration was compared at phi = 0 only, and its equations at 0 agreed."""
    for k, name, config, mapped in _constants(cs, coordinates):
        if mapped and moved_at(k) > DEPENDS_TOL:
            raise CoordinateSpecError(
                cs.name, f"configuration.{name}",
                f"{name} moves (the velocity map uses d{name}) but its configuration is the "
                f"constant {config}, and the truth depends on it: write {name} as a function "
                "of the document's positions")


#: A relative change of the truth above this, when a coordinate moves, is a dependence.
DEPENDS_TOL = 1e-9


__all__ = ["check_representatives", "held_coordinates"]
