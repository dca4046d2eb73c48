r"""The names and one-line summaries of the shipped models, read cheaply.

``wheeled-dyn list`` runs for every new user and must answer at once, so it must not load
Pinocchio or yourdfpy (together about 0.7 s here). Model files (``data/models/*.toml``: a
``name``, a ``summary`` or ``description``, at the top level or in a ``[model]`` table) are read
with :mod:`tomllib` alone; models that are defined only in Python
(:data:`~.registry.MODELS`) are listed from the registry, which needs the heavy imports.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

from ..errors import InputFileError
from ..paths import DATA_DIR

#: Folder of the shipped model files.
MODEL_FILES_DIR: Path = DATA_DIR / "models"


def _file_summary(path: Path) -> tuple[str, str]:
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        raise InputFileError(path, f"not a readable model file: {exc}") from None
    table = data.get("model", data) if isinstance(data.get("model", data), dict) else data
    name = str(table.get("name", path.stem))
    summary = str(table.get("summary", table.get("description", "")))
    return name, " ".join(summary.split())


def model_summaries(folder: Path | None = None) -> dict[str, str]:
    r"""``{name: summary}`` of the shipped models: the model files of ``folder`` (default
    :data:`MODEL_FILES_DIR`) when it holds any, then the registry's models not among them
    (the registry is imported only if the folder is missing or empty)."""
    folder = MODEL_FILES_DIR if folder is None else folder
    files = sorted(folder.glob("*.toml")) if folder.is_dir() else []
    out = dict(_file_summary(p) for p in files)
    if out:
        return out
    from .registry import MODELS
    return {name: entry.summary for name, entry in MODELS.items()}
