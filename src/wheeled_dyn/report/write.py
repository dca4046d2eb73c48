r"""Writing the three reports (Markdown, HTML, JSON) whole or not at all.

Every text is made in memory first; then each file is written to a temporary name in the
target folder and renamed over its final name (``os.replace`` is atomic), so a failure leaves
either the previous reports or none, never half a file.
"""

from __future__ import annotations

import json
import os
import tempfile
from collections.abc import Sequence
from pathlib import Path

from ..compare.result import DerivationResult
from ..errors import InputFileError
from .html import report_html
from .markdown import report_markdown
from .summary import ordered, summary_entry


def render(results: Sequence[DerivationResult], title: str, extra_md: Sequence[str] = (),
           extra_html: Sequence[str] = (), extra_json: dict | None = None) -> dict[str, str]:
    r"""The three reports as texts keyed by file name; derivations in the document's order,
    the JSON's ``summary`` first (one entry per derivation: id, counts, causes in one line)."""
    results = ordered(results)
    data = {"title": title, "summary": [summary_entry(r) for r in results],
            "derivations": [r.as_dict() for r in results], **(extra_json or {})}
    return {"report.md": report_markdown(results, title, extra_md),
            "report.html": report_html(results, title, extra_html),
            "report.json": json.dumps(data, indent=1, default=str, allow_nan=True)}


def write_reports(texts: dict[str, str | bytes], out: str | Path) -> list[Path]:
    r"""Write ``texts`` (text, or bytes for images) into folder ``out`` (created if needed);
    returns the paths."""
    out = Path(out)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputFileError(out, f"cannot create the report folder: {exc.strerror}") from None
    staged: list[tuple[Path, Path]] = []
    try:
        for name, text in texts.items():
            fd, tmp = tempfile.mkstemp(prefix=f".{name}.", dir=out)
            with os.fdopen(fd, "wb") as fh:
                fh.write(text if isinstance(text, bytes) else text.encode("utf-8"))
            os.chmod(tmp, 0o644)
            staged.append((Path(tmp), out / name))
    except OSError as exc:
        for tmp, _ in staged:
            tmp.unlink(missing_ok=True)
        raise InputFileError(out, f"cannot write the reports: {exc.strerror}") from None
    for tmp, final in staged:
        os.replace(tmp, final)
    return [final for _, final in staged]
