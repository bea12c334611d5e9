"""Report figures (matplotlib), model vs prints.

Each function takes table rows (lists of dicts) and returns a matplotlib Figure;
:func:`tiremesh.io.save_figure` writes it (PNG and SVG, atomically). The SVG is
deterministic (no dates; a fixed ``svg.hashsalt`` for its ids), so the same inputs
give the same files.
"""

from __future__ import annotations

import math
from collections import defaultdict
from pathlib import Path

import numpy as np

from tiremesh.io import cell_number_or_nan as _f
from tiremesh.units import MPA_PER_BAR

from ..ruler.ellipse import EllipseFit
from .trends import DISSERTATION_TABLE_4_1

MARKERS = "osD^v<>ph*"


def _plt():
    """pyplot on the Agg backend, with the report's style."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    plt.rcParams.update({"svg.hashsalt": "contactpatch", "figure.dpi": 100, "font.size": 9})
    return plt


def _ok(rows):
    """Rows where both the print and the model are ``ok``."""
    return [r for r in rows if r.get("status", "ok") == "ok" and r.get("model_status") == "ok"]


def _tires(rows):
    """Tire names of the rows, sorted."""
    return sorted({str(r.get("tire", "")) for r in rows})


def area_vs_length_width(paired):
    """Contact area vs length and vs width, model and prints (cf. Figure 6-3).

    Parameters
    ----------
    paired : list of dict
        Rows of :func:`contactpatch.pair_prints`.

    Returns
    -------
    matplotlib.figure.Figure
    """
    plt = _plt()
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2), sharey=True)
    rows = _ok(paired)
    for k, tire in enumerate(_tires(rows)):
        rs = [r for r in rows if r["tire"] == tire]
        m = MARKERS[k % len(MARKERS)]
        for ax, pk, mk in (
            (axes[0], "length_mm", "model_length_mm"),
            (axes[1], "width_mm", "model_width_mm"),
        ):
            ax.scatter(
                [_f(r[pk]) for r in rs],
                [_f(r["hull_area_mm2"]) for r in rs],
                marker=m,
                color=f"C{k}",
                label=f"{tire} (prints)",
            )
            ax.scatter(
                [_f(r[mk]) for r in rs],
                [_f(r["model_area_mm2"]) for r in rs],
                marker=m,
                facecolors="none",
                edgecolors=f"C{k}",
                label=f"{tire} (model)",
            )
    axes[0].set_xlabel("contact patch length [mm]")
    axes[1].set_xlabel("contact patch width [mm]")
    axes[0].set_ylabel("contact patch area [mm$^2$]")
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[1].legend(fontsize=7, loc="lower right")
    fig.suptitle(
        "Area vs length and width: prints (filled) and Rotta model (open), cf. Figure 6-3"
    )
    fig.tight_layout()
    return fig


def load_per_area(paired):
    """Load over print area vs inflation pressure, with the 1:1 line (cf. Figure 4-3).

    Parameters
    ----------
    paired : list of dict
        Print rows (``pressure_bar`` [bar], ``load_per_hull_area_N_mm2``).

    Returns
    -------
    matplotlib.figure.Figure
    """
    plt = _plt()
    fig, ax = plt.subplots(figsize=(5.5, 5))
    rows = [r for r in paired if r.get("status", "ok") == "ok"]
    for k, surface in enumerate(sorted({str(r.get("surface", "")) for r in rows})):
        rs = [r for r in rows if r.get("surface") == surface]
        ax.scatter(
            [MPA_PER_BAR * _f(r["pressure_bar"]) for r in rs],
            [_f(r["load_per_hull_area_N_mm2"]) for r in rs],
            marker=MARKERS[k],
            color=f"C{k}",
            label=surface,
        )
    p = [MPA_PER_BAR * _f(r["pressure_bar"]) for r in rows]
    if p:
        lim = [0, 1.15 * max(p)]
        ax.plot(lim, lim, "k-", lw=1, label="load / area = inflation pressure")
        ax.set_xlim(lim)
        ax.set_ylim(lim)
    ax.set_xlabel("inflation pressure [N/mm$^2$]")
    ax.set_ylabel("load / print area (hull) [N/mm$^2$]")
    ax.set_title("Load over contact area vs inflation pressure (cf. Figure 4-3)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def tire_trends(paired, tire: str):
    """Length, width and area vs pressure and vs load for one tire: prints and model.

    Parameters
    ----------
    paired : list of dict
        Rows of :func:`contactpatch.pair_prints`.
    tire : str
        The tire's name (``tire`` column).

    Returns
    -------
    matplotlib.figure.Figure
        2 x 3 log-log panels.
    """
    plt = _plt()
    rows = [r for r in _ok(paired) if r["tire"] == tire]
    fig, axes = plt.subplots(2, 3, figsize=(11, 6))
    qs = (
        ("length_mm", "model_length_mm", "length [mm]"),
        ("width_mm", "model_width_mm", "width [mm]"),
        ("hull_area_mm2", "model_area_mm2", "area [mm$^2$]"),
    )
    for row_i, (xkey, other, xlabel) in enumerate(
        (("pressure_bar", "load_N", "pressure [bar]"), ("load_N", "pressure_bar", "load [N]"))
    ):
        groups = defaultdict(list)
        for r in rows:
            groups[(str(r.get("surface")), _f(r[other]))].append(r)
        for j, (pk, mk, ylabel) in enumerate(qs):
            ax = axes[row_i, j]
            for k, ((surface, val), rs) in enumerate(sorted(groups.items())):
                rs = sorted(rs, key=lambda r: _f(r[xkey]))
                x = [_f(r[xkey]) for r in rs]
                unit = "N" if other == "load_N" else "bar"
                ax.plot(
                    x,
                    [_f(r[pk]) for r in rs],
                    marker=MARKERS[k % 10],
                    color=f"C{k}",
                    label=f"print, {surface}, {val:g} {unit}",
                )
                ax.plot(
                    x,
                    [_f(r[mk]) for r in rs],
                    ls="--",
                    marker=MARKERS[k % 10],
                    mfc="none",
                    color=f"C{k}",
                    label=f"model, {surface}, {val:g} {unit}",
                )
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel(xlabel)
            ax.set_ylabel(ylabel)
            ax.grid(alpha=0.3, which="both")
        axes[row_i, 2].legend(fontsize=6)
    fig.suptitle(f"{tire}: prints (solid) and model (dashed)")
    fig.tight_layout()
    return fig


def print_overlays(paired, *, columns: int = 4):
    """Each print's hull and ellipse with the model patch outline, same scale.

    Both are centred and turned so the rolling direction is vertical.

    Parameters
    ----------
    paired : list of dict
        Rows of :func:`contactpatch.pair_prints` (with ``hull_wkt`` and
        ``model_outline_wkt`` [mm]).
    columns : int
        Panels per figure row.

    Returns
    -------
    matplotlib.figure.Figure
    """
    import shapely
    from shapely import affinity

    plt = _plt()
    rows = [r for r in _ok(paired) if r.get("hull_wkt") and r.get("model_outline_wkt")]
    n = max(len(rows), 1)
    nr = math.ceil(n / columns)
    fig, axes = plt.subplots(nr, columns, figsize=(2.6 * columns, 3.6 * nr), squeeze=False)
    span = max(
        [_f(r["model_length_mm"]) for r in rows] + [_f(r["length_mm"]) for r in rows] + [1.0]
    )
    for ax in axes.ravel():
        ax.set_axis_off()
    for ax, r in zip(axes.ravel(), rows, strict=False):
        hull = shapely.from_wkt(r["hull_wkt"])
        c = hull.centroid
        ang = math.radians(_f(r.get("angle_deg", 0.0)))
        h = affinity.rotate(
            affinity.translate(hull, -c.x, -c.y), 90 - math.degrees(ang), origin=(0, 0)
        )
        ax.fill(*h.exterior.xy, color="0.75", label="print hull")
        el, ew = _f(r.get("ellipse_length_mm")), _f(r.get("ellipse_width_mm"))
        if np.isfinite(el) and np.isfinite(ew):
            b = EllipseFit((0.0, 0.0), el, ew, math.pi / 2).boundary(120)
            ax.plot(b[:, 0], b[:, 1], color="C3", lw=1, label="print ellipse")
        model = shapely.from_wkt(r["model_outline_wkt"])
        mc = model.centroid
        m = affinity.rotate(affinity.translate(model, -mc.x, -mc.y), 90, origin=(0, 0))
        ax.plot(*m.exterior.xy, color="C0", lw=1.2, label="model patch")
        ax.set_xlim(-0.3 * span, 0.3 * span)
        ax.set_ylim(-0.55 * span, 0.55 * span)
        ax.set_aspect("equal")
        ax.set_axis_on()
        ax.tick_params(labelsize=6)
        ax.set_title(
            f"{Path(str(r['file'])).stem} #{r['print']}\n{r.get('surface', '')}, "
            f"{_f(r['pressure_bar']):g} bar, {_f(r['load_N']):g} N",
            fontsize=7,
        )
    if rows:
        axes.ravel()[0].legend(fontsize=6, loc="lower left")
    fig.suptitle("Prints (grey hull, red ellipse) and model patches (blue), same scale [mm]")
    fig.tight_layout(rect=(0, 0, 1, 0.98))
    return fig


def drum_vs_plate(print_summary, model_summary):
    """Drum / plate ratios (Table 4-1): prints, model, and the dissertation's means.

    Parameters
    ----------
    print_summary, model_summary : list of dict
        Summaries of :func:`contactpatch.drum_plate_ratios` (length, width, area).

    Returns
    -------
    matplotlib.figure.Figure
    """
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6, 4))
    names = ["length", "width", "area"]
    diss = [s["mean"] for s in DISSERTATION_TABLE_4_1]
    x = np.arange(3)
    pm = [s["mean"] for s in print_summary][:3]
    ps = [s["stdev"] for s in print_summary][:3]
    mm = [s["mean"] for s in model_summary][:3]
    if len(pm) == 3:
        ax.bar(x - 0.27, pm, 0.25, yerr=ps, label="prints (mean, stdev)", color="0.6")
    if len(mm) == 3:
        ax.bar(x, mm, 0.25, label="model", color="C0")
    ax.bar(x + 0.27, diss, 0.25, label="Table 4-1 (measured)", color="C2")
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set_xticks(x, names)
    ax.set_ylabel("drum / plate")
    ax.set_ylim(0.6, 1.4)
    ax.legend(fontsize=8)
    ax.set_title("2.5 m drum vs flat plate")
    fig.tight_layout()
    return fig
