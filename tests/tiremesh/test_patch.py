"""3D Rotta model: sections 5.2 to 5.5, Figure 5-15, drums and disks (5.3, 7.2)."""

import math

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from numpy.testing import assert_allclose

import tiremesh as tm

BIG_APPLE = tm.TireGeometry.from_arc_length(128.2, 18.7)  # Table 3-2 tire 8
T37 = tm.TireGeometry.from_size(37, 18.7)  # sections 5.3 and 7.2: r0 = 18.5 mm
BAR = 0.1


def polygon_area(xy):
    x, y = xy[:, 0], xy[:, 1]
    return 0.5 * float(np.sum(x[:-1] * y[1:] - x[1:] * y[:-1]))


def test_solve_patch_figure_5_15():
    # Figure 5-15 (section 5.4; configuration in published-values.md): 128.2 mm carcass,
    # 18.7 mm rim, 5 mm deflection, flat -> length 118.7 mm, width 9.917 mm, area 795.5 mm^2
    p = tm.solve_patch(BIG_APPLE, 5.0, pressure=4 * BAR)
    assert_allclose(p.length, 118.7, rtol=5e-3)
    assert_allclose(p.width, 9.917, rtol=5e-3)
    assert_allclose(p.area, 795.5, rtol=5e-3)


def test_solve_patch_independent_of_section_count():
    # the patch ends are exact roots, so the results converge (spectrally) with n
    ref = tm.solve_patch(BIG_APPLE, 5.0, pressure=4 * BAR, camber=0.3, n_sections=2001)
    for n in (33, 65, 201):
        p = tm.solve_patch(BIG_APPLE, 5.0, pressure=4 * BAR, camber=0.3, n_sections=n)
        assert_allclose(p.length, ref.length, rtol=1e-12)
        assert_allclose([p.area, p.lateral_force], [ref.area, ref.lateral_force], rtol=1e-9)
        assert_allclose(p.width, ref.width, rtol=1e-4)


def test_solve_patch_ends_are_exact_roots():
    # section 5.2: the patch ends are where the section width reaches zero
    for kw in (
        dict(),
        dict(camber=0.6),
        dict(lateral=0.8),
        dict(slip=0.05),
        dict(surface=tm.Drum(2500)),
    ):
        p = tm.solve_patch(T37, 5.0, pressure=4 * BAR, **kw)
        assert_allclose(p.sections.width[[0, -1]], 0.0, atol=1e-9)
        assert np.all(p.sections.width[1:-1] > 0)


def test_solve_patch_flat_end_closed_form():
    # flat, no camber: the ends are where dv(phi) = 0, cos(phi) = (R - dw) / R (Eq. 5-17)
    p = tm.solve_patch(T37, 5.0, pressure=4 * BAR)
    R = T37.wheel_radius
    phi = math.acos((R - 5.0) / R)
    assert_allclose(p.phi[[0, -1]], [-phi, phi], rtol=1e-12)
    assert_allclose(p.length, 2 * (R - 5.0) * math.tan(phi), rtol=1e-12)


def test_solve_patch_outline_area_matches_integral():
    p = tm.solve_patch(T37, 5.0, pressure=4 * BAR, n_sections=801)
    assert_allclose(polygon_area(p.outline), p.area, rtol=1e-5)
    assert np.allclose(p.outline[0], p.outline[-1])
    assert polygon_area(p.outline) > 0  # counter-clockwise


@pytest.fixture(scope="module")
def camber_thrust():
    # sections 5.3, 7.2: 37 mm tire, 18.7 mm rim, 4 bar, 400 N, 45 degrees camber;
    # the printed values use Appendix C's length element (force_convention="appendix")
    kw = dict(load=400.0, pressure=4 * BAR, camber=math.radians(45), force_convention="appendix")
    return {
        "flat": tm.solve(T37, **kw),
        "drum": tm.solve(T37, surface=tm.Drum(2500), **kw),
        "toward": tm.solve(T37, surface=tm.Disk(3000, "toward"), **kw),
        "away": tm.solve(T37, surface=tm.Disk(3000, "away"), **kw),
    }


def test_camber_thrust_flat_section_7_2(camber_thrust):
    # section 7.2.2: 214.3 N on a straight track (the printed appendix code's value;
    # the issue asks 2 %, the model gives 214.45 N)
    assert_allclose(camber_thrust["flat"].lateral_force, 214.3, rtol=0.005)
    assert_allclose(camber_thrust["flat"].vertical_force, 400.0, rtol=1e-9)


def test_camber_thrust_drum_section_5_3_1(camber_thrust):
    # sections 5.3.1, 7.2.2: a 2.5 m drum lowers camber thrust by 2 to 3 % (1 to 4 % asked)
    ratio = camber_thrust["drum"].lateral_force / camber_thrust["flat"].lateral_force
    assert 0.96 <= ratio <= 0.99
    assert_allclose(camber_thrust["drum"].lateral_force, 208.5, rtol=0.005)  # 7.2.2


def test_camber_thrust_disk_section_5_3_2(camber_thrust):
    # sections 5.3.2, 7.2.3: a 3 m disk changes camber thrust by 1 to 6 % in opposite
    # directions for the two curvature directions; their mean is within 1 % of flat.
    # 5.3.2 and 7.2.3 disagree on the direction; like 7.2.3 the model gives more thrust
    # when the track curves away from the camber (see docs/model.md).
    flat = camber_thrust["flat"].lateral_force
    toward = camber_thrust["toward"].lateral_force / flat
    away = camber_thrust["away"].lateral_force / flat
    assert 0.94 <= toward <= 0.99
    assert 1.01 <= away <= 1.06
    assert_allclose(0.5 * (toward + away), 1.0, atol=0.01)


def test_disk_offset_matches_appendix_constant(camber_thrust):
    # section 5.3.2 offset, which Appendix C hard-codes as 1.4 mm; the exact offset
    # depends on the deflection (1.395 mm at 6 mm, 1.34 mm at the 400 N deflection)
    assert_allclose(abs(camber_thrust["toward"].disk_offset), 1.4, atol=0.1)
    p = tm.solve_patch(T37, 6.0, pressure=4 * BAR, camber=math.radians(45), surface=tm.Disk(3000))
    assert_allclose(abs(p.disk_offset), 1.4, atol=0.01)


def test_drum_patch_is_shorter_than_flat():
    flat = tm.solve(T37, load=400.0, pressure=4 * BAR)
    drum = tm.solve(T37, load=400.0, pressure=4 * BAR, surface=tm.Drum(2500))
    assert drum.length < flat.length
    assert drum.width > flat.width  # same area: the drum patch is shorter and wider


cases = st.tuples(
    st.floats(2.0, 8.0),  # deflection
    st.floats(-50.0, 50.0),  # camber [deg]
    st.floats(-1.0, 1.0),  # lateral [mm]
    st.floats(-3.0, 3.0),  # slip [deg]
    st.sampled_from(["flat", "drum:2500", "disk:3000:toward", "disk:3000:away"]),
)


@settings(max_examples=40, deadline=None)
@given(cases)
@example((2.0, 5e-324, 0.0, 0.0, "disk:3000:toward"))  # camber underflows to 0 rad
def test_solve_patch_mirror_symmetry(case):
    # camber, slip and lateral -> their negatives mirror the patch (y -> -y) and flip
    # the lateral force (section 5.1 sign conventions)
    dw, g, lat, a, surf = case
    kw = dict(pressure=4 * BAR, surface=tm.parse_surface(surf), n_sections=65)
    try:
        p = tm.solve_patch(
            T37, dw, camber=math.radians(g), lateral=lat, slip=math.radians(a), **kw
        )
    except tm.TireModelError:
        return
    if math.radians(g) == 0 and surf.startswith(
        "disk"
    ):  # no camber (a denormal g underflows): toward = centre on +y
        kw["surface"] = tm.Disk(3000, "away" if surf.endswith("toward") else "toward")
    q = tm.solve_patch(T37, dw, camber=-math.radians(g), lateral=-lat, slip=-math.radians(a), **kw)
    assert_allclose(q.lateral_force, -p.lateral_force, atol=1e-9 * abs(p.vertical_force))
    assert_allclose([q.area, q.length, q.width], [p.area, p.length, p.width], rtol=1e-9)
    assert_allclose(q.outline[:, 1].max(), -p.outline[:, 1].min(), atol=1e-9)


@settings(max_examples=25, deadline=None)
@given(st.floats(1.0, 11.0), st.floats(200.0, 900.0), st.integers(1, 14))
def test_solve_area_times_pressure_is_load(p_bar, load, tire_id):
    # section 6.1.1: patch area x inflation pressure = vertical load (load search to 1e-6)
    tire = tm.get_tire(tire_id)
    try:
        p = tm.solve(tire, load=load, pressure=p_bar * BAR)
    except tm.LoadTooHigh:
        return
    assert_allclose(p.area * p.pressure, load, rtol=1e-6)
    assert_allclose(p.vertical_force, load, rtol=1e-6)


@pytest.mark.parametrize("surface", [tm.Flat(), tm.Drum(2500)])
def test_solve_zero_camber_slip_lateral_gives_no_lateral_force(surface):
    p = tm.solve(T37, load=400.0, pressure=4 * BAR, surface=surface)
    assert abs(p.lateral_force) < 1e-9 * p.vertical_force
    assert abs(p.outline[:, 1].max() + p.outline[:, 1].min()) < 1e-9


def test_disk_without_camber_bends_the_patch():
    # section 5.3.2: on a disk the patch follows the curved track, so even without camber
    # it is bent (ends toward the track centre) and carries a small lateral force
    toward = tm.solve(T37, load=400.0, pressure=4 * BAR, surface=tm.Disk(3000, "toward"))
    away = tm.solve(T37, load=400.0, pressure=4 * BAR, surface=tm.Disk(3000, "away"))
    assert_allclose(toward.lateral_force, -away.lateral_force, rtol=1e-9)
    assert 0 < abs(toward.lateral_force) < 0.05 * toward.vertical_force
    ends_y = toward.centerline[[0, -1], 1]
    assert np.all(ends_y > toward.centerline[len(toward.phi) // 2, 1])


def test_solve_lateral_and_slip_signs():
    # Appendix C: positive lateral displacement pushes the patch to +y and raises force on +y
    lat = tm.solve(T37, load=400.0, pressure=4 * BAR, lateral=1.0)
    assert lat.lateral_force > 0
    slip = tm.solve(
        T37, load=400.0, pressure=4 * BAR, slip=math.radians(1), slip_kinematics="centre"
    )
    front = slip.centerline[slip.centerline[:, 0] > 0]
    assert np.all(front[:, 1] > 0)  # front of the patch turned toward +y


def test_cambered_patch_is_nearly_flat():
    # Figure 5-9: the 3D Rotta patch of a cambered tire is flat to a fraction of a mm
    p = tm.solve_patch(
        tm.TireGeometry.from_size(28, 15), 5.0, pressure=4 * BAR, camber=math.radians(30)
    )
    assert 0 < p.flatness < 0.2
    assert tm.solve_patch(T37, 5.0, pressure=4 * BAR).flatness < 1e-9
    # on a drum the patch follows the drum surface (equations 5-18, 5-19, 5-20, 5-21) to ~0.1 mm
    assert tm.solve_patch(T37, 5.0, pressure=4 * BAR, surface=tm.Drum(2500)).flatness < 0.1


@pytest.mark.parametrize(
    ("kwargs", "exc", "match"),
    [
        (dict(deflection=-1.0), tm.InvalidParameter, "deflection"),
        (dict(deflection=math.nan), tm.InvalidParameter, "deflection"),
        (dict(deflection=40.0), tm.InvalidParameter, "deflection"),
        (dict(deflection=5.0, pressure=0.0), tm.InvalidParameter, "pressure"),
        (dict(deflection=5.0, pressure=math.inf), tm.InvalidParameter, "pressure"),
        (dict(deflection=5.0, camber=math.pi / 2), tm.InvalidParameter, "camber"),
        (dict(deflection=5.0, camber=-2.0), tm.InvalidParameter, "camber"),
        (dict(deflection=5.0, lateral=math.nan), tm.InvalidParameter, "lateral"),
        (dict(deflection=5.0, slip=math.inf), tm.InvalidParameter, "slip"),
        (dict(deflection=5.0, n_sections=3), tm.InvalidParameter, "n_sections"),
        (dict(deflection=0.1, lateral=5.0), tm.NoContact, "edges cross"),
        (dict(deflection=5.0, lateral=40.0), tm.TireModelError, "lateral"),
    ],
)
def test_solve_patch_invalid(kwargs, exc, match):
    kw = dict(pressure=4 * BAR) | kwargs
    with pytest.raises(exc, match=match):
        tm.solve_patch(T37, **kw)


def test_surfaces_invalid():
    with pytest.raises(tm.InvalidParameter, match="drum diameter"):
        tm.Drum(-5)
    with pytest.raises(tm.InvalidParameter, match="curving"):
        tm.Disk(3000, "sideways")
    with pytest.raises(tm.InvalidParameter, match="surface"):
        tm.parse_surface("drum")
    assert tm.parse_surface("disk:3000:away") == tm.Disk(3000.0, "away")


def test_force_convention_ground_vs_appendix():
    # docs/model.md: the true ground length of a cambered slice is shorter than Appendix
    # C's d[(R - dv) sin phi]; upright on flat ground the two are the same
    kw = dict(load=400.0, pressure=4 * BAR)
    for camber, lateral, expected in ((45, 0.0, -0.0183), (10, 0.0, -0.00097), (0, 2.0, 0.0)):
        case = tm.LoadCase(T37, camber=math.radians(camber), lateral=lateral, **kw)
        ground = tm.solve(case).lateral_force
        appendix = tm.solve(case.replace(force_convention="appendix")).lateral_force
        assert_allclose(ground / appendix - 1, expected, atol=2e-4)
    p = tm.solve(T37, **kw)  # upright: the weights sum to the patch length
    assert_allclose(np.sum(p.x_weights), p.length, rtol=1e-6)
