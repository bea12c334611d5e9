"""Benchmark: analytical relationships (issue 14 part 3).

Times the docs run of ``tiremesh.relations`` (100,000 cases by default): the load
solves (solve_many), the stiffness deflection solves, the fits and the whole
``write_relations`` (sweep, fits, tables, figures).

Run: python scripts/bench_relations.py [N_CASES] [OUT_DIR]
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import tiremesh as tm
from tiremesh import relations as rel


def main() -> None:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 100_000
    out = Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp(prefix="relations_"))
    t0 = time.perf_counter()
    cases = rel.sweep_cases(n, seed=0)
    t1 = time.perf_counter()
    results = tm.solve_many(cases, n_sections=rel.N_SECTIONS, errors="flag")
    t2 = time.perf_counter()
    dw = np.where(results["ok"], results["deflection"], np.nan)
    results["vertical_stiffness"] = rel.vertical_stiffness(cases, dw)
    t3 = time.perf_counter()
    rel.fit_relations(cases, results)
    t4 = time.perf_counter()
    print(
        f"{n:,} cases: sampling {t1 - t0:.2f} s, load solves {t2 - t1:.1f} s "
        f"({n / (t2 - t1):,.0f} cases/s), stiffness solves {t3 - t2:.1f} s, fits {t4 - t3:.2f} s"
    )
    t0 = time.perf_counter()
    paths = rel.write_relations(out, n_cases=n, seed=0)
    dt = time.perf_counter() - t0
    print(f"write_relations({n:,} cases): {dt:.1f} s, {len(paths)} files in {out}")


if __name__ == "__main__":
    main()
