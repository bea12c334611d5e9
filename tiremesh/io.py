"""Files shared by all three packages: atomic output, tables (CSV / JSON / Parquet)
and figures.

This is the one home of file writing in the project (``contactpatch`` and ``inkprint``
import it from here; the package graph stays one-way). Every writer goes through
:func:`atomic_path`: the data land in a temporary file beside the target, which is
renamed over it only on success, so an interrupted run never leaves a half-written file.

Errors: any operating-system failure on an output (a read-only or missing folder,
``/proc``, a folder where a file is expected, a full disk) becomes an
:class:`OutputError` that names the path and the reason. Command lines check their
outputs up front with :func:`check_output_path` / :func:`check_table_path`, before any
work. Parquet needs the optional ``pyarrow`` (``pip install 'rotta-tire[parquet]'``),
imported only when a Parquet table is read or written; without it a
:class:`MissingDependency` says what to install.

CSV safety (formula injection, OWASP "CSV Injection"): every CSV written by
:func:`write_table` passes its cells (and header) through :func:`csv_cell`. A text
cell that starts with ``=``, ``+``, ``-``, ``@``, a tab or a carriage return, and is
not a plain decimal number, is written with a leading single quote (``'=HYPERLINK(..)``),
so a spreadsheet shows it as text instead of evaluating it. Numbers (``-3.5``,
``-1e-3``, also as text) are written unchanged. JSON and Parquet hold typed values and
are written unchanged. :func:`read_table` returns the quoted text as written.
"""

from __future__ import annotations

import contextlib
import csv
import importlib.util
import json
import math
import os
import re
from collections.abc import Iterable, Sequence
from pathlib import Path

from .errors import InvalidParameter, TireModelError

TABLE_FORMATS = (".csv", ".json", ".parquet")
"""Suffixes :func:`write_table` writes (the ``format=`` names are these without the dot)."""
PROJECT = "rotta-tire"
"""Distribution name, for ``pip install`` hints."""

_FORMULA_START = ("=", "+", "-", "@", "\t", "\r")
_DECIMAL = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


class OutputError(TireModelError, OSError):
    """An output file cannot be written; the message names the path and the reason.

    Attributes
    ----------
    path : str
        The file that could not be written.
    reason : str
        Why, in words (``'Permission denied'``, ``'it is a folder'``, ...).
    option : str or None
        The command-line option or parameter that named the file, if known.
    """

    def __init__(self, path, reason: str, option: str | None = None) -> None:
        self.path = str(path)
        self.reason = reason
        self.option = option
        where = f" (given as {option})" if option else ""
        super().__init__(f"cannot write {path}{where}: {reason}")


class MissingDependency(TireModelError, ImportError):
    """An optional package needed for the request is not installed.

    Attributes
    ----------
    package : str
        The missing import (``'pyarrow'``).
    extra : str
        The optional-dependency group that installs it (``'parquet'``).
    """

    def __init__(self, package: str, purpose: str, extra: str) -> None:
        self.package = package
        self.extra = extra
        super().__init__(
            f"{purpose} needs the optional package {package}, which is not installed: "
            f"pip install '{PROJECT}[{extra}]' (or pip install {package})"
        )


def _reason(exc: OSError) -> str:
    return exc.strerror or str(exc) or type(exc).__name__


def _temp_beside(target: Path, option: str | None = None) -> Path:
    """Create the target's folder and an empty temporary file in it (mode 0600)."""
    if target.is_dir():
        raise OutputError(target, "it is a folder; give a file name", option)
    folder = target.parent
    for anc in (folder, *folder.parents):
        if anc.exists():
            if not anc.is_dir():
                raise OutputError(target, f"{anc} is a file, not a folder", option)
            break
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OutputError(
            target, f"cannot create the folder {folder}: {_reason(exc)}", option
        ) from exc
    # imported here: a process that writes no file (``inkprint analyze``) need not
    # load tempfile and random
    import tempfile

    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=target.suffix, dir=folder)
    except OSError as exc:
        raise OutputError(
            target, f"cannot create a file in {folder}: {_reason(exc)}", option
        ) from exc
    os.close(fd)
    return Path(tmp)


def _about_output(exc: OSError, *paths: Path) -> bool:
    """Whether an OSError raised while writing concerns the output (no other file)."""
    names = {str(p) for p in paths}
    return exc.filename is None or str(exc.filename) in names


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

    Raises
    ------
    OutputError
        The folder or the file cannot be created, written or renamed (the message
        names ``path`` and the reason); nothing is left behind.
    """
    target = Path(path)
    tmp = _temp_beside(target)
    try:
        yield tmp
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp creates 0600; give the usual mode
        os.replace(tmp, target)
    except BaseException as exc:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        if isinstance(exc, OSError) and not isinstance(exc, TireModelError):
            if _about_output(exc, tmp, target):
                raise OutputError(target, _reason(exc)) from exc
        raise


def check_output_path(path: str | os.PathLike, *, option: str | None = None) -> Path:
    """Check up front that ``path`` can be written, exactly as :func:`atomic_path` will.

    Creates the folder if missing and a temporary file beside the target (removed at
    once); the target itself is not touched.

    Parameters
    ----------
    path : str or PathLike
        The output file.
    option : str, optional
        The option that named it (``'--output'``), quoted in the message.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    OutputError
        ``path`` is a folder, its folder cannot be created, or no file can be
        created there (the message names the path and the reason).
    """
    target = Path(path)
    os.unlink(_temp_beside(target, option))
    return target


def write_text_atomic(path: str | os.PathLike, text: str) -> Path:
    """Write ``text`` (UTF-8) to ``path`` atomically (:func:`atomic_path`).

    Parameters
    ----------
    path : str or PathLike
        Target file; its folder is created if missing.
    text : str

    Returns
    -------
    Path
        ``path``.
    """
    with atomic_path(path) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(path)


def table_columns(rows: Iterable[dict], first: Sequence[str] = ()) -> list[str]:
    """Column names of a table of dict rows.

    Parameters
    ----------
    rows : iterable of dict
    first : sequence of str
        Columns to put first, in this order (even if no row has them).

    Returns
    -------
    list of str
        ``first``, then every other key in first-seen order.
    """
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


def _table_format(path, format: str | None, option: str | None) -> str:
    """'csv' | 'json' | 'parquet' from ``format`` (with or without a dot) or the suffix."""
    names = ", ".join(TABLE_FORMATS)
    if format is not None:
        fmt = "." + str(format).lower().lstrip(".")
        if fmt not in TABLE_FORMATS:
            raise InvalidParameter("format", format, f"one of {names} (without the dot too)")
        return fmt[1:]
    ext = Path(path).suffix.lower()
    if ext not in TABLE_FORMATS:
        raise InvalidParameter(option or "path", str(path), f"a table file ending in {names}")
    return ext[1:]


def _pyarrow(purpose: str):
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError as exc:
        raise MissingDependency("pyarrow", purpose, "parquet") from exc
    return pa, pq


def _has_module(name: str) -> bool:
    """Whether ``name`` can be imported, without importing it."""
    try:
        return importlib.util.find_spec(name) is not None
    except (ImportError, ValueError):  # e.g. sys.modules[name] is None
        return False


def check_table_path(
    path: str | os.PathLike, *, format: str | None = None, option: str | None = None
) -> str:
    """Check a table output before any work: a known format, its optional package
    installed, and a writable place (:func:`check_output_path`).

    Parameters
    ----------
    path : str or PathLike
        The output table; its suffix picks the format unless ``format`` is given.
    format : {'csv', 'json', 'parquet'}, optional
        Override the suffix.
    option : str, optional
        The option that named the file (``'--output'``), quoted in messages.

    Returns
    -------
    str
        The format: ``'csv'``, ``'json'`` or ``'parquet'``.

    Raises
    ------
    InvalidParameter
        An unknown suffix or format (the message lists the known ones).
    MissingDependency
        Parquet without pyarrow installed.
    OutputError
        The file cannot be written there.
    """
    fmt = _table_format(path, format, option)
    if fmt == "parquet" and not _has_module("pyarrow"):
        raise MissingDependency("pyarrow", f"writing {path} (Parquet)", "parquet")
    check_output_path(path, option=option)
    return fmt


def csv_cell(value):
    """A value as written into a CSV cell, safe against formula injection.

    OWASP rule: text that starts with ``=``, ``+``, ``-``, ``@``, a tab or a carriage
    return, and is not a plain decimal number, gets a leading single quote, so a
    spreadsheet shows it as text rather than evaluating it. Numbers stay numbers.

    Parameters
    ----------
    value : object
        Cell value: a number, a string, None, or anything with a ``str``.

    Returns
    -------
    object
        Numbers (and bools) unchanged, ``''`` for None, text (quoted if needed).

    Examples
    --------
    >>> [csv_cell(v) for v in ("=HYPERLINK(1)", "@SUM(A1)", "-3.5", -1e-3, "big apple")]
    ["'=HYPERLINK(1)", "'@SUM(A1)", '-3.5', -0.001, 'big apple']
    """
    if value is None:
        return ""
    if hasattr(value, "item") and hasattr(value, "dtype"):  # numpy scalar
        value = value.item()
    if isinstance(value, bool | int | float):
        return value
    text = value if isinstance(value, str) else str(value)
    if text.startswith(_FORMULA_START) and not _DECIMAL.fullmatch(text):
        return "'" + text
    return text


def _write_csv(rows: Sequence[dict], cols: list[str], tmp: Path) -> None:
    with tmp.open("w", newline="", encoding="utf-8") as fh:
        w = csv.writer(fh, lineterminator="\n")
        # the csv module quotes only the line terminator's characters: a row with a
        # bare carriage return is quoted whole, so it cannot split into two rows
        w_all = csv.writer(fh, lineterminator="\n", quoting=csv.QUOTE_ALL)
        for cells in (
            [csv_cell(c) for c in cols],
            *([csv_cell(r.get(c)) for c in cols] for r in rows),
        ):
            cr = any(isinstance(c, str) and "\r" in c for c in cells)
            (w_all if cr else w).writerow(cells)


def _write_json(rows: Sequence[dict], cols: list[str], tmp: Path) -> None:
    data = [{k: _jsonable(r.get(k)) for k in cols if k in r} for r in rows]
    tmp.write_text(json.dumps(data, indent=1), encoding="utf-8")


def _plain(v):
    return v.item() if hasattr(v, "item") and hasattr(v, "dtype") else v


def _arrow_array(pa, values: list):
    """One typed Parquet column: bool, int64, float64 (NaN kept) or text."""
    vals = [_plain(v) for v in values]
    present = [v for v in vals if v is not None and v != ""]
    if present and all(isinstance(v, bool) for v in present):
        return pa.array([v if isinstance(v, bool) else None for v in vals], pa.bool_())
    numeric = all(isinstance(v, int | float) and not isinstance(v, bool) for v in present)
    if present and numeric:
        clean = [v if isinstance(v, int | float) else None for v in vals]
        if all(isinstance(v, int) and -(2**63) <= v < 2**63 for v in present):
            return pa.array(clean, pa.int64())
        return pa.array([None if v is None else float(v) for v in clean], pa.float64())
    return pa.array([None if v is None else str(v) for v in vals], pa.string())


def _write_parquet(rows: Sequence[dict], cols: list[str], tmp: Path) -> None:
    pa, pq = _pyarrow(f"writing {tmp.name} (Parquet)")
    arrays = [_arrow_array(pa, [r.get(c) for r in rows]) for c in cols]
    pq.write_table(pa.Table.from_arrays(arrays, names=cols), tmp)


_WRITERS = {"csv": _write_csv, "json": _write_json, "parquet": _write_parquet}


def write_table(
    rows: Sequence[dict],
    path: str | os.PathLike,
    *,
    columns: Sequence[str] | None = None,
    format: str | None = None,
) -> Path:
    """Write ``rows`` (dicts) as a table, atomically; the format follows the suffix.

    CSV cells are written safely against formula injection (:func:`csv_cell`: text
    starting with ``= + - @``, a tab or a carriage return that is not a number gets a
    leading ``'``); numbers are written as numbers in full precision.

    Parameters
    ----------
    rows : sequence of dict
        One dict per row; missing keys give empty cells (null in JSON and Parquet).
    path : str or PathLike
        ``.csv`` (header + rows, UTF-8), ``.json`` (a list of objects; NaN/inf ->
        null) or ``.parquet`` (typed columns: bool, int64, float64 with NaN kept, or
        text for mixed columns; needs ``pyarrow``).
    columns : sequence of str, optional
        Columns to write, in order (default: every key, first-seen order). Keys not
        listed are left out.
    format : {'csv', 'json', 'parquet'}, optional
        Write this format whatever the suffix.

    Returns
    -------
    Path
        ``path``.

    Raises
    ------
    InvalidParameter
        An unknown suffix or format (checked before anything is written).
    MissingDependency
        Parquet without pyarrow.
    OutputError
        The file cannot be written (the message names the path and the reason).
    """
    path = Path(path)
    fmt = _table_format(path, format, None)
    if fmt == "parquet":
        _pyarrow(f"writing {path} (Parquet)")
    cols = list(columns) if columns is not None else table_columns(rows)
    with atomic_path(path) as tmp:
        _WRITERS[fmt](rows, cols, tmp)
    return path


def cell_number(v) -> float | None:
    """A finite float from a table cell (CSV cells arrive as strings).

    Parameters
    ----------
    v : str, float or None
        Cell value.

    Returns
    -------
    float or None
        None for an empty cell, text, NaN or inf.
    """
    if v is None or v == "":
        return None
    try:
        x = float(v)
    except (TypeError, ValueError):
        return None
    return x if math.isfinite(x) else None


def cell_number_or_nan(v) -> float:
    """Like :func:`cell_number`, with NaN for missing values (for arrays and plots).

    Parameters
    ----------
    v : str, float or None
        Cell value.

    Returns
    -------
    float
        NaN for an empty cell, text or a non-finite number.
    """
    x = cell_number(v)
    return math.nan if x is None else x


def read_table(path: str | os.PathLike, *, format: str | None = None) -> list[dict]:
    """Rows of a CSV, JSON or Parquet table (as written by :func:`write_table`).

    Parameters
    ----------
    path : str or PathLike
        ``.json`` is read as JSON, ``.parquet`` with pyarrow, any other suffix as CSV
        with a header (UTF-8; a byte-order mark, as Excel writes, is skipped).
    format : {'csv', 'json', 'parquet'}, optional
        Read this format whatever the suffix.

    Returns
    -------
    list of dict
        One dict per row; CSV cells are strings (see :func:`cell_number`; cells
        quoted by :func:`csv_cell` keep their quote), JSON and Parquet values keep
        their types (NaN/inf were written to JSON as null).

    Raises
    ------
    MissingDependency
        A Parquet table without pyarrow installed.
    """
    path = Path(path)
    ext = path.suffix.lower()
    fmt = _table_format(path, format, None) if format is not None else ext.lstrip(".")
    if fmt == "json":
        return list(json.loads(path.read_text(encoding="utf-8-sig")))
    if fmt == "parquet":
        _, pq = _pyarrow(f"reading {path} (Parquet)")
        return pq.read_table(path).to_pylist()
    with path.open(newline="", encoding="utf-8-sig") as fh:
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
    "PROJECT",
    "TABLE_FORMATS",
    "MissingDependency",
    "OutputError",
    "atomic_path",
    "cell_number",
    "cell_number_or_nan",
    "check_output_path",
    "check_table_path",
    "csv_cell",
    "read_table",
    "save_figure",
    "table_columns",
    "write_table",
    "write_text_atomic",
]
