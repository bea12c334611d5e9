"""``contactpatch`` command line: pair prints with the model, and the report."""

from __future__ import annotations

import argparse
import sys
from collections.abc import Sequence

from .errors import ContactPatchError


def _cmd_compare(a) -> int:
    from .compare import pair_prints
    from .report import PAIRED_COLUMNS, read_table, write_csv

    paired = pair_prints(read_table(a.prints))
    cols = PAIRED_COLUMNS + [
        c for c in dict.fromkeys(k for r in paired for k in r) if c not in PAIRED_COLUMNS
    ]
    write_csv(paired, a.output, cols)
    n_ok = sum(r.get("model_status") == "ok" for r in paired)
    print(f"paired {n_ok} of {len(paired)} rows with the model; wrote {a.output}")
    return 0


def _cmd_report(a) -> int:
    from .report import build_report, read_table

    index = build_report(read_table(a.prints), a.output, renders=not a.no_renders, source=a.prints)
    print(f"wrote {index}")
    return 0


def build_parser() -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(prog="contactpatch", description="Rotta model vs ink prints.")
    sub = parser.add_subparsers(dest="command", required=True)
    p = sub.add_parser("compare", help="pair an inkprint batch table with the model")
    p.add_argument("prints", help="PRINTS.csv from `inkprint batch`")
    p.add_argument("-o", "--output", required=True, help="paired.csv")
    p.set_defaults(func=_cmd_compare)
    p = sub.add_parser("report", help="HTML report (figures, tables, renders) from a print table")
    p.add_argument("prints", help="PRINTS.csv from `inkprint batch`")
    p.add_argument("-o", "--output", required=True, help="report folder")
    p.add_argument("--no-renders", action="store_true", help="skip the 3D renders")
    p.set_defaults(func=_cmd_report)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    a = build_parser().parse_args(argv)
    try:
        return a.func(a)
    except (ContactPatchError, ValueError, OSError) as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
