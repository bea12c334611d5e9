"""Off-screen renders of the deformed tire (VTK, no display needed).

Views: ``iso`` (front quarter, from slightly below through the ground grid, so the
contact patch and a bulge show), ``side`` (along the axle), ``front`` (against the
rolling direction, cut at the central section: the Rotta section of Figure 5-5)
and ``bottom`` (straight up through the ground grid at the patch). The contact
patch's outline is drawn in every view. Each view shows a cutaway of the wheel around
the patch (:func:`view_region`: the rest is cut away at planes, so the tire ends
inside the frame) with a free margin all round (:func:`fit_camera`).

The image is laid out in three parts that never overlap: a title block on top (tire,
rim, pressure in bar, load, camber, slip, surface), the model, and a colour-bar
column on the right with rounded ticks and the quantity's unit; an axis triad sits
in the model's lower-left corner and a ruler gives the length scale in mm.

The format follows the output's suffix: PNG, JPEG, TIFF (raster) or PDF, SVG, EPS
(vector, through VTK's GL2PS exporter: text and lines as vectors, the shaded tire
as an embedded raster).

The scene is built with plain VTK (:mod:`tiremesh.vtkscene`), which imports several
times faster than pyvista; :func:`to_polydata` still gives the mesh as a pyvista
surface for interactive use.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from . import validate as v
from . import vtkscene as vs
from .case import LoadCase
from .errors import InvalidParameter
from .mesh import TireMesh, build_mesh, rim_mesh, support_mesh
from .solver import ContactPatch
from .units import MPA_PER_BAR

VIEWS = ("iso", "side", "front", "bottom")
#: scalar name -> (label, unit) of the colour bar
SCALARS = {
    "radial_deformation": ("radial deformation", "mm"),
    "lateral_displacement": ("lateral displacement", "mm"),
    "contact_pressure": ("contact pressure", "bar"),
    "contact": ("contact (1: on the surface)", ""),
}
#: output suffix -> Pillow format (raster) or None (vector, GL2PS)
FORMATS = {
    ".png": "PNG",
    ".jpg": "JPEG",
    ".jpeg": "JPEG",
    ".tif": "TIFF",
    ".tiff": "TIFF",
    ".pdf": None,
    ".svg": None,
    ".eps": None,
}
SURFACE_COLOR = (0.80, 0.80, 0.76)
GRID_COLOR = (0.45, 0.45, 0.45)
PATCH_COLOR = (0.85, 0.1, 0.1)
#: the rounded print footprint (tiremesh.footprint), when the load case asks for it
FOOTPRINT_COLOR = (0.1, 0.25, 0.85)
RIM_COLOR = (0.7, 0.72, 0.75)
INSIDE_COLOR = (0.62, 0.62, 0.62)
#: fractions of the image: title band height, colour-bar column width
TITLE_FRACTION = 0.13
BAR_FRACTION = 0.17


@dataclass(frozen=True)
class ViewCamera:
    """A parallel-projection camera looking at ``focal`` from a direction.

    Attributes
    ----------
    focal : (3,) float [mm]
    azimuth : float [deg]
        Direction of the camera seen from above, from the forward axis ``+x``
        toward ``+y``.
    elevation : float [deg]
        Above the ground plane (negative: from below, through the ground).
    scale : float [mm]
        Half the height the image shows (parallel scale).
    """

    focal: tuple[float, float, float]
    azimuth: float
    elevation: float
    scale: float

    def position(self, distance: float):
        """Camera placement ``distance`` from the focal point.

        Parameters
        ----------
        distance : float [mm]

        Returns
        -------
        list
            ``[position, focal point, view up]``, each an (x, y, z) tuple [mm, mm, -].
        """
        az, el = math.radians(self.azimuth), math.radians(self.elevation)
        d = np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])
        up = (0.0, 0.0, 1.0)
        if abs(math.cos(el)) < 1e-6:  # straight up or down: forward is up in the image
            up = (1.0, 0.0, 0.0)
        f = np.asarray(self.focal, float)
        return [tuple(f + distance * d), tuple(f), up]


def output_format(path) -> str | None:
    """The image format of an output path, checked before any work.

    Parameters
    ----------
    path : str or PathLike
        Its suffix picks the format (case-insensitive).

    Returns
    -------
    str or None
        Pillow format name (``'PNG'``, ``'JPEG'``, ``'TIFF'``), or None for a vector
        format (``.pdf``, ``.svg``, ``.eps``).

    Raises
    ------
    InvalidParameter
        (a ``ValueError``) for any other suffix, naming the supported ones.
    """
    suffix = Path(path).suffix.lower()
    if suffix not in FORMATS:
        raise InvalidParameter("path", str(path), "a file ending in " + " | ".join(FORMATS))
    return FORMATS[suffix]


def _check_camera(camera):
    """None, an (azimuth, elevation, zoom) tuple, or a pyvista camera position."""
    if camera is None:
        return None
    seq = list(camera)
    if len(seq) == 3 and all(isinstance(c, int | float) for c in seq):
        az, el, zoom = (float(c) for c in seq)
        if not all(math.isfinite(c) for c in (az, el, zoom)) or zoom <= 0 or abs(el) > 90:
            raise InvalidParameter(
                "camera", camera, "(azimuth deg, elevation deg in [-90, 90], zoom > 0)"
            )
        return (az, el, zoom)
    if len(seq) == 3 and all(len(c) == 3 for c in seq):
        return [tuple(float(x) for x in c) for c in seq]
    raise InvalidParameter(
        "camera", camera, "(azimuth deg, elevation deg, zoom) or [position, focal, view up]"
    )


def to_polydata(tire_mesh: TireMesh):
    """The mesh as a pyvista surface.

    Parameters
    ----------
    tire_mesh : TireMesh

    Returns
    -------
    pyvista.PolyData
        Vertices [mm] in the ground frame, triangle cells, the point data of
        ``tire_mesh.point_data`` and the cell data ``contact`` (0/1) and
        ``contact_pressure`` [bar] (the inflation pressure on the faces lying on the
        support surface, where the Rotta model carries the load; 0 elsewhere).
    """
    import pyvista as pv

    faces = np.column_stack([np.full(len(tire_mesh.mesh.faces), 3), tire_mesh.mesh.faces])
    poly = pv.PolyData(np.asarray(tire_mesh.mesh.vertices, float), faces.ravel())
    for name, arr in tire_mesh.point_data.items():
        poly.point_data[name] = np.asarray(arr)
    bar = tire_mesh.patch.pressure / MPA_PER_BAR
    poly.cell_data["contact"] = tire_mesh.face_contact.astype(np.uint8)
    poly.cell_data["contact_pressure"] = tire_mesh.face_contact * bar
    return poly


def view_camera(view: str, tire_mesh: TireMesh) -> ViewCamera:
    """The default camera of a view: its direction, and the bottom view's scale.

    The iso, side and front views are framed on the bounds of what they draw
    (:func:`fit_camera` on :func:`frame_points`) when rendered; the bottom view's
    scale follows from the patch alone (:func:`view_region`), so that bottom views
    of several cases can share one scale.

    Parameters
    ----------
    view : {'iso', 'side', 'front', 'bottom'}
    tire_mesh : TireMesh
        Or any object with its ``patch``.

    Returns
    -------
    ViewCamera
    """
    p = tire_mesh.patch
    r0 = p.tire.tire_radius
    side = -1.0 if p.camber >= 0 else 1.0  # look from the side the wheel leans away from
    span = max(p.length, 5 * r0)
    if view == "iso":
        return ViewCamera((0.0, 0.0, 0.6 * r0), -40.0 * side, -22.0, 0.72 * span)
    if view == "side":
        return ViewCamera((0.0, 0.0, 1.6 * r0), 90.0 * side, 0.0, 0.5 * max(p.length, 6 * r0))
    if view == "front":  # a little from below, through the ground: the patch shows
        return ViewCamera((0.0, 0.0, 0.9 * r0), 0.0, -14.0, 1.9 * r0)
    half_x, _ = _bottom_half_extents(p)
    return ViewCamera((0.0, 0.0, 0.0), 0.0, -90.0, half_x * (1 + FIT_MARGIN))


#: views framed on the bounds of what they draw (:func:`fit_camera`); the bottom view
#: has a scale of its own (:func:`view_camera`)
FITTED_VIEWS = ("iso", "side", "front")
#: free border around the model, a fraction of the half-height (or half-width)
FIT_MARGIN = 0.08
#: the front view shows the tire and rim behind its central section up to this
#: height above the rim's section [tire radii r0]
FRONT_FRAME_ABOVE = 0.3
#: depth of the renders' rim bed below the bead lines [mm] (:func:`tiremesh.mesh.rim_mesh`)
RIM_DEPTH = 12.0
#: the iso view shows the lower part of the wheel: this many patch lengths either
#: side of the patch's centre (so the patch stays large), and at least this many
#: times the height of the tire and rim, up to this height at most [wheel radii]
ISO_FRAME_LENGTH = 1.5
ISO_FRAME_SECTIONS = 2.0
ISO_FRAME_HEIGHT = 0.35
#: the front view's far cut faces the camera by this much [deg]
FRONT_CUT_TILT = 1.0
#: the side view shows the tire this far beyond the patch's ends [r0]
SIDE_FRAME_BEYOND = 2.0
#: the bottom view shows the tire and ground this far beyond the patch's ends [r0],
#: and the ground at least this far to each side [r0]
BOTTOM_FRAME_BEYOND = 1.5
BOTTOM_FRAME_SIDE = 2.5
#: ground grid spacing [mm]
GRID_SPACING = 10.0


def _bottom_half_extents(p: ContactPatch) -> tuple[float, float]:
    """Half-length and half-width [mm] of the bottom view's ground: whole grid cells,
    at least 3/4 as wide as long."""
    r0, s = p.tire.tire_radius, GRID_SPACING
    half_x = s * math.ceil((0.5 * p.length + BOTTOM_FRAME_BEYOND * r0) / s)
    half_y = s * math.ceil(max(BOTTOM_FRAME_SIDE * r0, 0.75 * half_x) / s)
    return half_x, half_y


def view_region(view: str, tire_mesh: TireMesh, *, camera: ViewCamera | None = None) -> list:
    """What a view shows, as half-spaces: the tire, rim, surface and patch outline
    are cut at their planes (a cutaway), so that the model ends inside the frame.

    The iso view shows the lower part of the wheel (:data:`ISO_FRAME_LENGTH`), the
    side view the tire around the patch (:data:`SIDE_FRAME_BEYOND`), the bottom view
    the patch and a stretch of tire and ground beyond its ends
    (:data:`BOTTOM_FRAME_BEYOND`). The front view shows the half behind the central
    section (the Rotta section, Figure 5-5) up to the rim's section
    (:data:`FRONT_FRAME_ABOVE`), cut there along the image's horizontal and turned
    a little toward the camera: the camera sees into the tire through the section,
    and no line of sight comes out through the far cut.

    Parameters
    ----------
    view : {'iso', 'side', 'front', 'bottom'}
    tire_mesh : TireMesh
    camera : ViewCamera, optional
        The direction the front view is seen from (default :func:`view_camera`'s).

    Returns
    -------
    list of (normal, offset)
        Keep the points ``p`` [mm] (ground frame) with ``normal . p <= offset`` for
        every pair (``normal``: (3,) float).
    """
    p = tire_mesh.patch
    r0 = p.tire.tire_radius
    ex, ez = np.eye(3)[0], np.eye(3)[2]
    if view == "iso":
        R = p.tire.wheel_radius
        h = max(
            (ISO_FRAME_LENGTH * p.length) ** 2 / (2 * R), ISO_FRAME_SECTIONS * _rim_top(tire_mesh)
        )
        return [(ez, min(h, ISO_FRAME_HEIGHT * R))]
    axle = (ez, p.tire.wheel_radius)  # the lower half of the wheel (the rest is hidden)
    if view == "side":
        half = 0.5 * p.length + SIDE_FRAME_BEYOND * r0
        return [(ex, half), (-ex, half), axle]
    if view == "front":
        right, up = image_axes(camera or view_camera(view, tire_mesh))
        tilt = math.radians(FRONT_CUT_TILT)
        n = math.cos(tilt) * up + math.sin(tilt) * np.cross(right, up)  # toward the camera
        top = _rim_top(tire_mesh) + FRONT_FRAME_ABOVE * r0
        return [(ex, 0.0), (n, float(n @ (top * ez)))]
    # a hair beyond the ground's outer grid lines, so that they stay
    half_x, half_y = (h + 0.01 * GRID_SPACING for h in _bottom_half_extents(p))
    ey = np.eye(3)[1]
    return [(ex, half_x), (-ex, half_x), (ey, half_y), (-ey, half_y), axle]


def _rim_top(tire_mesh: TireMesh) -> float:
    """Height of the rim bed over the central section [mm]."""
    v = np.asarray(tire_mesh.mesh.vertices, float)
    beads = v[np.asarray(tire_mesh.bead_vertices)]  # (2, n_sections, 3)
    k = int(np.argmin(np.abs(beads[0, :, 0])))
    return float(beads[:, k, 2].max()) + RIM_DEPTH


def image_axes(c: ViewCamera) -> tuple[np.ndarray, np.ndarray]:
    """Unit vectors of the image's right and up directions in the world.

    Parameters
    ----------
    c : ViewCamera

    Returns
    -------
    right, up : (3,) float
    """
    position, focal, up = c.position(1.0)
    look = np.asarray(focal, float) - np.asarray(position, float)
    right = np.cross(look, up)
    right /= np.linalg.norm(right)
    return right, np.cross(right, look) / np.linalg.norm(np.cross(right, look))


def fit_camera(c: ViewCamera, points, *, aspect: float, margin: float = FIT_MARGIN):
    """The camera looking the same way, framed on the bounds of ``points``.

    Parameters
    ----------
    c : ViewCamera
        Direction (azimuth, elevation) to keep.
    points : (n, 3) float [mm]
        What is drawn (tire, rim, patch outline, ruler).
    aspect : float
        Width / height of the model's part of the image [-].
    margin : float
        Free border, a fraction of the fitted half-height (or half-width).

    Returns
    -------
    ViewCamera
        Focal point at the centre of the projected bounds; parallel scale (half the
        image height [mm]) such that they fit both ways.
    """
    pts = np.asarray(points, float).reshape(-1, 3)
    right, up = image_axes(c)
    u, v = pts @ right, pts @ up
    uc, vc = 0.5 * (u.min() + u.max()), 0.5 * (v.min() + v.max())
    look = np.cross(up, right)  # away from the camera
    depth = float(np.mean(pts @ look))
    focal = uc * right + vc * up + depth * look
    half = max(0.5 * (v.max() - v.min()), 0.5 * (u.max() - u.min()) / aspect)
    return ViewCamera(tuple(float(x) for x in focal), c.azimuth, c.elevation, half * (1 + margin))


def frame_points(tire_mesh: TireMesh, view: str) -> np.ndarray:
    """What a view draws with its default camera, as points: the tire, rim, surface
    and patch outline cut to :func:`view_region`.

    Parameters
    ----------
    tire_mesh : TireMesh
    view : {'iso', 'side', 'front', 'bottom'}

    Returns
    -------
    (n, 3) float [mm]
    """
    below = view_camera(view, tire_mesh).elevation < 0
    parts = _view_parts(tire_mesh, view, view_region(view, tire_mesh), below=below)
    return _points(parts)


def _points(parts: dict) -> np.ndarray:
    pts = [vs.points_of(pd) for pd in _flat(parts.values())]
    return np.concatenate(pts) if pts else np.empty((0, 3))


def _flat(items):
    for x in items:
        yield from (x if isinstance(x, list) else [x])


def _view_parts(tire_mesh: TireMesh, view: str, region, *, below: bool, rim=True, surface=True):
    """A view's geometry as ``vtkPolyData`` (a dict) cut to ``region`` (None: uncut):
    ``tire``, ``rim``, ``surface`` (a slab, or a grid seen from ``below``),
    ``outlines`` (a list: the patch's, then the rounded footprint's if asked for) and,
    when the region cuts at ``x = 0`` (the front view), ``section``: the tire's and
    rim's sections there."""

    def cut(pd, planes=region):
        return pd if planes is None else vs.clip_halfspaces(pd, planes)

    tire = _tire_polydata(tire_mesh)
    parts = {"tire": cut(tire)}
    rims = [_trimesh_vtk(rim_mesh(tire_mesh, depth=RIM_DEPTH))] if rim else []
    if rims:
        parts["rim"] = cut(rims[0])
    if region is not None and any(np.allclose(n, (1, 0, 0)) and c == 0 for n, c in region):
        # sliced whole (a slice of the cut surface would lie on its ragged edge)
        others = [(n, c) for n, c in region if not np.allclose(n, (1, 0, 0))]
        parts["section"] = [cut(vs.slice_x(pd), others) for pd in [tire, *rims]]
    if surface and below:
        wide = _bottom_half_extents(tire_mesh.patch)[1] if view == "bottom" else None
        grid = ground_grid(tire_mesh, spacing=GRID_SPACING, half_width=wide)
        parts["surface"] = cut(vs.lines(grid))
    elif surface:
        parts["surface"] = cut(_trimesh_vtk(support_mesh(tire_mesh.patch, sink=0.3)))
    p = tire_mesh.patch
    rings = [p.outline] + ([p.footprint.outline] if p.case.footprint.kind != "rotta" else [])
    lifted = -0.2 if below else 0.2  # toward the camera
    parts["outlines"] = [
        cut(vs.lines([np.column_stack([x, xy[:, 1], p.surface.height(x) + lifted])]))
        for xy, x in ((xy, p.surface.roll(xy[:, 0])) for xy in rings)
    ]
    return parts


def render(
    tire_mesh: TireMesh | ContactPatch | LoadCase,
    path=None,
    *,
    view: str = "iso",
    scalars: str = "radial_deformation",
    size: tuple[int, int] = (1200, 900),
    camera=None,
    background="white",
    title: bool = True,
    show_surface: bool = True,
    show_rim: bool = True,
    scalar_bar: bool = True,
    ruler: bool = True,
    axes: bool = True,
    cmap: str = "viridis",
):
    """Render the deformed tire off-screen.

    Parameters
    ----------
    tire_mesh : TireMesh, ContactPatch or LoadCase
        The mesh; a patch or a load case (solved first) is meshed with the defaults
        of :func:`tiremesh.mesh.build_mesh`.
    path : str or Path, optional
        File to write (atomically); its suffix picks the format (:data:`FORMATS`):
        ``.png``, ``.jpg``/``.jpeg``, ``.tif``/``.tiff``, or vector ``.pdf``,
        ``.svg``, ``.eps``. The image array is returned either way.
    view : {'iso', 'side', 'front', 'bottom'}
    scalars : {'radial_deformation', 'lateral_displacement', 'contact_pressure', 'contact'}
        The colouring quantity (:data:`SCALARS`).
    size : (width, height) [px]
    camera : (azimuth, elevation, zoom), optional
        Look at the view's focal point from ``azimuth`` [deg] (seen from above, from
        the forward axis ``+x`` toward ``+y``; 0 = from the front, 90 = from the
        ``+y`` side) and ``elevation`` [deg] (above the ground; negative: from below,
        through the ground), magnified by ``zoom`` (1: the view's framing). A camera
        position ``[position, focal point, view up]`` (perspective) is accepted too.
    background : color
        A colour name (``'white'``, ``'black'``, ``'lightgray'``), ``'#rrggbb'`` or an
        RGB triple (0-1 or 0-255); the text turns white on a dark background.
    title : bool
        Title block: tire, rim, pressure [bar], load, camber, slip, surface.
    show_surface, show_rim, scalar_bar, ruler, axes : bool
        The support surface (a solid slab in the side and front views, a grid and
        outline in the views from below), the rim, the colour bar, the mm ruler and
        the x/y/z axis triad.
    cmap : str
        Colour map.

    Returns
    -------
    image : (height, width, 3) uint8

    Raises
    ------
    InvalidParameter
        (a ``ValueError``) for an unknown view, scalar, size, camera or suffix,
        before any work.
    """
    fmt = None if path is None else output_format(path)
    opts = _check_options(view, scalars, size, camera)
    bg = vs.parse_colour(background)
    _headless()
    if not isinstance(tire_mesh, TireMesh):
        tire_mesh = build_mesh(tire_mesh)
    parts = dict(surface=show_surface, rim=show_rim, bar=scalar_bar, ruler=ruler, axes=axes)
    win = _scene(tire_mesh, opts, bg, title, cmap, parts)
    try:
        image = win.screenshot()
        if path is not None and fmt is None:
            _save_vector(win, path)
    finally:
        win.close()
    if path is not None and fmt is not None:
        _write_image(path, image, fmt)
    return image


def render_many(items, *, size: tuple[int, int] = (1200, 900), n_around: int = 360) -> list[Path]:
    """Solve, mesh and render several load cases (e.g. in a worker process).

    Parameters
    ----------
    items : list of dict
        Each with ``case`` (:class:`tiremesh.LoadCase`), ``path`` (output file),
        ``view`` and optionally ``zoom`` (relative to the view's framing) and any
        other keyword option of :func:`render`.
    size : (width, height) [px]
    n_around : int
        Sections around the wheel of each mesh.

    Returns
    -------
    list of Path
        The files written, in order.
    """
    from .solver import solve

    out = []
    for item in items:
        opts = dict(item)
        case, path, view = opts.pop("case"), Path(opts.pop("path")), opts.pop("view")
        mesh = build_mesh(solve(case), n_around=n_around)
        zoom = opts.pop("zoom", 1.0)
        cam = view_camera(view, mesh)
        render(mesh, path, view=view, size=size, camera=(cam.azimuth, cam.elevation, zoom), **opts)
        out.append(path)
    return out


@dataclass(frozen=True)
class _Options:
    view: str
    scalars: str
    size: tuple[int, int]
    camera: object


def _check_options(view, scalars, size, camera) -> _Options:
    if view not in VIEWS:
        raise InvalidParameter("view", view, " | ".join(VIEWS))
    if scalars not in SCALARS:
        raise InvalidParameter("scalars", scalars, " | ".join(SCALARS))
    w = v.integer("size[0] (width)", int(size[0]), 16, 8192)
    h = v.integer("size[1] (height)", int(size[1]), 16, 8192)
    return _Options(view, scalars, (w, h), _check_camera(camera))


def _scene(tire_mesh: TireMesh, o: _Options, bg, title: bool, cmap, parts: dict):
    """The window with the tire, surface, rim, overlays and camera set."""
    w, h = o.size
    win = vs.Window(o.size, bg)
    try:
        ink = _ink(bg)
        top = TITLE_FRACTION if title else 0.0
        right = BAR_FRACTION if parts["bar"] else 0.0
        ren = win.renderer((0.0, 0.0, 1.0 - right, 1.0 - top), lights=True)
        # a free perspective camera sees the whole tire; the views their cutaway
        free = isinstance(o.camera, list)
        turned = None if free else _turned(o.camera, o.view, tire_mesh)
        region = None if free else view_region(o.view, tire_mesh, camera=turned)
        below = _from_below(o, tire_mesh)
        geometry = _view_parts(
            tire_mesh, o.view, region, below=below, rim=parts["rim"], surface=parts["surface"]
        )
        colour = _add_model(ren, geometry, o, cmap, ink)
        aspect = (1.0 - right) * w / ((1.0 - top) * h)
        cam = None if free else _camera(o.camera, o.view, tire_mesh, aspect, _points(geometry))
        if parts["ruler"]:
            ruler = (max(8, round(h / 50)), cam, _points(geometry))
            _add_ruler(ren, tire_mesh, o.view, ink, ruler)
        _set_camera(ren, o.camera, cam, tire_mesh)
        if title:
            _overlay_title(win, title_lines(tire_mesh), (0.0, 1.0 - top, 1.0, 1.0), ink, h)
        if parts["bar"]:
            _overlay_bar(win, o.scalars, colour, (1.0 - right, 0.0, 1.0, 1.0 - top), ink, h)
        if parts["axes"]:
            box = (0.0, 0.0, 0.13 * h / w * 1.33, 0.17 * (1 - top))
            _overlay_triad(win, ren, box, ink, max(8, round(h / 55)))
    except BaseException:
        win.close()
        raise
    return win


def _add_model(ren, geometry: dict, o: _Options, cmap, ink):
    """The actors of :func:`_view_parts`' geometry; returns the tire's colouring
    (:func:`_add_tire`)."""
    poly = geometry["tire"]
    colour = _add_tire(ren, poly, o.scalars, cmap)
    for pd in geometry.get("section", []):
        # the section lines, just in front of the cut at x = 0 (no z-fighting)
        section = vs.actor(pd, colour=ink, line_width=3)
        section.SetPosition(0.3, 0.0, 0.0)
        ren.AddActor(section)
    if "surface" in geometry:
        _add_surface(ren, geometry["surface"], o.view)
    for pd, c in zip(geometry["outlines"], (PATCH_COLOR, FOOTPRINT_COLOR), strict=False):
        ren.AddActor(vs.actor(pd, colour=c, line_width=3))
    if "rim" in geometry:
        ren.AddActor(vs.actor(geometry["rim"], colour=RIM_COLOR))
    return colour


def _tire_polydata(tire_mesh: TireMesh):
    """The tire as ``vtkPolyData`` with the arrays of :func:`to_polydata`."""
    m = tire_mesh.mesh
    bar = tire_mesh.patch.pressure / MPA_PER_BAR
    return vs.polydata(
        m.vertices,
        m.faces,
        point_data={k: np.asarray(a, float) for k, a in tire_mesh.point_data.items()},
        cell_data={
            "contact": tire_mesh.face_contact.astype(float),
            "contact_pressure": tire_mesh.face_contact * bar,
        },
    )


def _trimesh_vtk(mesh):
    return vs.polydata(mesh.vertices, mesh.faces)


def _from_below(o: _Options, tire_mesh: TireMesh) -> bool:
    """Whether the camera looks from below the ground (then the ground is a grid)."""
    if isinstance(o.camera, tuple):
        return o.camera[1] < 0
    if isinstance(o.camera, list):
        return o.camera[0][2] < o.camera[1][2]
    return view_camera(o.view, tire_mesh).elevation < 0


def _ink(background) -> tuple[float, float, float]:
    """Black text on a light background, white on a dark one."""
    r, g, b = (float(c) for c in tuple(background)[:3])
    return (0.0, 0.0, 0.0) if 0.299 * r + 0.587 * g + 0.114 * b > 0.5 else (1.0, 1.0, 1.0)


def title_lines(tire_mesh: TireMesh) -> list[str]:
    """The title block: tire and rim; load case; patch size.

    Parameters
    ----------
    tire_mesh : TireMesh

    Returns
    -------
    list of str
        E.g. ``['Schwalbe Big Apple 55-622 on a 18.7 mm rim', '4 bar, 400 N,
        camber 20 deg, slip 0 deg, drum 2.5 m', ...]``.
    """
    p = tire_mesh.patch
    name = p.tire.name or f"tire r0 = {p.tire.tire_radius:.1f} mm"
    return [
        f"{name} on a {p.tire.rim_width:.1f} mm rim",
        f"{p.pressure / MPA_PER_BAR:.3g} bar, {p.vertical_force:.0f} N, "
        f"camber {math.degrees(p.camber):.3g} deg, slip {math.degrees(p.slip):.3g} deg, "
        f"{surface_label(p.surface)}",
        f"patch {p.length:.1f} x {p.width:.1f} mm, {p.area:.0f} mm²; "
        f"deflection {p.deflection:.1f} mm",
    ]


def surface_label(surface) -> str:
    """'flat ground', 'drum 2.5 m', 'disk 3 m (toward)' ...

    Parameters
    ----------
    surface : tiremesh surface

    Returns
    -------
    str
    """
    name = type(surface).__name__.lower()
    d = getattr(surface, "diameter", None)
    if d is None:
        return "flat ground"
    extra = getattr(surface, "curving", None)
    return f"{name} {d / 1000:g} m" + (f" ({extra})" if isinstance(extra, str) else "")


def nice_ticks(lo: float, hi: float, n: int = 6):
    """Rounded colour-bar ticks covering ``[lo, hi]``.

    Parameters
    ----------
    lo, hi : float
        Data range (``lo == hi`` is widened by one unit).
    n : int
        About this many ticks.

    Returns
    -------
    (lo, hi) : float
        The range widened to whole steps.
    ticks : (k,) float
        Multiples of a 1-2-5 step from ``lo`` to ``hi``.
    decimals : int
        Decimals that show the step exactly.
    """
    if not (math.isfinite(lo) and math.isfinite(hi)):
        raise InvalidParameter("range", (lo, hi), "finite numbers")
    if hi - lo < 1e-12 * max(1.0, abs(lo), abs(hi)):
        lo, hi = lo - 0.5, hi + 0.5
    raw = (hi - lo) / max(n - 1, 1)
    mag = 10.0 ** math.floor(math.log10(raw))
    step = next(s * mag for s in (1, 2, 5, 10) if s * mag >= raw * 0.999)
    decimals = next(d for d in range(7) if abs(step * 10**d - round(step * 10**d)) < 1e-6)
    k0, k1 = math.floor(lo / step + 1e-9), math.ceil(hi / step - 1e-9)
    ticks = np.round(np.arange(k0, k1 + 1) * step, decimals) + 0.0  # + 0.0: no "-0"
    a, b = ticks[0], ticks[-1]
    return (float(a), float(b)), ticks, decimals


def _add_tire(ren, poly, scalars: str, cmap: str):
    """The tire coloured by ``scalars`` over a rounded range, its inside (seen
    through a cut) grey; returns the lookup table and the ``ticks, decimals`` of
    :func:`nice_ticks`."""
    from vtkmodules.util.numpy_support import vtk_to_numpy

    cell = scalars in ("contact", "contact_pressure")
    data = poly.GetCellData() if cell else poly.GetPointData()
    values = vtk_to_numpy(data.GetArray(scalars))
    lo = 0.0 if cell else float(values.min())
    (lo, hi), ticks, decimals = nice_ticks(lo, float(values.max()))
    lut = vs.lookup_table(cmap, lo, hi)
    smooth = vs.smooth_normals(poly)
    outside = vs.scalar_actor(smooth, scalars, lut, cell=cell)
    outside.GetProperty().BackfaceCullingOn()
    outside.GetProperty().SetSpecular(0.2)
    inside = vs.actor(smooth, colour=INSIDE_COLOR)
    inside.GetProperty().FrontfaceCullingOn()
    ren.AddActor(outside)
    ren.AddActor(inside)
    return lut, ticks, decimals


def _add_surface(ren, surface, view: str) -> None:
    """The support surface: a grid of lines (seen from below), else a solid slab,
    see-through in the views along the ground (side, front: a drum would hide the
    patch)."""
    if surface.GetNumberOfPolys() == 0:
        a = vs.actor(surface, colour=GRID_COLOR, line_width=1)
        a.GetProperty().SetOpacity(0.6)
        ren.AddActor(a)
        return
    slab = vs.actor(surface, colour=SURFACE_COLOR)
    if view in ("side", "front"):
        slab.GetProperty().SetOpacity(0.35)
    ren.AddActor(slab)


def ground_grid(
    tire_mesh: TireMesh, *, spacing: float = 10.0, half_width: float | None = None
) -> list[np.ndarray]:
    """The support surface under the tire as grid lines ``spacing`` mm apart,
    outline included, lying on the surface (a drum's lines follow its curve).

    Parameters
    ----------
    tire_mesh : TireMesh
    spacing : float [mm]
    half_width : float [mm], optional
        Across the wheel plane (default 2.5 tire radii); whole cells either way.

    Returns
    -------
    list of (k, 3) float [mm]
        Polylines.
    """
    p = tire_mesh.patch
    r0 = p.tire.tire_radius
    half_x = spacing * math.ceil((0.5 * p.length + 2.5 * r0) / spacing)
    half_y = spacing * math.ceil((2.5 * r0 if half_width is None else half_width) / spacing - 1e-9)
    s_fine = np.linspace(-half_x, half_x, 4 * round(2 * half_x / spacing) + 1)

    def on_surface(s, y):
        x = p.surface.roll(s)
        return np.column_stack([x, y, p.surface.height(x) - 0.05])

    out = [
        on_surface(s_fine, np.full(len(s_fine), y))
        for y in np.arange(-half_y, half_y + 1e-9, spacing)
    ]
    out += [
        on_surface(np.full(2, s), np.array([-half_y, half_y]))
        for s in np.arange(-half_x, half_x + 1e-9, spacing)
    ]
    return out


def _set_camera(ren, camera, c: ViewCamera | None, tire_mesh: TireMesh) -> None:
    cam = ren.GetActiveCamera()
    if isinstance(camera, list):
        position, focal, up = camera
    else:
        position, focal, up = c.position(8.0 * tire_mesh.patch.tire.wheel_radius)
        cam.ParallelProjectionOn()
        cam.SetParallelScale(c.scale)
    cam.SetPosition(*position)
    cam.SetFocalPoint(*focal)
    cam.SetViewUp(*up)
    if isinstance(camera, list):
        ren.ResetCamera()
    ren.ResetCameraClippingRange()


def _camera(camera, view: str, tire_mesh: TireMesh, aspect: float, points=None) -> ViewCamera:
    """The view's camera (fitted to ``points``, what it draws, default
    :func:`frame_points`, in :data:`FITTED_VIEWS`, with room for the front view's
    ruler below), turned to ``camera``'s azimuth and elevation and magnified by its
    zoom."""
    c = _turned(camera, view, tire_mesh)
    zoom = 1.0 if camera is None else camera[2]
    pts = frame_points(tire_mesh, view) if points is None else points
    if view in FITTED_VIEWS:
        c = fit_camera(c, pts, aspect=aspect)
        if view == "front":  # the ruler below the tire, its labels under it
            a, b = front_ruler(c, pts, _front_ruler_length(tire_mesh))
            below = np.stack([a, b]) - 0.17 * c.scale * image_axes(c)[1]
            c = fit_camera(c, np.concatenate([pts, below]), aspect=aspect)
    else:  # the bottom view's own scale, wide enough for its ground
        half_y = _bottom_half_extents(tire_mesh.patch)[1]
        scale = max(c.scale, half_y * (1 + FIT_MARGIN) / aspect)
        c = ViewCamera(c.focal, c.azimuth, c.elevation, scale)
    return ViewCamera(c.focal, c.azimuth, c.elevation, c.scale / zoom)


def _turned(camera, view: str, tire_mesh: TireMesh) -> ViewCamera:
    """The view's default camera turned to ``camera``'s (azimuth, elevation, zoom)."""
    c = view_camera(view, tire_mesh)
    if camera is None:
        return c
    return ViewCamera(c.focal, camera[0], camera[1], c.scale)


def _front_ruler_length(tire_mesh: TireMesh) -> float:
    return 20.0 * max(1, int(2.4 * tire_mesh.patch.tire.tire_radius // 20))


def front_ruler(c: ViewCamera, points, length: float) -> tuple[np.ndarray, np.ndarray]:
    """Ends of the front view's ruler: in the image plane through the focal point,
    centred under the framed points and just below them (clear of the tire).

    Parameters
    ----------
    c : ViewCamera
    points : (n, 3) float [mm]
        What the view frames (:func:`frame_points`).
    length : float [mm]

    Returns
    -------
    a, b : (3,) float [mm]
    """
    right, up = image_axes(c)
    pts = np.asarray(points, float)
    u, v = pts @ right, pts @ up
    f = np.asarray(c.focal, float)
    f_u, f_v = f @ right, f @ up
    mid = f + (0.5 * (u.min() + u.max()) - f_u) * right + (v.min() - 0.06 * c.scale - f_v) * up
    return mid - 0.5 * length * right, mid + 0.5 * length * right


def _text(ren, text: str, x: float, y: float, size: int, ink, *, bold=False, align="left"):
    from vtkmodules.vtkRenderingCore import vtkTextActor

    t = vtkTextActor()
    t.SetInput(text)
    prop = t.GetTextProperty()
    prop.SetFontSize(size)
    prop.SetColor(*ink)
    vs.use_font(prop, bold=bold)
    prop.SetJustification({"left": 0, "center": 1, "right": 2}[align])
    prop.SetVerticalJustificationToCentered()
    t.GetPositionCoordinate().SetCoordinateSystemToNormalizedViewport()
    t.SetPosition(x, y)
    ren.AddViewProp(t)
    return t


def _overlay_title(win, lines: list[str], viewport, ink, h: int) -> None:
    ren = win.renderer(viewport)
    n = len(lines)
    size = max(9, round(h * TITLE_FRACTION / (n + 1.6)))
    for i, line in enumerate(lines):
        y = 1.0 - (i + 0.8) / (n + 0.6)
        _text(ren, line, 0.015, y, size if i else round(size * 1.1), ink, bold=i == 0)


def _overlay_bar(win, scalars: str, colour, viewport, ink, h: int) -> None:
    """Vertical colour bar in its own column: label and unit on top, rounded ticks."""
    import textwrap

    from vtkmodules.vtkCommonCore import vtkDoubleArray
    from vtkmodules.vtkRenderingAnnotation import vtkScalarBarActor

    ren = win.renderer(viewport)
    label, unit = SCALARS[scalars]
    lines = textwrap.wrap(label, 12) + ([f"[{unit}]"] if unit else [])
    col_px = (viewport[2] - viewport[0]) * win.size[0]
    # the label fits its column (a glyph is at most ~0.75 font sizes wide)
    size = max(6, min(round(h / 48), int(0.9 * col_px / (0.75 * max(map(len, lines))))))
    rows_h = (viewport[3] - viewport[1]) * h
    for i, line in enumerate(lines):
        _text(ren, line, 0.5, 0.97 - 1.3 * size * (i + 0.5) / rows_h, size, ink, align="center")
    lut, ticks, decimals = colour
    bar = vtkScalarBarActor()
    bar.SetLookupTable(lut)
    bar.SetOrientationToVertical()
    bar.SetNumberOfLabels(len(ticks))
    labels = vtkDoubleArray()
    for t in ticks:
        labels.InsertNextValue(float(t))
    bar.SetUseCustomLabels(True)
    bar.SetCustomLabels(labels)
    bar.SetLabelFormat(f"%.{decimals}f")
    bar.SetTitle("")
    bar.SetTextPositionToSucceedScalarBar()
    bar.GetPositionCoordinate().SetCoordinateSystemToNormalizedViewport()
    bar.SetPosition(0.18, 0.05)
    bar.SetWidth(0.62)
    bar.SetHeight(0.9 - 1.3 * size * (len(lines) + 0.5) / rows_h)
    bar.SetBarRatio(0.3)
    bar.UnconstrainedFontSizeOn()
    tp = bar.GetLabelTextProperty()
    vs.use_font(tp)
    tp.SetFontSize(size)
    tp.SetColor(*ink)
    tp.SetItalic(False)
    tp.SetShadow(False)
    tp.SetBold(False)
    ren.AddViewProp(bar)


def _overlay_triad(win, main, viewport, ink, font_size: int) -> None:
    """x / y / z arrows turning with the main camera (an orientation marker that
    needs no interactor)."""
    from vtkmodules.vtkRenderingAnnotation import vtkAxesActor

    ren = win.renderer(viewport, layer=1)
    axes = vtkAxesActor()
    axes.SetShaftTypeToCylinder()
    axes.SetTotalLength(1.0, 1.0, 1.0)
    axes.SetCylinderRadius(0.04)
    axes.SetConeRadius(0.15)
    captions = (
        axes.GetXAxisCaptionActor2D(),
        axes.GetYAxisCaptionActor2D(),
        axes.GetZAxisCaptionActor2D(),
    )
    for cap in captions:
        prop = cap.GetCaptionTextProperty()
        vs.use_font(prop, bold=True)
        prop.SetColor(*ink)
        prop.SetShadow(False)
        prop.SetItalic(False)
        prop.SetBold(True)
        cap.GetTextActor().SetTextScaleModeToNone()
        prop.SetFontSize(font_size)
    ren.AddActor(axes)
    mc = main.GetActiveCamera()
    pos, focal = np.array(mc.GetPosition()), np.array(mc.GetFocalPoint())
    d = (pos - focal) / np.linalg.norm(pos - focal)
    cam = ren.GetActiveCamera()
    cam.SetFocalPoint(0.4, 0.4, 0.4)
    cam.SetPosition(*(np.array([0.4, 0.4, 0.4]) + 6.0 * d))
    cam.SetViewUp(*mc.GetViewUp())
    cam.ParallelProjectionOn()
    cam.SetParallelScale(1.05)
    ren.ResetCameraClippingRange()


def _add_ruler(ren, tire_mesh: TireMesh, view: str, ink, how) -> None:
    """A mm ruler with three round labels (0, half, full length); the front view's
    under the tire in the image. ``how``: font size, the fitted camera (or None) and
    the points it frames."""
    from vtkmodules.vtkRenderingAnnotation import vtkAxisActor2D

    font_size, cam, points = how
    p = tire_mesh.patch
    r0 = p.tire.tire_radius
    side = -1.0 if p.camber >= 0 else 1.0
    if view == "front":
        length = _front_ruler_length(tire_mesh)
        a, b = (0.0, -length / 2, -0.25 * r0), (0.0, length / 2, -0.25 * r0)
        if cam is not None:
            a, b = (tuple(x) for x in front_ruler(cam, points, length))
    else:
        step = 20.0 if p.length < 150 else 100.0
        length = step * max(1, int(p.length // step))
        if view == "side":
            a, b = (-length / 2, 0.0, -0.3 * r0), (length / 2, 0.0, -0.3 * r0)
        else:
            y = 2.0 * r0 * side
            a, b = (-length / 2, y, -0.1), (length / 2, y, -0.1)
    ruler = vtkAxisActor2D()
    for coord, pt in ((ruler.GetPositionCoordinate(), a), (ruler.GetPosition2Coordinate(), b)):
        coord.SetCoordinateSystemToWorld()
        coord.SetValue(*pt)
    ruler.SetRange(0.0, length)
    ruler.SetTitle("mm")
    ruler.SetFontFactor(0.8)
    ruler.AdjustLabelsOff()
    ruler.SetNumberOfLabels(3)
    ruler.SetLabelFormat("%.0f")
    ruler.SetNumberOfMinorTicks(0)
    ruler.GetProperty().SetColor(*ink)
    ruler.UseFontSizeFromPropertyOn()
    for tp in (ruler.GetLabelTextProperty(), ruler.GetTitleTextProperty()):
        vs.use_font(tp)
        tp.SetColor(*ink)
        tp.SetShadow(False)
        tp.SetItalic(False)
        tp.SetFontSize(font_size)
    ren.AddViewProp(ruler)


def _headless() -> None:
    """Without a display, ask VTK for its EGL window directly (VTK >= 9.4 wheels),
    instead of trying X first and warning 'bad X server connection'."""
    import os

    if not os.environ.get("DISPLAY") and not os.environ.get("WAYLAND_DISPLAY"):
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")


def _write_image(path, image, fmt: str) -> None:
    from PIL import Image

    from .io import atomic_path

    kw = {"quality": 92} if fmt == "JPEG" else {}
    with atomic_path(path) as tmp:
        Image.fromarray(np.asarray(image, np.uint8)).save(tmp, format=fmt, **kw)


def _save_vector(win, path) -> None:
    """PDF / SVG / EPS through GL2PS (text and lines vector, the shaded tire raster)."""
    from .io import atomic_path

    path = Path(path)
    with atomic_path(path) as tmp:
        target = tmp.with_suffix(path.suffix.lower())
        win.save_vector(str(target), "tiremesh render")
        if target != tmp:
            target.replace(tmp)


__all__ = [
    "FORMATS",
    "SCALARS",
    "VIEWS",
    "ViewCamera",
    "ground_grid",
    "nice_ticks",
    "output_format",
    "render",
    "render_many",
    "surface_label",
    "title_lines",
    "to_polydata",
    "view_camera",
    "view_region",
]
