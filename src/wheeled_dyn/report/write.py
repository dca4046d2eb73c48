r"""Writing the three reports (Markdown, HTML, JSON) whole or not at all.

Every text is made in memory first; then each file is written to a temporary name in the
target folder and renamed over its final name (``os.replace`` is atomic), so a failure leaves
either the previous reports or none, never half a file, and no temporary file
(:func:`~wheeled_dyn.output.write_files_atomic`).
"""

from __future__ import annotations

import json
from collections.abc import Mapping, Sequence
from pathlib import Path

from ..compare.records import DerivationResult
from ..disk_cache import save_memos
from ..output import write_files_atomic
from .html import report_html
from .markdown import report_markdown
from .summary import ordered, summary_entry


#: The version of the JSON report's contract (``docs/report-schema.json``).
SCHEMA = "wheeled-dyn-report/1"


def render(results: Sequence[DerivationResult], title: str, extra_md: Sequence[str] = (),
           extra_html: Sequence[str] = (), extra_json: dict | None = None,
           html_sections: Mapping[Path, str] | None = None) -> dict[str, str]:
    r"""The three reports as texts keyed by file name; derivations in the document's order,
    the JSON's ``summary`` first (one entry per derivation: id, counts, causes in one line).
    ``html_sections``: derivations' HTML sections made already, by file
    (:func:`~.html.report_html`)."""
    results = ordered(results)
    data = {"schema": SCHEMA, "title": title, "summary": [summary_entry(r) for r in results],
            "derivations": [r.as_dict() for r in results], **(extra_json or {})}
    texts = {"report.md": report_markdown(results, title, extra_md),
             "report.html": report_html(results, title, extra_html, html_sections),
             "report.json": json.dumps(data, indent=1, default=str, allow_nan=True)}
    save_memos()
    return texts


def write_reports(texts: dict[str, str | bytes], out: str | Path) -> list[Path]:
    r"""Write ``texts`` (text, or bytes for images) into folder ``out`` (created if needed);
    returns the paths. All files are staged under temporary names and renamed only when every
    one is written; on any failure (a full disk, Ctrl-C) the temporary files are removed."""
    return write_files_atomic(texts, out)
