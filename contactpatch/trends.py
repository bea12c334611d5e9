"""Trends of patch size with pressure and load, prints and model (sections 4.1.1, 6.2).

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

from ._util import number_or_nan as _f
from .errors import InvalidInput

QUANTITIES = {
    "length": ("length_mm", "model_length_mm"),
    "width": ("width_mm", "model_width_mm"),
    "area": ("hull_area_mm2", "model_area_mm2"),
}


def power_law_fit(x_pressure, x_load, y) -> dict:
    """Exponents of ``y ~ p^b F^c`` by least squares in logs.

    Returns
    -------
    dict with ``b`` (pressure exponent), ``c`` (load exponent), ``r2``, ``n``;
    NaN where a variable does not vary or there are too few points.
    """
    p, f, yy = (np.asarray(a, float) for a in (x_pressure, x_load, y))
    ok = (p > 0) & (f > 0) & (yy > 0) & np.isfinite(p) & np.isfinite(f) & np.isfinite(yy)
    p, f, yy = np.log(p[ok]), np.log(f[ok]), np.log(yy[ok])
    cols, names = [np.ones_like(yy)], []
    for arr, name in ((p, "b"), (f, "c")):
        if arr.size and np.ptp(arr) > 1e-12:
            cols.append(arr)
            names.append(name)
    out = {"b": math.nan, "c": math.nan, "r2": math.nan, "n": int(yy.size)}
    if yy.size < len(cols) + (1 if len(cols) > 2 else 0) or len(cols) == 1:
        return out
    A = np.column_stack(cols)
    coef, *_ = np.linalg.lstsq(A, yy, rcond=None)
    for name, value in zip(names, coef[1:], strict=True):
        out[name] = float(value)
    resid = yy - A @ coef
    ss = float(np.sum((yy - yy.mean()) ** 2))
    out["r2"] = 1.0 - float(np.sum(resid**2)) / ss if ss > 0 else math.nan
    return out


def trend_table(paired: list[dict], *, group_keys=("tire", "surface")) -> list[dict]:
    """One row per group and quantity: pressure and load exponents, prints and model."""
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
    """Section 6.2.4 style counts: per quantity and variable, in how many groups the
    prints and the model increase / decrease, and how often they agree."""
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
    """'Print length decreases with pressure in 6 of 6 cases; the model agrees in 6 of 6.'"""
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

    Returns
    -------
    pairs : list of dict
        One row per matched (drum, plate) pair with the ratios.
    summary : list of dict
        Table 4-1: per quantity max, min, mean, stdev of the ratio.
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


def rim_sensitivity(paired: list[dict], *, step: float = 0.1) -> list[dict]:
    """Model d log(y) / d log(rim width) per tire at its median load case (plate),
    by central differences of +-``step`` in rim width."""
    import tiremesh as tm

    from .compare import tire_of

    if not 0 < step < 0.5:
        raise InvalidInput("step", step, "(0, 0.5)")
    by_tire = defaultdict(list)
    for r in paired:
        if r.get("model_status") == "ok":
            by_tire[str(r.get("tire", ""))].append(r)
    out = []
    for name in sorted(by_tire):
        rs = sorted(by_tire[name], key=lambda r: (_f(r["pressure_bar"]), _f(r["load_N"])))
        r = rs[len(rs) // 2]
        tire = tire_of(r)
        vals = {}
        for sgn in (-1, 1):
            t = tm.TireGeometry(
                tire.tire_radius, tire.rim_width * (1 + sgn * step), tire.bead_seat_diameter
            )
            try:
                p = tm.solve(t, load=_f(r["load_N"]), pressure=0.1 * _f(r["pressure_bar"]))
            except tm.TireModelError:
                vals = {}
                break
            vals[sgn] = (p.length, p.width, p.area)
        if not vals:
            continue
        d = math.log((1 + step) / (1 - step))
        row = {
            "tire": name,
            "rim_width_mm": tire.rim_width,
            "pressure_bar": _f(r["pressure_bar"]),
            "load_N": _f(r["load_N"]),
        }
        for i, q in enumerate(("length", "width", "area")):
            row[f"dlog_{q}_dlog_rim"] = math.log(vals[1][i] / vals[-1][i]) / d
        out.append(row)
    return out
