"""A published linearised equation (the Whipple bicycle benchmark, Meijaard et al. 2007) judged
like any derivation: every printed number agrees to its printed digits with the tool's own
linearisation; a number changed in its last digits, or a wrong stability boundary, differs."""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

import pytest

from wheeled_dyn.compare.other_documents.linear import compare_linear, half_unit, is_linear_document
from wheeled_dyn.derivations.linear_document import MEIJAARD_2007

SHIPPED = Path(__file__).parents[1] / "src" / "wheeled_dyn" / "data" / "derivations"


@pytest.fixture(scope="module")
def result():
    return compare_linear(MEIJAARD_2007)


def test_half_unit_of_the_printed_digits():
    assert half_unit(80.81722) == pytest.approx(5e-6)
    assert half_unit(-0.8077402751993) == pytest.approx(5e-14)
    assert half_unit(0.0) == 0.0                         # a printed zero is exact


def test_benchmark_agrees_to_the_published_digits(result):
    counts = result.counts()
    assert counts["differs"] == 0 and counts["undecided"] == 0
    names = {r.element for r in result.records}
    assert {"M[1,1]", "C1[1,2]", "K0[2,2]", "K2[2,2]", "weave speed", "capsize speed"} <= names
    assert sum(r.key == "eigenvalue" for r in result.records) == 2 * 4 * 11


@pytest.mark.parametrize("old, new, element", [
    ("80.81722", "80.81724", "M[1,1]"),                      # two units in the last digit
    ("weave_speed = 4.29238253634111", "weave_speed = 4.29238253634911", "weave speed"),
])
def test_a_changed_digit_differs(tmp_path, old, new, element):
    text = MEIJAARD_2007.read_text()
    assert old in text
    planted = tmp_path / "planted.toml"
    planted.write_text(text.replace(old, new, 1))
    result = compare_linear(planted)
    wrong = [r.element for r in result.records if r.verdict != "agrees"]
    assert wrong == [element]


def test_only_linear_files_are_linear_documents():
    assert is_linear_document(MEIJAARD_2007)
    assert not any(is_linear_document(p) for p in SHIPPED.glob("*/*.toml"))


def test_compare_command_on_the_benchmark(tmp_path):
    out = tmp_path / "out"
    done = subprocess.run([sys.executable, "-m", "wheeled_dyn.cli.main", "compare", "bicycle",
                           str(MEIJAARD_2007), "--out", str(out)], capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    assert re.search(r"106 agree, .* 0 differ", done.stdout), done.stdout
    data = json.loads((out / "report.json").read_text())
    (doc,) = data["derivations"]
    assert doc["form"] == "linearised" and doc["counts"]["agrees"] == 106
    jsonschema = pytest.importorskip("jsonschema", reason="jsonschema is in the [test] extra")
    schema = json.loads((Path(__file__).parents[1] / "docs" / "report-schema.json").read_text())
    jsonschema.validate(data, schema)
    wrong = subprocess.run([sys.executable, "-m", "wheeled_dyn.cli.main", "compare", "wip",
                            str(MEIJAARD_2007), "--out", str(tmp_path / "x")],
                           capture_output=True, text=True, timeout=300)
    assert wrong.returncode == 2 and "not 'wip'" in wrong.stderr


def test_documented_example_is_the_shipped_file(tmp_path):
    r"""The example of docs/derivation-format.md ("Published linearised equations") is the
    shipped file cut short: it loads and every number in it agrees."""
    text = (Path(__file__).parents[1] / "docs" / "derivation-format.md").read_text()
    section = text.split("## Published linearised equations", 1)[1]
    example = section.split("```toml\n", 1)[1].split("```", 1)[0]
    path = tmp_path / "example.toml"
    path.write_text(example)
    result = compare_linear(path)
    assert result.counts()["differs"] == 0 and len(result.records) == 16 + 8 + 2
