"""Chart-paper gridlines taken out before grouping (inkprint.gridlines, issue 11)."""

import cv2
import numpy as np
import pytest
from numpy.testing import assert_allclose, assert_array_equal

import inkprint as ip
from inkprint.gridlines import find_gridlines
from tests.inkprint.drawn import drawn_scan

MM_PER_PX = 0.1  # 254 dpi


def _grid(shape, *, step=100, width=3, offset=20):
    m = np.zeros(shape, bool)
    for r in range(offset, shape[0], step):
        m[r : r + width, :] = True
    for c in range(offset, shape[1], step):
        m[:, c : c + width] = True
    return m


def test_find_gridlines_takes_out_the_lines_and_keeps_the_print_whole():
    printed = np.zeros((600, 800), bool)
    printed[150:330, 200:650] = True  # 45 x 18 mm, crossed by lines both ways
    sheet = printed | _grid(printed.shape)
    g = find_gridlines(sheet, mm_per_px=MM_PER_PX)
    assert g is not None
    assert_array_equal(sheet & ~g.removed, printed)


def test_find_gridlines_none_for_ribbed_prints_without_a_grid():
    # two ribbed prints side by side: their ribs are long thin rows of ink, but no
    # row runs unbroken over most of the sheet
    m = np.zeros((600, 800), bool)
    for c0 in (40, 420):
        for r in range(100, 300, 12):
            m[r : r + 5, c0 : c0 + 340] = True
    assert find_gridlines(m, mm_per_px=MM_PER_PX) is None


def test_gridlines_grazed_only_where_a_line_runs_along_the_edge():
    printed = np.zeros((600, 800), bool)
    printed[150:330, 200:650] = True
    crossed = find_gridlines(printed | _grid(printed.shape), mm_per_px=MM_PER_PX)
    box = printed[140:340, 190:660]  # the print's box grown by a line's band
    assert not crossed.grazed(box, 140, 190, mm_per_px=MM_PER_PX).any()
    # a line on the print's top edge: its ink cannot be told from the print's
    grazed = np.zeros_like(printed)
    grazed[121:330, 200:650] = True
    g = find_gridlines(grazed | _grid(printed.shape), mm_per_px=MM_PER_PX)
    kept = (grazed & ~g.removed)[90:340, 190:660]
    band = g.grazed(kept, 90, 190, mm_per_px=MM_PER_PX)
    assert np.count_nonzero(band.any(axis=0)) * MM_PER_PX > 40.0  # along the edge
    rows = np.flatnonzero(band.any(axis=1)) + 90
    assert rows.min() >= 119 and rows.max() <= 124  # the line's rows (and fringe) only


def test_find_gridlines_halo_speck_on_a_line_stays_apart():
    # a speck on a gridline just off a print's edge: the line between them is not
    # print ink (it joined the speck to the print: width +8 %)
    printed = np.zeros((600, 800), bool)
    printed[126:330, 200:650] = True  # top edge 3 px under the line at rows 120-122
    speck = np.zeros_like(printed)
    speck[115:124, 400:409] = True  # 0.9 mm, straddling the line
    sheet = printed | speck | _grid(printed.shape)
    g = find_gridlines(sheet, mm_per_px=MM_PER_PX)
    kept = sheet & ~g.removed
    _, labels = cv2.connectedComponents(kept.view(np.uint8), connectivity=8)
    assert labels[116, 404] != labels[200, 404]  # the speck is apart from the print
    assert_array_equal(kept[150:330, 200:650], printed[150:330, 200:650])


def _greys(printed, lines, *, ink=30, line=110, paper=240):
    grey = np.full(printed.shape, paper, np.uint8)
    grey[lines] = line
    grey[printed] = ink  # ink over a line is at least as dark as the ink
    return grey


def test_find_gridlines_ink_darker_than_the_line_stays_ink():
    # a tip sliver 2 x 1 mm lying on a vertical line, 2 mm beyond the print's
    # body: taken out with the line, the print lost 1 mm of length; darker than
    # the line (grey 30 on a line of 110), it stays ink with the grey levels given
    body = np.zeros((600, 800), bool)
    body[150:330, 200:600] = True
    sliver = np.zeros_like(body)
    sliver[230:250, 619:629] = True  # the line at columns 620-622
    lines = _grid(body.shape)
    sheet = body | sliver | lines
    blind = find_gridlines(sheet, mm_per_px=MM_PER_PX)
    assert (blind.removed & sliver).sum() == 20 * 5  # the line and a fringe column each side
    seen = find_gridlines(sheet, mm_per_px=MM_PER_PX, grey=_greys(body | sliver, lines))
    assert not (seen.removed & sliver).any()
    assert seen.dark_below == 0.75 * 110
    # the lines themselves still go, and ink as light as the line cannot be told
    assert_array_equal(seen.removed & ~sliver, blind.removed & ~sliver)
    faint = find_gridlines(sheet, mm_per_px=MM_PER_PX, grey=_greys(body | sliver, lines, ink=110))
    assert_array_equal(faint.removed, blind.removed)


def test_find_gridlines_dark_dot_on_a_line_is_not_kept():
    # a dark speck on a line away from every print is a dot: the line goes whole
    lines = _grid((600, 800))
    dot = np.zeros_like(lines)
    dot[219:224, 400:405] = True  # on the line at rows 220-222
    g = find_gridlines(lines | dot, mm_per_px=MM_PER_PX, grey=_greys(dot, lines))
    assert g.removed[220:223, 400:405].all()


def _pored_print(dpi: float, ss: int = 3) -> tuple:
    """A slick print 101.2 x 18.5 mm with a square lattice of pores (0.4 mm every
    1.2 mm, square to the sheet) on a scan cropped to 130 x 60 mm around it:
    :func:`drawn_scan` (grey, mm per px, (width along x, length along y, hull
    area) of the ink)."""
    mm = 25.4 / dpi / ss
    yy, xx = np.mgrid[0 : int(130 / mm), 0 : int(60 / mm)] * mm
    inside = ((xx - 30) / 9.25) ** 2 + ((yy - 65) / 50.6) ** 2 <= 1
    pores = np.hypot((xx - 30) % 1.2 - 0.6, yy % 1.2 - 0.6) < 0.2
    grey, px, truth = drawn_scan((inside & ~pores).astype(np.uint8), dpi, ss, 0.6)
    return cv2.GaussianBlur(grey, (0, 0), 0.7), px, truth


@pytest.mark.parametrize("dpi", [150.0, 300.0])
def test_analyze_scan_print_s_strips_between_pores_are_no_gridlines(dpi):
    # the ink between a slick print's rows of pores runs unbroken over 78 % of a
    # scan cropped to the print: 12 "gridlines" split it in two, width -36 %, status
    # ok; chart paper's lines are spread over the sheet (GRID_SPREAD)
    grey, px, (width, length, area) = _pored_print(dpi)
    res = ip.analyze_scan(ip.Scan(grey, px, "given"), rolling_axis="y", sensitivity=False)
    (p,) = res.prints
    assert not any(m.kind == "gridlines" for m in res.marks)
    assert_allclose([p.metrics.length, p.metrics.width], [length, width], rtol=0.01)
    assert_allclose(p.metrics.hull_area, area, rtol=0.02)
