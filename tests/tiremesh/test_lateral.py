"""Lateral mechanics (issue 6): sections 2.4, 5.6 to 5.9, 6.1, 6.2, 7.3.4."""

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

import tiremesh as tm
from tiremesh.beam import (
    beam_rotta,
    infinite_beam_point_load,
    solve_beam,
    tension_area,
    tension_hoop,
)
from tiremesh.lateral import Relaxation, solve_lateral, stiffnesses, tangent_rule
from tiremesh.mesh import build_mesh

T37 = tm.TireGeometry.from_size(37, 18.7)
BAR = 0.1


def r_squared(x, y):
    a = np.polyfit(x, y, 1)
    return 1 - np.sum((np.polyval(a, x) - y) ** 2) / np.sum((y - np.mean(y)) ** 2)


@pytest.mark.parametrize("relaxation", [0.0, 0.993])
def test_lateral_force_linear_in_displacement_section_6_1_3(relaxation):
    # section 6.1.3: lateral force grows linearly with the lateral displacement
    d = np.linspace(0.1, 2.0, 8)
    f = [
        solve_lateral(
            T37, load=400.0, pressure=4 * BAR, lateral=x, relaxation=relaxation
        ).lateral_force
        for x in d
    ]
    assert r_squared(d, f) >= 0.999
    assert np.all(np.diff(f) > 0)


def test_lateral_stiffness_nearly_linear_in_rim_width_section_6_2_2():
    # section 6.2.2 (Figure 6-4): lateral stiffness varies almost linearly with rim width
    rims = np.array([13.4, 15.0, 17.0, 18.7, 21.0, 24.0])
    k = [
        tm.solve(
            tm.TireGeometry.from_size(37, w), load=400.0, pressure=4 * BAR, lateral=1.0
        ).lateral_force
        for w in rims
    ]
    assert r_squared(rims, k) >= 0.98
    assert np.all(np.diff(k) > 0)


def test_normalized_lateral_stiffness_trends_section_6_2_4():
    # section 6.2.4 item 1: normalized lateral stiffness rises with pressure and falls with
    # load, for every catalogue tire over the dissertation's ranges (3-11 bar, 304-731 N)
    for tire in tm.load_catalog():
        g = tire.geometry()
        kp = [
            tm.solve(g, load=450.0, pressure=p * BAR, lateral=1.0).lateral_force / 450
            for p in (3, 5, 7, 9, 11)
        ]
        kl = [
            (lambda s: s.lateral_force / s.vertical_force)(
                tm.solve(g, load=f, pressure=6 * BAR, lateral=1.0)
            )
            for f in (304, 450, 600, 731)
        ]
        assert np.all(np.diff(kp) > 0), tire.name
        assert np.all(np.diff(kl) < 0), tire.name


def test_camber_thrust_deficiency_section_6_1_4():
    # section 6.1.4: the deficiency against the tangent rule falls as sinkage falls, and a
    # wide enough rim turns it into a surplus (Figure 6-2)
    cases = [
        solve_lateral(T37, load=400.0, pressure=p * BAR, camber=math.radians(10))
        for p in (2, 4, 6, 8, 11)
    ]
    sinkage = [c.patch.sinkage for c in cases]
    deficiency = [stiffnesses(c)["camber_thrust_deficiency"] for c in cases]
    assert np.all(np.diff(sinkage) < 0) and np.all(np.diff(deficiency) < 0)
    assert deficiency[0] > 0
    wide = solve_lateral(
        tm.TireGeometry.from_size(37, 34.0), load=400.0, pressure=4 * BAR, camber=math.radians(10)
    )
    assert stiffnesses(wide)["camber_thrust_deficiency"] < 0


def test_tangent_rule_section_2_4():
    # Eq. 2-5: tan(1 deg) = 0.017455 /deg, within 1 % up to 10 degrees; the approximation
    # is about 21 % too low at 45 degrees
    assert_allclose(tangent_rule(1.0), 0.017455064928218, rtol=1e-12)
    assert_allclose(tangent_rule(0.0), math.pi / 180, rtol=1e-12)
    assert abs(tangent_rule(10.0) / 0.017455064928218 - 1) < 0.011
    assert_allclose(1 - 0.017455064928218 / tangent_rule(45.0), 0.21, atol=0.01)


@pytest.mark.parametrize("rate", [0.99, 0.993, 0.998])
def test_beyond_patch_decay_length_eq_5_29(rate):
    # Eq. 5-28, 5-29: with relaxation rate i the displacement falls to 1/e over 1/(1 - i)
    r = solve_lateral(T37, load=400.0, pressure=4 * BAR, lateral=1.0, relaxation=rate)
    assert_allclose(r.relaxation_length, [1 / (1 - rate)] * 2, rtol=1e-6)
    beyond = ~r.in_patch
    assert np.all(r.dN[beyond] == 0) and r.beyond_lateral_force > 0
    lead = r.s > r.patch.x[-1]
    assert np.all(np.diff(np.abs(r.dh[lead])) <= 1e-12)


def test_beyond_patch_relaxation_sides_are_separate():
    r = solve_lateral(
        T37,
        load=400.0,
        pressure=4 * BAR,
        lateral=1.0,
        relaxation=Relaxation(lead_out=0.99, trail_out=0.998),
    )
    assert_allclose(r.relaxation_length, [500.0, 100.0], rtol=1e-6)


@pytest.mark.parametrize(
    "kw", [dict(lateral=1.0), dict(camber=math.radians(20)), dict(slip=math.radians(1))]
)
def test_friction_limits(kw):
    # section 5.6: infinite friction reproduces the no-slide result; friction 0 carries no
    # lateral force; a finite coefficient lowers it and makes sections slide
    base = solve_lateral(T37, load=400.0, pressure=4 * BAR, relaxation=0.993, **kw)
    inf = solve_lateral(
        T37, load=400.0, pressure=4 * BAR, relaxation=0.993, friction=math.inf, **kw
    )
    assert_allclose(inf.lateral_force, base.lateral_force, rtol=1e-12)
    assert not base.sliding.any()
    zero = solve_lateral(T37, load=400.0, pressure=4 * BAR, relaxation=0.993, friction=0.0, **kw)
    assert abs(zero.lateral_force) < 1e-6 * abs(base.lateral_force)
    mu = 0.5 * abs(base.lateral_force) / base.vertical_force
    one = solve_lateral(T37, load=400.0, pressure=4 * BAR, relaxation=0.993, friction=mu, **kw)
    assert abs(one.lateral_force) < abs(base.lateral_force) and one.sliding.any()
    # gripping sections keep their demand (their ground reaction) within mu dN
    grip = ~one.sliding[one.in_patch]
    dn = one.dN[one.in_patch]
    assert np.all(np.abs(one.reaction[grip]) <= mu * dn[grip] * (1 + 1e-9))


def test_slip_gives_cornering_force_and_positive_trail():
    a = [0.25, 0.5, 1.0]
    rs = [
        solve_lateral(T37, load=400.0, pressure=4 * BAR, slip=math.radians(x), relaxation=0.993)
        for x in a
    ]
    c = [stiffnesses(r)["norm_cornering_stiffness_1_deg"] for r in rs]
    assert_allclose(c, c[0], rtol=0.02) and 0.05 < c[0] < 0.5  # linear at small slip
    assert all(r.pneumatic_trail > 0 for r in rs)
    centre = solve_lateral(
        T37, load=400.0, pressure=4 * BAR, slip=math.radians(1), slip_kinematics="centre"
    )
    assert abs(centre.lateral_force) < 1e-6  # Appendix C's centred turn: no net force


def test_beam_matches_closed_form_point_load():
    # section 5.9: FD taut beam on a uniform foundation vs the infinite-beam solution
    x = np.linspace(-2000.0, 2000.0, 4001)
    for T in (0.0, 150.0, 430.0, 2500.0):
        f = np.zeros_like(x)
        f[2000] = 10.0 / (x[1] - x[0])
        u = solve_beam(x, EI=4.5e6, T=T, k=0.09, f=f)
        ua = infinite_beam_point_load(x, EI=4.5e6, T=T, k=0.09, P=10.0)
        assert_allclose(u, ua, atol=1e-4 * ua.max())


def test_tension_estimates_section_5_9_3_3():
    # Eq. 5-32 gives about twice Eq. 5-33 for a 28-622 tire
    t = tm.TireGeometry.from_size(28, 15)
    ratio = tension_area(0.5, t.tire_radius) / tension_hoop(0.5, t.wheel_radius, t.tire_radius)
    assert 1.4 < ratio < 2.6


def test_beam_rotta_iteration_section_7_3_4():
    # 7.3.4: with force and stiffness rates both taken at the current displacement the
    # iteration settles near wherever it starts; a consistent linearization does not
    patch = tm.solve(T37, load=400.0, pressure=4 * BAR, camber=math.radians(10))
    consistent = [beam_rotta(patch, start=s).net_force_orientation for s in (0.0, 1.0, 2.0)]
    assert_allclose(consistent, consistent[0], rtol=1e-6)
    assert consistent[0] > patch.net_force_orientation  # deflection beyond the patch adds thrust
    dissertation = [
        beam_rotta(patch, start=s, method="dissertation").net_force_orientation
        for s in (0.0, 1.0, 2.0)
    ]
    assert np.all(np.diff(dissertation) > 0.01)  # depends on the start


def test_mesh_shows_deformed_centreline():
    r = solve_lateral(T37, load=400.0, pressure=4 * BAR, lateral=2.0, relaxation=0.99)
    plain = build_mesh(r.patch, n_around=240)
    bent = build_mesh(r.patch, n_around=240, centreline=(r.s, r.dh))
    far = np.abs(np.angle(np.exp(1j * bent.section_phi[bent.point_data["section"]]))) > 0.6
    near = ~far & (bent.point_data["contact"] == 0)
    assert (
        bent.point_data["lateral_displacement"][near].mean()
        > plain.point_data["lateral_displacement"][near].mean()
    )
    assert bent.mesh.is_winding_consistent


def test_solve_lateral_invalid():
    with pytest.raises(tm.InvalidParameter, match="friction"):
        solve_lateral(T37, load=400.0, pressure=0.4, friction=-1)
    with pytest.raises(tm.InvalidParameter, match="relaxation"):
        solve_lateral(T37, load=400.0, pressure=0.4, relaxation=1.5)
    with pytest.raises(tm.InvalidParameter, match="slip_kinematics"):
        solve_lateral(T37, load=400.0, pressure=0.4, slip_kinematics="middle")
    with pytest.raises(tm.InvalidParameter, match="method"):
        beam_rotta(tm.solve(T37, load=400.0, pressure=0.4), method="magic")


def test_slip_kinematics_relaxation_moves_the_anchor_ahead():
    # Figure 4-15: the tread is displaced ahead of the leading edge; with the
    # stretched-string continuity the undisplaced point lies one decay length ahead
    # (1 / (1 - 0.993) = 142.9 mm): more cornering force, a shorter trail
    case = tm.LoadCase(T37, pressure=4 * BAR, load=400.0, slip=math.radians(1), relaxation=0.993)
    lead = solve_lateral(case)
    relax = solve_lateral(case.replace(slip_kinematics="relaxation"))
    assert abs(relax.lateral_force) > abs(lead.lateral_force)
    assert 0 < relax.pneumatic_trail < lead.pneumatic_trail
    # the patch displacement is the leading one shifted by the decay length x tan(slip)
    shift = relax.patch.sections.horz_deflection - lead.patch.sections.horz_deflection
    # (to 0.1 %: the patch ends and x move slightly with the new displacement)
    assert_allclose(shift, -(1 / (1 - 0.993)) * math.tan(math.radians(1)), rtol=2e-3)
    # without relaxation beyond the patch the two kinematics coincide
    zero = case.replace(relaxation=0.0)
    assert_allclose(
        tm.solve(zero.replace(slip_kinematics="relaxation")).lateral_force,
        tm.solve(zero).lateral_force,
        rtol=1e-12,
    )
