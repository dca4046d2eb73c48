r"""Plots (matplotlib, PNG) of the true and the documented trajectory and their energies."""

from __future__ import annotations

import io
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from ..derivations.schema import Derivation  # noqa: E402
from .documented import SideBySide  # noqa: E402

#: Units of a position by its dimension as exponents of (kg, m, s).
_UNIT_NAMES = {(0, 0, 0): "rad", (0, 1, 0): "m"}


def position_units(d: Derivation) -> list[str | None]:
    r"""The units of each of the document's positions: as ``[coordinates] units`` declares
    them, else from the dimension of the document's own :math:`A_{jj}`
    (:math:`[A_{jj}] = \mathrm{kg\,m^2}/[q_j]^2`, from the units of its symbols:
    ``rad`` for a dimensionless position, ``m`` for a length); None where neither says."""
    import sympy as sp

    from ..compare.judge.units import DimensionChecker, format_dim
    declared = d.coordinates.units
    checker = DimensionChecker(d)
    A = d.read_off(assume=True, unscale=True).A
    out: list[str | None] = []
    for j, q in enumerate(d.positions):
        if str(q) in declared:
            out.append(str(declared[str(q)]))
            continue
        problems: list[str] = []
        dim = None if A is None or A[j, j] == 0 else checker.dim(A[j, j], problems)
        if dim is None or problems:
            out.append(None)
            continue
        squared = [sp.Rational(want) - have for want, have in zip((1, 2, 0), dim)]
        if squared[0] != 0 or any(not (x / 2).is_integer for x in squared):
            out.append(None)
            continue
        kg, m, sec = (int(x / 2) for x in squared)
        out.append(_UNIT_NAMES.get((kg, m, sec)) or format_dim((kg, m, sec)))
    return out


def plot_side_by_side(s: SideBySide, path: str | Path | None = None) -> bytes:
    r"""One figure: each document position (true solid, documented dashed; in its units,
    :func:`position_units`), then the energy of each. Returns the PNG bytes (and writes them
    to ``path`` if given)."""
    d = s.derivation
    n = d.n
    units = position_units(d)
    fig, axes = plt.subplots(n + 1, 1, figsize=(8, 2.2 * (n + 1)), sharex=True)
    for i, name in enumerate(d.positions):
        ax = axes[i]
        ax.plot(s.truth.t, s.truth_doc_q[:, i], label="truth (Pinocchio, rolling reduced)")
        ax.plot(s.document.t, s.document.q[:, i], "--", label="document")
        ax.set_ylabel(f"{name} [{units[i]}]" if units[i] else f"{name} (no units declared)")
    axes[0].legend(loc="best", fontsize=8)
    ax = axes[n]
    ax.plot(s.truth.t, s.truth.energy - s.truth.energy[0], label="truth")
    ax.plot(s.document.t, s.document.energy - s.document.energy[0], "--",
            label="document" + ("" if s.document.has_potential else " (kinetic only)"))
    ax.set_ylabel("energy − E(0) [J]")
    ax.set_xlabel("time [s]")
    ax.legend(loc="best", fontsize=8)
    fig.suptitle(f"{d.title}\n({d.path.name}, zero input)", fontsize=9)
    fig.tight_layout()
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=90)
    plt.close(fig)
    data = buf.getvalue()
    if path is not None:
        Path(path).write_bytes(data)
    return data
