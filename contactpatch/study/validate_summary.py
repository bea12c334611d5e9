"""The model against the dissertation's summary statistics (rows with status
``summary`` in :mod:`.validate_points`): statistics over prints or tests whose
individual values are lost, so the model is summarised the same way over the
measured conditions it can reproduce.

A check whose measured row is missing from the measurements, or that has no model
value to compare, reads ``n/a`` with the reason; a named model error reads
``model error``. Agreement rules, stated in every row: a single stated value agrees when the model is
within a factor :data:`FACTOR` of it; a stated spread (max / min) when the model's mean
lies inside it; a stated range when the model's range covers it (``<a to >b``) or
overlaps it (``a-b``); a correlation when its sign is the same.
"""

from __future__ import annotations

import math
import re
from dataclasses import replace

import numpy as np

from tiremesh import TireModelError
from tiremesh.units import MPA_PER_BAR

from ..errors import ContactPatchError
from .validate_model import ModelRunner, Undefined
from .validate_points import Condition, Point
from .validate_stats import distinct_conditions

#: a single stated value agrees within this factor
FACTOR = 1.25
#: quantities whose conditions make up the summary's condition set (device 3, drum)
DRUM_QUANTITIES = (
    "lateral_stiffness",
    "cornering_stiffness",
    "camber_stiffness",
    "pneumatic_trail",
)
#: the test program of Table 4-3 (its footer: 3.45-6.21 bar; loads of Appendix B)
PROGRAM = {"pressure_bar": (3.45, 4.83, 6.21), "load_N": (324.0, 540.0, 731.0)}


def _printed(points: list[Point], csv_quantity: str) -> float:
    """The printed number of the summary row ``csv_quantity``; ValueError if the
    measurements have no such row (the check then reads 'n/a')."""
    for p in points:
        if p.csv_quantity == csv_quantity:
            return float(p.printed)
    raise ValueError(f"no row {csv_quantity!r} in the measurements")


def _row(item, source, quantity, measured, model, agree, rule, note="", ratio=math.nan):
    return {
        "item": item,
        "source": source,
        "quantity": quantity,
        "measured": measured,
        "model": model,
        "ratio": ratio,
        "agree": agree,
        "rule": rule,
        "note": note,
    }


def _spread(v) -> str:
    """'mean, sd, min, max (n)' of ``v``; ValueError if empty."""
    v = np.asarray(v, float)
    if v.size == 0:
        raise ValueError("no measured condition to summarise the model over")
    sd = v.std(ddof=1) if v.size > 1 else 0.0
    # a spread below 1e-9 of the mean is rounding (area x pressure = load): shown as 0
    sd = 0.0 if sd <= 1e-9 * max(abs(v.mean()), 1.0) else sd
    return f"mean {v.mean():.3g}, sd {sd:.2g}, min {v.min():.3g}, max {v.max():.3g} (n = {v.size})"


def _single(item, source, quantity, measured: float, model: float, note="", unit=""):
    if not math.isfinite(model):
        raise ValueError("no model value")
    ratio = model / measured
    agree = "yes" if 1 / FACTOR <= ratio <= FACTOR else "no"
    return _row(
        item,
        source,
        quantity,
        f"{measured:g}{unit}",
        f"{model:.3g}{unit}",
        agree,
        f"within x{FACTOR} of the stated value",
        note,
        ratio,
    )


def table_4_1(runner: ModelRunner, conds: list[Condition], points: list[Point]) -> list[dict]:
    """Drum / plate ratios of length, width and area (Table 4-1) vs the model's over
    ``conds`` (ellipse length and width; patch area, which is load / pressure on both).

    Parameters
    ----------
    runner : ModelRunner
    conds : list of Condition
        Measured drum conditions; each is also solved on a flat plate.
    points : list of Point
        Holding the printed summary rows ``drum_over_plate_*`` [%].

    Returns
    -------
    list of dict
        Three rows of :func:`summary_table` (length, width, area); agreement when
        the model's mean ratio lies inside the measured min..max.

    Raises
    ------
    ValueError
        If a printed row is missing or ``conds`` is empty.
    """
    rows = []
    for q, key in (("length", "ellipse_length"), ("width", "ellipse_width"), ("area", "ink_area")):
        model = [
            runner.value(key, c) / runner.value(key, replace(c, surface="flat")) for c in conds
        ]
        m = {
            s: _printed(points, f"drum_over_plate_{q}_{s}") / 100
            for s in ("mean", "min", "max", "stdev")
        }
        mean = float(np.mean(model))
        agree = "yes" if m["min"] <= mean <= m["max"] else "no"
        note = "area x pressure = load on any surface (6.1.1)" if q == "area" else ""
        rows.append(
            _row(
                "table_4_1",
                "Table 4-1",
                f"drum / plate {q}",
                f"mean {m['mean']:.3g}, sd {m['stdev']:.2g}, min {m['min']:.3g}, max {m['max']:.3g}",
                _spread(model),
                agree,
                "model mean inside the measured min..max",
                note,
                mean / m["mean"],
            )
        )
    return rows


def length_over_width(runner: ModelRunner, conds, points) -> dict:
    """Patch length / width (4.1.10 item 8) vs the model's ellipse on the drum.

    Parameters
    ----------
    runner : ModelRunner
    conds : list of Condition
        Measured drum conditions.
    points : list of Point
        Holding the printed summary rows ``contact_patch_length_over_width_*``.

    Returns
    -------
    dict
        A row of :func:`summary_table`; agreement when the model's mean lies inside
        the measured min..max.
    """
    v = [runner.value("ellipse_length", c) / runner.value("ellipse_width", c) for c in conds]
    m = {
        s: _printed(points, f"contact_patch_length_over_width_{s}")
        for s in ("mean", "stdev", "min", "max")
    }
    mean = float(np.mean(v))
    agree = "yes" if m["min"] <= mean <= m["max"] else "no"
    return _row(
        "length_over_width",
        "4.1.10 item 8",
        "patch length / width",
        f"mean {m['mean']:g}, sd {m['stdev']:g}, min {m['min']:g}, max {m['max']:g}",
        _spread(v),
        agree,
        "model mean inside the measured min..max",
        "",
        mean / m["mean"],
    )


def length_over_area(runner: ModelRunner, conds, points) -> dict:
    """Length / area 'about 0.076' per mm (1.2.1) vs the model's ellipse length / area.

    Parameters
    ----------
    runner : ModelRunner
    conds : list of Condition
        Measured drum conditions.
    points : list of Point
        Holding the printed summary row.

    Returns
    -------
    dict
        A row of :func:`summary_table`: the model's mean [1/mm] (ellipse length over
        patch area) within a factor :data:`FACTOR` of the stated value.
    """
    v = [runner.value("ellipse_length", c) / runner.value("ink_area", c) for c in conds]
    stated = _printed(points, "contact_patch_length_over_area")
    return _single(
        "length_over_area",
        "1.2.1",
        "patch length / area [1/mm]",
        stated,
        float(np.mean(v)),
        f"model {_spread(v)}; the source says 'about'",
    )


def trail_over_length(runner: ModelRunner, conds, points) -> dict:
    """Mean trail / patch length, 12.76 % (4.1.8), vs the model's trail over its
    ellipse length (median over ``conds``, the conditions of the cornering and trail
    measurements; conditions where the model's trail is undefined,
    :func:`.validate_model.trail`, are counted in the note).

    Parameters
    ----------
    runner : ModelRunner
    conds : list of Condition
        Measured drum conditions of the cornering-stiffness and trail points.
    points : list of Point
        Holding the printed summary row.

    Returns
    -------
    dict
        A row of :func:`summary_table`: the model's median [%] within a factor
        :data:`FACTOR` of the stated value.
    """
    v, skipped = [], 0
    for c in conds:
        try:
            v.append(runner.value("pneumatic_trail", c) / runner.value("ellipse_length", c) * 100)
        except Undefined:
            skipped += 1
    stated = _printed(points, "mean_trail_over_patch_length_avg")
    note = f"model {_spread(v)}; median shown; {skipped} conditions without a defined trail"
    return _single(
        "trail_over_length",
        "4.1.8",
        "mean trail / patch length [%]",
        stated,
        float(np.median(v)),
        note,
    )


def _numbers(points: list[Point], csv_quantity: str) -> list[float]:
    """The numbers in the printed text of summary row ``csv_quantity`` ('24 -> 23' ->
    [24, 23], '~3' -> [3]); ValueError if the row is missing."""
    text = next((p.printed for p in points if p.csv_quantity == csv_quantity), None)
    if text is None:
        raise ValueError(f"no row {csv_quantity!r} in the measurements")
    return [float(x) for x in re.findall(r"\d*\.?\d+", text)]


def rim_width(runner: ModelRunner, points: list[Point]) -> dict:
    """+24 % rim width -> +23 % normalized lateral stiffness (4.1.10 item 2) vs the
    model at every measured lateral-stiffness condition (median).

    Parameters
    ----------
    runner : ModelRunner
    points : list of Point
        The compared lateral-stiffness points give the conditions; the printed
        summary row gives both percentages.

    Returns
    -------
    dict
        A row of :func:`summary_table`: the model's median stiffness increase [%] for
        the stated rim-width increase, within a factor :data:`FACTOR` of the stated
        one.

    Raises
    ------
    ValueError
        If the row is missing or there is no measured lateral-stiffness condition.
    """
    rim_pct, stiff_pct = _numbers(points, "rim_width_increase_vs_norm_lat_stiffness_increase")
    conds = distinct_conditions(points, ("lateral_stiffness",))
    f = 1.0 + rim_pct / 100.0
    up = [
        (
            runner.value("lateral_stiffness", replace(c, rim_width=c.rim_width * f))
            / runner.value("lateral_stiffness", c)
            - 1
        )
        * 100
        for c in conds
    ]
    if not up:
        raise ValueError("no measured lateral-stiffness condition")
    return _single(
        "rim_width",
        "4.1.10 item 2; 6.2.2",
        f"stiffness increase for +{rim_pct:g} % rim [%]",
        stiff_pct,
        float(np.median(up)),
        f"model median over {len(up)} conditions, range {min(up):.3g}..{max(up):.3g} %; "
        "the decay length follows the wider rim's sections",
    )


def decay_over_length(runner: ModelRunner, conds, points) -> dict:
    """Decay length / patch length, '~3' when rolling (4.1.9.1), vs the model's taut-beam
    decay length over its ellipse length (Papadopoulos in 6.1.4: 'of order half').

    Parameters
    ----------
    runner : ModelRunner
        Its relaxation per tire gives the decay length.
    conds : list of Condition
        Measured drum conditions.
    points : list of Point
        Holding the printed summary row.

    Returns
    -------
    dict
        A row of :func:`summary_table`: the model's median ratio within a factor
        :data:`FACTOR` of the stated one.
    """
    (stated,) = _numbers(points, "decay_length_over_contact_patch_length")
    v = []
    for c in conds:
        relax = runner.relaxation(c.tire_id)
        ell = relax.length(runner.tire(c), c.pressure_bar * MPA_PER_BAR)
        v.append(ell / runner.value("ellipse_length", c))
    note = (
        f"model {_spread(v)}; the source says '~{stated:g}'; Papadopoulos found Rotta's "
        "decay length 'of order half the contact length' (6.1.4)"
    )
    return _single(
        "decay_over_length",
        "4.1.9.1",
        "decay length / patch length",
        stated,
        float(np.median(v)),
        note,
    )


def _bounds(text: str) -> tuple[float, float, bool]:
    """``'<0.15 to >0.35'`` -> (0.15, 0.35, True: must be covered); ``'a-b'`` ->
    (a, b, False: must overlap)."""
    nums = [float(x) for x in re.findall(r"\d*\.?\d+", text)]
    return nums[0], nums[-1], "<" in text


def stated_range(item, source, quantity, *, csv_quantity, points, model_values, note="") -> dict:
    """A stated range of a quantity vs the model's values at its measured conditions.

    Parameters
    ----------
    item : str
        Name of the check.
    source : str
        Where the dissertation states it.
    quantity : str
        Label, with its unit in brackets.
    csv_quantity : str
        The summary row whose printed text is the range (``'<a to >b'`` or ``'a-b'``).
    points : list of Point
    model_values : list of float
        The model's values (unit of the range).
    note : str

    Returns
    -------
    dict
        A row of :func:`summary_table`: agreement when the model's range covers a
        ``'<a to >b'`` range or overlaps an ``'a-b'`` range.

    Raises
    ------
    ValueError
        If the row is missing or there are no model values.
    """
    text = next((p.printed for p in points if p.csv_quantity == csv_quantity), "")
    if not text or not model_values:
        raise ValueError(f"no row {csv_quantity!r} or no model value to compare")
    lo, hi, cover = _bounds(text)
    mn, mx = min(model_values), max(model_values)
    ok = (mn <= lo and mx >= hi) if cover else (mn <= hi and mx >= lo)
    rule = "model range covers it" if cover else "model range overlaps it"
    return _row(
        item,
        source,
        quantity,
        text,
        f"{mn:.3g} to {mx:.3g} (n = {len(model_values)})",
        "yes" if ok else "no",
        rule,
        note,
    )


def _ranges(points: list[Point]) -> list[dict]:
    """The stated ranges of cornering and camber stiffness (abstract, 8.1.2, 7.2.1)."""
    model = lambda q, tire=None: [
        p.model
        for p in points
        if p.quantity == q and p.status == "compared" and tire in (None, p.condition.tire_id)
    ]
    return [
        stated_range(
            "cornering_range",
            "abstract; 8.1.2",
            "normalized cornering stiffness [1/deg]",
            csv_quantity="normalized_cornering_stiffness_range",
            points=points,
            model_values=model("cornering_stiffness"),
        ),
        stated_range(
            "camber_range",
            "abstract; 8.1.2",
            "normalized camber stiffness [1/deg]",
            csv_quantity="normalized_camber_stiffness_range",
            points=points,
            model_values=model("camber_stiffness"),
        ),
        stated_range(
            "maxxis_camber_range",
            "7.2.1",
            "Maxxis normalized camber stiffness [1/deg]",
            csv_quantity="normalized_camber_stiffness_range_TU_Delft",
            points=points,
            model_values=model("camber_stiffness", 6),
        ),
    ]


def table_4_3(runner: ModelRunner, points: list[Point]) -> list[dict]:
    """Table 4-3: correlation of true size with the max / min / avg normalized lateral
    stiffness of four 37-622 tires, vs the model over the test program's 3 x 3 grid.

    Parameters
    ----------
    runner : ModelRunner
    points : list of Point
        The ``table_4_3`` summary rows name the tires and print the correlations.

    Returns
    -------
    list of dict
        Three rows of :func:`summary_table` (max, min, avg): agreement when the
        model's correlation over :data:`PROGRAM` on the drum has the printed sign.

    Raises
    ------
    ValueError
        If fewer than 3 tires are named or a printed correlation is missing.
    """
    tires = {
        p.condition.tire_id: p.condition
        for p in points
        if p.item == "table_4_3" and p.condition is not None
    }
    stats = {"max": [], "min": [], "avg": []}
    size = []
    for tid in sorted(tires):
        c0 = tires[tid]
        v = [
            runner.value(
                "lateral_stiffness_extreme", replace(c0, pressure_bar=p, load_N=f, surface="drum")
            )
            for p in PROGRAM["pressure_bar"]
            for f in PROGRAM["load_N"]
        ]
        stats["max"].append(max(v))
        stats["min"].append(min(v))
        stats["avg"].append(float(np.mean(v)))
        size.append(2.0 * runner.tire(c0).tire_radius)
    if len(size) < 3:
        raise ValueError(f"a correlation needs 3 or more tires; the measurements name {len(size)}")
    rows = []
    for s, vals in stats.items():
        r_model = float(np.corrcoef(size, vals)[0, 1])
        r_meas = _printed(points, f"corr_true_size_vs_{s}_norm_lat_stiffness")
        agree = "yes" if np.sign(r_model) == np.sign(r_meas) else "no"
        rows.append(
            _row(
                "table_4_3",
                "Table 4-3; 6.2.3",
                f"correlation of true size with {s} norm. lateral stiffness",
                f"{r_meas:g}",
                f"{r_model:.3g}",
                agree,
                "same sign",
                f"tires {sorted(tires)}; model {s} per tire: "
                + ", ".join(f"{x:.3g}" for x in vals),
            )
        )
    return rows


def summary_table(runner: ModelRunner, points: list[Point]) -> list[dict]:
    """Every summary comparison (module docstring).

    Parameters
    ----------
    runner : ModelRunner
    points : list of Point
        With ``model`` set on the compared points.

    Returns
    -------
    list of dict
        ``item``, ``source`` (section), ``quantity``, ``measured``, ``model`` (text),
        ``ratio`` (model / measured where one number is compared), ``agree``, ``rule``,
        ``note``.
    """
    conds = distinct_conditions(points, DRUM_QUANTITIES)
    slip_conds = distinct_conditions(points, ("cornering_stiffness", "pneumatic_trail"))
    items = [
        (table_4_1, (runner, conds, points)),
        (length_over_width, (runner, conds, points)),
        (length_over_area, (runner, conds, points)),
        (trail_over_length, (runner, slip_conds, points)),
        (rim_width, (runner, points)),
        (decay_over_length, (runner, conds, points)),
        (_ranges, (points,)),
        (table_4_3, (runner, points)),
    ]
    rows = []
    for fn, args in items:
        try:
            out = fn(*args)
        except (TireModelError, ContactPatchError, ValueError) as exc:
            model_error = isinstance(exc, TireModelError | ContactPatchError)
            verdict = "model error" if model_error else "n/a"
            out = _row(
                fn.__name__.strip("_"),
                "",
                fn.__name__.strip("_"),
                "",
                "",
                verdict,
                "",
                f"{type(exc).__name__}: {exc}",
            )
        rows += out if isinstance(out, list) else [out]
    return rows


__all__ = [
    "DRUM_QUANTITIES",
    "FACTOR",
    "PROGRAM",
    "decay_over_length",
    "length_over_area",
    "length_over_width",
    "rim_width",
    "stated_range",
    "summary_table",
    "table_4_1",
    "table_4_3",
    "trail_over_length",
]
