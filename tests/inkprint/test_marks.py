"""Sorting ink into prints and marks (inkprint.marks): the straight-line test."""

import cv2
import numpy as np
import pytest
from numpy.testing import assert_allclose

import inkprint as ip
from inkprint.marks import (
    _chevron_arms,
    _hull_box,
    _hull_map,
    _line_run,
    _nearest_hull,
    _nearest_label,
    sort_ink,
)
from inkprint.options import AnalysisOptions
from tests.inkprint.drawn import drawn_scan
from tests.inkprint.test_classes import outcomes

PX_MM = 25.4 / 150.0  # 150 dpi: a 0.9 mm stroke is 5.3 px


def _piece(draw) -> np.ndarray:
    img = np.zeros((160, 160), np.uint8)
    draw(img)
    return img


def test_line_run_takes_the_line_not_the_sliver_it_touches():
    # a 6 px line 150 px (25 mm) long at 40 degrees, with a 24 x 9 px sliver of a
    # print's edge block touching it: the line's own pixels, none of the sliver's
    line = _piece(lambda im: cv2.line(im, (5, 150), (120, 53), 1, 6))
    sliver = np.zeros_like(line)
    sliver[95:104, 75:99] = 1
    got = _line_run(line | sliver, PX_MM, AnalysisOptions())
    far = sliver.astype(bool) & (cv2.distanceTransform(1 - line, cv2.DIST_L2, 3) > 6.0)
    assert far.sum() > 50  # the sliver does reach past a stroke from the line
    assert not (got.astype(bool) & far).any()
    assert_allclose(got[line.astype(bool)].mean(), 1.0, atol=0.02)


def test_line_run_rejects_an_arc_and_a_short_line():
    # a rib following a print's curved outline is not a straight line; nor is a
    # line shorter than line_length_mm (12 mm = 71 px)
    opts = AnalysisOptions()
    arc = _piece(lambda im: cv2.ellipse(im, (80, 160), (75, 75), 0, 200, 340, 1, 6))
    assert not _line_run(arc, PX_MM, opts).any()
    short = _piece(lambda im: cv2.line(im, (20, 80), (80, 80), 1, 6))
    short[70:90, 40:70] = 1
    assert not _line_run(short, PX_MM, opts).any()


def test_sort_ink_ruler_touching_edge_slivers_is_still_a_line(tmp_path):
    # ruler seed 5 at 150 dpi: the ruler crossed the print where its edge blocks are
    # narrow slivers; ruler and slivers made one piece too wide for a line, so the
    # ruler stayed thick ink and joined the print (width +194 %, unflagged)
    results, rows = outcomes(tmp_path, "ruler", 5)
    (r,) = results
    assert "line" in rows[0]["set_aside"]
    # measured within the bar (flagged too: the line grazes the edge, bound 2.5 %)
    assert r["outcome"] in ("pass", "overflagged"), r
    assert abs(r["err_width"]) <= 0.01 and abs(r["err_length"]) <= 0.01


def _ruler_piece(long_every: int = 3) -> np.ndarray:
    # a ruler's line, 3 px wide and 480 px (81 mm) long, ticks every 59 px (10 mm)
    # to its left, 14 px long and every third one 30 px (5 mm): each long tick is a
    # straight segment Hough finds
    img = np.zeros((500, 60), np.uint8)
    cv2.line(img, (45, 10), (48, 490), 1, 3)
    for k, y in enumerate(range(20, 490, 59)):
        cv2.line(img, (45 - (30 if k % long_every == 0 else 14), y), (45, y), 1, 2)
    return img.astype(bool)


def test_line_pixels_ruler_with_ticks_is_one_line():
    # mixed set 4260, file 30: lines fitted to the tick tips and to short
    # stretches of the ruler (1-12 degrees off it), extended across the box, took a
    # 35 px swath out of a ribbed print the ruler crossed and split it (length
    # -37.5 %); each line now must be inked along half its course, once
    from inkprint.marks import _line_pixels

    px, lines, _ = _line_pixels(_ruler_piece(), PX_MM)
    steep = [line for line in lines if abs(line[0][1]) > 0.99]
    assert len(steep) == 1  # the ruler, once
    ((d, _, (t0, t1)),) = steep
    assert_allclose(abs(d[0] / d[1]), 3.0 / 480.0, atol=0.006)  # within 0.35 degrees
    assert t1 - t0 > 400  # inked along its length
    for d, _, (t0, t1) in lines:  # the long ticks, if taken, are short lines
        if abs(d[1]) <= 0.99:
            assert t1 - t0 < 40
    assert px[200, 46] and not px[200, 10]


def test_bands_reach_as_far_as_the_line_is_inked():
    # a band goes past its line's inked stretch by half that stretch's length, not
    # by the box's diagonal: a 5 mm tick's band crossed the sheet
    from inkprint.marks import _bands, _line_pixels, _pool

    _, lines, width = _line_pixels(_ruler_piece(long_every=1), PX_MM)
    pooled = _pool(np.zeros((10, 10), bool), PX_MM, AnalysisOptions())
    box = (slice(0, 500), slice(0, 60))
    for band, (_, _, (t0, t1)) in zip(_bands(lines, width, box, pooled), lines, strict=True):
        length = np.hypot(*np.subtract(band.p1, band.p0)) / pooled.q
        assert_allclose(length, 2 * (t1 - t0), rtol=0.02)


def test_sort_ink_ruler_across_a_ribbed_print_keeps_it_whole(tmp_path):
    # mixed set 4260, file 30 (150 dpi): the ruler's spurious bands split the print
    # and its 23 mm end went aside as "a letter" (length -37.5 %, flagged only by
    # the pull of the marks, "up to 1.6 %")
    results, rows = outcomes(tmp_path, "ruler", 4260 * 100_003 + 30, dpi=None)
    (r,) = results
    assert r["outcome"] == "pass", r
    assert "writing" not in rows[0]["set_aside"]


def _nearest_hull_whole_box(hull_map, reach_px, at):
    # the reference: one distance transform over the box of all the hulls
    dist, ids = np.full(len(at), np.inf, np.float32), np.zeros(len(at), np.int32)
    ys, xs = np.nonzero(hull_map)
    if not len(ys):
        return dist, ids
    pad = int(np.ceil(reach_px)) + 2
    h, w = hull_map.shape
    r0, r1 = max(ys.min() - pad, 0), min(ys.max() + pad + 1, h)
    c0, c1 = max(xs.min() - pad, 0), min(xs.max() + pad + 1, w)
    r, c = np.divmod(at, w)
    inside = (r >= r0) & (r < r1) & (c >= c0) & (c < c1)
    d, nearest, lut = _nearest_label(hull_map[r0:r1, c0:c1])
    rr, cc = r[inside] - r0, c[inside] - c0
    far = d[rr, cc] > reach_px
    dist[inside] = np.where(far, np.inf, d[rr, cc])
    ids[inside] = np.where(far, 0, lut[nearest[rr, cc]])
    return dist, ids


def test_nearest_hull_by_clusters_equals_one_transform_over_all_hulls():
    # the transforms around each cluster of hulls give the distances and nearest
    # hulls of one transform over them all, on hull maps with hulls near and far
    rng = np.random.default_rng(7)
    for _ in range(150):
        h, w = rng.integers(60, 300, 2)
        hulls = []
        for _k in range(int(rng.integers(1, 10))):
            c = rng.uniform(-20, w + 20), rng.uniform(-20, h + 20)
            spread = rng.uniform(1, 40), rng.uniform(1, 25)
            pts = np.column_stack([rng.normal(c[i], spread[i], 12) for i in (0, 1)])
            hulls.append(cv2.convexHull(pts.astype(np.float32)) if rng.random() > 0.1 else None)
        hull_map = _hull_map(hulls, (h, w))
        reach = float(rng.uniform(0.5, 80))
        at = np.arange(h * w)
        got = _nearest_hull(hull_map, reach, at, [_hull_box(x, (h, w)) for x in hulls])
        want = _nearest_hull_whole_box(hull_map, reach, at)
        np.testing.assert_array_equal(got[0], want[0])
        np.testing.assert_array_equal(got[1], want[1])


def test_bar_field_a_tread_s_parallel_bars_are_no_lines():
    # held-out set 1 sheet 119 (160 dpi) and set 3 sheet 12 (300 dpi): a herringbone
    # print's straight bars, narrower than two strokes and longer than a line, were
    # 18-36 "ruler lines" and the print went missing. Side by side, turned alike and
    # as long, they are a tread's bars: 1.4 mm wide, 3 mm apart, 14-19 mm long
    from inkprint.marks import _bar_field

    px = 25.4 / 160.0
    n = 8
    rects = [((0.0, 0.0), (17.0 / px, 1.4 / px), 45.0) for _ in range(n)]
    step = 3.0 / px / np.sqrt(2)  # centres 3 mm apart across the bars
    corners = [(round(k * step), round(-k * step)) for k in range(n)]  # (row, col)
    assert _bar_field(rects, corners, px).all()
    # a ruler and lines drawn apart are lines: too few, not side by side, not alike
    assert not _bar_field(rects[:3], corners[:3], px).any()
    far = [(round(k * 8 * step), round(-k * 8 * step)) for k in range(n)]
    assert not _bar_field(rects, far, px).any()
    turned = [((0.0, 0.0), (17.0 / px, 1.4 / px), 10.0 * k) for k in range(n)]
    assert not _bar_field(turned, corners, px).any()
    long = [((0.0, 0.0), (60.0 / px, 1.4 / px), 45.0) for _ in range(n)]
    assert not _bar_field(long, corners, px).any()  # longer than a tread's bar


def test_bar_field_bars_offset_along_themselves_are_a_field():
    # held-out 11 sheet 21 (150 dpi): a herringbone's 10 mm bars at 35 degrees to
    # the print's axis, 6.4 mm apart along it, lie 3.6 mm apart across themselves
    # and 5.2 mm along: more than half their length, so no field (width -53 %)
    from inkprint.marks import _bar_field

    px = 25.4 / 150.0
    a = np.radians(55.0)
    u, v = np.array([np.cos(a), np.sin(a)]), np.array([-np.sin(a), np.cos(a)])
    rects = [((0.0, 0.0), (10.0 / px, 1.85 / px), 55.0) for _ in range(6)]
    centres = [(k * (5.2 * u + 3.6 * v)) / px for k in range(6)]  # (x, y) [px]
    corners = [(round(c[1]) + 500, round(c[0]) + 500) for c in centres]  # (row, col)
    assert _bar_field(rects, corners, px).all()
    # a neighbour beyond its length along it is not beside it
    far = [
        (
            round(k * (9.0 * u + 3.6 * v)[1] / px) + 500,
            round(k * (9.0 * u + 3.6 * v)[0] / px) + 500,
        )
        for k in range(6)
    ]
    assert not _bar_field(rects, far, px).any()


def test_sort_ink_pixel_noise_without_thick_ink_sorts():
    # no piece survives the stroke-wide opening: the thick ink's box is empty (the
    # fine tread's look for tips shaved off thick ink dilated an empty array: an
    # internal error on 23 noise pages)
    rng = np.random.default_rng(3)
    mask = rng.random((400, 300)) < 0.03
    ink = sort_ink(mask, mm_per_px=0.1)
    assert not ink.groups and ink.marks


def _herringbone(
    dpi: float,
    bar: float,
    ss: int = 4,
    *,
    off: float | None = None,
    step: float = 4.0,
    rib: float = 6.0,
    run: float = 1.0,
    size: tuple = (70.0, 28.0),
) -> tuple:
    """An elliptical herringbone print ``size`` (length, width) [mm]: a slick centre
    rib ``rib`` mm wide and bars ``bar`` mm wide running ``run`` mm along per mm
    across (1: 45 degrees), ``step`` mm apart, standing ``off`` mm off the rib
    either side (1.5 ``bar`` when None; 0: joined to it); grey image (area coverage
    of a ``ss`` x finer drawing), mm per px and the truth (length, width, hull area)
    of the drawn ink."""
    mm = 25.4 / dpi / ss
    off = 1.5 * bar if off is None else off
    h, w = int(60 / mm), int(100 / mm)
    cx, cy = w / 2, h / 2
    ink = np.zeros((h, w), np.uint8)
    cv2.rectangle(ink, (0, round(cy - rib / 2 / mm)), (w, round(cy + rib / 2 / mm)), 1, -1)
    for x in np.arange(-70.0, 70.0, step):
        for side in (-1, 1):
            y0, y1 = side * (rib / 2 + off), side * 20.0
            p0 = (round(cx + x / mm), round(cy + y0 / mm))
            p1 = (round(cx + (x + run * abs(y1 - y0)) / mm), round(cy + y1 / mm))
            cv2.line(ink, p0, p1, 1, max(1, round(bar / mm)))
    outline = np.zeros_like(ink)
    axes = (round(size[0] / 2 / mm), round(size[1] / 2 / mm))
    cv2.ellipse(outline, (round(cx), round(cy)), axes, 0, 0, 360, 1, -1)
    return drawn_scan(ink & outline, dpi, ss, 0.75)


@pytest.mark.parametrize("dpi, bar", [(160.0, 1.0), (200.0, 1.2), (300.0, 1.5)])
def test_analyze_scan_herringbone_bars_off_a_rib_are_tread(dpi, bar):
    # bars as wide as a marker's stroke standing off a centre rib were set aside as
    # bold letters (the print came out as its rib alone: width -78 %, flagged), then
    # read as lines reaching 3 x beyond the rib's body (flagged mark_on_edge)
    grey, mm, (length, width, area) = _herringbone(dpi, bar)
    res = ip.analyze_scan(ip.Scan(grey, mm, "given"), rolling_axis="x", sensitivity=False)
    (pr,) = res.prints
    assert pr.status == "ok", pr.warnings
    assert_allclose([pr.metrics.length, pr.metrics.width], [length, width], rtol=0.01)
    assert_allclose(pr.metrics.hull_area, area, rtol=0.02)


@pytest.mark.parametrize(
    "dpi, bar, step, rib, run, size",
    [
        (240.0, 1.75, 7.5, 11.5, 1.54, (61.5, 31.3)),
        (300.0, 1.5, 7.5, 11.5, 1.54, (61.5, 31.3)),
        (180.0, 1.6, 7.5, 11.5, 1.54, (61.5, 31.3)),
        (150.0, 1.85, 6.4, 9.0, 1.43, (72.2, 20.3)),
    ],
)
def test_analyze_scan_herringbone_bars_joined_to_the_rib_are_tread(dpi, bar, step, rib, run, size):
    # held-out 14 sheet 21 (240 dpi): bars joined to the rib by their ink were cut
    # from its rim as a marker's letters (the print came out as its rib alone:
    # width -63 %, flagged); kept, they still read as lines reaching 117 % beyond
    # the rib's body (flagged mark_on_edge) and their tips as dust on its edge.
    # Held-out 11 sheet 21 (150 dpi): 10 mm bars 5.2 mm apart along themselves were
    # no field (half their length at most: width -53 %, flagged)
    grey, mm, (length, width, area) = _herringbone(
        dpi, bar, off=0.0, step=step, rib=rib, run=run, size=size
    )
    res = ip.analyze_scan(ip.Scan(grey, mm, "given"), rolling_axis="x", sensitivity=False)
    (pr,) = res.prints
    assert pr.status == "ok", pr.warnings
    assert_allclose([pr.metrics.length, pr.metrics.width], [length, width], rtol=0.01)
    assert_allclose(pr.metrics.hull_area, area, rtol=0.02)


@pytest.mark.parametrize("dpi", [200.0, 300.0])
def test_analyze_scan_herringbone_wide_bars_are_no_pen_line(dpi):
    # held-out 12 sheet 93, 8 sheet 103: bars 3-3.5 mm wide at 45 degrees, a few a
    # side, vanish in the square opening that takes pen lines (a diagonal bar up to
    # 1.4 x as wide goes) and were flagged as a ruler's edge taken for tread; a pen
    # line is no wider than 2.5 strokes at its widest
    grey, mm, (length, width, area) = _herringbone(dpi, 3.0, off=2.0, step=9.0)
    res = ip.analyze_scan(ip.Scan(grey, mm, "given"), rolling_axis="x", sensitivity=False)
    (pr,) = res.prints
    assert pr.status == "ok", pr.warnings
    assert_allclose([pr.metrics.length, pr.metrics.width], [length, width], rtol=0.01)
    assert_allclose(pr.metrics.hull_area, area, rtol=0.02)


def _rect(centre, length, width, angle_deg):
    """OpenCV's minAreaRect of a bar, as if in a box at (0, 0)."""
    return ((float(centre[0]), float(centre[1])), (float(length), float(width)), angle_deg)


def test_chevron_arms_meet_end_to_end_lines_do_not():
    # two arms of a V meeting at its apex (the opening took the wider apex: a gap of
    # a bar's width); a ruler crossing a line at its middle; two parallel lines apart
    c45, s45 = np.cos(np.radians(45)), np.sin(np.radians(45))
    arm = 100.0
    top = _rect((200 - 0.5 * arm * c45, 200 - 0.5 * arm * s45 - 6), arm, 10, 45.0)
    bottom = _rect((200 - 0.5 * arm * c45, 200 + 0.5 * arm * s45 + 6), arm, 10, -45.0)
    cross = _rect((200, 200), 150, 10, 0.0)
    other = _rect((200, 200), 150, 10, 90.0)
    far = _rect((200, 400), 150, 10, 0.0)
    corners = [(0, 0)] * 2
    assert _chevron_arms([top, bottom], corners).all()
    assert not _chevron_arms([cross, other], corners).any()
    assert not _chevron_arms([cross, far], corners).any()


def _chevrons(dpi: float, bar: float, pitch: float, phase: float, ss: int = 4) -> tuple:
    """An 81 x 29 mm elliptical print of chevrons (V bars ``bar`` mm wide every
    ``pitch`` mm, 45 degrees, no centre rib; held-out 8 sheet 6): grey image, mm per
    px and the drawn ink's (length, width, hull area)."""
    mm = 25.4 / dpi / ss
    h, w = int(50 / mm), int(110 / mm)
    cx, cy = w / 2, h / 2
    ink = np.zeros((h, w), np.uint8)
    for x in np.arange(-81.0, 81.0, pitch) + phase:
        v = [
            [cx + (x - 29) / mm, cy - 29 / mm],
            [cx + x / mm, cy],
            [cx + (x - 29) / mm, cy + 29 / mm],
        ]
        cv2.polylines(ink, [np.array(v, np.int32)], False, 1, max(1, round(bar / mm)))
    outline = np.zeros_like(ink)
    cv2.ellipse(
        outline, (round(cx), round(cy)), (round(40.5 / mm), round(14.5 / mm)), 0, 0, 360, 1, -1
    )
    return drawn_scan(ink & outline, dpi, ss, 0.6)


@pytest.mark.parametrize(("bar", "pitch", "phase"), [(1.4, 2.4, 0.0), (1.6, 2.8, 0.7)])
def test_analyze_scan_chevron_print_at_360_dpi_is_one_print(bar, pitch, phase):
    # chevrons whose apex the opening took left straight arms 18 mm long: taken for
    # ruler lines, they split the print in two or three (length -36 to -87 %, some
    # unflagged: held-out 8 sheet 6, -36.5 % and a spurious print)
    grey, mm, (length, width, area) = _chevrons(360.0, bar, pitch, phase)
    res = ip.analyze_scan(ip.Scan(grey, mm, "given"), rolling_axis="x", sensitivity=False)
    (pr,) = res.prints
    assert pr.status == "ok", pr.warnings
    assert_allclose([pr.metrics.length, pr.metrics.width], [length, width], rtol=0.01)
    assert_allclose(pr.metrics.hull_area, area, rtol=0.02)


@pytest.mark.parametrize("dpi", [150.0, 300.0])
def test_is_print_framed_ruler_is_a_line_not_a_print(dpi):
    # held-out seed 8 sheet 15: a ruler drawn as a frame (1 mm lines), its ticks
    # along one side and numbers inside, 242 x 25 mm, was a print with status ok
    # (and three other sheets' rulers flagged "prints"); straight ink along both
    # long sides of its rectangle is a ruler's, no print's
    from inkprint.read import Scan
    from inkprint.synth import PrintSpec, SheetSpec, render_sheet

    p = PrintSpec(90.0, 35.0, (130.0, 150.0), 0.0, "ribbed")
    img, (t,) = render_sheet(SheetSpec((p,), dpi=dpi, size=(200.0, 280.0), specks=0))
    px = dpi / 25.4  # [px / mm]
    ruler = np.zeros(img.shape[:2], np.uint8)
    x0, y0, x1, y1 = (round(v * px) for v in (15.0, 20.0, 40.0, 262.0))
    cv2.rectangle(ruler, (x0, y0), (x1, y1), 1, round(1.0 * px))  # a 1 mm frame
    for k in range(0, 240):  # ticks every mm, 2/3.5/5 mm long
        y = round((21.0 + k) * px)
        tick = 5.0 if k % 10 == 0 else 3.5 if k % 5 == 0 else 2.0
        cv2.line(ruler, (x0, y), (x0 + round(tick * px), y), 1, max(1, round(0.2 * px)))
        if k % 10 == 0:  # a number: a small bold glyph
            cv2.rectangle(
                ruler,
                (x0 + round(7 * px), y - round(1.5 * px)),
                (x0 + round(9 * px), y + round(1.5 * px)),
                1,
                max(1, round(0.4 * px)),
            )
    ink = float(np.percentile(img, 1))
    img = np.where(ruler > 0, np.minimum(img, ink), img).astype(img.dtype)
    res = ip.analyze_scan(Scan(img, 25.4 / dpi, "given"), rolling_axis="x", sensitivity=False)
    (pr,) = res.prints
    assert_allclose([pr.metrics.length, pr.metrics.width], [t.length, t.width], rtol=0.01)
    assert any("ruler or a frame" in m.reason for m in res.marks)


def _lens_rib_scan(dpi: float, rib: float, groove: float, width: float) -> tuple:
    """An 85 mm long elliptic print rolling along x, ``width`` [mm] wide, of ribs
    ``rib`` wide between grooves ``groove`` wide, the middle rib on the axis: the
    outline cuts the outer ribs to lenses."""
    ss, length = 4, 85.0
    mm = 25.4 / dpi / ss
    h, w = round((width + 20) / mm), round((length + 20) / mm)
    y, x = np.mgrid[0:h, 0:w]
    u, v = (x + 0.5) * mm - (length + 20) / 2, (y + 0.5) * mm - (width + 20) / 2
    inside = (u / (length / 2)) ** 2 + (v / (width / 2)) ** 2 <= 1.0
    rib_at = np.abs(np.mod(v + rib / 2, rib + groove)) < rib
    return drawn_scan((inside & rib_at).astype(np.uint8), dpi, ss, 0.7)


@pytest.mark.parametrize(
    "dpi, rib, groove, width", [(300.0, 2.95, 1.49, 26.4), (200.0, 2.5, 1.2, 22.0)]
)
def test_sort_ink_outer_rib_lenses_are_the_prints(dpi, rib, groove, width):
    # held-out (gen. 2026-11-29) seed 1 sheet 40: a ribbed road print whose outline
    # cut both outer ribs to lenses 34-38 mm long and up to 1.4 mm wide, set aside as
    # ruler lines: width -21 %, unflagged. A lens is convex and tapers to both ends
    # (a ruler's edge is as wide all along): the print's
    grey, mm_px, (length, wide, area) = _lens_rib_scan(dpi, rib, groove, width)
    r = ip.analyze_scan(ip.Scan(grey, mm_px, "given"), rolling_axis="x", sensitivity=False)
    (pr,) = r.prints
    m = pr.metrics
    assert_allclose([m.length, m.width], [length, wide], rtol=0.005)
    assert_allclose(m.hull_area, area, rtol=0.01)
    assert "mark_on_edge" not in pr.flags, pr.warnings
    assert not [k for k in r.marks if k.kind == "line"], r.marks


def _tiny_rib_scan(dpi: float, length: float, width: float, rib: float, groove: float):
    """A tiny elliptic print rolling along x of ribs ``rib`` wide between grooves
    ``groove`` wide, the middle rib on the axis (``rib`` < 0: a groove, ribs
    ``-rib`` wide), on a 40 mm square sheet, with a marker's '=' (two 6 x 1.9 mm
    bars 1.5 mm apart) 10 mm below it."""
    shift = 0.0 if rib > 0 else 0.5 * (groove - rib)
    rib = abs(rib)
    ss = 4
    mm = 25.4 / dpi / ss
    n = round(40.0 / mm)
    y, x = np.mgrid[0:n, 0:n]
    u, v = (x + 0.5) * mm - 20.0, (y + 0.5) * mm - 14.0
    inside = (u / (length / 2)) ** 2 + (v / (width / 2)) ** 2 <= 1.0
    ink = inside & (np.abs(np.mod(v + rib / 2 + shift, rib + groove)) < rib)
    grey, mm_px, truth = drawn_scan(ink.astype(np.uint8), dpi, ss, 0.7)
    bars = (np.abs(u) <= 3.0) & ((np.abs(v - 24.0) <= 0.95) | (np.abs(v - 27.4) <= 0.95))
    cover = cv2.resize(bars.astype(np.float32), grey.shape[::-1], interpolation=cv2.INTER_AREA)
    return np.minimum(grey, 0.92 - 0.7 * cover).astype(np.float32), mm_px, truth


@pytest.mark.parametrize(
    "dpi, length, width, rib, groove",
    [
        (600.0, 15.86, 9.5, 3.0, 1.2),
        (600.0, 11.9, 9.0, 2.5, 1.0),
        (400.0, 14.0, 10.0, 2.2, 1.0),
        (600.0, 15.5, 5.4, -2.1, 1.2),  # two ribs
    ],
)
def test_analyze_scan_tiny_rib_print_is_a_print(dpi, length, width, rib, groove):
    # held-out (gen. 2026-11-29) seeds 1 and 2: 10-16 mm prints of three ribs 2.2-3 mm
    # wide, 0.70-0.74 of the hull inked, set aside as "a letter or a mark (a print
    # this small is solid)": six prints missing (and two-rib ones 13-18 mm long on
    # seeds 1-3). Parallel bars wider than a
    # marker's strokes whose grooves close are a rib print; the marker's '=' beside
    # it (two bars) stays a mark
    grey, mm_px, (t_len, t_wid, t_area) = _tiny_rib_scan(dpi, length, width, rib, groove)
    r = ip.analyze_scan(ip.Scan(grey, mm_px, "given"), rolling_axis="x", sensitivity=False)
    (pr,) = r.prints
    m = pr.metrics
    if rib < 0 and pr.flags:  # two ribs, their tips thin slivers: found, may be flagged
        assert "mark_on_edge" in pr.flags and m.length <= t_len, pr.warnings
        return
    assert_allclose([m.length, m.width], [t_len, t_wid], rtol=0.01)
    assert_allclose(m.hull_area, t_area, rtol=0.02)


def test_measure_print_rib_beside_a_tiny_print_is_its_own():
    # held-out (gen. 2026-11-29) seed 2 sheet 114: a 19.9 x 5.8 mm boxy print of two
    # ribs; the narrower, as long as the print and straight, set aside as a ruler
    # line: width -60 %, unflagged; then flagged (a line along a print within
    # group_distance_mm, no farther than its tips); then, both ribs kept, its 1.93 mm
    # groove (over two strokes) left the pair "a letter or a mark": missing. A
    # straight piece running from tip to tip along the rest of the print is its rib,
    # and a rib print's grooves close with a disk as wide as its narrower rib
    ss, dpi = 4, 600.0
    mm = 25.4 / dpi / ss
    n = round(36.0 / mm)
    y, x = np.mgrid[0:n, 0:n]
    u, v = (x + 0.5) * mm - 18.0, (y + 0.5) * mm - 18.0
    inside = (u / 9.925) ** 4 + (v / 2.9) ** 4 <= 1.0
    ribs = (v <= -0.58) | (v >= 1.35)
    grey, mm_px, (length, width, area) = drawn_scan((inside & ribs).astype(np.uint8), dpi, ss, 0.6)
    r = ip.analyze_scan(ip.Scan(grey, mm_px, "given"), rolling_axis="x", sensitivity=False)
    (pr,) = r.prints
    m = pr.metrics
    assert pr.flags == (), pr.warnings
    assert_allclose([m.length, m.width], [length, width], rtol=0.01)
    assert_allclose(m.hull_area, area, rtol=0.02)


def _rrect_rib_scan(dpi, length, width, radius, rib, groove, *, line=None):
    """A print rolling along x, a rounded rectangle ``length`` x ``width`` (corner
    ``radius``) [mm] of ribs ``rib`` wide between grooves ``groove`` wide from its
    top side down (the outline cuts the bottom rib to what is left), on a sheet
    ``length`` + 30 mm by ``width`` + 30 mm; ``line``: a pen line (x0, x1, y, w)
    [mm from the print's centre] drawn beside it, not counted in the truth."""
    ss = 4
    mm = 25.4 / dpi / ss
    h, w = round((width + 30.0) / mm), round((length + 30.0) / mm)
    y, x = np.mgrid[0:h, 0:w]
    u, v = (x + 0.5) * mm - w * mm / 2, (y + 0.5) * mm - h * mm / 2
    du = np.maximum(np.abs(u) - (length / 2 - radius), 0.0)
    dv = np.maximum(np.abs(v) - (width / 2 - radius), 0.0)
    inside = (np.abs(u) <= length / 2) & (np.abs(v) <= width / 2) & (du**2 + dv**2 <= radius**2)
    ribs = np.mod(v + width / 2, rib + groove) < rib
    grey, mm_px, truth = drawn_scan((inside & ribs).astype(np.uint8), dpi, ss, 0.6)
    if line is not None:
        x0, x1, yl, wl = line
        pen = (u >= x0) & (u <= x1) & (np.abs(v - yl) <= wl / 2)
        cover = cv2.resize(pen.astype(np.float32), grey.shape[::-1], interpolation=cv2.INTER_AREA)
        grey = np.minimum(grey, 0.92 - 0.75 * cover).astype(np.float32)
    return grey, mm_px, truth


@pytest.mark.parametrize(
    "dpi, length, width, radius, rib, groove",
    [
        (300.0, 91.6, 20.9, 3.0, 3.99, 0.91),  # held-out seed 4 sheet 16: bottom rib 1.7 mm
        (600.0, 19.7, 5.74, 1.2, 3.17, 1.22),  # sheet 36: two ribs, the second 1.35 mm
        (400.0, 40.0, 12.0, 2.0, 2.6, 1.0),  # bottom rib 0.8 mm, under a stroke
    ],
)
def test_sort_ink_outer_rib_cut_straight_is_the_prints(dpi, length, width, radius, rib, groove):
    # held-out (gen. 2026-11-29) seed 4 sheets 16 and 36, seed 3 sheet 108: a rounded
    # rectangle's outer rib, cut thin by the outline, as wide all along and as long
    # as the print: no lens, so set aside as a ruler's line (width -10 %, -45 %,
    # flagged; tiny ones missing). Running along the rest of the print from tip to
    # tip, it is the print's rib
    grey, mm_px, (t_len, t_wid, t_area) = _rrect_rib_scan(dpi, length, width, radius, rib, groove)
    r = ip.analyze_scan(ip.Scan(grey, mm_px, "given"), rolling_axis="x", sensitivity=False)
    (pr,) = r.prints
    assert pr.flags == (), pr.warnings
    assert_allclose([pr.metrics.length, pr.metrics.width], [t_len, t_wid], rtol=0.01)
    assert_allclose(pr.metrics.hull_area, t_area, rtol=0.02)


@pytest.mark.parametrize(
    "line",
    [
        (-30.0, 30.0, 13.0, 0.5),  # 60 mm of a 92 mm print's side: shorter than a rib
        (-52.0, 52.0, 13.0, 0.5),  # beyond both tips: a ruler's edge
        (-40.0, 52.0, 13.0, 0.8),  # beyond one tip
    ],
)
def test_sort_ink_pen_line_beside_a_rib_print_is_no_rib(line):
    # controls for the rule above: a straight pen line 2.5 mm below a ribbed print,
    # shorter than it or running on beyond a tip, stays a mark
    grey, mm_px, (t_len, t_wid, _) = _rrect_rib_scan(300.0, 91.6, 21.0, 3.0, 3.99, 0.91, line=line)
    r = ip.analyze_scan(ip.Scan(grey, mm_px, "given"), rolling_axis="x", sensitivity=False)
    (pr,) = r.prints
    m = pr.metrics
    assert_allclose(m.length, t_len, rtol=0.01)
    assert abs(m.width / t_wid - 1) <= 0.01 or "mark_on_edge" in pr.flags, (m.width, t_wid)
    assert m.width < t_wid + 1.0, m.width  # the line is never measured as the print's


def _siped(dpi: float, ss: int, length: float, shift: float) -> tuple:
    """A road print of siped blocks (held-out seed 5 sheet 105): three staggered
    rows 9.2 mm apart of 7.6 x 8 mm blocks 9.5 mm apart, each with three 0.5 mm
    sipes 1.9 mm apart (closed in the centre row, open to the outside in the outer
    rows, whose blocks the sides cut to solid bars) inside a rounded rectangle
    ``length`` x 24 mm (corner 4 mm) that cuts the blocks at its ends and sides,
    the rows shifted ``shift`` mm along; :func:`drawn_scan` of it."""
    mm = 25.4 / dpi / ss
    h, w = int(50 / mm), int((length + 30) / mm)
    cx, cy = w / 2, h / 2
    ink = np.zeros((h, w), np.uint8)
    for row, y in enumerate((-9.2, 0.0, 9.2)):
        top, bottom = (-4.0, -2.5) if row == 0 else (2.5, 4.0) if row == 2 else (-2.8, 2.8)
        for x in np.arange(-length, length, 9.5) + shift + 4.75 * (row % 2):
            c0, r0 = round(cx + x / mm), round(cy + (y - 4.0) / mm)
            c1, r1 = round(cx + (x + 7.6) / mm), round(cy + (y + 4.0) / mm)
            cv2.rectangle(ink, (c0, r0), (c1, r1), 1, -1)
            for k in (0, 1, 2):  # the sipes
                s0 = round(cx + (x + 1.9 + 1.9 * k) / mm)
                p0, p1 = (s0, round(cy + (y + top) / mm)), (s0, round(cy + (y + bottom) / mm))
                cv2.line(ink, p0, p1, 0, max(1, round(0.5 / mm)))
    outline = np.zeros_like(ink)  # a rounded rectangle: two crossed bars, four disks
    x0, x1 = round(cx - length / 2 / mm), round(cx + length / 2 / mm)
    y0, y1 = round(cy - 12 / mm), round(cy + 12 / mm)
    rad = round(4 / mm)
    cv2.rectangle(outline, (x0 + rad, y0), (x1 - rad, y1), 1, -1)
    cv2.rectangle(outline, (x0, y0 + rad), (x1, y1 - rad), 1, -1)
    for px in (x0 + rad, x1 - rad):
        for py in (y0 + rad, y1 - rad):
            cv2.circle(outline, (px, py), rad, 1, -1)
    return drawn_scan(ink & outline, dpi, ss, 0.8)


@pytest.mark.parametrize(
    "dpi, length, shift", [(400.0, 94.3, 1.1), (300.0, 74.6, 2.9), (200.0, 80.0, 0.4)]
)
def test_analyze_scan_siped_blocks_cut_at_the_tips_are_tread(dpi, length, shift):
    # held-out seed 5 sheet 105: a siped road print's tip blocks, combs the outline
    # cut, were set aside as a marker's letters (length -5.4 %, status ok; fixed by
    # _BoldJudge._cut_blocks). This drawing does not reproduce that failure (its
    # body is found whole); it guards that combs cut at the tips and sides stay
    # the print's, the label tests that letters stay apart
    grey, mm, (want_l, want_w, want_a) = _siped(dpi, 3, length, shift)
    res = ip.analyze_scan(ip.Scan(grey, mm, "given"), rolling_axis="x", sensitivity=False)
    (pr,) = res.prints
    assert pr.status == "ok", pr.warnings
    assert_allclose([pr.metrics.length, pr.metrics.width], [want_l, want_w], rtol=0.01)
    assert_allclose(pr.metrics.hull_area, want_a, rtol=0.02)


def _comb_print(dpi: float, teeth: int, ss: int = 3) -> tuple:
    """A car-like print 130 mm along x and 110 mm across: a solid body whose
    shoulder, the outer 16 mm on one side, is ``teeth`` bars 1.2 mm wide and 7 mm apart reaching to the outline (held-out set 1
    file 3 page 2). :func:`drawn_scan` of it: grey, mm per px, (length along x,
    width along y, hull area) of the drawn ink."""
    mm = 25.4 / dpi / ss
    h, w = int(150 / mm), int(170 / mm)
    yy, xx = np.mgrid[0:h, 0:w] * mm
    u, v = xx - 85.0, yy - 75.0
    inside = (u / 65.0) ** 2 + (v / 55.0) ** 2 <= 1.0
    centres = 7.0 * (np.arange(teeth) - (teeth - 1) / 2)
    bars = (np.abs(u[..., None] - centres) <= 0.6).any(axis=-1)
    ink = (inside & ((v > -39.0) | bars)).astype(np.uint8)
    return drawn_scan(ink, dpi, ss, 0.6)


@pytest.mark.parametrize("dpi", [150.0, 300.0])
def test_analyze_scan_comb_of_shoulder_bars_is_the_print_s(dpi):
    # held-out set 1 file 3 page 2: a car print's shoulder bars, 1.2 mm wide and
    # 7 mm apart (too far apart for a bar field), were 15 "ruler lines": width
    # -12.6 %, status ok
    grey, px, (length, width, area) = _comb_print(dpi, 15)
    res = ip.analyze_scan(ip.Scan(grey, px, "given"), rolling_axis="x", sensitivity=False)
    (p,) = res.prints
    assert p.status == "ok", p.warnings
    m = p.metrics
    assert_allclose([m.length, m.width, m.hull_area], [length, width, area], rtol=(0.01))
    assert not any(mk.kind == "line" for mk in res.marks)


@pytest.mark.parametrize("teeth", [2, 3])
def test_analyze_scan_two_or_three_bars_out_of_a_print_are_no_comb(teeth):
    # the control: two or three straight bars reaching out of a print are lines (a
    # ruler's edges) as before; the print is measured without them, and flagged
    grey, px, (_, width, _) = _comb_print(150.0, teeth)
    res = ip.analyze_scan(ip.Scan(grey, px, "given"), rolling_axis="x", sensitivity=False)
    (p,) = res.prints
    assert p.metrics.width < 0.9 * width
    assert sum(mk.kind == "line" for mk in res.marks) == teeth
