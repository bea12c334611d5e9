"""Judgement thresholds are options passed explicitly, and they reach the workers
(issue 9 item 5, issue 10 audit).

Before SolverOptions, ``tiremesh.tol.rim_clearance = 0.3`` gave LoadTooHigh rows with
one worker and ok rows with two: worker processes re-imported the module global.
"""

import math

import pytest
from numpy.testing import assert_allclose

import tiremesh as tm
from tiremesh.sweep import run_sweep

real_workers = pytest.mark.filterwarnings("error:worker processes failed")
TIGHT = tm.SolverOptions(rim_clearance=0.3)  # tire 6 at 4 bar then carries ~346 N
# not vectorizable (relaxation, friction): these go through the worker pool
CASES = [
    dict(tire=6, pressure_bar=4.0, load_N=load, relaxation=0.993, friction=1.0)
    for load in (400.0, 450.0, 500.0, 550.0)
]
PLAIN = [dict(tire=6, pressure_bar=4.0, load_N=load) for load in (400.0, 500.0)]


def statuses(rows):
    return [(r["status"], r["error"].split(":")[0]) for r in rows]


def test_solver_options_change_single_calls():
    tire = tm.get_tire(6)
    assert tm.max_load(tire, pressure=0.4, options=TIGHT) < 400.0 < tm.max_load(tire, pressure=0.4)
    with pytest.raises(tm.LoadTooHigh, match="largest load"):
        tm.solve(tire, pressure=0.4, load=400.0, options=TIGHT)
    with pytest.raises(tm.LoadTooHigh):
        tm.solve_lateral(tire, pressure=0.4, load=400.0, relaxation=0.993, options=TIGHT)
    many = tm.solve_many(
        tm.CaseTable.from_cases([tm.LoadCase(tire, pressure=0.4, load=400.0)]),
        errors="flag",
        options=TIGHT,
    )
    assert not many["ok"][0] and "LoadTooHigh" in many["error"][0]
    assert tm.solve(tire, pressure=0.4, load=400.0).vertical_force == pytest.approx(400.0)


def test_solver_options_trail_threshold_is_kept_on_the_result():
    case = tm.LoadCase(
        tm.get_tire(6), pressure=0.4, load=400.0, slip=math.radians(1), relaxation=0.993
    )
    r = tm.solve_lateral(case)
    assert math.isfinite(r.pneumatic_trail)
    strict = tm.solve_lateral(case, options=tm.SolverOptions(force_rtol=1.0))
    assert math.isnan(strict.pneumatic_trail)  # |Fy_patch| < Fz: counted as zero
    assert_allclose(strict.lateral_force, r.lateral_force, rtol=0)


@pytest.mark.parametrize(
    ("field", "value"),
    [
        ("rim_clearance", 0.0),
        ("rim_clearance", 1.5),
        ("force_rtol", -1.0),
        ("force_rtol", math.nan),
        ("trail_min_patch_share", 2.0),
        ("friction_rtol", 0.0),
        ("friction_max_iter", 0),
        ("friction_max_iter", 2.5),
        ("rim_clearance", "0.9"),
    ],
)
def test_solver_options_reject_bad_values(field, value):
    with pytest.raises(tm.InvalidParameter, match=field):
        tm.SolverOptions(**{field: value})


def test_solver_options_tol_refuses_moved_and_unknown_names():
    for name in ("rim_clearance", "force_rtol", "friction_rtol", "no_such_tolerance"):
        with pytest.raises(tm.InvalidParameter, match="SolverOptions"):
            setattr(tm.tol, name, 0.3)
    with pytest.raises(tm.InvalidParameter, match="options"):
        tm.solve(tm.get_tire(6), pressure=0.4, load=400.0, options={"rim_clearance": 0.3})
    with pytest.raises(tm.InvalidParameter, match="options"):
        run_sweep(CASES, workers=1, options={"rim_clearance": 0.3})


@real_workers
def test_solver_options_reach_local_worker_processes():
    default = run_sweep(CASES + PLAIN, workers=1)
    assert all(r["status"] == "ok" for r in default)
    one = run_sweep(CASES + PLAIN, workers=1, options=TIGHT)
    two = run_sweep(CASES + PLAIN, workers=2, options=TIGHT)
    assert statuses(one) == [("error", "LoadTooHigh")] * 6
    assert statuses(two) == statuses(one)


def test_solver_options_reach_dask_workers():
    from dask.distributed import LocalCluster

    local = run_sweep(CASES, workers=1, options=TIGHT)
    with LocalCluster(
        n_workers=1, processes=True, threads_per_worker=1, dashboard_address=None
    ) as cluster:
        remote = run_sweep(CASES, scheduler=cluster.scheduler_address, options=TIGHT)
        remote_default = run_sweep(CASES, scheduler=cluster.scheduler_address)
    assert statuses(remote) == statuses(local) == [("error", "LoadTooHigh")] * 4
    assert all(r["status"] == "ok" for r in remote_default)
