r"""CLI: ``wheeled-dyn view MODEL [--scenario NAME] [--export FILE.html]``.

Runs a scenario of :mod:`wheeled_dyn.simulate.scenarios` (or, for a model without one, holds
its neutral configuration) and shows it: with ``--export`` one self-contained HTML file that
plays offline, then stop; otherwise a live meshcat viewer whose URL is printed, kept until
Ctrl-C (no display needed: open the URL in any browser).
"""

from __future__ import annotations

import argparse
import time

from ..errors import UnknownNameError


def _trajectory(model: str, scenario: str | None, duration: float | None):
    import numpy as np

    from ..models.registry import load_model
    from ..simulate.scenarios import SCENARIOS, run_scenario
    if scenario is None:
        scenario = next((n for n, (_, m, _) in SCENARIOS.items() if m == model), None)
    if scenario is None:
        wm = load_model(model)
        q = np.zeros(wm.model.nq)
        return wm, np.array([0.0, 1.0]), np.vstack([q, q]), "the neutral configuration"
    if SCENARIOS.get(scenario, (None, model))[1] != model:
        valid = [n for n, (_, m, _) in SCENARIOS.items() if m == model]
        raise UnknownNameError(f"scenario of model {model}", scenario, valid)
    s = run_scenario(scenario, duration)
    return s.model, s.trajectory.t, s.trajectory.q, s.description


def _check_args(args: argparse.Namespace) -> None:
    r"""Duration, hold time and export place, before anything is simulated."""
    import math

    from ..errors import LimitError
    from ..output import check_output_file
    from .simulate_cmd import check_duration
    if args.duration is not None:
        check_duration(args.duration)
    if args.hold is not None and not (math.isfinite(args.hold) and args.hold >= 0):
        raise LimitError("--hold", args.hold, "seconds, 0 or more")
    if args.export:
        check_output_file(args.export, ".html")


def _cmd_view(args: argparse.Namespace) -> int:
    from ..viewer.show import close_all, show_trajectory
    _check_args(args)
    wm, times, qs, what = _trajectory(args.model, args.scenario, args.duration)
    if args.export:
        path = show_trajectory(wm, times, qs, export=args.export)
        print(f"{args.model}: {what}; animation written to {path}")
        return 0
    url = show_trajectory(wm, times, qs)
    print(f"{args.model}: {what}; live viewer at {url} (Ctrl-C to stop)", flush=True)
    try:
        while args.hold is None or args.hold > 0:
            time.sleep(0.2 if args.hold is None else args.hold)
            if args.hold is not None:
                break
    except KeyboardInterrupt:
        pass
    finally:
        close_all()
    return 0


def add_commands(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser("view", help="watch a model move in the browser (meshcat)")
    p.add_argument("model", help="model name (see 'wheeled-dyn list') or model file (.toml)")
    p.add_argument("--scenario", default=None,
                   help="fall or balance (wip), circle (tiago_base), roll (sphere_plane), "
                        "roll_down (sphere_sphere); default: the model's first")
    p.add_argument("--duration", type=float, default=None, help="seconds to simulate")
    p.add_argument("--export", default=None, help="write one self-contained HTML file and stop")
    p.add_argument("--hold", type=float, default=None,
                   help="keep a live viewer this many seconds, then stop (default: until Ctrl-C)")
    p.set_defaults(handler=_cmd_view)
