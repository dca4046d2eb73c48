r"""Benchmark of the ground-truth chain (issue "Ground truth"). Prints ratios measured in one run.

1. Reduced WIP terms A, C, Q, B in seed 001's coordinates per state, against raw Pinocchio
   ``crba + computeCoriolisMatrix + computeGeneralizedGravity`` on the full 6-coordinate model
   (target: ratio <= 3).
2. Exact Christoffel tensor for Baxter (19 joints), the largest fixed-base robot of
   example-robot-data (target <= 1 ms), against one ``crba`` call.
3. Constrained WIP simulation (zero input, from a tilt, 1 kHz output) speed as a multiple of
   real time (target >= 30; the closed-form ``simulate_fast`` of ``bench_simulation.py`` has
   the target of 100), with its energy drift.

Run: ``.venv/bin/python benchmarks/bench_core.py``
"""

from __future__ import annotations

import time

import numpy as np
import pinocchio as pin

from wheeled_dyn import CoordinateMap, builtin_coordinate_set, christoffel_tensor, load_model, simulate
from wheeled_dyn.paths import example_robot_data_share

SEED = 7
N_STATES = 2000


def per_call(fn, args_list, repeat: int = 3) -> float:
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        for args in args_list:
            fn(*args)
        best = min(best, (time.perf_counter() - t0) / len(args_list))
    return best


def main() -> None:
    rng = np.random.default_rng(SEED)
    wm = load_model("wip")
    model, data = wm.model, wm.model.createData()
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "seed001"))
    full_states = [(rng.uniform(-3, 3, 6), rng.normal(size=6)) for _ in range(N_STATES)]
    doc_states = [(rng.uniform(-3, 3, 3), rng.normal(size=3)) for _ in range(N_STATES)]

    def raw(q, v):
        pin.crba(model, data, q)
        pin.computeCoriolisMatrix(model, data, q, v)
        pin.computeGeneralizedGravity(model, data, q)

    t_raw = per_call(raw, full_states)
    t_red = per_call(cmap.terms, doc_states)
    qd, nd = np.array([s[0] for s in doc_states]), np.array([s[1] for s in doc_states])
    t_batch = per_call(cmap.terms_batch, [(qd, nd)]) / N_STATES
    print(f"1. raw Pinocchio on the full model (crba+coriolis+gravity): {t_raw * 1e6:6.1f} us/state")
    print(f"   reduced WIP A,C,Q,B,h in (dx,dpsi,dphi), one state per call: {t_red * 1e6:6.1f} us"
          f"  ratio {t_red / t_raw:5.1f}x")
    print(f"   the same, {N_STATES} states per call (terms_batch):          {t_batch * 1e6:6.1f} us"
          f"  ratio {t_batch / t_raw:5.1f}x (target <= 3x)")

    share = example_robot_data_share()
    baxter = pin.buildModelFromUrdf(str(share / "example-robot-data/robots/baxter_description/urdf/baxter.urdf"))
    bdata = baxter.createData()
    qs = [(pin.randomConfiguration(baxter),) for _ in range(200)]
    t_c = per_call(lambda q: christoffel_tensor(baxter, q), qs)
    t_m = per_call(lambda q: pin.crba(baxter, bdata, q), qs)
    print(f"2. exact Christoffel tensor, Baxter ({baxter.nv} joints): {t_c * 1e3:6.3f} ms "
          f"(target <= 1 ms); crba {t_m * 1e6:5.1f} us; ratio {t_c / t_m:5.0f}x")

    q0 = cmap.model_configuration(np.array([0.0, 0.0, 0.3]))
    duration = 5.0
    t0 = time.perf_counter()
    traj = simulate(cmap, q0, np.array([0.0, 0.0, 0.0]), duration, rate=1000.0, rtol=1e-8, atol=1e-10)
    wall = time.perf_counter() - t0
    print(f"3. constrained WIP simulation, {duration:.0f} s at 1 kHz output: {wall:6.2f} s wall, "
          f"{duration / wall:6.1f}x real time (target >= 30x); energy drift "
          f"{traj.relative_energy_drift():.1e} (wall time includes the energy of each sample)")


if __name__ == "__main__":
    from doc_block import recorded
    with recorded(__file__):      # its block of docs/benchmarks.md
        main()
