r"""Closed forms with intermediate variables (SYMORO-style, :mod:`wheeled_dyn.symbolic.tree`) of
trees of example-robot-data, against Pinocchio and SymPy measured in the same run.

For UR5 (6 joints) and TIAGo with its arm (the full 15-joint tree: planar base, torso, arm,
head, wheels), :func:`~wheeled_dyn.symbolic.tree.tree_dynamics`, and for the rolling reduction
of TIAGo that ``wheeled-dyn symbolic tiago`` prints
(:func:`~wheeled_dyn.symbolic.tree_wheeled.tree_wheeled`, standard parameters, 12 velocities):

- the derivation time (once, in process, after a warm-up on a one-joint model, from an empty
  SymPy cache) and the time to generate and compile the numeric code;
- operation counts of the generated code (:func:`~wheeled_dyn.symbolic.tree_code.operation_count`:
  intermediate variables, additions, multiplications, function calls), for the assignments
  alone (the figure the CLI prints) and with the outputs evaluated;
- the largest difference from Pinocchio at :data:`STATES` seeded random states, relative to the
  largest entry of each term (or 1): ``A`` against ``crba``, ``C`` against
  ``computeCoriolisMatrix``, the Christoffel symbols against
  :func:`wheeled_dyn.dynamics.christoffel_tensor`, ``Q`` against ``computeGeneralizedGravity``;
  for the reduction ``A, C, Q, h`` against the numeric reduction built on Pinocchio
  (:class:`wheeled_dyn.CoordinateMap` ``.terms``). Tolerance :data:`TOLERANCE`; the script
  prints OK or MISMATCH and exits with 1 on a mismatch. The full trees are also compared with
  Pinocchio on the model whose placements are made exact (``exact_model``): the URDFs write
  :math:`\pi/2` as ``1.57079632679`` (:math:`4.9\cdot10^{-12}` off), which the exact geometry
  rounds, so the first comparison cannot reach machine precision and the second shows what the
  code itself loses;
- the time of one numeric evaluation per state (best of :data:`REPEAT` passes over
  :data:`N_EVAL` states) of the generated code for ``A, C, Q`` (Python floats in and out), and
  of :func:`~wheeled_dyn.symbolic.tree_code.compile_terms` (``A, Q``, the dense Christoffel
  tensor and ``C`` as NumPy arrays), as a ratio to raw Pinocchio
  ``crba + computeCoriolisMatrix + computeGeneralizedGravity`` on the same model;
- ``wheeled-dyn symbolic tiago`` as a subprocess, wall time including start-up and printing,
  :data:`CLI_RUNS` times.

SymPy's ``LagrangesMethod`` and ``KanesMethod`` (the bodies of ``bench_symbolic.py``, built here
from the Pinocchio model with the same exact geometry; mass matrix and forcing, no
simplification) run on UR5 and on TIAGo's full tree, each in a child process stopped after
:data:`SYMPY_TIME_LIMIT` seconds, their time printed as a ratio to ``tree_dynamics``'s; when
one finishes, its mass matrix and forcing are checked against Pinocchio at a random state.
``LagrangesMethod`` is not run on TIAGo when it did not finish on UR5.

Run: ``.venv/bin/python benchmarks/bench_symbolic_tree.py``
"""

from __future__ import annotations

import multiprocessing as mp
import os
import subprocess
import sys
import time
from collections.abc import Callable, Sequence
from pathlib import Path

import numpy as np
import pinocchio as pin
import sympy as sp
from sympy.core.cache import clear_cache
from sympy.physics import mechanics as me

import wheeled_dyn as wd
from wheeled_dyn.coordinates import builtin_coordinate_set
from wheeled_dyn.dynamics import christoffel_tensor
from wheeled_dyn.models.registry import model_parameters
from wheeled_dyn.paths import example_robot_data_share
from wheeled_dyn.symbolic.exact import exact_model, exact_rotation, exact_translation
from wheeled_dyn.symbolic.kinematics import joint_kind
from wheeled_dyn.symbolic.parameters import named_parameters, numeric_parameters
from wheeled_dyn.symbolic.tree import TreeDynamics, tree_dynamics
from wheeled_dyn.symbolic.tree_code import (
    OperationCount, compile_assignments, compile_terms, operation_count)
from wheeled_dyn.symbolic.tree_wheeled import tree_wheeled

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_core import per_call  # noqa: E402  (seconds per call, best of passes)
from bench_symbolic import (  # noqa: E402  (the SymPy bodies and checks of the WIP benchmark)
    MechanicsSystem, body_parameters, kane_equations, lagrange_equations, numeric_equations)

SEED = 20261124
#: Random states of the check against Pinocchio.
STATES = 5
#: Largest difference from Pinocchio, relative to the largest entry of the term (or 1).
TOLERANCE = 1e-9
#: States per timing pass of the numeric evaluation, and passes (the best is kept).
N_EVAL = 200
REPEAT = 5
#: Runs of ``wheeled-dyn symbolic tiago``.
CLI_RUNS = 3
#: Wall-time limit of each SymPy derivation on UR5 (s), and of its numeric check afterwards.
SYMPY_TIME_LIMIT = 60.0
SYMPY_CHECK_LIMIT = 120.0
UR5_URDF = "example-robot-data/robots/ur_description/urdf/ur5_robot.urdf"


def timed(f: Callable, *args, **kw) -> tuple[object, float]:
    """``(f(*args, **kw), seconds)``, from an empty SymPy cache."""
    clear_cache()
    t0 = time.perf_counter()
    out = f(*args, **kw)
    return out, time.perf_counter() - t0


def relative_error(a, b) -> float:
    """Largest difference of ``a`` from ``b``, relative to the largest entry of ``b`` (or 1)."""
    a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    return float(np.abs(a - b).max()) / max(1.0, float(np.abs(b).max()))


def verdict(errors: dict[str, float]) -> str:
    worst = max(errors.values())
    return (", ".join(f"{k} {e:.1e}" for k, e in errors.items())
            + f" -> {'OK' if worst <= TOLERANCE else 'MISMATCH'}")


def pinocchio_terms(model: pin.Model, data: pin.Data) -> Callable:
    """Raw Pinocchio ``crba + computeCoriolisMatrix + computeGeneralizedGravity`` (the baseline)."""
    def raw(q: np.ndarray, v: np.ndarray) -> None:
        pin.crba(model, data, q)
        pin.computeCoriolisMatrix(model, data, q, v)
        pin.computeGeneralizedGravity(model, data, q)
    return raw


def has_float(assignments: Sequence[tuple[sp.Symbol, sp.Expr]]) -> bool:
    return any(e.has(sp.Float) for _, e in assignments)


def ops_line(label: str, ops: OperationCount) -> str:
    return f"   {label:<40} {ops}"


def tree_errors(model: pin.Model, n: int, f_terms: Callable, f_acq: Callable, p: np.ndarray
                ) -> dict[str, float]:
    """Largest relative differences of both generated forms from Pinocchio on ``model`` at
    :data:`STATES` seeded random states."""
    rng = np.random.default_rng(SEED)
    data = model.createData()
    pl = [float(x) for x in p]
    err = {"A": 0.0, "C": 0.0, "Christoffel": 0.0, "Q": 0.0}
    for _ in range(STATES):
        q = rng.uniform(-np.pi, np.pi, n)
        v = rng.uniform(-1.0, 1.0, n)
        A, Q, c, C = f_terms(q, v, p)
        A2, C2, Q2 = f_acq(list(q), list(v), pl)
        M = pin.crba(model, data, q)
        M = np.triu(M) + np.triu(M, 1).T
        Cp = pin.computeCoriolisMatrix(model, data, q, v)
        g = pin.computeGeneralizedGravity(model, data, q)
        err["A"] = max(err["A"], relative_error(A, M), relative_error(np.reshape(A2, (n, n)), M))
        err["C"] = max(err["C"], relative_error(C, Cp), relative_error(np.reshape(C2, (n, n)), Cp))
        err["Christoffel"] = max(err["Christoffel"],
                                 relative_error(c, christoffel_tensor(model, q)))
        err["Q"] = max(err["Q"], relative_error(Q, g), relative_error(Q2, g))
    return err


def bench_tree(title: str, model: pin.Model, names: Sequence[str] | None = None
               ) -> tuple[bool, float]:
    """Derivation, operation counts, check and evaluation time of ``tree_dynamics(model)``;
    prints its lines, returns (agreement, derivation seconds)."""
    td, t_derive = timed(tree_dynamics, model, coordinate_names=names)
    assert isinstance(td, TreeDynamics)
    n = td.n
    chris = [td.christoffel[i][j][k] for i in range(n) for j in range(n) for k in range(n)]
    Cmat = list(td.C())
    t0 = time.perf_counter()
    f_terms = compile_terms(td)
    f_acq = compile_assignments(td.assignments, td.q, td.qd, td.parameters,
                                [("A", list(td.A)), ("C", Cmat), ("Q", list(td.Q))])
    t_compile = time.perf_counter() - t0
    values = named_parameters(model)
    p = np.array([values[str(s)] for s in td.parameters])
    pl = [float(x) for x in p]

    err = tree_errors(model, n, f_terms, f_acq, p)
    err_exact = tree_errors(exact_model(model), n, f_terms, f_acq, p)
    ok = max(err.values()) <= TOLERANCE and max(err_exact.values()) <= TOLERANCE
    data = model.createData()

    erng = np.random.default_rng(SEED + 1)
    states = [(erng.uniform(-np.pi, np.pi, n), erng.uniform(-1.0, 1.0, n)) for _ in range(N_EVAL)]
    t_raw = per_call(pinocchio_terms(model, data), states, REPEAT)
    t_acq = per_call(f_acq, [(list(q), list(v), pl) for q, v in states], REPEAT)
    t_terms = per_call(f_terms, [(q, v, p) for q, v in states], REPEAT)

    print(f"{title}: {n} joints, {len(td.parameters)} parameters")
    print(f"   tree_dynamics (A, Q, Christoffel symbols): {t_derive:6.2f} s; code generated and "
          f"compiled (both forms below): {t_compile:5.2f} s; floats in the geometry: "
          f"{'yes' if has_float(td.assignments) else 'none'}")
    print(ops_line("operations, assignments alone:", operation_count(td.assignments)))
    print(ops_line("  with outputs A, Q, Christoffel:",
                   operation_count(td.assignments, list(td.A) + list(td.Q) + chris)))
    print(ops_line("  with outputs A, C, Q:",
                   operation_count(td.assignments, list(td.A) + Cmat + list(td.Q))))
    print(f"   against Pinocchio at {STATES} random states (relative): {verdict(err)}")
    print(f"   the same, placements of the Pinocchio model made exact: {verdict(err_exact)}")
    print(f"   raw Pinocchio crba+coriolis+gravity:                 {t_raw * 1e6:8.1f} us/state")
    print(f"   generated code A, C, Q (floats), one state per call: {t_acq * 1e6:8.1f} us"
          f"  ratio {t_acq / t_raw:6.1f}x")
    print(f"   compile_terms (A, Q, Christoffel, C as arrays):      {t_terms * 1e6:8.1f} us"
          f"  ratio {t_terms / t_raw:6.1f}x")
    return ok, t_derive


def pinocchio_system(model: pin.Model, g: float = 9.81) -> MechanicsSystem:
    r"""``model`` (revolute and prismatic joints) as frames and points of sympy.mechanics, with
    the exact placements of :mod:`wheeled_dyn.symbolic.exact`; velocities by
    ``v2pt_theory`` down the tree."""
    assert np.allclose(model.gravity.linear, [0.0, 0.0, -g])
    q = me.dynamicsymbols(f"q0:{model.nv}")
    N = me.ReferenceFrame("N")
    O = me.Point("O")
    O.set_vel(N, 0)
    frames, points = {0: N}, {0: O}
    bodies = []
    for j in range(1, model.njoints):
        lam = model.parents[j]
        Fp, Pp = frames[lam], points[lam]
        P = model.jointPlacements[j]
        Rp, pp = exact_rotation(P.rotation), exact_translation(P.translation)
        F0 = Fp if Rp == sp.eye(3) else Fp.orientnew(f"R{j}", "DCM", Rp)
        P0 = Pp.locatenew(f"O{j}", pp[0] * Fp.x + pp[1] * Fp.y + pp[2] * Fp.z)
        kind, a = joint_kind(model, j)
        axis = a[0] * F0.x + a[1] * F0.y + a[2] * F0.z
        qj = q[model.joints[j].idx_v]
        if kind == "revolute":
            F = F0.orientnew(f"F{j}", "Axis", (qj, axis))
            Pj = P0
            Pj.v2pt_theory(Pp, N, Fp)
        else:
            F = F0
            Pj = P0.locatenew(f"P{j}", qj * axis)
            Pj.set_vel(N, Pj.pos_from(O).dt(N))
        frames[j], points[j] = F, Pj
        bodies.append((F, Pj, body_parameters(model.names[j])))
    return MechanicsSystem(q, N, O, bodies, [s for *_, pis in bodies for s in pis], g)


def _sympy_child(method: str, model: pin.Model, qv: np.ndarray, vv: np.ndarray,
                 p: np.ndarray, conn) -> None:
    """Derives ``model``'s equations with SymPy's ``method``; sends the seconds, then the mass
    matrix and forcing at ``(qv, vv)``."""
    clear_cache()
    t0 = time.perf_counter()
    system = pinocchio_system(model)
    if method == "LagrangesMethod":
        M, F = lagrange_equations(system)
        speeds = [qi.diff() for qi in system.q]
    else:
        M, F, speeds = kane_equations(system)
    conn.send(time.perf_counter() - t0)
    conn.send(numeric_equations(M, F, system.q, speeds, system.params, qv, vv, p))
    conn.close()


def sympy_on(model: pin.Model, method: str) -> tuple[str, float | None, bool]:
    """One line: SymPy's ``method`` on ``model`` in a child process, stopped after
    :data:`SYMPY_TIME_LIMIT` s, its seconds (None when stopped) and False on a mismatch
    with Pinocchio (checked when it finishes: a wrong baseline fails the run too)."""
    rng = np.random.default_rng(SEED + 2)
    qv, vv = rng.uniform(-np.pi, np.pi, model.nv), rng.uniform(-1.0, 1.0, model.nv)
    p = np.concatenate([numeric_parameters(model)[j] for j in range(1, model.njoints)])
    ctx = mp.get_context("fork")
    parent, child = ctx.Pipe(duplex=False)
    proc = ctx.Process(target=_sympy_child, args=(method, model, qv, vv, p, child), daemon=True)
    t0 = time.perf_counter()
    proc.start()
    child.close()
    try:
        if not parent.poll(SYMPY_TIME_LIMIT):
            return (f"{method}: not finished within {SYMPY_TIME_LIMIT:.0f} s "
                    f"(stopped after {time.perf_counter() - t0:.0f} s)"), None, True
        seconds = parent.recv()
        if not parent.poll(SYMPY_CHECK_LIMIT):
            return (f"{method} (M, forcing; no simplification): {seconds:7.2f} s; its numeric "
                    f"check did not finish within {SYMPY_CHECK_LIMIT:.0f} s"), seconds, True
        Mn, Fn = parent.recv()
    except EOFError:
        proc.join()
        return (f"{method}: the child process ended without a result "
                f"(exit code {proc.exitcode})"), None, True
    finally:
        if proc.is_alive():
            proc.terminate()
        proc.join()
    data = model.createData()
    M = pin.crba(model, data, qv)
    M = np.triu(M) + np.triu(M, 1).T
    nle = pin.nonLinearEffects(model, data, qv, vv)
    err = {"mass matrix": relative_error(Mn, M), "forces": relative_error(Fn, -nle)}
    return (f"{method} (M, forcing; no simplification): {seconds:7.2f} s; {verdict(err)}",
            seconds, max(err.values()) <= TOLERANCE)


def sympy_lines(model: pin.Model, methods: Sequence[str], ours: float, name: str
                ) -> tuple[bool, bool]:
    """Prints SymPy's ``methods`` on ``model`` with their ratio to ``ours`` (seconds); returns
    (the first finished, every finished one agrees with Pinocchio)."""
    print(f"   sympy.physics.mechanics on {name} (same bodies, exact geometry; a child process, "
          f"limit {SYMPY_TIME_LIMIT:.0f} s each):")
    finished, agree = [], True
    for method in methods:
        line, seconds, ok = sympy_on(model, method)
        finished.append(seconds is not None)
        agree = agree and ok
        ratio = f"; ratio to tree_dynamics {seconds / ours:5.1f}x" if seconds else ""
        print(f"     {line}{ratio}")
    return finished[0], agree


def cli_runs() -> tuple[list[float], str]:
    r"""Wall times of ``wheeled-dyn symbolic tiago`` (a fresh process each) and its
    "derived in" line of the last run."""
    command = [str(Path(sys.executable).with_name("wheeled-dyn")), "symbolic", "tiago"]
    times, line = [], ""
    for _ in range(CLI_RUNS):
        t0 = time.perf_counter()
        out = subprocess.run(command, check=True, capture_output=True, text=True).stdout
        times.append(time.perf_counter() - t0)
        line = next((ln for ln in out.splitlines() if ln.startswith("derived in")), "")
    return times, line


def bench_reduction(tiago: wd.WheeledModel) -> tuple[bool, float]:
    """TIAGo's rolling reduction as ``wheeled-dyn symbolic tiago`` derives it."""
    cs = builtin_coordinate_set(tiago, None)
    red, t_derive = timed(tree_wheeled, tiago, cs, "standard")
    m = len(red.nu)
    outputs = [("A", list(red.A)), ("C", list(red.C)), ("Q", list(red.Q)), ("h", list(red.h))]
    t0 = time.perf_counter()
    f = compile_assignments(red.assignments, red.q, red.nu, red.parameters, outputs)
    t_compile = time.perf_counter() - t0
    values = {k.replace("(", "_").rstrip(")"): v for k, v in model_parameters(tiago).items()}
    pl = [float(values[str(s)]) for s in red.parameters]
    cmap = wd.CoordinateMap(tiago, cs)

    rng = np.random.default_rng(SEED)
    err = {"A": 0.0, "C": 0.0, "Q": 0.0, "h": 0.0}
    for _ in range(STATES):
        qd = rng.uniform(-np.pi, np.pi, len(red.q))
        nu = rng.uniform(-1.0, 1.0, m)
        A, C, Q, h = (np.array(x, dtype=float) for x in f(list(qd), list(nu), pl))
        q, v = cmap.state_from(dict(zip(cs.positions, qd)) | dict(zip(cs.velocities, nu)))
        t = cmap.terms(q, v)
        for key, ours, truth in (("A", A.reshape(m, m), t.A), ("C", C.reshape(m, m), t.C),
                                 ("Q", Q, t.Q), ("h", h, t.h)):
            err[key] = max(err[key], relative_error(ours, truth))
    ok = max(err.values()) <= TOLERANCE

    model, data = tiago.model, tiago.model.createData()
    erng = np.random.default_rng(SEED + 1)
    full = [(erng.uniform(-np.pi, np.pi, model.nv), erng.uniform(-1.0, 1.0, model.nv))
            for _ in range(N_EVAL)]
    doc = [(erng.uniform(-np.pi, np.pi, len(red.q)), erng.uniform(-1.0, 1.0, m))
           for _ in range(N_EVAL)]
    t_raw = per_call(pinocchio_terms(model, data), full, REPEAT)
    t_code = per_call(f, [(list(q), list(v), pl) for q, v in doc], REPEAT)
    t_num = per_call(cmap.terms, doc, REPEAT)

    print(f"3. TIAGo's rolling reduction (wheeled-dyn symbolic tiago: {cs.name} coordinates, "
          f"{len(red.q)} positions, {m} velocities, {len(red.parameters)} parameters)")
    print(f"   tree_wheeled (A, C, Q, B, h): {t_derive:6.2f} s; code generated and compiled: "
          f"{t_compile:5.2f} s; floats in the geometry: "
          f"{'yes' if has_float(red.assignments) else 'none'}")
    print(ops_line("operations, assignments alone:", operation_count(red.assignments)))
    print(ops_line("  with outputs A, C, Q, h:",
                   operation_count(red.assignments, [e for _, es in outputs for e in es])))
    print(f"   against the numeric reduction on Pinocchio (CoordinateMap.terms) at {STATES} "
          f"random states (relative): {verdict(err)}")
    print(f"   raw Pinocchio crba+coriolis+gravity, full model:     {t_raw * 1e6:8.1f} us/state")
    print(f"   generated code A, C, Q, h (floats), one state per call: {t_code * 1e6:5.1f} us"
          f"  ratio {t_code / t_raw:6.1f}x")
    print(f"   numeric reduction CoordinateMap.terms, one state:    {t_num * 1e6:8.1f} us"
          f"  ratio {t_num / t_raw:6.1f}x")
    return ok, t_derive


def main() -> int:
    share = example_robot_data_share()
    if share is None:
        print("example-robot-data is not installed: nothing to measure")
        return 1
    warm = pin.Model()
    warm.addJoint(0, pin.JointModelRY(), pin.SE3.Identity(), "warm")
    compile_terms(tree_dynamics(warm))          # imports warmed, not timed
    print(f"closed forms with intermediate variables, sympy {sp.__version__}, pinocchio "
          f"{pin.__version__}, python {sys.version.split()[0]}, {os.cpu_count()} cores; "
          f"tolerance {TOLERANCE:g}")
    ur5 = pin.buildModelFromUrdf(str(share / UR5_URDF))
    ok1, t_ur5 = bench_tree("1. UR5 (ur5_robot.urdf)", ur5)
    lagrange_finished, sym1 = sympy_lines(ur5, ("LagrangesMethod", "KanesMethod"), t_ur5, "UR5")
    tiago = wd.load_model("tiago")
    ok2, t_tiago = bench_tree("2. TIAGo with its arm (the full tree)", tiago.model,
                              tiago.coordinate_names)
    methods = ("LagrangesMethod", "KanesMethod") if lagrange_finished else ("KanesMethod",)
    _, sym2 = sympy_lines(tiago.model, methods, t_tiago, "TIAGo")
    if not lagrange_finished:
        print("     LagrangesMethod: not run (it did not finish on UR5's 6 joints within "
              f"{SYMPY_TIME_LIMIT:.0f} s above)")
    ok3, _ = bench_reduction(tiago)
    times, line = cli_runs()
    print(f"   wheeled-dyn symbolic tiago, wall incl. start-up and printing, {CLI_RUNS} runs: "
          f"{min(times):.2f} .. {max(times):.2f} s")
    print(f"   its last line: {line}")
    return 0 if ok1 and ok2 and ok3 and sym1 and sym2 else 1


if __name__ == "__main__":
    from doc_block import recorded
    with recorded(__file__):      # its block of docs/benchmarks.md
        code = main()
    sys.exit(code)
