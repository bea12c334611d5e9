"""A ruler's scale on the sheet: its ticks and numbers, where they cross a print.

A ruler laid on or beside the prints for scale leaves a row of ticks: thin,
straight, parallel bars a millimetre apart whose one end lies on the ruler's edge,
with numbers beyond the longest. Off the prints each tick is set aside as a mark
(too thin and short for a print); over a print the ticks and numbers that touch its
ink join it, and where the scale crosses the print's outline they stick out of it
(held-out 6 seed 2 sheet 103: a ruler across a 44 mm wide print, its '8' and ticks
beyond the print's edge, width +6.9 %, status ok). Under the scale the print's
edge cannot be told from the ruler's ink.

:func:`find_scales` finds the scales among the marks set aside: at least
:data:`MIN_TICKS` ticks (elongated, thin) parallel within :data:`TICK_TURN_DEG`,
one end of each on one line (within :data:`BASE_TOL_MM`), spaced along it at a
regular pitch (:data:`PITCH_MM`), of two lengths or more (:data:`TICK_LONGER`). A
label's strokes ('l', '1') are parallel too, but few, alike and not at a pitch.
:func:`scale_band` is the strip the scale covers: from just behind the edge to its
numbers, along the ticks found (and a pitch beyond them; across a print whose ink
the next tick would meet), as a polygon. :func:`on_scale` tells the scale's own
places in it: its ticks' (hidden in a print's ink too, placed from the ticks found
beside it), its edge line's and its numbers'. The pen-thin ink on those places that
sticks out of the rest of a print's hull is taken off the print
(:func:`inkprint.analyze._without_scale`), unless pen-thin ink off them sticks out
too. Then a print whose length, width or half its hull area shrinks by more than
``edge_uncertainty`` without the pen-thin ink left in that strip is flagged
``mark_on_edge`` (:func:`inkprint.analyze._ruler_pull`): the ink measured is an
upper bound of the print there, the rest a lower one.

The ticks' pitch, fitted over the whole scale, is a check of the sheet's scale:
:func:`scale_error` is how far it reads from every ruler's pitch
(:data:`inkprint.coords.RULER_PITCHES_MM`); far off, the file's dpi is wrong and the
sheet is flagged ``scale_mismatch``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .coords import RULER_PITCHES_MM, mm_to_px_length, px_to_mm_length
from .errors import InvalidInput, check_mm_per_px, check_points

__all__ = ["RulerScale", "find_scales", "on_scale", "scale_band", "scale_error"]

#: fewest ticks of a scale (a label has few parallel strokes on one base line)
MIN_TICKS = 10
#: a tick is a bar at least this many times longer than thick ...
TICK_ELONGATION = 4.0
#: ... no thicker than this [mm] and within this range of lengths [mm]
TICK_WIDTH_MM = 0.6
TICK_LENGTH_MM = (0.8, 9.0)
#: ... the longest of a scale's at least this many times its median tick (a ruler
#: marks halves and whole centimetres longer)
TICK_LONGER = 1.4
#: ticks of one scale are parallel within this [deg] ...
TICK_TURN_DEG = 4.0
#: ... one end of each on one line, within this [mm] ...
BASE_TOL_MM = 0.35
#: ... a line searched within this [deg] of the ticks' normal
BASE_SEARCH_DEG = 3.0
#: ... and most of the steps between neighbours along it (at least
#: :data:`PITCH_SHARE` of them) within :data:`PITCH_TOL` of a whole number of pitches
#: between these [mm] (a millimetre scale; an inch scale's sixteenths are 1.6 mm)
PITCH_MM = (0.5, 2.6)
PITCH_TOL = 0.2
PITCH_SHARE = 0.7
#: the strip a scale covers reaches this many of its longest ticks beyond its edge
#: (the ticks, then the numbers beyond the longest, as tall) and this [mm] behind it
#: (the ruler's edge line)
BAND_TICKS = 2.2
BAND_BEHIND_MM = 1.0
#: a tick's centroid farther than this share of the pitch from its place is left out
#: of the pitch's fit (a number's stroke, a tick the print's ink merged into)
OFF_PITCH = 0.3
#: a scale's pitch is off a ruler's only by what lies beyond this many standard errors
SURE = 3.0
#: an end of a scale's ticks within this of a print [mm] runs on across it
BAND_REACH_MM = 2.0
#: marks that may be a scale's ticks
TICK_KINDS = ("text", "dust", "writing", "sliver")
#: a scale's longest ticks: within this share of the longest (a centimetre's, whose
#: number stands beyond it; a half's is 0.7 of it)
MAJOR_SHARE = 0.85
#: a scale's number reaches this far either side of its tick [mm] (two digits of a
#: ruler's 2-3 mm tall numbers, and a stroke)
NUMBER_HALF_WIDTH_MM = 2.5


@dataclass(frozen=True)
class RulerScale:
    """A ruler's scale found on the sheet.

    Attributes
    ----------
    base : (2,) float [px]
        A point of the ruler's edge, the ticks' common end: (col, row).
    along : (2,) float
        Unit vector along the edge (col, row).
    out : (2,) float
        Unit vector along the ticks, from the edge to their tips (col, row).
    span : (2,) float [px]
        The ticks' extent along ``along`` from ``base`` (first, last).
    tick_px : float [px]
        The longest tick.
    ticks : int
        How many ticks were found.
    pitch_mm : float [mm]
        The step between neighbouring ticks (fitted over the scale).
    pitch_error_mm : float [mm]
        Its standard error (the ticks' scatter about their places).
    positions : (k,) float [px]
        The ticks found, along ``along`` from ``base`` (sorted).
    majors : (j,) float [px]
        Those of the longest ticks (within :data:`MAJOR_SHARE` of ``tick_px``): the
        numbers stand beyond them.
    tick_width_px : float [px]
        The ticks' median width.
    """

    base: np.ndarray
    along: np.ndarray
    out: np.ndarray
    span: tuple
    tick_px: float
    ticks: int
    pitch_mm: float
    pitch_error_mm: float = 0.0
    positions: tuple = ()
    majors: tuple = ()
    tick_width_px: float = 0.0


def _ticks(ink: np.ndarray, marks: list, mm_per_px: float) -> np.ndarray:
    """The marks that are tick-like bars: (k, 6) float rows of centre (col, row)
    [px], direction angle [rad in [0, pi)], length [px], the mark's index and its
    width [px]."""
    lo = mm_to_px_length(TICK_LENGTH_MM[0], mm_per_px)
    hi = mm_to_px_length(TICK_LENGTH_MM[1], mm_per_px)
    thick = mm_to_px_length(TICK_WIDTH_MM, mm_per_px)
    out = []
    for i, mk in enumerate(marks):
        if mk.kind not in TICK_KINDS:
            continue
        r0, c0, r1, c1 = mk.bbox
        # (a bar's box's diagonal is its length, up to its width more)
        if not lo <= np.hypot(r1 - r0, c1 - c0) <= hi + thick:
            continue
        rows, cols = np.nonzero(ink[r0:r1, c0:c1])
        if len(rows) < 3:
            continue
        x, y = cols - cols.mean(), rows - rows.mean()
        # the major axis from the second moments
        ang = 0.5 * np.arctan2(2.0 * np.dot(x, y), np.dot(x, x) - np.dot(y, y))
        length = float(np.ptp(x * np.cos(ang) + y * np.sin(ang))) + 1.0
        width = len(rows) / length
        if not (lo <= length <= hi and width <= thick and length >= TICK_ELONGATION * width):
            continue
        out.append((cols.mean() + c0, rows.mean() + r0, float(ang % np.pi), length, i, width))
    return np.asarray(out, float).reshape(-1, 6)


def _mean_axis(ang: np.ndarray) -> float:
    """The mean of axis directions ``ang`` [rad, modulo pi] (doubled angles)."""
    return float(0.5 * np.arctan2(np.sin(2 * ang).mean(), np.cos(2 * ang).mean()))


def _angle_groups(ang: np.ndarray) -> list[np.ndarray]:
    """Indices of ticks parallel within :data:`TICK_TURN_DEG` of each one, largest
    sets first (one per direction)."""
    tol = np.radians(TICK_TURN_DEG)
    diff = np.abs((ang[:, None] - ang[None, :] + np.pi / 2) % np.pi - np.pi / 2)
    near = diff <= tol
    order = np.argsort(-near.sum(axis=1), kind="stable")
    used = np.zeros(len(ang), bool)
    out = []
    for i in order:
        if used[i]:
            continue
        members = np.flatnonzero(near[i] & ~used)
        if len(members) < MIN_TICKS:
            break
        used[members] = True
        out.append(members)
    return out


def _on_a_pitch(t: np.ndarray, mm_per_px: float) -> tuple | None:
    """The pitch [mm] of positions ``t`` [px] along a line and its standard error
    [mm], or None when their steps are not mostly whole numbers of one pitch within
    :data:`PITCH_MM`."""
    steps = px_to_mm_length(np.diff(np.sort(t)), mm_per_px)
    steps = steps[steps > 0.25 * PITCH_MM[0]]
    if len(steps) < MIN_TICKS - 1:
        return None
    pitch = float(np.percentile(steps, 25))  # (the ticks hidden under a print: longer steps)
    if not PITCH_MM[0] <= pitch <= PITCH_MM[1]:
        return None
    q = steps / pitch
    whole = np.abs(q - np.round(q)) <= PITCH_TOL
    if whole.mean() < PITCH_SHARE:
        return None
    # the pitch fitted over the scale (the percentile is one step's, a few % off): each
    # tick's number of pitches from the first, counted step by step (counted from the
    # first tick with a guess a few % off it drifted over 100), the short steps' pitch
    # first (a few pitches each: rounded right whatever the guess), then a line
    # through the positions, counted again with its pitch and fitted again (a gap of
    # 30 pitches under a print, counted with a guess 3 % off, was one too many: 1.2 %
    # off on a 150 dpi page)
    x = px_to_mm_length(np.sort(t), mm_per_px)
    x = x[np.r_[True, np.diff(x) > 0.25 * PITCH_MM[0]]]
    step = np.diff(x)
    k = np.round(step / pitch)
    short = (k >= 1) & (k <= 3)
    if short.any():
        pitch = float(np.median(step[short] / k[short]))
    n = np.r_[0.0, np.cumsum(np.round(step / pitch))]
    on = np.ones(len(x), bool)
    for _ in range(3):
        pitch, b = np.polyfit(n[on], x[on], 1)
        n = np.r_[0.0, np.cumsum(np.round(step / pitch))]
        res = x - (pitch * n + b)
        on = np.abs(res) <= OFF_PITCH * pitch  # (a tick's centroid off its place)
    # the fitted pitch's standard error
    dof = max(int(on.sum()) - 2, 1)
    spread = float(np.sum((n[on] - n[on].mean()) ** 2))
    error = float(np.sqrt(np.sum(res[on] ** 2) / dof / max(spread, 1e-12)))
    return float(pitch), error


def _nearest_place(t: np.ndarray, found: np.ndarray, step: float) -> np.ndarray:
    """Each of ``t``'s nearest place on the lattice of step ``step`` through its
    nearest position in ``found`` (sorted): the scale's local phase, which a pitch
    fitted over the whole ruler would drift from over centimetres. With ``step``
    infinite: the nearest position itself."""
    if len(found) == 1:
        near = found[0]
    else:
        i = np.clip(np.searchsorted(found, t), 1, len(found) - 1)
        left, right = found[i - 1], found[i]
        near = np.where(t - left <= right - t, left, right)
    if not np.isfinite(step):
        return np.broadcast_to(near, t.shape).astype(float)
    return near + np.round((t - near) / step) * step


def on_scale(scale: RulerScale, points: np.ndarray, *, mm_per_px: float) -> np.ndarray:
    """Whether each of ``points`` lies on the scale's own ink: on a tick (within half
    the ticks' width and a pixel of a tick's place on the scale's pitch, between its
    edge line and its longest tick's tip), on its edge line (within
    :data:`BAND_BEHIND_MM` behind the ticks' base), or on a number (beyond the
    ticks, within :data:`BAND_TICKS` of the longest tick from the edge and
    :data:`NUMBER_HALF_WIDTH_MM` of a longest tick's place, their step the spacing
    of the longest ticks found).

    A tick's place is found from the tick found nearest along the scale, so the
    ticks hidden in a print's ink are placed where the scale puts them.

    Parameters
    ----------
    scale : RulerScale
    points : (k, 2) float [px]
        (col, row) on the sheet.
    mm_per_px : float [mm / px]

    Returns
    -------
    (k,) bool

    Raises
    ------
    InvalidInput
        ``mm_per_px`` not positive and finite, ``points`` not (k, 2) finite numbers.
    """
    mm_per_px = check_mm_per_px(mm_per_px)
    pts = check_points("points", points, "(col, row) pixels")
    if not len(scale.positions) or not len(pts):
        return np.zeros(len(pts), bool)
    rel = pts - scale.base
    t, s = rel @ scale.along, rel @ scale.out
    pitch = mm_to_px_length(scale.pitch_mm, mm_per_px)
    behind = mm_to_px_length(BAND_BEHIND_MM, mm_per_px)
    half = 0.5 * scale.tick_width_px + 1.0
    found = np.asarray(scale.positions, float)
    tick = (
        (np.abs(t - _nearest_place(t, found, pitch)) <= half)
        & (s >= -1.0)
        & (s <= scale.tick_px + 1.0)
    )
    edge = (s >= -behind) & (s <= 1.0)
    number = np.zeros(len(pts), bool)
    majors = np.asarray(scale.majors, float)
    if len(majors):
        # (their step: the least spacing of the longest ticks found, in whole pitches;
        # one found: only beside it)
        steps = np.round(np.diff(majors) / pitch) * pitch
        steps = steps[steps > 0]
        step = float(steps.min()) if len(steps) else np.inf
        place = _nearest_place(t, majors, step)
        number = (
            (s > scale.tick_px)
            & (s <= BAND_TICKS * scale.tick_px)
            & (np.abs(t - place) <= mm_to_px_length(NUMBER_HALF_WIDTH_MM, mm_per_px))
        )
    return tick | edge | number


def scale_error(scale: RulerScale) -> float:
    """How far the scale's pitch reads from the nearest ruler's pitch
    (:data:`inkprint.coords.RULER_PITCHES_MM`), less :data:`SURE` of its standard error (0 when
    within it): a sheet's scale off by that much (a file's dpi wrong) reads every
    length off by as much.

    Parameters
    ----------
    scale : RulerScale

    Returns
    -------
    float [-]
        A relative error.
    """
    off = min(abs(scale.pitch_mm / p - 1.0) for p in RULER_PITCHES_MM)
    return max(0.0, off - SURE * scale.pitch_error_mm / scale.pitch_mm)


def _one_scale(tk: np.ndarray, tol: float, mm_per_px: float) -> tuple | None:
    """The scale among ticks ``tk`` (rows of :func:`_ticks`, one direction): the
    base line most of their ends lie on (within ``tol`` [px]), its ticks of two
    lengths or more at a pitch; ``(RulerScale, on)`` with ``on`` (k,) bool its
    ticks, or None."""
    a0 = _mean_axis(tk[:, 2])
    # the end points of the ticks (each along its own axis)
    d = np.column_stack([np.cos(tk[:, 2]), np.sin(tk[:, 2])]) * (tk[:, 3:4] / 2)
    pts = np.concatenate([tk[:, :2] - d, tk[:, :2] + d])  # (2k, 2)
    # the base line: the line across the ticks most of their ends lie on, its
    # direction searched near the ticks' normal (their mean direction is a degree
    # off on short ticks; over a ruler's length that misses the line)
    turns = a0 + np.radians(np.linspace(-BASE_SEARCH_DEG, BASE_SEARCH_DEG, 4 * 15 + 1))
    best_n, a, base_s = 0, a0, 0.0
    for t in turns:
        srt = np.sort(pts @ np.array([np.cos(t), np.sin(t)]))
        count = np.searchsorted(srt, srt + 2 * tol, side="right") - np.arange(len(srt))
        i = int(np.argmax(count))
        if count[i] > best_n:
            best_n, a, base_s = int(count[i]), t, float(np.median(srt[i : i + count[i]]))
    if best_n < MIN_TICKS:
        return None
    u = np.array([np.cos(a), np.sin(a)])  # along the ticks
    n = np.array([-u[1], u[0]])  # along the edge
    s = tk[:, :2] @ u
    lo_end = np.abs(s - tk[:, 3] / 2 - base_s) <= tol
    hi_end = np.abs(s + tk[:, 3] / 2 - base_s) <= tol
    on = lo_end | hi_end
    if on.sum() < MIN_TICKS:
        return None
    # a ruler's ticks are of two lengths or more (millimetres, halves, centimetres);
    # a hatching's or a comb's strokes are alike
    lengths = tk[on, 3]
    if lengths.max() < TICK_LONGER * np.median(lengths):
        return None
    t = tk[on, :2] @ n
    fitted = _on_a_pitch(t, mm_per_px)
    if fitted is None:
        return None
    pitch, pitch_error = fitted
    sign = 1.0 if lo_end[on].sum() >= hi_end[on].sum() else -1.0
    t0 = float(np.median(t))
    base = base_s * u + t0 * n
    longest = float(tk[on, 3].max())
    return (
        RulerScale(
            base=base,
            along=n,
            out=sign * u,
            span=(float(t.min() - t0), float(t.max() - t0)),
            tick_px=longest,
            ticks=int(on.sum()),
            pitch_mm=pitch,
            pitch_error_mm=pitch_error,
            positions=tuple(np.sort(t - t0).tolist()),
            majors=tuple(np.sort(t[tk[on, 3] >= MAJOR_SHARE * longest] - t0).tolist()),
            tick_width_px=float(np.median(tk[on, 5])),
        ),
        on,
    )


def find_scales(ink: np.ndarray, marks: list, *, mm_per_px: float) -> list[RulerScale]:
    """Rulers' scales among the marks set aside (see the module's notes).

    Parameters
    ----------
    ink : (rows, cols) bool
        The sheet's ink.
    marks : list of inkprint.marks.Mark
        The ink set aside.
    mm_per_px : float [mm / px]

    Returns
    -------
    list of RulerScale

    Raises
    ------
    InvalidInput
        ``mm_per_px`` not positive and finite, ``ink`` not 2-D.
    """
    mm_per_px = check_mm_per_px(mm_per_px)
    ink = np.asarray(ink, bool)
    if ink.ndim != 2:
        raise InvalidInput("ink", ink.shape, "a (rows, cols) mask")
    ticks = _ticks(ink, marks, mm_per_px)
    if len(ticks) < MIN_TICKS:
        return []
    tol = mm_to_px_length(BASE_TOL_MM, mm_per_px)
    out = []
    for members in _angle_groups(ticks[:, 2]):
        # (one group may hold two rulers' ticks a few degrees apart, chained: the
        # scale found is taken out and the rest searched again)
        while len(members) >= MIN_TICKS:
            found = _one_scale(ticks[members], tol, mm_per_px)
            if found is None:
                break
            out.append(found[0])
            members = members[~found[1]]
    return out


def scale_band(
    scale: RulerScale, *, mm_per_px: float, ink: np.ndarray | None = None
) -> np.ndarray:
    """The strip a scale covers: (4, 2) float (col, row) [px] corners, from
    :data:`BAND_BEHIND_MM` behind its edge to :data:`BAND_TICKS` of its longest tick
    beyond it, along its ticks and a pitch beyond the first and last. With ``ink``
    (a print's outline points, (k, 2) (col, row) [px]): an end of the ticks whose
    next tick would lie within :data:`BAND_REACH_MM` of that ink runs on across it
    (the ticks under a print are hidden in its ink: a ruler ending over a print left
    its tick beside the edge out of the strip; a ruler ending short of a print, its
    last tick farther from the ink, does not cross it).

    Parameters
    ----------
    scale : RulerScale
    mm_per_px : float [mm / px]
    ink : (k, 2) float [px], optional

    Returns
    -------
    (4, 2) float [px]
    """
    pitch = mm_to_px_length(scale.pitch_mm, mm_per_px)
    behind = mm_to_px_length(BAND_BEHIND_MM, mm_per_px)
    t0, t1 = scale.span[0] - pitch, scale.span[1] + pitch
    s0, s1 = -behind, BAND_TICKS * scale.tick_px
    if ink is not None and len(ink):
        rel = np.asarray(ink, float) - scale.base
        t, s = rel @ scale.along, rel @ scale.out
        reach = mm_to_px_length(BAND_REACH_MM, mm_per_px)
        # the distance from each end's next tick (the base line to the longest
        # tick's length) to the ink
        across = np.maximum(0.0, np.maximum(-s, s - scale.tick_px))
        for end in (t0, t1):
            if np.min(np.hypot(t - end, across)) <= reach:
                t0, t1 = min(t0, t.min()), max(t1, t.max())
    return np.array(
        [
            scale.base + t * scale.along + s * scale.out
            for t, s in ((t0, s0), (t1, s0), (t1, s1), (t0, s1))
        ]
    )
