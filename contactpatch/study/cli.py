"""The study's commands: ``contactpatch compare``, ``contactpatch report`` and
``contactpatch validate``."""

from __future__ import annotations

import argparse
import json
import sys
from collections.abc import Sequence
from pathlib import Path

from tiremesh.errors import TireModelError
from tiremesh.io import check_output_path, check_table_path, read_table, table_columns, write_table

from ..errors import ContactPatchError

EXIT_OK, EXIT_SOME_FAILED, EXIT_USAGE, EXIT_INTERNAL = 0, 1, 2, 3


def compare_command(a: argparse.Namespace) -> int:
    """Pair a print table with the model and write the paired table.

    Parameters
    ----------
    a : argparse.Namespace
        ``prints`` (input table path), ``output`` (.csv or .json path).

    Returns
    -------
    int
        Exit status 0.
    """
    from .compare import PAIRED_COLUMNS, pair_prints

    check_table_path(a.output, option="--output")
    paired = pair_prints(read_table(a.prints))
    write_table(paired, a.output, columns=table_columns(paired, first=PAIRED_COLUMNS))
    n_ok = sum(r.get("model_status") == "ok" for r in paired)
    _say(a, f"paired {n_ok} of {len(paired)} rows with the model; wrote {a.output}")
    if n_ok < len(paired):
        print(f"{len(paired) - n_ok} rows not paired (see model_status)", file=sys.stderr)
        return EXIT_SOME_FAILED
    return EXIT_OK


def report_command(a: argparse.Namespace) -> int:
    """Write the HTML report of a print table.

    Parameters
    ----------
    a : argparse.Namespace
        ``prints`` (input table path), ``output`` (folder), ``no_renders`` (bool).

    Returns
    -------
    int
        Exit status 0, or 1 when some rows could not be compared with the model
        (their count on stderr; they are listed in the report's errors table).
    """
    from .report import build_report

    check_output_path(f"{a.output}/index.html", option="--output")
    rows = read_table(a.prints)
    index = build_report(rows, a.output, renders=not a.no_renders, source=a.prints)
    _say(a, f"wrote {index}")
    n_err = report_errors(index)
    if n_err:
        print(
            f"{n_err} of {len(rows)} rows failed (no print or no model); see "
            f"{Path(index).parent / 'tables' / 'errors.csv'}",
            file=sys.stderr,
        )
        return EXIT_SOME_FAILED
    return EXIT_OK


def report_errors(index) -> int:
    """The number of error rows of a written report (its ``report.json``).

    Parameters
    ----------
    index : str or PathLike
        The report's ``index.html``.

    Returns
    -------
    int
        Rows whose print or model failed (the report's errors table).
    """
    doc = json.loads((Path(index).parent / "report.json").read_text(encoding="utf-8"))
    return int(doc["config"]["errors"])


def validate_command(a: argparse.Namespace) -> int:
    """Compare the model with the measurements of Dressel (2013) and write the results.

    Parameters
    ----------
    a : argparse.Namespace
        ``output`` (folder), ``measurements`` (CSV path or None for the packaged copy).

    Returns
    -------
    int
        Exit status 0.
    """
    from .validate import validate

    check_output_path(f"{a.output}/summary.md", option="--output")
    v = validate(a.output, a.measurements)
    if a.verbosity < 0:
        return EXIT_OK
    st = v.settings
    print(
        f"{st['n_rows']} measurement rows; casing modulus E = {st['modulus_N_mm2']:.4g} N/mm^2 "
        f"(t = {st['thickness_mm']:g} mm), fitted across all tires; {st['seconds']} s"
    )
    print(f"{'quantity':<58} {'n':>3} {'median':>8} {'worst':>8} {'RMS log':>8}")
    for s in v.statistics:
        print(
            f"{s['label'] + ' [' + s['unit'] + ']':<58} {s['n']:>3} {s['median_ratio']:>8.3g} "
            f"{s['worst_ratio']:>8.3g} {s['rms_log_error']:>8.3g}"
        )
    for row in v.variants:
        if row["variant"].startswith("taut beam, E fitted (leave"):
            print(
                f"leave one tire out (lateral stiffness): RMS log error {row['rms_log_error']:.3g}"
            )
    print(f"wrote {a.output}/summary.md, index.html, tables (CSV, JSON) and figures/")
    return 0


def _say(a: argparse.Namespace, message: str) -> None:
    if a.verbosity >= 0:
        print(message)


def _common() -> argparse.ArgumentParser:
    common = argparse.ArgumentParser(add_help=False)
    g = common.add_mutually_exclusive_group()
    g.add_argument(
        "-q",
        "--quiet",
        dest="verbosity",
        action="store_const",
        const=-1,
        default=argparse.SUPPRESS,
        help="errors only",
    )
    g.add_argument(
        "-v",
        "--verbose",
        dest="verbosity",
        action="store_const",
        const=1,
        default=argparse.SUPPRESS,
        help="more detail",
    )
    return common


def build_parser() -> argparse.ArgumentParser:
    """The ``contactpatch`` argument parser.

    Returns
    -------
    argparse.ArgumentParser
        Sub-commands ``compare``, ``report`` and ``validate``; each sets ``func``;
        ``--version`` and ``-q``/``-v`` everywhere.
    """
    from .. import __version__

    common = _common()
    parser = argparse.ArgumentParser(
        prog="contactpatch",
        parents=[common],
        description="Rotta model vs ink prints.",
        epilog="exit status: 0 ok, 1 some rows failed, 2 usage or input error, 3 internal error",
    )
    parser.add_argument("--version", action="version", version=f"%(prog)s {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser(
        "compare", parents=[common], help="pair an inkprint batch table with the model"
    )
    p.add_argument("prints", help="PRINTS.csv from `inkprint batch`")
    p.add_argument("-o", "--output", required=True, help="paired.csv (or .json)")
    p.set_defaults(func=compare_command)
    p = sub.add_parser(
        "report",
        parents=[common],
        help="HTML report (figures, tables, renders) from a print table",
    )
    p.add_argument("prints", help="PRINTS.csv from `inkprint batch`")
    p.add_argument("-o", "--output", required=True, help="report folder")
    p.add_argument("--no-renders", action="store_true", help="skip the 3D renders")
    p.set_defaults(func=report_command)
    p = sub.add_parser(
        "validate",
        parents=[common],
        help="compare the model with the measurements of Dressel (2013)",
    )
    p.add_argument(
        "-o", "--output", default="validation", help="output folder (default: validation)"
    )
    p.add_argument(
        "--measurements",
        default=None,
        help="CSV with the columns of measured-dressel2013.csv (default: the packaged copy)",
    )
    p.set_defaults(func=validate_command)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Run the ``contactpatch`` command line.

    Parameters
    ----------
    argv : sequence of str, optional
        Arguments (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        Exit status: 0 all good, 1 some rows failed (their count on stderr), 2 a usage,
        input or file error (one line on stderr naming what and why), 3 an internal
        error (``-v`` shows the traceback).
    """
    try:
        a = build_parser().parse_args(argv)
    except SystemExit as exc:  # usage error (2), --help or --version (0)
        return exc.code if isinstance(exc.code, int) else EXIT_USAGE
    a.verbosity = getattr(a, "verbosity", 0)  # -q / -v before or after the command
    try:
        return a.func(a)
    except (ContactPatchError, TireModelError, ValueError, KeyError) as exc:
        print(f"error: {exc}", file=sys.stderr)
    except OSError as exc:
        where = f"{exc.filename}: " if getattr(exc, "filename", None) else ""
        print(f"error: {where}{exc.strerror or exc}", file=sys.stderr)
    except Exception as exc:
        if a.verbosity > 0:
            import traceback

            traceback.print_exc()
        print(
            f"error: internal error {type(exc).__name__}: {exc} (a bug: please report it; "
            "rerun with -v for the traceback)",
            file=sys.stderr,
        )
        return EXIT_INTERNAL
    return EXIT_USAGE


if __name__ == "__main__":
    sys.exit(main())
