"""Issue 11: tread blocks the outline cuts to slivers, tip blocks past the tread gap,
and synthetic edges drawn where their truth says (seeds of the mixed sets).

Each reproduces a file of ``python -m inkprint.accuracy`` that gave a silent wrong
number (``make_case(kind, seed=S * 100_003 + k)`` is file ``k`` of seed ``S``).
"""

from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose

import inkprint as ip
from inkprint.accuracy import SILENT
from inkprint.group import thin_protrusions
from inkprint.synth import PrintSpec, SheetSpec, render_sheet
from inkprint.synth_cases import make_case
from tests.inkprint.test_classes import assert_passes, outcomes


def mixed_file(seed: int, k: int) -> int:
    return seed * 100_003 + k


def test_sort_ink_keeps_slivers_at_the_rolling_ends_of_a_wide_print(tmp_path):
    # 4244/0035: the knob column the outline cut to 0.3 mm bars at the rolling ends
    # of a print wider than long was set aside as text: length -5.9 %
    results, rows = outcomes(tmp_path, "wide", mixed_file(4244, 35), dpi=None)
    assert_passes(results)
    (r,) = results
    assert_allclose([r["err_length"], r["err_width"]], 0.0, atol=0.005)
    assert rows[0]["set_aside"].count("text") == 0


def test_edge_spots_keep_slivers_along_the_sides_at_400_dpi(tmp_path):
    # 4245/0069: knobs cut to 2 px bars along the sides were dropped as pen strokes
    # beside the print: width -1.1 %
    results, _ = outcomes(tmp_path, "tips", mixed_file(4245, 69), dpi=None)
    assert_passes(results)


def test_edge_spots_keep_a_tip_block_past_one_and_a_half_tread_gaps(tmp_path):
    # 4245/0012: a dark tip block 1.56 x the knobs' median gap from the core was an
    # edge spot: length -2.8 %; edge_spot_pattern_factor (2.0) keeps it
    results, _ = outcomes(tmp_path, "ruler", mixed_file(4245, 12), dpi=None)
    assert not [r for r in results if r["outcome"] in SILENT], results
    assert_allclose(results[0]["err_length"], 0.0, atol=0.005)
    # (the thin ink joining the block to the tip is kept as a tapering tip since
    # tip_taper_strokes; without it the block lies apart and the factor decides)
    # (and the cut caps off: a sliver of the taper on the lattice's site joins it)
    old = ip.AnalysisOptions(edge_spot_pattern_factor=1.5, tip_taper_strokes=0.0, cut_caps=False)
    from inkprint.batch import Options

    results, _ = outcomes(
        tmp_path / "old",
        "ruler",
        mixed_file(4245, 12),
        dpi=None,
        options=Options(sensitivity=False, analysis=old),
    )
    assert results[0]["err_length"] < -0.02


def test_sort_ink_keeps_a_curved_tip_sliver_on_a_pdf_page():
    # 4244/0028 page 1: a knob cut to a curved sliver at a tip (300 dpi) was text:
    # hull area -2.1 %
    case = make_case("pdf", seed=mixed_file(4244, 28))
    img, truths = render_sheet(case.sheets[1])
    res = ip.analyze_scan(ip.Scan(img, 25.4 / case.sheets[1].dpi, "given"), sensitivity=False)
    for p, t in zip(res.prints, truths, strict=True):
        m = p.metrics
        assert_allclose(
            [m.length / t.length, m.width / t.width, m.hull_area / t.hull_area],
            1.0,
            atol=0.01,
        )


def test_thin_protrusions_keeps_a_sliver_along_the_outline_drops_a_stroke():
    m = np.zeros((80, 120), bool)
    m[20:60, 20:100] = True  # the print's thick ink
    m[62:64, 30:90] = True  # a sliver along its lower edge, 2 px beyond it
    m[5:18, 50:52] = True  # a pen stroke sticking out above it
    kept = thin_protrusions(m, width_px=6.0, along_px=6.0)
    assert kept[62:64, 30:90].all() and not kept[5:18, 50:52].any()
    dropped = thin_protrusions(m, width_px=6.0)  # along_px=0: no sliver kept
    assert not dropped[62:64, 30:90].any()
    strict = ip.AnalysisOptions(sliver_solidity=1.0, sliver_elongation=40.0)
    assert not thin_protrusions(m, width_px=6.0, along_px=6.0, options=strict)[62:64].any()


@pytest.mark.parametrize("dpi", [150.0, 300.0])
def test_render_sheet_draws_a_print_as_wide_as_its_truth(dpi):
    # the renderer filled every supersampled pixel the outline touched: prints were
    # drawn 0.4 px wider than their truth (+0.9 % on a 7.6 mm print at 150 dpi);
    # centre sampling leaves the analysis' own +0.16 px
    errs = []
    for seed in range(4):
        rng = np.random.default_rng(seed)
        p = PrintSpec(
            float(rng.uniform(50, 90)),
            float(rng.uniform(8, 14)),
            (60.0, 40.0),
            float(rng.uniform(-30, 30)),
            "slick",
            ink=0.8,
            unevenness=0.0,
        )
        spec = SheetSpec((p,), dpi=dpi, size=(120.0, 80.0), grain=0.0, specks=0, seed=seed)
        img, (t,) = render_sheet(spec)
        m = ip.analyze_scan(ip.Scan(img, 25.4 / dpi, "given"), sensitivity=False).prints[0]
        errs.append((m.metrics.width - t.width) / (25.4 / dpi))
    assert_allclose(np.mean(errs), 0.15, atol=0.1)  # [px]
    assert_allclose(render_sheet(spec)[1][0].hull_area, t.hull_area, rtol=1e-12)


@pytest.mark.parametrize(("seed", "k"), [(4244, 15), (4245, 15)])
def test_edge_field_faint_speck_next_to_a_lightly_inked_knob_adds_nothing(tmp_path, seed, k):
    # a halo speck (0.45 x the print's ink) touching a knob inked 0.7 x the median
    # was half as dark as that knob: it read as ink, width +1.7 % and +1.0 %
    results, _ = outcomes(tmp_path, "tips", mixed_file(seed, k), dpi=None)
    assert_passes(results)


def test_analyze_scan_slivers_joined_to_a_gridline_flag_the_print(tmp_path):
    # 4245/0005: tip slivers joined by a gridline inside the print read as pen
    # strokes and were set aside: hull area -5.1 %, unflagged; now flagged
    results, _ = outcomes(tmp_path, "grid", mixed_file(4245, 5), dpi=None)
    assert not [r for r in results if r["outcome"] in SILENT], results
    # since the gridline's pixels stay print ink only with print ink right across
    # them, the line no longer joins the slivers: the print measures within the bar
    assert all(r["outcome"] in ("pass", "flagged") for r in results), results


def test_analyze_scan_knob_pattern_taped_square_is_not_misaligned(tmp_path):
    # 4244/0098: two wide-groove prints taped within 0.5 degrees, read within 0.1 %,
    # were flagged axis_misaligned (own axis of the knob pattern off by ~0.7 deg)
    results, rows = outcomes(tmp_path, "mtb", mixed_file(4244, 98), dpi=None)
    assert_passes(results)
    assert all(r["flags"] == "" for r in rows)


def _four_blocks() -> tuple:
    """Ink and darkness of four dark 20 x 20 px blocks, 20 px apart across and 10 px
    along, on an 80 x 80 px box."""
    mask = np.zeros((80, 80), bool)
    dark = np.zeros((80, 80))
    for r, c in ((10, 10), (10, 50), (40, 10), (40, 50)):
        mask[r : r + 20, c : c + 20] = True
        dark[r : r + 20, c : c + 20] = 0.9
    return mask, dark


def test_edge_spots_faint_speck_on_the_core_outline_is_a_spot():
    # four dark 20 x 20 px blocks; a faint dot (a third of their darkness) whose
    # centre lies just inside the hull's bottom side but which pokes 3 px out of it.
    # Before, only the centroid was tested against the core's hull: the dot was kept
    # and widened the print (knobby print at 150 dpi: width +2.3 %, unflagged)
    from inkprint.group import Group, edge_spots

    mask, dark = _four_blocks()
    yy, xx = np.mgrid[:80, :80]
    dot = (yy - 58.5) ** 2 + (xx - 40) ** 2 <= 3.5**2  # hull bottom: row 59
    mask |= dot
    dark[dot] = 0.3
    g = Group(slice(0, 80), slice(0, 80), mask)
    spots = edge_spots(g, dark, mm_per_px=25.4 / 150)
    assert spots.n_spots == 1
    assert not (spots.load_bearing & dot).any()
    # the same dot inked dark is a tread block continuing the pattern: kept
    dark[dot] = 0.9
    kept = edge_spots(g, dark, mm_per_px=25.4 / 150)
    assert kept.n_spots == 0 and kept.load_bearing[dot].all()


def test_edge_spots_without_tread_gap_same_spots():
    # the band's re-measures skip the tread gap when no small dark blob outside the
    # core needs it: the same load-bearing ink, tread_gap 0
    from inkprint.group import Group, edge_spots

    mask, dark = _four_blocks()
    mask[70:73, 40:43] = True  # a faint speck below: a spot either way
    dark[70:73, 40:43] = 0.2
    g = Group(slice(0, 80), slice(0, 80), mask)
    full = edge_spots(g, dark, mm_per_px=25.4 / 150)
    lean = edge_spots(g, dark, mm_per_px=25.4 / 150, tread_gap=False)
    assert_allclose(full.tread_gap, 10.0, atol=1.5)  # the 10 px gaps between rows
    assert lean.tread_gap == 0.0 and lean.n_spots == full.n_spots == 1
    assert (lean.load_bearing == full.load_bearing).all()


def _dotted_print(dpi: float, side: float, pitch: float, dot: float) -> tuple:
    """A 74 x 15 mm elliptical print of diamonds (``side`` mm squares turned 45
    degrees on a ``pitch`` mm lattice) whose outer row, cut by the outline, is
    dots ``dot`` mm round (a file tread as the held-out prints have it); the grey,
    mm per px and the drawn truth (tests.inkprint.drawn)."""
    import cv2
    import shapely
    from shapely import affinity

    from tests.inkprint.drawn import drawn_scan

    ss, length, width, margin = 4, 74.0, 15.0, 20.0
    px = 25.4 / dpi / ss
    outline = affinity.scale(shapely.Point(0, 0).buffer(1.0, quad_segs=64), length / 2, width / 2)
    r = side / np.sqrt(2)
    img = np.zeros((int((width + 2 * margin) / px), int((length + 2 * margin) / px)), np.uint8)
    for i in np.arange(-length / 2 - pitch, length / 2 + pitch, pitch):
        for j in np.arange(-width / 2 - pitch, width / 2 + pitch, pitch):
            for u, v in ((i, j), (i + pitch / 2, j + pitch / 2)):
                cell = shapely.Polygon([(u - r, v), (u, v - r), (u + r, v), (u, v + r)])
                if not outline.contains(cell.centroid):
                    continue
                if not outline.contains(cell):  # the outer row: a dot
                    cell = cell.centroid.buffer(dot / 2, quad_segs=8)
                xy = np.array(cell.exterior.coords)
                pts = (xy[:, 0] + length / 2 + margin, width / 2 + margin - xy[:, 1])
                cv2.fillPoly(img, [np.round(np.column_stack(pts) / px).astype(np.int32)], 1)
    return drawn_scan(img, dpi, ss, 0.8)


@pytest.mark.parametrize(
    ("dpi", "side", "pitch", "dot"),
    [
        (180.0, 1.6, 2.4, 0.7),
        (300.0, 1.6, 2.4, 0.7),
        (180.0, 2.0, 2.8, 0.9),
        (300.0, 2.0, 2.8, 0.9),
        (300.0, 2.0, 2.8, 0.55),
        (400.0, 2.0, 2.8, 0.55),
    ],
)
def test_edge_spots_keep_a_row_of_dark_dots_along_the_outline(dpi, side, pitch, dot):
    # held-out sets 11, 13, 14: file prints whose outer row of diamonds is dots
    # 0.5-0.8 mm^2, as dark as the print, were 6-8.5 % narrow with status ok (the
    # dots dropped as pen-thin ink beside the print); here before: width -3.1 to
    # -6.8 %, hull area -4 to -8.8 %. Held-out 6 sheet 87 (400 dpi): dots 0.23-0.48
    # mm^2, the larger ones (0.3 mm^2 or more, the floor then) along 15 % of its
    # length: no row, the 16 dots dropped, width -3.6 % with status ok (0.55 mm dots)
    grey, mm, truth = _dotted_print(dpi, side, pitch, dot)
    res = ip.analyze_scan(ip.Scan(grey, mm, "given"), sensitivity=False, rolling_axis="x")
    (p,) = res.prints
    m = p.metrics
    assert_allclose([m.length, m.width], truth[:2], rtol=0.01)
    assert_allclose(m.hull_area, truth[2], rtol=0.02)
    assert p.status == "ok"


def _shouldered_print(dpi: float, cut: float) -> tuple:
    """A 98 x 72 mm elliptical slick print whose two grooves 3.5 mm wide, chords
    ``cut`` mm inside its ends, cut its shoulders off as crescents; the grey, mm per
    px and the drawn truth (tests.inkprint.drawn)."""
    import cv2

    from tests.inkprint.drawn import drawn_scan

    ss, length, width, margin = 2, 98.0, 72.0, 20.0
    px = 25.4 / dpi / ss
    h, w = round((width + 2 * margin) / px), round((length + 2 * margin) / px)
    img = np.zeros((h, w), np.uint8)
    centre = (w // 2, h // 2)
    cv2.ellipse(img, centre, (round(length / 2 / px), round(width / 2 / px)), 0, 0, 360, 1, -1)
    for side in (-1, 1):
        x = centre[0] + side * (length / 2 - cut) / px
        x0, x1 = sorted((round(x), round(x - side * 3.5 / px)))
        img[:, x0:x1] = 0
    return drawn_scan(img, dpi, ss, 0.8)


@pytest.mark.parametrize("dpi", [200.0, 300.0])
def test_find_prints_joins_shoulders_cut_off_by_a_groove(dpi):
    # held-out motorcycle road prints: grooves running out to the outline cut off
    # its shoulders, crescents 39-71 mm^2 more than 3 mm off the print, set aside as
    # fragments (under 5 % of the print): hull area -2 to -5 % with status ok
    grey, mm, truth = _shouldered_print(dpi, 7.0)
    res = ip.analyze_scan(ip.Scan(grey, mm, "given"), sensitivity=False, rolling_axis="x")
    (p,) = res.prints
    assert_allclose([p.metrics.length, p.metrics.width], truth[:2], rtol=0.01)
    assert_allclose(p.metrics.hull_area, truth[2], rtol=0.02)
    assert not any(m.kind == "fragment" for m in res.marks)


def _toothed_spine(dpi: float, angle: float) -> tuple:
    """A 17 x 1.8 mm bar with 1.0 x 0.9 mm teeth every 2.1 mm on both sides (a
    track tire's file print, 3.6 mm across them, 0.74 of its hull inked), turned
    ``angle`` degrees; the grey, mm per px and the drawn truth
    (tests.inkprint.drawn)."""
    import cv2
    import shapely
    from shapely import affinity

    from tests.inkprint.drawn import drawn_scan

    ss = 4
    px = 25.4 / dpi / ss
    parts = [shapely.box(-8.5, -0.9, 8.5, 0.9)]
    for x in np.arange(-7.35, 7.4, 2.1):
        parts += [
            shapely.box(x - 0.5, 0.9, x + 0.5, 1.8),
            shapely.box(x - 0.5, -1.8, x + 0.5, -0.9),
        ]
    ink = affinity.rotate(shapely.union_all(parts), angle, origin=(0, 0))
    img = np.zeros((round(40 / px), round(40 / px)), np.uint8)
    xy = np.array(ink.exterior.coords)
    cv2.fillPoly(img, [np.round((xy + 20.0) / px).astype(np.int32)], 1)
    return drawn_scan(img, dpi, ss, 0.8)


@pytest.mark.parametrize("dpi", [300.0, 400.0])
@pytest.mark.parametrize(("angle", "axis"), [(0.0, "x"), (90.0, "y")])
def test_is_print_toothed_spine_is_a_tiny_print(dpi, angle, axis):
    # held-out set 12 sheet 103: a 16.8 x 3.6 mm file print, a spine with teeth
    # along it inking 0.79 of its hull, was "a letter or a mark" (missing)
    grey, mm, truth = _toothed_spine(dpi, angle)
    res = ip.analyze_scan(ip.Scan(grey, mm, "given"), sensitivity=False, rolling_axis=axis)
    (p,) = res.prints
    assert_allclose([p.metrics.length, p.metrics.width], [17.0, 3.6], rtol=0.01)
    assert_allclose(p.metrics.hull_area, truth[2], rtol=0.02)


def _knob_rows(dpi: float, shape: float, offset: float, dash: float | None = None) -> tuple:
    """An 88 x 69 mm print (outline ``|u/44|^shape + |v/34.5|^shape <= 1``) of 6.7 x
    4.8 mm blocks in rows 5.8 mm apart along x, 3.4 mm across (a block row's centre
    ``offset`` mm off the axis): the outline cuts the tip row at the right-hand tip
    to slivers 0.4 mm thick (or thinner) one row gap beyond the last full row; one
    sliver when ``offset`` is 0 on an ellipse, two side by side when it is half a
    pitch on a flatter tip. ``dash``: a pen dash 2.5 x 0.4 mm along x that far [mm]
    beyond the left-hand tip's ink, on the axis. The grey, mm per px, the print's
    own drawn truth (tests.inkprint.drawn), the slivers' (count, thickest along x
    [mm], gap to the row inside [mm]) and the dash's centre (row, col) [px] or None."""
    import cv2

    from tests.inkprint.drawn import drawn_scan

    ss, length, width, margin = 4, 88.0, 69.0, 15.0
    block, gap, sliver = (6.7, 4.8), (5.8, 3.4), 0.4
    mm = 25.4 / dpi / ss
    h, w = round((width + 2 * margin) / mm), round((length + 2 * margin) / mm)
    v = ((np.arange(h) + 0.5) * mm - h * mm / 2)[:, None]
    u = ((np.arange(w) + 0.5) * mm - w * mm / 2)[None, :]
    inside = np.abs(u / (length / 2)) ** shape + np.abs(v / (width / 2)) ** shape <= 1.0
    x0 = length / 2 - sliver  # the tip row's inner edge
    rows = np.mod(u - x0, block[0] + gap[0]) < block[0]
    cols = np.mod(v - offset + block[1] / 2, block[1] + gap[1]) < block[1]
    ink = (inside & rows & cols).astype(np.uint8)
    tip = ink[:, u[0] >= x0]
    n, _ = cv2.connectedComponents(tip)
    inner = np.flatnonzero(ink[:, u[0] < x0].any(axis=0))[-1]
    slivers = (n - 1, np.ptp(np.flatnonzero(tip.any(axis=0))) * mm, x0 - u[0, inner])
    _, _, truth = drawn_scan(ink, dpi, ss, 0.8)
    at = None
    if dash is not None:
        left = u[0, np.flatnonzero(ink.any(axis=0))[0]]
        c = left - dash - 1.25
        ink[(np.abs(u - c) <= 1.25) & (np.abs(v) <= 0.2)] = 1
        at = (h // 2 // ss, round((c - u[0, 0]) / mm) // ss)
    grey, px, _ = drawn_scan(ink, dpi, ss, 0.8)
    return grey, px, truth, slivers, at


def _one_print_within_the_bar(grey, px, truth):
    """The sheet's result, its one print within 1 % of the truth's length and width
    and 2 % of its hull area, status ok."""
    res = ip.analyze_scan(ip.Scan(grey, px, "given"), rolling_axis="x", sensitivity=False)
    (p,) = res.prints
    m = p.metrics
    assert_allclose([m.length, m.width], truth[:2], rtol=0.01)
    assert_allclose(m.hull_area, truth[2], rtol=0.02)
    assert p.status == "ok", p.warnings
    return res


@pytest.mark.parametrize("dpi", [150.0, 300.0])
@pytest.mark.parametrize(("shape", "offset", "n"), [(2.0, 0.0, 1), (2.5, 4.1, 2)])
def test_judge_thin_keeps_tip_slivers_a_row_gap_out(dpi, shape, offset, n):
    # held-out 6 seed 1 sheets 29 and 91: knob prints whose block rows lie 5.0 and
    # 5.8 mm apart, their tip knobs cut to slivers 5.1 and 6.1 mm out (past
    # TIP_BLOCK_REACH x group_distance_mm, 4.5 mm) set aside as text: length -7.3
    # and -9.9 %, unflagged. A sliver cut across the axis within TIP_ROW_GAP x the
    # print's row gap is its tip block; two side by side off one tip are a row of
    # them, not each other's word (here before: length -7.1 to -7.2 %, status ok)
    grey, px, truth, slivers, _ = _knob_rows(dpi, shape, offset)
    assert slivers[0] == n and slivers[1] <= 0.45 and slivers[2] > 4.5, slivers
    res = _one_print_within_the_bar(grey, px, truth)
    assert not [k for k in res.marks if k.kind in ("text", "sliver")], res.marks


@pytest.mark.parametrize("dpi", [150.0, 300.0])
def test_judge_thin_pen_dash_a_row_gap_off_a_tip_is_no_tip_block(dpi):
    # the control: a pen dash standing along the axis (2.5 x 0.4 mm), a row gap
    # (5.8 mm) off the other tip of the same print, is no block the outline cut
    # across (TIP_ROW_ELONGATION): set aside, the print its own length with its
    # sliver (before: -7.2 %, the sliver set aside; with the elongation test off the
    # dash is the print's at 150 dpi: length +9.3 %)
    grey, px, truth, _, at = _knob_rows(dpi, 2.0, 0.0, dash=5.8)
    res = _one_print_within_the_bar(grey, px, truth)
    dashes = [
        k for k in res.marks if k.bbox[0] <= at[0] <= k.bbox[2] and k.bbox[1] <= at[1] <= k.bbox[3]
    ]
    assert [k.kind for k in dashes] == ["text"], res.marks


def _rib_print_with_specks(specks) -> tuple:
    """A 111 x 40 mm superellipse (n = 4) print at 360 dpi of four ribs 8.4 mm
    wide along x between 2.1 mm grooves, and round halo specks 0.31 mm across
    (0.075 mm^2), as dark as the print: per ``(end, k, d)``, ``d`` mm beyond the
    outline's end ``end`` (+-1) on the middle of rib ``k``. The grey, mm per px and
    the drawn truth of the print, specks left out (tests.inkprint.drawn: their
    coverage taken off its grey as it takes the print's)."""
    import cv2

    from tests.inkprint.drawn import drawn_scan

    dpi, ss, n, darkness = 360.0, 3, 4.0, 0.8
    px = 25.4 / dpi / ss
    a, b, cx, cy, r = 55.5, 20.0, 63.5, 28.0, 0.155
    t = np.linspace(0, 2 * np.pi, 1440, endpoint=False)
    c, s = np.cos(t), np.sin(t)
    xy = np.column_stack(
        [cx + a * np.sign(c) * np.abs(c) ** (2 / n), cy + b * np.sign(s) * np.abs(s) ** (2 / n)]
    )
    ink = np.zeros((round(2 * cy / px), round(2 * cx / px)), np.uint8)
    cv2.fillPoly(ink, [np.round(xy / px).astype(np.int32)], 1)
    rib, groove = (2 * b - 3 * 2.1) / 4, 2.1
    for k in range(3):
        y0 = cy - b + (k + 1) * rib + k * groove
        ink[round(y0 / px) : round((y0 + groove) / px)] = 0
    dots = np.zeros_like(ink)
    for end, k, d in specks:
        y = -b + rib / 2 + k * (rib + groove)
        x = cx + end * (a * (1 - abs(y / b) ** n) ** (1 / n) + d + r)
        cv2.circle(dots, (round(x / px), round((cy + y) / px)), round(r / px), 1, -1)
    grey, mm, truth = drawn_scan(ink, dpi, ss, darkness)
    h, w = grey.shape
    grey -= darkness * cv2.resize(dots.astype(np.float32), (w, h), interpolation=cv2.INTER_AREA)
    return grey, mm, truth


HALO_SPECKS = ((1, 1, 1.5), (1, 3, 0.8), (-1, 2, 2.0), (-1, 0, 1.0), (-1, 3, 0.5))


@pytest.mark.parametrize("n", [4, 5])
def test_edge_spots_drop_lone_halo_specks_off_a_rib_print_s_ends(n):
    # held-out 6 seed 1 sheet 99: four halo specks 0.06-0.08 mm^2, as dark as the
    # print, 0.5-2 mm off a rib print's ends and far apart: more than DUST_MOST
    # (3), they were kept as the pattern's dots, length +3.4 % with status ok (here
    # +3.5 %). Under DUST_SPECK_MM2 with no other small blob within
    # DUST_ROW_STROKES strokes, each is dust (a file row's dots lie a pitch apart)
    grey, mm, truth = _rib_print_with_specks(HALO_SPECKS[:n])
    res = ip.analyze_scan(ip.Scan(grey, mm, "given"), rolling_axis="x", sensitivity=False)
    (p,) = res.prints
    m = p.metrics
    assert_allclose([m.length, m.width], truth[:2], rtol=0.01)
    assert_allclose(m.hull_area, truth[2], rtol=0.02)
    assert p.status == "ok" and p.n_edge_spots == n
    assert m.length < p.metrics_all.length - 2.0  # with them: the specks' reach


def _turned_knob_print(dpi: float, angle: float, wedge: float = 0.5) -> tuple:
    """Held-out 6 seed 2 sheet 19's knobby print: a 98 x 66 mm ellipse of 5.09 x
    6.68 mm knobs in rows 4.7 mm apart along its axis, 3.64 mm across (no stagger),
    turned ``angle`` degrees on the sheet with its lattice; the outline cuts the tip
    row at one tip to a wedge ``wedge`` mm thick, a row gap beyond the last full
    row. The grey, mm per px, the drawn truth (length along the print's axis, width
    across it, hull area of the drawn pixels) and the wedge's (thickness along the
    axis, extent across it, gap to the row inside) [mm]."""
    import cv2

    ss, length, width = 3, 98.0, 66.0
    (kx, ky), (gx, gy) = (5.09, 6.68), (4.7, 3.64)
    mm = 25.4 / dpi / ss
    side = 0.5 * np.hypot(length, width) + 12.0
    c = (np.arange(round(2 * side / mm), dtype=np.float32) + 0.5) * mm - side
    t = np.radians(angle)
    cos, sin = np.float32(np.cos(t)), np.float32(np.sin(t))
    u = c[None, :] * cos + c[:, None] * sin  # along the print's axis
    v = c[:, None] * cos - c[None, :] * sin  # across it
    x0 = length / 2 - wedge  # the tip row's inner edge
    ink = (
        ((u / (length / 2)) ** 2 + (v / (width / 2)) ** 2 <= 1.0)
        & (np.mod(u - x0, kx + gx) < kx)
        & (np.mod(v + ky / 2, ky + gy) < ky)
    )
    tip = ink & (u >= x0)
    cut = (u[tip].max() - x0, np.ptp(v[tip]), x0 - u[ink & (u < x0)].max())
    ink = ink.astype(np.uint8)
    del u, v, tip
    hull = cv2.convexHull(cv2.findNonZero(ink)).reshape(-1, 2).astype(np.float32)
    corners = (hull[:, None, :] + np.float32([[0, 0], [1, 0], [0, 1], [1, 1]])).reshape(-1, 2)
    hull = cv2.convexHull(corners).reshape(-1, 2).astype(float) * mm
    along, across = np.array([np.cos(t), np.sin(t)]), np.array([-np.sin(t), np.cos(t)])
    truth = (np.ptp(hull @ along), np.ptp(hull @ across), cv2.contourArea(hull.astype(np.float32)))
    h, w = ink.shape
    cover = cv2.resize(ink.astype(np.float32), (w // ss, h // ss), interpolation=cv2.INTER_AREA)
    grey = 0.92 - 0.8 * cover + np.random.default_rng(0).normal(0, 0.01, cover.shape)
    return grey.astype(np.float32), 25.4 / dpi, truth, cut


@pytest.mark.parametrize(("dpi", "angle"), [(240.0, 139.0), (150.0, 41.0), (300.0, 41.0)])
def test_row_gap_turned_knob_lattice_keeps_a_cut_tip_knob(dpi, angle):
    """Held-out 6 seed 2 sheet 19 (240 dpi): a knobby MTB print 98 x 66 mm, its
    major axis at ~139 deg on the sheet and its knob lattice with it (~41 deg to the
    sheet); the outline cut a tip knob to a thin wedge (~0.5 x 5 mm) a row gap (4.7
    mm) beyond the print. The row gap was taken from the knobs' axis-aligned boxes,
    whose spans overlap on a lattice so turned: no gap, and the wedge was set aside
    as a pen mark (length -5.4 %, status ok). From each knob's own hull
    (marks._corner_points) the gap is 4.7 mm and the wedge the print's tip block.
    Here (a 0.5 x 6.7 mm wedge) before: length -5.3 to -5.4 %, hull area -1.7
    to -1.9 %, status ok."""
    grey, mm, truth, (thick, across, gap) = _turned_knob_print(dpi, angle)
    assert thick <= 0.55 and across > 4.0 and 4.5 < gap < 4.8, (thick, across, gap)
    res = ip.analyze_scan(ip.Scan(grey, mm, "given"), sensitivity=False)
    (p,) = res.prints
    m = p.metrics
    assert_allclose([m.length, m.width], truth[:2], rtol=0.01)
    assert_allclose(m.hull_area, truth[2], rtol=0.02)
    assert p.status == "ok", p.warnings
    assert not [k for k in res.marks if k.kind in ("text", "sliver")], res.marks


def test_sliver_excess_tip_block_set_aside_as_writing_is_flagged():
    # held-out 6 seed 5 sheet 10 page 2 (its print cropped, JPEG): a knob print
    # (94.27 x 104.52 mm, 200 dpi) whose staggered, turned rows are no lattice for
    # inkprint.caps, its tip block cut to a 2 x 0.6 mm sliver 3.8 mm off the last row
    # and set aside as writing: length -5.2 % with status ok before. A lone solid
    # piece off the tip near the axis, within a block's size of the outline, is
    # looked at as a block the outline cut (analyze._tip_pieces): flagged, the
    # warning's excess within 0.5 % of the truth's
    path = Path(__file__).parent / "data" / "tip_sliver_knobs.jpg"
    res = ip.analyze_scan(path, rolling_axis="y", sensitivity=False)
    (p,) = res.prints
    assert_allclose(p.metrics.width, 104.52, rtol=0.01)
    assert p.metrics.length < 0.96 * 94.27  # (the sliver left out)
    assert p.flags == ("mark_on_edge",)
    (w,) = p.warnings
    assert "set aside as a pen mark, tick or letter" in w
    said = float(w.split("(counted half) is ")[1].split(" %")[0])
    assert abs(said - 100.0 * (94.27 / p.metrics.length - 1.0)) < 0.5


def test_spots_keep_two_mirrored_cut_dots_where_a_lens_is_widest():
    # held-out 6 seed 7 sheet 86 page 1 (its print cropped): a tiny file print (13.47
    # x 3.64 mm, hull 36.1 mm^2, 300 dpi) whose outline cut its next rows to one dot
    # a side at its middle, 0.15-0.19 mm^2, 7-8 px off the body: dropped as dust
    # specks (group.DUST_SHARE), width -10.4 % with status ok before. Two alike,
    # mirrored about the axis where it is widest, are the outline's cut elements
    # (group._mirrored): kept, within the bar
    path = Path(__file__).parent / "data" / "tiny_file_mirrored.png"
    res = ip.analyze_scan(path, rolling_axis="x", sensitivity=False)
    (p,) = res.prints
    m = p.metrics
    assert_allclose([m.length, m.width], [13.47, 3.64], rtol=0.01)
    assert_allclose(m.hull_area, 36.1, rtol=0.02)
    assert p.n_edge_spots == 0


def test_comb_excess_herringbone_arms_set_aside_as_ticks_are_flagged():
    # held-out 6 seed 3 sheet 116 (the page, grey, outside its two prints and their
    # labels blanked, JPEG): a 60.16 x 12.11 mm herringbone print at 200 dpi whose
    # V's thin arms, 28 along both sides, were set aside as pen marks or ticks
    # reaching out of it: width -51 % with status ok before. With four or more
    # such ticks under no ruler's scale it is flagged (analyze._comb_excess), the
    # warning's excess that of the truth's width within 5 %; the other print (a
    # 102.8 x 17.7 mm one) stays unflagged
    path = Path(__file__).parent / "data" / "herringbone_comb.jpg"
    res = ip.analyze_scan(path, rolling_axis="auto", sensitivity=False)
    comb, other = sorted(res.prints, key=lambda p: p.metrics.length)
    assert_allclose(comb.metrics.length, 60.16, rtol=0.01)
    assert comb.metrics.width < 0.6 * 12.11  # (its arms left out)
    assert comb.flags == ("mark_on_edge",)
    (w,) = comb.warnings
    assert "were set aside as pen marks or ticks" in w
    said = float(w.split("(counted half) is ")[1].split(" %")[0])
    assert abs(said - 100.0 * (12.11 / comb.metrics.width - 1.0)) < 5.0
    assert other.status == "ok"
