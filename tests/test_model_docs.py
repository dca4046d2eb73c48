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
ARM = ROOT / "tests" / "data" / "two_link_arm" / "two_link_arm.toml"


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


def test_the_lengths_example_is_the_tested_arm_and_its_lengths_are_as_listed():
    r"""The second example (Lengths) is the two-link arm's model file, and its lengths are the
    ones the text lists."""
    from wheeled_dyn.models.registry import load_model
    (block,) = [b for b in re.findall(r"```toml\n(.*?)```", DOC.read_text(), re.S)
                if b.startswith("# A two-link arm")]
    assert block == ARM.read_text()
    lengths = load_model(str(ARM)).dimensions
    assert lengths["origin_x(elbow)"] == lengths["length(upper_arm)"] == 1.0
    assert (lengths["radius(upper_arm)"], lengths["length(forearm)"],
            lengths["radius(forearm)"]) == (0.02, 0.8, 0.015)
    others = [v for k, v in lengths.items() if k.startswith("origin_") and k != "origin_x(elbow)"]
    assert others and not any(others)
