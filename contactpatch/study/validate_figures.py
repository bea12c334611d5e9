"""Figures of the validation (matplotlib, Agg, no mathtext).

Each function takes plain rows (the dicts written to ``points.json`` and
``validation.json``) and returns a Figure; :func:`tiremesh.io.save_figure` writes it.
Build and save them inside :func:`figure_style`.
"""

from __future__ import annotations

import math
import textwrap

import numpy as np

from .style import tire_colours
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
MARKERS = "osD^v<>ph*XP"


#: matplotlib settings of the validation's figures (see :func:`figure_style`)
STYLE = {
    "svg.hashsalt": "contactpatch-validate",
    "figure.dpi": 100,
    "font.size": 10,
    "text.parse_math": False,
    "text.usetex": False,
}


def _plt():
    """pyplot on the Agg backend."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def figure_style():
    """Context manager with :data:`STYLE` (plain-text labels, no mathtext; fixed SVG
    ids): build *and* save the figures inside it, since tick labels are drawn at save
    time. Leaves the global matplotlib settings alone.

    Returns
    -------
    context manager
        :func:`matplotlib.pyplot.rc_context` with :data:`STYLE` (Agg backend).
    """
    return _plt().rc_context(STYLE)


def _finite(*xs) -> bool:
    return all(isinstance(x, int | float) and math.isfinite(x) and x != 0 for x in xs)


def _panel(ax, rows, quantities, colors):
    """One measured-vs-model panel: compared points filled, ambiguous ones open with
    a bar spanning their two loads; the 1:1 line and factor-2 lines."""
    vals = []
    for j, q in enumerate(quantities):
        marker = MARKERS[j % len(MARKERS)]
        for r in rows:
            if r["quantity"] != q or not _finite(r.get("measured"), r.get("model")):
                continue
            m, y = abs(r["measured"]), abs(r["model"])
            vals += [m, y]
            c = colors.get(r.get("tire_id"), "0.4")
            if r["status"] == "compared":
                ax.plot(m, y, marker, color=c, ms=5, mec="k", mew=0.4)
            elif r["status"] == "ambiguous" and _finite(r.get("model_alt")):
                lo, hi = sorted((y, abs(r["model_alt"])))
                ax.plot([m, m], [lo, hi], "-", color=c, lw=1)
                ax.plot(m, y, marker, mfc="none", color=c, ms=6)
                vals.append(hi)
    if not vals:
        ax.text(0.5, 0.5, "no points", transform=ax.transAxes, ha="center")
        return
    lo, hi = min(vals) / 1.5, max(vals) * 1.5
    t = np.geomspace(lo, hi, 2)
    ax.plot(t, t, "k-", lw=0.8, label="1:1")
    ax.plot(t, 2 * t, "k:", lw=0.6, label="x2, /2")
    ax.plot(t, t / 2, "k:", lw=0.6)
    ax.set(xscale="log", yscale="log", xlim=(lo, hi), ylim=(lo, hi))
    _log_ticks(ax, subs=(1.0, 2.0, 5.0) if hi / lo < 300 else (1.0,))
    ax.set_xlabel("measured")
    ax.set_ylabel("model")


def _log_ticks(ax, which: str = "xy", subs=(1.0, 2.0, 5.0)) -> None:
    """Log-axis major ticks at ``subs`` x 10^k labelled with %g (plain text, no
    mathtext), no minor ticks (fast to draw)."""
    from matplotlib.ticker import FormatStrFormatter, LogLocator, NullLocator

    for axis in [a for n, a in (("x", ax.xaxis), ("y", ax.yaxis)) if n in which]:
        axis.set_major_locator(LogLocator(subs=subs, numticks=12))
        axis.set_major_formatter(FormatStrFormatter("%g"))
        axis.set_minor_locator(NullLocator())


def measured_vs_model(rows: list[dict], stats: list[dict]):
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
    matplotlib.figure.Figure
    """
    plt = _plt()
    tires = sorted({r["tire_id"] for r in rows if isinstance(r.get("tire_id"), int)})
    names = {r["tire_id"]: str(r.get("tire", "")) for r in rows if r.get("tire_id") in tires}
    by_name = tire_colours(names.values())  # the report's colour of each tire
    colors = {t: by_name[names[t]] for t in tires}
    by_q = {s["quantity"]: s for s in stats}
    fig, axes = plt.subplots(2, 4, figsize=(13, 8.4))
    for ax, (title, qs) in zip(axes.ravel(), PANELS.items(), strict=True):
        _panel(ax, rows, qs, colors)
        n = sum(by_q.get(q, {}).get("n", 0) for q in qs)
        med = [by_q[q]["median_ratio"] for q in qs if q in by_q]
        sub = f"n = {n}" + (f", median ratio {med[0]:.3g}" if len(med) == 1 else "")
        ax.set_title(textwrap.fill(title, 34) + f"\n{sub}", fontsize=9.5)
        if len(qs) > 1:
            for j, q in enumerate(qs):
                label = QUANTITIES[q][0].split(" (")[0]
                ax.plot([], [], MARKERS[j], color="0.5", label=textwrap.fill(label, 22))
            ax.legend(fontsize=8, loc="upper left", framealpha=0.85)
    handles = [
        plt.Line2D([], [], marker="o", ls="", color=colors[t], mec="k", mew=0.4) for t in tires
    ]
    fig.legend(
        handles,
        [f"{t}: {names.get(t, '')}" for t in tires],
        loc="lower center",
        ncol=4,
        fontsize=9,
        frameon=False,
    )
    fig.suptitle(
        "Rotta model vs the measurements preserved in Dressel (2013); open: load ambiguous"
    )
    fig.subplots_adjust(left=0.06, right=0.99, top=0.88, bottom=0.2, wspace=0.38, hspace=0.6)
    return fig


def relaxation_figure(curve: dict, variants: list[dict]):
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
    matplotlib.figure.Figure
    """
    plt = _plt()
    fig, (a, b) = plt.subplots(1, 2, figsize=(12, 4.6))
    e = np.asarray(curve["modulus"], float)
    rms = np.asarray(curve["rms_log_error"], float)
    pos = e > 0
    a.plot(e[pos], rms[pos], "k-", lw=1, label="in sample, all fit tires")
    a.axhline(rms[0], color="0.5", ls="--", lw=0.8, label="E = 0 (taut string)")
    a.axvline(curve["fitted"], color="C3", lw=1, label=f"fitted E = {curve['fitted']:.3g} N/mm^2")
    for x in curve["loto"]:
        a.axvline(x, color="C0", lw=0.6, alpha=0.7)
    a.plot([], [], color="C0", lw=0.6, label="E fitted without one tire")
    a.set_xscale("log")
    _log_ticks(a, "x", subs=(1.0,))
    a.set(
        xlabel="casing modulus E [N/mm^2] (t fixed)",
        ylabel="RMS log error, static lateral stiffness",
    )
    a.legend(fontsize=9)
    a.set_title("Taut beam of 5.9: the one fitted parameter")
    names = [v["variant"] for v in variants]
    y = np.arange(len(names))
    b.barh(
        y,
        [v["rms_log_error"] for v in variants],
        color=["C3" if v["fitted_parameters"] else "0.6" for v in variants],
    )
    b.set_yticks(y, names, fontsize=9)
    b.invert_yaxis()
    b.set_xlabel("RMS log error of the static lateral stiffness\n(red: 1 fitted parameter)")
    b.set_title("How the decay length beyond the patch is set")
    fig.subplots_adjust(left=0.07, right=0.98, top=0.92, bottom=0.17, wspace=0.85)
    return fig


__all__ = ["PANELS", "STYLE", "figure_style", "measured_vs_model", "relaxation_figure"]
