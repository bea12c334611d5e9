"""The one place where image pixels become millimetres (and back).

Image code works in continuous ``(row, col)`` pixel coordinates: pixel ``(r, c)``
covers rows ``[r, r + 1)`` and columns ``[c, c + 1)``, its centre is
``(r + 0.5, c + 0.5)``. Millimetres: ``x`` to the right, ``y`` up, origin at the
sheet's bottom-left corner. The scale is ``mm_per_px`` (square pixels); a resolution
in dots per inch converts to it here and nowhere else.
"""

from __future__ import annotations

import numpy as np

from tiremesh.units import MM_PER_IN

PT_PER_IN = 72.0  # PDF points per inch
MM_PER_CM = 10.0
#: rulers' tick pitches [mm]: millimetres, sixteenths and tenths of an inch (not half
#: millimetres: a millimetre scale read at twice the file's dpi would pass for one;
#: :mod:`inkprint.ruler`)
RULER_PITCHES_MM = (1.0, MM_PER_IN / 16, MM_PER_IN / 10)


def dpi_to_mm_per_px(dpi):
    """Scale of a scan from its resolution.

    Parameters
    ----------
    dpi : float or array [dots per inch]

    Returns
    -------
    mm_per_px : float or array [mm / px]
    """
    return MM_PER_IN / dpi


def mm_per_px_to_dpi(mm_per_px):
    """Resolution of a scan from its scale.

    Parameters
    ----------
    mm_per_px : float or array [mm / px]

    Returns
    -------
    dpi : float or array [dots per inch]
    """
    return MM_PER_IN / mm_per_px


def dots_per_cm_to_dpi(dots_per_cm):
    """Resolution in dots per centimetre (JPEG's JFIF unit 2) -> dots per inch.

    Parameters
    ----------
    dots_per_cm : float [dots per cm]

    Returns
    -------
    dpi : float [dots per inch]
    """
    return dots_per_cm * (MM_PER_IN / MM_PER_CM)


def pdf_px_per_pt(mm_per_px: float) -> float:
    """Render scale of a PDF page that gives pixels of ``mm_per_px``.

    Parameters
    ----------
    mm_per_px : float [mm / px]

    Returns
    -------
    float [px / pt]
        Pixels per PDF point (1/72 inch).
    """
    return mm_per_px_to_dpi(mm_per_px) / PT_PER_IN


def px_to_mm(rows, cols, *, n_rows: int, mm_per_px: float):
    """Continuous pixel coordinates -> sheet coordinates.

    Parameters
    ----------
    rows, cols : (n,) float [px]
        Continuous (row, col) image coordinates.
    n_rows : int
        Image height [px] (row 0 is the top of the sheet, ``y`` points up).
    mm_per_px : float [mm / px]

    Returns
    -------
    x, y : (n,) float [mm]
    """
    rows = np.asarray(rows, float)
    cols = np.asarray(cols, float)
    return cols * mm_per_px, (n_rows - rows) * mm_per_px


def mm_to_px(x, y, *, n_rows: int, mm_per_px: float):
    """Sheet coordinates -> continuous pixel coordinates (inverse of :func:`px_to_mm`).

    Parameters
    ----------
    x, y : (n,) float [mm]
    n_rows : int
        Image height [px].
    mm_per_px : float [mm / px]

    Returns
    -------
    rows, cols : (n,) float [px]
    """
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    return n_rows - y / mm_per_px, x / mm_per_px


def px_to_mm_length(length_px, mm_per_px: float):
    """A length (or distance) in pixels -> mm.

    Parameters
    ----------
    length_px : float or array [px]
    mm_per_px : float [mm / px]

    Returns
    -------
    float or array [mm]
    """
    return length_px * mm_per_px


def mm_to_px_length(length_mm, mm_per_px: float):
    """A length (or distance) in mm -> pixels (not rounded).

    Parameters
    ----------
    length_mm : float or array [mm]
    mm_per_px : float [mm / px]

    Returns
    -------
    float or array [px]
    """
    return length_mm / mm_per_px


def binned_mm_per_px(mm_per_px: float, factor: float) -> float:
    """Pixel size of an image binned (pooled, sampled) by ``factor`` pixels a side.

    Parameters
    ----------
    mm_per_px : float [mm / px]
        Pixel size of the full image.
    factor : float
        Pixels of the full image per binned pixel, along a side (below 1: finer).

    Returns
    -------
    float [mm / px]
    """
    return mm_per_px * factor


def area_px_to_mm2(n_pixels, mm_per_px: float):
    """Area of ``n_pixels`` whole pixels.

    Parameters
    ----------
    n_pixels : int, float or array [px]
    mm_per_px : float [mm / px]

    Returns
    -------
    float or array [mm^2]
        A float for a scalar ``n_pixels``.
    """
    if np.ndim(n_pixels) == 0:
        return float(n_pixels) * mm_per_px * mm_per_px
    return np.asarray(n_pixels, float) * mm_per_px * mm_per_px


def area_mm2_to_px(area_mm2, mm_per_px: float) -> int:
    """Smallest whole number of pixels covering ``area_mm2``.

    Parameters
    ----------
    area_mm2 : float [mm^2]
    mm_per_px : float [mm / px]

    Returns
    -------
    int [px]
    """
    return int(np.ceil(area_mm2 / mm_per_px**2))


__all__ = [
    "RULER_PITCHES_MM",
    "area_mm2_to_px",
    "area_px_to_mm2",
    "binned_mm_per_px",
    "dots_per_cm_to_dpi",
    "dpi_to_mm_per_px",
    "mm_per_px_to_dpi",
    "mm_to_px",
    "mm_to_px_length",
    "pdf_px_per_pt",
    "px_to_mm",
    "px_to_mm_length",
]
