"""Unit conversion at the edges (CLI, files). Inside the package: mm, N, N/mm^2, rad.

Constants as in the dissertation's ``Rotta_constants`` (Appendix C).
"""

from __future__ import annotations

import math
import re

from .errors import InvalidParameter

MPA_PER_BAR = 0.1
MPA_PER_PSI = 0.00689475728
MPA_PER_KPA = 0.001
N_PER_KG = 9.81  # Appendix C uses g = 9.81 m/s^2
N_PER_LBF = 4.4482216
MM_PER_IN = 25.4

_PRESSURE = {"bar": MPA_PER_BAR, "psi": MPA_PER_PSI, "kpa": MPA_PER_KPA, "mpa": 1.0, "n/mm2": 1.0}
_FORCE = {
    "n": 1.0,
    "kn": 1000.0,
    "kg": N_PER_KG,
    "kgf": N_PER_KG,
    "lb": N_PER_LBF,
    "lbf": N_PER_LBF,
}
_LENGTH = {"mm": 1.0, "cm": 10.0, "m": 1000.0, "in": MM_PER_IN}
_NUM = re.compile(r"^\s*([-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?)\s*([A-Za-z/^0-9]*)\s*$")

PRESSURE_FORMS = "4bar, 60psi, 400kPa, 0.4MPa"
"""Examples of accepted pressures, quoted in error messages."""
FORCE_FORMS = "400N, 40kg"
"""Examples of accepted forces, quoted in error messages."""
LENGTH_FORMS = "25mm, 2.5cm, 0.6m, 1in"
"""Examples of accepted lengths, quoted in error messages."""


def _parse(name: str, text, table: dict[str, float], default: str, how: dict) -> float:
    """``how``: ``forms`` (examples), ``require_unit`` and ``positive`` flags."""
    forms = how["forms"]
    if isinstance(text, bool):
        raise InvalidParameter(name, text, f"a number with a unit, e.g. {forms}")
    bare = isinstance(text, int | float) or hasattr(text, "dtype")
    if bare:
        number, unit = float(text), ""
    else:
        m = _NUM.match(str(text))
        if not m:
            raise InvalidParameter(name, text, f"a number with a unit, e.g. {forms}")
        number, unit = float(m.group(1)), m.group(2)
    if not unit and how["require_unit"]:
        raise InvalidParameter(
            name,
            text,
            f"a number with a unit, e.g. {forms}",
            "a bare number has no unit; write the unit after the number",
        )
    unit = (unit or default).lower().replace("^", "")
    if unit not in table:
        raise InvalidParameter(name, text, f"a unit among {', '.join(table)} (e.g. {forms})")
    value = number * table[unit]
    if not math.isfinite(value):
        raise InvalidParameter(name, text, "a finite number")
    if how["positive"] and value <= 0:
        raise InvalidParameter(name, text, f"a value > 0 with a unit, e.g. {forms}")
    return value


def parse_pressure(
    text: str | float,
    *,
    default: str = "bar",
    name: str = "pressure",
    require_unit: bool = False,
    positive: bool = False,
) -> float:
    """Parse a pressure with a unit: '4bar', '60 psi', '400kPa', '0.4MPa'.

    Command lines pass ``require_unit=True, positive=True``: a bare ``60`` could be
    bar or psi (a 14.5-fold difference), so it is refused with the accepted forms.

    Parameters
    ----------
    text : str or float [unit in the text, else ``default``]
        Number with a unit among bar, psi, kPa, MPa, N/mm2 (case-insensitive).
    default : str
        Unit of a bare number when ``require_unit`` is False (default ``'bar'``).
    name : str
        Parameter name for the error message (e.g. ``'--pressure'``).
    require_unit : bool
        Refuse a bare number (a float, or text without a unit).
    positive : bool
        Refuse a pressure <= 0.

    Returns
    -------
    pressure : float [N/mm^2]

    Raises
    ------
    InvalidParameter
        Malformed text, an unknown or (with ``require_unit``) missing unit, a
        non-finite value, or (with ``positive``) a value <= 0.

    Examples
    --------
    >>> parse_pressure("4bar")
    0.4
    >>> parse_pressure("60", require_unit=True, name="--pressure")
    Traceback (most recent call last):
    ...
    tiremesh.errors.InvalidParameter: --pressure = '60' is invalid: allowed a number with a unit, e.g. 4bar, 60psi, 400kPa, 0.4MPa (a bare number has no unit; write the unit after the number)
    """
    how = {"forms": PRESSURE_FORMS, "require_unit": require_unit, "positive": positive}
    return _parse(name, text, _PRESSURE, default, how)


def parse_force(
    text: str | float,
    *,
    default: str = "n",
    name: str = "load",
    require_unit: bool = False,
    positive: bool = False,
) -> float:
    """Parse a force with a unit: '400N', '40kg', '90lb'.

    ``kg`` means kilogram-force with g = 9.81 m/s^2 (Appendix C ``Rotta_constants``).
    Command lines pass ``require_unit=True, positive=True``.

    Parameters
    ----------
    text : str or float [unit in the text, else ``default``]
        Number with a unit among N, kN, kg, kgf, lb, lbf (case-insensitive).
    default : str
        Unit of a bare number when ``require_unit`` is False (default ``'n'``).
    name : str
        Parameter name for the error message (e.g. ``'--load'``).
    require_unit : bool
        Refuse a bare number (a float, or text without a unit).
    positive : bool
        Refuse a force <= 0.

    Returns
    -------
    force : float [N]

    Raises
    ------
    InvalidParameter
        Malformed text, an unknown or (with ``require_unit``) missing unit, a
        non-finite value, or (with ``positive``) a value <= 0.
    """
    how = {"forms": FORCE_FORMS, "require_unit": require_unit, "positive": positive}
    return _parse(name, text, _FORCE, default, how)


def parse_length(
    text: str | float,
    *,
    default: str = "mm",
    name: str = "length",
    require_unit: bool = False,
    positive: bool = False,
) -> float:
    """Parse a length with an optional unit: '2.5m', '2500mm', '98in'.

    Parameters
    ----------
    text : str or float [unit in the text, else ``default``]
        Number with an optional unit among mm, cm, m, in (case-insensitive).
    default : str
        Unit of a bare number (default ``'mm'``).
    name : str
        Parameter name for the error message.
    require_unit : bool
        Refuse a bare number (a float, or text without a unit).
    positive : bool
        Refuse a length <= 0.

    Returns
    -------
    length : float [mm]

    Raises
    ------
    InvalidParameter
        Malformed text, an unknown or (with ``require_unit``) missing unit, a
        non-finite value, or (with ``positive``) a value <= 0.
    """
    how = {"forms": LENGTH_FORMS, "require_unit": require_unit, "positive": positive}
    return _parse(name, text, _LENGTH, default, how)
