r"""Benchmark of tilting-wheel rolling (issue "Rolling in general"). Prints ratios measured in
one run.

1. Reduced terms A, C, Q, B, h of the bicycle (roll, steer, rear-wheel rates) and of Upkie
   (pitch, hips, knees, left wheel) per state, one state per call and N states per call
   (``wheel_batch.terms_batch``), against raw Pinocchio ``crba + computeCoriolisMatrix +
   computeGeneralizedGravity`` on the same full model (target: ratio <= 5). Timings are the
   best of several interleaved repetitions (the machine is shared).
2. The bicycle's eigenvalues over 100 speeds (0-10 m/s): M, C1, K0, K2 from two linearisations
   of the true reduced dynamics, then one batched eigenvalue call (target < 1 s); and, for
   reference, 100 fresh linearisations.
3. Zero-input simulation of the rolling coin and of the bicycle at 5 m/s: speed as a multiple of
   real time, energy drift and contact drift before projection.

Run: ``.venv/bin/python benchmarks/bench_rolling.py``
"""

from __future__ import annotations

import time

import numpy as np
import pinocchio as pin

from wheeled_dyn.constraints.rolling_linear import linearise, speed_form
from wheeled_dyn.constraints.wheel_batch import terms_batch
from wheeled_dyn.constraints.wheel_reduction import RollingReduction
from wheeled_dyn.models.registry import load_model

SEED = 7
N_STATES = 1000
REPEAT = 5


def best(fn, repeat: int = REPEAT) -> float:
    out = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        out = min(out, time.perf_counter() - t0)
    return out


def _states(name: str, rng):
    wm = load_model(name)
    if name == "bicycle":
        red = RollingReduction(wm, ("roll", "steer", "rear_wheel"), ("z", "pitch"))
    else:
        red = RollingReduction(wm, ("pitch", "left_hip", "left_knee", "right_hip",
                                    "right_knee", "left_wheel"), ("z0", "roll"))
    qs = []
    for _ in range(N_STATES):
        q = np.zeros(wm.nv)
        q[2] = 0.3 if name == "bicycle" else 0.5
        q[[0, 1, 3]] = rng.uniform(-1, 1, 3)
        if name == "bicycle":
            q[wm.index("roll")] = rng.uniform(-0.3, 0.3)
            q[wm.index("steer")] = rng.uniform(-0.5, 0.5)
        else:
            q[4] = rng.uniform(-0.3, 0.3)
            q[[6, 7, 9, 10]] = rng.uniform(-0.6, 0.6, 4)
        qs.append(red.on_ground(q))
    return wm, red, np.array(qs), rng.normal(size=(N_STATES, red.n))


def bench_terms(name: str, rng) -> None:
    wm, red, qs, nus = _states(name, rng)
    model, data = wm.model, wm.model.createData()
    vs = np.array([red.velocity_matrix(q) @ nu for q, nu in zip(qs, nus)])
    single = qs[:200], nus[:200]

    def raw():
        for q, v in zip(qs, vs):
            pin.crba(model, data, q)
            pin.computeCoriolisMatrix(model, data, q, v)
            pin.computeGeneralizedGravity(model, data, q)

    def one():
        for q, nu in zip(*single):
            red.terms(q, nu)

    t_raw, t_one, t_batch = np.inf, np.inf, np.inf
    for _ in range(REPEAT):                     # interleaved: the same load on all three
        t_raw = min(t_raw, best(raw, 1) / N_STATES)
        t_one = min(t_one, best(one, 1) / len(single[0]))
        t_batch = min(t_batch, best(lambda: terms_batch(red, qs, nus), 1) / N_STATES)
    print(f"1. {name} ({wm.nv} joints, {red.m} contact rows, {red.n} velocities)")
    print(f"   raw Pinocchio crba+coriolis+gravity, full model: {t_raw * 1e6:7.1f} us/state")
    print(f"   reduced terms, one state per call:               {t_one * 1e6:7.1f} us"
          f"  ratio {t_one / t_raw:6.1f}x")
    print(f"   reduced terms, {N_STATES} states per call:          {t_batch * 1e6:7.1f} us"
          f"  ratio {t_batch / t_raw:6.1f}x (target <= 5x)")


def bench_sweep() -> None:
    wm = load_model("bicycle")
    red = RollingReduction(wm, ("roll", "steer", "rear_wheel"), ("z", "pitch"))
    q0 = red.on_ground(np.zeros(wm.nv))
    unit = np.array([0.0, 0.0, 1.0 / 0.3])
    speeds = np.linspace(0.0, 10.0, 100)

    def sweep():
        form, _, _ = speed_form(red, q0, ("roll", "steer"), unit, (0, 1), 9.81)
        return form.eigenvalues(speeds)

    t_sweep = best(sweep)
    ev = sweep()
    stable = speeds[ev.real.max(axis=1) < 0]

    def fresh():
        for v in speeds:
            linearise(red, q0, ("roll", "steer"), unit * v)

    t_fresh = best(fresh, 1)
    print(f"2. bicycle eigenvalues at 100 speeds: {t_sweep * 1e3:7.1f} ms (target < 1000 ms);"
          f" 100 fresh linearisations {t_fresh * 1e3:7.1f} ms")
    print(f"   stable speeds on the grid: {stable.min():.3f} .. {stable.max():.3f} m/s")


def bench_simulation() -> None:
    coin = load_model("rolling_coin")
    red = RollingReduction(coin, ("psi", "phi", "theta"), ("z",))
    q = np.zeros(coin.nv)
    q[4] = 0.2
    duration = 2.0
    t0 = time.perf_counter()
    red.simulate(q, np.array([1.0, 0.5, 8.0]), 0.05, rate=100)    # SciPy's first import
    warm = time.perf_counter() - t0
    t0 = time.perf_counter()
    traj = red.simulate(q, np.array([1.0, 0.5, 8.0]), duration, rate=100)
    wall = time.perf_counter() - t0
    print(f"3. coin, {duration} s zero input: {duration / wall:6.1f}x real time, energy drift "
          f"{traj.relative_energy_drift():.1e}, contact drift {traj.drift:.1e} m (after a "
          f"0.05 s run that imports the integrator: {warm:.2f} s)")
    bike = load_model("bicycle")
    red = RollingReduction(bike, ("roll", "steer", "rear_wheel"), ("z", "pitch"))
    q = red.on_ground(np.zeros(bike.nv))
    t0 = time.perf_counter()
    traj = red.simulate(q, np.array([0.05, 0.0, 5.0 / 0.3]), duration, rate=100)
    wall = time.perf_counter() - t0
    print(f"   bicycle at 5 m/s, {duration} s: {duration / wall:6.1f}x real time, energy drift "
          f"{traj.relative_energy_drift():.1e}, contact drift {traj.drift:.1e} m")


def main() -> None:
    rng = np.random.default_rng(SEED)
    bench_terms("bicycle", rng)
    try:
        bench_terms("upkie", rng)
    except Exception as exc:          # upkie-description missing
        print(f"1. upkie skipped: {exc}")
    bench_sweep()
    bench_simulation()


if __name__ == "__main__":
    from doc_block import recorded
    with recorded(__file__):      # its block of docs/benchmarks.md
        main()
