"""LoadCase and CaseTable: validation at construction, replace, units, batches."""

import math
import pickle

import numpy as np
import pytest
from numpy.testing import assert_allclose

import tiremesh as tm

T = tm.get_tire(1)


def test_loadcase_validates_each_field_by_name():
    base = dict(pressure=0.4, load=400.0)
    for change, name in [
        (dict(pressure=0.0), "pressure"),
        (dict(pressure=math.nan), "pressure"),
        (dict(load=-5.0), "load"),
        (dict(camber=2.0), "camber"),
        (dict(slip=math.inf), "slip"),
        (dict(lateral=math.nan), "lateral"),
        (dict(n_sections=3), "n_sections"),
        (dict(friction=-1.0), "friction"),
        (dict(relaxation=1.5), "relaxation"),
        (dict(slip_kinematics="middle"), "slip_kinematics"),
        (dict(surface="cobbles"), "surface"),
        (dict(pressure=[0.4, 0.5]), "pressure"),
    ]:
        with pytest.raises(tm.InvalidParameter, match=name):
            tm.LoadCase(T, **{**base, **change})
    with pytest.raises(tm.InvalidParameter, match="load/deflection"):
        tm.LoadCase(T, pressure=0.4)
    with pytest.raises(tm.InvalidParameter, match="load/deflection"):
        tm.LoadCase(T, pressure=0.4, load=1.0, deflection=1.0)
    with pytest.raises(tm.InvalidParameter, match="tire"):
        tm.LoadCase("tire 1", pressure=0.4, load=1.0)


def test_loadcase_replace_switches_load_and_deflection():
    c = tm.LoadCase(T, pressure=0.4, load=400.0)
    d = c.replace(deflection=4.0)
    assert d.load is None and d.deflection == 4.0
    assert d.replace(load=300.0).deflection is None
    with pytest.raises(tm.InvalidParameter, match="camber"):
        c.replace(camber=-3.0)
    assert c.load == 400.0  # frozen: the original is untouched


def test_loadcase_from_units_converts_at_the_edge():
    c = tm.LoadCase.from_units(
        T, pressure_bar=4.0, load_N=400.0, camber_deg=45.0, slip_deg=1.0, surface="drum:2500"
    )
    assert_allclose([c.pressure, c.camber, c.slip], [0.4, math.pi / 4, math.radians(1)])
    assert c.surface == tm.Drum(2500)
    d = c.describe()
    assert_allclose([d["pressure_bar"], d["camber_deg"]], [4.0, 45.0])
    assert d["surface"] == "drum:2500"


def test_loadcase_is_hashable_and_picklable():
    c = tm.LoadCase(T, pressure=0.4, load=400.0, surface=tm.Disk(3000, "away"))
    assert pickle.loads(pickle.dumps(c)) == c
    assert {c: 1}[c.replace(load=400.0)] == 1


def test_solve_accepts_case_or_keywords_identically():
    c = tm.LoadCase(T, pressure=0.4, load=400.0, camber=0.3)
    a, b = tm.solve(c), tm.solve(T, pressure=0.4, load=400.0, camber=0.3)
    assert_allclose([a.length, a.width, a.area], [b.length, b.width, b.area], rtol=0, atol=0)
    assert a.case == c and a.camber == 0.3
    assert_allclose(tm.solve(c, camber=0.0).lateral_force, 0.0, atol=1e-9)


def test_casetable_broadcasts_like_numpy():
    t = tm.CaseTable.from_columns(
        tire_radius=15.0, rim_width=15.0, pressure=0.4, load=[100.0, 400.0]
    )
    assert len(t) == 2
    assert_allclose(t.tire_radius, [15.0, 15.0])
    out = tm.solve_many(tire_radius=15.0, rim_width=15.0, pressure=0.4, load=[100.0, 400.0])
    assert_allclose(out["vertical_force"], [100.0, 400.0], rtol=1e-8)
    with pytest.raises(tm.InvalidParameter, match="columns"):
        tm.CaseTable.from_columns(
            tire_radius=[15.0, 16.0, 17.0], rim_width=15.0, pressure=0.4, load=[1.0, 2.0]
        )


def test_solve_many_rows_do_not_depend_on_batch_companions():
    rng = np.random.default_rng(3)
    surfaces = [tm.Flat(), tm.Drum(2500), tm.Disk(3000), tm.Disk(3000, "away")]
    cases = [
        tm.LoadCase(
            tm.get_tire(int(rng.integers(1, 9))),
            pressure=float(rng.uniform(0.3, 0.7)),
            load=float(rng.uniform(150, 450)),
            camber=float(rng.uniform(-0.5, 0.5)),
            surface=surfaces[int(rng.integers(0, 4))],
            slip_kinematics="centre",
        )
        for _ in range(24)
    ]
    whole = tm.solve_many(cases)
    perm = rng.permutation(len(cases))
    shuffled = tm.solve_many([cases[i] for i in perm])
    halves = [tm.solve_many(cases[:10]), tm.solve_many(cases[10:])]
    for k in ("deflection", "length", "width", "area", "lateral_force"):
        assert_allclose(shuffled[k], whole[k][perm], rtol=1e-9, atol=1e-9)
        assert_allclose(np.concatenate([h[k] for h in halves]), whole[k], rtol=1e-9, atol=1e-9)
    one = tm.solve(cases[5].replace(n_sections=65))
    assert_allclose(whole["length"][5], one.length, rtol=1e-9)


def test_solve_many_mixes_load_and_deflection_cases():
    a = tm.LoadCase(T, pressure=0.4, load=300.0)
    b = tm.LoadCase(T, pressure=0.4, deflection=3.0)
    out = tm.solve_many([a, b])
    assert_allclose(out["vertical_force"][0], 300.0, rtol=1e-8)
    assert_allclose(out["deflection"][1], 3.0)


def test_contactpatch_repr_is_short_and_html_escapes():
    tire = tm.TireGeometry(15.0, 15.0, name="<b>$x$</b>")
    p = tm.solve(tire, pressure=0.4, load=300.0)
    assert len(repr(p)) < 250 and "length" in repr(p)
    html = p._repr_html_()
    assert "<b>$x$</b>" not in html and "&lt;b&gt;" in html
    assert "length_mm" in html


def test_loadcase_option_errors_list_every_allowed_value():
    base = dict(pressure=0.4, load=400.0)
    for name, allowed in (
        ("slip_kinematics", tm.case.SLIP_KINEMATICS),
        ("friction_model", tm.case.FRICTION_MODELS),
        ("force_convention", tm.case.FORCE_CONVENTIONS),
    ):
        with pytest.raises(tm.InvalidParameter, match=name) as info:
            tm.LoadCase(T, **base, **{name: "middle"})
        assert all(repr(a) in str(info.value) for a in allowed), str(info.value)
    with pytest.raises(tm.InvalidParameter, match="'leading', 'centre' or 'relaxation'"):
        tm.CaseTable.from_columns(
            tire_radius=20.0, rim_width=19.0, pressure=0.4, load=400.0, slip_kinematics="x"
        )


@pytest.mark.parametrize("kinematics", tm.case.SLIP_KINEMATICS)
def test_loadcase_slip_kinematics_same_patch_force_in_solve_and_solve_lateral(kinematics):
    # one definition of the slip kinematics (module docstring of tiremesh.case): the
    # patch of solve_lateral is solve's, section by section
    case = tm.LoadCase(
        T,
        pressure=0.4,
        load=400.0,
        slip=math.radians(2),
        lateral=0.3,
        relaxation=0.993,
        slip_kinematics=kinematics,
    )
    p = tm.solve(case)
    r = tm.solve_lateral(case)
    assert_allclose(r.patch.lateral_force, p.lateral_force, rtol=1e-12)
    assert_allclose(r.patch_lateral_force, p.lateral_force, rtol=1e-9, atol=1e-9)
    assert_allclose(r.dh[r.in_patch], p.sections.horz_deflection, rtol=0, atol=1e-12)
    if kinematics != "centre":  # the leading-edge kinematics give a cornering force
        assert abs(p.lateral_force) > 5.0
