"""``inkprint`` command line: a thin layer over the library.

``inkprint analyze SCAN...`` prints a table (one row per print); ``inkprint batch
SRC -o results.csv`` runs a whole campaign; ``inkprint synth -o DIR`` writes the
synthetic sample set (or, with ``--mixed N``, a set mixing every failure class).

Conventions: ``--version``; ``-q`` (errors only) and ``-v`` (warnings and set-aside
marks per sheet; tracebacks of unexpected errors), before or after the command
(``inkprint -q batch ...`` = ``inkprint batch -q ...``); quantities carry their unit
(``--pressure 4bar|60psi|400kPa|0.4MPa``, ``--load 400N|40kg``: a bare number is
refused, it could mean anything); errors go to stderr, never as a traceback. Exit
status: 0 all good, 1 some files or prints failed (the count on stderr), 2 the
command could not run (bad arguments or options, an output that cannot be
written, a locked output, an unreachable scheduler), 3 an internal error (a bug).
"""

from __future__ import annotations

import argparse
import dataclasses
import gc
import re
import sys
from collections.abc import Sequence
from pathlib import Path

_NUMBER = re.compile(r"^\s*[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?\s*$")
PRESSURE_FORMS = "4bar, 60psi, 400kPa or 0.4MPa"
LOAD_FORMS = "400N or 40kg"


def _version() -> str:
    from . import __version__

    return f"inkprint {__version__}"


def _common() -> argparse.ArgumentParser:
    """``-q`` / ``-v`` for the program and every command (before or after it)."""
    p = argparse.ArgumentParser(add_help=False)
    v = p.add_argument_group("messages").add_mutually_exclusive_group()
    for flags, name, text in (
        (("-q", "--quiet"), "quiet", "errors only (no progress bar)"),
        (("-v", "--verbose"), "verbose", "warnings and marks set aside; tracebacks"),
    ):
        v.add_argument(
            *flags, dest=name, action="store_true", default=argparse.SUPPRESS, help=text
        )
    return p


def _positive_seconds(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = float("nan")
    if not value > 0 or value == float("inf"):
        raise argparse.ArgumentTypeError(f"{text!r}: a number of seconds > 0")
    return value


def _scale_options(p: argparse.ArgumentParser) -> None:
    g = p.add_argument_group("scale (default: the file's DPI metadata)")
    m = g.add_mutually_exclusive_group()
    m.add_argument("--dpi", type=float, help="scan resolution [dots per inch]")
    m.add_argument("--mm-per-px", type=float, help="scan scale [mm per pixel]")
    m.add_argument("--pixels", action="store_true", help="no scale: measure in pixels")
    m.add_argument(
        "--paper",
        metavar="SIZE",
        help="a photo of the whole sheet on a darker surface: rectify the page from its "
        "corners, the scale from its paper (A4, A3, A5, letter, legal or WxH in mm)",
    )
    g.add_argument(
        "--trust-dpi",
        action="store_true",
        help="accept 72 or 96 dpi metadata (camera / screen defaults, refused otherwise)",
    )
    g.add_argument("--pages", metavar="LIST", help="PDF pages, 0-based: e.g. 0,2-4 (default all)")
    t = p.add_argument_group("threshold and measure")
    t.add_argument("--method", choices=["otsu", "fixed", "sauvola"], default="otsu")
    t.add_argument("--threshold", type=float, help="grey level in (0, 1) for --method fixed")
    t.add_argument("--no-band", action="store_true", help="skip the threshold sensitivity band")
    t.add_argument(
        "--rolling-axis",
        choices=["auto", "x", "y"],
        default="auto",
        help="rolling direction on the sheet: x across the image, y up it, auto the "
        "print's longer axis (default; said in axis_source)",
    )
    p.add_argument("--overlay", metavar="DIR", help="write QA overlay PNGs to DIR")
    _threshold_options(p)


# judgement thresholds on the command line: (flag, AnalysisOptions field, metavar, help)
THRESHOLDS = (
    (
        "--group-mm",
        "group_mm",
        "MM",
        "tread elements closer than this are one print (replaces the footprint rule)",
    ),
    (
        "--group-distance",
        "group_distance_mm",
        "MM",
        "elements closer than this are always one print",
    ),
    (
        "--group-print-gap",
        "group_print_gap",
        "FRACTION",
        "parts side by side (car ribs) closer than this share of the footprint they "
        "make are one print; near it the print is flagged grouping_uncertain",
    ),
    (
        "--group-groove-max",
        "group_groove_max_mm",
        "MM",
        "no groove inside a print is wider: tread-pattern and side-by-side joins stop here",
    ),
    (
        "--min-patch-area",
        "min_patch_area_mm2",
        "MM2",
        "less ink than this is not a print (default: scales with the sheet)",
    ),
    ("--min-patch-width", "min_patch_width_mm", "MM", "narrower than this is a line, not a print"),
    ("--min-patch-length", "min_patch_length_mm", "MM", "shorter than this is a dot, not a print"),
    ("--speck-area", "speck_area_mm2", "MM2", "smaller ink blobs are specks (removed)"),
    (
        "--stroke-width",
        "stroke_width_mm",
        "MM",
        "marks thinner than this are pen, lines, gridlines",
    ),
    ("--edge-spot-area", "edge_spot_area_mm2", "MM2", "blobs this large form the print's core"),
    (
        "--edge-spot-faintness",
        "edge_spot_faintness",
        "FRACTION",
        "blobs outside the core lighter than this share of its darkness bore no load "
        "(0 keeps every blob; a tread-sized one left out flags the print faint_edge)",
    ),
    (
        "--edge-spot-distance",
        "edge_spot_distance_mm",
        "MM",
        "small blobs farther than this from the core bore no load",
    ),
    (
        "--edge-spot-pattern",
        "edge_spot_pattern_factor",
        "FACTOR",
        "small dark blobs within this many tread gaps of the print bear load (tip blocks)",
    ),
    (
        "--mark-overhang",
        "mark_overhang_mm",
        "MM",
        "thin ink reaching farther out of a print is a mark; a sliver along its edge no "
        "thicker than this is its own",
    ),
    (
        "--fine-element",
        "fine_element_mm",
        "MM",
        "separate ink elements no longer than this in a dense regular field are a fine "
        "tread (knurl, diamond file, dots), not dust or text (0: off)",
    ),
    (
        "--edge-mark",
        "edge_mark_mm",
        "MM",
        "a mark set aside along more of a print's outline than this flags it mark_on_edge",
    ),
    (
        "--edge-uncertainty",
        "edge_uncertainty",
        "FRACTION",
        "a line taken out along a print's edge that may hide more than this share of its "
        "length or width flags it mark_on_edge",
    ),
    (
        "--mark-pull",
        "mark_pull",
        "FRACTION",
        "a mark touching a print that may stretch it by more than this share flags it "
        "mark_on_edge",
    ),
    (
        "--grid-span",
        "grid_span",
        "FRACTION",
        "chart-paper gridlines run unbroken over at least this share of the sheet",
    ),
    (
        "--grid-ink-darker",
        "grid_ink_darker",
        "FRACTION",
        "a gridline pixel darker than this share of the lines' grey is print ink over "
        "the line (0: off)",
    ),
    (
        "--axis-tolerance",
        "axis_misaligned_deg",
        "DEG",
        "a print turned more than this from the given --rolling-axis is flagged axis_misaligned",
    ),
    ("--band", "sensitivity", "FRACTION", "relative threshold change of the band (0.1 = +-10 %%)"),
)


def _threshold_options(p: argparse.ArgumentParser) -> None:
    from .options import AnalysisOptions

    defaults = AnalysisOptions()
    g = p.add_argument_group("judgement thresholds (inkprint.AnalysisOptions)")
    for flag, name, metavar, text in THRESHOLDS:
        d = getattr(defaults, name)
        g.add_argument(
            flag,
            dest=name,
            type=float,
            metavar=metavar,
            help=f"{text}" + ("" if d is None else f" (default {d:g})"),
        )


def _pages(text: str | None):
    """'0,2-4' -> (0, 2, 3, 4); None / 'all' -> None."""
    from .errors import InvalidInput

    if text is None or text.strip().lower() == "all":
        return None
    out = []
    for part in text.split(","):
        m = re.fullmatch(r"\s*(\d+)\s*(?:-\s*(\d+)\s*)?", part)
        if not m or (m.group(2) and int(m.group(2)) < int(m.group(1))):
            raise InvalidInput("--pages", text, "0-based pages like 0,2-4, or all")
        out += range(int(m.group(1)), int(m.group(2) or m.group(1)) + 1)
    return tuple(out)


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
        trust_dpi=a.trust_dpi,
        paper=a.paper,
        method=a.method,
        threshold=a.threshold,
        sensitivity=not a.no_band,
        rolling_axis=a.rolling_axis,
        pages=_pages(a.pages),
        overlay_dir=a.overlay,
        analysis=_analysis_options(a),
    )


def quantity(text: str, *, kind: str, flag: str) -> float:
    """A pressure [N/mm^2] or load [N] given with its unit on the command line.

    Parameters
    ----------
    text : str
        E.g. '4bar', '60psi', '400kPa', '0.4MPa'; '400N', '40kg'.
    kind : {'pressure', 'load'}
    flag : str
        The option's name, for the message.

    Returns
    -------
    float
        [N/mm^2] for a pressure, [N] for a load; always > 0.

    Raises
    ------
    inkprint.InvalidInput
        A bare number (no unit), an unknown unit, or a value <= 0.
    """
    from tiremesh.errors import InvalidParameter
    from tiremesh.units import parse_force, parse_pressure

    from .errors import InvalidInput

    forms = PRESSURE_FORMS if kind == "pressure" else LOAD_FORMS
    if _NUMBER.match(text):
        raise InvalidInput(
            flag, text, f"a number with its unit, e.g. {forms} (a bare number is ambiguous)"
        )
    parse = parse_pressure if kind == "pressure" else parse_force
    try:
        value = parse(str(text), name=flag)
    except InvalidParameter as exc:
        raise InvalidInput(flag, text, f"a number with its unit, e.g. {forms}") from exc
    if not value > 0:
        raise InvalidInput(flag, text, f"> 0 (a {kind} must be positive)")
    return value


def _line(r: dict, unit: str) -> str:
    page = f" p{r['page']}" if str(r.get("page", "0")) not in ("0", "") else ""
    line = (
        f"{r['file']}{page} #{r['print']}: L {r[f'length_{unit}']:.2f} {unit}, "
        f"W {r[f'width_{unit}']:.2f} {unit}, gross {r[f'hull_area_{unit}2']:.1f} {unit}2, "
        f"net {r[f'area_{unit}2']:.1f} {unit}2 ({100 * r['net_to_gross']:.0f} %), ellipse "
        f"{r[f'ellipse_length_{unit}']:.2f} x {r[f'ellipse_width_{unit}']:.2f} {unit}, "
        f"axis {r['axis_source']}, {r['n_edge_spots']} edge spots"
    )
    pct = r.get("load_per_hull_area_pct")
    if pct is not None and pct == pct:
        line += f", load/area {r['load_per_hull_area_N_mm2']:.4f} N/mm2 ({pct:.1f} % of inflation)"
    if r.get("flags"):
        line += f"  [{r['flags']}]"
    return line


def _print_rows(rows: list[dict], a) -> None:
    unit = "px" if a.pixels else "mm"
    if a.json:
        import json

        print(json.dumps(rows, indent=1, default=str))
    elif a.csv:
        from tiremesh.io import table_columns

        from .csvsafe import write_rows

        write_rows(sys.stdout, rows, table_columns(rows))
    else:
        for r in rows:
            if r["status"] != "error":
                print(_line(r, unit))


def _report_problems(rows: list[dict], a) -> int:
    """Errors (always) and warnings (with -v) on stderr; the number of error rows."""
    errors = [r for r in rows if r.get("status") == "error"]
    for r in errors:
        page = f" page {r['page']}" if r.get("page") not in ("", None) else ""
        print(f"{r['file']}{page}: error: {r['error']}", file=sys.stderr)
    if a.verbose:
        seen = set()
        for r in rows:
            for w in str(r.get("warnings") or "").split("; "):
                if w and (r["file"], w) not in seen:
                    seen.add((r["file"], w))
                    print(f"{r['file']}: warning: {w}", file=sys.stderr)
            if r.get("set_aside") and (r["file"], "aside") not in seen:
                seen.add((r["file"], "aside"))
                print(f"{r['file']}: set aside {r['set_aside']}", file=sys.stderr)
    flagged = sum(1 for r in rows if r.get("status") == "flagged")
    if flagged and not a.quiet:
        print(f"{flagged} print(s) flagged (see the flags column; -v for why)", file=sys.stderr)
    return len(errors)


#: what an analysis imports on first use, in the order it does: warmed by
#: :func:`_warm_imports` while the first file is read and decoded (Pillow first
#: when a file is not a PNG: a plain PNG is read without it)
WARM_MODULES = (
    "cv2",
    "inkprint.analyze",
    "numpy.ma",
    "concurrent.futures",
    "shapely",
    "contactpatch",
)


def _warm_imports(pillow: bool):
    """Import :data:`WARM_MODULES` (``PIL.Image`` first with ``pillow``) in a
    background thread; the thread, to join.

    The main thread meanwhile reads, hashes and decodes the first file, in C code
    that releases the GIL (OpenCV's PNG decode alone takes 60 ms at 300 dpi), so
    these imports (30-50 ms; 130 ms without .pyc files) mostly cost no wall time.
    Started once the main thread's module-level imports are done: it then waits for
    a module the thread is importing only from a function, holding no import lock,
    so the two never wait on each other in a cycle. A failed import is left for the
    analysis to report.
    """
    import importlib
    import threading

    def run():
        for name in ("PIL.Image",) * pillow + WARM_MODULES:
            try:
                importlib.import_module(name)
                if name == "PIL.Image":
                    sys.modules[name].preinit()  # the format plugins Image.open loads
            except Exception:
                return

    t = threading.Thread(target=run, name="inkprint-warm-imports", daemon=True)
    t.start()
    return t


def _one_blas_thread() -> None:
    """One OpenBLAS thread for this process, unless the user chose a number.

    Only before numpy is first imported (OpenBLAS reads it when it loads). An
    analysis's linear algebra is on small matrices (one thread does it, the same
    numbers); the pool's idle threads spin on the cores the analysis uses: 50 ms
    of a 0.5 s ``inkprint analyze``.
    """
    import os

    if "numpy" not in sys.modules:
        os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")


def _no_collection_at_exit() -> None:
    """Freeze the garbage collector's objects when the process exits (once).

    At exit the interpreter clears every module and runs a last cyclic collection
    over all the objects the imports made (numpy, OpenCV, shapely, the analysis):
    30 ms of a 0.4 s ``inkprint analyze``, for memory the system frees anyway.
    :func:`gc.freeze`, run as an exit handler, leaves them to it; what is not
    in a cycle is still freed (and flushed) as before. The command line's own files
    are closed by then (``with`` blocks); a library call never registers this.
    """
    import atexit

    atexit.unregister(gc.freeze)  # once, however often main() runs in a process
    atexit.register(gc.freeze)


def _cmd_analyze(a) -> int:
    """``inkprint analyze``, the garbage collector paused until the first file is
    analysed.

    The imports (numpy, OpenCV, shapely, the analysis: 30 000 objects, made while
    the first file is read and decoded) and one analysis leave no cyclic garbage
    worth a pass, and every pass over those objects is lost time (10-25 ms of CPU
    of a 0.4 s run); the collector runs as usual from the second file on.
    """
    collecting = gc.isenabled()
    gc.disable()
    try:
        return _analyze_files(a, resume=collecting)
    finally:
        if collecting:
            gc.enable()


def _analyze_files(a, *, resume: bool) -> int:
    _one_blas_thread()
    from .batch import Job, process_file
    from .jobs import resolve_once
    from .read import read_file_bytes  # noqa: F401  (numpy, before the thread starts)

    warm = _warm_imports(pillow=not all(str(f).lower().endswith(".png") for f in a.scans))

    meta = {}
    if a.load is not None:
        meta["load_N"] = quantity(a.load, kind="load", flag="--load")
    if a.pressure is not None:
        from tiremesh.units import MPA_PER_BAR

        meta["pressure_bar"] = (
            quantity(a.pressure, kind="pressure", flag="--pressure") / MPA_PER_BAR
        )
    # one file after the other: each uses the cores for its prints
    opts = dataclasses.replace(_options(a), threads=None)
    if opts.overlay_dir:
        Path(opts.overlay_dir).mkdir(parents=True, exist_ok=True)
    rows = []
    for f in a.scans:
        real, err = resolve_once(f)
        job = Job(real or f, {(-1, -1): {"file": f, **meta}} if meta else {}, f, err)
        rows.extend(process_file(job, options=opts))
        if resume:
            gc.enable()
    warm.join()
    _print_rows(rows, a)
    n_err = _report_problems(rows, a)
    if n_err:
        print(f"{n_err} of {len(a.scans)} file(s) or page(s) failed", file=sys.stderr)
    return 1 if n_err else 0


REPORT_COLUMNS = ("pressure_bar", "load_N")


def _reportable(rows: list[dict]) -> tuple[list[dict], list[str]]:
    """Rows the model can be paired with, and the names of the ok prints left out
    (no manifest row with a tire, pressure_bar and load_N)."""
    ok, missing = [], []
    for r in rows:
        if r.get("status") != "ok":
            continue
        has_tire = any(
            str(r.get(k) or "").strip()
            for k in ("tire", "tire_id", "arc_length_mm", "tire_radius_mm")
        )
        if has_tire and all(str(r.get(k) or "").strip() for k in REPORT_COLUMNS):
            ok.append(r)
        else:
            missing.append(f"{r.get('file')}#{r.get('print')}")
    return ok, missing


def _prework(a):
    """The report's manifest-only parts (model, renders, 3D view, validation), started
    in worker processes before the scans are analysed; None when the manifest cannot
    be read here (the batch then says why)."""
    from contactpatch.study.prework import Prework

    from .csvsafe import read_csv

    try:
        rows = read_csv(a.manifest)
    except Exception:  # run_batch reports the manifest's problem
        return None
    return Prework(rows, renders=not a.no_renders) if rows else None


def _report(res, a, pre=None) -> int:
    from contactpatch import build_report

    rows, missing = _reportable(res.rows)
    if missing:
        print(
            f"report: {len(missing)} print(s) without a manifest row giving the tire, "
            f"pressure_bar and load_N are left out: {', '.join(missing[:10])}"
            + (" ..." if len(missing) > 10 else ""),
            file=sys.stderr,
        )
    if not rows:
        print(
            "error: --report: no print has a manifest row to pair with the model", file=sys.stderr
        )
        return 1
    index = build_report(
        rows,
        a.report,
        renders=not a.no_renders,
        source=str(res.outputs[0]),
        precomputed=pre,
    )
    if not a.quiet:
        print(f"wrote the report: {index}")
    from contactpatch.study.cli import report_errors

    n_err = report_errors(index)
    if n_err:
        print(
            f"report: {n_err} of {len(rows)} print(s) not paired with the model", file=sys.stderr
        )
        return 1
    return 0


def _cmd_batch(a) -> int:
    from .errors import InvalidInput

    if a.report and not a.manifest:
        raise InvalidInput(
            "--report",
            a.report,
            "with --manifest: the report pairs each print with the model, which needs the "
            "tire, pressure_bar, load_N and surface of every print",
        )
    pre = _prework(a) if a.report else None
    try:
        status = _batch_and_report(a, pre)
    finally:
        if pre is not None:
            pre.cancel()  # a failed batch or report: no worker left running
    return status


def _batch_and_report(a, pre) -> int:
    from .batch import run_batch

    res = run_batch(
        a.src,
        a.output,
        manifest=a.manifest,
        options=_options(a),
        workers=a.workers,
        scheduler=a.scheduler,
        scheduler_timeout=a.scheduler_timeout,
        resume=not a.no_resume,
        retry_errors=a.retry_errors,
        progress=not a.quiet,
        allow_outside=a.allow_outside,
    )
    n_ok = sum(1 for r in res.rows if r.get("status") == "ok")
    n_flagged = sum(1 for r in res.rows if r.get("status") == "flagged")
    if not a.quiet:
        print(
            f"{res.n_files} files ({res.n_skipped} already done), {n_ok + n_flagged} prints "
            f"({n_ok} ok, {n_flagged} flagged), {res.n_errors} errors"
        )
        for path in res.outputs:
            print(f"wrote {path}")
    _report_problems(res.rows, a)
    status = 0
    if res.n_errors:
        print(f"{res.n_errors} error row(s) in {res.outputs[0]}", file=sys.stderr)
        status = 1
    if a.report:
        status = max(status, _report(res, a, pre))
    return status


def _cmd_synth(a) -> int:
    if a.mixed:
        from .synth_cases import make_mixed_set

        manifest, truth = make_mixed_set(a.output, n_files=a.mixed, seed=a.seed)
        if not a.quiet:
            print(f"wrote {manifest}, {truth} and {a.mixed} files")
        return 0
    from .synth import make_sample_set

    path = make_sample_set(a.output, dpi=a.dpi)
    if not a.quiet:
        print(f"wrote {path} and its scans")
    return 0


def _analyze_parser(p: argparse.ArgumentParser) -> None:
    p.add_argument("scans", nargs="+", help="PNG, JPEG, TIFF or PDF files")
    _scale_options(p)
    p.add_argument("--load", help=f"vertical load with its unit: {LOAD_FORMS}")
    p.add_argument("--pressure", help=f"inflation pressure with its unit: {PRESSURE_FORMS}")
    out = p.add_mutually_exclusive_group()
    out.add_argument("--csv", action="store_true", help="CSV on stdout (spreadsheet-safe)")
    out.add_argument("--json", action="store_true")
    p.set_defaults(func=_cmd_analyze)


def _batch_parser(p: argparse.ArgumentParser) -> None:
    from tiremesh.parallel import DEFAULT_SCHEDULER_TIMEOUT

    p.add_argument(
        "src", nargs="?", help="folder, glob pattern or file (optional with --manifest)"
    )
    p.add_argument(
        "-o",
        "--output",
        required=True,
        help="the table, its format by extension: results.csv (a .json twin is written "
        "too), results.json or results.parquet (needs pyarrow); other extensions are "
        "refused before any work; a re-run resumes from it in the same format",
    )
    p.add_argument(
        "--manifest",
        help="CSV: file, [page], [print], tire, pressure_bar, load_N, surface, [dpi], "
        "[rolling_axis], [group_mm]",
    )
    p.add_argument(
        "--allow-outside", action="store_true", help="read manifest files outside its folder"
    )
    p.add_argument(
        "--workers", type=int, help="local worker processes (default: the idle cores, at least 1)"
    )
    p.add_argument("--scheduler", help="dask.distributed scheduler address, e.g. tcp://host:8786")
    p.add_argument(
        "--scheduler-timeout",
        type=_positive_seconds,
        default=DEFAULT_SCHEDULER_TIMEOUT,
        metavar="SECONDS",
        help="wait this long for the scheduler to accept and answer, checked before any "
        f"work (default {DEFAULT_SCHEDULER_TIMEOUT:g})",
    )
    p.add_argument("--no-resume", action="store_true", help="ignore rows already in the output")
    p.add_argument(
        "--retry-errors", action="store_true", help="analyse files that failed before again"
    )
    p.add_argument(
        "--report", metavar="DIR", help="also write the model-vs-print report (needs --manifest)"
    )
    p.add_argument("--no-renders", action="store_true", help="report without the 3D renders")
    _scale_options(p)
    p.set_defaults(func=_cmd_batch)


def _synth_parser(p: argparse.ArgumentParser) -> None:
    p.add_argument("-o", "--output", required=True, help="folder")
    p.add_argument("--dpi", type=float, default=150.0, help="sample set resolution")
    p.add_argument(
        "--mixed", type=int, metavar="N", help="instead: N files mixing every failure class"
    )
    p.add_argument("--seed", type=int, default=0, help="seed of --mixed")
    p.set_defaults(func=_cmd_synth)


#: the commands: (name, the function adding its options, its help)
COMMANDS = (
    ("analyze", _analyze_parser, "measure the prints on one or more scans"),
    ("batch", _batch_parser, "analyse a folder, glob or manifest of scans into one table"),
    ("synth", _synth_parser, "write synthetic scans with their manifest and truth"),
)


def _command(argv: Sequence[str] | None) -> str | None:
    """The command a command line names: its first word that is no option (the
    program's own options, -q, -v, -h and --version, take no value); None if none."""
    args = sys.argv[1:] if argv is None else argv
    return next((str(w) for w in args if not str(w).startswith("-")), None)


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The ``inkprint`` argument parser (subcommands analyze, batch, synth).

    Parameters
    ----------
    command : str, optional
        Give only this command its options (the others are listed, without theirs):
        a run builds what it parses, not every command's options and imports (the
        batch's scheduler module). Default, or a name that is no command: every
        command.

    Returns
    -------
    argparse.ArgumentParser
    """
    common = _common()
    parser = argparse.ArgumentParser(
        prog="inkprint",
        parents=[common],
        description="Ink prints of tire contact patches (Dressel 2013, 4.1.1).",
        epilog="exit status: 0 ok, 1 some files or prints failed (count on stderr), "
        "2 usage, input or output error, 3 internal error",
    )
    parser.add_argument("--version", action="version", version=_version())
    sub = parser.add_subparsers(dest="command", required=True)
    every = command not in {name for name, _, _ in COMMANDS}
    for name, fill, text in COMMANDS:
        p = sub.add_parser(name, parents=[common], help=text)
        if every or name == command:
            fill(p)
    return parser


def _fail(message: str, a=None, code: int = 2) -> int:
    print(f"error: {message}", file=sys.stderr)
    if a is not None and getattr(a, "verbose", False):
        import traceback

        traceback.print_exc()
    return code


def main(argv: Sequence[str] | None = None) -> int:
    """Run the ``inkprint`` command line.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments without the program name (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status: 0 all good, 1 some files or prints failed (the count on
        stderr), 2 the command could not run (argparse's own usage errors exit 2
        too, as ``SystemExit``), 3 an internal error.
    """
    from tiremesh.errors import TireModelError

    from .allocator import keep_freed_memory
    from .errors import InkPrintError

    keep_freed_memory()  # this process analyses sheets: reuse freed image buffers
    _no_collection_at_exit()
    a = build_parser(_command(argv)).parse_args(argv)
    a.quiet = getattr(a, "quiet", False)  # -q / -v before or after the command
    a.verbose = getattr(a, "verbose", False)
    if a.quiet and a.verbose:
        return _fail("-q and -v exclude each other")
    try:
        return a.func(a)
    except (InkPrintError, TireModelError, ValueError) as exc:
        return _fail(str(exc), a)
    except BrokenPipeError:
        sys.stderr.close()
        return 0
    except OSError as exc:
        where = exc.filename or ""
        why = exc.strerror or str(exc)
        return _fail(f"cannot write or read {where}: {why}" if where else why, a)
    except KeyboardInterrupt:
        return _fail("interrupted", None, 130)
    except Exception as exc:  # never a traceback for the user; -v shows it
        return _fail(f"unexpected {type(exc).__name__}: {exc} (run with -v for details)", a, 3)


if __name__ == "__main__":
    sys.exit(main())
