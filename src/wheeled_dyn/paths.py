r"""Where the shipped files are: URDFs, derivation files, built-in coordinate sets."""

from __future__ import annotations

import os
from pathlib import Path

PACKAGE_DIR = Path(__file__).resolve().parent
DATA_DIR = PACKAGE_DIR / "data"


def urdf_dir() -> Path:
    r"""The folder of shipped URDFs: inside an installed wheel (``wheeled_dyn/_urdf``) or the
    repository's ``urdf/`` for an editable install."""
    packaged = PACKAGE_DIR / "_urdf"
    if packaged.is_dir():
        return packaged
    return PACKAGE_DIR.parents[1] / "urdf"


def example_robot_data_share() -> Path | None:
    r"""``<site-packages>/cmeel.prefix/share`` where example-robot-data keeps its robots, or None."""
    try:
        import cmeel  # noqa: F401  (installed with example-robot-data)
        from cmeel import consts
    except ImportError:
        return None
    import site
    import sysconfig
    roots = [sysconfig.get_paths()["purelib"], *site.getsitepackages()]
    for root in roots:
        share = Path(root) / consts.CMEEL_PREFIX / "share"
        if (share / "example-robot-data" / "robots").is_dir():
            return share
    return None


def resolved(path: str | Path) -> Path:
    r"""``Path(path).resolve()``: the absolute path with its symbolic links followed; a loop
    of links (where Python raises a ``RuntimeError``) is
    :class:`~wheeled_dyn.errors.InputFileError` naming the path."""
    try:
        return Path(path).resolve()
    except RuntimeError:
        from .errors import InputFileError
        raise InputFileError(path, "its symbolic links make a loop (the link points back to "
                                   "itself through other links): point it at a file") from None


def file_stamp(path: str | Path) -> tuple[int, int, int, int] | None:
    r"""``(mtime_ns, ctime_ns, size, inode)`` of a file, None when it is missing: what
    changes when the file is saved (an editor's save, a rename over it). The change time
    moves with every write and every change of the times, which no program sets back: a
    file rewritten in place at its old size with its old mtime restored is another file."""
    try:
        st = os.stat(path)
    except (OSError, ValueError):
        return None
    return st.st_mtime_ns, st.st_ctime_ns, st.st_size, st.st_ino
