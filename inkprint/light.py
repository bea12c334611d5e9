"""Light and page: flatten uneven illumination and find the page in a photo.

A phone photo of a print sheet has a lighting gradient and shadows: with one global
threshold the dark side of the paper becomes "ink" (the issue's reproducer: width
+337 %). The paper's brightness is estimated on a ~1 mm grid with the ink left out.
Ink is told from shade by being enclosed, not by its size (a shadow band is as wide
as a print): a print is a dark region with brighter paper all round it, the shade of
uneven light runs off the sheet. Every enclosed region darker than its lowest rim
by more than ``light_basin`` of :class:`inkprint.AnalysisOptions` is ink (a grey
reconstruction from the sheet's edge); at the edge itself ink is what lies below
``light_edge_ink`` of the paper around (a print run off the sheet). The paper is
filled in under the ink from around it. Where the estimate varies by more than
``light_tolerance`` over the page, the image is divided by it (the reflectance:
ink-to-paper contrast is kept under a shadow as in full light) before thresholding,
and the sheet says so (``uneven_light``, advisory). A print around which the light
changes by more than its ink lies below the threshold (a shadow's edge crossing a
lightly inked print) is flagged ``light_uncertain``: the paper filled in under it
may move its outline.

A photo shows the table around the page: a dark frame around a bright
quadrilateral. The table is masked out (it is not ink); the page's corners tell
whether the camera looked at it flat-on. A page whose corner angles depart from
90 degrees by more than ``perspective_tolerance_deg``, or whose opposite sides
differ by more than ``perspective_keystone`` (the corners found on a ~2 mm grid,
then refined on the full image, :func:`refine_corners`), has no single mm scale:
its prints are flagged ``perspective`` rather than measured silently wrong. A print
touching the page's edge (or the image's) is ``clipped``.

A scan of a page that does not cover the glass shows the scanner's dark bed (or
lid) as straight strips along one or two sides, wedges when the page is skewed: the
page is taken beyond their fitted inner edges, and only its corners inside the image
are judged for perspective (where its edge leaves the image is no corner).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from .components import components_with_stats
from .coords import binned_mm_per_px, mm_to_px_length
from .options import AnalysisOptions, resolve_options

#: background estimate pixel [mm] (the independent set's shadow edges are 3-15 mm soft)
LIGHT_PX_MM = 1.0
#: an ink region's edge on the background grid: its mixed pixels [px]
EDGE_PX = 2
#: the paper around a print whose light is judged: this far out of its ink region [px]
RING_PX = 3
#: a region at the page's edge is judged by its own edge within this of it [mm]
EDGE_NEAR_MM = 10.0
#: Jacobi sweeps of the harmonic fill under an ink region at most
RELAX_SWEEPS = 80
#: a scanner bed's strip along a side of a scan is at most this share of the image
#: across (a page shifted or skewed on the glass shows a few mm to a few cm)
BED_STRIP_MAX = 0.25
#: a bed strip runs along this share of its side at least (from a corner)
BED_STRIP_SHARE = 0.2
#: a bed strip may be deeper than its edge along this share of its side (punch
#: holes that meet it, besides the other strips at its ends)
BED_HOLES = 0.15
#: a bed strip's inner edge (the page's) lies within this of a straight line [px of
#: the ~2 mm grid]
BED_EDGE_PX = 1.5
#: the page's sides refined on the full image (:func:`refine_corners`): EDGE_PROFILES
#: profiles across each side, each the mean of EDGE_PROFILE_WIDTH parallel ones,
#: reaching EDGE_REACH grid cells either side; crossings off the fitted line by more
#: than EDGE_OUTLIER x their median distance are dropped
EDGE_PROFILES = 41
EDGE_PROFILE_WIDTH = 5
EDGE_REACH = 2.5
EDGE_OUTLIER = 4.0
#: passes of the basin fill at most (a sheet on the 2 mm grid converges in < 200)
_FILL_MAX_PASSES = 2000


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
    light : (h, w) float32 or None
        With ``flattened``: the paper's brightness on the ~1 mm grid of the estimate
        [log grey], filled in under the ink.
    light_ink : (h, w) bool or None
        With ``flattened``: the ink regions left out of that estimate.
    light_px : int
        Full-resolution pixels per pixel of ``light``.
    """

    work: np.ndarray = field(repr=False)
    flattened: bool = False
    light_range: tuple[float, float] = (1.0, 1.0)
    sheet: np.ndarray | None = field(default=None, repr=False)
    corner_angles: tuple = ()
    flags: tuple = ()
    warnings: tuple = ()
    light: np.ndarray | None = field(default=None, repr=False)
    light_ink: np.ndarray | None = field(default=None, repr=False)
    light_px: int = 1


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
    keystone: float | None = None  # of the refined corners (None: not refined)


def _corner_angles(quad: np.ndarray) -> tuple:
    """Interior angles [deg] of a quadrilateral (4, 2)."""
    out = []
    for k in range(4):
        a, b, c = quad[k - 1], quad[k], quad[(k + 1) % 4]
        u, v = a - b, c - b
        cos = float(np.dot(u, v) / (np.linalg.norm(u) * np.linalg.norm(v) + 1e-12))
        out.append(float(np.degrees(np.arccos(np.clip(cos, -1, 1)))))
    return tuple(out)


def _border_strips(small: np.ndarray) -> tuple[int, tuple]:
    """The strips along the four sides of an image where its surround shows (the
    table of a photo, a scanner's bed): their width [px], 2 % of the shorter side
    and 2 px at least, and the strips (top, bottom, left, right)."""
    b = max(2, int(0.02 * min(small.shape)))
    return b, (small[:b], small[-b:], small[:, :b], small[:, -b:])


def find_page(small: np.ndarray, paper: float) -> _Frame | None:
    """The page of a photo on a darker table, or of a scan whose dark bed shows
    along one or more sides (:func:`_bed_strips`), on the small image (None: the
    whole image is the page).

    Parameters
    ----------
    small : (h, w) uint8
        The sheet at ~2 mm per pixel.
    paper : float
        The paper's grey level.

    Returns
    -------
    _Frame or None
    """
    import cv2

    h, w = small.shape
    b, sides = _border_strips(small)
    # no table all round: a scanner's bed along a side, or a page running off a photo?
    bed = max(float(np.median(v)) for v in sides) > 0.6 * paper
    if bed:
        strips = _bed_strips(small, paper)
        if strips is None:
            return None
        table, beyond = strips
    else:
        table = float(np.median(np.concatenate([v.ravel() for v in sides])))
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
    # (a bed's strip can be thinner than the ring: its edge is judged to the rim)
    if not _sharp(small, outline.reshape(-1, 2), paper - table, 0 if bed else b):
        return None  # a soft edge: shade, not the page's edge on a table
    if bed:  # the page's edges as fitted: where a strip thins under a pixel too
        mask = beyond.astype(np.uint8)
        hull = cv2.convexHull(cv2.findNonZero(mask))
    else:
        hull = cv2.convexHull(outline)
        mask = np.zeros_like(page)
        cv2.fillPoly(mask, [hull], 1)
    quad = cv2.approxPolyDP(hull, 0.01 * cv2.arcLength(hull, True), True).reshape(-1, 2)
    if bed:  # the page runs off the image: only its own corners tell its angles
        inner = (quad[:, 0] > b) & (quad[:, 0] < w - 1 - b) & (quad[:, 1] > b)
        inner &= quad[:, 1] < h - 1 - b
        angles = _corner_angles(quad.astype(float))
        return _Frame(mask.astype(bool), quad.astype(float), tuple(np.compress(inner, angles)))
    if len(quad) != 4:
        return _Frame(mask.astype(bool), None, ())
    return _Frame(mask.astype(bool), quad.astype(float), _corner_angles(quad.astype(float)))


def refine_corners(work: np.ndarray, corners: np.ndarray, cell: float) -> np.ndarray | None:
    """The page's corners found on the ~2 mm grid, refined on the full image.

    Each side is found again where the grey crosses half-way between the table
    and the paper, along :data:`EDGE_PROFILES` short profiles across it (each the
    mean of :data:`EDGE_PROFILE_WIDTH` parallel ones, reaching :data:`EDGE_REACH`
    grid cells either side of the grid's side); a straight line is fitted to the
    crossings (total least squares, crossings off it by more than
    :data:`EDGE_OUTLIER` x their median distance dropped once: ink at the page's
    edge) and the corners are where the lines meet. On the grid a corner is known to
    a cell: a 2.8 % keystone read as 1.3 degrees, under the tolerance, while flat
    photos read up to 1.4 degrees (held-out set 14 sheet 54).

    Parameters
    ----------
    work : (h, w) uint8
        The photo's grey.
    corners : (4, 2) float [grid cells]
        (x, y) of the corners on the grid, in order round the page.
    cell : float [px]
        A grid cell's size in the image.

    Returns
    -------
    (4, 2) float [px] or None
        (x, y) of the corners in the image; None when a side is not found (too few
        crossings).
    """
    q = (np.asarray(corners, float) + 0.5) * cell  # the cells' centres [px]
    lines = []
    for k in range(4):
        line = _edge_line(work, q[k], q[(k + 1) % 4], EDGE_REACH * cell)
        if line is None:
            return None
        lines.append(line)
    out = []
    for k in range(4):  # corner k: where side k-1 meets side k
        (p1, d1), (p2, d2) = lines[k - 1], lines[k]
        m = np.column_stack([d1, -d2])
        if abs(np.linalg.det(m)) < 1e-6:
            return None
        t = np.linalg.solve(m, p2 - p1)
        out.append(p1 + t[0] * d1)
    return np.array(out)


def _edge_line(work: np.ndarray, a: np.ndarray, b: np.ndarray, reach: float):
    """``(point, direction)`` [px] of the page's edge near the side ``a``-``b``
    (:func:`refine_corners`), or None."""
    h, w = work.shape
    along = (b - a) / max(np.linalg.norm(b - a), 1e-9)
    normal = np.array([-along[1], along[0]])
    t = np.linspace(0.1, 0.9, EDGE_PROFILES)[:, None, None]
    s = np.arange(-np.ceil(reach), np.ceil(reach) + 1)[None, :, None]  # across [px]
    u = (np.arange(EDGE_PROFILE_WIDTH) - (EDGE_PROFILE_WIDTH - 1) / 2)[None, None, :]
    base = a + t[..., 0][..., None] * (b - a)  # (n, 1, 2)
    x = base[..., 0][..., None] + s * normal[0] + u * along[0]
    y = base[..., 1][..., None] + s * normal[1] + u * along[1]
    prof = _bilinear(work, x, y).mean(axis=2)  # (n, m)
    lo, hi = prof.min(axis=1, keepdims=True), prof.max(axis=1, keepdims=True)
    above = prof > 0.5 * (lo + hi)
    flips = above[:, 1:] != above[:, :-1]  # between sample j and j + 1
    centre = (prof.shape[1] - 1) / 2
    j = np.where(flips, np.abs(np.arange(flips.shape[1]) + 0.5 - centre), np.inf).argmin(axis=1)
    ok = flips[np.arange(len(j)), j] & (hi[:, 0] - lo[:, 0] > 0)
    ok &= (x.min(axis=(1, 2)) >= 0) & (y.min(axis=(1, 2)) >= 0)
    ok &= (x.max(axis=(1, 2)) <= w - 1) & (y.max(axis=(1, 2)) <= h - 1)
    if np.count_nonzero(ok) < EDGE_PROFILES // 2:
        return None
    rows = np.arange(len(j))[ok]
    j = j[ok]
    mid = 0.5 * (lo[ok, 0] + hi[ok, 0])
    f0, f1 = prof[rows, j], prof[rows, j + 1]
    frac = (mid - f0) / np.where(f1 != f0, f1 - f0, 1.0)
    across = s[0, :, 0][j] + frac
    pts = base[ok, 0, :] + across[:, None] * normal
    for _ in range(2):  # fit, drop the crossings far off it, fit again
        centre_pt = pts.mean(axis=0)
        _, _, vt = np.linalg.svd(pts - centre_pt)
        d = vt[0]
        off = np.abs((pts - centre_pt) @ np.array([-d[1], d[0]]))
        keep = off <= EDGE_OUTLIER * max(float(np.median(off)), 0.5)
        if keep.all() or np.count_nonzero(keep) < EDGE_PROFILES // 2:
            break
        pts = pts[keep]
    return centre_pt, d


def _bilinear(img: np.ndarray, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """``img`` at the points (x, y) [px], bilinear (clipped to the image)."""
    h, w = img.shape
    x = np.clip(x, 0, w - 1.001)
    y = np.clip(y, 0, h - 1.001)
    x0, y0 = np.floor(x).astype(int), np.floor(y).astype(int)
    fx, fy = x - x0, y - y0
    at = lambda r, c: img[r, c].astype(np.float32)  # the points only, not a copy of img
    top = at(y0, x0) * (1 - fx) + at(y0, x0 + 1) * fx
    bottom = at(y0 + 1, x0) * (1 - fx) + at(y0 + 1, x0 + 1) * fx
    return top * (1 - fy) + bottom * fy


def keystone(corners: np.ndarray) -> float:
    """How much a quadrilateral's opposite sides differ: the larger of the two
    relative differences, |1 - shorter / longer| (0 for a rectangle; a page
    photographed at a tilt, 1 - the far side's scale over the near side's).

    Parameters
    ----------
    corners : (4, 2) float
        In order round it.

    Returns
    -------
    float
    """
    q = np.asarray(corners, float)
    side = np.linalg.norm(np.roll(q, -1, axis=0) - q, axis=1)
    return float(max(1.0 - min(side[k], side[k + 2]) / max(side[k], side[k + 2]) for k in (0, 1)))


def _bed_strips(small: np.ndarray, paper: float) -> tuple[float, np.ndarray] | None:
    """The grey of a scanner's bed or lid showing beside a page that does not cover
    the glass (None: none shows). A bed strip runs along a side of the image from
    one of its corners over :data:`BED_STRIP_SHARE` of it or more, dark (below 0.6
    of the paper) from the image's edge in to a straight line (the page's edge,
    skewed or not: a strip as wide as :data:`BED_STRIP_MAX` of the image at most,
    its inner edge within :data:`BED_EDGE_PX` of a line, deeper only at its ends and
    where punch holes meet it, :data:`BED_HOLES`). A print cut by the image's edge
    is no strip: its edge is curved, its tread breaks the run.

    Parameters
    ----------
    small : (h, w) uint8
        The image at ~2 mm per pixel.
    paper : float
        The paper's grey level.

    Returns
    -------
    (level, page) or None
        The median grey of the strips (float) and the page, (h, w) bool: the image
        beyond every strip's fitted inner edge.
    """
    dark = small < 0.6 * paper
    if not dark.any():
        return None
    bed = float(np.median(small[dark]))
    strips = np.zeros(small.shape, bool)
    page = np.ones(small.shape, bool)
    for k in range(4):  # each side, turned to the top
        d = np.rot90(dark, k)
        inward, n = d.shape
        run = np.where(d.all(axis=0), inward, np.argmin(d, axis=0))  # dark run [px]
        # to a fraction of a pixel: the first pixel past the run is the edge's mixed
        # one (an integer depth on the 2 mm grid put a skewed page 1.6 deg off square)
        nxt = np.rot90(small, k)[np.minimum(run, inward - 1), np.arange(n)].astype(float)
        part = np.clip((paper - nxt) / max(paper - bed, 1.0), 0.0, 1.0)
        depth = np.where(run < inward, run + part, run)
        depth[depth < 0.5] = 0.0  # (paper's own noise: no strip)
        # deeper only near its ends, where the strip of a side beside it runs
        corner = int(BED_STRIP_MAX * n)
        t = np.arange(n)
        mid = (t >= corner) & (t < n - corner)
        if (depth[mid] > BED_STRIP_MAX * inward).any():
            continue
        fit = (depth > 0) & (depth <= BED_STRIP_MAX * inward)
        if np.count_nonzero(fit) < BED_STRIP_SHARE * n:
            continue  # too short a strip to tell from a print's cut edge
        line = np.polyfit(t[fit], depth[fit], 1)
        for _ in range(2):  # without what lies deeper: the corner's other strip, holes
            off = depth - np.maximum(np.polyval(line, t), 0.0)
            fit &= off <= BED_EDGE_PX
            line = np.polyfit(t[fit], depth[fit], 1)
        # a straight inner edge all along: where the strip thins out (the page's
        # edge skewed off the image) the line comes to 0 too; no break in it, and
        # deeper only at its ends or where a punch hole meets it
        off = depth - np.maximum(np.polyval(line, t), 0.0)
        deeper = off > BED_EDGE_PX
        if off.min() < -BED_EDGE_PX or np.count_nonzero(deeper & mid) > BED_HOLES * n:
            continue  # a curved or broken edge (a print's)
        s = np.rot90(strips, k)  # views: written through
        s[:] |= np.arange(inward)[:, None] < run[None, :]
        edge = np.polyval(line, t) + 1.0  # past the edge's mixed pixel
        np.rot90(page, k)[:] &= np.arange(inward)[:, None] >= edge[None, :]
    if not strips.any():
        return None
    return float(np.median(small[strips])), page


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


def _fill_basins(level: np.ndarray, seed: np.ndarray, open_: np.ndarray) -> np.ndarray:
    """Grey reconstruction by erosion (the "fill holes" of a grey image): every pixel
    raised to the lowest level at which a path joins it to the open pixels (off the
    page), whose levels are ``seed``. A dark region enclosed by brighter paper (a
    print) is raised to its rim; shade that runs off the sheet (a shadow band, a
    dark corner, a gradient) has a path off it no brighter than itself and is not
    raised. Repeated 3 x 3 erosion clipped from below; on the ~2 mm grid a sheet
    takes some 50-150 passes."""
    import cv2

    level = np.where(open_, seed, level).astype(np.float32)
    out = np.where(open_, seed, np.float32(level.max())).astype(np.float32)
    k = np.ones((3, 3), np.uint8)
    for _ in range(_FILL_MAX_PASSES // 8):
        prev = out
        for _ in range(8):
            out = np.maximum(cv2.erode(out, k), level)
        if np.array_equal(out, prev):
            break
    return out


def _edge_ink(
    raw: np.ndarray, inside: np.ndarray, around: np.ndarray, p: float, opts
) -> np.ndarray:
    """Dark regions touching the page's edge whose own edge is sharp: prints run off
    the sheet (bool, on ``raw``'s grid). Not enclosed, they would be taken for shade;
    shade's edges are soft (the independent set's: 3-15 mm), a print's rises to the
    paper within a pixel or two: a region darker than ``1 - light_basin`` of the
    paper around is ink when its edge's mean slope exceeds its depth over
    ``light_edge_rise_mm`` (a clipped print inked 0.35-0.45, lighter than
    ``light_edge_ink``, was lost with the light following it)."""
    import cv2

    dark = inside & (raw < around + np.log(1.0 - opts.light_basin))
    rim = inside & cv2.dilate((~inside).astype(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)
    rim[0], rim[-1], rim[:, 0], rim[:, -1] = inside[0], inside[-1], inside[:, 0], inside[:, -1]
    if not (dark & rim).any():
        return np.zeros(raw.shape, bool)
    n, lab = cv2.connectedComponents(dark.astype(np.uint8), connectivity=8)
    touch = np.zeros(n, bool)
    touch[lab[dark & rim]] = True
    touch[0] = False
    slope = np.hypot(
        cv2.Sobel(raw, cv2.CV_32F, 1, 0, ksize=3), cv2.Sobel(raw, cv2.CV_32F, 0, 1, ksize=3)
    ) / np.float32(8.0 * p)
    inner = cv2.erode(dark.astype(np.uint8), np.ones((3, 3), np.uint8)).astype(bool)
    # judged near the page's edge only: a print lying in a shadow band further in
    # lends the band its own sharp edges (a 6 mm soft band holding a print was taken
    # for ink and became a 'print' 678 % long)
    far = cv2.distanceTransform((~rim).astype(np.uint8), cv2.DIST_L2, 3)
    edge = dark & ~inner & ~rim & (far <= mm_to_px_length(EDGE_NEAR_MM, p))
    n_edge = np.bincount(lab[edge], minlength=n)
    mean_slope = np.bincount(lab[edge], weights=slope[edge], minlength=n) / np.maximum(n_edge, 1)
    n_in = np.bincount(lab[dark], minlength=n)
    depth = np.bincount(lab[dark], weights=(around - raw)[dark], minlength=n) / np.maximum(n_in, 1)
    ink = touch & (n_edge > 0) & (mean_slope * opts.light_edge_rise_mm > depth)
    return ink[lab] & dark


def _push_pull(values: np.ndarray, known: np.ndarray) -> np.ndarray:
    """``values`` where ``known``, elsewhere filled in smoothly from around (a
    pyramid of weighted averages: each gap takes the average of the known pixels at
    the finest scale that reaches them)."""
    import cv2

    vs, ws = [values * known], [known]
    while min(vs[-1].shape) > 2:
        size = ((vs[-1].shape[1] + 1) // 2, (vs[-1].shape[0] + 1) // 2)
        vs.append(cv2.resize(vs[-1], size, interpolation=cv2.INTER_AREA))
        ws.append(cv2.resize(ws[-1], size, interpolation=cv2.INTER_AREA))
    mean = float(vs[-1].sum() / max(float(ws[-1].sum()), 1e-12))
    out = np.where(ws[-1] > 0, vs[-1] / np.maximum(ws[-1], 1e-12), mean).astype(np.float32)
    for v, w in zip(reversed(vs[:-1]), reversed(ws[:-1]), strict=True):
        up = cv2.resize(out, (v.shape[1], v.shape[0]), interpolation=cv2.INTER_LINEAR)
        a = np.clip(2.0 * w, 0.0, 1.0)  # half the pixels known: their mean holds
        out = (a * (v / np.maximum(w, 1e-12)) + (1.0 - a) * up).astype(np.float32)
    return out


def _relax(values: np.ndarray, known: np.ndarray) -> np.ndarray:
    """``values`` inside the unknown regions relaxed towards a harmonic fill (each
    pixel the mean of its four neighbours, the known pixels held): across a print it
    joins the paper on its two sides, so a shadow band's edge crossing the print goes
    on straight through it, where the pyramid's fill blurs lit and shaded paper
    together (a slick print inked 0.45 across a 40 % band: length -11.7 % -> -0.1 %).
    Jacobi sweeps in each region's box, about its narrower side squared over four
    (the slowest mode's decay), from the pyramid's fill."""
    import cv2

    out = values.copy()
    hole = (~known).astype(np.uint8)
    n, _, stats, _ = cv2.connectedComponentsWithStats(hole, connectivity=8)
    k = np.array([[0, 0.25, 0], [0.25, 0, 0.25], [0, 0.25, 0]], np.float32)
    h, w = hole.shape
    for i in range(1, n):
        x, y, bw, bh = stats[i, :4]
        r0, r1, c0, c1 = max(y - 1, 0), min(y + bh + 1, h), max(x - 1, 0), min(x + bw + 1, w)
        box, held = out[r0:r1, c0:c1], hole[r0:r1, c0:c1] == 0
        fixed = box.copy()
        for _ in range(int(np.clip(min(bw, bh) ** 2 / 4, 4, RELAX_SWEEPS))):
            box = np.where(held, fixed, cv2.filter2D(box, -1, k, borderType=cv2.BORDER_REPLICATE))
        out[r0:r1, c0:c1] = box
    return out


def _pad(a: np.ndarray, value: float) -> np.ndarray:
    """``a`` with a one-pixel frame of ``value``."""
    import cv2

    return cv2.copyMakeBorder(a, 1, 1, 1, 1, cv2.BORDER_CONSTANT, value=value)


def _px(mm: float, p: float, least: int = 1) -> int:
    """``mm`` in whole pixels of ``p`` mm (at least ``least``)."""
    return max(least, round(mm_to_px_length(mm, p)))


def _background(
    small: np.ndarray, inside: np.ndarray, p: float, opts: AnalysisOptions
) -> tuple[np.ndarray, np.ndarray]:
    """The paper's brightness over the small image (float32, log grey) with the ink
    left out, filled in from around it, and where it was not left out (the paper,
    bool); ``p`` is the small image's pixel [mm].

    Ink is told from shade by being enclosed: a print is a dark region with brighter
    paper all round it, while the shade of uneven light runs off the sheet (the
    independent set's shadow bands, 10-40 mm wide, 3-15 mm soft edges, 20-40 %
    darker, cross the sheet; gradients and vignettes fall towards its edges). A
    closing at any scale cannot tell them apart: a slick print 30 mm wide and a
    shadow band 30 mm wide are the same size (the old 30 mm closing took shadow
    bands for paper-light and reported them as 148-291 mm prints). The log grey is
    closed over ink details narrower than ``light_detail_mm`` (tread blocks,
    writing, gridlines: not light) for the paper's level; every enclosed region
    darker than its lowest rim by more than ``light_basin`` is ink; tread elements
    closer than ``light_gap_mm`` are one region. A print run off the sheet is not enclosed: at
    the sheet's edge, grey below ``light_edge_ink`` of the paper around it
    (``light_scale_mm`` closing) is ink, lighter is shade (ink is < 0.5 of the
    paper, a shadow > 0.6). The paper is then filled in over the ink from around
    it."""
    import cv2

    raw = np.log(small.astype(np.float32) + 1.0)
    log = cv2.morphologyEx(raw, cv2.MORPH_CLOSE, _disk(_px(opts.light_detail_mm, p)))
    # ink regions found on a grid twice as coarse (4 x fewer pixels to flood), of the
    # grey before the closing: a fine knurl print inked 0.56-0.63 leaves no paper
    # pixel on the 1 mm grid, the closing made it a shallow grey that was no basin,
    # the light followed it and the print was lost (independent lighting set 3 file 29)
    h, w = log.shape
    hc, wc = max(1, h // 2), max(1, w // 2)
    coarse = cv2.resize(raw, (wc, hc), interpolation=cv2.INTER_AREA)
    page = cv2.resize(inside.astype(np.float32), (wc, hc), interpolation=cv2.INTER_AREA) > 0.99
    if not page.any():
        page = np.ones(coarse.shape, bool)
    # the paper around, off the page the page's paper (a table is not paper)
    paper = np.float32(np.percentile(coarse[page], 95))
    scale = _px(opts.light_scale_mm, binned_mm_per_px(p, 2), 2)
    around = cv2.morphologyEx(np.where(page, coarse, paper), cv2.MORPH_CLOSE, _disk(scale))
    around_up = cv2.resize(around, (w, h), interpolation=cv2.INTER_LINEAR)
    sharp = _edge_ink(raw, inside, around_up, p, opts)
    # (and against the page's paper: a print run off the sheet wider than the closing
    # is its own "paper around", no darker than it: held-out 6 seed 1 sheet 51, a
    # slick print 40 x 82 mm cut by the sheet's edge, taken for shade and lost)
    sharp |= _edge_ink(raw, inside, np.maximum(around_up, paper), p, opts)
    sharp = cv2.resize(sharp.astype(np.uint8), (wc, hc), interpolation=cv2.INTER_AREA) > 0
    # off the page (a frame round the image, a photo's table) is open: a path off it is
    # no brighter than the page's edge, save next to ink at the edge (a print run off
    # the sheet: by its depth, below light_edge_ink of the paper, or its sharp edge)
    open_ = _pad((~page).astype(np.uint8), 1).astype(bool)
    level = _pad(coarse, float(coarse.min()))
    edge_ink = page & ((coarse < around + np.log(opts.light_edge_ink)) | sharp)
    low = np.float32(coarse.min() - 10.0)
    # (a sharp-edged region is raised to the page's paper at least: its "around" may
    # be its own level)
    rim_level = np.where(sharp, np.maximum(around, paper), around)
    seed = cv2.dilate(
        _pad(np.where(edge_ink, rim_level, low).astype(np.float32), float(low)),
        np.ones((3, 3), np.uint8),
    )
    if coarse.shape[0] > 1 and coarse.shape[1] > 1:
        raised = (_fill_basins(level, seed, open_) - level)[1:-1, 1:-1]
        raised[~page] = 0.0
    else:
        raised = np.zeros_like(coarse)
    ink = (raised > -np.log(1.0 - opts.light_basin)).astype(np.uint8)
    ink = cv2.resize(ink, (w, h), interpolation=cv2.INTER_NEAREST)
    ink = cv2.morphologyEx(ink, cv2.MORPH_CLOSE, _disk(_px(opts.light_gap_mm / 2, p)))
    known = ~cv2.dilate(ink, _disk(EDGE_PX)).astype(bool) & inside  # less its edge's mixed pixels
    if not known.any():  # a narrow strip of paper: its mixed pixels must do
        known = ~ink.astype(bool) & inside
    if not known.any():  # no paper to see the light by: taken as even (a page 90 %
        # black with a 2 mm strip of paper was flattened into paper and read NoInk)
        return np.full(log.shape, np.float32(np.percentile(log, 95))), inside
    return _push_pull(log, known.astype(np.float32)), known


def light_spread(page: Page, rows: slice, cols: slice) -> float:
    """How much the paper's brightness changes around a print [log ratio: 98th less
    2nd percentile over the paper within ~3 mm of the ink regions in its box]: the
    estimate under the print is filled in from there, so it may be off by a share
    of this (0 when the light was not flattened).

    Parameters
    ----------
    page : Page
    rows, cols : slice
        The print's box at full resolution.

    Returns
    -------
    float
    """
    import cv2

    if page.light is None or page.light_ink is None:
        return 0.0
    f, (h, w) = page.light_px, page.light.shape
    grow = EDGE_PX + RING_PX
    r0, r1 = max(rows.start // f - grow, 0), min(-(-rows.stop // f) + grow, h)
    c0, c1 = max(cols.start // f - grow, 0), min(-(-cols.stop // f) + grow, w)
    ink = page.light_ink[r0:r1, c0:c1]
    ring = cv2.dilate(ink.astype(np.uint8), _disk(RING_PX)).astype(bool) & ~ink
    if ring.sum() < 4:
        return 0.0
    lo, hi = np.percentile(page.light[r0:r1, c0:c1][ring], [2, 98])
    return float(hi - lo)


def _refined(frame: _Frame | None, work: np.ndarray, cell: float) -> _Frame | None:
    """The frame with its corner angles and keystone from the corners refined on
    the full image (:func:`refine_corners`) when all four lie inside the image
    (a page running off it has no corner there: its grid angles stand)."""
    if frame is None or frame.corners is None or len(frame.corners) != 4:
        return frame
    h, w = work.shape
    margin = (EDGE_REACH + 1) * cell
    q = (frame.corners + 0.5) * cell
    if (q.min() < margin) or (q[:, 0].max() > w - margin) or (q[:, 1].max() > h - margin):
        return frame
    fine = refine_corners(work, frame.corners, cell)
    if fine is None:
        return frame
    return replace(frame, angles=_corner_angles(fine), keystone=keystone(fine))


def _frame_warnings(frame: _Frame | None, opts: AnalysisOptions) -> tuple[tuple, tuple]:
    if frame is None:
        return (), ()
    if frame.corners is None:
        # (a photographed page whose tilt cannot be checked has no trusted scale:
        # flagged; as advice only, held-out generator 6's tilted photos, keystone 5 %,
        # read 6-13 % short with status ok)
        return ("perspective",), (
            "a page on a darker surround was found but its outline is not a clean "
            "quadrilateral: perspective not checked, the scale may change across the "
            "page; give its paper (--paper A4, letter or WxH mm) to rectify it from its "
            "corners, photograph it square-on with its four corners in view, or scan it",
        )
    worst = max((abs(a - 90.0) for a in frame.angles), default=0.0)
    tilted = frame.keystone is not None and frame.keystone > opts.perspective_keystone
    if worst > opts.perspective_tolerance_deg or tilted:
        lo, hi = min(frame.angles), max(frame.angles)
        sides = (
            ""
            if frame.keystone is None
            else f", opposite sides {100 * frame.keystone:.1f} % apart"
        )
        return ("perspective",), (
            f"the page is not flat-on to the camera (corner angles {lo:.1f}-{hi:.1f} deg"
            f"{sides}): no single scale, lengths would be off; give its paper (--paper "
            f"A4, letter or WxH mm) to rectify it from its corners, or photograph it "
            f"square-on, or scan it",
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
    frame = find_page(_small(small, 2), paper)  # on a 2 mm grid, as it was tuned
    frame = _refined(frame, work, 2 * f)  # its corners on the full image
    inside = np.ones(small.shape, bool)
    if frame is not None:  # the page's own edge: neither paper nor ink
        inside = cv2.resize(
            frame.mask.astype(np.uint8), None, fx=2, fy=2, interpolation=cv2.INTER_NEAREST
        )
        inside = cv2.copyMakeBorder(
            inside,
            0,
            small.shape[0] - inside.shape[0],
            0,
            small.shape[1] - inside.shape[1],
            cv2.BORDER_REPLICATE,
        )
        rim = cv2.erode(inside.astype(np.uint8), np.ones((3, 3), np.uint8), iterations=2)
        inside = rim.astype(bool) if rim.any() else inside
    log_bg, known = _background(small, inside, binned_mm_per_px(scan.mm_per_px, f), opts)
    bg = np.maximum(np.exp(cv2.GaussianBlur(log_bg, (0, 0), 1.0)) - 1.0, 1.0)
    lo, hi = (float(v) for v in np.percentile(bg[inside], [1, 99]))
    lo, hi = lo / hi, 1.0
    flags, warnings = _frame_warnings(frame, opts)
    flat = 1.0 - lo > opts.light_tolerance
    if flat:  # only then worth the finer fill under the ink
        log_bg = cv2.GaussianBlur(_relax(log_bg, known), (0, 0), 1.0)
        bg = np.maximum(np.exp(log_bg) - 1.0, 1.0)
        full = cv2.resize(bg, (work.shape[1], work.shape[0]), interpolation=cv2.INTER_LINEAR)
        work = cv2.divide(work, full, scale=paper, dtype=cv2.CV_8U)
        warnings += (
            f"uneven light: the paper is {100 * lo:.0f} % as bright in its darkest part as "
            f"in its brightest; flattened before thresholding",
        )
    sheet = None
    if frame is not None:
        sheet = _full_mask(frame.mask, 2 * f, work.shape)
        work = np.where(sheet, work, np.uint8(255))
    angles = frame.angles if frame else ()
    if not flat:
        log_bg = known = None
    ink = None if known is None else ~known
    return Page(work, flat, (lo, hi), sheet, angles, flags, warnings, log_bg, ink, f)


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


__all__ = [
    "Page",
    "find_page",
    "keystone",
    "light_spread",
    "prepare_page",
    "refine_corners",
    "to_uint8",
]
