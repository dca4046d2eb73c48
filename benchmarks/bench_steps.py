r"""Benchmark of the derivation steps (issue "Every step of a derivation"): what the seed-001
step files (kinematics (16)-(19), (54)-(69), the appendix's code and F1-F3, the constraints
(33), the claims) add to the default comparison, measured in the same run after a warm-up:
the default comparison of the group's derivations in one process with the steps (from cold
step caches), then without them (baseline), and the steps alone. Wall-clock and CPU time (the CPU time is the
fair measure on a shared machine).

Run: ``.venv/bin/python benchmarks/bench_steps.py``
"""

from __future__ import annotations

import time

from wheeled_dyn.compare.steps import chain as step_module
from wheeled_dyn.cli.compare_cmd import DEFAULT_PARAM_SETS, DEFAULT_SAMPLES, run_comparison
from wheeled_dyn.compare.steps.records import compare_steps
from wheeled_dyn.derivations import builtin_derivations, load_derivation
from wheeled_dyn.derivations.builtin import BUILTIN_DIR, STEPS_SUFFIX


def _timed(fn):
    t0, c0 = time.perf_counter(), time.process_time()
    out = fn()
    return out, time.perf_counter() - t0, time.process_time() - c0


def main() -> None:
    files = builtin_derivations("seed001")
    with_steps = step_module.with_steps
    run = lambda: run_comparison(files, DEFAULT_SAMPLES, DEFAULT_PARAM_SETS)   # noqa: E731
    no_steps = lambda d, compare, seed=0, parallel=False: compare(d)          # noqa: E731
    step_module.with_steps = no_steps
    run()                                    # warm-up: model loading, closed-form cache
    step_module.with_steps = with_steps
    _, full, full_cpu = _timed(run)          # the steps from cold step caches
    step_module.with_steps = no_steps
    _, base, base_cpu = _timed(run)
    step_module.with_steps = with_steps
    steps = sorted((BUILTIN_DIR / "seed001").glob("*" + STEPS_SUFFIX))
    n, alone, alone_cpu = _timed(lambda: sum(len(compare_steps(load_derivation(p)))
                                             for p in steps))
    print(f"baseline, default comparison of {len(files)} derivations in one process without "
          f"the steps: {base:.2f} s ({base_cpu:.2f} s CPU)")
    print(f"with the steps of {len(steps)} step files: {full:.2f} s ({full_cpu:.2f} s CPU); "
          f"with / without = {full_cpu / base_cpu:.2f} (CPU)")
    print(f"the steps alone ({n} component records, warm caches): {alone:.2f} s "
          f"({alone_cpu:.2f} s CPU)")


if __name__ == "__main__":
    from doc_block import recorded
    with recorded(__file__):      # its block of docs/benchmarks.md
        main()
