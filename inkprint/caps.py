"""Cut caps: the next row of a tread's elements, cut by the outline to slivers;
and pieces at a print's edge off its tread's lattice.

Where the contact outline runs a little past a print's last row of knobs or blocks,
it prints a sliver of the next row: a cap of each element there, cut straight (or
along the outline's curve) on its far side and holding the element's own edge on
the side towards the print. Such a cap can be a pixel or two deep and a whole
element wide; at the print's tip it adds a row's gap to its length. Alone on the
paper a row's gap away, it reads as a letter's stroke, a bold pen stroke or dust,
and the print came out short with status ok (held-out 6 seed 6: a knobby print
-10.2 % long, a wide one -14.5 %, a siped chart print -6.7 %, one under a ruler
-10.3 %).

A cap is told from a pen's stroke by where it lies: on a site of the lattice of the
print's whole elements (:func:`inkprint.sites.fit_lattice`), inside the footprint
of an element laid there, reaching the footprint's edge towards the print (the far
side is what the outline cut off), a step beyond an element the print kept, and
wide enough across to be a cap, not a speck. A letter's stroke matches all of it
only by chance to a pixel or two.

The same lattice judges the pieces at a print's edge (:func:`off_lattice`): a
label's bold letters joined to a knobby print as its elements lie where its tread
puts none, and the print is flagged (:func:`inkprint.analyze._label_flags`).

Pure numpy over one crop; :func:`inkprint.analyze.measure_print` uses it.
"""

from __future__ import annotations

import numpy as np

from .components import components_with_stats
from .errors import InvalidInput
from .group import hull_fill, outline_points
from .sites import Lattice, fit_lattice, nearest_site, site_distance

__all__ = ["cut_caps", "off_lattice", "pieces_on_outline"]

#: fewest whole elements (within CAP_SPREAD of their median area) of a print whose
#: caps are looked for
CAP_ELEMENTS = 8
CAP_SPREAD = 1.5
#: the lattice is fitted to this many whole elements nearest a cap
CAP_NEIGHBOURS = 16
#: neighbours for the lattice's fit when none fits with the usual reach: within this
#: many times the nearest distance (knobs 12 mm apart along and 9 mm across,
#: staggered: diagonals 1.43 x)
CAP_REACH = 1.9
#: ... and holding its elements to this share of its step (a tread of knobs of
#: several widths is no lattice to a pixel; held-out 6 seed 2 sheet 3: 5.6 %, a
#: label's letter taken for a cap; the caps fixed: 2-3.5 %)
CAP_MISFIT = 0.045
#: a cap is smaller than this share of a whole element (larger pieces are the
#: pattern joins' :mod:`inkprint.pattern`)
CAP_SHARE = 0.5
#: a cap spans at least CAP_ACROSS of the element's width across, and the whole
#: width (CAP_FULL of it), reaches one of its sides (a corner) or is a shallow lens
#: (CAP_LENS); a narrower one is a corner's sliver along the element's edge, this
#: many times wider than deep (a round halo speck at a site's corner read a siped
#: print 2.5 % wide, held-out 6 seed 3 sheet 37)
CAP_FULL = 0.8
CAP_ACROSS = 0.25
CAP_SLIVER = 3.0
#: a cap's site has at least this many of its eight neighbouring sites kept (a
#: tip's row: the one inwards and both diagonals; a corner's: two)
CAP_KEPT_SITES = 2
#: a piece at the edge is on the lattice when one of the OFF_LAID elements nearest
#: it, laid on its site, holds it (:func:`off_lattice`)
OFF_LAID = 4
#: ... grown by this share of the lattice's step besides the give (a tread's rows a
#: little uneven: held-out 6 seed 6 sheet 65, a cut knob two rows out of the fit
#: lay 8 px off its site)
OFF_GIVE = 0.05
#: a lattice holds near a piece when at most this share of the elements it was
#: fitted to lie off their sites (a few letters among them; independent sets 2 and
#: 3: treads of knobs in pairs fitted by their median, 4 good prints flagged)
OFF_SITES = 0.2
#: ... holds this share of its ink at least (an edge piece can be an element and a
#: sliver of the next, joined by the blur; a letter lies mostly between sites)
OFF_SHARE = 0.5
#: a cap fills its hull to this share at least (a letter's bends do not)
CAP_SOLID = 0.75
#: ... a lens at most this deep for its span across (an outline's arc over an
#: element's edge)
CAP_LENS = 0.5
#: the site is re-anchored on the kept elements around it of at least this share of
#: the whole ones' median area (a cut one's centroid lies off its site)
CAP_ANCHOR = 0.9
#: the give [px] of a cap's fit in its footprint and of its edge on the footprint's,
#: besides the lattice's misfit
CAP_GIVE_PX = 1.5


def _whole(areas: np.ndarray) -> np.ndarray:
    med = np.median(areas[areas >= 0.5 * areas.max()]) if len(areas) else 0.0
    return (areas >= med / CAP_SPREAD) & (areas <= med * CAP_SPREAD)


def cut_caps(kept: np.ndarray, free: np.ndarray, *, elements: tuple | None = None) -> np.ndarray:
    """The caps of a print's elements cut by its outline, among the ink near it.

    Parameters
    ----------
    kept : (h, w) bool
        The print's load-bearing ink, in a crop that reaches a lattice step beyond it.
    free : (h, w) bool
        The other ink in the same crop (set aside, or dropped from the print; no
        other print's).
    elements : tuple, optional
        ``kept``'s 8-connected pieces as :func:`inkprint.components.components_with_stats`
        gives them (count, labels, stats, centroids), when already known.

    Returns
    -------
    (h, w) bool
        The pieces of ``free`` that are cut caps (8-connected pieces, whole).

    Raises
    ------
    InvalidInput
        ``free`` not of ``kept``'s shape.
    """
    import cv2

    kept, free = np.asarray(kept, bool), np.asarray(free, bool)
    if free.shape != kept.shape or kept.ndim != 2:
        raise InvalidInput("free", free.shape, f"a (rows, cols) mask of kept's shape {kept.shape}")
    out = np.zeros(kept.shape, bool)
    if elements is None:
        elements = components_with_stats(kept.view(np.uint8), connectivity=8)
    n, lab, st, cen = elements
    if n - 1 < CAP_ELEMENTS or not free.any():
        return out
    areas = st[1:, 4].astype(float)
    whole = _whole(areas)
    if np.count_nonzero(whole) < CAP_ELEMENTS:
        return out
    centres = cen[1:]  # (x, y)
    w_ids = np.flatnonzero(whole)
    med = float(np.median(areas[whole]))
    _, flab, fst, fcen = components_with_stats(free.view(np.uint8), connectivity=8)
    small = (fst[1:, 4] < CAP_SHARE * med) & (fst[1:, 4] >= 2)
    if not small.any():
        return out
    hull = cv2.convexHull(outline_points(kept))
    lattices = _Lattices(centres, w_ids)
    for j in np.flatnonzero(small) + 1:
        c = fcen[j]
        if cv2.pointPolygonTest(hull, (float(c[0]), float(c[1])), False) >= 0:
            continue  # (inside the hull it changes nothing)
        lattice, near = lattices.at(c)
        if lattice is None:
            continue
        site = nearest_site(lattice, c[None])[0]
        if _is_cap(flab, fst, j, site, lattice, lab, st, centres, near):
            x, y, w, h = fst[j, :4]
            out[y : y + h, x : x + w] |= flab[y : y + h, x : x + w] == j
    return out


def off_lattice(kept: np.ndarray, *, pieces: tuple | None = None) -> np.ndarray:
    """The pieces at a print's edge that lie off its tread's lattice.

    A label's letters or a mark joined to a knobby print as its elements (a bold
    'GP5000 28' 4 mm off a knobby print's side: +26 % wide with status ok, held-out
    6 seed 6 sheet 60) lie where the tread puts none. Each piece touching the ink's
    hull is laid against the lattice of the 16 whole elements nearest it that do
    not (:func:`inkprint.sites.fit_lattice`, misfit under :data:`CAP_MISFIT` of a
    step): the element nearest its site, laid there, holds an element of the print
    or the outline's cut piece of one (within :data:`CAP_GIVE_PX` and the misfit),
    never a letter but by chance. No judgement without such a lattice (fewer than
    :data:`CAP_ELEMENTS` whole elements inside, a tread of several kinds).

    Parameters
    ----------
    kept : (h, w) bool
        The print's load-bearing ink.
    pieces : tuple, optional
        ``kept``'s 8-connected pieces, :func:`inkprint.components.components_with_stats`'s
        ``(n, labels, stats, centroids)``, when the caller has them (labelled here
        otherwise).

    Returns
    -------
    (h, w) bool
        The pieces (8-connected, whole) at the edge off every site.

    Raises
    ------
    InvalidInput
        ``kept`` not a (rows, cols) mask, or ``pieces``' labels not of its shape.
    """

    kept = np.asarray(kept, bool)
    if kept.ndim != 2:
        raise InvalidInput("kept", kept.shape, "a (rows, cols) mask")
    out = np.zeros(kept.shape, bool)
    n, lab, st, cen = pieces or components_with_stats(kept.view(np.uint8), connectivity=8)
    if np.shape(lab) != kept.shape:
        raise InvalidInput(
            "pieces", np.shape(lab), f"kept's pieces, labels of its shape {kept.shape}"
        )
    if n - 1 < CAP_ELEMENTS:
        return out
    whole = _whole(st[1:, 4].astype(float))
    edge = pieces_on_outline(kept, lab, n)
    inner = np.flatnonzero(whole & ~edge[1:])
    if len(inner) < CAP_ELEMENTS:
        return out
    centres = cen[1:]
    lattices = _Lattices(centres, inner)
    grown = {}  # (element, give [px]) -> (its footprint grown, its centroid there)
    pieces = np.flatnonzero(edge[1:])
    if lattices.whole is not None and len(pieces):  # (every piece's site at once)
        sites = dict(zip(pieces, nearest_site(lattices.whole, centres[pieces]), strict=True))
    for k in pieces:
        lattice, near = lattices.at(centres[k])
        if lattice is None:
            continue
        site = (
            sites[k] if lattice is lattices.whole else nearest_site(lattice, centres[k][None])[0]
        )
        x, y, w, h = st[k + 1, :4]
        pys, pxs = np.nonzero(lab[y : y + h, x : x + w] == k + 1)
        pts = np.column_stack([pxs + x, pys + y]).astype(float) - site
        give = _off_give(lattice)
        # (the elements nearest the site, each laid there: a tread's knobs of a few
        # widths, by column; each grown once, when first needed)
        r = int(np.ceil(give))

        def laid(e, r=r):
            if (e, r) not in grown:
                elem, ec = _laid(lab, st, centres, e)
                grown[e, r] = (_grown(elem, r), ec)
            return grown[e, r]

        if not any(
            _share_in(pts + laid(e)[1], laid(e)[0], r) >= OFF_SHARE for e in near[:OFF_LAID]
        ):
            out[y : y + h, x : x + w] |= lab[y : y + h, x : x + w] == k + 1
    return out


def pieces_on_outline(kept: np.ndarray, labels: np.ndarray, n: int) -> np.ndarray:
    """Which pieces of a print's ink touch its outline: the rim of its hull, 3 px
    wide.

    Parameters
    ----------
    kept : (h, w) bool
        The print's load-bearing ink.
    labels : (h, w) int
        Its pieces' labels (0: paper), as :func:`inkprint.components.components_with_stats`
        gives them.
    n : int
        The labels' count, the paper's included.

    Returns
    -------
    (n,) bool
        Per label; the paper's (0) False.

    Raises
    ------
    InvalidInput
        ``kept`` not a (rows, cols) mask, or ``labels`` not of its shape.
    """
    import cv2

    kept = np.asarray(kept, bool)
    if kept.ndim != 2:
        raise InvalidInput("kept", kept.shape, "a (rows, cols) mask")
    if np.shape(labels) != kept.shape:
        raise InvalidInput("labels", np.shape(labels), f"labels of kept's shape {kept.shape}")
    rim = np.zeros(kept.shape, np.uint8)
    cv2.polylines(rim, [cv2.convexHull(outline_points(kept))], True, 1, thickness=3)
    edge = np.zeros(n, bool)
    edge[labels[(rim > 0) & kept]] = True
    edge[0] = False
    return edge


def _fitted(centres: np.ndarray) -> Lattice | None:
    """The lattice of element centres ``centres`` ((k, 2) x, y), None when none fits
    to :data:`CAP_MISFIT` of its step."""
    # (an elongated staggered lattice's diagonal is beyond the usual reach)
    lattice = fit_lattice(centres) or fit_lattice(centres, reach=CAP_REACH)
    if lattice is None or lattice.misfit > CAP_MISFIT * lattice.step:
        return None
    return lattice


class _Lattices:
    """The lattice of a print's elements ``ids`` near a point: the one of them all
    when it fits (a print's tread fitted once), else that of the
    :data:`CAP_NEIGHBOURS` nearest the point (a large print's lattice drifts)."""

    def __init__(self, centres: np.ndarray, ids: np.ndarray):
        self.centres, self.ids = centres, ids
        self.whole = _fitted(centres[ids])
        if self.whole is not None:  # (each element on its site or off, once)
            self.off = _off_sites(self.whole, centres[ids])
        self._fits = {}  # (neighbouring pieces share their nearest elements: one fit)

    def at(self, point: np.ndarray) -> tuple:
        """``(lattice or None, near)``: the lattice near ``point`` ((2,) x, y) and
        the ids of the :data:`CAP_NEIGHBOURS` elements nearest it; None when more
        than :data:`OFF_SITES` of those lie off their sites (beyond
        :data:`CAP_GIVE_PX`, the misfit and :data:`OFF_GIVE` of a step: a tread of
        pairs of knobs fits a lattice by its median and is none)."""
        d = np.hypot(*(self.centres[self.ids] - point).T)
        order = np.argsort(d)[:CAP_NEIGHBOURS]
        near = self.ids[order]
        if self.whole is not None:
            lattice, off = self.whole, self.off[order]
            return (None if np.mean(off) > OFF_SITES else lattice), near
        key = near.tobytes()
        if key not in self._fits:
            lattice = _fitted(self.centres[near])
            if (
                lattice is not None
                and np.mean(_off_sites(lattice, self.centres[near])) > OFF_SITES
            ):
                lattice = None
            self._fits[key] = lattice
        return self._fits[key], near


def _off_give(lattice: Lattice) -> float:
    """How far [px] an element may lie off its site for :func:`off_lattice`:
    :data:`CAP_GIVE_PX`, the misfit and :data:`OFF_GIVE` of a step."""
    return CAP_GIVE_PX + lattice.misfit + OFF_GIVE * lattice.step


def _off_sites(lattice: Lattice, centres: np.ndarray) -> np.ndarray:
    """Which element centres ((k, 2) x, y) lie off their sites by more than
    :func:`_off_give`. (k,) bool."""
    return site_distance(lattice, centres) > _off_give(lattice)


def _laid(lab: np.ndarray, st: np.ndarray, centres: np.ndarray, e: int) -> tuple:
    """``(elem, ec)``: element ``e``'s ink in its box ((h, w) uint8 0/1) and its
    centroid (x, y) in that box."""
    ex, ey, ew, eh = st[e + 1, :4]
    return (lab[ey : ey + eh, ex : ex + ew] == e + 1).astype(np.uint8), centres[e] - [ex, ey]


def _grown(elem: np.ndarray, r: int) -> np.ndarray:
    """The element ``elem`` ((h, w) 0/1) padded and grown by ``r`` [px]."""
    import cv2

    return cv2.dilate(np.pad(elem, r), np.ones((2 * r + 1, 2 * r + 1), np.uint8))


def _share_in(pts: np.ndarray, grown: np.ndarray, r: int) -> float:
    """The share of the points ``pts`` ((n, 2) x, y in the element's box) inside
    its footprint ``grown`` by ``r`` [px] (:func:`_grown`)."""
    idx = np.round(pts).astype(int) + r
    ok = (idx >= 0).all(1) & (idx[:, 0] < grown.shape[1]) & (idx[:, 1] < grown.shape[0])
    hit = np.zeros(len(pts), bool)
    hit[ok] = grown[idx[ok, 1], idx[ok, 0]] > 0
    return float(hit.mean()) if len(pts) else 1.0


def _inside(pts: np.ndarray, elem: np.ndarray, give: float) -> bool:
    """Whether all points ``pts`` ((n, 2) x, y in ``elem``'s box) lie in the
    element grown by ``give`` [px]."""
    r = int(np.ceil(give))
    return _share_in(pts, _grown(elem, r), r) >= 1.0


def _neighbour_steps(basis: np.ndarray) -> np.ndarray:
    """(8, 2) steps [px] from a site to its eight neighbours: along both basis
    vectors and both diagonals, each way."""
    a, b = basis
    return np.array([a, -a, b, -b, a + b, -a - b, a - b, b - a])


def _is_cap(flab, fst, j, site, lattice, lab, st, centres, near) -> bool:
    """Whether piece ``j`` of ``flab`` is a cap of the element at ``site``: at least
    :data:`CAP_KEPT_SITES` neighbouring sites hold elements of the print, and the
    nearest whole element laid at the site holds the piece (:func:`_held`)."""
    import cv2

    steps = _neighbour_steps(lattice.basis)
    give = CAP_GIVE_PX + lattice.misfit
    dist = np.hypot(*(centres[:, None, :] - (site + steps)[None]).transpose(2, 0, 1))  # (k, 8)
    hit = dist.min(axis=0) <= 2.0 * give
    if np.count_nonzero(hit) < CAP_KEPT_SITES:
        return False
    # the site from the whole elements kept around it (the fit's origin is off by a
    # pixel or two a step beyond the elements it was fitted to; a cut one's centroid
    # is off its own site)
    area = st[1:, 4]
    full = area >= CAP_ANCHOR * np.median(area[near])  # (uncut: their centroid on site)
    held = hit & full[dist.argmin(axis=0)]
    if held.any():
        site = (centres[dist.argmin(axis=0)[held]] - steps[held]).mean(axis=0)
    e = near[int(np.argmin(np.hypot(*(centres[near] - site).T)))]  # (laid there)
    elem, ec = _laid(lab, st, centres, e)
    x, y, w, h = fst[j, :4]
    piece = (flab[y : y + h, x : x + w] == j).astype(np.uint8)
    pys, pxs = np.nonzero(piece)
    pts = np.column_stack([pxs + x, pys + y]).astype(float) - site + ec  # in elem's crop
    hull = cv2.convexHull(np.column_stack([pxs, pys]).astype(np.int32))
    if hull_fill(len(pts), hull) < CAP_SOLID:
        return False  # (a letter's bends; a cap is a footprint cut by a smooth outline)
    return _held(pts, elem, ec, steps[hit].mean(axis=0), give)


def _held(pts: np.ndarray, elem: np.ndarray, ec: np.ndarray, inward: np.ndarray, give) -> bool:
    """Whether an element ``elem`` ((h, w) 0/1, centroid ``ec`` (x, y)) holds the
    piece's pixels ``pts`` ((n, 2) (x, y) in its crop) as a cap: all inside it
    (grown by ``give`` [px]), the piece's inner edge on the element's side facing
    ``inward`` (its side's normal nearest that direction), and the piece a full
    cap (:data:`CAP_FULL` of the element across), a corner (reaching a side) or
    a shallow lens (:data:`CAP_LENS`), :data:`CAP_ACROSS` of it across at least, or
    a corner's sliver (:data:`CAP_SLIVER`)."""
    import cv2

    if not _inside(pts, elem, give):
        return False  # (ink outside the footprint)
    eys, exs = np.nonzero(elem)
    exy = np.column_stack([exs, eys]).astype(float)
    turn = np.radians(cv2.minAreaRect(exy.astype(np.float32))[2])
    normals = np.array([[np.cos(turn), np.sin(turn)], [-np.sin(turn), np.cos(turn)]])
    normals = np.vstack([normals, -normals])
    u = normals[int(np.argmax(normals @ inward))]
    e_in, p_in = (exy - ec) @ u, (pts - ec) @ u
    if abs(p_in.max() - e_in.max()) > give:
        return False  # (not reaching the footprint's edge towards the print)
    across = np.array([-u[1], u[0]])
    e_ac, p_ac = (exy - ec) @ across, (pts - ec) @ across
    span, e_span = p_ac.max() - p_ac.min() + 1.0, e_ac.max() - e_ac.min() + 1.0
    depth = p_in.max() - p_in.min() + 1.0
    corner = p_ac.max() >= e_ac.max() - give or p_ac.min() <= e_ac.min() + give
    if span < CAP_ACROSS * e_span:  # (a speck on a site's edge or corner is round)
        return corner and span >= CAP_SLIVER * depth
    return span >= CAP_FULL * e_span or corner or depth <= CAP_LENS * span
