"""Benchmark: parameter sweeps (issue 6).

* 10,000 load-searched cases, flat ground, zero camber (vectorized: solve_many);
  target >= 2,000 cases per second on this 2-core machine; split into turning the
  rows into load cases (case_from_row) and solving their CaseTable (solve_many);
* a cambered sweep with friction and deflection beyond the patch (one
  solve_lateral per case), on 1 and on 2 local workers.

* solve_many scaling: 1k / 10k / 100k cases, cases per second and peak memory (each
  size in a fresh process, peak RSS from getrusage), chunked (chunk_size=2048);
* a 1,000-case batch with 10 % infeasible cases against the same batch without
  them, side by side (errors="flag"): the ratio of the two times against the 1.5x
  target. The infeasible cases are of four kinds: two the prescreen flags before any
  search (loads beyond capacity, laterals beyond the construction) and two that
  fail in the middle of the load search (large slip; slip with camber).

Run: python scripts/bench_sweep.py  (``--quick``: a smoke run with tiny sizes)
"""

from __future__ import annotations

import json
import subprocess
import sys
import time
from collections import Counter
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import tiremesh as tm
from tiremesh.sweep import VECTOR_SECTIONS, case_from_row, grid, run_sweep


def _columns(m: int, seed: int = 0) -> dict:
    rng = np.random.default_rng(seed)
    return dict(
        tire_radius=rng.uniform(10, 23, m),
        rim_width=rng.uniform(13.4, 18.7, m),
        pressure=rng.uniform(0.2, 1.1, m),
        load=rng.uniform(304, 731, m),
        camber=rng.uniform(-0.5, 0.5, m),
    )


def _one_size(m: int) -> dict:
    """Run in a fresh process: cases/s and peak RSS of solve_many on m cases."""
    import resource

    cols = _columns(m)
    t0 = time.perf_counter()
    out = tm.solve_many(errors="flag", **cols)
    dt = time.perf_counter() - t0
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    return {
        "m": m,
        "seconds": dt,
        "cases_per_s": m / dt,
        "peak_MB": peak,
        "ok": int(out["ok"].sum()),
    }


def scaling(sizes=(1_000, 10_000, 100_000)) -> None:
    base = None
    for m in sizes:
        got = subprocess.run(
            [sys.executable, __file__, "--one", str(m)], capture_output=True, text=True, check=True
        )
        r = json.loads(got.stdout.strip().splitlines()[-1])
        base = base or r["cases_per_s"]
        print(
            f"solve_many {m:>7,} cases: {r['seconds']:6.2f} s, {r['cases_per_s']:6,.0f} cases/s "
            f"({r['cases_per_s'] / base:.2f}x of {sizes[0]:,}), peak RSS {r['peak_MB']:.0f} MB, {r['ok']:,} ok"
        )


def _mixed(cols: dict, m: int) -> tuple[dict, np.ndarray]:
    """``cols`` with 10 % infeasible cases of four kinds, in equal shares: two the
    prescreen catches before any search (load beyond capacity, lateral displacement
    beyond the construction) and two that fail in the middle of the load search
    (large slip: BulgeLimit; slip with camber: BulgeLimit / PatchEndLimit)."""
    bad = np.nonzero(np.random.default_rng(2).random(m) < 0.10)[0]
    kind = np.arange(bad.size) % 4
    mixed = {k: v.copy() for k, v in cols.items()}
    mixed["lateral"], mixed["slip"] = np.zeros(m), np.zeros(m)
    mixed["load"][bad[kind == 0]] = 50_000.0  # LoadTooHigh (prescreen)
    mixed["lateral"][bad[kind == 1]] = 60.0  # BulgeLimit (prescreen)
    mixed["slip"][bad[kind == 2]] = 0.5  # fails mid-search
    mixed["slip"][bad[kind == 3]] = 0.35  # fails mid-search, with camber
    mixed["camber"][bad[kind == 3]] = 0.6
    return mixed, bad


def infeasible(m: int = 1000, repeats: int = 3) -> None:
    cols = _columns(m, seed=1)
    mixed, bad = _mixed(cols, m)
    cols = {**cols, "lateral": np.zeros(m), "slip": np.zeros(m)}
    times = {"clean": [], "10% infeasible": []}
    for _ in range(repeats):  # interleaved, best of the repeats
        for name, c in (("clean", cols), ("10% infeasible", mixed)):
            t0 = time.perf_counter()
            out = tm.solve_many(errors="flag", **c)
            times[name].append(time.perf_counter() - t0)
    kinds = Counter(e.split(":")[0] for e in out["error"] if e)
    a, b = min(times["clean"]), min(times["10% infeasible"])
    print(
        f"{m:,} cases: clean {a:.3f} s, with 10 % infeasible {b:.3f} s "
        f"({bad.size} planted, {int((~out['ok']).sum())} flagged: {dict(kinds)}): "
        f"ratio {b / a:.2f} vs target 1.5 -> {'met' if b / a <= 1.5 else 'MISSED'}"
    )


def main() -> None:
    if len(sys.argv) == 3 and sys.argv[1] == "--one":
        print(json.dumps(_one_size(int(sys.argv[2]))))
        return
    if "--quick" in sys.argv:  # smoke run: tiny sizes, seconds
        scaling((200, 1_000))
        infeasible(200, repeats=1)
        return
    scaling()
    infeasible()
    rng = np.random.default_rng(0)
    cases = [
        {
            "tire_radius_mm": float(r),
            "rim_width_mm": float(w),
            "pressure_bar": float(p),
            "load_N": float(f),
        }
        for r, w, p, f in zip(
            rng.uniform(10, 23, 10_000),
            rng.uniform(13.4, 18.7, 10_000),
            rng.uniform(2, 11, 10_000),
            rng.uniform(304, 731, 10_000),
            strict=True,
        )
    ]
    t0 = time.perf_counter()
    rows = run_sweep(cases)
    dt = time.perf_counter() - t0
    ok = sum(r["status"] == "ok" for r in rows)
    print(
        f"flat sweep: {len(cases):,} load-searched cases ({ok:,} solved) in {dt:.2f} s -> {len(cases) / dt:,.0f} cases/s"
    )
    t0 = time.perf_counter()
    load_cases = [case_from_row(c) for c in cases]
    t1 = time.perf_counter()
    tm.solve_many(tm.CaseTable.from_cases(load_cases), n_sections=VECTOR_SECTIONS)
    t2 = time.perf_counter()
    print(f"  of which rows -> LoadCase: {t1 - t0:.2f} s, CaseTable + solve_many: {t2 - t1:.2f} s")
    lat = grid(
        tire=list(range(1, 15)),
        pressure_bar=[3.0, 5.0, 7.0, 9.0],
        load_N=[304.0, 500.0],
        camber_deg=[10.0, 30.0],
        friction=[1.0],
        relaxation=[0.993],
    )
    for workers in (1, 2):
        t0 = time.perf_counter()
        run_sweep(lat, workers=workers)
        dt = time.perf_counter() - t0
        print(
            f"cambered sweep with friction + relaxation: {len(lat)} cases, {workers} worker(s): "
            f"{dt:.2f} s -> {len(lat) / dt:,.0f} cases/s"
        )


if __name__ == "__main__":
    main()
