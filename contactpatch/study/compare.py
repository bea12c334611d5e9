"""Pair ink prints with the Rotta model (Dressel 2013, section 6.2, Figure 6-3).

Every print row of an ``inkprint batch`` table (status ``ok``) is paired with the
model solved at the row's load case, built by :func:`case_of` (the one place a table
row becomes a :class:`tiremesh.LoadCase`): same tire, rim, pressure, load and surface
(plate -> flat ground, drum -> a drum of ``drum_diameter_mm``, default the 2.5 m TU
Delft drum; disk -> a disk of ``disk_diameter_mm``, default 3 m). Each distinct load
case is solved once. The model's pointed patch is compared both raw and through its
fitted ellipse, as section 5.4 does (the Appendix C ellipse: least squares on the
patch edges and centre line); the print's ellipse is the direct fit to its hull. A
print the model cannot solve (a load beyond what the tire carries at that pressure,
an unknown tire) gets a recorded reason, not a crash.

Columns read: ``tire_id`` or ``tire`` (catalogue, Table 3-2) or ``arc_length_mm`` /
``tire_radius_mm``; ``rim_width_mm`` (optional override); ``bead_seat_diameter_mm``;
``pressure_bar``; ``load_N``; ``surface`` (plate | flat | drum | disk, or a
:func:`tiremesh.parse_surface` form such as ``drum:2000``); ``drum_diameter_mm``,
``disk_diameter_mm``.
"""

from __future__ import annotations

import math

import tiremesh as tm
from tiremesh.io import cell_number

from ..errors import InvalidInput
from ..ruler.model import appendix_ellipse

#: default diameters [mm] of the test rigs when a row names only the kind
DEFAULT_DIAMETER_MM = {"drum": 2500.0, "disk": 3000.0}  # TU Delft drum (section 3.4)
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
    "model_rounded_length_mm",
    "model_rounded_width_mm",
    "model_rounded_area_mm2",
)
#: print / model ratios: name -> (print column, model column)
RATIOS = {
    "ratio_length": ("length_mm", "model_length_mm"),
    "ratio_width": ("width_mm", "model_width_mm"),
    "ratio_area": ("hull_area_mm2", "model_area_mm2"),
    "ratio_ellipse_length": ("ellipse_length_mm", "model_ellipse_length_mm"),
    "ratio_ellipse_width": ("ellipse_width_mm", "model_ellipse_width_mm"),
    "ratio_ellipse_area": ("ellipse_area_mm2", "model_ellipse_area_mm2"),
    "ratio_rounded_length": ("length_mm", "model_rounded_length_mm"),
    "ratio_rounded_width": ("width_mm", "model_rounded_width_mm"),
    "ratio_rounded_area": ("hull_area_mm2", "model_rounded_area_mm2"),
}
#: the paired table's leading columns (the others follow in first-seen order)
PAIRED_COLUMNS = [
    "file",
    "print",
    "tire",
    "surface",
    "pressure_bar",
    "load_N",
    "length_mm",
    "model_length_mm",
    "ratio_length",
    "width_mm",
    "model_width_mm",
    "ratio_width",
    "hull_area_mm2",
    "model_area_mm2",
    "ratio_area",
    "ellipse_length_mm",
    "model_ellipse_length_mm",
    "ratio_ellipse_length",
    "net_to_gross",
    "load_per_hull_area_pct",
    "model_sinkage_pct",
    "model_status",
    "model_error",
]


def tire_of(row: dict) -> tm.TireGeometry:
    """The tire of a table row.

    Parameters
    ----------
    row : dict
        With ``tire_id`` (catalogue id or name), or ``arc_length_mm`` or
        ``tire_radius_mm`` with ``rim_width_mm``, or ``tire`` (a catalogue name);
        optional ``rim_width_mm`` [mm] and ``bead_seat_diameter_mm`` [mm] (622).

    Returns
    -------
    tiremesh.TireGeometry

    Raises
    ------
    InvalidInput
        The row names no tire.
    tiremesh.InvalidParameter
        The catalogue does not know the tire, or the dimensions are invalid.
    """
    rim = cell_number(row.get("rim_width_mm"))
    bead = cell_number(row.get("bead_seat_diameter_mm")) or 622.0
    name = str(row.get("tire", "") or "").strip()
    tid = str(row.get("tire_id", "") or "").strip()
    if tid:
        return tm.get_tire(tid, rim_width=rim)
    arc, radius = cell_number(row.get("arc_length_mm")), cell_number(row.get("tire_radius_mm"))
    if rim is not None and arc is not None:
        return tm.TireGeometry.from_arc_length(arc, rim, bead_seat_diameter=bead, name=name)
    if rim is not None and radius is not None:
        return tm.TireGeometry(radius, rim, bead, name=name)
    if name:
        return tm.get_tire(name, rim_width=rim)
    raise InvalidInput(
        "tire", row.get("tire"), "a tire_id, a catalogue name, or arc_length_mm + rim_width_mm"
    )


def surface_of(row: dict) -> tm.Surface:
    """The support surface of a table row.

    Parameters
    ----------
    row : dict
        ``surface``: plate | flat | drum | disk (default plate), or any
        :func:`tiremesh.parse_surface` form; a bare drum or disk takes
        ``drum_diameter_mm`` / ``disk_diameter_mm`` [mm] from the row, else
        :data:`DEFAULT_DIAMETER_MM`.

    Returns
    -------
    tiremesh.Surface

    Raises
    ------
    tiremesh.InvalidParameter
        An unknown surface.
    """
    spec = str(row.get("surface", "") or "plate").strip().lower()
    if spec in DEFAULT_DIAMETER_MM:
        diameter = cell_number(row.get(f"{spec}_diameter_mm")) or DEFAULT_DIAMETER_MM[spec]
        spec = f"{spec}:{diameter!r}"
    return tm.parse_surface(spec)


def case_of(row: dict) -> tm.LoadCase:
    """The model's load case of a print-table row.

    Parameters
    ----------
    row : dict
        Tire columns (:func:`tire_of`), surface columns (:func:`surface_of`),
        ``pressure_bar`` [bar] and ``load_N`` [N]; values may be CSV strings.

    Returns
    -------
    tiremesh.LoadCase
        Hashable: equal rows give equal cases.

    Raises
    ------
    InvalidInput
        Missing pressure or load, or no tire.
    tiremesh.InvalidParameter
        A value outside the model's domain.
    """
    tire = tire_of(row)
    surface = surface_of(row)
    p_bar, load = cell_number(row.get("pressure_bar")), cell_number(row.get("load_N"))
    if p_bar is None or load is None:
        raise InvalidInput(
            "pressure_bar/load_N",
            (row.get("pressure_bar"), row.get("load_N")),
            "numbers (pressure in bar, load in N)",
        )
    return tm.LoadCase.from_units(tire, pressure_bar=p_bar, load_N=load, surface=surface)


def solve_case(case: tm.LoadCase) -> dict:
    """The model's columns for one load case.

    Parameters
    ----------
    case : tiremesh.LoadCase

    Returns
    -------
    dict
        :data:`MODEL_KEYS`: deflection [mm], sinkage [%], length, width [mm], area
        [mm^2], the Appendix C ellipse (section 5.4), the outline as WKT (ground
        ``x`` forward, ``y`` lateral [mm]) and the rounded print footprint's length,
        width [mm] and area [mm^2] (:mod:`tiremesh.footprint`: the case's own if it
        asks for one, else the fitted defaults; NaN if it vanishes).

    Raises
    ------
    tiremesh.TireModelError
        The model cannot solve the case (e.g. the load is too high).
    """
    p = tm.solve(case)
    e = appendix_ellipse(p)
    ring = ", ".join(f"{x:.4f} {y:.4f}" for x, y in p.outline)
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
        **_rounded_columns(p),
    }


def _rounded_columns(p) -> dict:
    """The rounded footprint's columns next to the plain patch's."""
    from tiremesh.footprint import Footprint, FootprintVanished, rounded_footprint

    fp = p.case.footprint if p.case.footprint.kind == "rounded" else Footprint("rounded")
    try:
        r = rounded_footprint(p.outline, fp)
        vals = (r.length, r.width, r.area)
    except FootprintVanished:
        vals = (math.nan,) * 3
    names = ("model_rounded_length_mm", "model_rounded_width_mm", "model_rounded_area_mm2")
    return dict(zip(names, vals, strict=True))


def _failed(status: str, error: str) -> dict:
    return {**{k: "" for k in MODEL_KEYS}, "model_status": status, "model_error": error}


def _model_columns(row: dict, cache: dict) -> dict:
    """Model columns of one ``ok`` print row, from the cache when the case repeats."""
    try:
        case = case_of(row)
    except (tm.TireModelError, InvalidInput, ValueError) as exc:
        return _failed("error", f"{type(exc).__name__}: {exc}")
    if case not in cache:
        try:
            cache[case] = solve_case(case)
        except (tm.TireModelError, ValueError) as exc:
            cache[case] = _failed("error", f"{type(exc).__name__}: {exc}")
    return {**cache[case], "model_tire": case.tire.name}


def ratios(row: dict) -> dict:
    """Print over model for the columns of :data:`RATIOS`.

    Parameters
    ----------
    row : dict
        A paired row.

    Returns
    -------
    dict of str to float
        NaN where a value is missing or the model's is 0.
    """
    out = {}
    for name, (a, b) in RATIOS.items():
        x, y = cell_number(row.get(a)), cell_number(row.get(b))
        out[name] = x / y if x is not None and y else math.nan
    return out


def pair_prints(rows: list[dict], *, cache: dict | None = None) -> list[dict]:
    """Every print row with the model's columns and the print / model ratios.

    Parameters
    ----------
    rows : list of dict
        An ``inkprint batch`` table (values as read from CSV are fine).
    cache : dict, optional
        Shared across calls: :class:`tiremesh.LoadCase` -> model columns; each
        distinct case is solved once (failures are remembered too).

    Returns
    -------
    list of dict
        Rows with :data:`MODEL_KEYS`, ``model_tire`` and the :data:`RATIOS` added;
        rows that are not ``ok`` prints get ``model_status = 'skipped'``.
    """
    cache = {} if cache is None else cache
    out = []
    for row in rows:
        r = dict(row)
        if str(row.get("status", "ok")) != "ok":
            r.update(_failed("skipped", "print not measured"))
        else:
            r.update(_model_columns(row, cache))
        r.update(ratios(r))
        out.append(r)
    return out
