"""Sort a sheet's ink into prints and marks that are not prints (issue 11, item 3).

Thresholds are fields of :class:`inkprint.AnalysisOptions`. The sorting works on a
copy of the ink mask pooled to ~``stroke_width_mm / POOL_STROKES`` per pixel (area-weighted:
a pooled pixel is ink when most of it is), then carries the result back to the full
resolution.

1. **Thick and thin.** An opening with a disk ``stroke_width_mm`` wide keeps the ink
   that is wider than a pen stroke: tread elements (knobs, blocks, ribs, a slick
   print's body); what survives in pieces of less than :data:`MIN_THICK_DISKS`
   disks (where two lines cross, a letter's junction, a dust dot) does not count.
   The rest is *thin*: pen writing, ruler lines and their ticks, gridlines, dust,
   pixel noise, and the thin edges of prints (clipped knobs, rib tails, halo specks).
   **Fine treads.** A knurl, diamond-file or dot-field tread prints as a dense
   regular field of small separate elements (0.5-1.5 mm), each too thin or too
   small to be thick: the thin pieces that make such a field (compact, alike in
   size and spacing, with neighbours all round, their ink filling the field's area:
   :func:`_fine_fields`, ``fine_*`` options) are thick ink, whole. Text is sparse
   strokes in lines, dust isolated specks, pixel noise irregular: none is a field.
   The print's blobs as large as a share of its elements are its core for the
   edge-spot rule (``Group.fine_area_mm2``).
2. **Footprints.** The thick elements are linked into prints by the footprint rule
   of :mod:`inkprint.group`.
   **Bold strokes.** A marker's letters (strokes wider than ``stroke_width_mm``) are
   thick ink too, linked to the print they touch. A print's *body* is the core (ink
   wider than two strokes) of its elements that are mostly core, or of a long one
   whose pores are filled (a file tread); thick ink reaching out of the body's hull
   is judged (:func:`_bold_strokes`): a piece of a body element outside its core
   reaching farther than ``bold_reach_mm`` is a letter unless it fills ``bold_fill``
   of what it adds to its element's hull (a tip, a corner; judged beside a body
   filling ``bold_body_fill`` of its hull); another element, with the ink joined to
   it, is a letter unless it lies along the outline (a sliver) or is a compact blob
   (a tread block; a bold '0' is one too when the print has no small blocks and it
   lies within ``group_distance_mm`` of a letter). Letters are set aside (``text``)
   and the prints regrouped without them.
3. **Thin ink.** Each connected piece of thin ink is judged against the prints'
   convex hulls:

   * ``line`` / ``gridlines`` / ``noise`` / ``text``: at least ``line_length_mm``
     long and mostly outside every print (a ruler crossing a print, chart paper,
     a pixel-noise page, a line of writing); set aside whole. The parts of a line
     inside a print's grooves stay (they are short and do not move the hull). Once
     the lines are taken out, what touched them (a ruler's tick) is the print's
     only as a compact blob.
   * the print's own edge: within ``group_distance_mm`` of a print and reaching no
     farther than ``mark_overhang_mm`` out of its hull (rib tails, slivers), a
     compact blob apart from the print's thick ink (a clipped knob), or a dot no
     longer than ``dot_mm`` (halo specks: the edge-spot rule of section 7.1.1
     decides about them). The hull judging this is the prints' *core*: their thick
     ink opened by two stroke widths, so the foot of a pen stroke meeting the edge
     does not widen it;
   * ``text``: thin strokes reaching farther out (a pen label touching a print), or
     strokes away from every print;
   * a thin piece alone off a print's tip along its major axis (no other piece
     within twice ``group_distance_mm``): a tread block the outline cut to a sliver, the
     print's, beside a block pattern (``tip_block_strokes``); beside a one-piece
     print it cannot be told from a pen stroke: set aside as ``sliver``, and the
     print is flagged with the size it would have with it;
   * ``dust``: small dots away from every print.

Nothing set aside is ever merged into a print; every mark is reported with its kind
and box (:class:`Mark`), and drawn on the QA overlay.
"""

from __future__ import annotations

import dataclasses
import functools
from dataclasses import dataclass, field

import numpy as np

from .components import components_with_stats, components_with_stats_in
from .coords import area_px_to_mm2, binned_mm_per_px, mm_to_px_length, px_to_mm_length
from .errors import check_mm_per_px
from .group import (
    SMALL_PRINT_FILL,
    SMALL_PRINT_MM2,
    Group,
    PartsJoined,
    _closed_fill,
    _hole_sized,
    _outside_distance,
    element_graph,
    hull_fill,
    join_side_by_side,
    join_tips,
    linked_edges,
    merge_overlapping,
    outline_points,
    reading_order,
    union_labels,
)
from .options import AnalysisOptions, resolve_options

#: a tread's bars (not lines): at least BAR_FIELD_MIN straight narrow pieces side by
#: side, turned alike within BAR_ANGLE_DEG, each centre within BAR_SPACING widths of
#: its neighbour's line and within BAR_ALONG of its length along it, none longer than
#: BAR_MAX_MM (see ``_bar_field``)
BAR_FIELD_MIN = 4
BAR_ANGLE_DEG = 5.0
BAR_SPACING = 4.0
#: (0.5 at first: a herringbone's 10 mm bars at 55 degrees, 6.4 mm apart along the
#: print, lie 5.2 mm apart along themselves; held-out 11 sheet 21, 150 dpi)
BAR_ALONG = 0.75
BAR_MAX_MM = 40.0
#: a piece taken for a cut copy of a print's tread element is a letter when chained
#: to at least this many letters (strokes) set aside from the print (``_BoldJudge``)
LABEL_LETTERS = 3
#: cut copies of a print's elements whose boxes lie closer than this many times its
#: elements' gap (median, each to its nearest) are a word's letters (a lattice's cut
#: blocks lie a gap apart; a word's letters a fraction of a mm)
WORD_GAP = 0.5
#: a blob on a word's line no taller than this many times the line's band is one of
#: its letters (:func:`_on_the_line`)
LINE_MATE_HEIGHT = 1.5
#: a comb's teeth (bars reaching out of one print's body) lie side by side with no gap
#: over this many times their median gap (see ``_comb_teeth``)
COMB_GAP = 2.5
#: ... nor a chevron's arms: two meeting end to end within CHEVRON_GAP of their
#: widths, turned CHEVRON_TURN_DEG or more from each other (see ``_chevron_arms``)
CHEVRON_GAP = 2.0
CHEVRON_TURN_DEG = 20.0
#: a bar fills at least this share of its least rectangle (a letter's stroke curves
#: or crosses another)
BAR_FILL = 0.8
#: a punch hole inks its box's inscribed disc to within this share (a square: +27 %)
HOLE_DISC = 0.12
#: ... and fills at least this share of its least enclosing circle (a disc: 0.9-1;
#: a square: 2 / pi)
HOLE_CIRCLE = 0.8
#: a line is fitted to at most about this many of a piece's pixels (a subsample)
LINE_FIT_POINTS = 2000
#: the pooled grid has this many pixels across a stroke (``stroke_width_mm``)
POOL_STROKES = 5.0
#: the Voronoi partition of the elements is sampled every this many mm
GRAPH_STEP_MM = 0.5
#: thick ink smaller than this many stroke disks is thin (the crossing of two lines,
#: a letter's junction, a dust dot): a tread element is larger
MIN_THICK_DISKS = 3
#: thick ink under this many stroke disks, with more thin ink attached than its own
#: area, is a letter's junction (thin)
SMALL_THICK_DISKS = 12
#: a compact thin blob is at most this many times longer than wide
COMPACT_ASPECT = 4.0
#: ... or this many, for what a line set aside touched (a ruler's tick is a bar)
LINE_COMPACT_ASPECT = 2.5
#: ... and fills at least this fraction of its convex hull
COMPACT_SOLIDITY = 0.85
#: a lone thin piece off a print's tip is a tread block the outline cut (convex)
#: when it fills at least this share of its hull after closing: such a sliver 3 x 12
#: pooled px filled 0.71 (mixed set 5006 file 29); a label's first letter beside a
#: tip 0.25-0.59 ('4', 'B', 'F' at 150-400 dpi, strokes 0.35-0.8 mm)
TIP_SLIVER_SOLIDITY = 0.65
#: ... off a block pattern's tip it may lie this many times ``group_distance_mm``
#: out (a pattern's gap along the rolling direction)
TIP_BLOCK_REACH = 1.5
#: ... or, where the print's own rows lie farther apart, this many times its gap
#: between consecutive rows along its major axis (:func:`_row_gap`; held-out 6
#: seed 1 sheets 29, 91: knob prints with rows 5.0 and 5.8 mm apart, tip knobs cut
#: to slivers 5.1 and 6.1 mm out set aside as text, length -7.3 % and -9.9 %,
#: unflagged) ...
TIP_ROW_GAP = 1.3
#: ... the rows found within this many degrees of the hull's major axis
ROW_TURN_DEG = 20.0
#: ... but never beyond this many times ``group_distance_mm``
TIP_ROW_REACH = 3.0
#: a sliver beyond ``TIP_BLOCK_REACH`` (and each of a row of slivers off one tip)
#: is at least this many times longer across the print's axis than along it: the
#: outline cut it across; a letter's stroke ('1', 'l') stands any way
TIP_ROW_ELONGATION = 2.0
#: a long thin convex piece beside a print filling at most this share of its smallest
#: box tapers to both ends: a lens, the print's outer rib the outline cut (a
#: parabolic lens fills 2/3; a ruler's edge, as wide all along, about 1)
LENS_RECT_FILL = 0.8
#: a long thin straight piece beside a print is its outer rib the outline cut when it
#: runs along at least this share of the print's extent in its direction, its ends
#: within a stroke of the print's tips (a rib cut from a rounded rectangle: the whole
#: length; a ruler's or a drawn line runs on beyond the tips)
RIB_SPAN = 0.75
#: ... and fills at least this share of its smallest box: straight (a letter's
#: stroke bends, a dimension line's end ticks stand across)
RIB_RECT_FILL = 0.7
#: straight segments at least this long are a line's (Hough, on the long marks)
LINE_SEGMENT_MM = 5.0
#: a line fitted to them is inked along at least this share of its course across
#: the piece's box
LINE_SUPPORT = 0.5
#: a line crossing a print is bridged where ink lies this close [mm] on both sides
BRIDGE_MM = 1.0
#: the reason given for bold pen strokes set aside (their marks' kind is 'text')
BOLD_REASON = "bold pen strokes (a marker's letters) touching or near a print"
#: why a thin piece touching a print is set aside (followed by its reach)
TICK_REASON = "a pen mark or tick reaching"
#: bold pen strokes are looked for again this many times after regrouping without
#: those found (each pass can only set more aside)
BOLD_PASSES = 3
#: a thick sliver along a print's outline lies no deeper out of its body's hull than
#: this many strokes
SLIVER_STROKES = 3.0
#: this many compact blobs out of a print's body, as large as one another within
#: :data:`TREAD_BLOCK_SPREAD`, are its tread's blocks (a file shoulder beside a slick
#: centre rib), not a marker's letters: few letters are compact (a bold 'O', '0')
TREAD_BLOCKS = 8
TREAD_BLOCK_SPREAD = 1.5
#: ... and strokes as large as the tread's repeated blocks, their boxes' sides within
#: this share of those blocks' (:meth:`_BoldJudge._repeated_blocks`)
BLOCK_SIDE = 0.15
#: beside a fine field, a stroke more than this many times longer than wide is a
#: line's piece, no letter (:meth:`_BoldJudge._field_kinds`; as
#: :data:`inkprint.analyze.LETTER_ASPECT`)
FIELD_BAR_ASPECT = 8.0
#: a fine field is a print's body when it holds this share of the print's thick ink
FIELD_SHARE = 0.75
#: thick elements make a fine field up to this many ``fine_element_mm`` apart (dots
#: of 2.4 mm, 3.5 mm apart, survive the stroke-wide opening whole)
FIELD_THICK_SPACING = 2.0
#: a tiny print's elements inside its field's hull, at least this many, judge how
#: alike their areas are (:func:`_fine_fields` with ``inner``)
INNER_ELEMENTS = 5
#: a fine tread's element is at least this long [mm] (pixel noise is smaller)
FINE_ELEMENT_MIN_MM = 0.3
#: ... fills at least this share of its box (a dot 0.79, a diamond 0.5; a letter's
#: strokes less) ...
FINE_FILL = 0.35
#: ... and is at most this many times longer than wide
FINE_ASPECT = 3.0
#: a fine tread's elements are neighbours within this many times the nearest one's
#: distance (a square lattice's diagonal: 1.41)
FINE_RING = 1.5
#: neighbours looked at per element (a hexagonal lattice has 6)
FINE_K = 8
#: a blob of a fine tread's print at least this share of its elements' median area
#: is one of them (the outline cuts the edge rows' elements: 150 dpi knurl, half
#: diamonds of 0.25 mm^2 left out as edge spots, length -14 %)
FINE_PART = 0.25


@dataclass(frozen=True)
class Mark:
    """Ink set aside: not a print, never merged into one.

    Attributes
    ----------
    kind : str
        'line', 'gridlines', 'text', 'dust', 'noise', 'texture', 'writing',
        'fragment', 'sliver' (a thin piece alone off a print's tip: a sliver of it
        or a pen mark, the print flagged with its size with it).
    bbox : (row0, col0, row1, col1) int [px]
        Box on the sheet.
    area_mm2 : float [mm^2]
        Its ink.
    reason : str
        Why it is not a print.
    """

    kind: str
    bbox: tuple[int, int, int, int]
    area_mm2: float
    reason: str = ""


@dataclass(frozen=True)
class SortedInk:
    """A sheet's ink sorted into candidate prints and marks.

    Attributes
    ----------
    groups : list of Group
        Candidate prints (full resolution), top to bottom.
    marks : list of Mark
        Ink set aside.
    mark_map : (H, W) bool or None
        Where marks were set aside, on the pooled grid (``q`` sheet pixels a side).
    q : int
        Pooling factor of ``mark_map``.
    grazed : (rows, cols) bool or None
        Ink of straight lines set aside (rulers) with print ink right across the
        line: where a line runs along a print's edge the edge lies under it
        (:func:`remove_lines`); None without lines.
    """

    groups: list
    marks: list = field(default_factory=list)
    mark_map: np.ndarray | None = field(default=None, repr=False)
    q: int = 1
    grazed: np.ndarray | None = field(default=None, repr=False)

    def marks_near(self, rows: slice, cols: slice) -> np.ndarray:
        """Sheet pixels of a box that lie on or next to a mark set aside.

        Parameters
        ----------
        rows, cols : slice [px]
            A box of the sheet.

        Returns
        -------
        (h, w) bool
        """
        import cv2

        h, w = rows.stop - rows.start, cols.stop - cols.start
        if self.mark_map is None:
            return np.zeros((h, w), bool)
        q = self.q
        r0, c0 = rows.start // q, cols.start // q
        r1, c1 = -(-rows.stop // q), -(-cols.stop // q)
        small = cv2.dilate(self.mark_map[r0:r1, c0:c1].astype(np.uint8), np.ones((3, 3), np.uint8))
        big = np.repeat(np.repeat(small.astype(bool), q, axis=0), q, axis=1)
        return big[rows.start - r0 * q :, cols.start - c0 * q :][:h, :w]


@dataclass(frozen=True)
class _Pooled:
    """The pooled mask: ``mask`` (H, W) bool, factor ``q`` and pixel size [mm]."""

    mask: np.ndarray
    q: int
    px_mm: float


def _pool(mask: np.ndarray, mm_per_px: float, opts: AnalysisOptions) -> _Pooled:
    import cv2

    q = max(1, int(mm_to_px_length(opts.stroke_width_mm / POOL_STROKES, mm_per_px)))
    m8 = mask.view(np.uint8) if mask.dtype == bool else (mask > 0).astype(np.uint8)
    if q == 1:
        return _Pooled(m8.astype(bool, copy=False), 1, mm_per_px)
    h, w = mask.shape
    hh, ww = -(-h // q), -(-w // q)
    padded = m8 * np.uint8(255)
    if hh * q > h or ww * q > w:  # (a sheet a multiple of q a side needs no copy)
        padded = cv2.copyMakeBorder(
            padded, 0, hh * q - h, 0, ww * q - w, cv2.BORDER_CONSTANT, value=0
        )
    small = cv2.resize(padded, (ww, hh), interpolation=cv2.INTER_AREA)
    return _Pooled(small >= 128, q, binned_mm_per_px(mm_per_px, q))


@functools.lru_cache(maxsize=64)
def _disk(diameter_px: float) -> np.ndarray:
    """A digital disk of the given diameter [px] (pixel centres within the radius;
    OpenCV's small "ellipses" are closer to a plus sign, which fits in the
    crossing of two thin lines). Cached: not to be written to."""
    r = max(diameter_px, 2.0) / 2.0
    n = int(np.floor(r))
    y, x = np.mgrid[-n : n + 1, -n : n + 1]
    return (x * x + y * y <= r * r).astype(np.uint8)


@dataclass(frozen=True)
class _Parts:
    """Thick elements and thin pieces of the pooled mask (labels and stats)."""

    thick: np.ndarray
    n_thick: int
    thin: np.ndarray
    n_thin: int
    thin_stats: np.ndarray
    core: np.ndarray
    thick_stats: np.ndarray
    fine: np.ndarray | None = None  # (n_thick + 1,) bool: a fine tread's elements
    # (rows, cols) slices: a box holding every thick pixel with a margin of paper
    # (:func:`_ink_box`); None: the whole mask
    box: tuple | None = None


def _split(pooled: _Pooled, opts: AnalysisOptions) -> _Parts:
    """Thick elements and thin pieces of the pooled mask.

    Thick: what an opening with a stroke-wide disk keeps, less the small blobs
    that belong to thin ink - under :data:`MIN_THICK_DISKS` disks (where two
    lines cross, a dust dot), or under :data:`SMALL_THICK_DISKS` disks with more
    thin ink attached than their own area (a letter's junction).
    """
    import cv2

    m = pooled.mask.view(np.uint8)
    kernel = _disk(mm_to_px_length(opts.stroke_width_mm, pooled.px_mm))
    disk = int(kernel.sum())
    opened = cv2.morphologyEx(m, cv2.MORPH_OPEN, kernel)
    # the thick ink lies in the opened ink's box: what is found of it alone is found
    # there (the paper around it left out, the same result: :func:`_ink_box`)
    core_disk = _disk(mm_to_px_length(2 * opts.stroke_width_mm, pooled.px_mm))
    box = _ink_box(opened, core_disk.shape[0] // 2)
    # the prints' bodies: thick ink wider than two strokes
    core = np.zeros_like(opened)
    if opened[box].size:
        core[box] = cv2.morphologyEx(opened[box], cv2.MORPH_OPEN, core_disk)
        skinny = opened[box] & ~core[box]
        origin = (box[0].start, box[1].start)
        lines, teeth = _straight_skinny(skinny, pooled, opts, origin=origin)
        opened[box] &= ~lines
        # (a comb's teeth count into the print's hull as its body does: dust at
        # their tips is the print's, not a pen mark on its outline)
        core[box] |= teeth
    n1, l1, s1, _ = components_with_stats_in(opened, box, connectivity=8)
    area = s1[:, cv2.CC_STAT_AREA]
    keep = area >= MIN_THICK_DISKS * disk
    keep[0] = False
    check = np.flatnonzero(keep & (area < SMALL_THICK_DISKS * disk))
    # the ink less the thick elements (none outside the box; 0 / 1 both, and the
    # thick elements are the opened ink: read from it, not from their labels, here
    # and below: there they are the ink that is not thin, ``m ^ thin``)
    thin = m.copy()
    thin[box] &= opened[box] ^ 1
    pieces = None  # the thin pieces, once labelled
    if len(check):
        pieces = components_with_stats(thin, connectivity=8)
        for k in check:
            keep[k] = _attached_thin(l1, pieces[1], pieces[2], s1, k) <= 0.5 * area[k]
    if not keep[1:].all():  # drop pieces: the others keep their order (raster)
        keep[0] = True
        new = np.cumsum(keep, dtype=np.int32) - 1
        new[~keep] = 0
        # relabelled at the thick pixels only (a few % of the box), and the pixels of
        # the pieces dropped are thin ink again
        at = np.flatnonzero(opened.view(bool))  # (l1's pixels: its labels of ``opened``)
        was = np.take(l1, at)
        np.put(l1, at, new[was])
        np.put(thin, at[~keep[was]], 1)
        n1, s1 = int(keep.sum()), s1[keep]
        pieces = None  # (else the thin ink and its pieces are the same as before)
    n2, l2, s2, c2 = pieces or components_with_stats(thin, connectivity=8)
    # a thin piece joined to thick ink is what the opening shaved off it (a
    # diamond's tip), no element of its own: among a fine field's whole elements
    # those bits made the areas irregular (held-out 6 sheet 87: 20 tips of 0.1 mm^2
    # beside 40 diamonds of 1.9 mm^2; the shoulder rows set aside, width -23 %)
    whole = None
    if l1[box].size:
        grown = cv2.dilate(m[box] ^ thin[box], np.ones((3, 3), np.uint8))
        whole = np.bincount(l2[box][grown > 0], minlength=n2) == 0
    fine = _fine_fields(s2, c2, pooled.px_mm, opts, whole=whole)
    fine_el = None
    if fine.any():  # a fine tread's elements are thick ink, whole
        # (the box grows to hold them, with the same margin of paper)
        box = _box_with(box, s2[np.flatnonzero(fine)], core_disk.shape[0] // 2, m.shape)
        fine_px = np.zeros(l1.shape, bool)
        fine_px[box] = fine[l2[box]]
        thick = np.zeros(l1.shape, bool)
        thick[box] = (l1[box] > 0) | fine_px[box]
        n1, l1, s1, _ = components_with_stats_in(thick, box, connectivity=8)
        fine_el = np.bincount(l1[box][fine_px[box]], minlength=n1) > 0
        fine_el[0] = False
        thin = m.copy()
        thin[box] &= (l1[box] == 0).view(np.uint8)
        n2, l2, s2, _ = components_with_stats(thin, connectivity=8)
    cored = np.zeros(l1.shape, bool)
    cored[box] = core[box].view(bool) & ~thin[box].view(bool)  # (the core is ink)
    return _Parts(l1, n1 - 1, l2, n2 - 1, s2, cored, s1, fine_el, box)


def _box_with(box: tuple, stats: np.ndarray, margin: int, shape) -> tuple[slice, slice]:
    """``box`` (rows, cols slices; empty: none) grown to hold the pieces of ``stats``
    (OpenCV's left, top, width, height, ...; at least one) with ``margin`` [px]
    around them, within an image of ``shape``."""
    r0 = max(int((stats[:, 1] - margin).min()), 0)
    c0 = max(int((stats[:, 0] - margin).min()), 0)
    r1 = min(int((stats[:, 1] + stats[:, 3] + margin).max()), shape[0])
    c1 = min(int((stats[:, 0] + stats[:, 2] + margin).max()), shape[1])
    rows, cols = box
    if rows.stop > rows.start and cols.stop > cols.start:
        r0, r1 = min(r0, rows.start), max(r1, rows.stop)
        c0, c1 = min(c0, cols.start), max(c1, cols.stop)
    return slice(r0, r1), slice(c0, c1)


def _ink_box(mask: np.ndarray, margin: int) -> tuple[slice, slice]:
    """The box of a mask's ink grown by ``margin`` [px] on every side (within the
    image): (rows, cols); empty slices without ink.

    An opening (or erosion, dilation) by a kernel reaching at most ``margin`` from
    its centre gives the same pixels in this box as on the whole mask, and none
    outside it: an ink pixel's kernel lies in the box (or runs off the image, the
    same way in both), and the result is ink only within ``margin`` of the ink.
    Labelling the ink's pieces there numbers them the same (in raster order).

    Parameters
    ----------
    mask : (h, w) uint8 or bool
    margin : int [px]

    Returns
    -------
    rows, cols : slice
    """
    import cv2

    x, y, w, h = cv2.boundingRect(mask.view(np.uint8))
    if w == 0 or h == 0:
        return slice(0, 0), slice(0, 0)
    rows, cols = mask.shape
    return (
        slice(max(y - margin, 0), min(y + h + margin, rows)),
        slice(max(x - margin, 0), min(x + w + margin, cols)),
    )


def _fine_fields(
    stats: np.ndarray,
    centroids: np.ndarray,
    px_mm: float,
    opts,
    *,
    whole=None,
    inner: bool = False,
) -> np.ndarray:
    """Which pieces (``stats``, ``centroids``: :func:`components_with_stats`'s, label 0
    the background) are the elements of a fine tread: a dense regular field of small
    similar elements (knurl, diamond file, dot field), each too thin or too small to
    count as thick ink. (n,) bool.

    An element is compact (at least :data:`FINE_ELEMENT_MIN_MM` and at most
    ``fine_element_mm`` long, filling :data:`FINE_FILL` of its box, at most
    :data:`FINE_ASPECT` times longer than wide) with a neighbour within
    ``fine_spacing_mm``; elements within :data:`FINE_RING` times either's nearest
    neighbour's distance are linked into fields. A field is tread when it holds
    ``fine_min_elements``, is regular (``fine_regularity``: its spacings and areas
    alike), two-dimensional (``fine_neighbours``) and dense (``fine_ink_share``).
    Text is sparse strokes in lines, dust isolated specks, pixel noise irregular.
    ``whole`` ((n,) bool): the pieces that are a whole piece of ink, the only
    elements (default: all). ``inner``: the areas' regularity judged on the elements
    inside the field's hull (at least :data:`INNER_ELEMENTS`; a tiny print's outline
    cuts most of its outer ones smaller)."""
    out = np.zeros(len(stats), bool)
    if opts.fine_element_mm <= 0 or len(stats) <= opts.fine_min_elements:
        return out
    w, h, area = (stats[:, k].astype(float) for k in (2, 3, 4))
    long, short = np.maximum(w, h), np.minimum(w, h)
    ext = px_to_mm_length(long, px_mm)
    cand = (ext >= FINE_ELEMENT_MIN_MM) & (ext <= opts.fine_element_mm)
    cand &= (area >= FINE_FILL * w * h) & (long <= FINE_ASPECT * short)
    cand[0] = False
    if whole is not None:
        cand &= whole
    idx = np.flatnonzero(cand)
    if len(idx) < opts.fine_min_elements:
        return out
    pts = px_to_mm_length(centroids[idx], px_mm)  # [mm]
    k = min(FINE_K, len(idx) - 1)
    d, j = _nearest_within(pts, k, opts.fine_spacing_mm)
    nn = d[:, 0]
    ring = np.isfinite(d) & (d <= FINE_RING * nn[:, None])  # (inf: none that near)
    ring &= d <= FINE_RING * nn[np.minimum(j, len(idx) - 1)]  # both ways
    a = np.repeat(np.arange(len(idx)), k)[ring.ravel()]
    comp = union_labels(len(idx), a, j[ring])
    n_comp = int(comp.max()) + 1
    count = ring.sum(axis=1)
    sizes = np.bincount(comp, minlength=n_comp)
    for c in np.flatnonzero(sizes >= opts.fine_min_elements):
        on = comp == c
        at = _inner(pts[on], np.median(nn[on])) if inner else slice(None)
        sp = np.percentile(nn[on], [20, 50, 80])
        ar = np.percentile(area[idx[on]][at], [20, 80])
        ink = area_px_to_mm2(area[idx[on]].sum(), px_mm) / (on.sum() * sp[1] ** 2)
        ok = (
            sp[2] <= opts.fine_regularity * sp[0]
            and ar[1] <= 2 * opts.fine_regularity * ar[0]
            and np.median(count[on]) >= opts.fine_neighbours
            and ink >= opts.fine_ink_share
        )
        out[idx[on]] = ok
    return out


def _inner(pts: np.ndarray, spacing: float) -> np.ndarray:
    """Which of points ``pts`` ((k, 2) [mm]) lie inside their convex hull by more
    than a quarter ``spacing`` [mm], when at least :data:`INNER_ELEMENTS` do (else
    all). (k,) bool."""
    import cv2

    hull = cv2.convexHull(pts.astype(np.float32)).reshape(-1, 2).astype(float)
    edge = np.roll(hull, -1, axis=0) - hull
    length = np.hypot(edge[:, 0], edge[:, 1])
    if len(hull) < 3 or not (length > 0).all():
        return np.ones(len(pts), bool)
    # inside a convex polygon the distance to its outline is the least over its
    # edges' lines (normals turned to the inside: the hull's centre is inside)
    normal = np.column_stack([-edge[:, 1], edge[:, 0]]) / length[:, None]
    normal *= np.sign(np.sum(normal * (hull.mean(axis=0) - hull), axis=1))[:, None]
    depth = np.einsum("kmc,mc->km", pts[:, None, :] - hull[None], normal).min(axis=1)
    inside = depth > 0.25 * spacing
    return inside if inside.sum() >= INNER_ELEMENTS else np.ones(len(pts), bool)


def _nearest_within(pts: np.ndarray, k: int, radius: float) -> tuple:
    """The ``k`` nearest other points of each point within ``radius`` (exact, on a
    grid of ``radius`` cells: every pair that near lies in neighbouring cells):
    distances (n, k) (inf where fewer) and indices (n, k) (n there), nearest first.
    Numpy only: scipy's KD-tree cost 0.25 s of imports in a one-file run."""
    n = len(pts)
    cell = np.floor(pts / radius).astype(np.int64)
    cell -= cell.min(axis=0)
    width = int(cell[:, 1].max()) + 3
    key = (cell[:, 0] + 1) * width + cell[:, 1] + 1
    order = np.argsort(key, kind="stable")
    sorted_key = key[order]
    src, dst = [], []
    for dx in (-1, 0, 1):
        for dy in (-1, 0, 1):
            want = key + dx * width + dy
            lo = np.searchsorted(sorted_key, want, "left")
            cnt = np.searchsorted(sorted_key, want, "right") - lo
            i = np.repeat(np.arange(n), cnt)
            start = np.repeat(lo - np.r_[0, np.cumsum(cnt)[:-1]], cnt)
            src.append(i)
            dst.append(order[start + np.arange(len(i))])
    i, jj = np.concatenate(src), np.concatenate(dst)
    dist = np.hypot(*(pts[i] - pts[jj]).T)
    ok = (i != jj) & (dist <= radius)
    i, jj, dist = i[ok], jj[ok], dist[ok]
    o = np.lexsort((dist, i))
    i, jj, dist = i[o], jj[o], dist[o]
    rank = np.arange(len(i)) - np.searchsorted(i, i, "left")
    keep = rank < k
    d = np.full((n, k), np.inf)
    j = np.full((n, k), n)
    d[i[keep], rank[keep]] = dist[keep]
    j[i[keep], rank[keep]] = jj[keep]
    return d, j


def _straight_skinny(
    skinny: np.ndarray, pooled: _Pooled, opts: AnalysisOptions, *, origin: tuple = (0, 0)
) -> tuple[np.ndarray, np.ndarray]:
    """Of the thick ink narrower than two strokes (``skinny``, uint8, a box of the
    pooled mask whose first row and column are ``origin``), the straight lines and
    a comb's teeth (:func:`_comb_teeth`; uint8 over the box each): lines are pieces at least ``line_length_mm`` long and at most two
    strokes wide along their whole length (a ruler's or a drawn line thick enough
    to survive the opening, where it crosses a print too; a rib follows the outline
    or is wider).

    A line that touches a narrow sliver of a print (a half block at the edge) is one
    piece with it, too wide as a whole: then the line's own pixels are taken - those
    within a stroke of the straight line fitted to the piece - when they run
    unbroken for ``line_length_mm`` and hold most of the piece (:func:`_line_run`)."""
    import cv2

    _n, lab, stats, _ = components_with_stats(skinny, connectivity=8)
    out = np.zeros(skinny.shape, np.uint8)
    long = np.maximum(stats[:, cv2.CC_STAT_WIDTH], stats[:, cv2.CC_STAT_HEIGHT])
    ks = np.flatnonzero(px_to_mm_length(long, pooled.px_mm) >= opts.line_length_mm)
    ks = ks[ks > 0]
    if not len(ks):
        return out, out
    bars, runs = [], []  # the straight narrow pieces, and lines run through wider ones
    whole_of = ([], [])  # ... the whole ink piece of each (:func:`_piece_key`)
    for k in ks:
        x, y, w, h = stats[k, :4]
        r, c = _first_pixel(lab, stats, k)
        # (the whole mask's)
        whole, at = _piece_at(pooled.mask, (r + origin[0], c + origin[1]), corner=True)
        if _tiny_print(whole, pooled.px_mm, opts):
            continue  # the spine of a track tire's file tread print, not a line
        piece = (lab[y : y + h, x : x + w] == k).view(np.uint8)
        rect = cv2.minAreaRect(outline_points(piece))  # (the hull's points)
        (_, _), (a, b), _ = rect
        narrow = px_to_mm_length(min(a, b) + 1, pooled.px_mm) <= 2.0 * opts.stroke_width_mm
        if narrow and px_to_mm_length(max(a, b) + 1, pooled.px_mm) >= opts.line_length_mm:
            bars.append(((y, x), piece, rect))
            whole_of[0].append(_piece_key(whole, at))
        elif not narrow and (run := _line_run(piece, pooled.px_mm, opts)).any():
            runs.append(((y, x), run, cv2.minAreaRect(outline_points(run))))
            whole_of[1].append(_piece_key(whole, at))
    rects, corners = [r for _, _, r in bars], [c for c, _, _ in bars]
    tread = _bar_field(rects, corners, pooled.px_mm) | _chevron_arms(rects, corners)
    tread = np.r_[tread, np.zeros(len(runs), bool)]
    comb = np.zeros(len(tread), bool)
    if len(tread) >= BAR_FIELD_MIN:
        lines = bars + runs
        rects, corners = [r for _, _, r in lines], [c for c, _, _ in lines]
        owners = _owners(whole_of[0] + whole_of[1], lines)
        comb = _comb_teeth(rects, corners, owners, pooled.px_mm)
        comb &= ~tread  # (a herringbone's bar field is judged as before)
    teeth = np.zeros(skinny.shape, np.uint8)
    for ((y, x), piece, _), bar, tooth in zip(bars + runs, tread, comb, strict=True):
        if tooth or not bar:
            (teeth if tooth else out)[y : y + piece.shape[0], x : x + piece.shape[1]] |= piece
    teeth[out > 0] = 0
    return out, teeth


def _bar_field(rects: list, corners: list, px_mm: float) -> np.ndarray:
    """Which straight narrow pieces are the bars of a tread, not lines: at least
    :data:`BAR_FIELD_MIN` of them side by side, each turned as its neighbour within
    :data:`BAR_ANGLE_DEG`, as long within a factor 2, no longer than
    :data:`BAR_MAX_MM`, its centre within :data:`BAR_SPACING` widths of the
    neighbour's line and within :data:`BAR_ALONG` of its length along it (a herringbone tread's
    1.4 mm bars 3 mm apart at 160 dpi were 36 "ruler lines"; the print went
    missing). A ruler is one line; chart paper's gridlines are taken out before,
    and run across the page. ``rects``: OpenCV's ``minAreaRect`` of each, in its
    box at ``corners`` ((row, col) [px]). (k,) bool."""
    n = len(rects)
    out = np.zeros(n, bool)
    if n < BAR_FIELD_MIN:
        return out
    centre, long, wide, u, turn = _bars(rects, corners)
    d = centre[None, :, :] - centre[:, None, :]  # (i, j): j's centre from i's
    along = np.abs(np.einsum("ijk,ik->ij", d, u))
    across = np.abs(np.einsum("ijk,ik->ij", d, u[:, ::-1] * [-1, 1]))
    side = (
        (turn <= BAR_ANGLE_DEG)
        & (across <= BAR_SPACING * wide[:, None])
        & (along <= BAR_ALONG * long[:, None])
        & (
            np.maximum(long[:, None], long[None, :])
            <= 2 * np.minimum(long[:, None], long[None, :])
        )
    )
    np.fill_diagonal(side, False)
    side &= side.T
    short = px_to_mm_length(long, px_mm) <= BAR_MAX_MM
    i, j = np.nonzero(side & short[:, None] & short[None, :])
    comp = union_labels(n, i, j)
    sizes = np.bincount(comp, minlength=n)
    return sizes[comp] >= BAR_FIELD_MIN


def _box_gaps(boxes: np.ndarray) -> np.ndarray:
    """Gaps [px] between boxes ((n, 4) x, y, w, h), each to each ((n, n); inf on
    the diagonal): the distance between their nearest points."""
    b = np.asarray(boxes, float)
    x0, y0, x1, y1 = b[:, 0], b[:, 1], b[:, 0] + b[:, 2], b[:, 1] + b[:, 3]
    dx = np.maximum(0, np.maximum(x0[:, None] - x1[None], x0[None] - x1[:, None]))
    dy = np.maximum(0, np.maximum(y0[:, None] - y1[None], y0[None] - y1[:, None]))
    d = np.hypot(dx, dy)
    np.fill_diagonal(d, np.inf)
    return d


def _piece_key(whole: np.ndarray, corner: tuple) -> tuple:
    """An ink piece's name and size: the (row, col) of its first pixel in raster
    order and its pixel count, from its crop (uint8) whose box starts at ``corner``
    (:func:`_piece_at`)."""
    first = int(whole.argmax())  # (the first 1 of the crop, row by row)
    w = whole.shape[1]
    return (corner[0] + first // w, corner[1] + first % w), np.count_nonzero(whole)


def _owners(wholes: list, bars: list) -> tuple:
    """The ink piece each straight narrow piece belongs to ((k,) int: alike for
    pieces of one ink piece) and its share of that piece's ink ((k,) float):
    ``wholes``, each one's whole piece (:func:`_piece_key`); ``bars`` as
    :func:`_straight_skinny`'s ((row, col), uint8 crop, rectangle)."""
    keys = np.array([key for key, _ in wholes]).reshape(-1, 2)
    _, own = np.unique(keys, axis=0, return_inverse=True)
    share = [np.count_nonzero(b[1]) / n for (_, n), b in zip(wholes, bars, strict=True)]
    return own.ravel(), np.array(share)


def _comb_teeth(rects: list, corners: list, owners: tuple, px_mm: float) -> np.ndarray:
    """Which straight narrow pieces are the teeth of a print's comb, not lines: at
    least :data:`BAR_FIELD_MIN` of one ink piece with a body (together under half
    its ink), turned alike within :data:`BAR_ANGLE_DEG` of their median, none longer
    than :data:`BAR_MAX_MM`, side by side at as many places across them at least two
    widths apart, no gap between neighbours over :data:`COMB_GAP` times the median gap
    (a tooth missing doubles one; a car print's
    shoulder bars 1 mm wide and 7 mm apart reaching out of its rib, held-out set 1
    file 3 page 2: 15 "ruler lines", width -12.6 %, unflagged; :func:`_bar_field`
    asks for bars within 4 widths). A ruler across a print leaves two pieces on one
    line, or four on two; ``rects``, ``corners``: as :func:`_bar_field`'s;
    ``owners``: :func:`_owners`. (k,) bool."""
    owner, share = owners
    out = np.zeros(len(rects), bool)
    centre, long, wide, u, _ = _bars(rects, corners)
    angle = np.arctan2(u[:, 1], u[:, 0])
    for k in np.unique(owner):
        mine = np.flatnonzero(owner == k)
        if len(mine) < BAR_FIELD_MIN or share[mine].sum() >= 0.5:
            continue
        mid = np.angle(np.median(np.exp(2j * angle[mine]))) / 2  # (the axis, 0-180)
        turn = np.degrees(np.abs(np.angle(np.exp(2j * (angle[mine] - mid))))) / 2
        teeth = mine[(turn <= BAR_ANGLE_DEG) & (px_to_mm_length(long[mine], px_mm) <= BAR_MAX_MM)]
        if len(teeth) < BAR_FIELD_MIN:
            continue
        normal = np.array([-np.sin(mid), np.cos(mid)])
        across = np.sort(centre[teeth] @ normal)
        gaps = np.diff(across)
        gaps = gaps[gaps > 2.0 * np.median(wide[teeth])]  # (two pieces of one line: one)
        if len(gaps) + 1 >= BAR_FIELD_MIN and gaps.max() <= COMB_GAP * np.median(gaps):
            out[teeth] = True
    return out


def _like_bars(rects: list, corners: list, field: np.ndarray) -> np.ndarray:
    """Which straight narrow pieces outside a tread's field of bars (``field``,
    (k,) bool: :func:`_bar_field`) are like its bars: turned as one of them within
    :data:`BAR_ANGLE_DEG`, no longer than the longest and as wide within a factor
    1.5 (a herringbone's last bars at its tips lie farther apart than the field's
    spacing). None without a field; ``rects``, ``corners``: as
    :func:`_bar_field`'s. (k,) bool."""
    out = np.zeros(len(rects), bool)
    if not field.any() or field.all():
        return out
    _, long, wide, _, turn = _bars(rects, corners)
    w = np.median(wide[field])
    like = (
        (turn[:, field] <= BAR_ANGLE_DEG).any(axis=1)
        & (long <= long[field].max())
        & (wide <= 1.5 * w)
        & (wide >= w / 1.5)
    )
    return like & ~field


def _bars(rects: list, corners: list) -> tuple:
    """Centres (x, y) [px] on the sheet, lengths and widths [px] and unit vectors
    along, of straight pieces, and the turn between each two (k, k) [deg, 0-90]:
    OpenCV's ``minAreaRect`` of each (``rects``), in its box at ``corners`` ((row,
    col) [px])."""
    centre = np.array(
        [[r[0][0] + c[1], r[0][1] + c[0]] for r, c in zip(rects, corners, strict=True)]
    )
    size = np.array([r[1] for r in rects], float)
    long, wide = size.max(axis=1) + 1, size.min(axis=1) + 1
    angle = np.radians([r[2] + (90.0 if r[1][1] > r[1][0] else 0.0) for r in rects])
    u = np.column_stack([np.cos(angle), np.sin(angle)])
    turn = np.degrees(np.abs(np.angle(np.exp(2j * (angle[:, None] - angle[None, :]))))) / 2
    return centre, long, wide, u, turn


def _piece_rects(labels: np.ndarray, stats: np.ndarray, ks) -> tuple[list, list]:
    """OpenCV's ``minAreaRect`` of each piece ``ks`` of ``labels`` (``stats``:
    OpenCV's), in its box, and the boxes' corners ((row, col) [px]): the input of
    :func:`_bar_field` and :func:`_chevron_arms`."""
    import cv2

    rects, corners = [], []
    for k in ks:
        x, y, w, h = stats[k, :4]
        piece = (labels[y : y + h, x : x + w] == k).view(np.uint8)
        rects.append(cv2.minAreaRect(outline_points(piece)))  # (the hull's points)
        corners.append((y, x))
    return rects, corners


def _chevron_arms(rects: list, corners: list) -> np.ndarray:
    """Which straight narrow pieces are a chevron's arms, not lines: two that meet
    end to end (within :data:`CHEVRON_GAP` of their widths: the opening took the
    wider apex) turned at least :data:`CHEVRON_TURN_DEG` from each other (a
    herringbone print's chevrons whose four arms were taken for ruler lines split
    it in two: held-out 8 sheet 6, length -36.5 %). ``rects``, ``corners``: as
    :func:`_bar_field`'s. (k,) bool."""
    n = len(rects)
    out = np.zeros(n, bool)
    if n < 2:
        return out
    centre, long, wide, u, turn = _bars(rects, corners)
    ends = np.stack([centre - 0.5 * long[:, None] * u, centre + 0.5 * long[:, None] * u], 1)
    d = np.linalg.norm(ends[:, None, :, None, :] - ends[None, :, None, :, :], axis=-1)
    meet = d.min(axis=(2, 3)) <= CHEVRON_GAP * np.maximum(wide[:, None], wide[None, :])
    pair = meet & (turn >= CHEVRON_TURN_DEG)
    np.fill_diagonal(pair, False)
    return pair.any(axis=1)


def _piece_at(mask: np.ndarray, seed: tuple[int, int], *, corner: bool = False):
    """The 8-connected piece of ``mask`` holding pixel ``seed``, cropped to its box.

    The same pixels as the piece of ``components_with_stats(mask)`` holding ``seed``
    (``labels[box] == labels[seed]``), found by a flood fill from the seed: its cost
    is the piece's, not the whole mask's labelling (a pooled letter sheet, 2 Mpx).

    Parameters
    ----------
    mask : (h, w) bool
        Ink.
    seed : (row, col) int [px]
        An ink pixel.

    corner : bool
        Return the box's first row and column too.

    Returns
    -------
    (bh, bw) uint8
        1 on the piece, 0 elsewhere, in the piece's bounding box; with ``corner``,
        this and the box's (row, col) [px].
    """
    import cv2

    h, w = mask.shape
    fill = np.zeros((h + 2, w + 2), np.uint8)  # (OpenCV's frame of one pixel)
    flags = 8 | cv2.FLOODFILL_MASK_ONLY | (1 << 8)  # 8-connected, the mask set to 1
    img = np.ascontiguousarray(mask).view(np.uint8)
    _, _, _, (x, y, bw, bh) = cv2.floodFill(
        img, fill, (int(seed[1]), int(seed[0])), 1, 0, 0, flags
    )
    crop = fill[y + 1 : y + 1 + bh, x + 1 : x + 1 + bw].copy()
    return (crop, (y, x)) if corner else crop


def _tiny_print(piece: np.ndarray, px_mm: float, opts: AnalysisOptions) -> bool:
    """Whether an ink piece (``piece``: uint8 crop of its box, :func:`_piece_at`)
    is a tiny print: its hull under ``SMALL_PRINT_MM2``, at least
    ``min_patch_width_mm`` wide and inked over ``SMALL_PRINT_FILL`` of it once its
    pores and notches narrower than a stroke are closed (a track tire's file tread
    print, 12 x 2.8 mm at 150 dpi: its spine between the pattern's teeth is a
    straight bar under two strokes wide, taken for a ruler's line; the print went
    missing). A line with its ticks, or across a print, is wider or fills less."""
    import cv2

    pts = outline_points(piece)
    (_, _), (a, b), _ = cv2.minAreaRect(pts)
    if px_to_mm_length(min(a, b) + 1, px_mm) < opts.min_patch_width_mm:
        return False
    if area_px_to_mm2(cv2.contourArea(cv2.convexHull(pts)), px_mm) >= SMALL_PRINT_MM2:
        return False
    return _closed_fill(piece.view(bool), mm_to_px_length(opts.stroke_width_mm, px_mm)) >= (
        SMALL_PRINT_FILL
    )


def _line_run(piece: np.ndarray, px_mm: float, opts: AnalysisOptions) -> np.ndarray:
    """The pixels of ``piece`` (uint8 crop) on a straight line through it: within a
    stroke of the line fitted to the piece (least squares on up to
    :data:`LINE_FIT_POINTS` of its pixels, refitted twice to the pixels near it),
    when they hold at least half the piece, lie no wider than two strokes and run
    for ``line_length_mm`` with no gap over a stroke; else none."""
    import cv2

    ys, xs = np.nonzero(piece)
    pts = np.column_stack([xs, ys]).astype(np.float32)
    reach = mm_to_px_length(opts.stroke_width_mm, px_mm)
    near = np.ones(len(pts), bool)
    for _ in range(3):  # least squares, then on the pixels near the line, twice
        use = pts[near][:: max(1, int(near.sum()) // LINE_FIT_POINTS)]  # a subsample
        vx, vy, x0, y0 = cv2.fitLine(use, cv2.DIST_L2, 0, 0.01, 0.01).ravel()
        off = (pts - [x0, y0]) @ np.array([-vy, vx])
        near = np.abs(off) <= reach
        if not near.any():
            return np.zeros(piece.shape, np.uint8)
    out = np.zeros(piece.shape, np.uint8)
    if near.sum() < 0.5 * len(pts) or np.ptp(off[near]) + 1 > 2.0 * reach:
        return out
    along = np.sort((pts[near] - [x0, y0]) @ np.array([vx, vy]))
    runs = np.split(along, np.flatnonzero(np.diff(along) > reach) + 1)
    run = max(runs, key=np.ptp)
    if px_to_mm_length(np.ptp(run) + 1, px_mm) < opts.line_length_mm:
        return out
    out[ys[near], xs[near]] = 1
    return out


def _attached_thin(thick_lab, thin_lab, thin_stats, thick_stats, k: int) -> int:
    """Pixels of the thin pieces touching thick blob ``k``."""
    import cv2

    x, y, w, h = thick_stats[k, :4]
    r0, c0 = max(y - 1, 0), max(x - 1, 0)
    box = (slice(r0, y + h + 1), slice(c0, x + w + 1))
    ring = cv2.dilate((thick_lab[box] == k).view(np.uint8), np.ones((3, 3), np.uint8))
    ids = np.unique(thin_lab[box][ring.astype(bool)])
    ids = ids[ids > 0]
    return int(thin_stats[ids, cv2.CC_STAT_AREA].sum())


def _groups_of_elements(
    parts: _Parts, pooled: _Pooled, opts: AnalysisOptions, bridge=None, drop=None
) -> PartsJoined:
    """:func:`_joined_elements`, with each punch hole (:func:`_punch_holes`) a group
    of its own, joined to none (``is_print`` sets it aside)."""
    holes = _punch_holes(parts, pooled) if parts.n_thick else np.zeros(0, bool)
    if not holes.any():
        return _joined_elements(parts, pooled, opts, bridge, drop)
    joined = _joined_elements(parts, pooled, opts, bridge, _either(drop, holes))
    return _own_groups(joined, holes if drop is None else holes & ~drop)


def _joined_elements(
    parts: _Parts, pooled: _Pooled, opts: AnalysisOptions, bridge=None, drop=None
) -> PartsJoined:
    """Print index of each thick element (footprint rule, hull overlaps, tip blocks
    and parts side by side: :func:`inkprint.group.join_tips`,
    :func:`inkprint.group.join_side_by_side`) and the doubtful joins. The ``bridge``
    pixels (lines taken out) count as the ink of the nearest element, so a line
    that crossed a print does not widen the gap between its two sides. ``drop``
    ((n,) bool): elements set aside (bold pen strokes), grouped with none (index
    -1)."""
    import cv2

    n = parts.n_thick
    if n == 0:
        return PartsJoined(np.zeros(0, int), np.zeros(0), np.zeros(0, bool))
    labels, box = parts.thick, parts.box
    if drop is not None:
        labels = labels.copy()  # (no element outside the box)
        sub = labels[box] if box is not None else labels
        sub[...] = np.where(np.r_[False, drop][sub], 0, sub)
    own = labels  # (the hulls: without the bridges)
    if bridge is not None and bridge.any():
        reach = mm_to_px_length(
            opts.stroke_width_mm + BRIDGE_MM, pooled.px_mm
        )  # a line's width, a groove
        labels = _bridged(labels, bridge, reach)
        wbox = None  # (the bridges may reach out of the box)
    else:
        wbox = box
    step = max(1, int(mm_to_px_length(GRAPH_STEP_MM, pooled.px_mm)))
    graph = element_graph(labels, n, px_mm=pooled.px_mm, step=step, box=wbox)
    link = linked_edges(graph, options=opts)
    comp = union_labels(n, graph.a[link], graph.b[link])
    comp = merge_overlapping(_hulls(own, comp, box=box), comp)
    sizes = parts.thick_stats[1:, cv2.CC_STAT_AREA].astype(float)
    comp = join_tips(graph, comp, sizes, options=opts)
    hulls = _hulls(own, comp, box=box)
    joined = join_side_by_side(graph, comp, hulls, px_mm=pooled.px_mm, options=opts)
    if joined.comp is not comp:
        merged = merge_overlapping(_hulls(own, joined.comp, box=box), joined.comp)
        if merged is not joined.comp:
            # the hull of joined ribs overlapping another group: one print with it
            joined = _regrouped(joined, merged)
    if drop is None or not drop.any():
        return joined
    return _regrouped(joined, np.where(drop, -1, joined.comp))


def _punch_holes(parts: _Parts, pooled: _Pooled) -> np.ndarray:
    """Which thick elements are punch holes of the page: discs of a hole's size and
    place (:func:`inkprint.group._hole_sized`) as much inked as the disc inscribed in
    their box, to :data:`HOLE_DISC`. A hole 5 mm off a knobby print continued its
    knobs' pattern and joined it (held-out set 5 sheet 87: width +26.7 %); a knob
    is square (4 / pi of its disc), a letter hollow. (n,) bool."""
    import cv2

    st = parts.thick_stats[1:].astype(float)
    w, h, area = st[:, 2], st[:, 3], st[:, 4]
    rows, cols = pooled.mask.shape
    cx, cy = st[:, 0] + 0.5 * w, st[:, 1] + 0.5 * h
    edge = np.minimum.reduce([cx, cy, cols - cx, rows - cy])
    sized = _hole_sized(
        *(px_to_mm_length(v, pooled.px_mm) for v in (np.maximum(w, h), np.minimum(w, h), edge))
    )
    hole = sized & (np.abs(area / (0.25 * np.pi * w * h) - 1.0) <= HOLE_DISC)
    for i in np.flatnonzero(hole):
        # ... and a disc: it fills its least enclosing circle (a square knob the
        # print's outline rounded at one corner inks its box's disc, not its circle:
        # held-out seed 8 sheet 93, set aside as a hole, hull area -20 %)
        x, y = int(st[i, 0]), int(st[i, 1])
        piece = (parts.thick[y : y + int(h[i]), x : x + int(w[i])] == i + 1).view(np.uint8)
        (_, _), r = cv2.minEnclosingCircle(cv2.findNonZero(piece))
        hole[i] = area[i] >= HOLE_CIRCLE * np.pi * (r + 0.5) ** 2
    return hole


def _own_groups(joined: PartsJoined, elements: np.ndarray) -> PartsJoined:
    """``joined`` with each of ``elements`` ((n,) bool, grouped with none) a group
    of its own, after the others."""
    k = len(joined.doubt_gap)
    idx = np.flatnonzero(elements)
    comp = joined.comp.copy()
    comp[idx] = k + np.arange(len(idx))
    extra = np.zeros(len(idx))
    return PartsJoined(
        comp, np.r_[joined.doubt_gap, extra], np.r_[joined.doubt_joined, extra.astype(bool)]
    )


def _regrouped(joined: PartsJoined, comp: np.ndarray) -> PartsJoined:
    """``joined`` with its groups mapped to ``comp`` (each element's new group, -1:
    none), renumbered 0..k-1; a new group's doubt is the largest of its old ones."""
    used = np.unique(comp[comp >= 0])
    new = np.where(comp >= 0, np.searchsorted(used, comp), -1)
    to_new = np.full(len(joined.doubt_gap), -1)
    to_new[joined.comp] = new
    keep = to_new >= 0
    gap = np.zeros(len(used))
    np.maximum.at(gap, to_new[keep], joined.doubt_gap[keep])
    was = np.zeros(len(used), bool)
    np.logical_or.at(was, to_new[keep], joined.doubt_joined[keep])
    return PartsJoined(new, gap, was)


def _bridged(labels: np.ndarray, bridge: np.ndarray, reach: float) -> np.ndarray:
    """``labels`` with the ``bridge`` pixels within ``reach`` [px] of an element
    labelled as the nearest one. Computed in the bridge's box grown by the farthest
    a distance of ``reach`` can run (OpenCV's 3x3 L2 distance steps at least 0.955
    px a pixel), which holds every element pixel that near."""

    rows = np.flatnonzero(bridge.any(axis=1))
    cols = np.flatnonzero(bridge.any(axis=0))
    m = int(np.ceil(reach / 0.955)) + 2
    h, w = labels.shape
    box = (
        slice(max(rows[0] - m, 0), min(rows[-1] + m + 1, h)),
        slice(max(cols[0] - m, 0), min(cols[-1] + m + 1, w)),
    )
    lab = labels[box]
    if not (lab > 0).any():
        return labels
    dist, nearest, lut = _nearest_label(lab)
    out = labels.copy()
    out[box] = np.where(bridge[box] & (lab == 0) & (dist <= reach), lut[nearest], lab)
    return out


def _nearest_label(labels: np.ndarray) -> tuple:
    """Distance [px] of every pixel to the nearest labelled one (``labels`` > 0),
    the index of that pixel (OpenCV's Voronoi cells) and the table from index to
    its label: ``lut[nearest]`` labels every pixel as its nearest labelled one."""
    import cv2

    dist, nearest = cv2.distanceTransformWithLabels(
        (labels == 0).view(np.uint8), cv2.DIST_L2, 3, labelType=cv2.DIST_LABEL_PIXEL
    )
    on = labels > 0
    lut = np.zeros(int(nearest.max()) + 1, np.int32)
    lut[nearest[on]] = labels[on]
    return dist, nearest, lut


def _hulls(labels: np.ndarray, comp: np.ndarray, core=None, *, box=None) -> list:
    """Convex hull (cv2 float32 points, pooled x=col, y=row) of each group, from the
    ``core`` pixels of its elements where given and they are most of the element
    (a fine tread like a file pattern has little core: whole). ``box``: (rows, cols)
    slices holding every element with a margin of paper (:func:`_ink_box`), where
    the outlines are traced (the same outlines: traced in raster order from their
    first pixel; OpenCV's one-pixel frame of paper is paper there too)."""
    import cv2

    offset = (0, 0)
    if box is not None:
        labels = labels[box]
        core = core[box] if core is not None else None
        offset = (box[1].start, box[0].start)
    ink = labels > 0
    src = ink.view(np.uint8)
    if core is not None:
        n = len(comp) + 1
        on = np.flatnonzero(ink)  # (sums over the ink only)
        lab = labels.ravel()[on]
        share = np.bincount(lab[core.ravel()[on]], minlength=n) / np.maximum(
            np.bincount(lab, minlength=n), 1
        )
        cored = share >= 0.5
        cored[0] = False
        keep = np.where(cored[lab], core.ravel()[on], True)
        src = np.zeros(labels.size, np.uint8)
        src[on[keep]] = 1
        src = src.reshape(labels.shape)
    contours, _ = cv2.findContours(src, cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_SIMPLE, offset=offset)
    pts: list[list] = [[] for _ in range(int(comp.max()) + 1 if len(comp) else 0)]
    for c in contours:
        x, y = c[0, 0]
        g = comp[labels[y - offset[1], x - offset[0]] - 1]
        if g >= 0:  # (an element set aside belongs to no print)
            pts[g].append(c)
    return [cv2.convexHull(np.concatenate(p)).astype(np.float32) if p else None for p in pts]


@dataclass(frozen=True)
class _Bold:
    """Bold pen strokes among the thick ink (:func:`_bold_strokes`): the elements
    set aside ((n,) bool), the pixels set aside ((H, W) bool or None: those
    elements and the strokes cut from the prints' bodies) and a tread's bars cut
    from a body's rim and kept ((H, W) bool or None: they count into the print's
    hull as its core does)."""

    elements: np.ndarray
    pixels: np.ndarray | None
    bars: np.ndarray | None = None


def _bold_strokes(
    parts: _Parts, comp: np.ndarray, pooled: _Pooled, opts: AnalysisOptions, network=None
):
    """Bold pen strokes among the thick ink (a :class:`_Bold`). Marker letters whose
    strokes are wider than ``stroke_width_mm`` survive the opening as thick ink and
    the footprint rule links them to the print they touch (a label of 1.1-1.4 mm
    strokes touching a slick print, independent set 1 file 12: width +60 %,
    unflagged).

    A print's body: the core (ink wider than two strokes) of its elements that are
    mostly core, and of its elements at least ``line_length_mm`` long that are so
    once their holes are filled (a file tread's pores). Judged against the body's
    hull:

    * a piece of a body element outside its core (a letter one piece of ink with
      the print) reaching farther than ``bold_reach_mm`` out of it is a letter unless
      it inks ``bold_fill`` of what it adds to its element's hull (a tip, a corner);
      a nearer piece is one when joined to a letter. Only beside a body filling
      ``bold_body_fill`` of its hull (slick, file tread): a car print's shoulder
      bars between grooves stand out of its body like letters;
    * another element reaching farther than ``mark_overhang_mm`` out of it, with all
      the ink connected to it when that holds no body element (a letter apart from
      the print), else alone: lying along the outline (no deeper out of the hull
      than :data:`SLIVER_STROKES` strokes and ``sliver_elongation`` times longer: a
      tip sliver the outline cut) it is the print's; a compact blob (a tread block;
      a bold '0') is a letter only when the print has no such element inside the
      body's hull (its tread has no small blocks) and it lies within
      ``group_distance_mm`` of a letter, or of such a blob that does; any other
      shape (a letter, a scribble) is a letter."""
    n = parts.n_thick
    out = np.zeros(n, bool)
    if n == 0:
        return _Bold(out, None)
    judge = _BoldJudge(parts, comp, pooled, opts, network)
    pixels, bars = None, None
    for g in np.unique(comp[judge.cored | judge.long | judge.fine]):
        if g < 0:
            continue
        found = judge.print_strokes(np.flatnonzero(comp == g) + 1)
        if found is None:
            continue
        strokes, box, cut, tread = found
        out[strokes - 1] = True
        if cut.any():
            if pixels is None:
                pixels = np.zeros(parts.thick.shape, bool)
            pixels[box] |= cut
        if tread.any():
            if bars is None:
                bars = np.zeros(parts.thick.shape, bool)
            bars[box] |= tread
    return _Bold(out, pixels, bars)


class _BoldJudge:
    """The judgement of :func:`_bold_strokes`, print by print (its sheet-wide
    quantities computed once)."""

    def __init__(self, parts: _Parts, comp: np.ndarray, pooled: _Pooled, opts, network=None):
        st, px = parts.thick_stats, pooled.px_mm
        self.parts, self.pooled, self.opts, self.st = parts, pooled, opts, st
        box = parts.box if parts.box is not None else (slice(None), slice(None))
        core_px = np.bincount(parts.thick[box][parts.core[box]], minlength=parts.n_thick + 1)
        self.cored = core_px[1:] >= 0.5 * st[1:, 4]
        # a fine tread's elements: thin pieces of a field (:func:`_split`), or thick
        # elements that make one (:data:`FIELD_THICK_SPACING`)
        centres = st[:, :2] + 0.5 * st[:, 2:4]
        spacing = FIELD_THICK_SPACING * opts.fine_element_mm
        spaced = dataclasses.replace(opts, fine_spacing_mm=spacing)
        self.fine = _fine_fields(st, centres, px, spaced)[1:]
        if parts.fine is not None:
            self.fine |= parts.fine[1:]
        # the elements a line set aside touched (``network``: (H, W) bool or None)
        self.on_line = np.zeros(parts.n_thick + 1, bool)
        if network is not None:
            self.on_line = np.bincount(parts.thick[network], minlength=parts.n_thick + 1) > 0
        self.long = px_to_mm_length(np.maximum(st[1:, 2], st[1:, 3]), px) >= opts.line_length_mm
        self.lut = np.r_[0, comp]  # an element's print, -1: set aside
        self.over = mm_to_px_length(opts.mark_overhang_mm, px)
        self.cut_reach = mm_to_px_length(opts.bold_reach_mm, px)
        self.stroke_disk = _disk(mm_to_px_length(opts.stroke_width_mm, px))
        self.core_disk = _disk(mm_to_px_length(2.0 * opts.stroke_width_mm, px))
        # a sliver without core is thinner than two strokes; curving with the
        # outline its depth out of the hull's chords is more (a chevron print's tip,
        # independent set 1 file 36: 1.9 mm deep, 10.7 mm long)
        self.sliver = mm_to_px_length(SLIVER_STROKES * opts.stroke_width_mm, px)
        self.near = mm_to_px_length(opts.group_distance_mm, px)

    def judge(self, piece: np.ndarray, off: np.ndarray, hull: np.ndarray, reach: float) -> str:
        """'stroke', 'blob' or '' (the print's) for a piece (uint8 crop at ``off``)."""
        import cv2

        p = cv2.findNonZero(piece).reshape(-1, 2).astype(float) + off
        d = _outside_distance(p, hull)
        if d.max() <= reach:
            return ""
        across = d.max() - max(d.min(), 0.0) + 1.0
        if across <= self.sliver and max(piece.shape) >= self.opts.sliver_elongation * across:
            return ""  # along the outline: a sliver the outline cut
        return "blob" if _compact_piece(piece, COMPACT_ASPECT) else "stroke"

    def print_strokes(self, els: np.ndarray):
        """The letters of one print (its elements ``els``): the elements set aside,
        the print's box and the pixels cut from its body there; None without a body."""
        import cv2

        st = self.st
        x0, y0 = st[els, 0].min(), st[els, 1].min()
        box = (
            slice(y0, (st[els, 1] + st[els, 3]).max()),
            slice(x0, (st[els, 0] + st[els, 2]).max()),
        )
        local = self.parts.thick[box]
        body, is_body, field_area = self._body(els, local, box)
        if not body.any():
            return None
        hull = cv2.convexHull(outline_points(body)).reshape(-1, 2).astype(float)
        member = np.zeros(len(self.lut), bool)
        cut, rest, shaved = np.zeros(local.shape, bool), [], None
        solid = np.count_nonzero(body) / max(cv2.contourArea(hull.astype(np.float32)), 1.0)
        if solid >= self.opts.bold_body_fill:  # a slick or file tread body
            # (a pixel off the body: the opening shaves the outline's staircase, and
            # a ring of such pixels joined every letter's foot into one piece)
            shaved = cv2.dilate(body.view(np.uint8), np.ones((3, 3), np.uint8)).view(bool)
            member[els[is_body]] = True
            # (with the pores filled: a file tread's tip is a sliver full of them)
            mine = _filled(member[local].view(np.uint8)).view(bool)
            cut, rest = self._rim(local, body, mine, shaved, hull)
        kinds, reach = self._elements(els, is_body, box, hull)
        judged, (kinds, word) = kinds, self._cut_blocks(els, kinds)
        kinds, blocks = self._repeated_blocks(els, kinds)
        if field_area:
            kinds = self._field_kinds(els, kinds, field_area)
        sizes = self._block_sizes(els, kinds)
        if sizes is not None:  # the tread's blocks, and the rim's pieces as large
            kinds = {
                i: ("" if k == "blob" and sizes[0] <= st[els[i], 4] <= sizes[1] else k)
                for i, k in kinds.items()
            }
            cut = _without_pieces(cut, sizes)
        strokes = [i for i, k in kinds.items() if k == "stroke"]
        # a herringbone's bars off a centre rib, apart or cut from it
        bars, kept = self._tread_bars(els, strokes, cut, box, hull)
        strokes = [i for i, bar in zip(strokes, bars, strict=True) if not bar]
        cut, tread = kept, cut & ~kept  # (the bars cut from the rim: the print's)
        member[:] = False
        member[els[strokes]] = True
        # (and letters set aside by an earlier pass, grouped with the print then)
        taken = cut | member[local] | (self.lut[local] < 0)
        if not taken.any():
            return els[:0], box, cut, tread
        blobs = [i for i, k in kinds.items() if k == "blob"]
        if blobs and not (~is_body & ~reach).any():
            # no element like a block inside the body's hull (its tread has none):
            # the blobs chained to a stroke within the distance are letters too
            strokes += self._chained(blobs, els, local, taken)
        # a label's letter taken for a cut copy of a tread element (an 'l' for a
        # chevron's arm) is one of the letters chained to it (held-out set 2 file 45:
        # 'Pirelli 33mm' 3 mm off a chevron print; 'l' and 'i' were the print's)
        copies = [
            i for i, k in judged.items() if k == "stroke" and kinds[i] == "" and i not in blocks
        ]
        if copies and len(strokes) >= LABEL_LETTERS:
            strokes += self._chained(copies, els, local, taken)
        if word:
            # (the word's next letters on its line, whatever their kind: 'run 18'
            # beside a siped print, 'run' taken, the bold '18' kept as its body:
            # held-out 6 seed 1 sheet 60, length +16.7 %)
            others = [i for i in range(len(els)) if i not in strokes]
            strokes += _on_the_line(self.st[els], word, others)
        if rest:
            self._feet(rest, taken, box, shaved, hull, cut)
        return els[strokes], box, cut, tread

    def _cut_blocks(self, els, kinds: dict) -> tuple[dict, list]:
        """``kinds`` with the strokes that are whole or cut copies of the print's
        own tread elements (:func:`inkprint.pattern.cut_copy`, with paper inside
        their hulls: under :data:`COMPACT_SOLIDITY`) set to '' (the print's). A
        siped print's blocks are combs of ribs; those the outline cut at its tips
        were set aside as a marker's letters (held-out seed 5 sheet 105: length
        -5.4 %, status ok). A label's letters are no copies of a tread's blocks.
        With the copies that are a word's letters (:meth:`_word`), strokes again."""
        from .pattern import cut_copy, typical_elements

        strokes = [i for i, k in kinds.items() if k == "stroke"]
        # (the typical elements of the others: a label's letters below a slick
        # print's tip, 12 of its 14 elements, were its "tread", each letter a copy
        # of it: held-out set 1 file 30, width +226 %, unflagged)
        own = np.setdiff1d(np.arange(len(els)), strokes)
        refs = typical_elements(self.parts.thick, self.st, els[own]) if strokes else []
        if not refs:
            return kinds, []
        out = dict(kinds)
        copies = []
        for i in strokes:
            piece = _crop(self.parts.thick, self.st, els[i])
            if cut_copy(piece, refs, solid=COMPACT_SOLIDITY):
                out[i] = ""
                copies.append(i)
        # copies closer together than a block's side are no blocks of the lattice:
        # a word's letters ('run' beside a siped print, each like a block with its
        # sipe: held-out 6 seed 1 sheet 60, length +39.8 %, status ok)
        word = self._word(els, copies, own)
        for i in word:
            out[i] = "stroke"
        return out, word

    def _repeated_blocks(self, els, kinds: dict) -> tuple[dict, set]:
        """``kinds`` with the strokes that are a tread's blocks set to '' (the
        print's), and those blocks: when at least :data:`TREAD_BLOCKS` strokes are
        whole copies of one another (:func:`inkprint.pattern.copies_of_one`), those,
        the strokes as large (their boxes' sides within :data:`BLOCK_SIDE` of the
        copies' median, their areas within :data:`TREAD_BLOCK_SPREAD`: blocks the
        light or the scan made ragged) and the strokes that are cut copies of them
        (:func:`inkprint.pattern.cut_copy`: blocks the outline cut). A siped print's
        blocks are combs, each like a bold letter, and when only a few blocks print
        solid (their sipes closed, in a shadow) those few are the whole body and
        every other block was set aside as a letter (held-out 6 seed 2 sheet 63: a
        63 x 50 mm print of 37 blocks came out as one 7 x 4 mm block, status ok). A
        label does not repeat one letter so."""
        from .pattern import TRIES, copies_of_one, cut_copy

        strokes = np.asarray([i for i, k in kinds.items() if k == "stroke"], int)
        if len(strokes) < TREAD_BLOCKS:
            return kinds, set()
        st = self.st[els[strokes]]
        hit = copies_of_one(self.parts.thick, self.st, els[strokes])
        if hit.sum() < TREAD_BLOCKS:
            return kinds, set()
        side = np.median(st[hit, 2:4], axis=0)
        area = np.median(st[hit, 4])
        hit |= (np.abs(st[:, 2:4] / side - 1.0) <= BLOCK_SIDE).all(axis=1) & (
            np.abs(np.log(st[:, 4] / area)) <= np.log(TREAD_BLOCK_SPREAD)
        )
        refs = [
            np.pad(_crop(self.parts.thick, self.st, els[i]), 2).astype(np.float32)
            for i in strokes[hit][:: max(1, int(hit.sum()) // TRIES)]
        ]
        for j in np.flatnonzero(~hit):
            hit[j] = cut_copy(_crop(self.parts.thick, self.st, els[strokes[j]]), refs)
        blocks = {int(i) for i in strokes[hit]}
        return {i: ("" if i in blocks else k) for i, k in kinds.items()}, blocks

    def _word(self, els, copies: list, own: np.ndarray) -> list:
        """Of the ``copies`` (indices into ``els``), those in a chain of at least
        :data:`LABEL_LETTERS` whose boxes lie under :data:`WORD_GAP` times the
        print's own elements' gap (``own``: the median of each one's gap to its
        nearest) apart: a word's letters, not a lattice's cut blocks."""
        if len(copies) < LABEL_LETTERS or len(own) < 2:
            return []
        gap = np.median(_box_gaps(self.st[els[own], :4]).min(axis=1))
        d = _box_gaps(self.st[els[copies], :4])
        i, j = np.nonzero(np.triu(d < WORD_GAP * gap, 1))
        chain = union_labels(len(copies), i, j)
        sizes = np.bincount(chain)
        return [k for k, g in zip(copies, chain, strict=True) if sizes[g] >= LABEL_LETTERS]

    def _field_kinds(self, els, kinds: dict, field_area: float) -> dict:
        """``kinds`` judged beside a fine field (median element ``field_area`` [px]):
        a blob more than twice as large is a letter (the field's elements are alike,
        those the outline cut smaller); a stroke a line set aside touched, or more
        than :data:`FIELD_BAR_ASPECT` times longer than wide, is a line's piece, no
        letter (held-out 7 sheet 93: a ruler's 8 x 1.2 mm stub beyond a file print's
        tip, set aside as a letter, flagged the print), left to the lines' rules; so
        is a lone stroke (a label is two letters or more), but not a lone blob more
        than twice as large: a stub is long, a digit compact (the label sweep: a
        bold '4' touching a knurl print's side, width +16.6 %, status ok)."""
        out, grown = {}, set()
        for i, k in kinds.items():
            if k == "blob" and self.st[els[i], 4] > 2 * field_area:
                k = "stroke"
                grown.add(i)
            elif k == "stroke" and self.on_line[els[i]]:
                k = ""
            elif k == "stroke":
                _, a, b = _piece_shape(_crop(self.parts.thick, self.st, els[i]).view(np.uint8))
                k = "" if a > FIELD_BAR_ASPECT * b else k
            out[i] = k
        if sum(k == "stroke" for k in out.values()) < 2:  # a label has letters, a stub none
            out = {i: ("" if k == "stroke" and i not in grown else k) for i, k in out.items()}
        return out

    def _block_sizes(self, els, kinds: dict) -> tuple | None:
        """The range of areas [px] of the print's tread blocks: the largest set of
        at least :data:`TREAD_BLOCKS` of its blobs (``kinds``) within
        :data:`TREAD_BLOCK_SPREAD` of one another's area; None without one. A file
        shoulder's diamonds beside a slick centre rib reach out of its body like a
        marker's letters (a 64 x 20 mm print at 300 dpi came out as its rib alone,
        width -65 %, flagged)."""
        blobs = [i for i, k in kinds.items() if k == "blob"]
        if len(blobs) < TREAD_BLOCKS:
            return None
        area = np.sort(self.st[els[blobs], 4].astype(float))
        # for each blob as the smallest: how many lie within the spread above it
        top = np.searchsorted(area, TREAD_BLOCK_SPREAD * area, side="right")
        best = int(np.argmax(top - np.arange(len(area))))
        if top[best] - best < TREAD_BLOCKS:
            return None
        return area[best], area[top[best] - 1]

    def _tread_bars(self, els, strokes: list, cut: np.ndarray, box: tuple, hull) -> tuple:
        """Which of the strokes (element indices; (k,) bool) are a tread's bars, and
        ``cut`` (the strokes cut from the body's rim, bool over ``box``) without its
        pieces that are: straight (filling :data:`BAR_FILL` of their least
        rectangles) and side by side in a field (:func:`_bar_field`), the strokes and
        the rim's pieces together. A herringbone print's bars as wide as a marker's
        stroke, standing 1.2 mm off its centre rib, were set aside as bold letters
        (a 70 x 28 mm print came out as its rib alone: width -78 %, flagged); bars
        joined to the rib by a neck of ink were cut from its rim as letters (held-out
        14 sheet 21, 240 dpi: 14 bars, width -63 %, flagged). With a field found, the
        other strokes and pieces are judged again against the hull of the body and
        its bars (``hull``: the body's, (m, 2) (x, y) over the box): the short bars at
        its tips and the crescents the outline cut lie within it or along it."""
        out = np.zeros(len(strokes), bool)
        n_cut, cut_lab, cut_st = 0, None, None
        if cut.any():
            n_cut, cut_lab, cut_st, _ = components_with_stats(cut.view(np.uint8), connectivity=8)
            n_cut -= 1
        if len(strokes) + n_cut < BAR_FIELD_MIN:
            return out, cut
        rects, corners = _piece_rects(self.parts.thick, self.st, els[strokes])
        area = list(self.st[els[strokes], 4])
        if n_cut:
            r, c = _piece_rects(cut_lab, cut_st, range(1, n_cut + 1))
            rects += r
            corners += [(y + box[0].start, x + box[1].start) for y, x in c]
            area += list(cut_st[1:, 4])
        size = np.array([r[1] for r in rects], float) + 1
        straight = np.asarray(area, float) >= BAR_FILL * size[:, 0] * size[:, 1]
        if np.count_nonzero(straight) < BAR_FIELD_MIN:
            return out, cut
        idx = np.flatnonzero(straight)
        field = np.zeros(len(rects), bool)
        sel = [rects[j] for j in idx], [corners[j] for j in idx]
        field[idx] = _bar_field(*sel, self.pooled.px_mm)
        if not field.any():  # (a comb's teeth lie farther apart: all of this print)
            share = np.asarray(area, float)[idx] / self.st[els, 4].sum()
            owners = np.zeros(len(idx), int), share
            field[idx] = _comb_teeth(*sel, owners, self.pooled.px_mm)
        if not field.any():
            return out, cut
        crops = [_crop(self.parts.thick, self.st, k).view(np.uint8) for k in els[strokes]]
        crops += [_crop(cut_lab, cut_st, k).view(np.uint8) for k in range(1, n_cut + 1)]
        field |= self._beside_field(field, rects, corners, crops, box, hull)
        out = field[: len(strokes)]
        if field[len(strokes) :].any():
            bar = np.r_[False, field[len(strokes) :]]
            cut = cut & ~bar[cut_lab]
        return out, cut

    def _beside_field(self, field, rects, corners, crops, box, hull) -> np.ndarray:
        """Which of the pieces outside a field of bars (``field``, (k,) bool; their
        ``rects`` and ``corners`` as :func:`_bar_field`'s, sheet (row, col) [px];
        ``crops``: each in its box) lie within or along the hull of the body
        (``hull``, (m, 2) (x, y) over ``box``) and the field's bars: the short bars
        at a herringbone's tips, the crescents its outline cut. (k,) bool."""
        import cv2

        origin = np.array([box[1].start, box[0].start], float)
        pts = [hull] + [
            cv2.boxPoints(rects[j]) + np.array([corners[j][1], corners[j][0]]) - origin
            for j in np.flatnonzero(field)
        ]
        grown = cv2.convexHull(np.concatenate(pts).astype(np.float32)).reshape(-1, 2)
        out = np.zeros(len(field), bool)
        for j in np.flatnonzero(~field):
            off = np.array([corners[j][1], corners[j][0]], float) - origin
            out[j] = not self.judge(crops[j], off, grown.astype(float), self.over)
        return out

    def _body(self, els, local, box) -> tuple:
        """The print's body (bool over its box), which of ``els`` make it and, when
        it is a fine field, the field's median element area [px] (else None).

        A print holding a fine field (``fine_min_elements`` of its elements a fine
        tread's: dots, knurl) has that field for body when no element has a core
        (none wider than two strokes), and no short element (under
        ``line_length_mm``: a letter, not a rib or a slick centre) reaching more
        than ``mark_overhang_mm`` out of the field's hull is in it. The field must
        hold :data:`FIELD_SHARE` of the print's ink (a file tread at 150 dpi, some
        of its slanted bars a field, the others reaching out of it: 277 of them set
        aside as letters, the print in four pieces). A marker label
        overlapping a dot-field print had its letters grouped with the dots
        (held-out 12 sheet 64: 'run 11' across its tip, length +40 %; held-out 8
        sheet 119: 'F=840N' over its shoulder, bold digits with a core, width
        +9.9 %; both unflagged)."""
        import cv2

        cored = self.cored[els - 1].copy()
        fine = self.fine[els - 1]
        area = None  # the field's median element [px]
        member = np.zeros(len(self.lut), bool)
        area_of = self.st[els, 4]
        if (
            np.count_nonzero(fine) >= self.opts.fine_min_elements
            and area_of[fine].sum() >= FIELD_SHARE * area_of.sum()
        ):
            member[els[fine]] = True
            field = member[local]
            area = float(np.median(self.st[els[fine], 4]))
            if not cored.any():
                return field, fine.copy(), area
            hull = cv2.convexHull(outline_points(field)).reshape(-1, 2).astype(float)
            x0, y0 = box[1].start, box[0].start
            for i in np.flatnonzero(cored & ~fine & ~self.long[els - 1]):
                x, y, w, h = self.st[els[i], :4]
                e = outline_points(local[y - y0 : y - y0 + h, x - x0 : x - x0 + w] == els[i])
                e = e.reshape(-1, 2) + np.array([x - x0, y - y0])
                cored[i] = _outside_distance(e.astype(float), hull).max() <= self.over
            member[:] = False
        member[els[cored]] = True
        body = member[local] & self.parts.core[box]
        is_body = cored
        for i in np.flatnonzero(~self.cored[els - 1] & self.long[els - 1]):
            el = (local == els[i]).view(np.uint8)  # its pores filled, then its core
            c = cv2.morphologyEx(_filled(el), cv2.MORPH_OPEN, self.core_disk).view(bool)
            if np.count_nonzero(c & el.view(bool)) >= 0.5 * np.count_nonzero(el):
                is_body[i] = True
                body |= c
        return _main_pieces(body, local), is_body, area

    def _rim(self, local, body, mine, shaved, hull) -> tuple:
        """The pieces of the body's elements outside the body: the strokes cut (bool
        over the box) and the others (a letter's foot when joined to a letter)."""

        cut, rest = np.zeros(local.shape, bool), []
        rim = (mine & ~shaved).view(np.uint8)
        if not rim.any():
            return cut, rest
        m, rl, rs, _ = components_with_stats(rim, connectivity=8)
        for c in range(1, m):
            x, y, w, h = rs[c, :4]
            piece = (rl[y : y + h, x : x + w] == c).view(np.uint8)
            where = (slice(y, y + h), slice(x, x + w), piece.view(bool))
            if max(w, h) + 2 <= self.cut_reach:  # (a piece a pixel off the body: no)
                rest.append(where)
                continue
            kind = self.judge(piece, np.array([x, y], float), hull, self.cut_reach)
            if kind:  # a tip or a corner the opening cut extends its element convexly
                e = local == local[_first_pixel(rl, rs, c)]
                own = outline_points(body & e)
                fill = 0.0
                if own is not None:
                    fill = _hull_fill(self._inked(body & e, where), own, where)
                # a bar standing out of a slick print is no tread block
                kind = "" if fill >= self.opts.bold_fill else "stroke"
            if kind == "stroke":
                cut[where[:2]] |= where[2]
            else:
                rest.append(where)
        return cut, rest

    def _inked(self, core: np.ndarray, where: tuple) -> np.ndarray:
        """The ink of a piece (``where``: its rows, cols and bool crop) with its
        element's core ``core`` (bool over the box), the pores between them closed,
        in a window about the piece as large again each way (bool over the box; the
        other pieces of the body's elements left out: a marker label lying along a
        slick print, its letters joined to it side by side, filled each other's
        hulls)."""
        import cv2

        rows, cols, piece = where
        h, w = rows.stop - rows.start, cols.stop - cols.start
        r0, c0 = max(rows.start - h, 0), max(cols.start - w, 0)
        win = (slice(r0, rows.stop + h), slice(c0, cols.stop + w))
        ink = core[win].view(np.uint8).copy()
        ink[rows.start - r0 : rows.stop - r0, cols.start - c0 : cols.stop - c0] |= piece
        # (the pores the outline cut closed too: a file tread's tip is ragged with
        # them, 5001 file 100 at 150 dpi)
        ink = cv2.morphologyEx(np.pad(ink, 1), cv2.MORPH_CLOSE, self.stroke_disk)[1:-1, 1:-1]
        out = np.zeros(core.shape, bool)
        out[win] = ink.view(bool)
        return out

    def _elements(self, els, is_body, box, hull) -> tuple:
        """The kind of each other element reaching out of the body's hull, judged
        with the ink joined to it (alone when that holds a body element), and which
        of ``els`` reach out of it."""
        st, lab = self.st, self.parts.thick
        x0, y0 = box[1].start, box[0].start
        reach = np.zeros(len(els), bool)
        # (an element whose box lies within the hull lies within it: its box's
        # corners judge most elements of a print at once)
        others = np.flatnonzero(~is_body)
        x, y, w, h = (st[els[others], j] for j in range(4))
        corners = np.stack([x, y, x + w - 1, y, x, y + h - 1, x + w - 1, y + h - 1], 1)
        corners = corners.reshape(-1, 2) - np.array([x0, y0])
        out = _outside_distance(corners.astype(float), hull).reshape(-1, 4).max(1) > self.over
        for i in others[out]:
            x, y, w, h = st[els[i], :4]
            e = outline_points(lab[y : y + h, x : x + w] == els[i]).reshape(-1, 2)
            reach[i] = _outside_distance(e + np.array([x - x0, y - y0]), hull).max() > self.over
        kinds = {}  # element index -> 'stroke' | 'blob' | ''
        if not reach.any():
            return kinds, reach
        # the ink's pieces about the print (a margin of group_distance_mm: a letter's
        # ink lies about its thick ink)
        m = int(np.ceil(self.near))
        H, W = lab.shape
        wy, wx = max(y0 - m, 0), max(x0 - m, 0)
        win = (slice(wy, min(box[0].stop + m, H)), slice(wx, min(box[1].stop + m, W)))
        _, ink_lab, ink_st, _ = components_with_stats(self.pooled.mask[win], connectivity=8)
        local = lab[box]  # each element's ink piece
        idmap = np.zeros(len(self.lut), ink_lab.dtype)
        idmap[local[local > 0]] = ink_lab[y0 - wy :, x0 - wx :][
            : local.shape[0], : local.shape[1]
        ][local > 0]
        ids = idmap[els]
        for i in np.flatnonzero(reach):
            c = ids[i]
            if c in ids[is_body]:  # joined to the body by thin ink: the element alone
                x, y, w, h = st[els[i], :4]
                piece = (lab[y : y + h, x : x + w] == els[i]).view(np.uint8)
            else:
                x, y, w, h = ink_st[c, :4]
                piece = (ink_lab[y : y + h, x : x + w] == c).view(np.uint8)
                x, y = x + wx, y + wy
            kinds[i] = self.judge(piece, np.array([x - x0, y - y0], float), hull, self.over)
        return kinds, reach

    def _chained(self, blobs: list, els, local, taken) -> list:
        """Of the blobs (element indices), those within ``group_distance_mm`` of the
        ink ``taken`` (strokes), or of such a blob that is (``taken`` grows)."""
        import cv2

        out, grow = [], True
        while grow and blobs:
            dist = cv2.distanceTransform((~taken).view(np.uint8), cv2.DIST_L2, 3)
            grow = False
            for i in list(blobs):
                if dist[local == els[i]].min() <= self.near:
                    out.append(i)
                    blobs.remove(i)
                    taken |= local == els[i]
                    grow = True
        return out

    def _feet(self, rest: list, taken, box, shaved, hull, cut) -> None:
        """Add to ``cut`` the pieces of ``rest`` that are a letter's foot: joined to
        a letter (``taken``) by ink outside the body, or within a stroke of it, and
        reaching out of the body's hull."""
        import cv2

        _, joined, _, _ = components_with_stats(self.pooled.mask[box] & ~shaved, connectivity=8)
        ids = np.unique(joined[taken & ~shaved])
        grown = cv2.dilate(taken.view(np.uint8), self.stroke_disk).view(bool)
        for rows, cols, piece in rest:
            if not (
                (grown[rows, cols] & piece).any()
                or np.isin(joined[rows, cols][piece], ids[ids > 0]).any()
            ):
                continue
            if _reach(piece.view(np.uint8), np.array([cols.start, rows.start]), hull) > 0:
                cut[rows, cols] |= piece


def _on_the_line(boxes: np.ndarray, word: list, blobs: list) -> list:
    """Of ``blobs`` (indices into ``boxes``, (n, >= 4) x, y, w, h [px]), those on
    the line of the letters ``word`` (indices, at least two) and next to it, chained
    one by one: each within the line's band across it (half its own height or more
    inside, no taller than :data:`LINE_MATE_HEIGHT` bands, its box no larger than
    as many times the largest letter's) and less than a band from the word's ends
    along it."""
    b = np.asarray(boxes[:, :4], float)
    corners = b[:, None, :2] + b[:, None, 2:4] * np.array([[0, 0], [1, 0], [0, 1], [1, 1]])
    c = b[word, :2] + 0.5 * b[word, 2:4]
    w, v = np.linalg.eigh(np.cov(c.T))
    u = v[:, np.argmax(w)]
    nrm = np.array([-u[1], u[0]])
    along, across = corners @ u, corners @ nrm  # (n, 4)
    lo, hi = across[word].min(), across[word].max()
    a0, a1 = along[word].min(), along[word].max()
    band, out, left = hi - lo, [], list(blobs)
    most = LINE_MATE_HEIGHT * b[word, 2:4].prod(axis=1).max()  # (no block's size)
    left = [i for i in left if b[i, 2:4].prod() <= most]
    grow = True
    while grow and left:
        grow = False
        for i in list(left):
            b0, b1 = across[i].min(), across[i].max()
            inside = min(b1, hi) - max(b0, lo)
            gap = max(along[i].min() - a1, a0 - along[i].max())
            if inside >= 0.5 * (b1 - b0) and b1 - b0 <= LINE_MATE_HEIGHT * band and gap < band:
                out.append(i)
                left.remove(i)
                a0, a1 = min(a0, along[i].min()), max(a1, along[i].max())
                grow = True
    return out


def _without_pieces(cut: np.ndarray, sizes: tuple) -> np.ndarray:
    """``cut`` (bool) less its pieces whose area [px] lies within ``sizes`` (low,
    high) or below: a tread block joined to the body by a neck, or its part."""
    if not cut.any():
        return cut
    _, lab, st, _ = components_with_stats(cut.view(np.uint8), connectivity=8)
    keep = st[:, 4] > sizes[1]
    keep[0] = False
    return keep[lab]


def _main_pieces(body: np.ndarray, local: np.ndarray) -> np.ndarray:
    """Of the body (bool), each element's largest piece (``local``: the elements'
    labels). An element is one piece of ink: its core in pieces means ink joined to
    it by a neck narrower than two strokes - a bold letter's bowl touching a slick
    print's tip (file 78 of independent set 10: a 'P' joined to the tip was part of
    the body, length +5.3 %, unflagged), not the print's body."""
    n, lab, st, _ = components_with_stats(body.view(np.uint8), connectivity=8)
    if n <= 2:
        return body
    el_of = np.zeros(n, np.int64)
    el_of[lab[body]] = local[body]
    area = st[:, 4]
    best = np.zeros(int(local.max()) + 1, area.dtype)
    np.maximum.at(best, el_of[1:], area[1:])
    keep = area >= best[el_of]
    keep[0] = False
    return keep[lab]


def _hull_fill(inked: np.ndarray, own: np.ndarray, where: tuple) -> float:
    """How much of what a piece (``where``: its rows, cols and bool crop in a box)
    adds to the hull of ``own`` (an element's core, outline points) is inked
    (``inked``, bool over the box): about 1 for a tip or a corner of a print
    (convex with it), far less for a stroke standing out of its edge (paper on
    either side of it)."""
    import cv2

    rows, cols, piece = where
    p = cv2.findNonZero(piece.view(np.uint8)).reshape(-1, 2) + np.array([cols.start, rows.start])
    core = cv2.convexHull(own)
    both = cv2.convexHull(np.concatenate([own.reshape(-1, 2), p]).astype(np.int32))
    grown = cv2.fillConvexPoly(np.zeros(inked.shape, np.uint8), both, 1)
    grown &= 1 - cv2.fillConvexPoly(np.zeros(inked.shape, np.uint8), core, 1)
    room = int(np.count_nonzero(grown))
    return float(np.count_nonzero(grown.view(bool) & inked)) / max(room, 1)


def _filled(piece: np.ndarray) -> np.ndarray:
    """A piece (uint8) with its holes filled (a closing would also fill the notch
    between a print and a letter's foot joined to it, and keep the foot)."""
    import cv2

    contours, _ = cv2.findContours(piece, cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_SIMPLE)
    return cv2.drawContours(np.zeros_like(piece), contours, -1, 1, cv2.FILLED)


def _reach(piece: np.ndarray, off: np.ndarray, hull: np.ndarray) -> float:
    """How far [px] a piece (uint8 crop at ``off``, (x, y)) reaches out of a hull."""
    import cv2

    return float(_outside_distance(cv2.findNonZero(piece).reshape(-1, 2) + off, hull).max())


def _either(a: np.ndarray | None, b: np.ndarray | None) -> np.ndarray | None:
    """The union of two masks, either of which may be None."""
    if a is None or b is None:
        return b if a is None else a
    return a | b


def _first_pixel(labels: np.ndarray, stats: np.ndarray, k: int) -> tuple[int, int]:
    """(row, col) of a pixel of piece ``k`` (on its box's top row)."""
    x, y, w = stats[k, :3]
    return int(y), int(x + np.argmax(labels[y, x : x + w] == k))


def _piece_shape(piece: np.ndarray) -> tuple[float, float, float]:
    """Solidity, longer and shorter side [px] of a piece (uint8 crop) after closing
    pinholes and one-pixel notches: a tread block inked near the threshold
    binarizes ragged (dpi72 seed 6 at 150 dpi: solidity 0.79 as is, set aside as a
    pen mark, length -1.2 %); a letter's counter (the hole of an 'o') is several
    pixels across and stays open."""
    import cv2

    crop = cv2.morphologyEx(
        np.pad(piece, 1), cv2.MORPH_CLOSE, np.ones((3, 3), np.uint8), borderValue=0
    )
    pts = cv2.findNonZero(crop)
    (_, _), (a, b), _ = cv2.minAreaRect(pts)
    hull = cv2.convexHull(pts)
    solid = hull_fill(len(pts), hull)
    return solid, max(a, b) + 1.0, min(a, b) + 1.0


def _compact_piece(piece: np.ndarray, aspect: float) -> bool:
    """Whether a piece (uint8 crop) is a compact blob: convex, filling
    :data:`COMPACT_SOLIDITY` of its hull (:func:`_piece_shape`), at most ``aspect``
    times longer than wide."""
    solid, a, b = _piece_shape(piece)
    return solid >= COMPACT_SOLIDITY and a <= aspect * b


def _line_kind(crop: np.ndarray, extent_mm: float, px_mm: float) -> tuple[str, str]:
    """What a long thin piece (its bool crop) is: line, gridlines, noise or text."""
    import cv2

    h, w = crop.shape
    fill = float(crop.mean())
    big = px_to_mm_length(min(h, w), px_mm)
    pts = cv2.findNonZero(crop.astype(np.uint8)).astype(np.float32)
    (_, _), (a, b), _ = cv2.minAreaRect(pts)
    aspect = max(a, b) / max(min(a, b), 1.0)
    size = f"{extent_mm:.0f} mm"
    if fill >= 0.2 and big >= 20:
        return "noise", f"pixel noise spread over {size}"
    if aspect >= 5:
        return "line", f"a straight line {size} long (a ruler or a drawn line)"
    if big >= 30:
        return "gridlines", f"gridlines over {size}"
    return "text", f"writing or a pen stroke {size} long"


def _hull_box(hull, shape) -> tuple | None:
    """Box (row0, row1, col0, col1, ends included) holding the pixels
    :func:`_hull_map` fills for a hull (its rounded vertices' box; None: no hull)."""
    if hull is None:
        return None
    p = np.round(hull).astype(np.int32).reshape(-1, 2)
    return (int(p[:, 1].min()), int(p[:, 1].max()), int(p[:, 0].min()), int(p[:, 0].max()))


def _hull_map(hulls: list, shape) -> np.ndarray:
    """Pooled map of the prints' hulls (0: none, k + 1: print k)."""
    import cv2

    out = np.zeros(shape, np.int32)
    for k, hull in enumerate(hulls):
        if hull is not None:
            cv2.fillPoly(out, [np.round(hull).astype(np.int32)], k + 1)
    return out


@dataclass(frozen=True)
class _ThinStats:
    """Per thin piece 1..n (index 0 unused): extent [mm], area [mm^2], gap to the
    nearest print hull and farthest reach out of it [mm], that print (-1: none),
    and the fraction of its pixels inside a hull."""

    extent: np.ndarray
    area: np.ndarray
    gap: np.ndarray
    reach: np.ndarray
    target: np.ndarray
    inside: np.ndarray
    touch: np.ndarray


def _thin_stats(parts: _Parts, hull_map, near: tuple, on: np.ndarray, pooled: _Pooled):
    """Statistics of the thin pieces (a :class:`_ThinStats`); ``on``: the thin
    pixels (flat indices, ascending), ``near``: :func:`_nearest_hull` at them."""
    import cv2

    n = parts.n_thin + 1
    st = parts.thin_stats
    extent = px_to_mm_length(
        np.maximum(st[:, cv2.CC_STAT_WIDTH], st[:, cv2.CC_STAT_HEIGHT]), pooled.px_mm
    )
    area = area_px_to_mm2(st[:, cv2.CC_STAT_AREA].astype(float), pooled.px_mm)
    near_dist, ids = near
    lab, d = parts.thin.ravel()[on], px_to_mm_length(near_dist, pooled.px_mm)
    gap, reach = np.full(n, np.inf), np.zeros(n)
    target = np.full(n, -1)
    if len(lab):
        order = np.lexsort((d, lab))
        first = order[np.r_[True, lab[order][1:] != lab[order][:-1]]]
        gap[lab[first]], target[lab[first]] = d[first], ids[first] - 1
        np.maximum.at(reach, lab, d)
    inside = np.bincount(lab, weights=(hull_map.ravel()[on] > 0), minlength=n) / np.maximum(
        st[:, cv2.CC_STAT_AREA], 1
    )
    thick_near = cv2.dilate((parts.thick > 0).view(np.uint8), np.ones((3, 3), np.uint8))
    touch = np.bincount(lab, weights=thick_near.ravel()[on], minlength=n) > 0
    return _ThinStats(extent, area, gap, reach, target, inside, touch)


def _compact(parts: _Parts, k: int, aspect: float | None = None, *, along: float = 0.0) -> bool:
    """Whether thin piece ``k`` is a compact blob (a clipped tread block: convex,
    filling :data:`COMPACT_SOLIDITY` of its hull, at most ``aspect`` (default
    :data:`COMPACT_ASPECT`) times longer than wide), not a stroke (a letter, a tick).
    With ``along`` > 0 (the piece lies along the print's outline, no thicker across
    it than ``mark_overhang_mm`` and ``sliver_elongation`` times longer), a sliver
    filling at least ``along`` (``sliver_solidity``) of its hull, of any length, is
    one too: a tread block the outline cut to a thin bar along the edge."""
    solid, a, b = _piece_shape(_crop(parts.thin, parts.thin_stats, k).view(np.uint8))
    if along > 0:
        return solid >= along
    return solid >= COMPACT_SOLIDITY and a <= (aspect or COMPACT_ASPECT) * b


def _judge_thin(t: _ThinStats, parts: _Parts, opts: AnalysisOptions, network=None, prints=None):
    """Per thin piece: the print it belongs to (-1: set aside), and the kind of mark
    for the short ones ('' for long ones, judged by shape later).

    Near a print (within ``group_distance_mm`` of its hull), a thin piece is the
    print's own when it is a dot, reaches no farther than ``mark_overhang_mm`` out
    of the hull (a rib's tail, a sliver along the edge), or, apart from the print's
    thick ink, is a compact blob (a clipped tread block). A pen stroke, a letter or a
    ruler's tick sticking out is not. A piece that was part of a line set aside
    (``network``: a ruler's tick, what a gridline touched) is the print's only as
    a compact blob (a tread block the line crossed).
    """
    long = t.extent >= opts.line_length_mm
    near = (t.target >= 0) & (t.gap <= opts.group_distance_mm)
    dot = t.extent <= opts.dot_mm
    own = near & (dot | (t.reach <= opts.mark_overhang_mm))
    on_line = np.zeros(len(own), bool)
    if network is not None:
        on_line = np.bincount(parts.thin[network], minlength=len(own)) > 0
        on_line[0] = False
    own &= ~on_line
    # lying along the outline: no thicker across it than the overhang allowed
    with np.errstate(invalid="ignore"):  # inf - inf: far from every print
        across = np.where(np.isfinite(t.gap), t.reach - t.gap, np.inf)
    along = (
        ~on_line
        & (across <= opts.mark_overhang_mm)
        & (t.extent >= opts.sliver_elongation * across)
    )
    for k in np.flatnonzero(near & ~own & (~t.touch | on_line) & ~long):
        aspect = LINE_COMPACT_ASPECT if on_line[k] else COMPACT_ASPECT
        own[k] = _compact(parts, k, aspect, along=opts.sliver_solidity if along[k] else 0.0)
    kind = np.where(long, "", np.where(dot, "dust", "text")).astype("<U6")
    if prints is not None:
        blocks = np.r_[_block_prints(parts, prints[1], prints[2], opts), False]
        # off a block pattern's tip a cut block lies a pattern gap out, which can
        # exceed group_distance_mm (a synth knob print's tip knob cut to 2.4 x 1.3
        # mm, 3.5 mm out: set aside as a pen mark, length -8.6 %, unflagged)
        reach = np.where(blocks[t.target], TIP_BLOCK_REACH, 1.0) * opts.group_distance_mm
        free = (t.target >= 0) & ~own & ~t.touch & ~on_line & ~long & ~dot
        beyond = free & blocks[t.target] & (t.gap > reach)
        beyond &= t.gap <= TIP_ROW_REACH * opts.group_distance_mm
        for p in np.unique(t.target[beyond]):
            rows = px_to_mm_length(
                _row_gap(parts, prints[1], p, prints[0][p], prints[2], opts), prints[2]
            )
            at = beyond & (t.target == p)
            reach[at] = np.maximum(reach[at], TIP_ROW_GAP * rows)
        cand = free & (t.gap <= reach)
        across = cand & (t.gap > TIP_BLOCK_REACH * opts.group_distance_mm)
        tip = _lone_tip_pieces(
            t, parts, cand, own, prints, opts, across=across, rows=blocks[t.target]
        )
        own |= tip & blocks[t.target]
        kind = np.where(tip & ~blocks[t.target], "sliver", kind)
    lens = np.zeros(len(own), bool)
    stroke = mm_to_px_length(opts.stroke_width_mm, prints[2]) if prints is not None else 0.0
    for k in np.flatnonzero(near & long & ~on_line & (t.inside < 0.5)):
        hull = prints[0][t.target[k]] if prints is not None else None
        piece = _crop(parts.thin, parts.thin_stats, k)
        lens[k] = _outer_rib(piece, parts.thin_stats[k, :2], hull, stroke)
    keep = np.where(long, (t.inside >= 0.5) | lens, own)
    owner = np.where(keep, t.target, -1)
    return owner, kind


def _outer_rib(piece: np.ndarray, origin, body: np.ndarray | None, stroke: float) -> bool:
    """Whether a long thin piece (bool crop whose corner is at ``origin``, (x, y)
    [px]) beside a print is its outer rib the outline cut, not a line: a lens
    (:func:`_lens`), or straight along ``body`` (the print's hull or outline points,
    (x, y) [px]; None: not judged) from tip to tip (:func:`_rib_along`)."""
    if _lens(piece.view(np.uint8)):
        return True
    if body is None:
        return False
    ys, xs = np.nonzero(piece)
    return _rib_along(np.column_stack([xs, ys]) + np.asarray(origin), body.reshape(-1, 2), stroke)


def _rib_along(piece: np.ndarray, hull: np.ndarray, stroke: float) -> bool:
    """Whether a long thin piece (its pixels ``piece``, (n, 2) (x, y) [px]) beside a
    print (its ``hull``, (m, 2) (x, y) [px]) is the print's outer rib the outline
    cut: straight (filling :data:`RIB_RECT_FILL` of its smallest box) and, along its
    own direction, running over :data:`RIB_SPAN` of the print's extent with both
    ends within a ``stroke`` [px] of the print's tips. A ruler's or a drawn line runs
    on beyond a tip; a rib cut from a rounded rectangle's side, as wide all along,
    is no lens (held-out seed 4 sheets 16 and 36: an 88 mm rib 1.7 mm wide and a
    20 mm one 1.35 mm wide set aside as ruler lines, width -10 % and -45 %,
    flagged)."""
    import cv2

    pts = np.asarray(piece, np.float32)
    (_, _), (a, b), ang = cv2.minAreaRect(pts)
    if len(pts) < RIB_RECT_FILL * (a + 1.0) * (b + 1.0):
        return False
    t = np.radians(ang if a >= b else ang + 90.0)
    d = np.array([np.cos(t), np.sin(t)])
    u = pts @ d
    v = np.asarray(hull, float) @ d
    return bool(
        u.min() >= v.min() - stroke
        and u.max() <= v.max() + stroke
        and np.ptp(u) >= RIB_SPAN * np.ptp(v)
    )


def _lens(piece: np.ndarray) -> bool:
    """Whether a long thin piece (uint8 crop) beside a print is a lens: convex
    (filling :data:`COMPACT_SOLIDITY` of its hull) and tapering to both ends (filling
    at most :data:`LENS_RECT_FILL` of its smallest box): a print's outer rib the
    outline cut, its own. A ruler's or a drawn line is as wide all along (held-out
    ribbed road prints: both outer ribs, 34-38 mm long and up to 1.5 mm wide, set
    aside as lines, width -21 and -25 % unflagged)."""
    solid, a, b = _piece_shape(piece)
    return solid >= COMPACT_SOLIDITY and np.count_nonzero(piece) <= LENS_RECT_FILL * a * b


def _lone_tip_pieces(
    t: _ThinStats, parts: _Parts, cand, own, prints: tuple, opts, *, across, rows
):
    """Which of the thin pieces ``cand`` ((n,) bool: near a print, apart from its thick
    ink, neither a dot nor a compact blob) lie alone off the ends of that print along
    its major axis (beyond 0.8 of its half-length from its centre), convex (filling
    :data:`TIP_SLIVER_SOLIDITY` of its hull), with no other piece longer than ``dot_mm``
    and not a print's ``own`` within twice ``group_distance_mm`` of it (a letter
    has its word about it, some touching the print; a label's '5' lay 3.05 mm from
    its 'E', mixed set 5001 file 24). A tread
    block the outline cut to a sliver at a print's tip (mixed set 5006 file 29 at 150
    dpi: 1.9 x 0.24 mm, 1.5 mm beyond the print; set aside as a pen mark, length
    -2.15 %, unflagged) and a lone pen stroke look alike there. ``prints``: the
    prints' hulls and the print of each thick element.

    Off a block pattern's print (``rows``, (n,) bool per piece), a row of such
    pieces off one tip, each cut across the print's major axis
    (:data:`TIP_ROW_ELONGATION`), is a row of the pattern's blocks the outline cut:
    they need not be alone from each other. ``across`` ((n,) bool): the pieces that
    must be cut across to count (those beyond ``TIP_BLOCK_REACH``)."""
    from .group import _at_the_ends

    hulls = prints[0]
    out = np.zeros(len(cand), bool)
    ks = np.flatnonzero(cand)
    if not len(ks):
        return out
    st = parts.thin_stats
    centre = st[:, :2] + 0.5 * st[:, 2:4]  # (x, y) of the boxes' centres
    for k in ks:
        hull = hulls[t.target[k]]
        if hull is not None and len(hull) >= 3:
            xy = hull.reshape(-1, 2).astype(float)
            out[k] = bool(_at_the_ends(xy, centre[k : k + 1], axis=_hull_axis(hull))[0])
        # the outline cuts a block to a convex piece; a letter ('4', 'B') fills
        # less of its hull (sweep of labels at tips: first letters of '4.5 bar',
        # 'B7' kept as tip blocks, length +5..+10 %, unflagged)
        if out[k]:
            solid = _piece_shape(_crop(parts.thin, st, k).view(np.uint8))[0]
            out[k] = solid >= TIP_SLIVER_SOLIDITY
    if not out.any():
        return out
    cut = np.zeros(len(cand), bool)  # cut across the print's major axis
    for k in np.flatnonzero(out):
        axis = _hull_axis(hulls[t.target[k]])
        ys, xs = np.nonzero(_crop(parts.thin, st, k))
        u = np.column_stack([xs, ys]) @ axis
        v = np.column_stack([xs, ys]) @ np.array([-axis[1], axis[0]])
        cut[k] = np.ptp(v) + 1.0 >= TIP_ROW_ELONGATION * (np.ptp(u) + 1.0)
    out &= cut | ~across
    # alone: no other piece longer than a dot, not the print's own, within the
    # distance (box to box), near the print or not (a word's next letters lie
    # farther from the print than the letter touching it); the others of a row of
    # slivers cut across off the same print do not count
    far = mm_to_px_length(2.0 * opts.group_distance_mm, prints[2])
    others = np.flatnonzero(~own & (t.extent > opts.dot_mm))
    others = others[others > 0]
    row = out & cut & rows
    ks = np.flatnonzero(out)
    gaps = _box_gaps(st[np.r_[ks, others], :4])[: len(ks), len(ks) :]  # (k, others)
    for k, gap in zip(ks, gaps, strict=True):
        mate = row[others] & (t.target[others] == t.target[k]) if row[k] else False
        out[k] = not ((gap <= far) & (others != k) & ~mate).any()
    return out


def _hull_axis(hull) -> np.ndarray:
    """The major axis (unit (x, y) vector) of a convex hull ((k, 1, 2) or (k, 2)
    (x, y) [px]) from the second moments of its area (its vertices' spread would
    lean toward where the outline has most corners)."""
    import cv2

    m = cv2.moments(np.asarray(hull, np.float32).reshape(-1, 1, 2))
    if m["m00"] <= 0:
        return np.array([1.0, 0.0])
    t = 0.5 * np.arctan2(2.0 * m["mu11"], m["mu20"] - m["mu02"])
    return np.array([np.cos(t), np.sin(t)])


def _row_gap(parts: _Parts, comp: np.ndarray, p: int, hull, px_mm: float, opts) -> float:
    """The gap [px] between consecutive rows of print ``p``'s blocks (thick
    elements at least ``tip_block_strokes`` strokes a side, squared) along the major
    axis of its ``hull`` ((k, 1, 2) or (k, 2) (x, y) [px]): the blocks' spans along
    the axis, merged where they overlap, leave the rows' gaps between them (staggered
    rows too); their median. 0 when they leave none (a chevron's or a turned
    pattern's rows overlap along the axis)."""
    side = mm_to_px_length(opts.tip_block_strokes * opts.stroke_width_mm, px_mm)
    ks = np.flatnonzero((comp == p) & (parts.thick_stats[1:, 4] >= side * side)) + 1
    if len(ks) < 2 or hull is None:
        return 0.0
    ax = _hull_axis(hull)
    turn = np.arctan2(ax[1], ax[0]) + np.radians(np.linspace(-ROW_TURN_DEG, ROW_TURN_DEG, 41))
    axes = np.stack([np.cos(turn), np.sin(turn)], axis=1)  # (a, 2)
    # each block's span along the axis from its own hull's corners: its box's corners
    # reach far past a block turned to the sheet (a knob lattice at 45 deg to it left
    # no gap between the boxes' spans; held-out 6 seed 2 sheet 19: a cut knob 4.7 mm
    # off a knobby print's tip set aside as a pen mark, length -5.4 %, status ok)
    corners = _corner_points(parts.thick, parts.thick_stats, ks)
    u = np.einsum("nkc,ac->ank", corners, axes)  # (a, n, m)
    u0, u1 = u.min(2), u.max(2)
    order = np.argsort(u0, axis=1)
    u0, u1 = np.take_along_axis(u0, order, 1), np.take_along_axis(u1, order, 1)
    gaps = u0[:, 1:] - np.maximum.accumulate(u1, axis=1)[:, :-1]  # (a, n - 1)
    gaps = np.where(gaps > 0, gaps, 0.0)
    # the rows' direction: where they leave the most paper between them (a
    # near-round print's hull axis may lean 10-20 degrees off its rows)
    best = gaps[np.argmax(gaps.sum(1))]
    best = best[best > 0]
    return float(np.median(best)) if len(best) else 0.0


def _corner_points(labels: np.ndarray, stats: np.ndarray, ks: np.ndarray) -> np.ndarray:
    """The corners of each element's convex hull: (n, m, 2) (x, y) [px] (pixel
    corners, each hull's last corner repeated to the longest's count m)."""
    import cv2

    hulls = []
    for k in ks:
        x, y, w, h = stats[k, :4]
        pts = cv2.findNonZero((labels[y : y + h, x : x + w] == k).view(np.uint8))
        hull = cv2.convexHull(pts).reshape(-1, 2).astype(float) + np.array([x, y], float)
        # (each pixel's four corners: a pixel's span is one wide)
        hulls.append((hull[:, None, :] + [[0, 0], [1, 0], [0, 1], [1, 1]]).reshape(-1, 2))
    m = max(len(h) for h in hulls)
    return np.stack([np.concatenate([h, np.repeat(h[-1:], m - len(h), 0)]) for h in hulls])


def _block_prints(parts: _Parts, comp: np.ndarray, px_mm: float, opts) -> np.ndarray:
    """Per print: whether its thick ink holds two or more blocks at least
    ``tip_block_strokes`` strokes a side (squared): a block pattern, whose tip blocks
    the outline can cut to slivers (see :func:`inkprint.group.thin_protrusions`)."""
    n = int(comp.max()) + 1 if len(comp) else 0
    side = mm_to_px_length(opts.tip_block_strokes * opts.stroke_width_mm, px_mm)
    big = parts.thick_stats[1:, 4] >= side * side
    ok = comp >= 0
    return np.bincount(comp[ok & big], minlength=n)[:n] >= 2


def _short_reason(kind: str, t: _ThinStats, k: int, opts: AnalysisOptions) -> str:
    if kind == "dust":
        return "a speck away from the prints"
    if kind == "sliver":
        return (
            f"a thin piece ({t.extent[k]:.1f} mm) alone off a print's tip: a sliver of "
            f"the print the outline cut, or a pen mark (the print is flagged)"
        )
    if t.target[k] >= 0 and t.gap[k] <= opts.group_distance_mm:
        return f"{TICK_REASON} {t.reach[k]:.1f} mm out of a print"
    return f"writing or a mark ({t.extent[k]:.1f} mm) away from the prints"


def _nearest_hull(
    hull_map: np.ndarray, reach_px: float, at: np.ndarray, boxes: list
) -> tuple[np.ndarray, np.ndarray]:
    """Distance [pooled px] to the nearest print hull and that print's map id, up to
    ``reach_px`` from the hulls (beyond: inf and 0; computed on the hulls' box only,
    and there around each cluster of hulls, :func:`_hull_clusters`), at the pixels
    ``at`` (flat indices into the map). ``boxes``: each hull's box in the map
    (:func:`_hull_box`)."""

    dist = np.full(len(at), np.inf, np.float32)
    ids = np.zeros(len(at), np.int32)
    on = (hull_map[::4, ::4] if hull_map.size > 4_000_000 else hull_map) != 0
    ys, xs = np.flatnonzero(on.any(axis=1)), np.flatnonzero(on.any(axis=0))  # the box
    if not len(ys) or not len(at):
        return dist, ids
    f = 4 if hull_map.size > 4_000_000 else 1
    pad = int(np.ceil(reach_px)) + f + 1
    h, w = hull_map.shape
    r0, r1 = max(ys.min() * f - pad, 0), min(ys.max() * f + pad + 1, h)
    c0, c1 = max(xs.min() * f - pad, 0), min(xs.max() * f + pad + 1, w)
    r, c = np.divmod(at, w)
    inside = (r >= r0) & (r < r1) & (c >= c0) & (c < c1)
    if not inside.any():
        return dist, ids
    rr, cc = r[inside], c[inside]
    d_at, id_at = np.full(len(rr), np.inf, np.float32), np.zeros(len(rr), np.int32)
    for br0, br1, bc0, bc1 in _hull_clusters(boxes, reach_px, (r0, r1, c0, c1)):
        sel = np.flatnonzero((rr >= br0) & (rr < br1) & (cc >= bc0) & (cc < bc1))
        if not len(sel):
            continue
        d, nearest, lut = _nearest_label(hull_map[br0:br1, bc0:bc1])
        d_k = d[rr[sel] - br0, cc[sel] - bc0]
        near = d_k <= reach_px  # (within the reach of one cluster only)
        d_at[sel[near]] = d_k[near]
        id_at[sel[near]] = lut[nearest[rr[sel[near]] - br0, cc[sel[near]] - bc0]]
    far = d_at > reach_px
    dist[inside] = np.where(far, np.inf, d_at)
    ids[inside] = np.where(far, 0, id_at)
    return dist, ids


def _hull_clusters(boxes: list, reach_px: float, box: tuple) -> list:
    """Boxes (row0, row1, col0, col1, ends excluded) of the distance transforms of
    :func:`_nearest_hull` within ``box``: one per cluster of hulls (``boxes``: each
    hull's (row0, row1, col0, col1), ends included; None: no hull), grown by the
    farthest a distance of ``reach_px`` runs (OpenCV's 3x3 L2 steps are at least
    0.955 px a pixel). Clusters' boxes closer than twice that are merged, so no
    other hull lies within ``reach_px`` of a cluster's grown box: there the
    transform of that box equals that of the whole map, the nearest labels
    included (every path from a hull within the reach stays in the box). Apart are
    only a sheet's separate prints (on the 8-print sheet a third fewer pixels)."""
    pad = int(np.ceil(reach_px / 0.955)) + 2
    out = [list(b) for b in boxes if b is not None]
    merged = True
    while merged:  # (a handful of prints: pairs checked until none is close)
        merged = False
        for i in range(len(out)):
            for j in range(i):
                a, b = out[i], out[j]
                if max(a[0] - b[1], b[0] - a[1], a[2] - b[3], b[2] - a[3]) <= 2 * pad:
                    out[j] = [min(a[0], b[0]), max(a[1], b[1]), min(a[2], b[2]), max(a[3], b[3])]
                    del out[i]
                    merged = True
                    break
            if merged:
                break
    r0, r1, c0, c1 = box
    return [
        (
            max(a[0] - pad, r0),
            min(a[1] + pad + 1, r1),
            max(a[2] - pad, c0),
            min(a[3] + pad + 1, c1),
        )
        for a in out
    ]


@dataclass(frozen=True)
class _Sorted:
    """One sorting pass on the pooled grid."""

    parts: _Parts
    comp: np.ndarray
    hulls: list
    hull_map: np.ndarray
    stats: _ThinStats
    owner: np.ndarray
    kind: np.ndarray
    doubt: tuple = ((), ())  # per print: doubtful side-by-side gap [mm], joined?
    bold_px: np.ndarray | None = None


def _sort_pooled(pooled: _Pooled, opts: AnalysisOptions, network=None, bridge=None) -> _Sorted:
    parts = _split(pooled, opts)
    joined = _groups_of_elements(parts, pooled, opts, bridge)
    bold = _bold_strokes(parts, joined.comp, pooled, opts, network)
    bars = bold.bars  # (of the last grouping)
    for _ in range(BOLD_PASSES):
        if not bold.elements.any():
            break
        # without the letters the prints' neighbours change: letters they kept
        # apart from a print may now join it (independent set 1 file 30: the rest of
        # a label took the print's place beside it, width +133 %)
        joined = _groups_of_elements(parts, pooled, opts, bridge, drop=bold.elements)
        more = _bold_strokes(parts, joined.comp, pooled, opts, network)
        bars = more.bars
        if not more.elements.any():
            break
        bold = _Bold(bold.elements | more.elements, _either(bold.pixels, more.pixels))
    comp = joined.comp
    core = parts.core if bars is None else parts.core | bars
    hulls = _hulls(parts.thick, comp, core, box=parts.box) if len(comp) else []
    hull_map = _hull_map(hulls, pooled.mask.shape)
    on = np.flatnonzero(parts.thin > 0)  # the thin pixels, flat
    reach = mm_to_px_length(opts.line_length_mm, pooled.px_mm)
    near = _nearest_hull(hull_map, reach, on, [_hull_box(h, hull_map.shape) for h in hulls])
    stats = _thin_stats(parts, hull_map, near, on, pooled)
    owner, kind = _judge_thin(stats, parts, opts, network, (hulls, comp, pooled.px_mm))
    owner[0] = -1
    for k in np.flatnonzero((stats.extent >= opts.line_length_mm) & (owner >= 0)):
        ids = hull_map[_box(parts.thin_stats, k)][_crop(parts.thin, parts.thin_stats, k)]
        if (ids > 0).any():  # the print holding most (a lens outside: the nearest)
            owner[k] = int(np.bincount(ids[ids > 0]).argmax()) - 1
    doubt = (joined.doubt_gap, joined.doubt_joined)
    bold_px = bold.pixels
    if bold.elements.any():  # the elements set aside, with the pieces of the others
        bold_px = (bold_px if bold_px is not None else False) | np.r_[False, bold.elements][
            parts.thick
        ]
    return _Sorted(parts, comp, hulls, hull_map, stats, owner, kind, doubt, bold_px)


@dataclass(frozen=True)
class _Band:
    """A straight line set aside, extended across its network's box: end points
    (x, y) and width, in sheet pixels."""

    p0: tuple
    p1: tuple
    width: float


def _line_pixels(crop: np.ndarray, px_mm: float) -> tuple[np.ndarray, list, float]:
    """The straight lines of a thin network (rulers, gridlines): their pixels (a bool
    crop), the lines themselves fitted to all their pixels (direction, a point and
    the range along the direction from it where the line is inked, crop pixels),
    and their width [px].

    Hough finds segments at least :data:`LINE_SEGMENT_MM` long; segments of one
    direction are split by their offset into lines, and each line is refitted to
    every network pixel along it (``cv2.fitLine``): a gridline crossing the sheet
    is placed to a fraction of a pixel, so its course under a print is known."""
    import cv2

    m = crop.view(np.uint8) * np.uint8(255)
    n = max(8, int(mm_to_px_length(LINE_SEGMENT_MM, px_mm)))
    segs = cv2.HoughLinesP(m, 1, np.pi / 360, threshold=n // 2, minLineLength=n, maxLineGap=2)
    if segs is None:
        return np.zeros(crop.shape, bool), [], 0.0
    # paper around the crop: a straight line that fills its own box (one along the
    # image's edge) has no paper in it, and its distances would be unbounded
    dt = cv2.distanceTransform(
        cv2.copyMakeBorder(m, 1, 1, 1, 1, cv2.BORDER_CONSTANT), cv2.DIST_L2, 3
    )
    width = float(np.ceil(2.0 * np.percentile(dt[1:-1, 1:-1][crop], 95))) + 1.0
    ys, xs = np.nonzero(crop)
    pts = np.column_stack([xs, ys]).astype(np.float32)
    fits = []  # (support [px], line, its pixels)
    for ang in _directions(segs.reshape(-1, 4).astype(float)):
        nrm = np.array([-np.sin(ang), np.cos(ang)])
        rho = pts @ nrm
        for r in _offsets(segs, nrm, width):
            near = np.abs(rho - r) <= width
            if near.sum() < n:
                continue
            vx, vy, x0, y0 = cv2.fitLine(pts[near], cv2.DIST_HUBER, 0, 0.01, 0.01).ravel()
            d = np.abs((pts - [x0, y0]) @ np.array([-vy, vx]))
            sup = d <= 0.5 * width + 1.0
            along = pts[sup] @ np.array([vx, vy]) - (x0 * vx + y0 * vy)
            line = (np.array([vx, vy]), (float(x0), float(y0)), (along.min(), along.max()))
            fits.append((len(np.unique(np.round(along))), line, sup))
    # a line is inked along most of the piece (a ruler's tick tips, or a short
    # stretch of the ruler, fit lines a few degrees off it: extended across the
    # box, five such bands took a 35 px swath out of a print the ruler crossed
    # and split it); one already taken is not taken again
    lines, on = [], np.zeros(len(pts), bool)
    span = float(max(crop.shape))
    for support, line, sup in sorted(fits, key=lambda f: -f[0]):
        if support < max(n, LINE_SUPPORT * min(span, _chord(crop.shape, line))):
            continue
        if np.count_nonzero(sup & ~on) < 0.5 * np.count_nonzero(sup):
            continue
        lines.append(line)
        on |= sup
    out = np.zeros(crop.shape, bool)
    out[ys[on], xs[on]] = True
    return out, lines, width


def _chord(shape, line) -> float:
    """Length [px] of a line (direction, point, ...) within a box of ``shape``."""
    (vx, vy), (x0, y0) = line[:2]
    h, w = shape
    ts = []
    for v, p, hi in ((vx, x0, w), (vy, y0, h)):
        if abs(v) > 1e-9:
            ts.append(sorted(((-0.5 - p) / v, (hi - 0.5 - p) / v)))
    lo = max(t[0] for t in ts)
    hi_ = min(t[1] for t in ts)
    return max(hi_ - lo, 0.0)


def _directions(segs: np.ndarray) -> list[float]:
    """Distinct directions [rad, in [0, pi)] of Hough segments (within 2 degrees)."""
    ang = np.arctan2(segs[:, 3] - segs[:, 1], segs[:, 2] - segs[:, 0]) % np.pi
    length = np.hypot(segs[:, 2] - segs[:, 0], segs[:, 3] - segs[:, 1])
    out: list[list] = []
    for a, w in sorted(zip(ang, length, strict=True)):
        if out and abs(a - out[-1][0]) < np.radians(2):
            out[-1][1].append((a, w))
        else:
            out.append([a, [(a, w)]])
    if len(out) > 1 and np.pi - out[-1][0] + out[0][0] < np.radians(2):
        out[0][1] += [(a - np.pi, w) for a, w in out.pop()[1]]  # wrap around 0 / pi
    return [float(np.average([a for a, _ in c[1]], weights=[w for _, w in c[1]])) for c in out]


def _offsets(segs: np.ndarray, nrm: np.ndarray, width: float) -> list[float]:
    """Distinct offsets along ``nrm`` of the segments' mid points (lines apart by
    more than two widths)."""
    mid = 0.5 * (segs[:, :2] + segs[:, 2:])
    rho = np.sort(mid @ nrm)
    groups = np.split(rho, np.flatnonzero(np.diff(rho) > 2 * width) + 1)
    return [float(np.median(g)) for g in groups if len(g)]


def _bands(lines: list, width: float, box, pooled: _Pooled) -> list:
    """Lines (crop coordinates) extended beyond their inked range by half its length
    on either side (their course under a print they cross; for a line spanning its
    piece's box, as far as the box's diagonal from its middle), in sheet pixels.
    Not by the box's diagonal whatever the line: a ruler's 5 mm tick extended over
    the ruler's length crossed the sheet."""
    q = pooled.q
    out = []
    for d, (x0, y0), (t0, t1) in lines:
        reach = 0.5 * (t1 - t0)
        a = (np.array([x0, y0]) + (t0 - reach) * d + 0.5) * q - 0.5
        b = (np.array([x0, y0]) + (t1 + reach) * d + 0.5) * q - 0.5
        off = np.array([box[1].start, box[0].start]) * q
        out.append(_Band(tuple(a + off), tuple(b + off), width * q))
    return out


def _lines(first: _Sorted, pooled: _Pooled, opts: AnalysisOptions) -> tuple:
    """Straight-line pixels of the long marks set aside (pooled bool), the whole
    networks they are part of, the lines extended (:class:`_Band`) and their marks.

    Taking only the lines (not the whole network) leaves what merely touches a line
    - a tread block a gridline crosses, a ruler's tick - to be judged on its own."""
    parts, st = first.parts, first.stats
    lines = np.zeros(pooled.mask.shape, bool)
    network = np.zeros(pooled.mask.shape, bool)
    marks, bands = [], []
    for k in np.flatnonzero((first.owner < 0) & (st.extent >= opts.line_length_mm)):
        if k == 0:
            continue
        box, crop = _box(parts.thin_stats, k), _crop(parts.thin, parts.thin_stats, k)
        kind, why = _line_kind(crop, st.extent[k], pooled.px_mm)
        if kind in ("line", "gridlines"):
            px, found, width = _line_pixels(crop, pooled.px_mm)
            if px.any():
                lines[box] |= px
                network[box] |= crop
                bands += _bands(found, width, box, pooled)
                area = area_px_to_mm2(int(np.count_nonzero(px)), pooled.px_mm)
                marks.append(_mark(kind, box[0], box[1], pooled, None, area, why))
    return lines, network, bands, marks


def sort_ink(mask, *, mm_per_px: float, options: AnalysisOptions | None = None) -> SortedInk:
    """Sort a sheet's ink into candidate prints and marks (see the module's notes).

    Parameters
    ----------
    mask : (rows, cols) bool
        Ink of the sheet.
    mm_per_px : float [mm / px]
    options : AnalysisOptions, optional
        Defaults when None.

    Returns
    -------
    SortedInk
    """
    mm_per_px = check_mm_per_px(mm_per_px)
    opts = resolve_options(options)
    mask = np.asarray(mask, bool)
    pooled = _pool(mask, mm_per_px, opts)
    first = _sort_pooled(pooled, opts)
    lines, network, bands, line_marks = _lines(first, pooled, opts)
    sorted_, grazed, lost = first, None, None
    if bands:  # take the lines out of the ink, bridge them inside prints, sort again
        bridge = mm_to_px_length(BRIDGE_MM, mm_per_px)
        graze = mm_to_px_length(opts.grid_graze_mm, mm_per_px)
        mask, lost, grazed = remove_lines(mask, bands, bridge_px=bridge, graze_px=graze)
        pooled = _pool(mask, mm_per_px, opts)
        # what the lines' ink touched is the line's too (a ruler's tick): a tick
        # beside a print's tip, inside its hull while the line was in it, lay along
        # its outline once the line was out and read as a sliver of it (independent
        # set 1 file 96: a ruler along a print through its tips, length +1.7 %)
        import cv2

        touched = np.zeros(pooled.mask.shape, np.uint8)
        for b in bands:  # the bands taken out, on the pooled grid, a pixel wider
            p0 = tuple(np.round(np.divide(b.p0, pooled.q) * 16).astype(int))
            p1 = tuple(np.round(np.divide(b.p1, pooled.q) * 16).astype(int))
            cv2.line(touched, p0, p1, 1, int(np.ceil(b.width / pooled.q)) + 3, cv2.LINE_8, 4)
        touched = touched.view(bool)
        sorted_ = _sort_pooled(
            pooled, opts, (network & ~lines | touched) & pooled.mask, lines & ~pooled.mask
        )
    parts, st, owner = sorted_.parts, sorted_.stats, sorted_.owner
    thin_lut = np.where(owner >= 0, owner + 1, np.where(st.extent >= opts.line_length_mm, -1, -2))
    thin_lut[0] = 0
    # (without lines there are no line pixels)
    line_px = (lines & ~pooled.mask) if bands else None
    group_map = _GroupMap(
        parts,
        np.r_[0, np.where(sorted_.comp >= 0, sorted_.comp + 1, -2)],
        thin_lut,
        line_px,
        sorted_.bold_px,
    )
    shape = mask.shape
    marks = line_marks + _thin_marks(parts, st, owner, sorted_.kind, pooled, shape, opts)
    marks += _bold_marks(sorted_.bold_px, pooled)
    marks = [_clip_mark(m, shape) for m in marks]
    aside = _aside_ink(st, owner, len(sorted_.hulls), opts)
    fine = _fine_areas(parts, sorted_.comp, len(sorted_.hulls), pooled.px_mm)
    groups = [
        dataclasses.replace(
            _lost_on_edge(g, lost) if lost is not None else g,
            aside_mm2=a,
            doubt_gap_mm=float(dg),
            doubt_joined=bool(dj),
            fine_area_mm2=float(fa),
        )
        for g, a, fa, dg, dj in zip(
            _full_groups(mask, group_map, (sorted_.comp, owner), sorted_.hulls, pooled, opts),
            aside,
            fine,
            *sorted_.doubt,
            strict=True,
        )
        if g
    ]
    groups.sort(key=reading_order)
    return SortedInk(groups, marks, group_map.marks(), pooled.q, grazed)


def _fine_areas(parts: _Parts, comp: np.ndarray, n: int, px_mm: float) -> np.ndarray:
    """Per print: :data:`FINE_PART` of the median area [mm^2] of its fine tread's
    elements (:func:`_fine_fields`; 0 for a print without one): blobs at least
    that large are tread, not edge spots (``Group.fine_area_mm2``)."""
    out = np.zeros(n)
    if parts.fine is None or not n:
        return out
    fine = parts.fine[1:] & (comp >= 0)
    areas = area_px_to_mm2(parts.thick_stats[1:, 4].astype(float), px_mm)
    for g in np.unique(comp[fine]):
        out[g] = FINE_PART * np.median(areas[fine & (comp == g)])
    return out


def _aside_ink(st: _ThinStats, owner: np.ndarray, n: int, opts: AnalysisOptions) -> np.ndarray:
    """Per print: ink [mm^2] of the short thin pieces set aside that touch its hull."""
    sel = (owner < 0) & (st.target >= 0) & (st.gap <= 0.0) & (st.extent < opts.line_length_mm)
    sel[0] = False
    return np.bincount(st.target[sel], weights=st.area[sel], minlength=n)[:n]


def remove_lines(mask: np.ndarray, bands: list, *, bridge_px: float = 0.0, graze_px: float = 0.0):
    """Take straight lines out of an ink mask, bridging them where they cross ink.

    The line's pixels are removed; where ink lies on both sides of it within
    ``bridge_px`` (a line crossing a print, its voids and grooves included), a
    closing across the line puts the ink back. Where a line runs along a print's
    edge, the part of the print under it is lost (the ``lost`` mask says where: the
    outline is uncertain there).

    Parameters
    ----------
    mask : (rows, cols) bool
    bands : list of _Band
        The lines (sheet pixels).
    bridge_px : float [px]
        Reach of the bridge on each side of a line.
    graze_px : float [px]
        Least run along a line of its ``grazed`` pixels.

    Returns
    -------
    cleaned : (rows, cols) bool
    lost : (rows, cols) bool
        Ink under the lines not bridged.
    grazed : (rows, cols) bool
        Of it, the pixels with thick ink kept right across the line within a
        line's width, in runs along the line at least ``graze_px`` long: where a
        line runs along a print's edge, the edge lies somewhere under it.
    """
    import cv2

    by_dir: dict[int, np.ndarray] = {}
    for b in bands:
        d = np.subtract(b.p1, b.p0)
        ang = round(np.degrees(np.arctan2(d[1], d[0]))) % 180
        band = by_dir.setdefault(ang, np.zeros(mask.shape, np.uint8))
        p0 = tuple(np.round(np.multiply(b.p0, 16)).astype(int))
        p1 = tuple(np.round(np.multiply(b.p1, 16)).astype(int))
        cv2.line(band, p0, p1, 1, max(1, int(np.ceil(b.width)) + 2), cv2.LINE_8, 4)
    m8 = mask.view(np.uint8)
    all_bands = np.zeros(mask.shape, np.uint8)
    for band in by_dir.values():
        all_bands |= band
    out = m8 & ~all_bands & 1
    restored = np.zeros(mask.shape, np.uint8)
    line_px = max(int(np.ceil(b.width)) for b in bands)  # the widest line
    span = line_px + 4 + 2 * int(np.ceil(bridge_px))
    for ang, band in by_dir.items():  # a closing across the line
        restored |= band & cv2.morphologyEx(out, cv2.MORPH_CLOSE, _line_kernel(ang + 90, span))
    cleaned = (out | (m8 & restored)).view(bool)
    lost = m8 & all_bands & ~restored & 1
    grazed = np.zeros(mask.shape, np.uint8)
    width = line_px + 2
    # thick ink (a print, not a ruler's tick) right across the line, a line's width off
    thick = cv2.morphologyEx(cleaned.view(np.uint8), cv2.MORPH_OPEN, _disk(width))
    # across the line from the print's ink, over the line and a pixel of paper at
    # most: where the line has left the edge, paper between them shows the edge
    across = 2 * (width - 1) + 1
    for ang, band in by_dir.items():
        near = lost & band & cv2.dilate(thick, _line_kernel(ang + 90, across))
        if graze_px > 1:  # runs along the line (a line leaving the edge at a slant: short)
            near = cv2.morphologyEx(near, cv2.MORPH_OPEN, _line_kernel(ang, round(graze_px)))
        grazed |= near
    return cleaned, lost.view(bool), grazed.view(bool)


def _line_kernel(angle_deg: float, length: int) -> np.ndarray:
    """A one-pixel line of ``length`` at ``angle_deg`` (image x, y), as a kernel."""
    import cv2

    n = length | 1
    k = np.zeros((n, n), np.uint8)
    a = np.radians(angle_deg)
    dx, dy = np.cos(a) * (n // 2), np.sin(a) * (n // 2)
    c = n // 2
    cv2.line(k, (round(c - dx), round(c - dy)), (round(c + dx), round(c + dy)), 1, 1)
    return k


def _lost_on_edge(g: Group, lost: np.ndarray) -> Group:
    """The group with ``line_along`` set to the longest stretch [px] of its outline
    that a line covered without a bridge (a line along its edge, a print split by
    a ruler; a line merely crossing the edge covers about its own width)."""
    import cv2

    r0, r1 = max(g.rows.start - 2, 0), g.rows.stop + 2
    c0, c1 = max(g.cols.start - 2, 0), g.cols.stop + 2
    near = np.zeros(lost[r0:r1, c0:c1].shape, np.uint8)
    near[g.rows.start - r0 : g.rows.stop - r0, g.cols.start - c0 : g.cols.stop - c0] = g.mask
    touch = cv2.dilate(near, np.ones((5, 5), np.uint8)) & lost[r0:r1, c0:c1].view(np.uint8)
    n, _, stats, _ = components_with_stats(touch, connectivity=8)
    if n <= 1:
        return g
    longest = float(np.hypot(stats[1:, cv2.CC_STAT_WIDTH], stats[1:, cv2.CC_STAT_HEIGHT]).max())
    return dataclasses.replace(g, line_along=longest)


def _box(stats: np.ndarray, k: int) -> tuple[slice, slice]:
    x, y, w, h = stats[k, :4]
    return slice(y, y + h), slice(x, x + w)


def _crop(labels: np.ndarray, stats: np.ndarray, k: int) -> np.ndarray:
    return labels[_box(stats, k)] == k


def _thin_marks(parts, stats: _ThinStats, owner, kind, pooled, shape, opts) -> list:
    """Marks for the thin pieces set aside."""
    out = []
    for k in np.flatnonzero(owner[1:] < 0) + 1:
        rows, cols = _box(parts.thin_stats, k)
        if kind[k]:
            why = _short_reason(str(kind[k]), stats, k, opts)
            kk = str(kind[k])
        else:
            kk, why = _line_kind(
                _crop(parts.thin, parts.thin_stats, k), stats.extent[k], pooled.px_mm
            )
        out.append(_mark(kk, rows, cols, pooled, shape, stats.area[k], why))
    return out


def _bold_marks(bold: np.ndarray | None, pooled: _Pooled) -> list:
    """Marks for the bold pen strokes set aside (:func:`_bold_strokes`), one per
    piece."""
    if bold is None:
        return []
    n, _, st, _ = components_with_stats(bold, connectivity=8)
    why = BOLD_REASON
    return [
        _mark(
            "text",
            _box(st, k)[0],
            _box(st, k)[1],
            pooled,
            None,
            area_px_to_mm2(int(st[k, 4]), pooled.px_mm),
            why,
        )
        for k in range(1, n)
    ]


def _mark(kind, rows, cols, pooled: _Pooled, shape, area, why) -> Mark:
    q = pooled.q
    h, w = shape if shape is not None else (1 << 62, 1 << 62)
    box = (
        int(rows.start * q),
        int(cols.start * q),
        int(min(rows.stop * q, h)),
        int(min(cols.stop * q, w)),
    )
    return Mark(kind, box, float(area), why)


def _clip_mark(m: Mark, shape) -> Mark:
    r0, c0, r1, c1 = m.bbox
    return Mark(m.kind, (r0, c0, min(r1, shape[0]), min(c1, shape[1])), m.area_mm2, m.reason)


@dataclass(frozen=True)
class _GroupMap:
    """The sheet's pooled group map, cropped on demand: k + 1 on print k's pixels,
    -1 on a line mark's, -2 on another mark's, 0 on paper. ``thick_lut`` and
    ``thin_lut`` give those values of the thick elements and thin pieces of
    ``parts``; ``lines``: the lines' pixels beside the ink (-1), or None.

    (Built whole, the map is a gather over every pixel of the sheet, and finding the
    prints' boxes in it a scan of the whole map: the prints need it in their boxes
    only, their boxes are their pieces', and the marks are thin pixels.)"""

    parts: _Parts
    thick_lut: np.ndarray
    thin_lut: np.ndarray
    lines: np.ndarray | None
    bold: np.ndarray | None = None

    @property
    def shape(self) -> tuple:
        """(H, W) of the pooled grid."""
        return self.parts.thick.shape

    def crop(self, rows: slice, cols: slice) -> np.ndarray:
        """The map over a box, (h, w) int."""
        out = self.thick_lut[self.parts.thick[rows, cols]]
        thin = self.parts.thin[rows, cols]
        on = thin > 0
        out[on] = self.thin_lut[thin[on]]
        if self.lines is not None:
            out[self.lines[rows, cols]] = -1
        if self.bold is not None:
            out[self.bold[rows, cols]] = -2
        return out

    def marks(self) -> np.ndarray:
        """Where the map is negative (a mark), (H, W) bool."""
        on = self.parts.thin > 0
        out = np.zeros(on.shape, bool)
        out[on] = (self.thin_lut < 0)[self.parts.thin[on]]
        if self.lines is not None:
            out |= self.lines
        if self.bold is not None:
            out |= self.bold
        return out


def _full_groups(mask, group_map: _GroupMap, owners: tuple, hulls: list, pooled, opts):
    """Each print's ink at full resolution (None for one without ink). ``owners``:
    the print of each thick element (0-based) and of each thin piece (1-based, -1:
    none); a print's box holds its pieces' boxes."""
    import cv2

    n_groups = len(hulls)
    comp, owner = owners
    parts = group_map.parts
    ids = np.r_[comp, owner[1:]].astype(np.intp)
    st = np.concatenate([parts.thick_stats[1:], parts.thin_stats[1:]])[ids >= 0]
    ids = ids[ids >= 0]
    big = np.iinfo(np.int64).max
    r0, c0 = np.full(n_groups, big), np.full(n_groups, big)
    r1, c1 = np.full(n_groups, -1), np.full(n_groups, -1)
    top, left = st[:, cv2.CC_STAT_TOP], st[:, cv2.CC_STAT_LEFT]
    np.minimum.at(r0, ids, top)
    np.minimum.at(c0, ids, left)
    np.maximum.at(r1, ids, top + st[:, cv2.CC_STAT_HEIGHT] - 1)
    np.maximum.at(c1, ids, left + st[:, cv2.CC_STAT_WIDTH] - 1)
    for k in range(n_groups):
        if r1[k] < 0:
            yield None
            continue
        box = (r0[k], c0[k], r1[k], c1[k])
        yield _full_group(mask, group_map, k + 1, box, hulls[k], pooled, opts)


def _full_group(mask, group_map, gid: int, box, hull, pooled: _Pooled, opts: AnalysisOptions):
    """Group ``gid``'s ink at full resolution (None if it has none)."""
    import cv2

    q, (h, w) = pooled.q, mask.shape
    y0, x0, y1, x1 = box
    r0, r1 = max(y0 - 1, 0), min(y1 + 2, group_map.shape[0])
    c0, c1 = max(x0 - 1, 0), min(x1 + 2, group_map.shape[1])
    local = group_map.crop(slice(r0, r1), slice(c0, c1))
    region = cv2.dilate((local == gid).astype(np.uint8), np.ones((3, 3), np.uint8))
    region &= ((local == 0) | (local == gid)).astype(np.uint8)  # not a mark, not another print
    rows = slice(r0 * q, min(r1 * q, h))
    cols = slice(c0 * q, min(c1 * q, w))
    ink = mask[rows, cols] & _upsample(region, q, rows, cols)
    # a pen mark set aside touching the print: how far along its outline
    touching = cv2.dilate((local == gid).astype(np.uint8), np.ones((3, 3), np.uint8))
    removed = float(np.count_nonzero(touching & (local == -2))) * q / 2.0
    # a line's stub inside the print's pooled pixels is as thin as the line; a pen
    # stroke lying along the print's edge fills a stroke disk: take two
    for code, k in ((-1, 1.0), (-2, 2.0)):
        near = cv2.dilate(
            (local == code).astype(np.uint8),
            _disk(mm_to_px_length(k * opts.stroke_width_mm, pooled.px_mm)),
        )
        near &= region
        if near.any():
            near_full = _upsample(near, q, rows, cols) & ~_inside(hull, q, rows, cols)
            before = int(np.count_nonzero(ink))
            width = mm_to_px_length(
                k * opts.stroke_width_mm, binned_mm_per_px(pooled.px_mm, 1 / q)
            )
            ink = _drop_thin_near(ink, near_full, width)
            removed = max(removed, (before - int(np.count_nonzero(ink))) / width)
    if not ink.any():
        return None
    return _tight(Group(rows, cols, ink, float(removed)))


def _upsample(small: np.ndarray, q: int, rows: slice, cols: slice) -> np.ndarray:
    big = (
        np.repeat(np.repeat(small.astype(bool), q, axis=0), q, axis=1)
        if q > 1
        else small.astype(bool)
    )
    return big[: rows.stop - rows.start, : cols.stop - cols.start]


def _inside(hull, q: int, rows: slice, cols: slice) -> np.ndarray:
    """Sheet pixels of the box inside a print's pooled hull (none without a hull)."""
    import cv2

    inside = np.zeros((rows.stop - rows.start, cols.stop - cols.start), np.uint8)
    if hull is not None:
        pts = (hull.reshape(-1, 2) + 0.5) * q - np.array([cols.start, rows.start]) - 0.5
        cv2.fillPoly(inside, [np.round(pts * 16).astype(np.int32)], 1, cv2.LINE_8, 4)
    return inside.view(bool)


def _drop_thin_near(ink: np.ndarray, near: np.ndarray, width_px: float) -> np.ndarray:
    """Remove, at full resolution, the ink in ``near`` narrower than ``width_px``
    (the stub of a line, the foot of a pen stroke where a mark touches a print)."""
    import cv2

    thick = cv2.morphologyEx(ink.view(np.uint8), cv2.MORPH_OPEN, _disk(width_px))
    return ink & ~(near & ~thick.view(bool))


def _tight(g: Group) -> Group:
    """The group with its box shrunk to its ink (``edge_marks`` kept)."""
    rows = np.flatnonzero(g.mask.any(axis=1))
    cols = np.flatnonzero(g.mask.any(axis=0))
    r0, r1, c0, c1 = rows[0], rows[-1] + 1, cols[0], cols[-1] + 1
    return Group(
        slice(g.rows.start + r0, g.rows.start + r1),
        slice(g.cols.start + c0, g.cols.start + c1),
        g.mask[r0:r1, c0:c1],
        g.edge_marks,
    )


__all__ = ["Mark", "SortedInk", "sort_ink"]
