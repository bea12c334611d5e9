"""Trends of patch size with pressure and load, prints and model (Dressel 2013,
sections 4.1.1, 6.2).

* :func:`power_law_fit`: per group (tire, surface), the log-log regression
  ``log y = a + b log p + c log F`` -> the exponents of pressure (``b``) and load
  (``c``), with R^2; where only one of the two varies, only its exponent.
* :func:`sign_agreement`: the way section 6.2.4 counts ("increases with pressure in
  11 of 11 cases"), for prints and model, and how often they agree.
* :func:`drum_plate_ratios`: drum over plate for prints taken at the same load case,
  summarised like Table 4-1 (max, min, mean, stdev).
* :func:`rim_sensitivity`: the model's d log(y) / d log(rim width).
"""

from __future__ import annotations

import math
from collections import defaultdict

import numpy as np

import tiremesh as tm
from tiremesh.io import cell_number_or_nan as _f

from ..errors import InvalidInput
from .compare import case_of

#: a log-variable spanning less than this does not vary (no exponent is fitted)
LOG_SPAN_ATOL = 1e-12
#: Table 4-1 of the dissertation: measured drum / plate ratios of prints
DISSERTATION_TABLE_4_1 = [
    {"quantity": "length_mm", "max": 1.05, "min": 0.81, "mean": 0.92, "stdev": 0.031},
    {"quantity": "width_mm", "max": 1.32, "min": 0.83, "mean": 1.12, "stdev": 0.085},
    {"quantity": "hull_area_mm2", "max": 1.19, "min": 0.68, "mean": 1.04, "stdev": 0.082},
]
QUANTITIES = {
    "length": ("length_mm", "model_length_mm"),
    "width": ("width_mm", "model_width_mm"),
    "area": ("hull_area_mm2", "model_area_mm2"),
}


def log_design(x_pressure, x_load, y) -> tuple[np.ndarray, list[str], np.ndarray]:
    """Design of the log-log regression ``log y = a + b log p + c log F``.

    Points with a value <= 0 or not finite in any of the three are left out; a
    variable whose logs span less than :data:`LOG_SPAN_ATOL` gets no column.

    Parameters
    ----------
    x_pressure : (n,) float [bar]
    x_load : (n,) float [N]
    y : (n,) float

    Returns
    -------
    A : (m, k) float
        Design matrix: a column of ones, then ``log p`` and/or ``log F``
        (``k`` = 1 to 3, ``m`` <= n points kept).
    names : list of str
        Exponent name of each column after the first (``"b"``, ``"c"``).
    log_y : (m,) float
        ``log y`` of the points kept.
    """
    p, f, yy = (np.asarray(a, float) for a in (x_pressure, x_load, y))
    ok = (p > 0) & (f > 0) & (yy > 0) & np.isfinite(p) & np.isfinite(f) & np.isfinite(yy)
    p, f, yy = np.log(p[ok]), np.log(f[ok]), np.log(yy[ok])
    cols, names = [np.ones_like(yy)], []
    for arr, name in ((p, "b"), (f, "c")):
        if arr.size and np.ptp(arr) > LOG_SPAN_ATOL:
            cols.append(arr)
            names.append(name)
    return np.column_stack(cols), names, yy


def power_law_fit(x_pressure, x_load, y) -> dict:
    """Exponents of ``y ~ p^b F^c`` by least squares in logs.

    Parameters
    ----------
    x_pressure : (n,) float [bar]
        Inflation pressures (any unit: only ratios matter).
    x_load : (n,) float [N]
        Loads.
    y : (n,) float
        The size (length, width or area); points with a value <= 0 or not finite in
        any of the three are left out.

    Returns
    -------
    dict
        ``b`` (pressure exponent), ``c`` (load exponent), ``r2`` (coefficient of
        determination in logs), ``n`` (points used); NaN where a variable does not
        vary or there are too few points.
    """
    A, names, yy = log_design(x_pressure, x_load, y)
    out = {"b": math.nan, "c": math.nan, "r2": math.nan, "n": int(yy.size)}
    if yy.size < A.shape[1] + (1 if A.shape[1] > 2 else 0) or A.shape[1] == 1:
        return out
    coef, *_ = np.linalg.lstsq(A, yy, rcond=None)
    for name, value in zip(names, coef[1:], strict=True):
        out[name] = float(value)
    resid = yy - A @ coef
    ss = float(np.sum((yy - yy.mean()) ** 2))
    out["r2"] = 1.0 - float(np.sum(resid**2)) / ss if ss > 0 else math.nan
    return out


def trend_table(paired: list[dict], *, group_keys=("tire", "surface")) -> list[dict]:
    """Pressure and load exponents of length, width and area, prints and model.

    Parameters
    ----------
    paired : list of dict
        Rows of :func:`contactpatch.pair_prints`; only rows with both the print and
        the model ``ok`` count.
    group_keys : tuple of str
        Columns that define a group (one power-law fit each).

    Returns
    -------
    list of dict
        One row per group and quantity: the group keys, ``quantity``, ``n``,
        ``print_pressure_exp``, ``model_pressure_exp``, ``print_load_exp``,
        ``model_load_exp``, ``print_r2``, ``model_r2``.
    """
    groups = defaultdict(list)
    for r in paired:
        if r.get("status", "ok") == "ok" and r.get("model_status") == "ok":
            groups[tuple(str(r.get(k, "")) for k in group_keys)].append(r)
    rows = []
    for key in sorted(groups):
        rs = groups[key]
        p = [_f(r.get("pressure_bar")) for r in rs]
        f = [_f(r.get("load_N")) for r in rs]
        for q, (pk, mk) in QUANTITIES.items():
            fp = power_law_fit(p, f, [_f(r.get(pk)) for r in rs])
            fm = power_law_fit(p, f, [_f(r.get(mk)) for r in rs])
            rows.append(
                {
                    **dict(zip(group_keys, key, strict=True)),
                    "quantity": q,
                    "n": fp["n"],
                    "print_pressure_exp": fp["b"],
                    "model_pressure_exp": fm["b"],
                    "print_load_exp": fp["c"],
                    "model_load_exp": fm["c"],
                    "print_r2": fp["r2"],
                    "model_r2": fm["r2"],
                }
            )
    return rows


def sign_agreement(trends: list[dict]) -> list[dict]:
    """Section 6.2.4 style counts of how sizes change with pressure and load.

    Parameters
    ----------
    trends : list of dict
        Rows of :func:`trend_table`.

    Returns
    -------
    list of dict
        Per quantity and variable (``pressure``, ``load``): ``cases`` (groups with
        both exponents), ``print_increases``, ``model_increases`` and ``agree`` (same
        sign).
    """
    out = []
    for q in QUANTITIES:
        for var in ("pressure", "load"):
            pe = [t[f"print_{var}_exp"] for t in trends if t["quantity"] == q]
            me = [t[f"model_{var}_exp"] for t in trends if t["quantity"] == q]
            both = [
                (a, b) for a, b in zip(pe, me, strict=True) if np.isfinite(a) and np.isfinite(b)
            ]
            if not both:
                continue
            n = len(both)
            out.append(
                {
                    "quantity": q,
                    "variable": var,
                    "cases": n,
                    "print_increases": sum(a > 0 for a, _ in both),
                    "model_increases": sum(b > 0 for _, b in both),
                    "agree": sum(np.sign(a) == np.sign(b) for a, b in both),
                }
            )
    return out


def describe_agreement(row: dict) -> str:
    """One row of :func:`sign_agreement` as a sentence.

    Parameters
    ----------
    row : dict
        A row of :func:`sign_agreement`.

    Returns
    -------
    str
        E.g. 'Print length decreases with pressure in 6 of 6 cases; the model agrees
        in 6 of 6.'
    """
    n, inc = row["cases"], row["print_increases"]
    word = "increases" if inc >= n - inc else "decreases"
    k = inc if word == "increases" else n - inc
    return (
        f"Print {row['quantity']} {word} with {row['variable']} in {k} of {n} cases; "
        f"the model agrees in {row['agree']} of {n}."
    )


def drum_plate_ratios(
    rows: list[dict],
    *,
    keys=("length_mm", "width_mm", "hull_area_mm2"),
    match=("tire", "pressure_bar", "load_N"),
) -> tuple[list[dict], list[dict]]:
    """Drum over plate ratios for prints (or model columns) of the same load case.

    Parameters
    ----------
    rows : list of dict
        Print rows (or paired rows with the model's columns renamed to the print's).
    keys : tuple of str
        Columns to take ratios of.
    match : tuple of str
        Columns that must agree for a drum row and a plate row to pair up.

    Returns
    -------
    pairs : list of dict
        One row per matched (drum, plate) pair with the ratios.
    summary : list of dict
        Table 4-1: per quantity ``max``, ``min``, ``mean``, ``stdev`` of the ratio
        and ``n``.
    """
    by_case = defaultdict(lambda: {"drum": [], "plate": []})
    for r in rows:
        if r.get("status", "ok") != "ok":
            continue
        s = str(r.get("surface", "")).lower()
        s = "plate" if s in ("plate", "flat") else s
        if s in ("drum", "plate"):
            by_case[tuple(str(r.get(k, "")) for k in match)][s].append(r)
    pairs = []
    for case in sorted(by_case):
        d = by_case[case]
        for drum, plate in zip(d["drum"], d["plate"], strict=False):
            row = dict(zip(match, case, strict=True))
            for k in keys:
                a, b = _f(drum.get(k)), _f(plate.get(k))
                row[k] = a / b if b else math.nan
            pairs.append(row)
    summary = []
    for k in keys:
        v = np.array([p[k] for p in pairs if np.isfinite(p[k])])
        if v.size:
            summary.append(
                {
                    "quantity": k,
                    "max": float(v.max()),
                    "min": float(v.min()),
                    "mean": float(v.mean()),
                    "stdev": float(v.std(ddof=1)) if v.size > 1 else math.nan,
                    "n": int(v.size),
                }
            )
    return pairs, summary


def _median_case(rows: list[dict]) -> dict:
    """The middle row by (pressure, load)."""
    rows = sorted(rows, key=lambda r: (_f(r["pressure_bar"]), _f(r["load_N"])))
    return rows[len(rows) // 2]


def _sizes(case: tm.LoadCase) -> tuple[float, float, float] | None:
    """Model length, width [mm] and area [mm^2], or None if it cannot be solved."""
    try:
        p = tm.solve(case)
    except tm.TireModelError:
        return None
    return p.length, p.width, p.area


def rim_sensitivity(paired: list[dict], *, step: float = 0.1) -> list[dict]:
    """The model's d log(size) / d log(rim width) per tire, on flat ground.

    Central differences of +-``step`` in rim width at each tire's median load case
    (by pressure, then load).

    Parameters
    ----------
    paired : list of dict
        Rows of :func:`contactpatch.pair_prints` (rows with the model ``ok`` count).
    step : float [-]
        Relative rim-width change, in (0, 0.5).

    Returns
    -------
    list of dict
        Per tire: ``tire``, ``rim_width_mm``, ``pressure_bar``, ``load_N`` and
        ``dlog_{length,width,area}_dlog_rim``; tires the model cannot solve at either
        rim width are left out.
    """
    if not 0 < step < 0.5:
        raise InvalidInput("step", step, "(0, 0.5)")
    by_tire = defaultdict(list)
    for r in paired:
        if r.get("model_status") == "ok":
            by_tire[str(r.get("tire", ""))].append(r)
    out = []
    for name in sorted(by_tire):
        r = _median_case(by_tire[name])
        case = case_of(r).replace(surface=tm.Flat())
        tire = case.tire
        sizes = [
            _sizes(
                case.replace(
                    tire=tm.TireGeometry(
                        tire.tire_radius,
                        tire.rim_width * (1 + sgn * step),
                        tire.bead_seat_diameter,
                    )
                )
            )
            for sgn in (-1, 1)
        ]
        if None in sizes:
            continue
        d = math.log((1 + step) / (1 - step))
        row = {
            "tire": name,
            "rim_width_mm": tire.rim_width,
            "pressure_bar": _f(r["pressure_bar"]),
            "load_N": _f(r["load_N"]),
        }
        for i, q in enumerate(("length", "width", "area")):
            row[f"dlog_{q}_dlog_rim"] = math.log(sizes[1][i] / sizes[0][i]) / d
        out.append(row)
    return out
