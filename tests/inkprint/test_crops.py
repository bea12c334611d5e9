"""Work done in a box of the sheet (the thick ink's, inkprint.marks and
inkprint.components): the same result as on the whole sheet, on synthetic sheets
with prints, a ruler and specks, and on random masks."""

import cv2
import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_array_equal

from inkprint.components import components_with_stats, components_with_stats_in
from inkprint.group import _element_widths
from inkprint.marks import (
    _box_with,
    _disk,
    _hulls,
    _ink_box,
    _piece_at,
    _pool,
    _split,
    _straight_skinny,
)
from inkprint.options import AnalysisOptions
from inkprint.synth import PrintSpec, SheetSpec, render_sheet


def _sheet_mask(seed: int, treads=("knobby", "ribbed"), line=True) -> np.ndarray:
    """Ink of a small 300 dpi sheet with prints, specks and a ruler's line."""
    prints = tuple(
        PrintSpec(40.0, 12.0, (35.0 + 45.0 * i, 45.0), 10.0 * i, t) for i, t in enumerate(treads)
    )
    img, _ = render_sheet(SheetSpec(prints, dpi=300.0, seed=seed, specks=30, size=(120.0, 90.0)))
    grey = img if img.ndim == 2 else cv2.cvtColor(img, cv2.COLOR_BGR2GRAY)
    mask = grey < 128
    if line:
        cv2.line(mask.view(np.uint8), (30, 900), (1300, 960), 1, 14)  # 1.2 mm wide
    return mask


@pytest.fixture(
    scope="module",
    params=[(1, ("knobby", "ribbed")), (2, ("knobby", "ribbed")), (3, ("file", "knurl"))],
)
def pooled(request):
    # (a file and a knurl tread: fine tread elements join the thick ink, _split's box grows)
    seed, treads = request.param
    return _pool(_sheet_mask(seed, treads), 25.4 / 300.0, AnalysisOptions())


def _random_mask(seed: int, shape, share: float) -> np.ndarray:
    """Random ink in a random box of a larger mask (paper around it)."""
    rng = np.random.default_rng(seed)
    h, w = shape
    out = np.zeros(shape, bool)
    r0, c0 = rng.integers(0, h // 2 + 1), rng.integers(0, w // 2 + 1)
    r1, c1 = rng.integers(r0 + 1, h + 1), rng.integers(c0 + 1, w + 1)
    out[r0:r1, c0:c1] = rng.random((r1 - r0, c1 - c0)) < share
    return out


@settings(max_examples=80, deadline=None)
@given(
    seed=st.integers(0, 2**31),
    h=st.integers(2, 300),
    w=st.integers(2, 300),
    share=st.sampled_from([0.0, 0.05, 0.3, 0.7, 0.95]),
    margin=st.integers(0, 3),
    connectivity=st.sampled_from([4, 8]),
)
def test_components_with_stats_in_a_box_equal_the_whole_labelling(
    seed, h, w, share, margin, connectivity
):
    # the box may start on an odd row or column: the numbering stays OpenCV's
    mask = _random_mask(seed, (h, w), share)
    box = _ink_box(mask, margin)
    n0, lab0, st0, c0 = components_with_stats(mask, connectivity=connectivity)
    n1, lab1, st1, c1 = components_with_stats_in(mask, box, connectivity=connectivity)
    assert n1 == n0
    assert_array_equal(lab1, lab0)
    assert_array_equal(st1, st0)
    assert st1.dtype == st0.dtype
    assert_array_equal(c1, c0)  # to the last bit


@settings(max_examples=40, deadline=None)
@given(seed=st.integers(0, 2**31), diameter=st.sampled_from([3.0, 5.3, 8.0, 10.6]))
def test_opening_in_the_ink_box_equals_the_whole_opening(seed, diameter):
    mask = _random_mask(seed, (120, 150), 0.6).view(np.uint8)
    mask = cv2.morphologyEx(mask, cv2.MORPH_CLOSE, np.ones((3, 3), np.uint8))
    kernel = _disk(diameter)
    box = _ink_box(mask, kernel.shape[0] // 2)
    got = np.zeros_like(mask)
    if mask[box].size:
        got[box] = cv2.morphologyEx(mask[box], cv2.MORPH_OPEN, kernel)
    assert_array_equal(got, cv2.morphologyEx(mask, cv2.MORPH_OPEN, kernel))


def test_ink_box_is_empty_without_ink():
    rows, cols = _ink_box(np.zeros((5, 7), np.uint8), 2)
    assert np.zeros((5, 7))[rows, cols].size == 0


def test_piece_at_is_the_labelled_piece(pooled):
    n, lab = cv2.connectedComponents(pooled.mask.view(np.uint8), connectivity=8)
    for k in range(1, n, max(1, n // 25)):
        ys, xs = np.nonzero(lab == k)
        x, y, w, h = cv2.boundingRect(np.column_stack([xs, ys]).astype(np.int32))
        want = (lab[y : y + h, x : x + w] == k).view(np.uint8)
        assert_array_equal(_piece_at(pooled.mask, (ys[-1], xs[-1])), want)


def test_straight_skinny_in_a_box_equals_the_whole_sheet(pooled):
    opts = AnalysisOptions()
    m = pooled.mask.view(np.uint8)
    opened = cv2.morphologyEx(m, cv2.MORPH_OPEN, _disk(5.3))
    core = cv2.morphologyEx(opened, cv2.MORPH_OPEN, _disk(10.6))
    whole, teeth = _straight_skinny(opened & ~core, pooled, opts)
    assert whole.any()  # the ruler's line
    box = _ink_box(opened, 6)
    origin = (box[0].start, box[1].start)
    got, got_teeth = _straight_skinny(opened[box] & ~core[box], pooled, opts, origin=origin)
    assert_array_equal(got, whole[box])
    assert_array_equal(got_teeth, teeth[box])
    assert not whole[~np.pad(np.ones_like(got, bool), _pads(box, m.shape))].any()


def _pads(box, shape) -> tuple:
    return (
        (box[0].start, shape[0] - box[0].stop),
        (box[1].start, shape[1] - box[1].stop),
    )


def test_split_box_holds_the_thick_ink_with_paper_around(pooled):
    parts = _split(pooled, AnalysisOptions())
    rows, cols = parts.box
    inside = np.zeros(parts.thick.shape, bool)
    inside[rows, cols] = True
    assert parts.n_thick > 0
    assert not (parts.thick[~inside] > 0).any()
    assert not parts.core[~inside].any()
    # a pixel of paper around the thick ink within the box (or the image's edge)
    frame = inside & ~cv2.erode(inside.view(np.uint8), np.ones((3, 3), np.uint8)).view(bool)
    h, w = inside.shape
    frame[[0, h - 1], :] = frame[:, [0, w - 1]] = False
    assert not (parts.thick[frame] > 0).any()


def test_box_with_holds_the_box_and_the_pieces():
    stats = np.array([[10, 20, 5, 4, 9], [40, 2, 3, 3, 5]])  # left, top, width, height
    rows, cols = _box_with((slice(30, 50), slice(30, 60)), stats, 2, (100, 70))
    assert (rows, cols) == (slice(0, 50), slice(8, 60))
    rows, cols = _box_with((slice(0, 0), slice(0, 0)), stats[:1], 2, (100, 70))
    assert (rows, cols) == (slice(18, 26), slice(8, 17))


def test_hulls_and_widths_in_the_box_equal_the_whole_sheet(pooled):
    parts = _split(pooled, AnalysisOptions())
    comp = np.arange(parts.n_thick) % 3 - 1  # some elements in no group (-1)
    for core in (None, parts.core):
        want = _hulls(parts.thick, comp, core)
        got = _hulls(parts.thick, comp, core, box=parts.box)
        assert len(got) == len(want)
        for a, b in zip(got, want, strict=True):
            assert (a is None and b is None) or np.array_equal(a, b)
    px = pooled.px_mm
    want = _element_widths(parts.thick, parts.n_thick, px)
    assert_array_equal(_element_widths(parts.thick[parts.box], parts.n_thick, px), want)


@pytest.mark.parametrize("connectivity", [4, 8])
def test_components_with_stats_all_ink_has_a_zero_background(connectivity):
    # hypothesis found it (seed 8405517, a 2 x 2 mask of ink): OpenCV's dense path
    # left the absent background's box at its initial values, the box version zeros
    mask = np.ones((2, 3), bool)
    whole = components_with_stats(mask, connectivity=connectivity)
    boxed = components_with_stats_in(mask, _ink_box(mask, 0), connectivity=connectivity)
    assert_array_equal(whole[2][0], [0, 0, 0, 0, 0])
    assert_array_equal(whole[2], boxed[2])
    assert_array_equal(whole[3], boxed[3])
