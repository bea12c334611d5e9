"""Contact patch cut from a deformed-tire mesh by its support surface.

Rotta's side bulges meet the surface tangentially, so slicing the mesh with a plane
offset by a small epsilon cuts far wider than the patch (the gap grows only as the
square of the distance from the edge). Instead, the patch is the union of the faces
*lying on* the surface (all three vertices within ``atol``): exact when the patch
edges are mesh vertices, as in :func:`tiremesh.mesh.build_mesh`.

Everything asked of the surface goes through the :class:`tiremesh.Surface` protocol
(``gap`` and ``unroll``), so any surface works. Coordinates: ``(s, y)`` [mm], with
``s`` the arc length along the surface in the rolling direction (on flat ground the
ground ``x``; on a drum what paper wrapped around the drum records).
"""

from __future__ import annotations

import numpy as np

from ..errors import InvalidInput, NoPatch

#: a mesh vertex within this distance [mm] of the support surface lies on it
SURFACE_ATOL = 1e-6


def surface_coordinates(surface, vertices) -> np.ndarray:
    """Coordinates of points on a support surface, as paper laid on it records them.

    Parameters
    ----------
    surface : tiremesh.Surface
        The support surface (its ``unroll``).
    vertices : (n, 3) float [mm]
        Points in the ground frame (on or near the surface).

    Returns
    -------
    coords : (n, 2) float [mm]
        ``(surface.unroll(x), y)``: arc length along the surface, and lateral.
    """
    v = np.asarray(vertices, float)
    return np.column_stack([surface.unroll(v[:, 0]), v[:, 1]])


def _check_atol(atol) -> float:
    atol = float(atol)
    if not np.isfinite(atol) or atol < 0:
        raise InvalidInput("atol", atol, ">= 0 mm")
    return atol


def contact_faces(tire_mesh, *, atol: float = SURFACE_ATOL) -> np.ndarray:
    """The mesh faces lying on the support surface.

    Parameters
    ----------
    tire_mesh : tiremesh.mesh.TireMesh
        Deformed-tire mesh; its ``patch.surface`` is the support surface.
    atol : float [mm]
        A vertex whose distance to the surface (``surface.gap``) is at most this
        lies on it.

    Returns
    -------
    mask : (n_faces,) bool
        True where all three vertices lie on the surface.
    """
    atol = _check_atol(atol)
    gap = np.abs(tire_mesh.patch.surface.gap(tire_mesh.mesh.vertices))
    return np.all((gap <= atol)[tire_mesh.mesh.faces], axis=1)


def patch_from_mesh(tire_mesh, *, atol: float = SURFACE_ATOL, allow_multiple: bool = True):
    """The contact patch of a deformed-tire mesh, as a region on the surface.

    Parameters
    ----------
    tire_mesh : tiremesh.mesh.TireMesh
    atol : float [mm]
        Distance within which a vertex lies on the surface (:func:`contact_faces`).
    allow_multiple : bool
        Return a MultiPolygon when the contact splits into pieces; otherwise raise.

    Returns
    -------
    shapely Polygon or MultiPolygon [mm]
        In :func:`surface_coordinates` ``(s, y)``.

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
