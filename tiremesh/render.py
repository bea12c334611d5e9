"""Off-screen renders of the deformed tire (pyvista, no display needed).

Views: ``iso`` (front-left, above the ground), ``side`` (along the axle),
``front`` (against the rolling direction, showing the section bulges) and
``bottom`` (from below through the support surface, showing the contact patch).
The tire is coloured by a per-vertex quantity of :class:`tiremesh.mesh.TireMesh`
with a scalar bar; a ruler gives the length scale in mm.
"""

from __future__ import annotations

import numpy as np

from . import _validate as v
from .case import LoadCase
from .errors import InvalidParameter
from .mesh import TireMesh, build_mesh, rim_mesh, support_mesh
from .solver import ContactPatch

VIEWS = ("iso", "side", "front", "bottom")
SCALARS = {
    "radial_deformation": "radial deformation [mm]",
    "lateral_displacement": "lateral displacement [mm]",
    "contact": "contact",
    "section": "section index",
}
SURFACE_COLOR = (0.80, 0.80, 0.76)


def to_polydata(tire_mesh: TireMesh):
    """The mesh as ``pyvista.PolyData`` with its point data arrays."""
    import pyvista as pv

    faces = np.column_stack([np.full(len(tire_mesh.mesh.faces), 3), tire_mesh.mesh.faces])
    poly = pv.PolyData(np.asarray(tire_mesh.mesh.vertices, float), faces.ravel())
    for name, arr in tire_mesh.point_data.items():
        poly.point_data[name] = np.asarray(arr)
    poly.cell_data["contact"] = tire_mesh.face_contact.astype(np.uint8)
    return poly


def _trimesh_to_pv(mesh):
    import pyvista as pv

    faces = np.column_stack([np.full(len(mesh.faces), 3), mesh.faces])
    return pv.PolyData(np.asarray(mesh.vertices, float), faces.ravel())


def _camera(view: str, tire_mesh: TireMesh):
    """Camera ``[position, focal point, view up]`` and parallel scale (None: perspective)."""
    p = tire_mesh.patch
    R, r0 = p.tire.wheel_radius, p.tire.tire_radius
    side = -1.0 if p.camber >= 0 else 1.0  # look from the side the wheel leans away from
    if view == "iso":
        focal = np.array([0.0, 0.0, 1.0 * r0])
        span = max(p.length, 5 * r0)
        pos = focal + np.array([1.0, 1.1 * side, 0.75]) * 1.9 * span
        return [tuple(pos), tuple(focal), (0, 0, 1)], None
    if view == "side":
        focal = np.array([0.0, 0.0, 1.6 * r0])
        pos = focal + np.array([0.0, side, 0.0]) * 4.0 * R
        return [tuple(pos), tuple(focal), (0, 0, 1)], 0.45 * max(p.length, 6 * r0)
    if view == "front":
        focal = np.array([0.0, 0.0, 1.3 * r0])
        pos = focal + np.array([1.0, 0.0, 0.0]) * 4.0 * R
        return [tuple(pos), tuple(focal), (0, 0, 1)], 1.6 * r0
    # bottom: looking up through the (translucent) surface, forward = up in the image
    focal = np.array([0.0, 0.0, 0.0])
    pos = focal + np.array([0.0, 0.0, -1.0]) * 4.0 * R
    return [tuple(pos), tuple(focal), (1, 0, 0)], 0.6 * p.length + 2 * r0


def render(
    tire_mesh: TireMesh | ContactPatch | LoadCase,
    path=None,
    *,
    view: str = "iso",
    scalars: str = "radial_deformation",
    size: tuple[int, int] = (1200, 900),
    camera=None,
    show_surface: bool = True,
    show_rim: bool = True,
    scalar_bar: bool = True,
    ruler: bool = True,
    cmap: str = "viridis",
):
    """Render the deformed tire off-screen.

    Parameters
    ----------
    tire_mesh : TireMesh, ContactPatch or LoadCase
        The mesh; a patch or a load case (solved first) is meshed with the defaults
        of :func:`tiremesh.mesh.build_mesh`.
    path : str or Path, optional
        PNG file to write (atomically); the image array is returned either way.
    view : {'iso', 'side', 'front', 'bottom'}
    scalars : {'radial_deformation', 'lateral_displacement', 'contact', 'section'}
    size : (width, height) [px]
    camera : pyvista camera position ``[position, focal point, view up]``, optional
        Overrides ``view``.
    show_surface, show_rim, scalar_bar, ruler : bool

    Returns
    -------
    image : (height, width, 3) uint8
    """
    _headless()
    import pyvista as pv

    if view not in VIEWS:
        raise InvalidParameter("view", view, " | ".join(VIEWS))
    if scalars not in SCALARS:
        raise InvalidParameter("scalars", scalars, " | ".join(SCALARS))
    w = v.integer("size[0] (width)", int(size[0]), 16, 8192)
    h = v.integer("size[1] (height)", int(size[1]), 16, 8192)
    if not isinstance(tire_mesh, TireMesh):
        tire_mesh = build_mesh(tire_mesh)

    poly = to_polydata(tire_mesh)
    if view == "front" and camera is None:
        # cut at the central section: the cut edge is the Rotta section (Figure 5-5)
        poly = poly.clip(normal=(1.0, 0.0, 0.0), origin=(0.0, 0.0, 0.0), invert=True)
    pl = pv.Plotter(off_screen=True, window_size=(w, h))
    try:
        pl.set_background("white")
        _add_tire(pl, poly, scalars, cmap, scalar_bar)
        if show_surface:
            ground = _trimesh_to_pv(support_mesh(tire_mesh.patch, sink=0.3))
            opacity = 0.25 if view == "bottom" else 1.0
            pl.add_mesh(ground, color=SURFACE_COLOR, opacity=opacity, smooth_shading=False)
        if show_rim:
            pl.add_mesh(_trimesh_to_pv(rim_mesh(tire_mesh)), color=(0.7, 0.72, 0.75), metallic=0.5)
        if ruler:
            _add_ruler(pl, tire_mesh, view)
        _set_camera(pl, camera, view, tire_mesh)
        image = pl.screenshot(return_img=True)
    finally:
        pl.close()
    if path is not None:
        _write_png(path, image)
    return image


def _add_tire(pl, poly, scalars: str, cmap: str, scalar_bar: bool) -> None:
    bar = dict(
        title=SCALARS[scalars],
        color="black",
        vertical=False,
        position_x=0.2,
        position_y=0.87,
        width=0.6,
        height=0.06,
        fmt="%.2f",
    )
    pl.add_mesh(
        poly,
        scalars=scalars,
        cmap=cmap,
        smooth_shading=True,
        show_scalar_bar=scalar_bar,
        scalar_bar_args=bar,
        specular=0.2,
    )


def _set_camera(pl, camera, view: str, tire_mesh: TireMesh) -> None:
    if camera is not None:
        pl.camera_position = camera
        return
    position, scale = _camera(view, tire_mesh)
    pl.camera_position = position
    if scale is not None:
        pl.enable_parallel_projection()
        pl.camera.parallel_scale = scale
    else:
        pl.camera.view_angle = 30.0


def _add_ruler(pl, tire_mesh: TireMesh, view: str) -> None:
    p = tire_mesh.patch
    r0 = p.tire.tire_radius
    side = -1.0 if p.camber >= 0 else 1.0
    if view == "front":
        length = 10.0 * max(1, int(2.4 * r0 // 10))
        a, b = (0.0, -length / 2, -0.12 * r0), (0.0, length / 2, -0.12 * r0)
    else:
        step = 10.0 if p.length < 150 else 50.0
        length = step * max(1, int(p.length // step))
        if view == "side":
            a, b = (-length / 2, 0.0, -0.25 * r0), (length / 2, 0.0, -0.25 * r0)
        else:
            y = 2.2 * r0 * side
            a, b = (-length / 2, y, 0.0), (length / 2, y, 0.0)
    pl.add_ruler(
        a,
        b,
        title="mm",
        number_labels=3,
        font_size_factor=0.8,
        label_color="black",
        tick_color="black",
        label_format="%.0f",
    )


def _headless() -> None:
    """Without a display, ask VTK for its EGL window directly (VTK >= 9.4 wheels),
    instead of trying X first and warning 'bad X server connection'."""
    import os

    if not os.environ.get("DISPLAY") and not os.environ.get("WAYLAND_DISPLAY"):
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")


def _write_png(path, image) -> None:
    from PIL import Image

    from .io import atomic_path

    with atomic_path(path) as tmp:
        Image.fromarray(np.asarray(image, np.uint8)).save(tmp, format="PNG")
