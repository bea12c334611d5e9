"""Synthetic print rows for benchmarks and tests of the report at scale.

The rows look like a batch's paired rows (``inkprint`` columns plus tire, pressure,
load and surface) on the four tires of the bundled set; each hull is an ellipse
written as WKT, so no scans are needed. Length and width follow a square-root law
in load and pressure with 3 % scatter; they are test data, not a model result.
"""

from __future__ import annotations

import math

import numpy as np

from tiremesh.units import MPA_PER_BAR

#: (tire id, tire name) cycled over the rows
TIRES = (
    (6, "Maxxis Radial Prototype 22-622"),
    (8, "Schwalbe Big Apple 55-622"),
    (10, "Schwalbe Marathon Plus 37-622"),
    (5, "Continental Grand Prix 23-622"),
)


def _ellipse_wkt(length: float, width: float, n: int = 49) -> str:
    ring = ", ".join(
        f"{length / 2 * math.cos(a):.3f} {width / 2 * math.sin(a):.3f}"
        for a in np.linspace(0, 2 * math.pi, n)
    )
    return f"POLYGON (({ring}))"


def synthetic_print_rows(n: int, *, seed: int = 0) -> list[dict]:
    """``n`` print rows like a batch's, on 4 tires (hull: an ellipse, no scans).

    Parameters
    ----------
    n : int
        Number of rows (two prints per sheet, drum and plate alternating).
    seed : int, optional
        Seed of the random scatter (same seed, same rows).

    Returns
    -------
    list of dict
        One dict per print: file, print, status, tire, tire_id, pressure_bar [bar],
        load_N [N], surface, length_mm / width_mm [mm], hull_area_mm2 [mm^2], the
        ellipse columns, net_to_gross, angle_deg, mm_per_px,
        load_per_hull_area_N_mm2 [N/mm^2], load_per_hull_area_pct [%] and hull_wkt.
    """
    rng = np.random.default_rng(seed)
    rows = []
    for i in range(n):
        tid, name = TIRES[i % 4]
        p, load = float(rng.choice([4.0, 5.5, 6.9])), float(rng.choice([304.0, 400.0, 500.0]))
        L = 80 * (load / 400) ** 0.5 * (5 / p) ** 0.5 * rng.normal(1, 0.03)
        W = 11 * (load / 400) ** 0.5 * rng.normal(1, 0.03)
        area = math.pi * L * W / 4
        hull = 1.02 * area
        rows.append(
            {
                "file": f"sheet{i // 2:04d}.png",
                "print": i % 2,
                "status": "ok",
                "tire": name,
                "tire_id": tid,
                "pressure_bar": p,
                "load_N": load,
                "surface": "drum" if i % 2 == 0 else "plate",
                "length_mm": L,
                "width_mm": W,
                "hull_area_mm2": hull,
                "ellipse_length_mm": L,
                "ellipse_width_mm": W,
                "ellipse_area_mm2": area,
                "net_to_gross": 0.8,
                "angle_deg": 0.0,
                "mm_per_px": 0.17,
                "load_per_hull_area_N_mm2": load / hull,
                "load_per_hull_area_pct": 100.0 * load / hull / (MPA_PER_BAR * p),
                "hull_wkt": _ellipse_wkt(L, W),
            }
        )
    return rows


__all__ = ["TIRES", "synthetic_print_rows"]
