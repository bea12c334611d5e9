"""Sorting ink into prints and marks (inkprint.marks): the straight-line test."""

import cv2
import numpy as np
from numpy.testing import assert_allclose

from inkprint.marks import _hull_box, _hull_map, _line_run, _nearest_hull, _nearest_label
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
