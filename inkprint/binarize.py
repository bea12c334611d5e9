"""Grey scan -> ink mask (section 4.1.1: "converted from grey-scale to black-and-white").

Methods: ``otsu`` (default; global, from the grey histogram), ``fixed`` (a given
threshold) and ``sauvola`` (local). Uneven light is flattened before thresholding
(:func:`inkprint.light.prepare_page`), so the global threshold holds under a
gradient or a shadow. Ink is darker than the threshold. The work is done on 8-bit
grey (levels 0..255); the threshold is reported as a grey level in [0, 1] (for
Sauvola, the local threshold map's median). Specks (paper grain, dust) stay in the
sheet's mask: they are sorted out with the other marks (:mod:`inkprint.marks`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .components import cleared
from .coords import mm_to_px_length
from .errors import AllInk, InvalidInput, NoInk, check_mm_per_px
from .light import to_uint8
from .options import AnalysisOptions, resolve_options

METHODS = ("otsu", "fixed", "sauvola")
#: the two Otsu classes must differ by this much of the paper's level to be ink
MIN_CONTRAST = 0.25
#: on a sheet of almost only paper, ink is this many grain deviations below it ...
SPARSE_NOISE_SIGMAS = 6.0
#: ... in at least this many pixels (else the sheet is blank)
SPARSE_MIN_PIXELS = 50


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
    level : float or (rows, cols) float32 [0..255]
        The threshold itself on the 8-bit grey (scalar, or the local map), for
        re-thresholding.
    """

    mask: np.ndarray
    threshold: float
    method: str
    level: object


def _otsu(work: np.ndarray, sheet: np.ndarray | None = None) -> float:
    """Otsu's level on 8-bit grey [0..255] (ink is below it); a page without two
    distinct grey classes (blank, uniform, faint grain) raises NoInk. ``sheet``
    (bool, or None: all) holds the pixels of the sparse-ink fallback's histogram
    (:func:`_sparse_ink_level`)."""
    import cv2

    hist = cv2.calcHist([work], [0], None, [256], [0, 256]).ravel().astype(float)
    if np.count_nonzero(hist) < 2:
        raise NoInk("no ink on the sheet (blank page: a single grey level)")
    levels = np.arange(256.0)
    w, m = np.cumsum(hist)[:-1], np.cumsum(hist * levels)[:-1]
    total, msum = hist.sum(), float(hist @ levels)
    mu0 = np.divide(m, w, out=np.zeros(255), where=w > 0)
    mu1 = np.divide(msum - m, total - w, out=np.zeros(255), where=total > w)
    t = int(np.argmax(w * (total - w) * (mu0 - mu1) ** 2))  # between-class variance
    ink, paper = float(mu0[t]), float(mu1[t])
    if paper - ink >= MIN_CONTRAST * paper:
        return float(t + 1)  # ink: grey <= t, i.e. grey < t + 1
    if sheet is not None:  # the paper's grain from the paper alone, not its fill
        where = np.asarray(sheet, bool).view(np.uint8)
        hist = cv2.calcHist([work], [0], where, [256], [0, 256]).ravel().astype(float)
    sparse = _sparse_ink_level(hist, levels)
    if sparse is not None:
        return sparse
    raise NoInk(
        f"no print found: nothing on the sheet is much darker than the paper "
        f"(darkest class {ink / 255:.2f} vs paper {paper / 255:.2f})"
    )


def _sparse_ink_level(hist: np.ndarray, levels: np.ndarray) -> float | None:
    """The level half-way between the paper (the median grey) and the ink (the
    median of the pixels ``MIN_CONTRAST`` darker than the paper and
    ``SPARSE_NOISE_SIGMAS`` of its grain) when there are at least
    ``SPARSE_MIN_PIXELS`` of those; else None.

    On a sheet that is almost all paper, Otsu's two classes are the paper's own
    lighter and darker grain: one 12 x 3 mm print alone on a letter sheet (0.05 %
    of it, inked at 0.6) gave "nothing darker than the paper" (independent set 1,
    file 1). Otsu is kept wherever its classes differ (a sheet with a bicycle
    print), so its level does not change there."""
    cum = np.cumsum(hist)
    total = cum[-1]
    paper = float(np.searchsorted(cum, 0.5 * total))  # the median grey
    q = [np.searchsorted(cum, f * total) for f in (0.25, 0.75)]
    sigma = float(q[1] - q[0]) / 1.349  # the paper's grain (interquartile range)
    bound = min(paper * (1.0 - MIN_CONTRAST), paper - SPARSE_NOISE_SIGMAS * sigma)
    dark = hist * (levels < bound)
    n = float(dark.sum())
    if n < SPARSE_MIN_PIXELS:
        return None
    ink = float(np.searchsorted(np.cumsum(dark), 0.5 * n))  # their median grey
    return 0.5 * (paper + ink) + 0.5


def threshold_level(
    grey,
    *,
    method: str = "otsu",
    threshold: float | None = None,
    window_px: int = 51,
    k: float = 0.2,
    sheet: np.ndarray | None = None,
):
    """Threshold for ``grey``: a scalar, or a local map for ``sauvola``.

    Parameters
    ----------
    grey : (rows, cols) uint8 [0..255], or float in [0, 1]
        Light paper, dark ink.
    method : {'otsu', 'fixed', 'sauvola'}
    threshold : float, optional
        Grey level in (0, 1) for ``method='fixed'``.
    window_px : int [px]
        Sauvola window (made odd).
    k : float
        Sauvola's k.
    sheet : (rows, cols) bool, optional
        The paper's pixels (:attr:`inkprint.light.Page.sheet`): where Otsu finds no
        ink, the sparse-ink fallback's histogram is taken over them only. Off a
        photographed sheet the work is white fill; in the histogram it made the
        paper's grain look wide (its interquartile range spanned paper to fill), so
        tiny prints alone on a photographed sheet gave "nothing darker than the
        paper" (held-out sets 11 and 12: 3 sheets, 5 prints). Otsu's own level is
        taken over the whole image as before (over the sheet alone it moved 0.016
        lower on a photographed sheet, held-out set 8 sheet 118, and a print's tip
        knobs were set aside).

    Returns
    -------
    float or (rows, cols) float32 [0..255]
        8-bit grey level below which a pixel is ink.

    Raises
    ------
    NoInk
        (Otsu) No two distinct grey classes: a blank or uniform page.
    InvalidInput
        Unknown method, a fixed threshold outside (0, 1), or a ``sheet`` not of the
        grey's shape.
    """
    if method not in METHODS:
        raise InvalidInput("method", method, " | ".join(METHODS))
    work = to_uint8(grey)
    if sheet is not None and np.shape(sheet) != work.shape:
        raise InvalidInput(
            "sheet", f"a mask of shape {np.shape(sheet)}", f"a bool mask of shape {work.shape}"
        )
    if method == "fixed":
        if threshold is None or not (0.0 < float(threshold) < 1.0):
            raise InvalidInput("threshold", threshold, "(0, 1) grey level with method='fixed'")
        return 255.0 * float(threshold)
    if method == "otsu":
        return _otsu(work, sheet)
    from skimage.filters import threshold_sauvola

    w = int(window_px) | 1
    return 255.0 * threshold_sauvola(work / 255.0, window_size=max(w, 3), k=float(k)).astype(
        np.float32
    )


def below(work: np.ndarray, level) -> np.ndarray:
    """``work < level`` for 8-bit grey.

    For a scalar level the comparison is made with an 8-bit bound, a few times
    faster than numpy's comparison of every pixel as a float, with the same result:
    an integer grey ``x`` is below ``L`` exactly when it is below ``ceil(L)``.

    Parameters
    ----------
    work : (rows, cols) uint8
    level : float or (rows, cols) array
        Grey level [0..255] (a map for Sauvola).

    Returns
    -------
    (rows, cols) bool
    """
    if work.dtype != np.uint8 or np.ndim(level) != 0 or not np.isfinite(level):
        return work < level
    bound = math.ceil(float(level))
    if bound > 255:
        return np.ones(work.shape, bool)
    return work < np.uint8(max(bound, 0))


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
    mb = np.asarray(mask, bool)
    n, labels = cv2.connectedComponents(mb.view(np.uint8), connectivity=8)
    if n <= 1:
        return np.zeros(mb.shape, bool)
    # areas from the ink pixels only (OpenCV's statistics sum over every pixel)
    flat = np.flatnonzero(mb)
    lab = labels.ravel()[flat]
    keep = np.bincount(lab, minlength=n) >= min_pixels
    return cleared(mb, flat[~keep[lab]])


def binarize(
    grey,
    *,
    mm_per_px: float,
    method: str = "otsu",
    threshold: float | None = None,
    window_mm: float = 15.0,
    k: float = 0.2,
    scale_level: float = 1.0,
    sheet: np.ndarray | None = None,
    options: AnalysisOptions | None = None,
) -> Binarization:
    """Binarize a grey scan (light paper, dark ink).

    Parameters
    ----------
    grey : (rows, cols) uint8 [0..255], or float in [0, 1]
        E.g. :attr:`inkprint.light.Page.work`.
    mm_per_px : float [mm / px]
        Scale (the Sauvola window is physical).
    method : {'otsu', 'fixed', 'sauvola'}
    threshold : float, optional
        Grey level in (0, 1) for ``method='fixed'``.
    window_mm : float [mm]
        Sauvola window.
    k : float
        Sauvola's k.
    sheet : (rows, cols) bool, optional
        The paper's pixels, for the histogram of Otsu's sparse-ink fallback
        (:func:`threshold_level`).
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
    mm_per_px = check_mm_per_px(mm_per_px)
    opts = resolve_options(options)
    if not (np.isfinite(window_mm) and window_mm > 0):
        raise InvalidInput("window_mm", window_mm, "> 0 mm (the Sauvola window)")
    work = to_uint8(grey)
    level = threshold_level(
        work,
        method=method,
        threshold=threshold,
        window_px=round(mm_to_px_length(window_mm, mm_per_px)),
        k=k,
        sheet=sheet,
    )
    level = level * scale_level
    mask = below(work, level)
    frac = float(np.count_nonzero(mask)) / mask.size
    if frac > opts.max_ink_fraction:
        raise AllInk(
            f"{100 * frac:.0f} % of the sheet is darker than the threshold: no paper to measure against"
        )
    if frac < opts.min_ink_fraction:
        raise NoInk("no ink on the sheet (blank page)")
    med = float(level) if np.ndim(level) == 0 else float(np.median(level))
    return Binarization(mask=mask, threshold=med / 255.0, method=method, level=level)
