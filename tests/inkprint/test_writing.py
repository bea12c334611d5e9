"""Pages of writing only: a label's rows of bold marker letters, joined into one
group, are writing, not a print (:func:`inkprint.group._rows_of_letters`); a
tread's bars in rows stay a print."""

import cv2
import numpy as np
import pytest
from numpy.testing import assert_allclose

import inkprint as ip
from inkprint.group import Group, is_print

ROWS = ("Compass Stampede Pass 32", "p = 5.3 bar")


def _label_page(dpi: float, height: float, stroke: float, gap: float) -> ip.Scan:
    """Two rows of bold letters (``height`` mm capitals, ``stroke`` mm strokes,
    ``gap`` mm of paper between the rows), grey on a grey page with noise."""
    mm = 25.4 / dpi
    ink = np.zeros((int(120 / mm), int(160 / mm)), np.uint8)
    scale = height / mm / 22.0  # a DUPLEX capital is 22 px at scale 1
    y = int(30 / mm)
    for row in ROWS:
        cv2.putText(
            ink,
            row,
            (int(15 / mm), y),
            cv2.FONT_HERSHEY_DUPLEX,
            scale,
            255,
            max(1, round(stroke / mm)),
            cv2.LINE_AA,
        )
        y += int((height + gap) / mm)
    rng = np.random.default_rng(0)
    grey = 0.92 - 0.55 * ink.astype(np.float32) / 255 + rng.normal(0, 0.01, ink.shape)
    return ip.Scan(grey.astype(np.float32), mm, "given")


@pytest.mark.parametrize(
    "dpi, height, stroke, gap",
    [
        (150.0, 4.5, 1.4, 1.5),
        (150.0, 5.5, 1.6, 2.0),
        (300.0, 4.0, 1.2, 1.2),
        (600.0, 4.5, 1.4, 1.5),
    ],
)
def test_analyze_scan_rows_of_bold_letters_are_no_print(dpi, height, stroke, gap):
    # held-out 6 sheet 79: 'Compass Stampede Pass 32' over 'p = 5.3 bar' on a page of
    # writing only came out as an 86 x 15 mm print, unflagged (and so here before,
    # on all of these)
    with pytest.raises(ip.NoInk, match="lines of writing"):
        ip.analyze_scan(_label_page(dpi, height, stroke, gap), sensitivity=False)


def _bar_rows(mm: float, bar: float, groove: float) -> np.ndarray:
    """A 60 x 24 mm elliptical print of slanted bars ``bar`` mm wide, 3 mm apart,
    in two rows either side of a ``groove`` mm centre groove (a herringbone tread
    without its centre rib)."""
    h, w = round(30 / mm), round(70 / mm)
    out = np.zeros((h, w), np.uint8)
    cy, cx = h / 2, w / 2
    for x in np.arange(6.0, 64.0, 3.0):
        for side in (-1, 1):
            y0, y1 = side * groove / 2, side * 13.0
            p0 = (round(x / mm), round(cy + y0 / mm))
            p1 = (round((x + 0.5 * side * (y1 - y0)) / mm), round(cy + y1 / mm))
            cv2.line(out, p0, p1, 1, max(1, round(bar / mm)))
    ellipse = np.zeros_like(out)
    cv2.ellipse(
        ellipse, (round(cx), round(cy)), (round(30 / mm), round(12 / mm)), 0, 0, 360, 1, -1
    )
    return (out & ellipse).astype(bool)


@pytest.mark.parametrize("dpi", [150.0, 300.0])
def test_is_print_bars_in_two_rows_are_a_print(dpi):
    mm = 25.4 / dpi
    m = _bar_rows(mm, 1.2, 2.0)
    g = Group(slice(0, m.shape[0]), slice(0, m.shape[1]), m)
    check = is_print(g, mm_per_px=mm)
    assert check.ok, check.reason
    _rows, cols = np.nonzero(m)
    assert_allclose(np.ptp(cols) * mm, 60.0, rtol=0.05)  # the fixture is what it says
