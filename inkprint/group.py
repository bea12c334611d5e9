"""Whole footprints from tread elements, and load-bearing ink from edge spots.

The thresholds named below are fields of :class:`inkprint.AnalysisOptions`.

Footprints (section 4.1.1, "groups of pixels are identified"). A print's tread
elements (knobs, blocks, ribs: the ink that is wider than a pen stroke, see
:mod:`inkprint.marks`) are linked into one print by footprint-scale structure, not
one fixed distance: the gap between two neighbouring elements (the free space
between their edges, from a Voronoi partition of the sheet) is a groove of the same
print when it is

* at most ``group_distance_mm`` (3 mm: the knobs and sipes of bicycle treads), or
* at most ``group_size_factor`` x the narrower element's width (off by default: the
  side-by-side rule below judges a car print's ribs at the footprint's scale), or
* at most ``group_pattern_factor`` x the tread pattern's own gap around the two
  elements: the smallest gap from each to its *other* neighbours, counting only
  neighbours no farther than :data:`PATTERN_REACH` x their widths (wide-groove knobs
  as far apart as they are wide): the wider of the two when the two are such
  neighbours themselves, else the narrower; an element with no pattern (a sliver, a
  slick print) takes only a wider element's. Two prints on a sheet are farther
  apart than their grooves are wide.

Elements linked are one print; groups whose convex hulls overlap are one print too.
Then the groups themselves are compared (:func:`join_tips`,
:func:`join_side_by_side`): a small group continuing a larger one's tread pattern
(a knobby print's tip blocks) joins it, and groups lying side by side (a car print's
ribs between its 4-15 mm circumferential grooves) are one print when their gap is
small beside the whole footprint they make (``group_print_gap``); a decision near
that limit flags the print ``grouping_uncertain``. ``group_mm`` replaces the rule by
one distance (``--group-mm``, manifest column).

Edge spots (section 7.1.1, "determining which sections near the edge actually bore
weight and which merely touched the paper"): the print's *core* is its large, dark
blobs (area >= ``edge_spot_area_mm2``, peak darkness >= ``edge_spot_faintness`` x
the large blobs' median). A blob outside the core's hull bore no load when it is
*faint* (peak darkness below that fraction: ink that was not pressed) or *small and
isolated*: below the area and farther from the nearest core blob than
``edge_spot_distance_mm`` or ``edge_spot_pattern_factor`` x the core's own tread
gap, whichever is larger. So small dark blocks at the tips that continue the tread
pattern along the rolling direction are kept (before, their centroids' distance to the core's hull dropped
them: length -2.4 %), and a dark speck far out is dropped. The peak, not the mean,
is used because a small dot's anti-aliased rim lowers its mean. Results are reported
both with all ink and with load-bearing ink only.

Before the rule, pen-thin ink (narrower than ``stroke_width_mm``) outside the hull of
the print's thick ink is taken out when it is joined to the print (a stroke's foot,
a ruler's tick) or lies beside it (a label's letters, specks: counted as edge
spots); thin slivers off the print's ends along its major axis - tip blocks cut by
the outline - and convex slivers lying along its outline, no thicker across it than
``mark_overhang_mm`` (blocks the outline cut to a bar: at the sides, or at the
rolling ends of a print wider than long) are left to the rule, so they are kept
(:func:`thin_protrusions`; an addition to section 7.1.1, which knew no labels
touching a print).
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass, field, replace

import numpy as np

from .components import cleared, components_with_stats, piece_stats, reduce_at
from .coords import (
    area_mm2_to_px,
    area_px_to_mm2,
    binned_mm_per_px,
    mm_to_px_length,
    px_to_mm_length,
)
from .errors import InvalidInput, check_mm_per_px
from .options import AnalysisOptions, resolve_options
from .sites import fit_lattice, nearest_site

#: a neighbour counts for the tread pattern's gap when no farther than this many
#: times the narrower element's width (2 before: knobby blocks 3 mm wide, 6-8 mm
#: apart, had no pattern at all and each was a "print" of its own, s2_039 under a
#: 46 % light gradient: 3 prints -> ~50 of 5 x 3 mm; the independent generator's
#: knobs are up to 2.7 x as far apart as they are wide)
PATTERN_REACH = 3.0
#: a lone element (no pattern of its own) continues its neighbour's pattern within
#: this share of group_pattern_factor x that pattern's gap (one groove, not three)
LONE_PATTERN_FACTOR = 0.5
#: an element's pattern neighbours are at least 1 / this of its width
PATTERN_SIZE = 4.0
#: ribs side by side face each other over this share of the longer one's extent or
#: more: a car print's ribs run its length, a label of fused bold letters beside a
#: slick print half of it at most (a 40 mm label 4.4 mm off a 90 mm print joined it
#: as a rib: width +32 %, unflagged)
RIB_ALONG = 0.5
#: rounds of :func:`join_tips` (a chain of tip blocks joins block by block)
TIP_ROUNDS = 4
#: a punch hole's diameter range [mm], roundness (length / width at most), solid
#: share of its hull at least, and its centre's distance from the image's edge at
#: most [mm] (ISO 838: 12 mm; a US punch: 13 mm; a skewed or shifted page: more)
PUNCH_HOLE_MM = (4.5, 9.0)
PUNCH_HOLE_ROUND = 1.2
PUNCH_HOLE_FILL = 0.9
PUNCH_HOLE_EDGE_MM = 25.0
#: a print with a hull under this [mm^2] (a tiny print) is solid: it inks at least
#: SMALL_PRINT_FILL of its hull (a letter, a ring, a tick does not)
SMALL_PRINT_MM2 = 150.0
SMALL_PRINT_FILL = 0.8
#: ... and so is a print narrower than this [mm]
NARROW_PRINT_MM = 6.0
#: ... or inks SMALL_BODY_FILL of it around one body: the widest disk in its ink is
#: SMALL_BODY_SHARE of its width or more (a tread's scallops; writing's strokes reach
#: 0.2-0.59 of it, at most 0.49 where they ink 0.7 of their hull: held-out set 1)
SMALL_BODY_FILL = 0.7
#: a group set aside by that rule may still be a tiny tread print
#: (:func:`maybe_tiny_print`): its pieces of at least MAYBE_SPECK of the largest
#: span at most MAYBE_SPAN of its width on the mean (a tread's elements: 0.09-0.38 in
#: held-out sets 1-8; a word's letters span its height: 0.70-1.0) ...
MAYBE_SPAN = 0.4
MAYBE_SPECK = 0.05
#: ... and it is at most MAYBE_ASPECT times as long as wide (tiny prints: up to 6.4;
#: two dust fibres side by side, 96 x 4.6 mm, held-out 6 seed 9 sheet 11: 21) ...
MAYBE_ASPECT = 8.0
#: ... or it is one body (its other pieces specks) at least MAYBE_BODY_MM long and
#: MAYBE_BODY_ASPECT times as long as wide (a scalloped tiny print 11-21 mm long;
#: a single letter 6-8 mm), whose hull's core,
#: MAYBE_CORE_DEPTH of its width or more inside, it inks MAYBE_CORE_FILL or more (a
#: tread cuts a tiny print's edges, its core 0.96-1.0 inked; a marker's bold word
#: fused to one body leaves gaps between its letters and their counters: 0.79)
MAYBE_BODY_MM = 10.0
MAYBE_BODY_ASPECT = 2.0
MAYBE_CORE_DEPTH = 0.2
MAYBE_CORE_FILL = 0.9
#: a tiny group of this many parallel bars or more may be a rib print
#: (:func:`_rib_stack`) ...
RIB_STACK_MIN = 3
#: ... their longer sides within this angle [deg] of their mean direction ...
RIB_STACK_PARALLEL_DEG = 10.0
#: ... each lying beside the longest over at least this share of its own length
#: (an ellipse's outer rib, the outline cut, lies within its neighbour's length)
RIB_STACK_BESIDE = 0.8
#: ... counting the pieces of at least this share of the largest (not specks); two
#: bars do when they are at least this long [mm] (a marker's '=' is shorter)
RIB_STACK_SPECK = 0.05
RIB_PAIR_MM = 10.0
#: ... all but one bar at least this many strokes (``stroke_width_mm``) wide: a
#: marker's letters are narrower. 1.5 (2 before): tiny rib prints at 600 dpi whose
#: ribs are 1.5-1.7 mm wide, 1.7-1.9 strokes (held-out seeds 3 and 5 sheets 36 and
#: 49: set aside as "a letter or a mark", missing)
RIB_STACK_WIDE = 1.5
#: ... and two bars shorter than RIB_PAIR_MM are a rib print when both are this
#: many strokes wide or more, wider than a marker's strokes (held-out seed 4 sheet
#: 36: an 8.9 x 7.2 mm print of two 2.8 mm ribs, missing)
RIB_PAIR_BOLD = 3.0
SMALL_BODY_SHARE = 0.7
#: a line of writing has at least this many letters spanning its width, they hold
#: this share of its ink and leave gaps: the ink fills less than TEXT_LINE_FILL of
#: the hull (``text_line_aspect``; a road tire's slender print fills 0.7 or more, a
#: chevron tread's 0.87); letters are at least TEXT_LETTER_MM high (a tiny print's
#: file-tread diamonds, ~1 mm, are not letters)
TEXT_LINE_LETTERS = 6
TEXT_LINE_INK = 0.7
TEXT_LINE_FILL = 0.6
TEXT_LETTER_MM = 2.5
#: a bar along a row of letters, lower than TEXT_LETTER_MM and longer than this many
#: times that, is an underline (:func:`_letters_in_a_row`)
UNDERLINE_LETTERS = 4.0
#: in a row of writing among others, a letter spans this share of the row or more
#: (a lower-case letter without ascender nor descender: 0.49 of its row on held-out
#: 6 sheet 79)
TEXT_ROW_SPAN = 0.4
#: ... and each row holds this many letters or more (held-out 6 sheet 8: 'F = 299 N')
TEXT_ROW_LETTERS = 4
#: a word of a line of writing set aside beside it (:func:`word_in_a_line`): a small
#: group in line with a mark of writing that runs along the line (WORD_LINE_ASPECT
#: times longer than high or more: a label's letters above a tiny print, each about
#: as high as wide, are no line running down into it, held-out set 8 sheet 54),
#: their extents across the line overlapping by WORD_ROW_OVERLAP of the lower, their
#: heights within WORD_HEIGHT_RATIO (a group of two rows beside one row of the rest),
#: at most WORD_GAP of its height from it along the line; of WORD_LETTERS pieces or
#: more (each WORD_PIECE_SHARE of its ink) or one piece shorter than WORD_ASPECT
#: times its height, none running WORD_ASPECT times the row's height along it
WORD_LINE_ASPECT = 1.5
WORD_ROW_OVERLAP = 0.5
WORD_HEIGHT_RATIO = 3.0
WORD_GAP = 1.5
WORD_LETTERS = 2
WORD_PIECE_SHARE = 0.1
WORD_ASPECT = 2.0
#: a row is TEXT_LETTER_MM high or more; its letters span this share of that or more,
#: in a row among others and in a line alone: lower-case letters are shorter ('a' and
#: 'r' of 'p = 3.4 bar' under 'F = 446 N', held-out set 14 sheet 93, and of
#: 'Bridgestone S22 ...', set 13 sheet 42: 2.3-2.5 mm; under 2.8 mm capitals 1.7-2
#: mm); a tiny print's file diamonds, ~1 mm, stay under it
TEXT_ROW_LETTER_SHARE = 0.6
#: the direction across rows of writing is looked for at these turns [deg] from the
#: least rectangle's, on about this many of the ink's pixels
TEXT_ROW_TURNS = np.arange(-3.0, 3.01, 0.5)
TEXT_ROW_SAMPLE = 5000
#: a bar fills this share of its least rectangle or more and is this many times
#: longer than wide: half the largest pieces of rows of writing are no bars (an 'l',
#: a '1', a '-' are), a tread's bars in rows all are
TEXT_BAR_FILL = 0.8
#: ... and are no tread: pieces within this relative difference of the median
#: piece's ink are alike ...
TEXT_ALIKE_AREA = 0.1
#: ... and when this share of the pieces is, they are a tread's elements
TEXT_ALIKE_SHARE = 0.5
TEXT_BAR_ASPECT = 2.5
#: a row's neighbouring pieces are alike in shape when, laid over each other by
#: their centroids, they share this much of their union (intersection over union);
#: when TEXT_ALIKE_SHARE of the neighbours are, the row is a tread's (chevrons,
#: each the last one shifted), not writing (letters differ from their neighbours:
#: an 'll' or '00' is a pair, not a row)
TEXT_SHAPE_ALIKE = 0.6
#: A tread's teeth (:func:`_teeth`) line each side of a print along at least this
#: share of its length. An elliptic outline cuts a file tread's shoulder rows to
#: teeth over 0.43-0.45 of it (held-out 6 sheets 19 and 81: asked for half, they
#: were dropped as strokes' feet; width -2.9 % -> -2.5 %, -8.9 % -> -8.2 %, the rest
#: being the outer row's dots); a label touches one side.
TEETH_SPAN = 0.4
#: ... each reaching at most this many strokes' widths out of the thick ink's hull
#: (one, before: a tiny file print's inner row of diamonds, joined to its slick
#: centre, stands out farther where the grooves run at 40-65 degrees; dropped as
#: strokes' feet, a fifth of the ink: in a sweep of 60 drawn prints two silent,
#: hull area -2.4 and -2.7 %, and four flagged, -2.4 to -8.3 %, now in the bar)
TEETH_DEPTH = 2.0
#: ... or, on one side, fewer along a shorter stretch at a regular pitch: its
#: stubs' gaps along the print within this share of their median (the outline cuts
#: only a file print's middle teeth to stubs on one side: held-out 6 seed 7 sheet
#: 10, three at 0.3 of the length, -0.31, -0.01, +0.28 of the half-length, the
#: other side's seven spanning 0.62; dropped as strokes' feet, -11 % wide)
TEETH_PITCH = 0.25


@dataclass(frozen=True)
class Group:
    """Ink of one candidate print.

    Attributes
    ----------
    rows, cols : slice [px]
        Bounding box in the sheet.
    mask : (h, w) bool
        The group's ink inside the box.
    edge_marks : float [px]
        Length of the longest stretch of the print's outline covered by a mark set
        aside (the feet of a label's strokes, a line's stub): there the outline is
        uncertain.
    line_along : float [px]
        Length of the longest stretch of the outline along which a straight line
        (a ruler) was taken out without a bridge: a line running along the print
        over ``line_length_mm`` or more (a print split by a ruler) flags it; a
        shorter one is judged by its effect on the measures (``SortedInk.grazed``).
    aside_mm2 : float [mm^2]
        Ink of the short marks (pen strokes) set aside that touch the group: a group
        that is mostly such strokes is writing, not a print.
    doubt_gap_mm : float [mm]
        Gap of a side-by-side join or split near the rule's limit
        (:func:`join_side_by_side`): the grouping is uncertain (0: it is not).
    doubt_joined : bool
        Whether that join was made (parts taken as one print) or not.
    fine_area_mm2 : float [mm^2]
        For a print with a fine tread (a dense regular field of small elements:
        knurl, diamond file, dots; :func:`inkprint.marks.sort_ink`), the area above
        which a blob is one of its elements: part of the core of the section 7.1.1
        rule (:func:`edge_spots`), not an edge spot. 0: no fine tread.
    stacked : bool
        Whether it holds a stack of pen-thin strokes found regular
        (:func:`inkprint.stack.stroke_stacks`): they are its tread, not a ruler's
        edge reaching beyond its body.
    ribs : bool
        Whether that stack is of lines along the print (its ribs, each
        ``STACK_LINE_MM`` long or more): the outline cuts their ends to long wedges.
    """

    rows: slice
    cols: slice
    mask: np.ndarray
    edge_marks: float = 0.0
    aside_mm2: float = 0.0
    line_along: float = 0.0
    doubt_gap_mm: float = 0.0
    doubt_joined: bool = False
    fine_area_mm2: float = 0.0
    stacked: bool = False
    ribs: bool = False

    @property
    def n_pixels(self) -> int:
        """Number of ink pixels [px]."""
        return int(np.count_nonzero(self.mask))


@dataclass(frozen=True)
class ElementGraph:
    """Neighbouring tread elements and the gaps between them.

    Attributes
    ----------
    widths : (n,) float [mm]
        Width of each element (twice its largest inscribed radius).
    a, b : (m,) int
        Neighbouring pairs (0-based element indices, a < b).
    gaps : (m,) float [mm]
        Free space between the two elements' edges.
    """

    widths: np.ndarray
    a: np.ndarray
    b: np.ndarray
    gaps: np.ndarray


def element_graph(
    labels: np.ndarray, n: int, *, px_mm: float, step: int = 1, box: tuple | None = None
) -> ElementGraph:
    """Voronoi neighbours of labelled elements and their gaps.

    Parameters
    ----------
    labels : (h, w) int32
        0 = paper, 1..n = elements.
    n : int
        Number of elements.
    px_mm : float [mm]
        Size of a pixel of ``labels``.
    step : int
        Sample every ``step``-th pixel for the partition (coarser, faster; each
        element must keep a sample: elements wider than ``step`` px).
    box : (rows, cols) slice, optional
        A box holding every element with at least a pixel of paper around them
        (or the image's edge), where their widths are found (the same widths:
        :func:`_element_widths`); the partition is the whole image's.

    Returns
    -------
    ElementGraph
    """
    import cv2

    widths = _element_widths(labels if box is None else labels[box], n, px_mm)
    lab = _sampled(labels, n, step, box) if step > 1 else labels
    ink = lab > 0
    dist, nearest = cv2.distanceTransformWithLabels(
        (~ink).astype(np.uint8), cv2.DIST_L2, 3, labelType=cv2.DIST_LABEL_PIXEL
    )
    a, b, g = _least_per_pair(*_voronoi_pairs(lab, ink, dist, nearest), n)
    g = px_to_mm_length(g, binned_mm_per_px(px_mm, step))
    return ElementGraph(widths, a - 1, b - 1, g)


def _least_per_pair(a: np.ndarray, b: np.ndarray, g: np.ndarray, n: int) -> tuple:
    """Each pair of labels (1..n) once, the lower first, with its least gap:
    ``(a, b, gap)`` from :func:`_voronoi_pairs`'s repeated pairs."""
    lo, hi = np.minimum(a, b), np.maximum(a, b)
    key = lo * (n + 1) + hi
    order = np.argsort(key, kind="stable")
    key, g = key[order], g[order]
    first = np.flatnonzero(np.r_[True, key[1:] != key[:-1]]) if len(key) else np.zeros(0, int)
    gmin = np.minimum.reduceat(g, first) if len(first) else np.zeros(0)
    uk = key[first]
    return uk // (n + 1), uk % (n + 1), gmin


def _sampled(labels: np.ndarray, n: int, step: int, box: tuple | None) -> np.ndarray:
    """``labels`` sampled every ``step``-th pixel, each element that no sample hits
    (narrower than ``step`` px) given the sample its first pixel falls in, where
    that is paper: a fine tread's diamond tips the outline cut to 0.5 mm triangles
    fell between the samples, were nobody's neighbours and went as dust (held-out
    9 sheet 87, a knurl print's last rows: width -1.6 %, unflagged)."""
    lab = labels[::step, ::step].copy()
    have = np.zeros(n + 1, bool)
    have[lab[lab > 0]] = True
    if have[1:].all():
        return lab
    sub = labels if box is None else labels[box]
    r0, c0 = (0, 0) if box is None else (box[0].start or 0, box[1].start or 0)
    rows, cols = np.nonzero(sub)
    vals = sub[rows, cols]
    miss = ~have[vals]
    k, first = np.unique(vals[miss], return_index=True)
    r = (rows[miss][first] + r0) // step
    c = (cols[miss][first] + c0) // step
    free = lab[r, c] == 0
    lab[r[free], c[free]] = k[free]
    return lab


def _voronoi_pairs(lab, ink, dist, nearest) -> tuple:
    """Element pairs whose Voronoi cells touch, with the gap [px] across each touch:
    ``(a, b, gap)`` (labels 1..n, repeated per touching pixel pair), from a distance
    transform of the paper with the nearest ink pixel's label."""
    lut = np.zeros(int(nearest.max()) + 1, np.int32)
    lut[nearest[ink]] = lab[ink]
    return _touching(lut[nearest], dist)


def _touching(owner, dist) -> tuple:
    """``(a, b, gap)`` of :func:`_voronoi_pairs` from each pixel's element (``owner``)
    and its distance to it."""
    pairs = []
    for sl0, sl1 in (
        ((slice(None), slice(None, -1)), (slice(None), slice(1, None))),
        ((slice(None, -1), slice(None)), (slice(1, None), slice(None))),
    ):
        o0, o1 = owner[sl0], owner[sl1]
        cut = o0 != o1
        pairs.append((o0[cut], o1[cut], dist[sl0][cut] + dist[sl1][cut]))
    a = np.concatenate([p[0] for p in pairs]).astype(np.int64)
    b = np.concatenate([p[1] for p in pairs]).astype(np.int64)
    return a, b, np.concatenate([p[2] for p in pairs]).astype(float)


def _element_widths(labels: np.ndarray, n: int, px_mm: float) -> np.ndarray:
    """Twice the largest inscribed radius of each element [mm].

    The same in any box of ``labels`` holding the elements with a pixel of paper
    around them (or the image's edge): the distance transform's passes give an
    element's pixels the same values from that paper on, whatever lies beyond it
    (paper, 0 too)."""
    import cv2

    ink = labels > 0
    dt = cv2.distanceTransform(ink.view(np.uint8), cv2.DIST_L2, 3)
    best = np.zeros(n + 1, np.float32)
    reduce_at(np.maximum, best, labels[ink], values=dt[ink])
    return px_to_mm_length(2.0 * best[1:].astype(float), px_mm)


def _pattern_gaps(graph: ElementGraph, n: int):
    """Per element: the smallest and second-smallest gap to a pattern neighbour
    (:data:`PATTERN_REACH`, :data:`PATTERN_SIZE`) and the first one's index (inf /
    -1 when none)."""
    w = graph.widths
    ok = graph.gaps <= PATTERN_REACH * np.minimum(w[graph.a], w[graph.b])
    src = np.concatenate([graph.a[ok], graph.b[ok]])
    dst = np.concatenate([graph.b[ok], graph.a[ok]])
    gap = np.concatenate([graph.gaps[ok], graph.gaps[ok]])
    # an element's pattern is of neighbours not far narrower than itself: a slick
    # print's gap to a label's bold letters is no tread gap of it (a label 6.7 mm
    # off it continued that "pattern" and joined it: width +41 %, unflagged)
    like = w[dst] * PATTERN_SIZE >= w[src]
    src, dst, gap = src[like], dst[like], gap[like]
    first, second, who = np.full(n, np.inf), np.full(n, np.inf), np.full(n, -1)
    order = np.lexsort((gap, src))
    src, dst, gap = src[order], dst[order], gap[order]
    start = np.flatnonzero(np.r_[True, src[1:] != src[:-1]]) if len(src) else np.zeros(0, int)
    first[src[start]], who[src[start]] = gap[start], dst[start]
    nxt = start + 1
    has2 = nxt < len(src)
    has2[has2] &= src[nxt[has2]] == src[start[has2]]
    second[src[start[has2]]] = gap[nxt[has2]]
    return first, second, who


def linked_edges(graph: ElementGraph, *, options: AnalysisOptions | None = None) -> np.ndarray:
    """Which neighbour pairs belong to one print (the rule of the module's notes).

    Parameters
    ----------
    graph : ElementGraph
    options : AnalysisOptions, optional
        Uses ``group_mm``, ``group_distance_mm``, ``group_size_factor``,
        ``group_pattern_factor`` and ``group_groove_max_mm`` (defaults when None).

    Returns
    -------
    (m,) bool
    """
    opts = resolve_options(options)
    g, a, b = graph.gaps, graph.a, graph.b
    if opts.group_mm is not None:
        return g <= opts.group_mm
    n = len(graph.widths)
    w = graph.widths
    first, second, who = _pattern_gaps(graph, n)
    pa = np.where(who[a] == b, second[a], first[a])  # a's pattern gap without b
    pb = np.where(who[b] == a, second[b], first[b])
    # a gap wider than a groove is no tread's: two slick prints 39 mm apart made a
    # "pattern" whose half let a letter 19 mm off one join it (held-out set 1
    # sheet 114: both prints and their label one 112 x 82 mm print)
    pa[pa > opts.group_groove_max_mm] = np.inf
    pb[pb > opts.group_groove_max_mm] = np.inf
    # two pattern neighbours (no farther apart than PATTERN_REACH x the narrower's
    # width) continue the wider of their two patterns: a knobby print's tip blocks,
    # split by a 1-2 mm sipe, face the next row across its 3-8 mm gap (with the
    # narrower pattern the tip row was cut off, s2_076: length -12.4 %); farther
    # apart, the narrower
    near = g <= PATTERN_REACH * np.minimum(w[a], w[b])
    pattern = np.where(near, np.maximum(pa, pb), np.minimum(pa, pb))
    # an element without a pattern of its own (a sliver, a slick print) takes the
    # other's only when that one is at least as wide: a tip sliver continues the
    # print's knobs, but a slick print does not continue the spacing of a label's
    # bold letters beside it (s4_013: letters 2.7 mm apart, 6.9 mm away, joined the
    # print once PATTERN_REACH gave them a pattern: width +143 %)
    lone_a, lone_b = np.isinf(pa), np.isinf(pb)
    one = lone_a ^ lone_b
    # ... and across one groove of it: a tip block the outline cut lies where the
    # next block would (a marker's letter 11.8 mm off a car rib whose blocks are
    # 5.3 mm apart joined it: width +12.6 %, held-out set 1 sheet 37)
    pattern = np.where(one, LONE_PATTERN_FACTOR * np.minimum(pa, pb), pattern)
    pattern[one & ((lone_a & (w[a] > w[b])) | (lone_b & (w[b] > w[a])))] = np.inf
    return (
        (g <= opts.group_distance_mm)
        | (g <= opts.group_size_factor * np.minimum(w[a], w[b]))
        | (
            np.isfinite(pattern)
            & (g <= opts.group_pattern_factor * pattern)
            & (g <= opts.group_groove_max_mm)
        )
    )


def join_tips(
    graph: ElementGraph,
    comp: np.ndarray,
    sizes: np.ndarray,
    *,
    options: AnalysisOptions | None = None,
) -> np.ndarray:
    """Join a small group to its nearest neighbouring group when it continues that
    group's tread pattern: it holds less than ``group_tip_share`` of the
    neighbour's ink and its gap is within ``group_pattern_factor`` x the
    neighbour's tread gap (the median over its elements of the gap to their
    nearest element in it).

    A knobby print's tip blocks (cut by the outline to slivers, or a row of two
    blocks) face the print across a 3-8 mm gap; beside a sliver the element rule
    has no pattern of its own to compare with, so the tip was a fragment or a
    print of its own (s2_008: length -1.5 % and a spurious 4.3 x 9.1 mm print).
    Whether such a block bore load is then the edge-spot rule's (section 7.1.1).

    Parameters
    ----------
    graph : ElementGraph
    comp : (n,) int
        Group of each element.
    sizes : (n,) float
        Ink of each element (any unit).
    options : AnalysisOptions, optional
        Uses ``group_tip_share``, ``group_pattern_factor``,
        ``group_groove_max_mm`` and ``group_mm`` (none joined with it).

    Returns
    -------
    (n,) int
        Groups after joining (renumbered).
    """
    opts = resolve_options(options)
    if opts.group_mm is not None or not len(graph.a):
        return comp
    # a tip block whose nearest group is another tip block joins once that one has
    # joined the print (s2_039: two of a knobby print's tip blocks, -0.9 % length)
    for _ in range(TIP_ROUNDS):
        joined = _join_tips_once(graph, comp, sizes, opts)
        if joined is comp:
            break
        comp = joined
    return comp


def _join_tips_once(graph: ElementGraph, comp, sizes, opts: AnalysisOptions) -> np.ndarray:
    """One round of :func:`join_tips`: each small group with its nearest group."""
    k = int(comp.max()) + 1 if len(comp) else 0
    if k < 2:
        return comp
    ink = np.bincount(comp, weights=sizes, minlength=k)
    ga, gb = comp[graph.a], comp[graph.b]
    same = ga == gb
    nearest = np.full(len(comp), np.inf)
    for side in (graph.a, graph.b):
        np.minimum.at(nearest, side[same], graph.gaps[same])
    tread = np.full(k, np.nan)
    ok = np.isfinite(nearest)
    order = np.lexsort((nearest[ok], comp[ok]))
    gi, gv = comp[ok][order], nearest[ok][order]
    start = np.flatnonzero(np.r_[True, gi[1:] != gi[:-1]]) if len(gi) else np.zeros(0, int)
    count = np.diff(np.r_[start, len(gi)])
    tread[gi[start]] = 0.5 * (gv[start + (count - 1) // 2] + gv[start + count // 2])
    # every pair of groups that are neighbours, both ways: small -> large
    cross = ~same
    src = np.r_[ga[cross], gb[cross]]
    dst = np.r_[gb[cross], ga[cross]]
    gap = np.r_[graph.gaps[cross], graph.gaps[cross]]
    order = np.lexsort((gap, src))
    src, dst, gap = src[order], dst[order], gap[order]
    first = np.flatnonzero(np.r_[True, src[1:] != src[:-1]]) if len(src) else np.zeros(0, int)
    s, d, g = src[first], dst[first], gap[first]  # each group's nearest neighbour
    join = (
        (ink[s] < opts.group_tip_share * ink[d])
        & (g <= opts.group_pattern_factor * np.nan_to_num(tread[d], nan=0.0))
        & (g <= opts.group_groove_max_mm)
    )
    if not join.any():
        return comp
    return union_labels(k, s[join], d[join])[comp]


@dataclass(frozen=True)
class PartsJoined:
    """Groups after :func:`join_side_by_side`.

    Attributes
    ----------
    comp : (n,) int
        Group of each element (renumbered 0..k-1).
    doubt_gap : (k,) float [mm]
        Per group: the gap of a join or a split that lay within
        ``group_doubt_factor`` of the rule's limit (0: none).
    doubt_joined : (k,) bool
        Whether that doubtful decision joined the parts (else kept them apart).
    """

    comp: np.ndarray
    doubt_gap: np.ndarray
    doubt_joined: np.ndarray


def _straight_side(hull_mm: np.ndarray) -> bool:
    """Whether a part's hull ((k, 2) [mm]) has a straight side at least
    :data:`STRAIGHT_SIDE` of its longer extent: a rib's edge along a groove (a car
    print's half), not a print's rounded outline. Two prints side by side 16-19 mm
    apart, near the side-by-side limit, were both flagged ``grouping_uncertain``
    though each is whole (ten prints on the held-out development sets)."""
    import cv2

    h = cv2.convexHull(np.asarray(hull_mm, np.float32).reshape(-1, 1, 2)).reshape(-1, 2)
    if len(h) < 3:
        return False
    side = np.hypot(*(np.roll(h, -1, axis=0) - h).T).max()
    return bool(side >= STRAIGHT_SIDE * max(cv2.minAreaRect(h)[1]))


def _side_by_side(p: np.ndarray, q: np.ndarray) -> tuple[float, float, float]:
    """How two convex hulls ((k, 2) points) face each other across the line that
    separates them best: the length over which their extents along that line
    overlap, and the shorter and the longer of the two extents along it (the
    lengths along a groove between two ribs)."""
    best, axis = -np.inf, None
    for a, b in ((p, q), (q, p)):
        e = np.roll(a, -1, axis=0) - a
        n = np.column_stack([e[:, 1], -e[:, 0]])
        norm = np.hypot(n[:, 0], n[:, 1])
        ok = norm > 0
        n = n[ok] / norm[ok, None]
        sep = np.maximum(
            (b @ n.T).min(axis=0) - (a @ n.T).max(axis=0),
            (a @ n.T).min(axis=0) - (b @ n.T).max(axis=0),
        )
        if len(sep) and sep.max() > best:
            best, axis = float(sep.max()), n[int(np.argmax(sep))]
    if axis is None:
        return 0.0, 0.0
    t = np.array([-axis[1], axis[0]])
    pa, qa = p @ t, q @ t
    overlap = min(pa.max(), qa.max()) - max(pa.min(), qa.min())
    return float(overlap), float(min(np.ptp(pa), np.ptp(qa))), float(max(np.ptp(pa), np.ptp(qa)))


def join_side_by_side(
    graph: ElementGraph,
    comp: np.ndarray,
    hulls: list,
    *,
    px_mm: float,
    options: AnalysisOptions | None = None,
) -> PartsJoined:
    """Join groups of elements that are parts of one footprint lying side by side
    (a car print's ribs between its circumferential grooves).

    The element rule (:func:`linked_edges`) compares a gap with the elements beside
    it: a car rib's blocks are cut by 1-2 mm sipes, so its 4-10 mm circumferential
    grooves read as paper and every car print of the independent set came out as
    2-4 ribs (s1_061: width -78 %). Here the groups themselves are compared, at the
    scale of the footprint they would make:

    * two groups are candidate parts when they face each other across their gap
      (their extents along it overlap over ``group_rib_overlap`` x the shorter one
      and over ``group_rib_gaps`` x the gap) and both are tread (their widest element
      at least ``group_rib_strokes`` x ``stroke_width_mm``): ribs run side by side
      within one outline; a speck or a block beside a print does not, nor a label's
      line of bold letters (s1_103: 1.5-1.9 mm strokes 6.7 mm from a print, reaching
      beyond its end). A narrower part is a rib when it is one piece of ink running
      alongside the other over ``group_rib_overlap`` x the longer's extent (a car
      print's 2.1 mm middle ribs: held-out 6 sheet 33, the print reported as five);
      any two parts face each other over :data:`RIB_ALONG` of the longer's;
    * candidates are joined nearest first (single linkage); a join is kept when
      its gap is at most ``group_print_gap`` x the smaller extent of the hull of
      everything it joins (a car print's 4-10 mm grooves are <= 0.13 x its 80-185
      mm; two bicycle prints 20-30 mm apart are >= 0.2 x theirs), else split.

    A decision whose gap lies within ``group_doubt_factor`` of that limit, on either
    side, is reported (``doubt_gap``): the print is flagged, ``--group-mm`` decides.

    Parameters
    ----------
    graph : ElementGraph
        The elements' neighbours and gaps (:func:`element_graph`).
    comp : (n,) int
        Group of each element (:func:`linked_edges`, :func:`merge_overlapping`).
    hulls : list of (k, 1, 2) float32 or None
        Hull of each group [px].
    px_mm : float [mm]
        Size of a pixel of the hulls.
    options : AnalysisOptions, optional
        Uses ``group_print_gap``, ``group_rib_overlap``, ``group_rib_gaps``,
        ``group_rib_strokes``, ``stroke_width_mm``, ``group_doubt_factor`` and
        ``group_groove_max_mm`` (defaults when None).

    Returns
    -------
    PartsJoined
    """

    opts = resolve_options(options)
    k = len(hulls)
    none = PartsJoined(comp, np.zeros(k), np.zeros(k, bool))
    if k < 2:
        return none
    ga, gb = comp[graph.a], comp[graph.b]
    cross = ga != gb
    if not cross.any():
        return none
    lo, hi = np.minimum(ga, gb)[cross], np.maximum(ga, gb)[cross]
    gap = graph.gaps[cross]
    key = lo * k + hi
    order = np.lexsort((gap, key))
    key, gap = key[order], gap[order]
    first = np.flatnonzero(np.r_[True, key[1:] != key[:-1]])
    pairs = [(float(gap[i]), int(key[i] // k), int(key[i] % k)) for i in first]
    pts = [
        None if h is None else px_to_mm_length(h.reshape(-1, 2).astype(float), px_mm)
        for h in hulls
    ]
    widest = np.zeros(k)
    np.maximum.at(widest, comp, graph.widths)
    tread = widest >= opts.group_rib_strokes * opts.stroke_width_mm
    count = np.bincount(comp, minlength=k)
    # a narrow part running alongside is one piece of ink (a rib) or a field of
    # FIELD_ELEMENTS fine elements or more (a file or knurl shoulder beside a slick
    # centre: held-out 4th generator seed 8 sheets 5 and 48, 3 mm apart, the
    # shoulders were prints of their own, width -44 % and -71 % with status ok)
    single, field = count == 1, count >= FIELD_ELEMENTS
    links = []
    for g, p, q in sorted(pairs):
        if pts[p] is None or pts[q] is None or not 0 < g <= opts.group_groove_max_mm:
            continue
        if not (tread[p] or tread[q]):
            continue
        overlap, shorter, longer = _side_by_side(pts[p], pts[q])
        narrow = p if not tread[p] else q
        if not (tread[p] and tread[q]) and not (
            (single[narrow] and overlap >= opts.group_rib_overlap * longer)
            or field[narrow]  # (alongside as any two parts, below: a shoulder is shorter)
        ):
            continue  # a narrow part is a rib running alongside the other, one piece
        if (
            overlap >= opts.group_rib_overlap * shorter
            and overlap >= opts.group_rib_gaps * g
            and overlap >= RIB_ALONG * longer
        ):
            links.append((g, p, q))
    if not links:
        return none
    joins = _join_tree(links, pts, k)
    kept, doubt, near = _kept_joins(joins, opts)
    for leaves in near:  # two rounded prints kept apart: no doubt
        if len(leaves) == 2 and not any(_straight_side(pts[i]) for i in leaves):
            for i in leaves:
                doubt.pop(i, None)
    if opts.group_mm is not None:  # the rule's joins; near its limit, either way, ribs
        ribs = [v for v in kept if len(v) >= RIBS_IN_DOUBT or not doubt.keys() & set(v)]
        ribs += [v for v in near if len(v) >= RIBS_IN_DOUBT]
        return _kept_apart(comp, k, joins, ribs)
    lab = np.arange(k)
    for leaves in kept:
        lab[leaves] = leaves[0]
    _, new = np.unique(lab, return_inverse=True)
    n_new = int(new.max()) + 1
    gaps, joined = np.zeros(n_new), np.zeros(n_new, bool)
    for i, (g, j) in doubt.items():
        if g > gaps[new[i]]:
            gaps[new[i]], joined[new[i]] = g, j
    return PartsJoined(new[comp], gaps, joined)


#: a part of this many elements narrower than a tread's (a knurl or file field) can
#: be a rib running alongside another part (:func:`join_side_by_side`)
FIELD_ELEMENTS = 12
#: a speck beside a fine tread smaller than its elements (``Group.fine_area_mm2``)
#: and farther than this many of its pattern gaps from its core is an edge spot
SPECK_GAPS = 1.5
#: ... or one off every site of its lattice (:func:`_off_sites`), fitted to the
#: core's elements within this factor of their median area (whole ones)
SITE_SIZES = 1.5
#: ... the lattice fitted to the nearest this many of them
SITE_ELEMENTS = 16
#: a dot outside a print's core shorter than ``stroke_width_mm`` and under this
#: share of the core's median blob's area is a dust speck (:func:`_spots`; not
#: beside a fine tread, whose dots the outline cuts to crescents as small)
DUST_SHARE = 0.05
#: ... when there are at most this many such dots (more are a row of elements)
DUST_MOST = 3
#: ... but for two alike (within DOT_SIZES in area), one on each side of the print's
#: major axis, mirroring each other about it (along it within this many pixels and
#: half their extent) within MIRROR_MIDDLE of the half-length of its middle, where
#: a lens is widest: the outline's two cut elements of its outer rows
#: (:func:`_mirrored`; a tiny file print's cut diamonds, 0.15-0.19 mm^2, held-out
#: 6 seed 7 sheet 86 at 300 dpi: dropped as dust, width -10.4 % with status ok)
MIRROR_PX = 1.5
MIRROR_MIDDLE = 0.3
#: ... or, of more, those under DUST_SPECK_MM2 with no other small blob outside the
#: core within this many strokes (``stroke_width_mm``): a row of elements' dots lie
#: a pattern pitch apart, and are larger (file rows' dots: 0.12-0.8 mm^2 at 180-400
#: dpi; halo specks 0.06-0.08 mm^2)
DUST_ROW_STROKES = 4.0
DUST_SPECK_MM2 = 0.1
#: a group is a ruler or a frame when ink runs along both long sides of its
#: minimum-area rectangle (FRAME_INSET_PX inside, sampled at FRAME_SAMPLES points)
#: over this share of their length (:func:`_framed`)
FRAME_SIDE = 0.95
FRAME_INSET_PX = 1.5
FRAME_SAMPLES = 400
FRAME_INNER = 0.25
#: lines across the inside of a frame checked for a rib inked along its length
FRAME_RIB_LINES = 15
#: a fragment within SHOULDER_GAP_MM of a print's hull that grows it by at most
#: SHOULDER_HULL times its own ink is a shoulder of it (:func:`join_shoulders`)
SHOULDER_GAP_MM = 5.0
SHOULDER_HULL = 4.0
#: a straight spine with teeth along it is a tiny print (:func:`_toothed_spine`): this
#: long [mm] or more, its core (ink SPINE_CORE of the width from the paper) along
#: SPINE_ALONG of its length, within SPINE_STRAIGHT of its width across
SPINE_MIN_MM = 8.0
SPINE_CORE = 0.15
SPINE_ALONG = 0.8
SPINE_STRAIGHT = 0.6
#: this many dark dots or more about a print make a row of its tread (:func:`_dot_row`)
DOT_ROW = 6
#: a line of bold writing (:func:`text_line`): at most this high [mm], this many
#: times longer, of this many pieces or more (each this share of its ink or more) in
#: one row (overlapping along it by at most this share), their sizes this spread
TEXT_LINE_HEIGHT_MM = 12.0
TEXT_LINE_ASPECT = 4.0
TEXT_LINE_MIN = 4
TEXT_LINE_PIECE = 0.01
TEXT_LINE_OVERLAP = 0.2
TEXT_LINE_SIZES = 2.0
#: ... or this many of them with a bowl (an enclosed hole of at least this share of
#: the median piece's ink)
TEXT_LINE_BOWLS = 2
TEXT_LINE_BOWL = 0.05
#: ... each no longer than this many strokes' widths (a diamond the outline cut; a
#: letter's stroke is longer)
DOT_STROKES = 1.5
#: ... each at least this much ink [mm^2] (the held-out rows' dots: 0.5-0.8; a faint
#: label's bits at 150 dpi: 0.06-0.3, of all sizes), tried first, then the second
#: (held-out 6 sheet 87 at 400 dpi: dots 0.23-0.48, the larger ones along 15 % of
#: the print: no row, width -3.6 % with status ok; with the smaller floor alone a
#: tiny print's row of 0.3 mm^2 dots and smaller specks were no longer alike in
#: size, held-out 8 sheet 54: width -20 %), along this share of the print's length or
#: more (the held-out rows: 0.28 of it, where the outline runs flat), alike in size:
#: their 80th percentile of ink at most DOT_SIZES x their 20th (a tread's row)
DOT_LEAST_MM2 = (0.3, 0.2, 0.05)
#: ... with this many dots or more for each floor (a tiny file print's outer row at
#: 360 dpi: twelve dots of 0.08-0.13 mm^2 beside its slick centre, dropped as thin
#: dots, held-out 6 seed 1 sheet 108: width -10 % with status ok; at the smallest
#: floor a row must be longer than a few halo specks)
DOT_ROWS = (DOT_ROW, DOT_ROW, 10)
#: ... each within this many strokes (``stroke_width_mm``) of the print's other ink
#: for each floor (at the smallest, a pen label's broken strokes touching a print's
#: edge, 'A3 400N', were a row: width +6.6 % with status ok, own set seed 6012 file
#: 6; a tiny file print's outer dots lie a groove, 0.25-0.35 mm, off its diamonds)
DOT_NEAR_STROKES = (np.inf, np.inf, 1.0)
DOT_SPAN = 0.2
#: ... or, with no row, this many dots or more on each side of the print
#: (:func:`_two_sided_row`), their gaps to the body within this factor (a tiny file
#: print's outer row cut to six dots where it is widest, three a side, 0.13-0.2
#: mm^2 a groove off its body: dropped as thin dots, held-out 6 seed 5 sheet 66 at
#: 300 dpi, width -9.3 % with status ok)
TWO_SIDED_DOTS = 3
TWO_SIDED_GAPS = 1.5
#: a found row's neighbours (:func:`_row_neighbours`): dots within this many times
#: the tread's groove of the print's ink or its rows (a tiny file print's corner
#: pieces, 0.06-0.19 mm^2 beside rows of 0.25 mm^2 diamonds, dropped as thin dots:
#: hull area -2 to -4 % with status ok in a sweep of drawn prints at 300-600 dpi)
ROW_GROOVES = 1.5
DOT_SIZES = 2.0
#: with ``group_mm`` given, a join of the side-by-side rule near its limit that
#: would join this many parts or more (a car print's ribs; two prints side by side
#: are two) is flagged as kept apart (:func:`_kept_apart`)
RIBS_IN_DOUBT = 3
#: ... and two parts kept apart near the limit are in doubt only when one has a
#: straight side this share of its longer extent (a rib's edge; :func:`_straight_side`)
STRAIGHT_SIDE = 0.4


def _kept_apart(comp: np.ndarray, k: int, joins: list, kept: list) -> PartsJoined:
    """With ``group_mm`` given: the groups apart that the side-by-side rule would
    join (``kept``), each with the gap of that join as its doubt (not joined). A car
    print's ribs kept apart by a ``group_mm`` under its grooves (held-out sheets:
    13.1 mm given, 18.2 mm grooves) were reported as ribs, each a "print" with status
    ok; two prints parted on purpose that lie as a footprint's ribs would are flagged
    too, the warning naming the gap. A join within ``group_doubt_factor`` of the
    rule's limit, on either side, counts when it joins :data:`RIBS_IN_DOUBT` parts or
    more (a footprint's ribs): ribs 14.2 mm apart across an 84 mm print (0.17 of its
    width, the limit 0.18) kept apart by ``group_mm`` 12.3 were three "prints" with
    status ok (held-out set 14 sheet 119), and so were a car print's ribs just over
    the limit with ``group_mm`` 13.6 (fresh held-out set 15 sheet 57, a PDF at 150
    dpi: the rule alone flags them). Two prints side by side near the limit, parted
    by a ``group_mm`` under their gap as the rule's own warning advises, are not
    flagged again."""
    gaps = np.zeros(k)
    for leaves in kept:
        inside = set(np.ravel(leaves).tolist())
        g = max(j[0] for j in joins if inside.issuperset(np.ravel(j[1]).tolist()))
        gaps[leaves] = g
    return PartsJoined(comp, gaps, np.zeros(k, bool))


def reading_order(g: Group) -> tuple:
    """Sort key of the prints on a sheet: top to bottom by the box's middle row,
    then left to right (the order of ``SortedInk.groups`` and of a sheet's
    prints).

    Parameters
    ----------
    g : Group

    Returns
    -------
    (int, int)
        Twice the box's middle row and its first column [px].
    """
    return (g.rows.start + g.rows.stop, g.cols.start)


def _join_tree(links: list, pts: list, k: int) -> list:
    """Single linkage of ``k`` groups over ``links`` ((gap, p, q), nearest first):
    the joins, each ``(gap, leaves of the joined node, its hull [mm])``."""
    import cv2

    parent = list(range(k))
    members: dict[int, list] = {i: [i] for i in range(k)}
    hull_of = {i: pts[i].astype(np.float32) for i in range(k) if pts[i] is not None}
    joins = []
    for g, p, q in links:
        rp, rq = _root(parent, p), _root(parent, q)
        if rp == rq:
            continue
        parent[rq] = rp
        members[rp] = members[rp] + members.pop(rq)
        both = np.concatenate([hull_of[rp], hull_of.pop(rq)])
        hull_of[rp] = cv2.convexHull(both).reshape(-1, 2)
        joins.append((g, list(members[rp]), hull_of[rp]))
    return joins


def _root(parent: list, i: int) -> int:
    """The root of ``i`` in a union-find forest (halving the path)."""
    while parent[i] != i:
        parent[i] = parent[parent[i]]
        i = parent[i]
    return i


def _kept_joins(joins: list, opts: AnalysisOptions) -> tuple[list, dict, list]:
    """Top down through :func:`_join_tree`'s joins: a join is kept when its gap is at
    most ``group_print_gap`` x the smaller extent of its hull; every join below a
    kept one is kept (its gap is no larger, its whole inside). Returns the kept
    joins' leaves, per leaf ``(gap, joined)`` of a decision within
    ``group_doubt_factor`` of the limit, or not kept and of :data:`RIBS_IN_DOUBT`
    parts or more, and the leaves of the joins not kept within it or of that many
    parts."""
    import cv2

    kept, doubt, near = [], {}, []
    done: set = set()
    limit = opts.group_print_gap
    for g, leaves, hull in reversed(joins):
        if done.issuperset(leaves):
            continue
        ratio = g / max(min(cv2.minAreaRect(hull)[1]), 1e-9)
        # (three parts or more facing each other across grooves up to
        # group_groove_max_mm are a car print's ribs, or prints laid side by side:
        # in doubt however far over the limit; held-out 11 sheet 91, a car print's
        # three ribs 12.9 mm apart, 0.22 of its length: width -66 %, unflagged)
        ribs = ratio > limit and len(leaves) >= RIBS_IN_DOUBT
        if ribs or limit / opts.group_doubt_factor < ratio <= limit * opts.group_doubt_factor:
            for i in leaves:
                doubt.setdefault(i, (g, ratio <= limit))
            if ratio > limit:
                near.append(leaves)
        if ratio <= limit:
            kept.append(leaves)
            done.update(leaves)
    return kept, doubt, near


def union_labels(n: int, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Connected components of ``n`` nodes joined by the edges (a, b).

    Parameters
    ----------
    n : int
    a, b : (m,) int

    Returns
    -------
    (n,) int
        Component index 0..k-1 of each node, in order of first appearance.
    """
    lab = np.arange(n)
    if len(a):
        while True:
            m = np.minimum(lab[a], lab[b])
            new = lab.copy()
            np.minimum.at(new, a, m)
            np.minimum.at(new, b, m)
            new = new[new]  # pointer jumping
            if np.array_equal(new, lab):
                break
            lab = new
    _, comp = np.unique(lab, return_inverse=True)
    return comp


def merge_overlapping(hulls: list, comp: np.ndarray) -> np.ndarray:
    """Join groups whose convex hulls overlap by more than a fifth of the smaller.

    Parameters
    ----------
    hulls : list of (k, 1, 2) float32 or None
        Hull of each group (cv2 point layout); None for an empty group.
    comp : (n,) int
        Group of each element.

    Returns
    -------
    (n,) int
        Groups after joining (renumbered).
    """
    import cv2

    k = len(hulls)
    boxes = np.array([cv2.boundingRect(h) if h is not None else (0, 0, 0, 0) for h in hulls])
    areas = np.array([cv2.contourArea(h) if h is not None else 0.0 for h in hulls])
    x0, y0 = boxes[:, 0], boxes[:, 1]
    x1, y1 = x0 + boxes[:, 2], y0 + boxes[:, 3]
    ia, ib = np.nonzero(np.triu((x0[:, None] < x1) & (x0 < x1[:, None]), 1))
    ea, eb = [], []
    for i, j in zip(ia, ib, strict=True):
        if not (y0[i] < y1[j] and y0[j] < y1[i]) or min(areas[i], areas[j]) <= 0:
            continue
        inter, _ = cv2.intersectConvexConvex(hulls[i], hulls[j])
        if inter > 0.2 * min(areas[i], areas[j]):
            ea.append(i)
            eb.append(j)
    if not ea:
        return comp
    joined = union_labels(k, np.array(ea), np.array(eb))
    return joined[comp]


@dataclass(frozen=True)
class PrintCheck:
    """Whether a group looks like a contact print.

    Attributes
    ----------
    ok : bool
    reason : str
        Why not ('' when ``ok``).
    kind : str
        What it is instead: 'dust', 'fragment', 'line', 'writing' or 'texture'.
    short : bool
        Set aside only for being shorter than a print (``min_patch_length_mm``): a
        letter's piece, or an element of a print its grouping left out
        (:func:`inkprint.pattern.join_pattern_pieces`).
    """

    ok: bool
    reason: str = ""
    kind: str = ""
    short: bool = False
    #: set aside only because a print this small or narrow is solid
    #: (:func:`_solid_if_small`): a tiny tread print is not (:func:`maybe_tiny_print`)
    small: bool = False


def is_print(
    group: Group,
    *,
    mm_per_px: float,
    options: AnalysisOptions | None = None,
    floor_mm2: float | None = None,
    image_shape: tuple[int, int] | None = None,
) -> PrintCheck:
    """Whether a group looks like a contact print; if not, what it is and why.

    Parameters
    ----------
    group : Group
    mm_per_px : float [mm / px]
    options : AnalysisOptions, optional
        Uses ``min_patch_area_mm2``, ``min_patch_length_mm``, ``min_patch_width_mm``,
        ``max_patch_aspect`` and
        ``min_net_to_gross`` (defaults when None).
    floor_mm2 : float, optional [mm^2]
        Ink-area floor (default: ``options.min_patch_area_mm2`` or 0).
    image_shape : (rows, cols), optional
        With it, a group spanning three or four sides of the image is texture.

    Returns
    -------
    PrintCheck
    """
    import cv2

    opts = resolve_options(options)
    floor = floor_mm2 if floor_mm2 is not None else (opts.min_patch_area_mm2 or 0.0)
    area = area_px_to_mm2(group.n_pixels, mm_per_px)
    if area < floor:
        return PrintCheck(False, f"too little ink ({area:.2f} mm^2 < {floor:.3g})", "dust")
    if image_shape is not None and _sides(group, image_shape) >= 3:
        return PrintCheck(
            False, "texture or noise spread over the whole page, not a print", "texture"
        )
    # the rectangle and the hull of all the ink pixels are those of the row ends
    pts = outline_points(group.mask).reshape(-1, 2).astype(np.float32)
    (_, _), (a, b), _ = cv2.minAreaRect(pts)
    length = px_to_mm_length(max(a, b) + 1, mm_per_px)
    width = px_to_mm_length(min(a, b) + 1, mm_per_px)
    hull = cv2.convexHull(pts)
    # (a print's end cut by the image's edge is measured and flagged clipped)
    cut = image_shape is not None and _sides(group, image_shape, near=False) > 0
    if image_shape is not None and _punch_hole(
        group, hull, (length, width), mm_per_px, image_shape
    ):
        return PrintCheck(
            False,
            f"a punch hole ({0.5 * (length + width):.1f} mm round, solid, near the edge)",
            "hole",
        )
    if length < opts.min_patch_length_mm and not cut:
        return PrintCheck(
            False,
            f"a mark or a letter's piece ({length:.1f} mm long: shorter than a print)",
            "writing",
            short=True,
        )
    if width < opts.min_patch_width_mm:
        return PrintCheck(False, f"a line ({width:.2f} mm wide)", "line")
    if length / width > opts.max_patch_aspect:
        return PrintCheck(False, f"a line ({length / width:.0f} x longer than wide)", "line")
    if _framed(group.mask, cv2.minAreaRect(pts)):
        return PrintCheck(
            False,
            f"a ruler or a frame ({length:.0f} x {width:.1f} mm, straight lines along both "
            f"long sides)",
            "line",
        )
    fill = hull_fill(group.n_pixels, hull)
    if fill < opts.min_net_to_gross:
        return PrintCheck(
            False, f"writing or marks ({100 * fill:.0f} % of its hull inked)", "writing"
        )
    if (
        length / width >= opts.text_line_aspect
        and fill < TEXT_LINE_FILL
        and _letters_in_a_row(group.mask, pts, width_px=min(a, b) + 1, mm_per_px=mm_per_px)
    ):
        return PrintCheck(
            False,
            f"a line of writing ({length:.0f} x {width:.1f} mm, letters across it)",
            "writing",
        )
    if fill < TEXT_LINE_FILL and _rows_of_letters(group.mask, pts, mm_per_px, opts):
        return PrintCheck(
            False,
            f"lines of writing ({length:.0f} x {width:.1f} mm, letters in rows)",
            "writing",
        )
    # a print cut by the image's edge need not be solid: measured, flagged clipped
    # (a knobby print's last 9 x 7 mm read as a letter and went missing)
    if cut:
        return PrintCheck(True)
    return _solid_if_small(group.mask, hull, fill, min(a, b) + 1, mm_per_px, opts)


def join_shoulders(groups: list, fragments: list, *, mm_per_px: float) -> tuple[list, list]:
    """Join to a print the fragments beside it that are pieces of its outline.

    A groove running out to a print's outline cuts off its shoulder: a sliver
    beyond the groove, too far (3 mm and more) for the footprint rule and too small
    beside the print (``min_patch_fraction``) to be one of its own (held-out motorcycle
    road prints: two crescents 39 and 71 mm^2 beside a 5700 mm^2 print set aside as
    fragments, hull area -2 to -5 % with status ok, four prints of three sets). A
    fragment is a shoulder when it lies within :data:`SHOULDER_GAP_MM` of the
    print's hull and joining it grows the hull by at most :data:`SHOULDER_HULL`
    times its own ink: it hugs the outline (a small print 10 mm off a large one
    grows it by many times its ink). The section 7.1.1 rule then judges it with the
    print's other blobs.

    Parameters
    ----------
    groups : list of Group
        The prints.
    fragments : list of Group
        Groups too small beside the largest print to be prints.
    mm_per_px : float [mm / px]

    Returns
    -------
    tuple of (list of Group, list of Group)
        The prints with their shoulders, and the fragments left.
    """
    import cv2

    if not groups or not fragments:
        return groups, fragments
    gap_px = mm_to_px_length(SHOULDER_GAP_MM, mm_per_px)
    hulls = []
    for g in groups:
        pts = np.add(outline_points(g.mask).reshape(-1, 2), (g.cols.start, g.rows.start))
        hulls.append(cv2.convexHull(pts.astype(np.float32)))
    groups, left = list(groups), []
    for f in fragments:
        pts = np.add(outline_points(f.mask).reshape(-1, 2), (f.cols.start, f.rows.start))
        pts = pts.astype(np.float32)
        for i, hull in enumerate(hulls):
            x, y, w, h = cv2.boundingRect(hull)
            if (
                f.cols.start > x + w + gap_px
                or f.cols.stop < x - gap_px
                or f.rows.start > y + h + gap_px
                or f.rows.stop < y - gap_px
            ):
                continue
            if _outside_distance(pts.astype(float), hull.reshape(-1, 2)).min() > gap_px:
                continue
            grown = cv2.convexHull(np.vstack([hull.reshape(-1, 2), pts]))
            if cv2.contourArea(grown) - cv2.contourArea(hull) > SHOULDER_HULL * f.n_pixels:
                continue
            groups[i], hulls[i] = union(groups[i], f), grown
            break
        else:
            left.append(f)
    return groups, left


def union(g: Group, other: Group) -> Group:
    """``g`` with ``other``'s ink added (their boxes' union; ``g``'s other fields).

    Parameters
    ----------
    g, other : Group

    Returns
    -------
    Group
    """
    r0, c0 = min(g.rows.start, other.rows.start), min(g.cols.start, other.cols.start)
    r1, c1 = max(g.rows.stop, other.rows.stop), max(g.cols.stop, other.cols.stop)
    mask = np.zeros((r1 - r0, c1 - c0), bool)
    for h in (g, other):
        mask[h.rows.start - r0 : h.rows.stop - r0, h.cols.start - c0 : h.cols.stop - c0] |= h.mask
    return replace(g, rows=slice(r0, r1), cols=slice(c0, c1), mask=mask)


def text_line(group: Group, *, mm_per_px: float) -> bool:
    """Whether a group is a line of bold writing alone: a marker's label 'G-One
    40-622' (61 x 6 mm, 11 letters) away from the prints was reported as a print
    (held-out 6 seed 1 sheet 92, rectified).

    Such a group is at most :data:`TEXT_LINE_HEIGHT_MM` across and at least
    :data:`TEXT_LINE_ASPECT` times longer than that; its pieces (each at least
    :data:`TEXT_LINE_PIECE` of its ink), :data:`TEXT_LINE_MIN` or more, lie in one row
    along it (consecutive pieces overlapping along it by at most
    :data:`TEXT_LINE_OVERLAP` of the shorter) and differ in size as letters do (their
    80th percentile of ink over their 20th more than :data:`TEXT_LINE_SIZES`; a
    hyphen, an 'i' and a 'G') or :data:`TEXT_LINE_BOWLS` of them have a bowl (an
    enclosed hole: 'O', 'e', '6'). A narrow print's row of bars across it (a ladder
    tread) is alike bar to bar, and no bar has a hole.

    Parameters
    ----------
    group : Group
    mm_per_px : float [mm / px]

    Returns
    -------
    bool
    """
    import cv2

    pts = outline_points(group.mask)  # (the hull's, not every pixel: a large print's)
    if pts is None:
        return False
    (_, _), (a, b), turn = cv2.minAreaRect(pts)
    long, across = max(a, b) + 1.0, min(a, b) + 1.0
    if (
        px_to_mm_length(across, mm_per_px) > TEXT_LINE_HEIGHT_MM
        or long < TEXT_LINE_ASPECT * across
    ):
        return False
    n, lab, st, _ = cv2.connectedComponentsWithStats(group.mask.view(np.uint8), connectivity=8)
    ink = st[1:, cv2.CC_STAT_AREA].astype(float)
    keep = np.flatnonzero(ink >= TEXT_LINE_PIECE * ink.sum()) + 1
    if len(keep) < TEXT_LINE_MIN:
        return False
    t = np.radians(turn if a >= b else turn + 90.0)  # along the line: the box's long side
    axis = np.array([np.cos(t), np.sin(t)])
    ys, xs = np.nonzero(np.isin(lab, keep))
    t, ids = xs * axis[0] + ys * axis[1], lab[ys, xs]
    lo, hi = piece_range(ids, t, n)
    lo, hi = lo[keep], hi[keep]
    order = np.argsort(lo)
    lo, hi = lo[order], hi[order]
    overlap = np.minimum(hi[:-1], hi[1:]) - np.maximum(lo[:-1], lo[1:])
    shorter = np.minimum(hi - lo, np.roll(hi - lo, -1))[:-1] + 1.0
    if (overlap > TEXT_LINE_OVERLAP * shorter).any():
        return False
    p20, p80 = np.percentile(ink[keep - 1], [20, 80])
    if p80 > TEXT_LINE_SIZES * p20:
        return True
    # or letters with a bowl ('O', 'e', '6', '4'): a tread's bars and blocks have none
    inv = (lab == 0).view(np.uint8)
    _, holes, hst, _ = cv2.connectedComponentsWithStats(inv, connectivity=4)
    h, w = lab.shape
    x0, y0, x1, y1 = hst[:, 0], hst[:, 1], hst[:, 0] + hst[:, 2], hst[:, 1] + hst[:, 3]
    inner = (x0 > 0) & (y0 > 0) & (x1 < w) & (y1 < h)
    inner &= hst[:, cv2.CC_STAT_AREA] >= TEXT_LINE_BOWL * np.median(ink[keep - 1])
    inner[0] = False
    # the piece round each bowl: left of the bowl's first pixel (raster order)
    _, first = np.unique(holes.ravel(), return_index=True)
    r, c = np.divmod(first[np.flatnonzero(inner)], w)
    around = lab[r, c - 1][c > 0]
    return len(np.intersect1d(around[around > 0], keep)) >= TEXT_LINE_BOWLS


def word_in_a_line(group: Group, writing: np.ndarray, *, mm_per_px: float) -> bool:
    """Whether a small group is a word of a line of writing set aside beside it.

    A marker's bold letters fused into a word read as a tiny print when the rest of
    their line was set aside apart from them: 'Bite' (9.6 x 3.3 mm, 4 pieces) of
    '... Bite 40' and 'p =' (8.7 x 4.1 mm) of 'p = 2.4 bar' were reported as prints
    on pages of writing only (held-out set 14 sheets 93 and 69).

    Such a group holds under :data:`SMALL_PRINT_MM2` of ink and lies in line with a
    mark of writing that runs along the line (:data:`WORD_LINE_ASPECT` times longer
    than high or more): their extents across the line overlap by
    :data:`WORD_ROW_OVERLAP` of the lower one, neither is more than
    :data:`WORD_HEIGHT_RATIO` times the other's height, and the paper between them
    along the line is at most :data:`WORD_GAP` of the group's height. Its ink is
    letters: a piece spanning :data:`TEXT_ROW_SPAN` of the lower height across the
    line, and :data:`WORD_LETTERS` or more pieces (each :data:`WORD_PIECE_SHARE` of
    its ink or more: 'p' and '=') or, one fused piece ('40'), shorter along the line
    than :data:`WORD_ASPECT` times its height; no piece runs along the line
    :data:`WORD_ASPECT` times the row's height or more. A tiny print is one solid
    body at least 2.5 times as long as wide (a track tire's: 10-18 x 2.5-4 mm; with
    a letter joined to it, it is no word) or a lattice of elements ~1 mm
    (:mod:`inkprint.lattice`, found apart).

    Parameters
    ----------
    group : Group
    writing : (k, 4) int [px]
        Boxes (row0, col0, row1, col1) of the marks of writing on the sheet.
    mm_per_px : float [mm / px]

    Returns
    -------
    bool
    """
    import cv2

    if not len(writing) or area_px_to_mm2(group.n_pixels, mm_per_px) >= SMALL_PRINT_MM2:
        return False
    box = np.array([group.rows.start, group.cols.start, group.rows.stop, group.cols.stop])
    b = np.asarray(writing, float).reshape(-1, 4)
    stats = None
    for a, k in ((0, 1), (1, 0)):  # across (a) a line along (k) the rows, or columns
        height, length = box[a + 2] - box[a], box[k + 2] - box[k]
        if length < height:
            continue  # a word runs along its line
        other = b[:, a + 2] - b[:, a]
        overlap = np.minimum(box[a + 2], b[:, a + 2]) - np.maximum(box[a], b[:, a])
        gap = np.maximum(b[:, k] - box[k + 2], box[k] - b[:, k + 2])
        beside = (
            (b[:, k + 2] - b[:, k] >= WORD_LINE_ASPECT * other)  # a piece of a line
            & (overlap >= WORD_ROW_OVERLAP * np.minimum(height, other))
            & (other <= WORD_HEIGHT_RATIO * height)
            & (height <= WORD_HEIGHT_RATIO * other)
            & (gap <= WORD_GAP * height)
        )
        if not beside.any():
            continue
        if stats is None:
            stats = components_with_stats(group.mask.view(np.uint8), connectivity=8)[2][1:]
        extent = stats[:, cv2.CC_STAT_HEIGHT if a == 0 else cv2.CC_STAT_WIDTH]
        run = stats[:, cv2.CC_STAT_WIDTH if a == 0 else cv2.CC_STAT_HEIGHT]
        ink = stats[:, cv2.CC_STAT_AREA]
        line = min(height, other[beside].max())  # a row's height
        if (run >= WORD_ASPECT * line).any():
            continue  # a piece longer than letters are (a tiny print's body)
        pieces = np.count_nonzero(ink >= WORD_PIECE_SHARE * ink.sum())
        if (extent >= TEXT_ROW_SPAN * line).any() and pieces >= WORD_LETTERS:
            return True
        if length < WORD_ASPECT * height:  # one piece: a word's fused letters
            return True
    return False


def _framed(mask: np.ndarray, rect: tuple) -> bool:
    """Whether ink runs straight along both long sides of its minimum-area
    rectangle ``rect`` (OpenCV's, over ``mask``'s pixels) over :data:`FRAME_SIDE` of
    their length, with paper inside those lines (a line :data:`FRAME_INNER` of the
    width further in is inked along less than half its length): a ruler's edges or
    a drawn frame. A print's outline is curved at its ends (a car print's straight
    rib edges end in its rounded shoulders) and a solid rib is ink inside too
    (held-out seed 8 sheet 15: a ruler's frame, ticks and numbers, 242 x 25 mm,
    reported as a print, status ok)."""
    import cv2

    box = cv2.boxPoints(rect)  # (4, 2) x, y corners in order
    sides = [(box[i], box[(i + 1) % 4]) for i in range(4)]
    lengths = np.array([float(np.hypot(*(b - a))) for a, b in sides])
    width = float(lengths.min())
    if lengths.max() < 4 * FRAME_INSET_PX or width < 4 * FRAME_INSET_PX:
        return False
    centre = box.mean(axis=0)
    longest = np.argsort(lengths)[-2:]  # the two long sides
    for k in longest:
        a, b = sides[k]
        inward = centre - 0.5 * (a + b)
        inward = inward / max(float(np.hypot(*inward)), 1e-9)
        edge = _inked_along(mask, a, b, FRAME_INSET_PX * inward)
        inner = _inked_along(mask, a, b, FRAME_INNER * width * inward)
        if edge < FRAME_SIDE or inner >= 0.5:
            return False
    # nothing inked along the whole length inside (from the last side, across to the
    # other): a ribbed print's inner ribs are (fifth held-out seed 4 sheet 16: a 92 x
    # 21 mm print of ribs with straight sides, the line a quarter of its width in
    # lying in a groove: "a ruler or a frame")
    for f in np.linspace(FRAME_INNER, 1.0 - FRAME_INNER, FRAME_RIB_LINES):
        if _inked_along(mask, a, b, f * width * inward) >= FRAME_SIDE:
            return False
    return True


def _inked_along(mask: np.ndarray, a: np.ndarray, b: np.ndarray, shift: np.ndarray) -> float:
    """The share of :data:`FRAME_SAMPLES` points on the segment ``a``-``b`` (x, y
    [px]) moved by ``shift`` that have ink within a pixel."""
    t = np.linspace(0.0, 1.0, FRAME_SAMPLES)[:, None]
    pts = a + t * (b - a) + shift
    r, c = np.round(pts[:, 1]).astype(int), np.round(pts[:, 0]).astype(int)
    # the 3 x 3 pixels around each point at once (k, 9)
    rr = np.clip(r[:, None] + _AROUND[0], 0, mask.shape[0] - 1)
    cc = np.clip(c[:, None] + _AROUND[1], 0, mask.shape[1] - 1)
    return float(mask[rr, cc].astype(bool).any(axis=1).mean())


#: the row and column offsets of a pixel's 3 x 3 neighbourhood, itself included
_AROUND = np.mgrid[-1:2, -1:2].reshape(2, -1)


def _solid_if_small(mask, hull, fill: float, width_px: float, mm_per_px: float, opts):
    """The :class:`PrintCheck` of a group whose hull (OpenCV points) is under
    :data:`SMALL_PRINT_MM2` or whose width ``width_px`` [px] is under
    :data:`NARROW_PRINT_MM`: such a print is solid (a track tire's,
    :func:`_small_print_fill`), a word of a marker's fused bold letters is not (43 x
    4.9 mm in three pieces, 0.7 of its hull inked, 4-9 mm below a slick print:
    reported as a print of its own)."""
    import cv2

    hull_mm2 = area_px_to_mm2(cv2.contourArea(hull), mm_per_px)
    width = px_to_mm_length(width_px, mm_per_px)
    if fill >= SMALL_PRINT_FILL or (hull_mm2 >= SMALL_PRINT_MM2 and width >= NARROW_PRINT_MM):
        return PrintCheck(True)
    fill = _small_print_fill(mask, fill, width_px, mm_per_px, opts)
    if fill >= SMALL_PRINT_FILL:
        return PrintCheck(True)
    return PrintCheck(
        False,
        f"a letter or a mark ({hull_mm2:.0f} mm^2, {width:.1f} mm wide, {100 * fill:.0f} % "
        f"of its hull inked: a print this small or narrow is solid)",
        "writing",
        small=True,
    )


def maybe_tiny_print(mask: np.ndarray, *, mm_per_px: float) -> bool:
    """Whether a group that the small-print rule set aside (a print this small or
    narrow is solid: :func:`_solid_if_small`) may be a tiny tread print after all.

    Its significant pieces (at least :data:`MAYBE_SPECK` of the largest) are a
    tread's elements, small across it (spanning at most :data:`MAYBE_SPAN` of its
    width on the area-weighted mean), or it is one scalloped body at least
    :data:`MAYBE_BODY_MM` long and :data:`MAYBE_BODY_ASPECT` times as long as wide
    that inks its hull's core (:data:`MAYBE_CORE_FILL`); either at most
    :data:`MAYBE_ASPECT` times as long as wide. A word's letters each span its
    height; fused to one body in a bold marker, they leave gaps in its core. Such a
    group is measured and flagged ``maybe_mark``, not dropped (held-out generator
    6, seeds 1-8: 17 prints missing, 9 of them tiny prints set aside by the rule or
    as fragments).

    Parameters
    ----------
    mask : (h, w) bool
        The group's ink.
    mm_per_px : float [mm / px]

    Returns
    -------
    bool

    Raises
    ------
    InvalidInput
        ``mask`` not a (rows, cols) mask, or ``mm_per_px`` not a positive finite
        scale.
    """
    import cv2

    mm_per_px = check_mm_per_px(mm_per_px)
    mask = np.asarray(mask, bool)
    if mask.ndim != 2:
        raise InvalidInput("mask", mask.shape, "a (rows, cols) mask")
    n, lab, st, _ = components_with_stats(mask, connectivity=8)
    if n < 2:
        return False
    area = st[1:, cv2.CC_STAT_AREA]
    big = area >= MAYBE_SPECK * area.max()
    if np.count_nonzero(big) == 1:
        return _solid_core_body(lab == 1 + int(np.argmax(area)), mm_per_px)
    rows, cols = np.nonzero(lab)
    pts = np.column_stack([cols, rows]).astype(np.float32)
    (_, _), (a, b), angle = cv2.minAreaRect(pts)
    width = min(a, b) + 1.0
    if max(a, b) + 1.0 > MAYBE_ASPECT * width:
        return False
    # each piece's extent across the group (along the rectangle's shorter side)
    t = np.deg2rad(angle) + (0.5 * np.pi if a > b else 0.0)
    across = cols * np.cos(t) + rows * np.sin(t)
    k = lab[rows, cols] - 1
    lo, hi = np.full(n - 1, np.inf), np.full(n - 1, -np.inf)
    reduce_at(np.minimum, lo, k, values=across)
    reduce_at(np.maximum, hi, k, values=across)
    span = (hi - lo + 1.0)[big] / width
    return float(np.average(span, weights=area[big])) <= MAYBE_SPAN


def _solid_core_body(body: np.ndarray, mm_per_px: float) -> bool:
    """Whether one body ((h, w) bool) is as long and slender as a tiny print
    (:data:`MAYBE_BODY_MM`, :data:`MAYBE_BODY_ASPECT`, :data:`MAYBE_ASPECT`) and
    inks its hull's core (:data:`MAYBE_CORE_DEPTH`, :data:`MAYBE_CORE_FILL`)."""
    import cv2

    pts = outline_points(body).reshape(-1, 2).astype(np.float32)
    (_, _), (a, b), _ = cv2.minAreaRect(pts)
    length, width = max(a, b) + 1.0, min(a, b) + 1.0
    slender = MAYBE_BODY_ASPECT <= length / width <= MAYBE_ASPECT
    if px_to_mm_length(length, mm_per_px) < MAYBE_BODY_MM or not slender:
        return False
    hull = np.zeros((body.shape[0] + 2, body.shape[1] + 2), np.uint8)
    cv2.fillPoly(hull, [cv2.convexHull(pts).astype(np.int32) + 1], 1)
    depth = cv2.distanceTransform(hull, cv2.DIST_L2, 5)[1:-1, 1:-1]
    core = depth >= MAYBE_CORE_DEPTH * width
    return bool(core.any()) and float(body[core].mean()) >= MAYBE_CORE_FILL


def _small_print_fill(mask: np.ndarray, fill: float, width_px: float, mm_per_px, opts) -> float:
    """The inked share of a tiny print's hull as judged (``fill``: of the hull of
    ``mask``; ``width_px``: its width [px]): with its halo specks left out, its pores
    and notches closed, or, scalloped by its tread deeper than a stroke, as solid
    when it is one body (``SMALL_PRINT_FILL`` then)."""
    fill = max(fill, _main_blob_fill(mask))  # halo specks widen a tiny hull
    if fill < SMALL_PRINT_FILL:
        # a file tread's pores and notches are narrower than a pen stroke (a track
        # tire's 14 x 2.9 mm print at 400 dpi: 71 % inked, 35 mm^2, missing)
        stroke = mm_to_px_length(opts.stroke_width_mm, mm_per_px)
        fill = max(fill, _closed_fill(mask, stroke))
    if SMALL_BODY_FILL <= fill < SMALL_PRINT_FILL:
        # a disk nearly its width fits in it, in no letter's strokes (a track tire's
        # 10.4 x 2.2 mm file print at 200 dpi: 80 % inked, missing); or it is a
        # straight spine with teeth along it
        if _body_share(mask, width_px) >= SMALL_BODY_SHARE or _toothed_spine(
            mask, width_px, mm_per_px
        ):
            fill = SMALL_PRINT_FILL
    if fill < SMALL_PRINT_FILL and _rib_stack(mask, mm_per_px, opts):
        fill = SMALL_PRINT_FILL
    return fill


def _rib_stack(mask: np.ndarray, mm_per_px: float, opts) -> bool:
    """Whether a tiny group is a rib print: :data:`RIB_STACK_MIN` or more parallel
    bars (their longer sides within :data:`RIB_STACK_PARALLEL_DEG`), all but one
    :data:`RIB_STACK_WIDE` strokes wide or more (``stroke_width_mm``: a marker's
    letters are narrower; the outline may cut an outer rib thin), whose
    grooves a disk two strokes wide closes to :data:`SMALL_PRINT_FILL` of its hull
    (held-out 2026-11-29 seeds 1 and 2: 10-16 mm prints of three ribs 2.2-3 mm
    wide, 0.74 of the hull inked, set aside as "a letter or a mark"; six missing).
    Two bars are a rib print when the group is :data:`RIB_PAIR_MM` long or more
    (seeds 1-3: 13-18 mm prints of two ribs, missing), or both are
    :data:`RIB_PAIR_BOLD` strokes wide; a marker's '=' is two shorter, thinner
    bars."""
    import cv2

    n, lab, st, _ = components_with_stats(mask.view(np.uint8), connectivity=8)
    areas = st[1:, cv2.CC_STAT_AREA]
    big = 1 + np.flatnonzero(areas >= RIB_STACK_SPECK * areas.max()) if n > 1 else []
    pts = outline_points(mask).reshape(-1, 2).astype(np.float32)
    longest = px_to_mm_length(max(cv2.minAreaRect(pts)[1]) + 1, mm_per_px)
    if len(big) < 2:
        return False
    stroke = mm_to_px_length(opts.stroke_width_mm, mm_per_px)
    angles, widths, outlines = [], [], []
    for k in big:
        x, y, w, h = st[k, :4]
        pts = outline_points(lab[y : y + h, x : x + w] == k).reshape(-1, 2).astype(np.float32)
        (_, _), (a, b), angle = cv2.minAreaRect(pts)
        widths.append(min(a, b) + 1)
        angles.append(np.deg2rad(angle + (0.0 if a >= b else 90.0)))
        outlines.append(pts + np.array([x, y], np.float32))
    bold = len(big) == 2 and min(widths) >= RIB_PAIR_BOLD * stroke
    least = 2 if longest >= RIB_PAIR_MM or bold else RIB_STACK_MIN
    if len(big) < least:
        return False
    wide = [b for b in widths if b >= RIB_STACK_WIDE * stroke]
    if len(wide) < least - 1:  # (the outer ribs the outline cut may be thin)
        return False
    # axial directions: doubled angles, their mean resultant
    c, s = np.cos(2 * np.array(angles)), np.sin(2 * np.array(angles))
    mean = 0.5 * np.arctan2(s.mean(), c.mean())
    spread = np.abs(np.angle(np.exp(1j * (np.array(angles) - mean) * 2))) / 2
    if np.rad2deg(spread.max()) > RIB_STACK_PARALLEL_DEG:
        return False
    # side by side: each bar lies along the longest over RIB_STACK_BESIDE of its own
    # length (a marker's word fused into pieces end to end, 43 x 4.9 mm, is no rib
    # print)
    d = np.array([np.cos(mean), np.sin(mean)])
    spans = np.array([[(o @ d).min(), (o @ d).max()] for o in outlines])
    ref = spans[np.argmax(spans[:, 1] - spans[:, 0])]
    shared = np.minimum(spans[:, 1], ref[1]) - np.maximum(spans[:, 0], ref[0])
    if (shared < RIB_STACK_BESIDE * (spans[:, 1] - spans[:, 0])).any():
        return False
    # the bars alone (a speck 2.6 mm off a 20 mm two-rib print, in its group, left
    # 0.61 of the hull inked: held-out seed 4 sheet 36), their grooves closed by a
    # disk as wide as the narrowest wide bar, two strokes at least: a rib tire's
    # grooves are narrower than its ribs (seed 2 sheet 114: ribs 2.3 and 3.4 mm
    # wide, the groove 1.9 mm), a marker's '=' has a wider gap than its strokes;
    # three strokes at most
    # (the bars two strokes wide or more when there are: an outer rib the outline
    # cut thin narrowed the disk, and a 1.9 mm groove stayed open, seed 2 sheet 114)
    bars = [b for b in wide if b >= 2.0 * stroke] or wide
    size = float(np.clip(min(bars, default=0.0), 2.0 * stroke, 3.0 * stroke))
    return _closed_fill(np.isin(lab, big), size) >= SMALL_PRINT_FILL


def _toothed_spine(mask: np.ndarray, width_px: float, mm_per_px: float) -> bool:
    """Whether one piece of ink is a straight spine with teeth along it, a track
    tire's file print: :data:`SPINE_MIN_MM` long or more, its core (ink
    :data:`SPINE_CORE` of its width or more from the paper) one straight bar along
    :data:`SPINE_ALONG` of its length or more, no wider across than
    :data:`SPINE_STRAIGHT` of its width. A 17.7 x 3.6 mm print whose rectangular
    teeth left 0.79 of its hull inked, its spine 0.45 of its width, was "a letter
    or a mark" (held-out set 12 sheet 103; set 6 sheet 77 alike, 0.78); a letter is
    shorter, a bold 'l' narrower than a print (``min_patch_width_mm``)."""
    import cv2

    n, _, _, _ = components_with_stats(mask.view(np.uint8), connectivity=8)
    if n != 2:
        return False
    pts = outline_points(mask).reshape(-1, 2).astype(np.float32)
    (_, _), (a, b), angle = cv2.minAreaRect(pts)
    if px_to_mm_length(max(a, b) + 1, mm_per_px) < SPINE_MIN_MM:
        return False
    dist = cv2.distanceTransform(np.pad(mask.view(np.uint8), 1), cv2.DIST_L2, 5)[1:-1, 1:-1]
    rows, cols = np.nonzero(dist >= SPINE_CORE * width_px)
    if len(rows) < 2:
        return False
    t = np.deg2rad(angle + (0.0 if a >= b else 90.0))  # along the longer side
    u = cols * np.cos(t) + rows * np.sin(t)
    v = -cols * np.sin(t) + rows * np.cos(t)
    rr, cc = np.nonzero(mask)
    whole = np.ptp(cc * np.cos(t) + rr * np.sin(t)) + 1.0
    covered = np.unique(np.round(u).astype(int)).size
    lo, hi = np.percentile(v, [2, 98])  # (a tooth's root reaches the core here and there)
    return covered >= SPINE_ALONG * whole and hi - lo + 1.0 <= SPINE_STRAIGHT * width_px


def _punch_hole(group: Group, hull: np.ndarray, size: tuple, mm_per_px: float, shape) -> bool:
    """Whether a group is a punch hole of the page (the scanner's dark lid showing
    through it): a solid disc (:func:`_hole_sized`) filling :data:`PUNCH_HOLE_FILL`
    of its ``hull`` (OpenCV points). No tire print is a solid disc: the smallest (a
    track tire's) are 2.5-4 mm wide and 10-18 mm long. ``size``: (length, width)
    of its rectangle [mm]."""
    h, w = shape
    r = 0.5 * (group.rows.start + group.rows.stop)
    c = 0.5 * (group.cols.start + group.cols.stop)
    edge = px_to_mm_length(min(r, c, h - r, w - c), mm_per_px)
    return bool(_hole_sized(*size, edge)) and hull_fill(group.n_pixels, hull) >= PUNCH_HOLE_FILL


def _hole_sized(long_mm, short_mm, edge_mm):
    """Whether ink of extents ``long_mm`` x ``short_mm`` [mm] whose centre lies
    ``edge_mm`` from the image's edge has a punch hole's size and place: round
    (:data:`PUNCH_HOLE_ROUND`), :data:`PUNCH_HOLE_MM` across (ISO 838 and the US
    three-hole punch: 5.5-8 mm), within :data:`PUNCH_HOLE_EDGE_MM` of the edge.

    Parameters
    ----------
    long_mm, short_mm, edge_mm : float or (n,) float [mm]

    Returns
    -------
    bool or (n,) bool
    """
    lo, hi = PUNCH_HOLE_MM
    return (
        (short_mm >= lo)
        & (long_mm <= hi)
        & (long_mm <= PUNCH_HOLE_ROUND * short_mm)
        & (edge_mm <= PUNCH_HOLE_EDGE_MM)
    )


def _letters_in_a_row(
    mask: np.ndarray, pts: np.ndarray, *, width_px: float, mm_per_px: float
) -> bool:
    """Whether a long group's ink is :data:`TEXT_LINE_LETTERS` or more pieces in one
    row, each spanning half the group's width or more (and
    :data:`TEXT_ROW_LETTER_SHARE` of :data:`TEXT_LETTER_MM`: lower-case letters),
    together :data:`TEXT_LINE_INK` of its ink (``pts``: the group's outline points).
    Whether the pieces leave gaps (a hollow hull) is the caller's. A bar along the
    row (an underline's stretch left with the letters: lower than
    :data:`TEXT_LETTER_MM`, longer than :data:`UNDERLINE_LETTERS` times that) is
    left out of its ink and its width: 'Schwalbe G-One Bite 40' with 33 mm of its
    underline, 35 % of the ink, was a 73 x 5.8 mm "print"; 'Bridgestone S22 ...
    1812 N' with its underline, 108 x 4.2 mm, its letters (2.3-2.8 mm) under half
    the width with the underline (held-out set 13 sheets 0, 42)."""
    n, lab, st, _ = components_with_stats(mask.view(np.uint8), connectivity=8)
    if n - 1 < TEXT_LINE_LETTERS or n - 1 > 50 * TEXT_LINE_LETTERS:
        return False
    # the direction across the row: across the outline's major principal axis
    _, along = _major_axis(pts.astype(float))
    across = np.array([-along[1], along[0]])
    rows, cols = np.nonzero(lab)
    ids = lab[rows, cols]
    t = cols * across[0] + rows * across[1]
    letter = mm_to_px_length(TEXT_LETTER_MM, mm_per_px)
    u = cols * along[0] + rows * along[1]
    bar = (_extents(ids, t, n) < letter) & (_extents(ids, u, n) > UNDERLINE_LETTERS * letter)
    if bar.any():  # the row's width without it
        keep = ~bar[ids]
        ids, t = ids[keep], t[keep]
        width_px = float(np.ptp(t)) + 1.0 if len(t) else 0.0
    span = max(0.5 * width_px, TEXT_ROW_LETTER_SHARE * letter)
    if not _letter_row(ids, t, n, span, TEXT_LINE_LETTERS):
        return False
    # a row of chevrons is no writing: each is its neighbour shifted (fifth
    # held-out seeds 2 and 4: chevron prints whose outline cuts every V to a
    # slightly different size, "a line of writing", three missing)
    return not _alike_neighbours(lab, st, np.flatnonzero(_extents(ids, t, n) >= span), along)


def _alike_neighbours(lab: np.ndarray, st: np.ndarray, pieces: np.ndarray, along) -> bool:
    """Whether :data:`TEXT_ALIKE_SHARE` or more of the neighbouring pairs among
    ``pieces`` (labels in ``lab``, OpenCV's stats ``st``), in their order along
    ``along`` (a unit (x, y) direction), are alike in shape
    (:data:`TEXT_SHAPE_ALIKE`, laid over each other by their centroids): a
    tread's repeated elements."""
    if len(pieces) < 3:
        return False
    crops, centres = [], []
    for k in pieces:
        x, y, w, h = st[k, :4]
        crop = lab[y : y + h, x : x + w] == k
        ys, xs = np.nonzero(crop)
        crops.append(crop)
        centres.append((y + ys.mean(), x + xs.mean(), ys.mean(), xs.mean()))
    centres = np.array(centres)
    order = np.argsort(centres[:, 1] * along[0] + centres[:, 0] * along[1])
    alike = 0
    for i, j in itertools.pairwise(order):
        a, b = crops[i], crops[j]
        # b shifted so its centroid falls on a's, both on one canvas
        dy = round(centres[i, 2] - centres[j, 2])
        dx = round(centres[i, 3] - centres[j, 3])
        y0, x0 = min(0, dy), min(0, dx)
        h = max(a.shape[0], b.shape[0] + dy) - y0
        w = max(a.shape[1], b.shape[1] + dx) - x0
        ca = np.zeros((h, w), bool)
        cb = np.zeros((h, w), bool)
        ca[-y0 : -y0 + a.shape[0], -x0 : -x0 + a.shape[1]] = a
        cb[dy - y0 : dy - y0 + b.shape[0], dx - x0 : dx - x0 + b.shape[1]] = b
        alike += np.count_nonzero(ca & cb) >= TEXT_SHAPE_ALIKE * np.count_nonzero(ca | cb)
    return alike >= TEXT_ALIKE_SHARE * (len(pieces) - 1)


def piece_range(ids: np.ndarray, values: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Per piece, the least and the largest of a value over its pixels.

    Numpy only (``components.reduce_at``): scipy's ``ndimage`` minimum and maximum
    cost a one-file run its import.

    Parameters
    ----------
    ids : (k,) int
        Each pixel's piece, 0..n-1 (best in raster order: runs reduce first).
    values : (k,) float
        The value at each pixel.
    n : int
        Number of pieces.

    Returns
    -------
    lo, hi : (n,) float
        Least and largest value per piece (+inf and -inf for a piece with none).
    """
    lo, hi = np.full(n, np.inf), np.full(n, -np.inf)
    reduce_at(np.minimum, lo, ids, values=values)
    reduce_at(np.maximum, hi, ids, values=values)
    return lo, hi


def _extents(ids: np.ndarray, values: np.ndarray, n: int) -> np.ndarray:
    """Per piece (labels 0..n-1 of pixels ``ids`` in raster order), the extent of
    ``values`` over its pixels, max - min + 1 (-inf for a piece with none)."""
    lo, hi = piece_range(ids, values, n)
    return hi - lo + 1


def _letter_row(ids: np.ndarray, across: np.ndarray, n: int, span: float, least: int) -> bool:
    """Whether ink pixels (their pieces ``ids``, labels 1..n-1, and coordinates
    ``across`` a row [px]) are a row of letters: ``least`` or more pieces spanning
    ``span`` [px] or more across it, together :data:`TEXT_LINE_INK` of the ink."""
    tall = _extents(ids, across, n) >= span  # (the background, no pixel here: -inf)
    ink = np.bincount(ids, minlength=n)
    return np.count_nonzero(tall) >= least and ink[tall].sum() >= TEXT_LINE_INK * ink.sum()


def _rows_of_letters(mask: np.ndarray, pts: np.ndarray, mm_per_px: float, opts) -> bool:
    """Whether a group's ink is two or more rows of letters: bands along the
    long side of its least rectangle (``pts``: its outline points), paper between
    them, each a row of letters (:data:`TEXT_ROW_LETTERS` or more pieces spanning
    :data:`TEXT_ROW_SPAN` of it, :data:`TEXT_LINE_INK` of its ink), inking
    less than :data:`TEXT_LINE_FILL` of its rectangle; its median piece no wider
    than two strokes (``stroke_width_mm``), half its largest pieces no bars
    (:data:`TEXT_BAR_FILL`, :data:`TEXT_BAR_ASPECT`), and not half of them alike in
    ink (:data:`TEXT_ALIKE_AREA`, :data:`TEXT_ALIKE_SHARE`: a tread's elements;
    specks left out of these counts): a label's lines of marker
    letters joined into one group (held-out 6 sheet 79: 'Compass Stampede Pass 32'
    over 'p = 5.3 bar', an 86 x 15 mm "print" on a page of writing only). A car
    print's ribs are solid; a knobby print's rows of knobs are wider than strokes."""
    import cv2

    (_, _), (a, b), angle = cv2.minAreaRect(pts.astype(np.float32))
    rows, cols = np.nonzero(mask)
    # across the rows: the least rectangle's long side leans with unequal rows
    # (1.1 deg at 150 dpi: the rows' projections merged), so the direction among
    # those about it that leaves most paper between the rows (on a subsample)
    step = max(1, len(rows) // TEXT_ROW_SAMPLE)
    turns = np.deg2rad(angle + (90.0 if a >= b else 0.0) + TEXT_ROW_TURNS)
    sub = np.outer(cols[::step], np.cos(turns)) + np.outer(rows[::step], np.sin(turns))
    sub = np.round(sub - sub.min(axis=0)).astype(int)
    paper = [np.count_nonzero(np.bincount(c) == 0) for c in sub.T]
    t = turns[int(np.argmax(paper))]
    across = np.round(cols * np.cos(t) + rows * np.sin(t)).astype(int)
    across -= across.min()
    inked = np.bincount(across) > 0
    edges = np.flatnonzero(np.diff(np.r_[False, inked, False].astype(np.int8)))
    bands = edges.reshape(-1, 2)  # [start, stop) of the inked runs across
    tall_px = mm_to_px_length(TEXT_LETTER_MM, mm_per_px)
    bands = bands[bands[:, 1] - bands[:, 0] >= tall_px]
    if len(bands) < 2:  # (most prints: no paper along them; the pieces not needed)
        return False
    n, lab, st, _ = components_with_stats(mask.view(np.uint8), connectivity=8)
    if n - 1 < 2 * TEXT_ROW_LETTERS or n - 1 > 100 * TEXT_LINE_LETTERS:
        return False
    ids = lab[rows, cols]
    along = np.round(cols * -np.sin(t) + rows * np.cos(t)).astype(int)
    band_of = np.searchsorted(bands[:, 0], across, side="right") - 1
    for k, (lo, hi) in enumerate(bands):
        on = (band_of == k) & (across < hi)
        box = (hi - lo) * (np.ptp(along[on]) + 1)
        if np.count_nonzero(on) >= TEXT_LINE_FILL * box:
            return False  # a solid band: a rib
        span = max(TEXT_ROW_SPAN * (hi - lo), TEXT_ROW_LETTER_SHARE * tall_px)
        if not _letter_row(ids[on], across[on], n, span, TEXT_ROW_LETTERS):
            return False
    # strokes: the widest disk in the median piece spans two strokes at most
    dist = cv2.distanceTransform(np.pad(mask.view(np.uint8), 1), cv2.DIST_L2, 5)[1:-1, 1:-1]
    widest = np.zeros(n)
    np.maximum.at(widest, ids, dist[rows, cols])
    # (over the pieces larger than specks: chart paper's bits in the group made the
    # median a speck's, and a knob print's rows "letters": fifth held-out seed 3
    # sheet 31, 3 x 5 mm knobs on 1 mm chart paper, missing)
    areas = st[1:, cv2.CC_STAT_AREA]
    big = areas >= RIB_STACK_SPECK * areas.max()
    if 2.0 * np.median(widest[1:][big]) > mm_to_px_length(2.0 * opts.stroke_width_mm, mm_per_px):
        return False
    # a tread's elements are alike (the outline cuts only the outer ones); letters
    # differ in ink (siped blocks, each three slits in a 6 mm square, read as 'E's
    # in rows: fifth held-out seed 3 sheet 97, a 91 x 64 mm print missing)
    sizes = areas[big]
    alike = np.abs(sizes / np.median(sizes) - 1.0) <= TEXT_ALIKE_AREA
    if len(sizes) >= 2 * TEXT_ROW_LETTERS and alike.mean() >= TEXT_ALIKE_SHARE:
        return False
    # ... and when the outline cut half of them, the rest are whole copies of one
    # element, more of them than a label repeats a letter (held-out seed 3 sheet 9
    # page 2: a 78 x 18 mm print of siped blocks in two rows, the outer row cut to
    # 'E's, set aside as "lines of writing": missing; drawn labels: 4 at most)
    from .pattern import MIN_ELEMENTS, copies_of_one

    if copies_of_one(lab, st, 1 + np.flatnonzero(big)).sum() >= MIN_ELEMENTS:
        return False
    # letters are curved or crossed strokes; a tread's bars are straight
    bars = []
    for k in 1 + np.argsort(-st[1:, cv2.CC_STAT_AREA])[: 4 * TEXT_LINE_LETTERS]:
        x, y, w, h = st[k, :4]
        p = cv2.findNonZero((lab[y : y + h, x : x + w] == k).view(np.uint8))
        (_, _), (rw, rh), _ = cv2.minAreaRect(p)
        fill = st[k, cv2.CC_STAT_AREA] / max((rw + 1) * (rh + 1), 1.0)
        bars.append(fill >= TEXT_BAR_FILL and max(rw, rh) >= TEXT_BAR_ASPECT * min(rw, rh))
    return float(np.mean(bars)) < 0.5


def _body_share(mask: np.ndarray, width_px: float) -> float:
    """The widest disk in the ink (twice the largest distance to the paper) as a
    share of the group's width ``width_px`` [px]: about 1 for a solid bar, a
    stroke's width over the letter's for writing."""
    import cv2

    dist = cv2.distanceTransform(np.pad(mask.view(np.uint8), 1), cv2.DIST_L2, 5)
    return 2.0 * float(dist.max()) / max(width_px, 1.0)


def _closed_fill(mask: np.ndarray, size_px: float) -> float:
    """Inked share of the hull of the ink closed by a disk ``size_px`` [px] wide
    (``stroke_width_mm``): a tiny file tread print's pores and the notches its
    pattern cuts in the outline are narrower than a pen stroke and fill in; a
    letter's counters and the room between its strokes are wider and stay."""
    import cv2

    d = max(3, round(size_px) | 1)
    disk = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (d, d))
    closed = cv2.morphologyEx(np.pad(mask.view(np.uint8), d), cv2.MORPH_CLOSE, disk)
    pts = outline_points(closed)
    if pts is None:
        return 0.0
    hull = cv2.convexHull(pts)
    return hull_fill(cv2.countNonZero(closed), hull)


def _main_blob_fill(mask: np.ndarray) -> float:
    """Inked share of the hull of the largest blob, when it holds at least 80 % of
    the ink (a solid tiny print with halo specks around it), else 0."""
    import cv2

    n, lab, stats, _ = components_with_stats(mask.view(np.uint8), connectivity=8)
    if n < 3:
        return 0.0
    k = 1 + int(np.argmax(stats[1:, cv2.CC_STAT_AREA]))
    px = int(stats[k, cv2.CC_STAT_AREA])
    if px < 0.8 * int(stats[1:, cv2.CC_STAT_AREA].sum()):
        return 0.0
    return hull_fill(px, cv2.convexHull(outline_points(lab == k)))


def _sides(group: Group, shape: tuple[int, int], *, near: bool = True) -> int:
    """How many sides of the image the group's box reaches (within 1 % when
    ``near``, else its ink touching them)."""
    h, w = shape
    mr, mc = (max(1, h // 100), max(1, w // 100)) if near else (0, 0)
    return sum(
        (
            group.rows.start <= mr,
            group.rows.stop >= h - mr,
            group.cols.start <= mc,
            group.cols.stop >= w - mc,
        )
    )


def group_blobs(mask, *, mm_per_px: float, options: AnalysisOptions | None = None) -> list[Group]:
    """Group a sheet's ink into candidate prints (the footprint rule; marks set aside).

    Parameters
    ----------
    mask : (rows, cols) bool
        Ink of the sheet.
    mm_per_px : float [mm / px]
    options : AnalysisOptions, optional
        Grouping and mark thresholds (defaults when None).

    Returns
    -------
    list of Group
        Top to bottom (by the box's centre row), then left to right.
    """
    from .marks import sort_ink

    return sort_ink(mask, mm_per_px=mm_per_px, options=options).groups


@dataclass(frozen=True)
class EdgeSpots:
    """The section 7.1.1 split of one group's ink.

    Attributes
    ----------
    load_bearing : (h, w) bool
        The group's ink without edge spots.
    n_blobs : int
        8-connected ink blobs in the group.
    n_spots : int
        Blobs judged edge spots (touched the paper, bore no load).
    spot_pixels : int [px]
        Ink pixels of the edge spots.
    tread_gap : float [px]
        The core's typical gap between its blobs (0 for a one-blob core).
    faint_blocks : (h, w) bool or None
        The faint edge spots larger than a dot (extent over ``dot_mm``): lightly
        inked tread blocks or light touches, the rule's judgement call (None when
        there is none).
    thin : (h, w) bool or None
        The pen-thin ink beside the print left out as a pen's strokes or dots
        (:func:`edge_spots`; None when there is none).
    """

    load_bearing: np.ndarray
    n_blobs: int
    n_spots: int
    spot_pixels: int
    tread_gap: float = 0.0
    faint_blocks: np.ndarray | None = field(default=None, repr=False)
    thin: np.ndarray | None = field(default=None, repr=False)


@dataclass(frozen=True)
class _Blobs:
    """8-connected blobs of a group: labels (0 = paper), areas [mm^2], centroids
    (x = col, y = row) [px], peak darkness and extent (the longer side of its box)
    [mm], per blob 1..n; the ink pixels (flat indices, raster order) and their
    labels."""

    labels: np.ndarray
    areas: np.ndarray
    centroids: np.ndarray
    peak: np.ndarray
    extents: np.ndarray
    at: np.ndarray
    ids: np.ndarray


@dataclass(frozen=True)
class _Pieces:
    """The 8-connected pieces of a mask, labelled once for all that need them
    (:func:`_thin_parts`, :func:`_blobs`, :func:`_block_frames`): the number of
    labels ``n`` (0 = paper), the labels (OpenCV's numbering), the ink pixels (flat
    indices, raster order) and their labels, and OpenCV's statistics (int64) and
    centroids of every piece (from the ink pixels, :func:`piece_stats`)."""

    n: int
    labels: np.ndarray
    at: np.ndarray
    ids: np.ndarray
    stats: np.ndarray
    cent: np.ndarray

    def without(self, flat: np.ndarray) -> _Pieces | None:
        """The pieces of the mask without its pixels at ``flat`` (flat indices of
        ink) when those are whole pieces: the others as OpenCV labels that ink (its
        raster order kept, as :func:`_unspecked` renumbers); None when a piece
        loses only some of its pixels (it may fall apart: label it again)."""
        import cv2

        lost = np.bincount(self.labels.ravel()[flat], minlength=self.n)
        hit = lost > 0
        if np.any(hit & (lost != self.stats[:, cv2.CC_STAT_AREA])):
            return None
        keep = ~hit
        keep[0] = True
        new = np.cumsum(keep, dtype=np.int32) - 1
        new[~keep] = 0
        stay = keep[self.ids]
        return _Pieces(
            int(keep.sum()),
            new[self.labels],
            self.at[stay],
            new[self.ids[stay]],
            self.stats[keep],
            self.cent[keep],
        )

    def only(self, which: np.ndarray) -> tuple:
        """The statistics and centroids of the pieces ``which`` ((n,) bool), zeros
        for the others: :func:`piece_stats` of their pixels alone (a piece's
        statistics are sums over its own pixels)."""
        return (
            np.where(which[:, None], self.stats, 0),
            np.where(which[:, None], self.cent, 0.0),
        )


def _pieces(mask: np.ndarray) -> _Pieces:
    """The :class:`_Pieces` of a mask (bool, or uint8 with non-zero ink)."""
    import cv2

    mask = mask if mask.dtype == bool else mask.astype(bool)
    n, lab = cv2.connectedComponents(mask.view(np.uint8), connectivity=8)
    on = np.flatnonzero(mask)
    # statistics from the ink pixels (OpenCV's sum over every pixel of the box)
    st, cent = piece_stats(lab, on, n)
    return _Pieces(n, lab, on, lab.ravel()[on], st, cent)


def _unspecked(mask: np.ndarray, min_pixels: int) -> tuple[np.ndarray, _Pieces]:
    """:func:`inkprint.binarize.remove_specks` of a mask (bool) and the
    :class:`_Pieces` of what is left, labelled once: the pieces kept, renumbered
    1..k, are OpenCV's own labels of that ink (it numbers pieces in the raster order
    of where they begin, :func:`inkprint.components.components_with_stats_in`, which
    dropping others does not change)."""
    import cv2

    mb = np.asarray(mask, bool)
    n, lab = cv2.connectedComponents(mb.view(np.uint8), connectivity=8)
    on = np.flatnonzero(mb)
    keep = np.bincount(lab.ravel()[on], minlength=n) >= min_pixels
    keep[0] = True
    if min_pixels > 1 and not keep.all():
        new = np.cumsum(keep, dtype=np.int32) - 1
        new[~keep] = 0
        gone = ~keep[lab.ravel()[on]]
        mb, on, lab, n = cleared(mb, on[gone]), on[~gone], new[lab], int(keep.sum())
    st, cent = piece_stats(lab, on, n)
    return mb, _Pieces(n, lab, on, lab.ravel()[on], st, cent)


def _blobs(group: Group, darkness, mm_per_px: float, pieces: _Pieces | None = None) -> _Blobs:
    """The blobs of ``group`` (``pieces``: its mask's, if already labelled)."""
    import cv2

    p = pieces if pieces is not None else _pieces(group.mask)
    peak = np.zeros(p.n, np.float32)
    reduce_at(np.maximum, peak, p.ids, values=np.asarray(darkness, np.float32).ravel()[p.at])
    st = p.stats
    side = np.maximum(st[1:, cv2.CC_STAT_WIDTH], st[1:, cv2.CC_STAT_HEIGHT])
    return _Blobs(
        p.labels,
        area_px_to_mm2(st[1:, cv2.CC_STAT_AREA], mm_per_px),
        p.cent[1:],
        peak[1:].astype(float),
        px_to_mm_length(side.astype(float), mm_per_px),
        p.at,
        p.ids,
    )


def outline_points(mask: np.ndarray) -> np.ndarray | None:
    """The first and last ink pixel of every row, as OpenCV points.

    Every vertex of the convex hull of the ink's pixels is one of them, so
    ``cv2.convexHull`` (and ``cv2.minAreaRect``) of these few points equals that of
    all the ink pixels, at a fraction of the cost on a large print.

    Parameters
    ----------
    mask : (h, w) bool or uint8
        The ink.

    Returns
    -------
    (n, 1, 2) int32 or None
        (x, y) [px]; None without ink.
    """
    m = mask.view(bool) if mask.dtype == np.uint8 else mask.astype(bool, copy=False)
    rows = np.flatnonzero(m.any(axis=1))
    if rows.size == 0:
        return None
    sub = m[rows]
    left = sub.argmax(axis=1)
    right = m.shape[1] - 1 - sub[:, ::-1].argmax(axis=1)
    two = right != left
    x = np.concatenate([left, right[two]])
    y = np.concatenate([rows, rows[two]])
    return np.stack([x, y], axis=1).astype(np.int32).reshape(-1, 1, 2)


def hull_fill(n_pixels: int, hull: np.ndarray) -> float:
    """Inked share of a convex hull (OpenCV points) holding ``n_pixels`` ink pixels:
    over the pixels the hull covers, its area plus half its perimeter plus one (the
    pixel centres on and inside a pixel polygon, as Pick's theorem counts them), so
    that a solid blob fills about 1 whatever its size.

    Parameters
    ----------
    n_pixels : int
    hull : (k, 1, 2) int or float
        ``cv2.convexHull`` of the ink's pixels [px].

    Returns
    -------
    float
    """
    import cv2

    return n_pixels / max(cv2.contourArea(hull) + 0.5 * cv2.arcLength(hull, True) + 1.0, 1.0)


def _outside_core(blobs: _Blobs, core_mask: np.ndarray, faint: np.ndarray) -> np.ndarray:
    """Whether each blob lies outside the convex hull of the core: its centroid does,
    or, for a ``faint`` blob ((n,) bool), any of its pixels (a faint speck on the
    core's outline, its centre just inside, still widens the hull by its radius:
    width +2.3 % on a knobby print at 150 dpi)."""
    import cv2

    hull = cv2.convexHull(outline_points(core_mask))
    out = np.array(
        [cv2.pointPolygonTest(hull, (float(x), float(y)), False) < 0 for x, y in blobs.centroids]
    )
    if faint.any():
        inside = cv2.fillConvexPoly(np.zeros(core_mask.shape, np.uint8), hull, 1)
        beyond = np.bincount(blobs.labels[inside == 0], minlength=len(out) + 1)[1:] > 0
        out |= faint & beyond
    return out


def _off_sites(blobs: _Blobs, core: np.ndarray, which: np.ndarray) -> np.ndarray:
    """Which of the blobs ``which`` ((n,) bool; those smaller than a whole element)
    are no element the outline cut. The lattice of the core's whole elements near
    a blob (the core blobs within :data:`SITE_SIZES` of their median area, the
    :data:`SITE_ELEMENTS` nearest it, :func:`inkprint.sites.fit_lattice`: a large
    print's lattice drifts across it) holds a cut element inside its element's
    footprint at a site, reaching the element's edge on the side towards the
    print (the outline takes a cap off the far side). A blob is off it with a pixel
    farther from the nearest site than the elements' circumradius (the median over
    them of the farthest pixel from their centroid), with none as far as their
    inradius (half :func:`_element_widths`), or with none near the element's edge
    towards the whole elements near it (twice the give), the give a pixel and the
    fit's misfit. Not off without a lattice. (n,) bool."""
    out = np.zeros(len(which), bool)
    if not which.any() or not core.any():
        return out
    area = np.median(blobs.areas[core])
    whole = core & (blobs.areas >= area / SITE_SIZES) & (blobs.areas <= SITE_SIZES * area)
    which = which & (blobs.areas < area / SITE_SIZES)  # (cut ones: smaller)
    if np.count_nonzero(whole) < SITE_ELEMENTS // 2 or not which.any():
        return out
    ys, xs = np.divmod(blobs.at, blobs.labels.shape[1])
    on = whole[blobs.ids - 1]  # (the whole ones' pixels' reach from their centroid)
    k = blobs.ids[on] - 1
    far = np.zeros(len(which))
    np.maximum.at(far, k, np.hypot(xs[on] - blobs.centroids[k, 0], ys[on] - blobs.centroids[k, 1]))
    outer = float(np.median(far[whole]))
    inner = 0.5 * float(np.median(_element_widths(blobs.labels, len(which), 1.0)[whole]))
    centres = blobs.centroids[whole]
    cand = np.flatnonzero(which)
    pick = which[blobs.ids - 1]  # (the candidates' pixels, blob by blob)
    order = np.argsort(blobs.ids[pick], kind="stable")
    px = np.column_stack([xs[pick], ys[pick]])[order].astype(float)
    counts = np.bincount(blobs.ids[pick] - 1, minlength=len(which))[cand]
    for b, mine in zip(cand, np.split(px, np.cumsum(counts)[:-1]), strict=True):
        d = np.hypot(*(centres - blobs.centroids[b]).T)
        near = centres[np.argsort(d)[:SITE_ELEMENTS]]
        lattice = fit_lattice(near)
        if lattice is None:
            continue
        site = nearest_site(lattice, blobs.centroids[b : b + 1])[0]
        reach = np.hypot(*(mine - site).T).max()
        give = 1.0 + lattice.misfit
        # (the cap is cut off the side away from the print: what is left holds the
        # element's edge on the side towards the whole elements near it)
        inward = near.mean(axis=0) - site
        edge = site + inner * inward / max(float(np.hypot(*inward)), 1e-9)
        held = np.hypot(*(mine - edge).T).min()
        out[b] = reach > outer + give or reach < inner - give or held > 2.0 * give
    return out


def _core_gaps(blobs: _Blobs, core: np.ndarray, core_mask: np.ndarray) -> tuple:
    """Gap [px] from every blob to the nearest core blob, and the core's own tread
    gap [px]: the median over core blobs of the gap to their nearest core neighbour
    (0 for a one-blob core). ``core`` : (n,) bool, which blobs are the core;
    ``core_mask`` their pixels.

    One distance transform serves both: its distances give each blob's gap to the
    core, its nearest-piece labels the core's Voronoi neighbours
    (:func:`element_graph`'s partition; the core blobs are 8-connected pieces of the
    group's ink, so OpenCV's 8-connected pieces of the core are the core blobs,
    numbered in its own order: the median does not depend on it)."""
    import cv2

    dt, nearest = cv2.distanceTransformWithLabels(
        (~core_mask).view(np.uint8), cv2.DIST_L2, 3, labelType=cv2.DIST_LABEL_CCOMP
    )
    gaps = np.full(len(core) + 1, np.inf, np.float32)  # (ufunc.at is fast on one dtype)
    reduce_at(np.minimum, gaps, blobs.ids, values=dt.ravel()[blobs.at])
    gaps = gaps.astype(float)
    if core.sum() <= 1:
        return gaps[1:], 0.0
    a, b, g = _touching(nearest, dt)
    nearest_gap = np.full(int(core.sum()) + 1, np.inf)
    np.minimum.at(nearest_gap, a, g)
    np.minimum.at(nearest_gap, b, g)
    nearest_gap = nearest_gap[1:]
    return gaps[1:], float(np.median(nearest_gap[np.isfinite(nearest_gap)]))


def thin_protrusions(
    mask: np.ndarray,
    *,
    width_px: float,
    dots: bool = True,
    along_px: float = 0.0,
    options: AnalysisOptions | None = None,
) -> np.ndarray:
    """The ink without the pen-thin pieces sticking out of the print's outline.

    A label's stroke or a ruler's tick touching a print, left in its ink after the
    marks were set aside, widens its hull (label +6 %, ruler tick +4 % in width):
    ink narrower than ``width_px`` (gone after an opening with a disk that wide),
    outside the convex hull of what the opening keeps and joined to thick ink is
    not the print's; so is a stroke thin all through beside the print (a letter of
    a label; a dot is left to the section 7.1.1 rule). Thin ink inside that hull
    (ribs, sipes) is kept, and so are pieces thin all through off the ends along
    its major axis of a print with a block pattern (slivers of the tip blocks
    continuing the tread pattern: the section 7.1.1 rule decides).

    Parameters
    ----------
    mask : (h, w) bool
        The print's ink.
    width_px : float [px]
        Widest stroke to remove (``stroke_width_mm``).
    dots : bool
        Drop the pieces beside the print no longer than ``width_px`` too (the bits
        of a letter, halo specks); else only longer strokes.
    along_px : float [px]
        Keep (leave to the section 7.1.1 rule) a convex piece apart from the print
        lying along its outline, no thicker across it than this: a tread block the
        outline cut to a sliver (``mark_overhang_mm``; 0: none kept).
    options : AnalysisOptions, optional
        Uses ``sliver_solidity``, ``sliver_elongation`` and ``tip_block_strokes``
        (defaults when None).

    Returns
    -------
    (h, w) bool
        ``mask`` less the thin ink outside the thick ink's hull.
    """
    parts = _thin_parts(mask, width_px, along_px, resolve_options(options))
    return _drop_thin(mask, parts, dots=dots)


@dataclass(frozen=True)
class _ThinParts:
    """What :func:`thin_protrusions` drops, for either ``dots`` (computed once)."""

    at: np.ndarray  # (k,) int: the thin ink outside the thick ink's hull, flat indices
    ids: np.ndarray  # (k,) int32: its pieces (the ink's 8-connected pieces)
    foot: np.ndarray  # (n,) bool: pieces holding thick ink too
    stroke: np.ndarray  # (n,) bool: pieces longer than a stroke is wide
    ends: np.ndarray  # (n,) bool: pieces off the print's ends or along its outline
    tip: np.ndarray | None = None  # (k,) bool: a foot's thin ink that is a tapering tip
    extent: np.ndarray | None = None  # (n,) float: a piece apart's box's longer side [px]

    def dropped(self, *, dots: bool) -> np.ndarray:
        """Which of the thin pixels are dropped, (k,) bool: joined to the print's
        thick ink (a stroke's foot; not its tapering tip), or apart from the print,
        beside it: a stroke (longer than a stroke is wide) or, with ``dots``, a dot
        (a letter's bit, a halo speck)."""
        drop = self.foot | ((self.stroke | dots) & ~self.ends)
        drop[0] = False
        return drop[self.ids] if self.tip is None else drop[self.ids] & ~self.tip


def _thin_parts(
    mask: np.ndarray,
    width_px: float,
    along_px: float = 0.0,
    opts: AnalysisOptions | None = None,
    pieces: _Pieces | None = None,
) -> _ThinParts | None:
    """The thin ink outside the thick ink's hull. The ink's pieces (``pieces``, or
    labelled here, OpenCV's numbering, only when there is thin ink) give their
    statistics (box, centroid) to the pieces that need them: thin ink without thick
    ink (a foot's thin ink is dropped whatever its piece's size or place)."""
    import cv2

    d = max(3, round(width_px) | 1)
    disk = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (d, d))
    thick = cv2.morphologyEx(mask.view(np.uint8), cv2.MORPH_OPEN, disk)
    pts = outline_points(thick)
    if pts is None:
        return None
    hull_pts = cv2.convexHull(pts)
    hull = np.zeros(mask.shape, np.uint8)
    cv2.fillPoly(hull, [hull_pts], 1)
    thin = mask & ~(hull.view(bool) | thick.view(bool))
    if not thin.any():
        return None
    # only the thin ink of pieces that hold thick ink too (a stroke's foot on the
    # print); a piece thin all through (a sliver of a tip block, a speck) is left to
    # the section 7.1.1 rule
    pieces = pieces if pieces is not None else _pieces(mask)
    n, lab = pieces.n, pieces.labels
    foot = np.zeros(n, bool)
    foot[lab[thick.view(bool)]] = True
    at = np.flatnonzero(thin)
    ids = lab.ravel()[at]
    apart = np.zeros(n, bool)  # the pieces thin all through with ink outside the hull
    apart[ids] = True
    apart &= ~foot
    stats, cent = pieces.only(apart)
    extent = np.maximum(stats[:, cv2.CC_STAT_WIDTH], stats[:, cv2.CC_STAT_HEIGHT])
    stroke = extent > width_px
    ends = _at_the_ends(hull_pts.reshape(-1, 2).astype(float), cent) & apart
    if ends.any() and not _block_pattern(
        thick, resolve_options(opts).tip_block_strokes * width_px
    ):
        ends[:] = False
    if along_px > 0:
        ends |= _along_outline(
            (at, ids),
            lab,
            stats,
            (hull_pts, along_px),
            skip=foot | ends,
            opts=resolve_options(opts),
        )
    tip, o = None, resolve_options(opts)
    if (o.tip_taper_strokes > 0 or o.tread_teeth > 0) and foot[ids].any():
        tip = _print_stubs(thin, (at, foot[ids]), hull_pts.reshape(-1, 2), width_px, o)
    if o.tip_taper_strokes > 0 and foot[ids].any():  # (0: no thin ink kept at tips)
        frame = _block_frames(pieces, thin, (at, ids, foot), hull_pts.reshape(-1, 2))
        tip = frame if tip is None else tip | frame
    return _ThinParts(at, ids, foot, stroke, ends, tip, extent.astype(float))


def _block_frames(pieces: _Pieces, thin: np.ndarray, feet: tuple, hull_xy: np.ndarray):
    """Which of the thin pixels (flat indices ``at`` into ``thin``, their pieces
    ``ids`` among ``pieces``, the print's ink labelled, and which pieces hold thick
    ink, ``foot``) are a tread block's thin frame: a foot's thin ink off the print's
    ends whose piece, frame included, is a copy of the print's typical elements or
    of a part of one (:func:`inkprint.pattern.frame_copies`). A siped block the
    outline cut through its sipe keeps the block's frame on the far side, thinner
    than a stroke: taken for a label's foot, length -1.55 % with status ok
    (held-out seed 6 sheet 87)."""
    from .pattern import MIN_ELEMENTS, frame_copies

    at, ids, foot = feet
    n = len(foot)
    if n - 1 < MIN_ELEMENTS:
        return np.zeros(len(ids), bool)
    lab, st = pieces.labels, pieces.stats
    on = foot[ids]
    mine = np.unique(ids[on])
    ys, xs = np.divmod(at[on], lab.shape[1])
    which = np.searchsorted(mine, ids[on])  # each foot pixel's piece among ``mine``
    count = np.bincount(which)
    cent = np.column_stack([np.bincount(which, xs), np.bincount(which, ys)]) / count[:, None]
    mine = mine[_off_the_tips(hull_xy.astype(float), cent)]
    keep = np.zeros(n, bool)
    if len(mine):
        keep[mine] = frame_copies(lab, st, mine, part=thin)
    return keep[ids]


def _print_stubs(thin: np.ndarray, feet: tuple, hull_xy: np.ndarray, width_px: float, opts):
    """Which of the thin pixels ``feet`` (flat indices ``at`` into ``thin`` and
    whether each is a foot's) are the print's own: pieces of ``thin`` (the thin ink
    outside the thick ink's hull ``hull_xy``, (x, y) [px]), all a foot's, that are

    * a tapering tip: off the print's ends along its major axis, reaching no
      farther than ``tip_taper_strokes`` x ``width_px`` out of the hull (the end of
      a narrow print the opening cut short continues its outline; a stroke's foot
      sticks out farther);
    * its tread's teeth (:func:`_teeth`): a row of ``tread_teeth`` or more stubs
      no deeper than :data:`TEETH_DEPTH` strokes on each side, along most of its
      length."""

    import cv2

    at, is_foot = feet
    # OpenCV's labels, and the pieces' centroids from their pixels (``at``: all the
    # thin ink; exact sums, OpenCV's centroids; the paper's, label 0, is not used)
    n, lab = cv2.connectedComponents(thin.view(np.uint8), connectivity=8)
    ids = lab.ravel()[at]
    ys, xs = np.divmod(at, thin.shape[1])
    count = np.maximum(np.bincount(ids, minlength=n), 1)[:, None]
    cent = np.column_stack([np.bincount(ids, xs, n), np.bincount(ids, ys, n)]) / count
    hull_xy = hull_xy.astype(float)
    d = _outside_distance(np.column_stack([xs, ys]).astype(float), hull_xy)
    far = np.full(n, -np.inf)
    np.maximum.at(far, ids, d)
    all_feet = np.ones(n, bool)
    np.logical_and.at(all_feet, ids, is_foot)
    all_feet[0] = False
    ends = _off_the_tips(hull_xy, cent)
    ok = all_feet & ends & (far <= opts.tip_taper_strokes * width_px)
    if opts.tread_teeth > 0:
        stub = all_feet & ~ends & (far <= TEETH_DEPTH * width_px)
        ok |= _teeth(hull_xy, cent, stub, opts.tread_teeth)
    return ok[ids]


def _off_the_tips(hull_xy: np.ndarray, points: np.ndarray, *, end: float = 0.8) -> np.ndarray:
    """Whether each point (x, y) lies off a hull's ends along its major axis: beyond
    ``end`` x its half-length from the middle of its extent along the axis (the
    vertices' mean, :func:`_at_the_ends`, leans towards a ragged tip's many
    vertices: the other tip's last pixel was judged beside the print)."""
    c, axis = _major_axis(hull_xy)
    proj = (hull_xy - c) @ axis
    mid, half = 0.5 * (proj.max() + proj.min()), 0.5 * np.ptp(proj)
    return np.abs((points - c) @ axis - mid) > end * half


def _teeth(hull_xy: np.ndarray, cent: np.ndarray, stub: np.ndarray, least: int) -> np.ndarray:
    """Which of the stubs (``stub``: (n,) bool over pieces with centres ``cent``,
    (x, y)) are a tread's teeth: when at least ``least`` of them lie on each side
    of the hull's major axis and each side's span along it covers
    :data:`TEETH_SPAN` of the hull's length, or one side's does and the other's
    stubs lie at a regular pitch (:data:`TEETH_PITCH`) (a track tire's file tread
    print: a spine with a row of teeth down each side, joined to it by a pixel;
    dropped as pen strokes' feet, width -27 %). A label's letters touch one side."""
    out = np.zeros(len(stub), bool)
    if np.count_nonzero(stub) < 2 * least:
        return out
    c, axis = _major_axis(hull_xy)
    half = np.abs((hull_xy - c) @ axis).max()
    along = (cent[stub] - c) @ axis
    side = (cent[stub] - c) @ np.array([-axis[1], axis[0]]) > 0
    spans = []
    for s in (side, ~side):
        if np.count_nonzero(s) < least:
            return out
        a = np.sort(along[s])
        gaps = np.diff(a)
        regular = bool(np.all(np.abs(gaps - np.median(gaps)) <= TEETH_PITCH * np.median(gaps)))
        spans.append((np.ptp(a) >= TEETH_SPAN * 2 * half, regular))
    # each side along TEETH_SPAN of the length, or one of them at a regular pitch
    (long0, even0), (long1, even1) = spans
    if not ((long0 and (long1 or even1)) or (long1 and even0)):
        return out
    out[stub] = True
    return out


def _along_outline(thin: tuple, lab, stats, hull, *, skip, opts: AnalysisOptions) -> np.ndarray:
    """Per piece: convex (``sliver_solidity``), apart from the print and lying along
    the outline of ``hull`` (its points and ``along_px``), its thin ink no thicker
    across the outline than ``along_px`` [px] (the farthest minus the nearest
    distance out of the hull) and ``sliver_elongation`` times longer than that: a
    tread block the outline cut to a thin bar, not a stroke sticking out or a
    letter's foot. ``thin``: the thin pixels (flat indices) and their pieces."""
    import cv2

    hull_pts, along_px = hull
    n = len(stats)
    out = np.zeros(n, bool)
    at, ids = thin
    ys, xs = np.divmod(at, lab.shape[1])
    sel = ~skip[ids]
    if not sel.any():
        return out
    ys, xs, ids = ys[sel], xs[sel], ids[sel]
    d = _outside_distance(np.column_stack([xs, ys]).astype(float), hull_pts.reshape(-1, 2))
    has = np.bincount(ids, minlength=n) > 0
    across = _extents(ids, d, n)  # the farthest minus the nearest distance, + 1
    for k in np.flatnonzero(has & (across <= along_px)):
        x, y, w, h = stats[k, :4]
        pts = cv2.findNonZero((lab[y : y + h, x : x + w] == k).view(np.uint8))
        hull = cv2.convexHull(pts)
        fill = hull_fill(len(pts), hull)
        long = max(cv2.minAreaRect(pts)[1]) + 1.0
        out[k] = fill >= opts.sliver_solidity and long >= opts.sliver_elongation * across[k]
    return out


def _dot_row(
    parts: _ThinParts,
    darkness,
    mask: np.ndarray,
    size: tuple,
    opts,
    *,
    least: int = DOT_ROW,
    near: float = np.inf,
) -> np.ndarray:
    """Per piece: a dot apart from the print (thin all through, its box's longer
    side at most :data:`DOT_STROKES` x a stroke's width, at least
    ``size[1]`` of ink: ``size`` = both [px, px^2]; see :data:`DOT_LEAST_MM2`) as dark as its ink
    (peak darkness ``edge_spot_faintness`` x the ink's median or more), when
    ``least`` (:data:`DOT_ROW`) or more such dots, alike in size (:data:`DOT_SIZES`), lie along
    :data:`DOT_SPAN` of the print's length or more (a label's bits beside it are a
    cluster of all sizes):
    the outer row of a file tread's diamonds, cut to dots by the outline. Dropped
    as thin dots with a label's bits and halo specks, a file print read 6-8.5 %
    narrow with status ok (held-out sets 11, 13, 14: four prints, their dots
    0.5-0.8 mm^2, as dark as the print); left to the section 7.1.1 rule instead,
    which keeps the ones within the tread's reach. Halo specks are fainter
    (section 7.1.1), a label's dots are a few."""
    width_px = size[0]
    n = len(parts.foot)
    none = np.zeros(n, bool)
    ink = np.bincount(parts.ids, minlength=n)  # (a piece apart is thin all through)
    row = _dots(parts, darkness, mask, size, opts, least=least)
    if np.isfinite(near) and np.count_nonzero(row) >= least:
        # each within ``near`` strokes of the other ink (measured only for a row's
        # worth of dots: the distance transform is most of this rule's cost)
        row &= _body_gaps(parts, mask) <= near * width_px
    if np.count_nonzero(row) < least:
        return none
    # along the print's major axis: the dots' span against the ink's
    ys, xs = np.divmod(parts.at, mask.shape[1])
    rr, cc = np.nonzero(mask)
    _, (vx, vy) = _ink_axis(rr, cc)
    t_ink = cc * vx + rr * vy
    t = np.bincount(parts.ids, weights=xs * vx + ys * vy, minlength=n)[row] / ink[row]
    lo, hi = np.percentile(ink[row], [20, 80])
    return row if np.ptp(t) >= DOT_SPAN * np.ptp(t_ink) and hi <= DOT_SIZES * lo else none


def _body_gaps(parts: _ThinParts, mask: np.ndarray) -> np.ndarray:
    """Per piece: its distance [px] to the ink without the thin pieces apart from
    it (about the paper between them, plus a pixel). (n,) float, inf for a piece
    without thin pixels.

    The thin ink of pieces that hold thick ink (a foot's) is the print's here: a
    tiny file print's teeth, thin at 150 dpi, stand between its body and the cut
    dots beyond them, a pixel from the dots; measured to the thick ink alone the dots
    lay 5.7-6.7 px off, over a stroke, and were dropped (held-out 6 seed 2 sheet
    61: -16 % wide with status ok)."""
    import cv2

    body = mask.copy()
    body.ravel()[parts.at[~parts.foot[parts.ids]]] = False
    away = cv2.distanceTransform((~body).view(np.uint8), cv2.DIST_L2, 3).ravel()
    gap = np.full(len(parts.foot), np.inf)
    np.minimum.at(gap, parts.ids, away[parts.at])
    return gap


def _two_sided_row(parts: _ThinParts, darkness, mask: np.ndarray, size: tuple, opts):
    """Per piece: the outline's cut dots where a tiny print is widest, too few for a
    row along it (:data:`DOT_ROWS`): :data:`TWO_SIDED_DOTS` or more dots
    (:func:`_dots`, ``size`` as there) on each side of the print's major axis, each
    within a stroke of the print's body, alike in size (:data:`DOT_SIZES`) and in
    their gap to the body (the largest at most :data:`TWO_SIDED_GAPS` x the
    smallest and a pixel: one groove). A label's bits lie on one side, halo specks
    at gaps of all sizes. (n,) bool."""
    n = len(parts.foot)
    none = np.zeros(n, bool)
    row = _dots(parts, darkness, mask, size, opts, least=2 * TWO_SIDED_DOTS)
    if not row.any():
        return none
    gap = _body_gaps(parts, mask)
    row &= gap <= size[0]
    if np.count_nonzero(row) < 2 * TWO_SIDED_DOTS:
        return none
    ink = np.bincount(parts.ids, minlength=n)
    ys, xs = np.divmod(parts.at, mask.shape[1])
    cent = np.column_stack([np.bincount(parts.ids, xs, n), np.bincount(parts.ids, ys, n)])
    cent = cent[row] / ink[row, None]
    c, (vx, vy) = _ink_axis(*np.nonzero(mask))
    side = (cent - c) @ np.array([-vy, vx]) > 0
    lo, hi = np.percentile(ink[row], [20, 80])
    g = gap[row]
    if (
        min(np.count_nonzero(side), np.count_nonzero(~side)) < TWO_SIDED_DOTS
        or hi > DOT_SIZES * lo
        or g.max() > TWO_SIDED_GAPS * g.min() + 1.0
    ):
        return none
    return row


def _dots(
    parts: _ThinParts, darkness, mask: np.ndarray, size: tuple, opts, *, least: int = 1
) -> np.ndarray:
    """Per piece: a dot apart from the print (thin all through, its box's longer
    side at most :data:`DOT_STROKES` x ``size[0]`` [px], at least ``size[1]``
    [px^2] of ink), as dark as its ink (peak darkness ``edge_spot_faintness`` x the
    ink's median or more). (n,) bool; none when fewer than ``least`` are dots."""
    width_px, least_px = size
    n = len(parts.foot)
    ink = np.bincount(parts.ids, minlength=n)  # (a piece apart is thin all through)
    dot = ~parts.foot & ~parts.ends & (parts.extent <= DOT_STROKES * width_px)
    dot &= ink >= least_px
    dot[0] = False
    if np.count_nonzero(dot) < least:
        return np.zeros(n, bool)
    dark = np.asarray(darkness, float).ravel()
    peak = np.zeros(n)
    reduce_at(np.maximum, peak, parts.ids, values=dark[parts.at])
    return dot & (peak >= opts.edge_spot_faintness * float(np.median(dark[mask.ravel()])))


def _pair_gaps(labels: np.ndarray) -> tuple:
    """The gaps between the pieces of a labelled mask (``labels``, (h, w) int, 0 =
    paper): for each pair of pieces whose nearest-ink regions meet, their gap [px]
    (the paper's width between them, about; 0 for pieces touching 4-ways). Three
    (k,) arrays ``(a, b, gap)`` with a < b, one row a pair."""
    import cv2

    ink = labels > 0
    dist, nearest = cv2.distanceTransformWithLabels(
        (~ink).view(np.uint8), cv2.DIST_L2, 3, labelType=cv2.DIST_LABEL_PIXEL
    )
    return _least_per_pair(*_voronoi_pairs(labels, ink, dist, nearest), int(labels.max()))


def _row_neighbours(
    parts: _ThinParts, darkness, labels: np.ndarray, rows: np.ndarray, size: tuple, opts
) -> np.ndarray:
    """Per piece: a dot (:func:`_dots`, ``size`` = stroke width [px], least ink
    [px^2]) within :data:`ROW_GROOVES` x the tread's groove of the print's ink (the
    pieces holding thick ink) or of its rows' dots (``rows``, (n,) bool, found by
    :func:`_dot_row`), or of such a dot, chained: the outline's cut pieces at the
    rows' ends and at the print's corners, too few or too unlike in size for a row
    of their own. The groove is the median gap of the rows' dots to their nearest
    other row dot (:func:`_pair_gaps`; ``labels``: the print's pieces), the reach
    at most a stroke's width. (n,) bool, ``rows`` not among them."""
    n = len(parts.foot)
    out = np.zeros(n, bool)
    cand = _dots(parts, darkness, labels > 0, size, opts) & ~rows
    if not cand.any():
        return out
    a, b, gap = _pair_gaps(labels)
    both = rows[a] & rows[b]  # (the dots of a row next to the print's ink lie
    # closer to it than a groove where its edge cut them)
    nearest = np.full(n, np.inf)
    np.minimum.at(nearest, a[both], gap[both])
    np.minimum.at(nearest, b[both], gap[both])
    known = nearest[rows & np.isfinite(nearest)]
    groove = float(np.median(known)) if len(known) else 1.0
    close = gap <= min(ROW_GROOVES * max(groove, 1.0), size[0])
    a, b = a[close], b[close]
    on = parts.foot | rows  # the print's ink and its rows
    on[0] = False
    while True:
        new = np.concatenate([b[on[a] & cand[b] & ~on[b]], a[on[b] & cand[a] & ~on[a]]])
        if not len(new):
            return out
        on[new] = out[new] = True


def _outside_distance(points: np.ndarray, polygon: np.ndarray) -> np.ndarray:
    """Distance [px] of points (x, y) out of a convex polygon: the largest signed
    distance to its sides' lines (exact off a side, a little less off a corner;
    negative inside)."""
    v = polygon.astype(float)
    e = np.roll(v, -1, axis=0) - v
    length = np.hypot(e[:, 0], e[:, 1])
    ok = length > 0
    v, e, length = v[ok], e[ok], length[ok]
    if not len(v):
        return np.hypot(*(points - polygon[0]).T)
    normal = np.column_stack([e[:, 1], -e[:, 0]]) / length[:, None]
    if np.einsum("kd,kd->k", v.mean(axis=0) - v, normal).mean() > 0:
        normal = -normal  # the centre must lie inside every side
    # (p - v) . normal per point and side, summed as einsum's "pkd,kd->pk" sums (the
    # same numbers) without its (points, sides, 2) temporary: four times faster
    d = (points[:, :1] - v[:, 0]) * normal[:, 0]
    d += (points[:, 1:] - v[:, 1]) * normal[:, 1]
    return d.max(axis=1)


def _drop_thin(mask: np.ndarray, parts: _ThinParts | None, *, dots: bool) -> np.ndarray:
    if parts is None:
        return mask
    return cleared(mask, parts.at[parts.dropped(dots=dots)])


def _block_pattern(thick: np.ndarray, side_px: float) -> bool:
    """Whether the thick ink holds two or more blocks (pieces of at least
    ``side_px`` [px] squared, ``tip_block_strokes`` x the stroke width): only a
    block pattern has tip blocks the outline can cut to slivers off the print's
    ends; beside a one-piece print (slick, ribbed, file tread) a thin piece off its
    ends is a letter's stroke (a pen label at a slick print's tip: hull area
    +2.5 %)."""
    import cv2

    n, lab = cv2.connectedComponents(thick, connectivity=8)
    area = np.bincount(lab.ravel()[np.flatnonzero(thick)], minlength=n)  # (ink only)
    return int(np.count_nonzero(area[1:] >= side_px**2)) >= 2


def _at_the_ends(
    hull_xy: np.ndarray, points: np.ndarray, *, end: float = 0.8, axis: np.ndarray | None = None
) -> np.ndarray:
    """Whether each point (x, y) lies off a hull's ends along its major axis, or
    along ``axis`` (a unit vector in the points' frame), beyond ``end`` x its
    half-length from the centre (the vertices' mean), not beside it."""
    c, major = _major_axis(hull_xy)
    axis = major if axis is None else axis
    half = np.abs((hull_xy - c) @ axis).max()
    return np.abs((points - c) @ axis) > end * half


def _major_axis(xy: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Centre (mean) and major principal axis (unit vector) of points (x, y)."""
    c = xy.mean(axis=0)
    w, v = np.linalg.eigh((xy - c).T @ (xy - c))
    return c, v[:, np.argmax(w)]


def _ink_axis(rows: np.ndarray, cols: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """:func:`_major_axis` of ink pixels (their rows and columns), from about 4000 of
    them (every k-th) on a large print."""
    xy = np.column_stack([cols, rows])[:: max(1, len(rows) // 4000)]
    return _major_axis(xy.astype(float))


def _count_pieces(flat: np.ndarray, shape) -> int:
    """8-connected pieces of the pixels at ``flat`` (flat indices in ``shape``),
    counted in their box."""
    import cv2

    if not len(flat):
        return 0
    rows, cols = np.divmod(flat, shape[1])
    r0, c0 = rows.min(), cols.min()
    box = np.zeros((rows.max() - r0 + 1, cols.max() - c0 + 1), np.uint8)
    box[rows - r0, cols - c0] = 1
    return cv2.connectedComponents(box, connectivity=8)[0] - 1


def edge_spots(
    group: Group,
    darkness,
    *,
    mm_per_px: float,
    options: AnalysisOptions | None = None,
    tread_gap: bool = True,
) -> EdgeSpots:
    """Apply the section 7.1.1 rule to one group.

    Parameters
    ----------
    group : Group
    darkness : (h, w) float in [0, 1]
        1 - grey over the group's box.
    mm_per_px : float [mm / px]
    options : AnalysisOptions, optional
        Uses ``edge_spot_area_mm2``, ``edge_spot_faintness``,
        ``edge_spot_distance_mm`` and ``stroke_width_mm`` (defaults when None).
    tread_gap : bool
        Find the core's tread gap even when no blob's fate needs it (else the
        result's ``tread_gap`` is 0 then: a re-measure of the threshold band, which
        reports none of it, skips a distance transform of the print).

    Returns
    -------
    EdgeSpots
    """
    mm_per_px = check_mm_per_px(mm_per_px)
    kw = dict(mm_per_px=mm_per_px, options=options, tread_gap=tread_gap)
    return _edge_spots(group, darkness, _pieces(group.mask), **kw)


def _edge_spots(
    group: Group,
    darkness,
    pieces: _Pieces,
    *,
    mm_per_px: float,
    options: AnalysisOptions | None = None,
    tread_gap: bool = True,
) -> EdgeSpots:
    """:func:`edge_spots` with the pieces of the group's mask given (labelled once
    for the thin ink and the blobs; :func:`_unspecked`'s)."""
    opts = resolve_options(options)
    width = mm_to_px_length(opts.stroke_width_mm, mm_per_px)
    # the rule is off when no blob can be faint and no distance too far (1 m)
    rule_on = opts.edge_spot_faintness > 0 or opts.edge_spot_distance_mm < 1e3
    along = mm_to_px_length(opts.mark_overhang_mm, mm_per_px)
    # (a fine tread's elements are as thin as pen strokes: its edge rows are no
    # strokes beside the print, the 7.1.1 rule judges them with its core)
    fine = group.fine_area_mm2 > 0
    parts = None if fine else _thin_parts(group.mask, width, along, opts, pieces)  # both ways
    if parts is None:
        return _spots(group, darkness, mm_per_px, opts, gap=tread_gap, pieces=pieces)
    if rule_on:  # a row of dark dots along the outline: the 7.1.1 rule judges them
        # (the larger dots alone first: alike in size; then the smaller ones left,
        # a row of its own: a file print's whole diamonds in one row, the outline's
        # cut dots in the next)
        rows = zip(DOT_LEAST_MM2, DOT_ROWS, DOT_NEAR_STROKES, strict=True)
        # (the pieces kept along the outline or off the ends are dots of a row too:
        # a tiny file print's outer row, held-out 6 seed 4 sheet 116 at 300 dpi,
        # eight cut diamonds, five kept as slivers along the outline and the three
        # between them dropped as strokes: too few for a row, width -4.1 % with
        # status ok)
        found = np.zeros(len(parts.foot), bool)  # (pieces of the rows)
        for floor, least, near in rows:
            size = (width, area_mm2_to_px(floor, mm_per_px))
            among = replace(parts, ends=found)
            row = _dot_row(among, darkness, group.mask, size, opts, least=least, near=near)
            if row.any():
                found |= row
                parts = replace(parts, ends=parts.ends | row)
        size = (width, area_mm2_to_px(DOT_LEAST_MM2[-1], mm_per_px))
        if not found.any():  # (a tiny print's few cut dots where it is widest)
            found = _two_sided_row(parts, darkness, group.mask, size, opts)
            parts = replace(parts, ends=parts.ends | found)
        if found.any():  # (and the pieces the outline cut beside them)
            found |= _row_neighbours(parts, darkness, pieces.labels, found, size, opts)
            parts = replace(parts, ends=parts.ends | found)
    gone = parts.dropped(dots=rule_on)  # of the thin pixels; with dots=False a subset
    kept = cleared(group.mask, parts.at[gone])
    dots = parts.at[gone & ~parts.dropped(dots=False)]
    n_thin = _count_pieces(parts.at[gone], group.mask.shape) if kept.any() else 0
    if n_thin:  # pen-thin ink beside the print: strokes are marks, dots edge spots
        # (its pieces, those of the group but for the thin ones dropped whole)
        left = pieces.without(parts.at[gone])
        spots = _spots(
            replace(group, mask=kept), darkness, mm_per_px, opts, gap=tread_gap, pieces=left
        )
        return replace(
            spots,
            n_blobs=spots.n_blobs + n_thin,
            n_spots=spots.n_spots + _count_pieces(dots, group.mask.shape),
            spot_pixels=spots.spot_pixels + len(dots),
            thin=group.mask & ~kept,
        )
    return _spots(group, darkness, mm_per_px, opts, gap=tread_gap, pieces=pieces)


def _alone(xy: np.ndarray, which: np.ndarray, among: np.ndarray, reach: float) -> np.ndarray:
    """Which of the points ``which`` ((n,) bool over ``xy``, (n, 2) [px]) have no
    other of the points ``among`` ((n,) bool) within ``reach`` [px]. (n,) bool."""
    out = np.zeros(len(which), bool)
    ks, js = np.flatnonzero(which), np.flatnonzero(among | which)
    d = np.hypot(*(xy[ks, None, :] - xy[None, js, :]).transpose(2, 0, 1))
    d[ks[:, None] == js[None, :]] = np.inf
    out[ks] = d.min(axis=1) > reach
    return out


def _mirrored(blobs: _Blobs, which: np.ndarray, mask: np.ndarray, mm_per_px: float) -> np.ndarray:
    """Of the blobs ``which`` ((n,) bool), the two (when they are exactly two) alike
    in area (within :data:`DOT_SIZES`) that lie one on each side of the major axis
    of the print's ink ``mask``, mirroring each other about it (along it within
    :data:`MIRROR_PX` and half their larger extent; ``mm_per_px``: the blobs'
    extents are in mm), both within :data:`MIRROR_MIDDLE` of its half-length of its
    middle: where a lens is widest. (n,) bool."""
    out = np.zeros(len(which), bool)
    k = np.flatnonzero(which)
    if len(k) != 2 or blobs.areas[k].max() > DOT_SIZES * blobs.areas[k].min():
        return out
    rows, cols = np.nonzero(mask)
    c, axis = _ink_axis(rows, cols)
    at = blobs.centroids[k] - c  # (x, y) [px]
    along, across = at @ axis, at @ np.array([-axis[1], axis[0]])
    half = 0.5 * np.ptp(np.column_stack([cols, rows]) @ axis)
    give = MIRROR_PX + 0.5 * mm_to_px_length(float(blobs.extents[k].max()), mm_per_px)
    out[k] = bool(
        across[0] * across[1] < 0
        and abs(along[0] - along[1]) <= give
        and np.all(np.abs(along) <= MIRROR_MIDDLE * half)
    )
    return out


def _spots(
    group: Group,
    darkness,
    mm_per_px: float,
    opts: AnalysisOptions,
    *,
    gap: bool = True,
    pieces: _Pieces | None = None,
) -> EdgeSpots:
    """The section 7.1.1 rule on the blobs of ``group`` (see :func:`edge_spots`;
    ``gap``: find the tread gap even when no small dark blob outside the core needs
    it; ``pieces``: its mask's, if already labelled)."""
    blobs = _blobs(group, darkness, mm_per_px, pieces)
    n_blobs = len(blobs.areas)
    if n_blobs <= 1:
        return EdgeSpots(group.mask, n_blobs, 0, 0)
    large = blobs.areas >= opts.edge_spot_area_mm2
    if group.fine_area_mm2 > 0:  # a fine tread's elements are its core too
        large |= blobs.areas >= group.fine_area_mm2
    if not large.any():
        large = blobs.areas == blobs.areas.max()
    ref = float(np.median(blobs.peak[large]))
    faint = blobs.peak < opts.edge_spot_faintness * ref
    core = large & ~faint
    if not core.any():
        core = large
    core_mask = np.concatenate([[False], core])[blobs.labels]
    outside = _outside_core(blobs, core_mask, faint) & ~core
    small = outside & ~faint & (blobs.areas < opts.edge_spot_area_mm2)
    if not (gap or small.any()):  # only the faint ones can be spots: no gaps needed
        gaps, pattern = np.zeros(n_blobs), 0.0
    else:
        gaps, pattern = _core_gaps(blobs, core, core_mask)
    reach = max(
        mm_to_px_length(opts.edge_spot_distance_mm, mm_per_px),
        opts.edge_spot_pattern_factor * pattern,
    )
    spot = outside & (faint | (small & (gaps > reach)))
    if group.fine_area_mm2 > 0 and pattern > 0 and opts.edge_spot_distance_mm < 1e3:
        # (the distance rule on) a fine tread's lattice says where its elements lie: a speck smaller than
        # its elements farther from it than SPECK_GAPS pattern gaps is none, even
        # within edge_spot_distance_mm (held-out seed 8 sheet 28: a dot print's
        # 0.1 mm^2 speck 0.8 mm off, 1.8 gaps, length +19.8 % with status ok)
        speck = small & (blobs.areas < group.fine_area_mm2) & (gaps > SPECK_GAPS * pattern)
        spot |= outside & speck
        # ... and a piece smaller than its elements off every site of the tread's
        # lattice: the outline's cut elements lie on their elements' sites (held-out
        # 6 seed 4 sheet 109: a speck 0.5 mm off a tiny dot print's tip, 1.2 gaps,
        # +4.9 % long; seed 2 sheet 65, a knurl print's, +8.7 %: status ok)
        spot |= _off_sites(blobs, core, outside & small)
    # a dust speck: a dot shorter than a stroke is wide holding under DUST_SHARE of
    # the core's median blob's ink is no tread block the outline cut, whatever its
    # gap (held-out seeds 2, 3, 6 sheets 38, 103, 74: specks 1.9-2.8 mm off a car, a
    # knob and a rib print's tip, within their tread gap's reach: length +1.8 %,
    # +5.4 %, +8.3 % with status ok)
    # (not beside a fine tread: a dot's crescent the outline cut is as small, and
    # the rule above judges those by the lattice's gaps)
    if group.fine_area_mm2 == 0 and opts.edge_spot_distance_mm < 1e3:  # (the rule on)
        dust = outside & small & (blobs.extents < opts.stroke_width_mm)
        dust &= blobs.areas < DUST_SHARE * float(np.median(blobs.areas[core]))
        # (a few alone: a file tread's outer row of diamonds, cut to dots all along
        # the outline beside a slick centre, is many, each with another within a
        # few strokes; more than DUST_MOST specks, those alone are dust: held-out 6
        # seed 1 sheet 99, four halo specks 5-40 mm apart off a rib print's ends,
        # kept as the pattern's, length +3.4 % with status ok)
        if np.count_nonzero(dust) <= DUST_MOST:
            spot |= dust & ~_mirrored(blobs, dust, group.mask, mm_per_px)
        else:
            row = outside & small  # (a row's dots: some larger than dust)
            speck = dust & (blobs.areas < DUST_SPECK_MM2)
            reach = DUST_ROW_STROKES * mm_to_px_length(opts.stroke_width_mm, mm_per_px)
            spot |= speck & _alone(blobs.centroids, speck, row, reach)
    if not spot.any():
        return EdgeSpots(group.mask.copy(), n_blobs, 0, 0, pattern)
    is_spot = np.concatenate([[False], spot])[blobs.labels]
    blocks = spot & faint & (blobs.extents > opts.dot_mm)  # not a halo dot: a block?
    faint_blocks = np.concatenate([[False], blocks])[blobs.labels] if blocks.any() else None
    n_spots, n_px = int(spot.sum()), int(is_spot.sum())
    return EdgeSpots(group.mask & ~is_spot, n_blobs, n_spots, n_px, pattern, faint_blocks)


__all__ = [
    "PATTERN_REACH",
    "EdgeSpots",
    "ElementGraph",
    "Group",
    "PartsJoined",
    "PrintCheck",
    "edge_spots",
    "element_graph",
    "group_blobs",
    "hull_fill",
    "is_print",
    "join_shoulders",
    "join_side_by_side",
    "join_tips",
    "linked_edges",
    "maybe_tiny_print",
    "merge_overlapping",
    "reading_order",
    "text_line",
    "thin_protrusions",
    "union",
    "union_labels",
    "word_in_a_line",
]
