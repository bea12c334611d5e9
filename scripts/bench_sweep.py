"""Benchmark: parameter sweeps (issue 6).

* 10,000 load-searched cases, flat ground, zero camber (vectorized: solve_many);
  target >= 2,000 cases per second on this 2-core machine; split into turning the
  rows into load cases (case_from_row) and solving their CaseTable (solve_many);
* a cambered sweep with friction and deflection beyond the patch (one
  solve_lateral per case), on 1 and on 2 local workers.

Run: python scripts/bench_sweep.py
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import tiremesh as tm
from tiremesh.sweep import VECTOR_SECTIONS, case_from_row, grid, run_sweep


def main() -> None:
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
