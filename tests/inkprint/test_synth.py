"""The synthetic outline law (independent of the Rotta model)."""

import pytest
from numpy.testing import assert_allclose

from inkprint.synth import outline_law, superellipse_area


def test_outline_law_maxxis_section_4_1_1():
    # section 4.1.1: Maxxis radial, 304 N, 100 psi: a 7.57 mm wide plate print
    length, width = outline_law(304.0, 0.6895, 9.5)
    assert_allclose(width, 7.57, rtol=0.01)
    # load / area = 1.03 x inflation pressure (Figure 4-3: slightly above)
    assert_allclose(304.0 / superellipse_area(length, width), 1.03 * 0.6895, rtol=1e-9)


def test_outline_law_drum_over_plate_table_4_1():
    # Table 4-1 means: drum/plate length 92 %, width 112 %, area ~104 %
    lp, wp = outline_law(400.0, 0.5, 12.0)
    ld, wd = outline_law(400.0, 0.5, 12.0, surface="drum")
    assert_allclose([ld / lp, wd / wp], [0.92, 1.12])
    assert_allclose(superellipse_area(ld, wd) / superellipse_area(lp, wp), 1.03, atol=0.01)


@pytest.mark.parametrize(("args", "match"), [((0, 0.5, 10), "load"), ((300, -1, 10), "pressure")])
def test_outline_law_invalid(args, match):
    from inkprint import InvalidInput

    with pytest.raises(InvalidInput, match=match):
        outline_law(*args)
