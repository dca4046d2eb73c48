r"""CLI: ``wheeled-dyn report`` (the default job) and ``wheeled-dyn compare MODEL FILE...``.

The commands only: their arguments and handlers. What they are given is checked in
:mod:`.inputs`, comparisons run in :mod:`.running`, and what they print and write is made in
:mod:`.report_output`; the names those modules define stay importable from here."""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING

from ..errors import WheeledDynError
from .inputs import (DEFAULT_PARAM_SETS, DEFAULT_SAMPLES, MAX_PARAM_SETS, MAX_SAMPLES, MAX_STATES,
                     check_grid, check_model_names, input_files)
from .report_output import eval_fraction, print_summary, summary_heading, write_report
from .running import TABLE_COST, compare_report, progress, run_comparison, stage_display

if TYPE_CHECKING:
    from ..compare.engine import ComparisonEngine


def _cmd_report(args: argparse.Namespace) -> int:
    from ..derivations import builtin_derivations
    from ..output import check_output_folder
    check_grid(args.samples, args.param_sets)
    check_output_folder(args.out)
    t0 = time.perf_counter()
    results, sections, html = compare_report(builtin_derivations(args.group), args.samples,
                                             args.param_sets, table_group=args.group)
    print_summary(results)
    for entry in sections[2].get("tables", []):
        print(f"{entry['table']}: mismatched per the seed's table: "
              f"{', '.join(entry['table_mismatched'])}; per the machine: "
              f"{', '.join(entry['machine_mismatched'])}")
    write_report(results, f"wheeled_dyn: the derivations of {args.group} against the truth",
           Path(args.out), args.plots, sections, html)
    print(f"{len(results)} derivations, {args.samples} states × {args.param_sets} parameter "
          f"sets each, in {time.perf_counter() - t0:.1f} s")
    return 0


def _cmd_compare(args: argparse.Namespace) -> int:
    from ..output import check_output_folder
    check_grid(args.samples, args.param_sets)
    check_output_folder(args.out)
    files = input_files(args.files)
    from ..compare.engine import ComparisonEngine
    from ..models.registry import model_version
    engines: dict[tuple, ComparisonEngine] = {}

    def check() -> None:
        # one engine per content of the model's files: the truth is computed again when the
        # model file or the URDF was saved since
        try:
            version = model_version(args.model)
        except WheeledDynError:
            version = ()
        if version not in engines:
            engines.clear()
            engines[version] = ComparisonEngine(samples=args.samples,
                                                param_sets=args.param_sets, seed=2026,
                                                parallel_steps=True)
        # the arguments read again: a file that became a folder (without derivation files),
        # or a folder that gained one, is read as a fresh command reads it
        results = run_comparison(input_files(args.files), args.samples, args.param_sets,
                                 model=args.model, engine=engines[version])
        print_summary(results)
        write_report(results, f"wheeled_dyn: derivations of {args.model} against the truth",
               Path(args.out), args.plots)

    if not getattr(args, "watch", False):
        check()
        return 0
    from .watch import watch, watched_files
    try:
        check()
    except WheeledDynError as exc:          # the first version may be the broken one
        print(f"wheeled-dyn: error: {exc}", flush=True)
    return watch(lambda: watched_files(files, args.model), check)


def _without_cache(handler: Callable[[argparse.Namespace], int]
                   ) -> Callable[[argparse.Namespace], int]:
    r"""``handler`` run with the disk cache off when ``--no-cache`` is given."""
    def run(args: argparse.Namespace) -> int:
        from ..cache_trust import without_reuse
        with without_reuse(getattr(args, "no_cache", False)):
            return handler(args)
    return run


def add_commands(sub: argparse._SubParsersAction) -> None:
    for name, helptext, handler in (
            ("report", "compare the shipped derivations (seed 001's by default) with the truth; "
             "write reports/",
             _cmd_report),
            ("compare", "compare derivation files with the truth of a model", _cmd_compare)):
        p = sub.add_parser(name, help=helptext)
        if name == "compare":
            p.add_argument("model", help="model name (see 'wheeled-dyn list') or model file (.toml)")
            p.add_argument("files", nargs="+", help="derivation files (TOML) or folders")
            p.add_argument("--watch", action="store_true",
                           help="check the files again each time they are saved (the truth "
                                "is computed once); Ctrl-C to stop")
        else:
            from ..derivations.builtin import builtin_groups
            p.add_argument("--group", default="seed001", choices=builtin_groups(),
                           help="the shipped derivations to compare (default: seed001)")
        p.add_argument("--out", default="reports", help="folder for report.md/.html/.json")
        p.add_argument("--samples", type=int, default=DEFAULT_SAMPLES,
                       help="random states per parameter set")
        p.add_argument("--param-sets", type=int, default=DEFAULT_PARAM_SETS,
                       help="random physically consistent parameter sets")
        p.add_argument("--plots", action="store_true",
                       help="add simulations of each document beside the truth (PNG)")
        p.add_argument("--no-cache", action="store_true",
                       help="use nothing remembered from earlier runs (results, compiled "
                            "code, closed forms) and remember nothing; as WHEELED_DYN_REUSE=0")
        p.set_defaults(handler=_without_cache(handler))


__all__ = ["DEFAULT_PARAM_SETS", "DEFAULT_SAMPLES", "MAX_PARAM_SETS", "MAX_SAMPLES", "MAX_STATES",
           "TABLE_COST", "add_commands", "check_grid", "check_model_names", "compare_report",
           "eval_fraction", "input_files", "print_summary", "progress", "run_comparison",
           "stage_display", "summary_heading", "write_report"]
