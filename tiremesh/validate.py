"""Shared argument validation: every public function checks its inputs with these,
so every message names the parameter, its value and the allowed range."""

from __future__ import annotations

import numpy as np

from .errors import InvalidParameter


def _show(value):
    arr = np.asarray(value)
    return float(arr) if arr.ndim == 0 else arr


def finite(name: str, value, *, unit: str = "") -> np.ndarray:
    """Return ``value`` as a float array; raise if any element is NaN or inf.

    Parameters
    ----------
    name : str
        Parameter name, quoted in the error message.
    value : (...) float or array_like [unit of ``unit``]
        The value to check.
    unit : str
        Unit shown in the message (``"mm"``, ``"N/mm^2"``); empty for none.

    Returns
    -------
    arr : (...) float ndarray [unit of ``unit``]

    Raises
    ------
    InvalidParameter
        ``value`` is not numeric, or an element is NaN or inf.
    """
    try:
        arr = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InvalidParameter(name, value, f"a finite number{_unit(unit)}") from exc
    if not np.all(np.isfinite(arr)):
        bad = arr[~np.isfinite(arr)] if arr.ndim else arr
        raise InvalidParameter(name, _show(bad), f"a finite number{_unit(unit)}")
    return arr


def positive(name: str, value, *, unit: str = "") -> np.ndarray:
    """Return ``value`` as a float array that is finite and strictly positive.

    Parameters
    ----------
    name : str
        Parameter name, quoted in the error message.
    value : (...) float or array_like [unit of ``unit``]
    unit : str
        Unit shown in the message; empty for none.

    Returns
    -------
    arr : (...) float ndarray [unit of ``unit``]

    Raises
    ------
    InvalidParameter
        An element is not finite or is <= 0.
    """
    arr = finite(name, value, unit=unit)
    if np.any(arr <= 0):
        raise InvalidParameter(
            name, _show(arr[arr <= 0] if arr.ndim else arr), f"> 0{_unit(unit)}"
        )
    return arr


def in_range(
    name: str, value, lo: float, hi: float, *, unit: str = "", closed: bool = False
) -> np.ndarray:
    """Return ``value`` as a float array that is finite and inside (lo, hi).

    Parameters
    ----------
    name : str
        Parameter name, quoted in the error message.
    value : (...) float or array_like [unit of ``unit``]
    lo, hi : float [unit of ``unit``]
        Bounds of the allowed interval.
    unit : str
        Unit shown in the message; empty for none.
    closed : bool
        Allow the bounds themselves (``[lo, hi]``); default open ``(lo, hi)``.

    Returns
    -------
    arr : (...) float ndarray [unit of ``unit``]

    Raises
    ------
    InvalidParameter
        An element is not finite or lies outside the interval.
    """
    arr = finite(name, value, unit=unit)
    bad = (arr < lo) | (arr > hi) if closed else (arr <= lo) | (arr >= hi)
    if np.any(bad):
        br = "[]" if closed else "()"
        raise InvalidParameter(
            name,
            _show(arr[bad] if arr.ndim else arr),
            f"{br[0]}{lo:g}, {hi:g}{br[1]}{_unit(unit)}",
        )
    return arr


def integer(name: str, value, lo: int, hi: int) -> int:
    """Return ``value`` as a Python int in [lo, hi] (bools and floats are refused).

    Parameters
    ----------
    name : str
        Parameter name, quoted in the error message.
    value : int [-]
        Python or numpy integer.
    lo, hi : int [-]
        Inclusive bounds.

    Returns
    -------
    int [-]

    Raises
    ------
    InvalidParameter
        ``value`` is not an integer or lies outside [lo, hi].
    """
    if isinstance(value, bool) or not isinstance(value, int | np.integer):
        raise InvalidParameter(name, value, f"an integer in [{lo}, {hi}]")
    if not lo <= int(value) <= hi:
        raise InvalidParameter(name, value, f"an integer in [{lo}, {hi}]")
    return int(value)


def _unit(unit: str) -> str:
    return f" [{unit}]" if unit else ""
