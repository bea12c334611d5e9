"""contactpatch.ruler.extract: the contact patch cut from the mesh by the support surface."""

from dataclasses import dataclass
from typing import ClassVar

import numpy as np
import pytest
import trimesh
from numpy.testing import assert_allclose

import contactpatch as cp
import tiremesh as tm
from contactpatch.ruler.extract import SURFACE_ATOL, surface_coordinates
from tiremesh.mesh import TireMesh, build_mesh


@pytest.fixture(scope="module")
def mesh():
    return build_mesh(tm.solve(tm.get_tire(5), load=400.0, pressure=0.4), n_around=120)


def test_patch_from_mesh_is_one_polygon(mesh):
    geom = cp.patch_from_mesh(mesh, allow_multiple=False)
    assert geom.geom_type == "Polygon" and geom.is_valid


def test_patch_from_mesh_lifted_tire_has_no_patch(mesh):
    up = np.asarray(mesh.mesh.vertices) + np.array([0.0, 0.0, 0.5])
    lifted = trimesh.Trimesh(up, mesh.mesh.faces, process=False)
    t = TireMesh(
        lifted,
        mesh.point_data,
        mesh.face_contact,
        mesh.patch,
        mesh.section_phi,
        mesh.bead_vertices,
    )
    with pytest.raises(cp.NoPatch, match="no mesh face"):
        cp.patch_from_mesh(t)


def test_patch_from_mesh_split_pieces(mesh):
    # lift a band of contact sections across the middle: two pieces
    v = np.array(mesh.mesh.vertices)
    mid = np.abs(v[:, 0]) < 5.0
    v[mid, 2] += 1.0
    t = TireMesh(
        trimesh.Trimesh(v, mesh.mesh.faces, process=False),
        mesh.point_data,
        mesh.face_contact,
        mesh.patch,
        mesh.section_phi,
        mesh.bead_vertices,
    )
    geom = cp.patch_from_mesh(t)
    assert geom.geom_type == "MultiPolygon" and len(geom.geoms) == 2
    with pytest.raises(cp.NoPatch, match="2 pieces"):
        cp.patch_from_mesh(t, allow_multiple=False)


def test_contact_faces_invalid_tolerance(mesh):
    with pytest.raises(cp.InvalidInput, match="atol"):
        cp.contact_faces(mesh, atol=-1)


def test_contact_faces_tolerance_is_an_option(mesh):
    # contact vertices are snapped onto the surface: exact with atol = 0
    assert SURFACE_ATOL == 1e-6
    on = cp.contact_faces(mesh)
    assert np.array_equal(on, cp.contact_faces(mesh, atol=0.0))
    assert np.array_equal(on, mesh.face_contact)
    # a loose tolerance takes in the bulges meeting the surface tangentially
    assert cp.contact_faces(mesh, atol=1.0).sum() > on.sum()


@dataclass(frozen=True)
class Stretched(tm.SurfaceBase):
    """A made-up surface whose paper records twice the ground x."""

    kind: ClassVar[str] = "stretched"

    def unroll(self, x):
        return 2.0 * np.asarray(x, float)


def test_surface_coordinates_use_the_surface_protocol():
    v = np.array([[1.0, 2.0, 0.0], [-3.0, 0.5, 0.0]])
    assert_allclose(surface_coordinates(Stretched(), v), [[2.0, 2.0], [-6.0, 0.5]])
    assert_allclose(surface_coordinates(tm.Flat(), v), v[:, :2])
    drum = tm.Drum(500.0)
    phi = np.array([-0.1, 0.0, 0.2])  # points on the drum at these angles
    on = np.column_stack([250 * np.sin(phi), phi, 250 * np.cos(phi) - 250])
    assert_allclose(surface_coordinates(drum, on), np.column_stack([250 * phi, phi]))


@pytest.mark.parametrize("surface", ["flat", "drum:500"])
def test_patch_from_mesh_matches_the_model_outline(surface):
    # the model's outline is unrolled along the surface, as the cut is
    patch = tm.solve(tm.get_tire(5), load=400.0, pressure=0.4, surface=surface)
    geom = cp.patch_from_mesh(build_mesh(patch, n_around=120), allow_multiple=False)
    x0, y0, x1, y1 = geom.bounds
    # the patch ends are mesh vertices: the same length; the widest section need not be
    assert_allclose([x0, x1], [patch.outline[:, 0].min(), patch.outline[:, 0].max()], atol=1e-9)
    assert_allclose(y1 - y0, patch.width, rtol=1e-3)
    assert_allclose(geom.area, patch.area, rtol=1e-3)
