"""Pair ink prints with the Rotta model (section 6.2, Figure 6-3).

Every print row of an ``inkprint batch`` table (status ``ok``) is paired with the
model solved at the same tire, rim, pressure, load and surface (plate -> flat
ground, drum -> a drum of ``drum_diameter_mm``, default the 2.5 m TU Delft drum).
Each distinct load case is solved once. The model's pointed patch is compared both
raw and through its fitted ellipse, as section 5.4 does (the Appendix C ellipse:
least squares on the patch edges and centre line); the print's ellipse is the direct
fit to its hull. A print the model cannot solve (a load beyond what the tire carries
at that pressure, an unknown tire) gets a recorded reason, not a crash.

Columns read: ``tire_id`` or ``tire`` (catalogue, Table 3-2) or ``arc_length_mm`` /
``tire_radius_mm``; ``rim_width_mm`` (optional override); ``pressure_bar``;
``load_N``; ``surface`` (plate | flat | drum | disk); ``drum_diameter_mm``;
``bead_seat_diameter_mm``.
"""

from __future__ import annotations

import math

from ._util import number as _num
from .errors import InvalidInput

DRUM_DIAMETER_MM = 2500.0  # TU Delft (section 3.4)
MODEL_KEYS = (
    "model_status",
    "model_error",
    "model_deflection_mm",
    "model_sinkage_pct",
    "model_length_mm",
    "model_width_mm",
    "model_area_mm2",
    "model_ellipse_length_mm",
    "model_ellipse_width_mm",
    "model_ellipse_area_mm2",
    "model_outline_wkt",
)
RATIO_KEYS = (
    "ratio_length",
    "ratio_width",
    "ratio_area",
    "ratio_ellipse_length",
    "ratio_ellipse_width",
    "ratio_ellipse_area",
)


def tire_of(row):
    """TireGeometry of a table row (catalogue id or name, or explicit dimensions)."""
    import tiremesh as tm

    rim = _num(row.get("rim_width_mm"))
    bead = _num(row.get("bead_seat_diameter_mm")) or 622.0
    tid = str(row.get("tire_id", "") or "").strip()
    if tid:
        return tm.get_tire(tid, rim_width=rim)
    arc, radius = _num(row.get("arc_length_mm")), _num(row.get("tire_radius_mm"))
    if rim is not None and arc is not None:
        return tm.TireGeometry.from_arc_length(
            arc, rim, bead_seat_diameter=bead, name=str(row.get("tire", ""))
        )
    if rim is not None and radius is not None:
        return tm.TireGeometry(radius, rim, bead, name=str(row.get("tire", "")))
    name = str(row.get("tire", "") or "").strip()
    if name:
        return tm.get_tire(name, rim_width=rim)
    raise InvalidInput(
        "tire", row.get("tire"), "a tire_id, a catalogue name, or arc_length_mm + rim_width_mm"
    )


def surface_of(row):
    """Support surface of a row: plate/flat -> Flat, drum -> Drum, disk -> Disk."""
    import tiremesh as tm

    kind = str(row.get("surface", "plate") or "plate").strip().lower()
    if kind in ("plate", "flat", "ground", "floor", "track"):
        return tm.Flat()
    if kind == "drum":
        return tm.Drum(_num(row.get("drum_diameter_mm")) or DRUM_DIAMETER_MM)
    if kind == "disk":
        return tm.Disk(_num(row.get("disk_diameter_mm")) or 3000.0)
    raise InvalidInput("surface", kind, "plate | flat | drum | disk")


def solve_case(tire, pressure: float, load: float, surface) -> dict:
    """Model columns for one load case (pressure [N/mm^2], load [N])."""
    import tiremesh as tm

    from .model import appendix_ellipse

    p = tm.solve(tire, load=load, pressure=pressure, surface=surface)
    e = appendix_ellipse(p)
    ring = ", ".join(
        f"{x:.4f} {y:.4f}" for x, y in p.outline
    )  # ground frame: x forward, y lateral
    return {
        "model_status": "ok",
        "model_error": "",
        "model_deflection_mm": p.deflection,
        "model_sinkage_pct": 100 * p.sinkage,
        "model_length_mm": p.length,
        "model_width_mm": p.width,
        "model_area_mm2": p.area,
        "model_ellipse_length_mm": e.length if e else math.nan,
        "model_ellipse_width_mm": e.width if e else math.nan,
        "model_ellipse_area_mm2": e.area if e else math.nan,
        "model_outline_wkt": f"POLYGON (({ring}))",
    }


def pair_prints(rows: list[dict], *, cache: dict | None = None) -> list[dict]:
    """Paired table: every print row with the model's columns and the ratios.

    Parameters
    ----------
    rows : list of dict
        An ``inkprint batch`` table (values as read from CSV are fine).
    cache : dict, optional
        Load-case cache shared across calls (key -> model columns); each distinct
        case is solved once.

    Returns
    -------
    list of dict
        Rows with ``MODEL_KEYS`` and ``RATIO_KEYS`` added; rows that are not ``ok``
        prints get ``model_status = 'skipped'``.
    """
    from tiremesh import TireModelError

    cache = {} if cache is None else cache
    out = []
    for row in rows:
        r = dict(row)
        if str(row.get("status", "ok")) != "ok":
            r.update(
                {k: "" for k in MODEL_KEYS},
                model_status="skipped",
                model_error="print not measured",
            )
            out.append(r)
            continue
        try:
            tire = tire_of(row)
            surface = surface_of(row)
            p_bar, load = _num(row.get("pressure_bar")), _num(row.get("load_N"))
            if p_bar is None or load is None:
                raise InvalidInput(
                    "pressure_bar/load_N",
                    (row.get("pressure_bar"), row.get("load_N")),
                    "numbers (pressure in bar, load in N)",
                )
            key = (tire.tire_radius, tire.rim_width, tire.bead_seat_diameter, p_bar, load, surface)
            if key not in cache:
                cache[key] = solve_case(tire, 0.1 * p_bar, load, surface)
            r.update(cache[key])
            r["model_tire"] = tire.name
        except (TireModelError, InvalidInput, ValueError) as exc:
            r.update(
                {k: "" for k in MODEL_KEYS},
                model_status="error",
                model_error=f"{type(exc).__name__}: {exc}",
            )
        r.update(_ratios(r))
        out.append(r)
    return out


def _ratios(r: dict) -> dict:
    def ratio(a, b):
        x, y = _num(r.get(a)), _num(r.get(b))
        return x / y if x is not None and y else math.nan

    return {
        "ratio_length": ratio("length_mm", "model_length_mm"),
        "ratio_width": ratio("width_mm", "model_width_mm"),
        "ratio_area": ratio("hull_area_mm2", "model_area_mm2"),
        "ratio_ellipse_length": ratio("ellipse_length_mm", "model_ellipse_length_mm"),
        "ratio_ellipse_width": ratio("ellipse_width_mm", "model_ellipse_width_mm"),
        "ratio_ellipse_area": ratio("ellipse_area_mm2", "model_ellipse_area_mm2"),
    }
