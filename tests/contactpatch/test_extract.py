"""Contact patch cut from the mesh by the support surface."""

import numpy as np
import pytest
import trimesh

import contactpatch as cp
import tiremesh as tm
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
