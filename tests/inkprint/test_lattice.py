"""Tiny prints of separate tread elements (inkprint.lattice, issue 11): a track or
file tire's print 2.5-4 mm wide whose tread prints as a lattice of diamonds with no
body joining them was set aside as writing ("a print this small or narrow is
solid") or as dust and text, and went missing (held-out sets: 11 of 12)."""

import cv2
import numpy as np
import pytest
from numpy.testing import assert_allclose

import inkprint as ip
from inkprint.errors import NoInk
from inkprint.read import Scan
from inkprint.synth import PrintSpec, SheetSpec, render_sheet

from .drawn import drawn_scan

SS = 4  # supersampling of the drawn fixtures


def _diamond_print(dpi, *, length=12.0, width=3.5, diag=0.9, pitch=1.6, size=(40.0, 30.0)):
    """Diamonds (squares turned 45 degrees, ``diag`` [mm] corner to corner, their
    corners rounded 0.15 mm as ink prints them) on a
    staggered lattice, ``pitch`` [mm] along x, rows ``pitch / 2`` apart across, those
    whose centre lies in an ellipse ``length`` x ``width`` [mm] (the held-out set's
    tiny file prints). Drawn at SS x the scan's resolution: grey, mm per px and the
    drawn ink's (length along x, width along y, hull area)."""
    mm = 25.4 / dpi / SS
    h, w = round(size[1] / mm), round(size[0] / mm)
    ink = np.zeros((h, w), np.uint8)
    cx, cy = size[0] / 2 + 0.13, size[1] / 2 - 0.21
    a, b = length / 2 - diag / 2, width / 2 - diag / 2  # centres' ellipse
    r = 0.15  # the corners' radius [mm]
    half = diag / 2 - r * np.sqrt(2)  # the rounded diamond reaches diag / 2
    for j, v in enumerate(np.arange(-b, b + 1e-9, pitch / 2)):
        for u in np.arange(-a - pitch, a + pitch, pitch) + 0.5 * pitch * (j % 2):
            if (u / a) ** 2 + (v / b) ** 2 > 1.0 + 1e-9:
                continue
            x, y = cx + u, cy + v
            pts = np.array([[x - half, y], [x, y - half], [x + half, y], [x, y + half]])
            poly = [np.round(pts / mm * 16).astype(np.int32)]
            cv2.fillPoly(ink, poly, 1, cv2.LINE_8, 4)
            cv2.polylines(ink, poly, True, 1, round(2 * r / mm), cv2.LINE_8, 4)
    grey, mm_px, truth = drawn_scan(ink, dpi, SS, 0.8)
    return Scan(grey, mm_px, "given"), truth


def _dot_print(dpi, *, length=10.45, width=13.0, dot=1.7, pitch=2.78, size=(40.0, 30.0)):
    """Round dots ``dot`` [mm] across on a hexagonal lattice ``pitch`` [mm] apart,
    its rows along y, cut by an ellipse ``length`` (x) by ``width`` (y) [mm]: the
    outline's dots are crescents (held-out seed 9 sheet 119). Grey, mm per px and
    the drawn ink's (length along x, width along y, hull area)."""
    mm = 25.4 / dpi / SS
    h, w = round(size[1] / mm), round(size[0] / mm)
    ink = np.zeros((h, w), np.uint8)
    cx, cy = size[0] / 2 + 0.11, size[1] / 2 - 0.17
    for j, u in enumerate(np.arange(-length, length, pitch * np.sqrt(3) / 2)):
        for v in np.arange(-width, width, pitch) + 0.5 * pitch * (j % 2):
            cv2.circle(
                ink, (round((cx + u) / mm), round((cy + v) / mm)), round(dot / 2 / mm), 1, -1
            )
    yy, xx = np.mgrid[0:h, 0:w]
    inside = ((xx * mm - cx) / (length / 2)) ** 2 + ((yy * mm - cy) / (width / 2)) ** 2 <= 1
    grey, mm_px, truth = drawn_scan(ink * inside.astype(np.uint8), dpi, SS, 0.7)
    return Scan(grey, mm_px, "given"), truth


@pytest.mark.parametrize("dpi", [400, 600])
def test_analyze_scan_tiny_dot_print_of_few_rows_is_found(dpi):
    # dots 1.1 mm apart, too far for the closing that makes a tiny print solid: set
    # aside as "a letter or a mark", missing (held-out seed 9 sheet 119, where most
    # elements lie on the outline: median 2 neighbours, fine_neighbours is 3); then
    # found without the crescents at its tips, no fine element's shape: length
    # -10 %, unflagged. Now found whole
    scan, (length, width, hull) = _dot_print(dpi)
    res = ip.analyze_scan(scan, rolling_axis="x", sensitivity=False)
    (p,) = res.prints
    assert "writing" not in res.rows()[0]["set_aside"]
    err = [p.metrics.length / length - 1, p.metrics.width / width - 1]
    within = max(abs(e) for e in err) <= 0.01 and abs(p.metrics.hull_area / hull - 1) <= 0.02
    assert p.flags or within, (err, p.metrics.hull_area / hull - 1, p.flags)
    assert_allclose([p.metrics.length, p.metrics.width], [length, width], rtol=0.02)


@pytest.mark.parametrize("dpi", [500, 600])
def test_analyze_scan_tiny_diamond_lattice_print_is_found_and_measured(dpi):
    scan, (length, width, hull) = _diamond_print(dpi)
    res = ip.analyze_scan(scan, rolling_axis="x", sensitivity=False)
    (p,) = res.prints
    assert_allclose([p.metrics.length, p.metrics.width], [length, width], rtol=0.01)
    assert_allclose(p.metrics.hull_area, hull, rtol=0.02)
    assert "writing" not in res.rows()[0]["set_aside"]
    # half a pixel is 1.06 % of its 47 px width at 500 dpi, 0.88 % at 600
    assert ("coarse_elements" in p.flags) == (dpi == 500)


@pytest.mark.parametrize("dpi", [300, 400])
def test_analyze_scan_tiny_diamond_lattice_print_at_300_400_dpi_is_flagged_coarse(dpi):
    # the width's ends are two diamonds' rounded corners (0.15 mm, 2 px), whose
    # half-contrast outline falls about a third of a pixel short on each side:
    # -1.2 to -1.5 % of a 2.4 mm width, out of the bar: flagged, not silent
    scan, (length, width, _) = _diamond_print(dpi)
    (p,) = ip.analyze_scan(scan, rolling_axis="x", sensitivity=False).prints
    assert_allclose(p.metrics.length, length, rtol=0.01)
    assert -0.02 < p.metrics.width / width - 1 < 0
    assert p.status == "flagged"
    assert "coarse_elements" in p.flags


@pytest.mark.parametrize("dpi", [300.0, 600.0])
def test_analyze_scan_tiny_knurl_print_turned_30_degrees_is_found(dpi):
    # the synthetic knurl tread, 10 x 3 mm: 19 diamonds, set aside as dust before
    p = PrintSpec(10.0, 3.0, (30.0, 30.0), 30.0, "knurl", block=1.2, gap=0.6)
    img, (t,) = render_sheet(SheetSpec((p,), dpi=dpi, size=(60.0, 60.0), specks=10))
    (pr,) = ip.analyze_scan(Scan(img, 25.4 / dpi, "given"), sensitivity=False).prints
    assert_allclose([pr.metrics.length, pr.metrics.width], [t.length, t.width], rtol=0.01)
    assert_allclose(pr.metrics.hull_area, t.hull_area, rtol=0.02)


def _blank(shape=(400, 400)):
    return np.full(shape, 0.92, np.float32)


def test_analyze_scan_a_dotted_line_is_no_lattice_print():
    # twelve dots in a row, 1.5 mm apart: one-dimensional, a drawn dotted line
    grey = _blank()
    for k in range(12):
        cv2.circle(grey, (60 + 15 * k, 200), 4, 0.1, -1, cv2.LINE_AA)
    with pytest.raises(NoInk):
        ip.analyze_scan(Scan(grey, 0.1, "given"), sensitivity=False)


def test_analyze_scan_a_word_of_small_letters_is_no_lattice_print():
    m = np.zeros((300, 900), np.uint8)
    cv2.putText(m, "Conti 28mm 6 bar", (30, 150), cv2.FONT_HERSHEY_SIMPLEX, 1.2, 1, 3)
    cv2.putText(m, "640 N front left", (30, 200), cv2.FONT_HERSHEY_SIMPLEX, 1.2, 1, 3)
    grey = np.where(m > 0, 0.1, 0.92).astype(np.float32)
    with pytest.raises(NoInk):
        ip.analyze_scan(Scan(grey, 0.1, "given"), sensitivity=False)


def test_analyze_scan_dot_grid_paper_is_no_lattice_print():
    # dots 5 mm apart over the page: too sparse for a tread's lattice
    grey = _blank((600, 600))
    for r in range(20, 600, 50):
        for c in range(20, 600, 50):
            cv2.circle(grey, (c, r), 3, 0.3, -1, cv2.LINE_AA)
    with pytest.raises(NoInk):
        ip.analyze_scan(Scan(grey, 0.1, "given"), sensitivity=False)


@pytest.mark.parametrize(
    ("length", "width", "block", "dpi"),
    [(12.6, 7.2, 1.2, 300.0), (21.0, 6.6, 1.0, 300.0), (10.0, 12.0, 1.4, 400.0)],
)
def test_analyze_scan_tiny_knurl_print_wider_than_6_mm_is_found(length, width, block, dpi):
    # tiny knurl prints 6.6-12 mm wide (held-out 4th generator seed 8 sheets 14 and
    # 28): fields of 40-70 elements wider than LATTICE_MAX_WIDTH_MM was (6 mm), set
    # aside as "a letter or a mark ... a print this small or narrow is solid"
    p = PrintSpec(length, width, (40.0, 40.0), 0.0, "knurl", block=block, gap=0.5)
    img, (t,) = render_sheet(SheetSpec((p,), dpi=dpi, size=(80.0, 80.0), specks=10))
    res = ip.analyze_scan(Scan(img, 25.4 / dpi, "given"), rolling_axis="x", sensitivity=False)
    (pr,) = res.prints
    assert_allclose(pr.metrics.width, t.width, rtol=0.01)
    assert_allclose(pr.metrics.hull_area, t.hull_area, rtol=0.02)
    # its ends are diamonds cut to wedges thinner than a pixel: 0.2-2.5 px short,
    # flagged where TIP_SHORT_PX (2 px) is over 1 % (under 200 px long)
    assert -2.5 * 25.4 / dpi <= pr.metrics.length - t.length <= 0.01 * t.length
    assert ("coarse_elements" in pr.flags) == (t.length / (25.4 / dpi) < 200), pr.warnings


def _crescent_sheet(dpi, *, dots_at=None, label_at=None, big=None, size=(60.0, 60.0)):
    """A sheet ``size`` [mm] of: a tiny print of round dots 1.0 mm across on a
    hexagonal lattice 1.69 mm apart (rows along x, half a row off the centre) cut by
    a 14 x 4 mm superellipse of exponent 2.9 centred at ``dots_at`` [mm]: most of
    its outer dots are crescents (held-out 6 seed 2 sheet 108, 25 pieces); a solid
    elliptic print ``big`` (centre x, y, semi-axes [mm]); the bold pen label
    'Vittoria Corsa' (3 mm letters, 0.5 mm stroke, its baseline from ``label_at``
    turned 20 deg). Scan, and the dots' (length, width, hull area) and centroid."""
    mm = 25.4 / dpi / SS
    h, w = round(size[1] / mm), round(size[0] / mm)
    yy, xx = np.mgrid[0:h, 0:w].astype(np.float32)
    xx, yy = (xx + 0.5) * mm, (yy + 0.5) * mm
    ink = np.zeros((h, w), np.uint8)
    truth = None
    if dots_at is not None:
        (cx, cy), pitch, dy = dots_at, 1.69, 1.69 * np.sqrt(3) / 2
        for j, v in enumerate(np.arange(-4, 5) * dy + 0.7):
            for u in np.arange(-6, 7) * pitch + 0.5 * pitch * (j % 2):
                centre = (round((cx + u) / mm * 16), round((cy + v) / mm * 16))
                cv2.circle(ink, centre, round(0.5 / mm * 16), 1, -1, cv2.LINE_8, 4)
        ink &= (np.abs(xx - cx) / 7.0) ** 2.9 + (np.abs(yy - cy) / 2.0) ** 2.9 <= 1
        on = ink > 0
        truth = drawn_scan(ink, dpi, SS, 0.8)[2], (xx[on].mean(), yy[on].mean())
    if big is not None:
        x0, y0, a, b = big
        ink |= (((xx - x0) / a) ** 2 + ((yy - y0) / b) ** 2 <= 1).astype(np.uint8)
    if label_at is not None:
        m = np.zeros((h, w), np.uint8)
        org = (round(label_at[0] / mm), round(label_at[1] / mm))
        scale = 3.0 / mm / 22.0  # HERSHEY_SIMPLEX's capitals: 22 px at scale 1
        cv2.putText(m, "Vittoria Corsa", org, cv2.FONT_HERSHEY_SIMPLEX, scale, 1, round(0.5 / mm))
        turned = cv2.getRotationMatrix2D(org, 20.0, 1.0)
        ink |= cv2.warpAffine(m, turned, (w, h), flags=cv2.INTER_NEAREST)
    grey, mm_px, _ = drawn_scan(ink, dpi, SS, 0.8)
    return Scan(grey, mm_px, "given"), truth


def _at(p, mm_px: float) -> np.ndarray:
    """A print's hull's centroid (x, y) [mm]."""
    mo = cv2.moments(p.hull_px[:, ::-1].astype(np.float32))
    return np.array([mo["m10"], mo["m01"]]) / mo["m00"] * mm_px


@pytest.mark.parametrize(
    ("dots_at", "big", "size"),
    [
        ((30.13, 29.79), None, (60.0, 60.0)),
        ((22.0, 30.0), (75.0, 30.0, 25.0, 17.0), (110.0, 60.0)),
    ],
    ids=["alone", "beside_a_print"],
)
def test_analyze_scan_tiny_dot_print_cut_to_crescents_is_found(dots_at, big, size):
    """Held-out 6 seed 2 sheet 108: a 14 x 4 mm print of dots at 200 dpi whose
    outline cuts most outer dots into crescents: the 20th to 80th percentile of
    all its elements' areas 3.7 x apart, set aside as dust specks, missing. Now
    its field's regularity is judged on its inner elements
    (lattice_prints -> marks._fine_fields(inner=True)): found and measured."""
    scan, ((length, width, _), centre) = _crescent_sheet(
        200.0, dots_at=dots_at, big=big, size=size
    )
    res = ip.analyze_scan(scan, rolling_axis="x", sensitivity=False)
    near = [p for p in res.prints if np.hypot(*(_at(p, scan.mm_per_px) - centre)) <= 1.0]
    assert len(near) == 1, ([_at(p, scan.mm_per_px) for p in res.prints], centre)
    assert len(res.prints) == 1 + (big is not None)
    (p,) = near
    assert_allclose([p.metrics.length, p.metrics.width], [length, width], rtol=0.02)
    assert set(p.flags) <= {"coarse_elements"}, p.warnings


def test_analyze_scan_slanted_bold_label_beside_a_print_is_no_lattice_print():
    """Held-out 6 seed 1 sheet 117: the pen label 'Vittoria Corsa' in bold 3 mm
    letters turned 20 deg beside a print became a lattice print with an earlier
    version of the inner-elements regularity (marks._fine_fields(inner=True)). It
    stays writing: the one print found is the solid one."""
    big = (75.0, 30.0, 25.0, 17.0)
    scan, _ = _crescent_sheet(200.0, label_at=(8.0, 52.0), big=big, size=(110.0, 60.0))
    res = ip.analyze_scan(scan, rolling_axis="x", sensitivity=False)
    (p,) = res.prints
    assert np.hypot(*(_at(p, scan.mm_per_px) - big[:2])) <= 1.0
    assert_allclose([p.metrics.length, p.metrics.width], [50.0, 34.0], rtol=0.01)
    assert "text" in [m.kind for m in res.marks]


@pytest.mark.parametrize("dpi", [400, 600])
@pytest.mark.parametrize(("beyond", "aside"), [(0.45, 0.0), (0.3, 0.25), (0.6, -1.0)])
def test_analyze_scan_speck_off_a_tiny_dot_print_s_tip_is_off_its_sites(dpi, beyond, aside):
    # a 0.08 mm^2 speck `beyond` mm off the outline of a 15.7 x 4.3 mm print of 1.04
    # mm dots 1.65 mm apart (held-out 6 seed 4 sheet 109), `aside` mm off its axis:
    # within 1.5 pattern gaps of the dots, it was kept as a cut dot, 1.4-6.5 % long
    # with status ok. A cut dot lies in its dot's place on the lattice and holds the
    # dot's edge towards the print (inkprint.sites, group._off_sites); the speck
    # is an edge spot. The print without the speck reads the same
    sc, truth = _dot_print(dpi, length=15.7, width=4.3, dot=1.04, pitch=1.65)
    mm, (cx, cy) = sc.mm_per_px, (20.11, 14.83)  # (_dot_print's centre)
    r = np.sqrt(0.08 / np.pi)
    u = 15.7 / 2 * np.sqrt(1 - (aside / 2.15) ** 2) + beyond + r
    yy, xx = np.mgrid[: sc.grey.shape[0], : sc.grey.shape[1]]
    grey = sc.grey.copy()
    grey[np.hypot(xx * mm - (cx + u), yy * mm - (cy + aside)) <= r] = 0.25
    clean = ip.analyze_scan(sc, rolling_axis="x", sensitivity=False)
    res = ip.analyze_scan(Scan(grey, mm, "given"), rolling_axis="x", sensitivity=False)
    (p,) = res.prints
    assert res.print_status(0) == clean.print_status(0) == "ok"
    assert_allclose([p.metrics.length, p.metrics.width], truth[:2], rtol=0.01)
    assert_allclose(p.metrics.hull_area, clean.prints[0].metrics.hull_area, rtol=1e-9)


def test_coarse_flag_outline_over_elements_not_found_fine():
    # held-out 6 seed 1 sheet 82 page 2 (the print cropped, chart paper): a tiny
    # file print, 23.03 x 4.72 mm at 240 dpi (43 px wide), its rows of diamonds
    # joined to a slick centre: no fine tread found, and the diamonds' tips cut short
    # by about a pixel a side: width -4.5 % with status ok before. Its outline runs
    # over 8 or more pieces besides the largest (analyze._outline_elements): judged
    # as a fine tread's across, flagged coarse_elements
    from pathlib import Path

    path = Path(__file__).parent / "data" / "tiny_file_chart.png"
    (p,) = ip.analyze_scan(path, rolling_axis="y", sensitivity=False).prints
    assert abs(p.metrics.length / 23.03 - 1.0) < 0.01
    assert p.metrics.width < 0.99 * 4.72  # (the tips cut short)
    assert p.flags == ("coarse_elements",)
    assert "rescan at" in p.warnings[0]
