"""docs/model-format.md: its complete example is a model file that reads, and says what the
tested Upkie file says (same tables and values), and every key the reader accepts is in its
table of keys."""

from __future__ import annotations

import re
from pathlib import Path

from wheeled_dyn.models.model_file import KEYS, read_model_file

ROOT = Path(__file__).resolve().parents[1]
DOC = ROOT / "docs" / "model-format.md"
UPKIE = ROOT / "tests" / "data" / "upkie_crouch" / "upkie_crouch.toml"


def test_the_example_reads_and_equals_the_tested_file(tmp_path):
    block = re.search(r"```toml\n(.*?)```", DOC.read_text(), re.S).group(1)
    path = tmp_path / "upkie_crouch.toml"
    path.write_text(block)
    assert dict(read_model_file(path).data) == dict(read_model_file(UPKIE).data)


def test_every_key_is_documented():
    text = DOC.read_text()
    for table, keys in KEYS.items():
        for key in keys:
            assert f"`{key}`" in text or f"[{key}]" in text or f"[[{key}]]" in text, (table, key)
