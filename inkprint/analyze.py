"""Analyse a scanned sheet: light, threshold, marks, footprints, edge spots, measure.

Steps (sections 3.5, 4.1.1, 7.1.1): flatten uneven light and find the page in a
photo (:mod:`inkprint.light`); threshold (:mod:`inkprint.binarize`); sort the ink
into prints and marks that are not prints - lines, gridlines, text, dust, noise -
and group each print's tread elements into one footprint (:mod:`inkprint.marks`,
:mod:`inkprint.group`); set apart the edge spots that bore no load; measure.

Each print is measured with :func:`contactpatch.measure` (the definitions shared with
the model) along its rolling direction: ``rolling_axis`` ``'x'`` or ``'y'`` (the
sheet's axes: x across the image from left to right, y up it) or ``'auto'`` (each
print's principal axis, the longer direction; the row says ``axis_source = auto``).
A given axis within ``axis_misaligned_deg`` (:class:`inkprint.AnalysisOptions`) of
the print's own axis (:func:`own_axis`: its hull's minimum-area rectangle, confirmed
by the principal axis, or by :func:`settled_turn`: its axis estimates agree in its
length and width) is snapped to it: a print taped square within a fraction of a
degree is measured along itself. Farther, the axis is used as given: a print taped
askew reads too wide along it (+4 % at 3 degrees, +27 % at 10), so it is flagged
``axis_misaligned`` with the fix (``auto`` or square the print). The *gross* outline is the convex hull of the
ink's sub-pixel edge (the iso-line half-way between the local paper and ink levels,
:func:`edge_field`), the *net* area the ink pixel count (at most the hull's area).
With the load and inflation pressure known, load / area is compared with the
inflation pressure (4.1.1, Figure 4-3). A sensitivity band re-measures each print
at the threshold x (1 -+ ``sensitivity``) of :class:`inkprint.AnalysisOptions`.

A print touching the image's edge (or the photographed page's) is flagged
``clipped``; a page photographed at an angle, ``perspective``: never a silent
partial number.
"""

from __future__ import annotations

import dataclasses
import itertools
import math
import os
from dataclasses import dataclass, field

import numpy as np

from .apart import split_apart
from .binarize import Binarization, below, binarize, remove_specks
from .caps import CAP_ELEMENTS, CAP_SHARE, CAP_SOLID, cut_caps, off_lattice, pieces_on_outline
from .components import components_with_stats, pixel_sums, reduce_at
from .coords import (
    area_mm2_to_px,
    area_px_to_mm2,
    mm_per_px_to_dpi,
    mm_to_px_length,
    px_to_mm,
    px_to_mm_length,
)
from .errors import InvalidInput, NoInk
from .faintlines import without_faint_lines
from .gridlines import Gridlines, find_gridlines, stroke_px
from .group import (
    SMALL_PRINT_MM2,
    TEXT_LINE_MIN,
    Group,
    PrintCheck,
    _at_the_ends,
    _edge_spots,
    _sides,
    _straight_side,
    _unspecked,
    edge_spots,
    hull_fill,
    is_print,
    join_shoulders,
    maybe_tiny_print,
    outline_points,
    reading_order,
    text_line,
    union,
    word_in_a_line,
)
from .lattice import (
    CORNER_FLAG,
    CORNER_SHORT_PX,
    TIP_SHORT_PX,
    coarse_elements,
    lattice_prints,
)
from .light import Page, light_spread, prepare_page
from .marks import BOLD_REASON, TICK_REASON, Mark, SortedInk, sort_ink
from .options import AnalysisOptions, resolve_options, resolve_threads
from .pattern import MARK_KINDS, join_pattern_pieces, mark_pieces
from .read import Scan, read_scan
from .results import BAND_KEYS, PrintResult, SheetResult, contact_pressure, marks_summary
from .ruler import find_scales, on_scale, scale_band
from .stack import join_stacks, stroke_stacks

AXES = ("auto", "x", "y")
#: the width of a print is good to about this much [px] (its two edges' sub-pixel
#: positions under blur, JPEG and ink mottle): held-out prints 18-24 px wide at 150
#: dpi read +0.15..+0.23 px wide (+0.7..+1.24 %); under CORNER_FLAG / EDGE_PX = 25 px
#: across a print is flagged ``coarse`` (:func:`_coarse_flag`)
EDGE_PX = 0.25
#: a print whose outline holds more than this share of a letter's box set aside, and
#: is shorter or narrower without its letter-sized pieces beside it by more than
#: ``edge_uncertainty``, is flagged ``mark_on_edge`` (:func:`_letters_pull`)
LETTER_INSIDE = 0.25
#: ... and less than this (a letter wholly inside it, a ruler's number over its
#: middle, leaves its outline where it is)
LETTER_WITHIN = 0.95
#: ... and its pieces beside them are followed this many letters along (a word)
LETTER_STEPS = 3
#: Letters set aside this close to a print's ink [mm] may have a letter joined to
#: its edge (:func:`_letters_beside_pull`).
LETTERS_BESIDE_MM = 1.5
#: ... and a piece of the print near them that an opening this many strokes wide
#: takes whole is a letter's stroke
THIN_PIECE = 1.0
#: ... a mark whose box is more than this many times longer than wide is no letter
LETTER_ASPECT = 8.0
#: pen-thin pieces left out along a print's edge that make a row of its elements
#: (:func:`_thin_excess`): this many, each at least this large [mm^2] and [px]
THIN_ROW = 4
THIN_ROW_MM2 = 0.3
THIN_ROW_PX = 20
#: a group under ``min_patch_fraction`` of a print's ink within this distance of it
#: (box to box) is a fragment of it; farther away it is judged as a print of its own
FRAGMENT_REACH_MM = 15.0


def _hull_px(mask, field, r0: int, c0: int) -> np.ndarray:
    """Convex hull of the ink's sub-pixel outline (continuous row, col), offset.

    The outline is the iso-line ``field = 0`` around ``mask``: for an anti-aliased
    edge it is the 50 % coverage line, so the hull is not biased by the pixel
    staircase. (The hull of the pixel *squares* overshoots a rotated or curved edge
    by up to 0.5 (|cos| + |sin|) px per side, 1.3 px in extent at 20 degrees; the
    hull of pixel *centres* falls short at the tips.) The net area stays the pixel
    count. The iso-line's vertices are the zero crossings of the field along the
    pixel rows and columns (marching squares places them by linear interpolation);
    its convex hull is the hull of those crossings, found here directly, without
    tracing the line (:func:`_crossings`: of each row's and column's crossings only
    the first and the last, the others lying between them; the hull of the same
    points as ``skimage.measure.find_contours``, at a fraction of the cost).
    """
    import cv2

    m8 = mask.astype(np.uint8)
    near = cv2.dilate(m8, np.ones((3, 3), np.uint8)).view(bool)
    # only a band along the pixel hull can hold hull points: fill the interior
    contours, _ = cv2.findContours(m8, cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_SIMPLE)
    inner = np.zeros_like(m8)
    cv2.fillPoly(inner, [cv2.convexHull(np.concatenate(contours))], 1)
    inner = cv2.erode(inner, np.ones((7, 7), np.uint8)).view(bool)
    rc = _crossings(_Level(field, near, inner))
    if not len(rc):
        rr, cc = np.nonzero(mask)
        rc = np.column_stack([rr + 1.0, cc + 1.0])
    rc = rc - 1.0 + 0.5  # undo padding; pixel centres at +0.5
    hull = cv2.convexHull(rc[:, ::-1].astype(np.float32)).reshape(-1, 2)[:, ::-1].astype(float)
    return np.column_stack([hull[:, 0] + r0, hull[:, 1] + c0])


@dataclass(frozen=True)
class _Level:
    """The level whose zero line :func:`_hull_px` follows: ``field`` near the ink
    (``near``), 1 (paper) away from it and around the box (a one-pixel frame that
    closes the outline), -1 (ink) in the hull's interior (``inner``); indexed in
    the framed box's (row, col) [px]."""

    field: np.ndarray
    near: np.ndarray
    inner: np.ndarray

    def below(self) -> np.ndarray:
        """Where the level is not above 0, in the box without its frame."""
        return self.inner | (self.near & ~(self.field > 0))

    def at(self, r: np.ndarray, c: np.ndarray) -> np.ndarray:
        """The level (float) at framed-box pixels (``r``, ``c``)."""
        h, w = self.field.shape
        r, c = r - 1, c - 1
        frame = (r < 0) | (r >= h) | (c < 0) | (c >= w)
        r, c = np.clip(r, 0, h - 1), np.clip(c, 0, w - 1)
        v = self.field[r, c].astype(float)
        v[~self.near[r, c] | frame] = 1.0
        v[self.inner[r, c] & ~frame] = -1.0
        return v


def _crossings(level: _Level) -> np.ndarray:
    """Where the level crosses 0 between 4-neighbour pixels, (row, col) in the
    framed box [px]: of the vertices of its zero iso-line, the first and the last
    along every row and every column (the others lie on the segment between them,
    inside the hull). A pixel is above the level when it is > 0 (marching squares'
    convention); the crossing is linearly interpolated."""
    below = level.below()
    r0, c0, r1, c1 = [], [], [], []  # the pixels on either side of each crossing
    for axis in (1, 0):  # along rows, then along columns
        lines = np.flatnonzero(below.any(axis=axis)) + 1  # framed
        sub = below[lines - 1] if axis == 1 else below[:, lines - 1].T
        first = sub.argmax(axis=1)  # the frame is above: the crossing before
        last = sub.shape[1] - 1 - sub[:, ::-1].argmax(axis=1)  # and after
        for k in (first, last + 1):  # the framed index of the pixel before
            r0.append(lines if axis == 1 else k)
            c0.append(k if axis == 1 else lines)
            r1.append(lines if axis == 1 else k + 1)
            c1.append(k + 1 if axis == 1 else lines)
    r0, c0, r1, c1 = (np.concatenate(v) for v in (r0, c0, r1, c1))
    f0, f1 = level.at(r0, c0), level.at(r1, c1)
    t = -f0 / (f1 - f0)  # f0 <= 0 < f1 or f1 <= 0 < f0: never 0 / 0
    return np.column_stack([np.where(r1 > r0, r0 + t, r0), np.where(c1 > c0, c0 + t, c0)])


def edge_field(
    grey, mask, *, mm_per_px: float, options: AnalysisOptions | None = None, local=None
) -> np.ndarray:
    """Signed field whose zero line is the print's edge at half contrast.

    Half-way between the local paper (max filter) and the local ink (min filter)
    over ``options.edge_window_mm``: for ink of any darkness the 50 % coverage line,
    so darker or lighter inking does not move the measured outline (a global
    threshold does: the hull then follows the darkest stretch of a long edge). Where
    the local contrast is below half the print's paper-to-ink contrast (inside the
    ink, on bare paper) the mask decides. Where the locally darkest ink is lighter
    than the print's median ink (a faint halo speck touching the edge, section 7.1.1;
    a knob inked lighter than the rest), the print's median ink stands in for it: a
    speck inked at half the print's darkness reads as paper instead of adding its
    width to the outline (next to a knob inked 0.7 x the median it read as ink:
    width +1.2 %). A one-pixel pip of the outline much darker than its neighbours
    along the edge (a dust speck touching it) takes their level.

    Parameters
    ----------
    grey : (h, w) float32 in [0, 1]
        The print's box of the scan.
    mask : (h, w) bool
        The print's ink in the box.
    mm_per_px : float [mm / px]
    options : AnalysisOptions, optional
        Uses ``edge_window_mm`` and ``edge_pip_jump`` (defaults when None).
    local : (lo, hi) of (h, w) float32, optional
        The grey's local ink and paper levels if already known (the same grey's
        for another mask): its minimum and maximum over ``edge_window_mm``.

    Returns
    -------
    (h, w) float32
        Negative on ink, positive on paper.
    """
    opts = resolve_options(options)
    lo, hi = local or _local_range(grey, mm_per_px, opts)
    paper, ink = _paper_and_ink(grey, mask)
    lo = np.minimum(lo, np.float32(ink))  # (a new array: the given range stays)
    dull = ~((hi - lo) > 0.5 * max(paper - ink, 1e-6))
    # grey - (lo + hi) / 2 where sharp, else the mask's level: computed in place in
    # the buffer of ``lo`` (the same numbers as np.where's, at half its cost)
    f = np.add(lo, hi, out=lo)
    f *= 0.5
    f = np.subtract(grey, f, out=f)
    f[dull & mask] = -0.5
    f[dull & ~mask] = 0.5
    f = f.astype(np.float32, copy=False)
    return _smooth_pips(f, mask, opts.edge_pip_jump * max(paper - ink, 1e-6))


def _paper_and_ink(grey, mask) -> tuple:
    """The median grey of the paper (not ``mask``) and of the ink (``mask``) in a
    box, from every 3rd row and column (plenty for two medians), in the grey's
    dtype; (1.0, 0.0) when the box holds no ink or no paper."""
    sub_g, sub_m = grey[::3, ::3], mask[::3, ::3]
    if sub_m.any() and (~sub_m).any():
        return _median(sub_g[~sub_m]), _median(sub_g[sub_m])
    return 1.0, 0.0


def _median(x: np.ndarray):
    """``np.median`` of a 1-D float array (grey levels, no NaN), the same number
    without its checks and its mean's machinery (a fifth of its cost on a print's
    few thousand samples): the middle value, or the middle two's sum halved in the
    array's dtype, as numpy's mean of them takes it."""
    k = len(x) // 2
    if len(x) % 2:
        return np.partition(x, k)[k]
    part = np.partition(x, (k - 1, k))
    return (part[k - 1] + part[k]) / x.dtype.type(2)


def _local_range(grey, mm_per_px: float, opts: AnalysisOptions) -> tuple:
    """The darkest and lightest grey within ``opts.edge_window_mm`` of every pixel
    (the local ink and paper levels of :func:`edge_field`)."""
    import cv2

    k = max(3, round(mm_to_px_length(opts.edge_window_mm, mm_per_px)) | 1)
    kernel = np.ones((k, k), np.uint8)
    return cv2.erode(grey, kernel), cv2.dilate(grey, kernel)


def _smooth_pips(f: np.ndarray, mask: np.ndarray, jump: float) -> np.ndarray:
    """The field with each one-pixel pip of the outline (an ink pixel joined to the
    ink by one side only) darker than both its neighbours along the edge by more
    than ``jump`` taking their mean: a dust speck touching the edge, not the edge (a
    print's edge changes its coverage from pixel to pixel by 1 / (2 R) for a radius
    of curvature R [px]; a one-pixel speck at a print's widest point read +1.2 %).
    An ink pixel joined by a corner only (a thick print's outline is joined by its
    sides) darker than all four side neighbours by ``jump`` takes their mean: a pen
    stroke's last pixel touching the edge (label 4265/6 at 150 dpi: width +1.5 %)."""
    import cv2

    m8 = mask.view(np.uint8) if mask.dtype == bool else mask.astype(np.uint8)
    n4 = cv2.filter2D(m8, -1, _CROSS, borderType=cv2.BORDER_CONSTANT)
    pts = cv2.findNonZero(cv2.compare(n4, 1, cv2.CMP_LE) & m8)
    if pts is None:
        return f
    cc, rr = pts.reshape(-1, 2).T
    h, w = f.shape
    up, down = np.maximum(rr - 1, 0), np.minimum(rr + 1, h - 1)
    left, right = np.maximum(cc - 1, 0), np.minimum(cc + 1, w - 1)
    vertical = ((m8[up, cc] & (rr > 0)) | (m8[down, cc] & (rr < h - 1))).astype(bool)
    a = np.where(vertical, f[rr, left], f[up, cc])
    b = np.where(vertical, f[rr, right], f[down, cc])
    lone = n4[rr, cc] == 0
    if lone.any():  # joined by a corner: all four side neighbours
        ud = np.minimum(f[up, cc], f[down, cc])
        lr = np.minimum(f[rr, left], f[rr, right])
        a = np.where(lone, ud, a)
        b = np.where(lone, lr, b)
    dust = np.minimum(a, b) - f[rr, cc] > jump
    if not dust.any():
        return f
    out = f.copy()
    mean = np.where(lone, 0.25, 0.5) * np.where(
        lone, f[up, cc] + f[down, cc] + f[rr, left] + f[rr, right], a + b
    )
    out[rr[dust], cc[dust]] = mean[dust]
    return out


_CROSS = np.array([[0, 1, 0], [1, 0, 1], [0, 1, 0]], np.float32)


@dataclass(frozen=True)
class MaskMeasurement:
    """Shared metrics of an ink mask and its outline.

    Attributes
    ----------
    metrics : contactpatch.PatchMetrics
        In mm (or px without a scale), sheet coordinates (x right, y up).
    hull_px : (k, 2) float [px]
        The gross outline, continuous (row, col) pixel coordinates of the sheet.
    snapped : bool
        A given rolling axis ('x', 'y') was turned onto the print's own axis
        (:func:`rolling_angle`), or confirmed by its tread's tracks
        (:func:`_tread_axis`); :func:`measure_print` flags the print from this
        one decision, not a second one.
    tracks_deg : float or None [deg]
        The turn of the tread's tracks from the given axis when they were found
        too faint to decide it and the outline did not confirm them
        (:func:`_tread_axis`): :func:`_axis_flags` tests the given axis against it.
    """

    metrics: object
    hull_px: np.ndarray = field(repr=False)
    snapped: bool = False
    tracks_deg: float | None = None


def measure_mask(
    mask,
    r0: int,
    c0: int,
    *,
    n_rows: int,
    mm_per_px: float,
    field=None,
    axis=None,
    hull_px=None,
    stations=None,
    snap_deg: float = 0.0,
    settle: float = 0.0,
) -> MaskMeasurement:
    """Shared metrics (:func:`contactpatch.measure`) of an ink mask cropped from a sheet.

    Parameters
    ----------
    mask : (h, w) bool
        Ink, cropped at row ``r0`` and column ``c0`` of the sheet [px].
    r0, c0 : int [px]
    n_rows : int [px]
        Height of the sheet.
    mm_per_px : float [mm / px]
    field : (h, w) float, optional
        Signed edge field over the crop (:func:`edge_field`) giving the sub-pixel
        outline; default: the pixel mask's own edge.
    axis : float or str, optional
        Rolling direction: an angle from +x [rad], ``'x'``, ``'y'`` (the sheet's
        axes, snapped to the print's own axis, see :func:`rolling_angle`) or None /
        ``'auto'`` (the hull's principal axis).
    hull_px : (k, 2) float, optional [px]
        The outline already found for this mask and field (a previous
        :class:`MaskMeasurement`'s ``hull_px``): not traced again.
    stations : sequence of float, optional
        Lateral stations of :func:`contactpatch.measure` (its default when None).
    snap_deg : float [deg]
        A given axis ('x', 'y') within this of the print's own axis is snapped to
        it (:func:`rolling_angle`).
    settle : float [-]
        A print of any solidity is snapped within ``snap_deg`` when its axis
        estimates give a length and width within this of each other
        (``axis_misaligned_excess``; :func:`rolling_angle`). 0: not.

    Returns
    -------
    MaskMeasurement
    """
    import shapely

    import contactpatch as cp

    if hull_px is None:
        if field is None:
            field = np.where(mask, -0.5, 0.5)
        hull_px = _hull_px(mask, field, r0, c0)
    axis, snapped, tracks = _mask_axis(
        mask, hull_px, axis, mm_per_px=mm_per_px, snap_deg=snap_deg, settle=settle
    )
    x, y = px_to_mm(hull_px[:, 0], hull_px[:, 1], n_rows=n_rows, mm_per_px=mm_per_px)
    n, row_sum, col_sum = pixel_sums(mask)  # the ink's centroid, exact sums
    cx, cy = px_to_mm(
        row_sum / n + 0.5 + r0, col_sum / n + 0.5 + c0, n_rows=n_rows, mm_per_px=mm_per_px
    )
    hull = shapely.Polygon(np.column_stack([x, y]))
    net = min(area_px_to_mm2(n, mm_per_px), hull.area)
    kw = {} if stations is None else {"stations": stations}
    m = cp.measure(hull, axis=axis, net_area=net, net_centroid=(float(cx), float(cy)), **kw)
    return MaskMeasurement(m, hull_px, snapped, tracks)


def _mask_axis(mask, hull_px, axis, *, mm_per_px: float, snap_deg: float, settle: float):
    """``(axis [rad], snapped, tracks)`` of :func:`measure_mask`: ``axis`` when an
    angle, else the tread's tracks' (:func:`_tread_axis`) or the hull's
    (:func:`rolling_angle`) for ``'x'``, ``'y'``, ``'auto'`` or None."""
    if not (axis is None or isinstance(axis, str)):
        return axis, False, None
    import cv2

    hull_area = cv2.contourArea(np.asarray(hull_px, np.float32))
    solid = np.count_nonzero(mask) / max(hull_area, 1.0)
    given = axis or "auto"
    axis, tracks = _tread_axis(mask, hull_px, given, solid, mm_per_px=mm_per_px, snap_deg=snap_deg)
    if axis is not None:
        return axis, True, tracks
    axis = rolling_angle(
        hull_px, given, snap_deg=snap_limit(snap_deg, solid), settle=settle, settle_deg=snap_deg
    )
    return axis, given != "auto" and axis != (0.0 if given == "x" else math.pi / 2), tracks


def _band_metrics(mask, r0: int, c0: int, field, *, n_rows: int, mm_per_px: float, axis, opts):
    """``{key: value}`` of ``BAND_KEYS`` for an ink mask cropped from a sheet (as
    :func:`measure_mask`, its outline, axis and :func:`contactpatch.measure`'s
    length, width, hull area, net area and direct ellipse, without the metrics the
    band does not report: station chords, the moments' ellipse, perimeter)."""
    import contactpatch as cp
    from contactpatch.ruler.metrics import BOUNDARY_SAMPLES, resample_ring

    hull_px = _hull_px(mask, field, r0, c0)
    angle, _, _ = _mask_axis(
        mask,
        hull_px,
        axis,
        mm_per_px=mm_per_px,
        snap_deg=opts.axis_misaligned_deg,
        settle=opts.axis_misaligned_excess,
    )
    x, y = px_to_mm(hull_px[:, 0], hull_px[:, 1], n_rows=n_rows, mm_per_px=mm_per_px)
    c, s = math.cos(angle), math.sin(angle)
    along, across = x * c + y * s, y * c - x * s
    hull_area = 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))
    area = min(area_px_to_mm2(np.count_nonzero(mask), mm_per_px), hull_area)
    ring = np.column_stack([np.append(x, x[0]), np.append(y, y[0])])
    ellipse = cp.fit_ellipse_direct(resample_ring(ring, BOUNDARY_SAMPLES))
    values = (np.ptp(along), np.ptp(across), hull_area, area, ellipse.length, ellipse.width)
    return dict(zip(BAND_KEYS, (float(v) for v in values), strict=True))


#: a tread's tracks decide a sparse print's axis when the sharpest lateral profile
#: is at least this much sharper than the median over the searched turns
#: (:class:`inkprint.treadaxis.TreadTurn` ``contrast``). 1.05 took a staggered
#: knob lattice's diagonal for the tracks on two nearly round knob prints of the
#: mixed set (seed 6012 files 48, 88: contrast 1.07, turned 9.5 deg, +3.8 %
#: unflagged); their true tracks read 1.15-1.25, and on the held-out sets 8 of
#: 360 prints decided by the tracks read 1.05-1.10, each left to the hull's rules
TREAD_CONTRAST = 1.10
#: ... or, for a turn within :data:`AXIS_AGREE_DEG`, when the edges of its profile
#: line up this much more sharply there than their median over the searched turns
#: (:class:`inkprint.treadaxis.TreadTurn` ``edge_contrast``). Knob prints at 200-400
#: dpi turned under a degree have their plateaus' sums of squares flat (contrast
#: 0.94-1.09: the tracks not trusted, the principal axis off the rectangle's: no
#: snap, no flag; width +1.0..+1.7 %, +12.9 % on a 25 mm print); their edges'
#: peak lay within 0.18 deg of the truth for every synth knob print of 200 with an
#: edge contrast over 4 (the worst: prints turned 0.2 deg read 0, the pixel grid's
#: own edges), one under it 1.1 deg off. Farther turns read wrong by 2-9 deg with
#: edge contrasts up to 6.5: there the sums of squares decide alone
TREAD_EDGE_CONTRAST = 4.0
#: turns searched for the tread's tracks [deg]; a sharpest turn within
#: :data:`TREAD_EDGE_DEG` of this limit is no peak (the profile still sharpening
#: beyond it: a slanted row or a pattern without tracks)
TREAD_SEARCH_DEG = 12.0
TREAD_EDGE_DEG = 1.0
#: the hull's rectangle refines the tracks' turn when within this many of its
#: resolutions (:class:`inkprint.treadaxis.TreadTurn`): a tiny long print's tracks
#: are a few bins long (held-out seed 9 sheet 113, 24 x 4 mm at 150 dpi: tracks
#: 6.85 deg, rectangle 7.50, truth 7.49; along the tracks +7.7 % wide). Offline,
#: 360 sparse prints of held-out seeds 7-11, 2026 and independent 111: 2 out of the
#: bar along the tracks alone, 0 refined so (1 within 5 resolutions: the hull's
#: rectangle can be fooled too)
TREAD_REFINE = 2.0
#: the tracks' turn is not used when the outline's own axis is clear (rectangle
#: and principal axis agree) and along the tracks the print reads more than this
#: longer or wider than along it: a print a few elements wide has few tracks (a
#: 22 x 3.5 mm knurl print turned 3.1 deg: tracks at 8.3 deg, +40 % wide). A
#: lattice-sheared knob hull differs by 0.1-1.5 % (held-out sparse prints: under
#: 0.4 % for 95 % of them; over 3 % only where the tracks were wrong)
TREAD_OUTLINE = 0.03


def _tread_axis(mask, hull_px, given: str, solid: float, *, mm_per_px: float, snap_deg: float):
    """A sparse print's rolling direction [rad] from its tread's tracks, or None;
    and the tracks' turn [deg] when they were found but too faint to decide it, or
    None.

    A tire's tread repeats around its circumference, so each element's track (its
    lateral position) repeats along the rolling direction: the ink projected across
    it piles into sharp peaks at the true axis (:func:`inkprint.treadaxis.tread_turn`;
    rows across the tire may slant - chevrons, staggered knobs - so only the
    lateral profile is used). For a print of separate elements (solidity under
    :data:`SNAP_SOLIDITY`) and a given axis ('x', 'y') this decides before its
    hull does: a knob pattern's hull is its outer knobs' corners, whose rectangle,
    least width and moments can agree on a turn of degrees that is not there (a
    60 x 40 mm knob print square to the sheet: all three at -4.1 to -4.6 deg,
    width -1.4 % along them; its tracks: 0.0 deg). Returns None for 'auto', a
    solid print, a turn beyond ``snap_deg`` [deg] (the tracks', or the outline's
    when its rectangle and principal axis agree on it: a print turned 30 deg had a
    lesser peak of its tracks' profile at 1 deg), or no clear peak
    (:data:`TREAD_CONTRAST`, or :data:`TREAD_EDGE_CONTRAST` within
    :data:`AXIS_AGREE_DEG`; :data:`TREAD_EDGE_DEG`). The hull's rectangle, when it
    agrees within :data:`TREAD_REFINE` of the tracks' resolution, gives the turn;
    when it is clear and the tracks' turn makes the print much larger
    (:data:`TREAD_OUTLINE`), the tracks are not used. Faint tracks (under both
    contrasts) decide when the rectangle or the principal axis agrees with them
    within :data:`TREAD_REFINE` resolutions (at least :data:`AXIS_AGREE_DEG`):
    synth knob prints taped 0-6 deg, 30 of 30 tracks within 0.3 deg of the truth
    at contrasts 1.01-1.15; else their turn is returned to be tested
    (:func:`_axis_flags`: a nearly round knob print's rectangle and moments lie 15-34
    deg off, no axis; turned 3-6 deg it read up to +3.5 % long, +3.1 % wide,
    unflagged).
    """
    if given not in ("x", "y") or snap_deg <= 0 or solid >= SNAP_SOLIDITY:
        return None, None
    from .treadaxis import tread_turn

    base = 0.0 if given == "x" else math.pi / 2
    turn, _ = own_axis(hull_px, base)
    clear = _principal_agrees(hull_px, base, turn)  # the outline's own axis is clear
    if abs(turn) > snap_deg and clear:
        return None, None  # turned farther, its outline says (flagged axis_misaligned)
    found = tread_turn(mask, given, mm_per_px=mm_per_px, limit_deg=TREAD_SEARCH_DEG)
    edge = abs(found.turn) > TREAD_SEARCH_DEG - TREAD_EDGE_DEG
    lined_up = found.edge_contrast >= TREAD_EDGE_CONTRAST and abs(found.turn) <= AXIS_AGREE_DEG
    weak = found.contrast < TREAD_CONTRAST and not lined_up
    if edge or abs(found.turn) > snap_deg:
        return None, None
    if weak:  # faint tracks, confirmed by the outline's rectangle or principal axis
        near = max(TREAD_REFINE * found.resolution, AXIS_AGREE_DEG)
        outline = (turn, _principal_turn(hull_px, base))
        if not any(abs(t - found.turn) <= near for t in outline):
            return None, found.turn
        return base + math.radians(found.turn), None
    if abs(turn - found.turn) <= TREAD_REFINE * found.resolution:
        return base + math.radians(turn), None  # the outline's rectangle: the finer
    if clear:
        xy = _sheet_xy(hull_px)
        if _turn_excess(xy, base + math.radians(found.turn), turn - found.turn) > TREAD_OUTLINE:
            return None, None  # the outline's clear axis makes the tracks' turn implausible
    return base + math.radians(found.turn), None


def _sheet_xy(hull_px) -> np.ndarray:
    """(row, col) pixel points -> sheet directions (x = col, y = -row) [px], float64
    (the scale does not change directions)."""
    hull_px = np.asarray(hull_px)
    return np.column_stack([hull_px[:, 1], -hull_px[:, 0]]).astype(np.float64)


#: the hull's principal axis confirms its own axis (:func:`own_axis`) when turned
#: from the given axis as it is within this [deg] or 30 % of the turn
AXIS_AGREE_DEG = 1.0


def rolling_angle(
    hull_px, rolling_axis: str, *, snap_deg: float = 0.0, settle: float = 0.0, settle_deg=None
) -> float:
    """Measuring direction [rad from the sheet's +x] for a rolling axis.

    Parameters
    ----------
    hull_px : (k, 2) float [px]
        The print's hull, (row, col).
    rolling_axis : {'auto', 'x', 'y'}
    snap_deg : float [deg]
        A given axis ('x', 'y') is snapped to the print's own axis nearest it
        (:func:`own_axis`, confirmed by the principal axis within
        :data:`AXIS_AGREE_DEG`) when that lies within this angle of it: a print
        taped or scanned askew is measured along itself (the tire rolled along the
        print's own axis; the given axis says which of its two axes is the length:
        a 123 x 21 mm print turned 0.35 degrees read 3 % too wide along the sheet's
        axis). One turned farther, or whose two axis estimates disagree, is
        measured as given and flagged ``axis_misaligned`` when that changes it
        (:func:`measure_print`). 0: as given.
    settle : float [-]
        Snapped also within ``settle_deg`` (default ``snap_deg``) when the print's
        three axis estimates (:func:`settled_turn`) give a length and width within
        this relative spread of each other: which of them is its axis does not
        change its numbers. 0: not.
    settle_deg : float [deg], optional

    Returns
    -------
    float
        'x': 0; 'y': pi/2 (or the print's own axis within ``snap_deg`` of them);
        'auto': the hull's major principal axis.
    """
    import cv2

    if rolling_axis not in AXES:
        raise InvalidInput("rolling_axis", rolling_axis, " | ".join(AXES))
    if rolling_axis != "auto":
        given = 0.0 if rolling_axis == "x" else math.pi / 2
        if snap_deg > 0:
            turn, _ = own_axis(hull_px, given)
            if abs(turn) <= snap_deg and _principal_agrees(hull_px, given, turn):
                return given + math.radians(turn)
        limit = snap_deg if settle_deg is None else settle_deg
        if settle > 0 and limit > 0:
            turn = settled_turn(hull_px, given, spread=settle)
            if turn is not None and abs(turn) <= limit:
                return given + math.radians(turn)
        return given
    # sheet coordinates: x = col, y = -row (the scale does not change directions)
    mo = cv2.moments(_sheet_xy(hull_px).astype(np.float32))
    return 0.5 * math.atan2(2 * mo["mu11"], mo["mu20"] - mo["mu02"])


#: a nearly round print (aspect under ``axis_uncertain_aspect``) is flagged turned
#: when its excess is over this many times ``axis_misaligned_excess``: its own axis
#: is less defined (4 before; 2 is the accuracy bar's 1 %: held-out seed 8 sheets 57
#: and 99, 1.1-1.2 x as long as wide, turned 2-7 deg, +1.1 to +1.6 % unflagged)
ROUND_EXCESS = 2.0
#: a print with less ink in its hull than this (net / gross: a knob or dot pattern)
#: is snapped to its own axis only within :data:`AXIS_AGREE_DEG`: its hull's two
#: axis estimates can agree and both be wrong by degrees (independent set 111
#: sheet 31: a knobby print square to the sheet read -5.5 and -6.7 degrees,
#: length -8 % when snapped)
SNAP_SOLIDITY = 0.5


def snap_limit(snap_deg: float, solidity: float) -> float:
    """The snapping angle for a print: ``snap_deg``, or at most
    :data:`AXIS_AGREE_DEG` under :data:`SNAP_SOLIDITY`.

    Parameters
    ----------
    snap_deg : float [deg]
        ``axis_misaligned_deg``.
    solidity : float [-]
        The print's net / gross (ink over hull area).

    Returns
    -------
    float [deg]
    """
    return snap_deg if solidity >= SNAP_SOLIDITY else min(snap_deg, AXIS_AGREE_DEG)


def _min_width_turn(xy: np.ndarray, given: float) -> float:
    """The direction of a convex outline's least width (rotating calipers: one
    caliper flush with an edge), turned from ``given`` [rad], [deg] in [-45, 45)."""
    import cv2

    hull = cv2.convexHull(xy.astype(np.float32)).reshape(-1, 2).astype(np.float64)
    edge = np.roll(hull, -1, axis=0) - hull
    edge = edge[np.hypot(edge[:, 0], edge[:, 1]) > 0]
    normal = np.column_stack([-edge[:, 1], edge[:, 0]]) / np.hypot(edge[:, 0], edge[:, 1])[:, None]
    width = np.ptp(normal @ hull.T, axis=1)  # (edges, points): a hull has hundreds at most
    e = edge[np.argmin(width)]
    return (math.degrees(math.atan2(e[1], e[0]) - given) + 45.0) % 90.0 - 45.0


def settled_turn(hull_px, given: float, *, spread: float) -> float | None:
    """The print's own axis turned from ``given``, when where exactly it lies does not matter.

    Three estimates of the print's axis - its hull's minimum-area rectangle
    (:func:`own_axis`), its least width (rotating calipers), its principal axis -
    each give a length and width (extents along and across); when these lie within
    ``spread`` of each other the rectangle's turn is returned. A knob or dot
    pattern's estimates can differ by degrees (a rounded hull's rectangle and
    moments are ill-defined), which is why such a print was snapped within 1
    degree only (:data:`SNAP_SOLIDITY`); but its length and width do not depend on
    the axis when the estimates agree in them. Where they do not (independent
    set 111 sheet 31: a knobby print square to the sheet, rectangle -5.5 deg,
    principal axis -6.7 deg, lengths 2.2 % apart) the print is not snapped.
    (On the held-out sets 2026 and 7-11 and independent 111, 945 prints: no print
    measured right along its true axis read out of the bar when snapped this way
    with ``spread`` 0.5 %.)

    Parameters
    ----------
    hull_px : (k, 2) float [px]
        The print's hull, (row, col).
    given : float [rad]
        Given rolling direction from the sheet's +x.
    spread : float [-]
        Largest relative difference of the lengths or widths along the three.

    Returns
    -------
    float [deg] or None
        The rectangle's turn in [-45, 45), None when the estimates disagree.
    """
    xy = _sheet_xy(hull_px)
    turn, _ = own_axis(hull_px, given)
    turns = (turn, _min_width_turn(xy, given), _principal_turn(hull_px, given))
    ext = np.array([_extents(xy, given + math.radians(t)) for t in turns])  # (3, 2)
    if np.max(np.ptp(ext, axis=0) / np.maximum(ext.min(axis=0), 1e-9)) > spread:
        return None
    return turn


def _principal_turn(hull_px, given: float) -> float:
    """The hull's principal axis nearest ``given`` [rad], turned from it [deg], in [-45, 45)."""
    return (math.degrees(rolling_angle(hull_px, "auto") - given) + 45.0) % 90.0 - 45.0


def _principal_agrees(hull_px, given: float, turn: float) -> bool:
    """Whether the hull's principal axis is turned from ``given`` [rad] as its
    own axis is (``turn`` [deg], :func:`own_axis`), within :data:`AXIS_AGREE_DEG`
    or 30 % of the turn: a rounded knob pattern's minimum-area rectangle can lie on
    a diagonal (-26 deg on a square print), its second moments do not follow."""
    principal = _principal_turn(hull_px, given)
    return abs(principal - turn) <= max(AXIS_AGREE_DEG, 0.3 * abs(turn))


def own_axis(hull_px, angle: float) -> tuple[float, float]:
    """The print's own axis nearest a given rolling direction, and the error of the given one.

    The own axes are those of the hull's minimum-area bounding rectangle (robust to
    a sparse knob pattern, whose second moments tilt by degrees); of its two axes the
    one nearest ``angle`` (modulo 90 degrees) is compared, so a print wider than long
    is compared along its short side.

    Parameters
    ----------
    hull_px : (k, 2) float [px]
        The print's hull, (row, col).
    angle : float [rad]
        Given rolling direction from the sheet's +x.

    Returns
    -------
    turn : float [deg]
        Own axis minus given axis, in [-45, 45).
    excess : float
        Largest relative excess of the length or the width measured along ``angle``
        over those along the own axis (0 when aligned).
    """
    import cv2

    xy = _sheet_xy(hull_px).astype(np.float32)
    own = math.radians(cv2.minAreaRect(xy)[2])
    turn = (math.degrees(own - angle) + 45.0) % 90.0 - 45.0

    return turn, _turn_excess(xy, angle, turn)


def _turn_excess(xy: np.ndarray, angle: float, turn: float) -> float:
    """The largest relative excess of the extents of points ``xy`` (x, y) along
    ``angle`` [rad] (and across) over those along ``angle`` + ``turn`` [deg]."""
    given, best = _extents(xy, angle), _extents(xy, angle + math.radians(turn))
    return float(np.max(given / np.maximum(best, 1e-9)) - 1.0)


def _mask_excess(more: np.ndarray, less: np.ndarray, angle: float) -> float:
    """The largest relative excess of the length or the width (along ``angle`` [rad]
    and across) of the pixels of mask ``more`` over those of mask ``less`` (both in
    one box, (row, col); extents of whole pixels)."""
    flip = np.array([1.0, -1.0])
    ext = [_extents(outline_points(m).reshape(-1, 2) * flip, angle) + 1.0 for m in (more, less)]
    return float(np.max(ext[0] / ext[1]) - 1.0)


def _extents(xy: np.ndarray, angle: float) -> np.ndarray:
    """Extents [px] of points along ``angle`` and across it."""
    c, s = math.cos(angle), math.sin(angle)
    return np.ptp(xy @ np.array([[c, -s], [s, c]], np.float64), axis=0)


def _band_values(m) -> dict:
    values = (
        m.length,
        m.width,
        m.hull_area,
        m.area,
        m.ellipse_direct.length,
        m.ellipse_direct.width,
    )
    return dict(zip(BAND_KEYS, values, strict=True))


def _grey(scan: Scan, page: Page, rows: slice, cols: slice) -> np.ndarray:
    """The grey [0, 1] of a box as thresholded: the page's flattened levels when
    the light was flattened or the page cut from a photo, else the scan's own."""
    if page.flattened or page.sheet is not None:
        return page.work[rows, cols] * np.float32(1 / 255)
    return scan.crop(rows, cols)


def _light_flag(ctx: _Context, g: Group, grey: np.ndarray, ink: np.ndarray, index: int) -> tuple:
    """``('light_uncertain', warning)`` when the light changes around the print by
    more than its ink lies below the threshold (x ``light_fill_error``), else ()."""
    change, margin = _light_margin(ctx, g, grey, ink)
    if ctx.opts.light_fill_error * change <= margin:
        return ()
    return (
        "light_uncertain",
        f"print #{index}: the light changes by {100 * math.expm1(change):.0f} % around "
        f"it (a shadow's edge or a steep gradient) while its ink is only "
        f"{100 * -math.expm1(-margin):.0f} % darker than the threshold: the paper's "
        f"brightness filled in under it may move its outline; light the sheet evenly "
        f"(no shadow across the print) or scan it",
    )


def _light_margin(ctx: _Context, g: Group, grey: np.ndarray, ink: np.ndarray) -> tuple:
    """How much the light changes around a print and how far its ink lies below the
    threshold, both as log ratios (0, inf when the light was not flattened).

    Under the print the paper's brightness is filled in from around it: where the
    light changes around the print (a shadow band's edge crossing it) the fill may
    be off by about that change, and ink lighter than the threshold by less than
    that may come out as paper (a print inked 0.45 under a 40 % shadow band: length
    -12 %, -47 % with a hard-edged band)."""
    change = light_spread(ctx.page, g.rows, g.cols)
    if change <= 0 or not ink.any():
        return 0.0, math.inf
    level = ctx.binarization.level
    t = (float(level) if np.ndim(level) == 0 else float(np.median(level))) / 255.0
    median = float(np.median(grey[ink][::2]))
    return change, math.log(max(t, 1e-3) / max(median, 1e-3))


def _darkness(grey: np.ndarray, mask: np.ndarray) -> np.ndarray:
    """Darkness relative to the paper around the print: 0 on paper, 1 for black
    (so faintness compares ink with ink whatever the light or the paper's shade)."""
    paper_px = grey[::3, ::3][~mask[::3, ::3]]
    paper = float(_median(paper_px)) if paper_px.size else 1.0
    return np.clip((paper - grey) / max(paper, 1e-3), 0.0, 1.0)


@dataclass(frozen=True)
class FoundPrints:
    """Ink of a sheet sorted into prints and the rest.

    Attributes
    ----------
    groups : list of Group
        The prints' ink (specks removed), top to bottom.
    marks : list of Mark
        Ink set aside (lines, text, dust, noise) and groups that are not prints.
    sorted : SortedInk
        The sorting (where the marks are, for the sensitivity band).
    grid : Gridlines or None
        Chart-paper gridlines taken out of the ink before sorting
        (:func:`inkprint.gridlines.find_gridlines`).
    """

    groups: list
    marks: list
    sorted: SortedInk = field(repr=False)
    grid: Gridlines | None = field(default=None, repr=False)
    #: rulers' scales among the marks (:func:`inkprint.ruler.find_scales`)
    scales: tuple = field(default=(), repr=False)
    #: (Group, Mark) pairs: groups set aside as letters only because a print this
    #: small is solid, or as fragments beside a print, that look like tiny tread
    #: prints (:func:`inkprint.group.maybe_tiny_print`); measured and flagged
    #: ``maybe_mark``
    unsure: tuple = field(default=(), repr=False)

    @property
    def rejected(self) -> list[str]:
        """Why each mark is not a print."""
        return [f"{m.kind}: {m.reason}" for m in self.marks]


def find_prints(
    mask,
    *,
    mm_per_px: float,
    options: AnalysisOptions | None = None,
    sheet_area_mm2: float | None = None,
    grey: np.ndarray | None = None,
    threads: int | None = 1,
) -> FoundPrints:
    """Sort a sheet's ink (:func:`inkprint.marks.sort_ink`) and keep the prints.

    Parameters
    ----------
    mask : (rows, cols) bool
        Ink of the sheet.
    mm_per_px : float [mm / px]
    options : AnalysisOptions, optional
        Grouping, mark, speck and print-shape thresholds (defaults when None).
    sheet_area_mm2 : float, optional [mm^2]
        Area of the page (for the automatic ink floor); default the image's.
    grey : (rows, cols) uint8 or float, optional
        The sheet's grey levels: ink printed over a gridline, darker than the line,
        stays ink (:func:`inkprint.gridlines.find_gridlines`).
    threads : int, optional
        Groups of ink checked at once (each split apart, cleared of specks and
        judged: :func:`_checked_parts`); None: the cores this process may use. The
        result does not depend on it.

    Returns
    -------
    FoundPrints
    """
    opts = resolve_options(options)
    threads = resolve_threads(threads)
    shape = mask.shape
    area = sheet_area_mm2 if sheet_area_mm2 is not None else area_px_to_mm2(mask.size, mm_per_px)
    floor = opts.patch_area_floor(area)
    speck_px = area_mm2_to_px(opts.speck_area_mm2, mm_per_px)
    grid = find_gridlines(mask, mm_per_px=mm_per_px, options=opts, grey=grey)
    sheet_ink = mask if grid is None else mask & ~grid.removed
    ink = sort_ink(sheet_ink, mm_per_px=mm_per_px, options=opts)
    marks, kept = list(ink.marks), []
    if grid is not None:
        marks.append(_grid_mark(grid.removed, mm_per_px))
    short = []  # (piece, its mark's index): too short for a print (is_print)
    small = []  # (piece, its mark): set aside only as not solid or as a fragment
    check_kw = dict(mm_per_px=mm_per_px, opts=opts, speck_px=speck_px, floor=floor, shape=shape)
    for g, check in _checked_parts(ink.groups, threads, **check_kw):
        ink_mm2 = area_px_to_mm2(g.n_pixels, mm_per_px)
        if check.ok and g.aside_mm2 > opts.writing_share * ink_mm2:
            check = PrintCheck(
                False,
                f"writing: {g.aside_mm2:.1f} mm^2 of pen strokes around {ink_mm2:.1f} mm^2 of "
                f"thicker ink (a letter's junctions)",
                "writing",
            )
        if check.ok:
            kept.append(g)
        else:
            if check.short:
                short.append((g, len(marks)))
            marks.append(_group_mark(g, check.kind, check.reason, mm_per_px))
            if check.small:
                small.append((g, marks[-1]))
    kept, marks = _join_pattern_marks(kept, short, marks, sheet_ink)
    kept = _without_texture_bits(kept, marks, shape, mm_per_px)
    kept = _without_words(kept, marks, mm_per_px)
    groups, fragments = _fragments(kept, opts, shape, mm_per_px)
    groups, fragments = join_shoulders(groups, fragments, mm_per_px=mm_per_px)
    biggest = max((g.n_pixels for g in kept), default=0)
    for g in fragments:
        why = f"a fragment beside the prints ({100 * g.n_pixels / biggest:.1f} % of the largest)"
        marks.append(_group_mark(g, "fragment", why, mm_per_px))
        small.append((g, marks[-1]))  # (a tiny print near a large one: maybe_mark)
    # (a ruler's numbers and ticks make no lattice print: its scale found first)
    scales = tuple(find_scales(sheet_ink, marks, mm_per_px=mm_per_px)) if groups else ()
    lattice = lattice_prints(sheet_ink, groups, marks=marks, mm_per_px=mm_per_px, options=opts)
    lattice = [g for g in lattice if not _under_a_scale(g, scales, mm_per_px)]
    stacks = stroke_stacks(sheet_ink, groups + lattice, marks=marks, mm_per_px=mm_per_px)
    # (a stack is as large as any print must be: min_patch_area_mm2, _width_mm,
    # _length_mm; its strokes leave more paper in its hull than a print's body)
    stacks = [g for g in stacks if _print_sized(g, opts, floor, shape, mm_per_px)]
    joined, stacks = join_stacks(groups, stacks, mm_per_px=mm_per_px)
    # (by identity: a Group's == compares its masks, ambiguous for numpy arrays)
    grown = [g for g, g0 in zip(joined, groups, strict=True) if g is not g0]
    if lattice or stacks or grown:  # their elements were set aside as marks
        new = lattice + stacks + grown
        marks = [
            mk for mk in marks if not any(_holds(g, mk.bbox, sheet_ink, mk.kind) for g in new)
        ]
        # a print a stack joined: the marks along its outline were its strokes
        # unless a mark still meets its box
        joined = [
            g
            if g is g0 or any(_meets(g, mk.bbox) for mk in marks)
            else dataclasses.replace(g, edge_marks=0.0)
            for g, g0 in zip(joined, groups, strict=True)
        ]
        groups = sorted(joined + lattice + stacks, key=reading_order)
    unsure = _maybe_tiny(small, marks, groups, scales, mm_per_px)
    return FoundPrints(groups, marks, ink, grid, scales, unsure)


def _checked_parts(groups: list, threads: int, **kw) -> list:
    """``(piece, PrintCheck)`` of every piece of ``groups`` (:func:`_checked`), in
    order, the groups on up to ``threads`` threads (each group's work is its own:
    the order of the result does not depend on them)."""
    threads = min(threads, len(groups))
    if threads <= 1:
        return [c for g in groups for c in _checked(g, **kw)]
    from concurrent.futures import ThreadPoolExecutor

    with ThreadPoolExecutor(threads, thread_name_prefix="inkprint-find") as pool:
        return [c for cs in pool.map(lambda g: _checked(g, **kw), groups) for c in cs]


def _checked(g0: Group, *, mm_per_px, opts, speck_px, floor, shape) -> list:
    """``(piece, PrintCheck)`` of each piece of a group of ink
    (:func:`inkprint.apart.split_apart`) with some ink left without its specks
    (:func:`inkprint.binarize.remove_specks`), judged by :func:`is_print`."""
    out = []
    for p in split_apart(g0, mm_per_px=mm_per_px, options=opts):
        g = dataclasses.replace(p, mask=remove_specks(p.mask, speck_px))
        if g.mask.any():
            out.append(
                (
                    g,
                    is_print(
                        g, mm_per_px=mm_per_px, options=opts, floor_mm2=floor, image_shape=shape
                    ),
                )
            )
    return out


#: a small group set aside whose box lies this much inside a print's box or more is
#: left among that print's marks (:func:`_maybe_tiny`)
UNSURE_INSIDE = 0.9


def _maybe_tiny(small: list, marks: list, groups: list, scales: tuple, mm_per_px: float):
    """The (group, mark) pairs of ``small`` whose mark is still set aside, whose box
    lies less than :data:`UNSURE_INSIDE` inside every print's (a print's elements
    left among its marks) and under no ruler's scale, and that may be tiny tread
    prints (:func:`inkprint.group.maybe_tiny_print`)."""
    left = {id(mk) for mk in marks}
    return tuple(
        (g, mk)
        for g, mk in small
        if id(mk) in left
        and not any(_box_share(mk.bbox, p) >= UNSURE_INSIDE for p in groups)
        and not _under_a_scale(g, scales, mm_per_px)
        and maybe_tiny_print(g.mask, mm_per_px=mm_per_px)
    )


def _join_pattern_marks(kept: list, short: list, marks: list, ink: np.ndarray) -> tuple:
    """The candidate prints with the pieces set aside that continue their pattern
    joined (:func:`inkprint.pattern.join_pattern_pieces`), and the marks left.

    The pieces: ``short``, (piece, its mark's index in ``marks``) set aside by
    :func:`is_print` as too short, and the pieces wholly inside the boxes of the
    letters and lines set aside before grouping (``ink``: the sheet's ink;
    :func:`inkprint.pattern.mark_pieces`). A mark goes when all its pieces joined.
    """
    aside = [k for k, m in enumerate(marks) if m.kind in MARK_KINDS]
    inside, owner = mark_pieces(ink, [marks[k].bbox for k in aside], kept)
    kept, joined = join_pattern_pieces(kept, [g for g, _ in short] + inside, marked=len(inside))
    gone = {k for (_, k), j in zip(short, joined, strict=False) if j}
    held = np.array([aside[k] for k in owner], int)
    took = joined[len(short) :]
    gone |= set(held[took]) - set(held[~took])
    return kept, [m for k, m in enumerate(marks) if k not in gone]


#: a print whose outline touches at least this many of its pieces besides the
#: largest runs over separate elements (:func:`_outline_elements`)
OUTLINE_ELEMENTS = 8


def _outline_elements(kept: np.ndarray, pieces: tuple) -> bool:
    """Whether a print's outline runs over :data:`OUTLINE_ELEMENTS` or more of its
    pieces besides the largest (``kept``: its ink, ``pieces`` its
    :func:`components_with_stats`): a file tread's rows of diamonds either side of
    a slick centre joined to it, not found a fine tread (held-out 6 seed 1 sheet 82
    page 2: 23.0 x 4.7 mm at 240 dpi, 43 px wide, its diamonds' tips cut short by a
    pixel a side: width -4.5 % with status ok)."""
    n, lab, st, _ = pieces
    if n - 2 < OUTLINE_ELEMENTS:
        return False
    on = pieces_on_outline(kept, lab, n)
    on[0] = False
    on[int(np.argmax(st[1:, 4])) + 1] = False
    return int(np.count_nonzero(on)) >= OUTLINE_ELEMENTS


def _coarse_flag(
    group: Group, metrics, index: int, mm_per_px: float, *, elements: bool = False
) -> tuple:
    """``('coarse_elements', warning)`` for a print of separate elements too few
    pixels wide or long (:func:`inkprint.lattice.coarse_elements`); ``('coarse',
    warning)`` for a print so few pixels wide (or long) that :data:`EDGE_PX` is
    more than ``CORNER_FLAG`` of that; else ``()``. ``elements``: its outline runs
    over separate elements (:func:`_outline_elements`)."""
    width_mm, length_mm = metrics.width, metrics.length
    short = coarse_elements(group, width_mm, mm_per_px, length_mm=length_mm, elements=elements)
    if short <= CORNER_FLAG:
        least = min(width_mm, length_mm)
        across = mm_to_px_length(least, mm_per_px)
        if EDGE_PX <= CORNER_FLAG * across:
            return ()
        dpi = mm_per_px_to_dpi(CORNER_FLAG * least / EDGE_PX)
        return (
            "coarse",
            f"print #{index} is {across:.0f} px across at this resolution: its edges are "
            f"good to about {EDGE_PX:g} px between them, {100 * EDGE_PX / across:.1f} % "
            f"of its size; rescan at {dpi:.0f} dpi or more",
        )
    # the resolution at which both shortfalls are CORNER_FLAG of the print
    dpi = max(
        mm_per_px_to_dpi(CORNER_FLAG * width_mm / CORNER_SHORT_PX),
        mm_per_px_to_dpi(CORNER_FLAG * length_mm / TIP_SHORT_PX),
    )
    return (
        "coarse_elements",
        f"print #{index}: a print of separate tread elements, "
        f"{mm_to_px_length(length_mm, mm_per_px):.0f} x "
        f"{mm_to_px_length(width_mm, mm_per_px):.0f} px at this resolution: its outline "
        f"is its elements' corners and tips, which the edge cuts short by up to "
        f"{CORNER_SHORT_PX:g} px across and {TIP_SHORT_PX:g} px along (length or width "
        f"up to {100 * short:.1f} % low); rescan at {dpi:.0f} dpi or more",
    )


def _holds(g: Group, bbox, ink=None, kind: str = "") -> bool:
    """Whether a mark's box (r0, c0, r1, c1) lies within the group's (a straight
    line's, ``kind`` 'line', also most of the sheet's ``ink`` in it in the group's
    mask: a lattice print's box held a tiny print's slick centre rib taken out as a
    ruler, and the rib went from the marks without joining the print, -11 % long
    unflagged)."""
    r0, c0, r1, c1 = bbox
    inside = g.rows.start <= r0 and r1 <= g.rows.stop and g.cols.start <= c0 and c1 <= g.cols.stop
    if not inside or kind != "line" or ink is None:
        return inside
    box = (slice(r0, r1), slice(c0, c1))
    own = g.mask[r0 - g.rows.start : r1 - g.rows.start, c0 - g.cols.start : c1 - g.cols.start]
    return 2 * np.count_nonzero(own & ink[box]) >= np.count_nonzero(ink[box])


def _box_share(bbox, g: Group) -> float:
    """The share of a mark's box (r0, c0, r1, c1) inside the group's box."""
    r0, c0, r1, c1 = bbox
    h = min(r1, g.rows.stop) - max(r0, g.rows.start)
    w = min(c1, g.cols.stop) - max(c0, g.cols.start)
    return max(h, 0) * max(w, 0) / max((r1 - r0) * (c1 - c0), 1)


def _meets(g: Group, bbox) -> bool:
    """Whether a mark's box (r0, c0, r1, c1) overlaps the group's."""
    r0, c0, r1, c1 = bbox
    return r0 < g.rows.stop and g.rows.start < r1 and c0 < g.cols.stop and g.cols.start < c1


def _without_texture_bits(kept: list, marks: list, shape, mm_per_px: float) -> list:
    """The candidate prints less the small ones (under ``SMALL_PRINT_MM2`` of ink)
    cut by the image's edge amid noise or texture set aside over the sheet: there a
    blob of the texture cannot be told from a print's last piece (a texture page
    gave a 6 x 4 mm "print" at its corner instead of "no print found"); they are
    set aside as texture (in ``marks``)."""
    out = []
    for g in kept:
        small = area_px_to_mm2(g.n_pixels, mm_per_px) < SMALL_PRINT_MM2
        if small and _sides(g, shape, near=False) and _spread_marks_over(marks, g):
            why = "a small blob cut by the image's edge amid texture or noise set aside"
            marks.append(_group_mark(g, "texture", why, mm_per_px))
        else:
            out.append(g)
    return out


def _without_words(kept: list, marks: list, mm_per_px: float) -> list:
    """The candidate prints less the words of a line of writing set aside beside
    them (:func:`inkprint.group.word_in_a_line`), which are set aside as writing
    (in ``marks``); a word set aside is writing beside the next ('40' after 'Bite'
    of '... Bite 40'). A line of bold writing alone (:func:`inkprint.group.text_line`)
    is set aside first."""
    lines = [text_line(g, mm_per_px=mm_per_px) for g in kept]
    why = "a line of writing: letters of unlike sizes in one row, no print's pattern"
    marks.extend(
        _group_mark(g, "writing", why, mm_per_px) for g, t in zip(kept, lines, strict=True) if t
    )
    out = [g for g, t in zip(kept, lines, strict=True) if not t]
    while True:
        writing = np.array([m.bbox for m in marks if m.kind in ("writing", "text")])
        words = [word_in_a_line(g, writing, mm_per_px=mm_per_px) for g in out]
        if not any(words):
            return out
        why = "a word of a line of writing beside it (letters in line with it)"
        marks.extend(
            _group_mark(g, "writing", why, mm_per_px) for g, w in zip(out, words, strict=True) if w
        )
        out = [g for g, w in zip(out, words, strict=True) if not w]


def _grid_mark(grid: np.ndarray, mm_per_px: float) -> Mark:
    import cv2

    x, y, w, h = cv2.boundingRect(grid.view(np.uint8))
    area = area_px_to_mm2(int(np.count_nonzero(grid)), mm_per_px)
    why = "chart-paper gridlines, taken out of the ink outside the prints' own ink"
    return Mark("gridlines", (y, x, y + h, x + w), area, why)


def _print_sized(g: Group, opts, floor: float, shape, mm_per_px: float) -> bool:
    """Whether group ``g`` passes :func:`is_print`'s size tests (ink floor, length,
    width, aspect), whatever its fill."""
    check = is_print(g, mm_per_px=mm_per_px, options=opts, floor_mm2=floor, image_shape=shape)
    return check.ok or not (check.short or check.kind in ("dust", "line"))


def _fragments(kept: list, opts, shape, mm_per_px: float) -> tuple[list, list]:
    """The groups kept as prints, and the fragments: under ``min_patch_fraction`` of
    the largest print's ink and beside a larger print (:func:`_beside_bigger`). A
    small piece cut by the image's edge is a print running off it (flagged clipped),
    not a fragment: a print 97 % off the sheet went missing."""
    biggest = max((g.n_pixels for g in kept), default=0)
    groups, fragments = [], []
    for g in kept:
        cut = _sides(g, shape, near=False) > 0
        small = g.n_pixels < opts.min_patch_fraction * biggest
        if small and not cut and _beside_bigger(g, kept, opts.min_patch_fraction, mm_per_px):
            fragments.append(g)
        else:
            groups.append(g)
    return groups, fragments


def _beside_bigger(g: Group, groups: list, fraction: float, mm_per_px: float) -> bool:
    """Whether group ``g`` lies within :data:`FRAGMENT_REACH_MM` (box to box) of a
    group with more than 1 / ``fraction`` times its ink: a fragment of that print
    (a shoulder beyond a wide groove, a tip), not a print of its own. A small print
    far from the others is one (held-out 6 seed 1 sheet 108: a 17 x 4 mm slick
    print and a 17 x 5 mm file print 25-60 mm from a 110 mm print, 2.5 % of its
    ink, set aside as fragments: missing)."""
    reach = mm_to_px_length(FRAGMENT_REACH_MM, mm_per_px)
    for h in groups:
        if h is g or g.n_pixels >= fraction * h.n_pixels:
            continue
        dr = max(0, h.rows.start - g.rows.stop, g.rows.start - h.rows.stop)
        dc = max(0, h.cols.start - g.cols.stop, g.cols.start - h.cols.stop)
        if np.hypot(dr, dc) <= reach:
            return True
    return False


def _group_mark(g: Group, kind: str, reason: str, mm_per_px: float) -> Mark:
    box = (g.rows.start, g.cols.start, g.rows.stop, g.cols.stop)
    return Mark(kind, box, area_px_to_mm2(g.n_pixels, mm_per_px), reason)


@dataclass(frozen=True)
class _BandWindow:
    """A print's box grown by the group distance (sheet rows and cols [px]) and the
    region near the print's ink in it, marks excepted (``(h, w) bool``): where
    re-thresholded ink still belongs to this print."""

    rows: slice
    cols: slice
    region: np.ndarray
    fine_area_mm2: float = 0.0


def _band_window(shape, g: Group, found: FoundPrints, mm_per_px: float, opts) -> _BandWindow:
    import cv2

    pad = int(np.ceil(mm_to_px_length(opts.group_distance_mm, mm_per_px)))
    h, w = shape
    r0, r1 = max(g.rows.start - pad, 0), min(g.rows.stop + pad, h)
    c0, c1 = max(g.cols.start - pad, 0), min(g.cols.stop + pad, w)
    region = np.zeros((r1 - r0, c1 - c0), np.uint8)
    region[g.rows.start - r0 : g.rows.stop - r0, g.cols.start - c0 : g.cols.stop - c0] = g.mask
    region = cv2.dilate(region, np.ones((2 * pad + 1, 2 * pad + 1), np.uint8)).astype(bool)
    rows, cols = slice(r0, r1), slice(c0, c1)
    region &= ~found.sorted.marks_near(rows, cols)
    if found.grid is not None:  # at another threshold the lines are wider by a pixel
        near = cv2.dilate(found.grid.removed[rows, cols].view(np.uint8), np.ones((3, 3), np.uint8))
        region &= ~near.view(bool)
    return _BandWindow(rows, cols, region, g.fine_area_mm2)


@dataclass(frozen=True)
class _Context:
    """What measuring a print needs of its sheet."""

    scan: Scan
    page: Page
    binarization: Binarization
    found: FoundPrints
    rolling_axis: str
    opts: AnalysisOptions


def sensitivity_band(ctx: _Context, group: Group, *, base: dict) -> dict:
    """Re-measure one print at the threshold x (1 -+ ``options.sensitivity``).

    Parameters
    ----------
    ctx : _Context
        The sheet (scan, page, threshold, sorted ink, axis, options).
    group : Group
        The print's ink at the sheet's threshold.
    base : dict
        ``{key: value}`` for ``BAND_KEYS`` at the threshold itself.

    Returns
    -------
    dict
        ``{key: (low, high)}`` over the three thresholds.
    """
    values = {k: [v] for k, v in base.items()}
    for band in _bands(ctx, group, _factors(ctx.opts)):
        for k, v in band.items():
            values[k].append(v)
    return _band_range(values)


def _factors(opts: AnalysisOptions) -> tuple:
    """The band's thresholds relative to the sheet's: 1 -+ ``sensitivity``."""
    return (1.0 - opts.sensitivity, 1.0 + opts.sensitivity)


def _bands(ctx: _Context, group: Group, factors) -> list:
    """The print's ``BAND_KEYS`` values at the threshold x each of ``factors``
    (:func:`_band_at`), in one window: its grey and that grey's local range found
    once for all."""
    win = _band_window(ctx.page.work.shape, group, ctx.found, ctx.scan.mm_per_px, ctx.opts)
    grey = _grey(ctx.scan, ctx.page, win.rows, win.cols)
    local = []  # the grey's local range, once one threshold needs it
    return [_band_at(ctx, win, f, grey=grey, local=local) for f in factors]


def _band_range(values: dict) -> dict:
    """``{key: (low, high)}`` of ``{key: [value, ...]}``."""
    return {k: (float(np.nanmin(v)), float(np.nanmax(v))) for k, v in values.items()}


def _outlined(mask: np.ndarray) -> bool:
    """Whether ink has an outline to measure: pixels not all on one line."""
    import cv2

    pts = outline_points(mask)
    return pts is not None and cv2.contourArea(cv2.convexHull(pts)) > 0


def _band_at(ctx: _Context, win: _BandWindow, factor: float, *, grey, local: list) -> dict:
    """The print's ``BAND_KEYS`` values with the sheet's threshold x ``factor`` in
    its window (:func:`_band_window`, whose ``grey`` is given; ``{}`` when nothing
    of it is left there). ``local``: [] or [the grey's local range], filled here."""
    opts, s = ctx.opts, ctx.scan.mm_per_px
    work = ctx.page.work[win.rows, win.cols]
    level = ctx.binarization.level
    level = level if np.ndim(level) == 0 else level[win.rows, win.cols]
    # (the ink's pieces labelled once: for the specks and the edge spots)
    ink, pieces = _unspecked(
        below(work, level * factor) & win.region, area_mm2_to_px(opts.speck_area_mm2, s)
    )
    if pieces.n <= 1:
        return {}
    spots = _edge_spots(
        Group(win.rows, win.cols, ink, fine_area_mm2=win.fine_area_mm2),
        _darkness(grey, ink),
        pieces,
        mm_per_px=s,
        options=opts,
        tread_gap=False,
    )
    if not _outlined(spots.load_bearing):
        return {}  # (no ink, or a line of pixels: no outline at this threshold)
    kept = _without_scale(ctx, Group(win.rows, win.cols, spots.load_bearing), spots.load_bearing)
    if not local:
        local.append(_local_range(grey, s, opts))
    fld = edge_field(grey, kept, mm_per_px=s, options=opts, local=local[0])
    grid = _grid_in(ctx.found.grid, win.rows, win.cols)
    return _band_metrics(
        kept,
        win.rows.start,
        win.cols.start,
        _paper_where_set_apart(fld, grid | (spots.load_bearing & ~kept), kept),
        n_rows=ctx.page.work.shape[0],
        mm_per_px=s,
        axis=ctx.rolling_axis,
        opts=opts,
    )


def _edge_margins(ink: np.ndarray, least_px: float, tread_gap: float) -> tuple[int, int]:
    """How near the image's top/bottom and left/right edges a print may come before
    it may run off the sheet: a tread cut by the edge can end in a groove short of
    it, and the widest groove it could end in is the widest one that crosses the
    whole print there, one and a half times over.

    Parameters
    ----------
    ink : (h, w) bool
        The print's load-bearing ink.
    least_px : float [px]
        The least margin (the grouping distance).
    tread_gap : float [px]
        The print's typical gap between its elements (0 for one blob).

    Returns
    -------
    (rows, cols) int [px]
        Margins to the top/bottom and to the left/right edges.

    Notes
    -----
    A groove that crosses the whole print along the rows shows as empty rows in its
    ink's projection. Before, the element gap ruled both ways: a car print of four
    ribs with 9 mm grooves between them, 12 mm off the left edge, was flagged
    ``clipped`` although its ribs run unbroken to their rounded ends along the rows
    (held-out seed 5 sheet 93, seeds 1 and 3 likewise).
    """
    out = []
    for axis in (1, 0):  # empty rows (sum over columns), then empty columns
        inked = np.flatnonzero(ink.any(axis=axis))
        cross = float(np.diff(inked).max() - 1) if inked.size > 1 else 0.0
        out.append(int(np.ceil(max(least_px, 1.5 * min(tread_gap, cross)))))
    return out[0], out[1]


def clipped(group: Group, shape, sheet=None, *, margin_px: int | tuple = 0) -> str:
    """Why a print may be cut off ('' if it is whole): it comes within
    ``margin_px`` of the image's edge (a tread running off the sheet can end in a
    groove short of it), or touches the edge of the page found in a photo.

    Parameters
    ----------
    group : Group
    shape : (rows, cols) int
        The image.
    sheet : (rows, cols) bool, optional
        The page inside a photo.
    margin_px : int or (rows, cols) int [px]
        One margin, or one to the top/bottom and one to the left/right edges
        (:func:`_edge_margins`).

    Returns
    -------
    str
    """
    import cv2

    h, w = shape
    r, c = group.rows, group.cols
    mr, mc = (margin_px, margin_px) if np.isscalar(margin_px) else margin_px
    if r.start <= mr or c.start <= mc or r.stop >= h - mr or c.stop >= w - mc:
        return (
            "reaches the image's edge: it may run off the sheet (measured: only the part "
            "on it); rescan it with a margin"
        )
    if sheet is None:
        return ""
    r0, r1, c0, c1 = (
        max(r.start - 2, 0),
        min(r.stop + 2, h),
        max(c.start - 2, 0),
        min(c.stop + 2, w),
    )
    off = np.zeros((r1 - r0, c1 - c0), np.uint8)
    off[:] = ~sheet[r0:r1, c0:c1]
    near = cv2.dilate(off, np.ones((5, 5), np.uint8))[r.start - r0 :, c.start - c0 :]
    if (near[: group.mask.shape[0], : group.mask.shape[1]].astype(bool) & group.mask).any():
        return "touches the page's edge in the photo: it may run off the page"
    return ""


def measure_print(ctx: _Context, group: Group, *, index: int = 0, sensitivity: bool = True):
    """Measure one print: edge spots (section 7.1.1), outline, metrics, band, flags.

    Parameters
    ----------
    ctx : _Context
        The sheet (scan, page, threshold, sorted ink, axis, options).
    group : Group
        The print's ink (from :func:`find_prints`).
    index : int
        The print's number on the sheet (0-based, top to bottom).
    sensitivity : bool
        Compute the threshold sensitivity band (else each band is the value itself).

    Returns
    -------
    PrintResult
    """
    opts, s = ctx.opts, ctx.scan.mm_per_px
    n_rows = ctx.page.work.shape[0]
    ctx, group, taken, ink, pieces = _ink_with_caps(ctx, group)
    g, grey, line_ink, spots, kept, hidden, no_core = ink
    kw = dict(
        n_rows=n_rows,
        mm_per_px=s,
        axis=ctx.rolling_axis,
        snap_deg=opts.axis_misaligned_deg,
        settle=opts.axis_misaligned_excess,
    )
    local = _local_range(grey, s, opts)
    fld_all = edge_field(grey, g.mask, mm_per_px=s, options=opts, local=local)
    same = np.array_equal(kept, g.mask)  # nothing set apart: one outline
    fld = fld_all if same else edge_field(grey, kept, mm_per_px=s, options=opts, local=local)
    # ink set aside beside the print (a ruler or a label touching it, gridlines) is
    # not its edge: next to it the field reads paper (a ruler's grey pulled the
    # outline a pixel out where it crossed the edge, width +2.9 % at 200 dpi)
    aside = (ctx.binarization.mask[g.rows, g.cols] & ~g.mask) | _grid_in(
        ctx.found.grid, g.rows, g.cols
    )
    fld = _paper_where_set_apart(fld, (g.mask & ~kept) | aside, kept)
    m = measure_mask(kept, g.rows.start, g.cols.start, field=fld, **kw)
    if same:  # the same ink, field, outline and direction: the same numbers
        m_all = m
    else:
        fld_all = _paper_where_set_apart(fld_all, aside, g.mask)
        kw["axis"] = m.metrics.orientation  # all ink measured along the same direction
        m_all = measure_mask(g.mask, g.rows.start, g.cols.start, field=fld_all, **kw)
    base = _band_values(m.metrics)
    band = (
        sensitivity_band(ctx, g, base=base)
        if sensitivity
        else {k: (v, v) for k, v in base.items()}
    )
    margin = _edge_margins(kept, mm_to_px_length(opts.group_distance_mm, s), spots.tread_gap)
    flags, warnings = _print_flags(
        ctx,
        group,
        m,
        index,
        margin,
        padded=g,
        kept=kept,
        hidden=hidden,
        faint=line_ink,
        pieces=pieces,
    )
    ink = (kept, hidden, spots.thin, spots.tread_gap, pieces)
    flags, warnings = _edge_mark_flags(ctx, g, m, index, ink, flags, warnings)
    faint = _faint_excess(ctx, g, spots, m, grey=grey, local=local, aside=aside, kept=kept)
    spread = _spots_spread(m.metrics, m_all.metrics) if spots.n_spots >= SPOTS_MANY else 0.0
    field = spots.n_spots >= SPOTS_FIELD  # (a field of them: SPOTS_FIELD_SPREAD)
    faint = _faint_flag(opts, index, faint=faint, no_core=no_core, spread=spread, field=field)
    flags, warnings = flags + faint[:1], warnings + faint[1:]
    elements = group.fine_area_mm2 <= 0 and _outline_elements(kept, pieces)
    coarse = _coarse_flag(group, m.metrics, index, s, elements=elements)
    flags, warnings = flags + coarse[:1], warnings + coarse[1:]
    light = _light_flag(ctx, g, grey, spots.load_bearing, index)
    flags, warnings = flags + light[:1], warnings + light[1:]
    return PrintResult(
        index=index,
        metrics=m.metrics,
        metrics_all=m_all.metrics,
        n_blobs=spots.n_blobs,
        n_edge_spots=spots.n_spots,
        edge_spot_area=area_px_to_mm2(spots.spot_pixels, s),
        hull_px=m.hull_px,
        band=band,
        bbox=(group.rows.start, group.cols.start, group.rows.stop, group.cols.stop),
        flags=flags,
        warnings=warnings,
        unit=ctx.scan.unit,
        caps=taken,
    )


#: edge spots out of the section 7.1.1 rule's domain: this many or more, making the
#: print more than :data:`SPOTS_SPREAD` x longer or wider with them
SPOTS_MANY = 3
SPOTS_SPREAD = 1.0
#: ... or SPOTS_FIELD or more making it more than SPOTS_FIELD_SPREAD x longer or
#: wider: a field of a fine tread's elements, some kept (a row of dots along a slick
#: centre, :func:`inkprint.group._dot_row`), the rest left out: a tiny print's 23
#: diamonds beside its rib, width -53 % with spread 0.66 (drawn in the tests); halo
#: specks about prints that pass: at most 15, spread up to 0.65 with fewer)
SPOTS_FIELD = 20
SPOTS_FIELD_SPREAD = 0.2


def _spots_spread(measured, all_ink) -> float:
    """The largest relative excess of the length or width of all a print's ink
    (``all_ink``, edge spots included) over its load-bearing ink's (``measured``)."""
    return max(all_ink.length / measured.length, all_ink.width / measured.width) - 1.0


def _faint_flag(
    opts, index: int, *, faint: float, no_core: bool, spread: float = 0.0, field: bool = False
) -> tuple:
    """``("faint_edge", warning)`` when a print is all edge spots, when its edge spots
    more than double its length or width (``spread`` > :data:`SPOTS_SPREAD`: a tiny
    print's slick centre kept, its fine diamonds or knurls beside it, each under the
    spot size, left out as edge spots; held-out 8 sheet 14, 10 sheet 118, 12 sheets
    51 and 61: width -65 to -77 %, unflagged; the next of 1214 prints: 0.58, one
    speck off a tiny print's tip), or when the faint blobs left out at its edge
    (section 7.1.1) change a measure by more than ``edge_uncertainty``; else ``()``.
    With ``field`` (:data:`SPOTS_FIELD` edge spots or more) the spread limit is
    :data:`SPOTS_FIELD_SPREAD`."""
    if spread > (SPOTS_FIELD_SPREAD if field else SPOTS_SPREAD):
        return (
            "faint_edge",
            f"print #{index}: its edge spots, left out as not load-bearing (section "
            f"7.1.1), would make it {100 * spread:.0f} % longer or wider: a fine tread's "
            f"elements too small at this resolution beside a slick centre? The rule is "
            f"for specks at an edge; see the overlay or rescan at a higher resolution",
        )
    if no_core:
        return (
            "faint_edge",
            f"print #{index}: all its ink is edge spots by the section 7.1.1 rule (faint "
            f"or small blobs apart from any core): measured with all of it; is it a print?",
        )
    if faint > opts.edge_uncertainty:
        return (
            "faint_edge",
            f"print #{index}: a blob larger than a dot at its edge, inked lighter than "
            f"{opts.edge_spot_faintness:g} of the print was left out as not load-bearing "
            f"(section 7.1.1); with it the length, width or hull area (counted half) is "
            f"{100 * faint:.1f} % larger. Which is right is a judgement: see the overlay, "
            f"or set --edge-spot-faintness (0 keeps every blob)",
        )
    return ()


def _hull_excess(less: np.ndarray, more: np.ndarray, angle: float) -> float:
    """How much longer or wider (along ``angle`` [rad] and across) the points ``more``
    span than the points ``less`` ((k, 2) (col, row) [px] each), or half how much
    larger their convex hull's area is."""
    import cv2

    flip = np.array([1.0, -1.0])  # (rows down, the sheet's y up)
    ext = _extents(more * flip, angle) / _extents(less * flip, angle)
    area = [cv2.contourArea(cv2.convexHull(p.astype(np.float32))) for p in (less, more)]
    return float(max(np.max(ext) - 1.0, 0.5 * (area[1] / area[0] - 1.0)))


def _with_excess(kept: np.ndarray, more: np.ndarray, angle: float) -> float:
    """How much longer or wider (along ``angle`` [rad] and across), or half how much
    larger in hull area, the ink ``kept`` is with the ink ``more`` (both over one box)."""
    import cv2

    both = kept | more
    areas = [
        cv2.contourArea(cv2.convexHull(outline_points(k).astype(np.float32))) for k in (both, kept)
    ]
    return max(_mask_excess(both, kept, angle), 0.5 * (areas[0] / max(areas[1], 1.0) - 1.0))


def _print_ink(ctx: _Context, group: Group, caps: Group | None = None) -> tuple:
    """``(g, grey, line_ink, spots, kept, hidden, no_core)``: the print's padded box
    without faint lines (:func:`_without_faint_lines`), its edge spots (section
    7.1.1), and its load-bearing ink (:func:`_load_bearing`) without a ruler's ink
    sticking out where its scale crosses the outline (:func:`_without_scale`), with
    the ``caps`` (:func:`_cut_caps`) kept."""
    g, grey, line_ink = _without_faint_lines(ctx, _with_paper(ctx, group), group)
    spots = edge_spots(g, _darkness(grey, g.mask), mm_per_px=ctx.scan.mm_per_px, options=ctx.opts)
    g, kept, hidden, no_core = _load_bearing(ctx, group, g, spots)
    kept = _without_scale(ctx, g, kept)
    if caps is not None:
        kept = kept | _in_box(caps, g)
    return g, grey, line_ink, spots, kept, hidden, no_core


def _ink_with_caps(ctx: _Context, group: Group) -> tuple:
    """``(ctx, group, taken, ink, pieces)``: the print's ink (:func:`_print_ink`'s
    tuple) with the caps of its next row of elements kept (:func:`_cut_caps`:
    ``group`` holds them, ``taken`` are their boxes, ``ctx`` has them no longer
    among its marks), and its load-bearing ink's pieces
    (:func:`components_with_stats`, 8-connected), labelled once for the caps, the
    lattice and the paler pieces."""
    ink = _print_ink(ctx, group)
    g, _, _, spots, kept = ink[:5]
    pieces = components_with_stats(kept.view(np.uint8), connectivity=8)
    caps, taken = _cut_caps(ctx, group, g, kept, spots, pieces=pieces), ()
    if caps is not None:  # the same steps with the caps' ink, the caps kept
        group, taken = union(group, caps), _piece_boxes(caps)
        ctx = _without_marks(ctx, taken)
        ink = _print_ink(ctx, group, caps)
        pieces = components_with_stats(ink[4].view(np.uint8), connectivity=8)
    return ctx, group, taken, ink, pieces


def _cut_caps(
    ctx: _Context, group: Group, g: Group, kept: np.ndarray, spots, *, pieces: tuple
) -> Group | None:
    """The caps of the print's next row of elements that its outline cut
    (:func:`inkprint.caps.cut_caps`) among the ink a lattice step around its
    load-bearing ink ``kept`` (in ``g``'s box) that no other print holds, but for
    the lightly inked blocks the section 7.1.1 rule left out (``spots``'s
    ``faint_blocks``: a faint tip block stays out, flagged ``faint_edge``); None
    when there are none, when ``cut_caps`` is off, or when the print has no coarse
    lattice (a fine tread's cut elements are the rule's). ``pieces``: ``kept``'s
    (:func:`components_with_stats`, 8-connected)."""
    if group.fine_area_mm2 > 0 or not ctx.opts.cut_caps:
        return None
    n, lab, st, cen = pieces
    if n - 1 < CAP_ELEMENTS:
        return None
    big = st[1:, 4] >= 0.5 * st[1:, 4].max()
    side = float(np.median(np.maximum(st[1:, 2], st[1:, 3])[big]))
    frame = _padded(dataclasses.replace(g, mask=kept), ctx.page.work.shape, round(2.5 * side))
    rows, cols = frame.rows, frame.cols
    # (the elements as labelled over g's box, moved into the frame: labelled once)
    dr, dc = g.rows.start - rows.start, g.cols.start - cols.start
    lab_f = np.zeros(frame.mask.shape, lab.dtype)
    lab_f[dr : dr + lab.shape[0], dc : dc + lab.shape[1]] = lab
    st_f, cen_f = st.copy(), np.add(cen, [dc, dr])
    st_f[1:, 0] += dc
    st_f[1:, 1] += dr
    free = ctx.binarization.mask[rows, cols] & ~frame.mask
    if ctx.found.grid is not None:
        free &= ~ctx.found.grid.removed[rows, cols]
    free &= ~_scale_strips(ctx, frame)  # (a ruler's ticks lie on a lattice too)
    for o in ctx.found.groups:
        if o is not group:
            free &= ~_in_box(o, frame)
    if spots.faint_blocks is not None:  # (lightly inked blocks: the rule's call)
        free &= ~_in_box(dataclasses.replace(g, mask=spots.faint_blocks), frame)
    caps = cut_caps(frame.mask, free, elements=(n, lab_f, st_f, cen_f))
    if not caps.any():
        return None
    r, c = np.flatnonzero(caps.any(axis=1)), np.flatnonzero(caps.any(axis=0))
    r0, r1, c0, c1 = r[0], r[-1] + 1, c[0], c[-1] + 1
    return Group(
        slice(rows.start + r0, rows.start + r1),
        slice(cols.start + c0, cols.start + c1),
        caps[r0:r1, c0:c1],
    )


def _scale_strips(ctx: _Context, g: Group, *, ink: np.ndarray | None = None) -> np.ndarray:
    """Where rulers' scales (:func:`inkprint.ruler.scale_band`; ``ink``: sheet (x, y)
    points a strip is run on across) cross ``g``'s box ((h, w) bool)."""
    import cv2

    under = np.zeros(g.mask.shape, np.uint8)
    origin = np.array([g.cols.start, g.rows.start], float)
    for sc in ctx.found.scales:
        band = scale_band(sc, mm_per_px=ctx.scan.mm_per_px, ink=ink) - origin
        cv2.fillConvexPoly(under, np.round(band * 16).astype(np.int32), 1, cv2.LINE_8, 4)
    return under.view(bool)


def _piece_boxes(g: Group) -> tuple:
    """Sheet boxes (row0, col0, row1, col1) [px] of the group's 8-connected pieces."""
    _, _, st, _ = components_with_stats(g.mask.view(np.uint8), connectivity=8)
    r, c = g.rows.start, g.cols.start
    return tuple(
        (int(r + y), int(c + x), int(r + y + h), int(c + x + w)) for x, y, w, h in st[1:, :4]
    )


def _covered(bbox, boxes: tuple) -> bool:
    """Whether a mark's box lies within one of ``boxes`` (grown by a pixel)."""
    r0, c0, r1, c1 = bbox
    return any(
        r0 >= b[0] - 1 and c0 >= b[1] - 1 and r1 <= b[2] + 1 and c1 <= b[3] + 1 for b in boxes
    )


def _without_marks(ctx: _Context, boxes: tuple) -> _Context:
    """The context without the marks set aside that ``boxes`` cover (a print's cut
    caps: no label beside it)."""
    marks = [mk for mk in ctx.found.marks if not _covered(mk.bbox, boxes)]
    return dataclasses.replace(ctx, found=dataclasses.replace(ctx.found, marks=marks))


def _load_bearing(ctx: _Context, group: Group, g: Group, spots) -> tuple:
    """``(g, kept, hidden, no_core)``: the ink measured of a print (``g``: its padded
    box without faint lines), its load-bearing ink (section 7.1.1) less the edge
    hidden under a label's letters (``hidden``, :func:`_under_text`). With no outline
    left (every blob an edge spot, a line of pixels: ``no_core``) all its ink is
    measured, flagged ``faint_edge`` by :func:`measure_print` (held-out seed 8 sheet
    60: a 5 x 5 mm piece at the image's edge crashed the sheet, ValueError)."""
    hidden = _under_text(ctx, g, spots.load_bearing)
    kept = spots.load_bearing if hidden is None else spots.load_bearing & ~hidden
    no_core = not _outlined(kept)
    if no_core:
        if not _outlined(g.mask):  # (all of it faint page-axis lines: the ink as found)
            g = _with_paper(ctx, group)
        kept, hidden = g.mask, None
    return g, kept, hidden, no_core


def _without_faint_lines(ctx: _Context, g: Group, group: Group) -> tuple:
    """The print's box ``g`` with faint page-axis lines divided out of its grey
    (:func:`inkprint.faintlines.without_faint_lines`), read on the paper within
    ``faint_line_reach_mm`` of the print's ink box (``group``), and the ink that
    was ink only for a line's grey (lighter than half contrast without it: the
    bulge where a line crosses the edge, a line's dash touching it) set aside.
    Returns the box (its mask without that ink), its grey and that ink (None: no
    line found)."""
    import cv2

    opts, s = ctx.opts, ctx.scan.mm_per_px
    reach = max(2, round(mm_to_px_length(opts.faint_line_reach_mm, s)))
    # the margin holds the box g at least (its paper for the edge field: wider than
    # faint_line_reach_mm under 35 dpi, or in pixels without a scale)
    grown = (group.rows.start - g.rows.start, group.cols.start - g.cols.start)
    grown += (g.rows.stop - group.rows.stop, g.cols.stop - group.cols.stop)
    big = _padded(group, ctx.page.work.shape, max(reach, *grown))
    grey = _grey(ctx.scan, ctx.page, big.rows, big.cols)
    paper, ink = (float(v) for v in _paper_and_ink(grey, big.mask))
    r, c = group.rows.start - big.rows.start, group.cols.start - big.cols.start
    h, w = group.mask.shape
    half = 0.5 * (paper + ink)
    flat, on_line = without_faint_lines(
        grey,
        (r, r + h, c, c + w),
        line_px=max(1, round(mm_to_px_length(opts.faint_line_mm, s))),
        darker=opts.faint_line_contrast * max(paper - ink, 0.0),
        least=opts.faint_line_least,
    )
    r, c = g.rows.start - big.rows.start, g.cols.start - big.cols.start
    box = (slice(r, r + g.mask.shape[0]), slice(c, c + g.mask.shape[1]))
    grey, on_line = flat[box], on_line[box]
    if not on_line.any():
        return g, grey, None
    # only the outline's pixels: a bulge, a line's stub (the ink inside stays ink
    # whatever the line's grey over it)
    rim = g.mask & ~cv2.erode(g.mask.view(np.uint8), np.ones((3, 3), np.uint8)).view(bool)
    faint = rim & on_line & (grey > half)
    return dataclasses.replace(g, mask=g.mask & ~faint), grey, faint


def _edge_mark_flags(ctx: _Context, g: Group, m, index: int, ink: tuple, flags, warnings):
    """The flags and warnings with ``mark_on_edge`` added when a mark may have moved
    the print's edge beyond ``edge_uncertainty``: the edge hidden under a label
    (:func:`_hidden_excess`), a line as wide as a stroke taken for tread
    (:func:`_reach_beyond_body`), a thin piece alone off its tip set aside
    (:func:`_sliver_excess`), pen-thin ink along its edge left out as a pen's
    (:func:`_thin_excess`), a letter joined to it beside letters set aside
    (:func:`_letters_beside_pull`). ``g``: the padded print; ``ink``: its ink
    measured, the ink under a label (or None), the pen-thin ink left out (or
    None), its tread gap [px] (0: none) and its pieces (:func:`components_with_stats`,
    8-connected)."""
    opts, (kept, hidden, spots_thin, gap, pieces) = ctx.opts, ink
    if "mark_on_edge" in flags:
        return flags, warnings
    angle = m.metrics.orientation
    why = ""
    if (
        hidden is not None
        and (under := _hidden_excess(ctx, g, m.hull_px, hidden, angle)) > opts.edge_uncertainty
    ):
        why = (
            f"a mark set aside (a label's letters, a ruler's tick) touches its edge and "
            f"hides it there: measured without the ink under it, its length, width or "
            f"hull area (counted half) may be up to {100 * under:.1f} % larger; see the "
            f"overlay, remove the mark or rescan"
        )
    elif not g.stacked and (reach := _reach_beyond_body(ctx, kept, angle)) > opts.body_reach:
        why = (
            f"its ink reaches {100 * reach:.0f} % beyond the print's body in length or "
            f"width: a line as wide as a pen stroke (a ruler's edge) taken for tread? See "
            f"the overlay, remove the line or rescan"
        )
    elif (
        sliver := _sliver_excess(ctx, g, kept, m, tread_gap=gap, pieces=pieces)
    ) > opts.edge_uncertainty:
        why = (
            f"thin ink off its tip was set aside as a pen mark, tick or letter; it may be "
            f"a tread element the outline cut to a sliver: with it the length, width or hull area "
            f"(counted half) is {100 * sliver:.1f} % larger. See the overlay"
        )
    elif (comb := _comb_excess(ctx, g, kept, m)) > opts.edge_uncertainty:
        why = (
            f"thin strokes reaching out of both its sides, {COMB_TICKS} or more a side, were "
            f"set aside as pen marks or ticks (a tread's thin bars, a herringbone's arms?): "
            f"with them its "
            f"length, width or hull area (counted half) is {100 * comb:.1f} % larger. See "
            f"the overlay"
        )
    elif (thin := _thin_excess(kept, m, spots_thin, ctx.scan.mm_per_px)) > opts.edge_uncertainty:
        why = (
            f"pen-thin ink along its edge was left out as a pen's strokes or dots (a "
            f"fine tread's elements the outline cut?): with it its length or width is "
            f"{100 * thin:.1f} % larger; see the overlay"
        )
    elif (inner := _inner_line_excess(ctx, g, kept, m)) > opts.edge_uncertainty:
        why = (
            f"a straight line taken out (a ruler?) lies along it, within its width or "
            f"just beside it, not far beyond its tips: a rib of its tread? With it its "
            f"length or width is "
            f"{100 * inner:.1f} % larger; see the overlay"
        )
    elif (
        ctx.found.grid is None  # (on chart paper gridlines' bits read as letters)
        and (beside := _letters_beside_pull(ctx, g, kept, m)) > opts.edge_uncertainty
    ):
        why = (
            f"letters set aside lie beside it and its ink near them is pen-thin: "
            f"without that ink it is {100 * beside:.1f} % shorter or narrower (a letter "
            f"of the label joined to its edge?); see the overlay, remove the label or "
            f"rescan"
        )
    elif (
        ctx.found.grid is None
        and (dark := _dark_letters_pull(ctx, g, kept, m)) > opts.edge_uncertainty
    ):
        why = (
            f"letters set aside lie beside it, a pen's ink darker than the print's, and "
            f"its ink near them is as dark: without that ink it is {100 * dark:.1f} % "
            f"shorter or narrower (a letter of the label joined to its edge?); see the "
            f"overlay, remove the label or rescan"
        )
    if not why:
        return flags, warnings
    return (*flags, "mark_on_edge"), (*warnings, f"print #{index}: {why}")


#: a line set aside is the print's own (a slick centre rib) when it lies within
#: the print's width, runs along at least :data:`INNER_LINE_ALONG` of its length
#: and reaches at most this share of it beyond either tip: a ruler crossing a
#: print runs on beyond it (at 0.25 and without the length, a ruler's edge piece
#: beside a tip passed: 7 good prints of the held-out sets flagged)
INNER_LINE_REACH = 0.2
INNER_LINE_ALONG = 0.5


def _inner_line_excess(ctx: _Context, g: Group, kept: np.ndarray, m) -> float:
    """How much longer or wider the print is with the straight lines set aside
    (marks of kind ``line``) that lie within it or along it: across, within its width
    or ``group_distance_mm`` beyond (a tiny rib print's outer ribs, as long as the
    print and straight, set aside as ruler lines: held-out 2026-11-29 seed 2 sheet
    114, width -60 %, unflagged); along,
    over :data:`INNER_LINE_ALONG` of its length, reaching at most
    :data:`INNER_LINE_REACH` of it beyond its tips. A
    tiny print's slick centre rib, 19 mm long and straight, is taken out as a
    ruler, and its diamonds alone read -2.3 % long (held-out seed 2026 sheet 81,
    unflagged once the print was measured along its own axis; a drawn one whose
    rib runs 2 mm beyond its diamonds, -21 %). The largest relative excess of
    length or width (pixel extents along the print's orientation), 0 when no line
    overlaps its box ``g`` (the padded print; ``kept``: its ink measured)."""
    r0, r1, c0, c1 = g.rows.start, g.rows.stop, g.cols.start, g.cols.stop
    beside = mm_to_px_length(ctx.opts.group_distance_mm, ctx.scan.mm_per_px)
    boxes = [
        mk.bbox
        for mk in ctx.found.marks
        if mk.kind == "line"
        and mk.bbox[0] < r1 + beside
        and mk.bbox[2] > r0 - beside
        and mk.bbox[1] < c1 + beside
        and mk.bbox[3] > c0 - beside
    ]
    if not boxes or not kept.any():
        return 0.0
    angle = m.metrics.orientation
    flip = np.array([1.0, -1.0])
    rot = np.array([[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]])
    hull = (np.asarray(m.hull_px, float)[:, ::-1] * flip) @ rot  # (along, across) [px]
    lo, hi = hull.min(axis=0), hull.max(axis=0)
    reach = INNER_LINE_REACH * (hi[0] - lo[0])
    lo, hi = lo - np.array([reach, 0.5]), hi + np.array([reach, 0.5])
    best = 0.0
    for a, b, c, d in boxes:
        rows, cols = slice(min(a, r0), max(c, r1)), slice(min(b, c0), max(d, c1))
        own = np.zeros((rows.stop - rows.start, cols.stop - cols.start), bool)
        own[r0 - rows.start : r1 - rows.start, c0 - cols.start : c1 - cols.start] = kept
        line = np.zeros(own.shape, bool)
        box = (slice(a - rows.start, c - rows.start), slice(b - cols.start, d - cols.start))
        line[box] = ctx.binarization.mask[a:c, b:d]
        line &= ~own
        px = np.argwhere(line)
        if not len(px):
            continue
        uv = ((px + np.array([rows.start, cols.start]))[:, ::-1] * flip) @ rot
        u0, u1 = uv.min(axis=0), uv.max(axis=0)
        along = u1[0] - u0[0] >= INNER_LINE_ALONG * (hi[0] - lo[0] - 2 * reach)
        # across: within its width, or beside it: its near side within the distance
        # and no wider across than that (a rib along it, not a ruler crossing it)
        inside = u0[1] >= lo[1] and u1[1] <= hi[1]
        near = u1[1] - u0[1] <= beside and (
            -beside <= u0[1] - hi[1] <= beside or -beside <= lo[1] - u1[1] <= beside
        )
        if along and u0[0] >= lo[0] and u1[0] <= hi[0] and (inside or near):
            best = max(best, _mask_excess(own | line, own, angle))
    return best


def _thin_excess(kept: np.ndarray, m, thin: np.ndarray | None, mm_per_px: float) -> float:
    """How much longer or wider (the largest relative excess, along the print's
    orientation and across) the print is with the pen-thin ink beside it that
    :func:`inkprint.group.edge_spots` left out as a pen's strokes or dots
    (``thin``, over ``kept``'s box: its ink measured) [mm / px]: a fine tread
    not found as one (a knurl print on a 300 dpi PDF page, its diamonds the outline
    cut to triangles along its sides: held-out seed 10 sheet 9, width -8.5 %,
    unflagged) loses its outer row so. 0 with fewer than :data:`THIN_ROW` pieces
    of :data:`THIN_ROW_MM2` and :data:`THIN_ROW_PX` or more: a label's letter
    beside a slick tip, cut to bits of a few pixels, is no row of elements. Fewer
    pieces count when two of them, alike in size (:data:`TIP_PAIR_RATIO`), lie off
    either tip (:func:`_tip_pair`): a print is symmetric fore and aft, a label is
    not (held-out 12 sheet 112: a knurl print on chart paper, the diamond the
    outline cut to a triangle at each tip left out, length -6.2 %, unflagged)."""
    if thin is None or not thin.any() or not kept.any():
        return 0.0
    _, lab, st, cen = components_with_stats(thin, connectivity=8)
    least = max(THIN_ROW_PX, area_mm2_to_px(THIN_ROW_MM2, mm_per_px))
    piece = np.r_[False, st[1:, 4] >= least]
    if piece.sum() < THIN_ROW:
        piece = _tip_pair(kept, m, piece, st[:, 4], cen)
        if not piece.any():
            return 0.0
    return _mask_excess(kept | piece[lab], kept, m.metrics.orientation)


#: two pieces off a print's tips are a pair when their areas differ by at most this
TIP_PAIR_RATIO = 2.0


def _tip_pair(kept: np.ndarray, m, piece: np.ndarray, area: np.ndarray, centres) -> np.ndarray:
    """Of the pieces ``piece`` ((n,) bool; their ``area`` [px] and ``centres`` (x, y)
    over ``kept``'s box), those of a pair off either tip of the ink ``kept`` along the
    print's orientation (beyond :data:`TIP_END` of its half-length from its centre,
    one each way), alike in area within :data:`TIP_PAIR_RATIO`; (n,) bool."""
    out = np.zeros(len(piece), bool)
    if np.count_nonzero(piece) < 2:
        return out
    along = _along(m)  # (row, col)
    # (the ink's extremes along any direction lie on its rows' first and last pixels)
    t = outline_points(kept).reshape(-1, 2)[:, ::-1] @ along
    c, half = 0.5 * (t.max() + t.min()), 0.5 * (t.max() - t.min())
    idx = np.flatnonzero(piece)
    u = (centres[idx][:, ::-1] @ along - c) / max(half, 1.0)
    fore, aft = idx[u > TIP_END], idx[u < -TIP_END]
    for i in fore:
        for j in aft:
            if max(area[i], area[j]) <= TIP_PAIR_RATIO * min(area[i], area[j]):
                out[[i, j]] = True
    return out


def _reach_beyond_body(ctx: _Context, ink: np.ndarray, angle: float) -> float:
    """How far the print's ink reaches beyond its body: the largest relative excess
    of its length or width (along ``angle`` [rad] and across) over those of its body,
    the ink closed by a square a stroke wide (grooves, sipes, a file pattern's
    pores) and opened by one 2.5 strokes wide (lines and slivers narrower go);
    0 when the body holds under a fifth of the ink (sparse knobs: nothing to judge
    by) or when no bar at least ``line_length_mm`` long and no wider than 2.5
    strokes lies outside the body's hull (a tapering tip)."""
    import cv2

    stroke = stroke_px(ctx.scan.mm_per_px, ctx.opts)
    ink8 = ink.view(np.uint8) if ink.dtype == bool else ink.astype(np.uint8)
    pad = int(np.ceil(2.5 * stroke)) + 2
    box = cv2.copyMakeBorder(ink8, pad, pad, pad, pad, cv2.BORDER_CONSTANT, value=0)
    body = _stroke_body(box, stroke)
    if cv2.countNonZero(body & box) < 0.2 * cv2.countNonZero(box):
        return 0.0
    # what lies outside the body's hull must hold a straight bar at least
    # line_length_mm long (a tip the opening took is short and tapers: slick and
    # knobby prints reach up to +65 % beyond their bodies so) that is no tread bar
    points = outline_points(body)
    for _ in range(2):
        hull = cv2.fillConvexPoly(np.zeros_like(box), cv2.convexHull(points), 1)
        out = box & (1 - cv2.dilate(hull, np.ones((3, 3), np.uint8)))
        lab, st, ks = _long_thin(out, stroke, ctx)
        if not len(ks):
            return 0.0
        # (a rib judged against the rest of the ink: the body, opened by 2.5
        # strokes, loses a narrow rib print's tapering tips)
        rest = outline_points(box & ~np.isin(lab, ks))
        bars = _bar_tread(lab, st, ks, ctx)
        bars |= _lenses(lab, st, ks, points if rest is None else rest, stroke)
        if bars.all():
            return 0.0
        if not bars.any():
            break
        # the rest judged against the hull of the body and its bars: the short bars
        # at a herringbone's tips, the crescents its outline cut (held-out 14 sheet
        # 21: the bars, then kept with the print, reached 117 % beyond its rib)
        points = np.concatenate([points, outline_points(np.isin(lab, ks[bars]))])
    return _mask_excess(box, body, angle)


def _stroke_body(ink8: np.ndarray, stroke: float) -> np.ndarray:
    """A print's body: its ink (uint8) closed by a square ``stroke`` [px] wide
    (grooves, sipes, a file pattern's pores), then opened by one 2.5 strokes wide
    (lines and slivers narrower go). Squares: separable, a fraction of a disk's cost
    at 300 dpi; a square opening takes a diagonal line up to 1.4 x as wide, a body
    stays a body."""
    import cv2

    body = ink8
    for op, size in ((cv2.MORPH_CLOSE, stroke), (cv2.MORPH_OPEN, 2.5 * stroke)):
        k = max(3, round(size) | 1)
        body = cv2.morphologyEx(body, op, np.ones((k, k), np.uint8))
    return body


def _long_thin(out: np.ndarray, stroke: float, ctx: _Context) -> tuple:
    """The pieces of ``out`` (uint8) at least ``line_length_mm`` long and no wider
    than 2.5 strokes (``stroke`` [px]): the labels, OpenCV's stats and the pieces'
    ids ((k,) int)."""
    import cv2

    n, lab, st, _ = components_with_stats(out, connectivity=8)  # (OpenCV's stats, from the ink)
    bar = mm_to_px_length(ctx.opts.line_length_mm, ctx.scan.mm_per_px)
    diag = np.hypot(st[1:, cv2.CC_STAT_WIDTH], st[1:, cv2.CC_STAT_HEIGHT])
    thin = st[1:, cv2.CC_STAT_AREA] <= 2.5 * stroke * diag
    ks = 1 + np.flatnonzero((diag >= bar) & thin)
    if len(ks):
        # and no wider than that at its widest (twice its inscribed radius): a
        # diagonal bar up to 1.4 x as wide goes in the square opening, a pen line
        # with its ticks is no wider than the line (held-out 12 sheet 93: a
        # herringbone's 3 mm bars, three a side, read as a ruler's edge)
        dt = cv2.distanceTransform(out, cv2.DIST_L2, 3)
        on = lab > 0
        widest = np.zeros(n)
        reduce_at(np.maximum, widest, lab[on], values=dt[on])
        ks = ks[2.0 * widest[ks] <= 2.5 * stroke + 1.0]
    return lab, st, ks


def _lenses(
    lab: np.ndarray, st: np.ndarray, ks: np.ndarray, body: np.ndarray, stroke: float
) -> np.ndarray:
    """Which of the long thin pieces ``ks`` (labels in ``lab``, OpenCV's stats
    ``st``) are outer ribs the outline cut, not a line ((k,) bool), judged against
    the rest of the print (``body``: its outline points, (x, y) [px]) within a
    ``stroke`` [px] (:func:`inkprint.marks._outer_rib`)."""

    from .marks import _outer_rib

    out = np.zeros(len(ks), bool)
    for i, k in enumerate(ks):
        x, y, w, h = st[k, :4]
        out[i] = _outer_rib(lab[y : y + h, x : x + w] == k, (x, y), body, stroke)
    return out


def _bar_tread(lab: np.ndarray, st: np.ndarray, ks: np.ndarray, ctx: _Context) -> np.ndarray:
    """Which of the long thin pieces ``ks`` (labels in ``lab``, OpenCV's stats
    ``st``) are a tread's bars side by side (:func:`inkprint.marks._bar_field`), not
    a line ((k,) bool): a herringbone print's bars off its centre rib reach 3 x
    beyond it; the pieces like them (:func:`inkprint.marks._like_bars`: its last
    bars, farther apart) are too."""
    from .marks import BAR_FIELD_MIN, _bar_field, _comb_teeth, _like_bars, _piece_rects

    if len(ks) < BAR_FIELD_MIN:
        return np.zeros(len(ks), bool)
    rects, corners = _piece_rects(lab, st, ks)
    px = ctx.scan.mm_per_px
    field = _bar_field(rects, corners, px)
    # (a comb's teeth, :func:`inkprint.marks._comb_teeth`: a car print's shoulder
    # bars 7 widths apart; all pieces of this one print, their body measured apart,
    # so one owner and no share of its ink to test)
    comb = _comb_teeth(rects, corners, (np.zeros(len(ks), int), np.zeros(len(ks))), px)
    return field | _like_bars(rects, corners, field) | comb


def _under_text(ctx: _Context, g: Group, kept: np.ndarray) -> np.ndarray | None:
    """The print's ink under the letters of a label touching it ((h, w) bool over the
    padded box ``g``; None when there is none): within ``mark_near_px``, and half a
    stroke (a marker's bold letter: a stroke), of the box of a text mark set aside
    (a letter, a tick). Its edge there is hidden: a letter's bar lying along the
    edge joins the print through the
    anti-aliased row between them and reads as its edge (mixed set 5006 file 24 at
    300 dpi: an 'E''s bottom bar 1.5 px out of a slick print's edge at its widest
    point, width +1.14 %, unflagged). Measured without it, the hull spans the notch:
    over a few mm of a smooth side it loses only the sagitta."""
    opts, s = ctx.opts, ctx.scan.mm_per_px
    r0, c0 = g.rows.start, g.cols.start
    h, w = kept.shape
    zone = None
    for mk in ctx.found.marks:
        if mk.kind != "text":
            continue
        # a pen letter's foot joined to the edge lies within half a stroke of its
        # box; a marker letter's within a stroke (a '1''s serif). A stroke for
        # every letter joined a pen label's boxes into one notch, whose tangents
        # bound the edge under it loosely (5007 file 6 flagged at 1.2 %)
        k = 1.0 if mk.reason == BOLD_REASON else 0.5
        near = max(opts.mark_near_px, round(k * stroke_px(s, opts)))
        a, b = max(mk.bbox[0] - r0 - near, 0), max(mk.bbox[1] - c0 - near, 0)
        c, d = min(mk.bbox[2] - r0 + near, h), min(mk.bbox[3] - c0 + near, w)
        if a >= c or b >= d:
            continue
        if zone is None:
            zone = np.zeros(kept.shape, bool)
        zone[a:c, b:d] = True
    if zone is None:
        return None
    zone &= kept
    if not zone.any() or not (kept & ~zone).any():
        return None
    return zone


def _hidden_excess(ctx: _Context, g: Group, hull_px: np.ndarray, hidden, angle: float) -> float:
    """How much larger the print may be with its edge under a label
    (:func:`_under_text`, over the padded box ``g``): the largest relative growth
    of its length or width (along ``angle`` [rad] and across), or half that of its
    hull area, when each edge of its outline ``hull_px`` (the sub-pixel hull, sheet
    (row, col)) spanning hidden ink gives way to the band over it, a stroke and two
    pixels deep (as far as a letter's foot hides the edge), cut by the visible
    outline's tangents on either side (its chords to the hull vertices a stroke
    farther on: the outline is convex). On the sub-pixel hull: on the pixels'
    staircase a tangent over a stroke tilts by a pixel, and the bound at a slick
    print's widest point read 1-2 % where the edge moves by a fraction of a pixel."""
    import cv2

    t = stroke_px(ctx.scan.mm_per_px, ctx.opts) + 2
    h = np.asarray(hull_px, float) - [g.rows.start, g.cols.start]  # (row, col) in g
    n = len(h)
    if n < 4:
        return 0.0
    zone = cv2.dilate(hidden.view(np.uint8), np.ones((3, 3), np.uint8)).view(bool)
    rows, cols = zone.shape
    centre = h.mean(axis=0)
    spans = np.zeros(n, bool)  # hull edge i (vertex i to i + 1) spans hidden ink
    for i in range(n):
        a, b = h[i], h[(i + 1) % n]
        length = float(np.hypot(*(b - a)))
        if length < 1.0:
            continue
        f = np.linspace(0.0, 1.0, max(3, int(length)))[:, None]
        on = np.round(a + f * (b - a)).astype(int)
        inside = (on[:, 0] >= 0) & (on[:, 0] < rows) & (on[:, 1] >= 0) & (on[:, 1] < cols)
        spans[i] = zone[on[inside, 0], on[inside, 1]].any()
    if spans.all():
        return 0.0  # (no visible outline to bound it by)
    extra = []
    # such edges in line are one stretch, bounded by the tangents beyond its ends: a
    # label across a round print's widest point left its hull a flat bottom of two
    # edges in line, and each edge's tangent on the other side was the other edge
    # itself, which cut the band to nothing (held-out seed 5 sheet 81: bound
    # 0.06 %, width -1.6 % with status ok). Edges at an angle keep their own
    # tangents (a stretch over a curved side bounded by its ends' was loose:
    # label sweep, 9 prints within the bar flagged; 7 with IN_LINE)
    d = np.roll(h, -1, axis=0) - h
    d /= np.maximum(np.hypot(d[:, 0], d[:, 1]), 1e-9)[:, None]
    nxt = np.roll(d, -1, axis=0)
    sine = np.abs(d[:, 0] * nxt[:, 1] - d[:, 1] * nxt[:, 0])
    in_line = spans & np.roll(spans, -1) & (sine < IN_LINE)
    starts = np.flatnonzero(spans & ~np.roll(in_line, 1))
    for s0 in starts:
        e0 = s0
        while in_line[e0] and (e0 + 1) % n != s0:
            e0 = (e0 + 1) % n
        e1 = (e0 + 1) % n
        a, b = h[s0], h[e1]
        length = float(np.hypot(*(b - a)))
        if length < 1.0:
            continue
        w0 = _vertex_beyond(h, s0, -1, t)
        w1 = _vertex_beyond(h, e1, 1, t)
        nrm = np.array([b[1] - a[1], a[0] - b[0]]) / length  # across the chord ...
        if (centre - a) @ nrm > 0:
            nrm = -nrm  # ... outward
        # the band over the stretch, at most t out, within the tangents on either
        # side (on a straight stretch they run along it: nearly nothing is added)
        band = [a, b, b + t * nrm, a + t * nrm]
        for p, q in ((h[w0], a), (b, h[w1])):
            band = _clip(band, p, q, centre)
        extra += band
    if not extra:
        return 0.0
    # (x = col, y = row)
    return _hull_excess(h[:, ::-1], np.concatenate([h, np.array(extra)])[:, ::-1], angle)


#: two hull edges are in line when the sine of the angle between them is under this
#: (:func:`_hidden_excess`; 6 degrees: a turned round print's hull across a label
#: bends by a few degrees at the vertex between two letters, held-out seed 2 sheet
#: 81, width -1.8 %, unflagged at 0.02)
IN_LINE = 0.1


def _vertex_beyond(h: np.ndarray, v: int, step: int, t: float) -> int:
    """The first vertex of the closed polygon ``h`` at least ``t`` from vertex ``v``
    going ``step`` (-1, 1) along it (``v`` itself when there is none)."""
    n, w = len(h), (v + step) % len(h)
    while np.hypot(*(h[w] - h[v])) < t and w != v:
        w = (w + step) % n
    return w


def _clip(poly: list, p: np.ndarray, q: np.ndarray, inner: np.ndarray) -> list:
    """The convex polygon ``poly`` (points) cut by the line through ``p`` and ``q``,
    keeping the side of ``inner``."""
    d = q - p
    length = float(np.hypot(*d))
    if length < 1e-9:
        return poly
    side = np.sign(d[0] * (inner[1] - p[1]) - d[1] * (inner[0] - p[0])) or 1.0

    def dist(x):  # signed distance from the line, positive on the inner side
        return side * (d[0] * (x[1] - p[1]) - d[1] * (x[0] - p[0])) / length

    out = []
    for i, x in enumerate(poly):
        y = poly[(i + 1) % len(poly)]
        dx, dy = dist(x), dist(y)
        if dx >= 0:
            out.append(x)
        if (dx >= 0) != (dy >= 0):
            out.append(x + (y - x) * dx / (dx - dy))
    return out


def _sliver_excess(
    ctx: _Context, g: Group, kept: np.ndarray, m, *, tread_gap: float = 0.0, pieces=None
) -> float:
    """How much larger the print is with the thin pieces off its tip that were set
    aside (marks of kind ``sliver``, :mod:`inkprint.marks`: a sliver of a tip block
    or a pen mark, which cannot be told apart beside a print without a block
    pattern; and pen marks or ticks reaching out of it off a tip, :func:`_off_a_tip`:
    a herringbone's last arms the outline cut to crescents, two of them, so not
    alone: held-out seeds 8, 10, 11, six prints -1.1 to -2.1 % long, unflagged; and
    a block's cut piece set aside as writing off a tip of a block print,
    :func:`_tip_pieces`, within ``tread_gap`` [px] steps):
    the largest relative excess of length, width or half the hull area
    over ``m`` (0 when none lies within ``group_distance_mm`` of the print's box
    ``g``, its ink ``kept``), measured in the box holding them too."""
    s, opts = ctx.scan.mm_per_px, ctx.opts
    near = max(mm_to_px_length(opts.group_distance_mm, s), TIP_PIECE_GAPS * tread_gap)
    r0, r1, c0, c1 = g.rows.start, g.rows.stop, g.cols.start, g.cols.stop
    around = [
        mk
        for mk in ctx.found.marks
        if mk.bbox[0] < r1 + near
        and mk.bbox[2] > r0 - near
        and mk.bbox[1] < c1 + near
        and mk.bbox[3] > c0 - near
    ]
    marks = [
        mk
        for mk in around
        if mk.kind == "sliver" or (mk.kind == "text" and mk.reason.startswith(TICK_REASON))
    ]
    ticks = [
        mk.bbox
        for mk in marks
        if mk.kind == "text" and _off_a_tip(mk.bbox, m) and _across(mk.bbox, m)
    ]
    boxes = [mk.bbox for mk in marks if mk.kind == "sliver"] + _mirrored_pairs(ticks, m)
    boxes += _tip_pieces(ctx, g, kept, m, tread_gap, pieces)
    return _excess_in_boxes(ctx, g, kept, m, boxes)


def _excess_in_boxes(ctx: _Context, g: Group, kept: np.ndarray, m, boxes: list) -> float:
    """How much larger the print ``m`` is (:func:`_excess_with`) with the ink set
    aside in ``boxes`` ((r0, c0, r1, c1) [px] on the sheet) measured with it, in a
    box holding them and the print's ``g`` (its ink ``kept``); 0 with no such ink."""
    if not boxes:
        return 0.0
    s, opts = ctx.scan.mm_per_px, ctx.opts
    r0, r1, c0, c1 = g.rows.start, g.rows.stop, g.cols.start, g.cols.stop
    pad = 2 + round(mm_to_px_length(opts.edge_window_mm, s))
    h, w = ctx.page.work.shape
    rows = slice(
        max(min([r0] + [b[0] - pad for b in boxes]), 0),
        min(max([r1] + [b[2] + pad for b in boxes]), h),
    )
    cols = slice(
        max(min([c0] + [b[1] - pad for b in boxes]), 0),
        min(max([c1] + [b[3] + pad for b in boxes]), w),
    )
    own = np.zeros((rows.stop - rows.start, cols.stop - cols.start), bool)
    own[r0 - rows.start : r1 - rows.start, c0 - cols.start : c1 - cols.start] = kept
    extra = np.zeros(own.shape, bool)
    for a, b, c, d in boxes:
        extra[max(a - rows.start, 0) : c - rows.start, max(b - cols.start, 0) : d - cols.start] = (
            True
        )
    ink = ctx.binarization.mask[rows, cols]
    extra &= ink & ~own
    if not extra.any():
        return 0.0
    grey = _grey(ctx.scan, ctx.page, rows, cols)
    both = own | extra
    fld = edge_field(grey, both, mm_per_px=s, options=opts, local=_local_range(grey, s, opts))
    fld = _paper_where_set_apart(fld, ink & ~both, both)
    return _excess_with(ctx, both, (rows.start, cols.start), fld, m)


#: a print with at least this many pen marks or ticks reaching out of it set aside
#: (``inkprint.marks.TICK_REASON``) on each side of its axis, under no ruler's
#: scale, is looked at as a comb: a tread's thin bars (:func:`_comb_excess`; a
#: label's strokes, a ruler's ticks lie on one side, or a few on the other: 4 good
#: prints of held-out 6 seeds 1 and 5 had 2-4 on one side and 0-2 on the other)
COMB_TICKS = 4
#: ... along at least this share of its length on each side, at a regular pitch (the
#: 80th percentile of their gaps along it at most COMB_PITCH x the 20th): a label's
#: strokes lie in a cluster (independent set seed 2 file 92: ten beside a file
#: print, 4 and 6 a side, over a third of its length, a first version flagged it)
COMB_SPAN = 0.5
COMB_PITCH = 2.0


def _comb_excess(ctx: _Context, g: Group, kept: np.ndarray, m) -> float:
    """How much larger the print is with the pen marks or ticks reaching out of it
    that were set aside (:data:`COMB_TICKS` or more on each side of its axis, along
    :data:`COMB_SPAN` of its length at a regular pitch, :data:`COMB_PITCH`, their
    boxes within ``group_distance_mm`` of its box ``g``, their centres under no
    ruler's scale; ``kept``: its ink): a herringbone print at 200 dpi whose V's
    thin arms, 14 along each side, were set aside as ticks (held-out 6 seed 3 sheet
    116: width -51 % with status ok). 0 with fewer."""
    s = ctx.scan.mm_per_px
    near = mm_to_px_length(ctx.opts.group_distance_mm, s)
    r0, r1, c0, c1 = g.rows.start, g.rows.stop, g.cols.start, g.cols.stop
    boxes = [
        mk.bbox
        for mk in ctx.found.marks
        if mk.kind == "text"
        and mk.reason.startswith(TICK_REASON)
        and mk.bbox[0] < r1 + near
        and mk.bbox[2] > r0 - near
        and mk.bbox[1] < c1 + near
        and mk.bbox[3] > c0 - near
    ]
    if len(boxes) < 2 * COMB_TICKS:
        return 0.0
    if ctx.found.scales:
        boxes = [
            b
            for b in boxes
            if not _under_a_scale(
                Group(slice(b[0], b[2]), slice(b[1], b[3]), None), ctx.found.scales, s
            )
        ]
    if len(boxes) < 2 * COMB_TICKS:
        return 0.0
    b = np.asarray(boxes, float)
    axis = _along(m)  # (row, col)
    at = 0.5 * (b[:, :2] + b[:, 2:]) - m.hull_px.mean(axis=0)
    across, along = at @ np.array([axis[1], -axis[0]]), at @ axis
    length = float(np.ptp(m.hull_px @ axis))
    for side in (across > 0, across < 0):
        t = np.sort(along[side])
        if len(t) < COMB_TICKS or np.ptp(t) < COMB_SPAN * length:
            return 0.0
        lo, hi = np.percentile(np.diff(t), [20, 80])
        if hi > COMB_PITCH * max(lo, 1.0):
            return 0.0
    return _excess_in_boxes(ctx, g, kept, m, boxes)


#: a piece set aside as writing off a block print's tip within this many of its tread
#: gaps of the outline, or within its blocks' size, is looked at as a block the
#: outline cut (:func:`_tip_pieces`)
TIP_PIECE_GAPS = 2.0
#: ... when it lies this close to the print's axis (a share of its half-width)
TIP_PIECE_AXIS = 0.5


def _tip_pieces(
    ctx: _Context, g: Group, kept: np.ndarray, m, tread_gap: float, pieces=None
) -> list:
    """Boxes (r0, c0, r1, c1) [px] of the marks set aside as writing (one piece,
    kind ``text``, not a tick, not under a ruler's scale) off a tip of a print with a
    block pattern (``g``: its padded box; at least ``CAP_ELEMENTS`` pieces of
    ``kept``, its ink there, labelled in ``pieces`` or here; its tread gap
    ``tread_gap`` [px] > 0), near its axis (within :data:`TIP_PIECE_AXIS` of its
    half-width), solid (a block cut by a smooth outline fills its hull to
    ``CAP_SOLID``, a letter's bends do not), smaller than half its median piece and
    within :data:`TIP_PIECE_GAPS` tread gaps of its outline or its blocks' size
    (the median longer side of its larger pieces; the next row's block begins a
    row's gap out, wider than the tread gap between neighbours): a block of the next row
    the outline cut, alone (:func:`_alone`: no letter of a word), which
    :func:`inkprint.caps.cut_caps` takes only on a tread
    that is a lattice (held-out 6 seed 5 sheet 10: a knob print's rows bent along
    an arc, its tip block cut to a 2 x 0.6 mm sliver 3.8 mm off the last row, set
    aside; length -5.2 % with status ok)."""
    import cv2

    if tread_gap <= 0:
        return []
    n, _, st, _ = pieces or components_with_stats(kept.view(np.uint8), connectivity=8)
    if n - 1 < CAP_ELEMENTS:
        return []
    median = float(np.median(st[1:, 4]))
    big = st[1:, 4] >= 0.5 * st[1:, 4].max()
    reach = max(
        TIP_PIECE_GAPS * tread_gap, float(np.median(np.maximum(st[1:, 2], st[1:, 3])[big]))
    )
    hull = np.asarray(m.hull_px, np.float32)[:, ::-1].copy()  # (x, y) = (col, row)
    axis = _along(m)  # (row, col)
    centre = m.hull_px.mean(axis=0)
    half = 0.5 * _extents(m.hull_px[:, ::-1] * np.array([1.0, -1.0]), m.metrics.orientation)[1]
    least = area_mm2_to_px(ctx.opts.speck_area_mm2, ctx.scan.mm_per_px)
    r0, r1, c0, c1 = g.rows.start, g.rows.stop, g.cols.start, g.cols.stop
    out = []
    for mk in ctx.found.marks:
        b = mk.bbox
        if mk.kind != "text" or mk.reason.startswith(TICK_REASON):
            continue
        if not (
            b[0] < r1 + reach and b[2] > r0 - reach and b[1] < c1 + reach and b[3] > c0 - reach
        ):
            continue
        if not _off_a_tip(b, m) or not _alone(b, ctx.found.marks):
            continue
        at = np.array([(b[0] + b[2]) / 2, (b[1] + b[3]) / 2])
        off = at - centre
        if abs(off @ np.array([axis[1], -axis[0]])) > TIP_PIECE_AXIS * half:
            continue
        if -cv2.pointPolygonTest(hull, (float(at[1]), float(at[0])), True) > reach:
            continue
        piece = ctx.binarization.mask[b[0] : b[2], b[1] : b[3]]
        k = int(np.count_nonzero(piece))
        if not least < k < CAP_SHARE * median:
            continue
        ys, xs = np.nonzero(piece)
        if hull_fill(k, cv2.convexHull(np.column_stack([xs, ys]).astype(np.int32))) < CAP_SOLID:
            continue
        if _under_a_scale(
            Group(slice(b[0], b[2]), slice(b[1], b[3]), piece),
            ctx.found.scales,
            ctx.scan.mm_per_px,
        ):
            continue
        out.append(b)
    return out


#: a mark is alone when no other mark but dust lies within this many times its box's
#: longer side of it (a label's letters lie within a letter of the next)
ALONE_SIDES = 2.0


def _alone(bbox, marks: list) -> bool:
    """Whether a mark's box (r0, c0, r1, c1) [px] has no other mark but dust within
    :data:`ALONE_SIDES` of its longer side: not a letter of a word (a label written
    against a print's tip, its letters near the axis: three good prints of
    held-out 6 seeds 1 and 7 flagged by :func:`_tip_pieces` without this)."""
    r = ALONE_SIDES * max(bbox[2] - bbox[0], bbox[3] - bbox[1])
    return not any(
        mk.kind != "dust"
        and tuple(mk.bbox) != tuple(bbox)
        and mk.bbox[0] < bbox[2] + r
        and mk.bbox[2] > bbox[0] - r
        and mk.bbox[1] < bbox[3] + r
        and mk.bbox[3] > bbox[1] - r
        for mk in marks
    )


def _off_a_tip(bbox, m) -> bool:
    """Whether a mark's box (r0, c0, r1, c1) [px] lies off a tip of the print measured
    ``m`` (its centre beyond :data:`TIP_END` of the hull's half-length from its
    centre along the print's orientation), not beside it."""
    at = np.array([[(bbox[0] + bbox[2]) / 2, (bbox[1] + bbox[3]) / 2]])
    return bool(_at_the_ends(m.hull_px, at, end=TIP_END, axis=_along(m))[0])


def _along(m) -> np.ndarray:
    """The unit vector (row, col) of the orientation of the print measured ``m``
    (rows run down)."""
    angle = float(m.metrics.orientation)
    return np.array([-math.sin(angle), math.cos(angle)])


#: a mark lies off a print's tip beyond this fraction of its half-length
TIP_END = 0.8


def _across(bbox, m) -> bool:
    """Whether a mark's box (r0, c0, r1, c1) [px] spans at least 1.5 x more across
    the print's orientation than along it: a piece of tread along the outline at a
    tip, not a tick or ruler mark along the print nor an upright letter."""
    angle = float(m.metrics.orientation)
    h, w = bbox[2] - bbox[0], bbox[3] - bbox[1]
    c, s = abs(math.cos(angle)), abs(math.sin(angle))
    return w * s + h * c >= 1.5 * (w * c + h * s)


def _mirrored_pairs(boxes: list, m) -> list:
    """Of mark boxes (r0, c0, r1, c1) [px], those with a partner of like size whose
    centre mirrors theirs about the print's rolling axis (the line along its
    orientation through its hull's centre) within the larger box's size: the cut
    ends of a tread element's two arms (a herringbone's V at its tip). A pen tick
    marking a tip, a ruler's tick or a label's stroke rarely has such a partner
    (flagging every pen mark off a tip flagged 14 good prints of the held-out sets
    for 3; pairs alone, 3 - ruler ticks, gridline bits and letters, each longer
    along the print than across it: :func:`_across`)."""
    if len(boxes) < 2:
        return []
    axis = _along(m)
    normal = np.array([axis[1], -axis[0]])
    centre = m.hull_px.mean(axis=0)
    b = np.asarray(boxes, float)
    at = 0.5 * (b[:, :2] + b[:, 2:]) - centre  # (n, 2) (row, col)
    size = np.max(b[:, 2:] - b[:, :2], axis=1)  # (n,)
    mirrored = at - 2.0 * np.outer(at @ normal, normal)
    far = np.hypot(*(mirrored[:, None, :] - at[None, :, :]).transpose(2, 0, 1))  # (n, n)
    alike = np.maximum(size[:, None], size[None, :]) <= 1.5 * np.minimum(
        size[:, None], size[None, :]
    )
    pair = (far <= np.maximum(size[:, None], size[None, :])) & alike
    np.fill_diagonal(pair, False)
    return [boxes[i] for i in np.flatnonzero(pair.any(axis=1))]


def _faint_excess(ctx: _Context, g: Group, spots, m, *, grey, local, aside, kept) -> float:
    """How much larger the print is with its block-sized faint edge spots
    (``spots.faint_blocks``, left out by the section 7.1.1 rule as not load-bearing):
    the largest relative excess of length, width or half the hull area over ``m``
    (0 when there are none). Measured along ``m``'s direction, the rest set apart as for
    ``m`` (``kept``: its ink, without the ink under a label)."""
    if spots.faint_blocks is None:
        return 0.0
    s, opts = ctx.scan.mm_per_px, ctx.opts
    # (a ruler's ticks beside the edge are no faint blocks of the print)
    ink = _without_scale(ctx, g, kept | spots.faint_blocks)
    fld = edge_field(grey, ink, mm_per_px=s, options=opts, local=local)
    fld = _paper_where_set_apart(fld, (g.mask & ~ink) | aside, ink)
    return _excess_with(ctx, ink, (g.rows.start, g.cols.start), fld, m)


def _excess_with(ctx: _Context, ink: np.ndarray, at: tuple, fld: np.ndarray, m) -> float:
    """How much larger the print ``m`` is measured as ``ink`` (a crop at ``at`` =
    (row, col) with its edge field ``fld``), along ``m``'s direction: the largest
    relative excess of length, width or hull area, the hull area counted half as for
    ``edge_uncertainty`` (its bar is twice as wide)."""
    with_it = measure_mask(
        ink,
        at[0],
        at[1],
        n_rows=ctx.page.work.shape[0],
        mm_per_px=ctx.scan.mm_per_px,
        field=fld,
        axis=m.metrics.orientation,
        stations=(0.0,),
    ).metrics
    weights = {"length": 1.0, "width": 1.0, "hull_area": 0.5}
    return max(
        wt * (getattr(with_it, k) / getattr(m.metrics, k) - 1.0) for k, wt in weights.items()
    )


def _paper_where_set_apart(fld: np.ndarray, apart: np.ndarray, ink: np.ndarray) -> np.ndarray:
    """The edge field with the ink set apart (edge spots, pen-thin pieces sticking
    out) and its one-pixel rim read as paper: the outline's iso-line may run one
    pixel outside the kept ink and would follow a tick's or a speck's grey there."""
    import cv2

    if not np.any(apart):
        return fld
    rim = cv2.dilate(apart.view(np.uint8), np.ones((3, 3), np.uint8)).view(bool) & ~ink
    return np.where(rim, np.maximum(fld, np.float32(0.5)), fld)


def _grid_in(grid: Gridlines | None, rows: slice, cols: slice) -> np.ndarray | bool:
    """The gridline ink taken out in a box (False without gridlines)."""
    return False if grid is None else grid.removed[rows, cols]


def _in_box(g: Group, box: Group) -> np.ndarray:
    """``g``'s ink in ``box``'s box ((h, w) bool of ``box.mask``'s shape)."""
    out = np.zeros(box.mask.shape, bool)
    r0, r1 = max(g.rows.start, box.rows.start), min(g.rows.stop, box.rows.stop)
    c0, c1 = max(g.cols.start, box.cols.start), min(g.cols.stop, box.cols.stop)
    if r0 < r1 and c0 < c1:
        out[
            r0 - box.rows.start : r1 - box.rows.start, c0 - box.cols.start : c1 - box.cols.start
        ] = g.mask[r0 - g.rows.start : r1 - g.rows.start, c0 - g.cols.start : c1 - g.cols.start]
    return out


def _padded(g: Group, shape, pad: int) -> Group:
    """The group with its box grown by ``pad`` pixels (within the sheet)."""
    h, w = shape
    r0, r1 = max(g.rows.start - pad, 0), min(g.rows.stop + pad, h)
    c0, c1 = max(g.cols.start - pad, 0), min(g.cols.stop + pad, w)
    mask = np.zeros((r1 - r0, c1 - c0), bool)
    mask[g.rows.start - r0 : g.rows.stop - r0, g.cols.start - c0 : g.cols.stop - c0] = g.mask
    return dataclasses.replace(g, rows=slice(r0, r1), cols=slice(c0, c1), mask=mask)


def _axis_flags(
    m: MaskMeasurement, index: int, flags: list, warnings: list, *, opts: AnalysisOptions
) -> tuple[list, list]:
    """Flag ``axis_misaligned``: the print measured along the given axis (not snapped
    to its own, :func:`rolling_angle`) while it is turned on the sheet: farther than
    ``axis_misaligned_deg`` (its own axis confirmed by the principal axis), or by an
    angle its two estimates (the minimum-area rectangle's, the principal axis') do
    not agree on but both put within ``axis_misaligned_deg`` and on the same side,
    beyond :data:`AXIS_AGREE_DEG` (the smaller turn tested); flagged when the given
    axis then reads longer or wider by more than ``axis_misaligned_excess`` (4 x
    that when the print is nearly round: its own axis is not defined). The
    unconfirmed turn was left unflagged before: knobby prints turned 7-8 degrees on
    held-out 2026 read 3-10 % wide with status ok. (One estimate alone is not
    trusted: a knob pattern taped square has its rectangle at -26 degrees and its
    principal axis at -4.) A snapped print (``m.snapped``) is measured along itself
    and not flagged: the snap is decided once, in :func:`measure_mask` (it was
    decided again here, from the outline's solidity rather than the pixels', and
    near :data:`SNAP_SOLIDITY` the two could disagree: a print neither snapped nor
    flagged)."""
    if m.snapped:
        return flags, warnings
    metrics, hull_px = m.metrics, m.hull_px
    aspect = max(metrics.aspect_ratio, 1.0 / max(metrics.aspect_ratio, 1e-9))
    given = float(metrics.orientation)
    deg, most = opts.axis_misaligned_deg, opts.axis_misaligned_excess
    turn, excess = own_axis(hull_px, given)
    if _principal_agrees(hull_px, given, turn):
        how = ""
    else:
        # either estimate within the tolerance may be the print's own axis: the
        # larger excess is what the given axis may read too large (before, only
        # two estimates on the same side counted, and the smaller turn: held-out
        # seed 8 sheets 57, 76, 99, turned 2-7 deg, read up to +1.6 % with status ok)
        cands = [
            t for t in (turn, _principal_turn(hull_px, given)) if AXIS_AGREE_DEG < abs(t) <= deg
        ]
        # and the tread's faint tracks where the outline gave no axis (_tread_axis):
        # turned, a candidate; square to the given axis, they confirm it (held-out
        # set 2 file 96: three knob prints taped within 0.3 deg, tracks 0.0-0.4 deg,
        # rectangle and moments -6..+5 deg: flagged, each within 0.3 %)
        if m.tracks_deg is not None and abs(m.tracks_deg) <= AXIS_AGREE_DEG:
            return flags, warnings
        if m.tracks_deg is not None and abs(m.tracks_deg) <= deg:
            cands.append(m.tracks_deg)
        if not cands:
            return flags, warnings
        xy = _sheet_xy(hull_px)
        excess, turn = max((_turn_excess(xy, given, t), t) for t in cands)
        how = " (its own axis is uncertain)"
    if excess > most and (aspect > opts.axis_uncertain_aspect or excess > ROUND_EXCESS * most):
        flags.append("axis_misaligned")
        warnings.append(
            f"print #{index} is turned {turn:+.1f} deg from the given rolling axis{how}: "
            f"its length and width along that axis read up to {100 * excess:.1f} % too "
            f"large; use --rolling-axis auto or square the print on the sheet"
        )
    return flags, warnings


def _line_flags(
    ctx: _Context, g: Group, m, index: int, *, padded: Group, kept, hidden
) -> tuple[list, list]:
    """``mark_on_edge`` (flags and warnings, lists) for a line taken out beside the
    print (splitting it, along its edge, its band beside the edge), or a mark set
    aside covering more than ``edge_mark_mm`` of its outline where no text mark hides
    its edge (``hidden``: the ink under a label, :func:`_under_text`)."""
    flags, warnings = [], []
    contact = px_to_mm_length(g.edge_marks, ctx.scan.mm_per_px)
    along = px_to_mm_length(g.line_along, ctx.scan.mm_per_px)
    other = _split_by_line(ctx, g)
    if other >= 0:
        flags.append("mark_on_edge")
        warnings.append(
            f"print #{index}: a straight line taken out (a ruler) runs between it and "
            f"the ink next to it (print #{other}): one print split by the line? Its "
            f"outline is uncertain; see the overlay, remove the line or rescan"
        )
    elif along >= ctx.opts.line_length_mm:
        flags.append("mark_on_edge")
        warnings.append(
            f"print #{index}: a straight line taken out runs along {along:.1f} mm of its "
            f"edge (a ruler splitting a print?): the outline there is uncertain; see the "
            f"overlay, remove the line or rescan"
        )
    elif (
        # (with the ink under a label: a ruler's ticks set aside as text notch the
        # outline next to the line, whose band then seemed to widen it, 5006 file 48)
        excess := _edge_uncertainty(
            ctx, padded, kept if hidden is None else kept | hidden, m.metrics.orientation
        )
    ) > ctx.opts.edge_uncertainty:
        flags.append("mark_on_edge")
        warnings.append(
            f"print #{index}: a line taken out (a gridline, a ruler) runs along its edge: "
            f"the edge there lies somewhere under the line, so its length, width or hull "
            f"area may be {100 * excess:.1f} % larger (area counted half); see the "
            f"overlay or rescan on plain paper"
        )
    elif contact > ctx.opts.edge_mark_mm and hidden is None:
        # (with the ink under a label measured out, the edge there is bounded by the
        # outline's tangents either side: _hidden_excess; a marker's letters along
        # 13 mm of a slick print's outline, its width within 0.5 %, were flagged)
        flags.append("mark_on_edge")
        warnings.append(
            f"print #{index}: a mark set aside covers {contact:.1f} mm of its outline (a "
            f"line along its edge, a label's strokes): the outline there is uncertain by up "
            f"to the mark's width; see the overlay, remove the mark or rescan"
        )
    return flags, warnings


def _letters_inside(marks: list, hull_px: np.ndarray) -> float:
    """The largest share of a letter's box (a mark of text or writing set aside)
    inside a print's outline ``hull_px`` ((k, 2) sheet (row, col) [px]): an outline
    running across a label's letter may hold the label's other letters, taken for
    tread blocks (:func:`_letters_pull`)."""
    import cv2

    if hull_px is None or len(hull_px) < 3:
        return 0.0
    lo, hi = hull_px.min(axis=0), hull_px.max(axis=0)
    best = 0.0
    for mk in marks:
        if mk.kind not in ("text", "writing"):
            continue
        r0, c0, r1, c1 = mk.bbox
        if r1 <= lo[0] or r0 >= hi[0] or c1 <= lo[1] or c0 >= hi[1]:
            continue
        box = np.zeros((r1 - r0, c1 - c0), np.uint8)
        pts = np.round((hull_px - [r0, c0])[:, ::-1] * 16).astype(np.int32)
        cv2.fillConvexPoly(box, pts, 1, cv2.LINE_8, 4)
        best = max(best, float(box.mean()))
    return best


#: a ruler's scale whose pitch reads farther than this from every ruler's pitch
#: (:func:`inkprint.ruler.scale_error`) flags the sheet ``scale_mismatch``: 2 %, not
#: the bar's 1 %: a photographed page's ruler read 1.1 % long (150 dpi, 25 ticks,
#: standard error 0.06 %) while its prints measured within 0.1 % (held-out 6 seed 3
#: sheet 81); a wrong dpi is off by far more (72, 96 for 300; 300 for 400: 25 %)
SCALE_MISMATCH = 0.02


def _scale_check(scan: Scan, scales: tuple) -> tuple:
    """``("scale_mismatch", warning)`` when a ruler's scale on the sheet reads its
    ticks' pitch more than :data:`SCALE_MISMATCH` off every ruler's pitch (beyond
    three standard errors of its fit): the file's
    scale (its dpi, or the one given) is wrong by as much, and so is every length on
    the sheet (a 300 dpi scan saved as 400 dpi reads 25 % short); else ``()``. The
    ticks' pitch is fitted over the whole scale, good to 0.05 % on the held-out rulers."""
    if scan.scale_source == "pixels" or not scales:
        return ()
    from .coords import RULER_PITCHES_MM
    from .ruler import scale_error

    worst = max(scales, key=scale_error)
    err = scale_error(worst)
    if err <= SCALE_MISMATCH:
        return ()
    dpi = mm_per_px_to_dpi(scan.mm_per_px)
    names = ("a millimetre ruler", "1/16 inch", "1/10 inch")
    fixes = ", ".join(
        f"{n}: --dpi {dpi * worst.pitch_mm / q:.0f}"
        for n, q in zip(names, RULER_PITCHES_MM, strict=True)
    )
    return (
        "scale_mismatch",
        f"a ruler on the sheet reads its ticks {worst.pitch_mm:.3f} mm apart at this "
        f"scale ({dpi:.0f} dpi, {scan.scale_source}), {100 * err:.1f} % off the nearest "
        f"ruler's pitch: every length here is off as much. The scale the ruler "
        f"gives ({fixes})",
    )


def _under_a_scale(g: Group, scales: tuple, mm_per_px: float) -> bool:
    """Whether the centre of a group's box lies under a ruler's scale
    (:func:`inkprint.ruler.scale_band`)."""
    import cv2

    centre = (0.5 * (g.cols.start + g.cols.stop), 0.5 * (g.rows.start + g.rows.stop))
    return any(
        cv2.pointPolygonTest(scale_band(sc, mm_per_px=mm_per_px).astype(np.float32), centre, False)
        >= 0
        for sc in scales
    )


def _scale_thin(ctx: _Context, g: Group, kept: np.ndarray) -> tuple:
    """``(under, less)``: where rulers' scales cross a print's box (their strips,
    :func:`inkprint.ruler.scale_band`, each run on across the print its ticks end
    beside) and its ink ``kept`` without the pen-thin ink there (what an opening
    with a stroke-wide disk removes: ticks, numbers, a tick's end beside the edge;
    the print's body and blocks stay); ``(None, None)`` when no strip meets its
    ink. ``g``: the print's padded box, ``kept`` its ink over it."""
    import cv2

    pts = outline_points(kept)
    origin = np.array([g.cols.start, g.rows.start], float)
    edge = None if pts is None else pts.reshape(-1, 2).astype(float) + origin
    under = _scale_strips(ctx, g, ink=edge)
    if not (under & kept).any():
        return None, None
    k = max(3, round(stroke_px(ctx.scan.mm_per_px, ctx.opts)) | 1)
    disk = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (k, k))
    body = cv2.morphologyEx(kept.view(np.uint8), cv2.MORPH_OPEN, disk).view(bool)
    return under, (kept & ~under) | (body & under)


def _without_scale(ctx: _Context, g: Group, kept: np.ndarray) -> np.ndarray:
    """A print's ink ``kept`` without a ruler's ticks, edge line and numbers that
    stick out of it where the ruler's scale crosses its outline (``kept`` itself
    when there are none, or when not all that sticks out is the scale's own).

    Under the scale's strip (:func:`_scale_thin`) the pen-thin ink on the scale's
    own places (:func:`inkprint.ruler.on_scale`: its ticks' places, hidden in the
    print's ink too, from the ticks found beside it; its edge line; its numbers)
    beyond the hull of the rest of the ink is the ruler's: it is taken off (ruler
    ink inside the outline moves nothing and stays; a tick the blur joined to the
    edge is the print's body to the opening and stays too). When pen-thin ink off
    the scale's places sticks out of the body's hull (a tread's sliver cut thin by
    the outline, a scale drawn off its found places) nothing is taken off and
    :func:`_ruler_pull` judges and flags as before. A ruler across a car print, its
    ticks beside the tread's side: width +1.6 %, flagged; a siped print's tip and
    side under a ruler, +6.2 % and +7.0 %, flagged (held-out 6 seed 3 sheets 30 and
    61): measured +0.0 %, +0.1 % and +0.4 % without the ruler's ink that sticks
    out."""
    if not ctx.found.scales:
        return kept
    under, less = _scale_thin(ctx, g, kept)
    if under is None:
        return kept
    rows, cols = np.nonzero(kept & under & ~less)
    pts = np.column_stack([cols + g.cols.start, rows + g.rows.start]).astype(float)
    own = np.zeros(len(pts), bool)
    for sc in ctx.found.scales:
        own |= on_scale(sc, pts, mm_per_px=ctx.scan.mm_per_px)
    scale = np.zeros(kept.shape, bool)
    scale[rows[own], cols[own]] = True
    rest = kept & ~scale
    if not _outlined(rest):
        return kept
    out = scale & ~_hull_rim(rest)
    # (pen-thin ink off the scale's places beyond the body's hull: not the ruler's?)
    if not out.any() or (less.any() and (kept & ~less & ~scale & ~_hull_rim(less)).any()):
        return kept
    return kept & ~out


def _hull_rim(ink: np.ndarray) -> np.ndarray:
    """The ink's convex hull filled, with a pixel's rim (the outline runs through
    the hull's edge pixels)."""
    import cv2

    hull = np.zeros(ink.shape, np.uint8)
    cv2.fillConvexPoly(hull, cv2.convexHull(outline_points(ink)).astype(np.int32), 1)
    return cv2.dilate(hull, np.ones((3, 3), np.uint8)).view(bool)


def _ruler_pull(ctx: _Context, g: Group, kept: np.ndarray, m) -> float:
    """How much a ruler's scale crossing the print's outline (its ticks and numbers,
    :func:`inkprint.ruler.scale_band`) may have pulled it out: how much longer or
    wider (along its orientation and across), or half how much larger in hull area,
    its ink is than without the pen-thin ink under the scale (what an opening with a
    stroke-wide disk removes there: ticks, numbers, a tick's end beside the edge;
    the print's body and blocks stay). The ink under the scale is an upper bound of
    the print there, the rest a lower one (held-out 6 seed 2 sheet 5: ticks beside a
    knob print's last row, length +1.7 %; seed 1 sheet 117: a tick's end beside a
    solid print's edge, width +1.8 %; both status ok before). ``g``: the print's
    padded box, ``kept`` its ink over it."""
    under, less = _scale_thin(ctx, g, kept)
    if under is None:
        return 0.0
    angle = m.metrics.orientation
    if not less.any():
        return 1.0
    pull = _with_excess(less, kept, angle)
    if ctx.rolling_axis in ("x", "y"):
        # (and along the axis given: ticks beside both sides can turn the print's own
        # axis, which a given axis snaps to, by degrees: a 110 x 30 mm slick print
        # read 4 % wide along the sheet, 0.5 % of it the ticks' along its own axis)
        given = 0.0 if ctx.rolling_axis == "x" else math.pi / 2
        pull = max(pull, _with_excess(less, kept, given))
    if m.metrics.solidity >= SNAP_SOLIDITY:
        # a solid print's edge is smooth: its outline under the scale beyond a
        # parabola through the outline either side (a number's stroke lying along the
        # edge, as wide as the opening: held-out 6 seed 1 sheet 117, width +1.8 %)
        pull = max(pull, _bump_pull(less, under, angle, 1.0, ctx.opts.edge_bump_px))
    return pull


def _letters_pull(marks: list, g: Group, kept: np.ndarray, m) -> float:
    """How much shorter or narrower (the largest relative excess, along the print's
    orientation and across) the print is without its pieces as large as letters
    beside the letters set aside that its outline runs across (more than
    :data:`LETTER_INSIDE` and less than :data:`LETTER_WITHIN` of a letter's box
    inside its hull ``m.hull_px``, :func:`_letters_inside`): pieces no larger than
    two letters with half their ink or more within a letter's size of such a
    letter's box, then of such a piece, :data:`LETTER_STEPS` times along (a word's
    next letters). A marker's label
    written against a knobby print came out half set aside as letters, half taken
    for tread blocks (held-out 6 sheet 34: '434 N', '43' set aside, width +23 %,
    unflagged); a ruler's numbers over a print's middle, or a tick beside its edge,
    leave its outline where it is. A thin piece touching the print set aside as a
    pen mark or tick (:data:`inkprint.marks.TICK_REASON`) is no seed: a ruler's
    ticks on the outline where it crosses a knobby print at its widest (own
    generator, fresh seed 6011 file 52: width -4.9 % without the blocks beside
    them), a tread block the outline cut to a sliver (a bundled scan, tire08 6.9
    bar 304 N: length -37 % without the blocks beside it), each flagged though
    measured as before. A letter inside the outline only because its neighbours
    are taken for the print's (at most :data:`LETTER_INSIDE` of its box inside the
    hull of the print's pieces larger than two letters, :func:`_body_hull`) is a
    seed too:
    held-out 6 seed 5 sheet 86, '51 kg' 3.8 mm off a car print's shoulder, 'k' set
    aside and '51', 'g' joined, width +22 % with status ok. ``g``: the print's
    padded box, ``kept`` its ink measured over it."""
    letters = [
        (mk, _letters_inside([mk], m.hull_px))
        for mk in marks
        if mk.kind in ("text", "writing") and not mk.reason.startswith(TICK_REASON)
    ]
    boxes = [mk.bbox for mk, share in letters if LETTER_INSIDE < share < LETTER_WITHIN]
    held = [mk for mk, share in letters if share >= LETTER_WITHIN]
    if held:  # (inside the outline only by the letters beside it, taken for the print's)
        body = _body_hull(
            g, kept, max(max(r1 - r0, c1 - c0) for r0, c0, r1, c1 in (mk.bbox for mk in held))
        )
        if body is not None:
            boxes += [mk.bbox for mk in held if _letters_inside([mk], body) <= LETTER_INSIDE]
    if not boxes:
        return 0.0
    size = max(max(r1 - r0, c1 - c0) for r0, c0, r1, c1 in boxes)  # a letter's [px]
    zone = np.zeros(kept.shape, bool)

    def near(r0, c0, r1, c1):  # (box over g's, grown by a letter's size)
        zone[max(r0 - size, 0) : max(r1 + size, 0), max(c0 - size, 0) : max(c1 + size, 0)] = True

    for r0, c0, r1, c1 in boxes:
        near(r0 - g.rows.start, c0 - g.cols.start, r1 - g.rows.start, c1 - g.cols.start)
    n, lab, st, _ = components_with_stats(kept, connectivity=8)
    small = np.maximum(st[:, 2], st[:, 3]) <= 2 * size
    small[0] = False
    drop = np.zeros(n, bool)
    pull = 0.0
    for _ in range(LETTER_STEPS):
        new = small & ~drop & (2 * np.bincount(lab[zone & kept], minlength=n) >= st[:, 4])
        if not new.any():
            break
        drop |= new
        rest = kept & ~drop[lab]
        if rest.any():
            pull = max(pull, _mask_excess(kept, rest, m.metrics.orientation))
        for x, y, w, h in st[np.flatnonzero(new), :4]:
            near(y, x, y + h, x + w)
    return pull


def _body_hull(g: Group, kept: np.ndarray, size: int) -> np.ndarray | None:
    """The hull ((k, 2) sheet (row, col) [px]) of a print's pieces larger than two
    letters (``size`` [px], a letter's box's longer side; :func:`_letters_pull`'s
    letters are the smaller ones), or None without such pieces."""
    import cv2

    _, lab, st, _ = components_with_stats(kept, connectivity=8)
    large = np.maximum(st[:, 2], st[:, 3]) > 2 * size
    large[0] = False
    if not large.any():
        return None
    hull = cv2.convexHull(outline_points(large[lab])).reshape(-1, 2)[:, ::-1]
    return hull + np.array([g.rows.start, g.cols.start], float)


#: pieces of a line of writing under this share of the median piece's ink are an
#: 'i''s dot or a full stop (:func:`_writing_pull`)
WRITING_DOTS = 0.3


def _writing_pull(g: Group, kept: np.ndarray, m, mm_per_px: float, pieces=None) -> float:
    """How much shorter or narrower (the largest relative excess, along the print's
    orientation and across) the print is without a line of writing joined to it:
    its pieces lying off its largest piece (at most :data:`LETTER_INSIDE` of their
    ink inside that piece's hull) that make a line of bold writing alone
    (:func:`inkprint.group.text_line`: one row of letter-sized pieces, of letters'
    sizes or with bowls; its dots, :data:`WRITING_DOTS`, left out of the row). A bold label set against a slick print's edge joins it
    whole, no letter set aside (held-out 6 seed 6 sheet 6, 'Maxxis Ardent 3.5bar'
    on chart paper: length +101 % with status ok). A tread's pieces around a block
    are no single row. ``g``: the print's padded box, ``kept`` its ink over it,
    ``pieces`` its pieces (:func:`components_with_stats`, 8-connected; None:
    labelled here)."""
    import cv2

    n, lab, st, _ = pieces or components_with_stats(kept, connectivity=8)
    if n - 2 < TEXT_LINE_MIN:
        return 0.0
    area = st[:, cv2.CC_STAT_AREA].astype(float)
    area[0] = 0.0
    body = int(np.argmax(area))
    hull = np.zeros(kept.shape, np.uint8)
    cv2.fillConvexPoly(hull, cv2.convexHull(outline_points(lab == body)), 1)
    inside = np.bincount(lab[hull.view(bool)], minlength=n)
    off = inside <= LETTER_INSIDE * area
    off[[0, body]] = False
    if np.count_nonzero(off) < TEXT_LINE_MIN:
        return 0.0
    # (an 'i''s dot, a full stop: over or under a letter along the row, left out)
    letters = off & (area >= WRITING_DOTS * np.median(area[off]))
    if not text_line(dataclasses.replace(g, mask=letters[lab]), mm_per_px=mm_per_px):
        return 0.0
    return _mask_excess(kept, kept & ~off[lab], m.metrics.orientation)


def _letters_beside_pull(ctx: _Context, g: Group, kept: np.ndarray, m) -> float:
    """How much shorter or narrower (the largest relative excess, along the print's
    orientation and across) the print is without its pen-thin ink near letters set
    aside beside it.

    Letters: marks of text or writing within :data:`LETTERS_BESIDE_MM` of its ink,
    shorter than ``line_length_mm`` and at most :data:`LETTER_ASPECT` times longer
    than wide (a ruler's stubs and ticks are no letters: held-out 7 sheet 93, a
    knurl print's tip beside a ruler's 9 mm stub, flagged at 1.1 %); near them:
    within a letter's size (their median box) of their boxes. Pen-thin: what lies
    outside the print's body (its ink closed by a square a stroke wide, then
    opened by one 2.5 strokes wide: grooves close, tread blocks stay), and its
    pieces apart that an opening :data:`THIN_PIECE` strokes wide takes whole (a
    letter's stroke joined to the print as a part of it; not for a fine tread,
    whose elements are that thin: held-out 7 sheet 93, a knurl print's tip beside
    a ruler's stub). A label written against a
    print's tip has a letter joined to it, its neighbours set aside (held-out 9
    sheets 15, 21, 33: 'p=4.5', '#20 7.5', 'p=3.8' over the tips, length +2.4 %,
    +3.6 %, +3.3 %, unflagged); a label beside the print leaves its body where it
    is. ``g``: the print's padded box, ``kept`` its ink measured over it."""
    import cv2

    mm_per_px = ctx.scan.mm_per_px
    zone, size = _letters_zone(_letters_beside(ctx, g, kept), kept.shape)
    if zone is None or not (zone & kept).any():
        return 0.0
    stroke = stroke_px(mm_per_px, ctx.opts)
    ink8 = kept.view(np.uint8) if kept.dtype == bool else kept.astype(np.uint8)
    thin = kept & ~_stroke_body(ink8, stroke).view(bool) & zone
    if g.fine_area_mm2 <= 0:  # (a fine tread's elements are pen-thin pieces apart)
        k = max(3, round(THIN_PIECE * stroke) | 1)
        stays = cv2.morphologyEx(ink8, cv2.MORPH_OPEN, np.ones((k, k), np.uint8)).view(bool)
        n, lab, st, _ = components_with_stats(kept, connectivity=8)
        held = np.bincount(lab[stays], minlength=n) > 0
        thin_piece = ~held & (np.maximum(st[:, 2], st[:, 3]) <= 2 * size)
        thin_piece &= np.bincount(lab[zone & kept], minlength=n) > 0  # (whole: a letter)
        thin_piece[0] = False
        thin |= thin_piece[lab]
    if not thin.any():
        return 0.0
    rest = kept & ~thin
    if not rest.any():
        return 0.0
    return _mask_excess(kept, rest, m.metrics.orientation)


def _letters_beside(
    ctx: _Context, g: Group, kept: np.ndarray, kinds=("text", "writing"), *, own=False
) -> list:
    """The boxes (r0, c0, r1, c1) over ``g``'s box [px] of the letters set aside
    beside a print (``kept``: its ink measured over ``g``'s box): marks of
    ``kinds`` (text or writing) within :data:`LETTERS_BESIDE_MM` of its ink (with
    ``own``: or within their own size, the next letter's place), shorter than
    ``line_length_mm`` and at most :data:`LETTER_ASPECT` times longer than wide."""
    mm_per_px = ctx.scan.mm_per_px
    near = mm_to_px_length(LETTERS_BESIDE_MM, mm_per_px)
    longest = mm_to_px_length(ctx.opts.line_length_mm, mm_per_px)
    r0, c0 = g.rows.start, g.cols.start
    h, w = kept.shape
    boxes = []
    for mk in ctx.found.marks:
        a, b, c, d = mk.bbox
        long_side, short_side = max(c - a, d - b), max(min(c - a, d - b), 1)
        if mk.kind not in kinds or long_side >= longest:
            continue
        if long_side > LETTER_ASPECT * short_side:  # a ruler's stub or tick, no letter
            continue
        a, b, c, d = a - r0, b - c0, c - r0, d - c0
        beside = max(near, long_side) if own else near
        lo = (max(int(a - beside), 0), max(int(b - beside), 0))
        hi = (min(int(np.ceil(c + beside)), h), min(int(np.ceil(d + beside)), w))
        if hi[0] > lo[0] and hi[1] > lo[1] and kept[lo[0] : hi[0], lo[1] : hi[1]].any():
            boxes.append((a, b, c, d))
    return boxes


def _letters_zone(boxes: list, shape) -> tuple:
    """Within a letter's size (the boxes' median) of the letters' ``boxes``: (h, w)
    bool over ``shape`` and that size [px]; (None, 0) without letters."""
    if not boxes:
        return None, 0
    size = int(np.median([max(c - a, d - b) for a, b, c, d in boxes]))  # a letter's [px]
    zone = np.zeros(shape, bool)
    for a, b, c, d in boxes:
        zone[max(a - size, 0) : max(c + size, 0), max(b - size, 0) : max(d + size, 0)] = True
    return zone, size


#: a label's ink is a pen's, not the print's, when the median grey of the letters
#: set aside beside a print lies below the darkest :data:`PEN_PRINT_PERCENTILE` %
#: of the print's ink by this share of the print's contrast (paper - ink median)
PEN_DARKER = 0.05
PEN_PRINT_PERCENTILE = 2.0


def _dark_letters_pull(ctx: _Context, g: Group, kept: np.ndarray, m) -> float:
    """How much shorter or narrower (the largest relative excess, along the print's
    orientation and across) the print is without its ink near letters set aside
    beside it (:func:`_letters_beside`, :func:`_letters_zone`) that is as dark as
    they are, when they are a pen's: darker than the print's darkest ink
    (:data:`PEN_DARKER`, :data:`PEN_PRINT_PERCENTILE`). A marker's letter joined
    to a print's tip is a piece of the print's ink (neither pen-thin nor apart) but
    a pen's darkness (held-out 12 sheet 75: 'p' joined to a herringbone print's
    tip, its '=2' set aside, length +3.1 %; held-out 2026 sheet 61, +2.2 %; both
    unflagged). 0 when the letters are no darker: their ink cannot be told from
    the print's (a pen as dark as the print, or lighter, left to the other rules).
    ``g``: the print's padded box, ``kept`` its ink measured over it."""
    import cv2

    # (a label's piece alone beside the prints is a fragment: '=' of 'F=640N')
    # (a letter's size from the print: the letter joined to it was one)
    boxes = _letters_beside(ctx, g, kept, ("text", "writing", "fragment"), own=True)
    zone, _ = _letters_zone(boxes, kept.shape)
    if zone is None or not (zone & kept).any():
        return 0.0
    grey = _grey(ctx.scan, ctx.page, g.rows, g.cols)
    ink = ctx.binarization.mask[g.rows, g.cols]
    H, W = ctx.binarization.mask.shape
    pen = []  # the letters' ink, each in its whole box on the sheet
    for a, b, c, d in boxes:
        rows = slice(max(a + g.rows.start, 0), min(c + g.rows.start, H))
        cols = slice(max(b + g.cols.start, 0), min(d + g.cols.start, W))
        pen.append(_grey(ctx.scan, ctx.page, rows, cols)[ctx.binarization.mask[rows, cols]])
    pen = np.concatenate(pen)
    if len(pen) < THIN_ROW_PX or not (kept & ~zone).any():
        return 0.0
    letters = float(np.median(pen))
    own = grey[kept & ~zone]
    paper = float(np.median(grey[~ink])) if (~ink).any() else 1.0
    darkest = float(np.percentile(own, PEN_PRINT_PERCENTILE))
    if darkest - letters < PEN_DARKER * (paper - float(np.median(own))):
        return 0.0
    dark = (kept & zone & (grey < 0.5 * (letters + darkest))).view(np.uint8)
    dark = cv2.morphologyEx(dark, cv2.MORPH_OPEN, np.ones((2, 2), np.uint8))
    # with the blurred rim of the strokes, lighter than their core (2 px)
    dark = cv2.dilate(dark, np.ones((5, 5), np.uint8)).view(bool) & kept & zone
    rest = kept & ~dark
    if not dark.any() or not rest.any():
        return 0.0
    return _mask_excess(kept, rest, m.metrics.orientation)


def _print_flags(
    ctx: _Context,
    g: Group,
    m,
    index: int,
    margin: tuple,
    *,
    padded: Group,
    kept: np.ndarray,
    hidden: np.ndarray | None = None,
    faint: np.ndarray | None = None,
    pieces: tuple | None = None,
) -> tuple[tuple, tuple]:
    flags, warnings = _line_flags(ctx, g, m, index, padded=padded, kept=kept, hidden=hidden)
    pull = 0.0
    if "mark_on_edge" not in flags:
        pull = _mark_pull(ctx, padded, kept, m.metrics.orientation, hidden=hidden, faint=faint)
    if pull > ctx.opts.mark_pull:
        flags.append("mark_on_edge")
        warnings.append(
            f"print #{index}: a mark set aside (a label, a line, a ruler's tick along the "
            f"edge) touches its edge: without the ink next to the mark or bulging out of "
            f"the outline near it, it is up to {100 * pull:.1f} % shorter or narrower; "
            f"see the overlay, remove the mark or rescan"
        )
    if "mark_on_edge" not in flags:
        _label_flags(ctx, padded, kept, m, index, flags, warnings, pieces=pieces)
    rpull = 0.0
    if ctx.found.scales and "mark_on_edge" not in flags:
        rpull = _ruler_pull(ctx, padded, kept, m)
    if rpull > ctx.opts.edge_uncertainty:
        flags.append("mark_on_edge")
        warnings.append(
            f"print #{index}: a ruler's scale (its ticks and numbers) crosses its outline: "
            f"without the ink under the scale it is {100 * rpull:.1f} % shorter or narrower "
            f"(or half as much smaller); move the ruler off the print or rescan"
        )
    spread = _spread_marks_over(ctx.found.marks, g)
    if spread and "mark_on_edge" not in flags:
        flags.append("mark_on_edge")
        warnings.append(
            f"print #{index} lies in {spread} set aside over the sheet (faint gridlines or "
            f"a texture): where it joins the print's edge the outline is uncertain; see "
            f"the overlay or rescan on plain paper"
        )
    if ctx.found.grid is not None and "mark_on_edge" not in flags:
        hull = m.metrics.hull_area
        if g.aside_mm2 > ctx.opts.grid_aside_share * hull:
            flags.append("mark_on_edge")
            warnings.append(
                f"print #{index}: {g.aside_mm2:.1f} mm^2 of pen-thin ink set aside touches "
                f"its edge on chart paper (tread slivers a gridline joined?): its outline "
                f"there is uncertain; see the overlay or rescan on plain paper"
            )
    for flag, why in _grouped_or_cut(ctx, g, index, margin):
        flags.append(flag)
        warnings.append(why)
    if ctx.rolling_axis != "auto":
        flags, warnings = _axis_flags(m, index, flags, warnings, opts=ctx.opts)
    elif m.metrics.aspect_ratio < ctx.opts.axis_uncertain_aspect:
        flags.append("axis_uncertain")
        warnings.append(
            f"print #{index} is nearly as wide as long ({m.metrics.aspect_ratio:.2f}): the "
            f"rolling direction was taken as its longer axis (auto); give --rolling-axis x|y"
        )
    if ctx.rolling_axis == "auto":
        flags, warnings = _auto_axis_flags(m, index, flags, warnings, opts=ctx.opts)
    return tuple(flags), tuple(warnings)


def _label_flags(
    ctx: _Context, padded: Group, kept, m, index: int, flags, warnings, *, pieces=None
):
    """Append ``mark_on_edge`` with its warning to ``flags``, ``warnings`` when a
    label's letters are taken for the print's: its outline runs across a letter
    set aside (:func:`_letters_pull`), or a line of writing joins it whole
    (:func:`_writing_pull`), either making it more than ``edge_uncertainty``
    larger. ``padded``: the print's padded box, ``kept`` its ink over it, ``pieces``
    its pieces (:func:`components_with_stats`, 8-connected; None: labelled here)."""
    # (on chart paper gridlines' bits read as letters: the grid's rules judge there)
    lpull = _letters_pull(ctx.found.marks, padded, kept, m) if ctx.found.grid is None else 0.0
    if lpull > ctx.opts.edge_uncertainty:
        flags.append("mark_on_edge")
        warnings.append(
            f"print #{index}: its outline runs across a letter set aside: without the "
            f"pieces beside it, as large as letters, it is {100 * lpull:.1f} % shorter "
            f"or narrower (letters of the same label taken for tread blocks?); see the "
            f"overlay, remove the label or rescan"
        )
        return
    wpull = _writing_pull(padded, kept, m, ctx.scan.mm_per_px, pieces)
    if wpull > ctx.opts.edge_uncertainty:
        flags.append("mark_on_edge")
        warnings.append(
            f"print #{index}: a line of writing joins its edge: without it the print is "
            f"{100 * wpull:.1f} % shorter or narrower (a label set against it?); see the "
            f"overlay, remove the label or rescan"
        )
        return
    off = off_lattice(kept, pieces=pieces) if padded.fine_area_mm2 <= 0 else None
    opull = (
        _with_excess(kept & ~off, off, m.metrics.orientation)
        if off is not None and off.any()
        else 0.0
    )
    if opull > ctx.opts.edge_uncertainty:
        flags.append("mark_on_edge")
        warnings.append(
            f"print #{index}: pieces at its edge lie off its tread's lattice: without them "
            f"it is {100 * opull:.1f} % shorter or narrower (a label's letters or a mark "
            f"taken for tread elements?); see the overlay, remove the mark or rescan"
        )
        return
    pale = _paler_at_edge(_grey(ctx.scan, ctx.page, padded.rows, padded.cols), kept, pieces)
    ppull = _with_excess(kept & ~pale, pale, m.metrics.orientation) if pale.any() else 0.0
    if ppull > ctx.opts.edge_uncertainty:
        flags.append("mark_on_edge")
        warnings.append(
            f"print #{index}: pieces at its edge are inked paler than the print: without "
            f"them it is {100 * ppull:.1f} % shorter or narrower (a label in another pen "
            f"taken for the print's?); see the overlay, remove the label or rescan"
        )


#: a piece on a print's outline whose ink (its pixels off its own edge) is on average
#: paler than this share of the print's is another pen's (:func:`_paler_at_edge`)
PALER_SHARE = 0.75
#: ... judged when it has at least this many such pixels
PALER_LEAST_PX = 20
#: ... the print's ink as the share of its pixels on pieces this pale or paler
PALER_END = 0.2


def _paler_at_edge(grey: np.ndarray, kept: np.ndarray, pieces: tuple | None = None) -> np.ndarray:
    """The pieces of a print's ink on its outline inked paler than the print.

    A label in a coloured pen or pencil reads paler than the print's ink in a grey
    scan; its letters joined to the print as elements went unflagged (held-out 6 seed
    7 sheet 2: '19' of a blue 'run 19' on a car print's shoulder, +10 % wide; seed 8
    sheet 59: a red '25 psi' beside a knobby print, +21 % long, both status ok). Each
    piece (8-connected) touching the ink's hull is compared by its mean darkness
    (:func:`_darkness`) over its pixels a pixel in from its edge (the scan's blur
    pales a thin stroke's edge, not its middle) with the print's paler end: the
    piece means under which :data:`PALER_END` of the ink lies (a label's few
    letters are not a fifth of a print's ink).

    Parameters
    ----------
    grey : (h, w) float [0, 1]
        The sheet's grey over the print's box (:func:`_grey`).
    kept : (h, w) bool
        The print's load-bearing ink.
    pieces : tuple, optional
        ``kept``'s 8-connected pieces (:func:`components_with_stats`), when the
        caller has them.

    Returns
    -------
    (h, w) bool
        The paler pieces on the outline.
    """
    import cv2

    out = np.zeros(kept.shape, bool)
    n, lab, _, _ = pieces or components_with_stats(kept.view(np.uint8), connectivity=8)
    if n <= 2:
        return out
    edge = pieces_on_outline(kept, lab, n)
    core = cv2.erode(kept.view(np.uint8), np.ones((3, 3), np.uint8)).view(bool)
    ids = lab[core]
    dark = _darkness(grey, kept)[core]
    count = np.bincount(ids, minlength=n)
    total = np.bincount(ids, dark, minlength=n)
    mean = total / np.maximum(count, 1)
    # the print's paler end: the pieces' mean darkness that PALER_END of its ink
    # (its pixels off the pieces' edges) lies under (an unevenly inked print's
    # blocks range from black to mid-grey: own generator seed 6012 sheet 88, a
    # knob print's paler tip knobs against its mean, flagged, within the bar)
    order = np.argsort(mean[1:]) + 1
    share = np.cumsum(count[order]) / max(count[1:].sum(), 1)
    ref = mean[order[min(np.searchsorted(share, PALER_END), len(order) - 1)]]
    paler = edge & (count >= PALER_LEAST_PX) & (mean < PALER_SHARE * ref)
    if paler.any():
        out = paler[lab]
    return out


def _auto_axis_flags(
    m: MaskMeasurement, index: int, flags: list, warnings: list, *, opts: AnalysisOptions
) -> tuple[list, list]:
    """Flag ``axis_ambiguous`` for a print measured along its principal axis (auto)
    whose minimum-area rectangle lies turned from it by more than
    :data:`AXIS_AGREE_DEG`, so that length or width along the rectangle's axis
    differ by more than ``axis_misaligned_excess``: a knob pattern's second moments
    tilt by degrees (held-out seed 8 sheet 64: a knobby print square to the sheet,
    principal axis -8.7 deg, width -6.8 % with status ok). A nearly round print
    (also ``axis_uncertain``, advisory) is flagged over :data:`ROUND_EXCESS` x that."""
    given = float(m.metrics.orientation)
    turn, excess = own_axis(m.hull_px, given)
    aspect = max(m.metrics.aspect_ratio, 1.0 / max(m.metrics.aspect_ratio, 1e-9))
    most = opts.axis_misaligned_excess * (
        ROUND_EXCESS if aspect < opts.axis_uncertain_aspect else 1.0
    )
    if abs(turn) > AXIS_AGREE_DEG and excess > most:
        # a lens's minimum-area rectangle can lie on its diagonal (near square, a
        # few % smaller than the one along it); its least width does not: the
        # principal axis agreeing with that is no ambiguity (held-out 6 seed 2:
        # 5 lens and tiny prints turned 40-45 deg on the sheet, flagged although
        # within 0.1 % along their axis)
        xy = _sheet_xy(m.hull_px)
        caliper = _min_width_turn(xy, given)
        if abs(caliper) <= AXIS_AGREE_DEG or _turn_excess(xy, given, caliper) <= most:
            return flags, warnings
        flags.append("axis_ambiguous")
        warnings.append(
            f"print #{index}: its principal axis, taken as the rolling direction (auto), "
            f"and its bounding rectangle's axis differ by {abs(turn):.1f} deg: its length "
            f"or width along one reads {100 * excess:.1f} % larger than along the other; "
            f"give --rolling-axis x|y"
        )
    return flags, warnings


def _grouped_or_cut(ctx: _Context, g: Group, index: int, margin: tuple) -> list:
    """``(flag, warning)`` for a grouping near the footprint rule's limit and for a
    print the image's edge may cut."""
    out = []
    if g.doubt_gap_mm > 0:
        out.append(("grouping_uncertain", _grouping_warning(g, index, ctx.opts.group_mm)))
    cut = clipped(g, ctx.page.work.shape, ctx.page.sheet, margin_px=margin)
    if cut:
        out.append(("clipped", f"print #{index} {cut}"))
    return out


def _grouping_warning(g: Group, index: int, group_mm: float | None) -> str:
    """What a side-by-side grouping near the rule's limit means, and its fix (or,
    ``group_mm`` given, what it kept apart that the rule would join)."""
    gap = g.doubt_gap_mm
    if group_mm is not None:
        return (
            f"print #{index}: ink beside it lies {gap:.1f} mm away, alongside it as a "
            f"footprint's ribs lie: --group-mm {group_mm:g} keeps it apart as another "
            f"print; if they are one print (a car tire's ribs), give --group-mm over "
            f"{gap:.1f} (mm)"
        )
    if g.doubt_joined:
        return (
            f"print #{index}: parts of it lie side by side {gap:.1f} mm apart, near the "
            f"limit between one footprint's grooves and two prints: taken as one print "
            f"(a car tire's ribs); if they are two prints, give --group-mm under "
            f"{gap:.1f} (mm)"
        )
    return (
        f"print #{index}: ink beside it lies {gap:.1f} mm away, near the limit between "
        f"one footprint's grooves and two prints: taken as another print; if they are "
        f"one print (a car tire's ribs), give --group-mm over {gap:.1f} (mm)"
    )


def _split_by_line(ctx: _Context, g: Group) -> int:
    """Index of another print whose box lies within ``group_distance_mm`` of this
    one's, both touched by a straight line taken out along their edges (a ruler
    crossing a block tread can leave its halves apart), else -1."""
    if g.line_along <= 0:
        return -1
    reach = mm_to_px_length(ctx.opts.group_distance_mm, ctx.scan.mm_per_px)
    for j, o in enumerate(ctx.found.groups):
        if o.line_along <= 0 or (o.rows, o.cols) == (g.rows, g.cols):
            continue
        apart_r = max(o.rows.start - g.rows.stop, g.rows.start - o.rows.stop)
        apart_c = max(o.cols.start - g.cols.stop, g.cols.start - o.cols.stop)
        if max(apart_r, apart_c) <= reach:
            return j
    return -1


def _edge_uncertainty(ctx: _Context, g: Group, kept: np.ndarray, angle: float) -> float:
    """The largest relative growth of a print's length or width (along ``angle``
    [rad] and across), or half that of its hull area, with the ink of the lines
    taken out along its edge added (gridlines, rulers): the edge lies somewhere
    under the line, between the ink measured and the line's far side. A line
    crossing the edge leaves it visible on both sides and adds nothing; one
    grazing a print's tip or widest side adds up to its width. ``g`` is the
    print's padded box, ``kept`` its ink measured."""
    import cv2

    grid, lines = ctx.found.grid, ctx.found.sorted.grazed
    if grid is None and lines is None:
        return 0.0
    s = ctx.scan.mm_per_px
    t = stroke_px(s, ctx.opts) + 2  # room for a line's band beside the ink
    big = _padded(dataclasses.replace(g, mask=kept), ctx.page.work.shape, t)
    own = big.mask
    band = np.zeros(own.shape, bool)
    if grid is not None:
        grazed = grid.grazed(own, big.rows.start, big.cols.start, mm_per_px=s, options=ctx.opts)
        if _dark_beside(ctx.page.work[big.rows, big.cols], own, grazed, t, grid.dark_below):
            # ink that dark under the line shows: only the edge's last, partly
            # covered pixel can hide there (the row next to the ink)
            ring = cv2.dilate(own.view(np.uint8), np.ones((3, 3), np.uint8)).view(bool)
            grazed &= ring
        band |= grazed
    if lines is not None:
        near = cv2.dilate(own.view(np.uint8), np.ones((2 * t + 1, 2 * t + 1), np.uint8))
        band |= lines[big.rows, big.cols] & near.view(bool)
    if not band.any():
        return 0.0
    own_pts = outline_points(own)
    band = _tangent_bound(own_pts, band, t)
    less, more = (p.reshape(-1, 2).astype(float) for p in (own_pts, outline_points(own | band)))
    return _hull_excess(less, more, angle)


def _tangent_bound(own_pts: np.ndarray, band: np.ndarray, t: int) -> np.ndarray:
    """The pixels of a line's ``band`` that can hold the print's edge hidden under it
    (``own_pts``: the print's ink's :func:`inkprint.group.outline_points` in the
    band's box),
    where the line crosses the edge: the print's outline is convex, so the stretch
    hidden between two visible hull vertices lies inside the lines through each of
    them and a hull vertex at least ``t`` [px] farther along the visible outline
    (the chords' extensions, half a pixel of slack). Only where the line crosses the
    edge: a piece of band no longer than ``2 t``, or a hull edge no longer than
    ``4 t`` (along a long graze the vertices beside it may be no vertices of the
    whole print, a tip block hidden under the line: the band stays whole). A ruler
    crossing a slick print's widest point at 50 degrees bounded its width +5.3 %;
    the edge under it can move it by a fraction of a pixel."""
    import cv2

    hull = cv2.convexHull(own_pts).reshape(-1, 2).astype(float)  # (x, y)
    n = len(hull)
    inside = cv2.fillConvexPoly(np.zeros(band.shape, np.uint8), hull.astype(np.int32), 1)
    ys, xs = np.nonzero(band & ~inside.view(bool))
    if n < 4 or not len(xs):
        return band
    q = np.column_stack([xs, ys]).astype(float)
    a, ab = hull, np.roll(hull, -1, axis=0) - hull
    chord = np.hypot(ab[:, 0], ab[:, 1])
    f = np.clip(((q[:, None] - a) * ab).sum(-1) / np.maximum(chord**2, 1e-9), 0.0, 1.0)
    nearest = np.argmin(np.hypot(*(q[:, None] - a - f[..., None] * ab).transpose(2, 0, 1)), 1)
    _, lab, stats, _ = components_with_stats(band, connectivity=8)
    short = np.maximum(stats[:, 2], stats[:, 3]) <= 2 * t  # a line crossing the edge
    crossing = short[lab[ys, xs]] | (chord[nearest] <= 4 * t)
    centre, drop = hull.mean(axis=0), np.zeros(len(q), bool)
    for i in np.unique(nearest[crossing]):
        on = (nearest == i) & crossing
        for v, step in ((i, -1), ((i + 1) % n, 1)):  # the visible side before, after
            w = (v + step) % n
            while np.hypot(*(hull[w] - hull[v])) < t and w != v:
                w = (w + step) % n
            inner = _inner_distance(q[on], hull[w], hull[v], centre)
            drop[np.flatnonzero(on)[inner < -0.5]] = True
    out = band.copy()
    out[ys[drop], xs[drop]] = False
    return out


def _inner_distance(p: np.ndarray, a: np.ndarray, b: np.ndarray, centre: np.ndarray):
    """Signed distance [px] of points ``p`` (k, 2) from the line through ``a`` and
    ``b``, positive on the side of ``centre``."""
    d = b - a
    side = d[0] * (p[:, 1] - a[1]) - d[1] * (p[:, 0] - a[0])
    own = d[0] * (centre[1] - a[1]) - d[1] * (centre[0] - a[0])
    return np.sign(own) * side / max(float(np.hypot(*d)), 1e-9)


def _dark_beside(grey, own: np.ndarray, band: np.ndarray, t: int, dark_below) -> bool:
    """Whether the print's ink within ``t`` [px] of a gridline's ``band`` (its rim
    aside) is all darker than ``dark_below`` (:class:`Gridlines`): ink that dark
    under the line would have been kept as ink printed over it, so the edge is not
    hidden there (the lines' grey is lighter than the ink's)."""
    import cv2

    if dark_below is None or not band.any():
        return False
    inner = cv2.erode(own.view(np.uint8), np.ones((3, 3), np.uint8))
    grown = cv2.dilate(band.view(np.uint8), np.ones((2 * t + 1, 2 * t + 1), np.uint8))
    beside = (inner & grown).view(bool)
    return bool(beside.any()) and float(np.percentile(grey[beside], 90)) < dark_below


def _mark_pull(
    ctx: _Context,
    g: Group,
    kept: np.ndarray,
    angle: float,
    *,
    hidden: np.ndarray | None = None,
    faint: np.ndarray | None = None,
) -> float:
    """How much ink set aside (larger than a speck, not a gridline taken out) touching
    the print may have pulled it out: the largest relative excess of its length or
    width (along ``angle`` [rad] and across) over those of its ink without the
    pixels within ``mark_near_px``, and at least half a stroke, of that mark (a
    stroke's foot on the print's edge; a line crossing the edge only notches it, the
    hull spans the notch).
    ``g`` is the print's padded box, ``kept`` its ink measured (over ``g.mask``'s
    box): what the edge-spot rule took out of the group (a letter's strokes) counts
    as set aside; a faint line's bulge on the edge (``faint``: the ink that was ink
    only for the line's grey, over ``g.mask``'s box, :func:`_bulges`) does not."""
    import cv2

    h, w = ctx.page.work.shape
    # at least half a stroke: the foot a stroke-wide opening leaves where a tick
    # meets the edge at a shallow angle (marks._drop_thin_near) reaches that far from
    # the mark (a ruler's tick along the edge: width +4.5 %, unflagged with 2 px)
    near_px = max(ctx.opts.mark_near_px, round(0.5 * stroke_px(ctx.scan.mm_per_px, ctx.opts)))
    pad = near_px + 2
    r0, c0 = max(g.rows.start - pad, 0), max(g.cols.start - pad, 0)
    r1, c1 = min(g.rows.stop + pad, h), min(g.cols.stop + pad, w)
    ink = ctx.binarization.mask[r0:r1, c0:c1].copy()
    if ctx.found.grid is not None:
        ink &= ~ctx.found.grid.removed[r0:r1, c0:c1]
    own = np.zeros(ink.shape, bool)
    own[g.rows.start - r0 : g.rows.stop - r0, g.cols.start - c0 : g.cols.stop - c0] = kept
    box = (slice(g.rows.start - r0, g.rows.stop - r0), slice(g.cols.start - c0, g.cols.stop - c0))
    for no_mark in (hidden, _bulges(faint, ctx)):  # ink under a label; a line's bulge
        if no_mark is not None:
            ink[box] &= ~no_mark
    aside = remove_specks(ink & ~own, area_mm2_to_px(ctx.opts.speck_area_mm2, ctx.scan.mm_per_px))
    if not aside.any():
        return 0.0
    k = 2 * near_px + 1
    near = cv2.dilate(aside.view(np.uint8), cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (k, k)))
    core = own & ~near.view(bool)
    if not (own & near.view(bool)).any() or not core.any():
        return 0.0
    reach = mm_to_px_length(ctx.opts.tick_reach_mm, ctx.scan.mm_per_px)
    bump = _bump_pull(own, aside, angle, reach, ctx.opts.edge_bump_px)
    return max(_mask_excess(own, core, angle), bump)


def _bulges(faint: np.ndarray | None, ctx: _Context) -> np.ndarray | None:
    """Of the ink set aside as a faint line's (:func:`_without_faint_lines`), the
    bulges where a line crosses the edge: pieces no longer than two lines' widths.
    A longer piece is a line's dash lying on the edge, counted as a mark (a 500 dpi
    rib print's tips on millimetre paper: length +2.3 %, flagged only so)."""
    if faint is None or not faint.any():
        return faint
    _, lab, st, _ = components_with_stats(faint, connectivity=8)
    most = 2 * max(1, round(mm_to_px_length(ctx.opts.faint_line_mm, ctx.scan.mm_per_px)))
    small = np.r_[False, np.maximum(st[1:, 2], st[1:, 3]) <= most]
    return small[lab]


def _bump_pull(own: np.ndarray, aside: np.ndarray, angle: float, reach: float, bump: float):
    """The largest relative excess of the print's length or width (along ``angle``
    [rad] and across) over those without its outline's points sticking out more
    than ``bump`` [px] beyond a parabola fitted to the outline on either side of
    each stretch within ``reach`` [px] of ink set aside (``aside``): a ruler's tick
    lying along the edge inside the print, its end out of the edge by a pixel or
    two (width +1.4 %), or a letter's foot. A stretch whose sides a parabola does
    not follow to half a pixel (a knob pattern, a tip) is not judged. Every outer
    contour of ``own`` is judged: a ribbed print's ribs are apart, and the outer
    ones make its hull (only the longest was, the middle rib: a tick along an outer
    rib's edge went unseen, ruler 5007/84: width +4.5 %, unflagged)."""
    import cv2

    far = cv2.distanceTransform((~aside).view(np.uint8), cv2.DIST_L2, 3)
    contours, _ = cv2.findContours(own.view(np.uint8), cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_NONE)
    n = max(int(reach), 8)
    pts, drops = [], []
    for contour in contours:
        c = contour.reshape(-1, 2).astype(float)  # (x, y)
        pts.append(c)
        drops.append(_bumps(c, far, reach, bump, n))
    c, drop = np.concatenate(pts), np.concatenate(drops)
    if not drop.any() or drop.all():
        return 0.0
    flip = np.array([1.0, -1.0])
    ext = _extents(c * flip, angle) / _extents(c[~drop] * flip, angle)
    return float(np.max(ext) - 1.0)


def _bumps(c: np.ndarray, far: np.ndarray, reach: float, bump: float, n: int) -> np.ndarray:
    """Which points of one closed contour ``c`` ((k, 2) (x, y) [px]) stick out more
    than ``bump`` [px] beyond the parabola fitted to the ``n`` points on either
    side of each stretch within ``reach`` [px] of ink set aside (``far``: the
    distance to it at every pixel), see :func:`_bump_pull`."""
    drop = np.zeros(len(c), bool)
    inz = far[c[:, 1].astype(int), c[:, 0].astype(int)] <= reach
    if inz.all() or not inz.any() or len(c) < 8:
        return drop
    start = int(np.argmin(inz))  # begin outside every stretch
    c, inz = np.roll(c, -start, axis=0), np.roll(inz, -start)
    cuts = np.flatnonzero(np.diff(inz.astype(np.int8))) + 1
    if inz[-1]:  # a stretch running to the contour's end closes there (it was lost:
        cuts = np.r_[cuts, len(c)]  # a label's period on a slick edge, width +1.7 %)
    centre = c.mean(axis=0)
    for a, b in zip(cuts[::2], cuts[1::2], strict=False):
        side = np.r_[np.arange(a - n, a), np.arange(b, b + n)] % len(c)
        side = side[~inz[side]]
        t = c[b - 1] - c[a]
        if len(side) < 8 or not np.hypot(*t):
            continue
        t = t / np.hypot(*t)
        nrm = np.array([-t[1], t[0]])
        if (centre - c[a]) @ nrm > 0:
            nrm = -nrm  # outward
        x, y = (c - c[a]) @ t, (c - c[a]) @ nrm
        if len(np.unique(np.round(x[side], 6))) < 3:
            continue  # no parabola through fewer than three abscissae
        fit = np.polynomial.Polynomial.fit(x[side], y[side], 2)  # (scaled: well conditioned)
        if np.sqrt(np.mean((y[side] - fit(x[side])) ** 2)) > 0.5:
            continue
        run = np.arange(a, b)
        drop[run[y[run] - fit(x[run]) > bump]] = True
    return np.roll(drop, start)


def _spread_marks_over(marks: list, g: Group) -> str:
    """The kind of a mark spread over the sheet (``noise``, ``texture``) whose box
    holds the print's box ('' when none): its ink may join the print's edge unseen
    (faint gridlines at 150 dpi read as noise and widened prints by 8 %)."""
    for m in marks:
        r0, c0, r1, c1 = m.bbox
        if m.kind in ("noise", "texture") and (
            r0 <= g.rows.start and c0 <= g.cols.start and r1 >= g.rows.stop and c1 >= g.cols.stop
        ):
            return m.kind
    return ""


def _as_scan(scan, opts: AnalysisOptions) -> Scan:
    """A Scan as given, or read from a path (scale from the file)."""
    if isinstance(scan, Scan):
        return scan
    if isinstance(scan, str | os.PathLike):
        return read_scan(scan, options=opts)
    raise InvalidInput(
        "scan", type(scan).__name__, "an inkprint.Scan (from read_scan) or a path to a scan"
    )


#: a print of one ink element whose area lies within this factor of a neighbour's
#: mean element (its net area over its elements) is taken for one of them
LONE_ELEMENT_FACTOR = 3.0
#: ... when that neighbour has at least this many elements
LONE_ELEMENT_PEERS = 4
#: two prints side by side whose directions agree within this [deg] and whose ends
#: lie level within TWIN_ENDS of the length are one print split (:func:`_split_twins`)
TWIN_ANGLE_DEG = 2.0
TWIN_ENDS = 0.01
#: ... or, ribs of one print: the shorter lies along the longer's span (within
#: TWIN_ENDS of it), their middles level within RIB_MIDDLE of the longer's length,
#: the shorter at least RIB_SHORTEST of it (a car print's shoulder ribs are shorter
#: than its middle rib: held-out 6 seed 5 sheet 49, 30 and 33 mm beside 40 mm)
RIB_MIDDLE = 0.1
RIB_SHORTEST = 0.5
#: ... each with a straight side facing the other along this share of its length
#: (a rib's edge along the groove: :func:`_facing_side`), to within RIB_EDGE_PX
RIB_EDGE = 0.6
RIB_EDGE_PX = 1.5
#: set-aside marks of these kinds lying between two such prints may be the print's
#: own ribs: the gap between the prints is measured across them
RIB_MARK_KINDS = ("line", "writing")


def _no_slivers(prints: list, opts: AnalysisOptions) -> tuple[list, list]:
    """The prints measured at least ``min_patch_width_mm`` wide and, unless clipped,
    ``min_patch_length_mm`` long (numbered again, in order, their warnings too; a
    scan without a scale: all), and the others as marks. A group passes those
    floors with its specks; measured without them (section 7.1.1) a few gridline
    bits of millimetre chart paper printed dark came out as "prints" 5-20 mm long
    and 0.1 mm wide, each flagged (fifth held-out generator, seed 2: 64 such on
    two PDF pages).

    Parameters
    ----------
    prints : list of PrintResult
    opts : AnalysisOptions

    Returns
    -------
    (list of PrintResult, list of Mark)
    """
    keep, marks = [], []
    for p in prints:
        m = p.metrics
        short = m.length < opts.min_patch_length_mm and "clipped" not in p.flags
        if p.unit != "mm" or (m.width >= opts.min_patch_width_mm and not short):
            keep.append(p)
            continue
        r0, c0, r1, c1 = p.bbox
        marks.append(
            Mark(
                "line" if m.width < opts.min_patch_width_mm else "writing",
                (int(r0), int(c0), int(r1), int(c1)),
                float(m.area),
                f"measured {m.length:.1f} x {m.width:.2f} mm without its edge "
                f"spots: narrower or shorter than a print",
            )
        )
    if len(keep) == len(prints):
        return prints, []
    return _renumbered(keep), marks


def _renumbered(prints: list) -> list:
    """``prints`` numbered 0, 1, ... in their order, their warnings too."""
    out = []
    for new, p in enumerate(prints):
        if p.index == new:
            out.append(p)
            continue
        # every print's warning starts "print #<index>" (then ':', ' is turned', ...)
        old = f"print #{p.index}"
        warnings = tuple(
            f"print #{new}{w[len(old) :]}"
            if w.startswith(old) and not w[len(old) : len(old) + 1].isdigit()
            else w
            for w in p.warnings
        )
        out.append(dataclasses.replace(p, index=new, warnings=warnings))
    return out


def _with_unsure(ctx: _Context, measured: list, too_small: list, *, sensitivity: bool):
    """``(prints, too_small, taken)``: the prints ``measured`` with the groups of
    ``ctx.found.unsure`` whose box's centre lies in none of their hulls measured,
    flagged ``maybe_mark`` and numbered after them, in reading order (a manifest's
    print numbers keep to the prints); the marks ``too_small`` with those measured
    too short or narrow for a print (:func:`_no_slivers`); and the ids of the marks
    they were (no longer set aside). Each is measured without its own mark beside
    it (it is that mark); the other prints were judged with it."""
    import cv2

    hulls = [np.asarray(p.hull_px, np.float32)[:, ::-1].copy() for p in measured]
    extra, taken = [], set()
    for g, mk in ctx.found.unsure:
        centre = (0.5 * (g.cols.start + g.cols.stop), 0.5 * (g.rows.start + g.rows.stop))
        if any(len(h) > 2 and cv2.pointPolygonTest(h, centre, False) >= 0 for h in hulls):
            continue  # (a print's elements left among its marks)
        found = dataclasses.replace(ctx.found, marks=[m for m in ctx.found.marks if m is not mk])
        p = measure_print(dataclasses.replace(ctx, found=found), g, sensitivity=sensitivity)
        m = p.metrics
        why = (
            f"print #{p.index}: set aside as {mk.reason}, it looks like a tiny tread "
            f"print, {m.length:.1f} x {m.width:.1f} {p.unit}: measured for inspection, "
            f"not trusted; see the overlay"
        )
        flags = (*(f for f in p.flags if f != "maybe_mark"), "maybe_mark")
        extra.append(dataclasses.replace(p, flags=flags, warnings=(why, *p.warnings)))
        taken.add(id(mk))  # (measured: a print, or a sliver among too_small)
    extra, small = _no_slivers(extra, ctx.opts)
    if not extra:
        return measured, too_small + small, taken
    # (after the prints, so that a manifest's print numbers keep to them)
    return _renumbered(measured + extra), too_small + small, taken


def _lone_elements(prints: list, mm_per_px: float, opts: AnalysisOptions) -> list:
    """Flag ``grouping_uncertain`` a print of about one ink element lying within
    ``group_groove_max_mm`` of a print of :data:`LONE_ELEMENT_PEERS` or more
    elements of its size (within :data:`LONE_ELEMENT_FACTOR` of their mean net
    area), and that print: a row of a knob pattern the grouping kept apart (held-out
    2026 sheet 6: a knobby print's top row came out as seven 6.7 x 7.9 mm "prints",
    status ok, and the print was measured without it).

    Parameters
    ----------
    prints : list of PrintResult
    mm_per_px : float [mm/px]
    opts : AnalysisOptions

    Returns
    -------
    list of PrintResult
        The same, flagged where it applies.
    """
    many = [i for i, p in enumerate(prints) if p.n_blobs >= LONE_ELEMENT_PEERS]
    if not many:
        return prints
    # (a knob's blob count includes the specks of its texture: the area decides)
    most = LONE_ELEMENT_FACTOR * max(prints[k].metrics.area / prints[k].n_blobs for k in many)
    lone = [i for i, p in enumerate(prints) if i not in many and p.metrics.area <= most]
    if not lone:
        return prints
    hulls = {i: _hull_mm(prints[i], mm_per_px) for i in lone + many}
    notes = {}  # print -> its warning (the first that applies)
    for i in lone:
        for k in many:
            ratio = prints[i].metrics.area * prints[k].n_blobs / max(prints[k].metrics.area, 1e-12)
            gap = hulls[i].distance(hulls[k])
            if (
                gap <= opts.group_groove_max_mm
                and 1 / LONE_ELEMENT_FACTOR <= ratio <= LONE_ELEMENT_FACTOR
            ):
                notes.setdefault(
                    i,
                    f"print #{i} is one ink element the size of print #{k}'s elements, "
                    f"{gap:.1f} mm from it: one of its tread elements kept apart? Both are "
                    f"uncertain; see the overlay, or give --group-mm over that gap",
                )
                notes.setdefault(
                    k,
                    f"print #{k}: ink the size of its tread elements lies beside it as "
                    f"print #{i}: part of it kept apart? See the overlay, or give "
                    f"--group-mm over the gap",
                )
                break
    return _uncertain_grouping(prints, notes)


def _uncertain_grouping(prints: list, notes: dict) -> list:
    """``prints`` with those in ``notes`` ({index: warning}) flagged
    ``grouping_uncertain`` and warned."""
    out = list(prints)
    for i, why in notes.items():
        p = out[i]
        flags = p.flags if "grouping_uncertain" in p.flags else (*p.flags, "grouping_uncertain")
        out[i] = dataclasses.replace(p, flags=flags, warnings=(*p.warnings, why))
    return out


def _hull_mm(p, mm_per_px: float):
    """A print's hull as a shapely polygon in mm (x, y; distances and directions
    only: any origin)."""
    from shapely.geometry import Polygon

    h = np.asarray(p.hull_px, float)
    x, y = px_to_mm(h[:, 0], h[:, 1], n_rows=0, mm_per_px=mm_per_px)
    return Polygon(np.column_stack([x, y])).buffer(0)


def _split_twins(
    prints: list, mm_per_px: float, opts: AnalysisOptions, *, marks: list = ()
) -> list:
    """Flag ``grouping_uncertain`` two prints side by side, one print split along
    its length (two round prints side by side are two prints: a rib's edge along a
    groove is straight): their rolling directions agree within
    :data:`TWIN_ANGLE_DEG`, and

    * they are as long with their ends level, within :data:`TWIN_ENDS` of the
      length, one of them with a straight side (:func:`inkprint.group._straight_side`);
      or the shorter (at least :data:`RIB_SHORTEST` of the longer) lies along the
      longer's span with their middles level within :data:`RIB_MIDDLE` of its
      length, each with a straight side facing the other (:func:`_facing_sides`: a
      car print's shoulder ribs beside its longer middle rib);
    * the gap between them is at most ``group_groove_max_mm``, measured across the
      set-aside ``marks`` of :data:`RIB_MARK_KINDS` that lie between them (a rib
      print's middle ribs set aside as lines).

    Two prints of a sheet are seldom so level and so near. Before: a rib print whose
    middle ribs were set aside as ruler lines came out as two prints 81.3 mm long,
    6.8 mm apart, one unflagged at -52 % width (held-out seed 7 sheet 3); a car
    print at 600 dpi whose three thin middle ribs were set aside as lines came out
    as its two shoulders 41 mm apart, width -80 % with status ok (held-out 6 seed 9
    sheet 93); a car print's middle rib 40 mm long between shoulders of 30 and
    33 mm, 12.4 mm apart, width -68 % with status ok (seed 5 sheet 49).

    Parameters
    ----------
    prints : list of PrintResult
    mm_per_px : float [mm/px]
    opts : AnalysisOptions
    marks : list of Mark
        The sheet's set-aside ink.

    Returns
    -------
    list of PrintResult
        The same, flagged where it applies.
    """
    hulls = [_hull_mm(p, mm_per_px) for p in prints]
    between = [_box_mm(mk.bbox, mm_per_px) for mk in marks if mk.kind in RIB_MARK_KINDS]
    notes = {}
    # (a hull that is no polygon, a line of pixels, has no sides to compare)
    ok = [h.geom_type == "Polygon" and not h.is_empty for h in hulls]
    for i, j in itertools.combinations(np.flatnonzero(ok), 2):
        a, b = prints[i].metrics, prints[j].metrics
        turn = abs((a.orientation - b.orientation + np.pi / 2) % np.pi - np.pi / 2)
        if turn > np.deg2rad(TWIN_ANGLE_DEG):
            continue
        pair = (hulls[i], hulls[j])
        long_ = max(a.length, b.length)
        u = np.array([np.cos(a.orientation), np.sin(a.orientation)])
        ta, tb = (np.asarray(h.exterior.coords) @ u for h in pair)
        level = max(abs(ta.min() - tb.min()), abs(ta.max() - tb.max()))
        twins = abs(a.length - b.length) <= TWIN_ENDS * a.length and level <= TWIN_ENDS * a.length
        if not (twins or _ribs(ta, tb, long_, min(a.length, b.length))):
            continue
        gap = _gap_across(*pair, u, between)
        if gap > opts.group_groove_max_mm:
            continue
        # (two round prints side by side: a rib's edge is straight)
        if twins and not any(_straight_side(np.asarray(h.exterior.coords)) for h in pair):
            continue
        if not twins and not _facing_sides(*pair, u, px_to_mm_length(RIB_EDGE_PX, mm_per_px)):
            continue
        what = "as long and with its ends level" if twins else "level with it, as a rib"
        for k, other in ((i, j), (j, i)):
            notes.setdefault(
                k,
                f"print #{k} lies beside print #{other}, {gap:.1f} mm apart, {what}: one "
                f"print split along its length (ribs between them set aside as lines or "
                f"writing)? Both are uncertain; see the overlay, or give --group-mm over "
                f"the gap",
            )
    return _uncertain_grouping(prints, notes)


def _ribs(ta: np.ndarray, tb: np.ndarray, long_: float, short: float) -> bool:
    """Whether two prints' extents along their rolling direction (``ta``, ``tb``:
    their hulls' points projected on it [mm]) are a print's ribs: the shorter
    (``short``, at least :data:`RIB_SHORTEST` of ``long_``) within the longer's span
    (:data:`TWIN_ENDS` of its length over), their middles level within
    :data:`RIB_MIDDLE` of its length."""
    if short < RIB_SHORTEST * long_:
        return False
    (a0, a1), (b0, b1) = (ta.min(), ta.max()), (tb.min(), tb.max())
    if a1 - a0 < b1 - b0:
        (a0, a1), (b0, b1) = (b0, b1), (a0, a1)
    over = TWIN_ENDS * long_
    inside = b0 >= a0 - over and b1 <= a1 + over
    return bool(inside and abs((a0 + a1) - (b0 + b1)) / 2 <= RIB_MIDDLE * long_)


def _facing_sides(p, q, u: np.ndarray, tol: float) -> bool:
    """Whether two hulls (shapely polygons [mm]) side by side across the direction
    ``u`` each have a straight side facing the other: the hull's points within
    ``tol`` [mm] of its extreme towards the other span at least :data:`RIB_EDGE` of
    its extent along ``u`` (a rib's edge along a groove; a round print's flank
    touches that extreme over a short arc only)."""
    v = np.array([-u[1], u[0]])
    a, b = (np.asarray(h.exterior.coords) for h in (p, q))
    towards = np.sign(float((b @ v).mean() - (a @ v).mean()))
    for pts, sign in ((a, towards), (b, -towards)):
        across, along = sign * (pts @ v), pts @ u
        near = across >= across.max() - tol
        if np.ptp(along[near]) < RIB_EDGE * np.ptp(along):
            return False
    return True


def _box_mm(bbox: tuple, mm_per_px: float):
    """A mark's box ((row0, col0, row1, col1) [px]) as a shapely polygon in mm, as
    :func:`_hull_mm` places a print's hull."""
    from shapely.geometry import box

    r0, c0, r1, c1 = bbox
    xs, ys = px_to_mm([r0, r1], [c0, c1], n_rows=0, mm_per_px=mm_per_px)
    return box(xs.min(), ys.min(), xs.max(), ys.max())


def _gap_across(p, q, u: np.ndarray, marks: list) -> float:
    """The gap [mm] between two hulls ``p``, ``q`` (shapely polygons), across their
    rolling direction ``u`` when ``marks`` (polygons) lie between them: the widest
    stretch across ``u`` not covered by either hull or by a mark within their
    joint hull; without such a mark, their distance."""
    x0, y0, x1, y1 = (
        *np.minimum(p.bounds[:2], q.bounds[:2]),
        *np.maximum(p.bounds[2:], q.bounds[2:]),
    )
    near = [m for m in marks if x0 <= m.centroid.x <= x1 and y0 <= m.centroid.y <= y1]
    joint = p.union(q).convex_hull if near else None
    inside = [m for m in near if joint.contains(m.centroid)]
    if not inside:
        return float(p.distance(q))
    v = np.array([-u[1], u[0]])
    spans = sorted(
        (float(t.min()), float(t.max()))
        for t in (np.asarray(g.exterior.coords) @ v for g in (p, q, *inside))
    )
    widest, reach = 0.0, spans[0][1]
    for lo, hi in spans[1:]:
        widest = max(widest, lo - reach)
        reach = max(reach, hi)
    return widest


def no_print_message(found: FoundPrints) -> str:
    """Why a sheet has no print, from what was set aside (kinds counted, the three
    largest marks' reasons).

    Parameters
    ----------
    found : FoundPrints

    Returns
    -------
    str
    """
    if not found.marks:
        return "no print found on the sheet (no ink group at all)"
    largest = sorted(found.marks, key=lambda m: -m.area_mm2)[:3]
    why = "; ".join(dict.fromkeys(f"{m.kind}: {m.reason}" for m in largest))
    return f"no print found on the sheet: set aside {marks_summary(found.marks)} (largest: {why})"


def _with_paper(ctx: _Context, group: Group) -> Group:
    """The group's box grown by the paper around its ink that the edge field needs
    (both levels at the outline)."""
    pad = 2 + round(mm_to_px_length(ctx.opts.edge_window_mm, ctx.scan.mm_per_px))
    return _padded(group, ctx.page.work.shape, pad)


def _measure_all(ctx: _Context, groups: list, *, sensitivity: bool, threads: int | None):
    """:func:`measure_print` for every group, in order, on up to ``threads`` threads:
    each print's measurement and its re-measures of the threshold band are separate
    tasks; the band's two thresholds one task sharing its window's grey (or, with a
    thread for each, two: one print uses three threads)."""
    n = len(groups)
    threads = min(resolve_threads(threads), 3 * n if sensitivity else n)
    if threads <= 1:
        return [
            measure_print(ctx, g, index=i, sensitivity=sensitivity) for i, g in enumerate(groups)
        ]
    from concurrent.futures import ThreadPoolExecutor

    factors = _factors(ctx.opts) if sensitivity else ()
    split = [(f,) for f in factors] if threads >= 3 * n else [factors] if factors else []
    with ThreadPoolExecutor(threads, thread_name_prefix="inkprint-measure") as pool:
        # the bands first: the longer tasks
        bands = [
            [pool.submit(_bands, ctx, _with_paper(ctx, g), fs) for fs in split] for g in groups
        ]
        prints = [
            pool.submit(measure_print, ctx, g, index=i, sensitivity=False)
            for i, g in enumerate(groups)
        ]
        out = []
        for p, band in zip(prints, bands, strict=True):
            r = p.result()
            values = {k: [lo] for k, (lo, _) in r.band.items()}
            for b in (b for fut in band for b in fut.result()):
                for k, v in b.items():
                    values[k].append(v)
            out.append(dataclasses.replace(r, band=_band_range(values)) if band else r)
    return out


def analyze_scan(
    scan: Scan | str | os.PathLike,
    *,
    method: str = "otsu",
    threshold: float | None = None,
    window_mm: float = 15.0,
    sensitivity: bool = True,
    rolling_axis: str = "auto",
    options: AnalysisOptions | None = None,
    threads: int | None = None,
) -> SheetResult:
    """Find and measure every print on a scanned sheet.

    Parameters
    ----------
    scan : Scan, str or PathLike
        From :func:`inkprint.read_scan`, or a file read with it (the scale from the
        file's DPI; call :func:`read_scan` yourself to give one).
    method : {'otsu', 'fixed', 'sauvola'}
        Binarization (see :func:`inkprint.binarize`).
    threshold : float, optional
        Grey level in (0, 1) for ``method='fixed'``.
    window_mm : float [mm]
        Sauvola window.
    sensitivity : bool
        Compute the threshold sensitivity band.
    rolling_axis : {'auto', 'x', 'y'}
        Rolling direction on the sheet: length is measured along it, width across
        (see the module's notes).
    options : AnalysisOptions, optional
        Judgement thresholds (defaults when None).

    threads : int, optional
        Prints measured at once on a sheet with several (threads; the work is in
        OpenCV and numpy, which release the GIL). Default: one per print up to the
        cores this process may use; a batch passes 1 (it runs files in parallel).
        The result does not depend on it.

    Returns
    -------
    SheetResult
        Lengths in mm (px for a scan without a scale), prints top to bottom.

    Raises
    ------
    NoInk
        Blank sheet, or nothing on it is a print (the message says what was set
        aside: lines, text, dust, noise).
    AllInk, ScanReadError, ScaleMissing, InvalidInput

    Examples
    --------
    A synthetic 70 x 8 mm slick print on a small 150 dpi sheet:

    >>> import tempfile
    >>> from pathlib import Path
    >>> from inkprint import analyze_scan
    >>> from inkprint.synth import PrintSpec, SheetSpec, render_sheet, save_scan
    >>> spec = SheetSpec((PrintSpec(70.0, 8.0, (50.0, 30.0)),), size=(100.0, 60.0))
    >>> image, (truth,) = render_sheet(spec)
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     path = save_scan(image, Path(tmp) / "sheet.png", dpi=spec.dpi)
    ...     result = analyze_scan(path, sensitivity=False)
    >>> m = result.prints[0].metrics
    >>> round(m.length, 1), round(m.width, 1), round(truth.length, 1), round(truth.width, 1)
    (70.0, 8.0, 70.0, 8.0)
    """
    opts = resolve_options(options)
    if rolling_axis not in AXES:
        raise InvalidInput("rolling_axis", rolling_axis, " | ".join(AXES))
    resolve_threads(threads)  # refused before any work
    scan = _as_scan(scan, opts)
    s = scan.mm_per_px
    page = prepare_page(scan, options=opts)
    b = binarize(
        page.work,
        mm_per_px=s,
        method=method,
        threshold=threshold,
        window_mm=window_mm,
        sheet=page.sheet,
        options=opts,
    )
    sheet_px = b.mask.size if page.sheet is None else int(np.count_nonzero(page.sheet))
    found = find_prints(
        b.mask,
        mm_per_px=s,
        options=opts,
        sheet_area_mm2=area_px_to_mm2(sheet_px, s),
        grey=page.work,
        threads=threads,
    )
    if not found.groups and not found.unsure:
        raise NoInk(no_print_message(found))
    ctx = _Context(scan, page, b, found, rolling_axis, opts)
    measured, too_small = _no_slivers(
        _measure_all(ctx, found.groups, sensitivity=sensitivity, threads=threads), opts
    )
    unsure = set()  # (the marks measured as prints flagged maybe_mark)
    if found.unsure:
        measured, too_small, unsure = _with_unsure(
            ctx, measured, too_small, sensitivity=sensitivity
        )
    if not measured:
        found = dataclasses.replace(found, groups=[], marks=found.marks + too_small)
        raise NoInk(no_print_message(found))
    prints = _split_twins(_lone_elements(measured, s, opts), s, opts, marks=found.marks)
    checked = _scale_check(scan, found.scales)
    taken = tuple(b for p in prints for b in p.caps)
    return SheetResult(
        path=scan.path,
        page=scan.page,
        mm_per_px=s,
        scale_source=scan.scale_source,
        unit=scan.unit,
        method=b.method,
        threshold=b.threshold,
        shape=scan.shape,
        prints=prints,
        marks=[
            mk
            for mk in found.marks + too_small
            if not _covered(mk.bbox, taken) and id(mk) not in unsure
        ],
        rolling_axis=rolling_axis,
        axis_source="auto" if rolling_axis == "auto" else "given",
        flags=page.flags + (("uneven_light",) if page.flattened else ()) + checked[:1],
        warnings=page.warnings + checked[1:],
        light_range=page.light_range,
        n_pages=scan.n_pages,
        scales=found.scales,
    )


__all__ = [
    "AXES",
    "BAND_KEYS",
    "FoundPrints",
    "PrintResult",
    "SheetResult",
    "analyze_scan",
    "clipped",
    "contact_pressure",
    "edge_field",
    "find_prints",
    "measure_mask",
    "measure_print",
    "no_print_message",
    "rolling_angle",
    "sensitivity_band",
]
