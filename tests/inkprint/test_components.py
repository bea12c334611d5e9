"""Connected components with OpenCV's statistics (inkprint.components) and the
sub-pixel outline's crossings (inkprint.analyze._crossings): same results as the
library calls they replace, on masks and fields they were not written around."""

import cv2
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose, assert_array_equal

from inkprint.analyze import _crossings, _Level
from inkprint.binarize import remove_specks
from inkprint.components import DENSE, components_with_stats, piece_stats


def _random_mask(seed: int, shape, share: float, blur: float) -> np.ndarray:
    rng = np.random.default_rng(seed)
    noise = rng.random(shape).astype(np.float32)
    if blur > 0:
        noise = cv2.GaussianBlur(noise, (0, 0), blur)
        noise = (noise - noise.min()) / max(float(np.ptp(noise)), 1e-9)
    return noise < np.quantile(noise, share) if share > 0 else np.zeros(shape, bool)


@settings(max_examples=60, deadline=None)
@given(
    seed=st.integers(0, 2**31),
    h=st.integers(1, 90),
    w=st.integers(1, 90),
    share=st.sampled_from([0.0, 0.01, 0.1, 0.2, DENSE + 0.05, 0.6, 1.0]),
    blur=st.sampled_from([0.0, 1.5, 4.0]),
    connectivity=st.sampled_from([4, 8]),
)
def test_components_with_stats_equals_opencv(seed, h, w, share, blur, connectivity):
    mask = _random_mask(seed, (h, w), share, blur)
    n0, lab0, st0, c0 = cv2.connectedComponentsWithStats(
        mask.view(np.uint8), connectivity=connectivity
    )
    n1, lab1, st1, c1 = components_with_stats(mask, connectivity=connectivity)
    assert n1 == n0
    assert_array_equal(lab1, lab0)
    assert_array_equal(st1, st0)
    assert st1.dtype == np.int32
    assert_allclose(c1, c0, rtol=1e-12, atol=1e-9)


@settings(max_examples=40, deadline=None)
@given(
    seed=st.integers(0, 2**31),
    share=st.sampled_from([0.01, 0.1, 0.3, 0.6]),
    blur=st.sampled_from([0.0, 1.5]),
)
def test_piece_stats_equal_opencv_for_the_pieces_asked(seed, share, blur):
    # the labels of the plain labelling, the statistics of the pieces asked for
    mask = _random_mask(seed, (70, 90), share, blur)
    n0, lab0, st0, c0 = cv2.connectedComponentsWithStats(mask.view(np.uint8), connectivity=8)
    n, lab = cv2.connectedComponents(mask.view(np.uint8), connectivity=8)
    assert n == n0
    assert_array_equal(lab, lab0)
    which = np.random.default_rng(seed).random(n) < 0.5
    which[0] = False
    stats, cent = piece_stats(lab, np.flatnonzero(which[lab]), n)
    assert_array_equal(stats[which], st0[which])
    assert_array_equal(cent[which], c0[which])
    assert not stats[~which].any()


def test_components_with_stats_sparse_sheet_with_specks():
    # a sheet-sized sparse mask: the ink-only path (below DENSE), many pieces
    mask = _random_mask(3, (400, 300), 0.03, 0.0)
    mask[50:120, 40:200] = True
    assert mask.mean() < DENSE
    ref = cv2.connectedComponentsWithStats(mask.view(np.uint8), connectivity=8)
    got = components_with_stats(mask)
    assert got[0] == ref[0] > 100
    assert_array_equal(got[2], ref[2])
    assert_allclose(got[3], ref[3], rtol=1e-12)


@pytest.mark.parametrize("min_pixels", [0, 1, 2, 5, 40])
def test_remove_specks_equals_the_stats_rule(min_pixels):
    mask = _random_mask(7, (120, 150), 0.15, 0.8)
    _, lab, stats, _ = cv2.connectedComponentsWithStats(mask.view(np.uint8), connectivity=8)
    keep = stats[:, cv2.CC_STAT_AREA] >= min_pixels
    keep[0] = False
    expected = keep[lab] if min_pixels > 1 else mask
    assert_array_equal(remove_specks(mask, min_pixels), expected)


@settings(max_examples=60, deadline=None)
@given(seed=st.integers(0, 2**31), h=st.integers(2, 60), w=st.integers(2, 60))
def test_crossings_hull_equals_marching_squares(seed, h, w):
    # the hull of the zero crossings is the hull of skimage's iso-line (a field
    # without exact zeros: there marching squares drops zero-length segments)
    from skimage.measure import find_contours

    rng = np.random.default_rng(seed)
    field = cv2.GaussianBlur(rng.normal(size=(h, w)).astype(np.float32), (0, 0), 1.5)
    field[field == 0] = 1e-6
    f = np.pad(field, 1, constant_values=1.0)  # the frame _crossings puts around the box
    lines = [c for c in find_contours(f, 0.0) if len(c) >= 2]
    pts = _crossings(_plain_level(field))
    if not lines:
        assert len(pts) == 0
        return
    ref = cv2.convexHull(np.concatenate(lines)[:, ::-1].astype(np.float32)).reshape(-1, 2)
    got = cv2.convexHull(pts[:, ::-1].astype(np.float32)).reshape(-1, 2)
    assert_array_equal(np.sort(got, axis=0), np.sort(ref, axis=0))


def _plain_level(field: np.ndarray) -> _Level:
    """The field itself as the level, framed by 1 (paper)."""
    return _Level(field, np.ones(field.shape, bool), np.zeros(field.shape, bool))


def test_crossings_interpolate_linearly():
    # framed: [[1, 1, 1, 1], [1, -1, 3, 1], [1, 1, 1, 1]]
    pts = {tuple(p) for p in np.round(_crossings(_plain_level(np.array([[-1.0, 3.0]]))), 12)}
    # from the -1: half-way up, down and left; a quarter of the way right
    assert pts == {(0.5, 1.0), (1.5, 1.0), (1.0, 0.5), (1.0, 1.25)}


def test_crossings_keep_each_lines_first_and_last():
    # a row crossing 0 four times: only its first and last crossing are kept (the
    # hull's), every column's both
    pts = {tuple(p) for p in np.round(_crossings(_plain_level(np.array([[-1.0, 1.0, -1.0]]))), 12)}
    assert pts == {(1.0, 0.5), (1.0, 3.5), (0.5, 1.0), (1.5, 1.0), (0.5, 3.0), (1.5, 3.0)}


def test_framed_ribbed_print_with_straight_sides_is_no_frame():
    # fifth held-out generator (2026-11-29) seed 4 sheet 16: a 92 x 21 mm print of
    # ribs in a boxy outline, its outer ribs straight along both long sides and the
    # line a quarter of its width in lying in a groove: "a ruler or a frame",
    # missing. A rib inked along the whole length inside is no frame's; a ruler's
    # frame with its ticks still is
    from inkprint.group import _framed, outline_points

    mm = 25.4 / 300
    h, w = round(20.5 / mm), round(92 / mm)
    y, x = np.mgrid[0:h, 0:w]
    u, v = (x + 0.5) * mm - 46, (y + 0.5) * mm - 10.25
    inside = (np.abs(u) / 46) ** 40 + (np.abs(v) / 10.25) ** 40 <= 1
    ribs = inside & (np.mod(v + 10.25, 5.5) < 4.0)  # ribs 4 mm, grooves 1.5 mm
    frame = np.zeros((h, w), bool)
    frame[: round(1 / mm)] = frame[-round(1 / mm) :] = True
    frame[:, : round(0.8 / mm)] = frame[:, -round(0.8 / mm) :] = True
    frame[round(1 / mm) : round(4 / mm), :: round(5 / mm)] = True  # ticks
    for mask, framed in ((ribs, False), (frame, True)):
        pts = outline_points(mask).reshape(-1, 2).astype(np.float32)
        assert _framed(mask, cv2.minAreaRect(pts)) is framed
