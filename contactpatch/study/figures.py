"""Report figures, model vs prints, as SVG (drawn with :mod:`.svgplot`).

Each function takes table rows (lists of dicts) and a colour per tire
(:func:`contactpatch.study.style.tire_colours`, the same in every figure) and
returns the figure as an SVG document, which the page inlines and the report also
writes beside it as a file. Conventions in every figure: a tire's colour; prints
filled, the model open (dashed lines); a marker per surface (circle plate, square
drum); legends outside the axes; ticks at round values or at the data's own values,
labelled as plain numbers; pressure in bar; names written literally.

The output is deterministic (no date, fixed jitter), so the same inputs give the
same files.
"""

from __future__ import annotations

import math
from collections import defaultdict

import numpy as np

from tiremesh.io import cell_number_or_nan as _f
from tiremesh.units import MPA_PER_BAR

from .style import surface_marker
from .svgplot import LegendItem, Plot, nice_limits, text_width
from .trends import DISSERTATION_TABLE_4_1

#: (print column, model column, axis label) per size quantity
SIZES = (
    ("length_mm", "model_length_mm", "length [mm]"),
    ("width_mm", "model_width_mm", "width [mm]"),
    ("hull_area_mm2", "model_area_mm2", "area [mm²]"),
)


def _ok(rows):
    """Rows where both the print and the model are ``ok``."""
    return [r for r in rows if r.get("status", "ok") == "ok" and r.get("model_status") == "ok"]


def _groups(rows, keys) -> dict:
    out = defaultdict(list)
    for r in rows:
        out[tuple(str(r.get(k, "")) for k in keys)].append(r)
    return dict(sorted(out.items()))


def _surfaces(rows) -> list[str]:
    return sorted({str(r.get("surface", "")) for r in rows})


def _finite(values) -> list[float]:
    return [v for v in values if math.isfinite(v)]


def _legend_items(colours: dict, surfaces, *, kinds=True) -> list[LegendItem]:
    """One entry per tire (its colour), per surface (its marker), and prints
    (filled) / model (open)."""
    items = [LegendItem(t, c, "o") for t, c in colours.items()]
    items += [LegendItem(s, "#444", surface_marker(s), filled=False) for s in surfaces]
    if kinds:  # as drawn: markers only, no lines
        items += [
            LegendItem("prints: filled", "#444", "o"),
            LegendItem("model: open", "#444", "o", filled=False),
        ]
    return items


def _legend_height(plot_width: float, items, size=12) -> float:
    """Height a legend of ``items`` takes in rows across ``plot_width``."""
    rows, x = 1, 0.0
    for it in items:
        w = 34 + text_width(it.label, size) + 14
        if x > 0 and x + w > plot_width:
            rows, x = rows + 1, 0.0
        x += w
    return rows * size * 1.6


def area_vs_length_width(paired, colours: dict) -> str:
    """Contact area vs length and vs width, prints and model (cf. Figure 6-3).

    Parameters
    ----------
    paired : list of dict
        Rows of :func:`contactpatch.pair_prints`.
    colours : dict of str to str
        Colour per tire.

    Returns
    -------
    str
        SVG.
    """
    rows = _ok(paired)
    items = _legend_items(colours, _surfaces(rows))
    W, top, ph = 900.0, 12.0, 330.0
    leg = _legend_height(W - 80, items)
    plot = Plot(W, top + ph + 56 + leg + 10)
    area = _finite([_f(r[k]) for r in rows for k in ("hull_area_mm2", "model_area_mm2")])
    ylim = nice_limits(0.0, max(area, default=1.0), zero=True)
    small = len(rows) > 200
    for j, (pk, mk, label) in enumerate(SIZES[:2]):
        xs = _finite([_f(r[k]) for r in rows for k in (pk, mk)])
        p = plot.panel(
            80 + j * 420,
            top,
            380,
            ph,
            xlim=nice_limits(0, max(xs, default=1), zero=True),
            ylim=ylim,
        )
        for (tire, surface), rs in _groups(rows, ("tire", "surface")).items():
            c, m = colours.get(tire, "#888"), surface_marker(surface)
            kw = dict(colour=c, marker=m, size=3.2 if small else 4.5, alpha=0.7 if small else 1.0)
            p.scatter([_f(r[pk]) for r in rs], [_f(r["hull_area_mm2"]) for r in rs], **kw)
            p.scatter(
                [_f(r[mk]) for r in rs], [_f(r["model_area_mm2"]) for r in rs], filled=False, **kw
            )
        plot.axes(
            p,
            xlabel=f"contact patch {label}",
            ylabel="contact patch area [mm²]" if j == 0 else "",
            ylabels=j == 0,
        )
    plot.legend(items, 80, top + ph + 50, width=W - 80)
    return plot.svg("area_vs_length_width", "Contact area vs length and width")


def ratio_summary(paired, colours: dict) -> str:
    """Print / model ratios of length, width and area per tire: every print as a
    point, the median as a bar (the aggregate that scales to thousands of prints).

    Parameters
    ----------
    paired : list of dict
    colours : dict of str to str

    Returns
    -------
    str
        SVG: three panels side by side, one row per tire.
    """
    rows = _ok(paired)
    tires = list(colours)
    names = [t if len(t) <= 32 else t[:31] + "…" for t in tires]
    left = 20 + max([text_width(n, 12) for n in names] + [40])
    W, top = 900.0, 8.0
    ph = 30.0 * max(len(tires), 2)
    pw = (W - left - 90) / 3
    plot = Plot(W, top + ph + 50)
    rng = np.random.default_rng(0)  # jitter only: the same figure every time
    keys = (("ratio_length", "length"), ("ratio_width", "width"), ("ratio_area", "area"))
    for j, (key, label) in enumerate(keys):
        vals = {
            t: np.array(_finite([_f(r.get(key)) for r in rows if r["tire"] == t])) for t in tires
        }
        allv = np.concatenate([v for v in vals.values() if v.size] or [np.array([1.0])])
        lim = nice_limits(min(allv.min(), 1.0), max(allv.max(), 1.0), pad=0.08)
        p = plot.panel(left + j * (pw + 36), top, pw, ph, xlim=lim, ylim=(len(tires) - 0.5, -0.5))
        p.rule(1.0, axis="x", colour="#333")
        for k, t in enumerate(tires):
            v = vals[t]
            if not v.size:
                continue
            y = k + rng.uniform(-0.22, 0.22, v.size)
            p.scatter(v, y, colour=colours[t], size=2.6 if v.size > 50 else 3.6, alpha=0.65)
            med = float(np.median(v))
            p.segment(med, k - 0.36, med, k + 0.36, colour="#000", width=2.5)
        plot.axes(p, xlabel=f"{label}: print / model", ycats=names, ylabels=j == 0)
    return plot.svg("ratios", "Print / model ratios per tire")


def load_per_area(paired, colours: dict) -> str:
    """Load over print area vs inflation pressure, both in bar, with the 1:1 line
    (cf. Figure 4-3).

    Parameters
    ----------
    paired : list of dict
        Print rows (``pressure_bar``, ``load_per_hull_area_N_mm2`` [N/mm^2]).
    colours : dict of str to str

    Returns
    -------
    str
        SVG.
    """
    rows = [r for r in paired if r.get("status", "ok") == "ok"]
    items = _legend_items({t: c for t, c in colours.items()}, _surfaces(rows), kinds=False)
    p_bar = _finite([_f(r.get("pressure_bar")) for r in rows])
    q_bar = _finite([_f(r.get("load_per_hull_area_N_mm2")) / MPA_PER_BAR for r in rows])
    lim = nice_limits(0.0, max(p_bar + q_bar, default=1.0), zero=True)
    W, top, ph = 900.0, 12.0, 360.0
    leg_w = max([34 + text_width(i.label, 12) for i in items] + [100])
    plot = Plot(W, top + ph + 50)
    p = plot.panel(70, top, ph * 1.25, ph, xlim=lim, ylim=lim)
    p.segment(lim[0], lim[0], lim[1], lim[1], colour="#222", width=1.2)
    surfaces = _surfaces(rows)
    for (tire, surface), rs in _groups(rows, ("tire", "surface")).items():
        # surfaces side by side at one pressure, not on top of each other
        dx = _surface_offset(surface, surfaces) * (lim[1] - lim[0])
        p.scatter(
            [_f(r.get("pressure_bar")) + dx for r in rs],
            [_f(r.get("load_per_hull_area_N_mm2")) / MPA_PER_BAR for r in rs],
            colour=colours.get(tire, "#888"),
            marker=surface_marker(surface),
            size=3.2 if len(rows) > 200 else 4.5,
            alpha=0.8,
        )
    p.text(
        0.93 * lim[1],
        0.93 * lim[1],
        "load / area = inflation pressure",
        anchor="end",
        dy=-8,
        size=11,
    )
    plot.axes(p, xlabel="inflation pressure [bar]", ylabel="load / print area (hull) [bar]")
    x0 = 70 + ph * 1.25 + 30
    for k, it in enumerate(items):
        plot.legend([it], x0, top + 4 + 20 * k, width=min(leg_w, W - x0))
    return plot.svg("load_per_area", "Load over print area vs inflation pressure")


def _surface_offset(surface: str, surfaces: list[str]) -> float:
    """Horizontal offset of a surface's markers, as a fraction of the axis span
    (plate left, drum right; 0 with one surface)."""
    if len(surfaces) < 2:
        return 0.0
    k = surfaces.index(surface)
    return 0.012 * (2 * k / (len(surfaces) - 1) - 1)


def _shade(colour: str, level: int, n: int) -> str:
    """The tire's colour darker (first level) to lighter (last), as hex: from 25 %
    toward black to 45 % toward white, so that both ends stay clear of the white
    background and of each other (the tire's own colour with one level)."""
    c = colour.lstrip("#")
    rgb = np.array([int(c[i : i + 2], 16) for i in (0, 2, 4)], float)
    t = 0.0 if n <= 1 else -0.25 + 0.7 * level / (n - 1)
    mixed = rgb * (1 + t) if t < 0 else rgb + (255 - rgb) * t
    r, g, b = mixed.round().astype(int)
    return f"#{r:02x}{g:02x}{b:02x}"


def tire_trends(paired, tire: str, colour: str, *, name: str = "trends") -> str:
    """Length, width and area vs pressure and vs load for one tire (log-log):
    prints solid and filled, model dashed and open; with several prints of a case,
    the lines join the medians and each print is a small dot.

    Parameters
    ----------
    paired : list of dict
        Rows of :func:`contactpatch.pair_prints`.
    tire : str
        The tire's name (``tire`` column).
    colour : str
        The tire's colour (hex); its shades tell the levels of the variable held
        fixed along each line apart (darkest: lowest): load in the top row (x:
        pressure), pressure in the bottom row (x: load), as each row's legend says.
    name : str
        The figure's name (prefix of its SVG ids: unique on a page).

    Returns
    -------
    str
        SVG: 2 x 3 panels, a legend per row.
    """
    rows = [r for r in _ok(paired) if r["tire"] == tire]
    W, pw, ph, top, dx = 900.0, 178.0, 190.0, 10.0, 246.0
    plot = Plot(W, top + 2 * (ph + 62))
    panels = (
        ("pressure_bar", "load_N", "pressure [bar]", "N"),
        ("load_N", "pressure_bar", "load [N]", "bar"),
    )
    for i, (xkey, other, xlabel, unit) in enumerate(panels):
        levels = sorted({_f(r[other]) for r in rows})
        groups = _groups(rows, ("surface", other))
        y0 = top + i * (ph + 62)
        xs = _finite([_f(r[xkey]) for r in rows])
        for j, (pk, mk, ylabel) in enumerate(SIZES):
            ys = _finite([_f(r[k]) for r in rows for k in (pk, mk)])
            p = plot.panel(
                70 + j * dx,
                y0,
                pw,
                ph,
                xlim=_log_limits(xs),
                ylim=_log_limits(ys),
                xlog=True,
                ylog=True,
            )
            for (surface, val), rs in groups.items():
                c = _shade(colour, levels.index(_f(val)), len(levels))
                m = surface_marker(surface)
                for key, filled in ((pk, True), (mk, False)):
                    x, y, repeated = _medians(rs, xkey, key)
                    if repeated and filled:  # many prints per case: each as a dot
                        xs_all = [_f(r[xkey]) for r in rs]
                        ys_all = [_f(r[key]) for r in rs]
                        p.scatter(xs_all, ys_all, colour=c, size=1.8, alpha=0.35)
                    p.line(x, y, colour=c, dashed=not filled)
                    p.scatter(x, y, colour=c, marker=m, filled=filled, size=4)
            few = len(set(xs)) <= 6
            plot.axes(p, xlabel=xlabel, ylabel=ylabel, xticks=sorted(set(xs)) if few else None)
        x_leg = 70 + 2 * dx + pw + 20
        what = ("load", "N") if unit == "N" else ("pressure", "bar")
        _trend_legend(plot, (x_leg, y0, W - x_leg), colour, levels, what, _surfaces(rows))
    return plot.svg(name, f"{tire}: trends")


def _trend_legend(plot, box, colour: str, levels, what, surfaces) -> None:
    """A trend row's legend in a column at ``box`` (x, y, width): prints / model
    (line and fill), the surfaces (marker), and the shades: the levels of ``what``
    (name, unit), the variable held fixed along each line, darkest = lowest."""
    x, y, width = box
    items = [
        LegendItem("prints", "#444", "o", line=True),
        LegendItem("model", "#444", "o", filled=False, line=True, dashed=True),
    ]
    items += [LegendItem(s, "#444", surface_marker(s), filled=False) for s in surfaces]
    for k, it in enumerate(items):
        plot.legend([it], x, y + 20 * k, width=width)
    y += 20 * len(items) + 16
    plot.text(x, y, f"line shade: {what[0]}", size=12)
    for k, v in enumerate(levels):
        item = LegendItem(f"{v:g} {what[1]}", _shade(colour, k, len(levels)), None, line=True)
        plot.legend([item], x, y + 6 + 20 * k, width=width)


def _medians(rows, xkey: str, ykey: str):
    """Per distinct x: the median y; and whether any x has several rows."""
    by_x = defaultdict(list)
    for r in rows:
        x, y = _f(r[xkey]), _f(r[ykey])
        if math.isfinite(x) and math.isfinite(y):
            by_x[x].append(y)
    xs = sorted(by_x)
    return xs, [float(np.median(by_x[x])) for x in xs], any(len(v) > 1 for v in by_x.values())


def _log_limits(values) -> tuple[float, float]:
    v = [x for x in values if math.isfinite(x) and x > 0]
    if not v:
        return 1.0, 10.0
    lo, hi = min(v), max(v)
    if hi / lo < 1.05:
        lo, hi = lo / 1.1, hi * 1.1
    r = (hi / lo) ** 0.08
    return lo / r, hi * r


def drum_vs_plate(print_summary, model_summary) -> str:
    """Drum / plate ratios (Table 4-1): prints, model, and the dissertation's means.

    Parameters
    ----------
    print_summary, model_summary : list of dict
        Summaries of :func:`contactpatch.drum_plate_ratios` (length, width, area).

    Returns
    -------
    str
        SVG.
    """
    W, top, ph = 900.0, 12.0, 260.0
    plot = Plot(W, top + ph + 50)
    p = plot.panel(70, top, 560, ph, xlim=(-0.5, 2.5), ylim=(0.6, 1.45))
    bars = [
        ("prints (mean ± stdev)", print_summary, "#595959", False),
        ("model", model_summary, "#ffffff", False),
        ("Table 4-1, measured", DISSERTATION_TABLE_4_1, "#dddddd", True),
    ]
    p.rule(1.0, axis="y", colour="#000", dashed=False)
    for k, (label, summary, fill, hatch) in enumerate(bars):
        if len(summary) < 3:
            continue
        for i, s in enumerate(summary[:3]):
            x = i + (k - 1) * 0.27
            p.bar(x, 0.25, s["mean"], fill=fill, hatch=hatch)
            sd = s.get("stdev", math.nan)
            if label.startswith("prints") and math.isfinite(sd):
                p.segment(x, s["mean"] - sd, x, s["mean"] + sd, colour="#000", width=1.2)
            p.text(
                x,
                s["mean"] + (sd if label.startswith("prints") and math.isfinite(sd) else 0),
                f"{s['mean']:.3f}",
                size=10,
                dy=-5,
            )
    plot.axes(p, ylabel="drum / plate", xticks=[], xgrid=False)
    for i, name in enumerate(("length", "width", "area")):
        plot.text(p.sx(i), top + ph + 20, name, anchor="middle")
    for k, (label, _, fill, hatch) in enumerate(bars):
        y = top + 10 + 24 * k
        pat = "url(#drum_vs_plate-hatch)" if hatch else fill
        plot.items.append(
            f'<rect x="660" y="{y}" width="18" height="14" fill="{pat}" stroke="#222" stroke-width="0.8"/>'
        )
        plot.text(686, y + 11, label)
    return plot.svg("drum_vs_plate", "Drum / plate ratios")


__all__ = [
    "SIZES",
    "area_vs_length_width",
    "drum_vs_plate",
    "load_per_area",
    "ratio_summary",
    "tire_trends",
]
