"""``tiremesh`` command line: a thin layer over the library.

Units at this edge carry their names: ``--pressure 4bar`` / ``60psi`` / ``400kPa``,
``--load 400N`` / ``40kg``, angles in degrees, lengths in mm.
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

import numpy as np

from .case import SLIP_KINEMATICS, LoadCase
from .catalog import get_tire
from .errors import InvalidParameter, TireModelError
from .geometry import TireGeometry
from .units import parse_force, parse_length, parse_pressure


def add_tire_options(p: argparse.ArgumentParser) -> None:
    """Tire and load-case options shared by every subcommand that solves the model."""
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
        "--pressure", required=True, help="inflation pressure, e.g. 4bar, 60psi, 400kPa"
    )
    m = c.add_mutually_exclusive_group(required=True)
    m.add_argument("--load", help="vertical load, e.g. 400N or 40kg")
    m.add_argument("--deflection", help="wheel deflection in the wheel plane [mm]")
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
        help="how a slip angle displaces the tread: undisplaced at the leading edge "
        "(default) or turned about the patch centre (Appendix C)",
    )
    c.add_argument(
        "--sections", type=int, default=201, help="sections along the patch (default 201)"
    )


def tire_from_args(a: argparse.Namespace) -> TireGeometry:
    rim = None if a.rim_width is None else parse_length(a.rim_width, name="--rim-width")
    bead = parse_length(a.bead_seat, name="--bead-seat")
    given = [x for x in (a.tire, a.size, a.arc_length) if x is not None]
    if len(given) != 1:
        raise SystemExit("error: give exactly one of --tire, --size, --arc-length")
    if a.tire is not None:
        return get_tire(a.tire, rim_width=rim)
    if rim is None:
        raise SystemExit("error: --rim-width is required with --size or --arc-length")
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
    """
    load = None if a.load is None else parse_force(a.load, name="--load")
    deflection = None if a.deflection is None else parse_length(a.deflection, name="--deflection")
    relaxation = getattr(a, "relaxation", None)
    return LoadCase(
        tire_from_args(a),
        pressure=parse_pressure(a.pressure, name="--pressure"),
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
    )


def solve_from_args(a: argparse.Namespace):
    """Solve the load case the options describe; returns a ContactPatch."""
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


def _csv(rows: list[dict]) -> str:
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=list(rows[0]), lineterminator="\n")
    w.writeheader()
    w.writerows(rows)
    return buf.getvalue()


def _section_rows(patch) -> list[dict]:
    """Per-section arrays of a patch as table rows (unit-carrying names)."""
    sec = patch.sections
    cols = {
        "phi_rad": patch.phi,
        "x_mm": patch.x,
        "edge1_mm": sec.edge1,
        "edge2_mm": sec.edge2,
        "width_mm": sec.edge2 - sec.edge1,
        "radius1_mm": sec.radius1,
        "radius2_mm": sec.radius2,
        "dv_mm": sec.vert_deflection,
        "dh_mm": sec.horz_deflection,
        "dS_N_per_mm": patch.lateral_force_density,
        "dN_N_per_mm": patch.vertical_force_density,
    }
    n = len(patch.phi)
    return [{k: float(np.broadcast_to(v, (n,))[i]) for k, v in cols.items()} for i in range(n)]


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
    if patch.slip and not extra:
        print(_slip_note(patch.case))


def _cmd_solve(a: argparse.Namespace) -> int:
    from .io import write_text_atomic
    from .lateral import solve_lateral
    from .solver import solve

    case = case_from_args(a)
    if a.relaxation is not None or math.isfinite(a.friction):
        result = solve_lateral(case)
        patch, extra = result.patch, _lateral_summary(result)
    else:
        patch, extra = solve(case), {}
    summary = {**patch.summary(), **extra}
    _print_summary(a, patch, summary, extra)
    if a.sections_csv:
        write_text_atomic(a.sections_csv, _csv(_section_rows(patch)))
    if a.outline_csv:
        rows = [{"x_mm": float(x), "y_mm": float(y)} for x, y in patch.outline]
        write_text_atomic(a.outline_csv, _csv(rows))
    return 0


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


def _mesh_from_args(a: argparse.Namespace):
    from .mesh import build_mesh

    return build_mesh(
        case_from_args(a),
        n_around=a.around,
        n_patch=a.patch_sections,
        bulge_points=a.bulge_points,
        contact_points=a.contact_points,
        close_rim=getattr(a, "close_rim", False),
    )


def _cmd_mesh(a: argparse.Namespace) -> int:
    from .export import export_mesh

    tire_mesh = _mesh_from_args(a)
    for path in export_mesh(tire_mesh, a.output, patch=not a.no_patch):
        print(f"wrote {path}")
    print(f"{len(tire_mesh.mesh.vertices)} vertices, {tire_mesh.n_faces} faces")
    return 0


def _parse_size(text: str) -> tuple[int, int]:
    try:
        w, h = (int(t) for t in text.lower().split("x"))
    except ValueError as exc:
        raise InvalidParameter(
            "--image-size", text, "WIDTHxHEIGHT in pixels, e.g. 1200x900"
        ) from exc
    return w, h


def _cmd_render(a: argparse.Namespace) -> int:
    from .render import render

    size = _parse_size(a.image_size)
    tire_mesh = _mesh_from_args(a)
    scalars = {"radial": "radial_deformation", "lateral": "lateral_displacement"}.get(
        a.scalars, a.scalars
    )
    render(tire_mesh, a.output, view=a.view, scalars=scalars, size=size)
    print(f"wrote {a.output}")
    return 0


def _cmd_section(a: argparse.Namespace) -> int:
    import matplotlib

    matplotlib.use("Agg")
    from matplotlib.backend_bases import FigureCanvasBase

    from .io import save_figure
    from .plot import plot_section

    suffix = Path(a.output).suffix.lower()
    formats = FigureCanvasBase.get_supported_filetypes()
    if suffix[1:] not in formats:
        raise InvalidParameter("--output", a.output, "a figure file: ." + ", .".join(formats))
    ax = plot_section(case_from_args(a), math.radians(a.phi))
    ax.figure.tight_layout()
    save_figure(ax.figure, a.output, formats=(suffix,), dpi=a.dpi)
    print(f"wrote {a.output}")
    return 0


def _cmd_sweep(a: argparse.Namespace) -> int:
    from .io import TABLE_FORMATS, write_table
    from .sweep import parse_grid, read_cases, run_sweep, sweep_plots

    if (a.grid is None) == (a.cases is None):
        raise SystemExit("error: give exactly one of --grid and --cases")
    if Path(a.output).suffix.lower() not in TABLE_FORMATS:
        raise InvalidParameter("--output", a.output, "a .csv or .json file")
    cases = parse_grid(a.grid) if a.grid else read_cases(a.cases)
    rows = run_sweep(cases, workers=a.workers, scheduler=a.scheduler, progress=a.progress)
    write_table(rows, a.output)
    n_err = sum(r.get("status") != "ok" for r in rows)
    print(f"{len(rows)} cases, {n_err} errors; wrote {a.output}")
    if a.plots:
        for path in sweep_plots(rows, a.plots):
            print(f"wrote {path}")
    return 0


def _add_solve(sub) -> None:
    p = sub.add_parser("solve", help="solve one load case and print the contact patch and forces")
    add_tire_options(p)
    out = p.add_mutually_exclusive_group()
    out.add_argument("--json", action="store_true", help="print the summary as JSON")
    out.add_argument("--csv", action="store_true", help="print the summary as one CSV row")
    p.add_argument("--sections-csv", metavar="FILE", help="write per-section arrays to FILE")
    p.add_argument("--outline-csv", metavar="FILE", help="write the patch outline polygon to FILE")
    lat = p.add_argument_group("lateral mechanics (sections 5.6 to 5.8)")
    lat.add_argument(
        "--relaxation", type=float, help="relaxation rate beyond the patch [1/mm], e.g. 0.993"
    )
    lat.add_argument(
        "--friction", type=float, default=math.inf, help="friction coefficient (default inf)"
    )
    p.set_defaults(func=_cmd_solve)


def _add_sweep(sub) -> None:
    p = sub.add_parser("sweep", help="solve a grid or a CSV of cases into one table")
    p.add_argument(
        "--grid", help='e.g. "tire=5,8 pressure_bar=2:11:10 load_N=304,500 camber_deg=10"'
    )
    p.add_argument("--cases", help="CSV of cases (columns as the --grid keys)")
    p.add_argument("-o", "--output", required=True, help="sweep.csv | sweep.json")
    p.add_argument("--plots", metavar="DIR", help="stiffness and tangent-rule plots to DIR")
    p.add_argument("--workers", type=int, help="local processes for non-vectorizable cases")
    p.add_argument("--scheduler", help="dask.distributed scheduler address")
    p.add_argument("--progress", action="store_true", help="show a progress bar (stderr)")
    p.set_defaults(func=_cmd_sweep)


def _add_mesh(sub) -> None:
    p = sub.add_parser("mesh", help="build the deformed tire mesh and export it")
    add_tire_options(p)
    _mesh_options(p)
    p.add_argument("-o", "--output", required=True, help="tire.vtp | .ply | .stl | .obj | .glb")
    p.add_argument("--close-rim", action="store_true", help="close the beads with a rim band")
    p.add_argument("--no-patch", action="store_true", help="do not write <stem>_patch.vtp")
    p.set_defaults(func=_cmd_mesh)


def _add_render(sub) -> None:
    p = sub.add_parser("render", help="render the deformed tire to PNG (off-screen)")
    add_tire_options(p)
    _mesh_options(p)
    p.add_argument("-o", "--output", required=True, help="view.png")
    p.add_argument("--view", choices=["iso", "side", "front", "bottom"], default="iso")
    p.add_argument("--scalars", default="radial", help="radial | lateral | contact | section")
    p.add_argument("--image-size", default="1200x900", help="WIDTHxHEIGHT [px] (default 1200x900)")
    p.set_defaults(func=_cmd_render)


def _add_section(sub) -> None:
    p = sub.add_parser("section", help="plot one Rotta cross section (Figure 5-5)")
    add_tire_options(p)
    p.add_argument("-o", "--output", required=True, help="section.png | .svg | .pdf")
    p.add_argument(
        "--phi", type=float, default=0.0, help="section angle from bottom dead centre [deg]"
    )
    p.add_argument("--dpi", type=int, default=150)
    p.set_defaults(func=_cmd_section)


def build_parser() -> argparse.ArgumentParser:
    """The ``tiremesh`` argument parser: subcommands solve, sweep, mesh, render, section."""
    parser = argparse.ArgumentParser(
        prog="tiremesh",
        description="Rotta model of a bicycle tire pressed on a surface (Dressel 2013, ch. 5).",
    )
    sub = parser.add_subparsers(dest="command", required=True)
    for add in (_add_solve, _add_sweep, _add_mesh, _add_render, _add_section):
        add(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    a = parser.parse_args(argv)
    try:
        return a.func(a)
    except TireModelError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # e.g. piped into `head`
        sys.stderr.close()
        return 0


if __name__ == "__main__":
    sys.exit(main())
