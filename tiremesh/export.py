"""Export the deformed-tire mesh, keeping its data as far as each format allows.

=========  ===============================================================================
format     what the file keeps
=========  ===============================================================================
``.vtp``   VTK XML PolyData (ParaView): point data (radial deformation, lateral
           displacement, contact, section), cell data (contact); units, load case and
           solution as field data (JSON strings ``units``, ``load_case``, ``solution``)
``.ply``   binary PLY: vertex properties (the point data), vertex colours (radial
           deformation, viridis), face property ``contact``; units, load case and
           solution as ``comment tiremesh <key> <json>`` header lines
``.glb``   binary glTF 2.0, in metres (glTF's unit: positions x ``GLB_SCALE`` = 1e-3;
           the node matrix turns tiremesh's z-up ground frame to glTF's y-up): custom
           vertex attributes ``_RADIAL_DEFORMATION`` ... (values in mm), ``COLOR_0``;
           units, scale, load case and solution in the scene's ``extras``
``.obj``   Wavefront OBJ: vertex colours (radial deformation); units, load case and
           solution as ``# tiremesh <key> <json>`` comments. No scalars (OBJ has none)
``.stl``   binary STL: geometry and, per face, the contact flag (the 2 attribute
           bytes); units and a short load case in the 80-byte header. No vertex
           scalars and no room for the full load case: prefer ``.vtp``/``.ply``/``.glb``
=========  ===============================================================================

``surface=True`` also exports the support surface (ground, drum or disk, as a slab:
:func:`tiremesh.mesh.support_mesh`): as ``<stem>_surface<suffix>``, or in a ``.glb``
as a second mesh of the same scene. The load case is ``tire_mesh.patch.case.describe()``
(unit-carrying names); lengths are mm in every format but ``.glb`` (metres).

Every file is written atomically (temporary file beside the target, then renamed).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from .errors import InvalidParameter
from .io import atomic_path, check_output_path
from .mesh import TireMesh

FORMATS = (".vtp", ".ply", ".stl", ".obj", ".glb")
"""Suffixes :func:`export_mesh` writes."""
GLB_SCALE = 1e-3
"""Factor from the model's mm to glTF's metres, applied to ``.glb`` positions."""
POINT_DATA_UNITS = {
    "radial_deformation": "mm",
    "lateral_displacement": "mm",
    "contact": "1 on the support surface, else 0",
    "section": "section index around the wheel",
    "footprint": "1 on contact vertices inside the print footprint, else 0 (rounded footprint only)",
}
"""Units of the per-vertex data (``TireMesh.point_data``), stored in every file."""
LOSSY = {
    ".obj": "keeps vertex colours but no scalars (the format has none)",
    ".stl": "keeps geometry and a per-face contact flag only, with a short load case "
    "in its 80-byte header",
}
"""Formats that cannot hold every scalar, and what they keep (the CLI prints this)."""
FRAME = "ground frame: x forward (rolling direction), y lateral, z up"
_GLB_Y_UP = np.array(
    [[1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0], [0.0, -1.0, 0.0, 0.0], [0.0, 0.0, 0.0, 1.0]]
)


def check_mesh_path(path, *, option: str | None = None) -> str:
    """Check an export target before any work: a known suffix and a writable place.

    Parameters
    ----------
    path : str or PathLike
        Target file.
    option : str, optional
        The option that named it (``'--output'``), quoted in messages.

    Returns
    -------
    str
        The suffix (lower case), one of :data:`FORMATS`.

    Raises
    ------
    InvalidParameter
        An unsupported suffix.
    OutputError
        The file cannot be written there.
    """
    suffix = Path(path).suffix.lower()
    if suffix not in FORMATS:
        raise InvalidParameter(
            option or "path", str(path), "a file ending in " + ", ".join(FORMATS)
        )
    check_output_path(path, option=option)
    return suffix


def _json_safe(value):
    """JSON-safe copy: NaN -> None, +-inf -> 'inf' / '-inf', numpy scalars -> Python."""
    if isinstance(value, dict):
        return {str(k): _json_safe(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [_json_safe(v) for v in value]
    if hasattr(value, "item") and hasattr(value, "dtype"):
        value = value.item()
    if isinstance(value, float) and not math.isfinite(value):
        return None if math.isnan(value) else ("inf" if value > 0 else "-inf")
    if value is None or isinstance(value, bool | int | float | str):
        return value
    return str(value)


def file_metadata(tire_mesh: TireMesh, *, length_unit: str = "mm") -> dict:
    """What every exported file records besides the geometry.

    Parameters
    ----------
    tire_mesh : TireMesh
        The exported mesh (its ``patch`` gives the load case and the solution).
    length_unit : {'mm', 'm'}
        Unit of the file's positions (``'m'`` for glTF).

    Returns
    -------
    dict
        JSON-safe: ``generator``, ``units`` (positions and point data), ``frame``,
        ``load_case`` (``patch.case.describe()``; a NaN load or deflection, i.e. not
        given, as null, an infinite friction as ``'inf'``) and ``solution``
        (``patch.summary()``: deflection, vertical force, patch size).
    """
    from . import __version__

    patch = tire_mesh.patch
    return _json_safe(
        {
            "generator": f"tiremesh {__version__}",
            "units": {"length": length_unit, **POINT_DATA_UNITS},
            "frame": FRAME,
            "load_case": patch.case.describe(),
            "solution": patch.summary(),
        }
    )


def _colours(values: np.ndarray) -> np.ndarray:
    """(n, 4) uint8 viridis colours of ``values`` over their finite range."""
    from matplotlib import colormaps

    v = np.asarray(values, float)
    finite = np.isfinite(v)
    lo, hi = (v[finite].min(), v[finite].max()) if finite.any() else (0.0, 1.0)
    t = np.clip((np.where(finite, v, lo) - lo) / (hi - lo if hi > lo else 1.0), 0.0, 1.0)
    return np.round(colormaps["viridis"](t) * 255).astype(np.uint8)


def _colour_note(tire_mesh: TireMesh) -> str:
    v = np.asarray(tire_mesh.point_data["radial_deformation"], float)
    return f"vertex colours: radial_deformation [mm], viridis, {v.min():.6g} .. {v.max():.6g}"


def _write_vtp(poly, path: Path, meta: dict) -> Path:
    for key in ("units", "frame", "load_case", "solution"):
        poly.field_data[key] = [json.dumps(meta[key])]
    poly.field_data["generator"] = [meta["generator"]]
    with atomic_path(path) as tmp:
        poly.save(tmp, binary=True)
    return path


def _ply_bytes(mesh, meta: dict, comments: list[str]) -> bytes:
    """trimesh's binary PLY with ``comment tiremesh ...`` lines added to the header."""
    from trimesh.exchange.ply import export_ply

    data = export_ply(mesh, encoding="binary", include_attributes=True)
    header, sep, body = data.partition(b"end_header\n")
    lines = header.decode("ascii").splitlines()
    extra = [f"comment tiremesh {k} {json.dumps(meta[k])}" for k in ("units", "load_case")]
    extra += [f"comment tiremesh solution {json.dumps(meta['solution'])}"]
    extra += [f"comment tiremesh {c}" for c in (f"frame {meta['frame']}", *comments)]
    lines[2:2] = [line.replace("\n", " ") for line in extra]
    return ("\n".join(lines) + "\n").encode("ascii", "replace") + sep + body


def _attributed(tire_mesh: TireMesh):
    """A copy of the trimesh with the point data, face contact and colours attached."""
    import trimesh

    src = tire_mesh.mesh
    mesh = trimesh.Trimesh(vertices=src.vertices, faces=src.faces, process=False)
    for name, arr in tire_mesh.point_data.items():
        arr = np.asarray(arr)
        dtype = np.float32 if arr.dtype.kind == "f" else arr.dtype
        mesh.vertex_attributes[name] = arr.astype(dtype)
    mesh.face_attributes["contact"] = np.asarray(tire_mesh.face_contact, np.uint8)
    mesh.visual.vertex_colors = _colours(tire_mesh.point_data["radial_deformation"])
    return mesh


def _write_ply(mesh, path: Path, meta: dict, comments: list[str]) -> Path:
    with atomic_path(path) as tmp:
        tmp.write_bytes(_ply_bytes(mesh, meta, comments))
    return path


def _write_obj(mesh, path: Path, meta: dict, comments: list[str]) -> Path:
    lines = ["# tiremesh deformed-tire mesh (Wavefront OBJ)"]
    lines += [f"# tiremesh {k} {json.dumps(meta[k])}" for k in ("units", "load_case", "solution")]
    lines += [f"# tiremesh frame {meta['frame']}", *(f"# tiremesh {c}" for c in comments)]
    v = np.asarray(mesh.vertices, float)
    rows = [v]
    fmt = "v %.10g %.10g %.10g"
    if mesh.visual.kind == "vertex":
        rows.append(np.asarray(mesh.visual.vertex_colors, float)[:, :3] / 255.0)
        fmt += " %.4f %.4f %.4f"
    with atomic_path(path) as tmp, tmp.open("w", encoding="ascii", errors="replace") as fh:
        fh.write("\n".join(lines) + "\n")
        np.savetxt(fh, np.column_stack(rows), fmt=fmt)
        np.savetxt(fh, np.asarray(mesh.faces) + 1, fmt="f %d %d %d")
    return path


def _stl_header(meta: dict) -> bytes:
    c, s = meta["load_case"], meta["solution"]
    text = (
        f"tiremesh mm p={c['pressure_bar']:.4g}bar Fz={s['vertical_force_N']:.5g}N "
        f"camber={c['camber_deg']:.4g}deg slip={c['slip_deg']:.4g}deg "
        f"lat={c['lateral_mm']:.4g}mm {c['surface']} {c['tire']}"
    )
    return text.encode("ascii", "replace")[:80].ljust(80, b" ")


def _write_stl(mesh, path: Path, meta: dict, face_flag=None) -> Path:
    tri = np.asarray(mesh.vertices, float)[np.asarray(mesh.faces)]
    normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    length = np.linalg.norm(normal, axis=1, keepdims=True)
    normal = np.divide(normal, length, out=np.zeros_like(normal), where=length > 0)
    rec = np.zeros(len(tri), dtype=[("n", "<f4", (3,)), ("v", "<f4", (9,)), ("a", "<u2")])
    rec["n"], rec["v"] = normal, tri.reshape(-1, 9)
    if face_flag is not None:
        rec["a"] = np.asarray(face_flag, np.uint16)
    with atomic_path(path) as tmp, tmp.open("wb") as fh:
        fh.write(_stl_header(meta))
        fh.write(np.uint32(len(rec)).tobytes())
        fh.write(rec.tobytes())
    return path


def _glb_scene(tire_mesh: TireMesh, surface: bool):
    import trimesh

    meta = file_metadata(tire_mesh, length_unit="m")
    mesh = _attributed(tire_mesh)
    mesh.vertices = np.asarray(mesh.vertices) * GLB_SCALE
    attrs = {f"_{k.upper()}": np.asarray(v, np.float32) for k, v in mesh.vertex_attributes.items()}
    mesh.vertex_attributes.clear()
    mesh.vertex_attributes.update(attrs)
    units = {f"_{k.upper()}": u for k, u in POINT_DATA_UNITS.items() if f"_{k.upper()}" in attrs}
    mesh.metadata.update({"name": "tire", "attribute_units": units})
    scene = trimesh.Scene()
    scene.add_geometry(mesh, geom_name="tire", node_name="tire", transform=_GLB_Y_UP)
    if surface:
        ground = _support(tire_mesh)
        ground.vertices = np.asarray(ground.vertices) * GLB_SCALE
        scene.add_geometry(ground, geom_name="surface", node_name="surface", transform=_GLB_Y_UP)
    meta["scale_from_model"] = GLB_SCALE
    meta["attributes"] = dict(units)  # the mesh's extras and the scene's: one table
    meta["frame"] += "; positions in metres; the node matrix turns z-up into glTF's y-up"
    scene.metadata.update(meta)
    return scene


def _write_glb(tire_mesh: TireMesh, path: Path, surface: bool) -> Path:
    from trimesh.exchange.gltf import export_glb

    data = export_glb(_glb_scene(tire_mesh, surface))
    with atomic_path(path) as tmp:
        tmp.write_bytes(data)
    return path


def _support(tire_mesh: TireMesh):
    from .mesh import support_mesh

    return support_mesh(tire_mesh.patch)


def _write_surface(tire_mesh: TireMesh, path: Path, suffix: str, meta: dict) -> Path:
    ground = _support(tire_mesh)
    note = [f"support surface {meta['load_case']['surface']} (slab under the tire)"]
    if suffix == ".vtp":
        import pyvista as pv

        faces = np.column_stack([np.full(len(ground.faces), 3), ground.faces]).ravel()
        return _write_vtp(pv.PolyData(np.asarray(ground.vertices, float), faces), path, meta)
    if suffix == ".ply":
        return _write_ply(ground, path, meta, note)
    if suffix == ".obj":
        return _write_obj(ground, path, meta, note)
    return _write_stl(ground, path, meta)


def export_mesh(
    tire_mesh: TireMesh, path, *, patch: bool = True, surface: bool = False
) -> list[Path]:
    """Write the mesh to ``path`` (format from the suffix, see ``FORMATS``), keeping its
    scalars, units and load case as far as the format allows (module docstring).

    Parameters
    ----------
    tire_mesh : TireMesh
        The mesh (vertices in the ground frame [mm]).
    path : str or PathLike
        Target file, ending in one of ``FORMATS``.
    patch : bool
        For ``.vtp``, also write the patch outline as ``<stem>_patch.vtp``
        (:func:`patch_polydata`).
    surface : bool
        Also export the support surface (ground, drum or disk): ``<stem>_surface``
        plus the suffix, or for ``.glb`` a second mesh in the same file.

    Returns
    -------
    list of Path
        Files written.

    Raises
    ------
    InvalidParameter
        An unsupported suffix.
    OutputError
        A file cannot be written (the message names the path and the reason).
    """
    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in FORMATS:
        raise InvalidParameter("path", str(path), "a file ending in " + ", ".join(FORMATS))
    if suffix == ".glb":
        return [_write_glb(tire_mesh, path, surface)]
    meta = file_metadata(tire_mesh)
    written = [_write_tire(tire_mesh, path, suffix, meta)]
    if patch and suffix == ".vtp":
        written.append(_write_vtp(patch_polydata(tire_mesh), _beside(path, "_patch"), meta))
    if surface:
        written.append(_write_surface(tire_mesh, _beside(path, "_surface"), suffix, meta))
    return written


def _beside(path: Path, tag: str) -> Path:
    return path.with_name(path.stem + tag + path.suffix)


def _write_tire(tire_mesh: TireMesh, path: Path, suffix: str, meta: dict) -> Path:
    if suffix == ".vtp":
        from .render import to_polydata

        return _write_vtp(to_polydata(tire_mesh), path, meta)
    if suffix == ".stl":
        return _write_stl(tire_mesh.mesh, path, meta, tire_mesh.face_contact)
    mesh = _attributed(tire_mesh)
    if suffix == ".ply":
        return _write_ply(mesh, path, meta, [_colour_note(tire_mesh)])
    return _write_obj(mesh, path, meta, [_colour_note(tire_mesh)])


def patch_polydata(tire_mesh: TireMesh):
    """The solver's contact-patch outline as a closed polygon on the support surface.

    The outline's ``x`` (arc length along the surface) is rolled back onto the
    surface, so the polygon lies on a drum too.

    Parameters
    ----------
    tire_mesh : TireMesh
        Mesh whose ``patch`` supplies the outline.

    Returns
    -------
    pyvista.PolyData
        Points (2n, 3) [mm] in the ground frame, one polygon cell; field data
        ``length_mm``, ``width_mm`` [mm] and ``area_mm2`` [mm^2].
    """
    import pyvista as pv

    p = tire_mesh.patch
    xy = p.outline[:-1]
    # the outline's x is arc length along the surface (unrolled): wrap it back on
    x = p.surface.roll(xy[:, 0])
    pts = np.column_stack([x, xy[:, 1], p.surface.height(x)])
    poly = pv.PolyData(pts, faces=np.concatenate([[len(pts)], np.arange(len(pts))]))
    poly.field_data["length_mm"] = [p.length]
    poly.field_data["width_mm"] = [p.width]
    poly.field_data["area_mm2"] = [p.area]
    return poly


__all__ = [
    "FORMATS",
    "GLB_SCALE",
    "LOSSY",
    "POINT_DATA_UNITS",
    "check_mesh_path",
    "export_mesh",
    "file_metadata",
    "patch_polydata",
]
