"""Benchmark: vectorized Rotta solver vs the scalar brentq reference (issue 2).

Times, side by side in one run, on the same loaded cases (37 mm tire on an 18.7 mm
rim, 4 bar, 400 N; flat and 45 degrees camber):

* one load-searched solve (``tiremesh.solve``) and the deflection-only solve;
* the cross sections of that patch solved by the vectorized solver vs one
  ``scipy.optimize.brentq`` per section and side (tests/tiremesh/reference.py);
* a batch of 1,000 load cases solved together as arrays (``solve_many``).

Run: python scripts/bench_solver.py
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import tiremesh as tm
from tests.tiremesh.reference import reference_section


def best(fn, repeat=7, number=None):
    """Best-of-repeat time per call [s] (auto-scaled inner loop)."""
    if number is None:
        number, t = 1, 0.0
        while t < 0.2:
            t0 = time.perf_counter()
            for _ in range(number):
                fn()
            t = time.perf_counter() - t0
            number *= 2
        number //= 2
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        times.append((time.perf_counter() - t0) / number)
    return min(times)


def bench_case(tire, n, label, camber):
    kw = dict(pressure=0.4, camber=camber)
    t_load = best(lambda: tm.solve(tire, load=400.0, n_sections=n, **kw))
    t_sink = best(lambda: tm.find_sinkage(tire, 400.0, **kw))
    p = tm.solve(tire, load=400.0, n_sections=n, **kw)
    t_patch = best(lambda: tm.solve_patch(tire, p.deflection, n_sections=n, **kw))
    dv, dh = p.sections.vert_deflection, p.sections.horz_deflection
    t_vec = best(lambda: tm.solve_sections(tire.tire_radius, tire.rim_width, dv, dh, camber))
    delta = tire.tire_radius * camber

    def scalar_sections():
        for a, b in zip(dv, dh, strict=True):
            reference_section(tire.tire_radius, tire.rim_width, a, b, camber, delta=delta)

    def scalar_solve():
        # the same load case the scalar way: secant steps on the load, each solving the
        # patch's sections one brentq at a time (as the appendix's find_sinkage + fzero)
        dws = [p.deflection * 0.9, p.deflection * 1.1]
        forces = []
        for dw in dws:
            q = tm.solve_patch(tire, dw, n_sections=n, **kw)
            for a, b in zip(q.sections.vert_deflection, q.sections.horz_deflection, strict=True):
                reference_section(tire.tire_radius, tire.rim_width, a, b, camber, delta=delta)
            forces.append(q.vertical_force)
        for _ in range(4):
            dw = dws[-1] + (400.0 - forces[-1]) * (dws[-1] - dws[-2]) / (forces[-1] - forces[-2])
            q = tm.solve_patch(tire, dw, n_sections=n, **kw)
            for a, b in zip(q.sections.vert_deflection, q.sections.horz_deflection, strict=True):
                reference_section(tire.tire_radius, tire.rim_width, a, b, camber, delta=delta)
            dws.append(dw)
            forces.append(q.vertical_force)

    t_ref = best(scalar_sections, repeat=3, number=1)
    t_ref_solve = best(scalar_solve, repeat=2, number=1)
    print(f"[{label}] deflection {p.deflection:.4f} mm, lateral force {p.lateral_force:.2f} N")
    print(f"  load-searched solve (find_sinkage + {n} sections): {t_load * 1e3:8.3f} ms")
    print(f"    of which find_sinkage                          : {t_sink * 1e3:8.3f} ms")
    print(f"  solve at known deflection                         : {t_patch * 1e3:8.3f} ms")
    print(f"  {n} sections, vectorized solve_sections           : {t_vec * 1e3:8.3f} ms")
    print(f"  {n} sections, scalar brentq reference             : {t_ref * 1e3:8.3f} ms")
    print(f"  ratio scalar / vectorized (sections)              : {t_ref / t_vec:8.1f} x")
    print(f"  load-searched solve, scalar reference (6 secants) : {t_ref_solve * 1e3:8.1f} ms")
    print(f"  ratio scalar / vectorized (load-searched solve)   : {t_ref_solve / t_load:8.1f} x\n")


def main() -> None:
    tire = tm.TireGeometry.from_size(37, 18.7)
    n = 401
    print(f"tire r0={tire.tire_radius} mm, rim {tire.rim_width} mm, 4 bar, 400 N, {n} sections\n")
    for label, camber in (("flat, 0 deg", 0.0), ("flat, 45 deg", math.radians(45))):
        bench_case(tire, n, label, camber)

    m = 1000
    rng = np.random.default_rng(1)
    cases = dict(
        tire_radius=rng.uniform(10, 23, m),
        rim_width=rng.uniform(13.4, 18.7, m),
        pressure=rng.uniform(0.3, 0.8, m),
        load=rng.uniform(304, 731, m),
    )
    t_batch = best(lambda: tm.solve_many(**cases), repeat=3, number=1)
    print(f"batch of {m} load cases (flat, load search, 65 sections each): {t_batch * 1e3:.1f} ms")
    print(f"  -> {m / t_batch:,.0f} load cases per second")
    t_batch_c = best(lambda: tm.solve_many(camber=0.5, **cases), repeat=3, number=1)
    print(
        f"batch of {m} cambered load cases: {t_batch_c * 1e3:.1f} ms -> {m / t_batch_c:,.0f} per second"
    )


if __name__ == "__main__":
    main()
