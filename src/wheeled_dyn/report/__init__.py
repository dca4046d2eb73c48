r"""Reports of a comparison: Markdown, self-contained HTML, JSON."""

from .markdown import report_markdown, summary_lines
from .html import report_html
from .write import render, write_reports

__all__ = ["render", "report_html", "report_markdown", "summary_lines", "write_reports"]
