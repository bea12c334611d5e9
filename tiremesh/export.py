"""Export the deformed-tire mesh: VTK XML PolyData (``.vtp``, with point data, for
ParaView) and, through trimesh, ``.ply``, ``.stl``, ``.obj``, ``.glb``.

Every file is written atomically (temporary file beside the target, then renamed).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from .errors import InvalidParameter
from .io import atomic_path
from .mesh import TireMesh

FORMATS = (".vtp", ".ply", ".stl", ".obj", ".glb")


def patch_polydata(tire_mesh: TireMesh):
    """The solver's contact-patch outline as a closed polygon on the support surface
    (``pyvista.PolyData`` with one polygon cell)."""
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


def export_mesh(tire_mesh: TireMesh, path, *, patch: bool = True) -> list[Path]:
    """Write the mesh to ``path`` (format from the suffix, see ``FORMATS``).

    For ``.vtp`` the point data (radial deformation, lateral displacement, contact,
    section) go along, and with ``patch`` the patch polygon is written beside it as
    ``<stem>_patch.vtp``.

    Returns
    -------
    list of Path
        Files written.
    """
    from .render import to_polydata

    path = Path(path)
    suffix = path.suffix.lower()
    if suffix not in FORMATS:
        raise InvalidParameter("path", str(path), "a file ending in " + ", ".join(FORMATS))
    written = []
    if suffix == ".vtp":
        with atomic_path(path) as tmp:
            to_polydata(tire_mesh).save(tmp, binary=True)
        written.append(path)
        if patch:
            ppath = path.with_name(path.stem + "_patch.vtp")
            with atomic_path(ppath) as tmp:
                patch_polydata(tire_mesh).save(tmp, binary=True)
            written.append(ppath)
    else:
        with atomic_path(path) as tmp:
            tire_mesh.mesh.export(tmp, file_type=suffix[1:])
        written.append(path)
    return written
