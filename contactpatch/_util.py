"""Small shared helpers for table values (CSV cells arrive as strings)."""

from __future__ import annotations

import math


def number(v) -> float | None:
    """A finite float from a table cell, or None (empty, text, NaN, inf)."""
    if v is None or v == "":
        return None
    try:
        x = float(v)
    except (TypeError, ValueError):
        return None
    return x if math.isfinite(x) else None


def number_or_nan(v) -> float:
    """Like :func:`number`, with NaN for missing values (for arrays and plots)."""
    x = number(v)
    return math.nan if x is None else x
