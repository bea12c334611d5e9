"""Issue 11: marks touching a print's outline that widened it silently (seeds of the
mixed sets): a one-pixel dust speck at the widest point, a label's stroke off a
slick print's tip.

``make_case(kind, seed=S * 100_003 + k)`` is file ``k`` of seed ``S`` of
``python -m inkprint.accuracy``.
"""

import re
from types import SimpleNamespace

import cv2
import numpy as np
import pytest
from numpy.testing import assert_allclose

import inkprint as ip
from inkprint.accuracy import SILENT
from inkprint.analyze import _thin_excess, edge_field
from inkprint.group import thin_protrusions
from inkprint.synth import render_sheet
from inkprint.synth_cases import make_case
from tests.inkprint.drawn import drawn_scan
from tests.inkprint.test_classes import assert_passes, outcomes


def mixed_file(seed: int, k: int) -> int:
    return seed * 100_003 + k


def test_analyze_scan_dust_pip_at_the_widest_point():
    # 4244/0082 page 0: a one-pixel speck (grey 71) on the print's top row at its
    # widest point, paper (~230) on both sides of it: width +1.15 %
    case = make_case("pdf", seed=mixed_file(4244, 82))
    img, truths = render_sheet(case.sheets[0])
    res = ip.analyze_scan(ip.Scan(img, 25.4 / case.sheets[0].dpi, "given"), sensitivity=False)
    m, t = res.prints[0].metrics, truths[0]
    assert_allclose(
        [m.length / t.length, m.width / t.width, m.hull_area / t.hull_area], 1.0, atol=0.005
    )


def test_edge_field_dust_pip_reads_as_paper_an_edge_run_as_ink():
    grey = np.full((20, 40), 0.95, np.float32)
    grey[10:, :] = 0.05  # ink below row 10
    grey[9, 20] = 0.3  # a dust speck on the edge
    grey[9, 5:8] = 0.3  # a short run of the edge itself (three pixels)
    mask = grey < 0.5
    f = edge_field(grey, mask, mm_per_px=0.1)
    assert f[9, 20] > 0  # paper: the outline stays on the edge
    assert (f[9, 5:8] < 0).all()  # the run keeps its ink
    loose = ip.AnalysisOptions(edge_pip_jump=1.0)
    assert edge_field(grey, mask, mm_per_px=0.1, options=loose)[9, 20] < 0


def test_edge_field_pixel_joined_by_a_corner_reads_as_paper():
    # a pen stroke's last pixel touching the edge by a corner only (its side
    # neighbours paper): paper; a corner-joined pixel as light as the edge is kept,
    # and an edge's own staircase (pixels joined by a side) keeps its ink
    grey = np.full((20, 40), 0.95, np.float32)
    grey[10:, :] = 0.05
    grey[10, 20] = 0.7  # the edge pixel under it partly covered, not ink
    grey[9, 20] = 0.3  # the stroke's end: joined by the corners at (10, 19), (10, 21)
    grey[9, 30] = 0.3  # a speck joined by a side: a pip, as before
    grey[9, 5:8] = 0.3  # a run of the edge
    mask = grey < 0.5
    f = edge_field(grey, mask, mm_per_px=0.1)
    assert f[9, 20] > 0 and f[9, 30] > 0
    assert (f[9, 5:8] < 0).all()
    faint = grey.copy()
    faint[9, 20] = 0.45  # not darker than its side neighbours by the jump
    assert edge_field(faint, faint < 0.5, mm_per_px=0.1)[9, 20] < 0


def test_analyze_scan_label_stroke_end_on_the_edge(tmp_path):
    # mixed set 4265, file 6 (150 dpi): a faint label's stroke ends in a dark pixel
    # joined to the print's edge by a corner: width +1.54 %, unflagged
    results, _ = outcomes(tmp_path, "label", mixed_file(4265, 6), dpi=None)
    assert not [r for r in results if r["outcome"] in SILENT], results
    assert abs(results[0]["err_width"]) <= 0.01


def test_thin_protrusions_label_stroke_off_a_slick_print_tip(tmp_path):
    # 4246/0060: a label's letter (A) beside a slick print's tip, off its ends along
    # its major axis, was kept as a tip block's sliver: hull area +2.5 %
    results, _ = outcomes(tmp_path, "label", mixed_file(4246, 60), dpi=None)
    assert_passes(results)
    (r,) = results
    assert_allclose([r["err_width"], r["err_hull_area"]], 0.0, atol=0.015)


def test_thin_protrusions_keeps_tip_pieces_of_a_block_pattern_only():
    m = np.zeros((60, 200), bool)
    m[20:40, 20:180] = True  # one-piece print
    m[28:31, 182:186] = True  # a thin piece off its right end
    assert not thin_protrusions(m, width_px=6.0)[28:31, 182:186].any()
    blocks = m.copy()
    blocks[20:40, 95:105] = False  # two blocks: a tread pattern
    assert thin_protrusions(blocks, width_px=6.0)[28:31, 182:186].all()
    one = ip.AnalysisOptions(tip_block_strokes=20.0)  # no piece is a block
    assert not thin_protrusions(blocks, width_px=6.0, options=one)[28:31, 182:186].any()


def test_analyze_scan_ruler_tick_along_the_edge_flags_the_print(tmp_path):
    # 4244/0066: a ruler's tick lying along the print's lower edge inside it, its end
    # 1-2 px out of the edge 2.5 mm from the line: width +1.4 %, unflagged; now
    # mark_on_edge (the outline's bump over a parabola fitted beside it)
    results, rows = outcomes(tmp_path, "ruler", mixed_file(4244, 66), dpi=None)
    assert not [r for r in results if r["outcome"] in SILENT], results
    assert rows[0]["flags"] == "mark_on_edge"
    assert_allclose(results[0]["err_width"], 0.014, atol=0.003)  # the number flagged


def test_bump_pull_tick_end_out_of_a_smooth_edge():
    from inkprint.analyze import _bump_pull

    yy, xx = np.mgrid[:120, :400]
    own = ((xx - 200) / 180.0) ** 2 + ((yy - 40) / 40.0) ** 2 <= 1.0  # a smooth print
    aside = np.zeros_like(own)
    aside[81:120, 230:233] = True  # a line leaving its lower edge
    assert _bump_pull(own, aside, 0.0, 40.0, 1.0) == 0.0
    ticked = own.copy()
    ticked[78:82, 205:222] = True  # a tick's end 2 px out of the edge near the line
    # the points beyond 1 px out: a lower bound of the tick's 2 px on an 81 px width
    assert_allclose(_bump_pull(ticked, aside, 0.0, 40.0, 1.0), 1.0 / 80.0, atol=0.003)
    assert _bump_pull(ticked, aside, 0.0, 40.0, 3.0) == 0.0  # a bump under 3 px is edge


def test_bump_pull_stretch_across_the_contours_start():
    # a label over the print's top: the stretch of outline near it holds the
    # contour's first point (its top-left pixel), so it runs to the contour's end;
    # it was dropped and a period on the edge went unjudged (label 4259/6: width
    # +1.7 %, unflagged)
    from inkprint.analyze import _bump_pull

    yy, xx = np.mgrid[:120, :400]
    own = ((xx - 200) / 180.0) ** 2 + ((yy - 60) / 40.0) ** 2 <= 1.0
    top = np.flatnonzero(own.any(axis=1))[0]
    first = np.flatnonzero(own[top])[0]  # where findContours starts
    aside = np.zeros_like(own)
    aside[top - 12 : top - 2, first - 30 : first + 40] = True  # the label's letters
    assert _bump_pull(own, aside, 0.0, 40.0, 1.0) == 0.0
    dotted = own.copy()
    dotted[top - 2 : top, first - 1 : first + 2] = True  # a period on the edge, 2 px
    assert_allclose(_bump_pull(dotted, aside, 0.0, 40.0, 1.0), 2.0 / 81.0, atol=0.004)


def test_measure_print_label_period_on_a_slick_edge(tmp_path):
    # mixed set 4259, file 6: a label written on a slick print's edge, its period
    # kept as the print's own (a dot) on the edge at the print's widest point: width
    # +1.7 %, unflagged while the outline's stretch near the label was lost; then
    # flagged (mark_pull). Measured without the ink under the label, the hull spans
    # the notch at the widest point: width +0.17 %, and the tangents on either side
    # bound the hidden edge within the bar (not flagged)
    results, _ = outcomes(tmp_path, "label", mixed_file(4259, 6), dpi=None)
    assert not [r for r in results if r["outcome"] in SILENT], results
    assert [r["outcome"] for r in results] == ["pass"], results
    assert abs(results[0]["err_width"]) < 0.005


def test_tangent_bound_line_crossing_a_round_edge_adds_under_a_pixel():
    # a disk of radius 60 px crossed by a 5 px line at 50 degrees to its edge: the
    # line's ink near the edge bounds the hidden edge only within the tangents of
    # the visible outline either side (the disk's own edge, to half a pixel); a
    # line running along the edge for 60 px keeps its whole band
    from inkprint.analyze import _tangent_bound
    from inkprint.group import outline_points

    yy, xx = np.mgrid[:200, :200]
    r = np.hypot(yy - 100.0, xx - 100.0)
    line = np.zeros((200, 200), np.uint8)
    cv2.line(line, (100, 30), (196, 110), 1, 5)  # crosses the edge near (160, 80)
    line = line.astype(bool)
    own = (r <= 60.0) & ~line
    band = line & (r > 60.0) & (r <= 68.0)
    kept = _tangent_bound(outline_points(own), band, 8)
    assert band.sum() > 60 and kept.any()
    # the disk's edge under the line, to 2 px (the chords from vertices 8 px back run
    # out of a 60 px circle by ~0.7 px over the gap, plus the slack): the band reached 8
    assert r[band].max() > 67.0 and r[kept].max() <= 62.0
    # a horizontal line over the disk's top (rows 38-45) hides 45 px of its edge:
    # the vertices beside it need not bound what lies under it, the band stays
    graze = (yy >= 38) & (yy <= 45) & (r <= 61.0)
    own2 = (r <= 60.0) & ~graze
    kept2 = _tangent_bound(outline_points(own2), graze, 8)
    assert graze.sum() > 200 and kept2.sum() >= graze.sum() - 2  # (a corner pixel)


@pytest.mark.parametrize(("width_mm", "dpi"), [(1.6, 150.0), (2.0, 150.0), (1.6, 300.0)])
def test_measure_print_line_as_wide_as_a_stroke_along_a_print_is_flagged(width_mm, dpi):
    # mixed set 4269, file 12: a ruler line with ticks 1 mm wide (wider than a stroke: it
    # stays thick ink) lying along a print joined it, length +186 %, unflagged. The
    # print's ink reaching far beyond its body flags it; the plain print does not
    from inkprint.synth import PrintSpec, SheetSpec
    from inkprint.synth_effects import Line

    p = PrintSpec(60.0, 18.0, (100.0, 120.0), 10.0, "slick")
    line = Line((40.0, 113.0), (170.0, 136.0), width_mm, 0.9)
    for marks, flagged in (((line,), True), ((), False)):
        img, _ = render_sheet(SheetSpec((p,), dpi=dpi, marks=marks, specks=0))
        r = ip.analyze_scan(ip.Scan(img, 25.4 / dpi, "given"), sensitivity=False)
        (q,) = r.prints
        said = [w for w in q.warnings if "beyond the print's body" in w]
        assert bool(said) == flagged, (width_mm, q.flags, q.warnings)
        assert ("mark_on_edge" in q.flags) == flagged


def test_measure_print_ruler_along_a_print_is_not_measured(tmp_path):
    # mixed set 4269 file 12: a ruler's line as wide as a pen stroke along a print,
    # taken for tread (length +186 %, unflagged), was flagged by the bar it leaves
    # beyond the print's body; now its bar and ticks, thick ink outside the body that
    # fills little of what it adds to the hull, are set aside as strokes
    # (marks._bold_strokes) and the print is measured without them: length +0.03 %,
    # width +0.08 % (flagged clipped: it reaches the image's edge)
    results, _ = outcomes(tmp_path, "ruler", mixed_file(4269, 12), dpi=None)
    assert not [r for r in results if r["outcome"] in SILENT], results
    assert abs(results[0]["err_length"]) < 0.005 and abs(results[0]["err_width"]) < 0.005


def test_bump_pull_tick_on_an_outer_rib():
    # a ribbed print is three pieces: the outer ribs make its hull, the middle one
    # has the longest outline; a tick's end out of the upper rib's edge went unseen
    # when only the longest outline was judged (ruler 5007/84: width +4.5 %)
    from inkprint.analyze import _bump_pull

    yy, xx = np.mgrid[:160, :600]
    lens = ((xx - 300) / 280.0) ** 2 + ((yy - 80) / 60.0) ** 2 <= 1.0
    own = lens & (np.abs(yy - 80) % 40 >= 4)  # three ribs apart: grooves 8 px wide
    own &= ~((np.abs(yy - 80) >= 4) & (np.abs(yy - 80) < 16))  # the middle rib apart
    assert len(np.unique(cv2_labels(own))) - 1 >= 3
    aside = np.zeros_like(own)
    top = np.flatnonzero(own[:, 300])[0]
    aside[: top - 2, 330:333] = True  # a line leaving the upper rib's edge
    assert _bump_pull(own, aside, 0.0, 40.0, 1.0) == 0.0
    ticked = own.copy()
    ticked[top - 3 : top + 1, 300:325] = True  # the tick's end 3 px out of the edge
    width = np.ptp(np.flatnonzero(own.any(axis=1))) + 1
    pull = _bump_pull(ticked, aside, 0.0, 40.0, 1.0)  # the points beyond 1 px out
    assert 2.0 / width - 0.002 <= pull <= 3.0 / width + 0.002  # of the tick's 3 px


def cv2_labels(mask):
    import cv2

    return cv2.connectedComponents(mask.astype(np.uint8), connectivity=8)[1]


def test_letters_inside_share_of_a_letter_box_in_the_outline():
    # held-out 6 sheet 34: '434 N' written 1 mm above a knobby print, '43' set aside
    # as text and '4 N' taken for tread blocks (width +23 %, unflagged): the print's
    # outline reached over the letters set aside. A 100 x 60 px rectangle outline;
    # a letter box half inside it, one outside, dust inside (no letter)
    from inkprint.analyze import _letters_inside
    from inkprint.marks import Mark

    hull = np.array([[100, 100], [100, 200], [160, 200], [160, 100]], float)  # (row, col)
    half = Mark("text", (90, 120, 110, 130), 1.0)  # rows 90-110: 10 of 20 inside
    out = Mark("text", (60, 120, 80, 130), 1.0)
    dust = Mark("dust", (120, 150, 130, 160), 0.1)
    assert _letters_inside([out, dust], hull) == 0.0
    assert_allclose(_letters_inside([out, half, dust], hull), 0.5, atol=0.06)
    word = Mark("writing", (130, 90, 140, 110), 1.0)  # cols 90-110: 10 of 20 inside
    assert_allclose(_letters_inside([word], hull), 0.5, atol=0.06)


def _knob_field_with_letters(letters_on_top: bool):
    """A 200 x 100 px field of 10 x 10 px knobs 20 px apart (rows 50-150, cols
    50-250 of a 220 x 300 box) and letter-sized pieces 10 x 10 px: a word of three
    letters (12 px apart) above its top row, its first letter set aside (a mark),
    when ``letters_on_top``; else the mark is a ruler's number over the middle.
    The ink kept, the group, a measurement stand-in and the marks."""
    from types import SimpleNamespace

    from inkprint.group import Group
    from inkprint.marks import Mark

    kept = np.zeros((220, 300), bool)
    for r in range(50, 150, 20):
        for c in range(50, 250, 20):
            kept[r : r + 10, c : c + 10] = True
    if letters_on_top:
        first = (33, 100, 45, 110)  # set aside: (row0, col0, row1, col1)
        for c in (112, 124):  # the word's next letters, taken for tread
            kept[34:44, c : c + 10] = True
    else:
        first = (92, 140, 104, 150)  # between the knobs in the middle
    g = Group(slice(0, 220), slice(0, 300), kept)
    rows, cols = np.nonzero(kept)
    pts = np.column_stack([rows, cols]).astype(np.float32)
    hull = cv2.convexHull(pts)  # (the print's ink: the letter set aside is no part)
    m = SimpleNamespace(
        hull_px=hull.reshape(-1, 2).astype(float), metrics=SimpleNamespace(orientation=0.0)
    )
    return kept, g, m, [Mark("text", first, 1.0)]


def test_letters_pull_a_label_s_letters_taken_for_tread():
    # held-out 6 sheet 34: '434 N' above a knobby print, '43' set aside and '4 N'
    # measured with it (width +23 %, unflagged). Here a word above a knob field:
    # without its two letters taken for knobs the field is 101 px high, not 117 (the
    # pull is a bound: the knobs beside the letter go with them, up to 21 px more)
    from inkprint.analyze import _letters_pull

    kept, g, m, marks = _knob_field_with_letters(True)
    assert 117 / 101 - 1 - 0.01 <= _letters_pull(marks, g, kept, m) <= 117 / 80 - 1


def test_letters_pull_a_ruler_s_number_over_the_middle_pulls_nothing():
    # a ruler's numbers set aside over a print's middle (23 prints within the bar
    # flagged on the held-out development sets with the letter's box inside the
    # outline as the only test): wholly inside, or its pieces beside it removed, the
    # outline stays where it is
    import dataclasses

    from inkprint.analyze import _letters_pull

    kept, g, m, marks = _knob_field_with_letters(False)
    assert _letters_pull(marks, g, kept, m) == 0.0
    # (a letter straddling the top row: the knobs beside it go, the row stays)
    edge = [dataclasses.replace(marks[0], bbox=(44, 100, 56, 110))]
    assert _letters_pull(edge, g, kept, m) == 0.0


def test_letters_pull_a_tick_is_no_seed():
    # a thin piece touching a print set aside as a pen mark or tick: a ruler's ticks
    # where it crosses a knobby print at its widest (own generator seed 6011 file
    # 52, width -4.9 % without the blocks beside them), a tread block the outline
    # cut to a sliver (a bundled scan, tire08 6.9 bar 304 N: -37 %), both flagged
    # though measured as before. The word above the knob field, its first letter
    # set aside as a tick, is no seed
    import dataclasses

    from inkprint.analyze import _letters_pull
    from inkprint.marks import TICK_REASON

    kept, g, m, marks = _knob_field_with_letters(True)
    tick = [dataclasses.replace(marks[0], reason=f"{TICK_REASON} 1.2 mm out of a print")]
    assert _letters_pull(tick, g, kept, m) == 0.0


def test_thin_excess_row_of_cut_elements_flags_a_label_bit_does_not():
    # held-out seed 10 sheet 9: a knurl print not found as a fine tread lost its
    # outer rows of diamonds, cut to triangles by the outline, as pen-thin ink
    # (width -8.5 %, unflagged). At 300 dpi: a 60 x 20 mm print, six 1 mm^2 pieces
    # 1 mm off its top side: 2 mm wider with them
    mm = 25.4 / 300
    kept = np.zeros((320, 800), bool)
    kept[50:286, 45:754] = True  # 236 x 709 px: 20 x 60 mm
    m = SimpleNamespace(metrics=SimpleNamespace(orientation=0.0))
    row = np.zeros_like(kept)
    for c in range(100, 700, 100):
        row[26:38, c : c + 12] = True  # 12 x 12 px: 1.03 mm^2, 12 px (1 mm) off
    excess = _thin_excess(kept, m, row, mm)
    assert_allclose(excess, (286 - 26) / 236 - 1, rtol=1e-6)
    assert excess > ip.AnalysisOptions().edge_uncertainty
    # a label's letter beside the tip, cut to bits of a few pixels: no row
    bits = np.zeros_like(kept)
    for r in range(120, 220, 20):
        bits[r : r + 3, 760:763] = True
    assert _thin_excess(kept, m, bits, mm) == 0.0
    assert _thin_excess(kept, m, None, mm) == 0.0


def test_thin_excess_pair_off_both_tips_flags_one_piece_does_not():
    # held-out seed 12 sheet 112: a knurl print on chart paper, the diamond the
    # outline cut to a triangle at each tip left out as pen-thin ink (length -6.2 %,
    # unflagged): two pieces, too few for a row, alike and off either tip. At 300
    # dpi: a 60 x 20 mm print, 1 mm^2 triangles 1 mm beyond each tip
    mm = 25.4 / 300
    kept = np.zeros((320, 800), bool)
    kept[50:286, 45:754] = True  # 236 x 709 px: 20 x 60 mm
    m = SimpleNamespace(metrics=SimpleNamespace(orientation=0.0))
    fore, aft = np.zeros_like(kept), np.zeros_like(kept)
    fore[162:174, 766:778] = True  # 12 x 12 px beyond the right tip
    aft[162:174, 21:33] = True  # and its mirror beyond the left one
    excess = _thin_excess(kept, m, fore | aft, mm)
    assert_allclose(excess, (778 - 21) / 709 - 1, rtol=1e-6)
    assert excess > ip.AnalysisOptions().edge_uncertainty
    assert _thin_excess(kept, m, fore, mm) == 0.0  # one piece: a label's letter
    same = fore.copy()
    same[190:202, 766:778] = True  # two off the same tip: no pair
    assert _thin_excess(kept, m, same, mm) == 0.0
    big = fore.copy()
    big[150:186, 9:33] = True  # six times as large: no pair
    assert _thin_excess(kept, m, big, mm) == 0.0


def _rib_print(*, dpi=400.0, ss=4, length=19.0, width=10.0, rib=1.0, phase=0):
    """A tiny print drawn with exact truth: a slick centre rib ``rib`` mm wide along
    its whole length, 1.2 mm diamonds at a 2 mm pitch beside it (none within 1.2 mm
    of the rib), all cut by an ellipse ``length`` x ``width`` mm along x."""
    import cv2

    mm = 25.4 / dpi / ss
    n = int(40 / mm)
    cx = cy = n // 2
    outline = np.zeros((n, n), np.uint8)
    cv2.ellipse(outline, (cx, cy), (int(length / 2 / mm), int(width / 2 / mm)), 0, 0, 360, 1, -1)
    ink = np.zeros((n, n), np.uint8)
    half = int(length / 2 / mm)
    cv2.line(ink, (cx - half, cy), (cx + half, cy), 1, int(rib / mm))
    d = 0.6 / mm
    for k, u in enumerate(np.arange(-length / 2, length / 2 + 2, 2.0)):
        for v in np.arange(-width / 2, width / 2 + 2, 2.0) + ((k + phase) % 2):
            if abs(v) >= rib / 2 + 1.2:
                x, y = cx + u / mm, cy - v / mm
                pts = np.array([[x - d, y], [x, y - d], [x + d, y], [x, y + d]], np.int32)
                cv2.fillPoly(ink, [pts], 1)
    return drawn_scan(ink & outline, dpi, ss, 0.6)


@pytest.mark.parametrize("phase", [0, 1])
def test_inner_line_excess_flags_a_slick_centre_rib_taken_for_a_ruler(phase):
    # a tiny print's slick centre rib, straight and 19 mm long, is set aside as a
    # ruler: its diamonds alone read 11-21 % short (held-out seed 2026 sheet 81:
    # -2.3 %, unflagged). Flagged mark_on_edge with the excess the rib adds. (Phase
    # 0: the diamonds make a lattice print, whose box held the rib's mark: the mark
    # was dropped as one of its elements, the rib in neither the print nor the marks)
    grey, mm_per_px, (length, _, _) = _rib_print(phase=phase)
    r = ip.analyze_scan(ip.Scan(grey, mm_per_px, "given"), rolling_axis="x", sensitivity=False)
    (p,) = r.prints
    assert [mk.kind for mk in r.marks] == ["line"]
    assert p.metrics.length < 0.95 * length  # the rib's ends are lost
    assert p.flags == ("mark_on_edge",)
    (pct,) = re.findall(
        r"a rib of its tread\? With it its length or width is ([\d.]+) %", p.warnings[-1]
    )
    assert_allclose(float(pct), 100 * (length / p.metrics.length - 1), atol=1.0)


def _tip_crescents(*, dpi=300.0, ss=4, length=60.0, width=24.0, gap=2.0, arc=(3, 15)):
    """A slick print with two thin crescents (0.3 mm) ``gap`` mm beyond its right tip,
    along its outline (a herringbone's last arms the outline cut), drawn with exact
    truth of all the ink."""
    import cv2

    mm = 25.4 / dpi / ss
    n = int((length + 20) / mm)
    c = n // 2
    ink = np.zeros((n, n), np.uint8)
    cv2.ellipse(ink, (c, c), (int(length / 2 / mm), int(width / 2 / mm)), 0, 0, 360, 1, -1)
    axes = (int((length / 2 + gap) / mm), int((width / 2 + gap) / mm))
    for a0, a1 in ((arc[0], arc[1]), (-arc[1], -arc[0])):
        cv2.ellipse(ink, (c, c), axes, 0, a0, a1, 1, int(0.3 / mm))
    return drawn_scan(ink, dpi, ss, 0.6)


def test_sliver_excess_flags_tip_crescents_set_aside_as_pen_ticks():
    # two crescents off a tip are set aside as pen ticks (each reaches 2.2 mm out of
    # the print; two, so not a lone sliver): the print read -3.5 % long, unflagged
    # (a herringbone's cut arms: held-out seeds 8, 10, 11, -1.1 to -2.1 %). Flagged
    # with the length they add
    grey, mm_per_px, (length, _, _) = _tip_crescents()
    r = ip.analyze_scan(ip.Scan(grey, mm_per_px, "given"), rolling_axis="x", sensitivity=False)
    (p,) = r.prints
    assert [mk.reason.startswith("a pen mark or tick") for mk in r.marks] == [True, True]
    assert p.metrics.length < 0.97 * length
    assert p.flags == ("mark_on_edge",)
    (pct,) = re.findall(r"thin ink off its tip.* is ([\d.]+) % larger", p.warnings[-1])
    assert_allclose(float(pct), 100 * (length / p.metrics.length - 1), atol=0.5)


def _round_print_under_a_label(dpi: float, ss: int, dy: float) -> tuple:
    """A slick round print 21.5 mm across (grey 0.75 darker than paper) and a
    pen label 'F=620N' (Hershey strokes 0.3 mm, 0.45 darker) written across its
    bottom edge, its baseline ``dy`` mm below the print's lowest point; grey image,
    mm per px and the print's truth (length along x, width along y, hull area)."""
    mm = 25.4 / dpi / ss
    h = w = int(40 / mm)
    cx, cy, r = w // 2, int(15 / mm), int(10.75 / mm)
    disk = np.zeros((h, w), np.uint8)
    cv2.circle(disk, (cx, cy), r, 1, -1)
    pen = np.zeros_like(disk)
    scale = 5.0 / mm / 22.0  # Hershey simplex caps are about 22 units tall: 5 mm
    org = (cx - int(9.0 / mm), cy + r + int(dy / mm))
    cv2.putText(pen, "F=620N", org, cv2.FONT_HERSHEY_SIMPLEX, scale, 1, max(1, int(0.3 / mm)))
    pts = cv2.findNonZero(disk).reshape(-1, 2)
    truth = (
        (np.ptp(pts[:, 0]) + 1) * mm,
        (np.ptp(pts[:, 1]) + 1) * mm,
        cv2.contourArea(cv2.convexHull(pts)) * mm * mm,
    )
    size = (w // ss, h // ss)
    cover = cv2.resize(disk.astype(np.float32), size, interpolation=cv2.INTER_AREA)
    ink = cv2.resize(pen.astype(np.float32), size, interpolation=cv2.INTER_AREA)
    grey = 0.92 - np.maximum(0.75 * cover, 0.45 * ink)
    grey += np.random.default_rng(0).normal(0, 0.01, grey.shape)
    return grey.astype(np.float32), 25.4 / dpi, truth


@pytest.mark.parametrize(("dpi", "dy"), [(300.0, 4.6), (200.0, 5.0), (400.0, 4.3)])
def test_measure_print_label_across_a_round_print_s_edge_is_within_or_flagged(dpi, dy):
    # held-out seed 5 sheet 81: a label's letters across the bottom of a round
    # print took its edge with them; measured without it the hull's bottom was flat
    # over two edges, and each edge's tangent on the far side was the other edge:
    # the bound under the letters read 0.06 % and the width -1.6 % had status ok
    # (here: width -2.6 % at 300 dpi and -2.2 % at 200 dpi, status ok before)
    grey, mm, (length, width, area) = _round_print_under_a_label(dpi, 4, dy)
    res = ip.analyze_scan(ip.Scan(grey, mm, "given"), rolling_axis="x", sensitivity=False)
    (pr,) = res.prints
    m = pr.metrics
    within = (
        abs(m.length / length - 1) <= 0.01
        and abs(m.width / width - 1) <= 0.01
        and abs(m.hull_area / area - 1) <= 0.02
    )
    assert within or "mark_on_edge" in pr.flags, (m.length / length, m.width / width)
