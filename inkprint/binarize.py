"""Grey scan -> ink mask (section 4.1.1: "converted from grey-scale to black-and-white").

Methods: ``otsu`` (default; global, from the grey histogram), ``fixed`` (a given
threshold) and ``sauvola`` (local, for unevenly lit or inked scans). Ink is darker
than the threshold. The threshold used is kept in the result (for Sauvola, the local
threshold map's median). Specks (paper grain, dust) stay in the sheet's mask: they
are removed per print with :func:`remove_specks` (``speck_area_mm2`` of
:class:`inkprint.AnalysisOptions`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .coords import mm_to_px_length
from .errors import AllInk, InvalidInput, NoInk
from .options import AnalysisOptions, resolve_options

METHODS = ("otsu", "fixed", "sauvola")


@dataclass(frozen=True)
class Binarization:
    """An ink mask and the threshold that made it.

    Attributes
    ----------
    mask : (rows, cols) bool
        Ink: pixels darker than ``level`` (specks included).
    threshold : float [grey level in [0, 1]]
        Grey level used (median of the local map for Sauvola).
    method : str
        'otsu', 'fixed' or 'sauvola'.
    level : float or (rows, cols) float32
        The threshold itself (scalar, or the local map), for re-thresholding.
    """

    mask: np.ndarray
    threshold: float
    method: str
    level: object


def threshold_level(
    grey,
    *,
    method: str = "otsu",
    threshold: float | None = None,
    window_px: int = 51,
    k: float = 0.2,
):
    """Threshold for ``grey``: a scalar, or a local map for ``sauvola``.

    Parameters
    ----------
    grey : (rows, cols) float in [0, 1]
        1 = paper, 0 = ink.
    method : {'otsu', 'fixed', 'sauvola'}
    threshold : float, optional
        Grey level in (0, 1) for ``method='fixed'``.
    window_px : int [px]
        Sauvola window (made odd).
    k : float
        Sauvola's k.

    Returns
    -------
    float or (rows, cols) float32
        Grey level below which a pixel is ink.
    """
    if method not in METHODS:
        raise InvalidInput("method", method, " | ".join(METHODS))
    if method == "fixed":
        if threshold is None or not (0.0 < float(threshold) < 1.0):
            raise InvalidInput("threshold", threshold, "(0, 1) grey level with method='fixed'")
        return float(threshold)
    if method == "otsu":
        from skimage.filters import threshold_otsu

        sample = grey[::2, ::2] if grey.size > 4_000_000 else grey
        if float(sample.max()) - float(sample.min()) < 1e-3:
            return float(sample.min()) - 1.0  # uniform page: nothing is ink
        return float(threshold_otsu(sample, nbins=256))
    from skimage.filters import threshold_sauvola

    w = int(window_px) | 1
    return threshold_sauvola(grey, window_size=max(w, 3), k=float(k)).astype(np.float32)


def remove_specks(mask, min_pixels: int) -> np.ndarray:
    """Drop 8-connected ink blobs smaller than ``min_pixels``.

    Parameters
    ----------
    mask : (h, w) bool
        Ink.
    min_pixels : int [px]
        Blobs with fewer pixels are removed (<= 1: nothing is removed).

    Returns
    -------
    (h, w) bool
    """
    import cv2

    if min_pixels <= 1:
        return mask
    _, labels, stats, _ = cv2.connectedComponentsWithStats(mask.astype(np.uint8), connectivity=8)
    keep = stats[:, cv2.CC_STAT_AREA] >= min_pixels
    keep[0] = False
    return keep[labels]


def binarize(
    grey,
    *,
    mm_per_px: float,
    method: str = "otsu",
    threshold: float | None = None,
    window_mm: float = 15.0,
    k: float = 0.2,
    scale_level: float = 1.0,
    options: AnalysisOptions | None = None,
) -> Binarization:
    """Binarize a grey scan (1 = paper, 0 = ink).

    Specks are removed per print later (:func:`remove_specks` on each group's box):
    cheaper than on the whole sheet, and a speck far from any print only forms a
    group too small to be a print.

    Parameters
    ----------
    grey : (rows, cols) float in [0, 1]
    mm_per_px : float [mm / px]
        Scale (the Sauvola window is physical).
    method : {'otsu', 'fixed', 'sauvola'}
    threshold : float, optional
        Grey level in (0, 1) for ``method='fixed'``.
    window_mm : float [mm]
        Sauvola window.
    k : float
        Sauvola's k.
    scale_level : float
        Multiply the threshold (the sensitivity band uses 0.9 and 1.1).
    options : AnalysisOptions, optional
        Uses ``min_ink_fraction`` and ``max_ink_fraction`` (defaults when None).

    Returns
    -------
    Binarization

    Raises
    ------
    NoInk, AllInk, InvalidInput
    """
    opts = resolve_options(options)
    if not (np.isfinite(window_mm) and window_mm > 0):
        raise InvalidInput("window_mm", window_mm, "> 0 mm (the Sauvola window)")
    level = threshold_level(
        grey,
        method=method,
        threshold=threshold,
        window_px=round(mm_to_px_length(window_mm, mm_per_px)),
        k=k,
    )
    level = level * scale_level
    mask = grey < level
    frac = float(mask.mean())
    if frac > opts.max_ink_fraction:
        raise AllInk(
            f"{100 * frac:.0f} % of the sheet is darker than the threshold: no paper to measure against"
        )
    if frac < opts.min_ink_fraction:
        raise NoInk("no ink on the sheet (blank page)")
    med = float(level) if np.ndim(level) == 0 else float(np.median(level))
    return Binarization(mask=mask, threshold=med, method=method, level=level)
