"""Fine treads: a dense regular field of small separate elements is a print.

A knurl, diamond-file or dot-field tread prints as hundreds of ink elements
0.5-1.5 mm across, each thinner than a pen stroke or too small to count as thick
ink: taken one by one they were dust or text, and the print lost its edge rows or
went missing with status ok (independent set 10 file 81 at 600 dpi: missing; file
71 at 150 dpi: NoInk "set aside 196 text"). Text is sparse strokes in lines, dust
isolated specks: neither is a field (:func:`inkprint.marks._fine_fields`).
"""

import dataclasses
import math

import cv2
import numpy as np
import pytest
from numpy.testing import assert_allclose

import inkprint as ip
from inkprint.components import components_with_stats
from inkprint.marks import _fine_fields
from inkprint.options import AnalysisOptions
from inkprint.read import Scan
from inkprint.synth import PrintSpec, SheetSpec, render_sheet
from inkprint.synth_effects import Text

OPTS = AnalysisOptions()


def _knurl_sheet(dpi: float, **kw):
    p = PrintSpec(54.0, 24.0, (80.0, 120.0), 0.0, "knurl", **kw)
    img, (t,) = render_sheet(SheetSpec((p,), dpi=dpi, size=(160.0, 240.0), specks=0))
    return Scan(img, 25.4 / dpi, "given"), t


def _one_print(p: PrintSpec, dpi: float, size: tuple) -> tuple:
    """The one print found on a sheet of ``p`` (x rolling axis, no band) and its truth."""
    img, (t,) = render_sheet(SheetSpec((p,), dpi=dpi, size=size, specks=0))
    res = ip.analyze_scan(Scan(img, 25.4 / dpi, "given"), rolling_axis="x", sensitivity=False)
    (pr,) = res.prints
    return pr, t


def _assert_within(pr, t) -> None:
    m = pr.metrics
    assert_allclose([m.length, m.width], [t.length, t.width], rtol=0.01)
    assert_allclose(m.hull_area, t.hull_area, rtol=0.02)


@pytest.mark.parametrize("dpi", [150.0, 600.0])
def test_analyze_scan_knurl_print_is_measured_whole(dpi):
    scan, t = _knurl_sheet(dpi)
    res = ip.analyze_scan(scan, rolling_axis="x", sensitivity=False)
    (pr,) = res.prints
    assert_allclose(pr.metrics.length, t.length, rtol=0.01)
    assert_allclose(pr.metrics.width, t.width, rtol=0.01)
    assert_allclose(pr.metrics.hull_area, t.hull_area, rtol=0.02)
    assert "dust" not in res.rows()[0]["set_aside"]


def test_analyze_scan_dot_field_print_at_400_dpi_is_measured_whole():
    # round-ish dots 0.9 mm on a 1.3 mm lattice (held-out scan 45 page 2: NoInk,
    # "set aside 457 dust")
    scan, t = _knurl_sheet(400.0, block=0.9, gap=0.45)
    (pr,) = ip.analyze_scan(scan, rolling_axis="x", sensitivity=False).prints
    assert_allclose([pr.metrics.length, pr.metrics.width], [t.length, t.width], rtol=0.01)
    assert_allclose(pr.metrics.hull_area, t.hull_area, rtol=0.02)


def _fields(mask: np.ndarray, px_mm: float, opts=OPTS) -> np.ndarray:
    _n, _lab, stats, cent = components_with_stats(mask.astype(np.uint8), connectivity=8)
    return _fine_fields(stats, cent, px_mm, opts)


PX = 0.1  # [mm] a pixel of the drawn fixtures


def _dots(centres_mm, r_mm=0.45, shape=(600, 600)) -> np.ndarray:
    m = np.zeros(shape, np.uint8)
    for x, y in centres_mm:
        cv2.circle(m, (round(x / PX), round(y / PX)), round(r_mm / PX), 1, -1)
    return m.astype(bool)


def test_fine_fields_lattice_of_dots_is_a_field():
    xs, ys = np.meshgrid(np.arange(5, 55, 1.5), np.arange(5, 30, 1.3))
    xs = xs + 0.75 * (np.arange(xs.shape[0])[:, None] % 2)  # staggered rows
    found = _fields(_dots(np.column_stack([xs.ravel(), ys.ravel()])), PX)
    assert found[1:].all()


def test_fine_fields_scattered_specks_are_not_a_field():
    # as many dots as the lattice, as dense, at random places: dust
    rng = np.random.default_rng(1)
    n = 33 * 20
    pts = np.column_stack([rng.uniform(5, 55, n), rng.uniform(5, 30, n)])
    assert not _fields(_dots(pts), PX).any()


def test_fine_fields_lines_of_small_writing_are_not_a_field():
    m = np.zeros((400, 900), np.uint8)
    for k in range(8):  # a paragraph of 2 mm high letters, lines 3.5 mm apart
        cv2.putText(
            m,
            "Conti GP5000 28mm 6.2 bar 640 N front",
            (20, 40 + 35 * k),
            cv2.FONT_HERSHEY_SIMPLEX,
            0.6,
            1,
            2,
        )
    assert not _fields(m.astype(bool), PX).any()


def test_fine_fields_dot_grid_paper_is_not_a_field():
    # a dot-grid page's dots lie 5 mm apart: too sparse for a tread
    xs, ys = np.meshgrid(np.arange(2, 58, 5.0), np.arange(2, 58, 5.0))
    m = _dots(np.column_stack([xs.ravel(), ys.ravel()]), r_mm=0.3)
    assert not _fields(m, PX).any()


def test_fine_fields_off_when_fine_element_mm_is_zero():
    xs, ys = np.meshgrid(np.arange(5, 55, 1.5), np.arange(5, 30, 1.3))
    m = _dots(np.column_stack([xs.ravel(), ys.ravel()]))
    assert not _fields(m, PX, OPTS.replace(fine_element_mm=0.0)).any()


@pytest.mark.parametrize("n", [2, 40, 900])
def test_nearest_within_equals_brute_force(n):
    # the fine-field neighbours without scipy's KD-tree (0.25 s of imports in a
    # one-file run): the k nearest other points within the radius, exactly
    from inkprint.marks import _nearest_within

    pts = np.random.default_rng(n).random((n, 2)) * np.array([60.0, 20.0])
    d, j = _nearest_within(pts, 8, 3.0)
    full = np.hypot(*(pts[:, None, :] - pts[None, :, :]).transpose(2, 0, 1))
    np.fill_diagonal(full, np.inf)
    full[full > 3.0] = np.inf
    want = np.sort(full, axis=1)[:, :8]
    if want.shape[1] < 8:
        want = np.pad(want, ((0, 0), (0, 8 - want.shape[1])), constant_values=np.inf)
    np.testing.assert_allclose(d, want, rtol=1e-12)
    found = np.isfinite(d)
    np.testing.assert_allclose(full[np.nonzero(found)[0], j[found]], d[found], rtol=1e-12)
    assert (j[~found] == n).all()


@pytest.mark.parametrize(
    "dpi, length, width, rib, block",
    [(150.0, 64.5, 20.0, 6.0, 2.2), (300.0, 48.0, 25.0, 9.0, 1.8), (600.0, 64.5, 20.0, 6.0, 2.2)],
)
def test_analyze_scan_file_shoulders_beside_a_slick_rib_are_measured(
    dpi, length, width, rib, block
):
    # a road tire's slick centre rib between file shoulders (held-out 6 sheet 87):
    # the shoulders' diamonds reached out of the rib's body like a marker's letters
    # and were set aside with the rim pieces joined to the rib (width -33 % to
    # -65 %, flagged mark_on_edge: a useless result)
    p = PrintSpec(length, width, (80.0, 120.0), 0.0, "knurl", block=block, gap=0.5, rib=rib)
    pr, t = _one_print(p, dpi, (160.0, 240.0))
    assert pr.status == "ok", pr.warnings
    _assert_within(pr, t)


def test_fine_fields_tips_shaved_off_thick_ink_are_no_elements():
    # a lattice of dots with, among them, the bits an opening shaved off thick
    # elements (a diamond's tips: held-out 6 sheet 87, 20 of 0.1 mm^2 beside 40
    # diamonds of 1.9 mm^2): counted as elements, the field's areas are irregular
    pts = [(10 + 1.3 * i + 0.65 * (j % 2), 10 + 1.3 * j) for i in range(30) for j in range(6)]
    m = _dots(pts).astype(np.uint8)
    for i in range(30):  # small bits in the gaps of two rows, 0.3 x 0.3 mm
        for y_mm in (10.3, 12.9):
            x, y = round((10.5 + 1.3 * i) / PX), round(y_mm / PX)
            m[y : y + 3, x : x + 3] = 1
    _n, _lab, stats, cent = components_with_stats(m, connectivity=8)
    bits = stats[:, cv2.CC_STAT_AREA] <= 9
    bits[0] = False
    dots = ~bits
    dots[0] = False
    assert not _fine_fields(stats, cent, PX, OPTS)[dots].all()  # the rows with bits lost
    whole = _fine_fields(stats, cent, PX, OPTS, whole=~bits)
    assert whole[dots].all() and not whole[bits].any()


@pytest.mark.parametrize(
    ("dpi", "groove", "block"), [(150.0, 3.3, 2.2), (300.0, 3.3, 1.8), (300.0, 4.5, 2.2)]
)
def test_analyze_scan_file_shoulders_across_a_groove_from_the_rib_are_one_print(
    dpi, groove, block
):
    # a slick centre with file shoulders 3-4.5 mm of paper off it (held-out 4th
    # generator seed 8 sheets 5 and 48): the shoulders' diamonds, finer than a
    # tread's elements, came out as prints of their own, width -44 % and -71 % with
    # status ok (join_side_by_side took a narrow part only when one piece of ink).
    # A 4.5 mm groove is near the side-by-side rule's limit (0.18 x 30 mm): flagged.
    p = PrintSpec(
        120.0, 30.0, (80.0, 120.0), 0.0, "knurl", block=block, gap=0.5, rib=9.0, rib_groove=groove
    )
    pr, t = _one_print(p, dpi, (160.0, 240.0))
    assert pr.flags == (() if groove < 4 else ("grouping_uncertain",)), pr.warnings
    _assert_within(pr, t)


def test_analyze_scan_file_shoulders_of_a_print_off_the_sheet_join_it_clipped():
    # the same print running off the sheet's bottom edge: the shoulder beyond the
    # groove is cut by the edge; the print is one, flagged clipped (before, the
    # part off the edge was flagged and the rest read -44 % wide with status ok)
    p = PrintSpec(70.0, 50.0, (80.0, 12.0), 0.0, "knurl", block=2.2, gap=0.5, rib=12.0)
    p = dataclasses.replace(p, rib_groove=3.2)
    img, _ = render_sheet(SheetSpec((p,), dpi=300.0, size=(160.0, 240.0), specks=0))
    res = ip.analyze_scan(Scan(img, 25.4 / 300.0, "given"), rolling_axis="x", sensitivity=False)
    (pr,) = res.prints
    assert "clipped" in pr.flags
    # on the sheet: 37 mm of it; the upper shoulder, the groove and the rib down to
    # y = 6 mm at least (the page found in the image may cut it lower: flagged)
    assert pr.metrics.width > 37.0 - 12.0


@pytest.mark.parametrize(("dpi", "block", "gap"), [(200.0, 0.6, 1.0), (300.0, 0.5, 0.9)])
def test_analyze_scan_sparse_file_shoulders_are_the_print_not_dust(dpi, block, gap):
    # file shoulders of diamonds 0.5-0.6 mm long, 1.4-1.6 mm apart (ink share
    # 0.08-0.12 of the field) beside a slick centre: with fine_ink_share 0.12 they
    # were 1300-2200 "dust" and the print read 8-10 mm wide, not 39, status ok
    # (held-out seed 8 sheet 75: 7.2 mm for 41.7)
    p = PrintSpec(100.0, 40.0, (65.0, 35.0), 0.0, "knurl", block=block, gap=gap, rib=8.0)
    pr, t = _one_print(p, dpi, (130.0, 70.0))
    assert pr.status == "ok", pr.warnings
    _assert_within(pr, t)


def test_analyze_scan_speck_beside_a_fine_tread_is_an_edge_spot():
    # held-out seed 8 sheet 28: a 0.1 mm^2 speck 0.8 mm (1.8 pattern gaps) off a
    # dot print's end was kept (within edge_spot_distance_mm), length +19.8 % with
    # status ok; beyond SPECK_GAPS gaps and smaller than the elements it is a spot
    dpi = 300.0
    p = PrintSpec(30.0, 20.0, (40.0, 40.0), 0.0, "knurl", block=1.6, gap=0.4)
    img, (t,) = render_sheet(SheetSpec((p,), dpi=dpi, size=(80.0, 80.0), specks=0))
    mm = 25.4 / dpi
    yy, xx = np.mgrid[0 : img.shape[0], 0 : img.shape[1]]
    x_mm, y_mm = (xx + 0.5) * mm, 80.0 - (yy + 0.5) * mm
    ink = np.percentile(img[np.hypot(x_mm - 40.0, y_mm - 40.0) < 5.0], 5)
    at = 40.0 + 0.5 * t.length + 0.7  # 0.85 mm of paper to the print's end (10 px)
    speck = np.hypot(x_mm - at, y_mm - 40.0) <= 0.2
    img = np.where(speck, np.minimum(img, ink), img).astype(img.dtype)
    (pr,) = ip.analyze_scan(Scan(img, mm, "given"), rolling_axis="x", sensitivity=False).prints
    assert pr.n_edge_spots >= 1
    assert_allclose([pr.metrics.length, pr.metrics.width], [t.length, t.width], rtol=0.01)


def test_element_graph_element_between_the_samples_has_neighbours():
    # held-out 9 sheet 87: a knurl print's diamond tips, cut by the outline to 0.5 mm
    # triangles, were narrower than the partition's sampling step, fell between the
    # samples and went as dust (width -1.6 %, unflagged). Sampled every 2nd pixel:
    # a 1-pixel element at an odd row and column still has its neighbours
    from inkprint.group import element_graph

    labels = np.zeros((40, 40), np.int32)
    labels[4:16, 4:16] = 1  # a block
    labels[21, 9] = 2  # a tip bit 5 px below it, between the samples
    labels[4:16, 24:36] = 3  # the next block
    graph = element_graph(labels, 3, px_mm=0.1, step=2)
    pairs = set(zip(graph.a.tolist(), graph.b.tolist(), strict=True))
    assert (0, 1) in pairs  # (0-based: the block and the bit)
    gap = graph.gaps[(graph.a == 0) & (graph.b == 1)][0]
    assert 0.3 <= gap <= 0.8  # 5 px = 0.5 mm, to a sample's precision
    # every element keeps its own samples otherwise: the blocks' pair is the same
    full = element_graph(labels, 3, px_mm=0.1, step=1)
    assert (0, 2) in set(zip(full.a.tolist(), full.b.tolist(), strict=True))


@pytest.mark.parametrize("text", ["4", "7"])
def test_analyze_scan_lone_bold_digit_on_a_knurl_print_s_side_is_set_aside(text):
    # the label sweep, case 358: a marker's '4' (3.3 mm, 0.76 mm strokes) touching
    # a knurl print's side, more than twice a knurl element's area, was "a lone
    # stroke" (a ruler's stub) and the print's: width +16.6 %, status ok
    spec = SheetSpec(
        (PrintSpec(88.7, 16.0, (105.0, 140.0), 0.0, "knurl", ink=0.95),),
        dpi=300.0,
        seed=358,
        specks=5,
        marks=(Text(text, (90.3, 148.0), 3.3, 0.76, 1.0),),
        size=(215.9, 279.4),
    )
    img, (t,) = render_sheet(spec)
    res = ip.analyze_scan(ip.Scan(img, 25.4 / 300.0, "given"), rolling_axis="x", sensitivity=False)
    (p,) = res.prints
    m = p.metrics
    within = np.allclose([m.length, m.width], [t.length, t.width], rtol=0.01)
    assert within or p.status == "flagged", (m.length, t.length, m.width, t.width)
    assert within


def _tiny_file_print(
    dpi: float, pitch=0.9, groove=0.35, turn_deg=60.0, *, size=(17.0, 5.2, 2.6), n=3.5
) -> tuple:
    """A 17 x 5.2 mm superellipse (n = 3.5) file print: a slick centre 2.6 mm wide
    and on each side diamonds between two families of 0.35 mm grooves 0.9 mm apart
    at +-60 degrees to x (held-out generator 6's file tread), cut at the centre's
    edge (the inner ones join it) and by the outline (the outer row: 11 dots of
    0.055-0.117 mm^2 a side); pieces under 0.05 mm^2 left out. ``size``: length,
    width and the centre's width [mm]. The grey, mm per px and the drawn truth
    (tests.inkprint.drawn)."""
    import shapely

    from tests.inkprint.drawn import drawn_scan

    ss, margin = 4, 5.0
    length, width, centre = size[0], size[1], size[2] / 2
    turn = math.radians(turn_deg)
    px = 25.4 / dpi / ss
    t = np.linspace(0, 2 * np.pi, 1440, endpoint=False)
    c, s = np.cos(t), np.sin(t)
    outline = shapely.Polygon(
        np.column_stack(
            [
                length / 2 * np.sign(c) * np.abs(c) ** (2 / n),
                width / 2 * np.sign(s) * np.abs(s) ** (2 / n),
            ]
        )
    )
    # a cell between grooves k and m of the two families (normals n1, n2)
    to_xy = np.linalg.inv([[-math.sin(turn), math.cos(turn)], [math.sin(turn), math.cos(turn)]])
    k, m = np.meshgrid(np.arange(-16, 16), np.arange(-16, 16))
    lo1, hi1 = k.ravel() * pitch + groove / 2, (k.ravel() + 1) * pitch - groove / 2
    lo2, hi2 = m.ravel() * pitch + groove / 2, (m.ravel() + 1) * pitch - groove / 2
    quads = np.stack([np.c_[lo1, lo2], np.c_[hi1, lo2], np.c_[hi1, hi2], np.c_[lo1, hi2]], 1)
    sides = shapely.union(
        shapely.box(-length, -width, length, -centre), shapely.box(-length, centre, length, width)
    )
    cells = shapely.intersection(
        shapely.intersection(shapely.polygons(quads @ to_xy.T), sides), outline
    )
    band = shapely.intersection(outline, shapely.box(-length, -centre, length, centre))
    ink = shapely.union_all([band, *cells[~shapely.is_empty(cells)]])
    img = np.zeros((round((width + 2 * margin) / px), round((length + 2 * margin) / px)), np.uint8)
    offset = np.array([length / 2 + margin, width / 2 + margin])
    for q in getattr(ink, "geoms", [ink]):
        if q.area >= 0.05:
            xy = np.array(q.exterior.coords) + offset
            cv2.fillPoly(img, [np.round(xy / px).astype(np.int32)], 1)
    return drawn_scan(img, dpi, ss, 0.8)


@pytest.mark.parametrize(("pitch", "groove", "turn"), [(0.9, 0.35, 60.0), (0.85, 0.25, 50.0)])
def test_analyze_scan_tiny_file_print_keeps_its_outer_row_of_small_dots(pitch, groove, turn):
    # held-out 6 seed 1 sheet 108 (360 dpi): a 17 x 5.2 mm file print whose outer
    # row of diamonds the outline cut to twelve dots of 0.08-0.13 mm^2 beside its
    # slick centre, each under DOT_LEAST_MM2's floors then (0.3, 0.2): dropped as
    # thin dots, width -10 % with status ok. A row of DOT_ROWS (10) or more dots of
    # 0.05 mm^2 or more is left to the section 7.1.1 rule. Here before: the 22 dots
    # dropped, width -15 %, hull area -18 % (flagged mark_on_edge). (The hull area
    # is not checked: the tips' corner pieces, left out of the load-bearing ink,
    # cost it 0.9-4.3 % with the lattice's phase and the pixel grid, status ok).
    # At 50 degrees the row next to the outer one is whole diamonds of 0.25 mm^2, a
    # row at the 0.2 mm^2 floor: the outer dots were no longer looked at (a sweep of
    # 240 such drawings: 34 silent, -1 to -10 % wide; 29 now, each floor's row kept)
    grey, mm, truth = _tiny_file_print(360.0, pitch, groove, turn)
    res = ip.analyze_scan(ip.Scan(grey, mm, "given"), rolling_axis="x", sensitivity=False)
    (p,) = res.prints
    assert_allclose([p.metrics.length, p.metrics.width], truth[:2], rtol=0.01)


def _assert_measured_whole(grey, mm: float, truth: tuple) -> None:
    """The one print on the drawn sheet is ok and within the issue's bar of the drawn
    truth: 1 % in length and width, 2 % in hull area."""
    res = ip.analyze_scan(ip.Scan(grey, mm, "given"), rolling_axis="x", sensitivity=False)
    (p,) = res.prints
    assert res.print_status(0) == "ok"
    assert_allclose([p.metrics.length, p.metrics.width], truth[:2], rtol=0.01)
    assert_allclose(p.metrics.hull_area, truth[2], rtol=0.02)


@pytest.mark.parametrize(
    ("dpi", "pitch", "groove", "turn"),
    [
        (400.0, 0.853, 0.368, 41.7),
        (400.0, 0.898, 0.329, 48.9),
        (600.0, 0.754, 0.321, 59.8),
        (400.0, 0.797, 0.311, 41.0),
    ],
)
def test_analyze_scan_tiny_file_print_keeps_the_cut_pieces_beside_its_rows(
    dpi, pitch, groove, turn
):
    # the outline cuts a tiny file print's diamonds at its corners and at its rows'
    # ends to pieces of 0.06-0.19 mm^2: too few for a row of their own (DOT_ROWS),
    # or too small beside the row's whole diamonds (DOT_SIZES), they were dropped
    # as thin dots. Before, here (from a sweep of 60 such drawings at 300-600 dpi):
    # hull area -3.7 %; width -3.0 % and hull area -2.9 %; hull area -3.4 %; width
    # -1.1 % and hull area -3.0 %, each with status ok. group._row_neighbours
    # leaves the dots a groove or so off a row or the print to the 7.1.1 rule
    _assert_measured_whole(*_tiny_file_print(dpi, pitch, groove, turn))


@pytest.mark.parametrize(
    ("dpi", "pitch", "groove", "turn"), [(600.0, 0.895, 0.288, 62.0), (300.0, 0.962, 0.322, 58.5)]
)
def test_analyze_scan_tiny_file_print_keeps_its_inner_row_joined_to_the_centre(
    dpi, pitch, groove, turn
):
    # at 58-62 degrees the inner row of diamonds, joined to the slick centre by its
    # edge, stands out of the centre's hull farther than a stroke is wide: dropped
    # as strokes' feet, not teeth (group.TEETH_DEPTH: 1 stroke then), hull area
    # -2.4 % and -4.3 % (flagged)
    _assert_measured_whole(*_tiny_file_print(dpi, pitch, groove, turn))


@pytest.mark.parametrize("off_mm", [0.6, 0.7, 1.0])
def test_analyze_scan_speck_off_a_tiny_file_print_s_tip_is_an_edge_spot(off_mm):
    # a 0.1 mm^2 speck 0.6-1 mm beyond the tip of a file print whose rows were
    # found: the dots left to the section 7.1.1 rule with the rows
    # (group._row_neighbours) are judged by it, and a speck alone off the tip is
    # dust; kept, the print reads 6 % long. (Before the rule all three were
    # flagged: the inner row dropped, and at 0.6 mm the speck kept, +5.8 %)
    dpi, length, margin, width = 600.0, 17.0, 5.0, 5.2
    grey, mm, truth = _tiny_file_print(dpi, 0.895, 0.288, 62.0)
    r = math.sqrt(0.1 / math.pi)
    yy, xx = np.mgrid[: grey.shape[0], : grey.shape[1]]
    x, y = length + margin + off_mm + r, width / 2 + margin
    grey[np.hypot(xx * mm - x, yy * mm - y) <= r] = 0.12
    res = ip.analyze_scan(ip.Scan(grey, mm, "given"), rolling_axis="x", sensitivity=False)
    (p,) = res.prints
    assert res.print_status(0) == "ok"
    assert_allclose([p.metrics.length, p.metrics.width], truth[:2], rtol=0.01)
