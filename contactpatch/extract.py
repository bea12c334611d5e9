"""Contact patch cut from a deformed-tire mesh by its support surface.

Rotta's side bulges meet the surface tangentially, so slicing the mesh with a plane
offset by a small epsilon cuts far wider than the patch (the gap grows only as the
square of the distance from the edge). Instead, the patch is the union of the faces
*lying on* the surface (all three vertices within ``tol.surface_atol``): exact when
the patch edges are mesh vertices, as in :func:`tiremesh.mesh.build_mesh`.

Coordinates: ground ``(x, y)`` [mm]; on a drum, ``x`` is arc length along the drum
(the print on paper wrapped around the drum).
"""

from __future__ import annotations

import numpy as np

from ._tol import tol
from .errors import InvalidInput, NoPatch


def surface_coordinates(surface, vertices) -> np.ndarray:
    """(n, 2) coordinates of points on the support surface: ``(x, y)``, or
    ``(arc length along the drum, y)`` for a drum."""
    v = np.asarray(vertices, float)
    if getattr(surface, "kind", "") == "drum":
        rd = 0.5 * surface.diameter
        return np.column_stack([rd * np.arctan2(v[:, 0], v[:, 2] + rd), v[:, 1]])
    return v[:, :2].copy()


def contact_faces(tire_mesh, *, atol: float | None = None) -> np.ndarray:
    """Boolean mask of the mesh faces lying on the support surface."""
    atol = tol.surface_atol if atol is None else float(atol)
    if not np.isfinite(atol) or atol < 0:
        raise InvalidInput("atol", atol, ">= 0 mm")
    gap = np.abs(tire_mesh.surface_gap())
    on = gap <= atol
    return np.all(on[tire_mesh.mesh.faces], axis=1)


def patch_from_mesh(tire_mesh, *, atol: float | None = None, allow_multiple: bool = True):
    """The contact patch of a :class:`tiremesh.mesh.TireMesh` as a shapely geometry.

    Parameters
    ----------
    tire_mesh : TireMesh
    atol : float [mm], optional
        Distance within which a vertex lies on the surface (``tol.surface_atol``).
    allow_multiple : bool
        Return a MultiPolygon when the contact splits into pieces; otherwise raise.

    Returns
    -------
    shapely Polygon (or MultiPolygon)

    Raises
    ------
    NoPatch
        No face lies on the surface, or (``allow_multiple=False``) several pieces.
    """
    import shapely
    import trimesh

    faces_on = contact_faces(tire_mesh, atol=atol)
    if not np.any(faces_on):
        raise NoPatch("no mesh face lies on the support surface")
    faces = tire_mesh.mesh.faces[faces_on]
    # boundary edges: used by exactly one contact face
    edges = np.sort(np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]]), axis=1)
    boundary = edges[trimesh.grouping.group_rows(edges, require_count=1)]
    uv = surface_coordinates(tire_mesh.patch.surface, tire_mesh.mesh.vertices)
    pieces = list(shapely.get_parts(shapely.polygonize(shapely.linestrings(uv[boundary]))))
    # polygonize also returns each hole as a polygon of its own: keep only the pieces
    # that contact faces cover (the outer pieces already carry the holes)
    tree = shapely.STRtree(shapely.polygons(uv[faces]))
    keep = [p for p in pieces if tree.query(p.representative_point(), predicate="intersects").size]
    if not keep:
        raise NoPatch("the contact faces do not form a closed outline")
    geom = shapely.unary_union(keep)
    if geom.geom_type == "MultiPolygon" and not allow_multiple:
        raise NoPatch(f"the contact splits into {len(geom.geoms)} pieces")
    return geom
