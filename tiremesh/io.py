"""Files shared by all three packages: atomic output, tables (CSV / JSON) and figures.

This is the one home of file writing in the project (``contactpatch`` and ``inkprint``
import it from here; the package graph stays one-way). Every writer goes through
:func:`atomic_path`: the data land in a temporary file beside the target, which is
renamed over it only on success, so an interrupted run never leaves a half-written file.
"""

from __future__ import annotations

import contextlib
import csv
import json
import math
import os
import tempfile
from collections.abc import Iterable, Sequence
from pathlib import Path

TABLE_FORMATS = (".csv", ".json")


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike):
    """Yield a temporary path in the target's folder; on success it replaces ``path``.

    Parameters
    ----------
    path : str or PathLike
        Final file name. Its folder is created if missing.

    Yields
    ------
    tmp : Path
        Write here; renamed to ``path`` when the ``with`` block ends without error.
    """
    target = Path(path)
    target.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=target.suffix, dir=target.parent)
    os.close(fd)
    try:
        yield Path(tmp)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp creates 0600; give the usual mode
        os.replace(tmp, target)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


def write_text_atomic(path: str | os.PathLike, text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` atomically; return the path."""
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(path)


def table_columns(rows: Iterable[dict], first: Sequence[str] = ()) -> list[str]:
    """Column names: ``first`` (in order), then every other key in first-seen order."""
    return list(dict.fromkeys([*first, *(k for r in rows for k in r)]))


def _jsonable(v):
    if isinstance(v, float) and not math.isfinite(v):
        return None
    if hasattr(v, "item"):  # numpy scalar
        return _jsonable(v.item())
    if isinstance(v, int | float | str | bool) or v is None:
        return v
    try:
        return float(v)
    except (TypeError, ValueError):
        return str(v)


def write_table(
    rows: Sequence[dict], path: str | os.PathLike, *, columns: Sequence[str] | None = None
) -> Path:
    """Write ``rows`` (dicts) as a table, atomically; the format follows the suffix.

    Parameters
    ----------
    rows : sequence of dict
        One dict per row; missing keys give empty cells.
    path : str or PathLike
        ``.csv`` (header + rows) or ``.json`` (a list of objects; NaN/inf -> null).
    columns : sequence of str, optional
        Columns to write, in order (default: every key, first-seen order). Keys not
        listed are left out.

    Returns
    -------
    Path
    """
    path = Path(path)
    cols = list(columns) if columns is not None else table_columns(rows)
    ext = path.suffix.lower()
    if ext not in TABLE_FORMATS:
        raise ValueError(f"{path}: unknown table format {ext!r}; use one of {TABLE_FORMATS}")
    with atomic_path(path) as tmp:
        if ext == ".json":
            data = [{k: _jsonable(r.get(k)) for k in cols if k in r} for r in rows]
            tmp.write_text(json.dumps(data, indent=1), encoding="utf-8")
        else:
            with tmp.open("w", newline="", encoding="utf-8") as fh:
                w = csv.DictWriter(fh, fieldnames=cols, extrasaction="ignore", lineterminator="\n")
                w.writeheader()
                w.writerows(rows)
    return path


def cell_number(v) -> float | None:
    """A finite float from a table cell (CSV cells arrive as strings), or None
    (empty, text, NaN, inf)."""
    if v is None or v == "":
        return None
    try:
        x = float(v)
    except (TypeError, ValueError):
        return None
    return x if math.isfinite(x) else None


def cell_number_or_nan(v) -> float:
    """Like :func:`cell_number`, with NaN for missing values (for arrays and plots)."""
    x = cell_number(v)
    return math.nan if x is None else x


def read_table(path: str | os.PathLike) -> list[dict]:
    """Rows of a CSV (cells as strings) or JSON table written by :func:`write_table`."""
    path = Path(path)
    if path.suffix.lower() == ".json":
        return list(json.loads(path.read_text(encoding="utf-8")))
    with path.open(newline="", encoding="utf-8") as fh:
        return list(csv.DictReader(fh))


def save_figure(
    fig, stem: str | os.PathLike, *, formats: Sequence[str] = (".png", ".svg"), dpi: int = 130
) -> list[Path]:
    """Save a matplotlib figure as ``stem`` + each suffix (atomically) and close it.

    Parameters
    ----------
    fig : matplotlib.figure.Figure
    stem : str or PathLike
        Path without suffix.
    formats : sequence of str
        Suffixes, e.g. ``(".png", ".svg")``. SVG is written without a date, so
        re-running gives identical files.
    dpi : int
        Raster resolution.

    Returns
    -------
    list of Path
    """
    import matplotlib.pyplot as plt

    stem = Path(stem)
    out = []
    for ext in formats:
        path = stem.with_suffix(ext)
        kw = {"dpi": dpi} if ext in (".png", ".jpg", ".jpeg", ".tif", ".tiff") else {}
        if ext in (".svg", ".pdf"):
            kw["metadata"] = {"Date": None} if ext == ".svg" else {"CreationDate": None}
        with atomic_path(path) as tmp:
            fig.savefig(tmp, format=ext[1:], **kw)
        out.append(path)
    plt.close(fig)
    return out


__all__ = [
    "TABLE_FORMATS",
    "atomic_path",
    "cell_number",
    "cell_number_or_nan",
    "read_table",
    "save_figure",
    "table_columns",
    "write_table",
    "write_text_atomic",
]
