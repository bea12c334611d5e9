"""The one place where image (row, col) pixels become (x, y) millimetres.

Continuous pixel coordinates: pixel ``(r, c)`` covers rows ``[r, r + 1)`` and
columns ``[c, c + 1)``, its centre is ``(r + 0.5, c + 0.5)``. Millimetres: ``x`` to
the right, ``y`` up, origin at the sheet's bottom-left corner.
"""

from __future__ import annotations

import numpy as np


def px_to_mm(rows, cols, *, n_rows: int, mm_per_px: float):
    """(rows, cols) continuous pixel coordinates -> (x, y) [mm]."""
    rows = np.asarray(rows, float)
    cols = np.asarray(cols, float)
    return cols * mm_per_px, (n_rows - rows) * mm_per_px


def mm_to_px(x, y, *, n_rows: int, mm_per_px: float):
    """(x, y) [mm] -> (rows, cols) continuous pixel coordinates."""
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    return n_rows - y / mm_per_px, x / mm_per_px


def area_mm2(n_pixels, mm_per_px: float) -> float:
    """Area of ``n_pixels`` whole pixels [mm^2]."""
    return float(n_pixels) * mm_per_px * mm_per_px
