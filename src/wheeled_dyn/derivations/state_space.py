r"""The ``[state_space]`` table: a document's equations as a first-order system, as control
papers print them.

A state :math:`x` lists each of the document's positions and each of their velocities once,
in the document's order (``state = ["x", "theta", "dx", "dtheta"]``). The system is either

- linear, :math:`\dot x = A_s x + B_s u` (keys ``A`` and ``B``), about the point the file
  declares in ``[assumes] linearised_about``: each position's entry of :math:`x` is its
  deviation from that point (:math:`q - q_0`, 0 for a position the point does not give), a
  velocity's entry the velocity itself; or
- nonlinear, :math:`\dot x = f(x, u)` (key ``f``, one expression per entry of the state).

``inputs`` lists the document's inputs in the order of :math:`B_s`'s columns (by default the
symbols with ``input = true``, in the order the file declares them).

Each row whose entry is a velocity :math:`\dot q_i` is an equation solved for its
acceleration, :math:`\ddot q_i = (A_s x + B_s u)_k` — the comparison judges these like any
equations (by their equivalence to the true ones, with the linearised truth where a point is
declared). Each row whose entry is a position :math:`q_i` states that position's rate; it is
right when it is the velocity :math:`\dot q_i` of the state, and that is checked here, on the
document alone (:class:`StateRate`): a wrong one makes the system wrong whatever its
equations.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import sympy

from .matrices import MatrixReader

if TYPE_CHECKING:  # pragma: no cover
    from .loader import _Loader

#: Keys of ``[state_space]``.
STATE_SPACE_KEYS: tuple[str, ...] = ("state", "A", "B", "f", "inputs")
#: Where the table's element labels start.
TABLE = "state_space"


@dataclass(frozen=True)
class StateRate:
    r"""Row ``row`` (0-based) of a state-space form whose state entry is the position
    ``position``: the rate the document gives it (``written``, SymPy text) and whether that
    is its velocity ``velocity`` (None where the row holds a place the text lost)."""

    row: int
    position: str
    velocity: str
    written: str
    agrees: bool | None

    @property
    def label(self) -> str:
        r"""How the reports name the row: ``"state row 1 (the rate of x)"``."""
        return f"state row {self.row + 1} (the rate of {self.position})"


@dataclass(frozen=True)
class StateSpace:
    r"""What a ``[state_space]`` table says: the equations its velocity rows are (one per
    position, in the order of the positions, each solved for its acceleration), its position
    rows' rates, and the labels of the places the text lost."""

    equations: tuple[sympy.Eq, ...]
    rates: tuple[StateRate, ...]
    missing: tuple[str, ...]
    #: the state as the document orders it, and the row (0-based) each equation is
    state: tuple[str, ...] = ()
    rows: tuple[int, ...] = ()
    #: x' = A x + B u (else x' = f(x, u))
    linear: bool = True

    def note(self) -> str:
        r"""How the equations compared are the document's rows, for the reports."""
        where = ", ".join(f"equation {i + 1} is row {k + 1} ({self.state[k]}')"
                          for i, k in enumerate(self.rows))
        if not self.linear:
            return (f"the state-space form x' = f(x, u), x = ({', '.join(self.state)}), is "
                    f"compared as its velocity rows solved for the accelerations: {where}")
        return (f"the state-space form x' = A x + B u, x = ({', '.join(self.state)}), is "
                f"compared as its velocity rows solved for the accelerations: {where}; in "
                "equation i, K[i,j] is −A[row, column of position j], B[i,j] is B[row, j]")


def read_state_space(ld: "_Loader", table: Mapping[str, Any],
                     coordinates: tuple[tuple[sympy.Symbol, sympy.Symbol, sympy.Symbol], ...],
                     inputs: tuple[sympy.Symbol, ...],
                     point: Mapping[str, float] | None) -> StateSpace:
    r"""Read ``[state_space]`` (module docstring). ``coordinates``: per position (its symbol,
    its velocity's, its acceleration's); ``inputs``: the document's input symbols in their
    declared order; ``point``: ``[assumes] linearised_about`` (None where the file declares
    none). Errors name the file, the line and the key."""
    for key in table:
        if key not in STATE_SPACE_KEYS:
            raise ld.fail(f"{TABLE}.{key}", "unknown key; valid: " + ", ".join(STATE_SPACE_KEYS),
                          ld.line(TABLE, key))
    state = _state(ld, table.get("state"), coordinates)
    used = _inputs(ld, table.get("inputs"), inputs)
    reader = MatrixReader(ld, len(state), used, table=TABLE)
    if ("f" in table) == ("A" in table):
        raise ld.fail(TABLE, "give f (the nonlinear system) or A with B (the linear one), "
                      "one of them", ld.line(TABLE))
    if "f" in table:
        if "B" in table:
            raise ld.fail(f"{TABLE}.B", "B goes with A (x' = A x + B u); f holds the inputs "
                          "itself", ld.line(TABLE, "B"))
        rates = list(reader.grid("f", table["f"], len(state), 1, vector=True))
    else:
        rates = _linear(ld, reader, table, state, coordinates, used, point)
    return _split(state, rates, coordinates, tuple(reader.missing), "f" not in table)


def _state(ld: "_Loader", raw: Any, coordinates) -> tuple[sympy.Symbol, ...]:
    r"""The state as symbols: every position and every velocity exactly once."""
    names = {str(s): s for c in coordinates for s in c[:2]}
    if not isinstance(raw, list) or not all(isinstance(x, str) for x in raw):
        raise ld.fail(f"{TABLE}.state", "expected a list of the positions and velocities, "
                      f"e.g. {sorted(names)!r}", ld.line(TABLE, "state"))
    for x in raw:
        if x not in names:
            raise ld.fail(f"{TABLE}.state", f"{x!r} is neither a position nor a velocity of "
                          "the document; valid: " + ", ".join(names), ld.line(TABLE, "state"))
    lacking = [n for n in names if raw.count(n) != 1]
    if lacking:
        raise ld.fail(f"{TABLE}.state", f"{lacking[0]!r} appears {raw.count(lacking[0])} "
                      "times: the state lists every position and every velocity once",
                      ld.line(TABLE, "state"))
    return tuple(names[x] for x in raw)


def _inputs(ld: "_Loader", raw: Any, inputs: tuple[sympy.Symbol, ...]
            ) -> tuple[sympy.Symbol, ...]:
    r"""The inputs in the order of B's columns: ``inputs`` as given (declared inputs, each
    once), else as declared."""
    if raw is None:
        return inputs
    known = {str(u): u for u in inputs}
    if not isinstance(raw, list) or not all(isinstance(x, str) for x in raw) or \
            sorted(raw) != sorted(known):
        raise ld.fail(f"{TABLE}.inputs", "expected the document's inputs (symbols with input "
                      "= true), each once, in the order of B's columns: "
                      + (", ".join(known) or "the file declares none"), ld.line(TABLE, "inputs"))
    return tuple(known[x] for x in raw)


def _linear(ld: "_Loader", reader: MatrixReader, table: Mapping[str, Any],
            state: tuple[sympy.Symbol, ...], coordinates, inputs: tuple[sympy.Symbol, ...],
            point: Mapping[str, float] | None) -> list[sympy.Expr]:
    r"""The rates :math:`A_s x + B_s u`, each position's entry of :math:`x` its deviation from
    the declared point. A velocity's rate linear in a velocity (damping, a motor's back-EMF)
    is an error naming the entry: :math:`A\ddot q + C\dot q + Q = Bu` has no such term."""
    if point is None:
        raise ld.fail(f"{TABLE}.A", "x' = A x + B u is linear about a point: declare it in "
                      "[assumes] linearised_about (each position's value there; the state's "
                      "positions are the deviations from it)", ld.line(TABLE, "A"))
    n = len(state)
    A = reader.grid("A", table["A"], n, n)
    if "B" in table and not inputs:
        raise ld.fail(f"{TABLE}.B", "B needs document inputs (symbols with input = true)",
                      ld.line(TABLE, "B"))
    B = reader.grid("B", table["B"], n, len(inputs)) if "B" in table \
        else sympy.zeros(n, len(inputs))
    reader.without_inputs("A", A)
    positions = {c[0] for c in coordinates}
    for k, j in ((k, j) for k in range(n) for j in range(n)):
        if state[k] not in positions and state[j] not in positions and A[k, j] != 0:
            raise ld.fail(f"{TABLE}.A[{k + 1},{j + 1}]", f"{state[k]}' linear in the velocity "
                          f"{state[j]} (a damping, a motor's back-EMF): the equations of motion "
                          "A q'' + C q' + Q = B u have no such term", ld.line(TABLE, "A"))
    x = sympy.Matrix([s - point_value(point.get(str(s), 0.0)) if s in positions else s
                      for s in state])
    u = sympy.Matrix(inputs)
    rates = A * x + (B * u if inputs else sympy.zeros(n, 1))
    return [sympy.expand(r) for r in rates]


def point_value(x: float) -> sympy.Expr:
    r"""A linearisation point's coordinate as an exact number: a rational multiple of
    :math:`\pi` where the float is one to its last digit (``3.141592653589793`` as
    :math:`\pi`, so :math:`\cos\pi = -1` in the truth shown), else the rational it is."""
    near = sympy.nsimplify(x, [sympy.pi], tolerance=1e-15)
    if near.has(sympy.pi) and near.is_number and float(near) == x:
        return near
    return sympy.nsimplify(x, rational=True)


def _split(state: Sequence[sympy.Symbol], rates: Sequence[sympy.Expr], coordinates,
           missing: tuple[str, ...], linear: bool) -> StateSpace:
    r"""Velocity rows → equations (in the order of the positions); position rows → rates."""
    by_velocity = {c[1]: c for c in coordinates}
    by_position = {c[0]: c for c in coordinates}
    solved: dict[sympy.Symbol, tuple[int, sympy.Eq]] = {}
    checked = []
    for k, (s, rate) in enumerate(zip(state, rates)):
        if s in by_velocity:
            q, v, a = by_velocity[s]
            solved[q] = (k, sympy.Eq(a, rate, evaluate=False))
            continue
        q, v, _ = by_position[s]
        agrees = None if rate.has(sympy.nan) else sympy.simplify(rate - v) == 0
        checked.append(StateRate(k, str(q), str(v), sympy.sstr(rate), agrees))
    return StateSpace(tuple(solved[c[0]][1] for c in coordinates), tuple(checked), missing,
                      tuple(map(str, state)), tuple(solved[c[0]][0] for c in coordinates),
                      linear)


__all__ = ["STATE_SPACE_KEYS", "StateRate", "StateSpace", "point_value", "read_state_space"]
