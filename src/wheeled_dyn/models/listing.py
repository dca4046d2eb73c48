r"""The shipped models, read cheaply: the model files of ``data/models/``.

``wheeled-dyn list`` runs for every new user and must answer at once, so it must not load
Pinocchio or yourdfpy (together about 0.7 s here). Model files (``data/models/*.toml``,
:mod:`.model_file`) are read with :mod:`tomllib` alone; models written in Python
(:data:`~.benchmarks.PYTHON_BENCHMARKS`) are listed from their summaries.
"""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from ..errors import InputFileError
from ..paths import DATA_DIR, resolved
from .model_file import ModelFile, read_model_file

#: Folder of the shipped model files.
MODEL_FILES_DIR: Path = DATA_DIR / "models"

#: How a user adds a model (printed by ``wheeled-dyn list``).
ADD_MODEL_HINT = ("Your own robot: 'wheeled-dyn model robot.urdf --out robot.toml' writes a "
                  "starting model file; check it (docs/model-format.md), then give its path "
                  "wherever a model name is accepted (wheeled-dyn matrices robot.toml, a "
                  "derivation's model = \"robot.toml\").")


@lru_cache(maxsize=None)
def _files(folder: Path) -> dict[str, ModelFile]:
    out: dict[str, ModelFile] = {}
    for path in sorted(folder.glob("*.toml")) if folder.is_dir() else ():
        mf = read_model_file(path)
        if mf.name in out:
            raise InputFileError(path, f"model name {mf.name!r} is also the name in "
                                       f"{out[mf.name].path.name}")
        out[mf.name] = mf
    return out


def shipped_model_files(folder: Path | None = None) -> dict[str, ModelFile]:
    r"""``{name: ModelFile}`` of the model files in ``folder`` (default
    :data:`MODEL_FILES_DIR`), sorted by file name; read once."""
    return dict(_files(resolved(MODEL_FILES_DIR if folder is None else folder)))


def model_summaries(folder: Path | None = None) -> dict[str, str]:
    r"""``{name: summary}`` of the shipped models: the model files of ``folder`` (default
    :data:`MODEL_FILES_DIR`), then the models written in Python."""
    out = {name: mf.summary for name, mf in shipped_model_files(folder).items()}
    from .benchmarks import PYTHON_BENCHMARKS
    out.update({name: summary for name, summary, _ in PYTHON_BENCHMARKS})
    return out
