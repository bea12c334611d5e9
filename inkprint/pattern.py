"""Pieces that continue a print's tread pattern.

A print of separate elements (knobs, blocks) far apart for their size keeps only
the elements its grouping linked; an element left out on its own is a short piece
that :func:`inkprint.group.is_print` sets aside as a letter's piece. When the
outline cuts a row of knobs smaller, that whole row can fall out (held-out seed 5
sheet 90, an MTB print at 150 dpi whose 3.5 mm knobs lie 9.8 mm apart: its last
row and two knobs of the one before set aside as writing, width -28 %, status ok).

Such a piece is the print's when it *looks like* the print's elements and *lies
where the pattern puts one*:

* alike: its area is :data:`PIECE_AREA` of the print's typical element's (the
  elements within :data:`TYPICAL_SPREAD` of their median area, at least
  :data:`MIN_ELEMENTS` of them), and laid over one of those elements at the best
  shift at most :data:`MISMATCH` of its ink mismatches within its hull (a piece the
  outline cut lies inside a whole one);
* in step: from its nearest element it lies one of the pattern's steps away (the
  vectors from each typical element to its :data:`STEPS` nearest), within half an
  element's side.

A letter is seldom an element's copy, and never in step with a lattice but by
chance; a piece joined becomes an element, so a row joins one step at a time.

The same comparison serves elsewhere: the pieces of the letters and lines set
aside before grouping are offered too (:func:`mark_pieces`), and a piece cut far
off its element's middle is in step when it lies within an element laid at a
step (:func:`placed_copy`); rows of siped blocks whose many whole copies of one
element no label repeats are a tread, not writing (:func:`copies_of_one`); and a
block's thin frame at a tip, inside a copy of an element, is no stroke's foot
(:func:`frame_copies`).
"""

from __future__ import annotations

import numpy as np

from .components import components_with_stats
from .group import Group, union

__all__ = [
    "copies_of_one",
    "cut_copy",
    "frame_copies",
    "join_pattern_pieces",
    "mark_pieces",
    "typical_elements",
]

#: fewest typical elements of a print whose pattern is continued
MIN_ELEMENTS = 8
#: the typical elements' areas lie within this factor of their median
TYPICAL_SPREAD = 1.5
#: a piece's area within this range of the typical element's (a knob the outline
#: cut to a third, up to one a little larger)
PIECE_AREA = (0.3, 1.5)
#: share of a piece's ink that may mismatch an element's ink within the piece's
#: hull at the best shift (the binarization's ragged edges)
MISMATCH = 0.2
#: the typical elements laid under a piece (spread over their areas)
TRIES = 8
#: pattern steps: the vectors from each typical element to this many nearest ...
STEPS = 4
#: ... from at most this many elements spread over the print
STEP_SAMPLE = 256
#: a piece the outline cut far off its element's middle (a knob's wedge, a chevron's
#: last arm) is in step when it lies within an element laid at one step from one of
#: its NEAREST elements, grown by PLACE_TOL x half an element's side (the
#: pattern's irregularity), at most MISMATCH of its ink outside
NEAREST = 3
PLACE_TOL = 0.5
#: ... and is at least this share of the element's thickness (the widest disk in
#: it): a label's strokes 3 mm off a knob print's tip lay within knobs' places,
#: length +10 % (``test_measure_print_label_beside_a_knobby_tip_stays_unflagged``)
PLACE_THICK = 0.5
#: a piece is a whole copy of an element when, laid over it at the best shift,
#: their ink's intersection is this share of its union or more
WHOLE_IOU = 0.8
#: the kinds of marks whose pieces may be a print's elements (:func:`mark_pieces`):
#: a knob beside a ruler's ticks or a gridline taken for a letter, the last bars of
#: a chevron print cut by its outline taken for straight lines
MARK_KINDS = ("text", "line")
#: the opening that cuts such a piece from a gridline's or a stroke's thin
#: remnants through it (3 x 3 px: remnants one pixel wide)
OPEN = np.ones((3, 3), np.uint8)


def _elements(g: Group) -> tuple:
    """The group's elements: centroids (k, 2) sheet (row, col) [px], areas (k,)
    [px], OpenCV's stats (k + 1, 5) (x, y, w, h, area over the group's box; row
    0: the background) and labels (1..k)."""
    _, lab, st, cen = components_with_stats(g.mask.view(np.uint8), connectivity=8)
    cen = cen[1:, ::-1] + [g.rows.start, g.cols.start]
    return cen, st[1:, 4].astype(float), st, lab


def _one_element(p: Group) -> np.ndarray | None:
    """The centroid (2,) sheet (row, col) [px] of a piece that is one element; None
    for several (a word's letters)."""
    own = _elements(p)[0]
    return own[0] if len(own) == 1 else None


def _typical(areas: np.ndarray) -> np.ndarray:
    """Indices of the elements within :data:`TYPICAL_SPREAD` of the median area."""
    med = np.median(areas)
    return np.flatnonzero((areas >= med / TYPICAL_SPREAD) & (areas <= med * TYPICAL_SPREAD))


def _steps(cen: np.ndarray) -> np.ndarray:
    """The pattern's steps: (m, 2) vectors [px] from each element to its
    :data:`STEPS` nearest, both ways; from at most :data:`STEP_SAMPLE` elements
    spread over the print (a fine tread's thousands of dots: the distances of
    every pair were 3000 x 3000)."""
    pick = np.unique(np.linspace(0, len(cen) - 1, min(len(cen), STEP_SAMPLE)).astype(int))
    d = np.linalg.norm(cen[pick, None] - cen[None], axis=2)
    d[np.arange(len(pick)), pick] = np.inf
    k = min(STEPS, len(cen) - 1)
    near = np.argsort(d, axis=1)[:, :k]
    v = (cen[near] - cen[pick, None]).reshape(-1, 2)
    return np.concatenate([v, -v])


def typical_elements(labels: np.ndarray, stats: np.ndarray, ids: np.ndarray) -> list:
    """Crops of a print's typical elements to lay pieces over (:func:`cut_copy`):
    :data:`TRIES` spread over the areas of those within :data:`TYPICAL_SPREAD` of
    the median area, when there are :data:`MIN_ELEMENTS` such (else none: a
    label's few letters make no pattern).

    Parameters
    ----------
    labels : (H, W) int
        Labelled elements.
    stats : (n + 1, 5) int
        (x, y, w, h, area) [px] per label (row 0: the background).
    ids : (k,) int
        The print's elements' labels.

    Returns
    -------
    list of (h, w) float32
        0/1 crops, padded by 2 px.
    """
    if len(ids) < MIN_ELEMENTS:
        return []
    areas = stats[ids, 4].astype(float)
    typ = _typical(areas)
    if len(typ) < MIN_ELEMENTS:
        return []
    # spread over their areas: a pattern of two kinds of block (a siped print's
    # centre row and outer rows) has both among them
    typ = typ[np.argsort(areas[typ])]
    pick = typ[np.unique(np.linspace(0, len(typ) - 1, TRIES).round().astype(int))]
    out = []
    for k in ids[pick]:
        x, y, w, h = stats[k, :4]
        out.append(np.pad(labels[y : y + h, x : x + w] == k, 2).astype(np.float32))
    return out


def _hull_mask(piece: np.ndarray) -> tuple:
    """A piece's (uint8 0/1 crop) ink pixels (OpenCV points; None for no ink) and
    its convex hull filled, uint8 0/1 (None for no ink)."""
    import cv2

    pts = cv2.findNonZero(piece)
    if pts is None:
        return None, None
    return pts, cv2.fillConvexPoly(np.zeros(piece.shape, np.uint8), cv2.convexHull(pts), 1)


def _best_shifts(piece: np.ndarray, hull: np.ndarray, refs: list):
    """For each of ``refs`` at least as large as ``piece`` (uint8 0/1 crop), in
    order: (ref, row, col, mismatch) of ``piece`` laid over it at the best shift,
    the squared difference summed within its ``hull`` (:func:`_hull_mask`)."""
    import cv2

    p, m = piece.astype(np.float32), hull.astype(np.float32)
    for e in refs:
        if e.shape[0] < p.shape[0] or e.shape[1] < p.shape[1]:
            continue
        miss = cv2.matchTemplate(e, p, cv2.TM_SQDIFF, mask=m)
        r, c = np.unravel_index(int(np.argmin(miss)), miss.shape)
        yield e, r, c, float(miss[r, c])


def copies_of_one(labels: np.ndarray, stats: np.ndarray, ids: np.ndarray) -> np.ndarray:
    """Which of a group's pieces are whole copies of one of its typical elements
    (:func:`typical_elements`; the element the most are copies of): laid over it at
    the best shift, the two inks' intersection at least :data:`WHOLE_IOU` of their
    union. A tread repeats one element; writing repeats a letter a few times.

    Parameters
    ----------
    labels : (H, W) int
        Labelled pieces.
    stats : (n + 1, 5) int
        (x, y, w, h, area) [px] per label (row 0: the background).
    ids : (k,) int
        The pieces' labels.

    Returns
    -------
    (k,) bool
    """
    import cv2

    refs = typical_elements(labels, stats, ids)
    best = np.zeros(len(ids), bool)
    if not refs:
        return best
    crops = []
    for k in ids:
        x, y, w, h = stats[k, :4]
        crops.append((labels[y : y + h, x : x + w] == k).astype(np.float32))
    sums = [float(p.sum()) for p in crops]
    for e in refs:
        n_e = float(e.sum())
        hit = np.zeros(len(ids), bool)
        for j, (p, n_p) in enumerate(zip(crops, sums, strict=True)):
            pad = ((p.shape[0], p.shape[0]), (p.shape[1], p.shape[1]))
            both = float(cv2.matchTemplate(np.pad(e, pad), p, cv2.TM_CCORR).max())
            hit[j] = both >= WHOLE_IOU * (n_e + n_p - both)
        if hit.sum() > best.sum():
            best = hit
    return best


def frame_copies(
    labels: np.ndarray, stats: np.ndarray, ids: np.ndarray, *, part: np.ndarray
) -> np.ndarray:
    """Which of ``ids``' pieces are copies of the print's typical elements, or of a
    part of one, with their ``part`` in the element too: laid over one at the best
    shift (:func:`cut_copy`'s), at most :data:`MISMATCH` of the piece's ink and of
    its ``part``'s mismatches (a siped block the outline cut through its sipe keeps
    a thin frame that an opening takes for a stroke's foot; a label's stroke
    touching a block lies outside any block).

    Parameters
    ----------
    labels : (H, W) int
        The print's ink, labelled by pieces.
    stats : (n + 1, 5) int
        (x, y, w, h, area) [px] per label (row 0: the background).
    ids : (k,) int
        The pieces to test.
    part : (H, W) bool
        The pixels of each piece that must lie in the element.

    Returns
    -------
    (k,) bool
    """
    # (the other pieces' typical elements: a block with a stroke can be typical)
    refs = typical_elements(labels, stats, np.setdiff1d(np.arange(1, len(stats)), ids))
    out = np.zeros(len(ids), bool)
    for i, k in enumerate(ids):
        x, y, w, h = stats[k, :4]
        piece = (labels[y : y + h, x : x + w] == k).view(np.uint8)
        own = part[y : y + h, x : x + w] & piece.view(bool)
        pts, hull = _hull_mask(piece)
        for e, r, c, miss in _best_shifts(piece, hull, refs):
            if miss > MISMATCH * len(pts):
                continue
            if np.count_nonzero(own & (e[r : r + h, c : c + w] == 0)) <= MISMATCH * own.sum():
                out[i] = True
                break
    return out


def cut_copy(piece: np.ndarray, refs: list, *, solid: float = 1.0) -> bool:
    """Whether ``piece`` is one of a print's elements or a piece of one the outline
    cut: laid over one of ``refs`` (:func:`typical_elements`) at the best shift, at
    most :data:`MISMATCH` of its ink mismatches within its hull.

    Parameters
    ----------
    piece : (h, w) uint8 or bool
        0/1 crop.
    refs : list of (h', w') float32
    solid : float [-]
        A piece filling this share of its hull or more is no copy (a solid bar
        fits inside any block); 1: any piece may be.

    Returns
    -------
    bool
    """
    piece = piece.view(np.uint8)
    pts, hull = _hull_mask(piece)
    if pts is None or not refs:
        return False
    if len(pts) >= solid * np.count_nonzero(hull) and solid < 1.0:
        return False
    return any(miss <= MISMATCH * len(pts) for *_, miss in _best_shifts(piece, hull, refs))


def laid_elements(refs: list, tol: float) -> list:
    """The typical elements ready to be laid under pieces (:func:`placed_copy`):
    each grown and shrunk by ``tol`` [px], with its centroid.

    Parameters
    ----------
    refs : list of (h, w) float32
        Typical elements (:func:`typical_elements`).
    tol : float [px]
        How far a piece's outline may lie off an element's.

    Returns
    -------
    list of (grown (h', w') bool, shrunk (h', w') bool, centroid (2,) float [px],
    the widest disk's radius in it [px])
    """
    import cv2

    r = max(int(np.ceil(tol)), 1)
    disk = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (2 * r + 1, 2 * r + 1))
    out = []
    for e in refs:
        e8 = np.pad(e, r).astype(np.uint8)
        ce = np.argwhere(e8 > 0).mean(axis=0)
        thick = float(cv2.distanceTransform(e8, cv2.DIST_L2, 3).max())
        out.append((cv2.dilate(e8, disk) > 0, cv2.erode(e8, disk) > 0, ce, thick))
    return out


def placed_copy(piece: Group, anchors: np.ndarray, steps: np.ndarray, *, laid: list) -> bool:
    """Whether a piece is a copy of one of the print's elements, or of a part of one,
    laid where its pattern puts one: at a step from one of ``anchors``, the
    element's centroid there. It is :data:`PLACE_THICK` of the element's thickness
    or more, and within its hull at most :data:`MISMATCH` of its ink count
    mismatches: its ink outside the element grown, its paper inside the element
    shrunk (a letter's ring holds paper where a knob is solid).

    Parameters
    ----------
    piece : Group
        The piece (sheet box and ink).
    anchors : (a, 2) float [px]
        Sheet (row, col) of the elements near it.
    steps : (m, 2) float [px]
        The pattern's steps (:func:`_steps`).
    laid : list
        The typical elements, grown and shrunk (:func:`laid_elements`).

    Returns
    -------
    bool
    """
    import cv2

    mask = piece.mask.view(np.uint8)
    origin = np.array([piece.rows.start, piece.cols.start])
    ink = np.argwhere(mask > 0) + origin
    if not len(ink) or not laid:
        return False
    c = ink.mean(axis=0)
    at = (anchors[:, None] + steps[None]).reshape(-1, 2)
    radius = float(cv2.distanceTransform(np.pad(mask, 1), cv2.DIST_L2, 3).max())
    paper = None
    for grown, shrunk, ce, thick in laid:
        if radius < PLACE_THICK * thick:  # a pen's stroke inside a knob's place
            continue
        # positions where the element laid there could hold the piece's centroid
        near = at[np.all(np.abs(at - c) <= np.array(grown.shape) / 2, axis=1)]
        if not len(near):
            continue
        if paper is None:
            hull = _hull_mask(mask)[1]
            paper = np.argwhere((hull > 0) & (mask == 0)) + origin
        miss = _outside(ink, near, ce, grown, True) + _outside(paper, near, ce, shrunk, False)
        if (miss <= MISMATCH * len(ink)).any():
            return True
    return False


def _outside(pts: np.ndarray, at: np.ndarray, centre: np.ndarray, inside: np.ndarray, off: bool):
    """(positions,) int: how many of ``pts`` (n, 2) sheet px fall where ``inside``
    (an element's crop, its centroid ``centre``) laid with its centroid at each of
    ``at`` (p, 2) is not (``off``: True) or is (False)."""
    idx = np.round(pts[None] - at[:, None] + centre).astype(int)  # (p, n, 2)
    ok = (idx >= 0).all(axis=2) & (idx[..., 0] < inside.shape[0]) & (idx[..., 1] < inside.shape[1])
    hit = np.zeros(ok.shape, bool)
    hit[ok] = inside[idx[..., 0][ok], idx[..., 1][ok]]
    return (~hit if off else hit).sum(axis=1)


def join_pattern_pieces(prints: list, pieces: list, *, marked: int = 0) -> tuple[list, list]:
    """Join to each print the short pieces set aside that continue its pattern.

    A fine tread's print (``Group.fine_area_mm2``: knurl, file, dots) takes only
    the short pieces in step with a copy's centroid: its lattice is so dense that
    any place near it is one step from an element, and a label's letters beside a
    knurl print were joined as its elements (label sweep: width +6..+16 %, length
    +7.9 % with status ok).

    Parameters
    ----------
    prints : list of Group
        The candidate prints.
    pieces : list of Group
        Short pieces set aside (each one element: a letter's piece, or a knob).
    marked : int
        How many of ``pieces``, the last, are the pieces of marks set aside
        (:func:`mark_pieces`).

    Returns
    -------
    prints : list of Group
        The prints with the pieces joined.
    joined : (len(pieces),) bool
        Which pieces were joined.
    """
    joined = np.zeros(len(pieces), bool)
    if not pieces:
        return prints, joined
    single = {}  # piece -> its centroid, found once (a word's letters: None)
    out = []
    for g in prints:
        cen, areas, st, lab = _elements(g)
        typ = _typical(areas) if len(areas) else areas.astype(int)
        if len(typ) < MIN_ELEMENTS:
            out.append(g)
            continue
        fine = g.fine_area_mm2 > 0
        med = float(np.median(areas[typ]))
        steps = _steps(cen[typ])
        reach = np.linalg.norm(steps, axis=1).max() * 1.2
        tol = 0.5 * np.sqrt(med)
        refs = typical_elements(lab, st, typ + 1)
        laid = laid_elements(refs, PLACE_TOL * tol)
        anchors = cen.copy()
        grew = True
        while grew:
            grew = False
            for i in np.flatnonzero(~joined[: len(pieces) - marked if fine else None]):
                p = pieces[i]
                if not PIECE_AREA[0] * med <= p.n_pixels <= PIECE_AREA[1] * med:
                    continue
                if i not in single:
                    single[i] = _one_element(p)
                c = single[i]
                if c is None:
                    continue
                d = np.linalg.norm(anchors - c, axis=1)
                j = int(np.argmin(d))
                if d[j] > reach:
                    continue
                in_step = np.linalg.norm(steps - (c - anchors[j]), axis=1).min() <= tol
                if not (in_step and cut_copy(p.mask, refs)) and (
                    fine or not placed_copy(p, anchors[np.argsort(d)[:NEAREST]], steps, laid=laid)
                ):
                    continue
                g = union(g, p)
                anchors = np.vstack([anchors, c])
                joined[i] = grew = True
        out.append(g)
    return out, joined


def mark_pieces(ink: np.ndarray, boxes: list, prints: list) -> tuple[list, list]:
    """The separate pieces of ink inside marks' boxes, as candidate pieces for
    :func:`join_pattern_pieces`.

    A mark set aside before grouping (a letter, a straight line) can be one of a
    print's elements: a knob cut by the outline beside a gridline, or under a
    ruler's ticks, read as a letter (held-out seed 5 sheet 109 and seed 1 sheet 69:
    a corner knob left out, hull area -3.9 % and -3.7 % with status ok), a chevron
    print's last bars, cut straight by its outline, read as lines (seed 2 sheet 40:
    -3.9 %). Only boxes within half a print's longer side of its box are looked
    into.

    Parameters
    ----------
    ink : (rows, cols) bool
        The sheet's ink (gridlines taken out).
    boxes : list of (row0, col0, row1, col1) int [px]
        The marks' boxes on the sheet.
    prints : list of Group
        The candidate prints: their ink is no piece.

    Returns
    -------
    pieces : list of Group
        Each a piece of ink wholly inside a box (one touching the box's border runs
        on: a ruler, a line of writing), not a print's.
    owner : list of int
        The index in ``boxes`` of each piece's box.
    """
    import cv2

    pieces, owner = [], []
    h, w = ink.shape
    reach = [
        (g.rows.start - m, g.cols.start - m, g.rows.stop + m, g.cols.stop + m)
        for g in prints
        for m in [max(g.mask.shape) // 2]
    ]
    for k, (r0, c0, r1, c1) in enumerate(boxes):
        if not any(r0 < b[2] and b[0] < r1 and c0 < b[3] and b[1] < c1 for b in reach):
            continue
        r0, c0, r1, c1 = max(r0 - 1, 0), max(c0 - 1, 0), min(r1 + 1, h), min(c1 + 1, w)
        crop = ink[r0:r1, c0:c1].copy()
        for g in prints:
            a0, a1 = max(g.rows.start, r0), min(g.rows.stop, r1)
            b0, b1 = max(g.cols.start, c0), min(g.cols.stop, c1)
            if a0 < a1 and b0 < b1:
                own = g.mask[
                    a0 - g.rows.start : a1 - g.rows.start, b0 - g.cols.start : b1 - g.cols.start
                ]
                crop[a0 - r0 : a1 - r0, b0 - c0 : b1 - c0] &= ~own
        # (opened: a gridline's one-pixel remnants through a knob run on out of the box)
        crop = cv2.morphologyEx(crop.view(np.uint8), cv2.MORPH_OPEN, OPEN).astype(bool)
        n, lab, st, _ = components_with_stats(crop.view(np.uint8), connectivity=8)
        for j in range(1, n):
            x, y, cw, ch = st[j, :4]
            edge = (x == 0 and c0 > 0) or (y == 0 and r0 > 0)
            edge |= (x + cw == crop.shape[1] and c1 < w) or (y + ch == crop.shape[0] and r1 < h)
            if edge:
                continue
            mask = lab[y : y + ch, x : x + cw] == j
            pieces.append(Group(slice(r0 + y, r0 + y + ch), slice(c0 + x, c0 + x + cw), mask))
            owner.append(k)
    return pieces, owner
