"""Analyse a scanned sheet: binarize, group, edge spots, measure (sections 3.5, 4.1.1).

Each print is measured with :func:`contactpatch.measure` (the definitions shared with
the model): the *gross* outline is the convex hull of the ink's pixel squares (so a
patch's extent counts whole pixels: no 1 px bias), the *net* area is the ink pixel
count. With the load and inflation pressure known, load / area is compared with the
inflation pressure (4.1.1, Figure 4-3). A sensitivity band re-measures each print
at the threshold x (1 -+ ``tol.sensitivity``).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ._tol import tol
from .binarize import binarize, remove_specks
from .coords import area_mm2, px_to_mm
from .errors import InvalidInput, NoInk
from .group import Group, edge_spots, group_blobs, is_print
from .read import Scan

BAND_KEYS = ("length", "width", "hull_area", "area", "ellipse_length", "ellipse_width")


@dataclass(frozen=True)
class PrintResult:
    """One print on a sheet.

    Attributes
    ----------
    index : int
        0-based, top to bottom.
    metrics : contactpatch.PatchMetrics
        Load-bearing ink (edge spots removed).
    metrics_all : contactpatch.PatchMetrics
        All ink of the print.
    n_blobs, n_edge_spots : int
    edge_spot_area : float [mm^2]
    hull_px : (k, 2) float
        Load-bearing hull, continuous (row, col) pixel coordinates (for overlays).
    band : dict
        ``{key: (low, high)}`` over the thresholds x (1 -+ tol.sensitivity).
    bbox : (row0, col0, row1, col1)
    """

    index: int
    metrics: object
    metrics_all: object
    n_blobs: int
    n_edge_spots: int
    edge_spot_area: float
    hull_px: np.ndarray = field(repr=False)
    band: dict = field(repr=False)
    bbox: tuple[int, int, int, int] = (0, 0, 0, 0)


@dataclass(frozen=True)
class SheetResult:
    """All prints of one scanned sheet."""

    path: str
    page: int
    mm_per_px: float
    scale_source: str
    unit: str
    method: str
    threshold: float
    shape: tuple[int, int]
    prints: list[PrintResult]
    rejected: list[str]

    def rows(self, *, load: float | None = None, pressure: float | None = None) -> list[dict]:
        """One table row per print; ``load`` [N] and ``pressure`` [N/mm^2] add the
        load / area comparison of section 4.1.1."""
        u = self.unit
        out = []
        for p in self.prints:
            row = {
                "file": self.path,
                "page": self.page,
                "print": p.index,
                "n_prints": len(self.prints),
                "status": "ok",
                "error": "",
                "mm_per_px": self.mm_per_px,
                "dpi": 25.4 / self.mm_per_px,
                "scale_source": self.scale_source,
                "threshold_method": self.method,
                "threshold": self.threshold,
            }
            row.update(p.metrics.as_row(unit=u))
            a = p.metrics_all
            row.update(
                {
                    f"all_ink_area_{u}2": a.area,
                    f"all_ink_hull_area_{u}2": a.hull_area,
                    f"all_ink_length_{u}": a.length,
                    f"all_ink_width_{u}": a.width,
                    "n_blobs": p.n_blobs,
                    "n_edge_spots": p.n_edge_spots,
                    f"edge_spot_area_{u}2": p.edge_spot_area,
                }
            )
            for key, (lo, hi) in p.band.items():
                unit = f"_{u}2" if "area" in key else f"_{u}"
                row[f"{key}{unit}_lo"], row[f"{key}{unit}_hi"] = lo, hi
            row.update(contact_pressure(p.metrics, load, pressure))
            x, y = px_to_mm(
                p.hull_px[:, 0], p.hull_px[:, 1], n_rows=self.shape[0], mm_per_px=self.mm_per_px
            )
            ring = [*zip(x, y, strict=True), (x[0], y[0])]
            row["hull_wkt"] = "POLYGON ((" + ", ".join(f"{a:.4f} {b:.4f}" for a, b in ring) + "))"
            out.append(row)
        return out


def contact_pressure(metrics, load: float | None, pressure: float | None) -> dict:
    """Load / area and its percentage of the inflation pressure (section 4.1.1).

    ``load`` [N], ``pressure`` [N/mm^2]; NaN where not given.
    """
    nan = float("nan")
    if load is None or not np.isfinite(load):
        return {
            "load_per_hull_area_N_mm2": nan,
            "load_per_hull_area_pct": nan,
            "load_per_net_area_N_mm2": nan,
            "load_per_net_area_pct": nan,
        }
    gross, net = load / metrics.hull_area, load / metrics.area
    pct = (lambda q: 100.0 * q / pressure) if pressure else (lambda q: nan)
    return {
        "load_per_hull_area_N_mm2": gross,
        "load_per_hull_area_pct": pct(gross),
        "load_per_net_area_N_mm2": net,
        "load_per_net_area_pct": pct(net),
    }


def _hull_px(mask, field, r0: int, c0: int) -> np.ndarray:
    """Convex hull of the ink's sub-pixel outline (continuous row, col), offset.

    The outline is the iso-line ``field = 0`` (grey minus threshold, marching squares)
    around ``mask``: for an anti-aliased edge it is the 50 % coverage line, so the
    hull is not biased by the pixel staircase. (The hull of the pixel *squares*
    overshoots a rotated or curved edge by up to 0.5 (|cos| + |sin|) px per side,
    1.3 px in extent at 20 degrees; the hull of pixel *centres* falls short at the
    tips.) The net area stays the pixel count.
    """
    import cv2
    from skimage.measure import find_contours

    m8 = mask.astype(np.uint8)
    near = cv2.dilate(m8, np.ones((3, 3), np.uint8)).astype(bool)
    f = np.where(near, field, 1.0)
    # only a band along the pixel hull can hold hull points: fill the interior
    contours, _ = cv2.findContours(m8, cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_SIMPLE)
    inner = np.zeros_like(m8)
    cv2.fillPoly(inner, [cv2.convexHull(np.concatenate(contours))], 1)
    inner = cv2.erode(inner, np.ones((7, 7), np.uint8)).astype(bool)
    f = np.where(inner, -1.0, f)
    f = np.pad(f, 1, constant_values=1.0)  # close contours at the box edge
    pts = [c for c in find_contours(f, 0.0) if len(c) >= 2]
    if not pts:
        rr, cc = np.nonzero(mask)
        pts = [np.column_stack([rr + 1.0, cc + 1.0])]
    rc = np.concatenate(pts) - 1.0 + 0.5  # undo padding; pixel centres at +0.5
    hull = cv2.convexHull(rc[:, ::-1].astype(np.float32)).reshape(-1, 2)[:, ::-1].astype(float)
    return np.column_stack([hull[:, 0] + r0, hull[:, 1] + c0])


def edge_field(grey, mask, *, mm_per_px: float) -> np.ndarray:
    """Signed field whose zero line is the print's edge at half contrast.

    Half-way between the local paper (max filter) and the local ink (min filter)
    over ``tol.edge_window_mm``: for ink of any darkness the 50 % coverage line, so
    darker or lighter inking does not move the measured outline (a global threshold
    does: the hull then follows the darkest stretch of a long edge). Where the local
    contrast is below half the print's paper-to-ink contrast (inside the ink, on
    bare paper) the mask decides.
    """
    import cv2

    k = max(3, round(tol.edge_window_mm / mm_per_px) | 1)
    kernel = np.ones((k, k), np.uint8)
    lo, hi = cv2.erode(grey, kernel), cv2.dilate(grey, kernel)
    # levels from a subsample (every 3rd row and column is plenty for two medians)
    sub_g, sub_m = grey[::3, ::3], mask[::3, ::3]
    if sub_m.any() and (~sub_m).any():
        ink, paper = np.median(sub_g[sub_m]), np.median(sub_g[~sub_m])
    else:
        ink, paper = 0.0, 1.0
    sharp = (hi - lo) > 0.5 * max(paper - ink, 1e-6)
    return np.where(sharp, grey - 0.5 * (lo + hi), np.where(mask, -0.5, 0.5)).astype(np.float32)


def measure_mask(mask, r0: int, c0: int, *, n_rows: int, mm_per_px: float, field=None):
    """Shared metrics of an ink mask cropped at (r0, c0) of a sheet with n_rows rows;
    ``field`` (grey - threshold over the crop) gives the sub-pixel outline."""
    import shapely

    import contactpatch as cp

    if field is None:
        field = np.where(mask, -0.5, 0.5)
    hull_px = _hull_px(mask, field, r0, c0)
    x, y = px_to_mm(hull_px[:, 0], hull_px[:, 1], n_rows=n_rows, mm_per_px=mm_per_px)
    rr, cc = np.nonzero(mask)
    cx, cy = px_to_mm(
        rr.mean() + 0.5 + r0, cc.mean() + 0.5 + c0, n_rows=n_rows, mm_per_px=mm_per_px
    )
    hull = shapely.Polygon(np.column_stack([x, y]))
    net = min(area_mm2(len(rr), mm_per_px), hull.area)
    m = cp.measure(hull, net_area=net, net_centroid=(float(cx), float(cy)))
    return m, hull_px


def _band_values(m) -> dict:
    values = (
        m.length,
        m.width,
        m.hull_area,
        m.area,
        m.ellipse_direct.length,
        m.ellipse_direct.width,
    )
    return dict(zip(BAND_KEYS, values, strict=True))


def _sensitivity(scan: Scan, b, g: Group, base: dict) -> dict:
    """Re-measure one print at the threshold x (1 -+ tol.sensitivity)."""
    import cv2

    s = scan.mm_per_px
    pad = int(np.ceil(tol.group_distance_mm / s))
    h, w = scan.grey.shape
    r0, r1 = max(g.rows.start - pad, 0), min(g.rows.stop + pad, h)
    c0, c1 = max(g.cols.start - pad, 0), min(g.cols.stop + pad, w)
    region = np.zeros((r1 - r0, c1 - c0), np.uint8)
    region[g.rows.start - r0 : g.rows.stop - r0, g.cols.start - c0 : g.cols.stop - c0] = g.mask
    region = cv2.dilate(region, np.ones((2 * pad + 1, 2 * pad + 1), np.uint8)).astype(bool)
    grey = scan.grey[r0:r1, c0:c1]
    level = b.level if np.ndim(b.level) == 0 else b.level[r0:r1, c0:c1]
    values = {k: [v] for k, v in base.items()}
    for f in (1.0 - tol.sensitivity, 1.0 + tol.sensitivity):
        ink = remove_specks((grey < level * f) & region, int(np.ceil(tol.speck_area_mm2 / s**2)))
        if not ink.any():
            continue
        sub = Group(slice(r0, r1), slice(c0, c1), ink)
        spots = edge_spots(sub, 1.0 - grey, mm_per_px=s)
        if not spots.load_bearing.any():
            continue
        fld = edge_field(grey, spots.load_bearing, mm_per_px=s)
        m, _ = measure_mask(spots.load_bearing, r0, c0, n_rows=h, mm_per_px=s, field=fld)
        for k, v in _band_values(m).items():
            values[k].append(v)
    return {k: (float(np.nanmin(v)), float(np.nanmax(v))) for k, v in values.items()}


def analyze_scan(
    scan: Scan,
    *,
    method: str = "otsu",
    threshold: float | None = None,
    window_mm: float = 15.0,
    sensitivity: bool = True,
) -> SheetResult:
    """Find and measure every print on a scanned sheet.

    Parameters
    ----------
    scan : Scan
        From :func:`inkprint.read_scan`.
    method, threshold, window_mm
        Binarization (see :func:`inkprint.binarize.binarize`).
    sensitivity : bool
        Compute the threshold sensitivity band.

    Raises
    ------
    NoInk
        Blank sheet, or nothing on it looks like a print.
    AllInk
    """
    if not isinstance(scan, Scan):
        raise InvalidInput("scan", type(scan).__name__, "an inkprint.Scan (from read_scan)")
    s = scan.mm_per_px
    b = binarize(scan.grey, mm_per_px=s, method=method, threshold=threshold, window_mm=window_mm)
    n_rows = scan.grey.shape[0]
    prints, rejected = [], []
    speck_px = int(np.ceil(tol.speck_area_mm2 / s**2))
    for g0 in group_blobs(b.mask, mm_per_px=s):
        g = Group(g0.rows, g0.cols, remove_specks(g0.mask, speck_px))
        if not g.mask.any():
            continue
        ok, why = is_print(g, mm_per_px=s)
        if not ok:
            rejected.append(why)
            continue
        grey = scan.grey[g.rows, g.cols]
        spots = edge_spots(g, 1.0 - grey, mm_per_px=s)
        kw = dict(n_rows=n_rows, mm_per_px=s)
        fld_all = edge_field(grey, g.mask, mm_per_px=s)
        fld = edge_field(grey, spots.load_bearing, mm_per_px=s)
        m_all, _ = measure_mask(g.mask, g.rows.start, g.cols.start, field=fld_all, **kw)
        m, hull_px = measure_mask(spots.load_bearing, g.rows.start, g.cols.start, field=fld, **kw)
        base = _band_values(m)
        band = (
            _sensitivity(scan, b, g, base) if sensitivity else {k: (v, v) for k, v in base.items()}
        )
        prints.append(
            PrintResult(
                index=len(prints),
                metrics=m,
                metrics_all=m_all,
                n_blobs=spots.n_blobs,
                n_edge_spots=spots.n_spots,
                edge_spot_area=area_mm2(spots.spot_pixels, s),
                hull_px=hull_px,
                band=band,
                bbox=(g.rows.start, g.cols.start, g.rows.stop, g.cols.stop),
            )
        )
    if not prints:
        why = f" ({'; '.join(rejected[:3])})" if rejected else ""
        raise NoInk(f"no contact print on the sheet{why}")
    return SheetResult(
        path=scan.path,
        page=scan.page,
        mm_per_px=s,
        scale_source=scan.scale_source,
        unit=scan.unit,
        method=b.method,
        threshold=b.threshold,
        shape=scan.grey.shape,
        prints=prints,
        rejected=rejected,
    )
