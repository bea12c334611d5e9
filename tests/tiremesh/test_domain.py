"""The model never crashes inside its domain: every input solves, with finite
results, or raises a named error of the TireModelError hierarchy (issue: 30 % of
random cases ended in a raw IndexError)."""

import math

import numpy as np
import pytest

import tiremesh as tm
from tiremesh import errors as E

CATALOG = tm.load_catalog()
NAMED = {
    cls.__name__
    for cls in vars(E).values()
    if isinstance(cls, type) and issubclass(cls, tm.TireModelError)
}


def _random_cases(rng, m):
    tires = [tm.get_tire(int(k)) for k in rng.integers(1, len(CATALOG) + 1, m)]
    kinds = rng.integers(0, 4, m)
    diam = rng.uniform(300.0, 5000.0, m)
    surfaces = [
        [tm.Flat(), tm.Drum(d), tm.Disk(d), tm.Disk(d, "away")][k]
        for k, d in zip(kinds, diam, strict=True)
    ]
    return [
        tm.LoadCase(
            t,
            pressure=float(rng.uniform(0.1, 1.2)),
            load=float(rng.uniform(10.0, 1500.0)),
            camber=float(np.radians(rng.uniform(0.0, 70.0))),
            slip=float(np.radians(rng.uniform(0.0, 20.0))),
            lateral=float(rng.uniform(-5.0, 5.0)),
            surface=s,
            n_sections=33,
        )
        for t, s in zip(tires, surfaces, strict=True)
    ]


def test_solve_many_domain_2000_cases_named_errors_or_finite_results():
    cases = _random_cases(np.random.default_rng(2026), 2000)
    out = tm.solve_many(cases, errors="flag", n_sections=33)
    ok = out["ok"]
    for k in ("deflection", "length", "width", "area", "vertical_force", "lateral_force"):
        assert np.all(np.isfinite(out[k][ok])), k
        assert np.all(np.isnan(out[k][~ok])), k  # no plausible number on a failed row
    names = {e.split(":")[0] for e in out["error"][~ok]}
    assert names <= NAMED, names - NAMED
    assert ok.sum() > 200  # the domain is not all failure
    loads = np.array([c.load for c in cases])
    np.testing.assert_allclose(out["vertical_force"][ok], loads[ok], rtol=1e-6)


# 400 cases through solve_lateral (was 120): about 40 ms each, ~16 s on a loaded
# 2-core machine; the 2,000-case draw of the issue runs through solve_many above
@pytest.mark.parametrize("seed", [0, 1, 2, 3])
def test_solve_and_solve_lateral_domain_named_errors(seed):
    rng = np.random.default_rng(seed)
    for case in _random_cases(rng, 100):
        case = case.replace(friction=float(rng.choice([0.05, 0.3, 1.0, math.inf])))
        try:
            r = tm.solve_lateral(case)
        except tm.TireModelError as exc:
            assert type(exc).__name__ in NAMED and str(exc)
            continue
        values = [r.lateral_force, r.vertical_force, r.aligning_moment, r.patch.length]
        assert all(map(math.isfinite, values))
        assert abs(r.lateral_force) <= case.friction * r.vertical_force * (1 + 1e-9)
        trail = r.pneumatic_trail
        share = abs(r.patch_lateral_force) / max(abs(r.lateral_force), 1e-300)
        assert (
            math.isfinite(trail)
            or share < r.options.trail_min_patch_share
            or (abs(r.patch_lateral_force) <= r.options.force_rtol * r.vertical_force)
        )


def test_issue_reproducers_give_named_errors():
    with pytest.raises(tm.BulgeLimit, match="slip"):
        tm.solve(tm.get_tire(8), pressure=0.4, load=400.0, slip=math.radians(45))
    with pytest.raises(tm.TireModelError, match=r"camber|load"):
        tm.solve(
            tm.get_tire(6),
            pressure=0.20417,
            load=443.54,
            camber=math.radians(47.567),
            surface=tm.Drum(2500),
        )
    with pytest.raises(tm.InvalidParameter, match="drum diameter"):
        tm.Drum(100)


@pytest.mark.parametrize("diameter", [300.0, 350.0, 400.0])
def test_small_drum_solves_tire6(diameter):
    # the audit: tire 6 at 4 bar on a 300-400 mm drum raised NoContact "increase the
    # load" at every load. The load search started at the flat-ground patch ends,
    # beyond where a small drum leaves the tread (no contact, NaN width), and every
    # damped step returned there; it now starts at the surface's own contact ends.
    tire, drum = tm.get_tire(6), tm.Drum(diameter)
    lengths = []
    for load in (50.0, 200.0, 500.0):
        p = tm.solve(tire, pressure=0.4, load=load, surface=drum)
        np.testing.assert_allclose(p.vertical_force, load, rtol=1e-8)
        flat = tm.solve(tire, pressure=0.4, load=load)
        assert p.length < flat.length and p.deflection > flat.deflection  # 5.3.1
        lengths.append(p.length)
    assert np.all(np.diff(lengths) > 0)
    by_deflection = tm.solve(tire, pressure=0.4, deflection=p.deflection, surface=drum)
    np.testing.assert_allclose(by_deflection.vertical_force, 500.0, rtol=1e-6)


def test_surface_limit_names_the_drum_diameter():
    # the model's curvature limit: a patch end at R sin(phi) >= R_drum has no drum
    # under it (equation 5-20). Inside the domain (drum > 100 mm) the rim clearance
    # comes first (tire 8 on 101 mm at its largest load: 0.966 of the drum radius),
    # so the check is exercised directly.
    from tiremesh.solver.arrays import single_case_arrays
    from tiremesh.solver.load import surface_limit

    case = tm.LoadCase(tm.get_tire(8), pressure=0.1, load=300.0, surface=tm.Drum(101))
    cs = single_case_arrays(case)
    edge = math.asin(50.5 / float(cs.R[0, 0]))
    assert surface_limit(cs, 0, 30.0, (-0.99 * edge, 0.99 * edge)) is None
    err = surface_limit(cs, 0, 30.0, (-0.5 * edge, 1.01 * edge))
    assert isinstance(err, tm.SurfaceTooCurved) and isinstance(err, tm.ModelLimit)
    with pytest.raises(tm.SurfaceTooCurved, match=r"drum diameter = 101.*surface too curved"):
        raise err
    assert err.state["deflection_mm"] == 30.0 and err.state["case"] == 0
    flat = single_case_arrays(case.replace(surface=tm.Flat()))
    assert surface_limit(flat, 0, 30.0, (-1.0, 1.0)) is None


def test_solve_many_mixed_failures_are_flagged_early_and_rows_independent():
    # prescreen: loads beyond capacity are flagged LoadTooHigh even when other cases
    # of the batch fail at the largest deflection (it used to give up after 3 tries,
    # sending the overloads through the slow nested search); the slip anchor
    # re-solves only its unconverged cases and names failures per case
    from tiremesh.case import CaseTable
    from tiremesh.solver.api import _prescreen

    m = 1000  # the prescreen alone on the benchmark's batch (scripts/bench_sweep.py)
    rng = np.random.default_rng(1)
    cols = dict(
        tire_radius=rng.uniform(10, 23, m),
        rim_width=rng.uniform(13.4, 18.7, m),
        pressure=rng.uniform(0.2, 1.1, m),
        load=rng.uniform(304, 731, m),
        camber=rng.uniform(-0.5, 0.5, m),
        slip=np.zeros(m),
        lateral=np.zeros(m),
    )
    bad = np.nonzero(np.random.default_rng(2).random(m) < 0.10)[0]
    kind = np.arange(bad.size) % 4
    over = bad[kind == 0]
    cols["load"][over] = 50_000.0
    cols["lateral"][bad[kind == 1]] = 60.0
    cols["slip"][bad[kind == 2]] = 0.5  # beyond the model at the largest deflection
    cols["slip"][bad[kind == 3]] = 0.35
    cols["camber"][bad[kind == 3]] = 0.6
    table = CaseTable.from_columns(**cols)
    flagged = _prescreen(table)
    assert set(over) <= set(flagged)
    assert all(flagged[i].startswith("LoadTooHigh") for i in over)
    table = table.take(np.arange(120))  # the solve on a part of it
    over = over[over < 120]
    out = tm.solve_many(table, errors="flag")
    assert not out["ok"][over].any() and out["ok"].sum() >= 90
    ok = np.nonzero(out["ok"])[0]
    alone = tm.solve_many(table.take(ok[::-1]), errors="raise")  # shuffled, without the bad
    np.testing.assert_allclose(alone["lateral_force"][::-1], out["lateral_force"][ok], rtol=1e-7)
    np.testing.assert_allclose(alone["deflection"][::-1], out["deflection"][ok], rtol=1e-8)


@pytest.mark.parametrize("slip", [0.4, 0.5])
def test_solve_large_slip_names_slip_limit(slip):
    # a slip of 0.4-0.5 rad turns the tread line so far (x tan(slip), equation 5-17)
    # that sections inside the patch lose contact: the load search cannot step and
    # used to end in NotConverged ("no valid step"); it names the geometric limit
    case = tm.LoadCase(tm.get_tire(8), pressure=0.4, load=400.0, slip=slip)
    with pytest.raises(
        tm.SlipLimit, match=rf"slip = {slip} is invalid.*slip beyond contact"
    ) as ei:
        tm.solve(case)
    err = ei.value
    assert isinstance(err, tm.ModelLimit) and err.limit == "slip beyond contact"
    assert err.state["sections_off_ground"] >= 1
    assert abs(err.state["section_lateral_mm"]) > tm.get_tire(8).tire_radius
    assert err.state["deflection_mm"] > 0
    got = tm.solve_many(
        tire_radius=[20.6551473485506] * 2,
        rim_width=[15.357432904407501] * 2,
        pressure=[0.3950403795417967] * 2,
        load=[602.87] * 2,
        camber=[-0.1764785229644782] * 2,
        slip=[0.0, slip],
        errors="flag",
    )
    assert got["ok"].tolist() == [True, False]
    assert got["error"][1].startswith("SlipLimit: slip = ")


def test_slip_limit_none_without_slip_or_with_contact():
    from tiremesh.solver.arrays import single_case_arrays
    from tiremesh.solver.load import slip_limit

    zero = np.zeros((1, 1))
    for slip, expect in ((0.0, None), (0.02, None), (0.5, tm.SlipLimit)):
        cs = single_case_arrays(tm.LoadCase(tm.get_tire(8), pressure=0.4, load=400.0, slip=slip))
        dw = np.array([[5.0]])
        end = math.acos((float(cs.R[0, 0]) - 5.0) / float(cs.R[0, 0]))
        got = slip_limit(cs, (dw, (-end * zero - end, zero + end)), zero, 3)
        if expect is None:
            assert got is None
        else:
            assert isinstance(got, expect) and got.state["case"] == 3


def test_joint_newton_hands_diverging_case_to_nested_search():
    # slip 0.35 with camber 0.6 on this tire: the joint Newton step halves the
    # deflection toward 0 while the load residual grows; it used to run all
    # tol.max_iter (60) steps before the bracketed search named the limit
    from tiremesh.solver import load as ld

    calls = []
    orig = ld._newton_step

    def counting(cs, *a):
        calls.append(cs.m)
        return orig(cs, *a)

    ld._newton_step = counting
    try:
        out = tm.solve_many(
            tire_radius=[20.7],
            rim_width=[15.0],
            pressure=[1.003],
            load=[460.0],
            camber=[0.6],
            slip=[0.35],
            errors="flag",
        )
    finally:
        ld._newton_step = orig
    assert not out["ok"][0] and out["error"][0].split(":")[0] in {"PatchEndLimit", "SlipLimit"}
    assert len(calls) <= ld.STALL_STEPS + 10 < 60


def test_solve_many_resolve_after_failure_takes_no_step_for_solved_cases():
    # a mid-search failure raises with the others' converged solution (partial); the
    # group is solved again from it, marked solved: no Newton step for those cases
    # (it used to cost one more step over the whole batch) and bit-identical rows
    from tiremesh.solver import load as ld

    rng = np.random.default_rng(4)
    m = 40
    cols = dict(
        tire_radius=rng.uniform(10, 23, m),
        rim_width=rng.uniform(13.4, 18.7, m),
        pressure=rng.uniform(0.2, 1.1, m),
        load=rng.uniform(304, 731, m),
        camber=rng.uniform(-0.5, 0.5, m),
        slip=np.zeros(m),
    )
    rows = []
    orig = ld._newton_step

    def counting(cs, *a):
        rows.append(cs.m)
        return orig(cs, *a)

    ld._newton_step = counting
    try:
        clean = tm.solve_many(errors="flag", **cols)
        n_clean, rows[:] = sum(rows), []
        cols["slip"][7] = 0.5
        mixed = tm.solve_many(errors="flag", **cols)
        n_mixed = sum(rows)
    finally:
        ld._newton_step = orig
    assert mixed["error"][7].split(":")[0] in {"SlipLimit", "BulgeLimit"}
    assert mixed["ok"].sum() == m - 1
    keep = np.arange(m) != 7
    np.testing.assert_array_equal(mixed["deflection"][keep], clean["deflection"][keep])
    np.testing.assert_array_equal(mixed["lateral_force"][keep], clean["lateral_force"][keep])
    assert n_mixed <= n_clean + 6  # the failing case's own (at most 6) halved steps
