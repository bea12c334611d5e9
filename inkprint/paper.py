"""A photographed page rectified from its corners, its scale from its paper size.

A phone photo of a print sheet taken at a tilt has no single scale: the near side
of the page is larger than the far side (keystone), and the file's DPI is a camera
default. Without more, :func:`inkprint.light.prepare_page` flags such a page
``perspective`` (held-out generator 6's tilted photos, keystone 4-10 %, read 6-13 %
short when measured at the file's DPI).

A flat page is a plane: the four corners of its outline in the photo fix the
homography that maps the photo back onto the page (exact for any pinhole camera,
whatever the tilt). The page's size in mm must be known: the photo alone does not
tell an A4 sheet from a letter sheet once it is tilted (an isosceles trapezoid fixes
neither the camera's focal length nor the page's aspect ratio). Given the paper
(``--paper A4``, ``letter``, ``WxH`` in mm; a manifest column ``paper``), the page
is warped onto a rectangle of that size at the photo's finest scale along the page
and measured there, its scale from the paper (``scale_source`` 'paper').

A page whose outline is no clean quadrilateral with its four corners in the image
cannot be rectified: an error names the fix (a photo with all four corners on a
darker surround, or a scan with ``--dpi``). A paper size whose aspect ratio is far
from the outline's (more than :data:`ASPECT_TOLERANCE`, beyond what a tilt
explains) is refused as the wrong paper.
"""

from __future__ import annotations

import re

import numpy as np

from .coords import mm_to_px_length
from .errors import InvalidInput, ScaleMissing

__all__ = ["PAPERS", "page_corners", "paper_size", "rectify_page"]

#: paper sizes [mm] (width, height: portrait)
PAPERS = {
    "a3": (297.0, 420.0),
    "a4": (210.0, 297.0),
    "a5": (148.0, 210.0),
    "letter": (215.9, 279.4),
    "legal": (215.9, 355.6),
}
#: the outline's aspect ratio (mean of opposite sides) may differ from the paper's by
#: this share: a tilt foreshortens one direction (10 % keystone: up to 6 %); A4 and
#: letter differ by 9 %, so a wrong choice between them is not always caught
ASPECT_TOLERANCE = 0.12
#: the page's outline is found on a grid of about this many cells across the image's
#: shorter side (~2 mm cells on a letter or A4 page filling the photo)
GRID_CELLS = 108
#: the page is what is brighter than this share of the way from the surround to the
#: paper (a shadow on the page darkens it by up to 45 %)
PAGE_LEVEL = 0.25
#: the page's outline is simplified to four corners with a tolerance up to this share
#: of its perimeter (the corners are then refined on the full image)
QUAD_MAX_EPS = 0.05
#: the rectified page's outermost pixels (the page's own edge, the table's blur) are
#: set to its paper's grey [px]
RIM_PX = 2

_SIZE = re.compile(r"\s*(\d+(?:\.\d+)?)\s*[x*]\s*(\d+(?:\.\d+)?)\s*(?:mm)?\s*", re.IGNORECASE)


def paper_size(paper) -> tuple[float, float]:
    """A paper's size [mm] (width, height; portrait) from its name or dimensions.

    Parameters
    ----------
    paper : str or (2,) float
        'A3', 'A4', 'A5', 'letter', 'legal' (any case), 'WxH' in mm ('210x297'),
        or (width, height) [mm].

    Returns
    -------
    (float, float) [mm]
        The shorter side first.

    Raises
    ------
    InvalidInput
        An unknown name, or sides that are not positive.
    """
    allowed = "A3, A4, A5, letter, legal, or WxH in mm (e.g. 210x297)"
    if isinstance(paper, str):
        name = paper.strip().lower()
        if name in PAPERS:
            return PAPERS[name]
        m = _SIZE.fullmatch(paper)
        if m is None:
            raise InvalidInput("paper", paper, allowed)
        w, h = float(m.group(1)), float(m.group(2))
    else:
        try:
            w, h = (float(v) for v in paper)
        except (TypeError, ValueError):
            raise InvalidInput("paper", paper, allowed) from None
    if not (np.isfinite(w) and np.isfinite(h) and w > 0 and h > 0):
        raise InvalidInput("paper", paper, "sides > 0 mm")
    return (min(w, h), max(w, h))


def _ordered(q: np.ndarray) -> np.ndarray:
    """Corners (4, 2) (x, y) ordered top-left, top-right, bottom-right, bottom-left."""
    q = np.asarray(q, float)
    c = q.mean(axis=0)
    ang = np.arctan2(q[:, 1] - c[1], q[:, 0] - c[0])
    q = q[np.argsort(ang)]  # clockwise on the image (y down), from the left
    k = int(np.argmin(q.sum(axis=1)))  # the top-left: smallest x + y
    return np.roll(q, -k, axis=0)


def _lit_page(small: np.ndarray) -> np.ndarray:
    """The page on the grid (bool): the largest region brighter than
    :data:`PAGE_LEVEL` of the way from the surround (the image's border) to the
    paper, holes filled. A shadow or vignette darkens a corner of the page below
    half-way (the brightness threshold of :func:`inkprint.light.find_page`), which
    then cuts it off the outline."""
    import cv2

    from .light import _border_strips

    border = np.concatenate([v.ravel() for v in _border_strips(small)[1]])
    table, paper = float(np.median(border)), float(np.percentile(small, 95))
    bright = (small > table + PAGE_LEVEL * (paper - table)).astype(np.uint8)
    n, lab, stats, _ = cv2.connectedComponentsWithStats(bright, connectivity=4)
    if n < 2:
        return np.zeros(small.shape, bool)
    k = 1 + int(np.argmax(stats[1:, cv2.CC_STAT_AREA]))
    page = (lab == k).astype(np.uint8)
    contours, _ = cv2.findContours(page, cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_NONE)
    filled = np.zeros_like(page)
    cv2.drawContours(filled, contours, -1, 1, -1)
    return filled.astype(bool)


def _quad(mask: np.ndarray) -> np.ndarray | None:
    """Four corners (x, y) [cells] of the page's outline (its mask on the grid): its
    hull simplified until four vertices are left (the grid's steps along a tilted
    side leave five or six at the usual 1 %), or None (no quadrilateral within
    :data:`QUAD_MAX_EPS` of the perimeter)."""
    import cv2

    pts = cv2.findNonZero(mask.astype(np.uint8))
    if pts is None:
        return None
    hull = cv2.convexHull(pts)
    perimeter = cv2.arcLength(hull, True)
    for eps in np.linspace(0.01, QUAD_MAX_EPS, 9):
        quad = cv2.approxPolyDP(hull, eps * perimeter, True).reshape(-1, 2)
        if len(quad) == 4:
            return quad.astype(float)
        if len(quad) < 4:
            return None
    return None


def page_corners(pixels: np.ndarray) -> np.ndarray | None:
    """The corners of the page in a photo of it on a darker surround.

    Parameters
    ----------
    pixels : (rows, cols) uint8, uint16 or float32
        The photo's grey levels (larger is lighter).

    Returns
    -------
    (4, 2) float [px] or None
        (x, y) of the corners, top-left, top-right, bottom-right, bottom-left,
        refined on the full image (:func:`inkprint.light.refine_corners`); None when
        no page with four corners inside the image was found.
    """
    from .light import _small, find_page, refine_corners, to_uint8

    work = to_uint8(pixels)
    cell = max(2, round(min(work.shape) / GRID_CELLS))
    small = _small(work, cell)
    frame = find_page(small, float(np.percentile(small, 95)))
    if frame is None:
        return None
    q = frame.corners if frame.corners is not None else _quad(_lit_page(small))
    if q is None or len(q) != 4:
        return None
    h, w = small.shape
    if q.min() <= 1 or q[:, 0].max() >= w - 2 or q[:, 1].max() >= h - 2:
        return None  # a corner at the image's edge: the page runs off it
    fine = refine_corners(work, q, cell)
    return None if fine is None else _ordered(fine)


def rectify_page(scan, paper):
    """The page of a photographed sheet warped onto a rectangle of its paper's size.

    Parameters
    ----------
    scan : inkprint.Scan
        The photo (its own scale is not used).
    paper : str or (2,) float
        The sheet's paper (:func:`paper_size`).

    Returns
    -------
    inkprint.Scan
        The page alone, flat, at the photo's finest scale along the page [mm / px],
        ``scale_source`` 'paper'.

    Raises
    ------
    ScaleMissing
        No page with four corners in the photo (a scan of the glass, a page running
        off the photo, no darker surround): give ``--dpi`` or photograph the whole
        page on a darker surface.
    InvalidInput
        ``paper`` unknown, or its aspect ratio far from the page's outline.
    """
    import dataclasses

    import cv2

    w_mm, h_mm = paper_size(paper)
    q = page_corners(scan.pixels)
    where = f"{scan.path or 'the image'}" + (f" page {scan.page}" if scan.n_pages > 1 else "")
    if q is None:
        raise ScaleMissing(
            f"{where}: --paper {paper}: no page with four corners on a darker surround "
            f"was found to rectify; photograph the whole page on a darker surface, or "
            f"give the scan's resolution with --dpi instead"
        )
    side = np.linalg.norm(np.roll(q, -1, axis=0) - q, axis=1)  # top, right, bottom, left
    across, down = 0.5 * (side[0] + side[2]), 0.5 * (side[1] + side[3])
    if across > down:  # a landscape page
        w_mm, h_mm = h_mm, w_mm
    found, expected = down / across, h_mm / w_mm
    if abs(found / expected - 1.0) > ASPECT_TOLERANCE:
        raise InvalidInput(
            "paper",
            paper,
            f"a sheet of the page's shape: its outline is {found:.2f}:1 in the photo, "
            f"{paper} is {expected:.2f}:1 (give its real size, e.g. 210x297)",
        )
    # the finest scale along the page: no detail of the near side is lost
    mm_per_px = min(w_mm / max(side[0], side[2]), h_mm / max(side[1], side[3]))
    wide, tall = mm_to_px_length(w_mm, mm_per_px), mm_to_px_length(h_mm, mm_per_px)
    cols, rows = int(np.ceil(wide)), int(np.ceil(tall))
    dst = np.float32([[0, 0], [wide, 0], [wide, tall], [0, tall]]) - 0.5
    h = cv2.getPerspectiveTransform(np.float32(q), dst)
    flat = cv2.warpPerspective(
        scan.pixels, h, (cols, rows), flags=cv2.INTER_LINEAR, borderMode=cv2.BORDER_REPLICATE
    )
    paper_grey = np.percentile(flat, 95).astype(flat.dtype)
    r = RIM_PX
    flat[:r], flat[-r:], flat[:, :r], flat[:, -r:] = paper_grey, paper_grey, paper_grey, paper_grey
    return dataclasses.replace(
        scan, pixels=np.ascontiguousarray(flat), mm_per_px=mm_per_px, scale_source="paper"
    )
