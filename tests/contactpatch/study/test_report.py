"""contactpatch.study.report and .pages: the model vs print report (issue 5;
sections 4.1.1, 6.2, Table 4-1)."""

import math
import re
from html.parser import HTMLParser

from numpy.testing import assert_allclose

from contactpatch import build_report
from contactpatch.study.pages import SECTIONS, fmt
from contactpatch.study.report import compute_tables, report_config
from tiremesh.io import read_table


class Tables(HTMLParser):
    def __init__(self):
        super().__init__()
        self.tables, self.ids, self.imgs, self._cell = {}, set(), 0, None

    def handle_starttag(self, tag, attrs):
        a = dict(attrs)
        if "id" in a:
            self.ids.add(a["id"])
        if tag == "table":
            self.current = a.get("id")
            self.tables[self.current] = []
        elif tag == "tr":
            self.tables[self.current].append([])
        elif tag in ("td", "th"):
            self._cell = ""
        elif tag == "img":
            self.imgs += 1

    def handle_data(self, data):
        if self._cell is not None:
            self._cell += data

    def handle_endtag(self, tag):
        if tag in ("td", "th"):
            self.tables[self.current][-1].append(self._cell)
            self._cell = None


def test_report_end_to_end(print_table, tmp_path):
    rows, _ = print_table
    index = build_report(rows, tmp_path / "report", renders=True)
    text = index.read_text()
    parsed = Tables()
    parsed.feed(text)
    assert set(SECTIONS) <= parsed.ids
    assert {"paired-table", "trends-table", "drum-plate-table", "rim-table", "config"} <= set(
        parsed.tables
    )
    figures = {p.name for p in (tmp_path / "report" / "figures").iterdir()}
    for stem in (
        "area_vs_length_width",
        "load_per_area",
        "print_overlays",
        "drum_vs_plate",
        "trends_tire0",
    ):
        assert f"{stem}.png" in figures and f"{stem}.svg" in figures
    assert {"render_tire0_iso.png", "render_tire0_bottom.png"} <= figures
    assert parsed.imgs == 7  # 4 figures + 1 tire trend + 2 renders, embedded
    assert 'src="figures/' not in text  # self-contained: images are data URIs
    # numbers in the HTML equal the CSV's
    csv_rows = read_table(tmp_path / "report" / "tables" / "paired.csv")
    header, *body = parsed.tables["paired-table"]
    assert len(body) == len(csv_rows) == 8
    checked = 0
    for html_row, c in zip(body, csv_rows, strict=True):
        for col, cell in zip(header, html_row, strict=True):
            try:
                v = float(c[col])
            except ValueError:
                assert cell == c[col]
                continue
            assert_allclose(float(cell), v, rtol=1e-5)
            checked += 1
    assert checked > 100
    trends = read_table(tmp_path / "report" / "tables" / "trends.csv")
    header, *body = parsed.tables["trends-table"]
    for html_row, c in zip(body, trends, strict=True):
        i = header.index("print_pressure_exp")
        assert_allclose(float(html_row[i]), float(c["print_pressure_exp"]), rtol=1e-5)
    md = (tmp_path / "report" / "report.md").read_text()
    assert "decreases with pressure" in md and "| source |" in md


def test_report_is_stable(print_table, tmp_path):
    rows, _ = print_table
    a = build_report(rows, tmp_path / "a", renders=False)
    b = build_report(rows, tmp_path / "b", renders=False)
    for table in (tmp_path / "a" / "tables").iterdir():
        assert table.read_bytes() == (tmp_path / "b" / "tables" / table.name).read_bytes()
    strip = lambda t: re.sub(r"data:image/png;base64,[A-Za-z0-9+/=]+", "", t)
    assert strip(a.read_text()) == strip(b.read_text())
    assert (tmp_path / "a" / "figures" / "load_per_area.svg").read_bytes() == (
        tmp_path / "b" / "figures" / "load_per_area.svg"
    ).read_bytes()


def test_report_steps(print_table, tmp_path):
    rows, _ = print_table
    tables = compute_tables(rows)
    assert len(tables.paired) == len(rows)
    assert [*tables.as_dict()][:2] == ["paired", "trends"]
    sources = {r["source"] for r in tables.drum_plate_rows}
    assert sources == {"prints", "model", "dissertation (Table 4-1)"}
    config = report_config(rows, tables, source="x.csv")
    assert config["prints"] == 8 and config["source"] == "x.csv"
    assert "2.5 m drum" in config["surfaces"]


def test_fmt():
    assert [fmt(1), fmt(True), fmt(math.nan), fmt(1 / 3), fmt("2.50"), fmt("a"), fmt("")] == [
        "1",
        "True",
        "",
        "0.333333",
        "2.5",
        "a",
        "",
    ]
