"""Pages of writing only: a label's rows of bold marker letters, joined into one
group, are writing, not a print (:func:`inkprint.group._rows_of_letters`); a
tread's bars in rows stay a print."""

import cv2
import numpy as np
import pytest
from numpy.testing import assert_allclose

import inkprint as ip
from inkprint.group import Group, is_print

ROWS = ("Compass Stampede Pass 32", "p = 5.3 bar")


def _label_page(dpi: float, height, stroke: float, gap: float, rows=ROWS) -> ip.Scan:
    """Two rows of bold letters (``height`` mm capitals, or one height per row,
    ``stroke`` mm strokes, ``gap`` mm of paper between the rows), grey on a grey page
    with noise."""
    mm = 25.4 / dpi
    ink = np.zeros((int(120 / mm), int(160 / mm)), np.uint8)
    heights = np.broadcast_to(height, len(rows))
    y = int(30 / mm)
    for row, h in zip(rows, heights, strict=True):
        cv2.putText(
            ink,
            row,
            (int(15 / mm), y),
            cv2.FONT_HERSHEY_DUPLEX,
            h / mm / 22.0,  # a DUPLEX capital is 22 px at scale 1
            255,
            max(1, round(stroke / mm)),
            cv2.LINE_AA,
        )
        y += int((h + gap) / mm)
    rng = np.random.default_rng(0)
    grey = 0.92 - 0.55 * ink.astype(np.float32) / 255 + rng.normal(0, 0.01, ink.shape)
    return ip.Scan(grey.astype(np.float32), mm, "given")


@pytest.mark.parametrize(
    "dpi, height, stroke, gap",
    [
        (150.0, 4.5, 1.4, 1.5),
        (150.0, 5.5, 1.6, 2.0),
        (300.0, 4.0, 1.2, 1.2),
        (600.0, 4.5, 1.4, 1.5),
    ],
)
def test_analyze_scan_rows_of_bold_letters_are_no_print(dpi, height, stroke, gap):
    # held-out 6 sheet 79: 'Compass Stampede Pass 32' over 'p = 5.3 bar' on a page of
    # writing only came out as an 86 x 15 mm print, unflagged (and so here before,
    # on all of these)
    with pytest.raises(ip.NoInk, match="lines of writing"):
        ip.analyze_scan(_label_page(dpi, height, stroke, gap), sensitivity=False)


@pytest.mark.parametrize("stroke", [0.8, 1.0])
def test_analyze_scan_rows_with_short_lower_case_letters_are_no_print(stroke):
    # 'F = 446 N' over 'p = 3.4 bar' (held-out set 14 sheet 93: 30 x 12 mm, status
    # ok): the lower row's 'a' and 'r' are shorter than TEXT_LETTER_MM; here 2.8 mm
    # capitals at 300 dpi, a 24 x 9 mm "print" before
    scan = _label_page(300.0, (4.0, 2.8), stroke, 1.5, rows=("F = 446 N", "p = 3.4 bar"))
    with pytest.raises(ip.NoInk, match="lines of writing"):
        ip.analyze_scan(scan, sensitivity=False)


def _bar_rows(mm: float, bar: float, groove: float) -> np.ndarray:
    """A 60 x 24 mm elliptical print of slanted bars ``bar`` mm wide, 3 mm apart,
    in two rows either side of a ``groove`` mm centre groove (a herringbone tread
    without its centre rib)."""
    h, w = round(30 / mm), round(70 / mm)
    out = np.zeros((h, w), np.uint8)
    cy, cx = h / 2, w / 2
    for x in np.arange(6.0, 64.0, 3.0):
        for side in (-1, 1):
            y0, y1 = side * groove / 2, side * 13.0
            p0 = (round(x / mm), round(cy + y0 / mm))
            p1 = (round((x + 0.5 * side * (y1 - y0)) / mm), round(cy + y1 / mm))
            cv2.line(out, p0, p1, 1, max(1, round(bar / mm)))
    ellipse = np.zeros_like(out)
    cv2.ellipse(
        ellipse, (round(cx), round(cy)), (round(30 / mm), round(12 / mm)), 0, 0, 360, 1, -1
    )
    return (out & ellipse).astype(bool)


@pytest.mark.parametrize("dpi", [150.0, 300.0])
def test_is_print_bars_in_two_rows_are_a_print(dpi):
    mm = 25.4 / dpi
    m = _bar_rows(mm, 1.2, 2.0)
    g = Group(slice(0, m.shape[0]), slice(0, m.shape[1]), m)
    check = is_print(g, mm_per_px=mm)
    assert check.ok, check.reason
    _rows, cols = np.nonzero(m)
    assert_allclose(np.ptp(cols) * mm, 60.0, rtol=0.05)  # the fixture is what it says


def _two_labels(first: str, *, dpi: float, height: float, stroke: float, prints=()):
    """A page with ``first`` written over 'p = 2.4 bar' in bold marker letters
    (``inkprint.synth``'s Hershey labels), and ``prints``."""
    from inkprint.synth import SheetSpec, render_sheet
    from inkprint.synth_effects import Text

    marks = (
        Text(first, (30.0, 60.0), height=height, stroke=stroke, darkness=0.8),
        Text(
            "p = 2.4 bar", (30.0, 60.0 + 2.2 * height), height=height, stroke=stroke, darkness=0.8
        ),
    )
    img, truth = render_sheet(
        SheetSpec(tuple(prints), dpi=dpi, size=(150.0, 100.0), marks=marks, seed=3)
    )
    return ip.Scan(img, 25.4 / dpi, "given"), truth


@pytest.mark.parametrize("stroke", [0.9, 1.2])
@pytest.mark.parametrize("first", ["Compass Bite 40", "F = 446 N"])
def test_analyze_scan_words_of_a_line_are_no_print(first, stroke):
    # held-out set 14 sheets 69 and 93: 'p =' of 'p = 2.4 bar', and 'Bite' then '40'
    # of a label's line, the rest of it set aside as writing, were tiny "prints" with
    # status ok on pages of writing only; here before: '40' (one fused piece, 6.5 x
    # 4.4 mm) and 'F = 446 N' joined to 'ar' of the row above (29 x 14 mm)
    scan, _ = _two_labels(first, dpi=150.0, height=5.0, stroke=stroke)
    with pytest.raises(ip.NoInk, match="a word of a line of writing"):
        ip.analyze_scan(scan, sensitivity=False)


@pytest.mark.parametrize("dpi", [200.0, 300.0])
@pytest.mark.parametrize(
    ("tread", "gap", "height"),
    # (a file print with 'p' joined at 2 mm is lost: docs/inkprint.md, limits)
    [
        ("slick", 4.0, 3.0),
        ("slick", 4.0, 5.0),
        ("file", 4.0, 3.0),
        ("file", 4.0, 5.0),
        ("slick", 2.0, 3.0),
    ],
)
def test_analyze_scan_tiny_print_in_line_with_a_label_is_no_word(dpi, tread, gap, height):
    # a track tire's 12 x 3 mm print with its label written on along its line,
    # ``gap`` mm after it: one solid body longer than letters are, no word
    # (word_in_a_line); the label's first letter joined to it at 2 mm (200 dpi) is
    # flagged, as before, not set aside whole as writing
    from inkprint.synth import PrintSpec, SheetSpec, render_sheet
    from inkprint.synth_effects import Text

    spec = PrintSpec(12.0, 3.0, (40.0, 50.0), 0.0, tread)
    label = Text("p = 2.4 bar", (46.0 + gap, 50.0 + height / 2), height=height, stroke=0.9)
    img, (t,) = render_sheet(
        SheetSpec((spec,), dpi=dpi, size=(150.0, 100.0), marks=(label,), seed=3)
    )
    res = ip.analyze_scan(ip.Scan(img, 25.4 / dpi, "given"), sensitivity=False, rolling_axis="x")
    (p,) = res.prints
    if p.status == "ok":
        assert_allclose([p.metrics.length, p.metrics.width], [t.length, t.width], rtol=0.01)
    assert not any("a word of a line" in m.reason for m in res.marks)


def _pieces(shape, boxes) -> np.ndarray:
    """A mask with the filled boxes (row0, col0, row1, col1) [px]."""
    mask = np.zeros(shape, bool)
    for r0, c0, r1, c1 in boxes:
        mask[r0:r1, c0:c1] = True
    return mask


def test_word_in_a_line_letters_beside_a_line_of_writing():
    # 'p =' (a letter 30 px high, a bar) 10 px before a line of writing 30 px high
    from inkprint.group import word_in_a_line

    mask = _pieces((30, 60), [(0, 0, 30, 22), (12, 32, 20, 60)])
    g = Group(slice(100, 130), slice(200, 260), mask)
    line = np.array([[98, 270, 130, 450]])  # row0, col0, row1, col1
    assert word_in_a_line(g, line, mm_per_px=0.1)
    # the same line far along (60 px) or in another row: no word
    assert not word_in_a_line(g, np.add(line, [0, 60, 0, 60]), mm_per_px=0.1)
    assert not word_in_a_line(g, np.add(line, [40, 0, 40, 0]), mm_per_px=0.1)


def test_word_in_a_line_tiny_print_under_a_label_is_no_word():
    # held-out set 8 sheet 54: a 13 x 2.4 mm file print (diamonds) running down
    # from 3 mm under a label, its letters each about as high as wide above it
    from inkprint.group import word_in_a_line

    diamonds = [(r, 4, r + 18, 44) for r in range(0, 150, 25)]  # six, 1/6 of the ink each
    g = Group(slice(978, 1128), slice(1907, 1955), _pieces((150, 48), diamonds))
    letters = np.array([[903, 1890, 939, 1930], [905, 1932, 939, 1975], [912, 1972, 942, 2004]])
    assert not word_in_a_line(g, letters, mm_per_px=0.0847)
    # a line of writing running down into it would make it one (the rule's reach)
    down = np.array([[800, 1900, 960, 1960]])
    assert word_in_a_line(g, down, mm_per_px=0.0847)


def _glyph(mask: np.ndarray, k: int, x: int, y: int, w: int, h: int, t: int) -> None:
    """The ``k``-th of five letter shapes (an 'O', 'L', 'T', 'X', 'U'), ``w`` x ``h``
    [px] from (``x``, ``y``), strokes ``t`` [px] wide: neighbouring letters differ (a
    row of one shape repeated is a tread's elements, group.TEXT_SHAPE_ALIKE)."""
    x1, y1 = x + w, y + h
    strokes = [
        [((x, y), (x1, y)), ((x1, y), (x1, y1)), ((x1, y1), (x, y1)), ((x, y1), (x, y))],
        [((x, y), (x, y1)), ((x, y1), (x1, y1))],
        [((x, y), (x1, y)), ((x + w // 2, y), (x + w // 2, y1))],
        [((x, y), (x1, y1)), ((x1, y), (x, y1))],
        [((x, y), (x, y1)), ((x, y1), (x1, y1)), ((x1, y1), (x1, y))],
    ][k % 5]
    for a, b in strokes:
        cv2.line(mask, a, b, 1, thickness=t)


def _underlined_word(mm: float, bar_mm: float) -> Group:
    """Ten letters 6 mm high and 4 mm wide (1 mm strokes, :func:`_glyph`) 6 mm apart,
    a bar ``bar_mm`` high and 55 mm long 0.6 mm under them (an underline's
    stretch)."""
    px = lambda v: round(v / mm)
    mask = np.zeros((px(12.0), px(66.0)), np.uint8)
    for k in range(10):
        x, y = px(2.0 + 6.0 * k), px(2.0)
        _glyph(mask, k, x, y, px(4.0), px(6.0), px(1.0))
    y = px(2.0 + 6.0 + 0.6 + 0.5)
    cv2.rectangle(mask, (px(2.0), y), (px(57.0), y + px(bar_mm)), 1, thickness=-1)
    return Group(slice(0, mask.shape[0]), slice(0, mask.shape[1]), mask.astype(bool))


@pytest.mark.parametrize("dpi", [300.0, 500.0])
def test_is_print_underlined_line_of_letters_is_writing(dpi):
    # held-out set 13 sheet 0: 'Schwalbe G-One Bite 40' with 33 mm of its underline
    # (35 % of the ink) was a 73 x 5.8 mm "print" with status ok: the bar held the
    # ink of the letters under 70 %
    mm = 25.4 / dpi
    check = is_print(_underlined_word(mm, 2.0), mm_per_px=mm)
    assert not check.ok and check.kind == "writing" and "line of writing" in check.reason


@pytest.mark.parametrize("dpi", [300.0, 500.0])
def test_is_print_line_of_lower_case_letters_is_writing(dpi):
    # held-out set 13 sheet 42: 'Bridgestone S22 190/55 ZR17 2.2 bar 1812 N', a
    # 108 x 4.2 mm "print" with status ok: its lower-case letters (2.3-2.5 mm) were
    # under TEXT_LETTER_MM; here three capitals 3.3 mm high, nine letters 2.4 mm
    # (strokes 0.5 mm wide, :func:`_glyph`)
    mm = 25.4 / dpi
    px = lambda v: round(v / mm)
    mask = np.zeros((px(6.0), px(40.0)), np.uint8)
    for k in range(12):
        high = 2.8 if k in (0, 5, 9) else 1.9
        x, y = px(1.0 + 3.0 * k), px(1.0 + 3.3 - high)
        _glyph(mask, k, x, y, px(2.0), px(high), px(0.5))
    g = Group(slice(0, mask.shape[0]), slice(0, mask.shape[1]), mask.astype(bool))
    check = is_print(g, mm_per_px=mm)
    assert not check.ok and "line of writing" in check.reason


def test_rows_of_letters_knob_rows_among_specks_are_no_writing():
    # fifth held-out generator (2026-11-29) seed 3 sheet 31: a knob print (3 x 5 mm
    # knobs, 7 mm apart, staggered) on 1 mm chart paper, the paper's bits in its
    # group, set aside as "lines of writing": missing. The median piece was a
    # speck's (no wider than a stroke); over the pieces larger than specks it is a
    # knob's, wider than two strokes
    from inkprint.group import _rows_of_letters, outline_points
    from inkprint.options import AnalysisOptions

    mm = 25.4 / 240
    h, w = round(80 / mm), round(52 / mm)
    mask = np.zeros((h, w), bool)
    for i, v in enumerate(np.arange(2.5, 78, 7.0)):
        for u in np.arange(1.5, 50, 14.0) + (7.0 if i % 2 else 0.0):
            if u + 3 <= 52:
                mask[round(v / mm) : round((v + 5) / mm), round(u / mm) : round((u + 3) / mm)] = 1
    knobs = mask.copy()
    rng = np.random.default_rng(0)
    mask[rng.integers(0, h, 400), rng.integers(0, w, 400)] = True  # the chart's bits
    for m in (knobs, mask):
        assert not _rows_of_letters(m, outline_points(m).reshape(-1, 2), mm, AnalysisOptions())


def test_rows_of_letters_siped_blocks_alike_are_no_writing():
    # fifth held-out generator (2026-11-29) seed 3 sheet 97: a 91 x 64 mm print of
    # 4.8 x 5.7 mm blocks, each with three closed 0.5 mm sipes, in columns 7.6 mm
    # apart: strokes 1-1.3 mm wide, no bars, in rows, read as "lines of writing":
    # missing. A tread's elements are alike; a label's letters differ in ink
    from inkprint.group import _rows_of_letters, outline_points
    from inkprint.options import AnalysisOptions

    mm = 25.4 / 300
    mask = np.zeros((round(91 / mm), round(64 / mm)), bool)
    for j, u in enumerate(np.arange(0.0, 60, 7.6)):
        for v in np.arange(0.0, 80, 8.4) + (4.2 if j % 2 else 0.0):
            r0, c0 = round(v / mm), round(u / mm)
            mask[r0 : r0 + round(5.7 / mm), c0 : c0 + round(4.8 / mm)] = True
            for y in (1.5, 2.9, 4.2):
                rr = r0 + round(y / mm)
                mask[rr : rr + round(0.5 / mm), c0 + round(0.35 / mm) : c0 + round(4.45 / mm)] = 0
    opts = AnalysisOptions()
    assert not _rows_of_letters(mask, outline_points(mask).reshape(-1, 2), mm, opts)
    # two lines of a marker's writing at the same scale still are
    text = np.zeros((round(30 / mm), round(90 / mm)), np.uint8)
    for k, line in enumerate(["Compass Stampede", "p = 5.3 bar 32"]):
        cv2.putText(
            text, line, (5, round((10 + 12 * k) / mm)), cv2.FONT_HERSHEY_SIMPLEX, 2.2, 1, 9
        )
    ink = text > 0
    assert _rows_of_letters(ink, outline_points(ink).reshape(-1, 2), mm, opts)


@pytest.mark.parametrize(
    ("dpi", "length", "width", "pitch", "bar"),
    [(300.0, 85.0, 16.4, 5.6, 3.2), (240.0, 105.7, 15.2, 5.0, 2.8), (200.0, 92.5, 17.8, 6.0, 3.0)],
)
def test_analyze_scan_row_of_chevrons_is_a_print(dpi, length, width, pitch, bar):
    # fifth held-out generator (2026-11-29) seeds 2 and 4: elliptic road prints of
    # chevrons, each V apart from the next, the outline cutting them to slightly
    # different sizes: "a line of writing (letters across it)", three prints
    # missing. Each V is its neighbour shifted; letters differ from theirs. (Not
    # covered, docs/inkprint.md Known limits: arms as narrow as a marker's strokes,
    # ~1.8 mm, are set aside as a marker's letters; a V's arm the outline cut to a
    # speck off a tip is an edge spot, length -1.1..-1.8 %)
    from tests.inkprint.drawn import drawn_scan

    ss = 3
    mm = 25.4 / dpi / ss
    h, w = round((width + 20.0) / mm), round((length + 20.0) / mm)
    y, x = np.mgrid[0:h, 0:w]
    u, v = (x + 0.5) * mm - w * mm / 2, (y + 0.5) * mm - h * mm / 2
    inside = (u / (length / 2)) ** 2 + (v / (width / 2)) ** 2 <= 1.0
    vees = np.mod(u + 0.9 * np.abs(v), pitch) < bar
    grey, mm_px, (t_len, t_wid, t_area) = drawn_scan(
        (inside & vees).astype(np.uint8), dpi, ss, 0.6
    )
    r = ip.analyze_scan(ip.Scan(grey, mm_px, "given"), rolling_axis="x", sensitivity=False)
    (pr,) = r.prints
    assert pr.flags == (), pr.warnings
    assert_allclose([pr.metrics.length, pr.metrics.width], [t_len, t_wid], rtol=0.01)
    assert_allclose(pr.metrics.hull_area, t_area, rtol=0.02)


def _siped_two_rows(dpi: float, ss: int = 4) -> tuple:
    """A 78 x 18.2 mm print (a rounded rectangle along y, corners 3 mm) of blocks
    9.5 mm across and 7 mm along in two rows 2.9 mm apart, each block with three
    0.6 mm sipes across it inside a 1 mm frame; the outline cuts the outer row's
    blocks open, to 'E's (held-out seed 3 sheet 9 page 2). :func:`drawn_scan` of it,
    truth (length along y, width along x, hull area)."""
    from tests.inkprint.drawn import drawn_scan

    mm = 25.4 / dpi / ss
    h, w = int(100 / mm), int(50 / mm)
    yy, xx = (np.mgrid[0:h, 0:w] - [[[h / 2]], [[w / 2]]]) * mm
    blocks = np.zeros((h, w), bool)
    for x0 in (-9.1, 3.3):  # the outer row runs 3.7 mm past the outline
        for y0 in np.arange(-39.0, 39.0, 9.9):
            u, v = xx - x0, yy - y0
            block = (u >= 0) & (u <= 9.5) & (v >= 0) & (v <= 7.0)
            slits = (u >= 1.0) & (u <= 8.5) & (np.abs(np.mod(v - 1.45, 1.75) - 0.3) <= 0.3)
            blocks |= block & ~(slits & (v <= 6.0))
    r = 3.0
    qx, qy = np.maximum(np.abs(xx) - (9.1 - r), 0), np.maximum(np.abs(yy) - (39.0 - r), 0)
    ink = (blocks & (qx**2 + qy**2 <= r * r)).astype(np.uint8)
    grey, px, (w_mm, h_mm, area) = drawn_scan(ink, dpi, ss, 0.6)
    return grey, px, (h_mm, w_mm, area)


@pytest.mark.parametrize("dpi", [200.0, 300.0])
def test_analyze_scan_siped_blocks_cut_to_e_s_are_a_print(dpi):
    grey, px, (length, width, area) = _siped_two_rows(dpi)
    res = ip.analyze_scan(ip.Scan(grey, px, "given"), rolling_axis="y", sensitivity=False)
    (p,) = res.prints
    if p.status == "ok":
        m = p.metrics
        assert_allclose([m.length, m.width], [length, width], rtol=0.01)
        assert_allclose(m.hull_area, area, rtol=0.02)


def _photographed_label_and_print() -> tuple:
    """The label 'G-One 40-622' as photographed (held-out 6 seed 1 sheet 92, the page
    rectified: ``data/label_g_one.png``, 0.113 mm per px, a bold sans-serif 8 mm
    tall, its paper shaded) pasted 40 mm above a drawn slick 70 x 25 mm print: the
    grey, mm per px and the print's truth."""
    from pathlib import Path

    from .drawn import drawn_scan

    px, ss = 0.1130320204530061, 2
    mm = px / ss
    ink = np.zeros((int(130 / mm), int(120 / mm)), np.uint8)
    cv2.ellipse(
        ink, (int(60 / mm), int(95 / mm)), (int(35 / mm), int(12.5 / mm)), 0, 0, 360, 1, -1
    )
    grey, _, truth = drawn_scan(ink, 25.4 / px, ss, 0.6)
    label = cv2.imread(str(Path(__file__).parent / "data" / "label_g_one.png"), 0)
    label = label.astype(np.float32) * np.float32(0.92 / np.percentile(label, 95))
    r0, c0 = int(25 / px), int(5 / px)
    h, w = label.shape
    grey[r0 : r0 + h, c0 : c0 + w] = np.minimum(grey[r0 : r0 + h, c0 : c0 + w], label)
    return grey, px, truth


def test_analyze_scan_line_of_bold_letters_alone_is_no_print():
    # held-out 6 seed 1 sheet 92 (rectified): 'G-One 40-622' in bold letters 8 mm
    # tall, 40 mm from the print, was a 61 x 6 mm "print" with status ok (its 11
    # letters alike in ink, 53 % of its hull: no row of letters by the size or fill
    # tests). Its letters lie in one row, and 'O', 'e', '4', '0', '6' have bowls
    grey, px, (length, width, _) = _photographed_label_and_print()
    res = ip.analyze_scan(ip.Scan(grey, px, "given"), rolling_axis="x", sensitivity=False)
    (p,) = res.prints
    assert_allclose([p.metrics.length, p.metrics.width], [length, width], rtol=0.01)
    assert any(m.reason.startswith("a line of writing") for m in res.marks)


def test_text_line_ladder_tread_is_no_line_of_writing():
    # a narrow print of one row of bars across it (alike, no bowls): a print
    from inkprint.group import Group, text_line

    mm = 0.05
    mask = np.zeros((int(8 / mm), int(64 / mm)), bool)
    for k in range(12):
        x0 = int((2 + 5 * k) / mm)
        mask[int(1 / mm) : int(7 / mm), x0 : x0 + int(3 / mm)] = True
    g = Group(slice(0, mask.shape[0]), slice(0, mask.shape[1]), mask)
    assert not text_line(g, mm_per_px=mm)
    # the same row with two bars holed like an 'O' reads as letters
    for k in (3, 7):
        x0 = int((2 + 5 * k) / mm)
        mask[int(3 / mm) : int(5 / mm), x0 + int(1 / mm) : x0 + int(2 / mm)] = False
    assert text_line(g, mm_per_px=mm)
