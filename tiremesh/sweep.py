"""Parameter sweeps: tire x pressure x load x camber x slip x surface -> table.

Cases without friction or deflection beyond the patch are solved together as
arrays (:func:`tiremesh.solve_many`); the others one by one with
:func:`tiremesh.lateral.solve_lateral`, in parallel on local processes or on a Dask
cluster (``scheduler=ADDRESS``). Every case becomes one row; a case the model
cannot solve becomes a row with its error.

Case keys (units in the names): ``tire`` (catalogue id or name) or
``tire_radius_mm`` + ``rim_width_mm``; ``rim_width_mm``; ``pressure_bar``; ``load_N``;
``camber_deg``; ``slip_deg``; ``lateral_mm``; ``surface`` (flat | drum:D | disk:D);
``friction`` (inf); ``relaxation`` (0 = none).
"""

from __future__ import annotations

import csv
import itertools
import math
import os
from pathlib import Path

import numpy as np

from .errors import InvalidParameter, TireModelError

DEFAULTS = {
    "camber_deg": 0.0,
    "slip_deg": 0.0,
    "lateral_mm": 0.0,
    "surface": "flat",
    "friction": math.inf,
    "relaxation": 0.0,
}


def grid(**axes) -> list[dict]:
    """All combinations of the given value lists: ``grid(tire=[5, 8], pressure_bar=[3, 5])``."""
    keys = list(axes)
    vals = [np.atleast_1d(axes[k]).tolist() for k in keys]
    return [dict(zip(keys, combo, strict=True)) for combo in itertools.product(*vals)]


def parse_grid(spec: str) -> list[dict]:
    """'tire=5,8 pressure_bar=2:11:10 load_N=304,500' -> cases (a:b:n is a linspace)."""
    axes = {}
    for part in spec.split():
        if "=" not in part:
            raise InvalidParameter("grid", part, "key=v1,v2,... or key=start:stop:count")
        k, val = part.split("=", 1)
        if val.count(":") == 2:
            a, b, n = val.split(":")
            axes[k] = list(np.linspace(float(a), float(b), int(n)))
        else:
            axes[k] = [_auto(x) for x in val.split(",")]
    return grid(**axes)


def read_cases(path) -> list[dict]:
    with open(path, newline="", encoding="utf-8-sig") as fh:
        return [{k: _auto(v) for k, v in r.items() if v != ""} for r in csv.DictReader(fh)]


def _auto(v):
    try:
        return float(v)
    except (TypeError, ValueError):
        return v


def _tire(case):
    from .catalog import get_tire
    from .geometry import TireGeometry

    rim = case.get("rim_width_mm")
    if "tire" in case and str(case["tire"]).strip() != "":
        key = case["tire"]
        key = str(int(key)) if isinstance(key, float) and key.is_integer() else key
        return get_tire(key, rim_width=rim)
    if "tire_radius_mm" in case and rim is not None:
        return TireGeometry(float(case["tire_radius_mm"]), float(rim))
    raise InvalidParameter(
        "tire", case.get("tire"), "a catalogue tire or tire_radius_mm + rim_width_mm"
    )


def solve_case(case: dict) -> dict:
    """One row: the case and its results (never raises: errors are recorded)."""
    from .lateral import Relaxation, solve_lateral, stiffnesses
    from .surface import parse_surface

    c = {**DEFAULTS, **case}
    row = dict(case)
    try:
        tire = _tire(c)
        r = solve_lateral(
            tire,
            pressure=0.1 * float(c["pressure_bar"]),
            load=float(c["load_N"]),
            camber=math.radians(float(c["camber_deg"])),
            slip=math.radians(float(c["slip_deg"])),
            lateral=float(c["lateral_mm"]),
            surface=parse_surface(str(c["surface"])),
            relaxation=Relaxation.uniform(float(c["relaxation"])),
            friction=float(c["friction"]),
        )
        p = r.patch
        row.update(
            {
                "status": "ok",
                "error": "",
                "tire_radius": tire.tire_radius,
                "rim_width": tire.rim_width,
                "deflection_mm": p.deflection,
                "sinkage_pct": 100 * p.sinkage,
                "length_mm": p.length,
                "width_mm": p.width,
                "area_mm2": p.area,
                "vertical_force_N": r.vertical_force,
                "lateral_force_N": r.lateral_force,
                "patch_lateral_force_N": r.patch_lateral_force,
                "net_force_orientation_deg": math.degrees(r.net_force_orientation),
                "pneumatic_trail_mm": r.pneumatic_trail,
                "aligning_moment_Nmm": r.aligning_moment,
                "relaxation_length_mm": r.relaxation_length[1],
            }
        )
        row.update(stiffnesses(r))
    except (TireModelError, ValueError) as exc:
        row.update(status="error", error=f"{type(exc).__name__}: {exc}")
    return row


def _vector_rows(cases: list[dict]) -> list[dict]:
    """Plain cases (no friction, no relaxation) solved together as arrays."""
    from .lateral import tangent_rule
    from .load import solve_many
    from .surface import parse_surface

    rows, tires = [], []
    for case in cases:
        tires.append(_tire({**DEFAULTS, **case}))
    c = [{**DEFAULTS, **case} for case in cases]
    surf = [parse_surface(str(x["surface"])) for x in c]
    drum = [s.diameter if s.kind == "drum" else np.inf for s in surf]
    disk = [s.diameter if s.kind == "disk" else np.inf for s in surf]
    cam = np.radians([float(x["camber_deg"]) for x in c])
    side = [s.center_side(g) if s.kind == "disk" else 1.0 for s, g in zip(surf, cam, strict=True)]
    out = solve_many(
        tire_radius=[t.tire_radius for t in tires],
        rim_width=[t.rim_width for t in tires],
        bead_seat_diameter=[t.bead_seat_diameter for t in tires],
        pressure=[0.1 * float(x["pressure_bar"]) for x in c],
        load=[float(x["load_N"]) for x in c],
        camber=cam,
        slip=np.radians([float(x["slip_deg"]) for x in c]),
        lateral=[float(x["lateral_mm"]) for x in c],
        drum_diameter=drum,
        disk_diameter=disk,
        disk_side=side,
        n_sections=65,
    )
    for i, case in enumerate(cases):
        fy, fz = float(out["lateral_force"][i]), float(out["vertical_force"][i])
        row = dict(case)
        row.update(
            {
                "status": "ok",
                "error": "",
                "tire_radius": tires[i].tire_radius,
                "rim_width": tires[i].rim_width,
                "deflection_mm": float(out["deflection"][i]),
                "sinkage_pct": 100 * float(out["sinkage"][i]),
                "length_mm": float(out["length"][i]),
                "width_mm": float(out["width"][i]),
                "area_mm2": float(out["area"][i]),
                "vertical_force_N": fz,
                "lateral_force_N": fy,
                "net_force_orientation_deg": math.degrees(float(out["net_force_orientation"][i])),
            }
        )
        deg = float(c[i]["camber_deg"])
        if deg:
            row["norm_camber_stiffness_1_deg"] = fy / fz / deg
            row["tangent_rule_agreement"] = row["norm_camber_stiffness_1_deg"] / float(
                tangent_rule(deg)
            )
            row["camber_thrust_deficiency"] = 1 - row["tangent_rule_agreement"]
        if c[i]["lateral_mm"]:
            row["norm_lateral_stiffness_1_mm"] = fy / fz / float(c[i]["lateral_mm"])
        rows.append(row)
    return rows


def run_sweep(
    cases: list[dict],
    *,
    workers: int | None = None,
    scheduler: str | None = None,
    progress: bool = False,
) -> list[dict]:
    """Solve every case; rows in the order of ``cases``."""
    plain = [
        i
        for i, c in enumerate(cases)
        if float(c.get("friction", math.inf)) == math.inf
        and not float(c.get("relaxation", 0.0))
        and not float(c.get("slip_deg", 0.0))
    ]
    rows: list = [None] * len(cases)
    if plain:
        try:
            for i, r in zip(plain, _vector_rows([cases[i] for i in plain]), strict=True):
                rows[i] = r
        except (TireModelError, ValueError):
            for i in plain:  # one bad case: fall back to one by one, recording errors
                rows[i] = solve_case(cases[i])
    rest = [i for i in range(len(cases)) if rows[i] is None]
    for i, r in zip(
        rest, _map([cases[i] for i in rest], workers, scheduler, progress), strict=True
    ):
        rows[i] = r
    return rows


def _map(cases, workers, scheduler, progress):
    if not cases:
        return []
    if scheduler:
        from dask.distributed import Client

        with Client(scheduler, timeout="30s") as client:
            return client.gather(client.map(solve_case, cases, pure=False))
    n = workers if workers is not None else (os.cpu_count() or 1)
    if n <= 1 or len(cases) < 4:
        return [solve_case(c) for c in cases]
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(max_workers=n, mp_context=mp.get_context("forkserver")) as pool:
        return list(pool.map(solve_case, cases, chunksize=max(1, len(cases) // (4 * n))))


def write_rows(rows: list[dict], path) -> Path:
    from ._io import atomic_path

    cols = list(dict.fromkeys(k for r in rows for k in r))
    with atomic_path(path) as tmp, tmp.open("w", newline="", encoding="utf-8") as fh:
        w = csv.DictWriter(fh, fieldnames=cols, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    return Path(path)


def sweep_plots(rows: list[dict], out_dir) -> list[Path]:
    """Normalized stiffness vs pressure and load; tangent-rule agreement vs tire radius
    over rim width (Figure 6-2). PNG and SVG."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from ._io import atomic_path

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    ok = [r for r in rows if r.get("status") == "ok"]
    written = []
    for key, label in (
        ("norm_lateral_stiffness_1_mm", "normalized lateral stiffness [1/mm]"),
        ("norm_camber_stiffness_1_deg", "normalized camber stiffness [1/deg]"),
        ("norm_cornering_stiffness_1_deg", "normalized cornering stiffness [1/deg]"),
    ):
        rs = [r for r in ok if key in r]
        if not rs:
            continue
        fig, axes = plt.subplots(1, 2, figsize=(10, 4))
        for ax, xk in zip(axes, ("pressure_bar", "load_N"), strict=True):
            groups = {}
            for r in rs:
                other = "load_N" if xk == "pressure_bar" else "pressure_bar"
                groups.setdefault(
                    (str(r.get("tire", r.get("tire_radius_mm"))), r.get(other)), []
                ).append(r)
            for (tire, val), g in sorted(groups.items(), key=lambda kv: str(kv[0])):
                g.sort(key=lambda r: float(r[xk]))
                ax.plot(
                    [float(r[xk]) for r in g],
                    [float(r[key]) for r in g],
                    marker="o",
                    ms=3,
                    label=f"{tire}, {val:g}",
                )
            ax.set_xlabel(xk.replace("_", " "))
            ax.set_ylabel(label)
            ax.grid(alpha=0.3)
        axes[1].legend(fontsize=6)
        written += _save(fig, out / key, atomic_path, plt)
    rs = [r for r in ok if "tangent_rule_agreement" in r]
    if rs:
        fig, ax = plt.subplots(figsize=(6, 4))
        sc = ax.scatter(
            [r["tire_radius"] / r["rim_width"] for r in rs],
            [100 * r["tangent_rule_agreement"] for r in rs],
            c=[r["sinkage_pct"] for r in rs],
            s=12,
        )
        fig.colorbar(sc, label="sinkage [%]")
        ax.axhline(100, color="k", lw=0.8)
        ax.set_xlabel("tire radius / rim width")
        ax.set_ylabel("agreement with the tangent rule [%]")
        ax.set_title("Camber thrust vs the tangent rule (cf. Figure 6-2)")
        ax.grid(alpha=0.3)
        written += _save(fig, out / "tangent_rule_agreement", atomic_path, plt)
    return written


def _save(fig, stem, atomic_path, plt):
    paths = []
    for ext in (".png", ".svg"):
        with atomic_path(stem.with_suffix(ext)) as tmp:
            fig.savefig(
                tmp,
                format=ext[1:],
                bbox_inches="tight",
                dpi=120,
                metadata={} if ext == ".png" else {"Date": None},
            )
        paths.append(stem.with_suffix(ext))
    plt.close(fig)
    return paths
