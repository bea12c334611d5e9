"""Global fit of the rounded footprint (:mod:`tiremesh.footprint`) to the preserved prints.

Two parameters, ``spread_mm`` and ``threshold``, are fitted ONCE over all tires (never
per tire) to the print numbers Dressel (2013) preserves (``measured-dressel2013.csv``):

* the Maxxis Radial 22-622 ink prints at 6.895 bar, 304 N on the plate and on the
  drum (4.1.1): ellipse length, ellipse width, ink area;
* the mean length / width of all prints, 6.7 (4.1.10 item 8), modelled as the mean
  over the measured conditions of the data set, on drum and plate;
* the mean drum / plate ratios of length, width and area, 0.92 / 1.12 / 1.04
  (Table 4-1), over the same conditions;
* the Big Apple 55-622 at 3 bar on the drum, 103 mm long (4.1.8) at 540 N: the caption
  gives "450 N (55 kg, 121 lb)"; 55 kg and 121 lb both give 540 N and 450 N is not a
  load of the test grid (304, 324, 525, 540, 731 N), so 540 N is taken.

The prints' lengths and widths are those of the ellipse with the print's area and the
axis ratio of its second moments (ImageJ's "fit ellipse", 4.1.1): :func:`print_ellipse`.
The plain model is compared as the dissertation does, with Figure 5-15's ellipse
(:func:`contactpatch.appendix_ellipse`), and its area.

The objective is the sum of squared log ratios model / measured; the smoothed pressure
of each patch is computed once per spread of a grid (:data:`SPREADS`) and its level
sets at every threshold of :data:`THRESHOLDS`, so refits for leave-one-out are free.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

import tiremesh as tm
from tiremesh.footprint import FootprintVanished, level_outline, smoothed_pressure

from .validate_data import read_measurements
from .validate_model import surface_of
from .validate_points import Condition, condition_of

#: grids of the global fit [mm], [-]
SPREADS = np.round(np.arange(0.5, 4.01, 0.25), 3)
THRESHOLDS = np.round(np.arange(0.30, 0.601, 0.01), 3)
#: grid spacing of the fit [mm] (the convergence test bounds its error below 0.1 %)
FIT_RESOLUTION = 0.25
#: the Maxxis print condition (4.1.1) and the Big Apple drum length (4.1.8)
MAXXIS = Condition(6, "Maxxis Radial Prototype 22-622", 45.0, 13.4, 6.895, 304.0, "flat")
BIG_APPLE = Condition(8, "Schwalbe Big Apple 55-622", 128.2, 18.7, 3.0, 540.0, "drum")


def print_ellipse(ring) -> tuple[float, float]:
    """Length and width of the ellipse a print measurement fits (ImageJ "fit
    ellipse": the region's area and the axis ratio of its second moments).

    Parameters
    ----------
    ring : (k, 2) float [mm]
        Closed outline.

    Returns
    -------
    (length, width) : (float, float) [mm]
    """
    x, y = np.asarray(ring, float).T
    cr = x[:-1] * y[1:] - x[1:] * y[:-1]
    a = cr.sum() / 2
    cx = ((x[:-1] + x[1:]) * cr).sum() / (6 * a)
    cy = ((y[:-1] + y[1:]) * cr).sum() / (6 * a)
    x, y = x - cx, y - cy
    sxx = ((x[:-1] ** 2 + x[:-1] * x[1:] + x[1:] ** 2) * cr).sum() / 12
    syy = ((y[:-1] ** 2 + y[:-1] * y[1:] + y[1:] ** 2) * cr).sum() / 12
    sxy = ((x[:-1] * y[1:] + 2 * x[:-1] * y[:-1] + 2 * x[1:] * y[1:] + x[1:] * y[:-1]) * cr).sum()
    lam = np.linalg.eigvalsh(np.array([[sxx, sxy / 24], [sxy / 24, syy]]) / a)
    ratio = math.sqrt(lam[1] / lam[0])
    length = math.sqrt(4 * abs(a) / math.pi * ratio)
    return length, 4 * abs(a) / (math.pi * length)


def print_conditions(rows: list[dict] | None = None) -> list[Condition]:
    """The distinct tested (tire, pressure, load) of the data set, for the print
    statistics whose individual prints are lost (4.1.10, Table 4-1).

    Parameters
    ----------
    rows : list of dict, optional
        Rows of :func:`.validate_data.read_measurements` (default: the shipped copy).

    Returns
    -------
    list of Condition
        On the drum, one per distinct tire, pressure (0.1 bar) and load (10 N),
        sorted; rows the source interpolated or with two stated loads left out.
    """
    rows = rows if rows is not None else read_measurements()[0]
    seen = {}
    for r in rows:
        c, alt = condition_of(r)
        if c is None or c.surface != "drum" or math.isfinite(alt):
            continue
        if r.get("value_kind") == "interpolated_in_source":
            continue
        if math.isfinite(c.pressure_bar) and math.isfinite(c.load_N):
            key = (c.tire_id, round(c.pressure_bar, 1), round(c.load_N / 10))
            seen.setdefault(key, c)
    return [seen[k] for k in sorted(seen)]


@dataclass
class Shapes:
    """Solved patches and their level sets on the fit grids.

    Attributes
    ----------
    patches : dict
        ``(Condition) -> tiremesh.ContactPatch`` (plain).
    levels : dict
        ``(Condition, spread index) -> (T, 3)`` float: print-ellipse length, width
        [mm] and area [mm^2] at each threshold of :data:`THRESHOLDS` (NaN where the
        footprint vanishes).
    """

    patches: dict = field(default_factory=dict)
    levels: dict = field(default_factory=dict)


def _solve(cond: Condition):
    tire = tm.TireGeometry.from_arc_length(cond.arc_length, cond.rim_width, name=cond.tire)
    case = tm.LoadCase.from_units(
        tire, pressure_bar=cond.pressure_bar, load_N=cond.load_N, surface=surface_of(cond)
    )
    return tm.solve(case)


def _levels(outline, spread: float) -> np.ndarray:
    xs, ys, q = smoothed_pressure(outline, spread=spread, resolution=FIT_RESOLUTION)
    out = np.full((len(THRESHOLDS), 3), np.nan)
    for j, t in enumerate(THRESHOLDS):
        try:
            ring = level_outline(xs, ys, q, float(t))
        except FootprintVanished:
            continue
        x, y = ring.T
        area = 0.5 * abs(float(np.sum(x[:-1] * y[1:] - x[1:] * y[:-1])))
        out[j] = (*print_ellipse(ring), area)
    return out


def build_shapes(conditions: list[Condition]) -> Shapes:
    """Solve each condition (plain) and its rounded level sets on the fit grids.

    Parameters
    ----------
    conditions : list of Condition

    Returns
    -------
    Shapes
    """
    sh = Shapes()
    for c in conditions:
        if c in sh.patches:
            continue
        p = _solve(c)
        sh.patches[c] = p
        for i, s in enumerate(SPREADS):
            sh.levels[c, i] = _levels(p.outline, float(s))
    return sh


#: the preserved print numbers: name -> (measured value, group)
TARGETS = {
    "maxxis_plate_length": (78.2, "Maxxis plate"),
    "maxxis_plate_width": (7.57, "Maxxis plate"),
    "maxxis_plate_area": (461.7, "Maxxis plate"),
    "maxxis_drum_length": (68.8, "Maxxis drum"),
    "maxxis_drum_width": (7.87, "Maxxis drum"),
    "maxxis_drum_area": (425.1, "Maxxis drum"),
    "length_over_width_mean": (6.7, "4.1.10"),
    "drum_over_plate_length": (0.92, "Table 4-1"),
    "drum_over_plate_width": (1.12, "Table 4-1"),
    "drum_over_plate_area": (1.04, "Table 4-1"),
    "big_apple_drum_length": (103.0, "Big Apple"),
}


def fit_conditions(rows: list[dict] | None = None) -> dict:
    """The conditions each target needs.

    Parameters
    ----------
    rows : list of dict, optional
        Measurement rows (default: the shipped copy).

    Returns
    -------
    dict
        ``maxxis_plate``, ``maxxis_drum``, ``big_apple`` (Condition) and ``pairs``
        (list of (drum, plate) Conditions; the 1-5 % duplicates of a load or
        pressure and the source's interpolated rows removed).
    """
    drum = print_conditions(rows)
    flat = [Condition(*(getattr(c, f) for f in _FIELDS), surface="flat") for c in drum]
    return {
        "maxxis_plate": MAXXIS,
        "maxxis_drum": Condition(*(getattr(MAXXIS, f) for f in _FIELDS), surface="drum"),
        "big_apple": BIG_APPLE,
        "pairs": list(zip(drum, flat, strict=True)),
    }


_FIELDS = ("tire_id", "tire", "arc_length", "rim_width", "pressure_bar", "load_N")


def _plain(p) -> np.ndarray:
    from ..ruler.model import appendix_ellipse

    e = appendix_ellipse(p)
    return np.array([e.length, e.width, p.area])


def model_values(sh: Shapes, conds: dict, *, rounded: bool = True) -> dict:
    """Each target's model value: arrays (S, T) over the fit grids, or the plain
    model's scalars (``rounded=False``).

    Parameters
    ----------
    sh : Shapes
        From :func:`build_shapes` on all conditions of ``conds``.
    conds : dict
        :func:`fit_conditions`.
    rounded : bool
        Rounded footprint on the grids (default) or the plain patch.

    Returns
    -------
    dict
        Target name -> float or (S, T) array.
    """

    def get(c):
        if not rounded:
            return _plain(sh.patches[c])
        return np.stack([sh.levels[c, i] for i in range(len(SPREADS))])  # (S, T, 3)

    mp, md, ba = (get(conds[k]) for k in ("maxxis_plate", "maxxis_drum", "big_apple"))
    drum = np.stack([get(d) for d, _ in conds["pairs"]])
    flat = np.stack([get(f) for _, f in conds["pairs"]])
    ratio = (drum / flat).mean(axis=0)
    lw = np.concatenate([drum, flat])
    lw = (lw[..., 0] / lw[..., 1]).mean(axis=0)
    vals = {
        "maxxis_plate_length": mp[..., 0],
        "maxxis_plate_width": mp[..., 1],
        "maxxis_plate_area": mp[..., 2],
        "maxxis_drum_length": md[..., 0],
        "maxxis_drum_width": md[..., 1],
        "maxxis_drum_area": md[..., 2],
        "length_over_width_mean": lw,
        "drum_over_plate_length": ratio[..., 0],
        "drum_over_plate_width": ratio[..., 1],
        "drum_over_plate_area": ratio[..., 2],
        "big_apple_drum_length": ba[..., 0],
    }
    return {k: (float(v) if np.ndim(v) == 0 else v) for k, v in vals.items()}


def best_fit(values: dict, names) -> tuple[int, int, float]:
    """Grid minimum of the summed squared log ratios over the targets ``names``.

    Parameters
    ----------
    values : dict
        :func:`model_values` (rounded).
    names : iterable of str
        Targets in the fit.

    Returns
    -------
    (i, j, cost) : (int, int, float)
        Indices into :data:`SPREADS` and :data:`THRESHOLDS`, and the cost there.
    """
    cost = sum(np.log(values[n] / TARGETS[n][0]) ** 2 for n in names)
    cost = np.where(np.isfinite(cost), cost, np.inf)
    i, j = np.unravel_index(int(np.argmin(cost)), cost.shape)
    return int(i), int(j), float(cost[i, j])


def leave_one_out(values: dict, *, by: str = "number") -> list[dict]:
    """Refit without each target (``by='number'``) or each group (``'group'``) and
    predict what was left out.

    Parameters
    ----------
    values : dict
        :func:`model_values` (rounded).
    by : {'number', 'group'}

    Returns
    -------
    list of dict
        ``left_out``, ``spread_mm``, ``threshold``, and per left-out target
        ``name``, ``measured``, ``predicted``, ``ratio``.
    """
    keys = list(TARGETS) if by == "number" else sorted({g for _, g in TARGETS.values()})
    out = []
    for k in keys:
        left = [n for n in TARGETS if (n == k if by == "number" else TARGETS[n][1] == k)]
        i, j, _ = best_fit(values, [n for n in TARGETS if n not in left])
        for n in left:
            pred = float(values[n][i, j])
            meas = TARGETS[n][0]
            out.append(
                {
                    "left_out": k,
                    "spread_mm": float(SPREADS[i]),
                    "threshold": float(THRESHOLDS[j]),
                    "name": n,
                    "measured": meas,
                    "predicted": pred,
                    "ratio": pred / meas,
                }
            )
    return out
