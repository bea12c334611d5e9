"""Off-screen renders (issues 3, 13: title block, colour bar, views of the patch,
camera, formats), exports and the mesh/render/section CLI."""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from numpy.testing import assert_allclose
from PIL import Image

import tiremesh as tm
from tiremesh.export import export_mesh, patch_polydata
from tiremesh.mesh import build_mesh
from tiremesh.render import (
    BAR_FRACTION,
    TITLE_FRACTION,
    VIEWS,
    nice_ticks,
    render,
    title_lines,
    view_camera,
)

BASELINES = Path(__file__).resolve().parent / "baselines"
SIZE = (160, 120)
#: golden images: large enough for the title block and colour bar to be legible
GOLDEN_SIZE = (480, 360)
# mean absolute difference allowed against a baseline [0..255]: software rendering
# differs slightly between Mesa versions, a wrong camera or a missing tire does not
TOLERANCE = 8.0


@pytest.fixture(scope="module")
def tire_mesh():
    patch = tm.solve(tm.get_tire(8), load=400.0, pressure=0.4, camber=np.radians(20))
    return build_mesh(patch, n_around=240)


@pytest.mark.parametrize("view", VIEWS)
def test_render_view_matches_baseline(tire_mesh, view, tmp_path):
    out = tmp_path / f"{view}.png"
    img = render(tire_mesh, out, view=view, size=GOLDEN_SIZE)
    assert img.shape == (GOLDEN_SIZE[1], GOLDEN_SIZE[0], 3)
    png = np.asarray(Image.open(out).convert("RGB"))
    assert np.array_equal(png, img)
    # the model's part of the frame (below the title, left of the colour bar) shows
    # the tire over a plausible area
    w, h = GOLDEN_SIZE
    body = png[round(h * TITLE_FRACTION) :, : round(w * (1 - BAR_FRACTION))]
    tire = np.abs(body.astype(int) - 255).sum(axis=2) > 60
    assert 0.05 < tire.mean() < 0.95
    base = BASELINES / f"render_{view}.png"
    if os.environ.get("ROTTA_UPDATE_BASELINES"):
        base.parent.mkdir(exist_ok=True)
        Image.fromarray(png).save(base)
    ref = np.asarray(Image.open(base).convert("RGB")).astype(float)
    diff = np.abs(ref - png).mean()
    assert diff < TOLERANCE, f"{view}: mean abs difference {diff:.2f} vs {base}"


def test_title_block_states_the_load_case(tire_mesh):
    lines = title_lines(tire_mesh)
    assert lines[0] == "Schwalbe Big Apple 55-622 on a 18.7 mm rim"
    assert lines[1] == "4 bar, 400 N, camber 20 deg, slip 0 deg, flat ground"
    assert lines[2].startswith("patch ") and "mm²;" in lines[2]
    drum = tm.solve(tm.get_tire(8), load=400.0, pressure=0.69, surface=tm.Drum(2500))
    assert "6.9 bar" in title_lines(build_mesh(drum, n_around=60))[1]
    assert title_lines(build_mesh(drum, n_around=60))[1].endswith("drum 2.5 m")


@pytest.mark.parametrize(
    ("lo", "hi", "ticks", "decimals"),
    [
        (-3.59, 0.0, [-4, -3, -2, -1, 0], 0),
        (-3.51, 6.01, [-4, -2, 0, 2, 4, 6, 8], 0),
        (0.0, 4.0, [0, 1, 2, 3, 4], 0),
        (0.1, 0.35, [0.1, 0.15, 0.2, 0.25, 0.3, 0.35], 2),
        (2.0, 2.0, [1.4, 1.6, 1.8, 2.0, 2.2, 2.4, 2.6], 1),
    ],
)
def test_nice_ticks(lo, hi, ticks, decimals):
    (a, b), t, d = nice_ticks(lo, hi)
    assert_allclose(t, ticks, atol=1e-12)
    assert (a, b) == (t[0], t[-1]) and a <= lo and b >= hi
    assert d == decimals
    assert all(f"{x:.{d}f}" != "-0" + ("." + "0" * d if d else "") for x in t)


def test_colour_bar_column_is_clear_of_the_model(tire_mesh):
    w, h = GOLDEN_SIZE
    c = view_camera("side", tire_mesh)
    for scalars in ("radial_deformation", "lateral_displacement"):
        # zoomed in, the tire fills the model's part of the image from edge to edge...
        img = render(
            tire_mesh, view="side", size=GOLDEN_SIZE, scalars=scalars, camera=(c.azimuth, 0.0, 2.5)
        )
        x0 = round(w * (1 - BAR_FRACTION))
        body = img[round(h * TITLE_FRACTION) :, x0 - 3]
        assert (np.abs(body.astype(int) - 255).sum(axis=1) > 60).mean() > 0.5
        # ...and stops there: the bar's column left of the bar (and its label) is
        # background from top to bottom
        strip = img[round(h * TITLE_FRACTION) :, x0 : x0 + round(0.15 * w * BAR_FRACTION)]
        assert (strip == 255).all(), scalars


def test_render_colours_by_scalars(tire_mesh):
    a = render(tire_mesh, view="bottom", size=SIZE, scalars="radial_deformation")
    b = render(tire_mesh, view="bottom", size=SIZE, scalars="lateral_displacement")
    assert np.abs(a.astype(int) - b.astype(int)).mean() > 1.0


def test_contact_pressure_marks_the_patch(tire_mesh):
    img = render(tire_mesh, view="bottom", size=GOLDEN_SIZE, scalars="contact_pressure")
    w, h = GOLDEN_SIZE
    body = img[round(h * TITLE_FRACTION) :, : round(w * (1 - BAR_FRACTION))].astype(int)
    # viridis' top colour (the inflation pressure) where the patch is, and only there
    yellow = (np.abs(body - [253, 231, 37]).sum(axis=2) < 120).mean()
    patch_share = tire_mesh.patch.area / (2 * 0.55 * tire_mesh.patch.length + 80) ** 2
    assert 0.2 * patch_share < yellow < 0.2


def test_camera_and_background(tire_mesh):
    default = render(tire_mesh, view="iso", size=SIZE, title=False, scalar_bar=False)
    # the iso view's own direction (the tire leans toward +y: seen from -y)
    bare = dict(view="iso", size=SIZE, title=False, scalar_bar=False)
    turned = render(tire_mesh, camera=(120.0, 30.0, 1.0), **bare)
    assert np.abs(default.astype(int) - turned.astype(int)).mean() > 5.0
    c = view_camera("iso", tire_mesh)
    same = render(tire_mesh, camera=(c.azimuth, c.elevation, 1.0), **bare)
    assert np.abs(default.astype(int) - same.astype(int)).mean() < 1.0
    dark = render(tire_mesh, view="bottom", size=GOLDEN_SIZE, background="black")
    assert (dark[0, -1] == 0).all()  # the corner is background
    title = dark[: round(GOLDEN_SIZE[1] * TITLE_FRACTION)]
    assert (title.min(axis=2) > 200).any()  # white text on black


@pytest.mark.parametrize(
    ("suffix", "magic"),
    [
        (".jpg", b"\xff\xd8"),
        (".tiff", b"II"),
        (".svg", b"<?xml"),
        (".pdf", b"%PDF"),
        (".eps", b"%!PS"),
    ],
)
def test_render_formats_from_the_suffix(tire_mesh, tmp_path, suffix, magic):
    out = tmp_path / f"view{suffix.upper() if suffix == '.pdf' else suffix}"
    render(tire_mesh, out, view="bottom", size=SIZE)
    data = out.read_bytes()
    assert data.startswith(magic)
    if suffix in (".jpg", ".tiff"):
        assert Image.open(out).size == SIZE
    if suffix == ".svg":
        assert b"Schwalbe Big Apple 55-622" in data  # the title is vector text


def test_unsupported_suffix_fails_before_any_work(tmp_path):
    # the mesh argument is not even looked at: the suffix is checked first
    with pytest.raises(ValueError, match=r"\.png \| \.jpg .* \.pdf \| \.svg \| \.eps"):
        render(object(), tmp_path / "view.gif")
    assert not any(tmp_path.iterdir())


@pytest.mark.parametrize(
    ("kw", "match"),
    [
        ({"view": "top"}, "view"),
        ({"scalars": "heat"}, "scalars"),
        ({"scalars": "section"}, "scalars"),
        ({"size": (4, 4)}, "width"),
        ({"camera": (0.0, 95.0, 1.0)}, "camera"),
        ({"camera": (0.0, 10.0, 0.0)}, "camera"),
        ({"camera": (1.0, 2.0)}, "camera"),
    ],
)
def test_render_invalid(tire_mesh, kw, match):
    with pytest.raises(tm.InvalidParameter, match=match):
        render(tire_mesh, **kw)


def test_render_accepts_a_patch_or_a_load_case(tire_mesh):
    case = tire_mesh.patch.case
    ref = render(build_mesh(case), view="side", size=SIZE)
    assert np.array_equal(render(case, view="side", size=SIZE), ref)
    assert np.array_equal(render(tire_mesh.patch, view="side", size=SIZE), ref)


@pytest.mark.parametrize("surface", [tm.Flat(), tm.Drum(2500), tm.Disk(3000)])
def test_export_patch_outline_lies_on_the_surface(surface):
    patch = tm.solve(tm.get_tire(8), load=400.0, pressure=0.4, surface=surface)
    pts = np.asarray(patch_polydata(build_mesh(patch, n_around=120)).points)
    assert_allclose(surface.gap(pts), 0.0, atol=1e-9)
    # wrapped back from the unrolled outline: unrolling again gives the outline
    assert_allclose(surface.unroll(pts[:, 0]), patch.outline[:-1, 0], atol=1e-9)
    assert_allclose(pts[:, 1], patch.outline[:-1, 1])


def test_export_vtp_round_trip(tire_mesh, tmp_path):
    import pyvista as pv

    files = export_mesh(tire_mesh, tmp_path / "tire.vtp")
    assert [f.name for f in files] == ["tire.vtp", "tire_patch.vtp"]
    poly = pv.read(files[0])
    assert poly.n_points == len(tire_mesh.mesh.vertices)
    assert poly.n_cells == tire_mesh.n_faces
    for name, arr in tire_mesh.point_data.items():
        assert_allclose(poly.point_data[name], arr)
    patch = pv.read(files[1])
    assert_allclose(patch.field_data["area_mm2"][0], tire_mesh.patch.area)
    assert patch.n_cells == 1


@pytest.mark.parametrize("suffix", [".ply", ".stl", ".obj", ".glb"])
def test_export_trimesh_formats(tire_mesh, tmp_path, suffix):
    import trimesh

    (path,) = export_mesh(tire_mesh, tmp_path / f"tire{suffix}")
    back = trimesh.load(path, force="mesh", process=False)
    assert len(back.faces) == tire_mesh.n_faces


def test_export_invalid_format(tire_mesh, tmp_path):
    with pytest.raises(tm.InvalidParameter, match="path"):
        export_mesh(tire_mesh, tmp_path / "tire.fbx")


def _cli(*args):
    proc = subprocess.run(
        [sys.executable, "-m", "tiremesh.cli", *args], capture_output=True, text=True, timeout=300
    )
    assert proc.returncode == 0, proc.stderr
    return proc.stdout


def test_cli_mesh_render_section(tmp_path):
    common = ["--tire", "8", "--pressure", "4bar", "--load", "400N", "--camber", "10"]
    out = _cli("mesh", *common, "--around", "120", "-o", str(tmp_path / "t.vtp"))
    assert (tmp_path / "t.vtp").is_file() and (tmp_path / "t_patch.vtp").is_file()
    assert "faces" in out
    _cli("mesh", *common, "--around", "120", "--close-rim", "-o", str(tmp_path / "t.stl"))
    assert (tmp_path / "t.stl").stat().st_size > 0
    _cli(
        "render",
        *common,
        "--around",
        "120",
        "--view",
        "bottom",
        "--image-size",
        "200x150",
        "-o",
        str(tmp_path / "v.png"),
    )
    assert Image.open(tmp_path / "v.png").size == (200, 150)
    _cli("section", *common, "-o", str(tmp_path / "s.png"))
    assert Image.open(tmp_path / "s.png").size[0] > 100


def test_cli_render_background_error_names_the_flag(tmp_path):
    args = ["render", "--tire", "8", "--pressure", "4bar", "--load", "400N"]
    args += ["--background", "nocolour", "-o", str(tmp_path / "v.png")]
    proc = subprocess.run(
        [sys.executable, "-m", "tiremesh.cli", *args], capture_output=True, text=True, timeout=300
    )
    assert proc.returncode != 0 and not (tmp_path / "v.png").exists()
    assert "--background = 'nocolour' is invalid" in proc.stderr


def test_front_view_looks_through_the_ground_at_the_patch(tire_mesh):
    front = view_camera("front", tire_mesh)
    assert front.elevation < 0  # from below: the ground is a grid, the patch shows
    img = render(tire_mesh, view="front", size=GOLDEN_SIZE, title=False, scalar_bar=False)
    red = (img[..., 0] > 180) & (img[..., 1] < 80) & (img[..., 2] < 80)
    assert red.sum() > 150  # the patch outline, not a thin line at the bottom


def test_fit_camera_frames_the_points_both_ways():
    """The fitted camera looks the same way, centred on the points' projected box;
    its half-height covers the box (with the margin) in both directions."""
    from tiremesh.render import FIT_MARGIN, ViewCamera, fit_camera, image_axes

    c = ViewCamera((0.0, 0.0, 0.0), 0.0, 0.0, 1.0)  # from the front: right -y... up +z
    pts = np.array([[0.0, -10.0, 0.0], [0.0, 30.0, 0.0], [5.0, 0.0, 100.0]])
    tall = fit_camera(c, pts, aspect=1.0)
    _, up = image_axes(tall)
    assert_allclose(np.abs(up), [0, 0, 1], atol=1e-12)
    assert_allclose(np.asarray(tall.focal) @ up, 50.0, atol=1e-9)  # centre of z 0..100
    assert_allclose(tall.scale, 50.0 * (1 + FIT_MARGIN), rtol=1e-12)
    wide = fit_camera(c, pts, aspect=0.2)  # a narrow image: the width decides
    assert_allclose(wide.scale, 20.0 / 0.2 * (1 + FIT_MARGIN), rtol=1e-12)
    assert (tall.azimuth, tall.elevation) == (c.azimuth, c.elevation)


@pytest.mark.parametrize("view", VIEWS)
def test_fitted_views_keep_the_framed_tire_inside(tire_mesh, view):
    """Every view: every point it draws projects inside the model's part of the
    image; the front view's ruler lies below the tire (not across it)."""
    from tiremesh.render import _camera, frame_points, front_ruler, image_axes

    w, h = GOLDEN_SIZE
    aspect = (1 - BAR_FRACTION) * w / ((1 - TITLE_FRACTION) * h)
    c = _camera(None, view, tire_mesh, aspect)
    right, up = image_axes(c)
    pts = frame_points(tire_mesh, view)
    f = np.asarray(c.focal)
    u, v = (pts - f) @ right, (pts - f) @ up
    assert np.abs(v).max() < c.scale and np.abs(u).max() < c.scale * aspect
    if view == "front":
        a, b = front_ruler(c, pts, 40.0)
        assert max((a - f) @ up, (b - f) @ up) < v.min()
        assert -c.scale < (a - f) @ up  # and still in the image


@pytest.mark.parametrize("view", VIEWS)
def test_every_view_leaves_a_margin_around_the_model(tire_mesh, view):
    """A cutaway (:func:`tiremesh.render.view_region`) ends the wheel inside the
    frame: a border of the model's part of the image (below the title block, left
    of the colour bar) is background all round, but for the axis triad's corner."""
    w, h = GOLDEN_SIZE
    img = render(tire_mesh, view=view, size=GOLDEN_SIZE)
    body = img[round(h * TITLE_FRACTION) :, : round(w * (1 - BAR_FRACTION))]
    bh = body.shape[0]
    k = round(0.02 * bh)
    blank = (body == 255).all(axis=2)
    triad_w, triad_h = round(0.13 * h / w * 1.33 * w) + 2, round(0.17 * bh) + 2
    assert blank[:k].all() and blank[:, -k:].all(), view  # top, right
    assert blank[: bh - triad_h, :k].all(), view  # left, above the triad
    assert blank[-k:, triad_w:].all(), view  # bottom, right of the triad


def test_view_region_cuts_the_wheel_to_the_patch_neighbourhood(tire_mesh):
    """The half-spaces of each view keep the patch and drop the top of the wheel;
    the front view keeps the half behind the central section, its far cut turned
    toward the camera (no line of sight leaves the tire through it)."""
    from tiremesh.render import image_axes, view_region

    p = tire_mesh.patch
    top = np.array([0.0, 0.0, 2 * p.tire.wheel_radius])
    for view in VIEWS:
        planes = view_region(view, tire_mesh)
        assert all(n @ np.zeros(3) <= c for n, c in planes), view  # the patch centre
        assert any(n @ top > c for n, c in planes), view
    front = view_region("front", tire_mesh)
    assert_allclose(front[0][0], [1, 0, 0]) and front[0][1] == 0.0
    right, up = image_axes(view_camera("front", tire_mesh))
    look = np.cross(up, right)  # into the scene
    assert front[1][0] @ look < 0
