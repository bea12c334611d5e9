"""Rows of ``measured-dressel2013.csv`` as validation points.

Every row of the table becomes one :class:`Point` with a status, so that no row is
dropped silently:

``compared``          a measurement the model can reproduce at its stated conditions;
                      counted in the statistics
``duplicate``         the same measurement printed again (another unit, another table)
``ambiguous``         modelled, but the source states two loads; not counted
``summary``           a statistic over many prints or tests: compared in the summary table
``not a measurement`` averaged by the author (``interpolated_in_source``)
``not modelled``      outside what the model describes (reason given)
``model input``       the carcass arc length (Table 3-2), an input of the model
``model error``       the model raised a named error (set by :mod:`.validate`)
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field, replace

from tiremesh.units import MM_PER_IN, N_PER_KG

#: quantity -> (label, unit, where the dissertation gives it); the unit of ``measured``
QUANTITIES = {
    "lateral_stiffness": ("static lateral stiffness", "N/mm", "Appendix B captions"),
    "cornering_stiffness": (
        "normalized cornering stiffness",
        "1/deg",
        "Appendix B, Tables 4-4, 4-5, 4-6",
    ),
    "camber_stiffness": (
        "normalized camber stiffness",
        "1/deg",
        "Appendix B, Tables 4-4, 4-5, 4-6",
    ),
    "pneumatic_trail": ("mean pneumatic trail", "mm", "Appendix B, Table 4-4, 4.1.8"),
    "aligning_stiffness": ("normalized self-aligning torque stiffness", "m/deg", "Table 4-4"),
    "ink_area": ("ink-print area", "mm^2", "4.1.1"),
    "load_per_area": ("load / ink-print area", "N/mm^2", "4.1.1"),
    "ellipse_length": ("fitted-ellipse length", "mm", "4.1.1, 4.1.8"),
    "ellipse_width": ("fitted-ellipse width", "mm", "4.1.1"),
    "ellipse_area": ("fitted-ellipse area", "mm^2", "4.1.1"),
    "lateral_stiffness_extreme": (
        "normalized lateral stiffness, max and min over the test program",
        "1/mm",
        "Table 4-3",
    ),
    "decay_length": ("1/e distance of a point-load deflection", "mm", "3.11.4"),
    "tire_radius": ("tire radius r0 (calculated by the author)", "mm", "Table 3-2"),
    "true_size": ("true size 2 r0 (calculated by the author)", "mm", "Table 3-2"),
}
#: quantities that are not measurements (calculated in the source from the arc length)
GEOMETRY = ("tire_radius", "true_size")

#: CSV quantity -> (quantity, conversion of the printed value to the quantity's unit)
CSV_QUANTITIES = {
    "static_lateral_stiffness": ("lateral_stiffness", "as printed"),
    "normalized_static_lateral_stiffness": ("lateral_stiffness", "times load"),
    "cornering_stiffness": ("cornering_stiffness", "per load"),
    "normalized_cornering_stiffness": ("cornering_stiffness", "as printed"),
    "camber_stiffness": ("camber_stiffness", "per load"),
    "normalized_camber_stiffness": ("camber_stiffness", "as printed"),
    "mean_pneumatic_trail": ("pneumatic_trail", "as printed"),
    "pneumatic_trail": ("pneumatic_trail", "as printed"),
    "normalized_self_aligning_torque_stiffness": ("aligning_stiffness", "as printed"),
    "contact_patch_ink_area": ("ink_area", "as printed"),
    "contact_patch_load_over_ink_area": ("load_per_area", "as printed"),
    "contact_patch_ellipse_length": ("ellipse_length", "as printed"),
    "contact_patch_length_on_drum": ("ellipse_length", "as printed"),
    "contact_patch_ellipse_width": ("ellipse_width", "as printed"),
    "contact_patch_ellipse_area": ("ellipse_area", "as printed"),
    "normalized_static_lateral_stiffness_max": ("lateral_stiffness_extreme", "as printed"),
    "normalized_static_lateral_stiffness_min": ("lateral_stiffness_extreme", "as printed"),
    "distance_to_1_over_e_of_point_load_deflection": ("decay_length", "inch"),
    "tire_radius_r0_calc": ("tire_radius", "as printed"),
    "true_size_2r0_calc": ("true_size", "as printed"),
}

#: CSV quantity -> summary item (compared in the summary table, :mod:`.validate_stats`)
SUMMARY_ITEMS = {
    "contact_patch_length_over_width_": "length_over_width",
    "drum_over_plate_": "table_4_1",
    "contact_patch_length_over_area": "length_over_area",
    "mean_trail_over_patch_length_avg": "trail_over_length",
    "rim_width_increase_vs_norm_lat_stiffness_increase": "rim_width",
    "decay_length_over_contact_patch_length": "decay_over_length",
    "normalized_camber_stiffness_range_TU_Delft": "maxxis_camber_range",
    "normalized_cornering_stiffness_range": "cornering_range",
    "normalized_camber_stiffness_range": "camber_range",
    "normalized_static_lateral_stiffness_avg": "table_4_3",
    "corr_true_size_vs_": "table_4_3",
}

#: CSV quantity -> why the model does not reproduce it
NOT_MODELLED = {
    "normalized_twisting_torque_stiffness": (
        "the Rotta model has no longitudinal forces, so a cambered patch carries no "
        "twisting torque (4.1.7; Table 4-4's two runs differ by 81 %)"
    ),
    "decay_length_static_point_load": (
        "Schwalbe Durango 23-622 is not in Table 3-2 (no arc length or rim width)"
    ),
    "wheel_lateral_stiffness": "a property of the wheel, not of the tire (3.10.3)",
    "lateral_stiffness_uncertainty_device2_device3": (
        "measurement uncertainty (3.8.4, 3.9.4): quoted as context, not modelled"
    ),
}

#: test-program corners of Table 4-3 (3.45-6.21 bar, 324-731 N): where the measured
#: normalized lateral stiffness, rising with pressure and falling with load (6.2.4
#: item 1), has its max and min
TABLE_4_3_CORNERS = {"max": (6.21, 324.0), "min": (3.45, 731.0)}
#: printed values agreeing within this relative difference are the same measurement
SAME_VALUE_RTOL = 0.02


@dataclass(frozen=True)
class Condition:
    """A measured configuration: tire (Table 3-2), pressure, load, surface.

    ``load_N`` is NaN for unloaded rows, ``pressure_bar`` NaN for off-test rows;
    ``surface`` is ``'drum'`` (TU Delft 2.5 m), ``'flat'`` or ``''`` (off-test).

    Attributes
    ----------
    tire_id : int
        Tire number of Table 3-2.
    tire : str
        Tire name.
    arc_length : float [mm]
        Carcass arc length, bead to bead (Table 3-2).
    rim_width : float [mm]
        Rim width (Table 3-2).
    pressure_bar : float [bar]
        Inflation pressure (NaN off-test).
    load_N : float [N]
        Vertical load (NaN unloaded).
    surface : str
        ``'drum'``, ``'flat'``, ``''`` (off-test / not stated) or ``'device 1'``
        (rim width not recorded; not modelled).
    """

    tire_id: int
    tire: str
    arc_length: float
    rim_width: float
    pressure_bar: float = math.nan
    load_N: float = math.nan
    surface: str = ""


@dataclass
class Point:
    """One CSV row as a validation point (module docstring for ``status``).

    Attributes
    ----------
    row : int
        1-based data-row number of the CSV.
    csv_quantity, source, locator, value_kind, printed, printed_unit : str
        The row's ``quantity``, ``table_or_figure``, ``locator``, ``value_kind``,
        ``value`` and ``unit`` cells, as printed.
    status : str
        ``compared``, ``duplicate``, ``ambiguous``, ``summary``... (module docstring).
    quantity : str
        Key of :data:`QUANTITIES` ('' if none).
    measured : float
        The value in the quantity's unit (:data:`QUANTITIES`; NaN if none).
    condition : Condition or None
        Where it was measured.
    reason : str
        Why the status (or a caveat).
    item : str
        Summary item (:data:`SUMMARY_ITEMS`) of a ``summary`` row.
    alt_load_N : float [N]
        The second load the source states (NaN if it states only one).
    model, model_alt : float
        The model's value at the load and at ``alt_load_N`` (unit of ``measured``).
    modulus : float [N/mm^2]
        Casing modulus used (rate-dependent quantities).
    rate : float [per mm]
        Relaxation rate used (rate-dependent quantities).
    extra : dict
        Free-form extras.
    """

    row: int
    csv_quantity: str
    source: str
    locator: str
    value_kind: str
    printed: str
    printed_unit: str
    status: str
    quantity: str = ""
    measured: float = math.nan
    condition: Condition | None = None
    reason: str = ""
    item: str = ""
    alt_load_N: float = math.nan
    model: float = math.nan
    model_alt: float = math.nan
    modulus: float = math.nan
    rate: float = math.nan
    extra: dict = field(default_factory=dict)

    @property
    def ratio(self) -> float:
        """model / measured (NaN if either is missing)."""
        if self.measured and math.isfinite(self.measured) and math.isfinite(self.model):
            return self.model / self.measured
        return math.nan


def _number(text) -> float:
    try:
        return float(str(text).strip())
    except ValueError:
        return math.nan


def parse_load(text: str) -> tuple[float, float]:
    """A load cell in N: ``'304'`` -> 304, ``'33 kg'`` -> 33 x 9.81 (Appendix C's g);
    ``'450 or 540 (...)'`` -> (450, 540); anything else -> NaN.

    Parameters
    ----------
    text : str
        The ``load_N`` cell of a CSV row.

    Returns
    -------
    (load, alternative) : (float, float) [N]
        The alternative is NaN unless the source states two loads.
    """
    text = str(text).strip()
    m = re.fullmatch(r"([\d.]+)\s*kg", text)
    if m:
        return float(m.group(1)) * N_PER_KG, math.nan
    m = re.fullmatch(r"([\d.]+)\s+or\s+([\d.]+).*", text)
    if m:
        return float(m.group(1)), float(m.group(2))
    return _number(text), math.nan


def parse_surface(text: str) -> str | None:
    """``'drum'``, ``'flat'``, ``''`` (off-test / not stated) or None (device 1, whose
    rim width was not recorded: Table 4-5).

    Parameters
    ----------
    text : str
        The ``surface`` cell of a CSV row.

    Returns
    -------
    str or None
        ``'drum'`` or ``'flat'`` if the text names a drum or a flat plate (and no
        comparison, "vs"); None if it names device 1; else ``''``.
    """
    t = str(text).lower()
    if "device 1" in t:
        return None
    if "drum" in t and "vs" not in t:
        return "drum"
    if "flat plate" in t and "vs" not in t:
        return "flat"
    return ""


def condition_of(row: dict) -> tuple[Condition | None, float]:
    """The row's condition and its alternative load (NaN if none); None if the row
    names no Table 3-2 tire.

    Parameters
    ----------
    row : dict
        A row of :func:`.validate_data.read_measurements`.

    Returns
    -------
    condition : Condition or None
        None unless the ``tire`` cell reads ``'<id>: <name>'`` and the arc length and
        rim width are numbers; ``surface`` is ``'device 1'`` for device 1 rows.
    alt_load : float [N]
        The second load the source states (:func:`parse_load`), else NaN.
    """
    m = re.match(r"\s*(\d+):\s*(.*)", row.get("tire", ""))
    arc, rim = _number(row.get("arc_length_mm")), _number(row.get("rim_width_mm"))
    if not m or not (math.isfinite(arc) and math.isfinite(rim)):
        return None, math.nan
    load, alt = parse_load(row.get("load_N", ""))
    surface = parse_surface(row.get("surface", ""))
    cond = Condition(
        int(m.group(1)),
        m.group(2).strip(),
        arc,
        rim,
        _number(row.get("pressure_bar")),
        load,
        surface if surface is not None else "device 1",
    )
    return cond, alt


def _base(row: dict, status: str, **kw) -> Point:
    return Point(
        row=int(row["row"]),
        csv_quantity=row.get("quantity", ""),
        source=row.get("table_or_figure", ""),
        locator=row.get("locator", ""),
        value_kind=row.get("value_kind", ""),
        printed=row.get("value", ""),
        printed_unit=row.get("unit", ""),
        status=status,
        **kw,
    )


def _convert(value: float, how: str, load: float) -> float:
    return {"as printed": value, "times load": value * load, "per load": value / load}.get(
        how, value * MM_PER_IN if how == "inch" else math.nan
    )


def _measured_point(row: dict, quantity: str, how: str) -> Point:
    """A row of a modelled quantity: compared, or why not."""
    cond, alt = condition_of(row)
    value = _convert(_number(row.get("value")), how, cond.load_N if cond else math.nan)
    if row.get("value_kind") == "interpolated_in_source":
        return _base(
            row,
            "not a measurement",
            quantity=quantity,
            measured=value,
            condition=cond,
            reason="the author's average of the two neighbouring rows (Table 4-6)",
        )
    if cond is None:
        return _base(row, "not modelled", quantity=quantity, reason="no Table 3-2 tire")
    if cond.surface == "device 1":
        return _base(
            row,
            "not modelled",
            quantity=quantity,
            measured=value,
            condition=cond,
            reason="device 1: rim width not recorded (Table 4-5)",
        )
    if quantity == "lateral_stiffness_extreme":
        which = "max" if row["quantity"].endswith("_max") else "min"
        p, f = TABLE_4_3_CORNERS[which]
        cond = replace(cond, pressure_bar=p, load_N=f)
        return _base(
            row,
            "compared",
            quantity=quantity,
            measured=value,
            condition=cond,
            reason=f"conditions inferred: the {which} sits at {p} bar, {f:g} N "
            "(corner of the program; monotone trends of 6.2.4 item 1)",
        )
    status = "ambiguous" if math.isfinite(alt) else "compared"
    reason = f"load stated as {cond.load_N:g} N and as {alt:g} N" if status == "ambiguous" else ""
    if quantity == "decay_length":
        reason = "approximate: read from a photograph (3.11.4); unloaded tire"
    return _base(
        row,
        status,
        quantity=quantity,
        measured=value,
        condition=cond,
        reason=reason,
        alt_load_N=alt,
    )


def classify(row: dict) -> Point:
    """The :class:`Point` of one CSV row (duplicates are found by :func:`mark_duplicates`).

    Parameters
    ----------
    row : dict
        A row of :func:`.validate_data.read_measurements` (with ``row``).

    Returns
    -------
    Point
    """
    q = row.get("quantity", "")
    if q == "carcass_arc_length_bead_to_bead":
        return _base(row, "model input", reason="the model's input (Table 3-2)")
    if q in NOT_MODELLED:
        return _base(row, "not modelled", reason=NOT_MODELLED[q])
    for prefix, item in SUMMARY_ITEMS.items():
        if q.startswith(prefix):
            cond = condition_of(row)[0]
            return _base(
                row, "summary", item=item, condition=cond, reason="compared in the summary table"
            )
    if q in CSV_QUANTITIES:
        quantity, how = CSV_QUANTITIES[q]
        return _measured_point(row, quantity, how)
    return _base(row, "not modelled", reason=f"no model counterpart for {q!r}")


def _same_condition(a: Condition, b: Condition) -> bool:
    close = lambda x, y: (math.isnan(x) and math.isnan(y)) or abs(x - y) <= 0.01 * abs(y)
    return (
        a.tire_id == b.tire_id
        and a.surface == b.surface
        and close(a.pressure_bar, b.pressure_bar)
        and close(a.load_N, b.load_N)
    )


def _duplicate_of(p: Point, kept: Point) -> str:
    """Why ``p`` repeats ``kept`` ('' if it does not)."""
    if p.quantity != kept.quantity or not _same_condition(p.condition, kept.condition):
        return ""
    if p.source == kept.source and p.locator == kept.locator:
        if p.csv_quantity == kept.csv_quantity:
            return ""  # two runs of one table (Table 4-4)
        return f"the same caption's value in another unit (row {kept.row})"
    if abs(math.log(p.measured / kept.measured)) <= SAME_VALUE_RTOL:
        return f"the same measurement as row {kept.row} ({kept.source})"
    return ""


def _rank(p: Point) -> tuple:
    """Which of two equal points to keep: the quantity's own unit, then a table."""
    how = CSV_QUANTITIES.get(p.csv_quantity, ("", ""))[1]
    return (how != "as printed", p.value_kind != "table_exact", p.row)


def mark_duplicates(points: list[Point]) -> list[Point]:
    """Mark repeated measurements as ``duplicate`` (in place; returns ``points``).

    Within one caption the same value in another unit (N/deg and 1/deg), and across
    tables the same condition with a value equal within :data:`SAME_VALUE_RTOL`;
    two rows of one table at one condition (Table 4-4's runs) are both kept. A Table
    4-3 extreme equal to an Appendix B point at its inferred condition is a duplicate.

    Parameters
    ----------
    points : list of Point
        From :func:`classify`; only ``compared`` and ``ambiguous`` points are
        considered.

    Returns
    -------
    list of Point
        ``points`` itself, the repeats with status ``duplicate`` and the kept row
        named in ``reason``.
    """
    live = [p for p in points if p.status in ("compared", "ambiguous")]
    kept: list[Point] = []
    for p in sorted(live, key=_rank):
        why = next((w for k in kept if (w := _duplicate_of(p, k))), "")
        if why:
            p.status, p.reason = "duplicate", why
        else:
            kept.append(p)
    lateral = [p for p in kept if p.quantity == "lateral_stiffness"]
    for p in kept:
        if p.quantity != "lateral_stiffness_extreme":
            continue
        for k in lateral:
            norm = k.measured / k.condition.load_N
            if _same_condition(p.condition, k.condition) and abs(math.log(p.measured / norm)) <= (
                SAME_VALUE_RTOL
            ):
                p.status, p.reason = "duplicate", f"the same measurement as row {k.row}"
    return points


def classify_all(rows: list[dict]) -> list[Point]:
    """:func:`classify` every row, then :func:`mark_duplicates`.

    Parameters
    ----------
    rows : list of dict
        Rows of :func:`.validate_data.read_measurements`.

    Returns
    -------
    list of Point
        One point per row, in row order.
    """
    return mark_duplicates([classify(r) for r in rows])


__all__ = [
    "CSV_QUANTITIES",
    "GEOMETRY",
    "NOT_MODELLED",
    "QUANTITIES",
    "SUMMARY_ITEMS",
    "TABLE_4_3_CORNERS",
    "Condition",
    "Point",
    "classify",
    "classify_all",
    "condition_of",
    "mark_duplicates",
    "parse_load",
    "parse_surface",
]
