"""Chart-paper gridlines taken out before grouping (inkprint.gridlines, issue 11)."""

import cv2
import numpy as np
from numpy.testing import assert_array_equal

from inkprint.gridlines import find_gridlines

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
