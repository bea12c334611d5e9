"""Parameter sweeps (issue 6 item 6)."""

import math
import subprocess
import sys

import numpy as np
from numpy.testing import assert_allclose

import tiremesh as tm
from tiremesh.sweep import grid, parse_grid, run_sweep, sweep_plots


def test_sweep_vectorized_matches_single_solves():
    cases = grid(
        tire=[5, 8], pressure_bar=[3.0, 6.0], load_N=[304.0, 600.0], camber_deg=[0.0, 10.0]
    )
    rows = run_sweep(cases)
    assert len(rows) == 16 and all(r["status"] == "ok" for r in rows)
    for r in rows[::5]:
        p = tm.solve(
            tm.get_tire(int(r["tire"])),
            load=r["load_N"],
            pressure=0.1 * r["pressure_bar"],
            camber=math.radians(r["camber_deg"]),
            n_sections=65,
        )
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
