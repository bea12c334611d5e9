"""The tread's own axis from its tracks' lateral profile (inkprint.treadaxis)."""

import math

import cv2
import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

import inkprint as ip
from inkprint.synth import PrintSpec, SheetSpec, render_sheet
from inkprint.treadaxis import tread_turn

from .test_independent import _sheet_of_set

MM_PER_PX = 0.1


def knob_lattice(turn_deg, *, pitch=(6.0, 5.0), knob=(3.0, 2.5), stagger=0.5, size=(70, 45)):
    """A knob pattern: knobs ``knob`` (along, across) [mm] on a lattice ``pitch``,
    every other track shifted by ``stagger`` of a pitch, inside an ellipse of
    ``size`` [mm], its rolling direction turned ``turn_deg`` from +x (counter-
    clockwise), drawn at 0.1 mm / px: (mask, exact turn)."""
    n = int(1.3 * max(size) / MM_PER_PX)
    mask = np.zeros((n, n), np.uint8)
    c, s = math.cos(math.radians(turn_deg)), math.sin(math.radians(turn_deg))
    centre = n / 2
    for j in range(-8, 9):  # tracks across
        for i in range(-12, 13):  # knobs along
            u = (i + stagger * (j % 2)) * pitch[0]
            v = j * pitch[1]
            if (u / (size[0] / 2)) ** 2 + (v / (size[1] / 2)) ** 2 > 1:
                continue
            corners = np.array([[-1, -1], [1, -1], [1, 1], [-1, 1]]) * np.array(knob) / 2
            uv = corners + np.array([u, v])
            x, y = uv[:, 0] * c - uv[:, 1] * s, uv[:, 0] * s + uv[:, 1] * c
            pts = np.column_stack([centre + x / MM_PER_PX, centre - y / MM_PER_PX])
            cv2.fillPoly(mask, [np.round(pts * 16).astype(np.int32)], 1, shift=4)
    return mask.astype(bool)


@pytest.mark.parametrize("turn", [0.0, 3.3, -6.2, 9.0])
@pytest.mark.parametrize("stagger", [0.0, 0.5])
def test_tread_turn_finds_the_tracks_of_a_knob_pattern(turn, stagger):
    mask = knob_lattice(turn, stagger=stagger)
    found = tread_turn(mask, "x", mm_per_px=MM_PER_PX, limit_deg=12.0)
    assert found.turn == pytest.approx(turn, abs=0.1)
    assert found.contrast > 1.05


def test_tread_turn_along_y_is_the_same_turn():
    # the same pattern rolling up the sheet: turned 90 + t from +x, t from +y
    mask = knob_lattice(90.0 + 4.0)
    found = tread_turn(mask, "y", mm_per_px=MM_PER_PX, limit_deg=12.0)
    assert found.turn == pytest.approx(4.0, abs=0.1)


def test_tread_turn_of_a_slick_print_has_no_contrast():
    # no tracks: an ellipse of solid ink; its profile barely changes with the turn
    mask = np.zeros((800, 800), np.uint8)
    cv2.ellipse(mask, (400, 400), (300, 200), -5.0, 0, 360, 1, -1)
    found = tread_turn(mask.astype(bool), "x", mm_per_px=MM_PER_PX, limit_deg=12.0)
    assert found.contrast < 1.05


def test_tread_turn_of_an_empty_mask_is_no_turn():
    found = tread_turn(np.zeros((10, 10), bool), "x", mm_per_px=MM_PER_PX, limit_deg=12.0)
    assert (found.turn, found.contrast) == (0.0, 1.0)


@settings(max_examples=12, deadline=None)
@given(turn=st.floats(-10.0, 10.0), pitch=st.floats(4.5, 8.0), stagger=st.sampled_from([0.0, 0.5]))
@example(turn=0.125, pitch=5.0, stagger=0.0)  # CI's first: -0.15 for the mirror of 0.05
@example(turn=9.5, pitch=5.0, stagger=0.0)  # whole-bin profiles: 9.65 (a jitter peak)
@example(turn=10.0, pitch=5.0, stagger=0.0)  # whole-bin profiles: 10.15
def test_tread_turn_mirrored_pattern_turns_the_other_way(turn, pitch, stagger):
    # a mirror image across the rolling axis (rows flipped) negates the turn (within
    # the fine step's rounding either way: the cells are not mirrored with the ink)
    mask = knob_lattice(turn, pitch=(pitch, 5.0), stagger=stagger)
    a = tread_turn(mask, "x", mm_per_px=MM_PER_PX, limit_deg=12.0)
    b = tread_turn(mask[::-1], "x", mm_per_px=MM_PER_PX, limit_deg=12.0)
    assert b.turn == pytest.approx(-turn, abs=0.15)
    assert a.turn == pytest.approx(turn, abs=0.15)


@pytest.mark.parametrize(
    ("kw", "name"),
    [
        ({"axis": "z"}, "axis"),
        ({"limit_deg": 0.0}, "limit_deg"),
        ({"mm_per_px": -0.1}, "mm_per_px"),
    ],
)
def test_tread_turn_bad_input_names_the_parameter(kw, name):
    from inkprint.errors import InvalidInput

    args = {"axis": "x", "mm_per_px": MM_PER_PX, "limit_deg": 12.0} | kw
    axis = args.pop("axis")
    with pytest.raises(InvalidInput, match=rf"^{name} = "):
        tread_turn(np.zeros((10, 10), bool), axis, **args)


@pytest.mark.parametrize(
    "length, width, turn, dpi, seed",
    [(29.3, 30.8, 4.0, 200.0, 1), (37.1, 32.3, 6.0, 200.0, 31), (35.5, 30.1, 3.0, 150.0, 51)],
)
def test_analyze_scan_round_knob_print_turned_is_flagged_by_its_tracks(
    length, width, turn, dpi, seed
):
    # a nearly round sparse knob print taped 3-6 deg off the given axis: its
    # rectangle and moments lie 15-34 deg off (no axis), its faint tracks (contrast
    # 1.02-1.09) at the true turn; measured along the given axis it read up to
    # +3.5 % long and +3.1 % wide with status ok
    spec = SheetSpec(
        (PrintSpec(length, width, (40, 40), angle=turn, tread="mtb"),),
        dpi=dpi,
        size=(80, 80),
        seed=seed,
    )
    img, (t,) = render_sheet(spec)
    res = ip.analyze_scan(ip.Scan(img, 25.4 / dpi, "given"), rolling_axis="x", sensitivity=False)
    (p,) = res.prints
    within = (
        abs(p.metrics.length / t.length - 1) <= 0.01 and abs(p.metrics.width / t.width - 1) <= 0.01
    )
    assert within or "axis_misaligned" in p.flags, (p.metrics.length, t.length, p.metrics.width)
    assert not within  # (the control: along the given axis it is out of the bar)


def test_analyze_scan_knob_prints_square_by_their_tracks_are_not_flagged(tmp_path):
    # independent set 2 sheet 96: three wide knob prints taped within 0.3 deg of the
    # given axis; tracks at 0.0-0.4 deg, rectangle and moments at -6..+5 deg: all
    # three flagged axis_misaligned though within 0.3 % of the truth
    out = _sheet_of_set(tmp_path, 2, 96)
    assert [o["outcome"] for o in out] == ["pass"] * 3, out
