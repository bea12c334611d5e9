"""The tread's own axis from its tracks' lateral profile (inkprint.treadaxis)."""

import math

import cv2
import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from inkprint.treadaxis import tread_turn

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
