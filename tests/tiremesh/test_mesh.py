"""Deformed-tire mesh (sections 5.2, 5.3; Figure 5-13) and its contact patch.

The patch cut from the mesh by :mod:`contactpatch` is tested in
``tests/contactpatch/test_mesh_cut.py`` (tiremesh tests do not import contactpatch).
"""

import math

import numpy as np
import pytest
import trimesh
from numpy.testing import assert_allclose

import tiremesh as tm
from tiremesh.mesh import build_mesh, support_mesh

from .mesh_cases import CASES, T37, solve_case


@pytest.fixture(scope="module", params=list(CASES))
def case(request):
    patch = solve_case(request.param)
    return request.param, patch, build_mesh(patch)


def test_build_mesh_contact_faces_match_solver_patch(case):
    # the patch edges are mesh vertices: the contact faces cover the solver's patch
    # (area along the surface, extents in unrolled x and in y) to 2e-4
    _, patch, mesh = case
    area = mesh.mesh.area_faces[mesh.face_contact].sum()
    on = mesh.point_data["contact"].astype(bool)
    v = mesh.mesh.vertices[on]
    s = patch.surface.unroll(v[:, 0])
    assert_allclose(area, patch.area, rtol=2e-4)
    assert_allclose(np.ptp(s), patch.length, rtol=2e-4)
    assert_allclose(np.ptp(v[:, 1]), patch.width, rtol=2e-4)


def test_build_mesh_accepts_a_load_case():
    case = tm.LoadCase(T37, pressure=0.4, load=400.0, camber=math.radians(20))
    a = build_mesh(case, n_around=96)
    b = build_mesh(tm.solve(case), n_around=96)
    assert a.patch.case == case
    assert_allclose(a.mesh.vertices, b.mesh.vertices, rtol=0, atol=0)
    assert np.array_equal(a.mesh.faces, b.mesh.faces)


def test_build_mesh_validity(case):
    _, _, mesh = case
    m = mesh.mesh
    assert m.is_winding_consistent
    assert m.area_faces.min() > 1e-4  # no degenerate faces [mm^2]
    assert len(trimesh.grouping.unique_rows(np.sort(m.faces, axis=1))[0]) == len(m.faces)
    # the only open boundary is the two bead lines
    edges = m.edges_sorted
    boundary = edges[trimesh.grouping.group_rows(edges, require_count=1)]
    assert len(boundary) == 2 * len(mesh.section_phi)
    assert set(np.unique(boundary)) == set(mesh.bead_vertices.ravel())


def test_build_mesh_normals_point_outward(case):
    # outward: away from the section centre (the air side is inside)
    _, patch, mesh = case
    m = mesh.mesh
    sec = mesh.point_data["section"][m.faces[:, 0]]
    phi = mesh.section_phi[sec]
    cx, cy, cz = patch.to_ground(np.zeros_like(phi), np.zeros_like(phi), phi)
    away = m.triangles_center - np.column_stack([cx, cy, cz])
    assert np.all(np.einsum("ij,ij->i", m.face_normals, away) > 0)


def test_build_mesh_closed_rim_is_watertight():
    patch = tm.solve(T37, load=400.0, pressure=0.4)
    mesh = build_mesh(patch, close_rim=True)
    assert mesh.mesh.is_watertight and mesh.mesh.is_winding_consistent
    # encloses the air: close to the undeformed torus section x centroid circle
    r0, _w = T37.tire_radius, T37.rim_width
    theta0 = T37.rim_angle
    seg = (
        0.5 * r0**2 * (2 * np.pi - theta0 + np.sin(theta0))
    )  # circle minus the cap beyond the rim
    assert_allclose(mesh.mesh.volume, seg * 2 * np.pi * (T37.wheel_radius - r0), rtol=0.03)


def test_build_mesh_section_arc_length_is_carcass_length():
    # section 5.1: every section keeps the carcass arc length s0 (chords of the arcs
    # fall short by O(segment angle^2), so the error shrinks with bulge_points)
    patch = tm.solve(T37, load=400.0, pressure=0.4, camber=math.radians(30))
    errs = []
    for k in (16, 32, 64):
        lengths = build_mesh(patch, n_around=96, bulge_points=k).section_arc_lengths()
        errs.append(np.max(np.abs(lengths / T37.arc_length - 1)))
    assert errs[1] < 1e-3
    assert errs[2] < errs[1] / 3 < errs[0] / 9


def test_build_mesh_contact_lies_on_surface(case):
    _, _, mesh = case
    on = mesh.point_data["contact"].astype(bool)
    assert_allclose(mesh.surface_gap()[on], 0.0, atol=1e-9)
    assert np.all(mesh.surface_gap()[~on] > -1e-6)  # nothing below the surface
    assert_allclose(mesh.surface_gap(), mesh.patch.surface.gap(mesh.mesh.vertices))
    assert np.array_equal(mesh.face_contact, np.all(on[mesh.mesh.faces], axis=1))


def test_build_mesh_point_data():
    patch = tm.solve(T37, load=400.0, pressure=0.4, lateral=1.0)
    mesh = build_mesh(patch)
    pd = mesh.point_data
    far = np.abs(np.angle(np.exp(1j * mesh.section_phi[pd["section"]]))) > 0.5
    assert_allclose(pd["radial_deformation"][far], 0.0, atol=1e-9)
    assert_allclose(pd["lateral_displacement"][far], 0.0, atol=1e-9)
    on = pd["contact"].astype(bool)
    # the tread is pressed in (up to the deflection) and pushed toward +y by ~1 mm
    assert pd["radial_deformation"][on].max() == pytest.approx(patch.deflection, rel=0.05)
    assert 0.5 < np.median(pd["lateral_displacement"][on]) < 1.5


def test_build_mesh_invalid():
    patch = tm.solve(T37, load=400.0, pressure=0.4)
    with pytest.raises(tm.InvalidParameter, match="n_around"):
        build_mesh(patch, n_around=4)
    with pytest.raises(tm.InvalidParameter, match="bulge_points"):
        build_mesh(patch, bulge_points=1)
    with pytest.raises(tm.InvalidParameter, match="patch"):
        build_mesh("not a patch")
    with pytest.raises(tm.InvalidParameter, match="n_patch"):
        build_mesh(patch, n_around=32, n_patch=30)


@pytest.mark.parametrize("surface", [tm.Flat(), tm.Drum(2500), tm.Disk(3000)])
@pytest.mark.parametrize("sink", [0.0, 0.3])
def test_support_mesh_is_a_closed_slab(surface, sink):
    patch = tm.solve(T37, load=400.0, pressure=0.4, surface=surface)
    slab = support_mesh(patch, sink=sink, thickness=10.0)
    assert slab.is_watertight and slab.volume > 0
    gap = surface.gap(slab.vertices)
    top = gap > -sink - 5.0
    # top face `sink` below the surface, bottom 10 mm further, along the normal
    assert_allclose(gap[top], -sink, atol=1e-9)
    assert_allclose(gap[~top], -sink - 10.0, atol=1e-9)
    assert top.sum() == (~top).sum()


def test_support_mesh_of_a_drum_is_a_cylinder_segment():
    patch = tm.solve(T37, load=400.0, pressure=0.4, surface=tm.Drum(2500))
    slab = support_mesh(patch, extent=300.0, resolution=60)
    r = np.hypot(slab.vertices[:, 0], slab.vertices[:, 2] + 1250.0)
    assert_allclose(np.unique(np.round(r, 6)), [1250.0 - T37.tire_radius, 1250.0])
    # arc length along the top: the extent each way
    top = np.isclose(r, 1250.0)
    ang = np.arctan2(slab.vertices[top, 0], slab.vertices[top, 2] + 1250.0)
    assert_allclose([ang.min(), ang.max()], [-300.0 / 1250.0, 300.0 / 1250.0], rtol=1e-12)


def test_support_mesh_accepts_a_load_case():
    case = tm.LoadCase(T37, pressure=0.4, load=400.0, surface="drum:2500")
    assert_allclose(support_mesh(case).vertices, support_mesh(tm.solve(case)).vertices)
