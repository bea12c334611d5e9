"""A print of siped blocks (combs) in which a few blocks print solid: the combs are
the tread's blocks, not a marker's letters (marks._BoldJudge._repeated_blocks,
pattern.copies_of_one). Drawn with exact truth (tests.inkprint.drawn)."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

import inkprint as ip
from tests.inkprint.drawn import drawn_scan


def _combs_with_solid_blocks(dpi: float, solid: int) -> tuple:
    """Held-out 6 seed 2 sheet 63's siped print along x: a superellipse 63 x 50 mm
    (exponent 2.965) of 7.03 x 8.91 mm blocks, gaps 2.6 and 2.4 mm, columns
    staggered by half a pitch; three 0.78 mm sipes across each block, open at one
    end (3/4 of its height; alternate rows from alternate ends): combs of four bars.
    The ``solid`` lowest blocks whose centres lie inside the outline print solid
    (their sipes closed), the lowest of them cut by the outline to ~7 x 4.6 mm.
    The grey, mm per px, the drawn truth and the number of blocks with ink."""
    import cv2

    ss, length, width, n, margin = 4, 63.0, 50.0, 2.965, 12.0
    (bx, by), (gx, gy), sipe, phase = (7.03, 8.91), (2.6, 2.4), 0.78, 3.5
    mm = 25.4 / dpi / ss
    h, w = round((width + 2 * margin) / mm), round((length + 2 * margin) / mm)
    y = (h * mm / 2 - (np.arange(h) + 0.5) * mm)[:, None]  # up
    x = ((np.arange(w) + 0.5) * mm - w * mm / 2)[None, :]
    inside = np.abs(x / (length / 2)) ** n + np.abs(y / (width / 2)) ** n <= 1.0
    px, py = bx + gx, by + gy
    i = np.floor((x - phase) / px + 0.5)  # a block's column
    u = x - phase - i * px
    off = np.where(np.mod(i, 2) == 1, py / 2, 0.0)
    j = np.floor((y - off) / py + 0.5)  # its row in the column
    v = y - off - j * py
    block = (np.abs(u) <= bx / 2) & (np.abs(v) <= by / 2)
    sipes = np.zeros(u.shape, bool)
    for k in (1, 2, 3):
        sipes |= np.abs(u + bx / 2 - bx * k / 4) <= sipe / 2
    open_end = np.where(np.mod(j, 2) == 1, v <= 0.25 * by, v >= -0.25 * by)
    centres = []
    for ci in range(-8, 9):
        for cj in range(-8, 9):
            cx, cy = phase + ci * px, (py / 2 if ci % 2 else 0.0) + cj * py
            if abs(cx / (length / 2)) ** n + abs(cy / (width / 2)) ** n <= 1.0:
                centres.append((cy, abs(cx), ci, cj))
    shut = np.zeros(block.shape, bool)
    for _, _, ci, cj in sorted(centres)[:solid]:
        shut |= (i == ci) & (j == cj)
    ink = (inside & block & (shut | ~(sipes & open_end))).astype(np.uint8)
    ids = np.unique((i * 100 + j)[(inside & block)])
    grey, px_mm, truth = drawn_scan(ink, dpi, ss, 0.8)
    assert cv2.countNonZero(ink & shut.astype(np.uint8)) > 0
    return grey, px_mm, truth, len(ids)


@pytest.mark.parametrize(("dpi", "solid"), [(200.0, 3), (300.0, 3), (200.0, 1)])
def test_repeated_blocks_combs_with_a_few_solid_blocks_are_the_print(dpi, solid):
    """Held-out 6 seed 2 sheet 63 (200 dpi): 37 siped blocks (combs, 3 open sipes
    each) in a 63 x 50 mm print, a few bottom blocks solid (their sipes closed).
    Each comb was set aside as a marker's letter and the print reduced to a solid
    cut block: a 7 x 4 mm print, status ok. Strokes that are whole copies of one
    another (at least TREAD_BLOCKS of them) are the tread's blocks. Here (35 blocks)
    before: 2-4 prints, the largest -49 to -88 % long and -75 to -87 % wide
    (flagged), among them the solid cut block as a 7.4 x 4.6 mm print, status ok."""
    grey, mm, truth, blocks = _combs_with_solid_blocks(dpi, solid)
    assert 35 <= blocks <= 45, blocks
    res = ip.analyze_scan(ip.Scan(grey, mm, "given"), rolling_axis="x", sensitivity=False)
    p = max(res.prints, key=lambda p: p.metrics.hull_area)
    m = p.metrics
    assert_allclose([m.length, m.width], truth[:2], rtol=0.01)
    assert_allclose(m.hull_area, truth[2], rtol=0.02)
    assert p.status == "ok", p.warnings
    assert len(res.prints) == 1, [q.metrics for q in res.prints]
