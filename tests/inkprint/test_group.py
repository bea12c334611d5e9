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


# --- maybe_tiny_print: a group the small-print rule set aside, a tread or a word?


def _diamonds(length_mm, width_mm, pitch_mm, mm_per_px, *, angle_deg=0.0):
    """An elliptic field of separate square dots ``pitch_mm / 2`` wide on a
    ``pitch_mm`` lattice (a knurl print's elements), turned ``angle_deg``."""
    import cv2

    n = int(np.ceil(1.3 * max(length_mm, width_mm) / mm_per_px))
    y, x = np.mgrid[:n, :n] * mm_per_px
    c = 0.5 * n * mm_per_px
    t = np.deg2rad(angle_deg)
    u = (x - c) * np.cos(t) + (y - c) * np.sin(t)
    v = -(x - c) * np.sin(t) + (y - c) * np.cos(t)
    inside = (2 * u / length_mm) ** 2 + (2 * v / width_mm) ** 2 <= 1
    dots = (np.mod(u, pitch_mm) < pitch_mm / 2) & (np.mod(v, pitch_mm) < pitch_mm / 2)
    mask = (inside & dots).astype(np.uint8)
    return cv2.morphologyEx(mask, cv2.MORPH_OPEN, np.ones((2, 2), np.uint8)).astype(bool)


def _word(text, height_mm, mm_per_px, *, stroke_mm=0.6):
    """``text`` in a marker's letters ``height_mm`` high."""
    import cv2

    scale = height_mm / mm_per_px / 22.0
    thick = max(1, round(stroke_mm / mm_per_px))
    (w, h), base = cv2.getTextSize(text, cv2.FONT_HERSHEY_SIMPLEX, scale, thick)
    img = np.zeros((h + base + 4 * thick, w + 4 * thick), np.uint8)
    cv2.putText(img, text, (2 * thick, h + 2 * thick), cv2.FONT_HERSHEY_SIMPLEX, scale, 1, thick)
    return img.astype(bool)


@pytest.mark.parametrize(
    ("length", "width", "pitch", "angle"),
    [(16.0, 4.0, 1.0, 0.0), (12.0, 6.0, 1.3, 30.0), (20.0, 3.5, 0.9, 90.0)],
)
@pytest.mark.parametrize("dpi", [200, 300, 600])
def test_maybe_tiny_print_a_field_of_tread_elements(length, width, pitch, angle, dpi):
    from inkprint.group import maybe_tiny_print

    s = 25.4 / dpi
    mask = _diamonds(length, width, pitch, s, angle_deg=angle)
    assert maybe_tiny_print(mask, mm_per_px=s)


@pytest.mark.parametrize("text", ["36 kg", "77 psi", "F=831N", "3.3 bar", "GP5000", "kg"])
@pytest.mark.parametrize("dpi", [150, 300, 400])
def test_maybe_tiny_print_not_a_word(text, dpi):
    from inkprint.group import maybe_tiny_print

    s = 25.4 / dpi
    assert not maybe_tiny_print(_word(text, 5.0, s), mm_per_px=s)


def test_maybe_tiny_print_one_scalloped_body_long_enough():
    # one body 18 x 6 mm, its sides notched by grooves (a file tread's scallops, a
    # quarter of its width deep) with a speck beside: a tiny print; the same body 8
    # mm long is a letter's size, and a bar 60 x 5 mm a stroke
    import cv2

    from inkprint.group import maybe_tiny_print

    s = 25.4 / 300

    def body(length, width):
        n = int(1.4 * length / s)
        y, x = np.mgrid[:n, :n] * s
        c = 0.5 * n * s
        inside = ((x - c) / (length / 2)) ** 2 + ((y - c) / (width / 2)) ** 2 <= 1
        notch = (np.mod(x, 1.2) < 0.3) & (np.abs(y - c) > 0.4 * width)
        mask = (inside & ~notch).astype(np.uint8)
        cv2.circle(mask, (int(0.5 * n), int((c + width / 2 + 0.6) / s)), 1, 1, -1)
        return mask.astype(bool)

    assert maybe_tiny_print(body(18.0, 6.0), mm_per_px=s)
    assert not maybe_tiny_print(body(8.0, 5.0), mm_per_px=s)
    assert not maybe_tiny_print(body(60.0, 5.0), mm_per_px=s)
    assert not maybe_tiny_print(np.zeros((20, 20), bool), mm_per_px=s)


@pytest.mark.parametrize("text", ["Vittoria", "Schwalbe", "Maxxis"])
@pytest.mark.parametrize("dpi", [150.0, 200.0])
def test_maybe_tiny_print_not_a_bold_word_fused_to_one_body(text, dpi):
    # a marker's word 4.5 mm high in 1.3 mm strokes (inkprint.synth's pen), its
    # letters fused to one body at this resolution, as long and slender as a tiny
    # print: the gaps between its letters and their counters leave its core unfilled
    import cv2

    from inkprint.group import maybe_tiny_print
    from inkprint.synth import SheetSpec, render_sheet
    from inkprint.synth_effects import Text

    spec = SheetSpec(
        (),
        dpi=dpi,
        seed=5,
        specks=0,
        size=(60.0, 20.0),
        marks=(Text(text, (5.0, 8.0), 4.5, 1.3, 0.85),),
    )
    img, _ = render_sheet(spec)
    ink = (np.asarray(img, float) < 0.5 * (float(img.max()) + float(img.min()))).astype(np.uint8)
    st = cv2.connectedComponentsWithStats(ink, connectivity=8)[2]
    big = 1 + int(np.argmax(st[1:, 4]))
    assert st[big, 4] >= 0.8 * st[1:, 4].sum()  # (fused: one body)
    assert not maybe_tiny_print(ink.astype(bool), mm_per_px=25.4 / dpi)


@pytest.mark.parametrize("dpi", [150, 300])
def test_maybe_tiny_print_not_two_fibres_side_by_side(dpi):
    # two dust fibres 96 mm long, 0.4 mm thick, 4 mm apart (held-out 6 seed 9
    # sheet 11): each spans a tenth of the pair's width, like a tread's elements,
    # but the pair is 21 x longer than wide: no print's shape
    import cv2

    from inkprint.group import maybe_tiny_print

    s = 25.4 / dpi
    mask = np.zeros((round(8 / s), round(100 / s)), np.uint8)
    for y in (2.0, 6.0):
        cv2.line(
            mask,
            (round(2 / s), round(y / s)),
            (round(98 / s), round((y + 0.3) / s)),
            1,
            max(1, round(0.4 / s)),
        )
    assert not maybe_tiny_print(mask.astype(bool), mm_per_px=s)
    # the same pair 16 mm long is as slender as a tiny rib print's pieces
    short = mask[:, : round(18 / s)].copy()
    assert maybe_tiny_print(short.astype(bool), mm_per_px=s)


def test_maybe_tiny_print_refuses_bad_input():
    from inkprint.errors import InvalidInput
    from inkprint.group import maybe_tiny_print

    mask = np.zeros((20, 20), bool)
    with pytest.raises(InvalidInput, match="mask"):
        maybe_tiny_print(np.zeros((2, 20, 20), bool), mm_per_px=0.1)
    for bad in (0.0, -0.1, float("nan")):
        with pytest.raises(InvalidInput, match="mm_per_px"):
            maybe_tiny_print(mask, mm_per_px=bad)


def _teeth_case(top: list, bottom: list):
    """A 100 x 20 px hull along x and stubs' centres above (y < 0) and below it."""
    from inkprint.group import _teeth

    hull = np.array([[-50, -10], [50, -10], [50, 10], [-50, 10]], float)
    cent = np.array([[x, -11.0] for x in top] + [[x, 11.0] for x in bottom])
    stub = np.ones(len(cent), bool)
    return _teeth(hull, cent, stub, 3)


def test_teeth_rows_on_both_sides_along_the_print():
    assert _teeth_case([-30, -10, 10, 30], [-25, -5, 15, 35]).all()


def test_teeth_one_side_short_at_a_regular_pitch():
    # held-out 6 seed 7 sheet 10: a tiny file print's outline cut only its three
    # middle teeth on one side to stubs (0.3 of its length), seven on the other;
    # dropped as strokes' feet, -11 % wide with status ok
    assert _teeth_case([-15.5, -0.5, 14], [-27.5, -15, 0, 15, 28, 31.5, 34]).all()


@pytest.mark.parametrize(
    ("top", "bottom"),
    [
        ([-15, -9, 14], [-27.5, -15, 0, 15, 28]),  # the short side irregular
        ([-15, 0, 15], [-8, 0, 8]),  # both sides short
        ([-30, -10, 10, 30], []),  # one side only (a label's letters)
    ],
)
def test_teeth_not_without_a_row_along_the_print(top, bottom):
    assert not _teeth_case(top, bottom).any()
