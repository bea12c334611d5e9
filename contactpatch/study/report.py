"""Model vs print report: a self-contained HTML file plus its tables (Dressel 2013,
sections 4.1.1, 6.2).

:func:`build_report` takes an ``inkprint batch`` table and runs four named steps:

1. :func:`compute_tables` -> :class:`ReportTables` (pairing, trends, drum / plate,
   rim sensitivity, errors);
2. :func:`report_config` -> the configuration block (package, version, counts);
3. :func:`write_tables` -> ``tables/*.csv`` and ``report.json``, every table in full
   precision (through :func:`tiremesh.io.write_table`);
4. :func:`draw_figures` -> :class:`ReportFigures`, ``figures/*.png|svg`` and renders
   of the modelled tire (through :func:`tiremesh.io.save_figure`);

then writes the pages of :mod:`contactpatch.study.pages`: ``index.html`` (figures
embedded, readable in any browser with no server) and ``report.md`` (a Markdown
summary for version control).

The HTML shows the same numbers as the CSV files (formatted to 6 significant digits)
and contains no timestamp: the same inputs give the same tables and pages.
"""

from __future__ import annotations

import json
import platform
from dataclasses import dataclass, fields
from pathlib import Path

import tiremesh as tm
from tiremesh.io import cell_number_or_nan, save_figure, write_table, write_text_atomic

from . import figures as F
from .compare import DEFAULT_DIAMETER_MM, PAIRED_COLUMNS, case_of, pair_prints
from .pages import SECTIONS, html_page, markdown_page
from .trends import (
    DISSERTATION_TABLE_4_1,
    drum_plate_ratios,
    rim_sensitivity,
    sign_agreement,
    trend_table,
)


@dataclass(frozen=True)
class ReportTables:
    """Every table of the report (lists of row dicts), in the order they are written.

    Parameters
    ----------
    paired : list of dict
        :func:`contactpatch.pair_prints` of the print table.
    trends : list of dict
        :func:`contactpatch.trend_table`: pressure and load exponents.
    agreement : list of dict
        :func:`contactpatch.sign_agreement` of ``trends`` (section 6.2.4).
    drum_plate_prints, drum_plate_summary : list of dict
        :func:`contactpatch.drum_plate_ratios` of the prints (pairs, Table 4-1 style).
    drum_plate_model, drum_plate_model_summary : list of dict
        The same for the model's patches.
    rim_sensitivity : list of dict
        :func:`contactpatch.study.trends.rim_sensitivity`.
    errors : list of dict
        Rows whose print or model failed.
    """

    paired: list[dict]
    trends: list[dict]
    agreement: list[dict]
    drum_plate_prints: list[dict]
    drum_plate_summary: list[dict]
    drum_plate_model: list[dict]
    drum_plate_model_summary: list[dict]
    rim_sensitivity: list[dict]
    errors: list[dict]

    def as_dict(self) -> dict[str, list[dict]]:
        """The tables by name.

        Returns
        -------
        dict of str to list of dict
            Field name -> table, in field order.
        """
        return {f.name: getattr(self, f.name) for f in fields(self)}

    @property
    def drum_plate_rows(self) -> list[dict]:
        """Drum / plate summaries of the prints, the model and Table 4-1, with a
        ``source`` column (list of dict)."""
        return (
            [{"source": "prints", **s} for s in self.drum_plate_summary]
            + [{"source": "model", **s} for s in self.drum_plate_model_summary]
            + [{"source": "dissertation (Table 4-1)", **s} for s in DISSERTATION_TABLE_4_1]
        )


@dataclass(frozen=True)
class ReportFigures:
    """The report's figure files (PNG; an SVG lies beside each).

    Parameters
    ----------
    key : Path
        Area vs length and width (Figure 6-3).
    load : Path
        Load over area vs pressure (Figure 4-3).
    prints : Path
        Every print over its model patch.
    drum : Path
        Drum / plate ratios (Table 4-1).
    tire_trends : list of (Path, str)
        Per tire: the trend figure and the tire's name.
    renders : list of (Path, str)
        Renders of the modelled tires and their captions (empty when skipped).
    """

    key: Path
    load: Path
    prints: Path
    drum: Path
    tire_trends: list[tuple[Path, str]]
    renders: list[tuple[Path, str]]


@dataclass(frozen=True)
class ReportContent:
    """What the pages show.

    Parameters
    ----------
    config : dict
        :func:`report_config`.
    tables : ReportTables
    figures : ReportFigures
    """

    config: dict
    tables: ReportTables
    figures: ReportFigures


def _model_as_prints(paired: list[dict]) -> list[dict]:
    """Solved rows with the model's sizes under the print's column names."""
    return [
        {
            **r,
            "length_mm": r.get("model_length_mm"),
            "width_mm": r.get("model_width_mm"),
            "hull_area_mm2": r.get("model_area_mm2"),
        }
        for r in paired
        if r.get("model_status") == "ok"
    ]


def compute_tables(rows: list[dict]) -> ReportTables:
    """Pair the prints with the model and derive every table of the report.

    Parameters
    ----------
    rows : list of dict
        An ``inkprint batch`` table.

    Returns
    -------
    ReportTables
    """
    paired = pair_prints(rows)
    trends = trend_table(paired)
    dp_pairs, dp_summary = drum_plate_ratios(paired)
    mp_pairs, mp_summary = drum_plate_ratios(_model_as_prints(paired))
    return ReportTables(
        paired=paired,
        trends=trends,
        agreement=sign_agreement(trends),
        drum_plate_prints=dp_pairs,
        drum_plate_summary=dp_summary,
        drum_plate_model=mp_pairs,
        drum_plate_model_summary=mp_summary,
        rim_sensitivity=rim_sensitivity(paired),
        errors=[r for r in paired if r.get("status") != "ok" or r.get("model_status") == "error"],
    )


def report_config(rows: list[dict], tables: ReportTables, *, source: str = "") -> dict:
    """The configuration block: package, versions, input and counts.

    Parameters
    ----------
    rows : list of dict
        The print table.
    tables : ReportTables
    source : str
        Where the print table came from (shown as is).

    Returns
    -------
    dict of str to str or int
    """
    from .. import __version__

    solved = {
        (r.get("tire"), r.get("pressure_bar"), r.get("load_N"), r.get("surface"))
        for r in tables.paired
        if r.get("model_status") == "ok"
    }
    drum_m = DEFAULT_DIAMETER_MM["drum"] / 1000
    return {
        "package": "rotta-tire",
        "version": __version__,
        "python": platform.python_version(),
        "source": source,
        "files": len({r.get("file") for r in rows}),
        "prints": sum(1 for r in rows if r.get("status", "ok") == "ok"),
        "errors": len(tables.errors),
        "model cases": len(solved),
        "surfaces": f"plate -> flat ground; drum -> {drum_m:g} m drum unless "
        "drum_diameter_mm is given",
    }


def write_tables(out_dir, tables: ReportTables, config: dict) -> list[Path]:
    """Write every table as ``tables/NAME.csv`` and all of them as ``report.json``.

    Parameters
    ----------
    out_dir : str or PathLike
        Report folder.
    tables : ReportTables
    config : dict
        Stored in ``report.json`` beside the tables.

    Returns
    -------
    list of Path
        The files written.
    """
    out = Path(out_dir)
    written = []
    for name, rows in tables.as_dict().items():
        cols = [*PAIRED_COLUMNS, "model_outline_wkt"] if name == "paired" else None
        written.append(write_table(rows, out / "tables" / f"{name}.csv", columns=cols))
    doc = json.dumps({"config": config, **tables.as_dict()}, indent=1, default=str)
    written.append(write_text_atomic(out / "report.json", doc))
    return written


def _median_plate_row(paired: list[dict], tire: str) -> dict | None:
    """The tire's solved plate row in the middle by (pressure, load), if any."""
    num = cell_number_or_nan
    rs = [
        r
        for r in paired
        if r.get("tire") == tire
        and r.get("model_status") == "ok"
        and str(r.get("surface", "")).lower() in ("plate", "flat")
    ]
    rs.sort(key=lambda r: (num(r["pressure_bar"]), num(r["load_N"])))
    return rs[len(rs) // 2] if rs else None


def render_tires(paired: list[dict], fig_dir, *, size: tuple[int, int] = (640, 480)):
    """Bottom and iso views of the model of each tire at its median plate case.

    Parameters
    ----------
    paired : list of dict
        Rows of :func:`contactpatch.pair_prints`.
    fig_dir : str or PathLike
        Folder for ``render_tire{k}_{view}.png``.
    size : (int, int) [px]
        Image width and height.

    Returns
    -------
    list of (Path, str)
        Each image and its caption.
    """
    from tiremesh.mesh import build_mesh
    from tiremesh.render import render

    fig_dir = Path(fig_dir)
    fig_dir.mkdir(parents=True, exist_ok=True)
    out = []
    for k, name in enumerate(_solved_tires(paired)):
        r = _median_plate_row(paired, name)
        if r is None:
            continue
        case = case_of(r)
        mesh = build_mesh(tm.solve(case), n_around=360)
        d = case.describe()
        for view in ("iso", "bottom"):
            path = fig_dir / f"render_tire{k}_{view}.png"
            render(mesh, path, view=view, size=size)
            caption = f"{name}, {d['pressure_bar']:g} bar, {d['load_N']:g} N, plate: {view} view"
            out.append((path, caption))
    return out


def _solved_tires(paired: list[dict]) -> list[str]:
    return sorted({str(r.get("tire", "")) for r in paired if r.get("model_status") == "ok"})


def draw_figures(tables: ReportTables, fig_dir, *, renders: bool = True) -> ReportFigures:
    """Draw and save every figure of the report (PNG and SVG).

    Parameters
    ----------
    tables : ReportTables
    fig_dir : str or PathLike
        Folder for the figures.
    renders : bool
        Also render the modelled tires (:func:`render_tires`).

    Returns
    -------
    ReportFigures
    """
    fig_dir = Path(fig_dir)
    fig_dir.mkdir(parents=True, exist_ok=True)
    paired = tables.paired

    def save(fig, stem: str) -> Path:
        return save_figure(fig, fig_dir / stem)[0]

    return ReportFigures(
        key=save(F.area_vs_length_width(paired), "area_vs_length_width"),
        load=save(F.load_per_area(paired), "load_per_area"),
        prints=save(F.print_overlays(paired), "print_overlays"),
        drum=save(
            F.drum_vs_plate(tables.drum_plate_summary, tables.drum_plate_model_summary),
            "drum_vs_plate",
        ),
        tire_trends=[
            (save(F.tire_trends(paired, tire), f"trends_tire{k}"), tire)
            for k, tire in enumerate(_solved_tires(paired))
        ],
        renders=render_tires(paired, fig_dir) if renders else [],
    )


def build_report(rows: list[dict], out_dir, *, renders: bool = True, source: str = "") -> Path:
    """Write the model vs print report for a print table.

    Parameters
    ----------
    rows : list of dict
        An ``inkprint batch`` table (values as read from CSV are fine).
    out_dir : str or PathLike
        Report folder (created).
    renders : bool
        Include 3D renders of the modelled tires (the slow part).
    source : str
        Where the table came from, shown in the configuration block.

    Returns
    -------
    Path
        ``out_dir/index.html``; beside it ``report.md``, ``report.json``,
        ``tables/`` and ``figures/``, the page holding the sections :data:`SECTIONS`.
    """
    out = Path(out_dir)
    tables = compute_tables(rows)
    config = report_config(rows, tables, source=source)
    write_tables(out, tables, config)
    content = ReportContent(config, tables, draw_figures(tables, out / "figures", renders=renders))
    index = write_text_atomic(out / "index.html", html_page(content))
    write_text_atomic(out / "report.md", markdown_page(content))
    return index


__all__ = [
    "SECTIONS",
    "ReportContent",
    "ReportFigures",
    "ReportTables",
    "build_report",
    "compute_tables",
    "draw_figures",
    "render_tires",
    "report_config",
    "write_tables",
]
