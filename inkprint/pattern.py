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
"""

from __future__ import annotations

import numpy as np

from .components import components_with_stats
from .group import Group, union

__all__ = ["cut_copy", "join_pattern_pieces", "typical_elements"]

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
    import cv2

    piece = piece.view(np.uint8)
    pts = cv2.findNonZero(piece)
    if pts is None or not refs:
        return False
    hull = cv2.fillConvexPoly(np.zeros(piece.shape, np.uint8), cv2.convexHull(pts), 1)
    if len(pts) >= solid * np.count_nonzero(hull) and solid < 1.0:
        return False
    p, m = piece.astype(np.float32), hull.astype(np.float32)
    for e in refs:
        if e.shape[0] < p.shape[0] or e.shape[1] < p.shape[1]:
            continue
        if cv2.matchTemplate(e, p, cv2.TM_SQDIFF, mask=m).min() <= MISMATCH * len(pts):
            return True
    return False


def join_pattern_pieces(prints: list, pieces: list) -> tuple[list, list]:
    """Join to each print the short pieces set aside that continue its pattern.

    Parameters
    ----------
    prints : list of Group
        The candidate prints.
    pieces : list of Group
        Short pieces set aside (each one element: a letter's piece, or a knob).

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
        med = float(np.median(areas[typ]))
        steps = _steps(cen[typ])
        reach = np.linalg.norm(steps, axis=1).max() * 1.2
        tol = 0.5 * np.sqrt(med)
        refs = typical_elements(lab, st, typ + 1)
        anchors = cen.copy()
        grew = True
        while grew:
            grew = False
            for i in np.flatnonzero(~joined):
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
                if np.linalg.norm(steps - (c - anchors[j]), axis=1).min() > tol:
                    continue
                if not cut_copy(p.mask, refs):
                    continue
                g = union(g, p)
                anchors = np.vstack([anchors, c])
                joined[i] = grew = True
        out.append(g)
    return out, joined
