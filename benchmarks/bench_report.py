r"""Benchmark of the default report (issue "Comparison report"): every seed-001 derivation,
1000 states × 5 parameter sets each, and the seed's hand-made table reproduced, on the
machine's cores as ``wheeled-dyn report`` runs it; then the derivations in one process; and
the time of the truth alone (Pinocchio, reduced, batched) for one coordinate set on the same
grid, all measured in the same run. A first report (not timed) fills the disk cache: the
closed forms, and the printed forms (compiled code, text and LaTeX of expressions,
simplified cells and residuals: :class:`~wheeled_dyn.disk_cache.DiskMemo`). No verdict is
kept there: every comparison is made again (``WHEELED_DYN_REUSE=forms``).

Then the commands as a user runs them (issue "Fast enough to iterate on"), wall time including
start-up, rendering and writing, with the results cache off (``WHEELED_DYN_REUSE=forms``: the
closed forms and the printed forms stay remembered), :data:`RUNS` times each:
``wheeled-dyn compare wip .../eq25_lagrange.toml`` (target < 1 s) and ``wheeled-dyn report``
(target < 3 s); and ``wheeled-dyn report`` once with an empty cache folder (the closed forms
derived, nothing printed before: a first run on a new machine). ``wheeled-dyn list`` and
``--help`` (target < 0.3 s) against the interpreter's own start-up (``python -c pass``). And
the check again after a derivation file is saved, as ``compare --watch`` makes it (the same
engine: the truth reused; the file's comparison, its step files', the reports written). And
the two commands with everything remembered (``WHEELED_DYN_REUSE=1``, after one run that
fills the cache: nothing changed since), as a check made again runs (issue 25: the signed
cache must not make them slower).

The package's modules are byte-compiled first, as ``./wd`` does before every command: a shell
that sets ``PYTHONDONTWRITEBYTECODE`` would otherwise compile every module changed since the
last compilation in every command timed.

The linear algebra libraries get one thread per process, as the command gives them
(:func:`wheeled_dyn.cli.main.one_thread_each`), for the figures measured in this process too.

Run: ``.venv/bin/python benchmarks/bench_report.py``
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from wheeled_dyn.cli.main import one_thread_each

one_thread_each(os.environ)      # as the command runs: one BLAS thread per process (before NumPy)

import numpy as np  # noqa: E402

from wheeled_dyn import CoordinateMap, builtin_coordinate_set, load_model
from wheeled_dyn.cli.compare_cmd import (DEFAULT_PARAM_SETS, DEFAULT_SAMPLES, compare_report,
                                          run_comparison)
from wheeled_dyn.derivations import builtin_derivations
from wheeled_dyn.derivations.builtin import BUILTIN_DIR

#: Runs of each command.
RUNS = 5


def _command_times(*args: str, runs: int = RUNS, env: dict | None = None,
                   reuse: str = "forms") -> list[float]:
    r"""Wall times of ``wheeled-dyn ARGS --out TMP`` (a fresh process each; results not
    reused, unless ``reuse="1"``: then after one run, not timed, that stores them)."""
    command = [str(Path(sys.executable).with_name("wheeled-dyn")), *args]
    env = {**os.environ, **(env or {}), "WHEELED_DYN_REUSE": reuse}
    out = []
    with tempfile.TemporaryDirectory() as folder:
        if reuse == "1":
            subprocess.run([*command, "--out", folder], env=env, check=True,
                           stdout=subprocess.DEVNULL)
        for _ in range(runs):
            t0 = time.perf_counter()
            subprocess.run([*command, "--out", folder], env=env, check=True,
                           stdout=subprocess.DEVNULL)
            out.append(time.perf_counter() - t0)
    return out


def _times(command: list[str]) -> list[float]:
    r"""Wall times of ``command`` (:data:`RUNS` fresh processes)."""
    out = []
    for _ in range(RUNS):
        t0 = time.perf_counter()
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
        out.append(time.perf_counter() - t0)
    return out


def _check_after_saving(derivation: Path) -> list[float]:
    r"""Times of ``compare --watch``'s check after each of :data:`RUNS` saves of a copy of
    ``derivation``'s folder (the step files beside it come along): one engine throughout, as
    the command keeps, so the truth is computed at the first check only."""
    import shutil

    from wheeled_dyn.cli.report_output import write_report
    from wheeled_dyn.compare.engine import ComparisonEngine
    out = []
    with tempfile.TemporaryDirectory() as folder:
        copy = Path(shutil.copytree(derivation.parent, Path(folder) / "derivations"))
        path = copy / derivation.name
        engine = ComparisonEngine(samples=DEFAULT_SAMPLES, param_sets=DEFAULT_PARAM_SETS,
                                  seed=2026, parallel_steps=True)

        def check() -> None:
            with open(os.devnull, "w") as quiet:
                stdout, sys.stdout = sys.stdout, quiet
                try:
                    results = run_comparison([path], DEFAULT_SAMPLES, DEFAULT_PARAM_SETS,
                                             model="wip", engine=engine)
                    write_report(results, "watch", Path(folder) / "out")
                finally:
                    sys.stdout = stdout

        check()                                     # the first check: the truth computed
        for k in range(RUNS):
            path.write_text(path.read_text() + f"\n# saved {k}\n")    # a save
            t0 = time.perf_counter()
            check()
            out.append(time.perf_counter() - t0)
    return out


def main() -> None:
    import wheeled_dyn
    subprocess.run([sys.executable, "-m", "compileall", "-q", str(Path(wheeled_dyn.__file__).parent)],
                   check=True, stdout=subprocess.DEVNULL)     # as ./wd does (the docstring)
    os.environ["WHEELED_DYN_REUSE"] = "forms"  # every figure is a first check: no results reused
    raw_before = _raw_pinocchio(load_model("wip"))
    files = builtin_derivations("seed001")
    compare_report(files, DEFAULT_SAMPLES, DEFAULT_PARAM_SETS, table_group="seed001")  # fills
    t0 = time.perf_counter()
    results, _, _ = compare_report(files, DEFAULT_SAMPLES, DEFAULT_PARAM_SETS,
                                   table_group="seed001")
    total = time.perf_counter() - t0
    t0 = time.perf_counter()
    run_comparison(files, DEFAULT_SAMPLES, DEFAULT_PARAM_SETS)
    serial = time.perf_counter() - t0
    wm = load_model("wip")
    cmap = CoordinateMap(wm, builtin_coordinate_set(wm, "seed001"))
    rng = np.random.default_rng(0)
    n = DEFAULT_SAMPLES * DEFAULT_PARAM_SETS
    q, nu = rng.uniform(-3, 3, (n, 3)), rng.normal(size=(n, 3))
    t1 = time.perf_counter()
    cmap.terms_batch(q, nu)
    truth = time.perf_counter() - t1
    print(f"default report: {len(results)} derivations, {DEFAULT_SAMPLES} states x "
          f"{DEFAULT_PARAM_SETS} parameter sets each, and the seed's table reproduced, on the "
          f"machine's cores: {total:.2f} s (target <= 3 s)")
    print(f"the derivations alone, one process: {serial:.2f} s")
    print(f"baseline, the truth alone for one coordinate set on the same grid ({n} states): "
          f"{truth:.2f} s; report / baseline = {total / truth:.1f}x")
    eq25 = BUILTIN_DIR / "seed001" / "eq25_lagrange.toml"
    commands = {}
    for what, args, target in (("compare wip eq25_lagrange.toml",
                                ("compare", "wip", str(eq25)), 1), ("report", ("report",), 3)):
        times = commands[what] = _command_times(*args)
        print(f"wheeled-dyn {what}, results cache off, wall incl. start-up and writing, "
              f"{RUNS} runs: {min(times):.2f} .. {max(times):.2f} s (target < {target} s)")
        warm = _command_times(*args, reuse="1")
        print(f"wheeled-dyn {what}, everything remembered (nothing changed), wall, {RUNS} "
              f"runs: {min(warm):.2f} .. {max(warm):.2f} s")
    start = _times([sys.executable, "-c", "pass"])
    for what in (("list",), ("--help",)):
        times = _times([str(Path(sys.executable).with_name("wheeled-dyn")), *what])
        print(f"wheeled-dyn {' '.join(what)}, {RUNS} runs: {min(times):.2f} .. {max(times):.2f} s "
              f"(target < 0.3 s); baseline python -c pass {min(start):.3f} s, ratio "
              f"{min(times) / min(start):.1f}x")
    again = _check_after_saving(eq25)
    print(f"compare --watch, check after saving eq25_lagrange.toml (truth reused, reports "
          f"written), {RUNS} saves: {min(again):.2f} .. {max(again):.2f} s")
    with tempfile.TemporaryDirectory() as empty:
        (first,) = _command_times("report", runs=1, env={"WHEELED_DYN_CACHE": empty})
    print(f"wheeled-dyn report with an empty cache folder (closed forms derived, nothing "
          f"printed before): {first:.2f} s")
    raw = (raw_before + _raw_pinocchio(wm)) / 2
    slower = raw / REFERENCE_RAW
    print(f"this machine's speed: raw Pinocchio crba+coriolis+gravity on the WIP "
          f"{raw * 1e6:.1f} us/state (mean of the run's start and end), {slower:.2f}x its "
          f"{REFERENCE_RAW * 1e6:.1f} us of {REFERENCE_DAY}; python -c pass {min(start):.3f} s, "
          f"{min(start) / REFERENCE_START:.2f}x its {REFERENCE_START:.3f} s (the targets above "
          f"are absolute)")
    scaled = [f"{what} {min(t) / slower:.2f} .. {max(t) / slower:.2f} s (target < {target} s)"
              for (what, t), target in zip(commands.items(), (1, 3))]
    print(f"the same divided by {slower:.2f} (this machine against {REFERENCE_DAY}'s, by the "
          f"line above): default report {total / slower:.2f} s (target <= 3 s); "
          + "; ".join(scaled))


#: Raw Pinocchio's time per state (crba, Coriolis matrix, gravity of the WIP; as
#: ``bench_core.py``) on :data:`REFERENCE_DAY`, when ``compare`` of eq. 25 took 0.80–0.88 s and
#: ``report`` 2.40–2.48 s: the same code's figures scale with it on these shared machines.
REFERENCE_RAW, REFERENCE_DAY = 2.8e-6, "2026-11-25"
#: ``python -c pass`` on :data:`REFERENCE_DAY` (seconds).
REFERENCE_START = 0.015


def _raw_pinocchio(wm, states: int = 2000) -> float:
    r"""The best of three: seconds per state of ``crba``, ``computeCoriolisMatrix`` and
    ``computeGeneralizedGravity`` on ``wm``'s full model (code this project does not change:
    a measure of the machine)."""
    import pinocchio as pin
    rng = np.random.default_rng(7)
    model, data = wm.model, wm.model.createData()
    pairs = [(rng.uniform(-3, 3, model.nq), rng.normal(size=model.nv)) for _ in range(states)]
    best = np.inf
    for _ in range(3):
        t0 = time.perf_counter()
        for q, v in pairs:
            pin.crba(model, data, q)
            pin.computeCoriolisMatrix(model, data, q, v)
            pin.computeGeneralizedGravity(model, data, q)
        best = min(best, (time.perf_counter() - t0) / states)
    return best


if __name__ == "__main__":
    from doc_block import recorded
    with recorded(__file__):      # its block of docs/benchmarks.md
        main()
