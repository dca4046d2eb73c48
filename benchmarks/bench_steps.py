r"""Benchmark of the derivation steps (issue "Every step of a derivation"): what the seed-001
step files (kinematics (16)-(19), (54)-(69), the appendix's code and F1-F3, the constraints
(33), the claims) add to the default comparison, measured in the same run: the steps alone
(every ``*_steps.toml`` of the group, one process, from a cold cache) and the default
comparison of the group's derivations in one process (which includes them), wall-clock and CPU
time (the CPU time is the fair measure on a shared machine).

Run: ``.venv/bin/python benchmarks/bench_steps.py``
"""

from __future__ import annotations

import time

from wheeled_dyn.compare.commands import DEFAULT_PARAM_SETS, DEFAULT_SAMPLES, run_comparison
from wheeled_dyn.compare.step_records import compare_steps
from wheeled_dyn.derivations import builtin_derivations, load_derivation
from wheeled_dyn.derivations.builtin import BUILTIN_DIR, STEPS_SUFFIX


def main() -> None:
    steps = sorted((BUILTIN_DIR / "seed001").glob("*" + STEPS_SUFFIX))
    t0, c0 = time.perf_counter(), time.process_time()
    n = sum(len(compare_steps(load_derivation(p))) for p in steps)
    alone, alone_cpu = time.perf_counter() - t0, time.process_time() - c0
    files = builtin_derivations("seed001")
    t0, c0 = time.perf_counter(), time.process_time()
    run_comparison(files, DEFAULT_SAMPLES, DEFAULT_PARAM_SETS)
    serial, serial_cpu = time.perf_counter() - t0, time.process_time() - c0
    print(f"steps alone: {len(steps)} step files, {n} component records: {alone:.2f} s "
          f"({alone_cpu:.2f} s CPU)")
    print(f"default comparison of {len(files)} derivations in one process, steps included: "
          f"{serial:.2f} s ({serial_cpu:.2f} s CPU); steps / comparison = "
          f"{alone_cpu / serial_cpu:.0%} of the CPU time")


if __name__ == "__main__":
    main()
