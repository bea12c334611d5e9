"""Contact-patch metrics: one definition shared by model patches and ink prints.

The print measurements of Dressel 2013, section 4.1.1 (length, width and area of the
patch, and the load over the area) made into definitions that apply to any region.
Vocabulary of footprint practice: *gross* area is the area inside the outline (the
convex hull), *net* area the inked / contacting area, *net-to-gross* their ratio
(1 - void ratio). Length and width are the extents of the hull along and across the
patch axis; the footprint *shape factor* is the centre-line length over the mean
length at the shoulder stations.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .._tol import tol
from ..errors import InvalidInput
from .ellipse import (
    EllipseFit,
    axis_angle,
    ellipse_from_moments,
    fit_ellipse_direct,
    polygon_moments,
)

#: lateral stations as fractions of the half width (centre line, mid, shoulders)
DEFAULT_STATIONS = (-0.8, -0.5, 0.0, 0.5, 0.8)
#: points per hull boundary for the direct ellipse fit
BOUNDARY_SAMPLES = 360


@dataclass(frozen=True)
class PatchMetrics:
    """A measured contact patch (Dressel 2013, section 4.1.1); lengths in the units
    of the input coordinates, mm throughout this project.

    Parameters
    ----------
    area : float [mm^2]
        Net area of the region (ink / contact).
    hull_area : float [mm^2]
        Gross area (convex hull).
    solidity : float [-]
        ``area / hull_area`` (net-to-gross ratio).
    perimeter : float [mm]
        Perimeter of the hull.
    centroid : (2,) float [mm]
        Area centroid of the region.
    orientation : float [rad]
        Patch axis direction from +x, in (-pi/2, pi/2].
    length, width : float [mm]
        Hull extent along and across the axis.
    aspect_ratio : float [-]
        ``length / width``.
    stations : (k,) float [-]
        Lateral stations, fractions of the half width from the hull's mid line.
    station_lengths : (k,) float [mm]
        Hull chord length along the axis at each station.
    shape_factor : float [-]
        Centre-line length over the mean length at the outermost stations.
    ellipse_direct, ellipse_moments : EllipseFit
        Direct fit to the hull boundary; equal-moments ellipse of the hull.
    """

    area: float
    hull_area: float
    solidity: float
    perimeter: float
    centroid: tuple[float, float]
    orientation: float
    length: float
    width: float
    aspect_ratio: float
    stations: np.ndarray = field(repr=False)
    station_lengths: np.ndarray = field(repr=False)
    shape_factor: float
    ellipse_direct: EllipseFit
    ellipse_moments: EllipseFit

    def __repr__(self) -> str:
        return (
            f"PatchMetrics(length={self.length:.4g}, width={self.width:.4g}, "
            f"area={self.area:.5g}, hull_area={self.hull_area:.5g}, "
            f"shape_factor={self.shape_factor:.3g})"
        )

    def _repr_html_(self) -> str:
        """A summary table for notebooks (escaped)."""
        import html

        rows = "".join(
            f"<tr><th style='text-align:left'>{html.escape(k)}</th>"
            f"<td style='text-align:right'>{v:.5g}</td></tr>"
            for k, v in self.as_row().items()
            if isinstance(v, float | int)
        )
        return f"<table><caption>PatchMetrics</caption>{rows}</table>"

    def as_row(self, prefix: str = "", unit: str = "mm") -> dict[str, float]:
        """The metrics as a flat table row; names carry the unit.

        Parameters
        ----------
        prefix : str
            Put before every name (e.g. ``'print_'``).
        unit : str
            Length unit for the names (``length_mm``, ``area_mm2``).

        Returns
        -------
        dict of str to float
            Areas, lengths, angles [deg] and ratios; the two ellipses as
            ``ellipse_*`` (direct fit) and ``moments_ellipse_*``.
        """
        u, u2 = f"_{unit}", f"_{unit}2"
        row = {
            f"{prefix}area{u2}": self.area,
            f"{prefix}hull_area{u2}": self.hull_area,
            f"{prefix}net_to_gross": self.solidity,
            f"{prefix}perimeter{u}": self.perimeter,
            f"{prefix}centroid_x{u}": self.centroid[0],
            f"{prefix}centroid_y{u}": self.centroid[1],
            f"{prefix}angle_deg": float(np.degrees(self.orientation)),
            f"{prefix}length{u}": self.length,
            f"{prefix}width{u}": self.width,
            f"{prefix}aspect_ratio": self.aspect_ratio,
            f"{prefix}shape_factor": self.shape_factor,
        }
        for name, e in (
            ("ellipse", self.ellipse_direct),
            ("moments_ellipse", self.ellipse_moments),
        ):
            row[f"{prefix}{name}_length{u}"] = e.length
            row[f"{prefix}{name}_width{u}"] = e.width
            row[f"{prefix}{name}_area{u2}"] = e.area if e else np.nan
            row[f"{prefix}{name}_angle_deg"] = float(np.degrees(e.angle))
        return row


def as_geometry(obj):
    """A region as a shapely geometry.

    Parameters
    ----------
    obj : shapely Polygon / MultiPolygon, (n, 2) float [mm], or ContactPatch
        A region; a closed outline (n >= 3 points); a solved
        :class:`tiremesh.ContactPatch` (the footprint its load case asks for: the
        plain Rotta outline by default, the rounded print footprint with
        ``footprint='rounded'``); or any object with an ``outline`` attribute.

    Returns
    -------
    shapely Polygon or MultiPolygon

    Raises
    ------
    InvalidInput
        Another geometry type, or an outline that is not a finite (n >= 3, 2) array.
    """
    import shapely

    if hasattr(obj, "footprint") and hasattr(obj, "case"):
        obj = obj.footprint.outline  # a solved patch: the footprint its case asks for
    elif hasattr(obj, "outline") and not hasattr(obj, "geom_type"):
        obj = obj.outline
    if hasattr(obj, "geom_type"):
        if obj.geom_type not in ("Polygon", "MultiPolygon"):
            raise InvalidInput("region", obj.geom_type, "a Polygon or MultiPolygon")
        return obj
    pts = np.asarray(obj, float)
    if pts.ndim != 2 or pts.shape[1] != 2 or len(pts) < 3 or not np.all(np.isfinite(pts)):
        raise InvalidInput("region", f"array {pts.shape}", "a finite (n >= 3, 2) outline")
    return shapely.Polygon(pts).buffer(0)


def _principal_angle(hull) -> float:
    """Major principal axis of a region's second moments, from +x [rad]."""
    m = polygon_moments(hull)
    if m is None:
        return 0.0
    _, vec = np.linalg.eigh(m[2])
    return axis_angle(*vec[:, 1])


def resample_ring(coords, n: int) -> np.ndarray:
    """Points uniformly spaced by arc length along a closed ring.

    Parameters
    ----------
    coords : (m, 2) float [mm]
        Closed ring (first point repeated at the end).
    n : int
        Number of points wanted.

    Returns
    -------
    points : (n, 2) float [mm]
        Starting at the ring's first point; the end point is not repeated.
    """
    c = np.asarray(coords, float)
    seg = np.linalg.norm(np.diff(c, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    t = np.linspace(0.0, s[-1], n, endpoint=False)
    return np.column_stack([np.interp(t, s, c[:, 0]), np.interp(t, s, c[:, 1])])


def _check_options(stations, boundary_samples) -> np.ndarray:
    """``stations`` as an array, after checking both options of :func:`measure`."""
    st = np.asarray(stations, float)
    if st.ndim != 1 or st.size == 0 or np.any(np.abs(st) >= 1) or not np.all(np.isfinite(st)):
        raise InvalidInput("stations", stations, "fractions of the half width in (-1, 1)")
    if not isinstance(boundary_samples, int | np.integer) or boundary_samples < 5:
        raise InvalidInput("boundary_samples", boundary_samples, "an integer >= 5")
    return st


def _extents(hull, angle: float, stations: np.ndarray):
    """Length, width and station chords of the hull along / across ``angle``."""
    import shapely
    from shapely import affinity

    # rotate so the axis is +x: extents and station chords are then axis-aligned
    rot = affinity.rotate(hull, -angle, origin=(0, 0), use_radians=True)
    x0, y0, x1, y1 = rot.bounds
    width = y1 - y0
    ys = 0.5 * (y0 + y1) + stations * 0.5 * width
    lines = shapely.linestrings([[[x0 - 1, y], [x1 + 1, y]] for y in ys])
    chords = np.array([rot.intersection(line).length for line in lines])
    return float(x1 - x0), float(width), chords


def _net(geom, hull, net_area, net_centroid):
    """Net area and centroid: the region's own, or the ones given."""
    area = float(geom.area) if net_area is None else float(net_area)
    if not (np.isfinite(area) and 0 < area <= hull.area * (1 + tol.area_rtol)):
        raise InvalidInput("net_area", net_area, f"(0, hull area = {hull.area:.6g}]")
    if net_centroid is None:
        c = geom.centroid
        return area, (float(c.x), float(c.y))
    return area, tuple(map(float, net_centroid))


def measure(
    region,
    *,
    axis: float | None = None,
    stations=DEFAULT_STATIONS,
    net_area: float | None = None,
    net_centroid: tuple[float, float] | None = None,
    boundary_samples: int = BOUNDARY_SAMPLES,
) -> PatchMetrics:
    """Measure a contact patch: length, width, areas, shape factor, ellipses.

    The print metrics of Dressel 2013, section 4.1.1, applied alike to ink prints
    and to the model's patches.

    Parameters
    ----------
    region : shapely Polygon / MultiPolygon, (n, 2) float [mm], or ContactPatch
        The net region (ink, or the model's contact patch); see :func:`as_geometry`.
    axis : float [rad], optional
        Patch axis (rolling direction) from +x. Default: the major principal axis of
        the hull (prints may be rotated on the sheet).
    stations : (k,) float [-]
        Lateral stations in fractions of the half width (|f| < 1).
    net_area : float [mm^2], optional
        Net (ink) area when the region passed is only the outline (an ink print's
        hull, with the ink counted in pixels).
    net_centroid : (2,) float [mm], optional
        Net (ink) centroid, likewise.
    boundary_samples : int
        Points, uniform in arc length, taken along the hull boundary for the direct
        ellipse fit (so the fit does not depend on how the outline was sampled).

    Returns
    -------
    PatchMetrics
        Lengths [mm], areas [mm^2] and the axis [rad] in the input's coordinates.

    Raises
    ------
    InvalidInput
        An empty region, stations outside (-1, 1), a non-finite axis, a net area
        outside (0, hull area], or fewer than 5 boundary samples.

    Examples
    --------
    >>> import shapely
    >>> import contactpatch as cp
    >>> m = cp.measure(shapely.box(0, 0, 100, 10))
    >>> round(m.length, 6), round(m.width, 6), round(m.hull_area, 6)
    (100.0, 10.0, 1000.0)
    >>> round(m.shape_factor, 6), round(m.solidity, 6)
    (1.0, 1.0)
    """
    geom = as_geometry(region)
    if geom.is_empty or geom.area <= 0:
        raise InvalidInput("region", "empty", "a region with positive area")
    st = _check_options(stations, boundary_samples)
    hull = geom.convex_hull
    ang = _principal_angle(hull) if axis is None else float(axis)
    if not np.isfinite(ang):
        raise InvalidInput("axis", axis, "a finite angle in radians")
    length, width, chords = _extents(hull, ang, st)
    centre = chords[np.argmin(np.abs(st))]
    shoulder = chords[np.abs(st) == np.abs(st).max()].mean()
    area, centroid = _net(geom, hull, net_area, net_centroid)
    boundary = resample_ring(hull.exterior.coords, int(boundary_samples))
    return PatchMetrics(
        area=area,
        hull_area=float(hull.area),
        solidity=float(area / hull.area),
        perimeter=float(hull.length),
        centroid=centroid,
        orientation=ang,
        length=length,
        width=width,
        aspect_ratio=length / width,
        stations=st,
        station_lengths=chords,
        shape_factor=float(centre / shoulder) if shoulder > 0 else np.inf,
        ellipse_direct=fit_ellipse_direct(boundary),
        ellipse_moments=ellipse_from_moments(hull),
    )
