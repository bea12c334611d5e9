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


def _parse(name: str, text: str | float, table: dict[str, float], default: str) -> float:
    if isinstance(text, int | float):
        return float(text) * table[default]
    m = _NUM.match(str(text))
    if not m:
        raise InvalidParameter(name, text, f"a number with an optional unit ({', '.join(table)})")
    unit = (m.group(2) or default).lower().replace("^", "")
    if unit not in table:
        raise InvalidParameter(name, text, f"a unit among {', '.join(table)}")
    value = float(m.group(1)) * table[unit]
    if not math.isfinite(value):
        raise InvalidParameter(name, text, "a finite number")
    return value


def parse_pressure(text: str | float, *, default: str = "bar", name: str = "pressure") -> float:
    """'4bar', '60 psi', '400kPa', '0.4MPa' -> N/mm^2 (a bare number is in ``default``)."""
    return _parse(name, text, _PRESSURE, default)


def parse_force(text: str | float, *, default: str = "n", name: str = "load") -> float:
    """'400N', '40kg', '90lb' -> N (kg means kilogram-force, g = 9.81 m/s^2)."""
    return _parse(name, text, _FORCE, default)


def parse_length(text: str | float, *, default: str = "mm", name: str = "length") -> float:
    """'2.5m', '2500mm', '98in' -> mm."""
    return _parse(name, text, _LENGTH, default)
