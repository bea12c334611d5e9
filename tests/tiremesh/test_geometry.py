"""Tire geometry: equations 5-1, 5-2, 5-3, 5-4, 5-5, 5-6; Tables 5-1, 5-2 and 3-2."""

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

import tiremesh as tm
from tiremesh.geometry import rim_angle_from_arc_length


def sig4(x):
    return float(f"{x:.4g}")


def test_from_size_table_5_1():
    # Table 5-1 (section 5.1): 28 mm tire on a 15 mm rim
    t = tm.TireGeometry.from_size(28, 15)
    assert t.tire_radius == 14
    assert sig4(t.rim_angle) == 1.131  # printed 1.1307 rad
    assert_allclose(t.rim_angle, 1.1307, atol=5e-5)
    assert_allclose(t.rim_height, 25.8216, atol=5e-5)
    assert_allclose(t.arc_length, 72.1347, atol=5e-5)


def test_from_arc_length_table_5_2():
    # Table 5-2 (section 5.1): from w = 15 and s0 = 72.1347 recover theta0 and r0
    t = tm.TireGeometry.from_arc_length(72.1347, 15)
    assert_allclose(t.rim_angle, 1.1307, atol=5e-5)
    assert_allclose(t.tire_radius, 14.0, atol=5e-5)
    assert_allclose(t.rim_height, 25.8216, atol=5e-5)


def test_from_arc_length_round_trip_machine_precision():
    for size, rim in [(23, 13.4), (28, 15), (37, 18.7), (55, 25), (20, 19.9)]:
        a = tm.TireGeometry.from_size(size, rim)
        b = tm.TireGeometry.from_arc_length(a.arc_length, rim)
        assert_allclose(b.tire_radius, a.tire_radius, rtol=1e-13)


def test_rim_angle_from_arc_length_vectorized():
    w = np.array([13.4, 15.0, 18.7])
    s0 = np.array([51.5, 72.1347, 128.2])
    th = rim_angle_from_arc_length(w, s0)
    assert_allclose(w / s0, 2 * np.sin(th / 2) / (2 * np.pi - th), rtol=1e-14)


def test_catalog_table_3_2_radii():
    # Table 3-2 (section 3.2) prints radii to 0.1 mm; Eq. 5-6 must reproduce them
    tires = tm.load_catalog()
    assert len(tires) == 14
    for t in tires:
        g = t.geometry()
        assert abs(g.tire_radius - t.tire_radius) < 0.05 + 1e-9, t.name
        assert_allclose(g.arc_length, t.arc_length, rtol=1e-12)


def test_get_tire_by_id_and_name():
    assert tm.get_tire(8).name == "Schwalbe Big Apple 55-622"
    assert tm.get_tire("big apple") == tm.get_tire("8")
    assert tm.get_tire(8, rim_width=25).rim_width == 25
    with pytest.raises(tm.InvalidParameter, match="tire"):
        tm.get_tire("vredestein")  # ambiguous
    with pytest.raises(tm.InvalidParameter, match="tire"):
        tm.get_tire(99)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        (dict(tire_radius=-1, rim_width=10), "tire_radius"),
        (dict(tire_radius=math.nan, rim_width=10), "tire_radius"),
        (dict(tire_radius=10, rim_width=0), "rim_width"),
        (dict(tire_radius=10, rim_width=20), "rim_width"),
        (dict(tire_radius=10, rim_width=5, bead_seat_diameter=math.inf), "bead_seat_diameter"),
    ],
)
def test_tire_geometry_invalid(kwargs, match):
    with pytest.raises(tm.InvalidParameter, match=match):
        tm.TireGeometry(**kwargs)


def test_from_arc_length_rim_too_wide():
    with pytest.raises(tm.InvalidParameter, match=r"rim_width.*2/pi"):
        tm.TireGeometry.from_arc_length(30, 20)
    with pytest.raises(tm.InvalidParameter, match="arc_length"):
        tm.TireGeometry.from_arc_length(-30, 20)
