"""Parameter sweeps: tire x pressure x load x camber x slip x surface -> table.

Every row of a sweep becomes one :class:`~tiremesh.case.LoadCase` in one place,
:func:`case_from_row`. Cases without friction, deflection beyond the patch or slip
are solved together as arrays (:func:`tiremesh.solve_many` on a
:class:`~tiremesh.case.CaseTable`); the others one by one with
:func:`tiremesh.solve_lateral`, in parallel on local processes or on a Dask cluster
(``scheduler=ADDRESS``, through :func:`tiremesh.parallel.parallel_map`). Every case
becomes one row; a case the model cannot solve becomes a row with its error.

Case keys (units in the names), see :data:`CASE_KEYS`: ``tire`` (catalogue id or
name) or ``tire_radius_mm`` + ``rim_width_mm``; ``rim_width_mm``; ``pressure_bar``;
``load_N``; ``camber_deg``; ``slip_deg``; ``lateral_mm``; ``surface`` (flat | drum:D |
disk:D, or a :class:`~tiremesh.surface.Surface`); ``friction`` (inf);
``relaxation`` (0 = no deflection beyond the patch); ``slip_kinematics``
(leading | centre). Any other key is an error.
"""

from __future__ import annotations

import csv
import dataclasses
import difflib
import itertools
import math
from pathlib import Path
from types import SimpleNamespace

import numpy as np

from .case import LoadCase
from .errors import InvalidParameter, TireModelError
from .units import MPA_PER_BAR

CASE_KEYS = (
    "tire",
    "tire_radius_mm",
    "rim_width_mm",
    "pressure_bar",
    "load_N",
    "camber_deg",
    "slip_deg",
    "lateral_mm",
    "surface",
    "friction",
    "relaxation",
    "slip_kinematics",
)
DEFAULTS = {
    "camber_deg": 0.0,
    "slip_deg": 0.0,
    "lateral_mm": 0.0,
    "surface": "flat",
    "friction": math.inf,
    "relaxation": 0.0,
    "slip_kinematics": "leading",
}
VECTOR_SECTIONS = 65  # sections per patch of the vectorized path
STIFFNESS_PLOTS = (
    ("norm_lateral_stiffness_1_mm", "normalized lateral stiffness [1/mm]"),
    ("norm_camber_stiffness_1_deg", "normalized camber stiffness [1/deg]"),
    ("norm_cornering_stiffness_1_deg", "normalized cornering stiffness [1/deg]"),
)


def check_keys(cases) -> None:
    """Raise :class:`InvalidParameter` naming the first key that is not a case key.

    Parameters
    ----------
    cases : iterable of dict
        Sweep rows (or a grid's axes as one dict).

    Returns
    -------
    None

    Raises
    ------
    InvalidParameter
        A key outside :data:`CASE_KEYS` (e.g. ``camber`` instead of ``camber_deg``).
    """
    for case in cases:
        for key in case:
            if key not in CASE_KEYS:
                near = difflib.get_close_matches(str(key), CASE_KEYS, n=1)
                hint = f"; did you mean {near[0]!r}?" if near else ""
                raise InvalidParameter(
                    key,
                    case[key],
                    "a sweep key: " + ", ".join(CASE_KEYS),
                    f"unknown key {key!r}{hint}",
                )


MAX_CASES = 1_000_000
"""Largest sweep :func:`grid` / :func:`parse_grid` build without ``max_cases=``."""


def grid(*, max_cases: int = MAX_CASES, **axes) -> list[dict]:
    """All combinations of the given value lists.

    Parameters
    ----------
    max_cases : int
        Refuse (before building anything) a grid of more cases than this.
    **axes
        Case keys (:data:`CASE_KEYS`) with a value or a list of values each.

    Returns
    -------
    list of dict
        One case per combination, the last key varying fastest.

    Raises
    ------
    InvalidParameter
        An unknown key, an empty axis, or more than ``max_cases`` cases.

    Examples
    --------
    >>> grid(tire=[5, 8], pressure_bar=[3, 5])[1]
    {'tire': 5, 'pressure_bar': 5}
    """
    check_keys([axes])
    keys = list(axes)
    vals = [[_plain(x) for x in _values(axes[k])] for k in keys]
    _check_size({k: len(x) for k, x in zip(keys, vals, strict=True)}, max_cases)
    return [dict(zip(keys, combo, strict=True)) for combo in itertools.product(*vals)]


def _check_size(lengths: dict[str, int], max_cases: int) -> None:
    for k, n in lengths.items():
        if n < 1:
            raise InvalidParameter(k, "[]", "at least one value")
    total = math.prod(lengths.values())
    if total > max_cases:
        shape = " x ".join(f"{k}:{n}" for k, n in lengths.items())
        raise InvalidParameter(
            "grid", f"{total} cases ({shape})", f"at most max_cases = {max_cases} cases"
        )


def _values(axis) -> list:
    """An axis as a list: a scalar, a string or a Surface is one value."""
    if isinstance(axis, str | bytes) or np.ndim(axis) == 0:
        return [axis]
    return list(np.ravel(np.asarray(axis, dtype=object)))


def _plain(x):
    """numpy scalars as Python numbers (tables, JSON and equality stay simple)."""
    return x.item() if isinstance(x, np.generic) else x


TEXT_KEYS = ("tire", "surface", "slip_kinematics")
"""Grid keys whose values are text (the others are numbers)."""


def parse_grid(spec: str, *, max_cases: int = MAX_CASES) -> list[dict]:
    """Cases from a command-line grid, validated before any work.

    Parameters
    ----------
    spec : str
        Space-separated ``key=v1,v2,...`` or ``key=start:stop:count`` (a linspace),
        e.g. ``'tire=5,8 pressure_bar=2:11:10 load_N=304,500'``. Text keys
        (:data:`TEXT_KEYS`) take any non-empty values (``surface=drum:2500``).
    max_cases : int
        Refuse a grid of more cases than this (before building anything).

    Returns
    -------
    list of dict

    Raises
    ------
    InvalidParameter
        A malformed part (no ``=``, an empty value, a range not ``start:stop:count``
        with numbers and an integer count >= 1, a non-number for a numeric key), a
        key given twice, an unknown key, or more than ``max_cases`` cases.
    """
    axes: dict = {}
    for part in spec.split():
        k, eq, val = part.partition("=")
        if not eq or not k:
            raise InvalidParameter("grid", part, "key=v1,v2,... or key=start:stop:count")
        check_keys([{k: val}])
        if k in axes:
            raise InvalidParameter(k, val, "one entry per key", f"{k!r} is given twice")
        if k not in TEXT_KEYS and ":" in val:
            axes[k] = _range(k, val, max_cases)
        else:
            axes[k] = [_grid_value(k, x) for x in val.split(",")]
    return grid(max_cases=max_cases, **axes)


def _range(key: str, val: str, max_cases: int) -> list:
    """``start:stop:count`` of a numeric key as a linspace (count checked first)."""
    parts = val.split(":")
    allowed = "start:stop:count (numbers, count an integer >= 1), e.g. 2:4:3"
    if len(parts) != 3:
        raise InvalidParameter(key, val, allowed)
    try:
        a, b, n = float(parts[0]), float(parts[1]), int(parts[2])
    except ValueError as exc:
        raise InvalidParameter(key, val, allowed) from exc
    if not (math.isfinite(a) and math.isfinite(b)):
        raise InvalidParameter(key, val, allowed)
    _check_size({key: n}, max_cases)  # before allocating the axis
    return list(np.linspace(a, b, n))


def _grid_value(key: str, text: str):
    """One grid value: non-empty; a number unless ``key`` is a text key."""
    if not text.strip():
        raise InvalidParameter(key, text, "a non-empty value (key=v1,v2,...)")
    if key in TEXT_KEYS:
        return _auto(text, key)
    if not _is_number(text):
        raise InvalidParameter(key, text, "a number (or start:stop:count)")
    return float(text)


def read_cases(path) -> list[dict]:
    """Cases from a CSV file, one per row, columns named as the case keys (empty
    cells take the defaults).

    Parameters
    ----------
    path : str or PathLike

    Returns
    -------
    list of dict

    Raises
    ------
    InvalidParameter
        A column that is not a case key.
    """
    with open(path, newline="", encoding="utf-8-sig") as fh:
        cases = [{k: _auto(v, k) for k, v in r.items() if v != ""} for r in csv.DictReader(fh)]
    check_keys(cases)
    return cases


def _auto(v, key: str = ""):
    try:
        x = float(v)
    except (TypeError, ValueError):
        return v
    return int(x) if key == "tire" and x.is_integer() else x  # a catalogue id: 8, not 8.0


def _is_number(text: str) -> bool:
    return isinstance(_auto(text), float)


def _number(row: dict, key: str) -> float:
    if key not in row or row[key] is None or row[key] == "":
        raise InvalidParameter(key, None, "a value in every case")
    try:
        return float(row[key])
    except (TypeError, ValueError) as exc:
        raise InvalidParameter(key, row[key], "a number") from exc


def _tire(row: dict):
    from .catalog import get_tire
    from .geometry import TireGeometry

    rim = _number(row, "rim_width_mm") if "rim_width_mm" in row else None
    if "tire" in row and str(row["tire"]).strip() != "":
        key = row["tire"]
        key = str(int(key)) if isinstance(key, float) and key.is_integer() else key
        return get_tire(key, rim_width=rim)
    if "tire_radius_mm" in row and rim is not None:
        return TireGeometry(_number(row, "tire_radius_mm"), rim)
    raise InvalidParameter(
        "tire", row.get("tire"), "a catalogue tire or tire_radius_mm + rim_width_mm"
    )


def case_from_row(row: dict) -> LoadCase:
    """The load case of one sweep row (the only place a row becomes a case).

    Parameters
    ----------
    row : dict
        Case keys (:data:`CASE_KEYS`); missing optional keys take :data:`DEFAULTS`
        (note ``relaxation`` 0: no deflection beyond the patch unless asked for).

    Returns
    -------
    LoadCase

    Raises
    ------
    InvalidParameter
        An unknown key, a missing ``pressure_bar`` / ``load_N`` / tire, or a value
        the load case rejects (the message names the key).
    """
    check_keys([row])
    r = {**DEFAULTS, **row}
    return LoadCase.from_units(
        _tire(r),
        pressure_bar=_number(r, "pressure_bar"),
        load_N=_number(r, "load_N"),
        camber_deg=_number(r, "camber_deg"),
        slip_deg=_number(r, "slip_deg"),
        lateral_mm=_number(r, "lateral_mm"),
        surface=r["surface"],
        relaxation=_number(r, "relaxation"),
        friction=_number(r, "friction"),
        slip_kinematics=str(r["slip_kinematics"]).strip().lower(),
    )


def row_from_case(case: LoadCase) -> dict:
    """The sweep row of a load case (the inverse of :func:`case_from_row`).

    Parameters
    ----------
    case : LoadCase
        A load-searched case (``load`` given) whose options a sweep row can hold:
        one relaxation rate for all four, default sections and conventions.

    Returns
    -------
    dict
        Case keys (:data:`CASE_KEYS`) in the edge units: ``tire_radius_mm``,
        ``rim_width_mm`` [mm], ``pressure_bar`` [bar], ``load_N`` [N],
        ``camber_deg`` / ``slip_deg`` [deg], ``lateral_mm`` [mm], ``surface`` (spec),
        ``friction``, ``relaxation`` [1/mm], ``slip_kinematics``.

    Raises
    ------
    InvalidParameter
        The case holds what a row cannot (a deflection instead of a load, a bead
        seat other than 622 mm, four different relaxation rates, non-default
        sections or conventions); the message names the field: solve such a case
        with :func:`tiremesh.solve_lateral` directly.
    """
    if not isinstance(case, LoadCase):
        raise InvalidParameter("cases", type(case).__name__, "dict rows or tiremesh.LoadCase")
    fields = {f.name: f.default for f in dataclasses.fields(LoadCase)}
    for name in ("n_sections", "n_beyond", "friction_model", "force_convention"):
        if getattr(case, name) != fields[name]:
            raise InvalidParameter(name, getattr(case, name), f"{fields[name]!r} in a sweep")
    if case.footprint.kind != "rotta":
        raise InvalidParameter("footprint", case.footprint.spec, "'rotta' in a sweep")
    if case.load is None:
        raise InvalidParameter("load", None, "a load [N] in a sweep (not a deflection)")
    if case.tire.bead_seat_diameter != 622.0:
        raise InvalidParameter("tire.bead_seat_diameter", case.tire.bead_seat_diameter, "622")
    rates = dataclasses.astuple(case.relaxation)
    if len(set(rates)) != 1:
        raise InvalidParameter("relaxation", rates, "one rate for all four in a sweep")
    return {
        "tire_radius_mm": case.tire.tire_radius,
        "rim_width_mm": case.tire.rim_width,
        "pressure_bar": case.pressure / MPA_PER_BAR,
        "load_N": case.load,
        "camber_deg": math.degrees(case.camber),
        "slip_deg": math.degrees(case.slip),
        "lateral_mm": case.lateral,
        "surface": case.surface.spec,
        "friction": case.friction,
        "relaxation": rates[0],
        "slip_kinematics": case.slip_kinematics,
    }


def _result_row(row: dict, case: LoadCase, values: dict, extra=(), tail=()) -> dict:
    """The input row, status, tire size, the results common to both paths (with
    ``extra`` after the forces and ``tail`` after the force orientation), then the
    stiffnesses (:func:`tiremesh.lateral.stiffnesses`)."""
    from .lateral import stiffnesses

    t = case.tire
    out = dict(row)
    out.update(status="ok", error="", tire_radius=t.tire_radius, rim_width=t.rim_width)
    out.update(
        {
            "deflection_mm": values["deflection"],
            "sinkage_pct": 100 * values["sinkage"],
            "length_mm": values["length"],
            "width_mm": values["width"],
            "area_mm2": values["area"],
            "vertical_force_N": values["vertical_force"],
            "lateral_force_N": values["lateral_force"],
            **dict(extra),
            "net_force_orientation_deg": math.degrees(values["net_force_orientation"]),
            **dict(tail),
        }
    )
    forces = SimpleNamespace(
        lateral=case.lateral,
        slip=case.slip,
        camber=case.camber,
        lateral_force=values["lateral_force"],
        vertical_force=values["vertical_force"],
    )
    out.update(stiffnesses(forces))
    return out


def _error_row(row: dict, exc: Exception | str) -> dict:
    msg = exc if isinstance(exc, str) else f"{type(exc).__name__}: {exc}"
    return {**row, "status": "error", "error": msg}


def solve_case(row: dict, *, options=None) -> dict:
    """Solve one sweep row with :func:`tiremesh.solve_lateral` (friction, deflection
    beyond the patch, slip kinematics as the row says).

    Parameters
    ----------
    row : dict
        Case keys, see :func:`case_from_row`.
    options : SolverOptions, optional
        Judgement thresholds (:class:`tiremesh.SolverOptions`); sent to every worker
        by :func:`run_sweep`.

    Returns
    -------
    dict
        The row, ``status`` ('ok' | 'error'), ``error`` and the results
        (deflection, patch size, forces, trail, moment, stiffnesses). Never raises
        for a case the model rejects: the error is recorded.
    """
    from .lateral import solve_lateral

    try:
        case = case_from_row(row)
        r = solve_lateral(case, options=options)
    except (TireModelError, ValueError) as exc:
        return _error_row(row, exc)
    p = r.patch
    values = {
        "deflection": p.deflection,
        "sinkage": p.sinkage,
        "length": p.length,
        "width": p.width,
        "area": p.area,
        "vertical_force": r.vertical_force,
        "lateral_force": r.lateral_force,
        "net_force_orientation": r.net_force_orientation,
    }
    tail = {
        "pneumatic_trail_mm": r.pneumatic_trail,
        "aligning_moment_Nmm": r.aligning_moment,
        "relaxation_length_mm": r.relaxation_length[1],
    }
    return _result_row(row, case, values, {"patch_lateral_force_N": r.patch_lateral_force}, tail)


def _solve_vector(cases: list[LoadCase], options) -> list:
    """:func:`solve_many` of ``cases``: per case a dict of floats, or the error of a
    case the model rejects (a failing batch is bisected down to its bad cases)."""
    from .case import CaseTable
    from .solver import solve_many

    table = CaseTable.from_cases(cases)
    out = solve_many(table, n_sections=VECTOR_SECTIONS, errors="flag", options=options)
    keys = [k for k in out if k not in ("ok", "error")]
    return [
        {k: float(out[k][i]) for k in keys} if out["ok"][i] else str(out["error"][i])
        for i in range(len(cases))
    ]


def _vector_rows(rows: list[dict], options) -> list[dict]:
    """Plain rows (no friction, relaxation or slip) solved together as arrays."""
    out: list = [None] * len(rows)
    cases = {}
    for i, row in enumerate(rows):
        try:
            cases[i] = case_from_row(row)
        except (TireModelError, ValueError) as exc:
            out[i] = _error_row(row, exc)
    idx = list(cases)
    for i, got in zip(idx, _solve_vector([cases[i] for i in idx], options), strict=True):
        if isinstance(got, str):
            out[i] = _error_row(rows[i], got)
        else:
            out[i] = _result_row(rows[i], cases[i], got)
    return out


def _vectorizable(row: dict) -> bool:
    """No friction, no deflection beyond the patch, no slip: :func:`solve_many` gives
    the same forces as :func:`solve_lateral`."""
    try:
        return (
            float(row.get("friction", math.inf)) == math.inf
            and not float(row.get("relaxation", 0.0))
            and not float(row.get("slip_deg", 0.0))
        )
    except (TypeError, ValueError):
        return False  # solve_case records the error


def run_sweep(
    cases: list[dict],
    *,
    workers: int | None = None,
    scheduler: str | None = None,
    progress: bool | None = None,
    options=None,
) -> list[dict]:
    """Solve every case of a sweep.

    Parameters
    ----------
    cases : list of dict or LoadCase
        Case keys (:data:`CASE_KEYS`), e.g. from :func:`grid`, :func:`parse_grid`
        or :func:`read_cases`, or load cases (:func:`row_from_case`).
    workers : int, optional
        Local processes for the cases solved one by one (default: the CPU count).
    scheduler : str, optional
        Address of a Dask scheduler; overrides ``workers``.
    progress : bool, optional
        Show a progress bar (stderr) over all cases, the vectorized ones in chunks of
        :data:`VECTOR_CHUNK`; default: when stderr is a terminal.
    options : SolverOptions, optional
        Judgement thresholds (:class:`tiremesh.SolverOptions`), the same in this
        process, in local worker processes and on Dask workers (sent with every
        task). Default: the defaults.

    Returns
    -------
    list of dict
        One row per case, in the order of ``cases`` (see :func:`solve_case`).

    Raises
    ------
    InvalidParameter
        A case has an unknown key (nothing is solved).
    """
    from .options import SolverOptions
    from .parallel import parallel_map

    cases = [row_from_case(c) if isinstance(c, LoadCase) else c for c in cases]
    check_keys(cases)
    options = SolverOptions() if options is None else options
    if not isinstance(options, SolverOptions):
        raise InvalidParameter("options", type(options).__name__, "a tiremesh.SolverOptions")
    rows: list = [None] * len(cases)
    bar = _progress_bar(progress, len(cases))
    plain = [i for i, c in enumerate(cases) if _vectorizable(c)]
    for k in range(0, len(plain), VECTOR_CHUNK):  # chunks: bounded memory, a live bar
        part = plain[k : k + VECTOR_CHUNK]
        for i, r in zip(part, _vector_rows([cases[i] for i in part], options), strict=True):
            rows[i] = r
        bar.update(len(part))
    rest = [i for i in range(len(cases)) if rows[i] is None]
    results = parallel_map(
        solve_case,
        [cases[i] for i in rest],
        workers=workers,
        scheduler=scheduler,
        min_items=4,
        kwargs={"options": options},
    )
    for j, r in results:
        rows[rest[j]] = r
        bar.update(1)
    bar.close()
    return rows


#: cases of the vectorized path solved per call (a case's row does not depend on its
#: batch companions, so chunking changes no number)
VECTOR_CHUNK = 4096


def _progress_bar(progress: bool | None, total: int):
    """A tqdm bar on stderr (``progress`` None: only when stderr is a terminal), or a
    do-nothing stand-in."""
    import sys

    show = sys.stderr.isatty() if progress is None else bool(progress)
    if not show or total == 0:
        return SimpleNamespace(update=lambda n: None, close=lambda: None)
    from tqdm import tqdm

    return tqdm(total=total, desc="sweep", unit="case")


def sweep_plots(rows: list[dict], out_dir) -> list[Path]:
    """Figures of a sweep: normalized stiffnesses vs pressure and load, and the
    tangent-rule agreement vs tire radius over rim width (Figure 6-2).

    Parameters
    ----------
    rows : list of dict
        Rows of :func:`run_sweep` (or read back from its table: numbers as text).
    out_dir : str or PathLike
        Folder for the figures (created if missing).

    Returns
    -------
    list of Path
        PNG and SVG files written (a figure whose quantity no row has is skipped).
    """
    import matplotlib

    matplotlib.use("Agg")
    out = Path(out_dir)
    ok = [r for r in rows if r.get("status") == "ok"]
    written = []
    for key, label in STIFFNESS_PLOTS:
        rs = [r for r in ok if _has(r, key)]
        if rs:
            written += _stiffness_figure(rs, key, label, out / key)
    rs = [r for r in ok if _has(r, "tangent_rule_agreement")]
    if rs:
        written += _tangent_rule_figure(rs, out / "tangent_rule_agreement")
    return written


def _has(row: dict, key: str) -> bool:
    return row.get(key) not in (None, "")


def _save(fig, stem: Path) -> list[Path]:
    from .io import save_figure

    fig.tight_layout()
    return save_figure(fig, stem, formats=(".png", ".svg"), dpi=120)


def _stiffness_figure(rows: list[dict], key: str, label: str, stem: Path) -> list[Path]:
    """``key`` vs pressure (left) and load (right), one curve per tire and the other
    variable."""
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, xk, other in zip(
        axes, ("pressure_bar", "load_N"), ("load_N", "pressure_bar"), strict=True
    ):
        groups: dict = {}
        for r in rows:
            tire = str(r.get("tire", r.get("tire_radius_mm")))
            groups.setdefault((tire, r.get(other)), []).append(r)
        for (tire, val), g in sorted(groups.items(), key=lambda kv: str(kv[0])):
            g.sort(key=lambda r: float(r[xk]))
            ax.plot(
                [float(r[xk]) for r in g],
                [float(r[key]) for r in g],
                marker="o",
                ms=3,
                label=f"{tire}, {_label(val)}",
            )
        ax.set_xlabel(xk.replace("_", " "))
        ax.set_ylabel(label)
        ax.grid(alpha=0.3)
    axes[1].legend(fontsize=6)
    return _save(fig, stem)


def _label(val) -> str:
    return f"{val:g}" if isinstance(val, int | float) else str(val)


def _tangent_rule_figure(rows: list[dict], stem: Path) -> list[Path]:
    """Camber thrust against the tangent rule (cf. Figure 6-2), coloured by sinkage."""
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6, 4))
    sc = ax.scatter(
        [float(r["tire_radius"]) / float(r["rim_width"]) for r in rows],
        [100 * float(r["tangent_rule_agreement"]) for r in rows],
        c=[float(r["sinkage_pct"]) for r in rows],
        s=12,
    )
    fig.colorbar(sc, label="sinkage [%]")
    ax.axhline(100, color="k", lw=0.8)
    ax.set_xlabel("tire radius / rim width")
    ax.set_ylabel("agreement with the tangent rule [%]")
    ax.set_title("Camber thrust vs the tangent rule (cf. Figure 6-2)")
    ax.grid(alpha=0.3)
    return _save(fig, stem)


__all__ = [
    "CASE_KEYS",
    "DEFAULTS",
    "case_from_row",
    "check_keys",
    "grid",
    "parse_grid",
    "read_cases",
    "row_from_case",
    "run_sweep",
    "solve_case",
    "sweep_plots",
]
