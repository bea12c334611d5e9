"""Text of the validation: ``summary.md``, ``index.html`` and the fragments of
:func:`.validate.report_section`.

Every function reads the plain result dict (:meth:`.validate.Validation.to_dict`, or
``validation.json`` read back), so fresh and cached results print the same. Numbers
are shown to 3-4 significant digits; the CSV / JSON tables keep full precision.
HTML text is escaped with :func:`html.escape`.
"""

from __future__ import annotations

import html
import math
from collections import Counter

from . import numbers as N
from .pages import md_text

TITLE = "Validation against the measurements of Dressel (2013)"
STAT_COLUMNS = [
    ("label", "quantity"),
    ("unit", "unit"),
    ("n", "n"),
    ("n_tires", "tires"),
    ("median_ratio", "median model/meas."),
    ("worst_ratio", "worst"),
    ("worst_row", "worst row"),
    ("min_ratio", "min"),
    ("max_ratio", "max"),
    ("rms_log_error", "RMS log error"),
    ("n_not_positive", "opposite sign"),
    ("kind", "kind"),
]
VARIANT_COLUMNS = [
    ("variant", "decay length beyond the patch"),
    ("parameters", "parameters"),
    ("fitted_parameters", "fitted"),
    ("n", "n"),
    ("median_ratio", "median"),
    ("worst_ratio", "worst"),
    ("rms_log_error", "RMS log error"),
]
LOTO_COLUMNS = [
    ("tire_id", "tire"),
    ("tire", "name"),
    ("n", "n"),
    ("modulus_without_tire", "casing modulus E without it [N/mm²]"),
    ("ratios", "its model/meas."),
    ("rms_log_error", "RMS log error"),
]
POINTS_TITLE = "Every compared point"
POINT_TABLE_COLUMNS = [
    ("row", "row"),
    ("quantity", "quantity"),
    ("tire_id", "tire"),
    ("pressure_bar", "bar"),
    ("load_N", "N"),
    ("surface", "surface"),
    ("measured", "measured"),
    ("model", "model"),
    ("ratio", "model/meas."),
    ("source", "source"),
]
CORNERING_COLUMNS = [
    ("variant", "decay length beyond the patch"),
    ("n", "n"),
    ("median_ratio", "median"),
    ("min_ratio", "min"),
    ("max_ratio", "max"),
    ("rms_log_error", "RMS log error"),
]
TREND_COLUMNS = [
    ("quantity", "quantity"),
    ("variable", "with"),
    ("dissertation", "dissertation (measured)"),
    ("measured_pairs", "CSV pairs"),
    ("n_pairs", "pairs"),
    ("model_on_pairs", "model, same pairs"),
    ("measured_exponent", "slope meas."),
    ("model_exponent", "slope model"),
    ("model", "model, 10 % step"),
    ("n_model_conditions", "conditions"),
    ("agree", "agree"),
]
SUMMARY_COLUMNS = [
    ("source", "source"),
    ("quantity", "quantity"),
    ("measured", "measured"),
    ("model", "model"),
    ("agree", "agree"),
    ("rule", "rule"),
    ("note", "note"),
]
CSS = """section#validation table{border-collapse:collapse;font-size:13px;margin:0.8em 0}
section#validation td,section#validation th{border:1px solid #ccc;padding:2px 6px;vertical-align:top;text-align:left}
section#validation .num{text-align:right;font-variant-numeric:tabular-nums;white-space:nowrap}
section#validation th{background:#eee}
section#validation .vscroll,section#validation .figscroll{overflow-x:auto;max-width:100%}
section#validation .figscroll svg{display:block;max-width:none;width:100%;min-width:720px;height:auto}
section#validation figcaption{font-size:13px;color:#555}
section#validation .stack{display:none}
@media (max-width:600px){section#validation .stacked{position:relative;overflow:visible}
section#validation .stacked>svg{position:absolute;width:1px;height:1px;min-width:0;overflow:hidden;clip-path:inset(50%)}
section#validation .stacked>.stack{display:block}
section#validation .stack svg{display:block;width:100%;max-width:30rem;min-width:0;height:auto;margin:0 auto .6rem}}"""
#: why the model misses a quantity, with the dissertation's section
WHY = {
    "cornering_stiffness": (
        "this is with the decay length that reproduces the static lateral stiffness; a "
        "decay long enough for the cornering stiffness makes the lateral stiffness too "
        "high (below)"
    ),
    "pneumatic_trail": (
        "whatever the decay length, as the tread enters the patch undisplaced in the model's "
        "slip kinematics, so its force builds toward the trailing end and the trail is "
        "a quarter of the patch length (4.1.8 measures 12.76 % on average), while the "
        "measured centre line is displaced well ahead of the patch (Figure 4-15, 4.1.9.1); "
        "the dissertation found modelling that displacement 'fruitless' (8.1.4)"
    ),
    "aligning_stiffness": "it is the patch's cornering force times the trail (above)",
    "ellipse_length": "the model's patch is longer and pointed (6.2.1, 7.3.1)",
    "ellipse_width": "the model's patch is narrower than the prints (6.2.1)",
    "load_per_area": "area x pressure = load is built into the model (6.1.1)",
    "decay_length": (
        "the decay length that reproduces the lateral stiffness is a fraction of the "
        "measured one (3.11.4, 4.1.9.1): a Rotta foundation carrying the measured decay "
        "would be several times too stiff (Appendix C's 0.993 per mm, above)"
    ),
}


#: columns shown as ratios (3 decimals, as the report's ratios)
RATIO_KEYS = {
    "median_ratio",
    "worst_ratio",
    "min_ratio",
    "max_ratio",
    "ratio",
    "rms_log_error",
    "measured_exponent",
    "model_exponent",
}
#: columns shown as counts / identifiers
INT_KEYS = {"n", "n_tires", "n_not_positive", "n_pairs", "n_model_conditions", "row", "tire_id"}


def fmt(v, key: str = "") -> str:
    """Cell text, by quantity as in the report (:mod:`contactpatch.study.numbers`):
    ratios and exponents to 3 decimals, pressures [bar] to 0.01, loads [N] to 1,
    counts as integers, other numbers to 4 significant digits; anything that rounds
    to zero as ``0``; NaN / None empty.

    Parameters
    ----------
    v : object
        A table cell (float, int, str, None...).
    key : str
        Its column (sets the precision; without one, 4 significant digits).

    Returns
    -------
    str
    """
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return ""
    if isinstance(v, bool) or not isinstance(v, int | float):
        return str(v)
    if key in INT_KEYS and float(v).is_integer():
        return str(int(v))
    if key in RATIO_KEYS:
        return N.fixed(float(v), 3)
    if key in ("pressure_bar", "load_N"):
        return N.fmt(v, key)
    if isinstance(v, int):
        return str(v)
    return N._significant(float(v), 4)


def is_number(v) -> bool:
    """Whether a cell is a number (right-aligned).

    Parameters
    ----------
    v : object

    Returns
    -------
    bool
    """
    return isinstance(v, int | float) and not isinstance(v, bool)


def display_rows(rows: list[dict]) -> list[dict]:
    """Rows as shown: pressures in bar (the report's one pressure unit; 1 bar =
    0.1 N/mm^2) -- ``load / ink-print area`` in the statistics and points; areas
    in mm² (the data's ``mm^2``).

    Parameters
    ----------
    rows : list of dict

    Returns
    -------
    list of dict
        Copies where changed; ratios are unit-free and stay.
    """
    out = []
    for r in rows:
        if r.get("unit") == "N/mm^2":
            r = dict(r, unit="bar")
            for k in ("measured", "model"):
                if is_number(r.get(k)):
                    r[k] = 10.0 * r[k]
        elif r.get("unit") == "mm^2":
            r = dict(r, unit="mm²")
        out.append(r)
    return out


def _x(v) -> str:
    """A ratio as text, '0.41x'."""
    return f"{v:.3g}x" if isinstance(v, int | float) and math.isfinite(v) else "n/a"


def _stat(data: dict, quantity: str) -> dict:
    return next((s for s in data["statistics"] if s["quantity"] == quantity), {})


def _variant(data: dict, prefix: str) -> dict:
    return next((v for v in data["variants"] if v["variant"].startswith(prefix)), {})


def _quantity_limits(data: dict) -> list[str]:
    out = []
    for s in data["statistics"]:
        if s["kind"] != "measured" or 0.8 <= s["median_ratio"] <= 1.25:
            continue
        why = WHY.get(s["quantity"], "")
        out.append(
            f"{s['label'].capitalize()}: the model gives {_x(s['median_ratio'])} the "
            f"measured value (median of {s['n']}; worst {_x(s['worst_ratio'])})"
            + (f"; {why}." if why else ".")
        )
    return out


def _trend_limits(data: dict) -> list[str]:
    out = []
    for t in data["trends"]:
        if t["agree"] not in ("no", "partly"):
            continue
        model = f"is {t['model']}" if t["model"].startswith("mixed") else t["model"]
        out.append(
            f"{t['quantity'].replace('_', ' ').capitalize()} with {t['variable'].replace('_', ' ')}: "
            f"the dissertation says it {t['dissertation']}; the model {model} "
            f"at its {t['n_model_conditions']} measured conditions."
        )
    return out


def limits(data: dict) -> list[str]:
    """Plain statements of where the model cannot follow the measurements, from the
    results (quantities with a median ratio outside 0.8..1.25, trends and summary
    checks that disagree, the decay length and the pressure sensitivity).

    Parameters
    ----------
    data : dict
        :meth:`.validate.Validation.to_dict`.

    Returns
    -------
    list of str
    """
    out = _quantity_limits(data) + _trend_limits(data)
    lat = next(
        (
            t
            for t in data["trends"]
            if t["quantity"] == "lateral_stiffness" and t["variable"] == "pressure"
        ),
        None,
    )
    if lat and math.isfinite(lat["measured_exponent"]) and math.isfinite(lat["model_exponent"]):
        out.append(
            "Lateral stiffness vs pressure at fixed load: log-log slope "
            f"{lat['measured_exponent']:.2g} measured, {lat['model_exponent']:.2g} in the model "
            f"({lat['n_pairs']} pairs). Every Rotta force scales with the pressure; the real "
            "carcass adds a stiffness that does not, so the model is too soft at low and too "
            f"stiff at high pressure ({_extremes(data)})."
        )
    out += _cornering_limit(data)
    out += _trail_limit(data)
    app, beam = _variant(data, "Appendix C"), _variant(data, "taut beam, E fitted (leave")
    if app and beam:
        out.append(
            f"Decay length: with Appendix C's fixed 0.993 per mm (143 mm) the static lateral "
            f"stiffness is {_x(app['median_ratio'])} the measured (median; worst "
            f"{_x(app['worst_ratio'])}); with the taut-beam decay length ({_decays(data)}) it "
            f"is {_x(beam['median_ratio'])}. The measured decay lengths are longer (3.11.4: "
            "about 99 mm under a point load; 4.1.9.1: about 3 patch lengths rolling), so the "
            "Rotta sections beyond the patch are too stiff a foundation to carry both."
        )
    return out + _summary_limits(data)


def _cornering_limit(data: dict) -> list[str]:
    """One line: cornering stiffness under the three decay lengths vs the lateral
    stiffness under the same."""
    rows = [r for r in data.get("cornering", []) if r["quantity"] == "cornering_stiffness"]
    app = _variant(data, "Appendix C")
    if len(rows) < 3 or not app:
        return []
    beam, appx, roll = rows
    return [
        "No single decay length gives both the static lateral and the cornering stiffness: "
        f"with the taut-beam decay the cornering stiffness is {_x(beam['median_ratio'])} the "
        f"measured (median); with Appendix C's 143 mm it is {_x(appx['median_ratio'])} but the "
        f"lateral stiffness {_x(app['median_ratio'])}; with the rolling decay measured in "
        f"4.1.9.1 (about 3 patch lengths) it is {_x(roll['median_ratio'])}."
    ]


def _trail_limit(data: dict) -> list[str]:
    """One line: the pneumatic trail under each slip kinematics (4.1.8)."""
    rows = [r for r in data.get("trail", []) if r.get("n")]
    if not rows:
        return []
    parts = [
        f"{r['variant']} {_x(r['median_ratio'])} the measured, "
        f"{r['trail_pct_of_length']:.1f} % of the patch length"
        for r in rows
    ]
    return [
        "Pneumatic trail by slip kinematics (median model / measured; measured mean 12.76 % "
        "of the patch length, 4.1.8): " + "; ".join(parts) + "."
    ]


def _decays(data: dict) -> str:
    """Median and range of the decay lengths used for the lateral stiffness."""
    d = [
        p["decay_length_mm"]
        for p in data["points"]
        if p["quantity"] == "lateral_stiffness"
        and p["status"] == "compared"
        and isinstance(p["decay_length_mm"], float)
        and math.isfinite(p["decay_length_mm"])
    ]
    if not d:
        return "none"
    d.sort()
    return f"median {d[len(d) // 2]:.3g} mm, {d[0]:.3g} to {d[-1]:.3g} mm"


def _extremes(data: dict) -> str:
    """Lateral-stiffness ratios at the lowest and highest measured pressure."""
    pts = [
        p
        for p in data["points"]
        if p["quantity"] == "lateral_stiffness" and p["status"] == "compared"
    ]
    if not pts:
        return "no points"
    lo = min(pts, key=lambda p: p["pressure_bar"])
    hi = max(pts, key=lambda p: p["pressure_bar"])
    return (
        f"{lo['tire']} at {lo['pressure_bar']:g} bar: {_x(lo['ratio'])}; "
        f"{hi['tire']} at {hi['pressure_bar']:g} bar: {_x(hi['ratio'])}"
    )


def _summary_limits(data: dict) -> list[str]:
    """Summary checks that disagree (Table 4-3's three correlations in one line)."""
    out, corr = [], []
    for s in data["summaries"]:
        if s["agree"] != "no" or s["item"] == "cornering_range":
            continue
        if s["item"] == "table_4_3":
            corr.append(f"{s['measured']} vs {s['model']}")
            continue
        out.append(
            f"{s['quantity'].capitalize()} ({s['source']}): measured {s['measured']}; "
            f"model {s['model']}."
        )
    if corr:
        out.append(
            "Normalized lateral stiffness vs true size of four 37-622 tires (Table 4-3, 6.2.3): "
            "correlations of its max, min and average, measured vs model: "
            + "; ".join(corr)
            + ". The measured stiffness rises with carcass size, the model's falls, as 6.2.3 "
            "found: the longer decay of a larger tire does not make up for its softer sections."
        )
    return out


def _numeric(rows: list[dict], key: str) -> bool:
    """A column is numeric when every filled cell is a number."""
    cells = [r.get(key) for r in rows if r.get(key) not in (None, "")]
    return bool(cells) and all(is_number(c) for c in cells)


def _md_table(rows: list[dict], columns) -> str:
    rows = display_rows(rows)
    head = "| " + " | ".join(md_text(h) for _, h in columns) + " |"
    sep = "|" + "".join("---:|" if _numeric(rows, k) else "---|" for k, _ in columns)
    body = ["| " + " | ".join(md_text(fmt(r.get(k), k)) for k, _ in columns) + " |" for r in rows]
    return "\n".join([head, sep, *body])


def _html_table(rows: list[dict], columns) -> str:
    rows = display_rows(rows)
    num = {k for k, _ in columns if _numeric(rows, k)}
    head = "".join(
        f"<th{' class=num' if k in num else ''}>{html.escape(h)}</th>" for k, h in columns
    )
    body = "".join(
        "<tr>"
        + "".join(
            f"<td{' class=num' if is_number(r.get(k)) else ''}>{html.escape(fmt(r.get(k), k))}</td>"
            for k, _ in columns
        )
        + "</tr>"
        for r in rows
    )
    return (
        f"<div class='vscroll'><table><thead><tr>{head}</tr></thead>"
        f"<tbody>{body}</tbody></table></div>"
    )


def headline(data: dict) -> str:
    """One paragraph: what was compared and the fitted parameter.

    Parameters
    ----------
    data : dict
        :meth:`.validate.Validation.to_dict` (or ``validation.json`` read back).

    Returns
    -------
    str
        Plain text (not escaped): the row counts per status, the fitted casing
        modulus [N/mm^2] and its leave-one-tire-out RMS log error, the slip
        kinematics and the friction.
    """
    st, counts = data["settings"], Counter(p["status"] for p in data["points"])
    beam = _variant(data, "taut beam, E fitted (leave")
    return (
        f"{st['n_rows']} rows of measured-dressel2013.csv: {counts.get('compared', 0)} points "
        f"compared with the model, {counts.get('summary', 0)} summary statistics checked, "
        f"{counts.get('duplicate', 0)} duplicates, {counts.get('ambiguous', 0)} with an "
        f"ambiguous load, {counts.get('not a measurement', 0)} interpolated by the author, "
        f"{counts.get('not modelled', 0)} not modelled, {counts.get('model input', 0)} model "
        f"inputs, {counts.get('model error', 0)} model errors. One global parameter is fitted: "
        f"the casing modulus of the taut beam (5.9), E = {st['modulus_N_mm2']:.3g} N/mm² at "
        f"t = {st['thickness_mm']:g} mm (E t = {st['modulus_times_thickness_N_mm']:.3g} N/mm), "
        f"fitted to the {beam.get('n', 0)} static lateral stiffnesses; every reported value of "
        "a fitted tire uses E fitted without that tire (leave one tire out: RMS log error "
        f"{beam.get('rms_log_error', math.nan):.3g}). Slip kinematics "
        f"'{st['slip_kinematics']}', friction {st['friction']}."
    )


def _accounting(data: dict) -> list[dict]:
    """Rows not compared, grouped by status and reason."""
    groups = Counter(
        (p["status"], p["reason"].split(" (row")[0])
        for p in data["points"]
        if p["status"] not in ("compared", "summary")
    )
    return [{"status": s, "reason": r, "n": n} for (s, r), n in sorted(groups.items())]


def _sections(data: dict) -> list[tuple[str, str, list, list]]:
    """(title, intro, rows, columns) of each table, in page order."""
    return [
        (
            "Model / measured per quantity",
            "Ratios of the model to the measured value; "
            "the RMS log error is sqrt(mean(ln(model/measured)^2)).",
            data["statistics"],
            STAT_COLUMNS,
        ),
        (
            "The fitted parameter and leave-one-tire-out",
            "How the decay length beyond the "
            "patch is set (the static lateral stiffness depends on it most).",
            data["variants"],
            VARIANT_COLUMNS,
        ),
        (
            "Cornering stiffness vs the decay length",
            "None of these is fitted. The trail does not depend on the decay length.",
            data.get("cornering", []),
            CORNERING_COLUMNS,
        ),
        (
            "Leave one tire out, per tire",
            "E fitted without the tire, and the tire's lateral stiffnesses predicted with it.",
            data["loto"],
            LOTO_COLUMNS,
        ),
        (
            "Trends: what rises with pressure, load, rim width, arc length",
            "Measured: the "
            "dissertation's counts and the pairs of measured conditions of one tire in the CSV; "
            "model: the same pairs, and a 10 % step (5 % for arc length) at each measured "
            "condition. Lateral stiffness normalized by the load, as 6.2.4 counts it.",
            data["trends"],
            TREND_COLUMNS,
        ),
        (
            "Summary statistics of the dissertation",
            "Statistics whose individual values are "
            "lost, against the model over the measured drum conditions.",
            data["summaries"],
            SUMMARY_COLUMNS,
        ),
        (
            "Rows not compared",
            "Every CSV row has a status in points.csv.",
            _accounting(data),
            [("status", "status"), ("reason", "reason"), ("n", "n")],
        ),
        (
            POINTS_TITLE,
            "Model / measured for every compared row (leave-one-tire-out values; row = "
            "data row of the CSV, its line is row + 1).",
            [p for p in data["points"] if p["status"] == "compared"],
            POINT_TABLE_COLUMNS,
        ),
    ]


FIGURE_CAPTIONS = {
    "measured_vs_model": "Measured vs model, log axes, with the 1:1 line and factors of 2; "
    "colours are tires; open markers: load stated two ways (bar: both loads).",
    "relaxation_fit": "Left: RMS log error of the static lateral stiffness vs the casing "
    "modulus (one global parameter) with the leave-one-tire-out refits. Right: the error "
    "for each way of setting the decay length.",
}


def markdown_fragment(data: dict, link_base: str = "", level: int = 2) -> str:
    """The validation as Markdown (headings from ``level``; figures linked under
    ``link_base``).

    Parameters
    ----------
    data : dict
        :meth:`.validate.Validation.to_dict` (or ``validation.json`` read back).
    link_base : str
        Prefix of the figure links (``{link_base}figures/{name}.svg``).
    level : int
        Heading level of the title; sections are one level deeper.

    Returns
    -------
    str
        Markdown: headline, limits, figures, tables and the inputs, ending in a
        newline.
    """
    h = "#" * level
    parts = [f"{h} {TITLE}", headline(data), f"{h}# What the model cannot follow"]
    parts += [f"- {s}" for s in data["limits"]]
    for name, cap in FIGURE_CAPTIONS.items():
        parts.append(f"![{cap}]({link_base}figures/{name}.svg)\n\n*{cap}*")
    for title, intro, rows, cols in _sections(data):
        parts += [f"{h}# {title}", intro, _md_table(rows, cols)]
    st = data["settings"]
    parts.append(
        f"Measurements: {st['measurements']} (sha256 {st['measurements_sha256'][:12]}); "
        f"tiremesh {st['tiremesh_version']}; {st['seconds']} s."
    )
    return "\n\n".join(parts) + "\n"


def summary_markdown(data: dict) -> str:
    """``summary.md`` of the output folder (figures under ``figures/``).

    Parameters
    ----------
    data : dict
        :meth:`.validate.Validation.to_dict` (or ``validation.json`` read back).

    Returns
    -------
    str
        :func:`markdown_fragment` with a level-1 title and relative links.
    """
    return markdown_fragment(data, "", level=1)


def _img(name: str, svg: str, caption: str) -> str:
    from .pages import inline_svg
    from .svgplot import stack_html

    stack = stack_html(svg)  # small screens: the panels one below the other
    box = "figscroll stacked" if stack else "figscroll"
    return (
        f'<figure id="vfig-{name}" class="chart"><div class="{box}">'
        f"{inline_svg(svg, caption)}{stack}</div>"
        f"<figcaption>{html.escape(caption)} <span class='files'>(vector file: "
        f"<code>figures/{name}.svg</code> of the validation)</span></figcaption></figure>"
    )


def html_fragment(data: dict, figures: dict[str, str]) -> str:
    """A self-contained ``<section id="validation">`` (figures as inline SVG).

    Parameters
    ----------
    data : dict
        :meth:`.validate.Validation.to_dict` (or ``validation.json`` read back).
    figures : dict of str to str
        Figure name (a key of :data:`FIGURE_CAPTIONS`) -> SVG document; missing
        figures are left out.

    Returns
    -------
    str
        HTML (all text escaped) with its own ``<style>``; the table of every
        compared point is folded in ``<details>``.
    """
    parts = [
        '<section id="validation">',
        f"<style>{CSS}</style>",
        f"<h2>{html.escape(TITLE)}</h2>",
        f"<p>{html.escape(headline(data))}</p>",
        "<h3>What the model cannot follow</h3>",
        "<ul>" + "".join(f"<li>{html.escape(s)}</li>" for s in data["limits"]) + "</ul>",
    ]
    parts += [_img(n, figures[n], c) for n, c in FIGURE_CAPTIONS.items() if n in figures]
    for title, intro, rows, cols in _sections(data):
        table = _html_table(rows, cols)
        if title == POINTS_TITLE:  # long: folded
            table = f"<details><summary>{len(rows)} points</summary>{table}</details>"
        parts += [f"<h3>{html.escape(title)}</h3>", f"<p>{html.escape(intro)}</p>", table]
    parts.append("</section>")
    return "\n".join(parts)


def standalone_html(data: dict, figures: dict[str, str]) -> str:
    """``index.html``: the fragment in a page.

    Parameters
    ----------
    data : dict
        :meth:`.validate.Validation.to_dict` (or ``validation.json`` read back).
    figures : dict of str to str
        Figure name -> SVG document (:func:`html_fragment`).

    Returns
    -------
    str
        A complete HTML document around :func:`html_fragment`, ending in a newline.
    """
    return (
        '<!DOCTYPE html><html lang="en"><head><meta charset="utf-8">'
        f"<title>{html.escape(TITLE)}</title></head>"
        '<body style="font-family:system-ui,sans-serif;max-width:1200px;margin:2em auto">'
        f"{html_fragment(data, figures)}</body></html>\n"
    )


__all__ = [
    "TITLE",
    "display_rows",
    "fmt",
    "headline",
    "html_fragment",
    "is_number",
    "limits",
    "markdown_fragment",
    "standalone_html",
    "summary_markdown",
]
