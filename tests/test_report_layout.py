"""The structure of the three reports: summary first, the document's own order, causes first,
only differing elements in full, agreeing ones folded or summarised, offline HTML."""

from __future__ import annotations

import dataclasses
import json
import re

import pytest

from wheeled_dyn.cli.compare_cmd import run_comparison
from wheeled_dyn.compare.records import Cause
from wheeled_dyn.derivations import builtin_derivations
from wheeled_dyn.report import render
from wheeled_dyn.report.summary import anchor, cause_lines, element_anchor, ordered

#: A small grid: the layout is under test, not the engine's numbers.
SAMPLES, SETS = 40, 2
FILES = ("appendix_kim_A_C.toml", "eq25_lagrange.toml", "kim_eq1_3.toml")
#: JSON keys per derivation that CI users read (the root-cause issue's contract).
CONTRACT_KEYS = {"path", "source", "assumes", "conventions", "causes", "records", "energy"}


@pytest.fixture(scope="module")
def results():
    paths = [p for p in builtin_derivations("seed001") if p.name in FILES]
    return run_comparison(paths, SAMPLES, SETS)           # file-name order: appendix first


@pytest.fixture(scope="module")
def texts(results):
    return render(results, "layout test")


def _positions(text: str, needles) -> list[int]:
    found = [text.find(n) for n in needles]
    assert all(i >= 0 for i in found), needles
    return found


def test_derivations_come_in_the_documents_order(results, texts):
    names = [r.path.name for r in ordered(results)]
    # seed 001: eqs (1)-(3) in section 1, eq. (25) in 4.3.3, the appendix (8.1) last
    assert names == ["kim_eq1_3.toml", "eq25_lagrange.toml", "appendix_kim_A_C.toml"]
    ids = [anchor(r) for r in ordered(results)]
    html = texts["report.html"]
    sections = _positions(html, [f'<section id="{i}"' for i in ids])
    assert sections == sorted(sections)
    data = json.loads(texts["report.json"])
    assert [s["id"] for s in data["summary"]] == ids
    assert [d["path"].rsplit("/", 1)[-1] for d in data["derivations"]] == names


def test_declared_order_comes_before_equation_numbers(results):
    appendix = next(r for r in results if r.path.name == FILES[0])
    first = dataclasses.replace(appendix, source={**appendix.source, "order": "0"})
    others = [r for r in results if r is not appendix]
    assert ordered([*others, first])[0] is first


def test_summary_and_contents_lead_and_every_link_has_its_target(texts):
    html = texts["report.html"]
    summary, toc, first = _positions(html, ['id="summary"', 'id="contents"', "<section"])
    assert summary < toc < first
    ids = set(re.findall(r'id="([^"]+)"', html))
    targets = set(re.findall(r"href='#([^']+)'", html)) | set(re.findall(r'href="#([^"]+)"', html))
    assert targets and targets <= ids, targets - ids


def test_agreeing_elements_are_folded_and_differing_ones_shown(results, texts):
    html = texts["report.html"]
    for r in results:
        section = html[html.index(f'<section id="{anchor(r)}"'):]
        section = section[:section.index("</section>")]
        folded = section[section.index("<details>"):] if "<details>" in section else ""
        for rec in r.records:
            card = f'id="{element_anchor(r, rec.element)}"'
            if rec.verdict == "agrees":
                assert card not in section
            else:
                assert card in section and section.index(card) < section.index("<details>")
        assert folded.count("<tr>") - 1 == sum(rec.verdict == "agrees" for rec in r.records)


def test_causes_come_first_with_the_assumes_line(results):
    eq25 = next(r for r in results if r.path.name == "eq25_lagrange.toml")
    cause = Cause("quasi_coordinate_christoffel", ("C[1,2]", "C[2,1]"),
                  "the Christoffel formula applied to the heading speed x", latex=r"m_S d")
    told = dataclasses.replace(eq25, causes=(cause,), assumes=("identical wheels",))
    html = render([told], "t")["report.html"]
    section = html[html.index("<section"):]
    causes, assumes, matrices = _positions(section, [
        "the Christoffel formula applied to the heading speed x", "identical wheels",
        "Matrices"])
    assert causes < assumes < matrices
    summary = html[:html.index("<section")]
    assert "quasi-coordinate Christoffel: the Christoffel formula" in summary
    md = render([told], "t")["report.md"]
    assert md.index("**Causes:**") < md.index("**Assumes:** identical wheels")


def test_without_causes_the_elements_are_grouped_by_diagnosis(results):
    eq25 = next(r for r in results if r.path.name == "eq25_lagrange.toml")
    eq25 = dataclasses.replace(eq25, causes=())       # none computed: findings are grouped
    html = render([eq25], "t")["report.html"]
    section = html[html.index(f'<section id="{anchor(eq25)}"'):]
    assert section.index("Findings, grouped by diagnosis") < section.index("Matrices")
    assert "swapped symbol: dphi where dpsi fits — C[3,2]" in section


def test_row_factors_are_said_where_the_numbers_are_shown(results, texts):
    appendix = next(r for r in results if r.path.name == FILES[0])
    assert any(appendix.row_factors)
    html = texts["report.html"]
    section = html[html.index(f'<section id="{anchor(appendix)}"'):]
    section = section[:section.index("</section>")]
    assert "÷ -1" in section and "the truth is compared multiplied by -1" in section


def test_markdown_summarises_agreeing_elements(results, texts):
    md = texts["report.md"]
    assert md.index("## Summary") < md.index("## seed 001")
    for r in results:
        section = md[md.index(f'<a id="{anchor(r)}">'):]
        section = section[:section.find("<a id=", 1) % len(section) or len(section)]
        agree = [x.element for x in r.records if x.verdict == "agrees"]
        assert f"Agreeing ({len(agree)}): " + ", ".join(agree) in section
        for element in agree:
            assert f"| {element} |" not in section


def test_html_makes_no_network_request(texts):
    html = texts["report.html"]
    assert not re.search(r"<(script|link|img|iframe)\b[^>]*\b(src|href)=['\"]?(https?:)?//", html)
    assert "@import" not in html and "url(" not in html
    assert "http" not in html.replace("http://www.w3.org/1998/Math/MathML", "")


def test_json_keeps_the_per_derivation_contract(texts):
    data = json.loads(texts["report.json"])
    for d in data["derivations"]:
        assert CONTRACT_KEYS <= set(d)
    for s in data["summary"]:
        assert {"id", "title", "equations", "counts", "causes"} <= set(s)


def test_a_cause_is_not_repeated_among_the_grouped_findings(results):
    eq25 = next(r for r in results if r.path.name == "eq25_lagrange.toml")
    swapped = [x.element for x in eq25.records if any(d.startswith("swap: dphi where dpsi")
                                                       for d in x.texts)]
    assert swapped
    cause = Cause("swap", tuple(swapped), "psi-dot written as phi-dot in C[3,2]")
    lines = cause_lines(dataclasses.replace(eq25, causes=(cause,)))
    assert lines[0].computed and lines[0].elements == tuple(swapped)
    assert not any(set(swapped) & set(line.elements) for line in lines[1:])
    before = {e for line in cause_lines(dataclasses.replace(eq25, causes=()))
              for e in line.elements}
    after = {e for line in lines for e in line.elements}
    assert before == after             # every differing element is still named once
