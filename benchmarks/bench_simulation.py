r"""Constrained WIP simulation: the closed-form right-hand side (``simulate_fast``) against the
Pinocchio-backed one (``simulate``), in one run.

Scenario: seed 001's WIP (default parameters) released from a tilt of 0.3 rad at rest, zero
input, 10 s of motion sampled at 1 kHz (10 001 samples): the body falls and swings under the
axle, the wheels roll. Reported for each integrator: wall time (including the energy of every
sample), speed as a multiple of real time (target >= 100x for the fast one, >= 30x for the
Pinocchio-backed one), relative energy
drift (target <= 1e-6 over 10 s); then the agreement of the two trajectories. The fast one's
one-off cost (symbolic derivation into an empty cache, compilation) is reported apart.

Run: ``.venv/bin/python benchmarks/bench_simulation.py``.
"""

from __future__ import annotations

import os
import sys
import tempfile
import time

import numpy as np
import scipy
import sympy as sp

from wheeled_dyn import CoordinateMap, builtin_coordinate_set, load_model, simulate
from wheeled_dyn.simulate.fast import FAST_ATOL, FAST_RTOL, fast_model, simulate_fast
from wheeled_dyn.simulate.reduced import ATOL, RTOL

DURATION, RATE, TILT = 10.0, 1000.0, 0.3
#: Targets of the issue.
SPEED_TARGET, DRIFT_TARGET = 100.0, 1e-6
#: The Pinocchio-backed simulation's target (times real time).
PINOCCHIO_TARGET = 30.0
REPEAT = 3


def timed(f, *args, **kw):
    t0 = time.perf_counter()
    out = f(*args, **kw)
    return out, time.perf_counter() - t0


def main() -> int:
    wm = load_model("wip")
    cs = builtin_coordinate_set(wm, "seed001")
    cmap = CoordinateMap(wm, cs)
    q0 = cmap.model_configuration(np.array([0.0, 0.0, TILT]))
    nu0 = np.zeros(3)

    previous = os.environ.get("WHEELED_DYN_CACHE")
    with tempfile.TemporaryDirectory() as root:
        os.environ["WHEELED_DYN_CACHE"] = root
        try:
            fm, t_build = timed(fast_model, wm, cs)
        finally:
            if previous is None:
                os.environ.pop("WHEELED_DYN_CACHE")
            else:
                os.environ["WHEELED_DYN_CACHE"] = previous
    rhs_args = ([*q0, 0.1, 0.2, 0.3], [0.0, 0.0])
    n_calls = 20000
    t0 = time.perf_counter()
    for _ in range(n_calls):
        fm.rhs(*rhs_args)
    t_rhs = (time.perf_counter() - t0) / n_calls

    fast, t_fast = None, np.inf
    for _ in range(REPEAT):
        traj, t = timed(simulate_fast, wm, cs, q0, nu0, DURATION, RATE)
        if t < t_fast:
            fast, t_fast = traj, t
    same, t_same = timed(simulate_fast, wm, cs, q0, nu0, DURATION, RATE, rtol=RTOL, atol=ATOL)
    slow, t_slow = timed(simulate, cmap, q0, nu0, DURATION, RATE)

    d_fast, d_slow = fast.relative_energy_drift(), slow.relative_energy_drift()
    speed_fast, speed_slow = DURATION / t_fast, DURATION / t_slow
    def agreement(a, b):
        return (np.abs(a.q - b.q).max(), np.abs(a.nu - b.nu).max(),
                np.abs(a.energy - b.energy).max() / abs(b.energy[0]))
    phi = fast.q[:, wm.index("phi")]

    print(f"constrained WIP (seed001 coordinates), tilt {TILT} rad, zero input, "
          f"{DURATION:.0f} s at {RATE:.0f} Hz output ({len(fast.t)} samples); scipy "
          f"{scipy.__version__}, sympy {sp.__version__}, python {sys.version.split()[0]}")
    print(f"  motion: phi from {phi[0]:.2f} to {phi[-1]:.2f} rad (range {np.ptp(phi):.2f}), "
          f"x0 range {np.ptp(fast.q[:, 0]):.3f} m")
    print(f"  fast, one-off: symbolic derivation (empty cache) + compile {t_build:6.2f} s; "
          f"right-hand side {t_rhs * 1e6:5.2f} us/call")
    print(f"  fast (closed forms, DOP853 rtol={FAST_RTOL:g} atol={FAST_ATOL:g}): "
          f"{t_fast:7.3f} s wall, {speed_fast:7.1f}x real time (target >= {SPEED_TARGET:g}x), "
          f"energy drift {d_fast:.1e} (target <= {DRIFT_TARGET:g})")
    print(f"  fast at Pinocchio's tolerances (rtol={RTOL:g} atol={ATOL:g}):     "
          f"{t_same:7.3f} s wall, {DURATION / t_same:7.1f}x real time, energy drift "
          f"{same.relative_energy_drift():.1e}")
    print(f"  Pinocchio (simulate, DOP853 rtol={RTOL:g} atol={ATOL:g}):         "
          f"{t_slow:7.3f} s wall, {speed_slow:7.1f}x real time (target >= "
          f"{PINOCCHIO_TARGET:g}x), energy drift {d_slow:.1e}")
    print(f"  speed fast / Pinocchio: {speed_fast / speed_slow:6.1f}x (same tolerances: "
          f"{t_slow / t_same:6.1f}x)")
    for label, a in (("fast", fast), ("fast, same tolerances", same)):
        dq, dnu, dE = agreement(a, slow)
        print(f"  agreement with Pinocchio over {DURATION:.0f} s ({label}): max |dq| {dq:.1e}, "
              f"max |dnu| {dnu:.1e}, max |dE|/E0 {dE:.1e}")
    ok = speed_fast >= SPEED_TARGET and d_fast <= DRIFT_TARGET and speed_slow >= PINOCCHIO_TARGET
    print(f"  targets: {'met' if ok else 'NOT met'}")
    return 0 if ok else 1


if __name__ == "__main__":
    from doc_block import recorded
    with recorded(__file__):      # its block of docs/benchmarks.md
        code = main()
    sys.exit(code)
