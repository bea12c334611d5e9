"""Numbers in the report's pages, formatted by the quantity they are.

A column's name says what it holds (the library's keys carry their unit); its
*kind* (:func:`column_kind`) sets the digits shown:

========  =========================================  =================
kind      columns                                    shown as
========  =========================================  =================
``mm``    lengths ``*_mm``                           0.1 mm
``mm2``   areas ``*_mm2``                            1 mm^2
``ratio`` ``ratio_*``, ``net_to_gross``, drum/plate  3 decimals
``bar``   ``pressure_bar``, and N/mm^2 shown in bar  up to 2 decimals
``N``     ``load_N``                                 1 N
``pct``   ``*_pct``                                  0.1 %
``exp``   exponents, ``dlog_*`` sensitivities        2 decimals
``r2``    coefficients of determination              3 decimals
``int``   counts                                     as is
``text``  anything else                              as is
========  =========================================  =================

A value that rounds to zero at its precision is shown as ``0`` (never ``-0.0`` or
``1e-13``); NaN and empty cells as an empty string. The CSV tables keep full
precision. Pressure is shown in bar throughout: N/mm^2 columns are converted
(:func:`display_value`) and labelled so.
"""

from __future__ import annotations

import math

from tiremesh.units import MPA_PER_BAR

#: kind -> decimals
DECIMALS = {"mm": 1, "mm2": 0, "ratio": 3, "bar": 2, "N": 0, "pct": 1, "exp": 2, "r2": 3}
_TEXT_COLUMNS = {
    "file",
    "tire",
    "surface",
    "quantity",
    "source",
    "status",
    "error",
    "model_status",
    "model_error",
    "variable",
}
_INT_COLUMNS = {
    "print",
    "n",
    "cases",
    "print_dof",
    "model_dof",
    "print_increases",
    "model_increases",
    "agree",
}
_RATIO_COLUMNS = {"net_to_gross", "max", "min", "mean", "stdev"}


def column_kind(column: str) -> str:
    """The kind of quantity a column holds (see the module's table).

    Parameters
    ----------
    column : str
        Column name (``length_mm``, ``ratio_area``, ``print_pressure_exp`` ...).

    Returns
    -------
    str
        One of ``mm``, ``mm2``, ``ratio``, ``bar``, ``N``, ``pct``, ``exp``, ``r2``,
        ``int``, ``text``.
    """
    c = column
    if c in _TEXT_COLUMNS or c.endswith("_wkt"):
        return "text"
    if c in _INT_COLUMNS:
        return "int"
    if c.startswith("ratio_") or c in _RATIO_COLUMNS:
        return "ratio"
    if c.endswith("_N_mm2") or c.endswith("_bar"):
        return "bar"
    if c.endswith("_pct"):
        return "pct"
    if c.endswith("_exp") or c.endswith("_se") or c.startswith("dlog_"):
        return "exp"
    if c.endswith("r2"):
        return "r2"
    if c.endswith("_mm2"):
        return "mm2"
    if c.endswith("_mm"):
        return "mm"
    if c.endswith("_N"):
        return "N"
    return "text"


def display_value(value, column: str):
    """The value in the unit the page shows: N/mm^2 columns in bar.

    Parameters
    ----------
    value : object
        A table cell.
    column : str

    Returns
    -------
    object
        ``value`` [N/mm^2] / 0.1 for ``*_N_mm2`` columns, else ``value`` unchanged.
    """
    if column.endswith("_N_mm2"):
        x = as_number(value)
        return x / MPA_PER_BAR if x is not None else value
    return value


def as_number(value) -> float | None:
    """A finite or NaN float from a number or numeric text; None for text.

    Parameters
    ----------
    value : object

    Returns
    -------
    float or None
    """
    if isinstance(value, bool):
        return None
    if isinstance(value, int | float):
        return float(value)
    try:
        return float(str(value).strip())
    except ValueError:
        return None


def fixed(x: float, decimals: int) -> str:
    """``x`` to ``decimals`` decimals; ``0`` for anything that rounds to zero.

    Parameters
    ----------
    x : float
    decimals : int

    Returns
    -------
    str
        Empty for NaN; ``inf`` / ``-inf`` as such.
    """
    if math.isnan(x):
        return ""
    if math.isinf(x):
        return "inf" if x > 0 else "-inf"
    s = f"{x:.{decimals}f}"
    return "0" if float(s) == 0.0 else s


def fmt(value, column: str = "") -> str:
    """A cell as the pages show it (see the module's table).

    Parameters
    ----------
    value : object
        A table cell (number, numeric text, text, None).
    column : str
        Its column name, which sets the precision (:func:`column_kind`); without
        one, numbers get 4 significant digits.

    Returns
    -------
    str
    """
    if value is None:
        return ""
    kind = column_kind(column) if column else "any"
    if kind == "text" or isinstance(value, bool):
        return str(value)
    x = as_number(display_value(value, column))
    if x is None or (isinstance(value, str) and not value.strip()):
        return str(value)
    if kind == "int":
        return str(int(x)) if math.isfinite(x) and x == int(x) else fixed(x, 2)
    if kind == "any":
        return fixed(x, 0) if math.isfinite(x) and x == int(x) else _significant(x, 4)
    if kind == "bar":
        return _trim(fixed(x, DECIMALS["bar"]))
    if kind == "N":
        return fixed(x, 0) if math.isfinite(x) and abs(x - round(x)) < 0.05 else fixed(x, 1)
    return fixed(x, DECIMALS[kind])


def _trim(s: str) -> str:
    """'6.90' -> '6.9', '4.00' -> '4'."""
    return s.rstrip("0").rstrip(".") if "." in s else s


def _significant(x: float, digits: int) -> str:
    if not math.isfinite(x) or x == 0:
        return fixed(x, 0)
    decimals = max(0, digits - 1 - math.floor(math.log10(abs(x))))
    return fixed(x, decimals)


def estimate(value: float, se: float, dof: int) -> str:
    """An estimate with its standard error: ``-0.47 ± 0.03``.

    The error is shown to two significant digits and the value to the same decimal
    (at least 2, at most 4 decimals).

    Parameters
    ----------
    value : float
    se : float
        Standard error (NaN: not available).
    dof : int
        Residual degrees of freedom of the fit (0: the fit is exact, no error).

    Returns
    -------
    str
        Empty for a NaN value; ``-0.47 (exact fit, no error estimate)`` when
        ``dof == 0``.
    """
    if math.isnan(value):
        return ""
    if dof <= 0 or math.isnan(se):
        return f"{fixed(value, 2)} (exact fit, no error estimate)"
    # an error too small to show at 4 decimals (an exact relation, e.g. the model's
    # area = load / pressure) is shown as 0 beside 2 decimals
    d = 2 if se < 5e-5 else min(4, max(2, 1 - math.floor(math.log10(se))))
    return f"{fixed(value, d)} ± {fixed(se, d)}"


def interval(value: float, half_width: float, dof: int) -> str:
    """A 95 % interval as text, for tooltips: ``95 % interval -0.74 to -0.27 (1 dof)``.

    Parameters
    ----------
    value, half_width : float
    dof : int

    Returns
    -------
    str
        Empty when not available.
    """
    if dof <= 0 or math.isnan(value) or math.isnan(half_width):
        return ""
    lo, hi = value - half_width, value + half_width
    return f"95 % interval {fixed(lo, 3)} to {fixed(hi, 3)} (Student t, {dof} dof)"


def pressure_note(value_n_mm2) -> str:
    """Tooltip for a pressure shown in bar: the same in N/mm^2 (MPa).

    Parameters
    ----------
    value_n_mm2 : float or str [N/mm^2]

    Returns
    -------
    str
    """
    x = as_number(value_n_mm2)
    return "" if x is None or math.isnan(x) else f"{x:.4f} N/mm² (MPa)"


__all__ = [
    "DECIMALS",
    "as_number",
    "column_kind",
    "display_value",
    "estimate",
    "fixed",
    "fmt",
    "interval",
    "pressure_note",
]
