"""The ends of prints: a tiny print's thin tips taken for pen strokes' feet, a tiny
file tread print's spine taken for a ruler's line and its teeth for feet, and a bold
letter touching a print's tip taken for the tip (independent set 10, files 72 and 78;
held-out set 1, files 34 and 52).

Sheets are drawn with exact truth (:mod:`inkprint.synth`) or as fixtures below (a
print's ellipse, its hull known in closed form).
"""

import math

import numpy as np
import pytest
from numpy.testing import assert_allclose

import inkprint as ip
from inkprint.group import TEETH_SPAN, Group, _teeth, is_print, thin_protrusions
from inkprint.synth import PrintSpec, SheetSpec, render_sheet
from inkprint.synth_effects import Text


def _errors(m, length, width, area) -> list[float]:
    return [m.length / length - 1, m.width / width - 1, m.hull_area / area - 1]


def _assert_within(err, atol=(0.01, 0.01, 0.02)) -> None:
    """Length, width and hull area errors within the bar (1 %, 1 %, 2 %)."""
    for e, tol in zip(err, atol, strict=True):
        assert_allclose(e, 0.0, atol=tol, err_msg=str(err))


def _supersampled(draw, shape, ss: int = 4) -> np.ndarray:
    """Ink coverage in [0, 1] of what ``draw(canvas, f)`` paints at ``ss`` x the
    resolution (``f``: supersampled pixels per sheet pixel)."""
    import cv2

    big = np.zeros((shape[0] * ss, shape[1] * ss), np.uint8)
    draw(big, ss)
    return cv2.resize(big, (shape[1], shape[0]), interpolation=cv2.INTER_AREA) / 255.0


# -- a tiny print's tapering tips (track tires: 2.5-5 mm wide, 10-25 mm long) -------


@pytest.mark.parametrize(
    ("dpi", "length", "width", "angle", "tread"),
    [
        (150.0, 12.0, 2.8, 35.0, "slick"),  # main: length -1.7 %, unflagged
        (150.0, 19.5, 3.3, 0.0, "slick"),  # main: -1.1 %, flagged
        (150.0, 19.5, 3.3, 0.0, "file"),  # main: -2.8 %, flagged
        (200.0, 19.5, 3.3, 35.0, "slick"),  # main: -1.2 %, flagged
        (200.0, 19.5, 3.3, 0.0, "file"),  # main: missing (its spine a ruler's line)
    ],
)
def test_analyze_scan_tiny_print_keeps_its_tips(dpi, length, width, angle, tread):
    p = PrintSpec(length, width, (50.0, 40.0), angle=angle, tread=tread, exponent=2.0)
    img, (t,) = render_sheet(SheetSpec((p,), dpi=dpi, size=(100.0, 80.0), seed=3, specks=10))
    res = ip.analyze_scan(ip.Scan(img, 25.4 / dpi, "given"), sensitivity=False)
    (pr,) = res.prints
    # (under 25 px across, 150 dpi: flagged coarse, its width good to a quarter px)
    assert set(pr.flags) <= {"coarse"}, pr.warnings
    _assert_within(_errors(pr.metrics, t.length, t.width, t.hull_area))


def test_thin_protrusions_keep_a_tiny_print_s_tips_drop_a_stroke_s_foot():
    # a 19.5 x 3.3 mm ellipse at 200 dpi: its tips are pen-thin for 0.2 strokes out
    # of the hull of its thick ink; a 0.4 mm stroke from its side is a foot
    import cv2

    mm = 25.4 / 200.0
    shape = (60, 200)

    def draw(big, f):
        centre = (round(100 * f * 16), round(30 * f * 16))
        axes = (round(9.75 / mm * f * 16), round(1.65 / mm * f * 16))
        cv2.ellipse(big, centre, axes, 0, 0, 360, 255, -1, cv2.LINE_8, 4)

    ink = _supersampled(draw, shape) >= 0.5
    width = ip.AnalysisOptions().stroke_width_mm / mm
    kept = thin_protrusions(ink, width_px=width)
    cols = np.flatnonzero(ink.any(axis=0))
    assert_allclose(np.flatnonzero(kept.any(axis=0))[[0, -1]], cols[[0, -1]], atol=0)
    stroke = ink.copy()
    stroke[2:20, 99:102] = True  # a pen stroke 3 px wide from the top edge
    kept = thin_protrusions(stroke, width_px=width)
    assert not kept[2:15, 99:102].any()
    assert_allclose(np.flatnonzero(kept.any(axis=0))[[0, -1]], cols[[0, -1]], atol=0)


#: held-out set 1 file 34 at 150 dpi, binarized: a track tire's 12 x 2.8 mm file
#: tread print, a spine with a row of teeth down each side joined to it by a pixel
FILE_SPINE = """
........................##....###....###....###....###....###.......................
................####...####..#####..#####..#####..####...####...####................
...............#####..#####..#####..#####..#####..#####..#####..####...##...........
..........###...####...####...####...###...####...####...####...####...####.........
..........##..#..##..#.###..#.###..#.###.#..###.#..###.#..##..#..##..#..##..........
........#####################################################################.......
.......#######################################################################......
.......#######################################################################......
.......#######################################################################......
.......#######################################################################......
........#####################################################################.......
..........##..#..##..#.###..#.###.##.###.##.###.#..###.#..##..#..##..#..##..#.......
..........###...####...####...####...###....###...####...####...####...####.........
...............#####..#####..#####..#####..#####..#####..#####..####...##...........
................####...####..#####..#####..#####..#####..####...####................
.......................###....###....###....###....###...####.......................
"""


def _ascii(art: str) -> np.ndarray:
    return np.array([[c == "#" for c in row] for row in art.strip().splitlines()])


def test_thin_protrusions_keep_a_file_tread_s_teeth_not_a_label_s_feet():
    mm = 25.4 / 150.0
    ink = _ascii(FILE_SPINE)
    width = ip.AnalysisOptions().stroke_width_mm / mm
    kept = thin_protrusions(np.pad(ink, 4), width_px=width)
    rows = np.flatnonzero(kept.any(axis=1))
    assert_allclose(rows[[0, -1]] - 4, [0, ink.shape[0] - 1], atol=0)  # width -27 % before
    no_teeth = ip.AnalysisOptions(tread_teeth=0)
    before = thin_protrusions(np.pad(ink, 4), width_px=width, options=no_teeth)
    assert np.flatnonzero(before.any(axis=1))[0] - 4 > 0
    # teeth down one side only (a label's letters' feet along an edge): not a tread's
    one = np.pad(ink, 4)
    one[4 + 11 :] = False
    kept = thin_protrusions(one, width_px=width)
    np.testing.assert_array_equal(kept, thin_protrusions(one, width_px=width, options=no_teeth))


@pytest.mark.parametrize("span, kept", [(0.44, True), (0.9 * TEETH_SPAN, False)])
def test_teeth_rows_along_part_of_an_elliptic_print(span, kept):
    # an elliptic outline cuts a file tread's shoulder rows to teeth along 0.43-0.45
    # of the print's length (held-out 6 sheets 19 and 81: asked for half, they were
    # dropped as pen strokes' feet)
    t = np.linspace(0, 2 * np.pi, 64, endpoint=False)
    hull = np.column_stack([500 + 400 * np.cos(t), 300 + 100 * np.sin(t)])  # 800 x 200
    u = np.linspace(-0.5, 0.5, 7) * span * 800
    cent = np.vstack(
        [
            np.column_stack([500 + u, np.full(7, 200.0)]),
            np.column_stack([500 + u, np.full(7, 400.0)]),
        ]
    )
    stub = np.ones(len(cent), bool)
    assert _teeth(hull, cent, stub, 3).all() == kept
    one_side = stub.copy()
    one_side[7:] = False  # a label's letters' feet along one edge
    assert not _teeth(hull, cent, one_side, 3).any()


def test_analyze_scan_tiny_file_tread_print_with_teeth_at_150_dpi():
    # held-out set 1 file 34: its spine was taken for a ruler's line (missing), then
    # its teeth for pen strokes' feet (width -27 %, unflagged)
    mm = 25.4 / 150.0
    ink = _ascii(FILE_SPINE)
    grey = np.full((int(60 / mm), int(60 / mm)), 0.92, np.float32)
    r0, c0 = 150, 120
    grey[r0 : r0 + ink.shape[0], c0 : c0 + ink.shape[1]][ink] = 0.15
    res = ip.analyze_scan(ip.Scan(grey, mm, "given"), rolling_axis="x", sensitivity=False)
    (pr,) = res.prints
    assert set(pr.flags) <= {"coarse"}, pr.warnings  # (16 px across at 150 dpi)
    cols, rows = np.flatnonzero(ink.any(axis=0)), np.flatnonzero(ink.any(axis=1))
    m = pr.metrics
    assert_allclose(m.length, (np.ptp(cols) + 1) * mm, rtol=0.01)
    assert_allclose(m.width, (np.ptp(rows) + 1) * mm, rtol=0.01)


def test_is_print_tiny_file_tread_print_notched_by_its_pattern():
    # held-out set 1 file 52 at 400 dpi: a 14.3 x 2.9 mm print notched down each side
    # by its file pattern fills 71 % of its hull: "a print this small is solid", missing
    import cv2

    mm = 25.4 / 400.0
    mask = np.zeros((int(8 / mm), int(20 / mm)), np.uint8)
    cy, cx = mask.shape[0] // 2, mask.shape[1] // 2
    cv2.ellipse(mask, (cx, cy), (round(7.15 / mm), round(1.45 / mm)), 0, 0, 360, 1, -1)
    for x in np.arange(cx - 5.5 / mm, cx + 5.6 / mm, 1.0 / mm):
        for side in (-1, 1):
            y = cy + side * 1.45 / mm
            tri = np.array([[x - 0.4 / mm, y], [x + 0.4 / mm, y], [x, y - side * 1.1 / mm]])
            cv2.fillConvexPoly(mask, np.round(tri).astype(np.int32), 0)
    g = Group(slice(0, mask.shape[0]), slice(0, mask.shape[1]), mask.view(bool))
    assert is_print(g, mm_per_px=mm).ok
    # a letter as small is no print: an 'O' 5 mm tall with a 0.6 mm stroke
    ring = np.zeros((int(8 / mm), int(8 / mm)), np.uint8)
    cv2.ellipse(ring, (ring.shape[1] // 2, ring.shape[0] // 2), (34, 45), 0, 0, 360, 1, 9)
    g = Group(slice(0, ring.shape[0]), slice(0, ring.shape[1]), ring.view(bool))
    assert not is_print(g, mm_per_px=mm).ok


def test_is_print_tiny_print_scalloped_by_its_tread():
    # held-out set 1 file 90 at 200 dpi: a 10.4 x 2.2 mm file print, its sides
    # scalloped by its tread (bites wider than a stroke: closing leaves them), inks
    # 79 % of its hull: "a print this small is solid", missing. One body: the
    # widest disk in it spans 0.74-0.8 of its width, in writing's strokes 0.2-0.6
    import cv2

    from inkprint.group import _body_share

    mm = 25.4 / 200.0
    mask = np.zeros((int(6 / mm), int(14 / mm)), np.uint8)
    cy, cx = mask.shape[0] // 2, mask.shape[1] // 2
    cv2.ellipse(mask, (cx, cy), (round(5.2 / mm), round(1.1 / mm)), 0, 0, 360, 1, -1)
    for x in np.arange(cx - 4.2 / mm, cx + 4.3 / mm, 1.0 / mm):
        for side in (-1, 1):  # 0.4 mm deep bites 1 mm apart: 76 % of the hull inked
            cv2.circle(mask, (round(x), round(cy + side * 1.2 / mm)), round(0.5 / mm), 0, -1)
    g = Group(slice(0, mask.shape[0]), slice(0, mask.shape[1]), mask.view(bool))
    width = 2.2 / mm
    assert _body_share(g.mask, width) > 0.7
    assert is_print(g, mm_per_px=mm).ok
    # a marker's 'D' as long and as inked is writing: its strokes are 1.2 mm wide
    d = np.zeros((int(14 / mm), int(12 / mm)), np.uint8)
    cv2.ellipse(
        d,
        (round(3 / mm), round(7 / mm)),
        (round(4.4 / mm), round(5.4 / mm)),
        0,
        -90,
        90,
        1,
        round(1.2 / mm),
    )
    cv2.line(
        d, (round(3 / mm), round(1.6 / mm)), (round(3 / mm), round(12.4 / mm)), 1, round(1.2 / mm)
    )
    g = Group(slice(0, d.shape[0]), slice(0, d.shape[1]), d.view(bool))
    assert not is_print(g, mm_per_px=mm).ok


# -- a bold letter touching a print's tip ---------------------------------------------


def _tip_label(angle: float, dpi: float = 200.0, overlap: float = 0.06, stroke: float = 1.3):
    """A slick 87 x 33 mm elliptical print turned ``angle`` degrees, a bold marker 'P'
    (strokes ``stroke`` mm, 6.3 mm tall) touching its lower tip with its top-left
    corner (``overlap`` mm into it) and the rest of the word beside it; grey image,
    mm per px and the ellipse's truth (length, width, hull area)."""
    import cv2

    mm = 25.4 / dpi
    (cx, cy), a, b = (50.0, 80.0), 43.5, 16.5
    t = math.radians(angle)
    x0, y0 = cx + a * math.cos(t) - 0.3, cy + a * math.sin(t) - overlap

    def draw(big, ss):
        f = ss / mm
        axes = (round(a * f * 16), round(b * f * 16))
        cv2.ellipse(
            big, (round(cx * f * 16), round(cy * f * 16)), axes, angle, 0, 360, 255, -1, 8, 4
        )

        def rect(x, y, w, h):
            cv2.rectangle(
                big,
                (round(x * f), round(y * f)),
                (round((x + w) * f), round((y + h) * f)),
                255,
                -1,
            )

        rect(x0, y0, stroke, 6.3)  # the stem, the bowl's top and bottom bars
        rect(x0, y0, 3.1, stroke)
        rect(x0, y0 + 3.4 - stroke, 3.1, stroke)
        centre = (round((x0 + 2.9) * f), round((y0 + 1.7) * f))
        cv2.ellipse(big, centre, (round(1.7 * f),) * 2, 0, -90, 90, 255, round(stroke * f))

    # the rest of the word, drawn as the synthetic sheets draw labels (y up)
    word = Text("irelli", (x0 + 5.4, 200.0 - (y0 + 6.3)), 6.3, stroke, 0.7)
    img, _ = render_sheet(
        SheetSpec((), dpi=dpi, size=(120.0, 200.0), seed=1, specks=0, marks=(word,))
    )
    ink = _supersampled(draw, img.shape)
    grey = np.minimum((0.92 - 0.7 * ink).astype(np.float32), img.astype(np.float32) / 255.0)
    return grey, mm, (2 * a, 2 * b, math.pi * a * b)


@pytest.mark.parametrize("angle", [45.0, 60.0])
def test_analyze_scan_bold_letter_touching_a_tip_is_set_apart(angle):
    # independent set 10 file 78: a marker's 'P' touching a slick print's tip with
    # its corner was the print's (its bowl part of the body): length +5.3 %, ok
    grey, mm, (length, width, area) = _tip_label(angle)
    res = ip.analyze_scan(ip.Scan(grey, mm, "given"), sensitivity=False)
    (pr,) = res.prints
    _assert_within(_errors(pr.metrics, length, width, area))
    assert any(m.kind == "text" for m in res.marks)


def _rib_print(length, width, rib, groove, dpi, *, speck=None, ss=4):
    """A print of ribs along y (``rib`` wide, ``groove`` apart, one centred) in an
    ellipse ``length`` (y) x ``width`` (x) [mm], in an 80 x 80 mm sheet, blurred
    0.64 px; ``speck``: (gap, diameter [mm], outer) of a dust dot that far above the
    tip of the middle rib (or the outermost rib). :func:`drawn_scan` of it, truth
    (length along y, width along x, hull area) of the print without the speck."""
    import cv2

    from tests.inkprint.drawn import drawn_scan

    mm = 25.4 / dpi / ss
    n = int(80 / mm)
    yy, xx = (np.mgrid[0:n, 0:n] - n / 2) * mm
    pitch = rib + groove
    ribs = np.mod(xx + rib / 2, pitch) < rib
    ink = (ribs & ((2 * yy / length) ** 2 + (2 * xx / width) ** 2 <= 1.0)).astype(np.uint8)
    _, _, (w, h, a) = drawn_scan(ink, dpi, ss, 0.6)
    if speck is not None:
        gap, d, outer = speck
        c = round(n / 2 + (np.floor(width / 2 / pitch) * pitch if outer else 0.0) / mm)
        cy = np.flatnonzero(ink[:, c]).min() - (gap + d / 2) / mm
        cv2.circle(ink, (c, round(cy)), max(round(d / 2 / mm), 1), 1, -1)
    grey, px, _ = drawn_scan(ink, dpi, ss, 0.6)
    return cv2.GaussianBlur(grey, (0, 0), 0.64), px, (h, w, a)


@pytest.mark.parametrize(
    "length, width, rib, groove",
    [
        (9.0, 7.7, 1.73, 1.33),
        (9.7, 7.3, 1.55, 1.35),
        pytest.param(
            12.3,
            7.7,
            1.6,
            1.45,
            marks=pytest.mark.xfail(
                strict=True, reason="known limit: a 12 mm rib 1.6 mm wide is a ruler's line"
            ),
        ),
        (8.9, 7.2, 2.8, 1.56),
    ],
)
def test_analyze_scan_tiny_rib_print_at_600_dpi_is_a_print(length, width, rib, groove):
    # held-out seeds 3, 4, 5 (sheets 36, 101, 36, 49): tiny prints of two or three
    # ribs 1.5-1.7 mm wide (under two 0.9 mm strokes), or two 2.8 mm ribs 8.9 mm
    # long (under RIB_PAIR_MM), set aside as "a letter or a mark": missing
    grey, px, (ln, wd, area) = _rib_print(length, width, rib, groove, 600.0)
    res = ip.analyze_scan(ip.Scan(grey, px, "given"), rolling_axis="y", sensitivity=False)
    (pr,) = res.prints
    _assert_within(_errors(pr.metrics, ln, wd, area))


@pytest.mark.parametrize("text", ["=", "III", "II", "E"])
def test_analyze_scan_marker_bars_are_no_tiny_rib_print(text):
    # a marker's bars (0.9 mm strokes, 7 mm high letters) alone on a sheet: the
    # controls for the rib rules above
    img, _ = render_sheet(
        SheetSpec(
            (), dpi=600.0, size=(60.0, 40.0), marks=(Text(text, (20.0, 15.0), 7.0, 0.9),), seed=3
        )
    )
    with pytest.raises(ip.NoInk):
        ip.analyze_scan(ip.Scan(img, 25.4 / 600.0, "given"), sensitivity=False)


@pytest.mark.parametrize("gap, outer", [(1.9, False), (2.8, True), (2.8, False)])
@pytest.mark.parametrize("dpi", [300.0, 600.0])
def test_analyze_scan_dust_speck_off_a_rib_print_s_tip_is_an_edge_spot(gap, outer, dpi):
    # held-out seeds 2, 3, 6 (sheets 38, 103, 74): a dust dot 1.9-2.8 mm off a
    # print's tip, within twice its tread gap, kept as a tip block: length +1.8 %,
    # +5.4 %, +8.3 % with status ok (drawn, a 0.3 mm dot: +6.4 % and +0.9 % at
    # 300 dpi before)
    grey, px, (ln, wd, area) = _rib_print(33.3, 16.7, 2.9, 1.7, dpi, speck=(gap, 0.3, outer))
    res = ip.analyze_scan(ip.Scan(grey, px, "given"), rolling_axis="y", sensitivity=False)
    (pr,) = res.prints
    _assert_within(_errors(pr.metrics, ln, wd, area))


def _siped_blocks(tip: str) -> np.ndarray:
    """Three rows of six blocks 30 x 16 px (cols x rows), 8 px apart, each with a
    closed sipe 3 px wide across its middle; the middle row runs on at the left
    with ``tip``: 'frame', a block the outline cut 3 px left of its sipe (a 3 px
    strip and 3 px frame bars left of the sipe, its right half solid), or
    'stroke', a pen stroke 3 px wide and 40 px long reaching out of a whole block."""
    mask = np.zeros((3 * 24 + 8, 8 * 38 + 60), bool)

    def block(x0, y0, x_from=0):
        b = np.ones((16, 30), bool)
        b[3:13, 13:16] = False  # the sipe
        b[:, :x_from] = False
        mask[y0 : y0 + 16, x0 : x0 + 30] |= b

    for r in range(3):
        for c in range(6):
            block(90 + c * 38, 8 + r * 24)
    if tip == "frame":
        block(90 - 38, 32, x_from=10)  # 3 px strip (10-12), the sipe (13-15)
    else:
        block(90 - 38, 32)
        mask[38:41, 90 - 38 - 40 : 90 - 38] = True
    return mask


def test_thin_protrusions_keep_a_cut_siped_block_s_frame():
    # held-out seed 6 sheet 87: a siped block at a print's tip cut through near its
    # sipe kept a frame thinner than a stroke, dropped as a label's foot: length
    # -1.55 % with status ok
    mask = _siped_blocks("frame")
    out = thin_protrusions(mask, width_px=6.0)
    assert np.flatnonzero(out.any(axis=0)).min() == 90 - 38 + 10
    assert out.sum() == mask.sum()


@pytest.mark.parametrize("tip, copy", [("frame", True), ("stroke", False)])
def test_frame_copies_a_cut_block_s_frame_not_a_stroke_s(tip, copy):
    import cv2

    from inkprint.pattern import frame_copies

    mask = _siped_blocks(tip)
    _, lab, st, _ = cv2.connectedComponentsWithStats(mask.view(np.uint8), connectivity=8)
    k = lab[40, 90 - 38 + 20]  # the tip block's piece
    part = np.zeros_like(mask)
    part[:, : 90 - 38 + 13] = mask[:, : 90 - 38 + 13]  # left of its sipe
    assert frame_copies(lab, st, np.array([k]), part=part).tolist() == [copy]
