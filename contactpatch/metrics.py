"""Contact-patch metrics: one definition shared by model patches and ink prints.

Vocabulary of footprint practice (field notes): *gross* area is the area inside the
outline (the convex hull), *net* area the inked / contacting area, *net-to-gross*
their ratio (1 - void ratio). Length and width are the extents of the hull along
and across the patch axis; the footprint *shape factor* is the centre-line length
over the mean length at the shoulder stations.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

import numpy as np

from ._tol import tol
from .ellipse import EllipseFit, _polygon_moments, ellipse_from_moments, fit_ellipse_direct
from .errors import InvalidInput

#: lateral stations as fractions of the half width (centre line, mid, shoulders)
DEFAULT_STATIONS = (-0.8, -0.5, 0.0, 0.5, 0.8)


@dataclass(frozen=True)
class PatchMetrics:
    """Measured contact patch (units of the input coordinates, e.g. mm).

    Attributes
    ----------
    area : float
        Net area of the region (ink / contact).
    hull_area : float
        Gross area (convex hull).
    solidity : float
        ``area / hull_area`` (net-to-gross ratio).
    perimeter : float
        Perimeter of the hull.
    centroid : (2,) float
        Area centroid of the region.
    orientation : float [rad]
        Patch axis direction from +x, in (-pi/2, pi/2].
    length, width : float
        Hull extent along and across the axis.
    aspect_ratio : float
        ``length / width``.
    stations : (k,) float
        Lateral stations, fractions of the half width from the hull's mid line.
    station_lengths : (k,) float
        Hull chord length along the axis at each station.
    shape_factor : float
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

    def as_row(self, prefix: str = "", unit: str = "mm") -> dict[str, float]:
        """Flat dict for tables; names carry the unit."""
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

    def to_dict(self) -> dict:
        d = asdict(self)
        d["stations"] = self.stations.tolist()
        d["station_lengths"] = self.station_lengths.tolist()
        return d


def as_geometry(obj):
    """A shapely (Multi)Polygon from a Polygon, a closed (n, 2) outline or a
    contact-patch-like object with an ``outline`` attribute."""
    import shapely

    if hasattr(obj, "outline") and not hasattr(obj, "geom_type"):
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
    m = _polygon_moments(hull)
    if m is None:
        return 0.0
    _, vec = np.linalg.eigh(m[2])
    ang = float(np.arctan2(vec[1, 1], vec[0, 1]))
    if ang <= -np.pi / 2:
        ang += np.pi
    elif ang > np.pi / 2:
        ang -= np.pi
    return ang


def resample_ring(coords, n: int) -> np.ndarray:
    """(n, 2) points uniformly spaced by arc length along a closed ring."""
    c = np.asarray(coords, float)
    seg = np.linalg.norm(np.diff(c, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    t = np.linspace(0.0, s[-1], n, endpoint=False)
    return np.column_stack([np.interp(t, s, c[:, 0]), np.interp(t, s, c[:, 1])])


def measure(
    region,
    *,
    axis: float | None = None,
    stations=DEFAULT_STATIONS,
    net_area: float | None = None,
    net_centroid: tuple[float, float] | None = None,
) -> PatchMetrics:
    """Measure a contact patch.

    Parameters
    ----------
    region : shapely Polygon / MultiPolygon, (n, 2) outline, or ContactPatch
        The net region (ink, or the model's contact patch).
    axis : float [rad], optional
        Patch axis (rolling direction) from +x. Default: the major principal axis of
        the hull (prints may be rotated on the sheet).
    stations : sequence of float
        Lateral stations in fractions of the half width (|f| < 1).
    net_area, net_centroid : optional
        Net (ink) area and centroid when the region passed is only the outline (an
        ink print's hull, with the ink counted in pixels).

    Returns
    -------
    PatchMetrics
    """
    import shapely
    from shapely import affinity

    geom = as_geometry(region)
    if geom.is_empty or geom.area <= 0:
        raise InvalidInput("region", "empty", "a region with positive area")
    st = np.asarray(stations, float)
    if st.ndim != 1 or st.size == 0 or np.any(np.abs(st) >= 1) or not np.all(np.isfinite(st)):
        raise InvalidInput("stations", stations, "fractions of the half width in (-1, 1)")
    hull = geom.convex_hull
    ang = _principal_angle(hull) if axis is None else float(axis)
    if not np.isfinite(ang):
        raise InvalidInput("axis", axis, "a finite angle in radians")
    # rotate so the axis is +x: extents and station chords are then axis-aligned
    rot = affinity.rotate(hull, -ang, origin=(0, 0), use_radians=True)
    x0, y0, x1, y1 = rot.bounds
    length, width = x1 - x0, y1 - y0
    ymid = 0.5 * (y0 + y1)
    ys = ymid + st * 0.5 * width
    lines = shapely.linestrings([[[x0 - 1, y], [x1 + 1, y]] for y in ys])
    chords = np.array([rot.intersection(line).length for line in lines])
    outer = np.abs(st) == np.abs(st).max()
    centre = chords[np.argmin(np.abs(st))]
    shoulder = chords[outer].mean()
    c = geom.centroid
    area = float(geom.area) if net_area is None else float(net_area)
    if not (np.isfinite(area) and 0 < area <= hull.area * (1 + 1e-9)):
        raise InvalidInput("net_area", net_area, f"(0, hull area = {hull.area:.6g}]")
    centroid = (
        (float(c.x), float(c.y)) if net_centroid is None else tuple(map(float, net_centroid))
    )
    boundary = resample_ring(hull.exterior.coords, tol.boundary_samples)
    return PatchMetrics(
        area=area,
        hull_area=float(hull.area),
        solidity=float(area / hull.area),
        perimeter=float(hull.length),
        centroid=centroid,
        orientation=ang,
        length=float(length),
        width=float(width),
        aspect_ratio=float(length / width),
        stations=st,
        station_lengths=chords,
        shape_factor=float(centre / shoulder) if shoulder > 0 else np.inf,
        ellipse_direct=fit_ellipse_direct(boundary),
        ellipse_moments=ellipse_from_moments(hull),
    )
