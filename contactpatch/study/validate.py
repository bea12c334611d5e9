"""Validation of the Rotta model against every measurement Dressel (2013) preserves.

``contactpatch validate [-o DIR]`` and :func:`validate` compare the model with every
row of ``measured-dressel2013.csv`` it can model (a copy ships in
:mod:`.validate_data`): per point model / measured, statistics per quantity, trend
signs with pressure, load, rim width and arc length, the dissertation's summary
statistics, and the one fitted parameter (the casing modulus of the taut beam that
sets the decay length beyond the patch, section 5.9) with its leave-one-tire-out
errors. :func:`report_section` returns the HTML and Markdown fragments another report
includes. ``docs/validation.md`` explains the method and what the model cannot follow.

Modules
-------
``validate_data``     the measurements (verbatim CSV) and their reader
``validate_points``   rows -> points with a status (compared, duplicate, summary...)
``validate_relax``    decay length from the taut beam (equations 5-28, 5-29, 5-30, 5-31, 5-32, 5-33)
``validate_model``    the model's counterpart of each quantity
``validate_fit``      the fitted modulus, leave-one-tire-out, the decay-length variants
``validate_stats``    ratio statistics and trend signs
``validate_summary``  the dissertation's summary statistics vs the model
``validate_figures``  measured-vs-model and fit figures
``validate_pages``    Markdown summary and the HTML / Markdown fragments
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import time
from dataclasses import dataclass, field
from pathlib import Path

import tiremesh as tm
from tiremesh.io import write_table, write_text_atomic

from ..errors import ContactPatchError
from . import validate_pages as pages
from .validate_data import read_measurements
from .validate_figures import measured_vs_model, relaxation_figure
from .validate_fit import (
    RelaxationFit,
    cornering_variants,
    error_curve,
    fit_relaxation,
    loto_table,
    trail_kinematics,
    variants,
)
from .validate_model import (
    CAMBER_DEG,
    DRUM_DIAMETER,
    LATERAL_MM,
    RATE_DEPENDENT,
    SLIP_DEG,
    ModelRunner,
    slip_kinematics,
)
from .validate_points import QUANTITIES, Point, classify_all
from .validate_relax import THICKNESS_MM, BeamRelaxation
from .validate_stats import quantity_table, trend_table
from .validate_summary import summary_table

#: bump when the validation's method changes (part of the cache key)
VALIDATION_VERSION = "1"
#: columns of points.csv, in order
POINT_COLUMNS = [
    "row",
    "status",
    "quantity",
    "label",
    "unit",
    "tire_id",
    "tire",
    "rim_width_mm",
    "arc_length_mm",
    "pressure_bar",
    "load_N",
    "surface",
    "measured",
    "model",
    "ratio",
    "alt_load_N",
    "model_alt",
    "modulus_N_mm2",
    "rate_per_mm",
    "decay_length_mm",
    "source",
    "locator",
    "value_kind",
    "printed",
    "printed_unit",
    "csv_quantity",
    "item",
    "reason",
]
#: tables written as CSV and JSON: name -> key in the result dict
TABLES = {
    "points": "points",
    "statistics": "statistics",
    "trends": "trends",
    "summary_checks": "summaries",
    "decay_length_variants": "variants",
    "cornering_vs_decay_length": "cornering",
    "trail_vs_slip_kinematics": "trail",
    "leave_one_tire_out": "loto",
}
FIGURES = ("measured_vs_model", "relaxation_fit")


@dataclass
class Validation:
    """Everything the validation computed (:meth:`to_dict` is what is written).

    Attributes
    ----------
    points : list of Point
        Every row of the measurements, with its status and, where compared, the
        model's value (:func:`evaluate_points`).
    statistics : list of dict
        Ratio statistics per quantity (:func:`.validate_stats.quantity_table`).
    trends : list of dict
        Trend signs, measured vs model (:func:`.validate_stats.trend_table`).
    summaries : list of dict
        The dissertation's summary statistics vs the model
        (:func:`.validate_summary.summary_table`).
    variants : list of dict
        Lateral-stiffness errors per way of setting the decay length
        (:func:`.validate_fit.variants`).
    cornering : list of dict
        Cornering-stiffness errors under three decay lengths
        (:func:`.validate_fit.cornering_variants`).
    trail : list of dict
        Pneumatic-trail errors under each slip kinematics
        (:func:`.validate_fit.trail_kinematics`).
    loto : list of dict
        Leave-one-tire-out rows per fitted tire (:func:`.validate_fit.loto_table`).
    fit : RelaxationFit
        The fitted casing modulus and decay length.
    settings : dict
        The run's inputs and choices (:func:`settings`).
    curve : dict
        RMS log error vs casing modulus for the figure
        (:func:`.validate_fit.error_curve`).
    """

    points: list[Point]
    statistics: list[dict]
    trends: list[dict]
    summaries: list[dict]
    variants: list[dict]
    cornering: list[dict]
    trail: list[dict]
    loto: list[dict]
    fit: RelaxationFit
    settings: dict
    curve: dict = field(repr=False, default_factory=dict)

    def to_dict(self) -> dict:
        """JSON-ready result: settings, tables (``points`` as rows of
        :data:`POINT_COLUMNS`), the fit curve and the list of limits.

        Returns
        -------
        dict
            Keys ``settings``, ``points`` (list of row dicts), ``statistics``,
            ``trends``, ``summaries``, ``variants``, ``cornering``, ``trail``, ``loto``,
            ``fit_curve`` and ``limits`` (list of str); values are plain JSON types.
        """
        out = {
            "settings": self.settings,
            "points": [point_row(p) for p in self.points],
            "statistics": self.statistics,
            "trends": self.trends,
            "summaries": self.summaries,
            "variants": self.variants,
            "cornering": self.cornering,
            "trail": self.trail,
            "loto": self.loto,
            "fit_curve": self.curve,
        }
        out["limits"] = pages.limits(out)
        return out


def point_row(p: Point) -> dict:
    """A :class:`Point` as a row of :data:`POINT_COLUMNS`.

    Parameters
    ----------
    p : Point
        A validation point (with or without a condition).

    Returns
    -------
    dict
        Column of :data:`POINT_COLUMNS` -> value: the point's fields, the quantity's
        label and unit, the condition's fields (``rim_width_mm``, ``arc_length_mm``
        [mm], ``pressure_bar`` [bar], ``load_N`` [N]; NaN, '' or None without a
        condition), ``ratio`` (model / measured) and ``decay_length_mm``
        ``1 / (1 - rate)`` [mm] (NaN unless ``0 <= rate < 1``).
    """
    c = p.condition
    nan = math.nan
    return {
        "row": p.row,
        "status": p.status,
        "quantity": p.quantity,
        "label": QUANTITIES.get(p.quantity, ("",))[0],
        "unit": QUANTITIES.get(p.quantity, ("", ""))[1],
        "tire_id": c.tire_id if c else None,
        "tire": c.tire if c else "",
        "rim_width_mm": c.rim_width if c else nan,
        "arc_length_mm": c.arc_length if c else nan,
        "pressure_bar": c.pressure_bar if c else nan,
        "load_N": c.load_N if c else nan,
        "surface": c.surface if c else "",
        "measured": p.measured,
        "model": p.model,
        "ratio": p.ratio,
        "alt_load_N": p.alt_load_N,
        "model_alt": p.model_alt,
        "modulus_N_mm2": p.modulus,
        "rate_per_mm": p.rate,
        "decay_length_mm": 1.0 / (1.0 - p.rate) if 0 <= p.rate < 1 else nan,
        "source": p.source,
        "locator": p.locator,
        "value_kind": p.value_kind,
        "printed": p.printed,
        "printed_unit": p.printed_unit,
        "csv_quantity": p.csv_quantity,
        "item": p.item,
        "reason": p.reason,
    }


def evaluate_points(runner: ModelRunner, points: list[Point]) -> None:
    """Set ``model`` (and ``model_alt`` at the alternative load, the modulus and rate
    used) on compared and ambiguous points; a named model error becomes status
    ``model error`` with its message (in place).

    Parameters
    ----------
    runner : ModelRunner
        Solves the model (with the fitted decay length per tire).
    points : list of Point
        From :func:`.validate_points.classify_all`; points of any other status are
        left alone.

    Returns
    -------
    None
        ``points`` is modified in place: ``model`` and ``model_alt`` in the unit of
        :data:`.validate_points.QUANTITIES`, ``modulus`` [N/mm^2] and ``rate`` [per
        mm] for rate-dependent quantities, or ``status`` and ``reason``.
    """
    from dataclasses import replace

    for p in points:
        if p.status not in ("compared", "ambiguous"):
            continue
        try:
            p.model = runner.value(p.quantity, p.condition)
            if math.isfinite(p.alt_load_N):
                p.model_alt = runner.value(p.quantity, replace(p.condition, load_N=p.alt_load_N))
            if p.quantity in RATE_DEPENDENT:
                p.modulus = runner.relaxation(p.condition.tire_id).modulus
                p.rate = runner.rate(p.condition)
        except (tm.TireModelError, ContactPatchError) as exc:
            p.status, p.reason = "model error", f"{type(exc).__name__}: {exc}"


def run_validation(measurements: str | os.PathLike | None = None) -> Validation:
    """Compare the model with the measurements (no files written).

    Parameters
    ----------
    measurements : path, optional
        A CSV with the columns of ``measured-dressel2013.csv``; default the packaged
        copy (:mod:`.validate_data`).

    Returns
    -------
    Validation
    """
    t0 = time.perf_counter()
    rows, sha = read_measurements(measurements)
    points = classify_all(rows)
    fit = fit_relaxation(ModelRunner(lambda tid: BeamRelaxation()), points)
    runner = ModelRunner(fit.relaxation_for)
    evaluate_points(runner, points)
    v = Validation(
        points=points,
        statistics=quantity_table(points),
        trends=trend_table(runner, points),
        summaries=summary_table(runner, points),
        variants=variants(runner, points, fit),
        cornering=cornering_variants(runner, points),
        trail=trail_kinematics(runner, points),
        loto=loto_table(points, fit),
        fit=fit,
        settings={},
        curve=error_curve(fit),
    )
    v.settings = settings(
        fit, rows, sha=sha, measurements=measurements, seconds=time.perf_counter() - t0
    )
    return v


def settings(fit: RelaxationFit, rows, *, sha: str, measurements, seconds: float) -> dict:
    """The run's inputs and choices, for the outputs.

    Parameters
    ----------
    fit : RelaxationFit
        The fitted casing modulus and decay length.
    rows : list of dict
        The measurement rows (only counted).
    sha : str
        SHA-256 hex digest of the measurement text.
    measurements : path or None
        The measurement CSV as given (None: the packaged copy).
    seconds : float [s]
        Run time, recorded to 0.01 s.

    Returns
    -------
    dict
        ``validation_version``, ``tiremesh_version``, ``measurements``,
        ``measurements_sha256``, ``n_rows``, ``cache_key`` (:func:`cache_key`),
        ``surface``, ``lateral_mm`` [mm], ``slip_deg`` and ``camber_deg`` [deg],
        ``friction``, ``slip_kinematics``, ``thickness_mm`` [mm], ``modulus_N_mm2``
        [N/mm^2], ``modulus_times_thickness_N_mm`` [N/mm], ``decay_length_variant_mm``
        [mm], ``fit_quantity`` and ``seconds`` [s].
    """
    return {
        "validation_version": VALIDATION_VERSION,
        "tiremesh_version": tm.__version__,
        "measurements": str(measurements)
        if measurements
        else "packaged copy of measured-dressel2013.csv (contactpatch.study.validate_data)",
        "measurements_sha256": sha,
        "n_rows": len(rows),
        "cache_key": cache_key(sha),
        "surface": f"drum {DRUM_DIAMETER:g} mm (TU Delft, device 3) unless the row says flat plate",
        "lateral_mm": LATERAL_MM,
        "slip_deg": SLIP_DEG,
        "camber_deg": CAMBER_DEG,
        "friction": "inf (stiffnesses are slopes at zero angle)",
        "slip_kinematics": slip_kinematics(),
        "thickness_mm": THICKNESS_MM,
        "modulus_N_mm2": fit.modulus,
        "modulus_times_thickness_N_mm": fit.modulus * THICKNESS_MM,
        "decay_length_variant_mm": fit.length,
        "fit_quantity": "static lateral stiffness (Appendix B)",
        "seconds": round(seconds, 2),
    }


def cache_key(measurements_sha: str) -> str:
    """Hash of the measurements, the validation version and the source of
    :mod:`tiremesh`, :mod:`contactpatch.ruler` and the validation modules: any change
    to the model or the method invalidates cached results.

    Parameters
    ----------
    measurements_sha : str
        SHA-256 hex digest of the measurement text
        (:func:`.validate_data.read_measurements`).

    Returns
    -------
    str
        SHA-256 hex digest (64 characters).
    """
    h = hashlib.sha256(f"{VALIDATION_VERSION}\n{measurements_sha}\n".encode())
    roots = [Path(tm.__file__).parent, Path(__file__).parent.parent / "ruler"]
    files = [f for r in roots for f in sorted(r.rglob("*.py"))]
    files += sorted(Path(__file__).parent.glob("validate*.py"))
    for f in files:
        h.update(f.name.encode())
        h.update(f.read_bytes())
    return h.hexdigest()


def write_validation(v: Validation, out_dir: str | os.PathLike) -> dict:
    """Write tables (CSV and JSON), figures (SVG), ``validation.json``,
    ``summary.md`` and ``index.html`` into ``out_dir``, each atomically.

    Parameters
    ----------
    v : Validation
        The results (:func:`run_validation`).
    out_dir : path
        Output folder.

    Returns
    -------
    dict
        :meth:`Validation.to_dict`.
    """
    out = Path(out_dir)
    data = v.to_dict()
    for name, key in TABLES.items():
        cols = POINT_COLUMNS if key == "points" else None
        for ext in (".csv", ".json"):
            write_table(data[key], out / f"{name}{ext}", columns=cols)
    figs = out / "figures"
    svgs = {
        FIGURES[0]: measured_vs_model(data["points"], data["statistics"]),
        FIGURES[1]: relaxation_figure(data["fit_curve"], data["variants"]),
    }
    for name, svg in svgs.items():
        write_text_atomic(figs / f"{name}.svg", svg)
    write_text_atomic(out / "summary.md", pages.summary_markdown(data))
    write_text_atomic(out / "index.html", pages.standalone_html(data, svgs))
    write_text_atomic(out / "validation.json", json.dumps(_jsonable(data), indent=1))
    return data


def validate(
    out_dir: str | os.PathLike = "validation", measurements: str | os.PathLike | None = None
) -> Validation:
    """Run the validation and write its outputs (:func:`write_validation`).

    Parameters
    ----------
    out_dir : path
        Output folder (created if missing).
    measurements : path, optional
        Measurement CSV (default: the packaged copy).

    Returns
    -------
    Validation
    """
    v = run_validation(measurements)
    write_validation(v, out_dir)
    return v


def _figure_svgs(out: Path) -> dict[str, str]:
    return {
        name: (out / "figures" / f"{name}.svg").read_text(encoding="utf-8") for name in FIGURES
    }


def _jsonable(x):
    if isinstance(x, dict):
        return {k: _jsonable(v) for k, v in x.items()}
    if isinstance(x, list | tuple):
        return [_jsonable(v) for v in x]
    if isinstance(x, float) and not math.isfinite(x):
        return None
    if hasattr(x, "item"):
        return _jsonable(x.item())
    return x


def load_cached(out_dir: str | os.PathLike, key: str) -> dict | None:
    """The results in ``out_dir`` if they were written with cache key ``key`` and all
    their files are present; else None.

    Parameters
    ----------
    out_dir : path
        Folder of the validation's outputs.
    key : str
        The expected cache key (:func:`cache_key`).

    Returns
    -------
    dict or None
        ``validation.json`` as read (JSON nulls in the tables back to NaN), or None
        if it is missing, unreadable, of another key or a figure SVG is missing.
    """
    out = Path(out_dir)
    try:
        data = json.loads((out / "validation.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    if data.get("settings", {}).get("cache_key") != key:
        return None
    if not all((out / "figures" / f"{n}.svg").is_file() for n in FIGURES):
        return None
    return _nan_back(data)


def _nan_back(data: dict) -> dict:
    """JSON nulls in number columns back to NaN (tables read from validation.json)."""
    for key in TABLES.values():
        for row in data.get(key, []):
            for k, v in row.items():
                if v is None:
                    row[k] = math.nan
    return data


def report_section(
    out_dir: str | os.PathLike,
    *,
    measurements: str | os.PathLike | None = None,
    link_base: str | None = None,
) -> tuple[str, str]:
    """The validation as fragments of another report.

    Reads the results cached in ``out_dir`` when they match the current measurements
    and model source (:func:`cache_key`); otherwise runs the validation and writes
    them there (:func:`validate`).

    Parameters
    ----------
    out_dir : path
        Folder of the validation's outputs.
    measurements : path, optional
        Measurement CSV (default: the packaged copy).
    link_base : str, optional
        Prefix of the figure links in the Markdown fragment (default: the name of
        ``out_dir`` + '/', for a report written in its parent folder).

    Returns
    -------
    html : str
        A self-contained ``<section id="validation">`` (figures as inline SVG, all
        text escaped).
    markdown : str
        The same content in Markdown, linking the figures under ``link_base``.
    """
    out = Path(out_dir)
    sha = read_measurements(measurements)[1]
    data = load_cached(out, cache_key(sha))
    if data is None:
        data = _nan_back(_jsonable(write_validation(run_validation(measurements), out)))
    base = f"{out.name}/" if link_base is None else link_base
    return pages.html_fragment(data, _figure_svgs(out)), pages.markdown_fragment(data, base)


__all__ = [
    "FIGURES",
    "POINT_COLUMNS",
    "TABLES",
    "VALIDATION_VERSION",
    "Validation",
    "cache_key",
    "evaluate_points",
    "load_cached",
    "point_row",
    "report_section",
    "run_validation",
    "settings",
    "validate",
    "write_validation",
]
