"""Judgement thresholds of the print analysis, passed explicitly (never a global).

An :class:`AnalysisOptions` travels as an argument from the caller to every step
(:func:`inkprint.read_scan`, :func:`inkprint.binarize`, :func:`inkprint.group_blobs`,
:func:`inkprint.edge_spots`, :func:`inkprint.analyze_scan`) and, inside the batch
options, to worker processes and Dask workers: a worker re-imports :mod:`inkprint`, so
a module-level setting changed by the caller would not reach it.

Sizes are physical (mm, mm^2) and converted to pixels with the scan's scale
(:mod:`inkprint.coords`), so the same options work at 150 and 600 dpi.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from numbers import Integral, Real

from .errors import InvalidInput


def _finite(v) -> bool:
    return isinstance(v, Real) and not isinstance(v, bool) and math.isfinite(v)


# field -> (accepts the value, allowed range as told in the error)
_RULES = {
    "group_distance_mm": (lambda v: v > 0, "> 0 mm"),
    "group_mm": (lambda v: v > 0, "> 0 mm, or None for the footprint rule"),
    "group_size_factor": (lambda v: v >= 0, ">= 0 (times the smaller element's width)"),
    "group_pattern_factor": (lambda v: v >= 0, ">= 0 (times the tread pattern's gap)"),
    "group_tip_share": (lambda v: 0 <= v <= 1, "a share of the neighbour's ink in [0, 1]"),
    "group_print_gap": (lambda v: 0 <= v < 1, "a fraction of the footprint's extent in [0, 1)"),
    "group_rib_overlap": (lambda v: 0 <= v <= 1, "a fraction of the shorter part in [0, 1]"),
    "group_rib_gaps": (lambda v: v >= 0, ">= 0 (times the gap)"),
    "group_rib_strokes": (lambda v: v >= 0, ">= 0 (times stroke_width_mm)"),
    "group_doubt_factor": (lambda v: v >= 1, ">= 1 (a factor about group_print_gap)"),
    "group_groove_max_mm": (lambda v: v > 0, "> 0 mm"),
    "min_patch_area_mm2": (lambda v: v >= 0, ">= 0 mm^2, or None to scale with the sheet"),
    "min_patch_sheet_fraction": (lambda v: 0 <= v < 1, "a fraction of the sheet in [0, 1)"),
    "min_patch_fraction": (lambda v: 0 <= v <= 1, "a fraction of the largest print in [0, 1]"),
    "min_patch_width_mm": (lambda v: v >= 0, ">= 0 mm"),
    "min_patch_length_mm": (lambda v: v >= 0, ">= 0 mm"),
    "min_net_to_gross": (lambda v: 0 <= v <= 1, "a fraction in [0, 1]"),
    "max_patch_aspect": (lambda v: v >= 1, ">= 1 (length over width)"),
    "text_line_aspect": (lambda v: v >= 1, ">= 1 (length over width)"),
    "speck_area_mm2": (lambda v: v >= 0, ">= 0 mm^2"),
    "stroke_width_mm": (lambda v: v > 0, "> 0 mm"),
    "line_length_mm": (lambda v: v > 0, "> 0 mm"),
    "mark_overhang_mm": (lambda v: v >= 0, ">= 0 mm"),
    "bold_reach_mm": (lambda v: v >= 0, ">= 0 mm"),
    "bold_fill": (lambda v: 0 <= v <= 1, "a fraction in [0, 1]"),
    "bold_body_fill": (lambda v: 0 <= v <= 1, "a fraction in [0, 1]"),
    "light_tolerance": (lambda v: 0 <= v < 1, "a relative variation in [0, 1)"),
    "light_scale_mm": (lambda v: v > 0, "> 0 mm"),
    "light_detail_mm": (lambda v: v > 0, "> 0 mm"),
    "light_gap_mm": (lambda v: v >= 0, ">= 0 mm"),
    "light_basin": (lambda v: 0 < v < 1, "a relative darkness in (0, 1)"),
    "light_edge_ink": (lambda v: 0 < v < 1, "a fraction of the paper's brightness in (0, 1)"),
    "light_fill_error": (lambda v: v >= 0, ">= 0 (a share of the light's change)"),
    "light_edge_rise_mm": (lambda v: v > 0, "> 0 mm"),
    "perspective_tolerance_deg": (lambda v: 0 < v < 45, "an angle in (0, 45) degrees"),
    "perspective_keystone": (lambda v: 0 < v < 1, "a relative difference in (0, 1)"),
    "edge_spot_area_mm2": (lambda v: v >= 0, ">= 0 mm^2"),
    "edge_spot_faintness": (lambda v: 0 <= v <= 1, "a fraction in [0, 1]"),
    "edge_spot_distance_mm": (lambda v: v >= 0, ">= 0 mm"),
    "edge_spot_pattern_factor": (lambda v: v >= 0, ">= 0 (times the core's tread gap)"),
    "edge_window_mm": (lambda v: v > 0, "> 0 mm"),
    "edge_pip_jump": (lambda v: 0 < v <= 1, "a share of the paper-to-ink contrast in (0, 1]"),
    "faint_line_mm": (lambda v: v > 0, "> 0 mm"),
    "faint_line_reach_mm": (lambda v: v > 0, "> 0 mm"),
    "faint_line_contrast": (lambda v: v > 0, "> 0 (a share of the paper-to-ink contrast)"),
    "faint_line_least": (lambda v: 0 < v <= 1, "a transmission in (0, 1]"),
    "tip_block_strokes": (lambda v: v >= 0, ">= 0 (times the stroke width)"),
    "tip_taper_strokes": (lambda v: 0 <= v <= 1, "in [0, 1] (times the stroke width)"),
    "tread_teeth": (lambda v: v >= 0 and float(v).is_integer(), "a whole number >= 0"),
    "sliver_solidity": (lambda v: 0 < v <= 1, "a fraction in (0, 1]"),
    "sliver_elongation": (lambda v: v >= 1, ">= 1 (length over thickness)"),
    "edge_mark_mm": (lambda v: v >= 0, ">= 0 mm"),
    "mark_near_px": (lambda v: v >= 1 and float(v).is_integer(), "a whole number of pixels >= 1"),
    "mark_pull": (lambda v: 0 <= v < 1, "a relative change in [0, 1)"),
    "body_reach": (lambda v: v > 0, "> 0 (a relative change)"),
    "tick_reach_mm": (lambda v: v >= 0, ">= 0 mm"),
    "edge_bump_px": (lambda v: v > 0, "> 0 px"),
    "writing_share": (lambda v: v >= 0, ">= 0 (times the group's own ink)"),
    "grid_span": (lambda v: 0 < v <= 1, "a fraction of the sheet in (0, 1]"),
    "grid_min_lines": (lambda v: v >= 1 and float(v).is_integer(), "a whole number >= 1"),
    "grid_graze_mm": (lambda v: v >= 0, ">= 0 mm"),
    "grid_ink_darker": (lambda v: 0 <= v <= 1, "a fraction in [0, 1]"),
    "dot_mm": (lambda v: v >= 0, ">= 0 mm"),
    "fine_element_mm": (lambda v: v >= 0, ">= 0 mm"),
    "fine_spacing_mm": (lambda v: v >= 0, ">= 0 mm"),
    "fine_min_elements": (lambda v: v >= 2 and float(v).is_integer(), "a whole number >= 2"),
    "fine_regularity": (lambda v: v >= 1, ">= 1 (a ratio of spacings)"),
    "fine_neighbours": (lambda v: v >= 0, ">= 0 neighbours"),
    "fine_ink_share": (lambda v: 0 <= v <= 1, "a fraction in [0, 1]"),
    "edge_uncertainty": (lambda v: 0 <= v < 1, "a relative change in [0, 1)"),
    "grid_aside_share": (lambda v: v >= 0, ">= 0 (a share of the print's hull area)"),
    "axis_uncertain_aspect": (lambda v: v >= 1, ">= 1 (length over width)"),
    "axis_misaligned_deg": (lambda v: 0 <= v < 45, "an angle in [0, 45) degrees"),
    "axis_misaligned_excess": (lambda v: 0 <= v < 1, "a relative change in [0, 1)"),
    "sensitivity": (lambda v: 0 <= v < 1, "a relative change in [0, 1)"),
    "min_ink_fraction": (lambda v: 0 <= v < 1, "a fraction in [0, 1)"),
    "max_ink_fraction": (lambda v: 0 < v <= 1, "a fraction in (0, 1]"),
    "max_pixels": (lambda v: v >= 1 and float(v).is_integer(), "a whole number of pixels >= 1"),
    "min_dpi": (lambda v: v > 0, "> 0 dots per inch"),
    "max_dpi": (lambda v: v > 0, "> 0 dots per inch"),
    "pdf_dpi": (lambda v: v > 0, "> 0 dots per inch"),
}
#: fields that may be None (the rule then applies to a given value only)
_OPTIONAL = ("group_mm", "min_patch_area_mm2")


@dataclass(frozen=True)
class AnalysisOptions:
    """Thresholds that decide what is a print, an edge spot or a usable scan.

    Every field has the default the analysis was validated with; change one with
    ``AnalysisOptions(min_patch_area_mm2=50.0)`` or :meth:`replace`. Invalid values
    raise :class:`inkprint.InvalidInput` naming the field.

    Parameters
    ----------
    group_distance_mm : float [mm]
        Tread elements closer than this always belong to the same print.
    group_mm : float or None [mm]
        Override of the footprint rule: elements belong to one print exactly when
        closer than this (``--group-mm``, manifest column ``group_mm``). None: the
        footprint rule of :func:`inkprint.group_blobs` (grooves narrower than
        ``group_pattern_factor`` x the tread pattern's own gaps, or between parts
        side by side narrower than ``group_print_gap`` x the footprint, are inside
        a print).
    group_size_factor : float [-]
        A gap narrower than this fraction of the smaller element's width is a
        groove (0, off: it was 0.75 for car ribs, and joined two 30 mm wide slick
        prints 20 mm apart; ``group_print_gap`` judges ribs at the footprint's scale).
    group_pattern_factor : float [-]
        A gap within this many times the gaps around the two elements continues
        the tread pattern (wide-groove knobs; car blocks whose circumferential
        grooves are 2.5 x their lateral ones: at 2.5 a groove measured a pixel
        wider split the print).
    group_tip_share : float [-]
        A group with less ink than this share of its nearest neighbour's joins it
        when its gap is within ``group_pattern_factor`` x the neighbour's tread gap
        (a knobby print's tip blocks, a sliver cut by the outline).
    group_print_gap : float [-]
        Parts of a footprint lying side by side (a car print's ribs) are one print
        when the gap between them is at most this fraction of the smaller extent of
        the whole they make (a car print's 4-10 mm circumferential grooves are
        <= 0.13 x its 80-185 mm; two bicycle prints 20-30 mm apart >= 0.2 x theirs).
    group_rib_overlap : float [-]
        Two parts lie side by side when their extents along the gap between them
        overlap over at least this fraction of the shorter one (the ribs of one
        print end on its outline: the outer ones are shorter; a label beside a print
        often reaches beyond its end) ...
    group_rib_gaps : float [-]
        ... and over at least this many times the gap (ribs run along a groove; a
        speck or a block beside a print does not).
    group_rib_strokes : float [-]
        A part side by side is tread only when its widest element is at least this
        many times ``stroke_width_mm`` wide (a label's bold letters, 1.5-1.9 mm at
        400 dpi, are not a rib).
    group_doubt_factor : float [-]
        A side-by-side join or split whose gap lies within this factor of the
        ``group_print_gap`` limit flags the print ``grouping_uncertain`` (give
        ``--group-mm``): 1.15, 0.157-0.207 x the footprint, between the car prints'
        grooves (<= 0.13) and two bicycle prints 25 mm apart (0.21 x a 120 mm long
        knobby pair side by side: 1.35 flagged such pairs).
    group_groove_max_mm : float [mm]
        No groove inside a print is wider: the tread-pattern, tip and side-by-side
        joins stop at this gap (a bicycle's knobs are at most ~10 mm apart, a car's
        circumferential grooves 4-15 mm). Three motorcycle prints, each one piece
        37-47 mm apart, made a "pattern" of their own spacing and were joined into
        one 231 x 149 mm print (held-out set 1, sheet 24). ``group_mm`` overrides.
    min_patch_area_mm2 : float or None [mm^2]
        A group with less ink is dust or a mark, not a print; None (default):
        ``min_patch_sheet_fraction`` of the sheet's area.
    min_patch_sheet_fraction : float [-]
        The automatic ink-area floor as a fraction of the sheet (1e-4: 6 mm^2 on a
        letter sheet, 0.7 mm^2 on a 10 x 7 cm card).
    min_patch_fraction : float [-]
        A group with less ink than this fraction of the largest print's is a
        fragment or a mark beside the prints (unless the image's edge cuts it: a
        print running off the sheet, measured and flagged ``clipped``).
    min_patch_length_mm : float [mm]
        A group shorter than this along its longer axis is a dot or a piece of a
        letter, not a contact print: the smallest bicycle prints (a track tire at
        high pressure and a light load) are ~10 mm long, the independent
        generator's tiniest 7.1 mm; 4.5-5.7 mm blobs of marker writing on pages of
        writing only were reported as prints (held-out set 2, sheets 22 and 115).
    min_patch_width_mm : float [mm]
        A group narrower than this across its axis is a line or a mark.
    min_net_to_gross : float [-]
        A group whose ink covers less of its hull than this fraction is writing or
        marks, not a print (wide-groove knobby prints ink ~12 % of their hull).
    max_patch_aspect : float [-]
        A group longer than this many widths is a line, not a contact patch.
    text_line_aspect : float [-]
        A group at least this many widths long whose ink is :data:`TEXT_LINE_LETTERS`
        or more pieces each spanning most of its width, side by side in one row,
        with gaps between them (the ink fills less than ``TEXT_LINE_FILL`` of the
        hull), is a line of writing, not a print: a label in marker letters 4-6 mm
        high above the prints was taken for a 113 x 6 mm print (held-out set 1,
        sheets 23 and 26: 0.46-0.53 of the hull inked); a chevron tread's print
        (25 ribs across a 129 x 23 mm print) inks 0.87 of it.
    speck_area_mm2 : float [mm^2]
        Ink blobs smaller than this are paper grain or dust and are removed.
    stroke_width_mm : float [mm]
        Marks thinner than this (pen writing, ruler lines, gridlines) are told from
        tread elements, which are wider: ink that vanishes under an opening with a
        disk this wide is a thin mark.
    line_length_mm : float [mm]
        A thin mark this long, mostly outside the prints, is a line, gridlines or
        writing, and is set aside (never merged into a print).
    mark_overhang_mm : float [mm]
        A thin piece of ink reaching farther than this out of a print's outline (a
        label touching the print, a ruler's tick) is set aside; nearer, it is the
        print's own edge (see :mod:`inkprint.marks`).
    bold_reach_mm : float [mm]
        A piece of a print's thick ink outside its body (what an opening two strokes
        wide keeps) reaching farther than this out of the body's hull ...
    bold_fill : float [-]
        ... and inking less than this share of what it adds to its element's hull
        (its pores closed) is a marker's letter joined to the print and is set aside
        (bold letters, 1.1-1.4 mm strokes, touching a slick print: width +60 %;
        they ink 2-13 % of it); nearer, it is one only when joined to such letters.
        A print's tip or corner the opening cut fills what it adds: a slick or
        car print's 0.8-1.0, a file tread's ragged tip at 150 dpi 0.67.
    bold_body_fill : float [-]
        Pieces of a print's thick ink outside its body are judged so only when the
        body (its elements' cores) fills at least this share of its convex hull: a
        slick or file tread print's 0.80-1.0. A car print's body fills 0.72 of it,
        and the bars between its shoulder grooves, cut by the outline, stand out of
        it like letters (independent set 4 file 86: width -5.5 %, unflagged).
    dot_mm : float [mm]
        Thin ink no longer than this either way near a print is a dot (a halo
        speck, a clipped knob): the print's own, for the edge-spot rule to judge.
        On chart paper, dots do not keep a gridline under them as print ink.
    fine_element_mm : float [mm]
        A fine tread (knurl, diamond file, dot field) is a dense regular field of
        small separate ink elements, each thinner than a pen stroke or too small to
        count as thick ink: its elements are thin pieces no longer than this either
        way (and compact), 0 to look for none. Such a field is tread - print ink -
        not dust or text (:func:`inkprint.marks._fine_fields`).
    fine_spacing_mm : float [mm]
        ... whose centres lie at most this far from their nearest neighbour (a
        dot-grid paper's dots lie 5 mm apart).
    fine_min_elements : int
        ... at least this many in one field (linked neighbour to neighbour).
    fine_regularity : float [-]
        ... regular: the field's 80th percentile of the nearest-neighbour
        spacing at most this many times its 20th, and likewise the elements' areas
        at most twice this (scattered dust or pixel noise: 2.7 and more; a line of
        writing's letters differ in width and area).
    fine_neighbours : float
        ... two-dimensional: the median element has at least this many others
        within 1.5 times its nearest neighbour's distance (a lattice: 4 to 8; a
        diamond band two rows deep along a file tread's body: 3; a line of
        letters: 2).
    fine_ink_share : float [-]
        ... dense: its elements' ink fills at least this share of the field's
        area (the elements' count times the squared median spacing; a knurl or
        dot field 0.25-0.6, a file shoulder of 0.5 mm pores 1.3 mm apart 0.08-0.12,
        a dot-grid paper's dots 0.01). 0.08 (0.12 before: held-out seed 8 sheet 75,
        such shoulders were 1215 "dust" and the print read 7.2 mm wide, not 41.7).
    edge_spot_area_mm2 : float [mm^2]
        Section 7.1.1 rule: blobs at least this large (and dark) form the print's
        core.
    edge_spot_faintness : float [-]
        A blob outside the core whose peak darkness is below this fraction of the
        core's was not pressed: it bore no load. When one larger than a dot (extent
        over ``dot_mm``) left out this way would make the print's length,
        width or half its hull area larger by more than ``edge_uncertainty``, the print is
        flagged ``faint_edge``: a lightly inked tread block and a light touch look
        alike (the difficulty of section 7.1.1).
    edge_spot_distance_mm : float [mm]
        A small blob outside the core farther than this from it bore no load ...
    edge_spot_pattern_factor : float [-]
        ... and farther than this many times the core's own tread gap (the median
        gap between its blobs): nearer, a small dark block continues the tread
        pattern (a tip block; a knobby tread's gaps along and across differ by a
        third, so 1.5 dropped tip blocks).
    cut_caps : bool
        Join to a coarse print the caps of its next row of elements that its
        outline cut to slivers, found on its tread's lattice among the ink set
        aside or dropped around it (:mod:`inkprint.caps`; not in section 7.1.1,
        whose rule drops them as edge spots or never sees them: held-out prints a
        row's gap short, -6.7 to -14.5 %). False: the section 7.1.1 rule alone.
    edge_window_mm : float [mm]
        Window of the local paper and ink levels whose mean defines the print's
        edge (half contrast) for the outline.
    edge_pip_jump : float [-]
        A one-pixel pip of the outline (an ink pixel joined to the print by one
        side) darker than both its neighbours along the edge by more than this
        share of the paper-to-ink contrast is a dust speck touching the edge: the
        outline takes the neighbours' level there (a print's edge changes by
        1 / (2 R) per pixel, R its radius of curvature in pixels: under 0.3 for
        R above 1.7 px, a 0.3 mm tip at 150 dpi).
    faint_line_mm : float [mm]
        The widest faint page-axis line (a chart paper's gridline) divided out of a
        print's grey before its edge is found (:mod:`inkprint.faintlines`): where
        such a line crosses the edge the blurred edge and the line's grey add up
        and the outline bulged by a pixel (tiny prints on chart paper: width +1 to
        +5 %, unflagged).
    faint_line_reach_mm : float [mm]
        The margin of paper around the print's box in which each row's and
        column's line is read (the lighter side's median grey).
    faint_line_contrast : float [-]
        A row (column) darker than the rows near it by more than this share of the
        paper-to-ink contrast holds a line.
    faint_line_least : float [-]
        Only lines letting through this share of the paper's light or more are
        divided out: a darker line thresholds as ink and is taken out as a
        gridline (:mod:`inkprint.gridlines`), and ink printed over it may hide
        under it rather than multiply with it.
    tip_block_strokes : float [-]
        A thin piece apart from a print off its ends along its major axis may be a
        tip block the outline cut to a sliver (left to the edge-spot rule) only when
        the print's thick ink holds two or more blocks at least this many
        ``stroke_width_mm`` a side (squared); beside a one-piece print (slick,
        ribbed, file tread) it is a letter's stroke (a label at a slick print's tip
        read hull area +2.5 %).
    tip_taper_strokes : float [-]
        The pen-thin ink at a print's ends along its major axis, joined to its thick
        ink and reaching no farther than this many ``stroke_width_mm`` out of the
        hull of that thick ink, is the print's tapering tip (a stroke-wide opening
        cuts a narrow tip short), not a pen stroke's foot: kept. A track tire's
        3.3 mm wide print lost 0.13 mm at each tip so (0.2 strokes), length
        -1.4 %; a stroke's foot reaches farther, and a mark set aside beyond a tip
        flags the print (``mark_pull``). 0: every foot is dropped.
    tread_teeth : int
        Pen-thin stubs joined to a print, no deeper out of the hull of its thick ink
        than a stroke, are its tread's teeth, not pen strokes' feet, when at least
        this many lie on each side of its major axis, each side's row along 0.4 of
        its length or more (a track tire's file tread print: a spine with a row of
        teeth down each side, joined to it by a pixel at 150 dpi, read width
        -27 %); a label's letters touch one side. 0: never.
    sliver_solidity : float [-]
        A thin piece apart from a print, lying along its outline no thicker across
        it than ``mark_overhang_mm``, is a tread block the outline cut to a sliver
        (the print's own, left to the edge-spot rule) when it fills at least this
        share of its convex hull (a letter's bits fill less than 0.55) ...
    sliver_elongation : float [-]
        ... and is at least this many times longer than it is thick across the
        outline (a letter's foot beside the print is not).
    edge_mark_mm : float [mm]
        A mark set aside covering more of a print's outline than this (a label's
        strokes, a line's stub) flags the print ``mark_on_edge``: the outline there
        is uncertain by the mark's width.
    edge_uncertainty : float [-]
        A print whose length or width, or half its hull area, grows by more than
        this share with the ink of the lines taken out along its edge added
        (gridlines, rulers: the edge lies somewhere under the line; the ink
        measured is a lower bound, the line's far side an upper one) is flagged
        ``mark_on_edge``. A line crossing the edge, or grazing a long flat side
        away from the widest point, moves neither much.
    mark_near_px : int [px]
        Ink of a mark set aside (a label's letter, a ruler) this close to a print's
        ink, and at least half a stroke (``stroke_width_mm``) close, may be the
        mark's: a stroke's foot merged into the print's edge (the merge is the
        threshold's and the anti-aliasing's, in pixels; the foot a stroke-wide
        opening leaves where a tick meets the edge at a shallow angle reaches half
        a stroke: with 2 px alone a ruler's tick along the edge gave width +4.5 %,
        unflagged, at 200 dpi) ...
    mark_pull : float [-]
        ... and when the print's length or width without those pixels is smaller by
        more than this share, the print is flagged ``mark_on_edge`` (as
        ``edge_uncertainty``: the pixels within half a stroke bound the pull from
        above, so 0.6 %, not the 0.3 % a two-pixel lower bound needed; the outline
        also follows the mark's grey).
    body_reach : float [-]
        A print whose ink reaches farther than this share beyond its body (its ink
        closed by a square a stroke wide, then opened by one 2.5 strokes wide) in
        length or width is flagged ``mark_on_edge``: a line as wide as a pen
        stroke or wider (a ruler's edge lying along the print) was taken for tread
        and measured with it. Tip slivers cut by the outline reach a few percent.
    tick_reach_mm : float [mm]
        Within this of ink set aside touching a print (a ruler's ticks are 3-5 mm
        long) its outline is compared with a parabola fitted to the outline on
        either side ...
    edge_bump_px : float [px]
        ... and outline points more than this beyond it (a tick lying along the
        edge inside the print, its end out of the edge by a pixel or two) count
        into ``mark_pull`` as a mark's foot.
    writing_share : float [-]
        A group with more pen strokes set aside around it than this share of its
        own ink is writing, not a print.
    grid_span : float [-]
        A chart-paper gridline runs unbroken over at least this share of the
        sheet's width (height) ...
    grid_min_lines : int [-]
        ... and a grid has at least this many parallel lines.
    grid_graze_mm : float [mm]
        A gridline taken out grazes a print's edge where they touch over a run at
        least this long (a line leaving the edge at a slant touches it over a
        shorter run; see ``edge_uncertainty``).
    grid_ink_darker : float [-]
        A pixel on a gridline darker than this share of the lines' grey (their
        lower quartile) is ink printed over the line: chart paper's lines are
        lighter than a print's ink, so a tip sliver lying on a line stays the
        print's (length -3.5 % when it was taken out with the line), and where the
        print's ink beside a line is that dark its edge cannot hide under the line
        by more than its last pixel. 0 turns it off.
    grid_aside_share : float [-]
        On a sheet with gridlines, pen-thin ink set aside touching a print over more
        than this share of its hull area flags it ``mark_on_edge``: tread slivers a
        gridline joined read as strokes (hull area -5 %).
    axis_uncertain_aspect : float [-]
        With ``rolling_axis='auto'``, a print whose length / width is below this is
        flagged ``axis_uncertain`` (its longer axis may not be the rolling one).
    axis_misaligned_deg : float [deg]
        A given rolling axis ('x', 'y') within this of the print's own axis is
        snapped to it: a print taped or scanned askew is measured along itself (a
        static print's rolling direction is its own axis; the given axis says which
        of its two axes is the length; a 123 x 21 mm print turned 0.35 degrees read
        3 % too wide along the sheet's axis, prints turned 2-10 degrees on held-out
        2026 were all flagged at the former 1 degree); farther, or when the own
        axis is not confirmed by the principal axis, it is used as given and flags
        the print ``axis_misaligned`` ... (A print with under half its hull inked,
        a knob or dot pattern, is snapped within 1 degree only,
        ``analyze.SNAP_SOLIDITY``, unless its three axis estimates give a length
        and width within ``axis_misaligned_excess`` of each other:
        ``analyze.settled_turn``.)
    axis_misaligned_excess : float [-]
        ... when measuring along the given axis also lengthens or widens it by more
        than this share (half the 1 % bar; a nearly round print reads the same along
        any axis; one whose own axis is not defined, aspect below
        ``axis_uncertain_aspect``, by more than 4 x this). The own axis of a
        wide-groove knob pattern is uncertain by ~0.7 degrees: at 0.002, knobby
        prints taped square and read within 0.1 % were flagged.
    light_tolerance : float [-]
        When the paper's brightness varies by more than this fraction over the
        sheet (a gradient, a shadow), the light is flattened before thresholding.
    light_scale_mm : float [mm]
        At the sheet's edge, the paper next to a print run off it is looked for
        this far away (the ink there is not enclosed by paper).
    light_detail_mm : float [mm]
        Ink details narrower than twice this (tread blocks, writing, gridlines) are
        closed over before the paper's brightness is estimated; shadow edges are
        softer than this (the independent set's: 3-15 mm).
    light_gap_mm : float [mm]
        Ink regions closer than this (a tread's blocks) are left out of the paper's
        brightness together, with the paper between them.
    light_basin : float [-]
        A region enclosed by paper and darker than its lowest surrounding paper by
        more than this share is ink, not shade (ink is > 50 % darker; the paper's
        own mottle is < 2 %; shade runs off the sheet and is not enclosed).
    light_edge_ink : float [-]
        At the sheet's edge, grey below this fraction of the paper around is ink (a
        print run off the sheet), above it shade (ink < 0.5 of the paper, a
        shadow's paper > 0.6).
    light_edge_rise_mm : float [mm]
        At the sheet's edge, a dark region whose own edge rises to the paper
        around within this (mean slope over its depth) is ink, a softer one shade:
        a print's edge rises within 1-2 mm on the ~1 mm grid, a shadow's over its
        penumbra (the independent set's: 3-15 mm).
    light_fill_error : float [-]
        The paper's brightness filled in under a print may be off by this share of
        how much it changes around the print (98th less 2nd percentile, log): when
        that exceeds how far the print's median ink lies below the threshold (log),
        the print is flagged ``light_uncertain``. Slick prints inked 0.35-0.7
        across shadow bands 25-40 % deep, soft and hard-edged: every print off by
        more than 1 % had a change 1.33-3.9 x its margin (its margin read on the ink
        that was kept, so a print cut short reads a larger one), every one within
        the bar at most 1.21 x (0.9: flagged above 1.11 x).
    perspective_tolerance_deg : float [deg]
        A photographed page whose corners depart from right angles by more than
        this is not flat-on: its prints are flagged ``perspective``.
    perspective_keystone : float [-]
        ... or whose opposite sides (its corners refined on the full image) differ
        by more than this share: the scale then changes across the page by as much
        (held-out set 14 sheet 54: 3.7 %, corners within 1.33 degrees of square,
        length -2.4 % with status ok before). Flat photos of the held-out sets read
        0.01 % at most, tilted ones 3.7-15 %.
    sensitivity : float [-]
        Relative threshold change of the sensitivity band: each print is measured
        again at the threshold x (1 -+ ``sensitivity``).
    min_ink_fraction, max_ink_fraction : float [-]
        A sheet with less of its area inked than ``min_ink_fraction`` is blank
        (:class:`inkprint.NoInk`); with more than ``max_ink_fraction``, all ink
        (:class:`inkprint.AllInk`).
    max_pixels : int [px]
        Largest image accepted (width x height); larger files raise
        :class:`inkprint.ImageTooLarge` before decoding (decompression-bomb guard).
        2.5e8 is a letter sheet at 1800 dpi.
    min_dpi, max_dpi : float [dots per inch]
        Plausible scan resolutions: DPI metadata outside the range is ignored, a
        scale given outside it is refused.
    pdf_dpi : float [dots per inch]
        Resolution at which PDF pages are rendered when no scale is given.
    """

    group_distance_mm: float = 3.0
    group_mm: float | None = None
    group_size_factor: float = 0.0
    group_pattern_factor: float = 3.0
    group_tip_share: float = 0.1
    group_print_gap: float = 0.18
    group_rib_overlap: float = 0.8
    group_rib_gaps: float = 3.0
    group_rib_strokes: float = 3.0
    group_doubt_factor: float = 1.15
    group_groove_max_mm: float = 20.0
    min_patch_area_mm2: float | None = None
    min_patch_sheet_fraction: float = 1e-4
    min_patch_fraction: float = 0.05
    min_patch_width_mm: float = 2.0
    min_patch_length_mm: float = 6.0
    min_net_to_gross: float = 0.06
    max_patch_aspect: float = 30.0
    text_line_aspect: float = 5.0
    speck_area_mm2: float = 0.05
    stroke_width_mm: float = 0.9
    line_length_mm: float = 12.0
    mark_overhang_mm: float = 1.0
    bold_reach_mm: float = 2.0
    bold_fill: float = 0.4
    bold_body_fill: float = 0.75
    dot_mm: float = 1.5
    fine_element_mm: float = 2.5
    fine_spacing_mm: float = 3.0
    fine_min_elements: int = 24
    fine_regularity: float = 1.5
    fine_neighbours: float = 3.0
    fine_ink_share: float = 0.08
    edge_spot_area_mm2: float = 1.5
    edge_spot_faintness: float = 0.6
    edge_spot_distance_mm: float = 1.0
    edge_spot_pattern_factor: float = 2.0
    cut_caps: bool = True
    edge_window_mm: float = 0.6
    edge_pip_jump: float = 0.35
    faint_line_mm: float = 0.3
    faint_line_reach_mm: float = 2.0
    faint_line_contrast: float = 0.03
    faint_line_least: float = 0.5
    tip_block_strokes: float = 2.0
    tip_taper_strokes: float = 0.5
    tread_teeth: int = 3
    sliver_solidity: float = 0.75
    sliver_elongation: float = 2.0
    edge_mark_mm: float = 2.5
    edge_uncertainty: float = 0.006
    mark_near_px: int = 2
    mark_pull: float = 0.006
    body_reach: float = 0.15
    tick_reach_mm: float = 5.0
    edge_bump_px: float = 1.0
    writing_share: float = 0.5
    grid_span: float = 0.7
    grid_min_lines: int = 3
    grid_graze_mm: float = 1.0
    grid_ink_darker: float = 0.75
    grid_aside_share: float = 0.005
    axis_uncertain_aspect: float = 1.3
    axis_misaligned_deg: float = 10.0
    axis_misaligned_excess: float = 0.005
    light_tolerance: float = 0.1
    light_scale_mm: float = 30.0
    light_detail_mm: float = 2.5
    light_gap_mm: float = 5.0
    light_basin: float = 0.1
    light_edge_ink: float = 0.55
    light_fill_error: float = 0.9
    light_edge_rise_mm: float = 3.0
    perspective_tolerance_deg: float = 1.5
    perspective_keystone: float = 0.01
    sensitivity: float = 0.10
    min_ink_fraction: float = 1e-5
    max_ink_fraction: float = 0.6
    max_pixels: int = 250_000_000
    min_dpi: float = 30.0
    max_dpi: float = 10_000.0
    pdf_dpi: float = 300.0

    def __post_init__(self) -> None:
        if not isinstance(self.cut_caps, bool):
            raise InvalidInput("cut_caps", self.cut_caps, "True or False")
        for name, (ok, allowed) in _RULES.items():
            value = getattr(self, name)
            if value is None and name in _OPTIONAL:
                continue
            if not (_finite(value) and ok(value)):
                raise InvalidInput(name, value, allowed)
        for name in (
            "max_pixels",
            "mark_near_px",
            "grid_min_lines",
            "fine_min_elements",
            "tread_teeth",
        ):
            object.__setattr__(self, name, int(getattr(self, name)))
        if self.max_ink_fraction <= self.min_ink_fraction:
            raise InvalidInput(
                "max_ink_fraction",
                self.max_ink_fraction,
                f"> min_ink_fraction = {self.min_ink_fraction:g}",
            )
        if self.max_dpi <= self.min_dpi:
            raise InvalidInput("max_dpi", self.max_dpi, f"> min_dpi = {self.min_dpi:g}")
        if not self.min_dpi <= self.pdf_dpi <= self.max_dpi:
            raise InvalidInput(
                "pdf_dpi",
                self.pdf_dpi,
                f"[min_dpi, max_dpi] = [{self.min_dpi:g}, {self.max_dpi:g}]",
            )

    def replace(self, **changes) -> AnalysisOptions:
        """A copy with some fields changed (validated like a new instance).

        Parameters
        ----------
        **changes
            Field names and their new values, e.g. ``group_distance_mm=5.0``.

        Returns
        -------
        AnalysisOptions

        Raises
        ------
        InvalidInput
            An unknown field name, or a value outside the field's range.
        """
        names = {f.name for f in dataclasses.fields(self)}
        for name, value in changes.items():
            if name not in names:
                raise InvalidInput(name, value, "a field of AnalysisOptions")
        return dataclasses.replace(self, **changes)

    def patch_area_floor(self, sheet_area_mm2: float) -> float:
        """The ink-area floor of a print on a sheet of this area [mm^2].

        Parameters
        ----------
        sheet_area_mm2 : float [mm^2]

        Returns
        -------
        float [mm^2]
            ``min_patch_area_mm2``, or ``min_patch_sheet_fraction`` x the sheet.
        """
        if self.min_patch_area_mm2 is not None:
            return float(self.min_patch_area_mm2)
        return self.min_patch_sheet_fraction * float(sheet_area_mm2)


DEFAULT_OPTIONS = AnalysisOptions()


def resolve_threads(threads) -> int:
    """The threads a sheet's prints are measured on: ``threads``, or the cores this
    process may use when None.

    Parameters
    ----------
    threads : int or None

    Returns
    -------
    int

    Raises
    ------
    InvalidInput
        ``threads`` is not an integer >= 1 or None.
    """
    import os

    if threads is None:
        return len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else 1
    if isinstance(threads, bool) or not isinstance(threads, Integral) or threads < 1:
        raise InvalidInput("threads", threads, "an integer >= 1, or None (the cores)")
    return int(threads)


def resolve_options(options: AnalysisOptions | None) -> AnalysisOptions:
    """The options a step runs with: ``options``, or the defaults when None.

    Parameters
    ----------
    options : AnalysisOptions or None

    Returns
    -------
    AnalysisOptions

    Raises
    ------
    InvalidInput
        ``options`` is neither None nor an :class:`AnalysisOptions`.
    """
    if options is None:
        return DEFAULT_OPTIONS
    if not isinstance(options, AnalysisOptions):
        raise InvalidInput("options", type(options).__name__, "an inkprint.AnalysisOptions")
    return options


__all__ = ["DEFAULT_OPTIONS", "AnalysisOptions", "resolve_options", "resolve_threads"]
