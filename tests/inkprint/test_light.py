"""The page of a photo (inkprint.light): its corners refined on the full image,
perspective told by corner angles or by opposite sides of unequal length."""

import numpy as np
import pytest
from numpy.testing import assert_allclose

import inkprint as ip
from inkprint.light import keystone, prepare_page
from inkprint.synth import LETTER, PrintSpec, SheetSpec, render_sheet
from inkprint.synth_effects import Photo

DPI = 150.0


def _photo(tilt: float, *, dpi: float = DPI, seed: int = 2) -> ip.Scan:
    """A letter page with a print photographed on a table, its far (top) corners
    moved in by ``tilt`` mm each: its top side 2 x tilt shorter than its bottom."""
    spec = PrintSpec(90.0, 30.0, (108.0, 140.0), 0.0, "ribbed")
    img, _ = render_sheet(SheetSpec((spec,), dpi=dpi, photo=Photo(tilt=tilt), seed=seed))
    return ip.Scan(img, 25.4 / dpi, "given")


def test_keystone_of_a_trapezoid_and_a_rectangle():
    assert keystone(np.array([[0, 0], [10, 0], [10, 5], [0, 5]])) == 0.0
    trapezoid = np.array([[1, 0], [9, 0], [10, 5], [0, 5]])  # top 8, bottom 10
    assert_allclose(keystone(trapezoid), 0.2)


@pytest.mark.parametrize("seed", [2, 5])
def test_prepare_page_flat_photo_is_not_flagged(seed):
    page = prepare_page(_photo(0.0, seed=seed))
    assert page.sheet is not None and "perspective" not in page.flags
    assert_allclose(page.corner_angles, 90.0, atol=0.1)  # refined: on the grid +-1.4


@pytest.mark.parametrize(("tilt", "dpi"), [(2.0, 150.0), (3.0, 150.0), (3.0, 300.0)])
def test_prepare_page_mild_keystone_is_flagged(tilt, dpi):
    # held-out set 14 sheet 54: a 2.8-3.7 % keystone, its corners within 1.3
    # degrees of square on the 2 mm grid (tolerance 1.5): its print -2.4 % long
    # with status ok. Here the top side is 4-6 mm (1.9-2.8 %) shorter, the corners
    # 0.4-0.6 degrees off square
    page = prepare_page(_photo(tilt, dpi=dpi))
    assert "perspective" in page.flags
    assert max(abs(a - 90.0) for a in page.corner_angles) < 1.5  # the angles alone pass
    assert any("opposite sides" in w for w in page.warnings)
    want = 2 * tilt / LETTER[0]
    assert f"{100 * want:.1f} % apart" in " ".join(page.warnings)


def test_frame_warnings_page_without_clean_corners_is_flagged_perspective():
    # a page found on a darker surround whose outline is no clean quadrilateral:
    # its tilt cannot be checked, so neither can the scale. Advice only before:
    # held-out generator 6's tilted phone photos (keystone 5 %) read 6-13 % short
    # with status ok
    from inkprint.light import _Frame, _frame_warnings
    from inkprint.options import AnalysisOptions

    frame = _Frame(np.ones((8, 8), bool), None, ())
    flags, warnings = _frame_warnings(frame, AnalysisOptions())
    assert flags == ("perspective",)
    assert "perspective not checked" in warnings[0] and "scan it" in warnings[0]
    square = _Frame(
        np.ones((8, 8), bool), np.array([[0, 0], [7, 0], [7, 7], [0, 7]]), (90.0,) * 4, 0.0
    )
    assert _frame_warnings(square, AnalysisOptions()) == ((), ())


def _clipped_slick_sheet(dpi: float) -> tuple:
    """A 160 x 120 mm sheet: a slick print inked 0.78, a 100 x 82 mm rectangle with
    8 mm round corners, 60 mm of it off the image's left edge (40 mm on), and a 70
    x 20 mm elliptical slick print; the grey, mm per px and the drawn truths of the
    clipped print's visible part and of the ellipse (tests.inkprint.drawn)."""
    import cv2

    from tests.inkprint.drawn import drawn_scan

    ss, darkness, r = 2, 0.78, 8.0
    px = 25.4 / dpi / ss

    def at(*mm: float) -> tuple:
        return tuple(round(v / px) for v in mm)

    cut = np.zeros(at(120.0, 160.0), np.uint8)
    cv2.rectangle(cut, at(0.0, 19.0), np.subtract(at(40.0 - r, 101.0), 1).tolist(), 1, -1)
    cv2.rectangle(cut, at(0.0, 19.0 + r), np.subtract(at(40.0, 101.0 - r), 1).tolist(), 1, -1)
    for y in (19.0 + r, 101.0 - r):
        cv2.circle(cut, at(40.0 - r, y), round(r / px), 1, -1)
    other = np.zeros_like(cut)
    cv2.ellipse(other, at(115.0, 60.0), at(35.0, 10.0), 0, 0, 360, 1, -1)
    grey, mm, _ = drawn_scan(cut | other, dpi, ss, darkness)
    return grey, mm, drawn_scan(cut, dpi, ss, darkness)[2], drawn_scan(other, dpi, ss, darkness)[2]


@pytest.mark.parametrize("dpi", [200.0, 400.0])
def test_background_dark_slick_print_run_off_the_sheet_wider_than_the_closing(dpi):
    # held-out 6 seed 1 sheet 51: a dark slick print 40 x 82 mm cut by the sheet's
    # left edge, wider than the light's closing (light_scale_mm): the paper
    # "around" it was its own level, so its edge ink was none; taken for shade, it
    # went missing and the sheet read "uneven light: ... 29 %" (here 15 %). Its
    # sharp edge is judged against the page's paper too (light._background)
    grey, mm, cut, whole = _clipped_slick_sheet(dpi)
    res = ip.analyze_scan(ip.Scan(grey, mm, "given"), rolling_axis="x", sensitivity=False)
    assert "uneven_light" not in res.flags
    assert not any("uneven light" in w for w in res.warnings)
    assert len(res.prints) == 2
    clipped, other = sorted(res.prints, key=lambda p: p.bbox[1])
    assert "clipped" in clipped.flags and clipped.bbox[1] == 0
    assert not other.flags
    for p, t in ((clipped, cut), (other, whole)):
        assert_allclose([p.metrics.length, p.metrics.width], t[:2], rtol=0.01)
        assert_allclose(p.metrics.hull_area, t[2], rtol=0.02)
