"""Plain VTK plumbing for off-screen renders (no pyvista).

:mod:`tiremesh.render` builds its scenes with these helpers: VTK alone imports in a
fraction of the time pyvista needs (pyvista also imports matplotlib), which matters
when a report starts a worker just to render a few images.

* :func:`polydata` / :func:`lines` - numpy arrays to ``vtkPolyData``;
* :func:`lookup_table` - a colour map as a ``vtkLookupTable`` (viridis built in,
  other names through matplotlib);
* :func:`parse_colour` - 'white', '#202020', (0.1, 0.1, 0.1) or (32, 32, 32);
* :class:`Window` - an off-screen render window: renderers, screenshot, vector
  export (GL2PS).
"""

from __future__ import annotations

import numpy as np

from .errors import InvalidParameter

#: matplotlib's viridis at 17 stops (interpolated linearly in between)
VIRIDIS = (
    "#440154",
    "#48186a",
    "#472d7b",
    "#424086",
    "#3b528b",
    "#33638d",
    "#2c728e",
    "#26828e",
    "#21918c",
    "#1fa088",
    "#28ae80",
    "#3fbc73",
    "#5ec962",
    "#84d44b",
    "#addc30",
    "#d8e219",
    "#fde725",
)


def _vtk():
    """Load the VTK modules the renders need (object factories included)."""
    # imported for their side effect: they register the OpenGL back end, text
    # rendering and the default interactor style with VTK's object factories
    import importlib

    for name in ("vtkRenderingOpenGL2", "vtkRenderingFreeType", "vtkInteractionStyle"):
        importlib.import_module(f"vtkmodules.{name}")


def font_file(bold: bool = False) -> str | None:
    """A DejaVu Sans TrueType file (the system's, else matplotlib's copy), or None.

    VTK's built-in sans font draws square brackets like parentheses ('[mm]' reads
    '(mm)'); DejaVu Sans does not.

    Parameters
    ----------
    bold : bool

    Returns
    -------
    str or None
    """
    import importlib.util
    from pathlib import Path

    name = "DejaVuSans-Bold.ttf" if bold else "DejaVuSans.ttf"
    places = [Path("/usr/share/fonts/truetype/dejavu")]
    spec = importlib.util.find_spec("matplotlib")
    if spec and spec.submodule_search_locations:
        places.append(Path(spec.submodule_search_locations[0]) / "mpl-data" / "fonts" / "ttf")
    return next((str(d / name) for d in places if (d / name).is_file()), None)


def use_font(prop, *, bold: bool = False) -> None:
    """Set a ``vtkTextProperty`` to DejaVu Sans (:func:`font_file`) when available.

    Parameters
    ----------
    prop : vtkTextProperty
    bold : bool

    Returns
    -------
    None
        ``prop`` is changed in place.
    """
    path = font_file(bold)
    if path is None:
        prop.SetFontFamilyToArial()
        prop.SetBold(bold)
        return
    prop.SetFontFamily(4)  # VTK_FONT_FILE
    prop.SetFontFile(path)


def _hex_rgb(h: str) -> tuple[float, float, float]:
    h = h.lstrip("#")
    if len(h) == 3:
        h = "".join(c * 2 for c in h)
    return tuple(int(h[i : i + 2], 16) / 255.0 for i in (0, 2, 4))


def parse_colour(colour, *, name: str = "background") -> tuple[float, float, float]:
    """An RGB triple in [0, 1] from a name, a hex string or a tuple.

    Parameters
    ----------
    colour : str or sequence of 3 numbers
        A VTK / CSS colour name ('white', 'black', 'lightgray'), '#rrggbb' or '#rgb',
        floats in [0, 1] or integers in [0, 255].
    name : str
        The parameter named in the error (the CLI passes ``--background``).

    Returns
    -------
    (float, float, float)

    Raises
    ------
    InvalidParameter
    """
    if isinstance(colour, str):
        c = colour.strip()
        if c.startswith("#") and len(c) in (4, 7):
            try:
                return _hex_rgb(c)
            except ValueError:
                pass
        from vtkmodules.vtkCommonColor import vtkNamedColors

        named = vtkNamedColors()
        if named.ColorExists(c.lower()):
            return tuple(named.GetColor3d(c.lower()))
    else:
        try:
            vals = [float(x) for x in colour]
        except (TypeError, ValueError):
            vals = []
        if len(vals) == 3 and all(0 <= x <= 255 for x in vals):
            scale = 255.0 if any(x > 1 for x in vals) else 1.0
            return tuple(x / scale for x in vals)
    raise InvalidParameter(
        name, colour, "a colour name, '#rrggbb' or an RGB triple (0-1 or 0-255)"
    )


def lookup_table(cmap: str, lo: float, hi: float, n: int = 256):
    """A ``vtkLookupTable`` of ``n`` colours over ``[lo, hi]``.

    Parameters
    ----------
    cmap : str
        'viridis' (built in) or any matplotlib colour-map name (imports matplotlib).
    lo, hi : float
    n : int

    Returns
    -------
    vtkLookupTable
    """
    from vtkmodules.vtkCommonCore import vtkLookupTable

    t = np.linspace(0.0, 1.0, n)
    if cmap == "viridis":
        stops = np.array([_hex_rgb(h) for h in VIRIDIS])
        at = np.linspace(0.0, 1.0, len(stops))
        rgb = np.column_stack([np.interp(t, at, stops[:, k]) for k in range(3)])
    else:
        import matplotlib

        try:
            rgb = np.asarray(matplotlib.colormaps[cmap](t))[:, :3]
        except KeyError as exc:
            raise InvalidParameter("cmap", cmap, "a matplotlib colour-map name") from exc
    lut = vtkLookupTable()
    lut.SetNumberOfTableValues(n)
    for i, (r, g, b) in enumerate(rgb):
        lut.SetTableValue(i, float(r), float(g), float(b), 1.0)
    lut.SetRange(lo, hi)
    lut.Build()
    return lut


def _cell_array(counts, connectivity):
    from vtkmodules.util.numpy_support import numpy_to_vtkIdTypeArray
    from vtkmodules.vtkCommonDataModel import vtkCellArray

    offsets = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
    cells = vtkCellArray()
    cells.SetData(
        numpy_to_vtkIdTypeArray(offsets, deep=True),
        numpy_to_vtkIdTypeArray(np.ascontiguousarray(connectivity, np.int64).ravel(), deep=True),
    )
    return cells


def _points(points):
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonCore import vtkPoints

    pts = vtkPoints()
    pts.SetData(numpy_to_vtk(np.ascontiguousarray(points, np.float64), deep=True))
    return pts


def polydata(points, faces, *, point_data=None, cell_data=None):
    """A triangle surface as ``vtkPolyData``.

    Parameters
    ----------
    points : (n, 3) float
    faces : (m, 3) int
    point_data, cell_data : dict of str to array, optional
        Named per-point / per-cell arrays.

    Returns
    -------
    vtkPolyData
    """
    from vtkmodules.util.numpy_support import numpy_to_vtk
    from vtkmodules.vtkCommonDataModel import vtkPolyData

    faces = np.asarray(faces)
    pd = vtkPolyData()
    pd.SetPoints(_points(points))
    pd.SetPolys(_cell_array(np.full(len(faces), faces.shape[1]), faces))
    for data, target in ((point_data, pd.GetPointData()), (cell_data, pd.GetCellData())):
        for name, arr in (data or {}).items():
            a = numpy_to_vtk(np.ascontiguousarray(arr, np.float64), deep=True)
            a.SetName(name)
            target.AddArray(a)
    return pd


def lines(polylines):
    """Polylines as ``vtkPolyData`` line cells.

    Parameters
    ----------
    polylines : list of (k, 3) float
        Each a polyline (k >= 2).

    Returns
    -------
    vtkPolyData
    """
    from vtkmodules.vtkCommonDataModel import vtkPolyData

    pts = np.concatenate(polylines)
    counts = [len(p) for p in polylines]
    pd = vtkPolyData()
    pd.SetPoints(_points(pts))
    pd.SetLines(_cell_array(counts, np.arange(len(pts))))
    return pd


def _plane_x0():
    """The plane ``x = 0`` (normal +x) as a VTK implicit function."""
    from vtkmodules.vtkCommonDataModel import vtkPlane

    plane = vtkPlane()
    plane.SetOrigin(0.0, 0.0, 0.0)
    plane.SetNormal(1.0, 0.0, 0.0)
    return plane


def clip_x(pd, *, keep_negative: bool = True):
    """The part of a surface at ``x <= 0`` (or ``x >= 0``), data interpolated.

    Parameters
    ----------
    pd : vtkPolyData
        A surface in the ground frame [mm].
    keep_negative : bool
        Keep the rear half (``x <= 0``); False keeps the front half.

    Returns
    -------
    vtkPolyData
        The kept half, cut cells split at ``x = 0``.
    """
    from vtkmodules.vtkFiltersCore import vtkClipPolyData

    clip = vtkClipPolyData()
    clip.SetInputData(pd)
    clip.SetClipFunction(_plane_x0())
    clip.SetInsideOut(keep_negative)
    clip.Update()
    return clip.GetOutput()


def clip_halfspaces(pd, planes):
    """The part of a surface (or of lines) inside half-spaces, data interpolated: a
    cutaway with exact cut edges.

    Parameters
    ----------
    pd : vtkPolyData
        In the ground frame [mm].
    planes : sequence of (normal, offset)
        Keep the points ``p`` with ``normal . p <= offset`` for every plane
        (``normal``: (3,) float, ``offset`` [mm]).

    Returns
    -------
    vtkPolyData
        The cells inside, cut cells split at the planes.
    """
    from vtkmodules.vtkCommonDataModel import vtkPlane
    from vtkmodules.vtkFiltersCore import vtkClipPolyData

    for normal, offset in planes:
        n = np.asarray(normal, float)
        plane = vtkPlane()
        plane.SetNormal(*n)
        plane.SetOrigin(*(n * (offset / float(n @ n))))
        clip = vtkClipPolyData()
        clip.SetInputData(pd)
        clip.SetClipFunction(plane)
        clip.SetInsideOut(True)  # keep the side the normal points away from
        clip.Update()
        pd = clip.GetOutput()
    return pd


def points_of(pd) -> np.ndarray:
    """The points of a polydata as an array.

    Parameters
    ----------
    pd : vtkPolyData

    Returns
    -------
    (n, 3) float
        Empty (0, 3) when it has no point.
    """
    from vtkmodules.util.numpy_support import vtk_to_numpy

    pts = pd.GetPoints()
    if pts is None or pts.GetNumberOfPoints() == 0:
        return np.empty((0, 3))
    return np.asarray(vtk_to_numpy(pts.GetData()), float).reshape(-1, 3)


def slice_x(pd):
    """The section of a surface by the plane ``x = 0``.

    Parameters
    ----------
    pd : vtkPolyData
        A surface in the ground frame [mm].

    Returns
    -------
    vtkPolyData
        Line cells where the surface crosses ``x = 0``.
    """
    from vtkmodules.vtkFiltersCore import vtkCutter

    cut = vtkCutter()
    cut.SetInputData(pd)
    cut.SetCutFunction(_plane_x0())
    cut.Update()
    return cut.GetOutput()


def smooth_normals(pd):
    """Point normals for smooth shading (no splitting, orientation kept).

    Parameters
    ----------
    pd : vtkPolyData

    Returns
    -------
    vtkPolyData
        With point normals.
    """
    from vtkmodules.vtkFiltersCore import vtkPolyDataNormals

    f = vtkPolyDataNormals()
    f.SetInputData(pd)
    f.SplittingOff()
    f.ConsistencyOff()
    f.AutoOrientNormalsOff()
    f.ComputePointNormalsOn()
    f.ComputeCellNormalsOff()
    f.Update()
    return f.GetOutput()


def actor(pd, *, colour=None, line_width=None, opacity=1.0):
    """An actor of a polydata in one colour (scalars off).

    Parameters
    ----------
    pd : vtkPolyData
    colour : (float, float, float), optional
    line_width : float, optional [px]
        For lines (drawn unlit).
    opacity : float

    Returns
    -------
    vtkActor
    """
    from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper

    m = vtkPolyDataMapper()
    m.SetInputData(pd)
    m.ScalarVisibilityOff()
    a = vtkActor()
    a.SetMapper(m)
    prop = a.GetProperty()
    if colour is not None:
        prop.SetColor(*colour)
    if line_width is not None:
        prop.SetLineWidth(line_width)
        prop.SetLighting(False)
    prop.SetOpacity(opacity)
    return a


def scalar_actor(pd, name: str, lut, *, cell: bool):
    """An actor coloured by the named point (or cell) array through ``lut``.

    Parameters
    ----------
    pd : vtkPolyData
    name : str
        Array name.
    lut : vtkLookupTable
    cell : bool
        A cell array (else a point array).

    Returns
    -------
    vtkActor
    """
    from vtkmodules.vtkRenderingCore import vtkActor, vtkPolyDataMapper

    m = vtkPolyDataMapper()
    m.SetInputData(pd)
    m.SetLookupTable(lut)
    m.UseLookupTableScalarRangeOn()
    if cell:
        m.SetScalarModeToUseCellFieldData()
    else:
        m.SetScalarModeToUsePointFieldData()
    m.SelectColorArray(name)
    m.ScalarVisibilityOn()
    m.InterpolateScalarsBeforeMappingOn()
    a = vtkActor()
    a.SetMapper(m)
    return a


class Window:
    """An off-screen render window of ``size`` pixels.

    Parameters
    ----------
    size : (int, int) [px]
    background : (float, float, float)
    """

    def __init__(self, size, background) -> None:
        _vtk()
        from vtkmodules.vtkRenderingCore import vtkRenderWindow

        self.size = (int(size[0]), int(size[1]))
        self.background = tuple(background)
        self.win = vtkRenderWindow()
        self.win.SetOffScreenRendering(1)
        self.win.SetSize(*self.size)
        self.win.SetNumberOfLayers(2)
        self.win.SetMultiSamples(0)

    def renderer(self, viewport=(0.0, 0.0, 1.0, 1.0), *, layer: int = 0, lights: bool = False):
        """Add a renderer over ``viewport``.

        Parameters
        ----------
        viewport : tuple of 4 float, optional
            Normalized ``(x0, y0, x1, y1)`` of the window.
        layer : int, optional
            0 for the scene, 1 for an overlay drawn over it.
        lights : bool, optional
            Use a light kit instead of VTK's automatic headlight.

        Returns
        -------
        vtkRenderer
        """
        from vtkmodules.vtkRenderingCore import vtkLightKit, vtkRenderer

        ren = vtkRenderer()
        ren.SetViewport(*viewport)
        ren.SetBackground(*self.background)
        ren.SetLayer(layer)
        if layer:
            ren.SetPreserveColorBuffer(1)
        if lights:
            ren.AutomaticLightCreationOff()
            vtkLightKit().AddLightsToRenderer(ren)
        self.win.AddRenderer(ren)
        return ren

    def screenshot(self) -> np.ndarray:
        """Render and read the image.

        Returns
        -------
        (height, width, 3) uint8
        """
        from vtkmodules.util.numpy_support import vtk_to_numpy
        from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter

        self.win.Render()
        grab = vtkWindowToImageFilter()
        grab.SetInput(self.win)
        grab.SetInputBufferTypeToRGB()
        grab.ReadFrontBufferOff()
        grab.Update()
        w, h = self.size
        img = vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars()).reshape(h, w, 3)
        return np.ascontiguousarray(img[::-1])

    def save_vector(self, path: str, title: str) -> None:
        """Write PDF, SVG or EPS (from the suffix) through GL2PS: text and lines as
        vectors, shaded surfaces as an embedded raster.

        Parameters
        ----------
        path : str
            Output file; its suffix picks the format (other than pdf/svg: EPS).
        title : str
            Document title written into the file.
        """
        import importlib

        from vtkmodules.vtkIOExportGL2PS import vtkGL2PSExporter

        importlib.import_module("vtkmodules.vtkRenderingGL2PSOpenGL2")  # the GL2PS back end

        stem, suffix = path.rsplit(".", 1)
        exp = vtkGL2PSExporter()
        exp.SetRenderWindow(self.win)
        exp.SetFilePrefix(stem)
        setters = {"pdf": exp.SetFileFormatToPDF, "svg": exp.SetFileFormatToSVG}
        setters.get(suffix.lower(), exp.SetFileFormatToEPS)()
        exp.SetTitle(title)
        exp.CompressOff()
        exp.Write3DPropsAsRasterImageOn()
        if suffix.lower() != "svg":
            # PDF and EPS fonts have 8-bit encodings without the glyphs of 'mm²' and
            # DejaVu Sans: their text is drawn as outlines (SVG keeps UTF-8 text)
            exp.TextAsPathOn()
        exp.Write()

    def close(self) -> None:
        """Release the window's graphics resources."""
        self.win.Finalize()


__all__ = [
    "VIRIDIS",
    "Window",
    "actor",
    "clip_halfspaces",
    "clip_x",
    "font_file",
    "lines",
    "lookup_table",
    "parse_colour",
    "points_of",
    "polydata",
    "scalar_actor",
    "slice_x",
    "smooth_normals",
    "use_font",
]
