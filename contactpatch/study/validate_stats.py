"""Statistics of model / measured and trend signs (sections 4.1.10, 6.2.4).

* :func:`ratio_stats`, :func:`quantity_table`: per quantity the number of points, the
  median, geometric-mean, smallest, largest and worst ratio and the RMS log error.
* :func:`trend_table`: what rises with pressure, load, rim width and carcass arc length
  in the measurements (pairs of measured conditions of one tire, and the counts the
  dissertation states) and in the model (the same pairs, and a 10 % step at every
  measured condition).
"""

from __future__ import annotations

import math
from collections import defaultdict
from dataclasses import replace

import numpy as np

from tiremesh import TireModelError

from ..errors import ContactPatchError
from .validate_model import ModelRunner
from .validate_points import GEOMETRY, QUANTITIES, Condition, Point

#: conditions whose pressure and load agree within this are the same condition
SAME_RTOL = 0.02
#: relative step of the model's finite differences per variable
STEPS = {"pressure": 0.10, "load": 0.10, "rim_width": 0.10, "arc_length": 0.05}
#: what the dissertation states about the measured trends:
#: (quantity, variable, measured direction, statement and section)
TREND_STATEMENTS = (
    (
        "lateral_stiffness",
        "pressure",
        "rises",
        "rises with pressure in 11 of 11 cases (6.2.4 item 1)",
    ),
    ("lateral_stiffness", "load", "falls", "falls with load in 12 of 12 cases (6.2.4 item 1)"),
    (
        "lateral_stiffness",
        "rim_width",
        "rises",
        "+24 % rim width gave +23 % (4.1.10 item 2; 6.2.2)",
    ),
    (
        "lateral_stiffness",
        "arc_length",
        "rises",
        "rises with arc length, 37-622 tires (Table 4-3; 6.2.3)",
    ),
    ("cornering_stiffness", "load", "falls", "falls with load in 14 of 14 cases (6.2.4 item 2)"),
    (
        "cornering_stiffness",
        "pressure",
        "mixed",
        "falls with pressure in 8 of 14, rises in 2, both in 4 (6.2.4 item 2)",
    ),
    ("camber_stiffness", "pressure", "falls", "falls with pressure in 13 of 14 (6.2.4 item 3)"),
    ("camber_stiffness", "load", "rises", "rises with load in 13 of 14 (6.2.4 item 3)"),
    ("pneumatic_trail", "pressure", "falls", "falls with pressure (4.1.10 item 7)"),
    ("pneumatic_trail", "load", "rises", "rises with load (4.1.10 item 7)"),
)


def ratio_stats(ratios) -> dict:
    """Summary of model / measured ratios.

    Parameters
    ----------
    ratios : sequence of float
        Positive ratios (others are ignored).

    Returns
    -------
    dict
        ``n``, ``median_ratio``, ``geomean_ratio``, ``min_ratio``, ``max_ratio``,
        ``worst_ratio`` (farthest from 1 in log) and ``rms_log_error`` over the positive
        ratios (NaN when there are none), and ``n_not_positive``: ratios left out
        because the model has the opposite sign, is zero or is not finite.
    """
    ratios = list(ratios)
    r = np.asarray([x for x in ratios if x > 0 and math.isfinite(x)], float)
    bad = len(ratios) - int(r.size)
    if r.size == 0:
        nan = math.nan
        return dict(
            n_not_positive=bad,
            n=0,
            median_ratio=nan,
            geomean_ratio=nan,
            min_ratio=nan,
            max_ratio=nan,
            worst_ratio=nan,
            rms_log_error=nan,
        )
    e = np.log(r)
    return {
        "n": int(r.size),
        "median_ratio": float(np.median(r)),
        "geomean_ratio": float(np.exp(e.mean())),
        "min_ratio": float(r.min()),
        "max_ratio": float(r.max()),
        "worst_ratio": float(r[np.argmax(np.abs(e))]),
        "rms_log_error": float(np.sqrt(np.mean(e**2))),
        "n_not_positive": bad,
    }


def quantity_table(points: list[Point]) -> list[dict]:
    """One row per quantity with compared points: :func:`ratio_stats` plus the label,
    unit, number of tires and conditions, and whether it is a measurement.

    Parameters
    ----------
    points : list of Point

    Returns
    -------
    list of dict
        In the order of :data:`.validate_points.QUANTITIES`.
    """
    out = []
    for q, (label, unit, where) in QUANTITIES.items():
        pts = [p for p in points if p.quantity == q and p.status == "compared"]
        if not pts:
            continue
        row = {"quantity": q, "label": label, "unit": unit, "source": where}
        row.update(ratio_stats([p.ratio for p in pts]))
        worst = max(pts, key=lambda p: abs(math.log(p.ratio)) if p.ratio > 0 else math.inf)
        row["worst_row"] = worst.row
        row["n_tires"] = len({p.condition.tire_id for p in pts})
        row["n_conditions"] = len({p.condition for p in pts})
        row["kind"] = "calculated in the source" if q in GEOMETRY else "measured"
        out.append(row)
    return out


def trend_value(quantity: str, value: float, cond: Condition) -> float:
    """The value whose trend is counted: normalized (per load) for lateral stiffness,
    as 6.2.4 counts it; the value itself otherwise.

    Parameters
    ----------
    quantity : str
        Key of :data:`.validate_points.QUANTITIES`.
    value : float
        Measured or model value (unit of the quantity).
    cond : Condition
        Its condition (``load_N`` [N] normalizes the lateral stiffness).

    Returns
    -------
    float
        ``value / load_N`` [1/mm] for ``lateral_stiffness``, else ``value``.
    """
    return value / cond.load_N if quantity == "lateral_stiffness" else value


def _by_condition(points: list[Point], quantity: str) -> dict[Condition, Point]:
    """Compared points of ``quantity`` by condition (repeated runs: the first)."""
    out: dict[Condition, Point] = {}
    for p in points:
        if p.quantity == quantity and p.status == "compared" and p.condition not in out:
            out[p.condition] = p
    return out


def _differs_only_in(a: Condition, b: Condition, variable: str) -> bool:
    rel = lambda x, y: abs(x - y) / max(abs(x), abs(y))
    dp, df = rel(a.pressure_bar, b.pressure_bar), rel(a.load_N, b.load_N)
    if a.tire_id != b.tire_id or a.surface != b.surface:
        return False
    if variable == "pressure":
        return dp > SAME_RTOL and df <= SAME_RTOL
    if variable == "load":
        return df > SAME_RTOL and dp <= SAME_RTOL
    return False


def measured_pairs(points: list[Point], quantity: str, variable: str) -> list[tuple]:
    """Pairs of compared points of one tire differing only in ``variable``.

    Parameters
    ----------
    points : list of Point
    quantity : str
        Key of :data:`.validate_points.QUANTITIES`.
    variable : str
        ``'pressure'`` or ``'load'`` (others give no pairs); the two conditions
        differ in it by more than :data:`SAME_RTOL` and agree in the other within it.

    Returns
    -------
    list of (Point, Point)
        Ordered so that ``variable`` increases from the first to the second.
    """
    by = _by_condition(points, quantity)
    conds = list(by)
    var = {"pressure": "pressure_bar", "load": "load_N"}.get(variable)
    pairs = []
    for i, a in enumerate(conds):
        for b in conds[i + 1 :]:
            if var and _differs_only_in(a, b, variable):
                lo, hi = sorted((a, b), key=lambda c: getattr(c, var))
                pairs.append((by[lo], by[hi]))
    return pairs


def stepped(cond: Condition, variable: str) -> Condition:
    """``cond`` with ``variable`` increased by its :data:`STEPS` fraction.

    Parameters
    ----------
    cond : Condition
    variable : str
        A key of :data:`STEPS`: ``'pressure'``, ``'load'``, ``'rim_width'`` or
        ``'arc_length'``.

    Returns
    -------
    Condition
        A copy with that field multiplied by ``1 + STEPS[variable]``.
    """
    f = 1.0 + STEPS[variable]
    field = {"pressure": "pressure_bar", "load": "load_N"}.get(variable, variable)
    return replace(cond, **{field: getattr(cond, field) * f})


def model_signs(runner: ModelRunner, quantity: str, conds, variable: str) -> list:
    """Sign of the model's change when ``variable`` steps up, at each condition (None
    where the model raises a named error at either point).

    Parameters
    ----------
    runner : ModelRunner
    quantity : str
        Key of :data:`.validate_points.QUANTITIES`.
    conds : iterable of Condition
    variable : str
        A key of :data:`STEPS` (:func:`stepped`).

    Returns
    -------
    list of int or None
        Per condition the sign (-1, 0 or 1) of the change of :func:`trend_value`.
    """
    signs = []
    for c in conds:
        c2 = stepped(c, variable)
        try:
            y1 = trend_value(quantity, runner.value(quantity, c), c)
            y2 = trend_value(quantity, runner.value(quantity, c2), c2)
        except (TireModelError, ContactPatchError):
            signs.append(None)
            continue
        signs.append(int(np.sign(y2 - y1)))
    return signs


def direction(signs) -> str:
    """'rises', 'falls', 'mixed (k of n rise)' or '' for no signs.

    Parameters
    ----------
    signs : iterable of int
        Signs of changes (-1, 0, 1).

    Returns
    -------
    str
        'rises' if all are positive, 'falls' if all are negative, '' if there are
        none, else 'mixed (k of n rise)' (zeros count as not rising).
    """
    signs = list(signs)
    if not signs:
        return ""
    up = sum(s > 0 for s in signs)
    if up == len(signs):
        return "rises"
    if up == 0 and all(s < 0 for s in signs):
        return "falls"
    return f"mixed ({up} of {len(signs)} rise)"


def _agree(measured: str, model: str) -> str:
    """'yes', 'no', 'partly' (the model is mixed), or why the question does not apply."""
    if not model:
        return "n/a"
    if measured == "mixed":
        return "mixed in the measurements"
    if model == measured:
        return "yes"
    return "partly" if model.startswith("mixed") else "no"


def pair_exponents(quantity: str, pairs: list[tuple], variable: str) -> tuple[float, float]:
    """Mean log-log slope ``d log y / d log x`` over ``pairs``: (measured, model).

    Parameters
    ----------
    quantity : str
        Key of :data:`.validate_points.QUANTITIES` (``y`` is its
        :func:`trend_value`).
    pairs : list of (Point, Point)
        From :func:`measured_pairs`, with ``model`` set.
    variable : str
        ``'pressure'`` or ``'load'`` (``x``).

    Returns
    -------
    (measured, model) : (float, float)
        NaN for no pairs or another variable; a pair with a non-positive value makes
        its mean NaN.
    """
    var = {"pressure": "pressure_bar", "load": "load_N"}.get(variable)
    if not pairs or var is None:
        return math.nan, math.nan
    out = []
    for attr in ("measured", "model"):
        s = []
        for a, b in pairs:
            ya = trend_value(quantity, getattr(a, attr), a.condition)
            yb = trend_value(quantity, getattr(b, attr), b.condition)
            dx = math.log(getattr(b.condition, var) / getattr(a.condition, var))
            s.append(math.log(yb / ya) / dx if ya > 0 and yb > 0 else math.nan)
        out.append(float(np.mean(s)))
    return out[0], out[1]


def trend_row(runner: ModelRunner, points: list[Point], statement: tuple) -> dict:
    """One row of :func:`trend_table`.

    Parameters
    ----------
    runner : ModelRunner
    points : list of Point
        With ``model`` set.
    statement : tuple
        An entry of :data:`TREND_STATEMENTS`: (quantity, variable, measured
        direction, statement).

    Returns
    -------
    dict
        The columns listed in :func:`trend_table`, plus ``model_errors`` (measured
        conditions where the model raised a named error).
    """
    quantity, variable, measured, text = statement
    pairs = measured_pairs(points, quantity, variable)
    m_signs, model_pair_signs = [], []
    for a, b in pairs:
        ya = trend_value(quantity, a.measured, a.condition)
        yb = trend_value(quantity, b.measured, b.condition)
        m_signs.append(int(np.sign(yb - ya)))
        ma = trend_value(quantity, a.model, a.condition)
        mb = trend_value(quantity, b.model, b.condition)
        model_pair_signs.append(int(np.sign(mb - ma)))
    conds = list(_by_condition(points, quantity))
    signs = model_signs(runner, quantity, conds, variable)
    exps = pair_exponents(quantity, pairs, variable)
    same = sum(s == m for s, m in zip(model_pair_signs, m_signs, strict=True))
    model_dir = direction(s for s in signs if s is not None)
    return {
        "quantity": quantity,
        "variable": variable,
        "measured": measured,
        "dissertation": text,
        "measured_pairs": direction(m_signs) or "no pair",
        "n_pairs": len(pairs),
        "model_on_pairs": direction(model_pair_signs) or "no pair",
        "measured_exponent": exps[0],
        "model_exponent": exps[1],
        "pairs_agreeing": same,
        "model": model_dir,
        "n_model_conditions": sum(s is not None for s in signs),
        "model_errors": sum(s is None for s in signs),
        "agree": _agree(measured, model_dir),
    }


def trend_table(runner: ModelRunner, points: list[Point]) -> list[dict]:
    """Trend signs, measured vs model, for every statement of :data:`TREND_STATEMENTS`.

    Parameters
    ----------
    runner : ModelRunner
    points : list of Point
        With ``model`` set.

    Returns
    -------
    list of dict
        ``quantity``, ``variable``, ``measured`` (the dissertation's direction) and its
        ``dissertation`` statement; ``measured_pairs`` / ``model_on_pairs`` (the
        direction over the ``n_pairs`` pairs of measured conditions of one tire that
        differ only in the variable), ``pairs_agreeing`` and the mean log-log slopes
        ``measured_exponent`` / ``model_exponent`` over the pairs; ``model`` (the model's
        direction over its ``n_model_conditions`` measured conditions) and ``agree``.
    """
    return [trend_row(runner, points, s) for s in TREND_STATEMENTS]


def distinct_conditions(points: list[Point], quantities=None, surface: str = "drum") -> list:
    """The distinct conditions of compared points (of ``quantities``, on ``surface``),
    in row order.

    Parameters
    ----------
    points : list of Point
    quantities : collection of str, optional
        Quantities whose points count (default: all).
    surface : str
        ``'drum'``, ``'flat'``...

    Returns
    -------
    list of Condition
        Each once, in the order first met.
    """
    seen: dict[Condition, None] = {}
    for p in points:
        if p.status != "compared" or p.condition is None or p.condition.surface != surface:
            continue
        if quantities is None or p.quantity in quantities:
            seen.setdefault(p.condition, None)
    return list(seen)


def group_by(points: list[Point], key) -> dict:
    """``points`` grouped by ``key(point)``.

    Parameters
    ----------
    points : list of Point
    key : callable
        ``Point -> hashable``.

    Returns
    -------
    dict
        Key -> list of Point, in input order.
    """
    out = defaultdict(list)
    for p in points:
        out[key(p)].append(p)
    return dict(out)


__all__ = [
    "STEPS",
    "TREND_STATEMENTS",
    "direction",
    "distinct_conditions",
    "group_by",
    "measured_pairs",
    "model_signs",
    "pair_exponents",
    "quantity_table",
    "ratio_stats",
    "stepped",
    "trend_row",
    "trend_table",
    "trend_value",
]
