"""Figures of the validation, drawn with the report's own SVG plotter.

Each function takes plain rows (the dicts written to ``points.json`` and
``validation.json``) and returns an SVG document (:mod:`.svgplot`: plain text,
the report's font and tire colours, no matplotlib), inlined in the pages and written
beside them as ``figures/<name>.svg``.
"""

from __future__ import annotations

import math
import textwrap

import numpy as np

from .style import tire_colours
from .svgplot import LegendItem, Plot, log_ticks, nice_limits, text_width
from .validate_points import QUANTITIES

#: panels of :func:`measured_vs_model`: title -> quantities drawn in it
PANELS = {
    "static lateral stiffness [N/mm]": ("lateral_stiffness",),
    "normalized cornering stiffness [1/deg]": ("cornering_stiffness",),
    "normalized camber stiffness [1/deg]": ("camber_stiffness",),
    "mean pneumatic trail [mm]": ("pneumatic_trail",),
    "normalized aligning-torque stiffness [m/deg]": ("aligning_stiffness",),
    "ink prints, Maxxis 22-622 (4.1.1)": (
        "ink_area",
        "load_per_area",
        "ellipse_length",
        "ellipse_width",
        "ellipse_area",
    ),
    "Table 4-3 max / min norm. lateral stiffness [1/mm]": ("lateral_stiffness_extreme",),
    "geometry (Table 3-2) and point-load decay [mm]": (
        "tire_radius",
        "true_size",
        "decay_length",
    ),
}
MARKERS = "osD^v"
#: the figures' size [px of the SVG viewBox]: panel width and height
PANEL_W, PANEL_H = 250.0, 210.0


def _finite(*xs) -> bool:
    return all(isinstance(x, int | float) and math.isfinite(x) and x != 0 for x in xs)


def _panel_points(rows, quantities, colors):
    """The points of one panel: (x, y, colour, marker, compared, y_alt or None)."""
    pts = []
    for j, q in enumerate(quantities):
        marker = MARKERS[j % len(MARKERS)]
        for r in rows:
            if r["quantity"] != q or not _finite(r.get("measured"), r.get("model")):
                continue
            c = colors.get(r.get("tire_id"), "#666")
            m, y = abs(r["measured"]), abs(r["model"])
            if r["status"] == "compared":
                pts.append((m, y, c, marker, True, None))
            elif r["status"] == "ambiguous" and _finite(r.get("model_alt")):
                pts.append((m, y, c, marker, False, abs(r["model_alt"])))
    return pts


def _ticks(lo: float, hi: float) -> list[float]:
    """Log-axis ticks: 1-2-5 steps over a short range, decades (every other one
    beyond 8) over a long one, so labels never run into each other."""
    if hi / lo < 300:
        return log_ticks(lo, hi)
    k0, k1 = math.ceil(math.log10(lo)), math.floor(math.log10(hi))
    step = 1 if k1 - k0 <= 6 else 2
    return [10.0**k for k in range(k0, k1 + 1, step)]


def _log_limits(vals) -> tuple[float, float]:
    """Square log limits around the values: a factor 1.5 beyond them."""
    return min(vals) / 1.5, max(vals) * 1.5


def _draw_panel(plot, box, rows, quantities, colors):
    """One measured-vs-model panel at ``box`` (x, y) [px]: compared points filled,
    ambiguous ones open with a bar spanning their two loads; the 1:1 line and the
    factor-2 lines."""
    x0, y0 = box
    pts = _panel_points(rows, quantities, colors)
    vals = [v for p in pts for v in (p[0], p[1], p[5]) if v is not None]
    if not vals:
        p = plot.panel(x0, y0, PANEL_W, PANEL_H, xlim=(0, 1), ylim=(0, 1))
        plot.axes(p, xticks=[], yticks=[])
        p.text(0.5, 0.5, "no points", size=12)
        return
    lo, hi = _log_limits(vals)
    p = plot.panel(x0, y0, PANEL_W, PANEL_H, xlim=(lo, hi), ylim=(lo, hi), xlog=True, ylog=True)
    ticks = _ticks(lo, hi)
    plot.axes(p, xlabel="measured", ylabel="model", xticks=ticks, yticks=ticks)
    p.line([lo, hi], [lo, hi], colour="#111", width=1.2)
    for f in (2.0, 0.5):
        p.line([lo, hi], [f * lo, f * hi], colour="#777", dashed=True, width=0.9)
    for m, y, c, marker, compared, alt in pts:
        if alt is not None:
            p.segment(m, min(y, alt), m, max(y, alt), colour=c, width=1.2)
        p.scatter([m], [y], colour=c, marker=marker, filled=compared, size=4.2)


def _panel_title(plot, box, title, sub) -> None:
    x0, y0 = box
    lines = textwrap.wrap(title, 40)
    for k, line in enumerate(lines):
        plot.text(
            x0 + PANEL_W / 2,
            y0 - 30 - 15 * (len(lines) - 1 - k),
            line,
            anchor="middle",
            cls="title",
        )
    plot.text(x0 + PANEL_W / 2, y0 - 12, sub, anchor="middle", size=12)


def _tires(rows) -> tuple[list, dict, dict]:
    """Tire ids, their names and the report's colour of each."""
    tires = sorted({r["tire_id"] for r in rows if isinstance(r.get("tire_id"), int)})
    names = {r["tire_id"]: str(r.get("tire", "")) for r in rows if r.get("tire_id") in tires}
    by_name = tire_colours(names.values())  # the report's colour of each tire
    return tires, names, {t: by_name[names[t]] for t in tires}


def measured_vs_model(rows: list[dict], stats: list[dict]) -> str:
    """Measured vs model for every compared quantity, with the 1:1 line.

    Parameters
    ----------
    rows : list of dict
        Point rows (``quantity``, ``status``, ``measured``, ``model``, ``model_alt``,
        ``tire_id``, ``tire``).
    stats : list of dict
        Quantity statistics (``quantity``, ``n``, ``median_ratio``).

    Returns
    -------
    str
        An SVG document (:mod:`.svgplot`): 8 log-log panels in 4 columns, the tires'
        colours those of the report, markers per quantity in the mixed panels.
    """
    tires, names, colors = _tires(rows)
    by_q = {s["quantity"]: s for s in stats}
    col_w, row_h, top = PANEL_W + 120, PANEL_H + 150, 110
    width = 4 * col_w + 20
    legend = [LegendItem(f"{t}: {names.get(t, '')}", colors[t]) for t in tires]
    legend += [
        LegendItem("1:1", "#111", marker=None, line=True),
        LegendItem("x2, /2", "#777", marker=None, line=True, dashed=True),
        LegendItem("open: load stated two ways (bar: both)", "#666", filled=False),
    ]
    plot = Plot(width, top + 2 * row_h + 40)
    leg_h = plot.legend(legend, 20, 40, width=width - 40, size=12)
    top = max(top, 40 + leg_h + 60)
    plot.height = top + 2 * row_h + 10
    plot.text(20, 24, "Rotta model vs the measurements preserved in Dressel (2013)", cls="title")
    for k, (title, qs) in enumerate(PANELS.items()):
        box = (100 + (k % 4) * col_w, top + (k // 4) * row_h)
        _draw_panel(plot, box, rows, qs, colors)
        n = sum(by_q.get(q, {}).get("n", 0) for q in qs)
        med = [by_q[q]["median_ratio"] for q in qs if q in by_q]
        sub = f"n = {n}" + (f", median ratio {med[0]:.3g}" if len(med) == 1 else "")
        _panel_title(plot, box, title, sub)
        if len(qs) > 1:
            items = [
                LegendItem(QUANTITIES[q][0].split(" (")[0], "#555", marker=MARKERS[j])
                for j, q in enumerate(qs)
            ]
            plot.legend(items, box[0] - 60, box[1] + PANEL_H + 44, width=PANEL_W + 80, size=11)
    return plot.svg("vmm", "Measured vs model, log axes, 1:1 line and factors of 2")


def relaxation_figure(curve: dict, variants: list[dict]) -> str:
    """The fitted casing modulus and the decay-length choices compared.

    Parameters
    ----------
    curve : dict
        ``modulus`` (list, N/mm^2, first 0), ``rms_log_error`` (list), ``fitted`` (E),
        ``loto`` (list of E fitted without each tire).
    variants : list of dict
        Rows of :func:`.validate_fit.variants`.

    Returns
    -------
    str
        An SVG document (:mod:`.svgplot`): the error vs the modulus (left) and per
        way of setting the decay length (right).
    """
    e = np.asarray(curve["modulus"], float)
    rms = np.asarray(curve["rms_log_error"], float)
    pos = e > 0
    names = [str(v["variant"]) for v in variants]
    errs = [float(v["rms_log_error"]) for v in variants]
    cat_w = max([text_width(n, 12) for n in names] + [40])
    bx = 560 + 70 + cat_w  # the bar panel, its category names to the left
    plot = Plot(bx + 330, 420)
    xs = np.concatenate([e[pos], [curve["fitted"]], np.asarray(curve["loto"], float)])
    xs = xs[np.isfinite(xs) & (xs > 0)]
    ys = np.concatenate([rms[pos], [rms[0]]])
    ylim = nice_limits(float(np.nanmin(ys)), float(np.nanmax(ys)), zero=True)
    xlim = (xs.min() / 1.3, xs.max() * 1.3)
    a = plot.panel(90, 60, 470, 250, xlim=xlim, ylim=ylim, xlog=True)
    plot.axes(
        a,
        xlabel="casing modulus E [N/mm²] (t fixed)",
        ylabel="RMS log error, static lateral stiffness",
        xticks=_ticks(*xlim),
    )
    # E = 0 (the taut string) has no place on the log axis: its error is the dashed line
    for x in [x for x in curve["loto"] if x > 0]:
        a.rule(x, axis="x", colour="#0072B2", dashed=False, width=0.7)
    a.rule(rms[0], axis="y", colour="#777", dashed=True)
    if curve["fitted"] > 0:
        a.rule(curve["fitted"], axis="x", colour="#D55E00", dashed=False, width=1.4)
    a.line(e[pos], rms[pos], colour="#111", width=1.4)
    plot.text(90, 30, "Taut beam of 5.9: the one fitted parameter", cls="title")
    plot.legend(
        [
            LegendItem("in sample, all fit tires", "#111", marker=None, line=True),
            LegendItem("E = 0 (taut string)", "#777", marker=None, line=True, dashed=True),
            LegendItem(f"fitted E = {curve['fitted']:.3g} N/mm²", "#D55E00", None, line=True),
            LegendItem("E fitted without one tire", "#0072B2", marker=None, line=True),
        ],
        40,
        350,
        width=540,
    )
    b = plot.panel(
        bx,
        60,
        300,
        30 * len(names) + 10,
        xlim=nice_limits(0.0, max([*errs, 1e-9]), zero=True),
        ylim=(len(names) - 0.5, -0.5),
    )
    plot.axes(b, xlabel="RMS log error, static lateral stiffness", ycats=names, ygrid=False)
    for k, (v, err) in enumerate(zip(variants, errs, strict=True)):
        fill = "#D55E00" if v["fitted_parameters"] else "#999"
        b.items.append(_hbar(b, k, err, fill))
    plot.text(
        bx + 300, 30, "How the decay length beyond the patch is set", anchor="end", cls="title"
    )
    plot.text(
        bx, 60 + 30 * len(names) + 10 + 62, "orange: 1 fitted parameter; grey: none", size=12
    )
    return plot.svg("vrelax", "Casing modulus fit and the decay-length choices")


def _hbar(p, k: int, value: float, fill: str) -> str:
    """A horizontal bar of category ``k`` from 0 to ``value``."""
    x0, x1 = p.sx(max(p.xlim[0], 0.0)), p.sx(value)
    y0, y1 = p.sy(k - 0.35), p.sy(k + 0.35)
    return (
        f'<rect x="{x0:.1f}" y="{min(y0, y1):.1f}" width="{max(x1 - x0, 0):.1f}" '
        f'height="{abs(y1 - y0):.1f}" fill="{fill}" stroke="#222" stroke-width="0.8"/>'
    )


__all__ = ["PANELS", "measured_vs_model", "relaxation_figure"]
