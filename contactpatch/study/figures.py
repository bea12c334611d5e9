"""Report figures (matplotlib), model vs prints.

Each figure function takes table rows (lists of dicts) and a colour per tire
(:func:`contactpatch.study.style.tire_colours`, the same in every figure) and
returns a matplotlib Figure; :func:`figure_svg` saves it once, as SVG text with
the text kept as text, which the page embeds inline and the report also writes
beside it as a file. Conventions in every figure: a tire's colour; prints filled,
the model open (dashed lines); a marker per surface (circle plate, square drum);
legends outside the axes; plain tick labels (no mathtext: labels and tire names are
rendered literally, ``$`` included); pressure in bar.

The SVG is deterministic (no date; ids salted with the figure's name and prefixed
with it, so several figures can share one page).
"""

from __future__ import annotations

import io
import math
import re
from collections import defaultdict

import numpy as np

from tiremesh.io import cell_number_or_nan as _f
from tiremesh.units import MPA_PER_BAR

from .style import surface_marker
from .trends import DISSERTATION_TABLE_4_1

STYLE = {
    "figure.dpi": 100,
    "font.size": 9,
    "font.family": "sans-serif",
    "font.sans-serif": ["DejaVu Sans", "Arial", "Liberation Sans"],
    "svg.fonttype": "none",
    "text.parse_math": False,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "legend.frameon": False,
}
#: (print column, model column, axis label) per size quantity
SIZES = (
    ("length_mm", "model_length_mm", "length [mm]"),
    ("width_mm", "model_width_mm", "width [mm]"),
    ("hull_area_mm2", "model_area_mm2", "area [mm²]"),
)


def _plt():
    """pyplot on the Agg backend with the report's style."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    plt.rcParams.update(STYLE)
    return plt


def _ok(rows):
    """Rows where both the print and the model are ``ok``."""
    return [r for r in rows if r.get("status", "ok") == "ok" and r.get("model_status") == "ok"]


def _legend_handles(colours: dict, surfaces, *, kinds=True):
    """Legend entries: one per tire (its colour), per surface (its marker), and
    print (filled) / model (open)."""
    from matplotlib.lines import Line2D

    h = [Line2D([], [], color=c, marker="o", ls="", label=t) for t, c in colours.items()]
    h += [
        Line2D([], [], color="0.3", marker=surface_marker(s), ls="", mfc="none", label=s)
        for s in surfaces
    ]
    if kinds:
        h += [
            Line2D([], [], color="0.3", marker="o", ls="-", label="prints (filled, solid)"),
            Line2D(
                [], [], color="0.3", marker="o", mfc="none", ls="--", label="model (open, dashed)"
            ),
        ]
    return h


def _surfaces(rows) -> list[str]:
    return sorted({str(r.get("surface", "")) for r in rows})


def area_vs_length_width(paired, colours: dict):
    """Contact area vs length and vs width, prints and model (cf. Figure 6-3).

    Parameters
    ----------
    paired : list of dict
        Rows of :func:`contactpatch.pair_prints`.
    colours : dict of str to str
        Colour per tire.

    Returns
    -------
    matplotlib.figure.Figure
    """
    plt = _plt()
    fig, axes = plt.subplots(1, 2, figsize=(9, 4.6), sharey=True, layout="constrained")
    rows = _ok(paired)
    small = len(rows) > 200
    for (tire, surface), rs in sorted(_groups(rows, ("tire", "surface")).items()):
        c, m = colours.get(tire, "0.5"), surface_marker(surface)
        kw = dict(marker=m, s=12 if small else 30, alpha=0.7 if small else 1.0, linewidths=1)
        for ax, (pk, mk) in zip(axes, (SIZES[0][:2], SIZES[1][:2]), strict=True):
            area = [_f(r["hull_area_mm2"]) for r in rs]
            ax.scatter([_f(r[pk]) for r in rs], area, color=c, **kw)
            model_area = [_f(r["model_area_mm2"]) for r in rs]
            ax.scatter([_f(r[mk]) for r in rs], model_area, facecolors="none", edgecolors=c, **kw)
    axes[0].set_xlabel("contact patch length [mm]")
    axes[1].set_xlabel("contact patch width [mm]")
    axes[0].set_ylabel("contact patch area [mm²]")
    for ax in axes:
        ax.set_xlim(left=0)
        ax.set_ylim(bottom=0)
    fig.legend(
        handles=_legend_handles(colours, _surfaces(rows)),
        loc="outside lower center",
        ncol=min(4, len(colours) + 2),
        fontsize=8,
    )
    return fig


def _groups(rows, keys) -> dict:
    out = defaultdict(list)
    for r in rows:
        out[tuple(str(r.get(k, "")) for k in keys)].append(r)
    return out


def ratio_summary(paired, colours: dict):
    """Print / model ratios of length, width and area per tire: every print as a
    point, the median as a bar (the aggregate that scales to thousands of prints).

    Parameters
    ----------
    paired : list of dict
    colours : dict of str to str

    Returns
    -------
    matplotlib.figure.Figure
        Three panels side by side, one row per tire.
    """
    plt = _plt()
    rows = _ok(paired)
    tires = sorted({str(r["tire"]) for r in rows})
    height = 1.4 + 0.45 * max(len(tires), 2)
    fig, axes = plt.subplots(1, 3, figsize=(9.5, height), sharey=True, layout="constrained")
    rng = np.random.default_rng(0)  # jitter only: the same figure every time
    keys = ("ratio_length", "ratio_width", "ratio_area")
    for ax, key, label in zip(axes, keys, ("length", "width", "area"), strict=True):
        for k, tire in enumerate(tires):
            v = np.array([_f(r.get(key)) for r in rows if r["tire"] == tire])
            v = v[np.isfinite(v)]
            if not v.size:
                continue
            y = k + rng.uniform(-0.2, 0.2, v.size)
            ax.scatter(v, y, s=8 if v.size > 50 else 20, color=colours[tire], alpha=0.6)
            ax.vlines(np.median(v), k - 0.32, k + 0.32, color="k", lw=2)
        ax.axvline(1.0, color="0.3", lw=0.8, ls=":")
        ax.set_xlabel(f"{label}: print / model")
        ax.grid(axis="y", visible=False)
    axes[0].set_yticks(range(len(tires)), [_short(t, 30) for t in tires])
    axes[0].set_ylim(len(tires) - 0.5, -0.5)
    return fig


def _short(name: str, n: int = 24) -> str:
    """A tire name cut to ``n`` characters for tick labels."""
    return name if len(name) <= n else name[: n - 1] + "…"


def load_per_area(paired, colours: dict):
    """Load over print area vs inflation pressure, both in bar, with the 1:1 line
    (cf. Figure 4-3).

    Parameters
    ----------
    paired : list of dict
        Print rows (``pressure_bar``, ``load_per_hull_area_N_mm2`` [N/mm^2]).
    colours : dict of str to str

    Returns
    -------
    matplotlib.figure.Figure
    """
    plt = _plt()
    fig, ax = plt.subplots(figsize=(7.5, 4.2), layout="constrained")
    rows = [r for r in paired if r.get("status", "ok") == "ok"]
    for (tire, surface), rs in sorted(_groups(rows, ("tire", "surface")).items()):
        ax.scatter(
            [_f(r["pressure_bar"]) for r in rs],
            [_f(r.get("load_per_hull_area_N_mm2")) / MPA_PER_BAR for r in rs],
            marker=surface_marker(surface),
            color=colours.get(tire, "0.5"),
            s=14 if len(rows) > 200 else 30,
        )
    p = [_f(r["pressure_bar"]) for r in rows]
    p = [x for x in p if math.isfinite(x)]
    if p:
        lim = (0.0, 1.15 * max(p))
        ax.plot(lim, lim, "k-", lw=1)
        ax.annotate(
            "load / area = inflation pressure",
            (0.55 * lim[1], 0.55 * lim[1]),
            xytext=(8, -14),
            textcoords="offset points",
            fontsize=8,
        )
        ax.set_xlim(lim)
        ax.set_ylim(lim)
    ax.set_xlabel("inflation pressure [bar]")
    ax.set_ylabel("load / print area (hull) [bar]")
    fig.legend(
        handles=_legend_handles(colours, _surfaces(rows), kinds=False),
        loc="outside right upper",
        fontsize=8,
    )
    return fig


def _plain_log_ticks(ax, axis: str, values=()) -> None:
    """Log-axis ticks a reader can read: at the data's own values when there are a
    few (``values``), else at round 1-2-5 steps inside the axis' range; labels as
    plain numbers (never 4x10^0), no minor labels. Call after plotting."""
    from matplotlib.ticker import FixedLocator, FuncFormatter, NullFormatter, NullLocator

    a = ax.xaxis if axis == "x" else ax.yaxis
    v = sorted({round(x, 6) for x in values if math.isfinite(x) and x > 0})
    if not 0 < len(v) <= 6:
        lo, hi = ax.get_xlim() if axis == "x" else ax.get_ylim()
        raw = (hi - lo) / 5
        mag = 10.0 ** math.floor(math.log10(raw))
        step = next(k * mag for k in (1, 2, 5, 10) if k * mag >= raw)
        v = [k * step for k in range(math.ceil(lo / step), math.floor(hi / step) + 1)]
    a.set_major_locator(FixedLocator(v))
    a.set_major_formatter(FuncFormatter(lambda x, _: f"{x:.4g}"))
    a.set_minor_locator(NullLocator())
    a.set_minor_formatter(NullFormatter())


def _shade(colour: str, level: int, n: int):
    """The tire's colour darker (first level) to lighter (last)."""
    from matplotlib.colors import to_rgb

    rgb = np.array(to_rgb(colour))
    t = 0.0 if n <= 1 else 0.55 * level / (n - 1)
    return tuple(rgb + (1.0 - rgb) * t)


def tire_trends(paired, tire: str, colour: str):
    """Length, width and area vs pressure and vs load for one tire: prints and model.

    Parameters
    ----------
    paired : list of dict
        Rows of :func:`contactpatch.pair_prints`.
    tire : str
        The tire's name (``tire`` column).
    colour : str
        The tire's colour; its shades tell the levels of the other variable apart.

    Returns
    -------
    matplotlib.figure.Figure
        2 x 3 log-log panels.
    """
    plt = _plt()
    rows = [r for r in _ok(paired) if r["tire"] == tire]
    fig, axes = plt.subplots(2, 3, figsize=(9.5, 5.8), layout="constrained")
    panels = (
        ("pressure_bar", "load_N", "pressure [bar]", "N"),
        ("load_N", "pressure_bar", "load [N]", "bar"),
    )
    for row_i, (xkey, other, xlabel, unit) in enumerate(panels):
        levels = sorted({_f(r[other]) for r in rows})
        handles = []
        for j, (pk, mk, ylabel) in enumerate(SIZES):
            ax = axes[row_i, j]
            for (surface, val), rs in sorted(_groups(rows, ("surface", other)).items()):
                c = _shade(colour, levels.index(_f(val)), len(levels))
                rs = sorted(rs, key=lambda r: _f(r[xkey]))
                x = [_f(r[xkey]) for r in rs]
                m = surface_marker(surface)
                label = f"{surface}, {_f(val):g} {unit}"
                (h,) = ax.plot(x, [_f(r[pk]) for r in rs], marker=m, color=c, label=label)
                ax.plot(x, [_f(r[mk]) for r in rs], ls="--", marker=m, mfc="none", color=c)
                handles.append(h)
            ax.set_xscale("log")
            ax.set_yscale("log")
            _plain_log_ticks(ax, "x", [_f(r[xkey]) for r in rows])
            _plain_log_ticks(ax, "y")
            ax.set_xlabel(xlabel)
            ax.set_ylabel(ylabel)
        n = len(handles) // 3
        axes[row_i, 2].legend(
            handles=handles[:n],
            loc="upper left",
            bbox_to_anchor=(1.02, 1.0),
            fontsize=7,
            title="solid: prints\ndashed: model",
            title_fontsize=7,
        )
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
    fig, ax = plt.subplots(figsize=(6.4, 3.8), layout="constrained")
    names = ["length", "width", "area"]
    x = np.arange(3)
    bars = [
        ("prints (mean ± stdev)", print_summary, dict(color="0.35")),
        ("model", model_summary, dict(color="white", edgecolor="k")),
        ("Table 4-1, measured", DISSERTATION_TABLE_4_1, dict(color="0.8", hatch="//")),
    ]
    for k, (label, summary, kw) in enumerate(bars):
        if len(summary) < 3:
            continue
        mean = [s["mean"] for s in summary][:3]
        err = [s.get("stdev", math.nan) for s in summary][:3]
        err = None if label == "model" else [e if math.isfinite(e) else 0.0 for e in err]
        b = ax.bar(x + (k - 1) * 0.27, mean, 0.25, yerr=err, label=label, capsize=3, **kw)
        ax.bar_label(b, labels=[f"{m:.3f}" for m in mean], fontsize=7, padding=2)
    ax.axhline(1.0, color="k", lw=0.8)
    ax.set_xticks(x, names)
    ax.set_ylabel("drum / plate")
    ax.set_ylim(0.6, 1.45)
    ax.grid(axis="x", visible=False)
    fig.legend(loc="outside right upper", fontsize=8)
    return fig


def figure_svg(fig, name: str) -> str:
    """Save a figure once, as SVG text, and close it.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    name : str
        The figure's name: salts and prefixes the SVG's ids (unique on a page).

    Returns
    -------
    str
        The SVG document (text as ``<text>``; no date).
    """
    import matplotlib.pyplot as plt

    buf = io.StringIO()
    with plt.rc_context({"svg.hashsalt": name}):
        fig.savefig(buf, format="svg", metadata={"Date": None})
    plt.close(fig)
    svg = buf.getvalue()
    ids = set(re.findall(r'\bid="([^"]+)"', svg))
    if ids:
        pat = re.compile(
            r'(\bid="|url\(#|href="#)(' + "|".join(map(re.escape, ids)) + r')(?=[")])'
        )
        svg = pat.sub(lambda m: f"{m.group(1)}{name}-{m.group(2)}", svg)
    return svg


__all__ = [
    "area_vs_length_width",
    "drum_vs_plate",
    "figure_svg",
    "load_per_area",
    "ratio_summary",
    "tire_trends",
]
