r"""CLI: ``wheeled-dyn simulate FILE...``: the true and the documented model side by side."""

from __future__ import annotations

import argparse
import math

from ..errors import LimitError
from .models_cmd import parse_assignments

#: Longest simulated time in seconds (``simulate``, ``view``): a simulated second costs about
#: 0.4 s of computing (WIP, truth and document), so 60 s take about half a minute.
MAX_DURATION = 60.0
#: Largest magnitude of a starting velocity in ``--state`` (rad/s or m/s): faster starts make
#: the integrator take tiny steps for minutes.
MAX_RATE = 100.0


def check_duration(duration: float, option: str = "--duration") -> None:
    r"""Raise :class:`~wheeled_dyn.errors.LimitError` unless ``0 < duration <= MAX_DURATION``."""
    if not (math.isfinite(duration) and 0.0 < duration <= MAX_DURATION):
        raise LimitError(option, duration, f"seconds, more than 0 and at most {MAX_DURATION:g}",
                         "computing time grows with the simulated time")


def check_rates(start: dict[str, float], velocities) -> None:
    r"""Raise :class:`~wheeled_dyn.errors.LimitError` if a starting velocity of ``start``
    exceeds :data:`MAX_RATE` in magnitude."""
    names = {str(v) for v in velocities}
    for name, value in start.items():
        if name in names and abs(value) > MAX_RATE:
            raise LimitError(f"--state {name}", value, f"a rate of at most {MAX_RATE:g} in "
                             "magnitude", "faster starts make the integration take minutes")


def default_start(d) -> dict[str, float]:
    r"""A start that exercises every term: the last position (the pitch, in seed 001's
    coordinates) tilted by 0.2, every velocity 0.5 except the second (the heading rate) 1.5;
    a position the file draws in a ``[coordinates] ranges`` that leaves this out (a coin's
    lean away from lying flat) at its range's middle."""
    from ..compare.grid.assumptions import Assumptions, position_ranges
    start = {str(d.positions[-1]): 0.2}
    names = [str(p) for p in d.positions]
    for p, (low, high) in zip(names, position_ranges(d, names, Assumptions())):
        if not low <= start.get(p, 0.0) <= high:
            start[p] = 0.5 * (low + high)
    for i, v in enumerate(d.velocities):
        start[str(v)] = 1.5 if i == 1 else 0.5
    return start


def energy_deviation(energy) -> float:
    r"""The largest :math:`|E(t) - E(0)|` over a run (what the energy plot shows); NaN if the
    run left finite numbers."""
    import numpy as np
    e = np.asarray(energy, dtype=float)
    return float(np.abs(e - e[0]).max()) if np.isfinite(e).all() else float("nan")


def energy_summary(s) -> str:
    r"""One line: the largest energy deviation from the start, truth and document, in J."""
    truth, doc = energy_deviation(s.truth.energy), energy_deviation(s.document.energy)
    doc_text = f"{doc:.3g} J" if doc == doc else "not finite (the documented model diverges)"
    return (f"largest energy deviation from E(0) over {s.document.t[-1]:.2f} s: truth "
            f"{truth:.3g} J ({s.truth.relative_energy_drift():.1e} relative), document {doc_text}")


def _cmd(args: argparse.Namespace) -> int:
    from .inputs import check_model_names, input_files
    from .running import progress
    from ..derivations import load_derivations
    from ..output import check_output_folder, write_atomic
    from ..simulate.documented import side_by_side
    from ..simulate.plots import plot_side_by_side
    check_duration(args.duration)
    out = check_output_folder(args.out)
    state = parse_assignments(args.state, "--state")
    derivations = load_derivations(input_files(args.files))
    for d in derivations:
        check_model_names(d)
        check_rates(state, d.velocities)
    with progress(len(derivations), "simulating") as bar:
        for d in derivations:
            s = side_by_side(d, state or default_start(d), args.duration)
            path = write_atomic(out / f"{d.path.stem}_simulation.png", plot_side_by_side(s))
            bar.update()
            print(f"{d.path.name}: {path}  {energy_summary(s)}")
    return 0


def add_commands(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("simulate", help="simulate documented models beside the truth; PNG plots")
    p.add_argument("files", nargs="+", help="derivation files")
    p.add_argument("--state", default=None, help="start, document names, e.g. phi=0.2,dpsi=1")
    p.add_argument("--duration", type=float, default=4.0, help="seconds")
    p.add_argument("--out", default="reports", help="folder for the PNG files")
    p.set_defaults(handler=_cmd)
