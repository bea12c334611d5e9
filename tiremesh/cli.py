"""``tiremesh`` command line: a thin layer over the library.

Units at this edge carry their names and are never guessed: ``--pressure 4bar`` /
``60psi`` / ``400kPa`` / ``0.4MPa`` and ``--load 400N`` / ``40kg`` need their unit (a
bare ``60`` is refused with the accepted forms); angles in degrees, lengths in mm.

Conventions, for every command: ``--version``; ``-q`` (only results and errors) and
``-v`` (more detail; tracebacks of internal errors); errors on stderr, never a
traceback. Outputs are checked before any work (format, writable place, mesh size)
and written atomically. Exit status: 0 all good, 1 some sweep cases failed (the count
on stderr; the table is written with an ``error`` column), 2 a usage or input error
(bad value, unknown format, unwritable output, unreachable scheduler), 3 an internal
error (a bug: please report it with the ``-v`` output).
"""

from __future__ import annotations

import argparse
import csv
import io
import json
import math
import sys
from collections.abc import Sequence
from pathlib import Path

from .case import SLIP_KINEMATICS, LoadCase
from .catalog import get_tire
from .errors import InvalidParameter, TireModelError
from .geometry import TireGeometry
from .parallel import DEFAULT_SCHEDULER_TIMEOUT
from .units import FORCE_FORMS, PRESSURE_FORMS, parse_force, parse_length, parse_pressure

EXIT_OK, EXIT_FAILED_ROWS, EXIT_USAGE, EXIT_INTERNAL = 0, 1, 2, 3
"""Exit statuses (module docstring)."""
MAX_MESH_VERTICES = 5_000_000
"""Largest mesh ``mesh`` and ``render`` build without ``--max-vertices`` (about 2.5 GB
while building; refused before any work, the count and the limit in the message)."""
DPI_RANGE = (10, 1200)
"""Resolutions ``section --dpi`` accepts (a 6 x 5.5 in figure: up to 7200 x 6600 px)."""
IMAGE_SIZE_RANGE = (16, 8192)
"""Pixel widths and heights ``render --image-size`` accepts."""
_MESH_OPTIONS = {
    "n_around": "--around",
    "n_patch": "--patch-sections",
    "bulge_points": "--bulge-points",
    "contact_points": "--contact-points",
}


def add_tire_options(p: argparse.ArgumentParser) -> None:
    """Add the tire and load-case options shared by every subcommand that solves the
    model (``--tire``/``--size``/``--arc-length``, ``--pressure``, ``--load`` or
    ``--deflection``, angles in degrees, lengths in mm). Pressure and load need their
    unit (``4bar``, ``400N``).

    Parameters
    ----------
    p : argparse.ArgumentParser
        The (sub)command parser to extend.

    Returns
    -------
    None
    """
    g = p.add_argument_group("tire")
    g.add_argument("--tire", help="catalogue tire id or name (Table 3-2), e.g. 8 or 'big apple'")
    g.add_argument("--size", help="nominal size = carcass diameter [mm] (Table 5-1)")
    g.add_argument(
        "--arc-length", help="measured carcass arc length bead to bead [mm] (Table 5-2)"
    )
    g.add_argument("--rim-width", help="inner rim width [mm] (overrides the catalogue rim)")
    g.add_argument("--bead-seat", default="622", help="bead seat diameter [mm] (default 622)")
    c = p.add_argument_group("load case")
    c.add_argument(
        "--pressure",
        required=True,
        help=f"inflation pressure with its unit: {PRESSURE_FORMS} (a bare number is refused)",
    )
    m = c.add_mutually_exclusive_group(required=True)
    m.add_argument(
        "--load", help=f"vertical load with its unit: {FORCE_FORMS} (a bare number is refused)"
    )
    m.add_argument("--deflection", help="wheel deflection in the wheel plane [mm], > 0")
    c.add_argument("--camber", type=float, default=0.0, help="camber angle [deg]")
    c.add_argument("--slip", type=float, default=0.0, help="slip angle [deg]")
    c.add_argument("--lateral", default="0", help="lateral displacement of the patch [mm]")
    c.add_argument(
        "--surface",
        default="flat",
        help="flat | drum:DIAMETER_MM | disk:DIAMETER_MM[:toward|away] (default flat)",
    )
    c.add_argument(
        "--slip-kinematics",
        choices=SLIP_KINEMATICS,
        default="leading",
        help="how a slip angle displaces the tread: 'leading' undisplaced at the leading "
        "edge (default, brush model), 'relaxation' displaced ahead of the patch as the "
        "relaxation beyond it (Figure 4-15, 5.7), 'centre' turned about the patch centre "
        "(Appendix C)",
    )
    c.add_argument(
        "--sections", type=int, default=201, help="sections along the patch (default 201)"
    )


def tire_from_args(a: argparse.Namespace) -> TireGeometry:
    """The tire the options describe: a catalogue tire (``--tire``), or a size
    (Table 5-1) or measured arc length (Table 5-2, equation 5-6) on ``--rim-width``.

    Parameters
    ----------
    a : argparse.Namespace
        Parsed options of :func:`add_tire_options` (lengths as text, default mm).

    Returns
    -------
    TireGeometry

    Raises
    ------
    InvalidParameter
        Not exactly one of ``--tire``, ``--size``, ``--arc-length``, or no
        ``--rim-width`` with ``--size`` / ``--arc-length`` (and the model's own checks).
    """
    rim = None if a.rim_width is None else parse_length(a.rim_width, name="--rim-width")
    bead = parse_length(a.bead_seat, name="--bead-seat")
    given = [x for x in (a.tire, a.size, a.arc_length) if x is not None]
    if len(given) != 1:
        shown = " ".join(x for x in given) or "none"
        raise InvalidParameter(
            "--tire/--size/--arc-length", shown, "exactly one of --tire, --size, --arc-length"
        )
    if a.tire is not None:
        return get_tire(a.tire, rim_width=rim)
    if rim is None:
        raise InvalidParameter(
            "--rim-width", None, "a rim width (e.g. 19mm), required with --size or --arc-length"
        )
    if a.size is not None:
        size = parse_length(a.size, name="--size")
        return TireGeometry.from_size(
            size, rim, bead_seat_diameter=bead, name=f"{size:g} mm tire on {rim:g} mm rim"
        )
    s0 = parse_length(a.arc_length, name="--arc-length")
    return TireGeometry.from_arc_length(
        s0, rim, bead_seat_diameter=bead, name=f"{s0:g} mm carcass on {rim:g} mm rim"
    )


def case_from_args(a: argparse.Namespace) -> LoadCase:
    """The load case the options describe (units converted at this edge).

    Parameters
    ----------
    a : argparse.Namespace
        Parsed options of :func:`add_tire_options` (plus ``--relaxation`` and
        ``--friction`` where the subcommand has them).

    Returns
    -------
    LoadCase
        Relaxation 0 (no deflection beyond the patch) unless ``--relaxation`` is given.

    Raises
    ------
    InvalidParameter
        A pressure or load without its unit or <= 0, a deflection <= 0, or any value
        the model refuses (the message names the option and the accepted forms).
    """
    strict = {"require_unit": True, "positive": True}
    load = None if a.load is None else parse_force(a.load, name="--load", **strict)
    deflection = (
        None
        if a.deflection is None
        else parse_length(a.deflection, name="--deflection", positive=True)
    )
    relaxation = getattr(a, "relaxation", None)
    return LoadCase(
        tire_from_args(a),
        pressure=parse_pressure(a.pressure, name="--pressure", **strict),
        load=load,
        deflection=deflection,
        camber=math.radians(a.camber),
        slip=math.radians(a.slip),
        lateral=parse_length(a.lateral, name="--lateral"),
        surface=a.surface,
        n_sections=a.sections,
        relaxation=relaxation or 0.0,
        friction=getattr(a, "friction", math.inf),
        slip_kinematics=a.slip_kinematics,
        footprint=getattr(a, "footprint", None),
    )


def solve_from_args(a: argparse.Namespace):
    """Solve the load case the options describe (:func:`case_from_args`).

    Parameters
    ----------
    a : argparse.Namespace
        Parsed options of :func:`add_tire_options`.

    Returns
    -------
    ContactPatch
    """
    from .solver import solve

    return solve(case_from_args(a))


def _human(patch) -> str:
    s = patch.summary()
    t = patch.tire
    return "\n".join(
        [
            f"{t.name or 'tire'}: r0 = {t.tire_radius:.4g} mm, arc length {t.arc_length:.4g} mm, "
            f"rim {t.rim_width:.4g} mm, rim height {t.rim_height:.4g} mm, bead seat {t.bead_seat_diameter:g} mm",
            f"surface {s['surface']}, pressure {s['pressure_bar']:.4g} bar, camber {s['camber_deg']:.4g} deg, "
            f"slip {s['slip_deg']:.4g} deg, lateral {s['lateral_mm']:.4g} mm",
            f"deflection {s['deflection_mm']:.5g} mm (sinkage {s['sinkage_pct']:.4g} % of rim height)",
            f"contact patch: length {s['length_mm']:.5g} mm, width {s['width_mm']:.5g} mm, "
            f"area {s['area_mm2']:.5g} mm^2",
            f"forces: vertical {s['vertical_force_N']:.5g} N, lateral {s['lateral_force_N']:.5g} N, "
            f"net force {s['net_force_orientation_deg']:.4g} deg from vertical",
        ]
    )


def _section_rows(patch) -> list[dict]:
    """Per-section arrays of a patch as table rows (unit-carrying names)."""
    cols = patch.section_table()
    n = len(patch.phi)
    return [{k: float(v[i]) for k, v in cols.items()} for i in range(n)]


def _slip_note(case: LoadCase) -> str:
    if case.slip_kinematics == "centre":
        return (
            "note: a slip angle only turns the patch centre line here (Appendix C, "
            "--slip-kinematics centre), which carries no net force; use --slip-kinematics "
            "leading for the tread anchored at the leading edge and the cornering force"
        )
    return (
        "note: a slip angle acts on the patch alone here (tread anchored at the leading "
        "edge); add --relaxation 0.993 (and --friction) for the deflection beyond the patch, "
        "the cornering stiffness and the pneumatic trail"
    )


def _lateral_summary(r) -> dict:
    """Results of :func:`solve_lateral` beyond the patch summary (unit-carrying names)."""
    from .lateral import stiffnesses

    out = {
        "lateral_force_with_beyond_N": r.lateral_force,
        "patch_lateral_force_N": r.patch_lateral_force,
        "beyond_patch_lateral_force_N": r.beyond_lateral_force,
        "net_force_orientation_with_beyond_deg": math.degrees(r.net_force_orientation),
        "pneumatic_trail_mm": r.pneumatic_trail,
        "aligning_moment_Nmm": r.aligning_moment,
        "sliding_sections": int(r.sliding.sum()),
        "friction_iterations": r.iterations,
        "relaxation_length_lead_mm": r.relaxation_length[1],
    }
    out.update(stiffnesses(r))
    return out


def _verbosity(a: argparse.Namespace) -> int:
    return getattr(a, "verbose", 0) - getattr(a, "quiet", 0)


def _info(a: argparse.Namespace, message: str) -> None:
    """Informational line on stdout (``wrote ...``), silenced by ``-q``."""
    if _verbosity(a) >= 0:
        print(message)


def _warn(message: str) -> None:
    print(f"warning: {message}", file=sys.stderr)


def _csv(rows: list[dict]) -> str:
    from .io import csv_cell

    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow([csv_cell(k) for k in rows[0]])
    w.writerows([csv_cell(v) for v in r.values()] for r in rows)
    return buf.getvalue()


def _print_summary(a: argparse.Namespace, patch, summary: dict, extra: dict) -> None:
    if a.json:
        print(json.dumps(summary, indent=2))
        return
    if a.csv:
        print(_csv([summary]), end="")
        return
    print(_human(patch))
    for k, v in extra.items():
        print(f"{k}: {v:.6g}" if isinstance(v, float) else f"{k}: {v}")
    if patch.slip and not extra and _verbosity(a) >= 0:
        print(_slip_note(patch.case))


def _cmd_solve(a: argparse.Namespace) -> int:
    from .io import check_table_path, write_table
    from .lateral import solve_lateral
    from .solver import solve

    for option, path in (("--sections-csv", a.sections_csv), ("--outline-csv", a.outline_csv)):
        if path:
            check_table_path(path, option=option)
    case = case_from_args(a)
    if a.relaxation is not None or math.isfinite(a.friction):
        result = solve_lateral(case)
        patch, extra = result.patch, _lateral_summary(result)
    else:
        patch, extra = solve(case), {}
    extra.update(_footprint_summary(patch))
    summary = {**patch.summary(), **extra}
    _print_summary(a, patch, summary, extra)
    if a.sections_csv:
        write_table(_section_rows(patch), a.sections_csv)
    if a.outline_csv:
        rows = [{"x_mm": float(x), "y_mm": float(y)} for x, y in patch.outline]
        write_table(rows, a.outline_csv)
    return EXIT_OK


def _footprint_summary(patch) -> dict:
    """The rounded footprint next to the plain patch (empty for the plain patch)."""
    if patch.case.footprint.kind == "rotta":
        return {}
    fp = patch.footprint
    return {
        "footprint": patch.case.footprint.spec,
        "footprint_length_mm": fp.length,
        "footprint_width_mm": fp.width,
        "footprint_area_mm2": fp.area,
        "footprint_load_over_area_per_pressure": fp.mean_pressure(patch.vertical_force)
        / patch.pressure,
    }


def _mesh_options(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("mesh resolution")
    g.add_argument(
        "--around", type=int, default=720, help="sections around the wheel (default 720)"
    )
    g.add_argument(
        "--patch-sections", type=int, default=None, help="of which in the patch (default around/3)"
    )
    g.add_argument(
        "--bulge-points", type=int, default=32, help="segments per side bulge (default 32)"
    )
    g.add_argument(
        "--contact-points", type=int, default=12, help="segments across the patch (default 12)"
    )
    g.add_argument(
        "--max-vertices",
        type=_int_at_least(1),
        default=MAX_MESH_VERTICES,
        help=f"refuse a larger mesh before building it (default {MAX_MESH_VERTICES:,})",
    )


def mesh_vertex_count(res) -> int:
    """Vertices of the mesh :func:`tiremesh.mesh.build_mesh` builds at a resolution
    (an upper bound, exact to a few vertices).

    Parameters
    ----------
    res : tiremesh.mesh.MeshResolution
        From :func:`tiremesh.mesh.mesh_resolution`.

    Returns
    -------
    int
        ``n_patch (2 K + kc + 1) + (n_around - n_patch)(2 K + 1)`` for ``K`` bulge and
        ``kc`` contact segments.
    """
    k, kc = res.bulge_points, res.contact_points
    return res.n_patch * (2 * k + kc + 1) + (res.n_around - res.n_patch) * (2 * k + 1)


def _mesh_resolution(a: argparse.Namespace):
    """The checked resolution, refused before any work above ``--max-vertices``."""
    from .mesh import mesh_resolution

    try:
        res = mesh_resolution(a.around, a.patch_sections, a.bulge_points, a.contact_points)
    except InvalidParameter as exc:  # name the command-line option
        raise InvalidParameter(
            _MESH_OPTIONS.get(exc.name, exc.name), exc.value, exc.allowed
        ) from None
    n = mesh_vertex_count(res)
    if n > a.max_vertices:
        raise InvalidParameter(
            "mesh size",
            f"{n:,} vertices (--around {res.n_around}, --bulge-points {res.bulge_points}, "
            f"--contact-points {res.contact_points})",
            f"at most {a.max_vertices:,} vertices (--max-vertices); lower --around, "
            "--bulge-points or --contact-points",
        )
    return res


def _mesh_from_args(a: argparse.Namespace, res):
    from .mesh import build_mesh

    return build_mesh(
        case_from_args(a),
        n_around=res.n_around,
        n_patch=res.n_patch,
        bulge_points=res.bulge_points,
        contact_points=res.contact_points,
        close_rim=getattr(a, "close_rim", False),
    )


def _cmd_mesh(a: argparse.Namespace) -> int:
    from .export import LOSSY, check_mesh_path, export_mesh

    suffix = check_mesh_path(a.output, option="--output")
    res = _mesh_resolution(a)
    tire_mesh = _mesh_from_args(a, res)
    for path in export_mesh(tire_mesh, a.output, patch=not a.no_patch, surface=a.with_surface):
        _info(a, f"wrote {path}")
    _info(a, f"{len(tire_mesh.mesh.vertices)} vertices, {tire_mesh.n_faces} faces")
    if suffix in LOSSY:
        _warn(f"{suffix} {LOSSY[suffix]}; use .vtp, .ply or .glb to keep the scalars")
    return EXIT_OK


def _int_at_least(lo: int):
    def parse(text: str) -> int:
        try:
            n = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{text!r} is not an integer") from None
        if n < lo:
            raise argparse.ArgumentTypeError(f"{n} is invalid: allowed an integer >= {lo}")
        return n

    return parse


def _positive_seconds(text: str) -> float:
    try:
        t = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"{text!r} is not a number of seconds") from None
    if not (math.isfinite(t) and t > 0):
        raise argparse.ArgumentTypeError(f"{text} is invalid: allowed seconds > 0")
    return t


def _parse_size(text: str) -> tuple[int, int]:
    lo, hi = IMAGE_SIZE_RANGE
    allowed = f"WIDTHxHEIGHT in pixels, each {lo} .. {hi}, e.g. 1200x900"
    try:
        w, h = (int(t) for t in text.lower().split("x"))
    except ValueError:
        raise InvalidParameter("--image-size", text, allowed) from None
    if not (lo <= w <= hi and lo <= h <= hi):
        raise InvalidParameter("--image-size", text, allowed)
    return w, h


def _parse_camera(text: str) -> tuple[float, float, float]:
    allowed = "AZIMUTH,ELEVATION,ZOOM: degrees, degrees in -90 .. 90, a factor > 0; e.g. 30,20,1.2"
    try:
        az, el, zoom = (float(t) for t in text.split(","))
    except ValueError:
        raise InvalidParameter("--camera", text, allowed) from None
    if not (math.isfinite(az) and -90 <= el <= 90 and math.isfinite(zoom) and zoom > 0):
        raise InvalidParameter("--camera", text, allowed)
    return az, el, zoom


def _render_options(a: argparse.Namespace, render) -> dict:
    """The keyword options of ``render()`` the flags ask for (only those given)."""
    import inspect

    opts = {}
    if a.camera is not None:
        opts["camera"] = _parse_camera(a.camera)
    if a.background is not None:
        from .vtkscene import parse_colour

        opts["background"] = parse_colour(a.background, name="--background")
    if a.no_title:
        opts["title"] = False
    params = inspect.signature(render).parameters
    if opts and not {"title", "background"} <= set(params):
        flags = {"camera": "--camera", "background": "--background", "title": "--no-title"}
        raise InvalidParameter(
            " ".join(flags[k] for k in opts),
            "given",
            "not yet: this tiremesh.render.render() does not take these options",
        )
    return opts


def _cmd_render(a: argparse.Namespace) -> int:
    from . import render as render_module
    from .io import check_output_path

    scalars = {"radial": "radial_deformation", "lateral": "lateral_displacement"}.get(
        a.scalars, a.scalars
    )
    if a.view not in render_module.VIEWS:
        raise InvalidParameter("--view", a.view, " | ".join(render_module.VIEWS))
    if scalars not in render_module.SCALARS:
        allowed = "radial | lateral | " + " | ".join(render_module.SCALARS)
        raise InvalidParameter("--scalars", a.scalars, allowed)
    size = _parse_size(a.image_size)
    opts = _render_options(a, render_module.render)
    try:
        render_module.output_format(a.output)
    except InvalidParameter as exc:  # name the option
        raise InvalidParameter("--output", a.output, exc.allowed) from None
    check_output_path(a.output, option="--output")
    tire_mesh = _mesh_from_args(a, _mesh_resolution(a))
    render_module.render(tire_mesh, a.output, view=a.view, scalars=scalars, size=size, **opts)
    _info(a, f"wrote {a.output}")
    return EXIT_OK


def _cmd_section(a: argparse.Namespace) -> int:
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.backend_bases import FigureCanvasBase

    from .io import check_output_path, save_figure
    from .plot import plot_section

    suffix = Path(a.output).suffix.lower()
    formats = FigureCanvasBase.get_supported_filetypes()
    if suffix[1:] not in formats:
        raise InvalidParameter("--output", a.output, "a figure file: ." + ", .".join(formats))
    lo, hi = DPI_RANGE
    if not lo <= a.dpi <= hi:
        raise InvalidParameter("--dpi", a.dpi, f"an integer {lo} .. {hi} (dots per inch)")
    check_output_path(a.output, option="--output")
    ax = plot_section(case_from_args(a), math.radians(a.phi))
    ax.figure.tight_layout()
    save_figure(ax.figure, a.output, formats=(suffix,), dpi=a.dpi)
    _info(a, f"wrote {a.output}")
    return EXIT_OK


def _check_folder(path: str, option: str) -> None:
    """A folder for output files: created if missing, and writable."""
    from .io import check_output_path

    if Path(path).exists() and not Path(path).is_dir():
        raise InvalidParameter(option, path, "a folder (this is a file)")
    check_output_path(Path(path) / "probe", option=option)


def _cmd_sweep(a: argparse.Namespace) -> int:
    from .io import check_table_path, write_table
    from .parallel import connect_scheduler
    from .sweep import parse_grid, read_cases, run_sweep, sweep_plots

    if (a.grid is None) == (a.cases is None):
        raise InvalidParameter("--grid/--cases", "both" if a.grid else "neither", "exactly one")
    check_table_path(a.output, option="--output")
    if a.plots:
        _check_folder(a.plots, "--plots")
    cases = parse_grid(a.grid) if a.grid else read_cases(a.cases)
    client = None
    if a.scheduler:
        client = connect_scheduler(a.scheduler, timeout=a.scheduler_timeout)
    try:
        rows = run_sweep(cases, workers=a.workers, scheduler=client, progress=a.progress)
    finally:
        if client is not None:
            client.close()
    write_table(rows, a.output)
    n_err = sum(r.get("status") != "ok" for r in rows)
    _info(a, f"{len(rows)} cases, {n_err} errors; wrote {a.output}")
    if a.plots:
        for path in sweep_plots(rows, a.plots):
            _info(a, f"wrote {path}")
    if n_err:
        print(
            f"error: {n_err} of {len(rows)} cases failed; see the status and error "
            f"columns of {a.output}",
            file=sys.stderr,
        )
        return EXIT_FAILED_ROWS
    return EXIT_OK


def _add_solve(sub, common) -> None:
    p = sub.add_parser(
        "solve",
        parents=[common],
        help="solve one load case and print the contact patch and forces",
    )
    add_tire_options(p)
    out = p.add_mutually_exclusive_group()
    out.add_argument("--json", action="store_true", help="print the summary as JSON")
    out.add_argument("--csv", action="store_true", help="print the summary as one CSV row")
    p.add_argument(
        "--sections-csv",
        metavar="FILE",
        help="write per-section arrays to FILE (.csv|.json|.parquet)",
    )
    p.add_argument(
        "--outline-csv",
        metavar="FILE",
        help="write the patch outline to FILE (.csv|.json|.parquet)",
    )
    p.add_argument(
        "--footprint",
        default="rotta",
        metavar="KIND",
        help="'rotta' (default, the exact pointed patch) or 'rounded[:SPREAD_MM:THRESHOLD]': "
        "also print the ink print's rounded footprint (docs/model.md, beyond 7.3.1)",
    )
    lat = p.add_argument_group("lateral mechanics (sections 5.6 to 5.8)")
    lat.add_argument(
        "--relaxation", type=float, help="relaxation rate beyond the patch [1/mm], e.g. 0.993"
    )
    lat.add_argument(
        "--friction", type=float, default=math.inf, help="friction coefficient (default inf)"
    )
    p.set_defaults(func=_cmd_solve)


def _add_sweep(sub, common) -> None:
    p = sub.add_parser(
        "sweep", parents=[common], help="solve a grid or a CSV of cases into one table"
    )
    p.add_argument(
        "--grid", help='e.g. "tire=5,8 pressure_bar=2:11:10 load_N=304,500 camber_deg=10"'
    )
    p.add_argument("--cases", help="CSV of cases (columns as the --grid keys)")
    p.add_argument(
        "-o", "--output", required=True, help="sweep.csv | .json | .parquet (needs pyarrow)"
    )
    p.add_argument("--plots", metavar="DIR", help="stiffness and tangent-rule plots to DIR")
    p.add_argument(
        "--workers", type=_int_at_least(1), help="local processes for non-vectorizable cases"
    )
    p.add_argument("--scheduler", help="dask.distributed scheduler address, tcp://HOST:8786")
    p.add_argument(
        "--scheduler-timeout",
        type=_positive_seconds,
        default=DEFAULT_SCHEDULER_TIMEOUT,
        metavar="SECONDS",
        help=f"wait this long for the scheduler to answer (default {DEFAULT_SCHEDULER_TIMEOUT:g})",
    )
    p.add_argument(
        "--progress",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="progress bar on stderr (default: when stderr is a terminal)",
    )
    p.set_defaults(func=_cmd_sweep)


def _add_mesh(sub, common) -> None:
    p = sub.add_parser("mesh", parents=[common], help="build the deformed tire mesh and export it")
    add_tire_options(p)
    _mesh_options(p)
    p.add_argument(
        "-o",
        "--output",
        required=True,
        help="tire.vtp | .ply | .glb (keep the scalars) | .obj | .stl (geometry)",
    )
    p.add_argument("--close-rim", action="store_true", help="close the beads with a rim band")
    p.add_argument("--no-patch", action="store_true", help="do not write <stem>_patch.vtp")
    p.add_argument(
        "--with-surface",
        action="store_true",
        help="also export the ground, drum or disk (<stem>_surface.EXT; in a .glb, the same file)",
    )
    p.set_defaults(func=_cmd_mesh)


def _add_render(sub, common) -> None:
    p = sub.add_parser(
        "render", parents=[common], help="render the deformed tire to an image (off-screen)"
    )
    add_tire_options(p)
    _mesh_options(p)
    p.add_argument(
        "-o", "--output", required=True, help="view.png | .jpg | .tif | .pdf | .svg | .eps"
    )
    p.add_argument("--view", default="iso", help="iso | side | front | bottom (default iso)")
    p.add_argument(
        "--scalars",
        default="radial",
        help="colouring: radial, lateral or a name of tiremesh.render.SCALARS (default radial)",
    )
    p.add_argument("--image-size", default="1200x900", help="WIDTHxHEIGHT [px] (default 1200x900)")
    p.add_argument("--camera", metavar="AZ,EL,ZOOM", help="camera azimuth, elevation [deg], zoom")
    p.add_argument("--background", metavar="COLOUR", help="background colour (name or #hex)")
    p.add_argument("--no-title", action="store_true", help="no title (load case) on the image")
    p.set_defaults(func=_cmd_render)


def _add_section(sub, common) -> None:
    p = sub.add_parser(
        "section", parents=[common], help="plot one Rotta cross section (Figure 5-5)"
    )
    add_tire_options(p)
    p.add_argument("-o", "--output", required=True, help="section.png | .svg | .pdf")
    p.add_argument(
        "--phi", type=float, default=0.0, help="section angle from bottom dead centre [deg]"
    )
    lo, hi = DPI_RANGE
    p.add_argument("--dpi", type=int, default=150, help=f"raster resolution, {lo} .. {hi}")
    p.set_defaults(func=_cmd_section)


def _common_options() -> argparse.ArgumentParser:
    """``-q`` / ``-v`` for the program and every command (counted; not set unless given)."""
    p = argparse.ArgumentParser(add_help=False)
    g = p.add_argument_group("messages")
    g.add_argument(
        "-q", "--quiet", action="count", default=argparse.SUPPRESS, help="only results and errors"
    )
    g.add_argument(
        "-v",
        "--verbose",
        action="count",
        default=argparse.SUPPRESS,
        help="more detail (-vv: debug log; tracebacks of internal errors)",
    )
    return p


def _add_relations(sub, common) -> None:
    p = sub.add_parser(
        "relations",
        parents=[common],
        help="regenerate the closed-form relations fitted to dense model sweeps (8.2.2.1)",
    )
    p.add_argument("-o", "--output", required=True, metavar="DIR", help="output folder")
    p.add_argument(
        "--cases", type=_int_at_least(1000), default=100_000, help="cases swept (default 100000)"
    )
    p.add_argument("--seed", type=int, default=0, help="random seed of the sweep (default 0)")
    p.set_defaults(func=_cmd_relations)


def _cmd_relations(a: argparse.Namespace) -> int:
    from .relations import write_relations

    paths = write_relations(a.output, n_cases=a.cases, seed=a.seed)
    if _verbosity(a) >= 0:
        for path in paths:
            print(path)
    return EXIT_OK


def build_parser() -> argparse.ArgumentParser:
    """The ``tiremesh`` argument parser: subcommands solve, sweep, mesh, render, section,
    relations.

    Returns
    -------
    argparse.ArgumentParser
        Each subcommand sets ``func``, the handler :func:`main` calls; every one takes
        ``-q`` / ``-v``, the program ``--version``.
    """
    from . import __version__

    common = _common_options()
    parser = argparse.ArgumentParser(
        prog="tiremesh",
        parents=[common],
        description="Rotta model of a bicycle tire pressed on a surface (Dressel 2013, ch. 5).",
        epilog="exit status: 0 ok, 1 some sweep cases failed, 2 usage or input error, "
        "3 internal error",
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    for add in (_add_solve, _add_sweep, _add_mesh, _add_render, _add_section, _add_relations):
        add(sub, common)
    return parser


def _configure_messages(a: argparse.Namespace) -> None:
    import logging
    import warnings

    level = _verbosity(a)
    if level < 0:
        warnings.simplefilter("ignore")
    logging.basicConfig(
        level=logging.DEBUG if level > 1 else logging.INFO if level == 1 else logging.WARNING,
        format="%(levelname)s %(name)s: %(message)s",
    )


def _silence_stdout() -> None:
    """After a closed pipe (``| head``): no second error when Python flushes stdout."""
    import os

    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, sys.stdout.fileno())


def _error(message: str) -> None:
    print(f"error: {message}", file=sys.stderr)


def _run(a: argparse.Namespace) -> int:
    """Run the command, every failure a one-line message and an exit status."""
    try:
        return a.func(a)
    except TireModelError as exc:  # bad values, unwritable outputs, scheduler
        _error(str(exc))
    except BrokenPipeError:  # e.g. piped into `head`
        _silence_stdout()
        return EXIT_OK
    except OSError as exc:  # an input that cannot be read
        where = f"{exc.filename}: " if exc.filename else ""
        _error(f"{where}{exc.strerror or exc}")
    except MemoryError:
        _error("out of memory: lower the mesh resolution or the number of cases")
    except KeyboardInterrupt:
        _error("interrupted")
        return 130
    except Exception as exc:
        if _verbosity(a) > 0:
            import traceback

            traceback.print_exc()
        hint = "" if _verbosity(a) > 0 else "; rerun with -v for the traceback"
        _error(f"internal error {type(exc).__name__}: {exc} (a bug: please report it{hint})")
        return EXIT_INTERNAL
    return EXIT_USAGE


def main(argv: Sequence[str] | None = None) -> int:
    """Run the ``tiremesh`` command line.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments without the program name (default ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status: 0 all good (also when the output pipe closes early), 1 some sweep
        cases failed (their count on stderr), 2 a usage or input error (the message on
        stderr names the option and the accepted values, or the path and the reason),
        3 an internal error.
    """
    parser = build_parser()
    try:
        a = parser.parse_args(argv)
    except SystemExit as exc:  # usage error (2), --help or --version (0)
        return exc.code if isinstance(exc.code, int) else EXIT_USAGE
    _configure_messages(a)
    return _run(a)


if __name__ == "__main__":
    sys.exit(main())
