"""Exception hierarchy of :mod:`inkprint`.

A single call raises; in a batch every one of these becomes an error row for its
file and the batch goes on.
"""

from __future__ import annotations

import math
from typing import Any


class InkPrintError(Exception):
    """Base class of every error raised by :mod:`inkprint`."""


class InvalidInput(InkPrintError, ValueError):
    """A parameter is outside what the function accepts (names the parameter)."""

    def __init__(self, name: str, value: Any, allowed: str) -> None:
        self.name, self.value, self.allowed = name, value, allowed
        super().__init__(f"{name} = {value!r} is invalid: allowed {allowed}")


class ScanReadError(InkPrintError):
    """The file cannot be read as a scan (empty, truncated, not an image, bad PDF)."""


class ImageTooLarge(ScanReadError):
    """The image is larger than ``AnalysisOptions.max_pixels`` (decompression-bomb guard)."""


class ScaleMissing(InkPrintError):
    """No scale: the file has no usable DPI and none was given (``--dpi`` or
    ``--mm-per-px``), and pixels were not asked for."""


class ScaleUntrusted(ScaleMissing):
    """The file's DPI is 72 or 96, the default of cameras and screen software, not a
    scanner's resolution: give ``--dpi`` (or ``--trust-dpi`` if it is right)."""


class NoInk(InkPrintError):
    """No print found on the sheet (blank page, or only specks and marks)."""


class AllInk(InkPrintError):
    """The sheet is (nearly) all ink: no paper to threshold against."""


class OutputLocked(InkPrintError):
    """Another batch is writing the same output table (its lock file is held)."""


def check_mm_per_px(mm_per_px) -> float:
    """The scale given to a public step (``binarize``, ``sort_ink``, ``edge_spots``,
    ``find_scales``, ``tread_turn``), checked.

    Parameters
    ----------
    mm_per_px : float [mm / px]
        A positive finite scale (1 without one: pixels).

    Returns
    -------
    float [mm / px]

    Raises
    ------
    InvalidInput
        Naming ``mm_per_px`` when it is not a positive finite number.
    """
    try:
        value = float(mm_per_px)
    except (TypeError, ValueError):
        raise InvalidInput("mm_per_px", mm_per_px, "> 0 [mm / px], finite") from None
    if not (value > 0 and math.isfinite(value)):
        raise InvalidInput("mm_per_px", mm_per_px, "> 0 [mm / px], finite")
    return value


def check_points(name: str, points, unit: str):
    """Points given to a public step (``ruler.on_scale``, ``sites.fit_lattice``,
    ``sites.nearest_site``), checked: a (k, 2) float array of finite numbers.

    Parameters
    ----------
    name : str
        The parameter's name, for the error.
    points : array_like
    unit : str
        What the two columns are, for the error ('(col, row) pixels').

    Returns
    -------
    (k, 2) float ndarray

    Raises
    ------
    InvalidInput
        Naming ``name`` when the points are not (k, 2) finite numbers (a 1-D array is
        not reshaped: its pairing would be a guess).
    """
    import numpy as np  # (here: the command line parses its options before numpy loads)

    try:
        pts = np.asarray(points, float)
    except (TypeError, ValueError):
        raise InvalidInput(name, points, f"(k, 2) {unit}") from None
    if pts.ndim != 2 or pts.shape[1] != 2:
        raise InvalidInput(name, pts.shape, f"(k, 2) {unit}")
    if not np.isfinite(pts).all():
        raise InvalidInput(name, "non-finite values", f"(k, 2) finite {unit}")
    return pts
