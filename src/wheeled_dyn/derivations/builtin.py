r"""The shipped derivation files: :func:`builtin_derivations`, :func:`builtin_tables`.

They live inside the package, ``wheeled_dyn/data/derivations/<group>/*.toml`` (one group per
source document, e.g. ``seed001``), so that an installed toolkit finds them. In a group folder,
files named ``*_table.toml`` are hand-made comparison tables
(:func:`~wheeled_dyn.derivations.table.load_comparison_table`); every other ``*.toml`` is a
derivation file.
"""

from __future__ import annotations

from collections.abc import Iterable
from pathlib import Path

from ..errors import InputFileError
from ..paths import DATA_DIR

#: Folder of the shipped derivation files, one sub-folder per group.
BUILTIN_DIR = DATA_DIR / "derivations"
#: Files in a group folder whose name ends so are comparison tables, not derivations.
TABLE_SUFFIX = "_table.toml"
#: Files of earlier steps only (kinematics, energies ...) that feed the derivations they name.
STEPS_SUFFIX = "_steps.toml"


def derivation_files(paths: Iterable[str | Path]) -> list[Path]:
    r"""The files named by ``paths``: a file as is, a folder as its ``*.toml`` derivation files
    (sorted, tables left out)."""
    files: list[Path] = []
    for entry in paths:
        p = Path(entry)
        if p.is_dir():
            files.extend(f for f in sorted(p.glob("*.toml"))
                         if not f.name.endswith((TABLE_SUFFIX, STEPS_SUFFIX)))
        else:
            files.append(p)
    return files


def builtin_groups() -> list[str]:
    r"""Names of the groups of shipped derivation files (``seed001``, ...)."""
    if not BUILTIN_DIR.is_dir():
        return []
    return sorted(d.name for d in BUILTIN_DIR.iterdir() if d.is_dir())


def _group_dir(group: str) -> Path:
    if not isinstance(group, str):
        from ..errors import ArgumentError
        raise ArgumentError("builtin_derivations", "group", group,
                            "a group's name: " + ", ".join(builtin_groups()))
    folder = BUILTIN_DIR / group
    if not folder.is_dir():
        raise InputFileError(folder, f"no built-in derivation group {group!r}; groups: "
                             + (", ".join(builtin_groups()) or "none"))
    return folder


def builtin_derivations(group: str = "seed001") -> list[Path]:
    r"""Paths of the shipped derivation files of ``group`` (sorted; tables left out). Raises
    :class:`~wheeled_dyn.errors.InputFileError` for an unknown group."""
    return derivation_files([_group_dir(group)])


def builtin_tables(group: str = "seed001") -> list[Path]:
    r"""Paths of the shipped comparison tables (``*_table.toml``) of ``group``."""
    return sorted(_group_dir(group).glob("*" + TABLE_SUFFIX))
