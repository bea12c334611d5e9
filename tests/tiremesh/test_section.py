"""Rotta cross section: section 5.1, Tables 5-3 and 5-4, equations 5-7, 5-8, 5-9,
5-10, 5-11, 5-12, 5-13 and 5-14."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

import tiremesh as tm
from tiremesh.section import bulge_ratio, camber_delta_iteration, solve_bulge_angle

from .reference import reference_section

R0, W = 14.0, 15.0  # Table 5-1: 28 mm tire on a 15 mm rim
GAMMA = math.radians(45)


def test_slice_displacements_table_5_3():
    # Table 5-3 (section 5.1): 5 mm in the wheel plane at 45 degrees camber
    dv = 5 * math.cos(GAMMA)
    dh = dv * math.tan(GAMMA)
    assert_allclose([dv, dh, math.hypot(dv, dh)], [3.5355, 3.5355, 5.0], atol=5e-5)


def test_camber_delta_iteration_table_5_4():
    # Table 5-4 (section 5.1): delta 9.8995 -> 10.9956 after one correction; the
    # correction is exact after one step (fixed point r0 * camber), to machine precision
    d = camber_delta_iteration(R0, W, 5 * math.cos(GAMMA), GAMMA, steps=4)
    assert_allclose(d[0], 9.8995, atol=5e-5)
    assert_allclose(d[1], 10.9956, atol=5e-5)
    assert_allclose(d[1:], R0 * GAMMA, rtol=0, atol=1e-12)


def test_solve_sections_table_5_4():
    # Table 5-4 (section 5.1): edges -0.7780 / 9.7218, lowest point 3.5355 from both sides
    dv = 5 * math.cos(GAMMA)
    s = tm.solve_sections(R0, W, dv, dv * math.tan(GAMMA), GAMMA)
    assert_allclose(s.edge1, -0.7780, atol=5e-3)
    assert_allclose(s.edge2, 9.7218, atol=5e-3)
    assert_allclose(s.lowest1, 3.5355, atol=5e-5)
    assert_allclose(s.lowest2, 3.5355, atol=5e-5)
    assert_allclose(s.lowest1, s.lowest2, rtol=0, atol=1e-12)
    assert_allclose(s.delta, R0 * GAMMA, rtol=1e-15)


def test_solve_sections_uncambered_symmetric():
    s = tm.solve_sections(R0, W, np.linspace(0.1, 10, 50))
    assert_allclose(s.edge1, -s.edge2, atol=1e-12)
    assert_allclose(s.radius1, s.radius2, rtol=1e-13)
    assert_allclose(s.lateral_force_density(0.4), 0.0, atol=1e-12)


def test_solve_sections_zero_deflection_is_undeformed():
    # touching without deflection: both bulges are the undeformed circle
    s = tm.solve_sections(R0, W, 0.0)
    assert_allclose([s.edge1, s.edge2], 0.0, atol=1e-12)
    assert_allclose([s.radius1, s.radius2], R0, rtol=1e-12)


def test_bulge_ratio_inverse_round_trip():
    theta = np.linspace(1e-4, 2 * np.pi - 1e-3, 20001)
    q, _ = bulge_ratio(theta)
    assert_allclose(solve_bulge_angle(q), theta, rtol=0, atol=1e-11)


section_cases = st.tuples(
    st.floats(8.0, 30.0),  # r0
    st.floats(0.3, 0.85),  # rim width / (2 r0)
    st.floats(0.02, 0.45),  # dv / rim height
    st.floats(-0.25, 0.25),  # dh / r0
    st.floats(-60.0, 60.0),  # camber [deg]
)


@settings(max_examples=250, deadline=None)
@given(section_cases)
def test_solve_sections_matches_scalar_reference(case):
    # section 5.1: vectorized Newton vs one brentq per side and the appendix's delta loop
    r0, wr, dvr, dhr, gdeg = case
    w = 2 * r0 * wr
    h = r0 * (1 + math.sqrt(1 - wr * wr))
    g = math.radians(gdeg)
    dv = dvr * h * math.cos(g)
    dh = dhr * r0 + dv * math.tan(g)
    try:
        s = tm.solve_sections(r0, w, dv, dh, g)
    except tm.InvalidParameter:
        return  # outside Rotta's construction: the reference cannot solve it either
    ref = reference_section(r0, w, dv, dh, g)
    assert_allclose([s.edge1, s.edge2], [ref["e1"], ref["e2"]], rtol=0, atol=1e-8)
    assert_allclose([s.radius1, s.radius2], [ref["r1"], ref["r2"]], rtol=1e-9, atol=1e-8)
    assert_allclose(s.delta, ref["delta"], atol=1e-9)


@settings(max_examples=200, deadline=None)
@given(section_cases)
def test_solve_sections_conserves_arc_length(case):
    # section 5.1: s1 + s2 + (e2 - e1) = s0 in every section
    r0, wr, dvr, dhr, gdeg = case
    w = 2 * r0 * wr
    g = math.radians(gdeg)
    h = r0 * (1 + math.sqrt(1 - wr * wr))
    dv = np.linspace(0.02, dvr, 7) * h * math.cos(g)
    try:
        s = tm.solve_sections(r0, w, dv, dhr * r0 + dv * math.tan(g), g)
    except tm.InvalidParameter:
        return
    s0 = r0 * (2 * math.pi - 2 * math.asin(wr))
    assert_allclose(s.arc1 + s.arc2 + s.width, s0, rtol=1e-12)
    assert_allclose(s.lowest1, s.lowest2, atol=1e-10)


@settings(max_examples=100, deadline=None)
@given(section_cases)
def test_solve_sections_mirror_symmetry(case):
    # camber -> -camber and dh -> -dh mirrors the section: edges swap, force flips
    r0, wr, dvr, dhr, gdeg = case
    w, g = 2 * r0 * wr, math.radians(gdeg)
    dv = dvr * r0 * math.cos(g)
    dh = dhr * r0 + dv * math.tan(g)
    try:
        a = tm.solve_sections(r0, w, dv, dh, g)
        b = tm.solve_sections(r0, w, dv, -dh, -g)
    except tm.InvalidParameter:
        return
    assert_allclose([a.edge1, a.edge2], [-b.edge2, -b.edge1], atol=1e-10)
    assert_allclose(a.lateral_force_density(0.4), -b.lateral_force_density(0.4), atol=1e-10)


def test_width_sensitivities_match_finite_differences():
    eps = 1e-6
    args = (R0, W)
    s = tm.solve_sections(*args, 3.0, 1.0, 0.3)
    ddv = (
        tm.solve_sections(*args, 3 + eps, 1.0, 0.3).width
        - tm.solve_sections(*args, 3 - eps, 1.0, 0.3).width
    ) / (2 * eps)
    ddh = (
        tm.solve_sections(*args, 3.0, 1 + eps, 0.3).width
        - tm.solve_sections(*args, 3.0, 1 - eps, 0.3).width
    ) / (2 * eps)
    assert_allclose([s.dwidth_ddv, s.dwidth_ddh], [ddv, ddh], rtol=1e-7)


@pytest.mark.parametrize(
    ("args", "match"),
    [
        ((R0, W, math.nan), "vert_deflection"),
        ((R0, W, 3.0, math.inf), "horz_deflection"),
        ((R0, W, 3.0, 0.0, math.pi / 2), "camber"),
        ((R0, W, 30.0), "vert_deflection"),  # bead below the ground
        ((R0, W, 3.0, 60.0), "horz_deflection"),  # bulge runs out of carcass
        ((-R0, W, 3.0), "tire_radius"),
        ((R0, 30.0, 3.0), "rim_width"),
    ],
)
def test_solve_sections_invalid(args, match):
    with pytest.raises(tm.InvalidParameter, match=match):
        tm.solve_sections(*args)
