"""Parameter sweeps (issue 6 item 6)."""

import math
import subprocess
import sys

import numpy as np
import pytest
from numpy.testing import assert_allclose

import tiremesh as tm
from tiremesh.io import read_table, write_table
from tiremesh.sweep import (
    case_from_row,
    grid,
    parse_grid,
    read_cases,
    run_sweep,
    solve_case,
    sweep_plots,
)


def test_sweep_vectorized_matches_single_solves():
    cases = grid(
        tire=[5, 8], pressure_bar=[3.0, 6.0], load_N=[304.0, 600.0], camber_deg=[0.0, 10.0]
    )
    rows = run_sweep(cases)
    assert len(rows) == 16 and all(r["status"] == "ok" for r in rows)
    for r in rows[::5]:
        case = tm.LoadCase.from_units(
            tm.get_tire(int(r["tire"])),
            load_N=r["load_N"],
            pressure_bar=r["pressure_bar"],
            camber_deg=r["camber_deg"],
            n_sections=65,
        )
        p = tm.solve(case)
        assert_allclose(
            [r["deflection_mm"], r["lateral_force_N"]],
            [p.deflection, p.lateral_force],
            rtol=1e-7,
            atol=1e-9,
        )


def test_sweep_records_errors_and_mixed_cases():
    cases = [
        dict(tire=5, pressure_bar=1.0, load_N=5000.0),
        dict(tire=5, pressure_bar=4.0, load_N=400.0),
        dict(tire=5, pressure_bar=4.0, load_N=400.0, slip_deg=1.0, relaxation=0.993, friction=1.0),
        dict(tire="no such", pressure_bar=4.0, load_N=400.0),
    ]
    rows = run_sweep(cases, workers=1)
    assert [r["status"] for r in rows] == ["error", "ok", "ok", "error"]
    assert "largest load" in rows[0]["error"] and rows[2]["norm_cornering_stiffness_1_deg"] > 0


def test_sweep_on_dask_local_cluster_equals_local():
    from dask.distributed import LocalCluster

    cases = grid(
        tire=[5], pressure_bar=[3.0, 6.0], load_N=[400.0], slip_deg=[0.5, 1.0], relaxation=[0.993]
    )
    local = run_sweep(cases, workers=1)
    with LocalCluster(
        n_workers=2, threads_per_worker=1, processes=False, dashboard_address=None
    ) as cluster:
        remote = run_sweep(cases, scheduler=cluster.scheduler_address)
    assert local == remote


def test_sweep_plots_and_cli(tmp_path):
    rows = run_sweep(
        parse_grid("tire=6,8 pressure_bar=3:9:3 load_N=304,500 camber_deg=10 lateral_mm=1")
    )
    paths = sweep_plots(rows, tmp_path / "plots")
    assert {p.name for p in paths} >= {
        "tangent_rule_agreement.png",
        "norm_camber_stiffness_1_deg.svg",
    }
    out = subprocess.run(
        [
            sys.executable,
            "-m",
            "tiremesh.cli",
            "sweep",
            "--grid",
            "tire=5 pressure_bar=3,5 load_N=400",
            "-o",
            str(tmp_path / "s.csv"),
        ],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert out.returncode == 0, out.stderr
    assert (tmp_path / "s.csv").read_text().count("\n") == 3
    assert np.isfinite(rows[0]["tangent_rule_agreement"])


def test_case_from_row_is_the_one_conversion():
    row = dict(
        tire=8,
        pressure_bar=4.0,
        load_N=400.0,
        camber_deg=10.0,
        slip_deg=1.0,
        lateral_mm=0.5,
        surface="drum:2500",
        relaxation=0.99,
        friction=1.2,
        slip_kinematics="centre",
    )
    case = case_from_row(row)
    assert case == tm.LoadCase(
        tm.get_tire(8),
        pressure=0.4,
        load=400.0,
        camber=math.radians(10),
        slip=math.radians(1),
        lateral=0.5,
        surface=tm.Drum(2500),
        relaxation=tm.Relaxation.uniform(0.99),
        friction=1.2,
        slip_kinematics="centre",
    )
    # defaults: flat, no slip, no friction, no deflection beyond the patch
    plain = case_from_row(dict(tire_radius_mm=15.0, rim_width_mm=17.0, pressure_bar=3, load_N=300))
    assert plain.tire.tire_radius == 15.0 and plain.tire.rim_width == 17.0
    assert plain.surface == tm.Flat() and plain.friction == math.inf
    assert plain.relaxation == tm.Relaxation.uniform(0.0)
    # a Surface object passes through
    assert case_from_row({**row, "surface": tm.Disk(3000)}).surface == tm.Disk(3000)


@pytest.mark.parametrize(
    ("row", "match"),
    [
        (dict(tire=5, load_N=400.0), "pressure_bar"),
        (dict(tire=5, pressure_bar=4.0), "load_N"),
        (dict(pressure_bar=4.0, load_N=400.0), "tire"),
        (dict(tire=5, pressure_bar="lots", load_N=400.0), "pressure_bar"),
        (dict(tire=5, pressure_bar=4.0, load_N=400.0, camber_deg=95.0), "camber"),
        (dict(tire=5, pressure_bar=4.0, load_N=400.0, surface="moon"), "surface"),
        (dict(tire=5, pressure_bar=4.0, load_N=400.0, camber=45.0), "camber"),
    ],
)
def test_case_from_row_names_the_bad_key(row, match):
    with pytest.raises(tm.InvalidParameter, match=match):
        case_from_row(row)
    out = solve_case(row)  # recorded, not raised
    assert out["status"] == "error" and match in out["error"]


def test_unknown_grid_keys_are_errors(tmp_path):
    # `camber=45` used to be silently ignored (solved at zero camber)
    with pytest.raises(tm.InvalidParameter, match="camber_deg"):
        grid(tire=[5], pressure_bar=[4.0], load_N=[400.0], camber=[45.0])
    with pytest.raises(tm.InvalidParameter, match="presure_bar"):
        parse_grid("tire=5 presure_bar=4 load_N=400")
    with pytest.raises(tm.InvalidParameter, match="camber"):
        run_sweep([dict(tire=5, pressure_bar=4.0, load_N=400.0, camber=45.0)])
    path = tmp_path / "cases.csv"
    path.write_text("tire,pressure_bar,load_N,notes\n5,4,400,x\n")
    with pytest.raises(tm.InvalidParameter, match="notes"):
        read_cases(path)


def test_parse_grid_forms():
    cases = parse_grid("tire=5 pressure_bar=2:4:3 surface=flat,disk:3000:away")
    assert len(cases) == 6
    assert [c["pressure_bar"] for c in cases[::2]] == [2.0, 3.0, 4.0]
    assert {c["surface"] for c in cases} == {"flat", "disk:3000:away"}
    assert all(type(c["pressure_bar"]) is float for c in cases)
    with pytest.raises(tm.InvalidParameter, match="grid"):
        parse_grid("tire")


@pytest.mark.parametrize(
    ("spec", "match"),
    [
        ("tire=5 pressure_bar=", "pressure_bar.*non-empty"),
        ("tire=5 pressure_bar=2:4", "pressure_bar.*start:stop:count"),
        ("tire=5 pressure_bar=a:b:c", "pressure_bar.*start:stop:count"),
        ("tire=5 pressure_bar=2:4:x", "pressure_bar.*start:stop:count"),
        ("tire=5 pressure_bar=2:4:3:1", "pressure_bar.*start:stop:count"),
        ("tire=5 pressure_bar=2:inf:3", "pressure_bar.*start:stop:count"),
        ("tire=5 pressure_bar=2,,3", "pressure_bar.*non-empty"),
        ("tire=5 pressure_bar=four", "pressure_bar.*a number"),
        ("tire=5 pressure_bar=2 load_N=400 pressure_bar=3", "pressure_bar.*given twice"),
        ("tire=5 =4", "grid"),
        ("tire=5 camber=45", "camber.*did you mean 'camber_deg'"),
        ("tire=5 surface=", "surface.*non-empty"),
    ],
)
def test_parse_grid_rejects_malformed_parts_up_front(spec, match):
    with pytest.raises(tm.InvalidParameter, match=match):
        parse_grid(spec)


@pytest.mark.parametrize("count", ["0", "-3"])
def test_parse_grid_rejects_empty_ranges(count):
    with pytest.raises(tm.InvalidParameter, match="at least one value"):
        parse_grid(f"tire=5 pressure_bar=2:4:{count}")
    with pytest.raises(tm.InvalidParameter, match="at least one value"):
        grid(tire=5, pressure_bar=[])


def test_parse_grid_case_count_limit_before_allocation():
    # 1e8 values would take gigabytes: refused from the count alone
    with pytest.raises(tm.InvalidParameter, match="at most max_cases = 1000000"):
        parse_grid("tire=5 pressure_bar=1:2:100000000")
    with pytest.raises(tm.InvalidParameter, match=r"12 cases.*at most max_cases = 10"):
        parse_grid("tire=5,6 pressure_bar=1:2:3 load_N=300,400", max_cases=10)
    assert len(parse_grid("tire=5,6 pressure_bar=1:2:3 load_N=300,400", max_cases=12)) == 12
    with pytest.raises(tm.InvalidParameter, match="at most max_cases = 3"):
        grid(tire=[5, 6], load_N=[300.0, 400.0], max_cases=3)


def test_parse_grid_text_values_keep_colons():
    cases = parse_grid("tire=5 load_N=400 surface=drum:2500 slip_kinematics=relaxation,centre")
    assert [c["surface"] for c in cases] == ["drum:2500", "drum:2500"]
    assert [c["slip_kinematics"] for c in cases] == ["relaxation", "centre"]
    assert parse_grid("tire=5 friction=inf,0.5")[0]["friction"] == math.inf


def test_sweep_per_case_path_is_solve_lateral_of_the_case():
    row = dict(tire=5, pressure_bar=4.0, load_N=400.0, slip_deg=1.0, relaxation=0.993)
    (out,) = run_sweep([row], workers=1)
    r = tm.solve_lateral(case_from_row(row))
    assert out["status"] == "ok"
    assert out["lateral_force_N"] == r.lateral_force
    assert out["pneumatic_trail_mm"] == r.pneumatic_trail
    assert (
        out["norm_cornering_stiffness_1_deg"]
        == tm.stiffnesses(r)["norm_cornering_stiffness_1_deg"]
    )


def test_sweep_surfaces_as_objects_and_bad_cases_do_not_spoil_the_batch():
    cases = grid(
        tire=[5], pressure_bar=[1.0, 4.0], load_N=[400.0, 5000.0], surface=[tm.Drum(2500)]
    )
    rows = run_sweep(cases)
    assert [r["status"] for r in rows] == ["ok", "error", "ok", "error"]
    assert "largest load" in rows[1]["error"]
    for i in (0, 2):
        alone = run_sweep([cases[i]])[0]
        assert alone["deflection_mm"] == pytest.approx(rows[i]["deflection_mm"], rel=1e-9)
    # plain rows carry the same stiffness columns as rows solved one by one
    (cam,) = run_sweep([dict(tire=5, pressure_bar=4.0, load_N=400.0, camber_deg=10.0)])
    assert {"camber_stiffness_N_deg", "tangent_rule_agreement"} <= set(cam)


def test_sweep_table_round_trip(tmp_path):
    rows = run_sweep(parse_grid("tire=5 pressure_bar=3,5 load_N=400 camber_deg=5"), progress=True)
    for ext in (".csv", ".json"):
        back = read_table(write_table(rows, tmp_path / f"s{ext}"))
        assert [float(r["lateral_force_N"]) for r in back] == [r["lateral_force_N"] for r in rows]
    # figures from a table read back (numbers as text)
    paths = sweep_plots(read_table(tmp_path / "s.csv"), tmp_path / "plots")
    assert {p.name for p in paths} >= {"norm_camber_stiffness_1_deg.png"}


def test_run_sweep_takes_load_cases_like_rows():
    """Issue 9: sweeps take LoadCase; a case and its row solve to the same result."""
    from tiremesh.sweep import case_from_row, row_from_case

    case = tm.LoadCase.from_units(
        tm.get_tire(8), pressure_bar=4, load_N=400, camber_deg=10, surface="drum:2500"
    )
    row = row_from_case(case)
    again = case_from_row(row)
    assert again.tire.tire_radius == case.tire.tire_radius and again.surface == case.surface
    assert again.pressure == pytest.approx(case.pressure, rel=1e-15)
    by_case, by_row = run_sweep([case, case.replace(load=300.0)], workers=1), run_sweep([row])
    assert by_case[0]["status"] == "ok" and by_case[1]["load_N"] == 300.0
    assert by_case[0]["deflection_mm"] == pytest.approx(by_row[0]["deflection_mm"], rel=1e-12)


def test_row_from_case_refuses_what_a_row_cannot_hold():
    from tiremesh.sweep import row_from_case

    case = tm.LoadCase(tm.get_tire(8), pressure=0.4, deflection=5.0)
    with pytest.raises(tm.InvalidParameter, match="load"):
        run_sweep([case])
    with pytest.raises(tm.InvalidParameter, match="cases"):
        row_from_case({"tire": 8})


def test_run_sweep_progress_counts_vectorized_and_single_cases(capfd):
    """Issue 10 item 3: the sweep shows progress; the bar counts every case (the
    vectorized ones in chunks), and only on a terminal unless asked."""
    cases = grid(tire=[8], pressure_bar=[3.0, 4.0], load_N=[300.0, 400.0])
    cases += grid(tire=[8], pressure_bar=[4.0], load_N=[400.0], slip_deg=[1.0])
    run_sweep(cases, workers=1, progress=True)
    err = capfd.readouterr().err
    assert "sweep" in err and "5/5" in err
    run_sweep(cases, workers=1)  # stderr is not a terminal here: no bar
    assert "sweep" not in capfd.readouterr().err
