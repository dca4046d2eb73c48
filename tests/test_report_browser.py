"""The default report in a real browser (headless Chromium driven by playwright): it fits the
window at 1280 px and at a phone's width, its summary is in the first screenful, every link
inside the page has its target, and it makes no network request.

Set ``WHEELED_DYN_SCREENSHOTS=<dir>`` to keep the pictures for a look.
"""

from __future__ import annotations

import os
from pathlib import Path

import pytest

from browser import INSTALL_HINT, find_chromium
from wheeled_dyn.cli.main import main

playwright_api = pytest.importorskip(
    "playwright.sync_api", reason="playwright not installed (pip install -e '.[test]')")

pytestmark = [pytest.mark.browser,
              pytest.mark.skipif(find_chromium() is None, reason=INSTALL_HINT)]

#: A small grid: the layout is under test, not the engine's numbers.
SAMPLES, SETS = "40", "2"
#: Window sizes: a desktop screen and a phone.
DESKTOP = {"width": 1280, "height": 800}
PHONE = {"width": 400, "height": 800}
#: Page load limit, milliseconds.
LOAD_MS = 60_000


@pytest.fixture(scope="module")
def report(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("report")
    assert main(["report", "--out", str(out), "--samples", SAMPLES, "--param-sets", SETS]) == 0
    return out / "report.html"


@pytest.fixture(scope="module")
def browser():
    with playwright_api.sync_playwright() as p:
        b = p.chromium.launch(executable_path=find_chromium(), args=["--no-sandbox"])
        try:
            yield b
        finally:
            b.close()


def _open(browser, report: Path, viewport: dict):
    page = browser.new_page(viewport=viewport)
    requests: list[str] = []
    page.on("request", lambda r: requests.append(r.url))
    page.goto(report.as_uri(), timeout=LOAD_MS)
    return page, requests


def _keep(page, name: str) -> None:
    target = os.environ.get("WHEELED_DYN_SCREENSHOTS")
    if target:
        Path(target).mkdir(parents=True, exist_ok=True)
        page.screenshot(path=str(Path(target) / name))


@pytest.mark.parametrize("viewport", [DESKTOP, PHONE], ids=["1280px", "400px"])
def test_nothing_is_wider_than_the_window(browser, report, viewport):
    page, requests = _open(browser, report, viewport)
    _keep(page, f"report_{viewport['width']}.png")
    width = page.evaluate("window.innerWidth")
    assert page.evaluate("document.documentElement.scrollWidth") <= width
    # and no box sticks out of the page: wide formulas and matrices scroll inside their own
    # box (.m, .pane, .wide), which fits
    sticking = page.evaluate("""() => {
        const boxes = Array.from(document.querySelectorAll('.m, .pane, .wide, table, section'));
        return boxes.filter(e => !(e.parentElement && e.parentElement.closest('.m, .pane, .wide')))
                    .filter(e => e.getBoundingClientRect().right > window.innerWidth + 1)
                    .map(e => e.className || e.tagName).slice(0, 5);
    }""")
    assert sticking == []
    assert [u for u in requests if not u.startswith(("file:", "data:"))] == []
    page.close()


def test_summary_of_every_derivation_is_in_the_first_screenful(browser, report):
    page, _ = _open(browser, report, DESKTOP)
    rows = page.evaluate("""() => Array.from(document.querySelectorAll('#summary tr'))
        .slice(1).map(r => { const b = r.getBoundingClientRect();
                             return [b.top, b.bottom, b.left, b.right]; })""")
    sections = page.evaluate("document.querySelectorAll('section[id^=\"d-\"]').length")
    assert len(rows) == sections >= 8                   # seed 001's derivations, one row each
    height, width = DESKTOP["height"], DESKTOP["width"]
    for top, bottom, left, right in rows:
        assert 0 <= top and bottom <= height and left >= 0 and right <= width
    # each row names its causes, or says there is no difference
    texts = page.evaluate("""() => Array.from(document.querySelectorAll('#summary tr'))
        .slice(1).map(r => r.cells[3].innerText.trim())""")
    assert all(texts)
    page.close()


def test_every_link_inside_the_page_has_its_target(browser, report):
    page, _ = _open(browser, report, DESKTOP)
    missing = page.evaluate("""() => Array.from(document.querySelectorAll('a[href^="#"]'))
        .map(a => a.getAttribute('href').slice(1))
        .filter(id => !document.getElementById(id))""")
    assert missing == []
    sections = page.evaluate("""() => Array.from(document.querySelectorAll('section[id^="d-"]'))
        .map(s => s.id)""")
    linked = page.evaluate("""() => Array.from(document.querySelectorAll('#summary a'))
        .map(a => a.getAttribute('href').slice(1))""")
    assert set(sections) <= set(linked)
    # following a summary link brings its section's heading into view
    page.click(f"#summary a[href='#{sections[-1]}']")
    top = page.evaluate(f"document.getElementById('{sections[-1]}').getBoundingClientRect().top")
    assert abs(top) < 2
    page.close()
