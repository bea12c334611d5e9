"""CSV files that are safe to open in a spreadsheet (OWASP "CSV injection").

Every CSV :mod:`inkprint` writes (batch tables, ``inkprint analyze --csv``, the
synthetic manifests) goes through :func:`write_csv`. A text cell that starts with
``=``, ``+``, ``-``, ``@``, a tab or a carriage return would be run as a formula by
Excel, LibreOffice or Google Sheets (``=HYPERLINK(...)``, ``+cmd|...``, ``@SUM``);
such a cell is written with a single quote in front (``'=HYPERLINK(...)``), the
OWASP rule, and spreadsheets then show it as text. Numbers stay numbers: a cell
that reads as a number (``-3.5``, ``+2``, ``-1e-3``) is not touched. A text cell
that already starts with a quote and one of those characters gets one more quote,
so :func:`unescape_cell` (used when a batch reads its own table back to resume)
restores every cell exactly.

References
----------
.. [1] OWASP, "CSV Injection", https://owasp.org/www-community/attacks/CSV_Injection
"""

from __future__ import annotations

import csv
import os
from collections.abc import Sequence
from pathlib import Path

TRIGGERS = ("=", "+", "-", "@", "\t", "\r")


def _is_number(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return False
    return True


def escape_cell(value):
    """A cell value made safe for spreadsheets (text only; numbers unchanged).

    Parameters
    ----------
    value : object
        Cell value; only ``str`` values can be escaped.

    Returns
    -------
    object
        ``value``, or ``"'" + value`` for text starting with one of
        :data:`TRIGGERS` (or with a quote followed by one) that is not a number.
    """
    if not isinstance(value, str) or not value:
        return value
    if value[0] in TRIGGERS and not _is_number(value):
        return "'" + value
    if value[0] == "'" and value[1:2] and (value[1] in TRIGGERS or value[1] == "'"):
        return "'" + value
    return value


def unescape_cell(value):
    """Undo :func:`escape_cell` (for a table read back).

    Parameters
    ----------
    value : object

    Returns
    -------
    object
    """
    if isinstance(value, str) and value[:1] == "'" and value[1:2]:
        if value[1] in TRIGGERS or value[1] == "'":
            return value[1:]
    return value


def write_csv(
    rows: Sequence[dict],
    path: str | os.PathLike,
    *,
    columns: Sequence[str] | None = None,
    lineterminator: str = "\r\n",
) -> Path:
    """Write dict rows as a CSV with every cell escaped (:func:`escape_cell`), atomically.

    Parameters
    ----------
    rows : sequence of dict
        Missing keys give empty cells; keys not in ``columns`` are left out.
    path : str or PathLike
    columns : sequence of str, optional
        Columns in order (default: every key, first-seen order).
    lineterminator : str
        Line end (the csv module's CRLF by default).

    Returns
    -------
    Path
    """
    from tiremesh.io import atomic_path, table_columns

    cols = list(columns) if columns is not None else table_columns(rows)
    with atomic_path(path) as tmp, tmp.open("w", newline="", encoding="utf-8") as fh:
        write_rows(fh, rows, cols, lineterminator=lineterminator)
    return Path(path)


def write_rows(fh, rows: Sequence[dict], columns: Sequence[str], *, lineterminator="\n") -> None:
    """Write a header and escaped rows to an open text stream.

    Parameters
    ----------
    fh : text stream
    rows : sequence of dict
    columns : sequence of str
    lineterminator : str
    """
    w = csv.writer(fh, lineterminator=lineterminator)
    w.writerow([escape_cell(c) for c in columns])
    for r in rows:
        w.writerow([escape_cell(r.get(c, "")) for c in columns])


def read_csv(path: str | os.PathLike) -> list[dict]:
    """Rows of a CSV written by :func:`write_csv`, cells unescaped (strings).

    Parameters
    ----------
    path : str or PathLike

    Returns
    -------
    list of dict
    """
    with Path(path).open(newline="", encoding="utf-8-sig") as fh:
        return [
            {unescape_cell(k): unescape_cell(v) for k, v in r.items()} for r in csv.DictReader(fh)
        ]


__all__ = ["TRIGGERS", "escape_cell", "read_csv", "unescape_cell", "write_csv", "write_rows"]
