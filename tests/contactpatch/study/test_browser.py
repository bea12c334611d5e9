"""The report in a real browser (issue 13, done-when): headless Chromium through
Playwright at 1400 px and 400 px: no horizontal page overflow, no console error, no
network request, every figure visible; the tables sort and filter, a scan enlarges,
the 3D view draws, and printed (A4 landscape) every table fits the page.

Skipped, with the reason, when Playwright or a Chromium it can drive is missing
(``pip install playwright`` and ``python -m playwright install chromium``, or a system
Chromium such as Debian's ``chromium`` package, found on PATH or through
``$CHROMIUM``)."""

import itertools
import os
import shutil

import numpy as np
import pytest
from PIL import Image

from contactpatch import build_report

WIDTHS = (1400, 400)


def _launch(p):
    """A headless Chromium: Playwright's own, else a system one."""
    names = ("chromium", "chromium-browser", "google-chrome")
    found = [os.environ.get("CHROMIUM"), *(shutil.which(n) for n in names)]
    errors = []
    for exe in [None, *dict.fromkeys(e for e in found if e)]:
        try:
            return p.chromium.launch(
                executable_path=exe,
                args=["--no-sandbox", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"],
            )
        except Exception as exc:  # this browser is missing or broken: try the next
            errors.append(f"{exe or 'playwright chromium'}: {str(exc).splitlines()[0]}")
    pytest.skip("no Chromium that Playwright can launch: " + "; ".join(errors))


@pytest.fixture(scope="module")
def browser():
    sync_api = pytest.importorskip(
        "playwright.sync_api", reason="Playwright is not installed (pip install playwright)"
    )
    with sync_api.sync_playwright() as p:
        b = _launch(p)
        yield b
        b.close()


@pytest.fixture(scope="module")
def report_url(print_table, tmp_path_factory):
    rows, folder = print_table
    out = tmp_path_factory.mktemp("browser")
    index = build_report(rows, out, scan_dirs=[folder])  # as the main job: renders, validation
    alone = tmp_path_factory.mktemp("alone") / "index.html"
    shutil.copy(index, alone)  # the page travels alone: nothing beside it
    return alone.as_uri()


def _open(browser, url, width):
    page = browser.new_page(viewport={"width": width, "height": 900})
    seen = {"console": [], "requests": [], "errors": []}
    page.on(
        "console",
        lambda m: seen["console"].append(m.text) if m.type == "error" else None,
    )
    page.on("pageerror", lambda e: seen["errors"].append(str(e)))

    def route(r):
        if r.request.url != url and not r.request.url.startswith("data:"):
            seen["requests"].append(r.request.url)
            return r.abort()
        return r.continue_()

    page.route("**/*", route)
    page.goto(url)
    page.wait_for_load_state("load")
    return page, seen


@pytest.mark.parametrize("width", WIDTHS)
def test_report_in_a_browser(browser, report_url, width, tmp_path):
    page, seen = _open(browser, report_url, width)
    overflow = page.evaluate(
        "document.documentElement.scrollWidth - document.documentElement.clientWidth"
    )
    assert overflow <= 0, f"the page scrolls sideways by {overflow} px at {width} px"
    figures = page.locator("main figure")
    n = figures.count()
    assert n >= 20  # charts, scans, outlines, renders, the 3D view
    for i in range(n):
        f = figures.nth(i)
        f.scroll_into_view_if_needed()
        box = f.bounding_box()
        assert f.is_visible() and box["width"] > 50 and box["height"] > 50, i
    images = page.evaluate(
        "[...document.images].filter(i => i.src).map(i => [i.complete, i.naturalWidth])"
    )
    assert images and all(ok and w > 0 for ok, w in images)  # every image decoded
    assert page.locator("#tire3d").get_attribute("data-ready") == "1"
    page.locator("#tire3d canvas").scroll_into_view_if_needed()
    page.wait_for_timeout(300)
    shot = tmp_path / "viewer.png"
    page.locator("#tire3d canvas").screenshot(path=shot)
    px = np.asarray(Image.open(shot).convert("RGB")).astype(int)
    assert px.std() > 10, "the 3D view drew the tire"
    page.close()
    assert seen["console"] == [] and seen["errors"] == [], seen
    assert seen["requests"] == [], seen["requests"]


def test_tables_sort_filter_and_scans_enlarge(browser, report_url):
    page, seen = _open(browser, report_url, 1400)
    count = page.locator("#paired-table-count")
    page.fill("input[data-filter='paired-table']", "drum 6.9")
    assert count.inner_text() == "2 of 8 rows"
    page.fill("input[data-filter='paired-table']", "")
    assert count.inner_text() == "8 of 8 rows"
    header = page.locator("#paired-table thead th", has_text="length [mm]").first
    col = page.evaluate("h => [...h.parentNode.children].indexOf(h)", header.element_handle())
    header.click()
    cells = page.locator(f"#paired-table tbody tr td:nth-child({col + 1})").all_inner_texts()
    values = [float(c) for c in cells]
    assert values == sorted(values) and values != [float(c) for c in cells[::-1]]
    header.click()
    cells = page.locator(f"#paired-table tbody tr td:nth-child({col + 1})").all_inner_texts()
    assert [float(c) for c in cells] == sorted(values, reverse=True)
    page.locator("img.zoomable").first.click()
    assert page.locator("#lightbox").evaluate("d => d.open")
    page.keyboard.press("Escape")
    assert not page.locator("#lightbox").evaluate("d => d.open")
    page.close()
    assert seen["console"] == [] and seen["errors"] == [] and seen["requests"] == []


def test_printed_tables_fit_the_page(browser, report_url):
    page, _ = _open(browser, report_url, 1047)  # A4 landscape less 10 mm margins at 96 dpi
    page.emulate_media(media="print")
    wide = page.evaluate(
        """() => [...document.querySelectorAll('main table')]
             .filter(t => t.getBoundingClientRect().right > document.body.clientWidth + 1)
             .map(t => t.id || t.className)"""
    )
    assert wide == []
    assert page.evaluate("getComputedStyle(document.querySelector('nav.toc')).display") == "none"
    page.close()


def test_multi_panel_figures_stack_on_small_screens(browser, report_url):
    """Below 600 px each panel of a multi-panel figure is its own crop, one below the
    other, at a readable scale; at 1400 px the wide figure shows and the stack hides."""
    page, seen = _open(browser, report_url, 400)
    trends = page.locator("figure.chart .stacked").first
    trends.scroll_into_view_if_needed()
    crops = trends.locator(".stack > svg")
    assert crops.count() >= 3
    boxes = [crops.nth(k).bounding_box() for k in range(crops.count())]
    assert all(b["width"] > 250 for b in boxes), boxes
    assert all(b["height"] > 120 for b in boxes[:-1]), boxes  # panels (then the legend)
    assert all(b2["y"] >= b1["y"] + b1["height"] - 1 for b1, b2 in itertools.pairwise(boxes))
    assert trends.locator(":scope > svg").bounding_box()["width"] <= 2  # wide one hidden
    page.close()
    wide, _ = _open(browser, report_url, 1400)
    assert not wide.locator("figure.chart .stack").first.is_visible()
    assert wide.locator("figure.chart .stacked > svg").first.bounding_box()["width"] > 600
    wide.close()
    assert seen["console"] == [] and seen["errors"] == [], seen
