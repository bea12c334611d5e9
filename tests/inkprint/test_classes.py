"""Issue 11: each failure class of real scans, generated with exact truth
(inkprint.synth_cases), gives the right numbers or a flag / a clear error.

The bar per print: length and width within 1 %, hull area within 2 % of the truth;
a print that cannot be measured from the file (clipped, photographed at an angle, a
mark on its outline) must be flagged, never a silent wrong number.
"""

import dataclasses
import math

import numpy as np
import pytest

import inkprint as ip
from inkprint.accuracy import SILENT, compare
from inkprint.analyze import own_axis
from inkprint.batch import Job, Options, process_file
from inkprint.synth import PrintSpec, SheetSpec, render_sheet, save_scan
from inkprint.synth_cases import make_case, write_case

FAST = Options(sensitivity=False)


def outcomes(tmp_path, kind, seed, dpi=150.0, options=FAST):
    """Write one case, analyse it as a batch would (its manifest row), compare."""
    case = make_case(kind, seed=seed, dpi=dpi)
    path, manifest, truth = write_case(case, tmp_path, f"{kind}_{seed}")
    job = Job(str(path), {(-1, -1): manifest[0]}, path.name)
    rows = process_file(job, options=options)
    return compare(rows, truth), rows


def assert_passes(results):
    bad = [r for r in results if r["outcome"] not in ("pass", "flagged", "error_ok")]
    assert not bad, bad


def scan_of(spec: SheetSpec) -> tuple:
    img, truths = render_sheet(spec)
    return ip.Scan(img, 25.4 / spec.dpi, "given"), truths


def within(m, t):
    return (
        abs(m.length / t.length - 1) <= 0.01
        and abs(m.width / t.width - 1) <= 0.01
        and abs(m.hull_area / t.hull_area - 1) <= 0.02
    )


# -- whole footprints ---------------------------------------------------------------


@pytest.mark.parametrize("seed", [0, 3])
def test_group_blobs_wide_groove_knobs_make_one_print(tmp_path, seed):
    # knobs as far apart as they are wide: before, one "print" per knob row
    results, rows = outcomes(tmp_path, "mtb", seed)
    assert_passes(results)
    assert all(r["n_blobs"] > 10 for r in rows)  # many knobs, one print each


@pytest.mark.parametrize("apart", [110.0, 72.0])
def test_group_blobs_keeps_two_wide_groove_prints_apart(apart):
    # 6.5 mm between knobs: prints 65 mm and 27 mm apart (over 4 x their own gaps;
    # the pattern rule links gaps up to group_pattern_factor = 3 x)
    p = [
        PrintSpec(90, 45, (80, 60 + apart), 0.0, "mtb", block=5, gap=6.5, unevenness=0.0),
        PrintSpec(90, 45, (80, 60), 0.0, "mtb", block=5, gap=6.5, unevenness=0.0),
    ]
    scan, truths = scan_of(SheetSpec(tuple(p), size=(160, 230), specks=0))
    r = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x")
    assert len(r.prints) == 2
    assert all(within(q.metrics, t) for q, t in zip(r.prints, truths, strict=True))


def test_group_blobs_car_ribs_make_one_print(tmp_path):
    # ribs between 8-14 mm circumferential grooves (every car print tried split 3-4 ways)
    results, rows = outcomes(tmp_path, "car", 1)
    assert_passes(results)
    assert len(rows) == 1 and rows[0]["axis_source"] == "manifest"


def test_group_blobs_car_grooves_as_wide_as_the_pattern_rule_allowed(tmp_path):
    # mixed set 4265, file 36 (150 dpi): circumferential grooves of 13.9 mm, 2.57 x
    # the 5.4 mm lateral ones and 0.84 x the blocks: with group_pattern_factor 2.5
    # the first rib was a print of its own (width -21.7 %, and a spurious print)
    results, rows = outcomes(tmp_path, "car", 4265 * 100_003 + 36, dpi=None)
    assert_passes(results)
    assert len(rows) == 1


def test_group_blobs_group_mm_overrides_the_footprint_rule():
    spec = PrintSpec(120, 140, (100, 110), 0.0, "car", exponent=4.0, block=25, gap=12)
    scan, _ = scan_of(SheetSpec((spec,), size=(200, 220), specks=0))
    mask = ip.binarize(scan.grey, mm_per_px=scan.mm_per_px).mask
    whole = ip.group_blobs(mask, mm_per_px=scan.mm_per_px)
    split = ip.group_blobs(
        mask, mm_per_px=scan.mm_per_px, options=ip.AnalysisOptions(group_mm=2.0)
    )
    assert len(whole) == 1 and len(split) > 4  # blocks apart with a 2 mm override
    with pytest.raises(ip.InvalidInput, match="group_mm"):
        ip.AnalysisOptions(group_mm=0.0)


# -- rolling direction ----------------------------------------------------------------


def test_analyze_scan_rolling_axis_given_for_a_print_wider_than_long(tmp_path):
    results, rows = outcomes(tmp_path, "wide", 0)
    assert_passes(results)
    row = rows[0]
    assert row["width_mm"] > row["length_mm"] and row["axis_source"] == "manifest"


def test_analyze_scan_auto_axis_says_so_and_flags_near_round_prints():
    p = PrintSpec(50.0, 60.0, (60, 60), 0.0, "slick", unevenness=0.0)
    scan, (t,) = scan_of(SheetSpec((p,), size=(120, 120), specks=0))
    auto = ip.analyze_scan(scan, sensitivity=False)
    given = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x")
    m = auto.prints[0].metrics
    assert auto.axis_source == "auto" and auto.rows()[0]["axis_source"] == "auto"
    assert math.isclose(m.length, t.width, rel_tol=0.01)  # the longer axis: swapped
    assert "axis_uncertain" in auto.prints[0].flags and auto.prints[0].status == "ok"
    assert given.axis_source == "given" and within(given.prints[0].metrics, t)
    with pytest.raises(ip.InvalidInput, match="rolling_axis"):
        ip.analyze_scan(scan, rolling_axis="z")


@pytest.mark.parametrize("seed", [0, 1])
def test_analyze_scan_print_turned_against_the_given_axis_is_flagged(tmp_path, seed):
    # a print taped 2-10 degrees askew, rolling axis x from the manifest: along x it
    # reads up to +27 % wide; it must be flagged, never a silent number
    results, rows = outcomes(tmp_path, "turned", seed)
    assert [r["outcome"] for r in results] == ["flagged", "flagged"], results
    assert all("axis_misaligned" in r["flags"] for r in rows)
    assert all("--rolling-axis auto" in r["warnings"] for r in rows)


def test_own_axis_finds_the_turn_of_a_print_and_its_error():
    p = PrintSpec(80.0, 20.0, (60, 60), 4.0, "slick", unevenness=0.0)
    scan, _ = scan_of(SheetSpec((p,), size=(120, 120), specks=0))
    res = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x")
    turn, excess = own_axis(res.prints[0].hull_px, 0.0)
    assert turn == pytest.approx(4.0, abs=0.3)
    assert excess > 0.05  # the width along x: 80 sin 4 deg over 20 mm
    assert "axis_misaligned" in res.prints[0].flags
    square = ip.analyze_scan(
        scan_of(SheetSpec((dataclasses.replace(p, angle=0.0),), size=(120, 120), specks=0))[0],
        sensitivity=False,
        rolling_axis="x",
    )
    assert own_axis(square.prints[0].hull_px, 0.0)[1] < 0.002
    assert square.prints[0].flags == ()


# -- marks that are not prints ------------------------------------------------------------


def test_sort_ink_label_touching_a_print_is_set_aside(tmp_path):
    results, rows = outcomes(tmp_path, "label", 1)
    assert_passes(results)
    assert "text" in rows[0]["set_aside"]


@pytest.mark.parametrize("seed", [1, 6])
def test_sort_ink_ruler_across_a_print_is_set_aside(tmp_path, seed):
    results, rows = outcomes(tmp_path, "ruler", seed)
    assert_passes(results)
    assert "line" in rows[0]["set_aside"]


@pytest.mark.parametrize(
    ("kind", "k"),
    [("label", 96), ("ruler", 84)],  # files of the seed-4242 mixed set
)
def test_analyze_scan_mark_pulling_a_print_edge_is_flagged(tmp_path, kind, k):
    # a label's letter feet merged into the print's edge (+3.7 % width) and a ruler
    # crossing it (+1.3 %) passed unflagged: without the ink next to the mark the
    # print is narrower by more than options.mark_pull, so it is flagged, never silent
    results, rows = outcomes(tmp_path, kind, 4242 * 100_003 + k, dpi=None)
    assert not [r for r in results if r["outcome"] in SILENT], results
    (row,) = rows
    if kind == "ruler":
        # the ruler's own ink beside the edge now reads as paper, so it no longer
        # pulls the outline out (+1.3 % -> +0.8 %, within the bar); where it crosses
        # the edge the edge is bounded by the tangents either side (under a pixel),
        # and its pull (0.4 %) is under mark_pull: measured, unflagged, or flagged
        assert results[0]["outcome"] in ("pass", "overflagged"), results
        assert abs(results[0]["err_width"]) < 0.01
        return
    # the label's feet: measured without the ink under its letters (the hull spans
    # the notch), width +0.60 %; the tangents either side bound the hidden edge within
    # edge_uncertainty: measured, unflagged, or flagged (inkprint.analyze._under_text)
    assert results[0]["outcome"] in ("pass", "overflagged"), results
    assert abs(results[0]["err_width"]) < 0.01
    if row["status"] == "flagged":
        assert "mark_on_edge" in row["flags"]


def test_sort_ink_gridlines_never_merge_into_a_print(tmp_path):
    results, rows = outcomes(tmp_path, "grid", 1)
    assert not [r for r in results if r["outcome"] in SILENT], results
    assert all("gridlines" in r["set_aside"] for r in rows)
    found = [r for r in results if r["expect"] == "measure"]
    assert len(found) == 2 and all(r["outcome"] in ("pass", "overflagged") for r in found)
    for row in rows:  # flagged only with its reason: a gridline along the outline
        if row["status"] == "flagged":
            assert row["flags"] == "mark_on_edge" and "a mark set aside covers" in row["warnings"]
        else:
            assert row["flags"] == ""


def test_analyze_scan_faint_gridlines_are_taken_out_or_flag_the_prints(tmp_path):
    # 150 dpi chart paper, 5 mm grid of faint 0.28 mm lines (one along a print's edge
    # once widened it by 8 % without a flag): the grid is found and taken out; a
    # print whose edge grazes a line is flagged, the other measures within the bar.
    # Print #1's tread slivers on the lines were taken out with them (hull area
    # -3.0 %, unflagged) until ink darker than the lines was kept as ink
    results, rows = outcomes(tmp_path, "grid", 4243 * 100_003 + 95)
    assert not [r for r in results if r["outcome"] in SILENT], results
    assert all("gridlines" in r["set_aside"] for r in rows)
    assert {r["outcome"] for r in results} <= {"overflagged", "pass"}
    flagged = [r for r in rows if r["status"] == "flagged"]
    assert all(r["flags"] == "mark_on_edge" for r in flagged)
    # the line along print #0's edge was flagged by its whole width; the ink beside
    # it is darker than the line, so only a pixel can hide under it: both measure
    # within the bar (+0.7 % and +0.5 % in width)
    assert sum(r["outcome"] == "pass" for r in results) >= 1


def test_analyze_scan_gridlines_crossing_a_print_leave_it_measured():
    # the lines are taken out outside the print (inkprint.gridlines), so they neither
    # join it nor flag it; the print measures within the bar (issue 11, item 3)
    from inkprint.synth_effects import Grid

    p = PrintSpec(70.0, 18.0, (64.0, 62.0), 20.0, "slick")
    sheet = SheetSpec(
        (p,), dpi=200.0, size=(128.0, 124.0), specks=10, marks=(Grid(10.0, 0.2, 0.6),)
    )
    scan, (t,) = scan_of(sheet)
    r = ip.analyze_scan(scan, sensitivity=False)
    assert len(r.prints) == 1
    assert within(r.prints[0].metrics, t)
    # near its tips a horizontal line runs along the turned print's edge for a
    # millimetre: the line's far side bounds the edge there (a worst case, not the
    # error: the print measures within 0.2 %), so it may be flagged for that only
    if r.prints[0].flags:
        assert r.prints[0].flags == ("mark_on_edge",)
        assert "runs along its edge" in r.prints[0].warnings[0]


@pytest.mark.parametrize("seed", [0, 1])
def test_analyze_scan_noise_or_texture_page_gives_no_print_found(tmp_path, seed):
    results, rows = outcomes(tmp_path, "noise", seed)
    assert_passes(results)
    (row,) = rows
    assert row["status"] == "error" and "no print found" in row["error"]
    assert "noise" in row["error"] or "texture" in row["error"]


def test_no_print_message_names_what_was_set_aside():
    a = np.full((400, 400), 245, np.uint8)
    import cv2

    cv2.putText(a, "NOTES", (40, 200), cv2.FONT_HERSHEY_SIMPLEX, 2.0, 20, 2, cv2.LINE_AA)
    with pytest.raises(ip.NoInk, match=r"set aside .*text") as e:
        ip.analyze_scan(ip.Scan(a, 0.1, "given"), sensitivity=False)
    # the reason names what was set aside (the letters), never dust specks
    msg = str(e.value)
    assert msg.startswith("no print found on the sheet: set aside ")
    assert "dust" not in msg and "too little ink" not in msg
    kinds = msg.split("set aside ", 1)[1].split(" (", 1)[0]
    assert set(kinds.replace(",", "").split()[1::2]) <= {"text", "writing"}, msg


# -- light and scale -------------------------------------------------------------------


@pytest.mark.parametrize("seed", [1, 3])
def test_prepare_page_flattens_a_gradient_and_a_shadow(tmp_path, seed):
    results, rows = outcomes(tmp_path, "light", seed)
    assert_passes(results)
    assert all("uneven_light" in r["flags"] and r["status"] == "ok" for r in rows)
    assert all("flattened before thresholding" in r["warnings"] for r in rows)


def test_prepare_page_finds_the_page_of_a_flat_on_photo(tmp_path):
    results, rows = outcomes(tmp_path, "photo", 2)
    assert_passes(results)
    assert all(r["scale_source"] == "given" for r in rows)


def test_prepare_page_flags_a_photo_not_taken_flat_on(tmp_path):
    results, rows = outcomes(tmp_path, "tilted", 1)
    assert_passes(results)  # every print flagged
    assert all(r["status"] == "flagged" and "perspective" in r["flags"] for r in rows)
    assert "not flat-on" in rows[0]["warnings"]


@pytest.mark.parametrize("dpi", [72, 96])
def test_read_scan_distrusts_camera_and_screen_dpi(tmp_path, dpi):
    img, _ = render_sheet(SheetSpec((PrintSpec(60, 10, (50, 40)),), size=(100, 80)))
    path = save_scan(img, tmp_path / "cam.jpg", dpi=dpi)
    with pytest.raises(ip.ScaleUntrusted, match=r"--dpi.*--trust-dpi"):
        ip.read_scan(path)
    assert isinstance(ip.ScaleUntrusted("x"), ip.ScaleMissing)
    assert ip.read_scan(path, trust_dpi=True).dpi == pytest.approx(dpi, rel=1e-3)
    assert ip.read_scan(path, dpi=150).dpi == 150


def test_read_scan_72_dpi_file_with_the_real_dpi_in_the_manifest(tmp_path):
    results, _ = outcomes(tmp_path, "dpi72", 0)
    assert_passes(results)
    bare, rows = outcomes(tmp_path, "dpi72_bare", 0)
    assert_passes(bare) and rows[0]["error"].startswith("ScaleUntrusted")


def test_iter_scans_reads_every_pdf_page(tmp_path):
    results, rows = outcomes(tmp_path, "pdf", 0)
    assert_passes(results)
    pages = sorted({r["page"] for r in rows})
    assert len(pages) >= 2 and pages == list(range(len(pages)))
    path = tmp_path / "pdf_0.pdf"
    only = process_file(
        Job(str(path), {}, path.name), options=Options(sensitivity=False, pages=(1,))
    )
    assert {r["page"] for r in only} == {1}
    with pytest.raises(ip.InvalidInput, match="page"):
        list(ip.iter_scans(path, pages=[99]))


def test_analyze_scan_print_off_the_sheet_is_flagged_clipped(tmp_path):
    results, rows = outcomes(tmp_path, "clipped", 0)
    assert_passes(results)
    flagged = [r for r in rows if r["status"] == "flagged"]
    assert len(flagged) == 1 and flagged[0]["flags"] == "clipped"
    assert "image's edge" in flagged[0]["warnings"]


# -- edge spots and small prints ------------------------------------------------------------


@pytest.mark.parametrize("seed", [0, 1])
def test_edge_spots_keep_tip_blocks_and_drop_faint_specks_on_the_edge(tmp_path, seed):
    # dark clipped knobs at the tips continue the tread (kept: length); faint specks
    # touching the outline bore no load (dropped: width)
    results, _ = outcomes(tmp_path, "tips", seed)
    assert_passes(results)


def test_edge_field_faint_speck_touching_the_edge_adds_nothing():
    import shapely

    p = PrintSpec(60.0, 12.0, (50, 40), 0.0, "slick", unevenness=0.0, halo_touching=8)
    scan, (t,) = scan_of(SheetSpec((p,), dpi=300, size=(100, 80), specks=0, grain=0.0))
    m = ip.analyze_scan(scan, sensitivity=False).prints[0].metrics
    assert within(m, t)
    assert shapely.box(0, 0, 1, 1).area == 1  # (shapely available for the truth)


def test_analyze_scan_tiny_prints_are_measured(tmp_path):
    results, rows = outcomes(tmp_path, "tiny", 0, dpi=600.0)
    assert_passes(results)
    assert all(r["area_mm2"] < 100 for r in rows)  # under the old 100 mm^2 floor


def test_find_prints_size_floor_scales_with_the_sheet_and_is_an_option():
    opts = ip.AnalysisOptions()
    assert opts.patch_area_floor(60_000) == pytest.approx(6.0)
    assert opts.patch_area_floor(6_000) == pytest.approx(0.6)
    assert ip.AnalysisOptions(min_patch_area_mm2=50.0).patch_area_floor(6_000) == 50.0
    p = PrintSpec(9.0, 4.0, (20, 15), 0.0, "slick", unevenness=0.0)
    scan, (t,) = scan_of(SheetSpec((p,), dpi=600, size=(40, 30), specks=0))
    assert within(ip.analyze_scan(scan, sensitivity=False).prints[0].metrics, t)
    with pytest.raises(ip.NoInk, match="too little ink"):
        ip.analyze_scan(scan, options=ip.AnalysisOptions(min_patch_area_mm2=50.0))


def test_classic_sheets_still_measure_right(tmp_path):
    results, _ = outcomes(tmp_path, "classic", 3)
    assert_passes(results)


def test_analyze_scan_ruler_grey_beside_the_edge_adds_nothing(tmp_path):
    # ruler seed 9 at 200 dpi: where the ruler crossed the print's widest point its
    # grey beside the kept ink pulled the sub-pixel outline a pixel out on both
    # sides: width +2.9 %, unflagged; the ink set aside now reads as paper there
    results, _ = outcomes(tmp_path, "ruler", 9, dpi=None)
    assert [r["outcome"] for r in results] == ["pass"], results


def test_analyze_scan_halo_speck_on_a_gridline_stays_apart(tmp_path):
    # grid seed 27: a halo speck on a gridline beside the print's edge was joined to
    # it through the line (width +8.6 %, unflagged)
    results, _ = outcomes(tmp_path, "grid", 27, dpi=None)
    assert not [r for r in results if r["outcome"] in SILENT], results
    assert all(r["outcome"] == "pass" for r in results), results


def test_analyze_scan_small_clipped_knob_print_is_flagged_not_missing(tmp_path):
    # 4249/0074: the last 9 x 7 mm of a knobby print at the sheet's edge (52 % of its
    # hull inked) was taken for a letter and went missing; cut by the image's edge it
    # is measured and flagged clipped
    results, rows = outcomes(tmp_path, "clipped", 4249 * 100_003 + 74, dpi=None)
    assert not [r for r in results if r["outcome"] in SILENT], results
    assert any("clipped" in r["flags"] for r in rows)


def test_analyze_scan_ruler_tick_foot_on_the_edge_is_flagged(tmp_path):
    # 4251/0048 (200 dpi): a ruler's tick meets the print's edge at a shallow angle;
    # its last 1.5 mm stayed print ink, 3-4 px proud of the edge: width +4.5 %,
    # unflagged. The pixels within half a stroke of the tick now bound its pull
    results, rows = outcomes(tmp_path, "ruler", 4251 * 100_003 + 48, dpi=None)
    assert not [r for r in results if r["outcome"] in SILENT], results
    (row,) = rows
    assert row["flags"] == "mark_on_edge" and "touches its edge" in row["warnings"]


def test_analyze_scan_tip_sliver_on_a_gridline_is_kept(tmp_path):
    # 4252/0077 (200 dpi): print #0's last tip sliver lay on a vertical gridline and
    # went with it (length -3.5 %, unflagged); darker than the line, it stays ink.
    # Print #1's edge runs under a horizontal line: flagged, its error now -1.1 %
    # (was -5.3 %)
    results, _ = outcomes(tmp_path, "grid", 4252 * 100_003 + 77, dpi=None)
    assert not [r for r in results if r["outcome"] in SILENT], results
    (ok,) = [r for r in results if r["outcome"] == "pass"]
    assert abs(ok["err_length"]) < 0.002


@pytest.mark.parametrize("seed", [8, 10])
def test_analyze_scan_edge_beside_a_line_bounded_by_its_last_pixel(tmp_path, seed):
    # where the print's ink beside a gridline is darker than the line, ink under the
    # line would show: only the edge's last pixel can hide there. Seed 8 (150 dpi):
    # that pixel is 1.3 % of the width, flagged (the error is -1.3 %); seed 10: the
    # print whose whole-line bound flagged it at +0.01 % now passes
    results, _ = outcomes(tmp_path, "grid", seed, dpi=None)
    assert not [r for r in results if r["outcome"] in SILENT], results
    if seed == 10:
        assert sum(r["outcome"] == "pass" for r in results) >= 1


def test_analyze_scan_print_almost_off_the_sheet_is_flagged_not_missing(tmp_path):
    # 4254/0020 (200 dpi): a print 97 % off the sheet left a 60 x 2.5 mm strip at
    # the top edge, 4.6 % of the other print's ink: dropped as a fragment, so the
    # print went missing; cut by the image's edge it is kept, flagged clipped
    results, rows = outcomes(tmp_path, "clipped", 4254 * 100_003 + 20, dpi=None)
    assert not [r for r in results if r["outcome"] in SILENT], results
    assert sum("clipped" in r["flags"] for r in rows) == 1


def test_analyze_scan_texture_blob_at_the_image_edge_is_not_a_print(tmp_path):
    # 4254/0063: on a texture page a 6 x 4 mm blob cut by the image's corner was
    # kept as a (flagged) print instead of "no print found"
    results, rows = outcomes(tmp_path, "noise", 4254 * 100_003 + 63, dpi=None)
    assert [r["outcome"] for r in results] == ["error_ok"], results
    assert rows[0]["status"] == "error" and "texture" in rows[0]["error"]


def test_sort_ink_line_filling_its_own_box_is_measured(tmp_path):
    # clipped seed 6 at 150 dpi: a straight line piece filling its own box had no
    # paper in it; its distance transform was unbounded and the width inf crashed
    # the sheet (OverflowError); now measured and flagged clipped
    results, _ = outcomes(tmp_path, "clipped", 6)
    assert_passes(results)
