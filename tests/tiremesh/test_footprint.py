"""The rounded footprint (tiremesh.footprint; beyond the dissertation, 7.3.1).

Checked where it can fail (issue 14, item 2): wide tires on wide rims at low pressure,
narrow road tires at high pressure, drum and plate, camber. The rounded print must
carry the load (Figure 4-3: prints carry about the inflation pressure), stay convex
where the plain patch is, be shorter than the pointed patch (6.2.1, Figure 6-3) and
converge with the grid.
"""

from __future__ import annotations

import numpy as np
import pytest
import shapely
from numpy.testing import assert_allclose

import tiremesh as tm
from tiremesh.footprint import (
    Footprint,
    FootprintVanished,
    parse_footprint,
    rounded_footprint,
    smoothed_pressure,
)

#: (arc length [mm], rim width [mm], pressure [bar], load [N], surface, camber [deg])
CASES = {
    "wide_50mm_1bar_flat": (110.0, 30.0, 1.0, 300.0, "flat", 0.0),
    "wide_75mm_1.5bar_drum": (165.0, 40.0, 1.5, 500.0, "drum:2500", 0.0),
    "wide_100mm_2bar_flat": (220.0, 50.0, 2.0, 700.0, "flat", 0.0),
    "road_23mm_8bar_flat": (51.5, 13.4, 8.0, 400.0, "flat", 0.0),
    "road_22mm_10bar_drum": (45.0, 13.4, 10.0, 525.0, "drum:2500", 0.0),
    "touring_37mm_4bar_camber10": (78.0, 18.7, 4.0, 500.0, "flat", 10.0),
    "road_25mm_7bar_drum_camber5": (60.0, 13.4, 7.0, 400.0, "drum:2500", 5.0),
}


def _patch(name, footprint="rounded"):
    arc, rim, bar, load, surface, camber = CASES[name]
    tire = tm.TireGeometry.from_arc_length(arc, rim)
    case = tm.LoadCase.from_units(
        tire,
        pressure_bar=bar,
        load_N=load,
        surface=surface,
        camber_deg=camber,
        footprint=footprint,
    )
    return tm.solve(case)


def _convexity(ring) -> float:
    poly = shapely.Polygon(ring)
    return poly.area / poly.convex_hull.area


@pytest.mark.parametrize("name", sorted(CASES))
def test_rounded_footprint_convex_shorter_carries_load(name):
    p = _patch(name)
    fp = p.footprint
    if _convexity(p.outline) > 0.999:
        assert _convexity(fp.outline) > 0.999
    assert fp.length < p.length
    # load / print area vs p (Figure 4-3: measured 0.95 .. 1.04 p for the Maxxis)
    ratio = fp.mean_pressure(p.vertical_force) / p.pressure
    assert 0.85 < ratio < 1.2, ratio


@pytest.mark.parametrize("name", ["wide_100mm_2bar_flat", "road_22mm_10bar_drum"])
def test_rounded_footprint_converges_with_resolution(name):
    p = _patch(name, "rotta")
    fp = Footprint("rounded")
    h = 0.25
    a = rounded_footprint(p.outline, fp, resolution=h)
    b = rounded_footprint(p.outline, fp, resolution=h / 2)
    for q in ("length", "width", "area"):
        assert_allclose(getattr(a, q), getattr(b, q), rtol=1e-3)


def test_smoothed_pressure_conserves_load():
    p = _patch("touring_37mm_4bar_camber10", "rotta")
    _, _, q = smoothed_pressure(p.outline, spread=2.0, resolution=0.1)
    # integral of q over the plane = patch area, so integral of p q = Fz (5.5)
    assert_allclose(q.sum() * 0.1 * 0.1, p.area, rtol=2e-3)
    assert q.max() <= 1.0 + 1e-9


def test_rounded_footprint_small_spread_recovers_plain_patch():
    p = _patch("road_23mm_8bar_flat", "rotta")
    fp = rounded_footprint(p.outline, Footprint("rounded", 0.02, 0.5), resolution=0.01)
    assert_allclose(fp.width, p.width, rtol=2e-3)
    assert_allclose(fp.area, p.area, rtol=3e-3)
    assert_allclose(fp.length, p.length, rtol=1e-2)


def test_rounded_footprint_half_threshold_keeps_a_straight_edge():
    # a long rectangle: at threshold 0.5 the long sides stay, the corners round off
    ring = np.array([[-50, -10], [50, -10], [50, 10], [-50, 10], [-50, -10]], float)
    fp = rounded_footprint(ring, Footprint("rounded", 2.0, 0.5), resolution=0.1)
    assert_allclose(fp.width, 20.0, atol=0.01)
    assert_allclose(fp.length, 100.0, atol=0.01)
    assert fp.area < 2000.0
    wider = rounded_footprint(ring, Footprint("rounded", 2.0, 0.3), resolution=0.1)
    assert wider.width > 20.5


def test_footprint_default_patch_is_bit_identical():
    p = _patch("road_23mm_8bar_flat", "rotta")
    fp = p.footprint
    assert fp.outline is p.outline
    assert (fp.length, fp.width, fp.area) == (p.length, p.width, p.area)
    assert tm.LoadCase(p.tire, pressure=0.5, load=300.0).footprint.kind == "rotta"


def test_footprint_vanishes_with_a_named_error():
    ring = np.array([[-50, -0.2], [50, -0.2], [50, 0.2], [-50, 0.2], [-50, -0.2]], float)
    with pytest.raises(FootprintVanished, match="narrower than the spread"):
        rounded_footprint(ring, Footprint("rounded", 5.0, 0.5))


@pytest.mark.parametrize(
    "spec, match",
    [
        ("oval", "footprint"),
        ("rounded:0:0.5", "spread_mm"),
        ("rounded:2:1.5", "threshold"),
        ("rounded:x", "numbers"),
        ("rotta:2", "footprint"),
    ],
)
def test_parse_footprint_rejects(spec, match):
    with pytest.raises(tm.InvalidParameter, match=match):
        parse_footprint(spec)


def test_parse_footprint_specs():
    assert parse_footprint("rounded:1.5:0.4") == Footprint("rounded", 1.5, 0.4)
    assert parse_footprint("rounded").spread_mm == Footprint().spread_mm
    assert parse_footprint(Footprint("rounded", 3.0, 0.5).spec) == Footprint("rounded", 3.0, 0.5)


def test_cli_solve_footprint_prints_both(capsys):
    from tiremesh.cli import main

    args = ["solve", "--tire", "6", "--pressure", "6.895bar", "--load", "304N"]
    assert main([*args, "--footprint", "rounded:2:0.5"]) == 0
    out = capsys.readouterr().out
    assert "contact patch: length 88.4" in out
    assert "footprint: rounded:2:0.5" in out
    assert "footprint_length_mm: 71.1" in out
    assert main([*args, "--footprint", "oval"]) != 0
    assert "footprint" in capsys.readouterr().err


def test_render_draws_the_rounded_footprint():
    from tiremesh.mesh import build_mesh
    from tiremesh.render import FOOTPRINT_COLOR, render

    case = tm.LoadCase(tm.get_tire(8), pressure=0.4, load=400.0)
    blue = np.array(FOOTPRINT_COLOR) * 255
    share = []
    for fp in ("rotta", "rounded"):
        mesh = build_mesh(tm.solve(case.replace(footprint=fp)), n_around=120)
        img = render(mesh, view="bottom", size=(320, 240)).astype(int)
        share.append((np.abs(img - blue).sum(axis=2) < 60).mean())
    assert share[0] < 1e-4 < share[1]


def test_row_from_case_refuses_a_rounded_footprint():
    from tiremesh.sweep import row_from_case

    case = tm.LoadCase(tm.get_tire(1), pressure=0.5, load=300.0, footprint="rounded")
    with pytest.raises(tm.InvalidParameter, match="footprint"):
        row_from_case(case)
    assert row_from_case(case.replace(footprint="rotta"))["load_N"] == 300.0


@pytest.mark.parametrize("surface", ["flat", "drum:2500"])
def test_build_mesh_marks_the_rounded_footprint(surface, tmp_path):
    """Meshes follow the footprint the case asks for: the rounded print leaves out
    the pointed tips of the Rotta contact vertices, and exports keep the scalar."""
    import pyvista as pv

    from tiremesh.export import export_mesh
    from tiremesh.mesh import build_mesh

    case = tm.LoadCase(tm.get_tire(6), pressure=0.6895, load=304.0, surface=surface)
    plain = build_mesh(case, n_around=360)
    assert "footprint" not in plain.point_data  # the default stays as it was
    rounded = build_mesh(case.replace(footprint=tm.Footprint("rounded")), n_around=360)
    fp, contact = rounded.point_data["footprint"], rounded.point_data["contact"]
    assert fp.any() and not (fp & ~contact.astype(bool)).any()
    x = rounded.patch.surface.unroll(rounded.mesh.vertices[:, 0])
    on = x[fp == 1]
    half = rounded.patch.footprint.length / 2
    assert np.abs(on).max() <= half + 1e-6 and np.abs(on).max() > 0.9 * half
    assert np.abs(x[contact == 1]).max() > half + 1.0  # the tips are left out
    out = export_mesh(rounded, tmp_path / "t.vtp")[0]  # the tire (the patch beside it)
    assert_allclose(pv.read(out).point_data["footprint"], fp)
