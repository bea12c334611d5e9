"""contactpatch.study.validate: the model against the measurements of Dressel (2013).

Expectations cite the dissertation section they come from; the measured values are
rows of ``shared/reference/measured-dressel2013.csv`` (its ``locator`` column gives the
seed-text lines).
"""

import csv
import io
import math
import re
import subprocess
import sys
from collections import Counter
from pathlib import Path

import numpy as np
import pytest

import contactpatch
import tiremesh as tm
from contactpatch.study import validate as V
from contactpatch.study import validate_pages as P
from contactpatch.study import validate_relax as vr
from contactpatch.study.validate_data import MEASURED_CSV, read_measurements
from contactpatch.study.validate_fit import MEASURED_TRAIL_PCT
from contactpatch.study.validate_points import classify_all, parse_load, parse_surface
from tiremesh.beam import solve_beam
from tiremesh.io import read_table

REFERENCE = (
    Path(__file__).resolve().parents[4] / "shared" / "reference" / "measured-dressel2013.csv"
)


@pytest.fixture(scope="module")
def run(tmp_path_factory):
    """One full validation, written to a folder (the slow part, ~5 s)."""
    out = tmp_path_factory.mktemp("validation")
    v = V.validate(out)
    return v, out


def by_quantity(v):
    return {s["quantity"]: s for s in v.statistics}


# --- the measurements -------------------------------------------------------------


@pytest.mark.skipif(not REFERENCE.is_file(), reason="shared/reference not beside the repo")
def test_packaged_copy_is_the_reference_file():
    assert REFERENCE.read_text(encoding="utf-8") == MEASURED_CSV


def test_every_row_gets_a_status():
    rows, sha = read_measurements()
    points = classify_all(rows)
    assert len(rows) == len(points) == 195  # measured-dressel2013.md: 195 rows
    assert len(sha) == 64
    assert all(p.status for p in points)
    compared = Counter(p.quantity for p in points if p.status == "compared")
    # Appendix B captions: 13 static lateral stiffnesses (measured-dressel2013.md)
    assert compared["lateral_stiffness"] == 13
    # cornering: Appendix B 2 (one repeats Table 4-4), Table 4-4 2, Table 4-5 device 3 4,
    # Table 4-6 10 measured rows
    assert compared["cornering_stiffness"] == 2 - 1 + 2 + 4 + 10
    assert compared["camber_stiffness"] == 6 + 2 + 4 + 10
    # trail: Appendix B 5, Table 4-4 2, one repeated
    assert compared["pneumatic_trail"] == 6
    status = Counter(p.status for p in points)
    assert status["not a measurement"] == 10  # Table 4-6 interpolated rows
    assert status["model input"] == 14  # Table 3-2 arc lengths


def test_classification_details():
    points = {p.row: p for p in classify_all(read_measurements()[0])}
    kinds = Counter((p.status, p.reason.split(" (")[0]) for p in points.values())
    # device 1 of Table 4-5: rim width not recorded (measured-dressel2013.md)
    assert kinds[("not modelled", "device 1: rim width not recorded")] == 4
    # Appendix B prints N/mm and 1/mm for one measurement: one is a duplicate
    lateral = [p for p in points.values() if p.csv_quantity.endswith("static_lateral_stiffness")]
    assert Counter(p.status for p in lateral) == {"compared": 13, "duplicate": 13}
    # Table 4-4's two runs are both kept (section 4.2)
    runs = [
        p for p in points.values() if p.source == "Table 4-4" and p.quantity == "camber_stiffness"
    ]
    assert [p.status for p in runs] == ["compared", "compared"]
    # Section 4.1.8: 450 N and 55 kg = 540 N -> ambiguous, modelled but not counted
    amb = [p for p in points.values() if p.status == "ambiguous"]
    assert {p.quantity for p in amb} == {"pneumatic_trail", "ellipse_length"}
    assert all(p.condition.load_N == 450 and p.alt_load_N == 540 for p in amb)


def test_parsers():
    assert parse_load("33 kg")[0] == pytest.approx(33 * 9.81)  # Appendix C's g
    assert parse_load("304") == (304.0, pytest.approx(math.nan, nan_ok=True))
    assert parse_load("450 or 540 (caption inconsistent)") == (450.0, 540.0)
    assert math.isnan(parse_load("324-731 (range of program)")[0])
    assert parse_surface("TU Delft 2.5 m drum, non-skid tape (device 3)") == "drum"
    assert parse_surface("flat plate") == "flat"
    assert parse_surface("drum vs flat plate") == ""
    assert parse_surface("device 1 (UWM towed cart, flat track)") is None


# --- the taut beam (section 5.9) --------------------------------------------------


def test_free_section_stiffness_scales_with_pressure():
    tire = tm.get_tire(5)
    k1, k2 = vr.free_section_stiffness(tire, 0.3), vr.free_section_stiffness(tire, 0.6)
    assert k1 > 0
    assert k2 == pytest.approx(2 * k1, rel=1e-9)  # dS = p (r1 - r2), equation 5-25
    # the string's decay length sqrt(T / k) does not depend on the pressure (T = p pi r^2)
    s = vr.BeamRelaxation(0.0)
    assert s.length(tire, 0.3) == pytest.approx(s.length(tire, 0.6), rel=1e-9)


@pytest.mark.parametrize("EI", [2.0e4, 5.0e6])  # real and complex decay rates
def test_decay_length_matches_the_clamped_beam(EI):
    """The exponential with l = sqrt((T + 2 sqrt(k EI)) / k) carries the same integral as
    equation 5-30 beyond a clamped patch end; checked with tiremesh.beam.solve_beam
    holding a stiff 'patch' at u0 in the middle of a long beam (the stiffer the patch,
    the closer the clamp: 0.5 to 0.8 % short at this stiffness)."""
    k, T, u0, a = 0.3, 250.0, 1.0, 40.0
    x = np.linspace(-1500.0, 1500.0, 60001)
    patch = np.abs(x) <= a
    big = 1e8
    u = solve_beam(x, EI=EI, T=T, k=np.where(patch, big, k), f=np.where(patch, big * u0, 0.0))
    beyond = x > a
    integral = np.trapezoid(u[beyond], x[beyond])
    assert integral == pytest.approx(u0 * vr.decay_length(k, T, EI), rel=0.015)


def test_point_load_decay():
    k, T = 0.2, 200.0
    assert vr.point_load_decay(k, T, 0.0) == pytest.approx(math.sqrt(T / k))
    assert vr.point_load_decay(k, T, 1e6) > math.sqrt(T / k)


def test_fit_recovers_a_known_modulus():
    """Synthetic cases built from a modulus are fitted back to it."""
    lengths = vr.FIT_LENGTHS
    cases = []
    for tid, (k, T, inertia) in enumerate([(0.3, 200.0, 3e3), (0.1, 400.0, 2e4), (0.6, 150, 1e3)]):
        values = 10.0 + 0.8 * lengths  # force rising with the decay length
        true = vr.FitCase(tid, k, T, inertia, lengths, values, 1.0)
        cases.append(vr.FitCase(tid, k, T, inertia, lengths, values, float(true.model(7.0))))
    assert vr.fit_modulus(cases) == pytest.approx(7.0, rel=1e-3)
    loto = vr.leave_one_tire_out(cases, vr.fit_modulus)
    assert set(loto) == {0, 1, 2}
    assert all(v == pytest.approx(7.0, rel=1e-3) for v in loto.values())
    assert math.isnan(vr.fit_modulus([]))


# --- the full validation ----------------------------------------------------------


def test_counts_and_finite_values(run):
    v, _ = run
    st = by_quantity(v)
    assert {q: st[q]["n"] for q in ("lateral_stiffness", "cornering_stiffness")} == {
        "lateral_stiffness": 13,
        "cornering_stiffness": 17,
    }
    assert st["camber_stiffness"]["n"] == 22
    assert st["pneumatic_trail"]["n"] == 6
    for p in v.points:
        if p.status == "compared":
            assert math.isfinite(p.model) and p.ratio > 0, p.row
    assert v.settings["n_rows"] == 195


def test_intrinsic_and_geometric_agreement(run):
    v, _ = run
    pts = {p.row: p for p in v.points}
    ink_plate = next(
        p for p in pts.values() if p.quantity == "ink_area" and p.condition.surface == "flat"
    )
    # area x pressure = load is intrinsic to the model (6.1.1): 304 N / 0.6895 N/mm^2
    assert ink_plate.model == pytest.approx(304 / 0.6895, rel=1e-6)
    assert ink_plate.ratio == pytest.approx(304 / 0.6895 / 461.7, rel=1e-6)  # 4.1.1
    # the radius solved from the arc length (Table 5-2) matches Table 3-2's radius,
    # printed to 0.1 mm
    st = by_quantity(v)
    assert 0.99 < st["tire_radius"]["min_ratio"] <= st["tire_radius"]["max_ratio"] < 1.01


def test_lateral_stiffness_and_the_fit(run):
    v, _ = run
    st = by_quantity(v)["lateral_stiffness"]
    variants = {r["variant"]: r for r in v.variants}
    loto = variants["taut beam, E fitted (leave one tire out)"]
    appendix = variants["Appendix C rate"]
    # the reported values are the leave-one-tire-out predictions
    assert st["rms_log_error"] == pytest.approx(loto["rms_log_error"])
    assert 0.8 < st["median_ratio"] < 1.25
    # the taut beam beats Appendix C's fixed rate (5.8) out of sample
    assert loto["rms_log_error"] < 0.5 * appendix["rms_log_error"]
    assert appendix["median_ratio"] > 2  # 0.993 per mm: several times too stiff
    assert 0 <= v.fit.modulus <= vr.MODULUS_MAX
    assert {r["tire_id"] for r in v.loto} == {1, 3, 5, 6, 8, 11, 12}
    assert all(
        p.modulus == v.fit.loto_modulus[p.condition.tire_id]
        for p in v.points
        if p.quantity == "lateral_stiffness" and p.status == "compared"
    )


def test_no_single_decay_length_fits_lateral_and_cornering(run):
    v, _ = run
    corner = {r["variant"].split(" ")[0]: r for r in v.cornering}
    lateral = {r["variant"]: r for r in v.variants}
    # with the decay that fits the static lateral stiffness, cornering is far too low
    assert corner["taut"]["median_ratio"] < 0.6
    assert by_quantity(v)["cornering_stiffness"]["median_ratio"] == pytest.approx(
        corner["taut"]["median_ratio"]
    )
    # Appendix C's 0.993 per mm (5.8) gets cornering about right, lateral far too high
    assert 0.8 < corner["Appendix"]["median_ratio"] < 1.25
    assert lateral["Appendix C rate"]["median_ratio"] > 2
    # the trail (a patch integral) is several times the measured (4.1.8) either way
    assert by_quantity(v)["pneumatic_trail"]["median_ratio"] > 2


def test_trends_against_the_dissertation(run):
    v, _ = run
    t = {(r["quantity"], r["variable"]): r for r in v.trends}
    # 6.2.4 item 1: normalized lateral stiffness rises with pressure, falls with load;
    # "the Rotta model predicts both of these trends"
    assert t[("lateral_stiffness", "pressure")]["agree"] == "yes"
    assert t[("lateral_stiffness", "load")]["agree"] == "yes"
    # 6.2.4 item 3a: camber stiffness trends are "the opposite of what the Rotta model
    # with no lateral displacement predicts"
    assert t[("camber_stiffness", "load")]["agree"] == "no"
    assert t[("camber_stiffness", "pressure")]["agree"] == "no"
    # 6.2.2: lateral stiffness rises with rim width in model and measurements
    assert t[("lateral_stiffness", "rim_width")]["model"] == "rises"
    assert t[("cornering_stiffness", "load")]["n_pairs"] == 5  # Table 4-6 load pairs


def test_no_sign_mismatch_left_out(run):
    v, _ = run
    assert all(s["n_not_positive"] == 0 for s in v.statistics)
    from contactpatch.study.validate_stats import ratio_stats

    assert ratio_stats([1.0, 2.0, -1.0])["n_not_positive"] == 1


def test_figures_svg_plain_text_report_colours(run):
    """The validation's figures are the report's SVG: text as text, the 1:1 line,
    every panel's title, the report's colour of each tire, no matplotlib."""
    import xml.etree.ElementTree as ET

    from contactpatch.study.style import tire_colours
    from contactpatch.study.validate_figures import PANELS, measured_vs_model, relaxation_figure

    v, _ = run
    data = v.to_dict()
    svg = measured_vs_model(data["points"], data["statistics"])
    root = ET.fromstring(svg.split("?>", 1)[1])  # well-formed XML
    ns = "{http://www.w3.org/2000/svg}"
    texts = [t.text or "" for t in root.iter(f"{ns}text")]
    assert "1:1" in texts and not any("$" in t for t in texts)
    assert all(any(title.split()[0] in t for t in texts) for title in PANELS)
    names = {r["tire"] for r in data["points"] if isinstance(r.get("tire_id"), int)}
    for colour in set(tire_colours(names).values()):
        assert f'fill="{colour}"' in svg
    relax = relaxation_figure(data["fit_curve"], data["variants"])
    assert "casing modulus E [N/mm²]" in relax and "<image" not in relax
    # decade ticks on the modulus axis: no 1-2-5 labels running into each other
    assert ">10000</text>" in relax and ">2000</text>" not in relax


def test_outputs_written(run):
    v, out = run
    rows = read_table(out / "points.csv")
    assert len(rows) == 195
    assert rows[0].keys() >= {"row", "status", "measured", "model", "ratio", "locator"}
    for name in V.TABLES:
        assert (out / f"{name}.csv").is_file() and (out / f"{name}.json").is_file()
    for name in V.FIGURES:
        assert (out / "figures" / f"{name}.svg").stat().st_size > 5_000
        assert not (out / "figures" / f"{name}.png").exists()
    md = (out / "summary.md").read_text()
    assert "What the model cannot follow" in md and "normalized cornering stiffness" in md.lower()
    assert not list(out.glob(".*"))  # atomic writes leave no temporary files
    assert v.to_dict()["limits"]


def test_report_section_escapes_and_caches(run, monkeypatch):
    _, out = run
    html, md = V.report_section(out)
    assert html.startswith('<section id="validation">') and html.rstrip().endswith("</section>")
    assert html.count("<svg xmlns") == 2 and "data:image/png" not in html  # inline SVG
    assert "&lt;0.15 to &gt;0.35" in html  # the stated range of 8.1.2, escaped
    assert "<0.15" not in html
    assert f"]({out.name}/figures/measured_vs_model.svg)" in md
    assert md.startswith("## Validation against the measurements")

    def boom(*a, **k):
        raise AssertionError("should have used the cached results")

    monkeypatch.setattr(V, "run_validation", boom)
    html2, _ = V.report_section(out)  # cached: same inputs and model source
    assert html2 == html
    assert contactpatch.report_section is V.report_section


def test_report_section_numbers_follow_the_report(run):
    _, out = run
    html, md = V.report_section(out)
    # ratios to 3 decimals, right-aligned; no 4-6 digit noise, no tiny spreads
    assert re.search(r"<td class=num>1\.06[0-9]</td>", html)
    assert "sd 1.5e-11" not in html and "sd 0," in html
    assert "e-1" not in re.sub(r"base64,[^\"]+", "", html)
    # one pressure unit: load / area in bar; the modulus says it is one
    assert "<td>N/mm^2</td>" not in html and "<td>bar</td>" in html
    assert "casing modulus E without it [N/mm²]" in html
    assert "| bar |" in md and "---:|" in md
    # the figures sit in a scroll box rather than shrinking
    assert html.count('<div class="figscroll') == 2


def test_validation_fmt_by_quantity():
    assert [P.fmt(v, k) for v, k in ((1.06173552, "median_ratio"), (1e-13, "ratio"))] == [
        "1.062",
        "0",
    ]
    assert P.fmt(6.8948, "pressure_bar") == "6.89" and P.fmt(304.0, "load_N") == "304"
    assert P.fmt(13, "n") == "13" and P.fmt(83.8652) == "83.87" and P.fmt(math.nan) == ""
    row = {"unit": "N/mm^2", "measured": 0.5, "model": 0.52, "ratio": 1.04}
    assert P.display_rows([row]) == [{"unit": "bar", "measured": 5.0, "model": 5.2, "ratio": 1.04}]


def test_report_section_recomputes_when_stale(tmp_path, monkeypatch):
    (tmp_path / "figures").mkdir()
    (tmp_path / "validation.json").write_text('{"settings": {"cache_key": "old"}}')
    called = []

    def fake_run(measurements=None):
        called.append(True)
        raise RuntimeError("recomputing")

    monkeypatch.setattr(V, "run_validation", fake_run)
    with pytest.raises(RuntimeError, match="recomputing"):
        V.report_section(tmp_path)
    assert called


def _subset_csv(path: Path, tires=("1:", "6:")) -> Path:
    rows = list(csv.DictReader(io.StringIO(MEASURED_CSV)))
    keep = [r for r in rows if r["tire"].startswith(tires) or r["tire"].startswith("all")]
    with path.open("w", newline="", encoding="utf-8") as fh:
        w = csv.DictWriter(fh, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(keep)
    return path


def test_cli_validate_on_a_subset(tmp_path):
    src = _subset_csv(tmp_path / "subset.csv")
    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "contactpatch.cli",
            "validate",
            "-o",
            str(tmp_path / "v"),
            "--measurements",
            str(src),
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert out.returncode == 0, out.stderr
    assert "static lateral stiffness" in out.stdout
    data = read_table(tmp_path / "v" / "statistics.json")
    st = {r["quantity"]: r for r in data}
    assert st["lateral_stiffness"]["n"] == 3  # tire 1 (5.52 bar) and tire 6 (two loads)
    assert (tmp_path / "v" / "index.html").is_file()
    checks = {r["item"]: r["agree"] for r in read_table(tmp_path / "v" / "summary_checks.json")}
    # Table 4-3 names tires 5, 10, 11, 12, none in the subset: no verdict, not a 'no'
    assert checks["table_4_3"] == "n/a"
    assert checks["table_4_1"] == "yes"


def test_cli_keeps_the_other_commands():
    from contactpatch.study.cli import build_parser

    p = build_parser()
    assert p.parse_args(["validate"]).output == "validation"
    assert p.parse_args(["compare", "x.csv", "-o", "y.csv"]).func.__name__ == "compare_command"
    assert p.parse_args(["report", "x.csv", "-o", "d"]).func.__name__ == "report_command"


def test_trail_kinematics_compares_every_kinematics_with_section_4_1_8(run):
    """Issue 10 item 5: the trail under each slip kinematics. The tread displaced ahead
    of the patch along the relaxation (Figure 4-15) moves the force forward, so its
    trail is shorter than the leading-edge anchor's and its share of the patch length
    lies nearer the measured mean (12.76 %, 4.1.8); the table is written and named in
    the limits."""
    v, out = run
    rows = {r["variant"]: r for r in v.trail}
    assert set(rows) == {"leading", "centre", "relaxation"}
    lead, relax = rows["leading"], rows["relaxation"]
    assert lead["n"] == relax["n"] == 6
    assert relax["median_ratio"] < lead["median_ratio"]
    gap = lambda r: abs(r["trail_pct_of_length"] - MEASURED_TRAIL_PCT)
    assert gap(relax) < gap(lead)
    assert (out / "trail_vs_slip_kinematics.csv").exists()
    assert any("slip kinematics" in s for s in v.to_dict()["limits"])
