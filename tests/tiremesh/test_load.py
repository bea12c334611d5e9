"""Load search (Appendix C find_sinkage) and sinkage trends (section 6.1.2)."""

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

import tiremesh as tm

BAR = 0.1
T37 = tm.TireGeometry.from_size(37, 18.7)


def r_squared(x, y):
    a = np.polyfit(x, y, 1)
    return 1 - np.sum((np.polyval(a, x) - y) ** 2) / np.sum((y - y.mean()) ** 2)


def test_find_sinkage_hits_load():
    for kw in (
        dict(),
        dict(camber=0.7),
        dict(surface=tm.Drum(2500)),
        dict(lateral=1.0, slip=0.02),
    ):
        dw = tm.find_sinkage(T37, 400.0, pressure=4 * BAR, **kw)
        p = tm.solve_patch(T37, dw, pressure=4 * BAR, **kw)
        assert_allclose(p.vertical_force, 400.0, rtol=1e-6)


def test_find_sinkage_load_too_high_reports_max_load():
    fmax = tm.max_load(T37, pressure=1 * BAR)
    with pytest.raises(tm.LoadTooHigh, match=r"load.*largest load") as info:
        tm.find_sinkage(T37, 2 * fmax, pressure=1 * BAR)
    assert_allclose(info.value.max_load, fmax, rtol=1e-9)
    # just below the maximum is carried
    assert tm.find_sinkage(T37, 0.999 * fmax, pressure=1 * BAR) > 0


@pytest.mark.parametrize("load", [0.0, -5.0, math.nan, math.inf])
def test_find_sinkage_invalid_load(load):
    with pytest.raises(tm.InvalidParameter, match="load"):
        tm.find_sinkage(T37, load, pressure=4 * BAR)


def test_solve_requires_exactly_one_of_load_and_deflection():
    with pytest.raises(tm.InvalidParameter, match="load/deflection"):
        tm.solve(T37, pressure=0.4)
    with pytest.raises(tm.InvalidParameter, match="load/deflection"):
        tm.solve(T37, pressure=0.4, load=400, deflection=5)


@pytest.mark.parametrize("tire_id", [5, 8, 10])
def test_sinkage_linear_in_load_section_6_1_2(tire_id):
    # section 6.1.2: at constant pressure sinkage grows linearly with load (R^2 = 0.999)
    tire = tm.get_tire(tire_id)
    loads = np.linspace(304, 731, 8)  # the dissertation's load range
    for p_bar in (3.0, 4.0):
        s = np.array([tm.find_sinkage(tire, f, pressure=p_bar * BAR) for f in loads])
        assert r_squared(loads, s) >= 0.999


@pytest.mark.parametrize("tire_id", [5, 8, 10])
def test_sinkage_power_of_pressure_section_6_1_2(tire_id):
    # section 6.1.2: at constant load sinkage falls as about pressure^-0.7 (R^2 = 1)
    tire = tm.get_tire(tire_id)
    p = np.linspace(2, 11, 10) * BAR  # the dissertation's pressure range
    for load in (304.0, 400.0):
        s = np.array([tm.find_sinkage(tire, load, pressure=pi) for pi in p])
        slope, _ = np.polyfit(np.log(p), np.log(s), 1)
        assert abs(slope + 0.7) <= 0.05
        assert r_squared(np.log(p), np.log(s)) >= 0.999


def test_solve_many_matches_single_solves():
    rng = np.random.default_rng(0)
    m = 12
    radius = rng.uniform(10, 23, m)
    rim = rng.uniform(13, 19, m)
    pressure = rng.uniform(0.3, 0.8, m)
    load = rng.uniform(250, 600, m)
    camber = rng.uniform(-0.6, 0.6, m)
    drum = np.where(rng.random(m) < 0.5, np.inf, 2500.0)
    surfaces = [tm.Flat() if np.isinf(d) else tm.Drum(d) for d in drum]
    out = tm.solve_many(
        tire_radius=radius,
        rim_width=rim,
        pressure=pressure,
        load=load,
        camber=camber,
        surface=surfaces,
    )
    assert_allclose(out["vertical_force"], load, rtol=1e-6)
    for i in range(m):
        surf = surfaces[i]
        p = tm.solve(
            tm.TireGeometry(radius[i], rim[i]),
            load=load[i],
            pressure=pressure[i],
            camber=camber[i],
            surface=surf,
            n_sections=65,
        )
        assert_allclose(out["deflection"][i], p.deflection, rtol=1e-8)
        assert_allclose(out["lateral_force"][i], p.lateral_force, rtol=1e-7, atol=1e-9)
        assert_allclose([out["length"][i], out["width"][i]], [p.length, p.width], rtol=1e-9)


def test_solve_many_reports_which_load_is_too_high():
    with pytest.raises(tm.LoadTooHigh, match="load = 50000"):
        tm.solve_many(
            tire_radius=[15, 15], rim_width=[15, 15], pressure=[0.4, 0.4], load=[400, 50000]
        )
