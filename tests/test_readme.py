"""The README's Python API example runs as printed (in a scratch folder: it writes an HTML
animation), and what it claims in its comments holds."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

README = Path(__file__).parents[1] / "README.md"


def _python_blocks() -> list[str]:
    return re.findall(r"```python\n(.*?)```", README.read_text(encoding="utf-8"), re.S)


@pytest.mark.slow
def test_readme_python_example_runs(tmp_path, monkeypatch):
    (block,) = _python_blocks()
    monkeypatch.chdir(tmp_path)
    namespace: dict = {}
    exec(compile(block, str(README), "exec"), namespace)
    assert (tmp_path / "fall.html").is_file()
    assert namespace["result"].form == "matrices"           # the last: the rod from SymPy
    assert all(r.verdict == "agrees" for r in namespace["result"].records)
