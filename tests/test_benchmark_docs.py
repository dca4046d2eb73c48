"""docs/benchmarks.md is kept true by the benchmark scripts: each script rewrites its own block
(benchmarks/doc_block.py) with its output and the date, and leaves the rest of the page as it
was. The scripts themselves are not run here (they time things; they are run by hand)."""

from __future__ import annotations

import datetime
import importlib.util
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SCRIPTS = sorted((ROOT / "benchmarks").glob("bench_*.py"))


def _doc_block():
    spec = importlib.util.spec_from_file_location("doc_block", ROOT / "benchmarks" / "doc_block.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.name)
def test_each_script_writes_its_own_block(script):
    guard = script.read_text(encoding="utf-8").split('if __name__ == "__main__":', 1)[1]
    assert "with recorded(__file__):" in guard
    doc_block = _doc_block()
    text = doc_block.DOC.read_text(encoding="utf-8")
    begin, end = doc_block.markers(script.name)
    assert text.count(begin) == 1 and text.count(end) == 1 and text.index(begin) < text.index(end)


def test_a_block_is_rewritten_and_nothing_else():
    doc_block = _doc_block()
    text = doc_block.DOC.read_text(encoding="utf-8")
    new = doc_block.replace_block(text, "bench_core.py", "1. raw: 9.9 us\n", "2030-01-02", "3 cores")
    begin, end = doc_block.markers("bench_core.py")
    inside = new[new.index(begin):new.index(end)]
    assert "Last run 2030-01-02 (3 cores):" in inside and "```\n1. raw: 9.9 us\n```" in inside
    assert new.startswith(text[:text.index(begin)]) and new.endswith(text[text.index(end):])
    assert doc_block.replace_block(new, "bench_core.py", "1. raw: 9.9 us\n", "2030-01-02",
                                   "3 cores") == new
    with pytest.raises(ValueError, match="no block for bench_nothing.py"):
        doc_block.replace_block(text, "bench_nothing.py", "x", "2030-01-02", "3 cores")


def test_a_run_rewrites_its_block_and_a_failed_run_leaves_the_page(tmp_path, capsys):
    doc_block = _doc_block()
    doc = tmp_path / "benchmarks.md"
    begin, end = doc_block.markers("bench_x.py")
    doc.write_text(f"# B\n\nbefore\n{begin}\nold figures\n{end}\nafter\n", encoding="utf-8")
    with doc_block.recorded(str(tmp_path / "bench_x.py"), doc):
        print("1. fast: 1.0 s")
    text = doc.read_text(encoding="utf-8")
    assert "1. fast: 1.0 s" in capsys.readouterr().out           # still on the terminal
    assert "old figures" not in text and "1. fast: 1.0 s" in text
    assert f"Last run {datetime.date.today().isoformat()} (" in text
    assert text.startswith("# B\n\nbefore\n") and text.endswith("after\n")
    with pytest.raises(RuntimeError), doc_block.recorded(str(tmp_path / "bench_x.py"), doc):
        print("2. half a run")
        raise RuntimeError("stopped")
    assert doc.read_text(encoding="utf-8") == text
    assert list(tmp_path.iterdir()) == [doc]                      # no temporary file left
