"""An interactive 3D view of the deformed tire that works offline in one HTML file.

:func:`viewer_case` meshes a solved load case coarsely (a few thousand triangles)
and packs it as base64 arrays: vertex positions [mm], triangle indices, the radial
deformation per vertex [mm], the contact patch's outline and a ground grid lying
on the support surface. :func:`viewer_html` returns the ``<div>`` with a canvas,
the data as ``<script type="application/json">`` and a small WebGL script
(``assets/viewer.js``, no library, no network request): drag to turn, wheel to
zoom, buttons to switch cases and to look from below.
"""

from __future__ import annotations

import base64
import html
import json
import math
from importlib import resources

import numpy as np

#: coarse mesh for the browser: sections around, in the patch, bulge and contact points
VIEWER_MESH = dict(n_around=120, n_patch=40, bulge_points=10, contact_points=6)


def _b64(arr, dtype) -> str:
    return base64.b64encode(np.ascontiguousarray(arr, dtype=dtype).tobytes()).decode("ascii")


def _grid_segments(patch, spacing: float = 10.0) -> np.ndarray:
    """Ground grid line segments (2k, 3) [mm] on the support surface."""
    r0 = patch.tire.tire_radius
    half_x = spacing * math.ceil((0.5 * patch.length + 2.5 * r0) / spacing)
    half_y = spacing * math.ceil(2.5 * r0 / spacing)
    surf = patch.surface
    segs = []
    s = np.linspace(-half_x, half_x, 4 * round(2 * half_x / spacing) + 1)
    x = surf.roll(s)
    z = surf.height(x) - 0.05
    for y in np.arange(-half_y, half_y + 0.5 * spacing, spacing):
        pts = np.column_stack([x, np.full_like(x, y), z])
        segs.append(np.repeat(pts, 2, axis=0)[1:-1])  # a polyline as line segments
    for sx in np.arange(-half_x, half_x + 0.5 * spacing, spacing):
        xx = float(surf.roll(np.array([sx]))[0])
        zz = float(surf.height(np.array([xx]))[0]) - 0.05
        segs.append(np.array([[xx, -half_y, zz], [xx, half_y, zz]]))
    return np.concatenate(segs)


def _viewer_mesh(patch) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Vertices (N, 3) [mm], triangles (M, 3) and radial deformation (N,) [mm] of the
    coarse mesh: the steps of :func:`tiremesh.mesh.build_mesh` without its trimesh
    object (importing trimesh takes seconds; the browser needs only the arrays)."""
    from tiremesh import mesh as tmesh

    res = tmesh.mesh_resolution(**VIEWER_MESH)
    rings = tmesh.section_rings(patch, tmesh.plan_sections(patch, res), res, None)
    placed = tmesh.place_vertices(patch, rings)
    faces = tmesh.tire_faces(patch, placed, res)
    return placed.vertices, faces, np.asarray(placed.radial, float)


def _range_text(lo: float, hi: float) -> tuple[str, str]:
    def f(v):
        s = f"{v:.1f}"
        return "0" if float(s) == 0 else s

    return f"{f(lo)} mm", f"{f(hi)} mm"


def viewer_case(patch, label: str) -> dict:
    """One case for the viewer: the deformed tire's coarse mesh as base64 arrays.

    Parameters
    ----------
    patch : tiremesh.ContactPatch
        A solved load case.
    label : str
        Shown above the view and on its button.

    Returns
    -------
    dict
        ``label``, ``positions`` (float32 x 3), ``indices`` (uint16 x 3, or uint32
        when ``index_bits`` is 32),
        ``values`` (radial deformation [mm], float32), ``outline`` and ``grid``
        (float32 x 3 line points), ``lo``/``hi`` (colour range [mm]) and their
        texts, ``focus`` (point the camera turns about [mm]) and ``span`` [mm].
    """
    vertices, faces, values = _viewer_mesh(patch)
    lo, hi = float(values.min()), float(values.max())
    xy = patch.outline
    x = patch.surface.roll(xy[:, 0])
    outline = np.column_stack([x, xy[:, 1], patch.surface.height(x) - 0.2])
    r0 = patch.tire.tire_radius
    lo_text, hi_text = _range_text(lo, hi)
    small = len(vertices) < 65536
    return {
        "label": label,
        "positions": _b64(vertices, "<f4"),
        "indices": _b64(faces, "<u2" if small else "<u4"),
        "index_bits": 16 if small else 32,
        "values": _b64(values, "<f4"),
        "outline": _b64(outline, "<f4"),
        "grid": _b64(_grid_segments(patch), "<f4"),
        "lo": lo,
        "hi": hi,
        "lo_text": lo_text,
        "hi_text": hi_text,
        "focus": [0.0, 0.0, float(r0)],
        "span": float(max(patch.length, 5 * r0)),
    }


def viewer_script() -> str:
    """The viewer's JavaScript (``assets/viewer.js``).

    Returns
    -------
    str
    """
    return resources.files(__package__).joinpath("assets/viewer.js").read_text(encoding="utf-8")


def viewer_html(cases: list[dict]) -> str:
    """The interactive view: canvas, controls, colour scale, data and script.

    Parameters
    ----------
    cases : list of dict
        From :func:`viewer_case` (at least one).

    Returns
    -------
    str
        HTML; empty when there is no case.
    """
    if not cases:
        return ""
    buttons = "".join(
        f'<button type="button" data-case="{k}" aria-pressed="{str(k == 0).lower()}">'
        f"{html.escape(c['label'])}</button>"
        for k, c in enumerate(cases)
    )
    views = (
        '<button type="button" data-view="-0.7,-0.35">from below</button>'
        '<button type="button" data-view="-0.7,0.35">from above</button>'
        '<button type="button" data-view="0,0">front</button>'
        '<button type="button" data-view="-1.5708,0">side</button>'
    )
    data = json.dumps({"cases": cases}, separators=(",", ":")).replace("</", "<\\/")
    return (
        '<figure id="tire3d" class="viewer">'
        f'<div class="viewer-controls">{buttons}<span class="sep"></span>{views}</div>'
        '<p class="viewer-title"></p>'
        '<canvas width="800" height="500" aria-label="deformed tire, drag to turn"></canvas>'
        '<div class="viewer-scale"><span class="viewer-lo"></span><span class="ramp"></span>'
        '<span class="viewer-hi"></span> radial deformation; red: contact patch outline; '
        "grey: the support surface</div>"
        '<figcaption class="viewer-note">Drag to turn, wheel (or pinch) to zoom. '
        "The mesh is coarser than the renders' (a few thousand triangles).</figcaption>"
        f'<script type="application/json" id="viewer-data">{data}</script>'
        f"<script>{viewer_script()}</script></figure>"
    )


__all__ = ["VIEWER_MESH", "viewer_case", "viewer_html", "viewer_script"]
