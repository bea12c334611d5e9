"""Light and page: flatten uneven illumination and find the page in a photo.

A phone photo of a print sheet has a lighting gradient and shadows: with one global
threshold the dark side of the paper becomes "ink" (the issue's reproducer: width
+337 %). The paper's brightness is estimated at a large scale (``light_scale_mm`` of
:class:`inkprint.AnalysisOptions`): a grey closing removes the ink (anything
narrower than twice the scale), solid ink wider than that (a large slick print) is
recognised by its darkness (below 45 % of the paper) and filled in from around it,
and a light blur smooths the estimate. Where the estimate varies by more than
``light_tolerance`` over the page, the image is divided by it (the reflectance:
ink-to-paper contrast is kept under a shadow as in full light) before thresholding,
and the sheet says so.

A photo shows the table around the page: a dark frame around a bright
quadrilateral. The table is masked out (it is not ink); the page's corners tell
whether the camera looked at it flat-on. A page whose corner angles depart from
90 degrees by more than ``perspective_tolerance_deg`` has no single mm scale: its
prints are flagged ``perspective`` rather than measured silently wrong. A print
touching the page's edge (or the image's) is ``clipped``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .components import components_with_stats
from .coords import mm_to_px_length
from .options import AnalysisOptions, resolve_options

#: background estimate pixel [mm]
LIGHT_PX_MM = 2.0
#: solid ink below this fraction of the paper's brightness is not shade
SHADE_FLOOR = 0.3


@dataclass(frozen=True)
class Page:
    """A sheet ready to threshold.

    Attributes
    ----------
    work : (rows, cols) uint8
        Grey levels: the scan's own (8-bit) or, with ``flattened``, divided by the
        paper's brightness; outside the page of a photo, white.
    flattened : bool
        Whether uneven light was flattened.
    light_range : (low, high) float [-]
        The paper's brightness over the page relative to its brightest (1st and
        99th percentiles: high is 1).
    sheet : (rows, cols) bool or None
        The page inside a photo (None: the whole image is the page).
    corner_angles : tuple of float [deg]
        Corner angles of the page in a photo (empty otherwise).
    flags : tuple of str
        ``'perspective'`` when the page is not flat-on.
    warnings : tuple of str
        What was done or found (uneven light, perspective, page outline).
    """

    work: np.ndarray = field(repr=False)
    flattened: bool = False
    light_range: tuple[float, float] = (1.0, 1.0)
    sheet: np.ndarray | None = field(default=None, repr=False)
    corner_angles: tuple = ()
    flags: tuple = ()
    warnings: tuple = ()


def to_uint8(pixels) -> np.ndarray:
    """Grey levels as uint8 (0 = black, 255 = white); uint8 input is returned as is.

    Parameters
    ----------
    pixels : (rows, cols) uint8, uint16 or float32 in [0, 1]

    Returns
    -------
    (rows, cols) uint8
    """
    a = np.asarray(pixels)
    if a.dtype == np.uint8:
        return a
    if a.dtype == np.uint16:
        return (a >> 8).astype(np.uint8)
    return (np.clip(a, 0.0, 1.0) * 255.0 + 0.5).astype(np.uint8)


def _disk(radius: int):
    import cv2

    r = max(int(radius), 1)
    return cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (2 * r + 1, 2 * r + 1))


def _small(work: np.ndarray, f: int) -> np.ndarray:
    """``work`` shrunk ``f`` times (box average; the last ``< f`` rows and columns
    are left out: the integer factor is OpenCV's fast path)."""
    import cv2

    h, w = work.shape
    hh, ww = max(1, h // f), max(1, w // f)
    return cv2.resize(work[: hh * f, : ww * f], (ww, hh), interpolation=cv2.INTER_AREA)


@dataclass(frozen=True)
class _Frame:
    """The page found in a photo, on the small image: mask, corners, angles."""

    mask: np.ndarray
    corners: np.ndarray | None
    angles: tuple


def _corner_angles(quad: np.ndarray) -> tuple:
    """Interior angles [deg] of a quadrilateral (4, 2)."""
    out = []
    for k in range(4):
        a, b, c = quad[k - 1], quad[k], quad[(k + 1) % 4]
        u, v = a - b, c - b
        cos = float(np.dot(u, v) / (np.linalg.norm(u) * np.linalg.norm(v) + 1e-12))
        out.append(float(np.degrees(np.arccos(np.clip(cos, -1, 1)))))
    return tuple(out)


def find_page(small: np.ndarray, paper: float) -> _Frame | None:
    """The page of a photo on a darker table, on the small image (None: a scan).

    Parameters
    ----------
    small : (h, w) uint8
        The sheet at ~1 mm per pixel.
    paper : float
        The paper's grey level.

    Returns
    -------
    _Frame or None
    """
    import cv2

    h, w = small.shape
    b = max(2, int(0.02 * min(h, w)))
    ring = np.concatenate(
        [small[:b].ravel(), small[-b:].ravel(), small[:, :b].ravel(), small[:, -b:].ravel()]
    )
    table = float(np.median(ring))
    if table > 0.6 * paper:
        return None
    bright = (small > 0.5 * (table + paper)).astype(np.uint8)
    n, lab, stats, _ = components_with_stats(bright, connectivity=4)
    if n < 2:
        return None
    k = 1 + int(np.argmax(stats[1:, cv2.CC_STAT_AREA]))
    if stats[k, cv2.CC_STAT_AREA] < 0.2 * h * w:
        return None
    page = (lab == k).astype(np.uint8)
    contours, _ = cv2.findContours(page, cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_NONE)
    outline = max(contours, key=cv2.contourArea)
    if not _sharp(small, outline.reshape(-1, 2), paper - table, b):
        return None  # a soft edge: shade, not the page's edge on a table
    hull = cv2.convexHull(outline)
    mask = np.zeros_like(page)
    cv2.fillPoly(mask, [hull], 1)
    quad = cv2.approxPolyDP(hull, 0.01 * cv2.arcLength(hull, True), True).reshape(-1, 2)
    if len(quad) != 4:
        return _Frame(mask.astype(bool), None, ())
    return _Frame(mask.astype(bool), quad.astype(float), _corner_angles(quad.astype(float)))


def _sharp(small: np.ndarray, pts: np.ndarray, contrast: float, border: int) -> bool:
    """Whether the bright region's edge is a sharp step (a page's edge: within ~2 mm)
    rather than a penumbra; ``pts`` are (x, y) outline points of the small image."""
    import cv2

    h, w = small.shape
    x, y = pts[:, 0], pts[:, 1]
    keep = (x > border) & (x < w - 1 - border) & (y > border) & (y < h - 1 - border)
    if keep.sum() < 8:
        return False
    g = small.astype(np.float32)
    mag = np.hypot(
        cv2.Sobel(g, cv2.CV_32F, 1, 0, ksize=3), cv2.Sobel(g, cv2.CV_32F, 0, 1, ksize=3)
    )
    mag = cv2.dilate(mag, np.ones((3, 3), np.uint8))  # the step's peak near the outline
    return float(np.median(mag[y[keep], x[keep]])) / 8.0 > 0.35 * contrast


def _background(small: np.ndarray, inside: np.ndarray, paper: float, radius: int) -> np.ndarray:
    """The paper's brightness over the small image (float32), ink removed."""
    import cv2

    s = np.where(inside, small, np.uint8(min(round(paper), 255)))
    bg = cv2.morphologyEx(s, cv2.MORPH_CLOSE, _disk(radius))
    solid = (bg < SHADE_FLOOR * paper) & inside
    if solid.any():  # ink too wide for the closing: fill in from around it
        bg = cv2.inpaint(bg, solid.astype(np.uint8), max(3, radius // 2), cv2.INPAINT_TELEA)
    bg = cv2.GaussianBlur(bg.astype(np.float32), (0, 0), 1.0)
    return np.maximum(bg, 1.0)


def _frame_warnings(frame: _Frame | None, opts: AnalysisOptions) -> tuple[tuple, tuple]:
    if frame is None:
        return (), ()
    if frame.corners is None:
        return (), (
            "a page on a darker surround was found but its outline is not a clean "
            "quadrilateral: perspective not checked",
        )
    worst = max(abs(a - 90.0) for a in frame.angles)
    if worst > opts.perspective_tolerance_deg:
        lo, hi = min(frame.angles), max(frame.angles)
        return ("perspective",), (
            f"the page is not flat-on to the camera (corner angles {lo:.1f}-{hi:.1f} deg): "
            f"no single scale, lengths would be off; photograph it square-on or scan it",
        )
    return (), ()


def prepare_page(scan, *, options: AnalysisOptions | None = None) -> Page:
    """Flatten uneven light and find the page in a photo (see the module's notes).

    Parameters
    ----------
    scan : inkprint.Scan
    options : AnalysisOptions, optional
        Uses ``light_tolerance``, ``light_scale_mm`` and
        ``perspective_tolerance_deg`` (defaults when None).

    Returns
    -------
    Page
    """
    import cv2

    opts = resolve_options(options)
    work = to_uint8(scan.pixels)
    f = max(1, round(mm_to_px_length(LIGHT_PX_MM, scan.mm_per_px))) if scan.unit == "mm" else 4
    small = _small(work, f)
    paper = float(np.percentile(small, 95))
    frame = find_page(small, paper)
    inside = frame.mask if frame is not None else np.ones(small.shape, bool)
    radius = max(2, round(mm_to_px_length(opts.light_scale_mm, scan.mm_per_px) / f))
    bg = _background(small, inside, paper, radius)
    lo, hi = (float(v) for v in np.percentile(bg[inside], [1, 99]))
    lo, hi = lo / hi, 1.0
    flags, warnings = _frame_warnings(frame, opts)
    flat = 1.0 - lo > opts.light_tolerance
    if flat:
        full = cv2.resize(bg, (work.shape[1], work.shape[0]), interpolation=cv2.INTER_LINEAR)
        work = cv2.divide(work, full, scale=paper, dtype=cv2.CV_8U)
        warnings += (
            f"uneven light: the paper is {100 * lo:.0f} % as bright in its darkest part as "
            f"in its brightest; flattened before thresholding",
        )
    sheet = None
    if frame is not None:
        sheet = _full_mask(frame.mask, f, work.shape)
        work = np.where(sheet, work, np.uint8(255))
    return Page(work, flat, (lo, hi), sheet, frame.angles if frame else (), flags, warnings)


def _full_mask(small_mask: np.ndarray, f: int, shape) -> np.ndarray:
    """The small image's page mask at full resolution, less a 2-pixel rim (the
    page's own edge is neither paper nor ink)."""
    import cv2

    m = cv2.erode(small_mask.astype(np.uint8), np.ones((3, 3), np.uint8), iterations=2)
    full = cv2.resize(m, None, fx=f, fy=f, interpolation=cv2.INTER_NEAREST)[: shape[0], : shape[1]]
    if full.shape != tuple(shape):
        full = cv2.copyMakeBorder(
            full, 0, shape[0] - full.shape[0], 0, shape[1] - full.shape[1], cv2.BORDER_REPLICATE
        )
    return full.astype(bool)


__all__ = ["Page", "find_page", "prepare_page", "to_uint8"]
