r"""The ``wheeled-dyn`` command: a thin layer over the Python API.

Each feature package contributes its sub-commands through a function
``add_commands(subparsers)`` listed in :data:`COMMAND_MODULES`; the handler it registers with
``set_defaults(handler=...)`` receives the parsed arguments and returns an exit code. Errors of
the project's own type are printed as one line on stderr with exit code 2; Ctrl-C ends a
command with exit code 130 and one line, no traceback.
"""

from __future__ import annotations

import argparse
import importlib
import os
import signal
import sys
from collections.abc import Sequence

from .errors import WheeledDynError

#: Modules that define ``add_commands(subparsers)``, in the order they appear in ``--help``.
COMMAND_MODULES: tuple[str, ...] = (
    "wheeled_dyn.models.commands",
    "wheeled_dyn.compare.commands",
    "wheeled_dyn.simulate.commands",
    "wheeled_dyn.symbolic.commands",
    "wheeled_dyn.viewer.commands",
)


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="wheeled-dyn",
        description="Check hand-derived equations of motion of wheeled bodies against Pinocchio.",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name in COMMAND_MODULES:
        importlib.import_module(name).add_commands(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    try:
        return _run(argv)
    except KeyboardInterrupt:        # Ctrl-C: the writers have removed their temporary files
        # a second Ctrl-C (or the one the workers' shutdown sees) must not turn the clean
        # exit into a traceback or a death by signal
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        print("wheeled-dyn: interrupted", file=sys.stderr)
        return 130


def _run(argv: Sequence[str] | None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    handler = getattr(args, "handler", None)
    if handler is None:
        parser.print_help()
        return 1
    try:
        return int(handler(args) or 0)
    except WheeledDynError as exc:
        print(f"wheeled-dyn: error: {exc}", file=sys.stderr)
        return 2
    except BrokenPipeError:          # output piped into a reader that stopped (e.g. head)
        sys.stderr.close()
        return 0
    except OSError as exc:           # the system refused (a full disk, ...): one line too
        where = f"{exc.filename}: " if exc.filename else ""
        print(f"wheeled-dyn: error: {where}{exc.strerror or exc}", file=sys.stderr)
        return 2


def entry() -> None:
    r"""The ``wheeled-dyn`` command: :func:`main`'s exit code. After Ctrl-C the process ends
    at once with 130 (its files are already cleaned up): the interpreter's own shutdown could
    otherwise meet the interrupt again and end by the signal instead."""
    code = main()
    if code == 130:
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(130)
    sys.exit(code)


if __name__ == "__main__":  # pragma: no cover
    entry()
