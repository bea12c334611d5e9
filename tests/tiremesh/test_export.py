"""Exports keep their data (issue 12): every format is reopened with an independent
reader (pyvista / VTK, trimesh, the raw glTF JSON chunk, the PLY/OBJ header text) and
must hold the scalars (where the format allows), the units and the load case."""

import json
import math
import struct

import numpy as np
import pytest
from numpy.testing import assert_allclose

import tiremesh as tm
from tiremesh.export import (
    FORMATS,
    GLB_SCALE,
    LOSSY,
    check_mesh_path,
    export_mesh,
    file_metadata,
)
from tiremesh.io import OutputError
from tiremesh.mesh import build_mesh, support_mesh


@pytest.fixture(scope="module")
def tire_mesh():
    patch = tm.solve(
        tm.get_tire(8), load=400.0, pressure=0.4, camber=np.radians(20), surface="drum:2500"
    )
    return build_mesh(patch, n_around=120)


def _expected_case(tire_mesh) -> dict:
    """The load case as JSON: NaN (not given) -> null, inf -> 'inf'."""
    out = {}
    for k, v in tire_mesh.patch.case.describe().items():
        if isinstance(v, float) and math.isnan(v):
            v = None
        elif isinstance(v, float) and math.isinf(v):
            v = "inf"
        out[k] = v
    return out


def _tagged(lines, prefix: str) -> dict:
    """``<prefix> tiremesh <key> <json>`` lines of a header, as a dict."""
    out = {}
    for line in lines:
        if line.startswith(prefix + " tiremesh "):
            key, _, value = line[len(prefix) + 10 :].partition(" ")
            try:
                out[key] = json.loads(value)
            except json.JSONDecodeError:
                out[key] = value
    return out


def test_export_vtp_keeps_scalars_units_and_load_case(tire_mesh, tmp_path):
    import pyvista as pv

    files = export_mesh(tire_mesh, tmp_path / "t.vtp")
    poly = pv.read(files[0])
    for name, arr in tire_mesh.point_data.items():
        assert_allclose(poly.point_data[name], arr)
    assert_allclose(poly.cell_data["contact"], tire_mesh.face_contact)
    units = json.loads(poly.field_data["units"][0])
    assert units["length"] == "mm" and units["radial_deformation"] == "mm"
    assert json.loads(poly.field_data["load_case"][0]) == _expected_case(tire_mesh)
    solution = json.loads(poly.field_data["solution"][0])
    assert_allclose(solution["vertical_force_N"], 400.0, rtol=1e-6)
    patch = pv.read(files[1])
    assert json.loads(patch.field_data["load_case"][0])["surface"] == "drum:2500"


def test_export_ply_keeps_properties_colours_and_comments(tire_mesh, tmp_path):
    import pyvista as pv
    import trimesh
    import vtk

    (path,) = export_mesh(tire_mesh, tmp_path / "t.ply")
    raw = trimesh.load(path, process=False).metadata["_ply_raw"]
    vertex = raw["vertex"]["data"]
    for name, arr in tire_mesh.point_data.items():
        assert_allclose(vertex[name], arr, atol=1e-5)
    assert_allclose(raw["face"]["data"]["contact"], tire_mesh.face_contact)
    assert pv.read(path).point_data["RGBA"].shape == (len(tire_mesh.mesh.vertices), 4)
    reader = vtk.vtkPLYReader()
    reader.SetFileName(str(path))
    reader.Update()
    c = reader.GetComments()
    comments = [c.GetValue(i) for i in range(c.GetNumberOfValues())]  # without "comment "
    meta = _tagged(["comment " + text for text in comments], "comment")
    assert meta["units"]["length"] == "mm"
    assert meta["load_case"] == _expected_case(tire_mesh)


def _glb_json(path) -> dict:
    data = path.read_bytes()
    assert data[:4] == b"glTF"
    (length,) = struct.unpack("<I", data[12:16])
    return json.loads(data[20 : 20 + length])


def test_export_glb_in_metres_with_attributes_and_extras(tire_mesh, tmp_path):
    import trimesh

    (path,) = export_mesh(tire_mesh, tmp_path / "t.glb")
    scene = trimesh.load(path)
    tire = scene.geometry["tire"]
    assert_allclose(tire.vertices, tire_mesh.mesh.vertices * GLB_SCALE, atol=1e-6)
    assert_allclose(
        np.ravel(tire.vertex_attributes["_RADIAL_DEFORMATION"]),
        tire_mesh.point_data["radial_deformation"],
        atol=1e-5,
    )
    assert_allclose(np.ravel(tire.vertex_attributes["_CONTACT"]), tire_mesh.point_data["contact"])
    assert tire.visual.kind == "vertex"
    assert scene.metadata["units"]["length"] == "m"
    assert scene.metadata["scale_from_model"] == GLB_SCALE
    assert scene.metadata["attributes"]["_RADIAL_DEFORMATION"] == "mm"
    assert scene.metadata["load_case"] == _expected_case(tire_mesh)
    # the raw glTF JSON: extras on the scene, COLOR_0 and the custom attributes
    gltf = _glb_json(path)
    assert gltf["scenes"][0]["extras"]["load_case"]["tire"] == "Schwalbe Big Apple 55-622"
    attrs = gltf["meshes"][0]["primitives"][0]["attributes"]
    assert {"POSITION", "COLOR_0", "_RADIAL_DEFORMATION", "_LATERAL_DISPLACEMENT"} <= set(attrs)
    # glTF is y-up: the node turns the ground frame's z (up) into y
    world = scene.to_mesh() if hasattr(scene, "to_mesh") else scene.dump(concatenate=True)
    assert_allclose(world.vertices[:, 1], tire_mesh.mesh.vertices[:, 2] * GLB_SCALE, atol=1e-6)
    # the whole wheel is about 0.67 m across, not 670 m
    assert 0.5 < np.ptp(tire.vertices[:, 0]) < 1.0


def test_export_glb_mesh_extras_attribute_units_per_attribute(tire_mesh, tmp_path):
    # issue 12: the mesh-level extras said _CONTACT and _SECTION were in mm
    from tiremesh.export import POINT_DATA_UNITS

    (path,) = export_mesh(tire_mesh, tmp_path / "t.glb")
    gltf = _glb_json(path)  # the raw JSON chunk, no glTF library
    (tire,) = [m for m in gltf["meshes"] if m.get("name") == "tire"]
    units = tire["extras"]["attribute_units"]
    assert units["_CONTACT"] == POINT_DATA_UNITS["contact"] != "mm"
    assert units["_SECTION"] == POINT_DATA_UNITS["section"] != "mm"
    assert units["_RADIAL_DEFORMATION"] == units["_LATERAL_DISPLACEMENT"] == "mm"
    # the same table as the scene's extras, and one entry per custom attribute
    assert units == gltf["scenes"][0]["extras"]["attributes"]
    custom = {k for k in tire["primitives"][0]["attributes"] if k.startswith("_")}
    assert set(units) == custom


def test_export_obj_keeps_colours_units_and_load_case(tire_mesh, tmp_path):
    import trimesh

    (path,) = export_mesh(tire_mesh, tmp_path / "t.obj")
    back = trimesh.load(path, process=False)
    assert len(back.faces) == tire_mesh.n_faces and back.visual.kind == "vertex"
    assert_allclose(back.vertices, tire_mesh.mesh.vertices, atol=1e-6)
    meta = _tagged(path.read_text().splitlines(), "#")
    assert meta["units"]["length"] == "mm" and meta["load_case"] == _expected_case(tire_mesh)
    assert "radial_deformation" in meta["vertex"]


def test_export_stl_keeps_contact_flag_and_a_short_case(tire_mesh, tmp_path):
    import trimesh

    (path,) = export_mesh(tire_mesh, tmp_path / "t.stl")
    back = trimesh.load(path, process=False)
    assert len(back.faces) == tire_mesh.n_faces
    assert_allclose(back.face_attributes["stl"], tire_mesh.face_contact)
    header = back.metadata["header"]
    assert header.startswith("tiremesh mm p=4bar Fz=400N camber=20deg")
    assert "drum:2500" in header
    assert ".stl" in LOSSY and ".obj" in LOSSY


@pytest.mark.parametrize("suffix", [".vtp", ".ply", ".stl", ".obj"])
def test_export_with_surface_writes_the_support_surface(tire_mesh, tmp_path, suffix):
    import pyvista as pv

    files = export_mesh(tire_mesh, tmp_path / f"t{suffix}", surface=True, patch=False)
    assert [f.name for f in files] == [f"t{suffix}", f"t_surface{suffix}"]
    slab = support_mesh(tire_mesh.patch)
    back = pv.read(files[1])
    assert back.n_points == len(slab.vertices) or back.n_cells == len(slab.faces)
    assert_allclose(back.bounds, pv.wrap(slab.vertices).bounds, atol=1e-4)


def test_export_glb_with_surface_is_one_scene(tire_mesh, tmp_path):
    import trimesh

    (path,) = export_mesh(tire_mesh, tmp_path / "t.glb", surface=True)
    scene = trimesh.load(path)
    assert set(scene.geometry) == {"tire", "surface"}
    slab = support_mesh(tire_mesh.patch)
    assert_allclose(scene.geometry["surface"].vertices, slab.vertices * GLB_SCALE, atol=1e-6)


def test_file_metadata_load_case_is_describe(tire_mesh):
    meta = file_metadata(tire_mesh)
    assert meta["load_case"] == _expected_case(tire_mesh)
    assert meta["load_case"]["deflection_mm"] is None  # not given: the load was
    assert meta["load_case"]["friction"] == "inf"
    json.dumps(meta, allow_nan=False)  # strictly valid JSON


def test_check_mesh_path_refuses_unknown_suffix_and_unwritable(tmp_path):
    with pytest.raises(tm.InvalidParameter, match="--output"):
        check_mesh_path(tmp_path / "t.fbx", option="--output")
    with pytest.raises(OutputError, match=r"cannot write /proc/t\.vtp"):
        check_mesh_path("/proc/t.vtp")
    assert check_mesh_path(tmp_path / "T.GLB") == ".glb"
    assert set(FORMATS) == {".vtp", ".ply", ".stl", ".obj", ".glb"}


def test_export_unwritable_path_is_an_output_error(tire_mesh):
    with pytest.raises(OutputError, match=r"/proc/t\.ply"):
        export_mesh(tire_mesh, "/proc/t.ply")
