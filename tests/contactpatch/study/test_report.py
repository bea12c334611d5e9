"""contactpatch.study.report and .pages: the model vs print report (issues 5, 13;
sections 4.1.1, 6.2, Table 4-1)."""

import base64
import dataclasses
import json
import math
import re
import sys
from html.parser import HTMLParser

import numpy as np
import pytest
from PIL import Image

from contactpatch import build_report
from contactpatch.study import report as R
from contactpatch.study.numbers import estimate, fixed, fmt, interval
from contactpatch.study.pages import PAIRED_VIEW, RIM_VIEW, SECTIONS, cell_text, html_page
from tiremesh.io import read_table


class Page(HTMLParser):
    """Tables (cells and their classes), ids, images, links and scripts of a page."""

    def __init__(self):
        super().__init__()
        self.tables, self.ids, self.imgs, self.urls = {}, [], [], []
        self.details, self.current, self._cell = [], None, None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.append(a["id"])
        for key in ("src", "href"):
            if key in a and a[key] is not None:
                self.urls.append(a[key])
        if tag == "table":
            self.current = a.get("id")
            self.tables[self.current] = []
        elif tag == "tr" and self.current:
            self.tables[self.current].append([])
        elif tag in ("td", "th") and self.current:
            self._cell = ["", a.get("class") or ""]
        elif tag == "img":
            self.imgs.append(a)
        elif tag == "details":
            self.details.append("open" in a)

    def handle_data(self, data):
        if self._cell is not None:
            self._cell[0] += data

    def handle_endtag(self, tag):
        if tag in ("td", "th") and self._cell is not None:
            self.tables[self.current][-1].append(tuple(self._cell))
            self._cell = None
        elif tag == "table":
            self.current = None


@pytest.fixture(scope="module")
def report(print_table, tmp_path_factory):
    rows, folder = print_table
    out = tmp_path_factory.mktemp("report")
    index = build_report(rows, out, renders=True, validation=False, scan_dirs=[folder])
    page = Page()
    page.feed(index.read_text())
    return index, page, rows


def test_report_sections_files_and_self_containment(report):
    index, page, _ = report
    text = index.read_text()
    assert set(SECTIONS) <= set(page.ids)
    assert len(page.ids) == len(set(page.ids)), "ids are unique"
    assert {"paired-table", "trends-table", "drum-plate-table", "rim-table", "config"} <= set(
        page.tables
    )
    figures = {p.name for p in (index.parent / "figures").iterdir()}
    for stem in ("area_vs_length_width", "ratios", "load_per_area", "drum_vs_plate"):
        assert f"{stem}.svg" in figures and f"{stem}.png" not in figures  # saved once
    assert "trends_tire0.svg" in figures
    # complete on its own: every image a data URI, links only to anchors in the page
    assert all(u.startswith(("data:", "#")) for u in page.urls), page.urls
    assert not re.search(r"""(src|href)=["'](https?:|//|figures/)""", text)
    assert "<meta name='viewport' content='width=device-width, initial-scale=1'>" in text
    # every figure inline: the 4 charts and one per tire, no mathtext markup
    assert text.count('<figure id="fig-') == 5 and "$" not in re.sub(
        r"<script.*?</script>", "", text
    )


def test_report_renders_three_representative_cases_at_1200_px(report):
    index, page, _ = report
    renders = [i for i in page.imgs if i.get("src", "").startswith("data:image/png")]
    alts = [i["alt"] for i in renders]
    assert [a.split(":")[0] for a in alts] == ["low load", "high load", "cambered, drum"]
    assert "drum 2.5 m" in alts[2] and "10 deg" in alts[2] and "model only" in alts[2]
    assert all((i["width"], i["height"]) == ("1200", "900") for i in renders)
    for stem in ("render_low_load", "render_high_load", "render_cambered_drum"):
        img = Image.open(index.parent / "figures" / f"{stem}.png")
        assert img.size == (1200, 900)
        px = np.asarray(img.convert("L"))
        assert px[: int(0.13 * 900)].min() < 80  # the title block has text


def test_numbers_are_formatted_by_quantity_and_match_the_csv(report):
    index, page, _ = report
    header, *body = page.tables["paired-table"]
    csv_rows = read_table(index.parent / "tables" / "paired.csv")
    assert len(body) == len(csv_rows) == 8
    keys = [c.key for c in PAIRED_VIEW]
    assert [h[0] for h in header] == [c.header for c in PAIRED_VIEW]
    for html_row, c in zip(body, csv_rows, strict=True):
        for key, (text, cls) in zip(keys, html_row, strict=True):
            assert text == cell_text(c, key), key
            if key in ("tire", "surface", "print_id", "model_status", "model_error"):
                assert "num" not in cls  # text left
            else:
                assert cls == "num"  # numbers right
    lengths = [row[keys.index("length_mm")][0] for row in body]
    assert all(re.fullmatch(r"\d+\.\d", t) for t in lengths)  # mm to 0.1
    areas = [row[keys.index("hull_area_mm2")][0] for row in body]
    assert all(re.fullmatch(r"\d+", t) for t in areas)  # mm^2 to 1
    ratios = [row[keys.index("ratio_length")][0] for row in body]
    assert all(re.fullmatch(r"\d\.\d{3}", t) for t in ratios)
    # one pressure unit: load / area shown in bar, with N/mm2 only in a tooltip
    q = body[0][keys.index("load_per_hull_area_N_mm2")][0]
    assert float(q) == pytest.approx(10 * float(csv_rows[0]["load_per_hull_area_N_mm2"]), abs=0.01)
    assert "N/mm" not in "".join(h[0] for h in header)


def test_exponents_carry_errors_and_exact_zeros_print_as_0(report):
    _, page, _ = report
    header, *body = page.tables["trends-table"]
    col = [h[0] for h in header].index("print: pressure exponent")
    assert all(" ± " in row[col][0] for row in body)
    dof = [h[0] for h in header].index("dof")
    assert {row[dof][0] for row in body} == {"1"}  # 4 prints, 3 parameters
    header, *body = page.tables["rim-table"]
    area = [h[0] for h in header].index(RIM_VIEW[-1].header)
    assert {row[area][0] for row in body} == {"0"}  # area = load / pressure: exactly 0


def test_scans_outlines_and_viewer_are_embedded(report):
    index, page, _ = report
    text = index.read_text()
    qa = [i for i in page.imgs if "zoomable" in (i.get("class") or "")]
    assert len(qa) == 4 and all(i["src"].startswith("data:image/jpeg;base64,") for i in qa)
    assert text.count('<figure class="outline-card">') == 8
    assert all(page.details)  # few prints: the scans and outlines are shown open
    data = re.search(r'<script type="application/json" id="viewer-data">(.*?)</script>', text)
    cases = json.loads(data.group(1))["cases"]
    assert [c["label"] for c in cases] == ["low load", "high load", "cambered, drum"]
    pos = np.frombuffer(base64.b64decode(cases[0]["positions"]), "<f4").reshape(-1, 3)
    faces = np.frombuffer(base64.b64decode(cases[0]["indices"]), "<u2").reshape(-1, 3)
    assert np.isfinite(pos).all() and faces.max() < len(pos) and len(faces) > 1000


def test_markdown_page(report):
    index, _, _ = report
    md = (index.parent / "report.md").read_text()
    assert "decreases with pressure" in md and "| source |" in md
    assert "(figures/area_vs_length_width.svg)" in md and " ± " in md


def test_report_is_stable(print_table, tmp_path):
    rows, folder = print_table
    a = build_report(rows, tmp_path / "a", renders=False, validation=False, scan_dirs=[folder])
    b = build_report(rows, tmp_path / "b", renders=False, validation=False, scan_dirs=[folder])
    for table in (tmp_path / "a" / "tables").iterdir():
        assert table.read_bytes() == (tmp_path / "b" / "tables" / table.name).read_bytes()
    assert a.read_text() == b.read_text()
    for svg in (tmp_path / "a" / "figures").iterdir():
        assert svg.read_bytes() == (tmp_path / "b" / "figures" / svg.name).read_bytes()


def test_report_steps(print_table):
    rows, _ = print_table
    tables = R.compute_tables(rows)
    assert len(tables.paired) == len(rows)
    assert [*tables.as_dict()][:2] == ["paired", "trends"]
    sources = {r["source"] for r in tables.drum_plate_rows}
    assert sources == {"prints", "model", "dissertation (Table 4-1)"}
    config = R.report_config(rows, tables, source="x.csv")
    assert config["prints"] == 8 and config["source"] == "x.csv"
    assert "2.5 m drum" in config["surfaces"]
    cases = R.representative_cases(rows)
    assert [(c.label, c.view) for c in cases] == [
        ("low load", "bottom"),
        ("high load", "bottom"),
        ("cambered, drum", "iso"),
    ]
    low, high, drum = (c.case.describe() for c in cases)
    assert low["load_N"] < high["load_N"] and low["pressure_bar"] == high["pressure_bar"]
    assert drum["surface"] == "drum:2500" and drum["camber_deg"] == pytest.approx(10)


def test_validation_section_only_when_its_module_is_importable(monkeypatch, tmp_path):
    monkeypatch.setitem(sys.modules, "contactpatch.study.validate", None)  # not installed
    assert R.validation_fragments(tmp_path) is None


def test_validation_fragment_goes_into_the_page_and_its_contents(print_table, tmp_path):
    rows, folder = print_table
    build_report(rows, tmp_path, renders=False, validation=False, scan_dirs=[folder])
    content = _content(rows, tmp_path, folder)
    page = html_page(content)
    assert '<section id="validation">' not in page
    section = '<section id="validation"><h2>Validation against measurements</h2></section>'
    page = html_page(dataclasses.replace(content, validation=(section, "")))
    assert page.index('id="rim"') < page.index('id="validation"') < page.index('id="renders"')
    assert '<a href="#validation">Validation against measurements</a>' in page


def _content(rows, out, folder):
    tables = R.compute_tables(rows)
    colours = R.tire_colours(r["tire"] for r in tables.paired)
    figs = R.draw_figures(tables, out / "figures", colours)
    return R.ReportContent(
        config=R.report_config(rows, tables),
        tables=tables,
        figures=figs,
        colours=colours,
        sheets=R.collect_sheets(tables.paired, [folder]),
        viewer=[],
        validation=None,
        facts=R.key_facts(tables, colours),
        expand_prints=True,
        outline_scale=(150.0, 40.0),
    )


def test_fmt_by_quantity():
    assert fmt(83.86516448067997, "length_mm") == "83.9"
    assert fmt(748.0593799217922, "hull_area_mm2") == "748"
    assert fmt(0.838682729469956, "ratio_length") == "0.839"
    assert fmt("4.0", "pressure_bar") == "4" and fmt(6.9, "pressure_bar") == "6.9"
    assert fmt(0.4063848514696553, "load_per_hull_area_N_mm2") == "4.06"  # in bar
    assert fmt(304.0, "load_N") == "304" and fmt(304.25, "load_N") == "304.2"
    assert fmt(2.98758337343112e-14, "dlog_area_dlog_rim") == "0"
    assert fmt(-0.0004, "ratio_area") == "0"  # no "-0.000"
    assert fmt(math.nan, "length_mm") == "" and fmt("", "length_mm") == ""
    assert fmt("Schwalbe $big$ 55-622", "tire") == "Schwalbe $big$ 55-622"
    assert fmt(1) == "1" and fmt(True) == "True" and fmt(1 / 3) == "0.3333"
    assert fixed(-1e-13, 3) == "0" and fixed(-0.04, 1) == "0"


def test_estimates_with_errors():
    assert estimate(-0.4704, 0.00021, 1) == "-0.4704 ± 0.0002"
    assert estimate(-0.507, 0.0191, 1) == "-0.507 ± 0.019"
    assert estimate(-1.0, 1e-16, 1) == "-1.00 ± 0"
    assert estimate(-0.5, math.nan, 0) == "-0.50 (exact fit, no error estimate)"
    assert estimate(math.nan, 0.1, 3) == ""
    assert interval(-0.5, 0.25, 1) == "95 % interval -0.750 to -0.250 (Student t, 1 dof)"
