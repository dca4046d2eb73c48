r"""A published linearised equation of motion as data: :math:`M`, :math:`C_1`, :math:`K_0`,
:math:`K_2` of :math:`M\ddot p + v C_1\dot p + (g K_0 + v^2 K_2)p = f`, with the document's
claims (eigenvalues against speed, stability boundaries), read from a TOML file such as
``data/linearised/meijaard2007_benchmark.toml``.

Only transcription lives here; the truth these numbers are compared with comes from the model's
reduced dynamics (:func:`.rolling_linear.speed_form`).
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ..errors import InputFileError
from ..paths import DATA_DIR
from ..constraints.rolling_linear import SpeedForm
from .source import read_toml

#: The shipped transcription of Meijaard et al. (2007).
MEIJAARD_2007 = DATA_DIR / "linearised" / "meijaard2007_benchmark.toml"


@dataclass(frozen=True)
class LinearDocument:
    r"""A transcribed linearised equation: the model it is about, its positions (model
    coordinate names), the printed form, and the claims (``eigenvalues``: speed → the printed
    eigenvalues, complex; ``claims``: other named numbers such as ``weave_speed``)."""

    path: Path
    title: str
    model: str
    positions: tuple[str, ...]
    form: SpeedForm
    eigenvalues: dict[float, np.ndarray]
    claims: dict[str, float]
    #: ``[reduction]``: (independent velocities, dependent coordinates, independent
    #: velocities at unit forward speed) — how the model's rolling is eliminated for the truth
    reduction: tuple[tuple[str, ...], tuple[str, ...], dict[str, float]] = ((), (), {})
    source: dict[str, str] | None = None


def _matrix(path: Path, table: dict, key: str, k: int) -> np.ndarray:
    try:
        value = np.array(table[key], dtype=float)
    except KeyError:
        raise InputFileError(path, f"[form] has no {key!r} (expected a {k} x {k} matrix)") from None
    except (TypeError, ValueError):
        raise InputFileError(path, f"[form].{key} is not a matrix of numbers") from None
    if value.shape != (k, k) or not np.all(np.isfinite(value)):
        raise InputFileError(path, f"[form].{key} has shape {value.shape}, expected ({k}, {k}) "
                             "finite numbers")
    return value


def load_linear_document(path: str | Path = MEIJAARD_2007) -> LinearDocument:
    r"""Read a linearised-equation file; :class:`InputFileError` names what is missing."""
    path = Path(path)
    data, _ = read_toml(path)
    for key in ("model", "coordinates", "form"):
        if key not in data:
            raise InputFileError(path, f"missing [{key}]" if key != "model" else "missing model")
    positions = tuple(data["coordinates"].get("positions", ()))
    k = len(positions)
    if k == 0:
        raise InputFileError(path, "[coordinates].positions is empty")
    table = data["form"]
    form = SpeedForm(M=_matrix(path, table, "M", k), C1=_matrix(path, table, "C1", k),
                     K0=_matrix(path, table, "K0", k), K2=_matrix(path, table, "K2", k),
                     g=float(table.get("g", 9.81)))
    claims = dict(data.get("claims", {}))
    eig = {}
    for row in claims.pop("eigenvalues", []):
        values = np.array(row["values"], dtype=float)
        if values.shape != (2 * k, 2):
            raise InputFileError(path, f"eigenvalues at speed {row.get('speed')}: expected "
                                 f"{2 * k} [real, imaginary] pairs")
        eig[float(row["speed"])] = values[:, 0] + 1j * values[:, 1]
    return LinearDocument(path, str(data.get("title", "")), str(data["model"]), positions, form,
                          eig, {key: float(val) for key, val in claims.items()},
                          _reduction(path, data.get("reduction", {}), positions),
                          {k: str(v) for k, v in data.get("source", {}).items()})


def _reduction(path: Path, table: dict, positions: tuple[str, ...]
               ) -> tuple[tuple[str, ...], tuple[str, ...], dict[str, float]]:
    r"""``[reduction] independent = [...], dependent = [...], unit_speed = { name = rate }``;
    the positions must be among the independent velocities' coordinates."""
    if not table:
        return (), (), {}
    independent = tuple(table.get("independent", ()))
    dependent = tuple(table.get("dependent", ()))
    unit = table.get("unit_speed", {})
    if not independent or not all(isinstance(x, str) for x in (*independent, *dependent)):
        raise InputFileError(path, "[reduction].independent: expected joint names")
    missing = [p for p in positions if p not in independent]
    if missing:
        raise InputFileError(path, f"[reduction].independent lacks the positions {missing}")
    try:
        rates = {str(k): float(v) for k, v in dict(unit).items()}
    except (TypeError, ValueError):
        raise InputFileError(path, "[reduction].unit_speed: expected name = number") from None
    unknown = [k for k in rates if k not in independent]
    if unknown or not all(np.isfinite(list(rates.values()))):
        raise InputFileError(path, f"[reduction].unit_speed: {unknown or 'values'} not "
                             "finite rates of independent velocities")
    return independent, dependent, rates
