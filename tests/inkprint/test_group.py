"""Tests of inkprint.group's helpers for the section 7.1.1 rule's thin ink (the
pieces' gaps, a tread's rows of dots); its end-to-end cases are in test_fine_tread,
test_marks_on_prints and test_tips."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose, assert_array_equal

from inkprint.group import _pair_gaps


@settings(max_examples=60, deadline=None)
@given(
    gap=st.integers(0, 12),
    first=st.integers(1, 6),
    second=st.integers(1, 6),
    rows=st.integers(1, 5),
    across=st.booleans(),
)
def test_pair_gaps_two_bars_the_paper_between(gap, first, second, rows, across):
    # two bars, ``gap`` columns of paper between them (0: touching 4-ways): the
    # gap is the paper's width, exactly along a row
    w = 2 + first + gap + second + 2
    lab = np.zeros((rows + 4, w), np.int32)
    lab[2 : 2 + rows, 2 : 2 + first] = 1
    lab[2 : 2 + rows, 2 + first + gap : 2 + first + gap + second] = 2
    if across:
        lab = lab.T.copy()
    a, b, g = _pair_gaps(lab)
    assert_array_equal(a, [1])
    assert_array_equal(b, [2])
    assert_allclose(g, [gap], atol=1e-6)


def test_pair_gaps_each_pair_once_with_its_least_gap():
    # three dots in a row 3 and 1 px apart, and a fourth far below the first: each
    # pair whose nearest-ink regions meet, once, the lower label first
    lab = np.zeros((30, 20), np.int32)
    lab[2:5, 1:3], lab[2:5, 6:8], lab[3, 9], lab[25, 1:3] = 1, 2, 3, 4
    a, b, g = _pair_gaps(lab)
    got = {(int(i), int(j)): float(x) for i, j, x in zip(a, b, g, strict=True)}
    assert got[(1, 2)] == pytest.approx(3.0, abs=1e-6)
    assert got[(2, 3)] == pytest.approx(1.0, abs=1e-6)
    assert (1, 3) not in got  # (2 lies between them)
    assert got[(1, 4)] > 15.0
    assert len(got) == len(a) and all(i < j for i, j in got)


def test_pair_gaps_one_piece_has_no_pairs():
    lab = np.zeros((8, 8), np.int32)
    lab[2:5, 2:5] = 1
    a, b, g = _pair_gaps(lab)
    assert len(a) == len(b) == len(g) == 0
