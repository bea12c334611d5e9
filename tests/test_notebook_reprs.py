"""Issue 12, notebook use: short reprs without arrays, ``_repr_html_`` summaries and
``to_dataframe`` (pandas is in the test extras, so these run, never skip)."""

import math
import re

import numpy as np
import pandas as pd
import pytest
import shapely
from numpy.testing import assert_allclose

import contactpatch as cp
import inkprint as ip
import tiremesh as tm
from tests.inkprint.test_safety import FAST, small_sheet
from tiremesh.lateral import solve_lateral

T37 = tm.TireGeometry.from_size(37, 18.7)


def no_array(text: str) -> bool:
    """No numpy array printed: no 'array(', no '[' followed by many numbers."""
    return "array(" not in text and not re.search(r"\[\s*-?\d+\.?\d*(\s+-?\d+\.?\d*){5,}", text)


@pytest.fixture(scope="module")
def lateral():
    return solve_lateral(T37, load=400.0, pressure=0.4, lateral=1.0, relaxation=0.993)


def test_lateral_result_repr_short_with_forces_and_units(lateral):
    text = repr(lateral)
    assert text.startswith("LateralResult(") and len(text) < 300 and no_array(text)
    assert f"lateral_force={lateral.lateral_force:.4g} N" in text
    assert f"vertical_force={lateral.vertical_force:.4g} N" in text
    assert "pneumatic_trail=" in text and " mm" in text
    assert lateral.s.size > 50  # the arrays exist; they are just not printed


def test_lateral_result_repr_html_summary_table(lateral):
    html = lateral._repr_html_()
    assert "<table" in html and "LateralResult" in html and len(html) < 5000
    assert no_array(html)
    for key in ("lateral_force_N", "vertical_force_N", "pneumatic_trail_mm", "pressure_bar"):
        assert key in html
    assert f"{lateral.lateral_force:.4g}" in html


def test_patch_metrics_repr_short_no_arrays():
    m = cp.measure(shapely.box(0, 0, 100, 10))
    text = repr(m)
    assert text.startswith("PatchMetrics(") and len(text) < 200 and no_array(text)
    assert "length=100" in text and "width=10" in text and "area=1000" in text
    assert m.stations.size > 1  # not shown


def test_patch_metrics_repr_html_rows_and_escaped():
    m = cp.measure(shapely.box(0, 0, 100, 10))
    html = m._repr_html_()
    assert html.startswith("<table><caption>PatchMetrics</caption>") and len(html) < 4000
    assert no_array(html)
    cells = dict(re.findall(r"<th[^>]*>([^<]+)</th><td[^>]*>([^<]+)</td>", html))
    assert_allclose(float(cells["length_mm"]), 100.0)
    assert_allclose(float(cells["hull_area_mm2"]), 1000.0)
    assert "<script" not in html


def test_contact_patch_to_dataframe_one_row_per_section():
    patch = tm.solve(T37, load=400.0, pressure=0.4)
    df = patch.to_dataframe()
    assert isinstance(df, pd.DataFrame)
    table = patch.section_table()
    assert list(df.columns) == list(table)
    assert len(df) == len(next(iter(table.values())))
    assert_allclose(df["weight_mm"].sum(), np.sum(table["weight_mm"]))


def test_sheet_result_to_dataframe_rows_with_units(tmp_path):
    r = ip.analyze_scan(small_sheet(tmp_path / "s.png", length=60.0), sensitivity=False)
    df = r.to_dataframe()
    assert isinstance(df, pd.DataFrame) and len(df) == 1
    assert "length_mm" in df.columns
    assert math.isclose(df["length_mm"].iloc[0], 60.0, rel_tol=0.03)


def test_batch_result_to_dataframe(tmp_path):
    d = tmp_path / "scans"
    d.mkdir()
    small_sheet(d / "a.png")
    res = ip.run_batch(d, tmp_path / "r.csv", options=FAST, workers=1, progress=False)
    df = res.to_dataframe()
    assert isinstance(df, pd.DataFrame) and len(df) == 1 and df["status"].iloc[0] == "ok"


def test_print_result_repr_shows_units(tmp_path):
    r = ip.analyze_scan(small_sheet(tmp_path / "s.png"), sensitivity=False)
    p = r.prints[0]
    text = repr(p)
    assert len(text) < 200 and no_array(text)
    assert re.search(r"length \d+\.\d\d mm, width \d+\.\d\d mm, hull area \d+\.\d mm2", text)
    assert "length [mm]" in p._repr_html_()


def test_print_result_repr_in_pixels_without_a_scale(tmp_path):
    from PIL import Image

    path = small_sheet(tmp_path / "s.png")
    bare = tmp_path / "bare.png"
    Image.open(path).save(bare)  # no DPI metadata: no scale
    r = ip.analyze_scan(ip.read_scan(bare, allow_pixels=True), sensitivity=False)
    p = r.prints[0]
    assert r.unit == p.unit == "px"
    assert f"length {p.metrics.length:.2f} px" in repr(p) and " mm" not in repr(p)
    assert "length [px]" in p._repr_html_()
