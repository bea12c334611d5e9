"""Surface protocol: Flat, Drum, Disk (section 5.3) and parsing."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

import tiremesh as tm
from tiremesh.surface import curvature_drop

SURFACES = [tm.Flat(), tm.Drum(2500), tm.Disk(3000), tm.Disk(3000, "away")]


@pytest.mark.parametrize("surface", SURFACES)
def test_surface_spec_round_trips_and_meets_protocol(surface):
    assert isinstance(surface, tm.Surface)
    assert tm.parse_surface(surface.spec) == surface
    assert surface.describe()


def test_parse_surface_aliases_and_errors():
    assert tm.parse_surface("plate") == tm.Flat()
    assert tm.parse_surface("disk:3000") == tm.Disk(3000, "toward")
    for bad in ("drum", "drum:x", "disk:3000:sideways", "ice", "flat:3"):
        with pytest.raises(tm.InvalidParameter, match=r"surface|curving"):
            tm.parse_surface(bad)
    for bad in ("drum:100", "drum:-5", "disk:50"):
        with pytest.raises(tm.InvalidParameter, match="diameter"):
            tm.parse_surface(bad)


@pytest.mark.parametrize("surface", SURFACES)
def test_surface_unroll_roll_stretch_consistent(surface):
    x = np.linspace(-400, 400, 41)
    assert_allclose(surface.roll(surface.unroll(x)), x, atol=1e-9)
    h = 1e-4
    fd = (surface.unroll(x + h) - surface.unroll(x - h)) / (2 * h)
    assert_allclose(surface.stretch(x), fd, rtol=1e-7)
    pts = np.column_stack([x, np.zeros_like(x), surface.height(x)])
    assert_allclose(surface.gap(pts), 0.0, atol=1e-9)  # the surface's own points lie on it
    up = pts + np.array([0, 0, 2.0])
    assert np.all(surface.gap(up) > 0)


def test_drum_drop_follows_eq_5_21():
    # section 5.3.1: the drum falls below the contact plane by R_s (1 - cos phi_s) at the
    # ground position x = R sin(phi) = R_s sin(phi_s) (equation 5-20), read along the
    # section's radial line (/ cos phi, equation 5-21)
    R, Rs = 340.0, 1250.0
    phi = np.linspace(-0.3, 0.3, 13)
    drum = tm.Drum(2 * Rs)
    drop, ddrop = drum.drop(phi, R)
    x = R * np.sin(phi)
    assert_allclose(drop, (Rs - np.sqrt(Rs**2 - x**2)) / np.cos(phi), atol=1e-12)
    assert_allclose(drop * np.cos(phi), -drum.height(x), atol=1e-12)
    h = 1e-6
    fd = (drum.drop(phi + h, R)[0] - drum.drop(phi - h, R)[0]) / (2 * h)
    assert_allclose(ddrop, fd, rtol=1e-6, atol=1e-9)


def test_disk_shift_side_follows_camber_and_curving():
    phi = np.array([0.1])
    toward, away = tm.Disk(3000), tm.Disk(3000, "away")
    assert toward.shift(phi, 340.0, 0.2)[0] > 0
    assert toward.shift(phi, 340.0, -0.2)[0] < 0
    assert_allclose(away.shift(phi, 340.0, 0.2)[0], -toward.shift(phi, 340.0, 0.2)[0])
    assert_allclose(tm.Drum(2500).shift(phi, 340.0, 0.2)[0], 0.0)
    assert_allclose(toward.drop(phi, 340.0)[0], 0.0)


@settings(max_examples=60, deadline=None)
@given(st.floats(-0.9, 0.9), st.floats(200.0, 400.0), st.floats(1e-4, 1e-2))
def test_curvature_drop_is_odd_in_curvature(phi, R, k):
    a, da = curvature_drop(phi, R, k)
    b, db = curvature_drop(phi, R, -k)
    assert_allclose(a, -b, rtol=1e-12, atol=1e-12)
    assert_allclose(curvature_drop(phi, R, 0.0)[0], 0.0, atol=0)
    assert math.isfinite(float(da)) and math.isfinite(float(db))
