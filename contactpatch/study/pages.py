"""The report's pages: ``index.html`` (one self-contained file) and ``report.md``.

Each page is a list of sections, each drawn by one small function from a
:class:`contactpatch.study.report.ReportContent`. Numbers are formatted by the
quantity they are (:mod:`contactpatch.study.numbers`: mm to 0.1, mm^2 to 1, ratios to
3 decimals, exponents with their standard error, pressure in bar), the same in both
pages; the CSV tables hold them in full precision.

The HTML page is responsive (a viewport, a maximum width, wide tables scroll inside
their own box with a sticky header and first column) and prints landscape with
tables wrapped to the page. Its figures are inline SVG, its images data URIs, its
scripts inline (sorting and filtering the tables, enlarging the scans, the 3D view):
it makes no network request and needs no file beside it.
"""

from __future__ import annotations

import base64
import html
import math
import re
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import TYPE_CHECKING

from .footprints import footprint_rows
from .numbers import as_number, column_kind, estimate, fmt, interval, pressure_note
from .sheets import outline_svg
from .svgplot import stack_html
from .trends import describe_agreement
from .viewer import viewer_html

if TYPE_CHECKING:
    from .report import Figure, ReportContent, Sheet

#: ids of the HTML page's sections, in order (the validation section, when the
#: validation module is installed, follows ``rim``)
SECTIONS = (
    "summary",
    "key-figure",
    "ratios",
    "load-per-area",
    "paired",
    "footprints",
    "trends",
    "tires",
    "drum-plate",
    "rim",
    "renders",
    "viewer",
    "errors",
    "notes",
)
TITLE = "Contact patches: Rotta model vs ink prints"
NOTES = (
    "The model's patch has pointed ends; its ellipse (section 5.4) is what is compared "
    "with a print's.",
    "Area x pressure = load is built into the model; prints measure it.",
    "Which ink spots at a print's edge bore load is a judgement (7.1.1); the print table "
    "carries both all-ink and load-bearing numbers and a +-10 % threshold band.",
    "No deflection beyond the patch, friction or slip is modelled in these comparisons.",
    "Pressures are in bar throughout (1 bar = 0.1 N/mm² = 0.1 MPa); hover a load / area "
    "cell for N/mm².",
    "Exponents are least-squares fits in logs; ± is one standard error, with the 95 % "
    "interval (Student t) in the cell's tooltip. With as many points as parameters a "
    "fit is exact and has no error estimate.",
)


@dataclass(frozen=True)
class Column:
    """A column of an HTML or Markdown table.

    Attributes
    ----------
    key : str
        Row key (its name sets the number format, :func:`numbers.column_kind`).
    header : str
        Header text (with the unit).
    tip : str
        Header tooltip.
    """

    key: str
    header: str
    tip: str = ""


PAIRED_VIEW = (
    Column("print_id", "print", "scan file and print number on it"),
    Column("tire", "tire"),
    Column("surface", "surface"),
    Column("pressure_bar", "pressure [bar]", "inflation pressure"),
    Column("load_N", "load [N]"),
    Column("length_mm", "length [mm]", "print: hull extent along its principal axis"),
    Column("model_length_mm", "model length [mm]"),
    Column("ratio_length", "length print / model"),
    Column("width_mm", "width [mm]"),
    Column("model_width_mm", "model width [mm]"),
    Column("ratio_width", "width print / model"),
    Column("hull_area_mm2", "area [mm²]", "print: area of the convex hull (gross)"),
    Column("model_area_mm2", "model area [mm²]"),
    Column("ratio_area", "area print / model"),
    Column("ellipse_length_mm", "ellipse length [mm]", "print: direct ellipse fit"),
    Column("model_ellipse_length_mm", "model ellipse length [mm]", "section 5.4 ellipse"),
    Column("ratio_ellipse_length", "ellipse length print / model"),
    Column("net_to_gross", "net / gross area", "ink pixels over hull area"),
    Column("load_per_hull_area_N_mm2", "load / area [bar]", "load over hull area"),
    Column("model_sinkage_pct", "model sinkage [%]", "deflection over rim height"),
    Column("model_status", "model"),
    Column("model_error", "model error"),
)
TREND_VIEW = (
    Column("tire", "tire"),
    Column("surface", "surface"),
    Column("quantity", "size"),
    Column("n", "n", "prints in the fit"),
    Column("print_dof", "dof", "residual degrees of freedom of the prints' fit"),
    Column("print_pressure_exp", "print: pressure exponent"),
    Column("model_pressure_exp", "model: pressure exponent"),
    Column("print_load_exp", "print: load exponent"),
    Column("model_load_exp", "model: load exponent"),
    Column("print_r2", "print R²"),
    Column("model_r2", "model R²"),
)
DRUM_VIEW = (
    Column("source", "source"),
    Column("quantity", "size"),
    Column("n", "n"),
    Column("mean", "mean"),
    Column("stdev", "stdev"),
    Column("min", "min"),
    Column("max", "max"),
)
RIM_VIEW = (
    Column("tire", "tire"),
    Column("rim_width_mm", "rim width [mm]"),
    Column("pressure_bar", "pressure [bar]"),
    Column("load_N", "load [N]"),
    Column("dlog_length_dlog_rim", "d log length / d log rim"),
    Column("dlog_width_dlog_rim", "d log width / d log rim"),
    Column("dlog_area_dlog_rim", "d log area / d log rim"),
)
ERROR_VIEW = (
    Column("file", "file"),
    Column("print", "print"),
    Column("status", "print status"),
    Column("error", "error"),
    Column("model_status", "model"),
    Column("model_error", "model error"),
)
#: trend columns shown as "estimate ± standard error"
_ESTIMATES = ("print_pressure_exp", "model_pressure_exp", "print_load_exp", "model_load_exp")


def print_id(row: dict) -> str:
    """``'tire06_4bar_304N #0'``: the scan's name without suffix and the print number.

    Parameters
    ----------
    row : dict

    Returns
    -------
    str
    """
    stem = Path(str(row.get("file", ""))).stem
    p = row.get("print", "")
    return f"{stem} #{p}" if str(p) != "" else stem


def _asset(name: str) -> str:
    return resources.files(__package__).joinpath(f"assets/{name}").read_text(encoding="utf-8")


# --- cells and tables ----------------------------------------------------------------


def cell_text(row: dict, key: str) -> str:
    """The text of one cell, formatted by its quantity (the same in both pages).

    Parameters
    ----------
    row : dict
    key : str
        Column key (``print_id`` and the exponent keys are composed).

    Returns
    -------
    str
    """
    if key == "print_id":
        return print_id(row)
    if key in _ESTIMATES and f"{key}_se" in row:
        dof = row.get(f"{key.split('_', 1)[0]}_dof", 0)
        return estimate(_num(row.get(key)), _num(row.get(f"{key}_se")), int(dof or 0))
    return fmt(row.get(key, ""), key)


def _num(v) -> float:
    x = as_number(v)
    return math.nan if x is None else x


def _cell_tip(row: dict, key: str) -> str:
    if key.endswith("_N_mm2"):
        note = pressure_note(row.get(key))
        pct = as_number(row.get("load_per_hull_area_pct"))
        if note and pct is not None and math.isfinite(pct):
            note += f"; {pct:.1f} % of the inflation pressure"
        return note
    if key in _ESTIMATES:
        dof = int(row.get(f"{key.split('_', 1)[0]}_dof", 0) or 0)
        return interval(_num(row.get(key)), _num(row.get(f"{key}_ci95")), dof)
    return ""


def _td(row: dict, col: Column, colours: dict) -> str:
    text = html.escape(cell_text(row, col.key))
    kind = "text" if col.key in ("print_id",) else column_kind(col.key)
    cls = ' class="num"' if kind not in ("text",) else ""
    tip = _cell_tip(row, col.key)
    tip = f' title="{html.escape(tip)}"' if tip else ""
    if col.key == "tire" and str(row.get("tire", "")) in colours:
        text = _chip(colours[str(row["tire"])]) + text
    return f"<td{cls}{tip}>{text}</td>"


def _chip(colour: str) -> str:
    return f'<span class="chip" style="background:{colour}"></span>'


def table_html(rows, columns, table_id, *, colours=None, sortable=False, short=False) -> str:
    """A table in its own horizontal scroll box: sticky header and first column,
    text left, numbers right.

    Parameters
    ----------
    rows : list of dict
    columns : sequence of Column
    table_id : str
    colours : dict of str to str, optional
        Tire colours (a chip before each tire name).
    sortable : bool
        Click a header to sort (the page's inline script).
    short : bool
        No maximum height (a few rows).

    Returns
    -------
    str
    """
    colours = colours or {}
    head = "".join(
        f'<th scope="col"{_th_class(c)}{_title(c.tip)}>{html.escape(c.header)}</th>'
        for c in columns
    )
    body = "\n".join("<tr>" + "".join(_td(r, c, colours) for c in columns) + "</tr>" for r in rows)
    cls = "sticky1" + (" sortable" if sortable else "")
    wrap = "tablewrap short" if short else "tablewrap"
    return (
        f'<div class="{wrap}" tabindex="0"><table id="{table_id}" class="{cls}">'
        f"<thead><tr>{head}</tr></thead><tbody>\n{body}\n</tbody></table></div>"
    )


def _th_class(c: Column) -> str:
    kind = "text" if c.key == "print_id" else column_kind(c.key)
    return ' class="num"' if kind != "text" else ""


def _title(tip: str) -> str:
    return f' title="{html.escape(tip)}"' if tip else ""


# --- figures and images --------------------------------------------------------------


def inline_svg(svg: str, label: str) -> str:
    """An SVG document as an element to inline in HTML: no XML prolog, no fixed
    size (it scales to its box), labelled for screen readers.

    Parameters
    ----------
    svg : str
    label : str

    Returns
    -------
    str
    """
    start = svg.index("<svg")
    body = re.sub(r"<!--.*?-->", "", svg[start:], flags=re.S)
    head_end = body.index(">")
    head = re.sub(r'\s(width|height)="[^"]*"', "", body[:head_end])
    head += f' role="img" aria-label="{html.escape(label)}"'
    return head + body[head_end:]


_SCROLL_HINT = "<span class='scrollhint'>Scroll sideways for the whole figure. </span>"


def figure_html(fig: Figure) -> str:
    """A report figure, inline, with its caption and the name of its SVG file.

    Parameters
    ----------
    fig : Figure

    Returns
    -------
    str
    """
    stack = stack_html(fig.svg)  # small screens: the panels one below the other
    box, hint = ("chartbox stacked", "") if stack else ("chartbox", _SCROLL_HINT)
    return (
        f'<figure id="fig-{fig.name}" class="chart"><div class="{box}" tabindex="0">'
        f"{inline_svg(fig.svg, fig.caption)}{stack}</div>"
        f"<figcaption>{hint}"
        f"{html.escape(fig.caption)} <span class='files'>(vector file: "
        f"<code>figures/{fig.path.name}</code>)</span></figcaption></figure>"
    )


def data_uri(data: bytes, mime: str) -> str:
    """``data:MIME;base64,...``.

    Parameters
    ----------
    data : bytes
    mime : str

    Returns
    -------
    str
    """
    return f"data:{mime};base64," + base64.b64encode(data).decode("ascii")


# --- sections ------------------------------------------------------------------------


def _section(section_id: str, title: str, *body: str) -> str:
    return (
        f'<section id="{section_id}"><h2>{html.escape(title)}</h2>' + "".join(body) + "</section>"
    )


def _summary(c: ReportContent) -> str:
    facts = "".join(f"<div><b>{html.escape(v)}</b>{html.escape(k)}</div>" for k, v in c.facts)
    cfg = "".join(
        f"<tr><th scope='row'>{html.escape(k)}</th><td>{html.escape(str(v))}</td></tr>"
        for k, v in c.config.items()
    )
    return _section(
        "summary",
        "Summary and configuration",
        f'<div class="keyfacts">{facts}</div>',
        f'<div class="tablewrap short"><table id="config" class="config">{cfg}</table></div>',
        "<p>Model: A. E. Dressel (2013), chapter 5 (Rotta's model in 3D). Prints: sections "
        "3.5, 4.1.1. Tables in full precision: <code>tables/*.csv</code>, "
        "<code>report.json</code>; figures as vector files in <code>figures/</code>.</p>",
    )


def _key_figure(c: ReportContent) -> str:
    return _section(
        "key-figure",
        "Area vs length and width (Figure 6-3)",
        figure_html(c.figures.key),
        "<p>Measured patches are shorter and wider than the model's pointed patches "
        "(section 6.2.1).</p>",
    )


def _ratios(c: ReportContent) -> str:
    return _section(
        "ratios",
        "Print / model ratios by tire",
        figure_html(c.figures.ratios),
        "<p>Every print's size over the model's at its load case; the black bar is the "
        "tire's median. The dotted line is agreement.</p>",
    )


def _load_per_area(c: ReportContent) -> str:
    return _section(
        "load-per-area",
        "Load over print area vs inflation pressure (Figure 4-3)",
        figure_html(c.figures.load),
        "<p>The model carries the load at exactly the inflation pressure (area x pressure = "
        "load, 6.1.1); prints show how far real patches depart from that.</p>",
    )


def _paired(c: ReportContent) -> str:
    n = len(c.tables.paired)
    bar = (
        '<div class="tablebar"><label>Filter <input type="search" data-filter="paired-table"'
        ' placeholder="e.g. drum 6.9 Big Apple" aria-label="filter the paired table">'
        f'</label><span id="paired-table-count">{n} of {n} rows</span>'
        "<span>· click a header to sort</span></div>"
    )
    table = table_html(
        c.tables.paired, PAIRED_VIEW, "paired-table", colours=c.colours, sortable=True
    )
    return _section("paired", "Prints paired with the model", bar, table)


FOOTPRINT_VIEW = (
    Column("tire", "tire"),
    Column("surface", "surface"),
    Column("footprint", "model footprint"),
    Column("n", "n", "prints compared"),
    Column("ratio_length", "length print / model", "median over the prints"),
    Column("ratio_width", "width print / model", "median over the prints"),
    Column("ratio_area", "area print / model", "median over the prints"),
)


def _footprints(c: ReportContent) -> str:
    rows = footprint_rows(c.tables.paired)
    if not rows:
        return ""
    return _section(
        "footprints",
        "Plain patch vs rounded footprint (7.3.1)",
        "<p>Median print / model ratios (1 = agreement). The plain Rotta patch has pointed "
        "ends; its section 5.4 ellipse is the dissertation's comparison; the rounded "
        "footprint (beyond the dissertation, <code>docs/model.md</code>) spreads the "
        "membrane pressure through tread, ink and paper, with two global parameters "
        "fitted once to the prints the dissertation preserves.</p>",
        table_html(rows, FOOTPRINT_VIEW, "footprint-table", colours=c.colours, sortable=True),
    )


def _trends(c: ReportContent) -> str:
    sentences = "".join(
        f"<li>{html.escape(describe_agreement(a))}</li>" for a in c.tables.agreement
    )
    return _section(
        "trends",
        "Trends with pressure and load (section 6.2.4)",
        f"<ul>{sentences}</ul>",
        "<p>Exponents <code>b</code>, <code>c</code> of <code>size ~ pressure^b load^c</code>"
        " per tire and surface (least squares in logs), ± one standard error; hover a cell "
        "for its 95 % interval. <code>n</code> prints, <code>dof</code> residual degrees "
        "of freedom. Each tire's figure is in its section below.</p>",
        table_html(c.tables.trends, TREND_VIEW, "trends-table", colours=c.colours, sortable=True),
    )


def _tires(c: ReportContent) -> str:
    parts = [
        '<p class="legend-inline">In every figure and drawing: the tire\'s colour; prints '
        "filled, model open or as a line; circles plate, squares drum. Outlines: "
        "<i style='background:#bbb'></i>print hull, <i style='border-top:2px dotted #444'>"
        "</i>print ellipse, <i style='border-top:2px dashed #222'></i>model patch; rolling "
        "direction up, all at one scale.</p>"
    ]
    for k, tire in enumerate(c.colours):
        parts.append(_tire_section(c, k, tire))
    return _section("tires", "Tires: trends and prints", *parts)


def _tire_section(c: ReportContent, k: int, tire: str) -> str:
    rows = [r for r in c.tables.paired if str(r.get("tire", "")) == tire]
    ok = [r for r in rows if r.get("status", "ok") == "ok"]
    sheets = [s for s in c.sheets if any(str(r.get("tire", "")) == tire for r in s.rows)]
    facts = (
        f"{len(ok)} prints on {len(sheets)} sheets; pressures "
        + ", ".join(sorted({fmt(r.get("pressure_bar"), "pressure_bar") for r in ok}, key=float))
        + " bar; loads "
        + ", ".join(sorted({fmt(r.get("load_N"), "load_N") for r in ok}, key=float))
        + " N."
    )
    fig = c.figures.tire_trends.get(tire)
    body = "".join(_sheet_html(c, s, tire) for s in sheets)
    opened = " open" if c.expand_prints else ""
    return (
        f'<section id="tire-{k}" class="tire"><h3>{_chip(c.colours[tire])}'
        f"{html.escape(tire)}</h3><p>{html.escape(facts)}</p>"
        + (figure_html(fig) if fig else "")
        + f"<details{opened}><summary>Scans and outlines ({len(sheets)} sheets)</summary>"
        + f'<div class="sheets">{body}</div></details></section>'
    )


def _sheet_html(c: ReportContent, s: Sheet, tire: str) -> str:
    if s.qa_jpeg:
        alt = f"QA overlay of {s.file}: measured hulls (green) and print numbers"
        lazy = "" if c.expand_prints else ' loading="lazy"'
        thumb = (
            f'<figure class="thumb"><img class="zoomable" alt="{html.escape(alt)}"{lazy} '
            f'src="{data_uri(s.qa_jpeg, "image/jpeg")}"><figcaption>QA overlay, click to '
            "enlarge</figcaption></figure>"
        )
    else:
        thumb = '<p class="thumb missing">scan not found beside the table: no overlay</p>'
    span, width = c.outline_scale
    cards = "".join(
        f'<figure class="outline-card">{outline_svg(r, span, c.colours[tire], width=width)}'
        f"<figcaption>{html.escape(_outline_caption(r))}</figcaption></figure>"
        for r in s.rows
        if str(r.get("tire", "")) == tire and r.get("status", "ok") == "ok"
    )
    return (
        f'<div class="sheet"><h4>{html.escape(s.file)}</h4><div class="sheet-body">{thumb}'
        f'<div class="outlines">{cards}</div>{_aside_html(s)}</div></div>'
    )


def _outline_caption(r: dict) -> str:
    return (
        f"#{r.get('print')} {r.get('surface', '')}, {fmt(r.get('pressure_bar'), 'pressure_bar')}"
        f" bar, {fmt(r.get('load_N'), 'load_N')} N; L {fmt(r.get('length_mm'), 'length_mm')}"
        f" / {fmt(r.get('model_length_mm'), 'length_mm')} mm"
    )


def _aside_html(s: Sheet) -> str:
    if s.set_aside is None:
        return ""
    if not s.set_aside:
        return '<div class="aside">Set aside: nothing.</div>'
    items = "".join(f"<li>{html.escape(x)}</li>" for x in s.set_aside)
    return f'<div class="aside">Set aside on this sheet (not prints):<ul>{items}</ul></div>'


def _drum_plate(c: ReportContent) -> str:
    return _section(
        "drum-plate",
        "Drum vs plate (Table 4-1)",
        table_html(c.tables.drum_plate_rows, DRUM_VIEW, "drum-plate-table", short=True),
        "<p>Drum / plate ratios of prints (and model patches) at the same tire, pressure "
        "and load.</p>",
        figure_html(c.figures.drum),
    )


def _rim(c: ReportContent) -> str:
    return _section(
        "rim",
        "Model sensitivity to rim width",
        table_html(c.tables.rim_sensitivity, RIM_VIEW, "rim-table", colours=c.colours, short=True),
        "<p>d log(size) / d log(rim width) at each tire's median plate case (rim ±10 %). "
        "The model's area is load / pressure whatever the rim: its sensitivity is 0.</p>",
    )


def _renders(c: ReportContent) -> str:
    figs = "".join(
        f'<figure><img alt="{html.escape(r.caption)}" width="{r.size[0]}" height="{r.size[1]}"'
        f' loading="lazy" src="{data_uri(r.png, "image/png")}"><figcaption>'
        f"{html.escape(r.caption)} <span class='files'>(<code>figures/{r.path.name}</code>)"
        "</span></figcaption></figure>"
        for r in c.figures.renders
    )
    body = f'<div class="renders">{figs}</div>' if figs else "<p>(renders skipped)</p>"
    return _section("renders", "Renders of the modelled tire", body)


def _viewer(c: ReportContent) -> str:
    body = viewer_html(c.viewer) or "<p>(no solved case to show)</p>"
    return _section("viewer", "The deformed tire in 3D", body)


def _errors(c: ReportContent) -> str:
    errors = c.tables.errors
    body = table_html(errors, ERROR_VIEW, "errors-table", short=True) if errors else "<p>None.</p>"
    return _section("errors", "Prints not compared", body)


def _notes(c: ReportContent) -> str:
    items = "".join(f"<li>{html.escape(n)}</li>" for n in NOTES)
    return _section("notes", "What this can and cannot tell (section 7.3)", f"<ul>{items}</ul>")


def _validation(c: ReportContent) -> str:
    return c.validation[0] if c.validation else ""


HTML_SECTIONS = (
    _summary,
    _key_figure,
    _ratios,
    _load_per_area,
    _paired,
    _footprints,
    _trends,
    _tires,
    _drum_plate,
    _rim,
    _validation,
    _renders,
    _viewer,
    _errors,
    _notes,
)


def _toc(parts: list[str], c: ReportContent) -> str:
    items = []
    for part in parts:
        sid = re.match(r'\s*<section id="([^"]+)"', part)
        head = re.search(r"<h2[^>]*>(.*?)</h2>", part, re.S)
        if not (sid and head):
            continue
        items.append(f'<li><a href="#{sid.group(1)}">{re.sub(r"<[^>]+>", "", head.group(1))}</a>')
        if sid.group(1) == "tires":
            sub = "".join(
                f'<li><a href="#tire-{k}">{html.escape(t)}</a></li>'
                for k, t in enumerate(c.colours)
            )
            items[-1] += f"<ol>{sub}</ol>"
        items[-1] += "</li>"
    return f'<nav class="toc" aria-label="contents"><b>Contents</b><ol>{"".join(items)}</ol></nav>'


def html_page(content: ReportContent) -> str:
    """The self-contained HTML report.

    Parameters
    ----------
    content : ReportContent

    Returns
    -------
    str
        The page; one ``<section>`` per entry of :data:`SECTIONS` (plus
        ``validation`` when available).
    """
    head = (
        "<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>"
        "<meta name='viewport' content='width=device-width, initial-scale=1'>"
        f"<title>{TITLE}</title><style>{_asset('report.css')}</style></head><body><main>"
    )
    parts = [s(content) for s in HTML_SECTIONS]
    parts = [p for p in parts if p]
    lede = (
        f"<p class='lede'>{content.config.get('prints', 0)} prints from "
        f"{content.config.get('files', 0)} scans, {len(content.colours)} tires.</p>"
    )
    box = '<dialog id="lightbox" class="lightbox" aria-label="enlarged scan"><img alt=""></dialog>'
    tail = f"{box}</main><script>{_asset('report.js')}</script></body></html>"
    return "\n".join([head, f"<h1>{TITLE}</h1>", lede, _toc(parts, content), *parts, tail])


# --- Markdown ------------------------------------------------------------------------


def md_text(text) -> str:
    """Text made safe for a Markdown cell or line: HTML special characters escaped
    (a manifest cell such as ``<script>`` shows as text, never as markup), ``|``
    escaped and line breaks folded into spaces.

    Parameters
    ----------
    text : object
        Shown through ``str``.

    Returns
    -------
    str
    """
    t = html.escape(str(text), quote=False)
    return " ".join(t.replace("|", "\\|").splitlines())


def table_md(rows, columns) -> str:
    """A Markdown table, cells formatted as in the HTML page.

    Parameters
    ----------
    rows : list of dict
    columns : sequence of Column

    Returns
    -------
    str
    """

    esc = md_text
    lines = ["| " + " | ".join(esc(c.header) for c in columns) + " |"]
    lines.append("|" + "".join("---:|" if _th_class(c) else "---|" for c in columns))
    lines += ["| " + " | ".join(esc(cell_text(r, c.key)) for c in columns) + " |" for r in rows]
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
    out = [f"# {TITLE}", "", "## Configuration", ""]
    out += [f"- {md_text(k)}: {md_text(v)}" for k, v in content.config.items()]
    out += ["", f"![Area vs length and width](figures/{content.figures.key.path.name})", ""]
    out += ["## Trends", ""]
    out += [f"- {md_text(describe_agreement(a))}" for a in t.agreement]
    out += ["", "Exponents ± one standard error.", "", table_md(t.trends, TREND_VIEW), ""]
    out += ["## Plain patch vs rounded footprint (7.3.1)", "", "Median print / model ratios."]
    out += ["", table_md(footprint_rows(t.paired), FOOTPRINT_VIEW), ""]
    out += ["## Drum vs plate", "", table_md(t.drum_plate_rows, DRUM_VIEW), ""]
    out += ["## Rim width sensitivity (model)", "", table_md(t.rim_sensitivity, RIM_VIEW), ""]
    if content.validation:
        out += [content.validation[1], ""]
    out += ["## Prints paired with the model", "", table_md(t.paired, PAIRED_VIEW[:17]), ""]
    errors = table_md(t.errors, ERROR_VIEW) if t.errors else "None."
    out += ["## Errors", "", errors, ""]
    return "\n".join(out)


__all__ = [
    "DRUM_VIEW",
    "ERROR_VIEW",
    "FOOTPRINT_VIEW",
    "PAIRED_VIEW",
    "RIM_VIEW",
    "SECTIONS",
    "TREND_VIEW",
    "Column",
    "cell_text",
    "data_uri",
    "figure_html",
    "fmt",
    "html_page",
    "inline_svg",
    "markdown_page",
    "md_text",
    "print_id",
    "table_html",
    "table_md",
]
