"""The report's parts (issue 13): exponent errors, the SVG plotter and figures, scans
and outlines, the 3D view's data, the worker process, and a report of many prints."""

import base64
import io
import json
import math
import re
import shutil
import xml.etree.ElementTree as ET

import numpy as np
import pytest
from numpy.testing import assert_allclose
from PIL import Image

from contactpatch import build_report, pair_prints
from contactpatch.study import figures as F
from contactpatch.study import report as R
from contactpatch.study.samples import synthetic_print_rows
from contactpatch.study.sheets import locate_scans, outline_svg, qa_overlay, set_aside, sheets_of
from contactpatch.study.style import tire_colours
from contactpatch.study.svgplot import linear_ticks, log_ticks, nice_limits, tick_label
from contactpatch.study.trends import power_law_fit
from contactpatch.study.uncertainty import fit_with_errors
from contactpatch.study.viewer import viewer_case, viewer_html
from contactpatch.study.worker import Job

# --- exponents with their errors -----------------------------------------------------


def test_fit_with_errors_matches_the_fit_and_the_textbook_error():
    rng = np.random.default_rng(1)
    p = np.repeat([2.0, 4.0, 6.9, 9.0], 3)
    f = np.tile([304.0, 450.0, 731.0], 4)
    y = 3.0 * p**-0.5 * f**0.8 * np.exp(0.02 * rng.standard_normal(p.size))
    fit = fit_with_errors(p, f, y)
    ref = power_law_fit(p, f, y)
    assert_allclose([fit["b"], fit["c"]], [ref["b"], ref["c"]])
    assert fit["n"] == 12 and fit["dof"] == 9
    # ordinary least squares: cov = s^2 (A^T A)^-1
    A = np.column_stack([np.ones(p.size), np.log(p), np.log(f)])
    coef, *_ = np.linalg.lstsq(A, np.log(y), rcond=None)
    s2 = np.sum((np.log(y) - A @ coef) ** 2) / 9
    se = np.sqrt(np.diag(s2 * np.linalg.inv(A.T @ A)))
    assert_allclose([fit["b_se"], fit["c_se"]], se[1:])
    assert_allclose(fit["b_ci95"], 2.2621571628 * se[1], rtol=1e-8)  # t(0.975, 9)


def test_an_exact_fit_has_no_error_estimate():
    fit = fit_with_errors([2.0, 4.0, 2.0], [300.0, 300.0, 500.0], [1.0, 2.0, 3.0])
    assert fit["dof"] == 0 and math.isfinite(fit["b"]) and math.isnan(fit["b_se"])
    one = fit_with_errors([2.0, 4.0], [300.0, 300.0], [1.0, 2.0])
    assert one["dof"] == 0 and math.isnan(one["c"])


# --- the SVG plotter and the figures -------------------------------------------------


def test_ticks_are_round_and_plain():
    assert linear_ticks(0, 1500) == [0, 500, 1000, 1500]
    assert linear_ticks(0.6, 1.45) == [0.6, 0.8, 1.0, 1.2, 1.4]
    assert nice_limits(47.7, 139.1, zero=True) == (0.0, 150.0)
    assert log_ticks(3.5, 7.5, [4.0, 6.9, 4.0]) == [4.0, 6.9]  # the data's own values
    assert log_ticks(60, 140) == [60, 80, 100, 120, 140]  # under a decade: linear steps
    assert [tick_label(x) for x in (4.0, 6.9, 1e-17, 1200.0, 0.25)] == [
        "4",
        "6.9",
        "0",
        "1200",
        "0.25",
    ]


def _paired(print_table):
    return pair_prints(print_table[0])


def test_figures_are_well_formed_svg_with_literal_names(print_table):
    rows = [dict(r, tire="Tire $x^2$ & <b>") for r in print_table[0]]
    paired = pair_prints([dict(r, tire_id=6) for r in rows])
    colours = tire_colours(r["tire"] for r in paired)
    tables = R.compute_tables(rows)
    svgs = [
        F.area_vs_length_width(paired, colours),
        F.ratio_summary(paired, colours),
        F.load_per_area(paired, colours),
        F.tire_trends(paired, "Tire $x^2$ & <b>", colours["Tire $x^2$ & <b>"], name="t0"),
        F.drum_vs_plate(tables.drum_plate_summary, tables.drum_plate_model_summary),
    ]
    for svg in svgs:
        root = ET.fromstring(svg.split("?>", 1)[1])  # well-formed XML
        assert root.tag.endswith("svg") and root.get("viewBox")
    texts = "".join(svgs)
    assert "Tire $x^2$ &amp; &lt;b&gt;" in texts  # written literally, escaped
    # one colour per tire in every figure: the tire's colour fills the prints' markers
    assert all(colours["Tire $x^2$ & <b>"] in s for s in svgs[:3])


def test_trend_figure_ticks_at_the_data_values(print_table):
    paired = _paired(print_table)
    tire = paired[0]["tire"]
    svg = F.tire_trends(paired, tire, "#0072B2", name="t")
    labels = re.findall(r">([0-9.]+)</text>", svg)
    assert {"4", "6.9", "304", "500"} <= set(labels)
    assert not any("x10" in t or "e+" in t for t in labels)


# --- scans, outlines, set-aside lists ------------------------------------------------


def test_scans_are_found_by_name_and_checked_by_content(print_table, tmp_path):
    rows, folder = print_table
    found = locate_scans(rows, [folder])
    assert set(found) == {r["file"] for r in rows}
    # a different file under the same name is not taken for the scan
    decoy = tmp_path / "decoy"
    decoy.mkdir()
    name = rows[0]["file"]
    shutil.copy(folder / rows[2]["file"], decoy / name)
    assert locate_scans(rows, [decoy]).get(name) != decoy / name


def test_qa_overlay_draws_the_hulls(print_table):
    rows, folder = print_table
    sheet = sheets_of(rows)[rows[0]["file"]]
    jpeg = qa_overlay(folder / rows[0]["file"], sheet, max_side=600)
    img = np.asarray(Image.open(io.BytesIO(jpeg)).convert("RGB")).astype(int)
    assert max(img.shape[:2]) == 600
    green = (img[..., 1] > 110) & (img[..., 0] < 90) & (img[..., 2] < 90)
    assert green.sum() > 200  # the hull outlines


def test_outline_svg_one_scale(print_table):
    paired = _paired(print_table)
    a = outline_svg(paired[0], 150.0, "#0072B2", width=40.0)
    b = outline_svg(paired[1], 150.0, "#0072B2", width=40.0)
    vb = re.compile(r'viewBox="([^"]+)"')
    assert vb.search(a).group(1) == vb.search(b).group(1) == "-20.0 -81.0 40.0 162.0"
    root = ET.fromstring(a)
    kinds = [el.tag.split("}")[-1] for el in root]
    assert kinds[:3] == ["polygon", "ellipse", "polygon"]  # print hull, ellipse, model
    pts = np.array([[float(v) for v in p.split(",")] for p in root[0].get("points").split()])
    # centred, rolling direction up: the hull is tall and thin about the origin
    assert np.ptp(pts[:, 1]) > 5 * np.ptp(pts[:, 0]) and abs(pts.mean(axis=0)).max() < 3
    assert outline_svg({"print": 0}, 150.0, "#000") == ""


def test_set_aside_is_read_when_the_table_has_it():
    assert set_aside([{"file": "a"}]) is None
    assert set_aside([{"set_aside": '["label", "ruler"]'}]) == ["label", "ruler"]
    assert set_aside([{"rejected": "dust; label"}]) == ["dust", "label"]
    assert set_aside([{"rejected": ""}]) == []


# --- the 3D view ---------------------------------------------------------------------


def test_viewer_case_arrays(print_table):
    case = R.representative_cases(print_table[0])[0]
    import tiremesh as tm

    data = viewer_case(tm.solve(case.case), "low load")
    pos = np.frombuffer(base64.b64decode(data["positions"]), "<f4").reshape(-1, 3)
    idx = np.frombuffer(base64.b64decode(data["indices"]), "<u2").reshape(-1, 3)
    assert data["index_bits"] == 16
    val = np.frombuffer(base64.b64decode(data["values"]), "<f4")
    assert len(val) == len(pos) and idx.max() == len(pos) - 1
    assert data["lo"] <= val.min() and val.max() <= data["hi"]
    outline = np.frombuffer(base64.b64decode(data["outline"]), "<f4").reshape(-1, 3)
    assert_allclose(outline[0], outline[-1])  # closed
    html = viewer_html([data])
    assert "http" not in html.replace("http://www.w3.org", "") and "<script>" in html
    assert json.loads(re.search(r'id="viewer-data">(.*?)</script>', html).group(1))["cases"]


def test_viewer_case_same_mesh_as_build_mesh(print_table):
    """The viewer meshes without trimesh: the same arrays as build_mesh's."""
    import tiremesh as tm
    from contactpatch.study.viewer import VIEWER_MESH
    from tiremesh.mesh import build_mesh

    patch = tm.solve(R.representative_cases(print_table[0])[-1].case)
    data = viewer_case(patch, "x")
    m = build_mesh(patch, **VIEWER_MESH)
    pos = np.frombuffer(base64.b64decode(data["positions"]), "<f4").reshape(-1, 3)
    idx = np.frombuffer(base64.b64decode(data["indices"]), "<u2").reshape(-1, 3)
    val = np.frombuffer(base64.b64decode(data["values"]), "<f4")
    assert_allclose(pos, np.asarray(m.mesh.vertices, "<f4"), rtol=0, atol=0)
    np.testing.assert_array_equal(idx, m.mesh.faces)
    assert_allclose(val, np.asarray(m.point_data["radial_deformation"], "<f4"), rtol=0, atol=0)


# --- the worker process ----------------------------------------------------------------


def test_worker_returns_values_and_raises_errors():
    assert Job(math.hypot, 3.0, 4.0).result() == 5.0
    assert Job(round, 2.675, ndigits=1).result() == 2.7
    with pytest.raises(ValueError, match="math domain error"):
        Job(math.sqrt, -1.0).result()


# --- many prints ---------------------------------------------------------------------


def test_a_report_of_200_prints_aggregates_and_folds(tmp_path):
    rows = synthetic_print_rows(200)
    index = build_report(rows, tmp_path, renders=False, validation=False)
    text = index.read_text()
    assert text.count("<tr>") >= 200 and 'data-filter="paired-table"' in text
    # aggregate figures, not a panel per print; per-print drawings folded per tire
    assert text.count('<figure id="fig-') == 4 + 4
    assert text.count("<details>") == 4 and "<details open>" not in text
    assert text.count('<figure class="outline-card">') == 200
    assert len(text) < 2_500_000


def test_t975_table_is_scipys_quantile():
    """The tabulated t quantiles are scipy's, bit for bit (no number of the report
    changes), and larger degrees of freedom still ask scipy."""
    from scipy.special import stdtrit

    from contactpatch.study.uncertainty import T975, t975

    for dof in range(1, len(T975) + 2):
        assert t975(dof) == float(stdtrit(dof, 0.975))
    assert_allclose(t975(2), 4.302653, rtol=1e-6)


def test_stack_html_crops_each_panel_and_the_legend():
    from contactpatch.study.svgplot import LegendItem, Plot, stack_html

    plot = Plot(900, 400)
    for k in range(3):
        p = plot.panel(80 + 280 * k, 40, 200, 250, xlim=(0, 1), ylim=(0, 1))
        plot.axes(p, xlabel="x", ylabel="y" if k == 0 else "")
    plot.legend(
        [LegendItem("tire A", "#D55E00"), LegendItem("tire B", "#0072B2")], 80, 340, width=800
    )
    svg = plot.svg("demo")
    stack = stack_html(svg)
    boxes = re.findall(r'viewBox="([^"]+)"[^>]*><use href="#demo-all"/>', stack)
    assert len(boxes) == 4  # three panels, then the legend laid out again
    x0, _, w, _ = map(float, boxes[1].split())
    assert x0 >= 80 + 200 and x0 + w <= 80 + 2 * 280  # panel 2 alone, not its neighbours
    assert float(boxes[3].split()[1]) > 400  # the narrow legend lies below the wide view
    assert svg.count(">tire A</text>") == 2
    single = Plot(400, 300)
    single.panel(60, 20, 300, 240, xlim=(0, 1), ylim=(0, 1))
    assert stack_html(single.svg("one")) == ""  # one panel: scales, no stack
    empty = Plot(400, 300)
    empty.axes(empty.panel(60, 20, 300, 240, xlim=(0, 1), ylim=(0, 1)), xticks=[], yticks=[])
    assert "<svg" in empty.svg("empty")  # a panel without ticks (no points) draws
