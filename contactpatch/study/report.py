"""Model vs print report: one self-contained HTML file plus its tables and vector
figures (Dressel 2013, sections 4.1.1, 6.2).

:func:`build_report` takes an ``inkprint batch`` table and runs named steps:

1. :func:`compute_tables` -> :class:`ReportTables` (pairing, trends with standard
   errors, drum / plate, rim sensitivity, errors);
2. :func:`report_config` -> the configuration block (package, version, counts);
3. :func:`write_tables` -> ``tables/*.csv`` and ``report.json``, every table in full
   precision (through :func:`tiremesh.io.write_table`);
4. in worker processes, while the rest goes on: the 1200 px renders of
   :func:`representative_cases` (low and high load on the plate, cambered on the
   drum; :func:`tiremesh.render.render_many`) and the validation section, when
   :mod:`contactpatch.study.validate` provides ``report_section``; ``inkprint batch
   ... --report`` starts these, the model's columns and the 3D-view meshes before
   it analyses the scans (:mod:`contactpatch.study.prework`, ``precomputed=``);
5. :func:`draw_figures` -> :class:`ReportFigures`: every figure drawn once and
   saved once, as SVG (written to ``figures/`` and inlined in the page);
6. :func:`collect_sheets`: each scan's QA overlay and what was set aside on it;
7. :func:`viewer_cases`: the meshes of the interactive 3D view;

then writes the pages of :mod:`contactpatch.study.pages`: ``index.html`` (complete
on its own: figures inline, images as data URIs, no network request) and
``report.md`` (a Markdown summary for version control). A progress bar follows the
steps when the report is built in a terminal.

The pages show the numbers of the CSV files rounded by quantity and contain no
timestamp: the same inputs give the same tables and pages.
"""

from __future__ import annotations

import json
import math
import os
import platform
import shutil
import sys
import tempfile
from dataclasses import dataclass, fields
from pathlib import Path

import tiremesh as tm
from tiremesh.io import cell_number_or_nan, table_columns, write_table, write_text_atomic

from . import figures as F
from .compare import DEFAULT_DIAMETER_MM, PAIRED_COLUMNS, case_of, pair_prints
from .pages import SECTIONS, html_page, markdown_page
from .sheets import locate_scans, qa_overlay, set_aside, sheets_of
from .style import tire_colours
from .trends import DISSERTATION_TABLE_4_1, drum_plate_ratios, rim_sensitivity, sign_agreement
from .uncertainty import trend_table_with_errors

#: at most this many prints: their scans and outlines are shown open; beyond, folded
EXPAND_LIMIT = 48
#: beyond this many scans the QA overlays are embedded smaller (long side [px])
SCAN_LIMIT = 60
#: size of the report's renders [px]
RENDER_SIZE = (1200, 900)
#: camber of the cambered drum render when no print was taken cambered [deg]
RENDER_CAMBER_DEG = 10.0


@dataclass(frozen=True)
class ReportTables:
    """Every table of the report (lists of row dicts), in the order they are written.

    Parameters
    ----------
    paired : list of dict
        :func:`contactpatch.pair_prints` of the print table.
    trends : list of dict
        :func:`contactpatch.study.uncertainty.trend_table_with_errors`: pressure and
        load exponents with standard errors.
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
class Figure:
    """A matplotlib figure of the report, saved once as SVG.

    Parameters
    ----------
    name : str
    svg : str
        The SVG document (inlined in the page).
    caption : str
    path : Path
        The same SVG written beside the page (``figures/NAME.svg``).
    """

    name: str
    svg: str
    caption: str
    path: Path


@dataclass(frozen=True)
class Render:
    """A render of the model.

    Parameters
    ----------
    path : Path
        ``figures/render_*.png``.
    png : bytes
    caption : str
    size : (int, int) [px]
    """

    path: Path
    png: bytes
    caption: str
    size: tuple[int, int]


@dataclass(frozen=True)
class ReportFigures:
    """The report's figures.

    Parameters
    ----------
    key : Figure
        Area vs length and width (Figure 6-3).
    ratios : Figure
        Print / model ratios per tire (aggregate).
    load : Figure
        Load over area vs pressure, in bar (Figure 4-3).
    drum : Figure
        Drum / plate ratios (Table 4-1).
    tire_trends : dict of str to Figure
        Per tire: size vs pressure and load.
    renders : list of Render
        Renders of representative cases (empty when skipped).
    """

    key: Figure
    ratios: Figure
    load: Figure
    drum: Figure
    tire_trends: dict
    renders: list


@dataclass(frozen=True)
class Sheet:
    """A scanned sheet in the report.

    Parameters
    ----------
    file : str
        As the print table names it.
    rows : list of dict
        Its paired rows.
    qa_jpeg : bytes or None
        The QA overlay (None: the scan was not found).
    set_aside : list of str or None
        What the analysis set aside (None: not recorded in the table).
    """

    file: str
    rows: list
    qa_jpeg: bytes | None
    set_aside: list | None


@dataclass(frozen=True)
class ReportContent:
    """What the pages show.

    Parameters
    ----------
    config : dict
        :func:`report_config`.
    tables : ReportTables
    figures : ReportFigures
    colours : dict of str to str
        A colour per tire (sorted by name), shared by every figure and table.
    sheets : list of Sheet
    viewer : list of dict
        Cases of the 3D view (:func:`contactpatch.study.viewer.viewer_case`).
    validation : (str, str) or None
        HTML and Markdown of the validation section, when available.
    facts : list of (str, str)
        Key numbers of the summary (label, value).
    expand_prints : bool
        Show the scans and outlines open (few prints) or folded.
    outline_scale : (float, float) [mm]
        Height and width of every print outline drawing (one scale).
    """

    config: dict
    tables: ReportTables
    figures: ReportFigures
    colours: dict
    sheets: list
    viewer: list
    validation: tuple | None
    facts: list
    expand_prints: bool
    outline_scale: tuple


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


def compute_tables(rows: list[dict], *, model_cache: dict | None = None) -> ReportTables:
    """Pair the prints with the model and derive every table of the report.

    Parameters
    ----------
    rows : list of dict
        An ``inkprint batch`` table.
    model_cache : dict, optional
        Model columns already computed, by load case (``cache`` of
        :func:`contactpatch.pair_prints`; filled further here).

    Returns
    -------
    ReportTables
    """
    paired = pair_prints(rows, cache=model_cache)
    trends = trend_table_with_errors(paired)
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
        "units": "mm, N, bar (1 bar = 0.1 N/mm²)",
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
        # the paired table in full: its leading columns first, then every other one
        cols = table_columns(rows, first=PAIRED_COLUMNS) if name == "paired" else None
        written.append(write_table(rows, out / "tables" / f"{name}.csv", columns=cols))
    doc = json.dumps({"config": config, **tables.as_dict()}, indent=1, default=str)
    written.append(write_text_atomic(out / "report.json", doc))
    return written


# --- representative cases: renders and the 3D view ----------------------------------


@dataclass(frozen=True)
class ModelCase:
    """A load case shown as a render and in the 3D view.

    Parameters
    ----------
    label : str
        'low load', 'high load', 'cambered, drum'.
    case : tiremesh.LoadCase
    view : str
        Render view.
    stem : str
        File name stem of the render.
    note : str
        Said in the caption (e.g. that no print was taken at this camber).
    zoom : float
        Render zoom relative to the view's framing (renders compared side by side
        share one scale).
    """

    label: str
    case: object
    view: str
    stem: str
    note: str = ""
    zoom: float = 1.0


def _f(v) -> float:
    return cell_number_or_nan(v)


def _is_plate(r: dict) -> bool:
    return str(r.get("surface", "")).lower() in ("plate", "flat")


def representative_cases(rows: list[dict]) -> list[ModelCase]:
    """Low and high load on the plate, and the high load cambered on the drum, for
    the tire with the most prints, at its median pressure.

    Parameters
    ----------
    rows : list of dict
        Print rows (an ``inkprint batch`` table or its pairing): tire, pressure,
        load, surface of the prints whose ``status`` is ok.

    Returns
    -------
    list of ModelCase
        Empty when there is no print; a case the model cannot solve (or a row that
        names no tire the model knows) is left out.
    """
    ok = [r for r in rows if r.get("status", "ok") == "ok" and r.get("model_status", "ok") == "ok"]
    ok = [
        r
        for r in ok
        if math.isfinite(_f(r.get("pressure_bar"))) and math.isfinite(_f(r.get("load_N")))
    ]
    if not ok:
        return []
    counts: dict[str, int] = {}
    for r in ok:
        counts[str(r.get("tire", ""))] = counts.get(str(r.get("tire", "")), 0) + 1
    tire = min(counts, key=lambda t: (-counts[t], t))
    rows = [r for r in ok if str(r.get("tire", "")) == tire]
    base = [r for r in rows if _is_plate(r)] or rows
    pressures = sorted({_f(r["pressure_bar"]) for r in base})
    p = pressures[(len(pressures) - 1) // 2]
    at_p = sorted((r for r in base if _f(r["pressure_bar"]) == p), key=lambda r: _f(r["load_N"]))
    low, high = at_p[0], at_p[-1]
    try:
        cases = [ModelCase("low load", case_of(low), "bottom", "render_low_load")]
        if _f(high["load_N"]) != _f(low["load_N"]):
            cases.append(ModelCase("high load", case_of(high), "bottom", "render_high_load"))
        cases.append(_cambered_drum(rows, high))
    except (tm.TireModelError, ValueError):
        return []
    return [c for c in cases if _solves(c.case)]


def _cambered_drum(rows: list[dict], high: dict) -> ModelCase:
    drums = [r for r in rows if str(r.get("surface", "")).lower().startswith("drum")]
    d = next((_f(r.get("drum_diameter_mm")) for r in drums), math.nan)
    d = d if math.isfinite(d) and d > 0 else DEFAULT_DIAMETER_MM["drum"]
    cambered = [_f(r.get("camber_deg")) for r in drums if math.isfinite(_f(r.get("camber_deg")))]
    camber = next((c for c in cambered if c != 0), None)
    note = ""
    if camber is None:
        camber = RENDER_CAMBER_DEG
        note = f"model only: no print was taken at {camber:g} deg camber"
    case = case_of(high).replace(surface=tm.Drum(d), camber=math.radians(camber))
    return ModelCase("cambered, drum", case, "iso", "render_cambered_drum", note)


def _solves(case) -> bool:
    try:
        tm.solve(case)
    except tm.TireModelError:
        return False
    return True


def _same_scale(cases: list[ModelCase]) -> list[ModelCase]:
    """The bottom views drawn at one scale (the largest patch's framing)."""
    from tiremesh.render import view_camera

    class _Mesh:  # view_camera needs only the patch
        def __init__(self, patch):
            self.patch = patch

    bottoms = [c for c in cases if c.view == "bottom"]
    if len(bottoms) < 2:
        return cases
    scales = {c.stem: view_camera("bottom", _Mesh(tm.solve(c.case))).scale for c in bottoms}
    top = max(scales.values())
    return [
        ModelCase(c.label, c.case, c.view, c.stem, c.note, scales[c.stem] / top)
        if c.stem in scales
        else c
        for c in cases
    ]


def render_items(cases: list[ModelCase], fig_dir) -> list[dict]:
    """The items of :func:`tiremesh.render.render_many` for the cases (bottom views at
    one scale).

    Parameters
    ----------
    cases : list of ModelCase
    fig_dir : str or PathLike

    Returns
    -------
    list of dict
        ``case``, ``path`` (``fig_dir/STEM.png``), ``view``, ``zoom``.
    """
    return [
        {"case": c.case, "path": Path(fig_dir) / f"{c.stem}.png", "view": c.view, "zoom": c.zoom}
        for c in _same_scale(cases)
    ]


def render_caption(c: ModelCase, cases: list[ModelCase]) -> str:
    """What a render shows: label, tire, pressure, load, camber, surface, view.

    Parameters
    ----------
    c : ModelCase
    cases : list of ModelCase
        All the report's cases (to say when bottom views share one scale).

    Returns
    -------
    str
    """
    from tiremesh.render import surface_label

    d = c.case.describe()
    caption = (
        f"{c.label}: {d['tire']}, {d['pressure_bar']:g} bar, {d['load_N']:g} N, "
        f"camber {d['camber_deg']:g} deg, {surface_label(c.case.surface)}; "
        f"{c.view} view" + (f" ({c.note})" if c.note else "")
    )
    if c.view == "bottom" and sum(x.view == "bottom" for x in cases) > 1:
        caption += "; the bottom views share one scale"
    return caption


def render_cases(cases: list[ModelCase], fig_dir, size=RENDER_SIZE) -> list[Render]:
    """Render each case (with its title block) to ``fig_dir/STEM.png``, here.

    Parameters
    ----------
    cases : list of ModelCase
    fig_dir : str or PathLike
    size : (int, int) [px]

    Returns
    -------
    list of Render
    """
    from tiremesh.render import render_many

    paths = render_many(render_items(cases, fig_dir), size=size)
    return [
        Render(p, p.read_bytes(), render_caption(c, cases), tuple(size))
        for p, c in zip(paths, cases, strict=True)
    ]


def viewer_cases(cases: list[ModelCase]) -> list[dict]:
    """The representative cases as meshes for the 3D view.

    Parameters
    ----------
    cases : list of ModelCase

    Returns
    -------
    list of dict
    """
    from .viewer import viewer_case

    return [viewer_case(tm.solve(c.case), c.label) for c in cases]


def validation_fragments(out_dir):
    """The validation section (HTML, Markdown), or None when the validation module
    is not installed.

    Its results are cached in a folder shared by every report
    (``$ROTTA_CACHE_DIR`` or ``~/.cache/rotta-tire``) and copied to
    ``out_dir/validation`` (the Markdown's figure links).

    Parameters
    ----------
    out_dir : str or PathLike
        The report folder.

    Returns
    -------
    (str, str) or None
    """
    frags = validation_section()
    if frags is not None:
        copy_validation(out_dir)
    return frags


def _validation_cache() -> Path:
    root = os.environ.get("ROTTA_CACHE_DIR", Path.home() / ".cache" / "rotta-tire")
    return Path(root) / "validation"


def validation_section():
    """The validation section (HTML, Markdown) from the shared cache (computed and
    cached there when it is missing or stale), or None when the validation module is
    not installed.

    Returns
    -------
    (str, str) or None
    """
    try:
        from .validate import report_section
    except ImportError:
        return None
    return report_section(_validation_cache(), link_base="validation/")


def copy_validation(out_dir) -> Path:
    """Copy the cached validation outputs to ``out_dir/validation`` (the Markdown's
    figure links).

    Parameters
    ----------
    out_dir : str or PathLike
        The report folder.

    Returns
    -------
    Path
        ``out_dir/validation``.
    """
    return shutil.copytree(_validation_cache(), Path(out_dir) / "validation", dirs_exist_ok=True)


# --- figures and sheets --------------------------------------------------------------


def _svg_figure(svg: str, name: str, caption: str, fig_dir: Path) -> Figure:
    path = write_text_atomic(fig_dir / f"{name}.svg", svg)
    return Figure(name, svg, caption, path)


def draw_figures(tables: ReportTables, fig_dir, colours: dict, *, tick=None) -> ReportFigures:
    """Draw every figure once (:mod:`contactpatch.study.figures`) and save it once, as
    SVG in ``fig_dir``.

    Parameters
    ----------
    tables : ReportTables
    fig_dir : str or PathLike
    colours : dict of str to str
        A colour per tire.
    tick : callable, optional
        Called after each figure (progress).

    Returns
    -------
    ReportFigures
        Without renders.
    """
    fig_dir = Path(fig_dir)
    fig_dir.mkdir(parents=True, exist_ok=True)
    paired = tables.paired
    tick = tick or (lambda: None)

    def one(make, name, caption):
        f = _svg_figure(make(), name, caption, fig_dir)
        tick()
        return f

    key = one(
        lambda: F.area_vs_length_width(paired, colours),
        "area_vs_length_width",
        "Contact area vs length and width: prints filled, Rotta model open (cf. Figure 6-3).",
    )
    ratios = one(lambda: F.ratio_summary(paired, colours), "ratios", "Print / model ratios.")
    load = one(
        lambda: F.load_per_area(paired, colours),
        "load_per_area",
        "Load over print (hull) area vs inflation pressure, both in bar; the line is 1:1; "
        "markers of different surfaces are drawn slightly apart in pressure.",
    )
    drum = one(
        lambda: F.drum_vs_plate(tables.drum_plate_summary, tables.drum_plate_model_summary),
        "drum_vs_plate",
        "Drum / plate ratios: prints, model and the dissertation's measurements.",
    )
    trends = {
        tire: one(
            lambda tire=tire, k=k: F.tire_trends(
                paired, tire, colours[tire], name=f"trends_tire{k}"
            ),
            f"trends_tire{k}",
            f"{tire}: length, width and area vs pressure (top) and load (bottom), log-log; "
            "prints solid and filled, model dashed and open; a line's shade is the level of "
            "the variable held fixed along it (each row's legend), darkest = lowest.",
        )
        for k, tire in enumerate(colours)
    }
    return ReportFigures(key, ratios, load, drum, trends, [])


def collect_sheets(paired: list[dict], scan_dirs=(), *, tick=None) -> list[Sheet]:
    """Each scanned sheet with its QA overlay (when its scan is found) and what was
    set aside on it.

    Parameters
    ----------
    paired : list of dict
    scan_dirs : sequence of path
        Where to look for the scans first (:func:`contactpatch.study.sheets.locate_scans`).
    tick : callable, optional
        Called after each sheet (progress).

    Returns
    -------
    list of Sheet
    """
    by_file = sheets_of(paired)
    found = locate_scans(paired, scan_dirs)
    side = 800 if len(by_file) <= SCAN_LIMIT else 480
    out = []
    for f, rows in by_file.items():
        qa = None
        if f in found and any(r.get("status", "ok") == "ok" for r in rows):
            try:
                qa = qa_overlay(found[f], rows, max_side=side)
            except (OSError, ValueError):
                qa = None  # unreadable now: the card says the scan was not found
        out.append(Sheet(f, rows, qa, set_aside(rows)))
        if tick:
            tick()
    return out


def outline_scale(paired: list[dict]) -> tuple[float, float]:
    """Height and width [mm] of the print outline drawings, one scale for all: the
    longest and the widest patch (print or model) with a margin.

    Parameters
    ----------
    paired : list of dict

    Returns
    -------
    (float, float) [mm]
    """
    ok = [r for r in paired if r.get("status", "ok") == "ok"]
    longest = max([_f(r.get(k)) for r in ok for k in ("length_mm", "model_length_mm")] + [20.0])
    widest = max([_f(r.get(k)) for r in ok for k in ("width_mm", "model_width_mm")] + [10.0])
    longest = longest if math.isfinite(longest) else 200.0
    widest = widest if math.isfinite(widest) else 60.0
    return 1.05 * longest, 1.6 * widest


def key_facts(tables: ReportTables, colours: dict) -> list[tuple[str, str]]:
    """The summary's key numbers: prints, tires, median print / model ratios.

    Parameters
    ----------
    tables : ReportTables
    colours : dict

    Returns
    -------
    list of (str, str)
        (label, value).
    """
    import numpy as np

    ok = [r for r in tables.paired if r.get("model_status") == "ok"]
    facts = [("prints paired with the model", str(len(ok))), ("tires", str(len(colours)))]
    for key, label in (
        ("ratio_length", "length"),
        ("ratio_width", "width"),
        ("ratio_area", "area"),
    ):
        v = np.array([_f(r.get(key)) for r in ok])
        v = v[np.isfinite(v)]
        if v.size:
            facts.append((f"median print / model {label}", f"{np.median(v):.3f}"))
    return facts


# --- the whole report ----------------------------------------------------------------


def _progress(total: int, enabled: bool | None):
    from tqdm import tqdm

    on = sys.stderr.isatty() if enabled is None else enabled
    return tqdm(total=total, desc="report", unit="step", disable=not on, dynamic_ncols=True)


def build_report(
    rows: list[dict],
    out_dir,
    *,
    renders: bool = True,
    source: str = "",
    scan_dirs=(),
    validation: bool = True,
    progress: bool | None = None,
    precomputed=None,
) -> Path:
    """Write the model vs print report for a print table.

    Parameters
    ----------
    rows : list of dict
        An ``inkprint batch`` table (values as read from CSV are fine).
    out_dir : str or PathLike
        Report folder (created).
    renders : bool
        Include the 1200 px renders of representative cases.
    source : str
        Where the table came from, shown in the configuration block; its folder is
        also searched for the scans.
    scan_dirs : sequence of path
        Folders holding the scans (e.g. the batch's source folder), searched first
        for the QA overlays.
    validation : bool
        Include the validation section when the validation module is installed.
    progress : bool, optional
        Show a progress bar (default: when stderr is a terminal).
    precomputed : contactpatch.study.prework.Prework, optional
        The manifest-only parts started earlier (model columns, renders, 3D view,
        validation); the report is the same as without them. Its workers are
        stopped when the report is done or fails.

    Returns
    -------
    Path
        ``out_dir/index.html``; beside it ``report.md``, ``report.json``,
        ``tables/`` and ``figures/`` (SVG figures, PNG renders).

    Notes
    -----
    The renders and the validation run in worker processes
    (:class:`contactpatch.study.worker.Job`) while this one pairs, writes the tables,
    draws the figures and the scans and meshes the 3D view.

    The report is built whole in a hidden folder beside ``out_dir``
    (``.NAME.*.part``) and then moved in, one rename per entry, ``index.html``
    last: a step that fails leaves the previous report in ``out_dir`` untouched
    (and its partial files are removed). Other files in ``out_dir`` are kept.
    """
    out = Path(out_dir)
    out.parent.mkdir(parents=True, exist_ok=True)
    # built whole in a folder beside the target, then moved into place: a failing
    # step leaves the previous report as it was (see _install)
    part = Path(tempfile.mkdtemp(prefix=f".{out.name}.", suffix=".part", dir=out.parent))
    try:
        steps = {"renders": renders, "validation": validation}
        _build_into(
            rows, part, progress=progress, steps=steps, where=(source, scan_dirs), pre=precomputed
        )
        _install(part, out)
    finally:
        shutil.rmtree(part, ignore_errors=True)
        if precomputed is not None:
            precomputed.cancel()
    return out / "index.html"


#: what a report writes into its folder; ``index.html`` is moved in last
REPORT_ENTRIES = ("tables", "figures", "validation", "report.json", "report.md", "index.html")


def _install(part: Path, out: Path) -> None:
    """Move the finished report from ``part`` into ``out``, entry by entry (each move
    one rename on the same file system), ``index.html`` last; other files in ``out``
    are left alone, a previous report's folders are replaced whole."""
    out.mkdir(parents=True, exist_ok=True)
    old = Path(tempfile.mkdtemp(prefix=f".{out.name}.", suffix=".old", dir=out.parent))
    try:
        for name in REPORT_ENTRIES:
            src, dst = part / name, out / name
            if not src.exists():
                continue
            if dst.is_dir() and not dst.is_symlink():
                dst.rename(old / name)
            os.replace(src, dst)
    finally:
        shutil.rmtree(old, ignore_errors=True)


class _Done:
    """A worker's result already at hand (the :class:`.worker.Job` interface)."""

    def __init__(self, value) -> None:
        self.value = value

    def result(self):
        return self.value

    def cancel(self) -> None:
        pass


class _Validation:
    """The prework's validation section, waited for when the page needs it; computed
    here if the prework's worker failed (its error then reads as without prework)."""

    def __init__(self, pre, out: Path) -> None:
        self.pre, self.out = pre, out

    def result(self):
        frags = self.pre.result("validation")
        if frags is None:
            return validation_fragments(self.out)
        copy_validation(self.out)
        return frags

    def cancel(self) -> None:
        pass


def _from_prework(pre, cases, fig_dir: Path, out: Path, steps) -> tuple[dict, dict]:
    """The jobs the prework already did (as :class:`_Done`), and its model cache."""
    jobs: dict = {}
    model = pre.result("model") if pre is not None else None
    if model is not None and model["cases"] == cases:
        if steps["renders"] and cases and pre.renders and model["renders"] is not None:
            jobs["renders"] = _Done([pre.copy_render(p, fig_dir) for p in model["renders"]])
        jobs["viewer"] = _Done(model["viewer"])
    if steps["validation"] and pre is not None and pre.validation:
        jobs["validation"] = _Validation(pre, out)
    return jobs, (model["cache"] if model is not None else None)


def _start_jobs(rows, out: Path, steps, pre) -> tuple[list, dict, dict | None]:
    """The representative cases, the worker jobs (renders, validation: started here
    unless the prework did them) and the prework's model cache."""
    from tiremesh.render import render_many

    from .worker import Job

    fig_dir = out / "figures"
    cases = representative_cases(rows)
    jobs, cache = _from_prework(pre, cases, fig_dir, out, steps)
    if steps["renders"] and cases and "renders" not in jobs:
        jobs["renders"] = Job(render_many, render_items(cases, fig_dir), size=RENDER_SIZE)
    if steps["validation"] and "validation" not in jobs:
        jobs["validation"] = Job(validation_fragments, out)
    return cases, jobs, cache


def _build_into(rows, out: Path, *, progress, steps, where, pre=None) -> None:
    """Every file of the report, written into ``out`` (a fresh folder)."""
    (out / "figures").mkdir(parents=True, exist_ok=True)
    jobs: dict = {}
    try:
        cases, jobs, cache = _start_jobs(rows, out, steps, pre)
        tables = compute_tables(rows, model_cache=cache)
        ok = [r for r in tables.paired if r.get("model_status") == "ok"]
        colours = tire_colours(r.get("tire", "") for r in ok)
        n_files = len({r.get("file") for r in tables.paired})
        with _progress(n_files + len(colours) + 7, progress) as bar:
            content = _assemble(rows, tables, colours, out, cases, jobs, bar, where)
    finally:
        for job in jobs.values():
            job.cancel()  # only if still running: after an error in this process
    write_text_atomic(out / "report.md", markdown_page(content))
    write_text_atomic(out / "index.html", html_page(content))


def _wait(jobs: dict, name: str, bar, default=None):
    bar.set_postfix_str(name)
    value = jobs[name].result() if name in jobs else default
    bar.update(1)
    return value


def _assemble(rows, tables, colours, out, cases, jobs, bar, where) -> ReportContent:
    """Every part of the report, the workers' results last."""
    source, scan_dirs = where
    config = report_config(rows, tables, source=source)
    write_tables(out, tables, config)
    bar.set_postfix_str("figures")
    figs = draw_figures(tables, out / "figures", colours, tick=lambda: bar.update(1))
    bar.set_postfix_str("scans")
    dirs = [*scan_dirs, *([Path(source).parent] if source else [])]
    sheets = collect_sheets(tables.paired, dirs, tick=lambda: bar.update(1))
    bar.set_postfix_str("3D view")
    viewer = jobs["viewer"].result() if "viewer" in jobs else viewer_cases(cases)
    bar.update(1)
    paths = _wait(jobs, "renders", bar)
    rendered = (
        [
            Render(p, p.read_bytes(), render_caption(c, cases), RENDER_SIZE)
            for p, c in zip(paths, cases, strict=True)
        ]
        if paths is not None
        else []
    )
    frags = _wait(jobs, "validation", bar)
    n_ok = sum(1 for r in tables.paired if r.get("status", "ok") == "ok")
    return ReportContent(
        config=config,
        tables=tables,
        figures=ReportFigures(
            figs.key, figs.ratios, figs.load, figs.drum, figs.tire_trends, rendered
        ),
        colours=colours,
        sheets=sheets,
        viewer=viewer,
        validation=frags,
        facts=key_facts(tables, colours),
        expand_prints=n_ok <= EXPAND_LIMIT,
        outline_scale=outline_scale(tables.paired),
    )


__all__ = [
    "SECTIONS",
    "Figure",
    "ModelCase",
    "Render",
    "ReportContent",
    "ReportFigures",
    "ReportTables",
    "Sheet",
    "build_report",
    "collect_sheets",
    "compute_tables",
    "copy_validation",
    "draw_figures",
    "key_facts",
    "outline_scale",
    "render_caption",
    "render_cases",
    "render_items",
    "report_config",
    "representative_cases",
    "validation_fragments",
    "validation_section",
    "viewer_cases",
    "write_tables",
]
