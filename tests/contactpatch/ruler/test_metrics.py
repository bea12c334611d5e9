"""contactpatch.ruler.metrics: shared patch metrics (section 4.1.1)."""

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


def test_measure_boundary_samples_is_an_option():
    e = cp.EllipseFit((0.0, 0.0), 60.0, 12.0, 0.0)
    poly = shapely.Polygon(e.boundary(500))
    coarse = cp.measure(poly, boundary_samples=12)
    fine = cp.measure(poly)  # default: 360 points along the hull
    assert_allclose(fine.ellipse_direct.length, 60.0, rtol=1e-3)
    assert coarse.ellipse_direct and coarse.ellipse_direct.length != fine.ellipse_direct.length
    with pytest.raises(cp.InvalidInput, match="boundary_samples"):
        cp.measure(poly, boundary_samples=4)


def test_measure_net_area_and_centroid_of_an_outline():
    hull = shapely.box(0, 0, 20, 10)
    m = cp.measure(hull, net_area=150.0, net_centroid=(9.0, 5.0))
    assert_allclose([m.area, m.hull_area, m.solidity], [150.0, 200.0, 0.75])
    assert m.centroid == (9.0, 5.0)
    with pytest.raises(cp.InvalidInput, match="net_area"):
        cp.measure(hull, net_area=250.0)


def test_measure_outline_array_and_patch_like_object():
    ring = np.array([[0, 0], [40, 0], [40, 8], [0, 8], [0, 0]], float)

    class Patch:
        outline = ring

    a, b = cp.measure(ring), cp.measure(Patch())
    assert_allclose([a.length, a.width, a.area], [40, 8, 320])
    assert_allclose([b.length, b.width, b.area], [40, 8, 320])


def test_measure_follows_the_footprint_the_case_asks_for():
    """contactpatch.measure of a solved patch measures its case's footprint (the plain
    outline by default, bit for bit)."""
    case = tm.LoadCase(tm.get_tire(6), pressure=0.6895, load=304.0)
    plain = tm.solve(case)
    rounded = tm.solve(case.replace(footprint=tm.Footprint("rounded")))
    assert cp.measure(plain).area == cp.measure(plain.outline).area
    m = cp.measure(rounded)
    assert_allclose(m.area, rounded.footprint.area, rtol=1e-9)
    assert m.length < cp.measure(plain).length
