r"""CLI: ``wheeled-dyn simulate FILE...``: the true and the documented model side by side."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..models.commands import parse_assignments


def default_start(d) -> dict[str, float]:
    r"""A start that exercises every term: the last position (the pitch, in seed 001's
    coordinates) tilted by 0.2, every velocity 0.5 except the second (the heading rate) 1.5."""
    start = {str(d.positions[-1]): 0.2}
    for i, v in enumerate(d.velocities):
        start[str(v)] = 1.5 if i == 1 else 0.5
    return start


def _cmd(args: argparse.Namespace) -> int:
    from ..derivations import load_derivations
    from .documented import side_by_side
    from .plots import plot_side_by_side
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    for d in load_derivations([Path(f) for f in args.files]):
        start = parse_assignments(args.state, "--state") or default_start(d)
        s = side_by_side(d, start, args.duration)
        path = out / f"{d.path.stem}_simulation.png"
        plot_side_by_side(s, path)
        doc_drift = abs(s.document.energy[-1] - s.document.energy[0])
        print(f"{d.path.name}: {path}  truth energy drift {s.truth.relative_energy_drift():.1e}"
              f" (relative); document energy change {doc_drift:.3g} J over "
              f"{s.document.t[-1]:.2f} s")
    return 0


def add_commands(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("simulate", help="simulate documented models beside the truth; PNG plots")
    p.add_argument("files", nargs="+", help="derivation files")
    p.add_argument("--state", default=None, help="start, document names, e.g. phi=0.2,dpsi=1")
    p.add_argument("--duration", type=float, default=4.0, help="seconds")
    p.add_argument("--out", default="reports", help="folder for the PNG files")
    p.set_defaults(handler=_cmd)
