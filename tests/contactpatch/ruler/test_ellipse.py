"""contactpatch.ruler.ellipse: ellipse fits (direct, Appendix C least squares, moments)."""

import math

import numpy as np
import pytest
import shapely
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

import contactpatch as cp

ellipses = st.builds(
    lambda cx, cy, a, ratio, ang: cp.EllipseFit((cx, cy), 2 * a, 2 * a / ratio, ang),
    st.floats(-1e4, 1e4),
    st.floats(-1e4, 1e4),
    st.floats(0.05, 500.0),
    st.floats(1.05, 20.0),
    st.floats(-math.pi / 2 + 1e-3, math.pi / 2),
)


def angle_diff(a, b):
    return abs(np.angle(np.exp(2j * (a - b)))) / 2


@settings(max_examples=200, deadline=None)
@given(ellipses, st.integers(6, 200), st.sampled_from([cp.fit_ellipse_direct, cp.fit_ellipse_lsq]))
def test_fit_recovers_exact_ellipse(e, n, fit):
    # any centre, angle, axis ratio up to 20: recovered to 1e-9 relative
    t = np.linspace(0, 2 * np.pi, n, endpoint=False) + 0.3
    a, b = e.length / 2, e.width / 2
    c, s = np.cos(e.angle), np.sin(e.angle)
    pts = np.column_stack(
        [
            e.center[0] + c * a * np.cos(t) - s * b * np.sin(t),
            e.center[1] + s * a * np.cos(t) + c * b * np.sin(t),
        ]
    )
    r = fit(pts)
    assert r, r.reason
    assert_allclose([r.length, r.width], [e.length, e.width], rtol=1e-9)
    assert_allclose(
        r.center, e.center, rtol=0, atol=1e-9 * e.length + 1e-9 * max(map(abs, e.center))
    )
    assert angle_diff(r.angle, e.angle) < 1e-8
    assert -math.pi / 2 < r.angle <= math.pi / 2 and r.length >= r.width


def test_fit_noisy_ellipse():
    rng = np.random.default_rng(3)
    e = cp.EllipseFit((120.0, -40.0), 80.0, 10.0, 0.4)
    pts = e.boundary(400)[:-1] + rng.normal(0, 0.1, (399, 2))
    for fit in (cp.fit_ellipse_direct, cp.fit_ellipse_lsq):
        r = fit(pts)
        assert_allclose([r.length, r.width], [80.0, 10.0], rtol=0.02)
        assert angle_diff(r.angle, 0.4) < 0.01


@pytest.mark.parametrize(
    ("points", "reason"),
    [
        (np.zeros((0, 2)), "need >= 5"),
        ([[0, 0], [1, 1], [2, 0], [3, 3]], "need >= 5"),
        ([[i, 2 * i] for i in range(10)], "collinear"),
        ([[0, 0], [np.nan, 1], [2, 0], [3, 3], [4, 4]], "NaN"),
        (np.ones((3, 3)), "must be"),
    ],
)
def test_fit_degenerate_inputs_fail_softly(points, reason):
    for fit in (cp.fit_ellipse_direct, cp.fit_ellipse_lsq):
        r = fit(points)
        assert not r and reason in r.reason
        assert math.isnan(r.length)


def test_fit_lsq_hyperbola_is_a_failed_fit():
    x = np.linspace(1, 4, 30)
    r = cp.fit_ellipse_lsq(np.column_stack([np.r_[x, -x], np.r_[1 / x, -1 / x]]))
    assert not r and "not an ellipse" in r.reason


def test_ellipse_from_moments_polygon_and_mask():
    e = cp.EllipseFit((3.0, 4.0), 10.0, 4.0, 0.3)
    m = cp.ellipse_from_moments(shapely.Polygon(e.boundary(4000)))
    assert_allclose([m.length, m.width, m.angle], [10, 4, 0.3], rtol=1e-5)
    # a rasterized ellipse, 0.05 units per pixel
    yy, xx = np.mgrid[0:400, 0:400] * 0.05
    u, v = (
        (xx - 10) * np.cos(0.3) + (yy - 10) * np.sin(0.3),
        -(xx - 10) * np.sin(0.3) + (yy - 10) * np.cos(0.3),
    )
    mask = (u / 5) ** 2 + (v / 2) ** 2 <= 1
    mm = cp.ellipse_from_mask(mask, pixel_size=0.05)
    assert_allclose([mm.length, mm.width], [10, 4], rtol=5e-3)
    assert not cp.ellipse_from_mask(np.zeros((5, 5), bool))
    assert not cp.ellipse_from_moments(shapely.Polygon())
