"""The study's commands: ``contactpatch compare``, ``contactpatch report`` and
``contactpatch validate``."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from tiremesh.io import read_table, table_columns, write_table

from ..errors import ContactPatchError


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

    paired = pair_prints(read_table(a.prints))
    write_table(paired, a.output, columns=table_columns(paired, first=PAIRED_COLUMNS))
    n_ok = sum(r.get("model_status") == "ok" for r in paired)
    print(f"paired {n_ok} of {len(paired)} rows with the model; wrote {a.output}")
    return 0


def report_command(a: argparse.Namespace) -> int:
    """Write the HTML report of a print table.

    Parameters
    ----------
    a : argparse.Namespace
        ``prints`` (input table path), ``output`` (folder), ``no_renders`` (bool).

    Returns
    -------
    int
        Exit status 0.
    """
    from .report import build_report

    index = build_report(read_table(a.prints), a.output, renders=not a.no_renders, source=a.prints)
    print(f"wrote {index}")
    return 0


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

    v = validate(a.output, a.measurements)
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


def build_parser() -> argparse.ArgumentParser:
    """The ``contactpatch`` argument parser.

    Returns
    -------
    argparse.ArgumentParser
        Sub-commands ``compare``, ``report`` and ``validate``; each sets ``func``.
    """
    parser = argparse.ArgumentParser(prog="contactpatch", description="Rotta model vs ink prints.")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("compare", help="pair an inkprint batch table with the model")
    p.add_argument("prints", help="PRINTS.csv from `inkprint batch`")
    p.add_argument("-o", "--output", required=True, help="paired.csv (or .json)")
    p.set_defaults(func=compare_command)
    p = sub.add_parser("report", help="HTML report (figures, tables, renders) from a print table")
    p.add_argument("prints", help="PRINTS.csv from `inkprint batch`")
    p.add_argument("-o", "--output", required=True, help="report folder")
    p.add_argument("--no-renders", action="store_true", help="skip the 3D renders")
    p.set_defaults(func=report_command)
    p = sub.add_parser(
        "validate", help="compare the model with the measurements of Dressel (2013)"
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
        Exit status: 0 on success, 2 on an input or file error (message on stderr).
    """
    a = build_parser().parse_args(argv)
    try:
        return a.func(a)
    except (ContactPatchError, ValueError, OSError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
