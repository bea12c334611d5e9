"""Shared patch metrics and the model's appendix ellipse (section 5.4)."""

import math

import numpy as np
import pytest
import shapely
from numpy.testing import assert_allclose
from shapely import affinity

import contactpatch as cp
import tiremesh as tm


def test_measure_rectangle_with_hole():
    rect = shapely.box(0, 0, 100, 10).difference(shapely.box(40, 4, 60, 6))
    m = cp.measure(rect)
    assert_allclose([m.length, m.width, m.area, m.hull_area], [100, 10, 960, 1000])
    assert_allclose(m.solidity, 0.96)
    assert_allclose(m.orientation, 0.0, atol=1e-12)
    assert_allclose(m.station_lengths, 100.0)
    assert_allclose(m.shape_factor, 1.0)
    assert_allclose(m.perimeter, 220.0)


def test_measure_rotated_print_finds_its_axis():
    e = cp.EllipseFit((50.0, 20.0), 80.0, 8.0, 0.0)
    poly = affinity.rotate(shapely.Polygon(e.boundary(2000)), 35, origin=(0, 0))
    m = cp.measure(poly)
    assert_allclose(np.degrees(m.orientation), 35.0, atol=1e-6)
    assert_allclose([m.length, m.width], [80.0, 8.0], rtol=1e-4)
    assert_allclose([m.ellipse_direct.length, m.ellipse_direct.width], [80, 8], rtol=1e-4)
    assert_allclose([m.ellipse_moments.length, m.ellipse_moments.width], [80, 8], rtol=1e-4)
    # ellipse: chord at 0.8 of the half width is 0.6 of the centre line
    assert_allclose(m.shape_factor, 1 / 0.6, rtol=1e-3)
    row = m.as_row(prefix="print_")
    assert row["print_length_mm"] == m.length and "print_ellipse_area_mm2" in row


@pytest.mark.parametrize(
    ("region", "kw", "match"),
    [
        (shapely.Polygon(), {}, "region"),
        (shapely.LineString([(0, 0), (1, 1)]), {}, "region"),
        (np.array([[0, 0], [1, 1]]), {}, "region"),
        (shapely.box(0, 0, 2, 1), {"stations": (0, 1.2)}, "stations"),
        (shapely.box(0, 0, 2, 1), {"axis": math.nan}, "axis"),
    ],
)
def test_measure_invalid(region, kw, match):
    with pytest.raises(cp.InvalidInput, match=match):
        cp.measure(region, **kw)


def test_appendix_ellipse_figure_5_15():
    # Figure 5-15 (section 5.4; configuration in published-values.md): the fitted
    # ellipse is 98.49 mm long, 9.783 mm wide, 756.8 mm^2 (Appendix C's fit_ellipse on
    # the patch edges and centre line, 151 sections per half over 15 degrees)
    tire = tm.TireGeometry.from_arc_length(128.2, 18.7)
    patch = tm.solve_patch(tire, 5.0, pressure=0.4)
    e = cp.appendix_ellipse(patch)
    assert_allclose([e.length, e.width, e.area], [98.49, 9.783, 756.8], rtol=0.01)
    assert_allclose([e.length, e.width, e.area], [98.49, 9.783, 756.8], rtol=1e-3)  # in fact
    assert_allclose(e.length / patch.length, 0.8295, atol=0.005)  # 82.95 % of the patch
    # the direct fit to the outline is a different (longer) ellipse: say which one
    m = cp.measure(patch, axis=0.0)
    assert m.ellipse_direct.length > 1.05 * e.length
    assert_allclose(m.area, patch.area, rtol=1e-4)
