"""The JSON report's contract: what `render` writes validates against docs/report-schema.json,
and every cause, record and summary entry says what the schema promises. The files rendered
include seed 000's 4.12, whose energy-consistency records have no matrix index."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from wheeled_dyn.compare import ComparisonEngine
from wheeled_dyn.derivations import load_derivation
from wheeled_dyn.report.write import SCHEMA, render

from conftest import SEED

jsonschema = pytest.importorskip("jsonschema", reason="jsonschema is in the [test] extra")

ROOT = Path(__file__).parents[1]
SHIPPED = ROOT / "src" / "wheeled_dyn" / "data" / "derivations"
FILES = ("seed001/eq25_lagrange.toml", "seed001/kim_eq6_8.toml", "seed000/p4_12_bounce_pitch.toml")


@pytest.fixture(scope="module")
def rendered() -> dict[str, str]:
    engine = ComparisonEngine(samples=200, param_sets=2, seed=SEED)
    results = [engine.compare(load_derivation(SHIPPED / f)) for f in FILES]
    return render(results, "schema test")


def test_report_json_validates(rendered):
    schema = json.loads((ROOT / "docs" / "report-schema.json").read_text())
    data = json.loads(rendered["report.json"])
    jsonschema.validate(data, schema)
    assert data["schema"] == SCHEMA == schema["$id"]


def test_schema_names_every_cause_kind():
    from wheeled_dyn.compare.records import CAUSE_KINDS, VERDICTS
    schema = json.loads((ROOT / "docs" / "report-schema.json").read_text())
    assert set(schema["$defs"]["cause"]["properties"]["kind"]["enum"]) == set(CAUSE_KINDS)
    assert set(schema["$defs"]["verdict"]["enum"]) == set(VERDICTS)


def test_causes_name_records_and_agrees_is_finite(rendered):
    data = json.loads(rendered["report.json"])
    for d in data["derivations"]:
        labels = {r["element"] for r in d["records"]}
        for c in d["causes"]:
            missing = set(c["elements"]) - labels
            assert not missing, (d["path"], c["kind"], missing)
        for r in d["records"]:
            if r["verdict"] == "agrees":
                assert math.isfinite(r["max_error"]), (d["path"], r["element"])


def test_summary_anchors_exist_in_html(rendered):
    data = json.loads(rendered["report.json"])
    html = rendered["report.html"]
    assert [s["path"] for s in data["summary"]] == [d["path"] for d in data["derivations"]]
    for s in data["summary"]:
        assert f'id="{s["id"]}"' in html, s["id"]


def test_benchmark_bodies_have_closed_form_truths():
    r"""Seed 000's differential (no physical record): truths in Khalil's parameters, and the
    residual of the G-for-G² typo is :math:`(G^2 - G)/4\,ZZ_{pinion}` in the gear ratio G
    (a symbol: parameter sets draw it)."""
    import sympy as sp

    engine = ComparisonEngine(samples=100, param_sets=2, seed=SEED)
    result = engine.compare(load_derivation(SHIPPED / "seed000/p4_13_differential_theta1.toml"))
    records = {r.element: r for r in result.records}
    assert all(records[f"A[{i},{j}]"].truth for i in (1, 2) for j in (1, 2))
    G, ZZ = sp.Symbol("G", real=True), sp.Symbol("ZZ_pinion", real=True)
    expected = (G**2 - G) / 4 * ZZ
    assert sp.simplify(sp.sympify(records["A[1,2]"].residual, locals={"ZZ_pinion": ZZ, "G": G})
                       - expected) == 0


def test_latex_input_is_echoed():
    r"""A twin given in LaTeX: each element read from LaTeX is in the JSON and the HTML with
    the text it was parsed as."""
    twin = ROOT / "tests" / "data" / "latex_twins" / "eq25_lagrange.tex.toml"
    engine = ComparisonEngine(samples=100, param_sets=2, seed=SEED)
    result = engine.compare(load_derivation(twin))
    texts = render([result], "latex")
    data = json.loads(texts["report.json"])
    echoed = data["derivations"][0]["latex_input"]
    assert echoed and all(set(v) == {"latex", "read_as"} for v in echoed.values())
    assert "parsed as" in texts["report.html"] and "parsed as" in texts["report.md"]
    schema = json.loads((ROOT / "docs" / "report-schema.json").read_text())
    jsonschema.validate(data, schema)


def test_equation_records_name_their_equations(rendered):
    r"""Every record of the equations of motion names the document's equation labels."""
    data = json.loads(rendered["report.json"])
    by_path = {Path(d["path"]).name: d for d in data["derivations"]}
    eq25 = [r for r in by_path["eq25_lagrange.toml"]["records"]
            if r["step"] == "equations of motion"]
    assert eq25 and all(r["equation"] == "(25)" for r in eq25)
