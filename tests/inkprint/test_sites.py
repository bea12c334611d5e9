"""Tests of inkprint.sites: a fine tread's lattice fitted to its elements' centres,
and the distance of a speck from the nearest site."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

from inkprint.errors import InvalidInput
from inkprint.sites import FIT_SHARE, fit_lattice, nearest_site, site_distance


def _lattice_points(step, turn_deg, skew_deg, ratio, n=(5, 4), noise=0.0, seed=0):
    """Sites ``i a + j b`` (|a| = step, b at ``skew_deg`` to a, |b| = ratio x step),
    the lattice turned ``turn_deg``, shifted off the origin, with pixel noise."""
    t, s = np.radians(turn_deg), np.radians(turn_deg + skew_deg)
    basis = np.array([[np.cos(t), np.sin(t)], [np.cos(s), np.sin(s)]]) * [[step], [ratio * step]]
    ij = np.array([(i, j) for i in range(n[0]) for j in range(n[1])], float)
    rng = np.random.default_rng(seed)
    return ij @ basis + [37.3, 81.9] + rng.normal(0.0, noise, (len(ij), 2)), basis


@settings(max_examples=60, deadline=None)
@given(
    step=st.floats(8.0, 60.0),
    turn=st.floats(0.0, 180.0),
    skew=st.floats(50.0, 130.0),
    ratio=st.floats(0.8, 1.25),
)
def test_fit_lattice_recovers_the_sites(step, turn, skew, ratio):
    # every site of the lattice, inside the field and beyond it, is at distance 0;
    # a cell's centre is half a cell's diagonal off (the nearer of its two)
    pts, basis = _lattice_points(step, turn, skew, ratio)
    lat = fit_lattice(pts)
    assert lat is not None
    assert_allclose(site_distance(lat, pts), 0.0, atol=1e-6 * step)
    far = pts[0] + 7 * basis[0] - 3 * basis[1]  # (outside the fitted field)
    assert site_distance(lat, far[None])[0] == pytest.approx(0.0, abs=1e-6 * step)
    mid = pts[0] + 0.5 * (basis[0] + basis[1])
    half = 0.5 * min(np.hypot(*(basis[0] + basis[1])), np.hypot(*(basis[0] - basis[1])))
    assert site_distance(lat, mid[None])[0] == pytest.approx(half, rel=1e-6)


def test_fit_lattice_with_noise_reports_its_misfit():
    pts, _ = _lattice_points(26.0, 10.0, 60.0, 1.0, n=(6, 5), noise=0.5, seed=3)
    lat = fit_lattice(pts)
    assert lat is not None
    assert 0.2 < lat.misfit < 1.0
    assert lat.step == pytest.approx(26.0, rel=0.05)


def test_fit_lattice_outvotes_a_stray_centre():
    # a slick centre's centroid among the elements' (one in 21)
    pts, _ = _lattice_points(20.0, 0.0, 90.0, 1.0, n=(7, 3))
    lat = fit_lattice(np.vstack([pts, pts.mean(axis=0) + np.array([3.0, 7.0])]))
    assert lat is not None
    assert_allclose(site_distance(lat, pts), 0.0, atol=1e-6)


@pytest.mark.parametrize(
    "pts",
    [
        np.array([[0.0, 0.0], [10.0, 0.0], [0.0, 10.0], [10.0, 10.0], [20.0, 0.0]]),  # too few
        np.column_stack([np.arange(12) * 9.0, np.zeros(12)]),  # a row
    ],
    ids=["few", "row"],
)
def test_fit_lattice_none_without_two_directions_of_six_centres(pts):
    assert fit_lattice(pts) is None


def test_fit_lattice_none_for_a_scatter():
    # centres of all spacings (a label's bits): they miss any lattice's sites
    rng = np.random.default_rng(5)
    misses = [fit_lattice(rng.uniform(0, 100, (20, 2))) for _ in range(20)]
    assert sum(m is None for m in misses) >= 18
    for m in misses:
        assert m is None or m.misfit <= FIT_SHARE * m.step


def test_fit_lattice_and_sites_refuse_points_not_k_by_2_finite():
    # a flat array is not paired up as (x, y) (a guess), NaN is no centre
    pts, _ = _lattice_points(20.0, 0.0, 90.0, 1.0, n=(4, 3))
    lat = fit_lattice(pts)
    with pytest.raises(InvalidInput, match=r"^centres = \(24,\) .*\(k, 2\)"):
        fit_lattice(pts.ravel())
    with pytest.raises(InvalidInput, match=r"^centres = 'non-finite values'"):
        fit_lattice(np.vstack([pts, [[np.nan, 1.0]]]))
    for fn in (nearest_site, site_distance):
        with pytest.raises(InvalidInput, match=r"^points = \(3, 3\)"):
            fn(lat, np.zeros((3, 3)))


def test_fit_lattice_reach_finds_an_elongated_staggered_lattice():
    # knobs 12 px apart along a column, columns 17 px apart, every other one shifted
    # half a step: the diagonal (18.0 px) is 1.5 x the nearest step, beyond the
    # usual reach; within reach=1.9 the lattice is found and its sites are the knobs'
    i, j = np.meshgrid(np.arange(6), np.arange(6))
    pts = np.column_stack([17.0 * i.ravel(), 12.0 * j.ravel() + 6.0 * (i.ravel() % 2)])
    assert fit_lattice(pts) is None
    lat = fit_lattice(pts, reach=1.9)
    assert lat is not None
    assert_allclose(site_distance(lat, pts), 0.0, atol=1e-6)
    assert_allclose(site_distance(lat, np.array([[8.5, 3.0]])), np.hypot(8.5, 3.0), rtol=1e-6)


@pytest.mark.parametrize("reach", [1.0, 2.0, 0.5, np.nan])
def test_fit_lattice_reach_outside_1_2_raises(reach):
    pts, _ = _lattice_points(20.0, 0.0, 90.0, 1.0, n=(4, 3))
    with pytest.raises(InvalidInput, match=r"^reach = .*1 < reach < 2"):
        fit_lattice(pts, reach=reach)
