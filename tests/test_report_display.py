"""What a person sees: the summary line of a file without an equation label, the verdict pills
of a fully correct file, the row marker's own column, a result in a notebook, units on the
simulation plots, and the progress of a long check (stages of one derivation) on a terminal."""

from __future__ import annotations

import dataclasses
import fcntl
import os
import pty
import re
import struct
import subprocess
import sys
import termios
import threading
from pathlib import Path

import pytest

from wheeled_dyn.cli.compare_cmd import print_summary, run_comparison, summary_heading
from wheeled_dyn.compare.engine import STAGES, ComparisonEngine
from wheeled_dyn.derivations import builtin_derivations, load_derivation
from wheeled_dyn.report.html import derivation_html
from wheeled_dyn.report.notebook import SCOPE, scoped_css
from wheeled_dyn.simulate.plots import position_units

#: A small grid: what is shown is under test, not the engine's numbers.
SAMPLES, SETS = 40, 2
#: Seconds the command run on a terminal may take.
TTY_TIMEOUT = 300


def _builtin(group: str, name: str) -> Path:
    return next(p for p in builtin_derivations(group) if p.name == name)


@pytest.fixture(scope="module")
def kim():
    (result,) = run_comparison([_builtin("seed001", "kim_eq1_3.toml")], SAMPLES, SETS)
    return result


@pytest.fixture(scope="module")
def rod():
    (result,) = run_comparison([_builtin("seed000", "p4_4_rod_pendulum.toml")], SAMPLES, SETS)
    return result


# -- the summary line ------------------------------------------------------------------------
def test_summary_line_leaves_out_what_the_file_does_not_give(kim, tmp_path, capsys):
    notes = dataclasses.replace(kim, source={"document": "my notes, 26 Nov"})
    assert summary_heading(notes) == f"kim_eq1_3.toml — my notes, 26 Nov: {kim.title}"
    assert summary_heading(dataclasses.replace(kim, source={})) == f"kim_eq1_3.toml: {kim.title}"
    assert summary_heading(kim).startswith("kim_eq1_3.toml — seed 001 eqs (1)-(3): ")
    # and as the command prints it, for a file whose [source] has no equation label
    text = _builtin("seed000", "p4_4_rod_pendulum.toml").read_text(encoding="utf-8")
    text = re.sub(r'(?m)^equations = ".*"\n', "", text).replace(
        'document = "seed 000"', 'document = "my notes, 26 Nov"')
    path = tmp_path / "notes.toml"
    path.write_text(text, encoding="utf-8")
    print_summary(run_comparison([path], SAMPLES, SETS))
    first = capsys.readouterr().out.splitlines()[0]
    assert first.startswith("notes.toml — my notes, 26 Nov: Rod pendulum"), first
    assert "eqs" not in first


# -- the report section ----------------------------------------------------------------------
def test_a_count_of_zero_is_neutral(rod, kim):
    counts = rod.counts()
    assert counts["differs"] == 0 and counts["agrees"] > 0, counts    # fully correct
    html = derivation_html(rod)
    assert '<span class="pill zero">0 differ</span>' in html
    assert 'class="pill v-differs"' not in html
    assert f'<span class="pill v-agrees">{counts["agrees"]} agree</span>' in html
    assert f'<span class="pill v-differs">{kim.counts()["differs"]} differ</span>' \
        in derivation_html(kim)


def _tables(section: str, key: str) -> list[list[int]]:
    r"""Per matrix ``key`` of a section (document, then truth), the cells of each row."""
    out = []
    for block in re.findall(rf"<div><b>{key}</b>.*?<table class=\"mat\">(.*?)</table>", section,
                            re.DOTALL):
        rows = re.findall(r"<tr>(.*?)</tr>", block, re.DOTALL)
        out.append([len(re.findall(r"<t[dh][ >]", row)) for row in rows])
    return out


def test_the_row_marker_has_a_column_of_its_own(kim):
    r"""Kim (1)-(3)'s third equation is printed × −1: its "÷ -1" mark sits in a column every
    row has, so the matrix's columns stay aligned."""
    assert kim.row_factors[2] == "-1" and not any(kim.row_factors[:2])
    html = derivation_html(kim)
    for key, cols in (("A", 3), ("Q", 1), ("B", 2)):
        document, truth = _tables(html, key)
        assert document == [cols + 1] * 3, (key, document)      # the marks' column, then cols
        assert truth == [cols] * 3, (key, truth)
    assert html.count("<th class='div'>÷ -1</th>") == 3


# -- in a notebook ---------------------------------------------------------------------------
def test_a_result_shows_as_its_report_section(kim):
    shown = kim._repr_html_()
    assert shown.startswith(f'<div class="{SCOPE}"><style>')
    assert derivation_html(kim) in shown                  # the same HTML as the report
    section = shown[shown.index("<section"):]
    assert section.index('class="causes"') < section.index('class="pair"')


def test_the_report_style_stays_inside_the_result():
    css = scoped_css(".a{x:1}\nbody{y:2}\n.b,.c d{z:3}@media (max-width:7px){.e{w:4}}")
    assert css == (f".{SCOPE} .a{{x:1}}.{SCOPE}{{y:2}}.{SCOPE} .b,.{SCOPE} .c d{{z:3}}"
                   f"@media (max-width:7px){{.{SCOPE} .e{{w:4}}}}")
    from wheeled_dyn.report.html import CSS
    scoped = re.sub(r"@media[^{]*\{", "", scoped_css(CSS))
    for selectors in re.findall(r"(?:^|})([^{}]+)\{", scoped):
        for selector in selectors.split(","):
            assert selector.strip().startswith(f".{SCOPE}"), selector


# -- the simulation plots --------------------------------------------------------------------
def test_position_units_as_declared_and_as_the_document_s_own_inertia_says(tmp_path):
    r"""Two independent readings agree: the units a file declares for its positions, and the
    ones the dimension of its own :math:`A_{jj}` gives once the declaration is removed."""
    checked = 0
    for group in ("seed001", "seed000"):
        for path in builtin_derivations(group):
            d = load_derivation(path)
            declared = [str(d.coordinates.units.get(str(q))) for q in d.positions]
            if "None" in declared or d.read_off().A is None:
                continue
            assert position_units(d) == declared
            text = re.sub(r"(?m)^units = \{.*\}\n", "", path.read_text(encoding="utf-8"))
            if text == path.read_text(encoding="utf-8"):
                continue
            copy = tmp_path / group / path.name
            copy.parent.mkdir(exist_ok=True)
            copy.write_text(text, encoding="utf-8")
            inferred = position_units(load_derivation(copy))
            assert all(u is None or u == v for u, v in zip(inferred, declared)), path.name
            checked += sum(u is not None for u in inferred)
    assert checked >= 20


# -- progress --------------------------------------------------------------------------------
def test_the_engine_names_each_stage_of_a_derivation():
    path = _builtin("seed001", "kim_eq1_3.toml")
    calls: list[tuple[str, str]] = []
    engine = ComparisonEngine(samples=SAMPLES, param_sets=SETS,
                              on_stage=lambda name, stage: calls.append((name, stage)))
    result = engine.compare(load_derivation(path))
    assert {name for name, _ in calls} == {path.name}
    stages = [stage for _, stage in calls]
    assert set(stages) == set(STAGES), stages                # kim (1)-(3) is fed by steps
    firsts = [stages.index(s) for s in STAGES if s != "steps"]
    assert firsts == sorted(firsts), stages
    plain = ComparisonEngine(samples=SAMPLES, param_sets=SETS).compare(load_derivation(path))
    assert [(r.element, r.verdict) for r in result.records] == \
        [(r.element, r.verdict) for r in plain.records]       # a display decides nothing


def _on_a_terminal(args: list[str], cwd: Path) -> tuple[int, str]:
    r"""Run ``args`` with stderr on a pseudo-terminal 160 columns wide; (exit code, what the
    terminal received)."""
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 40, 160, 0, 0))
    received: list[bytes] = []

    def read() -> None:
        while True:
            try:
                chunk = os.read(master, 4096)
            except OSError:
                return
            if not chunk:
                return
            received.append(chunk)

    reader = threading.Thread(target=read, daemon=True)
    reader.start()
    try:
        done = subprocess.run(args, check=False, cwd=cwd, stderr=slave,
                              stdout=subprocess.DEVNULL, stdin=subprocess.DEVNULL,
                              timeout=TTY_TIMEOUT)
    finally:
        os.close(slave)
    reader.join(timeout=10)
    os.close(master)
    return done.returncode, b"".join(received).decode("utf-8", "replace")


@pytest.mark.slow
def test_a_check_on_a_terminal_shows_the_stages_it_goes_through(tmp_path):
    exe = Path(sys.executable).with_name("wheeled-dyn")
    path = _builtin("seed001", "kim_eq1_3.toml")
    code, shown = _on_a_terminal([str(exe), "compare", "wip", str(path), "--out",
                                  str(tmp_path), "--samples", str(SAMPLES), "--param-sets",
                                  str(SETS)], tmp_path)
    assert code == 0, shown
    seen = set(re.findall(r"kim_eq1_3\.toml: (\w+)\]", shown))
    assert {"judging", "causes"} <= seen <= set(STAGES), shown[-2000:]
