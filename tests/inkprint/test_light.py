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
