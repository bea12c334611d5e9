"""Sorting ink into prints and marks (inkprint.marks): the straight-line test."""

import cv2
import numpy as np
from numpy.testing import assert_allclose

from inkprint.marks import _line_run
from inkprint.options import AnalysisOptions
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
