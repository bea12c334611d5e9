"""Model vs print comparison and report (issue 5; sections 4.1.1, 6.2, Table 4-1)."""

import csv
import math
import re
import shutil
import subprocess
import sys
from html.parser import HTMLParser
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose

import contactpatch.compare as cmp
from contactpatch.report import SECTIONS, build_report, read_table
from contactpatch.trends import drum_plate_ratios, power_law_fit, sign_agreement, trend_table
from inkprint.batch import Options, run_batch

SAMPLES = Path(__file__).resolve().parents[2] / "assets" / "prints"


@pytest.fixture(scope="module")
def print_table(tmp_path_factory):
    """A batch table of a subset of the bundled scans (one tire, 4 sheets, 8 prints)."""
    d = tmp_path_factory.mktemp("subset")
    for f in sorted(SAMPLES.glob("tire06_*.jpg")):
        shutil.copy(f, d / f.name)
    manifest = [r for r in read_table(SAMPLES / "manifest.csv") if r["file"].startswith("tire06_")]
    with (d / "manifest.csv").open("w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=list(manifest[0]))
        w.writeheader()
        w.writerows(manifest)
    res = run_batch(
        None,
        d / "prints.csv",
        manifest=d / "manifest.csv",
        options=Options(sensitivity=False),
        workers=2,
        progress=False,
    )
    return res.rows, d


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


def test_pairing_solves_each_case_once_and_records_failures(print_table, monkeypatch):
    rows, _ = print_table
    calls = []
    real = cmp.solve_case
    monkeypatch.setattr(cmp, "solve_case", lambda *a: calls.append(a) or real(*a))
    heavy = dict(rows[0], load_N="50000", print="9")
    odd = dict(rows[0], tire_id="", tire="no such tire", print="8")
    paired = cmp.pair_prints([*rows, *rows, heavy, odd])
    assert len(calls) == len({(r["pressure_bar"], r["load_N"], r["surface"]) for r in rows}) + 1
    by_print = {r["print"]: r for r in paired[-2:]}
    assert (
        by_print["9"]["model_status"] == "error" and "largest load" in by_print["9"]["model_error"]
    )
    assert by_print["8"]["model_status"] == "error" and "tire" in by_print["8"]["model_error"]
    ok = [r for r in paired[: len(rows)]]
    assert all(r["model_status"] == "ok" for r in ok)
    for r in ok:
        assert_allclose(r["ratio_length"], float(r["length_mm"]) / r["model_length_mm"])
        # prints are shorter than the model's pointed patch (section 6.2.1)
        assert r["ratio_length"] < 1.0


def test_power_law_slopes_recovered_on_synthetic_tables():
    rng = np.random.default_rng(0)
    rows = []
    for tire, (b, c) in {"A": (-0.7, 1.0), "B": (-0.45, 0.55)}.items():
        for p in (2.0, 4.0, 6.9, 9.0):
            for f in (304.0, 450.0, 731.0):
                y = 3.0 * p**b * f**c * (1 + 1e-6 * rng.standard_normal())
                rows.append(
                    {
                        "tire": tire,
                        "surface": "plate",
                        "status": "ok",
                        "model_status": "ok",
                        "pressure_bar": p,
                        "load_N": f,
                        "length_mm": y,
                        "model_length_mm": 2 * p**-0.4 * f**0.4,
                        "width_mm": y / 10,
                        "model_width_mm": y / 11,
                        "hull_area_mm2": y * y,
                        "model_area_mm2": y * y,
                    }
                )
    t = {(r["tire"], r["quantity"]): r for r in trend_table(rows)}
    assert_allclose(
        [t["A", "length"]["print_pressure_exp"], t["A", "length"]["print_load_exp"]],
        [-0.7, 1.0],
        rtol=0.01,
    )
    assert_allclose(
        [t["B", "area"]["print_pressure_exp"], t["B", "area"]["print_load_exp"]],
        [-0.9, 1.1],
        rtol=0.01,
    )
    assert_allclose(t["A", "length"]["model_pressure_exp"], -0.4, rtol=0.01)
    fit = power_law_fit([1, 2, 3], [5, 5, 5], [1, 2**0.5, 3**0.5])
    assert_allclose(fit["b"], 0.5) and math.isnan(fit["c"])
    agree = {(a["quantity"], a["variable"]): a for a in sign_agreement(trend_table(rows))}
    assert (
        agree["length", "pressure"]["agree"] == 2
        and agree["length", "pressure"]["print_increases"] == 0
    )


def test_drum_plate_summary_like_table_4_1(print_table):
    rows, _ = print_table
    pairs, summary = drum_plate_ratios(rows)
    assert len(pairs) == 4
    s = {r["quantity"]: r for r in summary}
    # the sample scans follow Table 4-1's means: drum prints shorter and wider
    assert s["length_mm"]["mean"] < 1.0 < s["width_mm"]["mean"]
    assert_allclose(s["length_mm"]["mean"], 0.92, atol=0.03)
    assert s["length_mm"]["min"] <= s["length_mm"]["mean"] <= s["length_mm"]["max"]


def test_cli_compare_and_report(print_table, tmp_path):
    _, d = print_table
    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "contactpatch.cli",
            "compare",
            str(d / "prints.csv"),
            "-o",
            str(tmp_path / "paired.csv"),
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert out.returncode == 0, out.stderr
    assert len(read_table(tmp_path / "paired.csv")) == 8
    rep = subprocess.run(
        [
            sys.executable,
            "-m",
            "contactpatch.cli",
            "report",
            str(d / "prints.csv"),
            "-o",
            str(tmp_path / "rep"),
            "--no-renders",
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert rep.returncode == 0, rep.stderr
    assert (tmp_path / "rep" / "index.html").is_file()
    bad = subprocess.run(
        [
            sys.executable,
            "-m",
            "contactpatch.cli",
            "report",
            str(tmp_path / "none.csv"),
            "-o",
            str(tmp_path / "x"),
        ],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert bad.returncode == 2 and "Traceback" not in bad.stderr
