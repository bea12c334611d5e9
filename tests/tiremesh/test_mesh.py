"""Deformed-tire mesh (sections 5.2, 5.3; Figure 5-13) and its contact patch."""

import itertools
import math

import numpy as np
import pytest
import trimesh
from numpy.testing import assert_allclose

import contactpatch as cp
import tiremesh as tm
from tiremesh.mesh import build_mesh, support_mesh

T37 = tm.TireGeometry.from_size(37, 18.7)
CASES = {
    "flat": dict(),
    "flat-camber30": dict(camber=math.radians(30)),
    "drum": dict(surface=tm.Drum(2500)),
    "drum-camber30": dict(surface=tm.Drum(2500), camber=math.radians(30)),
    "disk-toward-camber30": dict(surface=tm.Disk(3000, "toward"), camber=math.radians(30)),
    "disk-away": dict(surface=tm.Disk(3000, "away")),
    "lateral-slip": dict(lateral=0.5, slip=math.radians(1)),
}


@pytest.fixture(scope="module", params=list(CASES))
def case(request):
    patch = tm.solve(T37, load=400.0, pressure=0.4, **CASES[request.param])
    return request.param, patch, build_mesh(patch)


def test_build_mesh_patch_matches_solver_outline(case):
    # issue 3: mesh patch vs the solver's own outline, 0.5 % at default resolution
    _, patch, mesh = case
    geom = cp.patch_from_mesh(mesh, allow_multiple=False)
    m = cp.measure(geom, axis=0.0)
    assert_allclose(geom.area, patch.area, rtol=5e-3)
    assert_allclose(m.length, patch.length, rtol=5e-3)
    assert_allclose(m.width, patch.width, rtol=5e-3)
    # in fact far better: the patch edges are mesh vertices
    assert_allclose(
        [geom.area, m.length, m.width], [patch.area, patch.length, patch.width], rtol=2e-4
    )


def test_build_mesh_patch_error_shrinks_with_resolution():
    patch = tm.solve(T37, load=400.0, pressure=0.4, camber=math.radians(30), surface=tm.Drum(2500))
    errors = []
    for n_patch in (12, 24, 48, 96):
        geom = cp.patch_from_mesh(build_mesh(patch, n_around=3 * n_patch, n_patch=n_patch))
        errors.append(abs(geom.area / patch.area - 1))
    # polygon inscribed in a smooth outline: second order in the section spacing
    assert all(b < a / 3 for a, b in itertools.pairwise(errors)), errors


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
    assert np.array_equal(cp.contact_faces(mesh), mesh.face_contact)


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


@pytest.mark.parametrize("surface", [tm.Flat(), tm.Drum(2500)])
def test_support_mesh_is_a_closed_slab(surface):
    patch = tm.solve(T37, load=400.0, pressure=0.4, surface=surface)
    slab = support_mesh(patch)
    assert slab.is_watertight and slab.volume > 0
    top = slab.vertices[slab.vertices[:, 2] > -1e-9]
    assert_allclose(tm.mesh.surface_gap(surface, top), 0.0, atol=1e-9)
