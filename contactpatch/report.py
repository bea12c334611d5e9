"""Model vs print report: a self-contained HTML file plus its tables (sections 4.1.1, 6.2).

``build_report(rows, out_dir)`` takes an ``inkprint batch`` table and writes

* ``index.html`` -- figures embedded, tables, the configuration and package version;
  readable in any browser with no server;
* ``report.md`` -- a Markdown summary for version control;
* ``tables/*.csv`` and ``report.json`` -- every table in full precision;
* ``figures/*.png|svg`` -- every figure, and renders of the modelled tire.

The HTML shows the same numbers as the CSV files (formatted to 6 significant digits)
and contains no timestamp: the same inputs give the same tables and pages.
"""

from __future__ import annotations

import base64
import csv
import html
import json
import math
import platform
from pathlib import Path

from ._io import atomic_path, write_text_atomic
from .compare import pair_prints
from .trends import (
    describe_agreement,
    drum_plate_ratios,
    rim_sensitivity,
    sign_agreement,
    trend_table,
)

PAIRED_COLUMNS = [
    "file",
    "print",
    "tire",
    "surface",
    "pressure_bar",
    "load_N",
    "length_mm",
    "model_length_mm",
    "ratio_length",
    "width_mm",
    "model_width_mm",
    "ratio_width",
    "hull_area_mm2",
    "model_area_mm2",
    "ratio_area",
    "ellipse_length_mm",
    "model_ellipse_length_mm",
    "ratio_ellipse_length",
    "net_to_gross",
    "load_per_hull_area_pct",
    "model_sinkage_pct",
    "model_status",
    "model_error",
]
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
DISSERTATION_TABLE_4_1 = [
    {"quantity": "length_mm", "max": 1.05, "min": 0.81, "mean": 0.92, "stdev": 0.031},
    {"quantity": "width_mm", "max": 1.32, "min": 0.83, "mean": 1.12, "stdev": 0.085},
    {"quantity": "hull_area_mm2", "max": 1.19, "min": 0.68, "mean": 1.04, "stdev": 0.082},
]


def fmt(v) -> str:
    """Cell text: numbers to 6 significant digits (the HTML and Markdown use this)."""
    if isinstance(v, bool):
        return str(v)
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return "" if math.isnan(v) else f"{v:.6g}"
    try:
        x = float(v)
    except (TypeError, ValueError):
        return str(v)
    return str(v) if not math.isfinite(x) or str(v).strip() == "" else f"{x:.6g}"


def write_csv(rows: list[dict], path, columns=None) -> Path:
    cols = columns or list(dict.fromkeys(k for r in rows for k in r))
    with atomic_path(path) as tmp, tmp.open("w", newline="", encoding="utf-8") as fh:
        w = csv.DictWriter(fh, fieldnames=cols, extrasaction="ignore", lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    return Path(path)


def read_table(path) -> list[dict]:
    with open(path, newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


def _table_html(rows, columns, table_id) -> str:
    head = "".join(f"<th>{html.escape(c)}</th>" for c in columns)
    body = "\n".join(
        "<tr>" + "".join(f"<td>{html.escape(fmt(r.get(c, '')))}</td>" for c in columns) + "</tr>"
        for r in rows
    )
    return (
        f'<table id="{table_id}"><thead><tr>{head}</tr></thead><tbody>\n{body}\n</tbody></table>'
    )


def _table_md(rows, columns) -> str:
    lines = ["| " + " | ".join(columns) + " |", "|" + "---|" * len(columns)]
    lines += ["| " + " | ".join(fmt(r.get(c, "")) for c in columns) + " |" for r in rows]
    return "\n".join(lines)


def _img(path: Path, alt: str) -> str:
    data = base64.b64encode(path.read_bytes()).decode("ascii")
    svg = path.with_suffix(".svg")
    link = f' <a href="figures/{svg.name}">SVG</a>' if svg.exists() else ""
    return (
        f'<figure><img alt="{html.escape(alt)}" src="data:image/png;base64,{data}">'
        f"<figcaption>{html.escape(alt)}{link}</figcaption></figure>"
    )


def _renders(paired, fig_dir: Path) -> list[tuple[Path, str]]:
    """Bottom and iso views of the model for each tire at its median plate case."""
    import tiremesh as tm
    from tiremesh.mesh import build_mesh
    from tiremesh.render import render

    from .compare import _num, tire_of

    out = []
    tires = sorted({str(r.get("tire", "")) for r in paired if r.get("model_status") == "ok"})
    for k, name in enumerate(tires):
        rs = [
            r
            for r in paired
            if r.get("tire") == name
            and r.get("model_status") == "ok"
            and str(r.get("surface", "")).lower() in ("plate", "flat")
        ]
        if not rs:
            continue
        rs.sort(key=lambda r: (_num(r["pressure_bar"]), _num(r["load_N"])))
        r = rs[len(rs) // 2]
        patch = tm.solve(
            tire_of(r), load=_num(r["load_N"]), pressure=0.1 * _num(r["pressure_bar"])
        )
        mesh = build_mesh(patch, n_around=360)
        for view in ("iso", "bottom"):
            path = fig_dir / f"render_tire{k}_{view}.png"
            render(mesh, path, view=view, size=(640, 480))
            out.append(
                (
                    path,
                    f"{name}, {_num(r['pressure_bar']):g} bar, {_num(r['load_N']):g} N, plate: {view} view",
                )
            )
    return out


def build_report(rows: list[dict], out_dir, *, renders: bool = True, source: str = "") -> Path:
    """Write the report for a print table; returns the path of ``index.html``."""
    from . import __version__
    from . import figures as F

    out = Path(out_dir)
    tables, fig_dir = out / "tables", out / "figures"
    tables.mkdir(parents=True, exist_ok=True)
    fig_dir.mkdir(parents=True, exist_ok=True)

    paired = pair_prints(rows)
    trends = trend_table(paired)
    agree = sign_agreement(trends)
    dp_pairs, dp_summary = drum_plate_ratios(paired)
    mp_pairs, mp_summary = drum_plate_ratios(
        [
            {
                **r,
                "length_mm": r.get("model_length_mm"),
                "width_mm": r.get("model_width_mm"),
                "hull_area_mm2": r.get("model_area_mm2"),
            }
            for r in paired
            if r.get("model_status") == "ok"
        ]
    )
    rim = rim_sensitivity(paired)
    errors = [r for r in paired if r.get("status") != "ok" or r.get("model_status") == "error"]
    n_files = len({r.get("file") for r in rows})
    n_prints = sum(1 for r in rows if r.get("status", "ok") == "ok")
    config = {
        "package": "rotta-tire",
        "version": __version__,
        "python": platform.python_version(),
        "source": source,
        "files": n_files,
        "prints": n_prints,
        "errors": len(errors),
        "model cases": len(
            {
                (r.get("tire"), r.get("pressure_bar"), r.get("load_N"), r.get("surface"))
                for r in paired
                if r.get("model_status") == "ok"
            }
        ),
        "surfaces": "plate -> flat ground; drum -> 2.5 m drum unless drum_diameter_mm is given",
    }

    all_tables = {
        "paired": paired,
        "trends": trends,
        "agreement": agree,
        "drum_plate_prints": dp_pairs,
        "drum_plate_summary": dp_summary,
        "drum_plate_model": mp_pairs,
        "drum_plate_model_summary": mp_summary,
        "rim_sensitivity": rim,
        "errors": errors,
    }
    for name, t in all_tables.items():
        write_csv(
            t,
            tables / f"{name}.csv",
            [*PAIRED_COLUMNS, "model_outline_wkt"] if name == "paired" else None,
        )
    with atomic_path(out / "report.json") as tmp:
        tmp.write_text(
            json.dumps({"config": config, **all_tables}, indent=1, default=str), encoding="utf-8"
        )

    figs = {}
    figs["key"] = F.save(F.area_vs_length_width(paired), fig_dir / "area_vs_length_width")[0]
    figs["load"] = F.save(F.load_per_area(paired), fig_dir / "load_per_area")[0]
    tire_figs = []
    for k, tire in enumerate(
        sorted({str(r.get("tire", "")) for r in paired if r.get("model_status") == "ok"})
    ):
        tire_figs.append(
            (F.save(F.tire_trends(paired, tire), fig_dir / f"trends_tire{k}")[0], tire)
        )
    figs["prints"] = F.save(F.print_overlays(paired), fig_dir / "print_overlays")[0]
    figs["drum"] = F.save(F.drum_vs_plate(dp_summary, mp_summary), fig_dir / "drum_vs_plate")[0]
    render_list = _renders(paired, fig_dir) if renders else []

    sentences = [describe_agreement(a) for a in agree]
    drum_rows = (
        [{"source": "prints", **s} for s in dp_summary]
        + [{"source": "model", **s} for s in mp_summary]
        + [{"source": "dissertation (Table 4-1)", **s} for s in DISSERTATION_TABLE_4_1]
    )
    trend_cols = [
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
    page = _html(
        config,
        figs,
        tire_figs,
        render_list,
        paired,
        trends,
        trend_cols,
        sentences,
        drum_rows,
        rim,
        errors,
    )
    index = write_text_atomic(out / "index.html", page)
    md = _markdown(config, paired, trends, trend_cols, sentences, drum_rows, rim, errors)
    write_text_atomic(out / "report.md", md)
    return index


CSS = """body{font-family:system-ui,sans-serif;margin:2em auto;max-width:1200px;color:#222}
table{border-collapse:collapse;font-size:12px;margin:1em 0}td,th{border:1px solid #ccc;padding:2px 6px;
text-align:right}th{background:#eee}figure{margin:1em 0}img{max-width:100%}figcaption{font-size:12px;color:#555}
section{margin-top:2em}code{background:#f4f4f4}"""


def _html(
    config, figs, tire_figs, renders, paired, trends, trend_cols, sentences, drum_rows, rim, errors
):
    cfg = "".join(
        f"<tr><th>{html.escape(k)}</th><td>{html.escape(str(v))}</td></tr>"
        for k, v in config.items()
    )
    parts = [
        "<!DOCTYPE html><html><head><meta charset='utf-8'><title>Contact patches: Rotta model vs ink prints"
        f"</title><style>{CSS}</style></head><body>",
        "<h1>Contact patches: Rotta model vs ink prints</h1>",
        f'<section id="summary"><h2>Summary and configuration</h2><table id="config">{cfg}</table>'
        "<p>Model: A. E. Dressel (2013), chapter 5 (Rotta's model in 3D). Prints: sections 3.5, 4.1.1. "
        "Tables in full precision: <code>tables/*.csv</code>, <code>report.json</code>.</p></section>",
        '<section id="key-figure"><h2>Area vs length and width (Figure 6-3)</h2>'
        + _img(figs["key"], "Contact area vs length and width, prints and model")
        + "<p>Measured patches are shorter and wider than the model's pointed patches (section 6.2.1).</p></section>",
        '<section id="load-per-area"><h2>Load over print area vs inflation pressure (Figure 4-3)</h2>'
        + _img(figs["load"], "Load / print area vs inflation pressure, with the 1:1 line")
        + "<p>The model carries the load at exactly the inflation pressure (area x pressure = load, 6.1.1); "
        "prints show how far real patches depart from that.</p></section>",
        '<section id="paired"><h2>Prints paired with the model</h2>'
        + _table_html(paired, PAIRED_COLUMNS, "paired-table")
        + "</section>",
        '<section id="trends"><h2>Trends with pressure and load (section 6.2.4)</h2><ul>'
        + "".join(f"<li>{html.escape(s)}</li>" for s in sentences)
        + "</ul>"
        + "<p>Exponents of log-log fits <code>y ~ pressure^b load^c</code> per tire and surface.</p>"
        + _table_html(trends, trend_cols, "trends-table")
        + "".join(_img(p, f"{t}: size vs pressure and load") for p, t in tire_figs)
        + "</section>",
        '<section id="drum-plate"><h2>Drum vs plate (Table 4-1)</h2>'
        + _table_html(
            drum_rows, ["source", "quantity", "max", "min", "mean", "stdev"], "drum-plate-table"
        )
        + _img(figs["drum"], "Drum / plate ratios: prints, model, dissertation")
        + "</section>",
        '<section id="rim"><h2>Model sensitivity to rim width</h2>'
        + _table_html(
            rim,
            [
                "tire",
                "rim_width_mm",
                "pressure_bar",
                "load_N",
                "dlog_length_dlog_rim",
                "dlog_width_dlog_rim",
                "dlog_area_dlog_rim",
            ],
            "rim-table",
        )
        + "<p>d log(size) / d log(rim width) at each tire's median plate case (rim +-10 %).</p></section>",
        '<section id="prints"><h2>Each print with its model patch</h2>'
        + _img(figs["prints"], "Print hulls and ellipses with the model patch, same scale")
        + "</section>",
        '<section id="renders"><h2>Renders of the modelled tire</h2>'
        + ("".join(_img(p, a) for p, a in renders) or "<p>(renders skipped)</p>")
        + "</section>",
        '<section id="errors"><h2>Prints not compared</h2>'
        + (
            _table_html(
                errors,
                ["file", "print", "status", "error", "model_status", "model_error"],
                "errors-table",
            )
            if errors
            else "<p>None.</p>"
        )
        + "</section>",
        '<section id="notes"><h2>What this can and cannot tell (section 7.3)</h2><ul>'
        "<li>The model's patch has pointed ends; its ellipse (section 5.4) is what is compared with a print's.</li>"
        "<li>Area x pressure = load is built into the model; prints measure it.</li>"
        "<li>Which ink spots at a print's edge bore load is a judgement (7.1.1); the print table carries both "
        "all-ink and load-bearing numbers and a +-10 % threshold band.</li>"
        "<li>No deflection beyond the patch, friction or slip is modelled in these comparisons.</li></ul></section>",
        "</body></html>",
    ]
    return "\n".join(parts)


def _markdown(config, paired, trends, trend_cols, sentences, drum_rows, rim, errors) -> str:
    out = ["# Contact patches: Rotta model vs ink prints", "", "## Configuration", ""]
    out += [f"- {k}: {v}" for k, v in config.items()]
    out += [
        "",
        "![Area vs length and width](figures/area_vs_length_width.png)",
        "",
        "## Trends",
        "",
    ]
    out += [f"- {s}" for s in sentences]
    out += ["", _table_md(trends, trend_cols), "", "## Drum vs plate", ""]
    out += [_table_md(drum_rows, ["source", "quantity", "max", "min", "mean", "stdev"]), ""]
    out += [
        "## Rim width sensitivity (model)",
        "",
        _table_md(
            rim, ["tire", "dlog_length_dlog_rim", "dlog_width_dlog_rim", "dlog_area_dlog_rim"]
        ),
        "",
    ]
    out += ["## Prints paired with the model", "", _table_md(paired, PAIRED_COLUMNS[:15]), ""]
    out += [
        "## Errors",
        "",
        _table_md(errors, ["file", "print", "error", "model_error"]) if errors else "None.",
        "",
    ]
    return "\n".join(out)
