"""``inkprint`` command line: a thin layer over the library.

``inkprint analyze SCAN...`` prints a table (one row per print); ``inkprint batch
SRC -o results.csv`` runs a whole campaign; ``inkprint synth -o DIR`` writes the
synthetic sample set.
"""

from __future__ import annotations

import argparse
import csv
import io
import json
import sys
from collections.abc import Sequence
from pathlib import Path

from .errors import InkPrintError


def _scale_options(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("scale (default: the file's DPI metadata)")
    m = g.add_mutually_exclusive_group()
    m.add_argument("--dpi", type=float, help="scan resolution [dots per inch]")
    m.add_argument("--mm-per-px", type=float, help="scan scale [mm per pixel]")
    m.add_argument("--pixels", action="store_true", help="no scale: measure in pixels")
    t = p.add_argument_group("threshold")
    t.add_argument("--method", choices=["otsu", "fixed", "sauvola"], default="otsu")
    t.add_argument("--threshold", type=float, help="grey level in (0, 1) for --method fixed")
    t.add_argument("--no-band", action="store_true", help="skip the threshold sensitivity band")
    p.add_argument("--overlay", metavar="DIR", help="write QA overlay PNGs to DIR")
    _threshold_options(p)


# judgement thresholds on the command line: (flag, AnalysisOptions field, metavar, help)
THRESHOLDS = (
    ("--group-distance", "group_distance_mm", "MM", "blobs closer than this form one print"),
    ("--min-patch-area", "min_patch_area_mm2", "MM2", "less ink than this is not a print"),
    ("--min-patch-width", "min_patch_width_mm", "MM", "narrower than this is a line, not a print"),
    ("--speck-area", "speck_area_mm2", "MM2", "smaller ink blobs are specks (removed)"),
    ("--edge-spot-area", "edge_spot_area_mm2", "MM2", "blobs this large form the print's core"),
    (
        "--edge-spot-distance",
        "edge_spot_distance_mm",
        "MM",
        "small blobs farther than this from the core bore no load",
    ),
    ("--band", "sensitivity", "FRACTION", "relative threshold change of the band (0.1 = +-10 %%)"),
)


def _threshold_options(p: argparse.ArgumentParser) -> None:
    from .options import AnalysisOptions

    defaults = AnalysisOptions()
    g = p.add_argument_group("judgement thresholds (inkprint.AnalysisOptions)")
    for flag, name, metavar, text in THRESHOLDS:
        g.add_argument(
            flag,
            dest=name,
            type=float,
            metavar=metavar,
            help=f"{text} (default {getattr(defaults, name):g})",
        )


def _analysis_options(a):
    """AnalysisOptions from the threshold flags given (the rest at their defaults)."""
    from .options import AnalysisOptions

    given = {name: getattr(a, name) for _, name, _, _ in THRESHOLDS}
    return AnalysisOptions(**{k: v for k, v in given.items() if v is not None})


def _options(a):
    from .batch import Options

    return Options(
        dpi=a.dpi,
        mm_per_px=a.mm_per_px,
        allow_pixels=a.pixels,
        method=a.method,
        threshold=a.threshold,
        sensitivity=not a.no_band,
        overlay_dir=a.overlay,
        analysis=_analysis_options(a),
    )


SUMMARY = [
    "file",
    "print",
    "status",
    "length_mm",
    "width_mm",
    "hull_area_mm2",
    "area_mm2",
    "net_to_gross",
    "ellipse_length_mm",
    "ellipse_width_mm",
    "angle_deg",
    "n_edge_spots",
    "load_per_hull_area_pct",
    "error",
]


def _cmd_analyze(a) -> int:
    from tiremesh.io import table_columns
    from tiremesh.units import MPA_PER_BAR, parse_force, parse_pressure

    from .batch import Job, process_file

    meta = {}
    if a.load is not None:
        meta["load_N"] = parse_force(a.load, name="--load")
    if a.pressure is not None:
        meta["pressure_bar"] = parse_pressure(a.pressure, name="--pressure") / MPA_PER_BAR
    opts = _options(a)
    if opts.overlay_dir:
        Path(opts.overlay_dir).mkdir(parents=True, exist_ok=True)
    rows = []
    for f in a.scans:
        job = Job(f, {-1: {"file": f, **meta}} if meta else {})
        rows.extend(process_file(job, options=opts))
    if a.json:
        print(json.dumps(rows, indent=1, default=str))
    elif a.csv:
        buf = io.StringIO()
        cols = table_columns(rows)
        w = csv.DictWriter(buf, fieldnames=cols, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
        print(buf.getvalue(), end="")
    else:
        unit = "px" if a.pixels else "mm"
        for r in rows:
            if r["status"] != "ok":
                print(f"{r['file']}: error: {r['error']}")
                continue
            line = (
                f"{r['file']} #{r['print']}: L {r[f'length_{unit}']:.2f} {unit}, W {r[f'width_{unit}']:.2f} {unit}, "
                f"gross {r[f'hull_area_{unit}2']:.1f} {unit}2, net {r[f'area_{unit}2']:.1f} {unit}2 "
                f"({100 * r['net_to_gross']:.0f} %), ellipse {r[f'ellipse_length_{unit}']:.2f} x "
                f"{r[f'ellipse_width_{unit}']:.2f} {unit}, {r['n_edge_spots']} edge spots"
            )
            pct = r.get("load_per_hull_area_pct")
            if pct is not None and pct == pct:
                line += f", load/area {r['load_per_hull_area_N_mm2']:.4f} N/mm2 ({pct:.1f} % of inflation)"
            print(line)
    return 2 if any(r["status"] != "ok" for r in rows) else 0


def _cmd_batch(a) -> int:
    from .batch import run_batch

    res = run_batch(
        a.src,
        a.output,
        manifest=a.manifest,
        options=_options(a),
        workers=a.workers,
        scheduler=a.scheduler,
        resume=not a.no_resume,
        retry_errors=a.retry_errors,
        progress=not a.quiet,
    )
    n_ok = sum(1 for r in res.rows if r.get("status") == "ok")
    print(
        f"{res.n_files} files ({res.n_skipped} already done), {n_ok} prints, {res.n_errors} errors"
    )
    for path in res.outputs:
        print(f"wrote {path}")
    if a.report:
        from contactpatch import build_report

        index = build_report(
            res.rows, a.report, renders=not a.no_renders, source=str(res.outputs[0])
        )
        print(f"wrote the report: {index}")
    return 0


def _cmd_synth(a) -> int:
    from .synth import make_sample_set

    path = make_sample_set(a.output, dpi=a.dpi)
    print(f"wrote {path} and its scans")
    return 0


def build_parser() -> argparse.ArgumentParser:
    """The ``inkprint`` argument parser (subcommands analyze, batch, synth).

    Returns
    -------
    argparse.ArgumentParser
    """
    parser = argparse.ArgumentParser(
        prog="inkprint", description="Ink prints of tire contact patches (Dressel 2013, 4.1.1)."
    )
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("analyze", help="measure the prints on one or more scans")
    p.add_argument("scans", nargs="+", help="PNG, JPEG, TIFF or PDF files")
    _scale_options(p)
    p.add_argument("--load", help="vertical load, e.g. 304N or 31kg (load / area vs pressure)")
    p.add_argument("--pressure", help="inflation pressure, e.g. 100psi or 6.9bar")
    out = p.add_mutually_exclusive_group()
    out.add_argument("--csv", action="store_true")
    out.add_argument("--json", action="store_true")
    p.set_defaults(func=_cmd_analyze)

    p = sub.add_parser("batch", help="analyse a folder, glob or manifest of scans into one table")
    p.add_argument(
        "src", nargs="?", help="folder, glob pattern or file (optional with --manifest)"
    )
    p.add_argument(
        "-o", "--output", required=True, help="results.csv (a .json twin is written too)"
    )
    p.add_argument(
        "--manifest", help="CSV: file, [print], tire, pressure_bar, load_N, surface, [dpi]"
    )
    p.add_argument("--workers", type=int, help="local worker processes (default: all cores)")
    p.add_argument("--scheduler", help="dask.distributed scheduler address, e.g. tcp://host:8786")
    p.add_argument("--no-resume", action="store_true", help="ignore rows already in the output")
    p.add_argument(
        "--retry-errors", action="store_true", help="analyse files that failed before again"
    )
    p.add_argument("--quiet", action="store_true", help="no progress bar")
    p.add_argument("--report", metavar="DIR", help="also write the model-vs-print report to DIR")
    p.add_argument("--no-renders", action="store_true", help="report without the 3D renders")
    _scale_options(p)
    p.set_defaults(func=_cmd_batch)

    p = sub.add_parser("synth", help="write the synthetic sample scans, manifest and truth")
    p.add_argument("-o", "--output", required=True, help="folder")
    p.add_argument("--dpi", type=float, default=150.0)
    p.set_defaults(func=_cmd_synth)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the ``inkprint`` command line.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments without the program name (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status: 0 on success, 2 on an error (or a file that failed in
        ``analyze``).
    """
    a = build_parser().parse_args(argv)
    try:
        return a.func(a)
    except (InkPrintError, ValueError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    except BrokenPipeError:
        sys.stderr.close()
        return 0


if __name__ == "__main__":
    sys.exit(main())
