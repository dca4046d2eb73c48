r"""What the ``compare``, ``report`` and ``simulate`` commands are given, checked before
anything is compared: the grid's size, the derivation files named (a folder stands for its
files), and the names a derivation uses of its model."""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

# the ranges of --samples and --param-sets and the check of a derivation's names are the
# engine's (the Python API checks with them too)
from ..compare.grid.inputs import MAX_PARAM_SETS, MAX_SAMPLES, MAX_STATES, check_model_names


#: Defaults of the default report: states per parameter set, parameter sets.
DEFAULT_SAMPLES, DEFAULT_PARAM_SETS = 1000, 5


def check_grid(samples: int, param_sets: int) -> None:
    r"""Raise :class:`~wheeled_dyn.errors.LimitError` unless ``1 <= samples <= MAX_SAMPLES``,
    ``1 <= param_sets <= MAX_PARAM_SETS`` and their product is at most ``MAX_STATES``."""
    from ..errors import LimitError
    if not 1 <= samples <= MAX_SAMPLES:
        raise LimitError("--samples", samples, f"an integer from 1 to {MAX_SAMPLES}")
    if not 1 <= param_sets <= MAX_PARAM_SETS:
        raise LimitError("--param-sets", param_sets, f"an integer from 1 to {MAX_PARAM_SETS}")
    if samples * param_sets > MAX_STATES:
        raise LimitError("--samples × --param-sets", samples * param_sets,
                         f"at most {MAX_STATES:,} states", "memory and time grow with them")


def input_files(entries: Sequence[str | Path]) -> list[Path]:
    r"""The derivation files named on the command line (a folder stands for its ``*.toml``
    files); a folder without any raises :class:`~wheeled_dyn.errors.InputFileError`."""
    from ..derivations.builtin import derivation_files
    from ..errors import InputFileError
    files: list[Path] = []
    for entry in entries:
        found = derivation_files([entry])
        if not found:
            raise InputFileError(entry, "folder without derivation files (*.toml)")
        files.extend(found)
    return files


__all__ = ["DEFAULT_PARAM_SETS", "DEFAULT_SAMPLES", "MAX_PARAM_SETS", "MAX_SAMPLES", "MAX_STATES",
           "check_grid", "check_model_names", "input_files"]
