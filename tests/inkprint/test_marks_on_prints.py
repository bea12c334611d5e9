"""Issue 11 item 3: marks touching a print measured as the print, silently (marks,
analyze): a marker's bold letters swallowed into a slick print, a pen letter's bar
lying along the edge at the widest point, a tip sliver set aside as a pen stroke, a
ruler's ticks beside a print's tips.

``make_case(kind, seed=S * 100_003 + k)`` is file ``k`` of seed ``S`` of
``python -m inkprint.accuracy``; the other sheets are drawn with exact truth.
"""

import math

import numpy as np
import pytest

import inkprint as ip
from inkprint.accuracy import SILENT
from inkprint.marks import BOLD_REASON
from inkprint.synth import PrintSpec, SheetSpec, _outline, render_sheet
from inkprint.synth_effects import Line, Text, text_extent

from .test_classes import outcomes


def mixed_file(seed: int, k: int) -> int:
    return seed * 100_003 + k


def _errors(pr, t) -> tuple[float, float, float]:
    m = pr.metrics
    return (m.length / t.length - 1, m.width / t.width - 1, m.hull_area / t.hull_area - 1)


def _one_print(spec: SheetSpec) -> tuple:
    """The sheet rendered and analysed: its result, its one print and that print's
    relative errors (length, width, hull area) against the truth."""
    img, truths = render_sheet(spec)
    r = ip.analyze_scan(ip.Scan(img, 25.4 / spec.dpi, "given"), sensitivity=False)
    (pr,) = r.prints
    return r, pr, _errors(pr, truths[0])


# -- a pen label's letters on the edge (mixed sets) ----------------------------------


def test_measure_print_letter_bar_along_the_widest_point(tmp_path):
    # 5006 file 24 at 300 dpi: an 'E''s bottom bar 1.5 px out of a slick print's
    # edge at its widest point, joined to it through the anti-aliased row between
    # them: width +1.14 %, unflagged. Measured without the ink under the label the
    # hull spans the notch (its sagitta is a hundredth of a pixel there)
    results, _ = outcomes(tmp_path, "label", mixed_file(5006, 24), dpi=None)
    assert [r["outcome"] for r in results] == ["pass"], results
    assert abs(results[0]["err_width"]) < 0.004


def test_measure_print_letter_feet_on_a_narrow_slick_print(tmp_path):
    # 5008 file 42 at 150 dpi: a label's feet on the top of an 8.8 mm wide slick
    # print: width +1.59 %, unflagged; the tangents on either side of the hidden
    # stretch bound it within edge_uncertainty
    results, _ = outcomes(tmp_path, "label", mixed_file(5008, 42), dpi=None)
    assert [r["outcome"] for r in results] == ["pass"], results
    assert abs(results[0]["err_width"]) < 0.007


# -- tip slivers (mixed sets) ----------------------------------------------------------


def test_sort_ink_keeps_a_lone_tip_sliver_of_a_block_pattern(tmp_path):
    # 5006 file 29 (a photo, manifest dpi 150): a knob at a print's tip cut by the
    # outline to a 1.9 x 0.24 mm sliver 1.5 mm beyond the print, set aside as a pen
    # stroke: length -2.15 %, unflagged. Alone off the tip of a block pattern it is
    # a tip block (the section 7.1.1 rule keeps it)
    results, _ = outcomes(tmp_path, "photo", mixed_file(5006, 29), dpi=None)
    assert not [r for r in results if r["outcome"] in SILENT], results
    assert all(r["outcome"] == "pass" for r in results), results
    assert max(abs(r["err_length"]) for r in results) < 0.003


def test_sort_ink_keeps_a_wedge_tip_block_on_a_pdf_page(tmp_path):
    # 5008 file 82, page 1 (JPEG-coded): a knobby print's tip block cut to a wedge
    # (2.7 mm, 0.24 mm from the print, reaching 1.3 mm out): hull area -2.04 %
    results, _ = outcomes(tmp_path, "pdf", mixed_file(5008, 82), dpi=None)
    assert all(r["outcome"] == "pass" for r in results), results
    assert max(abs(r["err_hull_area"]) for r in results) < 0.01


def test_measure_print_lone_stroke_off_a_slick_tip_is_flagged():
    # beside a print without a block pattern a lone thin piece off its tip cannot be
    # told from a tread sliver: it stays out of the measure (exact), and the print is
    # flagged with the size it would have with it (its 2.5 mm: length +4 %)
    p = PrintSpec(60.0, 14.0, (100.0, 120.0), 0.0, "slick", ink=0.85)
    stroke = Line((131.2, 120.0), (133.7, 120.5), 0.3, 0.85)
    spec = SheetSpec((p,), dpi=300.0, seed=2, specks=0, marks=(stroke,))
    r, pr, errors = _one_print(spec)
    assert max(abs(e) for e in errors) < 0.003
    assert "mark_on_edge" in pr.flags
    assert any("thin ink off its tip" in w for w in pr.warnings), pr.warnings
    assert any(m.kind == "sliver" for m in r.marks)


def _label_over_tip(tread: str, shift: float, above: float) -> SheetSpec:
    """A print 60 x 24 mm rolling along y, its tip at y = 150 mm, and a pen label
    'p=4.5' (4.5 mm letters, 0.6 mm strokes) across the tip: its baseline
    ``above`` [mm] over the tip (negative: into the print), its left end ``shift``
    of its length right of the print's axis."""
    p = PrintSpec(60.0, 24.0, (100.0, 120.0), 90.0, tread, ink=0.85)
    text = Text("p=4.5", (0.0, 0.0), 4.5, 0.6, 0.85)
    w, _ = text_extent(text)
    label = Text(text.text, (100.0 + shift * w, 150.0 + above), 4.5, 0.6, 0.85)
    return SheetSpec((p,), dpi=300.0, seed=3, specks=0, marks=(label,))


def _one_print_y(spec: SheetSpec) -> tuple:
    img, truths = render_sheet(spec)
    scan = ip.Scan(img, 25.4 / spec.dpi, "given")
    r = ip.analyze_scan(scan, rolling_axis="y", sensitivity=False)
    (pr,) = r.prints
    return pr, _errors(pr, truths[0])


@pytest.mark.parametrize(
    ("tread", "shift"), [("slick", -0.3), ("ribbed", -0.1), ("knobby", 0.1), ("knobby", 0.3)]
)
def test_measure_print_label_letter_joined_at_a_tip_is_flagged(tread, shift):
    # held-out seed 9 sheets 15, 21, 33 (seeds 8, 7: 4 more): a label written over a
    # print's tip, one letter ('=', '7', the 'p' of 'p=') joined to the print, its
    # neighbours set aside as letters: length +1.2..+4.9 % with status ok. Here
    # +1.2 % (slick, ribbed) and +3.8 % (knobby): the pen-thin ink near the letters
    # beside the print is measured out and the print flagged. On the knobby print
    # the 'p' is since no lone tip block (``marks.TIP_SLIVER_SOLIDITY``): exact
    pr, errors = _one_print_y(_label_over_tip(tread, shift, -0.3))
    if tread == "knobby":
        assert max(abs(e) for e in errors) < 0.003, errors
        return
    assert errors[0] > 0.01, errors  # the trap is real: the letter is measured
    assert "mark_on_edge" in pr.flags, (errors, pr.warnings)
    assert any("letters set aside lie beside it" in w for w in pr.warnings), pr.warnings


def test_measure_print_label_beside_a_knobby_tip_stays_unflagged():
    # the same label 3 mm over the tip: nothing joined, the print measured exactly
    for shift in (-0.5, -0.1, 0.3):
        pr, errors = _one_print_y(_label_over_tip("knobby", shift, 3.0))
        assert max(abs(e) for e in errors) < 0.002, errors
        assert pr.flags == (), pr.warnings


# -- a marker's bold letters -----------------------------------------------------------


def _bold_label_sheet(dpi: float, theta: float = 140.0) -> SheetSpec:
    """A slick print and a marker label (letters 6 mm, strokes 1.2 mm: thick ink)
    whose bottom-right corner touches the print's outline ``theta`` degrees round
    from its rolling axis, 0.3 mm into it."""
    p = PrintSpec(62.0, 24.0, (100.0, 120.0), 0.0, "slick", ink=0.85)
    uv = _outline(p)
    ang = np.degrees(np.arctan2(uv[:, 1], uv[:, 0]))
    k = int(np.argmin(np.abs((ang - theta + 180) % 360 - 180)))
    x, y = 100.0 + uv[k, 0], 120.0 + uv[k, 1]
    text = Text("GP5000 41", (0.0, 0.0), 6.0, 1.2, 0.85)
    w, _ = text_extent(text)
    label = Text(text.text, (x - w + 0.3, y - 0.3), 6.0, 1.2, 0.85)
    return SheetSpec((p,), dpi=dpi, seed=3, specks=0, marks=(label,))


@pytest.mark.parametrize("dpi", [150.0, 300.0])
def test_sort_ink_bold_label_touching_a_slick_print_is_set_aside(dpi):
    # independent set 1 files 12 and 30, set 2 file 92: bold letters (1.1-1.4 mm
    # strokes survive the stroke-wide opening) touching a slick print were linked to
    # it: width +60 %, +97 %, +23 %, unflagged. Here at 300 dpi: width +13 %
    spec = _bold_label_sheet(dpi)
    r, pr, errors = _one_print(spec)
    assert "mark_on_edge" in pr.flags or (
        abs(errors[0]) <= 0.01 and abs(errors[1]) <= 0.01 and abs(errors[2]) <= 0.02
    ), errors
    assert max(abs(e) for e in errors) < 0.01, errors
    assert sum(m.reason == BOLD_REASON for m in r.marks) >= 5


def test_sort_ink_bold_label_left_on_the_edge_is_flagged():
    # the label's corner lying along the print's shoulder: what is left of its feet
    # on the edge is measured out (the ink under the label), and the edge there,
    # hidden, bounded by the tangents on either side beyond edge_uncertainty
    spec = _bold_label_sheet(150.0, theta=100.0)
    _r, pr, errors = _one_print(spec)
    assert "mark_on_edge" in pr.flags, errors
    assert max(abs(e) for e in errors) < 0.015, errors


def test_sort_ink_bold_label_lying_along_a_slick_print_is_never_silent():
    # the label's baseline along the print's top, its letters joined to the print
    # side by side: each letter's piece, judged against the ink about it, filled the
    # hull it adds with its neighbours' ink and stayed (width +18 %, unflagged); the
    # ink about it is its element's core and the piece itself now
    p = PrintSpec(62.0, 24.0, (100.0, 120.0), 0.0, "slick", ink=0.85)
    text = Text("GP5000 41", (0.0, 0.0), 6.0, 1.2, 0.85)
    w, _ = text_extent(text)
    label = Text(text.text, (100.0 - 0.3 * w, 132.0 - 0.3), 6.0, 1.2, 0.85)
    spec = SheetSpec((p,), dpi=150.0, seed=3, specks=0, marks=(label,))
    _r, pr, errors = _one_print(spec)
    assert "mark_on_edge" in pr.flags, errors
    assert max(abs(e) for e in errors) < 0.03, errors


# -- a ruler along a print through its tips ---------------------------------------------


def test_sort_ink_ruler_along_a_print_keeps_its_ticks_out():
    # independent set 1 file 96: a ruler (0.69 mm line, ticks every mm) along a
    # print's rolling axis through both tips; the ticks beside a tip lay inside the
    # print's hull while the line was in it and, the line out, along its outline,
    # read as slivers of it (length +1.7 %). Ticks touching the band of a line taken
    # out are the line's. On a file tread the ticks joined the print: length +48 %
    a = math.radians(-23.0)
    d = np.array([math.cos(a), math.sin(a)])
    c = np.array([134.0, 130.0])
    p = PrintSpec(71.0, 21.0, tuple(c), -23.0, "file", ink=0.8)
    ruler = Line(tuple(c - 70 * d), tuple(c + 70 * d), 0.69, 0.85, 1.0)
    spec = SheetSpec((p,), dpi=300.0, seed=5, specks=0, marks=(ruler,))
    _r, _pr, errors = _one_print(spec)
    assert abs(errors[0]) < 0.01 and abs(errors[1]) < 0.01 and abs(errors[2]) < 0.02, errors


# -- a label between two prints -----------------------------------------------------------


@pytest.mark.parametrize("dpi", [150.0, 254.0])
def test_sort_ink_label_between_two_slick_prints_joins_neither(dpi):
    # held-out set 1 sheet 114: a pen label between two slick prints 39 mm apart,
    # 6-19 mm from them, linked both to one 112 x 82 mm "print" (the two missing):
    # the prints' gap made a "pattern" the letters continued
    p = PrintSpec(70.0, 22.0, (100.0, 185.0), 0.0, "slick", ink=0.85)
    q = PrintSpec(66.0, 24.0, (100.0, 129.0), 0.0, "slick", ink=0.85)
    label = Text("Vittoria 25c", (72.0, 154.0), 4.5, 1.3, 0.85)  # a marker's
    spec = SheetSpec((p, q), dpi=dpi, seed=5, specks=0, size=(200.0, 260.0), marks=(label,))
    img, truths = render_sheet(spec)
    r = ip.analyze_scan(ip.Scan(img, 25.4 / dpi, "given"), sensitivity=False)
    assert len(r.prints) == 2
    for pr, t in zip(r.prints, truths, strict=True):
        m = pr.metrics
        assert_ok = (
            abs(m.length / t.length - 1) <= 0.01
            and abs(m.width / t.width - 1) <= 0.01
            and abs(m.hull_area / t.hull_area - 1) <= 0.02
        )
        assert assert_ok, (m.length, t.length, m.width, t.width)


# -- a marker label over a fine tread's print ---------------------------------------------


def _fine_field_label_sheet(block: float, gap: float, dpi: float, where: str) -> SheetSpec:
    """A 52 x 46 mm knurl print of ``block`` mm diamonds and a marker label 'F=840N'
    (5 mm high, 1 mm strokes) starting 0.9 mm inside its tip (``where`` 'tip') or
    with its baseline 0.9 mm inside its top edge ('top')."""
    p = PrintSpec(52.0, 46.0, (80.0, 100.0), 0.0, "knurl", block=block, gap=gap)
    text = Text("F=840N", (0.0, 0.0), 5.0, 1.0, 0.85)
    w, _ = text_extent(text)
    pos = (80.0 + 26.0 - 0.9, 98.5) if where == "tip" else (80.0 - 0.3 * w, 100.0 + 23.0 - 0.9)
    label = Text(text.text, pos, 5.0, 1.0, 0.85)
    return SheetSpec((p,), dpi=dpi, size=(180.0, 200.0), seed=3, specks=0, marks=(label,))


@pytest.mark.parametrize(
    "block, gap, dpi, where",
    [(2.4, 1.0, 600.0, "top"), (2.4, 1.0, 300.0, "top"), (1.2, 0.6, 300.0, "tip")],
)
def test_sort_ink_label_over_a_fine_field_print_is_never_silent(block, gap, dpi, where):
    # held-out 12 sheet 64 ('run 11' across a dot-field print's tip: length +40 %)
    # and held-out 8 sheet 119 ('F=840N' over its shoulder: width +9.9 %), both
    # unflagged: a fine field has no core (no element wider than two strokes), so no
    # body to judge the letters against, or the bold digits had a core and were the
    # body. Before: width +6.6 %, +6.7 %, length +36 %, all unflagged
    spec = _fine_field_label_sheet(block, gap, dpi, where)
    r, pr, errors = _one_print(spec)
    within = abs(errors[0]) <= 0.01 and abs(errors[1]) <= 0.01 and abs(errors[2]) <= 0.02
    assert within or "mark_on_edge" in pr.flags, (errors, pr.flags)
    assert max(abs(e) for e in errors) < 0.1, errors
    assert any(m.kind == "text" for m in r.marks)


def test_sort_ink_fine_field_print_without_a_label_is_whole():
    # the fine field as the body judges nothing away from a print that has no mark
    p = PrintSpec(52.0, 46.0, (80.0, 100.0), 0.0, "knurl", block=2.4, gap=1.0)
    spec = SheetSpec((p,), dpi=300.0, size=(180.0, 200.0), seed=3, specks=0)
    r, pr, errors = _one_print(spec)
    assert max(abs(e) for e in errors[:2]) <= 0.01 and abs(errors[2]) <= 0.02, errors
    assert "mark_on_edge" not in pr.flags and not any(m.kind == "text" for m in r.marks)


# -- a marker's letter joined to a print, darker than it ------------------------------


def _dark_label_sheet(tread: str, dx: float, dy: float, dpi: float) -> SheetSpec:
    """A 64 x 30 mm print of ink 0.65 and a marker label 'p=2.5' of ink 0.95 (4.5
    mm high, 1 mm strokes) starting ``dx`` mm right of its tip, ``dy`` mm above its
    axis."""
    p = PrintSpec(64.0, 30.0, (90.0, 100.0), 0.0, tread, ink=0.65)
    label = Text("p=2.5", (122.0 + dx, 100.0 + dy), 4.5, 1.0, 0.95)
    return SheetSpec((p,), dpi=dpi, size=(200.0, 200.0), seed=4, specks=0, marks=(label,))


def _axis_x(spec: SheetSpec):
    img, truths = render_sheet(spec)
    r = ip.analyze_scan(
        ip.Scan(img, 25.4 / spec.dpi, "given"), rolling_axis="x", sensitivity=False
    )
    (pr,) = r.prints
    return pr, _errors(pr, truths[0])


@pytest.mark.parametrize(
    "tread, dx, dy, dpi",
    [
        ("slick", 0.0, -3.0, 300.0),
        ("ribbed", 0.5, -3.0, 200.0),
        ("file", -0.6, -3.0, 300.0),
        ("ribbed", 2.0, -3.0, 200.0),
    ],
)
def test_measure_print_dark_letter_joined_at_a_tip_is_flagged(tread, dx, dy, dpi):
    # held-out 12 sheet 75 ('p' of 'p=2' joined to a herringbone print's tip, '=2'
    # set aside: length +3.1 %) and held-out 2026 sheet 61 ('F' of 'F=640N' grouped
    # with the tip, '=' a fragment: +2.2 %), both unflagged: the joined letter is
    # neither pen-thin nor apart, but a marker's ink, darker than the print's. Here
    # before: length +2.0, +2.8, +1.1, +5.0 %, all unflagged. The ribbed print's 'p'
    # 0.5 mm off its tip is since measured out (no lone tip block: a letter fills
    # less of its hull, ``marks.TIP_SLIVER_SOLIDITY``); the others stay joined
    pr, errors = _axis_x(_dark_label_sheet(tread, dx, dy, dpi))
    within = abs(errors[0]) <= 0.01 and abs(errors[1]) <= 0.01 and abs(errors[2]) <= 0.02
    assert within or "mark_on_edge" in pr.flags, (errors, pr.flags)
    if not within:
        assert any("a pen's ink darker than the print's" in w for w in pr.warnings), pr.warnings


@pytest.mark.parametrize("tread", ["slick", "ribbed", "knobby"])
def test_measure_print_dark_label_apart_from_the_tip_is_not_flagged(tread):
    # the same label 3 mm beyond the tip, or along the side 16 mm above the axis:
    # its ink is apart, the print's own ink near it no darker than the print
    for dx, dy in ((3.0, -3.0), (-20.0, 16.0)):
        pr, errors = _axis_x(_dark_label_sheet(tread, dx, dy, 300.0))
        assert max(abs(e) for e in errors[:2]) <= 0.01 and abs(errors[2]) <= 0.02, errors
        assert "mark_on_edge" not in pr.flags, pr.warnings


def _first_letter_off_tip(tread, text, height, stroke, gap, dpi) -> SheetSpec:
    """A print rolling along x, its tip at x = 150 mm, and a pen label (ink as dark
    as the print's) starting ``gap`` mm beyond the tip on the print's axis."""
    p = PrintSpec(90.0, 28.0, (105.0, 140.0), 0.0, tread, ink=0.85)
    label = Text(text, (150.0 + gap, 140.0 - height / 2), height, stroke, 0.85)
    return SheetSpec((p,), dpi=dpi, size=(215.9, 279.4), seed=7, specks=5, marks=(label,))


@pytest.mark.parametrize(
    "tread, text, height, stroke, gap, dpi",
    [
        ("ribbed", "4.5 bar", 5.8, 0.42, 2.0, 400.0),
        ("ribbed", "B7", 7.1, 0.45, 1.0, 200.0),
        ("mtb", "4", 7.2, 0.79, 1.0, 200.0),
        ("knobby", "F=840N", 5.5, 0.46, 0.8, 150.0),
    ],
)
def test_sort_ink_first_letter_off_a_tip_is_no_tip_block(tread, text, height, stroke, gap, dpi):
    # a sweep of pen labels at prints' tips (400 sheets, exact truth): a label's
    # first letter 1-2.5 mm off the tip of a block-pattern print, its next letters
    # farther than group_distance_mm from the print, was kept as a lone tip block
    # (the outline's sliver): length +5..+10 %, unflagged, 7 of 400; here +4.9..+10 %
    # before. A letter is
    # no convex sliver and has its word about it: set aside, the print exact
    pr, errors = _axis_x(_first_letter_off_tip(tread, text, height, stroke, gap, dpi))
    assert max(abs(e) for e in errors) < 0.005, (errors, pr.flags)


# -- a marker's word beside a siped block print ------------------------------------


def _siped_print_and_word(dpi: float, below: float) -> tuple:
    """Held-out 6 seed 1 sheet 60's siped print along x (a superellipse 61 x 48.8
    mm, exponent 2.646; blocks 8.9 x 5.21 mm, gaps 3.13 and 2.16 mm, columns
    staggered by half a pitch, one 0.79 mm sipe across each block open at one end:
    'n's and 'u's) and its label 'run 18' (FONT_HERSHEY_DUPLEX, bold, 6.6 mm for
    its text height, turned 1.9 degrees) centred 43.06 mm left of the print's centre
    and ``below`` [mm] under it: its box 1.9 mm off the outline beside the tip (at
    ``below`` 12.49 as on the sheet). The grey, mm per px, the print's own drawn
    truth (tests.inkprint.drawn) and the label's box (row0, col0, row1, col1) [px]."""
    import cv2

    from tests.inkprint.drawn import drawn_scan

    ss, length, width, n = 4, 61.0, 48.8, 2.646
    (bx, by), (gx, gy), sipe, phase = (8.9, 5.21), (3.13, 2.16), 0.79, 4.0
    mm = 25.4 / dpi / ss
    left = -length / 2 - 30.0  # the sheet's left edge from the print's centre [mm]
    h, w = round((width + 12.0) / mm), round((length + 36.0) / mm)
    y = (h * mm / 2 - (np.arange(h) + 0.5) * mm)[:, None]  # up
    x = (left + (np.arange(w) + 0.5) * mm)[None, :]
    inside = np.abs(x / (length / 2)) ** n + np.abs(y / (width / 2)) ** n <= 1.0
    px, py = bx + gx, by + gy
    x0, y0 = -length / 2 - px + phase, -width / 2 - py  # a block's centre
    i = np.floor((x - x0) / px + 0.5)  # its column
    u = x - x0 - i * px
    off = np.where(np.mod(i, 2) == 1, py / 2, 0.0)
    j = np.floor((y - y0 - off) / py + 0.5)  # its row in the column
    v = y - y0 - off - j * py
    block = (np.abs(u) <= bx / 2) & (np.abs(v) <= by / 2)
    open_end = np.where(np.mod(j, 2) == 1, v <= 0.25 * by, v >= -0.25 * by)
    ink = (inside & block & ~((np.abs(u) <= sipe / 2) & open_end)).astype(np.uint8)
    _, _, truth = drawn_scan(ink, dpi, ss, 0.8)
    text, font = "run 18", cv2.FONT_HERSHEY_DUPLEX
    (_, th1), _ = cv2.getTextSize(text, font, 1.0, 1)
    thick, scale = round(0.58 / mm), 6.6 / mm / th1
    (tw, th), base = cv2.getTextSize(text, font, scale, thick)
    pad = thick + 4
    can = np.zeros((th + base + 2 * pad, tw + 2 * pad), np.uint8)
    cv2.putText(can, text, (pad, pad + th), font, scale, 1, thick, cv2.LINE_8)
    a = np.radians(1.88)
    turn = np.array([[np.cos(a), np.sin(a)], [-np.sin(a), np.cos(a)]])
    centre = np.array([(-43.06 - left) / mm, h / 2 + below / mm])
    shift = centre - turn @ (np.array(can.shape[::-1]) / 2)
    label = cv2.warpAffine(can, np.column_stack([turn, shift]), (w, h), flags=cv2.INTER_NEAREST)
    grey, mm_px, _ = drawn_scan(ink | label, dpi, ss, 0.8)
    rows, cols = np.flatnonzero(label.any(axis=1)), np.flatnonzero(label.any(axis=0))
    return grey, mm_px, truth, (rows[0] // ss, cols[0] // ss, rows[-1] // ss, cols[-1] // ss)


@pytest.mark.parametrize(("dpi", "below"), [(300.0, 12.49), (300.0, 6.0), (300.0, 0.0)])
def test_sort_ink_marker_word_beside_a_siped_print_is_set_aside(dpi, below):
    # held-out 6 seed 1 sheet 60: 'run 18' beside a siped print's tip, its 'r', 'u'
    # and 'n' taken for the print's blocks the outline cut (each a block with its
    # sipe) and the bold '18' kept with them: length +39.8 %, status ok (then +16.7
    # %, 'run' set aside, '18' kept). Copies of blocks closer together than the
    # lattice's gap are a word's letters (_BoldJudge._word), the next blobs on their
    # line its next letters (_on_the_line). Here before: length +39.7 %, status ok
    # (+15.9 % without _on_the_line); now ok within 0.2 % (OpenCV 5.0's glyphs; at
    # 240 dpi the word was flagged before). Glyphs differ between OpenCV versions:
    # a flagged print passes, a silently wrong one does not
    grey, px, truth, box = _siped_print_and_word(dpi, below)
    r = ip.analyze_scan(ip.Scan(grey, px, "given"), rolling_axis="x", sensitivity=False)
    (pr,) = r.prints
    m = pr.metrics
    errors = [m.length / truth[0] - 1, m.width / truth[1] - 1, m.hull_area / truth[2] - 1]
    if pr.status != "ok":
        assert pr.status == "flagged", pr.warnings
        return
    assert max(abs(e) for e in errors[:2]) <= 0.01 and abs(errors[2]) <= 0.02, errors
    letters = [
        k
        for k in r.marks
        if k.reason == BOLD_REASON
        and box[0] <= (k.bbox[0] + k.bbox[2]) / 2 <= box[2]
        and box[1] <= (k.bbox[1] + k.bbox[3]) / 2 <= box[3]
    ]
    assert len(letters) >= 4, r.marks  # r, u, n, 1, 8 (their pieces)
