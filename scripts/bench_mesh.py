"""Benchmark: deformed-tire mesh build + contact-patch extraction, and renders (issue 3).

Prints, in one run: face count, mesh build time, patch extraction time, their sum
(target <= 100 ms at the default ~100k faces), the time to solve the load case
beside them, and one off-screen PNG render per view (target <= 2 s).

Run: python scripts/bench_mesh.py
"""

from __future__ import annotations

import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

import contactpatch as cp
import tiremesh as tm
from tiremesh.mesh import build_mesh
from tiremesh.render import render


def best(fn, repeat=7):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return min(times), out


def main() -> None:
    base = tm.LoadCase(tm.get_tire(8), pressure=0.4, load=400.0)
    for label, case in (
        ("flat", base),
        ("drum, 30 deg camber", base.replace(surface=tm.Drum(2500), camber=np.radians(30))),
    ):
        t_solve, patch = best(lambda case=case: tm.solve(case))
        build_mesh(patch)  # warm imports
        t_build, mesh = best(lambda patch=patch: build_mesh(patch))
        t_cut, geom = best(lambda mesh=mesh: cp.patch_from_mesh(mesh))
        err = geom.area / patch.area - 1
        print(f"[{label}] {mesh.n_faces:,} faces, {len(mesh.mesh.vertices):,} vertices")
        print(f"  solve (load search)       : {t_solve * 1e3:7.1f} ms")
        print(f"  mesh build                : {t_build * 1e3:7.1f} ms")
        print(f"  patch from mesh           : {t_cut * 1e3:7.1f} ms")
        print(
            f"  build + patch             : {(t_build + t_cut) * 1e3:7.1f} ms  (target <= 100 ms)"
        )
        print(f"  mesh patch area vs solver : {err:+.2e}")
    with tempfile.TemporaryDirectory() as tmp:
        render(mesh, Path(tmp) / "warm.png", view="iso", size=(320, 240))
        for view in ("iso", "side", "front", "bottom"):
            t, _ = best(
                lambda view=view: render(mesh, Path(tmp) / f"{view}.png", view=view), repeat=3
            )
            print(f"  render {view:6s} 1200x900 PNG: {t:5.2f} s  (target <= 2 s)")


if __name__ == "__main__":
    main()
