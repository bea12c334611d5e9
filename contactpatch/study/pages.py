"""The report's pages: ``index.html`` (self-contained) and ``report.md``.

Each page is a list of sections, each drawn by one small function from a
:class:`contactpatch.study.report.ReportContent`. Numbers are formatted by
:func:`fmt` (6 significant digits), the same in both pages; the CSV tables hold them
in full precision.
"""

from __future__ import annotations

import base64
import html
import math
from pathlib import Path
from typing import TYPE_CHECKING

from .compare import PAIRED_COLUMNS
from .trends import describe_agreement

if TYPE_CHECKING:
    from .report import ReportContent

#: ids of the HTML page's sections, in order
SECTIONS = (
    "summary",
    "key-figure",
    "load-per-area",
    "paired",
    "trends",
    "drum-plate",
    "rim",
    "prints",
    "renders",
    "errors",
    "notes",
)
TITLE = "Contact patches: Rotta model vs ink prints"
TREND_COLUMNS = [
    "tire",
    "surface",
    "quantity",
    "n",
    "print_pressure_exp",
    "model_pressure_exp",
    "print_load_exp",
    "model_load_exp",
    "print_r2",
    "model_r2",
]
DRUM_COLUMNS = ["source", "quantity", "max", "min", "mean", "stdev"]
RIM_COLUMNS = [
    "tire",
    "rim_width_mm",
    "pressure_bar",
    "load_N",
    "dlog_length_dlog_rim",
    "dlog_width_dlog_rim",
    "dlog_area_dlog_rim",
]
ERROR_COLUMNS = ["file", "print", "status", "error", "model_status", "model_error"]
CSS = """body{font-family:system-ui,sans-serif;margin:2em auto;max-width:1200px;color:#222}
table{border-collapse:collapse;font-size:12px;margin:1em 0}td,th{border:1px solid #ccc;padding:2px 6px;
text-align:right}th{background:#eee}figure{margin:1em 0}img{max-width:100%}figcaption{font-size:12px;color:#555}
section{margin-top:2em}code{background:#f4f4f4}"""
NOTES = (
    "The model's patch has pointed ends; its ellipse (section 5.4) is what is compared "
    "with a print's.",
    "Area x pressure = load is built into the model; prints measure it.",
    "Which ink spots at a print's edge bore load is a judgement (7.1.1); the print table "
    "carries both all-ink and load-bearing numbers and a +-10 % threshold band.",
    "No deflection beyond the patch, friction or slip is modelled in these comparisons.",
)


def fmt(v) -> str:
    """Cell text: numbers to 6 significant digits.

    Parameters
    ----------
    v : object
        A table cell (number, numeric string, text, None).

    Returns
    -------
    str
        Empty for NaN; other values as text.
    """
    if isinstance(v, bool | int):
        return str(v)
    if isinstance(v, float):
        return "" if math.isnan(v) else f"{v:.6g}"
    try:
        x = float(v)
    except (TypeError, ValueError):
        return str(v)
    return str(v) if not math.isfinite(x) or str(v).strip() == "" else f"{x:.6g}"


# --- HTML building blocks ------------------------------------------------------------


def _table_html(rows, columns, table_id) -> str:
    head = "".join(f"<th>{html.escape(c)}</th>" for c in columns)
    body = "\n".join(
        "<tr>" + "".join(f"<td>{html.escape(fmt(r.get(c, '')))}</td>" for c in columns) + "</tr>"
        for r in rows
    )
    return (
        f'<table id="{table_id}"><thead><tr>{head}</tr></thead><tbody>\n{body}\n</tbody></table>'
    )


def _img(path: Path, alt: str) -> str:
    """The PNG embedded as a data URI, with a link to its SVG when there is one."""
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    svg = path.with_suffix(".svg")
    link = f' <a href="figures/{svg.name}">SVG</a>' if svg.exists() else ""
    return (
        f'<figure><img alt="{html.escape(alt)}" src="data:image/png;base64,{data}">'
        f"<figcaption>{html.escape(alt)}{link}</figcaption></figure>"
    )


def _section(section_id: str, title: str, *body: str) -> str:
    return f'<section id="{section_id}"><h2>{title}</h2>' + "".join(body) + "</section>"


# --- HTML sections -------------------------------------------------------------------


def _summary(c: ReportContent) -> str:
    cfg = "".join(
        f"<tr><th>{html.escape(k)}</th><td>{html.escape(str(v))}</td></tr>"
        for k, v in c.config.items()
    )
    return _section(
        "summary",
        "Summary and configuration",
        f'<table id="config">{cfg}</table>',
        "<p>Model: A. E. Dressel (2013), chapter 5 (Rotta's model in 3D). Prints: sections "
        "3.5, 4.1.1. Tables in full precision: <code>tables/*.csv</code>, "
        "<code>report.json</code>.</p>",
    )


def _key_figure(c: ReportContent) -> str:
    return _section(
        "key-figure",
        "Area vs length and width (Figure 6-3)",
        _img(c.figures.key, "Contact area vs length and width, prints and model"),
        "<p>Measured patches are shorter and wider than the model's pointed patches "
        "(section 6.2.1).</p>",
    )


def _load_per_area(c: ReportContent) -> str:
    return _section(
        "load-per-area",
        "Load over print area vs inflation pressure (Figure 4-3)",
        _img(c.figures.load, "Load / print area vs inflation pressure, with the 1:1 line"),
        "<p>The model carries the load at exactly the inflation pressure (area x pressure = "
        "load, 6.1.1); prints show how far real patches depart from that.</p>",
    )


def _paired(c: ReportContent) -> str:
    return _section(
        "paired",
        "Prints paired with the model",
        _table_html(c.tables.paired, PAIRED_COLUMNS, "paired-table"),
    )


def _trends(c: ReportContent) -> str:
    sentences = "".join(
        f"<li>{html.escape(describe_agreement(a))}</li>" for a in c.tables.agreement
    )
    return _section(
        "trends",
        "Trends with pressure and load (section 6.2.4)",
        f"<ul>{sentences}</ul>",
        "<p>Exponents of log-log fits <code>y ~ pressure^b load^c</code> per tire and "
        "surface.</p>",
        _table_html(c.tables.trends, TREND_COLUMNS, "trends-table"),
        *(_img(p, f"{t}: size vs pressure and load") for p, t in c.figures.tire_trends),
    )


def _drum_plate(c: ReportContent) -> str:
    return _section(
        "drum-plate",
        "Drum vs plate (Table 4-1)",
        _table_html(c.tables.drum_plate_rows, DRUM_COLUMNS, "drum-plate-table"),
        _img(c.figures.drum, "Drum / plate ratios: prints, model, dissertation"),
    )


def _rim(c: ReportContent) -> str:
    return _section(
        "rim",
        "Model sensitivity to rim width",
        _table_html(c.tables.rim_sensitivity, RIM_COLUMNS, "rim-table"),
        "<p>d log(size) / d log(rim width) at each tire's median plate case (rim +-10 %).</p>",
    )


def _prints(c: ReportContent) -> str:
    return _section(
        "prints",
        "Each print with its model patch",
        _img(c.figures.prints, "Print hulls and ellipses with the model patch, same scale"),
    )


def _renders(c: ReportContent) -> str:
    imgs = "".join(_img(p, a) for p, a in c.figures.renders)
    return _section("renders", "Renders of the modelled tire", imgs or "<p>(renders skipped)</p>")


def _errors(c: ReportContent) -> str:
    errors = c.tables.errors
    body = _table_html(errors, ERROR_COLUMNS, "errors-table") if errors else "<p>None.</p>"
    return _section("errors", "Prints not compared", body)


def _notes(c: ReportContent) -> str:
    items = "".join(f"<li>{html.escape(n)}</li>" for n in NOTES)
    return _section("notes", "What this can and cannot tell (section 7.3)", f"<ul>{items}</ul>")


HTML_SECTIONS = (
    _summary,
    _key_figure,
    _load_per_area,
    _paired,
    _trends,
    _drum_plate,
    _rim,
    _prints,
    _renders,
    _errors,
    _notes,
)


def html_page(content: ReportContent) -> str:
    """The self-contained HTML report (figures embedded as data URIs).

    Parameters
    ----------
    content : ReportContent

    Returns
    -------
    str
        The page; one ``<section>`` per entry of :data:`SECTIONS`.
    """
    head = (
        f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>{TITLE}</title>"
        f"<style>{CSS}</style></head><body>"
    )
    parts = [head, f"<h1>{TITLE}</h1>", *(s(content) for s in HTML_SECTIONS), "</body></html>"]
    return "\n".join(parts)


# --- Markdown ------------------------------------------------------------------------


def _table_md(rows, columns) -> str:
    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    lines += ["| " + " | ".join(fmt(r.get(c, "")) for c in columns) + " |" for r in rows]
    return "\n".join(lines)


def markdown_page(content: ReportContent) -> str:
    """The Markdown summary of the report (for version control).

    Parameters
    ----------
    content : ReportContent

    Returns
    -------
    str
    """
    t = content.tables
    rim_cols = ["tire", "dlog_length_dlog_rim", "dlog_width_dlog_rim", "dlog_area_dlog_rim"]
    errors = (
        _table_md(t.errors, ["file", "print", "error", "model_error"]) if t.errors else "None."
    )
    out = [f"# {TITLE}", "", "## Configuration", ""]
    out += [f"- {k}: {v}" for k, v in content.config.items()]
    out += ["", "![Area vs length and width](figures/area_vs_length_width.png)", ""]
    out += ["## Trends", ""]
    out += [f"- {describe_agreement(a)}" for a in t.agreement]
    out += ["", _table_md(t.trends, TREND_COLUMNS), ""]
    out += ["## Drum vs plate", "", _table_md(t.drum_plate_rows, DRUM_COLUMNS), ""]
    out += ["## Rim width sensitivity (model)", "", _table_md(t.rim_sensitivity, rim_cols), ""]
    out += ["## Prints paired with the model", "", _table_md(t.paired, PAIRED_COLUMNS[:15]), ""]
    out += ["## Errors", "", errors, ""]
    return "\n".join(out)


__all__ = ["SECTIONS", "fmt", "html_page", "markdown_page"]
