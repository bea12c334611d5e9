"""Issue 11: each failure class of real scans, generated with exact truth
(inkprint.synth_cases), gives the right numbers or a flag / a clear error.

The bar per print: length and width within 1 %, hull area within 2 % of the truth;
a print that cannot be measured from the file (clipped, photographed at an angle, a
mark on its outline) must be flagged, never a silent wrong number.
"""

import dataclasses
import math
import re

import numpy as np
import pytest
from numpy.testing import assert_allclose

import inkprint as ip
from inkprint.accuracy import SILENT, compare
from inkprint.analyze import own_axis, settled_turn
from inkprint.batch import Job, Options, process_file
from inkprint.read import Scan
from inkprint.synth import PrintSpec, SheetSpec, render_sheet, save_scan
from inkprint.synth_cases import _band, make_case, write_case
from inkprint.synth_effects import Light, Text

from .drawn import drawn_scan

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
    # (seed 3: square to the sheet, its knob pattern's axis estimates disagree,
    # one -4.1 deg: flagged axis_misaligned, a judged flag, measured within the bar)
    assert_passes([r for r in results if r["flags"] != "axis_misaligned"])
    assert all(r["outcome"] in ("pass", "overflagged") for r in results)
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


def test_lone_elements_flags_a_knob_sized_print_beside_a_knob_pattern():
    # a 7 x 7 mm blob 22.5 mm from a knobby print (6.5 mm grooves): beyond the
    # groove limit (20 mm) it is a print of its own; within it (the grouping kept a
    # row of knobs apart: held-out 2026 sheet 6, seven "prints" of one knob each,
    # status ok) both are flagged grouping_uncertain
    from inkprint.analyze import _lone_elements

    big = PrintSpec(90, 45, (80, 60), 0.0, "mtb", block=5, gap=6.5, unevenness=0.0)
    knob = PrintSpec(7.0, 7.0, (144, 60), 0.0, "slick", unevenness=0.0, exponent=8.0)
    scan, _ = scan_of(SheetSpec((big, knob), size=(200, 130), specks=0, dpi=200.0))
    r = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x")
    assert sorted(p.n_blobs >= 4 for p in r.prints) == [False, True]
    assert all(p.flags == () for p in r.prints)
    near = _lone_elements(r.prints, scan.mm_per_px, ip.AnalysisOptions(group_groove_max_mm=25))
    assert all(p.flags == ("grouping_uncertain",) for p in near)
    assert all(re.search(r"print #\d", p.warnings[-1]) for p in near)
    assert _lone_elements(r.prints, scan.mm_per_px, ip.AnalysisOptions()) == r.prints


@pytest.mark.parametrize("angle", [4.0, -3.0, 7.0, 0.0])
def test_analyze_scan_knob_pattern_turned_is_measured_along_itself(angle):
    # a knob pattern (a fifth of its hull inked) turned against the given axis: its
    # hull's rectangle, least width and principal axis give the same length and
    # width (within axis_misaligned_excess), so it is measured along itself,
    # unflagged (before: flagged axis_misaligned beyond 1 degree for every knob
    # pattern, which a crooked sheet made of half the held-out knobby prints)
    p = PrintSpec(90, 45, (80, 60), angle, "mtb", block=5, gap=6.5, unevenness=0.0)
    scan, (t,) = scan_of(SheetSpec((p,), size=(160, 130), specks=0))
    (q,) = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x").prints
    assert q.metrics.solidity < 0.5
    assert q.metrics.orientation == pytest.approx(math.radians(angle), abs=0.002)
    assert q.flags == () and within(q.metrics, t)


@pytest.mark.parametrize(
    ("length", "width", "angle"), [(60, 40, 0.0), (60, 40, 3.0), (60, 40, 6.0), (60, 58, 6.0)]
)
def test_analyze_scan_coarse_knob_print_is_measured_along_its_tracks(length, width, angle):
    # a few knobs across (5 mm knobs, 6 mm grooves): the hull is their outer corners,
    # its rectangle, least width and principal axis agree on a turn that is not
    # there (-4.1 deg square to the sheet: width -1.4 %, unflagged; 60 x 58 turned
    # 6 deg: along x, +1.1 % long, unflagged); the knobs' tracks give the turn
    p = PrintSpec(length, width, (80, 60), angle, "mtb", exponent=2.0, unevenness=0.0)
    scan, (t,) = scan_of(SheetSpec((p,), size=(160, 130), specks=0))
    (q,) = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x").prints
    assert q.metrics.solidity < 0.5
    assert math.degrees(q.metrics.orientation) == pytest.approx(angle, abs=0.1)
    assert q.flags == () and within(q.metrics, t)


@pytest.mark.parametrize(
    ("length", "width", "angle", "block", "gap", "dpi", "uneven", "exponent"),
    [
        (58.1, 12.5, 0.7, 4.8, 2.9, 200, 0.03, 4.0),  # before: width +1.5 %, unflagged
        (52.2, 14.7, -0.88, 3.7, 3.4, 200, 0.14, 3.0),  # +1.05 %
        (81.5, 16.7, 0.69, 4.7, 2.6, 200, 0.13, 4.0),  # +1.66 %
        (25.3, 13.0, 0.92, 3.0, 2.6, 400, 0.0, 3.0),  # length +2.4 %, width +12.9 %
    ],
)
def test_analyze_scan_knob_print_turned_under_a_degree_is_measured_along_its_tracks(
    length, width, angle, block, gap, dpi, uneven, exponent
):
    # knob prints turned under a degree, their knobs' lateral profile a row of
    # plateaus: its sum of squares is flat over a degree (contrast 0.96-0.99, the
    # tracks not trusted), and with the hull's principal axis off the rectangle's
    # they were measured along the sheet, unflagged. The steps at the plateaus'
    # edges line up only along the tracks (treadaxis._measures)
    p = PrintSpec(
        length, width, (length / 2 + 20, width / 2 + 20), angle, "mtb",
        block=block, gap=gap, unevenness=uneven, exponent=exponent,
    )  # fmt: skip
    spec = SheetSpec((p,), size=(length + 40, width + 40), specks=0, dpi=float(dpi))
    scan, (t,) = scan_of(spec)
    (q,) = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x").prints
    assert q.flags == () and within(q.metrics, t), (
        q.metrics.length / t.length,
        q.metrics.width / t.width,
    )


def test_analyze_scan_knob_print_tip_knob_cut_thin_a_pattern_gap_out_is_its_own():
    # a knob print (2.6 mm knobs, 3.6 mm grooves) whose outline cut a tip knob to a
    # 2.4 x 1.3 mm piece 3.5 mm beyond the next knob: farther than
    # group_distance_mm, it was set aside as a pen mark (length -8.6 %, unflagged).
    # Off a block pattern's tip a lone convex piece may lie 1.5 x that distance out
    L, W = 56.3465, 30.3975
    p = PrintSpec(
        L, W, (L / 2 + 20, W / 2 + 20), -0.75406, "mtb",
        block=2.62932, gap=3.62548, unevenness=0.14682, exponent=2.0,
    )  # fmt: skip
    scan, (t,) = scan_of(SheetSpec((p,), size=(L + 40, W + 40), specks=0, dpi=400.0, seed=1))
    (q,) = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x").prints
    assert q.flags == () and within(q.metrics, t), q.metrics.length / t.length - 1


@pytest.mark.parametrize("angle", [3.1, -5.3])
def test_analyze_scan_narrow_knurl_print_tracks_do_not_override_its_outline(angle):
    # a knurl print three diamonds wide: its lateral profile peaked 5 deg off (its
    # few tracks), its outline's axis clear; along the tracks it read +21 to +40 %
    # wide, flagged only coarse_elements. Tracks off the outline are not used:
    # turned beyond 1 deg, a sparse print's outline alone is not trusted either
    # (flagged); faint tracks the rectangle or principal axis confirms within a
    # degree decide (2026-12-07: tracks 3.02 and -5.28 deg, the outline's 3.2 and
    # -5.2: measured along them, still flagged coarse_elements)
    p = PrintSpec(22, 3.5, (40, 40), angle, "knurl", unevenness=0.0)
    img, _ = render_sheet(SheetSpec((p,), size=(80, 80), specks=0, dpi=150))
    (q,) = ip.analyze_scan(
        ip.Scan(img, 25.4 / 150, "given"), sensitivity=False, rolling_axis="x"
    ).prints
    own = abs(math.degrees(q.metrics.orientation) - angle) <= 0.3
    assert own or ("axis_misaligned" in q.flags and q.metrics.orientation == 0.0)
    assert q.status == "flagged"


def test_settled_turn_is_none_when_the_estimates_disagree_in_length():
    # a rhomboid hull (a knob pattern sheared by its stagger, independent 111 sheet
    # 31): its rectangle, least width and principal axis lie degrees apart and give
    # lengths more than 0.5 % apart: no snap; a rectangle turned 5 degrees: snapped
    xy = np.array([[0, 0], [80, 0], [80, 40], [0, 40]], float)  # (x, y) [px]
    c, s = math.cos(math.radians(5)), math.sin(math.radians(5))
    x, y = (xy @ np.array([[c, s], [-s, c]])).T  # turned +5 deg from +x
    turned = np.column_stack([-y, x])  # (row, col): rows run down
    assert settled_turn(turned, 0.0, spread=0.005) == pytest.approx(5.0, abs=0.01)
    sheared = np.array([[0, 0], [0, 80], [40, 92], [40, 12]], float)  # (row, col)
    assert settled_turn(sheared, 0.0, spread=0.005) is None
    assert settled_turn(sheared, 0.0, spread=0.5) is not None


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


@pytest.mark.parametrize(("rib", "groove"), [(18.0, 5.0), (24.0, 8.0), (30.0, 10.0)])
def test_group_blobs_car_ribs_cut_by_sipes_make_one_print(rib, groove):
    # independent set s1_061, s2_070, s1_016: ribs cut into blocks by 1-2 mm sipes,
    # the blocks narrower along the rib than the 4-10 mm grooves between ribs: every
    # car print came out as 2-4 ribs, each "ok" (s1_061: width -78 %)
    p = PrintSpec(130, 150, (100, 110), 0.0, "car", exponent=4.0, block=rib, gap=groove, sipe=1.5)
    scan, (t,) = scan_of(SheetSpec((p,), size=(200, 220), specks=0))
    r = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x")
    assert len(r.prints) == 1 and r.prints[0].flags == ()
    m = r.prints[0].metrics
    assert abs(m.width / t.width - 1) <= 0.01 and abs(m.length / t.length - 1) <= 0.01
    assert abs(m.hull_area / t.hull_area - 1) <= 0.02


def _narrow_ribs(dpi: float, ss: int = 4) -> tuple:
    """A 126 x 111 mm car print (superellipse, exponent 4) of five ribs 31, 2.1,
    9, 2.1 and 31 mm wide between 8.9 mm grooves (held-out 6 sheet 33): grey image,
    mm per px and the drawn ink's (length, width, hull area)."""
    mm = 25.4 / dpi / ss
    h, w = int(140 / mm), int(160 / mm)
    cx, cy = w / 2, h / 2
    u, v = np.meshgrid((np.arange(w) + 0.5 - cx) * mm, (np.arange(h) + 0.5 - cy) * mm)
    ink = np.abs(u / 63.0) ** 4 + np.abs(v / 55.6) ** 4 <= 1.0
    edges = np.cumsum([-55.5, 31, 8.9, 2.1, 8.9, 9, 8.9, 2.1, 8.9, 31])
    ink &= (np.searchsorted(edges, v) % 2 == 1) & (v <= 55.5)  # ribs, grooves between
    return drawn_scan(ink.astype(np.uint8), dpi, ss, 0.75)


@pytest.mark.parametrize("dpi", [150.0, 300.0])
def test_join_side_by_side_narrow_middle_ribs_join_the_print(dpi):
    # held-out 6 sheet 33: a car print's 2.1 mm ribs were no tread (under three
    # strokes wide, as a label's bold letters), so the print came out as five ribs
    grey, mm, (length, width, area) = _narrow_ribs(dpi)
    r = ip.analyze_scan(ip.Scan(grey, mm, "given"), sensitivity=False, rolling_axis="x")
    (pr,) = r.prints
    assert_allclose([pr.metrics.length, pr.metrics.width], [length, width], rtol=0.01)
    assert_allclose(pr.metrics.hull_area, area, rtol=0.02)


@pytest.mark.parametrize(
    ("stroke", "gap"), [(1.3, 4.0), (1.7, 4.0), (1.7, 6.7), (1.9, 6.7), (1.7, 9.0)]
)
def test_group_blobs_bold_label_beside_a_slick_print_stays_out(stroke, gap):
    # a marker label 40 mm long, its letters fused into three pieces, 4-6.7 mm below
    # a 90 mm slick print: the print's gap to the letters read as its tread pattern
    # (the label continued it), or the label as a rib beside it (it runs along 0.44
    # of the print): width +32 to +41 %, unflagged; then the fused label (43 x 4.9
    # mm, 0.7 of its hull inked) was a print of its own: a print that narrow is solid
    p = PrintSpec(90, 30, (100, 60), 0.0, "slick")
    word = Text("Schwalbe One 28", (58.0, 60 - 15 - gap - 5.0), 5.0, stroke, 0.85)
    scan, (t,) = scan_of(SheetSpec((p,), size=(200, 120), specks=0, marks=(word,)))
    r = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x")
    (pr,) = r.prints
    assert within(pr.metrics, t) and pr.flags == ()


def test_group_blobs_sparse_knobs_make_one_print():
    # s2_039: knobs 3 mm wide, 6-8 mm apart (beyond 2 x their width, the old reach of
    # the pattern rule): 3 prints came out as ~50 "prints" of 5 x 3 mm
    p = PrintSpec(90, 32, (100, 60), 0.0, "mtb", block=3.2, gap=7.0, unevenness=0.0)
    scan, (t,) = scan_of(SheetSpec((p,), size=(200, 120), specks=0))
    r = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x")
    assert len(r.prints) == 1 and within(r.prints[0].metrics, t)


def test_group_blobs_split_centre_knobs_keep_the_tip_row():
    # s2_076: the tip row was one centre knob split by a 1 mm sipe; its pattern gap
    # (the sipe) x 3 fell short of the 5 mm row gap, and the row became a print of its
    # own (length -12.4 %; here -11.2 % before)
    p = PrintSpec(60, 34, (100, 60), 0.0, "mtb", block=3.0, gap=5.0, unevenness=0.0, sipe=1.0)
    scan, (t,) = scan_of(SheetSpec((p,), size=(200, 120), specks=0))
    r = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x")
    assert len(r.prints) == 1 and within(r.prints[0].metrics, t)


def _knobby_blocks(tip=None, *, bl=3.2, row_gap=5.0, lat=4.0, cw=6.0, sw=4.0, sipe=1.0):
    """Blocks (u0, v0, u1, v1) [mm] of a knobby tread like the independent set's
    (s2_076): 7 rows along u, even rows a centre block split by a sipe plus two side
    blocks, odd rows two blocks, the end rows the split centre block alone; ``tip``
    (along, across): one more block beyond each end row."""
    boxes, pitch = [], bl + row_gap
    for i in range(7):
        u = i * pitch
        if i % 2:
            m = lat / 2
            boxes += [(u, m, u + bl, m + sw), (u, -m - sw, u + bl, -m)]
            continue
        boxes += [(u, sipe / 2, u + bl, cw / 2), (u, -cw / 2, u + bl, -sipe / 2)]
        if 0 < i < 6:
            off = cw / 2 + lat
            boxes += [(u, off, u + bl, off + sw), (u, -off - sw, u + bl, -off)]
    if tip:
        a, b = tip
        end = 6 * pitch + bl + row_gap
        boxes += [(-row_gap - a, -b / 2, -row_gap, b / 2), (end, -b / 2, end + a, b / 2)]
    return boxes


def _blocks_scan(boxes, dpi=300.0, marks=()):
    """A scan of dark blocks on paper (and of ``marks``, boxes that are not the
    print), and the truth (length along u, width, hull area) of the blocks as drawn
    (rounded to the pixel grid)."""
    import cv2

    px = 25.4 / dpi
    to_px = np.array([[1 / px, 1 / px]])
    every = list(boxes) + list(marks)
    corners = np.array([(u, v) for u0, v0, u1, v1 in every for u in (u0, u1) for v in (v0, v1)])
    pix = np.round((corners - corners.min(axis=0) + 15.0) * to_px).astype(int)
    img = np.full(tuple(pix.max(axis=0)[::-1] + int(15 / px)), 245, np.uint8)
    for c in pix.reshape(-1, 4, 2):
        img[c[:, 1].min() : c[:, 1].max(), c[:, 0].min() : c[:, 0].max()] = 40
    pix = pix[: 4 * len(boxes)]
    drawn = (pix.reshape(-1, 4, 2) - [[0, 0], [0, 1], [1, 0], [1, 1]]).reshape(-1, 2) * px
    hull = cv2.convexHull(drawn.astype(np.float32))
    truth = (np.ptp(drawn[:, 0]) + px, np.ptp(drawn[:, 1]) + px, cv2.contourArea(hull))
    return ip.Scan(img, px, "given"), truth


@pytest.mark.parametrize("tip", [None, (2.5, 1.6)])
def test_group_blobs_knobby_tip_blocks_join_the_print(tip):
    # independent set s2_076 (tip row: a centre block split by a 1 mm sipe, 5 mm from
    # the next row; the sipe was its pattern gap: length -12.4 % and a spurious print)
    # and s2_008 (a 2.5 x 1.6 mm block cut by the outline beyond that row: no pattern
    # of its own, dropped as a fragment: length -1.5 %); here -31 % and -11 %
    scan, (length, width, area) = _blocks_scan(_knobby_blocks(tip))
    r = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x")
    assert len(r.prints) == 1 and r.prints[0].flags == ()
    m = r.prints[0].metrics
    assert abs(m.length / length - 1) <= 0.01 and abs(m.width / width - 1) <= 0.01
    assert abs(m.hull_area / area - 1) <= 0.02


def test_group_blobs_bold_letters_beside_a_slick_print_stay_apart():
    # independent set s4_013: a label's bold letters (1.5 mm strokes, 2.7 mm apart)
    # 6.9 mm from a 10 mm wide slick print: the letters' spacing made a "pattern"
    # that linked them to the print, which has none (width +143 %)
    letters = [(10.0 + 2.7 * i + 1.5 * i, 11.9, 11.5 + 2.7 * i + 1.5 * i, 16.0) for i in range(5)]
    scan, (length, width, area) = _blocks_scan([(0.0, -5.0, 36.0, 5.0)], marks=letters)
    r = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x")
    m = r.prints[0].metrics
    assert len(r.prints) == 1 and r.prints[0].flags == ()
    assert abs(m.length / length - 1) <= 0.01 and abs(m.width / width - 1) <= 0.01
    assert abs(m.hull_area / area - 1) <= 0.02


def test_group_blobs_two_ribs_near_the_limit_are_flagged():
    # two straight-sided ribs 60 x 25 mm, 11.5 mm apart: 0.19 x the 60 mm they make
    # together, just over group_print_gap (0.18) and within its doubt: a car
    # print's halves or two prints, flagged, --group-mm decides
    scan, _ = _blocks_scan([(0.0, 0.0, 60.0, 25.0), (0.0, 36.5, 60.0, 61.5)])
    r = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x")
    assert all("grouping_uncertain" in q.flags for q in r.prints)


@pytest.mark.parametrize(
    ("apart", "n", "flagged"), [(12.0, 2, False), (14.0, 2, False), (22.0, 2, False)]
)
def test_group_blobs_side_by_side_prints_near_the_limit_are_flagged(apart, n, flagged):
    # two 90 x 30 mm slick prints side by side 12, 14 and 22 mm apart: 0.17, 0.19 and
    # 0.27 x the 72-82 mm they would make together. Near group_print_gap (0.18) it
    # could be a car print's ribs or two prints: they were flagged, --group-mm
    # deciding; 22 mm apart they are two prints (before, the size rule joined them
    # up to 0.75 x their 30 mm width: one print 82 mm wide, unflagged). 12 mm apart
    # they were joined, flagged; their rounded sides facing the band of paper
    # between them now cut them apart (inkprint.apart). Neither has a rib's straight
    # side (group._straight_side): two prints, unflagged (ten such prints within
    # the bar were flagged on the held-out development sets); test_group_blobs_
    # two_ribs_near_the_limit_are_flagged keeps the ribs' doubt
    p = [
        PrintSpec(90, 30, (100, 60 + 30 + apart), 0.0, "slick", unevenness=0.0),
        PrintSpec(90, 30, (100, 60), 0.0, "slick", unevenness=0.0),
    ]
    scan, truths = scan_of(SheetSpec(tuple(p), size=(200, 170), specks=0))
    r = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x")
    assert len(r.prints) == n
    if flagged:
        assert all(q.status == "flagged" and "grouping_uncertain" in q.flags for q in r.prints)
        assert all(any("--group-mm" in w for w in q.warnings) for q in r.prints)
    else:
        assert all(q.flags == () for q in r.prints)
    if n == 1:
        assert abs(r.prints[0].metrics.width - (60 + apart)) < 0.5  # both, and the gap
    else:
        assert all(within(q.metrics, t) for q, t in zip(r.prints, truths, strict=True))
    apart_ = ip.analyze_scan(
        scan, sensitivity=False, rolling_axis="x", options=ip.AnalysisOptions(group_mm=5.0)
    )
    assert len(apart_.prints) == 2 and all(q.flags == () for q in apart_.prints)
    assert all(within(q.metrics, t) for q, t in zip(apart_.prints, truths, strict=True))


def test_group_blobs_one_piece_prints_in_a_row_stay_apart():
    # held-out set 1 sheet 24: three prints, each one piece of ink, 37-47 mm apart:
    # each one's "pattern" gap was the spacing of the others, so the pattern rule
    # linked them into one 231 x 149 mm print, unflagged. No groove inside a print
    # is wider than group_groove_max_mm (20 mm)
    p = [PrintSpec(80, 40, (70, 40 + 80 * i), 0.0, "slick", unevenness=0.0) for i in range(3)]
    scan, truths = scan_of(SheetSpec(tuple(p), size=(140, 240), specks=0))
    r = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x")
    assert len(r.prints) == 3 and all(q.flags == () for q in r.prints)
    got = sorted(r.prints, key=lambda q: q.metrics.centroid[1])
    assert all(within(q.metrics, t) for q, t in zip(got, truths, strict=True))
    joined = ip.analyze_scan(
        scan,
        sensitivity=False,
        rolling_axis="x",
        options=ip.AnalysisOptions(group_groove_max_mm=1000.0),
    )
    assert len(joined.prints) == 1  # the rule without the limit: one "print"


@pytest.mark.parametrize("stroke", [0.9, 1.4])
def test_is_print_a_line_of_marker_letters_is_writing(stroke):
    # held-out set 1 sheets 23 and 26: a tire's name in marker letters 5 mm high
    # above the prints was taken for a 54 x 4 mm and a 113 x 6 mm print, status ok
    label = Text("Michelin Road 6 2.3 bar 1424 N", (15.0, 20.0), height=5.0, stroke=stroke)
    spec = PrintSpec(80, 35, (70, 80), 0.0, "slick", unevenness=0.0)
    scan, truths = scan_of(SheetSpec((spec,), size=(170, 130), specks=0, marks=(label,)))
    r = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x")
    assert len(r.prints) == 1 and within(r.prints[0].metrics, truths[0])
    assert any(m.kind == "writing" for m in r.marks)
    alone = SheetSpec((), size=(170, 60), specks=0, marks=(label,))
    with pytest.raises(ip.NoInk, match="a line of writing"):
        ip.analyze_scan(scan_of(alone)[0], sensitivity=False)


@pytest.mark.parametrize(("length", "found"), [(5.0, False), (7.5, True)])
def test_is_print_a_blob_shorter_than_a_print_is_a_dot(length, found):
    # held-out set 2 sheets 22 and 115: 4.5-5.7 mm blobs of marker writing on
    # pages of writing only were reported as prints; the smallest prints a tire
    # makes are ~10 mm long (the independent generator's tiniest 7.1 mm)
    spec = PrintSpec(length, 3.0, (30, 30), 0.0, "slick", unevenness=0.0)
    scan, truths = scan_of(SheetSpec((spec,), size=(60, 60), specks=0, dpi=600.0))
    if found:
        r = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x")
        assert len(r.prints) == 1 and within(r.prints[0].metrics, truths[0])
    else:
        with pytest.raises(ip.NoInk, match="a letter's piece"):
            ip.analyze_scan(scan, sensitivity=False, rolling_axis="x")
    with pytest.raises(ip.InvalidInput, match="min_patch_length_mm"):
        ip.AnalysisOptions(min_patch_length_mm=-1.0)


def test_is_print_a_slender_chevron_print_is_not_a_line_of_writing():
    # independent set 101 sheet 54: a 129 x 23 mm print whose chevron grooves cut
    # it into 25 ribs across its width (each rib hollow, a "V") was set aside as a
    # line of letters; its ink fills 0.87 of its hull, a line of letters' ~0.5
    import cv2

    px = 25.4 / 200
    img = np.full((int(60 / px), int(160 / px)), 245, np.uint8)
    centre = (int(80 / px), int(30 / px))
    cv2.ellipse(img, centre, (int(64 / px), int(11.5 / px)), 0, 0, 360, 50, -1, cv2.LINE_AA)
    for x in np.arange(20.0, 141.0, 4.8):
        v = np.array([[x, 17.0], [x + 9.0, 30.0], [x, 43.0]]) / px
        cv2.polylines(img, [v.astype(np.int32)], False, 245, int(1.0 / px), cv2.LINE_AA)
    r = ip.analyze_scan(ip.Scan(img, px, "given"), sensitivity=False, rolling_axis="x")
    assert len(r.prints) == 1 and r.prints[0].flags == ()
    assert_allclose = np.testing.assert_allclose
    assert_allclose([r.prints[0].metrics.length, r.prints[0].metrics.width], [128, 23], rtol=0.01)


@pytest.mark.parametrize(("gap", "linked"), [(5.0, True), (7.5, True), (11.81, False)])
def test_linked_edges_a_lone_element_continues_a_pattern_across_one_groove(gap, linked):
    # held-out set 1 sheet 37: a marker's letter (1.04 mm wide, no pattern of its
    # own) 11.81 mm off a car rib (28 mm wide) whose blocks are 5.33 mm apart took
    # the rib's pattern and joined it (width +12.6 %); a tip block the outline cut
    # lies one groove off, where the next block would
    from inkprint.group import ElementGraph, linked_edges

    graph = ElementGraph(
        widths=np.array([28.0, 28.0, 28.0, 1.04]),
        a=np.array([0, 1, 0]),
        b=np.array([1, 2, 3]),
        gaps=np.array([5.33, 5.33, gap]),
    )
    assert linked_edges(graph).tolist() == [True, True, linked]


def test_linked_edges_prints_farther_apart_than_a_groove_make_no_pattern():
    # held-out set 1 sheet 114: two slick prints (19.3 and 18.3 mm wide) 38.75 mm
    # apart made a "pattern" of their gap; a marker's letter 19.2 mm off one and
    # 13.8 mm off the other continued half of it and joined both (one 112 x 82 mm
    # print for two); no gap over group_groove_max_mm is a tread's
    from inkprint.group import ElementGraph, linked_edges

    graph = ElementGraph(
        widths=np.array([19.26, 18.34, 1.31]),
        a=np.array([0, 0, 1]),
        b=np.array([1, 2, 2]),
        gaps=np.array([38.75, 19.19, 13.8]),
    )
    assert linked_edges(graph).tolist() == [False, False, False]


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
    # rolling axis x from the manifest: a print taped 2-10 degrees askew (a crooked
    # sheet) is measured along its own axis, within the bar; one turned 20-40 degrees
    # reads up to +60 % wide along x: it must be flagged, never a silent number
    results, rows = outcomes(tmp_path, "turned", seed)
    got = sorted((r["expect"], r["outcome"]) for r in results)
    assert got == [("axis_misaligned", "flagged"), ("measure", "pass")], results
    askew, turned = sorted(rows, key=lambda r: -float(r["centroid_y_mm"]))
    assert askew["flags"] == "" and askew["axis_source"] == "manifest"
    assert "axis_misaligned" in turned["flags"]
    assert "--rolling-axis auto" in turned["warnings"]


def test_own_axis_finds_the_turn_of_a_print_and_its_error():
    # a print taped 4 degrees askew: measured along its own axis (within
    # axis_misaligned_deg, 10), unflagged; with a 2-degree tolerance along x, flagged
    p = PrintSpec(80.0, 20.0, (60, 60), 4.0, "slick", unevenness=0.0)
    scan, (t,) = scan_of(SheetSpec((p,), size=(120, 120), specks=0))
    res = ip.analyze_scan(scan, sensitivity=False, rolling_axis="x")
    m = res.prints[0].metrics
    assert res.prints[0].flags == ()
    assert math.degrees(m.orientation) == pytest.approx(4.0, abs=0.3)
    assert within(m, t)
    turn, excess = own_axis(res.prints[0].hull_px, 0.0)
    assert turn == pytest.approx(4.0, abs=0.3)
    assert excess > 0.05  # the width along x: 80 sin 4 deg over 20 mm
    tight = ip.analyze_scan(
        scan,
        sensitivity=False,
        rolling_axis="x",
        options=ip.AnalysisOptions(axis_misaligned_deg=2.0),
    )
    assert "axis_misaligned" in tight.prints[0].flags
    assert tight.prints[0].metrics.orientation == 0.0
    square = ip.analyze_scan(
        scan_of(SheetSpec((dataclasses.replace(p, angle=0.0),), size=(120, 120), specks=0))[0],
        sensitivity=False,
        rolling_axis="x",
    )
    assert own_axis(square.prints[0].hull_px, 0.0)[1] < 0.002
    assert square.prints[0].flags == ()


@pytest.mark.parametrize("angle, axis", [(0.4, "x"), (-0.6, "x"), (90.35, "y")])
def test_analyze_scan_slender_print_taped_nearly_square_is_measured_along_itself(angle, axis):
    # a 120 x 20 mm print with straight sides (a rounded rectangle) taped within a
    # degree of the given axis: along the sheet's axis its width reads L sin(angle)
    # too large (+4 % at 0.4 deg); it is measured along its own axis (independent
    # set 1, file 107: width +3.0 %, unflagged), unflagged
    p = PrintSpec(120.0, 20.0, (80, 80), angle, "slick", unevenness=0.0, exponent=8.0)
    scan, (t,) = scan_of(SheetSpec((p,), size=(160, 160), dpi=200.0, specks=0))
    res = ip.analyze_scan(scan, sensitivity=False, rolling_axis=axis)
    m = res.prints[0].metrics
    assert res.prints[0].flags == ()
    assert m.length == pytest.approx(t.length, rel=0.002)
    assert m.width == pytest.approx(t.width, rel=0.004)
    along = 0.0 if axis == "x" else 90.0
    assert math.degrees(m.orientation) == pytest.approx(angle, abs=0.15)
    assert abs(math.degrees(m.orientation) - along) <= 1.0


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


@pytest.mark.parametrize("seed", [4, 5])
def test_prepare_page_shadow_band_as_wide_as_a_print(tmp_path, seed):
    # a shadow band 10-40 mm wide crossing the sheet, a 30-50 % gradient and a
    # vignette (the independent set's lighting class). Before, the 30 mm closing of
    # the paper's brightness closed over the band: seed 4's band became a clipped
    # 'print' and both prints went missing; seed 5's band and a print merged into
    # one 'print' +276 % long
    results, rows = outcomes(tmp_path, "shade", seed)
    assert_passes(results)
    assert all(r["status"] == "ok" and "uneven_light" in r["flags"] for r in rows)
    assert len(rows) == 2


@pytest.mark.parametrize("dpi", [150.0, 300.0])
def test_prepare_page_slick_print_in_a_shadow_band(dpi):
    # a solid slick print 30 x 130 mm, inked 0.55-0.9, lying along a 35 mm shadow band
    # 40 % deep with 4 mm soft edges, a 45 % gradient and a 35 % vignette: the print
    # is as wide as the band, so the paper's estimate must leave it out by its being
    # enclosed by paper, not by its size (it must not be eaten, nor the band taken
    # for ink); nothing else on the sheet is a print (the dark corners neither)
    p = PrintSpec(130.0, 30.0, (108.0, 140.0), 60.0, "slick", ink=0.55)
    light = Light(
        gradient=0.45,
        direction=200.0,
        shadow=_band(None, (120.0, 150.0), 35.0, angle=60.0),
        shadow_depth=0.4,
        softness=4.0,
        vignette=0.35,
    )
    scan, (truth,) = scan_of(SheetSpec((p,), dpi=dpi, light=light))
    r = ip.analyze_scan(scan, sensitivity=False)
    assert len(r.prints) == 1 and "uneven_light" in r.flags
    assert within(r.prints[0].metrics, truth)
    assert not r.prints[0].flags


@pytest.mark.parametrize(
    ("ink", "depth", "soft", "flagged"),
    [
        (0.35, 0.25, 0.3, True),
        (0.45, 0.4, 6.0, True),
        (0.7, 0.4, 3.0, False),
        (0.55, 0.25, 3.0, False),
    ],
)
def test_analyze_scan_light_ink_across_a_shadow_edge(ink, depth, soft, flagged):
    # a slick print 100 x 25 mm crossed by a 30 mm shadow band. Ink 0.35 under a 25 %
    # band with hard (0.3 mm) edges: the paper filled in under the print is off where
    # the band crosses it and its lit part read as paper (length -22.8 %, unflagged);
    # ink 0.45 under a 40 % band, 6 mm soft: -17.8 %. Darker ink is measured within
    # the bar and not flagged
    p = PrintSpec(100.0, 25.0, (108.0, 140.0), 0.0, "slick", ink=ink)
    light = Light(
        gradient=0.3,
        direction=20.0,
        shadow=_band(None, (108.0, 120.0), 30.0, angle=70.0),
        shadow_depth=depth,
        softness=soft,
    )
    scan, (truth,) = scan_of(SheetSpec((p,), dpi=200.0, light=light))
    r = ip.analyze_scan(scan, sensitivity=False)
    big = max(r.prints, key=lambda q: q.metrics.hull_area)
    if flagged:
        assert all("light_uncertain" in q.flags for q in r.prints)
        assert "light the sheet evenly" in " ".join(big.warnings)
    else:
        assert len(r.prints) == 1 and not big.flags and within(big.metrics, truth)


@pytest.mark.parametrize("ink", [0.35, 0.45])
def test_prepare_page_lightly_inked_print_run_off_the_sheet(ink):
    # a print inked 0.35-0.45 running off the sheet's left edge is not enclosed by
    # paper and lighter than light_edge_ink: the light estimate followed it, the
    # sheet read as unevenly lit and the print vanished (no row at all); its sharp
    # edge at the sheet's edge tells it from shade
    p = PrintSpec(100.0, 25.0, (20.0, 140.0), 0.0, "slick", ink=ink)
    q = PrintSpec(80.0, 20.0, (120.0, 60.0), 0.0, "ribbed", ink=0.8)
    scan, (_, truth) = scan_of(SheetSpec((p, q), dpi=200.0))
    r = ip.analyze_scan(scan, sensitivity=False)
    assert "uneven_light" not in r.flags
    assert len(r.prints) == 2
    cut = [x for x in r.prints if "clipped" in x.flags]
    whole = [x for x in r.prints if not x.flags]
    assert len(cut) == 1 and len(whole) == 1 and within(whole[0].metrics, truth)


def test_prepare_page_finds_the_page_of_a_flat_on_photo(tmp_path):
    results, rows = outcomes(tmp_path, "photo", 2)
    assert_passes(results)
    assert all(r["scale_source"] == "given" for r in rows)


def test_prepare_page_flags_a_photo_not_taken_flat_on(tmp_path):
    results, rows = outcomes(tmp_path, "tilted", 1)
    assert_passes(results)  # every print flagged
    assert all(r["status"] == "flagged" and "perspective" in r["flags"] for r in rows)
    assert "not flat-on" in rows[0]["warnings"]


@pytest.mark.parametrize("seed", [4, 16, 18, 24])
def test_prepare_page_scanner_bed_along_the_sides(tmp_path, seed):
    # a page shifted and skewed on the glass: the dark bed along one or two sides
    # (seed 18: one strip thins out before its corner; 24: one ends halfway) and
    # punch holes. Before, the strips joined the prints (a whole-page "texture": every
    # print missing) or stayed as 1-3 mm "prints" cut by the edge; a page's corner
    # on the image's edge is no corner (an 88.3 deg angle flagged perspective)
    results, rows = outcomes(tmp_path, "scanner", seed, dpi=200.0)
    assert_passes(results)
    assert all(r["status"] == "ok" for r in rows)
    holes = make_case("scanner", seed=seed, dpi=200.0).sheets[0].bed.holes
    assert sum(int(n) for n in re.findall(r"(\d+) holes?", rows[0]["set_aside"])) == holes


def test_find_page_bed_strip_is_the_page_edge():
    # the strip's inner edge as fitted, on the ~2 mm grid: the page beyond it
    from inkprint.light import find_page

    small = np.full((140, 108), 230, np.uint8)
    edge = 6 + 0.05 * np.arange(108)  # the top strip: 12 mm to 22.8 mm, skewed 2.9 deg
    small[np.arange(140)[:, None] < edge[None, :].astype(int)] = 60
    frame = find_page(small, 230.0)
    assert frame is not None and frame.angles == ()  # no corner of the page inside
    top = np.argmax(frame.mask, axis=0)  # the first page row of each column
    assert_allclose(top, np.ceil(edge + 1.0), atol=1)


def test_find_page_print_cut_by_the_edge_is_no_bed():
    # a print run off the left edge: dark from the edge in, but a curved edge
    from inkprint.light import find_page

    small = np.full((140, 108), 230, np.uint8)
    rr, cc = np.mgrid[:140, :108]
    small[((rr - 70) / 50.0) ** 2 + (cc / 12.0) ** 2 <= 1] = 30
    assert find_page(small, 230.0) is None


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


@pytest.mark.parametrize(
    ("x_mm", "y_mm", "cut"),
    [
        (72.0, 120.0, False),  # ribs unbroken to their ends 12 mm off the left edge
        (120.0, 63.0, False),  # 18 mm off the bottom edge: more than 1.5 grooves
        (55.0, 120.0, True),  # run 5 mm off the left edge: the ribs are cut
        (120.0, 52.0, True),  # 7 mm off the bottom: it could end in a 10 mm groove
    ],
)
def test_analyze_scan_car_print_near_the_edge_is_clipped_only_where_a_groove_fits(x_mm, y_mm, cut):
    # held-out seed 5 sheet 93 (and seeds 1, 3): a car print of four ribs along the
    # rolling axis with 10 mm grooves, 12 mm off the left edge, was flagged clipped
    # (the margin was 1.5 grooves both ways); along the ribs there is no groove to
    # end in, across them there is
    p = PrintSpec(120.0, 150.0, (x_mm, y_mm), 0.0, "car", exponent=6.0)
    p = dataclasses.replace(p, width=90.0, block=18.0, gap=10.0, sipe=0.0)
    img, (t,) = render_sheet(SheetSpec((p,), dpi=200.0, size=(240.0, 240.0), specks=0))
    res = ip.analyze_scan(Scan(img, 25.4 / 200.0, "given"), rolling_axis="x", sensitivity=False)
    (pr,) = res.prints
    assert ("clipped" in pr.flags) is cut, pr.warnings
    if not cut:
        assert_allclose([pr.metrics.length, pr.metrics.width], [t.length, t.width], rtol=0.01)


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


def test_sort_ink_punch_hole_beside_a_knobby_print_joins_none():
    # held-out set 5 sheet 87: a punch hole 5 mm off a knobby print's side continued
    # its knobs' pattern and joined it (width +26.7 %, unflagged); a hole is a group
    # of its own, set aside
    from inkprint.synth_effects import Bed

    p = PrintSpec(110.0, 48.0, (42.0, 186.0), 90.0, "mtb", block=5.0, gap=4.0)  # 3 mm off
    spec = SheetSpec((p,), dpi=200.0, seed=4, specks=0, bed=Bed((), holes=2, level=0.3))
    scan, (truth,) = scan_of(spec)
    r = ip.analyze_scan(scan, sensitivity=False, rolling_axis="y")
    (pr,) = r.prints
    assert within(pr.metrics, truth), (pr.metrics.length, pr.metrics.width, truth.width)
    assert sum(m.kind == "hole" for m in r.marks) == 2


def test_sort_ink_knob_rounded_by_the_outline_near_the_corner_is_no_punch_hole():
    # held-out seed 8 sheet 93: a knobby print 25 mm from the page's corner, one
    # square knob cut round at its outer corner by the print's outline inked its
    # box's inscribed disc as a hole does; set aside as a punch hole, the hull area
    # read -20 % with status ok. A hole fills its least enclosing circle, a knob not.
    from .drawn import drawn_scan

    dpi, ss = 150.0, 4
    mm = 25.4 / dpi / ss
    n = round(120.0 / mm)
    yy, xx = np.mgrid[0:n, 0:n] * mm  # [mm] from the top left
    ink = np.zeros((n, n), np.uint8)
    for i in range(3):
        for j in range(4):
            x0, y0 = 8.0 + 11.0 * i, 8.0 + 11.0 * j
            knob = (xx >= x0) & (xx < x0 + 6.0) & (yy >= y0) & (yy < y0 + 6.0)
            if i == j == 0:  # the outline cuts the corner knob round
                knob &= np.hypot(xx - x0 - 6.0, yy - y0 - 6.0) <= 6.3
            ink[knob] = 1
    corner = ink[: round(14.0 / mm), : round(14.0 / mm)].sum() * mm * mm
    assert abs(corner / (np.pi * 9.0) - 1.0) < 0.12  # it inks its box's disc
    disc = np.hypot(xx - 100.0, yy - 10.0) <= 3.0  # a punch hole 10 mm off the edge
    grey, mm_px, truth = drawn_scan(ink, dpi, ss, 0.8)
    grey = np.minimum(grey, drawn_scan(disc.astype(np.uint8), dpi, ss, 0.8)[0])
    res = ip.analyze_scan(Scan(grey, mm_px, "given"), rolling_axis="y", sensitivity=False)
    (pr,) = res.prints
    assert_allclose(pr.metrics.hull_area, truth[2], rtol=0.02)
    assert [m.kind for m in res.marks].count("hole") == 1


@pytest.mark.parametrize(("length", "width", "tilted"), [(76.0, 50.0, True), (100.0, 60.0, False)])
def test_analyze_scan_auto_axis_tilted_by_a_knob_pattern_is_flagged(length, width, tilted):
    # held-out seed 8 sheet 64: a knobby print square to the sheet, measured along
    # its principal axis (auto) at -8.7 deg, width -6.8 % with status ok; a principal
    # axis off the bounding rectangle's by over a degree is flagged axis_ambiguous
    p = PrintSpec(length, width, (70.0, 60.0), 0.0, "mtb", block=6.0, gap=6.0)
    img, (t,) = render_sheet(SheetSpec((p,), dpi=200.0, size=(140.0, 120.0), specks=0))
    (pr,) = ip.analyze_scan(Scan(img, 25.4 / 200.0, "given"), sensitivity=False).prints
    assert (abs(math.degrees(pr.metrics.orientation)) > 1.0) == tilted
    assert ("axis_ambiguous" in pr.flags) == tilted, pr.warnings
    assert (pr.status == "flagged") == tilted
    if not tilted:
        assert within(pr.metrics, t)
