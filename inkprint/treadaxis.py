"""The direction of a tread pattern's tracks: the sharpest lateral profile.

A tire's tread repeats around its circumference, so each tread element's track
(its lateral position) repeats along the rolling direction: projected across that
direction, the ink of a print of separate elements (knobs, dots, a file or knurl
pattern) piles up into sharp peaks, one per track; projected across a direction
turned from it, the peaks smear. The turn whose lateral profile has the steepest
edges (the sum of squared steps from bin to bin) is the print's own axis; the sum
of squared bin counts (the skew detection of document scanners) says whether there
are tracks at all (``contrast``). Knobs pile into plateaus whose sums of squares
change little over a degree, so their peak wandered 0.5-1.1 deg (held-out knob
prints, width +1.5..+3.1 % unflagged); their edges do not. It needs no outline: a knob pattern's hull is its outer knobs'
corners, whose minimum-area rectangle and moments can lie degrees off (a staggered
knob lattice shears the hull) while its tracks do not. Rows across the tire may
slant (chevrons, staggered knobs): the profile along the rolling direction is not
used (with it, 15 of 85 sparse prints of held-out seed 8 and independent set 111
were found over 1 degree off; without, 4, each at the search's limit: no peak).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .coords import mm_to_px_length
from .errors import InvalidInput, check_mm_per_px

#: the profile's bins across the rolling direction [mm] (at least one pixel): fine
#: enough for a 0.6 mm groove between knurl diamonds
ACROSS_MM = 0.15
#: the mask is summed in cells this long along the rolling direction [mm]: a cell's
#: own smear when turned by the coarse step, 2 mm x 0.5 deg = 0.02 mm, is nothing
ALONG_MM = 2.0
#: the coarse search's step [deg], then refined in steps of :data:`FINE_STEP_DEG`
COARSE_STEP_DEG = 0.5
FINE_STEP_DEG = 0.05


@dataclass(frozen=True)
class TreadTurn:
    """The tread's own axis found from its tracks.

    Attributes
    ----------
    turn : float [deg]
        Own axis minus the given axis, within the searched limit: where the
        profile's edges are steepest.
    contrast : float [-]
        Sharpness at ``turn`` over the median sharpness of the searched turns:
        about 1 for ink without tracks (a slick print), 1.05-2.5 for element
        patterns.
    resolution : float [deg]
        One bin across over the ink's length along: the turn that shifts one
        tip's ink by a bin against the other's (0.15 mm over 20 mm: 0.43 deg).
    edge_contrast : float [-]
        Edge energy at ``turn`` over its median over the searched turns: how
        clearly the edges of the tracks (and of the outline) line up there.
    """

    turn: float
    contrast: float
    resolution: float = 0.0
    edge_contrast: float = 1.0


def _cells(mask: np.ndarray, axis: str, mm_per_px: float) -> tuple[np.ndarray, np.ndarray]:
    """Cells of the mask, :data:`ALONG_MM` along ``axis`` by :data:`ACROSS_MM`
    across (whole pixels): their centres (along, across) [bins] about their mean,
    across pointing left of the rolling direction, and their ink [px]."""
    import cv2

    along = max(1, round(mm_to_px_length(ALONG_MM, mm_per_px)))
    across = max(1, round(mm_to_px_length(ACROSS_MM, mm_per_px)))
    fr, fc = (across, along) if axis == "x" else (along, across)
    h, w = mask.shape
    total = cv2.integral(mask.view(np.uint8))  # (h + 1, w + 1): block sums by corners
    r = np.append(np.arange(0, h, fr), h)
    c = np.append(np.arange(0, w, fc), w)
    ink = total[np.ix_(r[1:], c[1:])] - total[np.ix_(r[:-1], c[1:])]
    ink = ink - total[np.ix_(r[1:], c[:-1])] + total[np.ix_(r[:-1], c[:-1])]
    rows, cols = np.nonzero(ink)
    if len(rows) < 2:
        return np.zeros((0, 2)), np.zeros(0)
    r, c = (rows + 0.5) * fr, (cols + 0.5) * fc
    # x: along +col, across up (-row); y: along up (-row), across -col
    pts = np.column_stack([c, -r] if axis == "x" else [-r, -c]).astype(np.float64)
    return (pts - pts.mean(axis=0)) / across, ink[rows, cols].astype(np.float64)


#: each profile bin is read at this many phases (sub-bins) and the measures averaged
#: over them: a cell's ink shared between two bins has a smaller sum of squares the
#: nearer it lies to their border, so with one phase the profile looked sharpest
#: where the cells fell on the bins' centres, at no turn (a knob print turned 0.33
#: deg read 0.01)
PHASES = 4


def _profiles(pts: np.ndarray, ink: np.ndarray, turns: np.ndarray):
    """Lateral profiles of cells ``pts`` (along, across) [bins] with ``ink``, across
    directions turned ``turns`` (t,) [rad], laid end to end: each bin's weight read
    at :data:`PHASES` offsets (a bin's sum of the sub-bins from each one), each
    profile's first sub-bin, and its extent ((t,) int) in bins. Each cell's ink is
    shared linearly between its two nearest sub-bins: with whole-bin rounding a
    measure of the profile jitters by ~0.5 % from one fine step to the next (cells
    hopping bins), and the largest jitter, not the peak, won (9.65 deg for a 9.5 deg
    knob lattice)."""
    q = PHASES
    v = q * (np.outer(np.cos(turns), pts[:, 1]) - np.outer(np.sin(turns), pts[:, 0]))  # (t, n)
    v = v - v.min(axis=1, keepdims=True)
    k = v.astype(np.int64)
    frac = v - k
    top = k.max(axis=1)
    span = top + 2 + 2 * q  # q empty sub-bins either side: a window stays in its profile
    offset = np.concatenate([[0], np.cumsum(span)[:-1]])
    idx = k + (offset + q)[:, None]
    w = np.broadcast_to(ink, v.shape)
    n = int(span.sum())
    h = np.bincount(idx.ravel(), weights=(w * (1.0 - frac)).ravel(), minlength=n)
    h += np.bincount((idx + 1).ravel(), weights=(w * frac).ravel(), minlength=n)
    c = np.concatenate([[0.0], np.cumsum(h)])
    window = np.zeros(n)
    window[: n - q + 1] = c[q:] - c[:-q]  # a bin starting at every sub-bin
    return window, offset, (top + 1) / q


def _measures(pts: np.ndarray, ink: np.ndarray, turns: np.ndarray) -> tuple:
    """Sharpness and edge energy of the lateral profiles (:func:`_profiles`), each
    (t,). Sharpness: the sum of squared bin weights times the bins spanned (so a
    profile is not sharper merely for being narrower). Edge energy: the sum of
    squared steps from bin to bin. A knob's track is a plateau as wide as the knob,
    and turning the profile only smears its two edges: the sum of squares barely
    changes over a degree and its peak wanders (held-out knob prints: 0.5-1.1 deg
    off, width +1.5..+3.1 %, unflagged), while the steps at the edges are steepest
    where the tracks are."""
    window, offset, extent = _profiles(pts, ink, turns)
    step = np.zeros_like(window)
    step[PHASES:] = window[PHASES:] - window[:-PHASES]  # (each profile starts empty)
    sharp = np.add.reduceat(window * window, offset) / PHASES * extent
    return sharp, np.add.reduceat(step * step, offset) / PHASES


def tread_turn(mask: np.ndarray, axis: str, *, mm_per_px: float, limit_deg: float) -> TreadTurn:
    """The turn of a tread pattern's tracks from a given rolling axis.

    Only turns within ``limit_deg`` are searched: farther, a knob lattice's
    diagonals can give a sharper lateral profile than its tracks (a staggered knob
    pattern: at 22-33 degrees), and a print turned that far is told by its outline.

    Parameters
    ----------
    mask : (h, w) bool
        The print's ink, (row, col).
    axis : {'x', 'y'}
        Given rolling axis: x along the columns, y up the rows.
    mm_per_px : float [mm / px]
    limit_deg : float [deg]
        Turns searched either side of ``axis`` (counter-clockwise positive).

    Returns
    -------
    TreadTurn

    Raises
    ------
    InvalidInput
        ``axis`` not 'x' or 'y', ``limit_deg`` outside (0, 45), ``mm_per_px`` not
        positive.
    """
    if axis not in ("x", "y"):
        raise InvalidInput("axis", axis, "x | y")
    if not 0 < limit_deg < 45:
        raise InvalidInput("limit_deg", limit_deg, "0 < limit_deg < 45 [deg]")
    mm_per_px = check_mm_per_px(mm_per_px)
    pts, ink = _cells(np.asarray(mask, bool), axis, mm_per_px)
    if len(ink) < 2:
        return TreadTurn(0.0, 1.0)
    coarse = np.arange(-limit_deg, limit_deg + 1e-9, COARSE_STEP_DEG)
    sharp, edges = _measures(pts, ink, np.radians(coarse))
    best = coarse[int(np.argmax(edges))]
    fine = best + np.arange(-COARSE_STEP_DEG, COARSE_STEP_DEG + 1e-9, FINE_STEP_DEG)
    edges_fine = _measures(pts, ink, np.radians(fine))[1]
    i = int(np.clip(np.argmax(edges_fine), 1, len(fine) - 2))
    # the parabola through the peak and its neighbours: a fraction of the fine step
    s0, s1, s2 = edges_fine[i - 1 : i + 2]
    bend = s0 - 2.0 * s1 + s2
    shift = 0.5 * (s0 - s2) / bend if bend < 0 else 0.0
    turn = fine[i] + float(np.clip(shift, -0.5, 0.5)) * FINE_STEP_DEG
    # whether there are tracks at all: the profile's sharpness there over its median
    contrast = _measures(pts, ink, np.radians([turn]))[0][0] / np.median(sharp)
    resolution = np.degrees(np.arctan(1.0 / max(np.ptp(pts[:, 0]), 1.0)))
    return TreadTurn(
        float(turn), float(contrast), float(resolution), float(edges_fine.max() / np.median(edges))
    )
