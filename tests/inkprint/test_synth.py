"""Synthetic sheets (inkprint.synth) measured against their exact truth.

The renderer is the ground truth of every analysis test, so it is checked on its
own: the ink it draws (pixel coverage, read through inkprint.coords) has the truth's
area, place, orientation and extents, and the truths come in sheet order.
"""

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

from inkprint.coords import dpi_to_mm_per_px, px_to_mm
from inkprint.synth import (
    TREADS,
    PrintSpec,
    SheetSpec,
    outline_law,
    render_sheet,
    superellipse_area,
)
from inkprint.synth_effects import Grid

DPI = 300


def clean_sheet(*prints):
    """Even paper, no grain, no specks: a pixel's darkness is its inked fraction."""
    return SheetSpec(prints, dpi=DPI, size=(160.0, 240.0), grain=0.0, gradient=0.0, specks=0)


def coverage(img, ink):
    """Inked fraction of each pixel, and the (x, y) [mm] of each pixel centre."""
    cov = np.clip(1.0 - img.astype(float) / np.median(img), 0, None) / ink
    rr, cc = np.mgrid[0 : img.shape[0], 0 : img.shape[1]]
    x, y = px_to_mm(rr + 0.5, cc + 0.5, n_rows=img.shape[0], mm_per_px=dpi_to_mm_per_px(DPI))
    return cov, x, y


# print size per tread: the wide-groove treads need room for their pattern
SIZES = {"mtb": (70.0, 45.0), "car": (95.0, 75.0)}


@pytest.mark.parametrize("tread", TREADS)
def test_rendered_print_has_its_true_area_place_orientation_and_extent(tread):
    length, width = SIZES.get(tread, (60.0, 12.0))
    p = PrintSpec(length, width, (80.0, 120.0), angle=30.0, tread=tread, unevenness=0.0)
    if tread == "car":
        p = PrintSpec(
            length,
            width,
            (80.0, 120.0),
            angle=30.0,
            tread=tread,
            unevenness=0.0,
            block=20.0,
            gap=8.0,
            exponent=4.0,
        )
    img, (truth,) = render_sheet(clean_sheet(p))
    cov, x, y = coverage(img, p.ink)
    s = dpi_to_mm_per_px(DPI)
    w = cov.sum()
    rtol = 0.02 if tread == "file" else 3e-3  # the file tread's 0.9 mm voids blur
    assert_allclose(w * s * s, truth.net_area, rtol=rtol)
    cx, cy = (cov * x).sum() / w, (cov * y).sum() / w
    atol = 0.05 if tread == "mtb" else 0.02  # few knobs: each corner's rounding counts
    assert_allclose([cx, cy], [truth.ink.centroid.x, truth.ink.centroid.y], atol=atol)
    dx, dy = x - cx, y - cy
    sxx, syy, sxy = ((cov * a * b).sum() / w for a, b in ((dx, dx), (dy, dy), (dx, dy)))
    if tread not in ("car", "mtb"):  # staggered blocks: their own axis is not the rolling one
        assert_allclose(0.5 * math.degrees(math.atan2(2 * sxy, sxx - syy)), truth.angle, atol=0.1)
    a = math.radians(truth.angle)
    along, across = dx * math.cos(a) + dy * math.sin(a), dy * math.cos(a) - dx * math.sin(a)
    inked = cov > 0.5
    # pixel centres: within 1 px (2 for the knurl's diamonds: a pointed tip at the
    # extreme covers under half of the pixels it crosses)
    tol = 2 * s if tread == "knurl" else s
    assert abs(np.ptp(along[inked]) - truth.length) <= tol
    assert abs(np.ptp(across[inked]) - truth.width) <= tol


def test_truths_come_top_to_bottom_whatever_the_spec_order():
    low = PrintSpec(50.0, 10.0, (80.0, 60.0), unevenness=0.0)
    high = PrintSpec(40.0, 9.0, (70.0, 180.0), angle=-20.0, unevenness=0.0)
    img, truths = render_sheet(clean_sheet(low, high))
    cov, x, y = coverage(img, low.ink)
    assert [round(t.length) for t in truths] == [40, 50]
    for t in truths:  # each truth's centroid is where its ink is drawn
        near = (np.abs(y - t.ink.centroid.y) < 30) & (cov > 0)
        w = cov[near].sum()
        centroid = [(cov * x)[near].sum() / w, (cov * y)[near].sum() / w]
        assert_allclose(centroid, [t.ink.centroid.x, t.ink.centroid.y], atol=0.02)


def test_superellipse_area_matches_polygon():
    import shapely

    from inkprint.synth import _outline

    p = PrintSpec(70.0, 8.0, (0, 0))
    assert_allclose(
        shapely.Polygon(_outline(p, 20000)).area, superellipse_area(70.0, 8.0), rtol=1e-5
    )


@pytest.mark.parametrize(("args", "match"), [((0, 0.5, 10), "load"), ((300, -1, 10), "pressure")])
def test_outline_law_invalid(args, match):
    from inkprint import InvalidInput

    with pytest.raises(InvalidInput, match=match):
        outline_law(*args)


@pytest.mark.parametrize(
    ("bed", "match"),
    [
        ({"strips": (("middle", 2.0, 5.0),)}, "side"),
        ({"strips": (("top", 2.0, float("nan")),)}, "strips"),
        ({"holes": 1.5}, "holes"),
        ({"level": 1.5}, "level"),
    ],
)
def test_scanner_bed_invalid(bed, match):
    import inkprint as ip
    from inkprint.synth_effects import Bed

    spec = SheetSpec((), dpi=100.0, size=(60.0, 80.0), bed=Bed(**bed))
    with pytest.raises(ip.InvalidInput, match=match):
        render_sheet(spec)


@pytest.mark.parametrize("rib", [0.0, -3.0, 24.0, float("nan"), "6", True])
def test_knurl_rib_invalid(rib):
    import inkprint as ip

    p = PrintSpec(60.0, 24.0, (80.0, 120.0), 0.0, "knurl", rib=rib)
    with pytest.raises(ip.InvalidInput, match="rib"):
        render_sheet(clean_sheet(p))


def test_knurl_rib_is_solid_across_its_width():
    # a slick centre strip 6 mm wide: the print's middle row of pixels is all ink
    img, (t,) = render_sheet(
        clean_sheet(PrintSpec(60.0, 24.0, (80.0, 120.0), 0.0, "knurl", rib=6.0))
    )
    dark = 1.0 - img.astype(float) / img.max()
    row = dark[img.shape[0] // 2]  # (the print's centre line: y = 120 of 240 mm)
    assert t.width == pytest.approx(24.0, abs=0.5)
    assert np.count_nonzero(row > 0.5) * 25.4 / DPI == pytest.approx(60.0, rel=0.02)


def test_grid_multiply_darkens_the_ink_over_a_line():
    # printed chart paper under the ink: the reflectances multiply (the ink over a
    # line darker than either); drawn over the print (default), the darker wins
    p = PrintSpec(40.0, 20.0, (30.0, 30.0), 0.0, "slick", ink=0.6, unevenness=0.0)
    out = {}
    for multiply in (False, True):
        g = Grid(10.0, 1.0, 0.5, multiply=multiply)
        sheet = SheetSpec((p,), dpi=100.0, size=(60.0, 60.0), specks=0, grain=0.0, marks=(g,))
        out[multiply], _ = render_sheet(sheet)
    row = out[True].shape[0] - round(25.0 / 0.254)  # the line at y = 25 mm
    inside, on = out[True][row - 10, 118], out[True][row, 118]
    assert on < inside - 20  # ink over the line is darker than the ink
    assert abs(int(out[False][row, 118]) - int(out[False][row - 10, 118])) < 6


def test_tiny_case_draws_lattice_prints_on_half_the_sheets():
    from inkprint.synth_cases import CLASSES

    rng = np.random.default_rng(3)
    treads = [CLASSES["tiny"](rng, 600.0).sheets[0].prints[1].tread for _ in range(20)]
    assert 4 <= treads.count("knurl") <= 16


@pytest.mark.parametrize(
    ("grid", "match"),
    [
        (Grid(multiply="yes"), "multiply"),
        (Grid(spacing=0.0), "spacing"),
        (Grid(spacing=float("nan")), "spacing"),
    ],
)
def test_grid_invalid(grid, match):
    from inkprint.errors import InvalidInput

    p = PrintSpec(20.0, 10.0, (30.0, 30.0))
    with pytest.raises(InvalidInput, match=match):
        render_sheet(SheetSpec((p,), dpi=100.0, size=(60.0, 60.0), marks=(grid,)))
