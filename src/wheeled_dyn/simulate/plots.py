r"""Plots (matplotlib, PNG) of the true and the documented trajectory and their energies."""

from __future__ import annotations

import io
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from .documented import SideBySide  # noqa: E402


def plot_side_by_side(s: SideBySide, path: str | Path | None = None) -> bytes:
    r"""One figure: each document position (true solid, documented dashed), then the energy
    of each. Returns the PNG bytes (and writes them to ``path`` if given)."""
    d = s.derivation
    n = d.n
    fig, axes = plt.subplots(n + 1, 1, figsize=(8, 2.2 * (n + 1)), sharex=True)
    for i, name in enumerate(d.positions):
        ax = axes[i]
        ax.plot(s.truth.t, s.truth_doc_q[:, i], label="truth (Pinocchio, rolling reduced)")
        ax.plot(s.document.t, s.document.q[:, i], "--", label="document")
        ax.set_ylabel(str(name))
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
