"""Off-screen renders, exports and the mesh/render/section CLI (issue 3)."""

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
from tiremesh.render import VIEWS, render

BASELINES = Path(__file__).resolve().parent.parent / "baselines"
SIZE = (160, 120)
# mean absolute difference allowed against a baseline [0..255]: software rendering
# differs slightly between Mesa versions, a wrong camera or a missing tire does not
TOLERANCE = 12.0


@pytest.fixture(scope="module")
def tire_mesh():
    patch = tm.solve(tm.get_tire(8), load=400.0, pressure=0.4, camber=np.radians(20))
    return build_mesh(patch, n_around=240)


@pytest.mark.parametrize("view", VIEWS)
def test_render_view_matches_baseline(tire_mesh, view, tmp_path):
    out = tmp_path / f"{view}.png"
    img = render(tire_mesh, out, view=view, size=SIZE)
    assert img.shape == (SIZE[1], SIZE[0], 3)
    png = np.asarray(Image.open(out).convert("RGB"))
    assert png.shape == img.shape
    # the tire covers a plausible part of the frame
    tire = np.abs(png.astype(int) - 255).sum(axis=2) > 60
    assert 0.05 < tire.mean() < 0.95
    base = BASELINES / f"render_{view}.png"
    if os.environ.get("ROTTA_UPDATE_BASELINES"):
        Image.fromarray(png).save(base)
    ref = np.asarray(Image.open(base).convert("RGB")).astype(float)
    assert np.abs(ref - png).mean() < TOLERANCE


def test_render_colours_by_scalars(tire_mesh):
    a = render(tire_mesh, view="bottom", size=SIZE, scalars="radial_deformation")
    b = render(tire_mesh, view="bottom", size=SIZE, scalars="lateral_displacement")
    assert np.abs(a.astype(int) - b.astype(int)).mean() > 1.0


@pytest.mark.parametrize(
    ("kw", "match"),
    [({"view": "top"}, "view"), ({"scalars": "heat"}, "scalars"), ({"size": (4, 4)}, "width")],
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
