r"""Rendered LaTeX and MathML are remembered across runs (the disk cache's
report/latex-<code>.pickle, report/mathml-<code>.pickle): a report rendered from the remembered
entries is the same text as one rendered from scratch."""

from __future__ import annotations

from conftest import SEED
from wheeled_dyn.compare.engine import ComparisonEngine
from wheeled_dyn.derivations import builtin_derivations, load_derivation
from wheeled_dyn.disk_cache import CACHE_ENV
from wheeled_dyn.report import html_text, symbols
from wheeled_dyn.report.write import render


def _results():
    path = next(p for p in builtin_derivations("seed000") if p.name == "p4_8_rolling_disk.toml")
    return [ComparisonEngine(samples=50, param_sets=2, seed=SEED).compare(load_derivation(path))]


def _forget() -> None:
    r"""What a new process does not have: the memos' entries in memory, the notations."""
    symbols.RENDERED.forget()
    html_text.MATHML.forget()
    html_text.mathml.cache_clear()
    symbols._NOTATIONS.clear()


def test_remembered_latex_renders_the_same_report(tmp_path, monkeypatch):
    monkeypatch.setenv(CACHE_ENV, str(tmp_path))
    results = _results()
    _forget()
    cold = render(results, "t")
    entry = symbols.RENDERED.path()
    assert entry.is_file() and entry.parent == tmp_path / "report"
    assert html_text.MATHML.path().is_file()
    # a new process: nothing in memory, the entries on disk
    _forget()
    warm = render(results, "t")
    assert warm["report.md"] == cold["report.md"]
    assert warm["report.html"] == cold["report.html"]
    assert len(symbols.RENDERED.entries()) > 0 and len(html_text.MATHML.entries()) > 0
    _forget()


def test_remembered_latex_is_named_by_the_code_that_rendered_it(tmp_path, monkeypatch):
    r"""Another SymPy (or other report code) reads another file: LaTeX it did not render is
    not served."""
    monkeypatch.setenv(CACHE_ENV, str(tmp_path))
    here = symbols.RENDERED.path()
    monkeypatch.setattr(symbols.sp, "__version__", "0.0-other")
    assert symbols.RENDERED.path() != here
