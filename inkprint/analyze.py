"""Analyse a scanned sheet: binarize, group, edge spots, measure (sections 3.5, 4.1.1).

Each print is measured with :func:`contactpatch.measure` (the definitions shared with
the model): the *gross* outline is the convex hull of the ink's sub-pixel edge (the
iso-line half-way between the local paper and ink levels, :func:`edge_field`; no
pixel-staircase or ink-darkness bias), the *net* area is the ink pixel count (at most
the hull's area). With the load and inflation pressure known, load / area is compared
with the inflation pressure (4.1.1, Figure 4-3). A sensitivity band re-measures each
print at the threshold x (1 -+ ``sensitivity``) of :class:`inkprint.AnalysisOptions`.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field

import numpy as np

from .binarize import Binarization, binarize, remove_specks
from .coords import area_mm2_to_px, area_px_to_mm2, mm_per_px_to_dpi, mm_to_px_length, px_to_mm
from .errors import InvalidInput, NoInk
from .group import Group, edge_spots, group_blobs, is_print
from .options import AnalysisOptions, resolve_options
from .read import Scan, read_scan

BAND_KEYS = ("length", "width", "hull_area", "area", "ellipse_length", "ellipse_width")


@dataclass(frozen=True)
class PrintResult:
    """One print on a sheet.

    Attributes
    ----------
    index : int
        0-based, top to bottom.
    metrics : contactpatch.PatchMetrics
        Load-bearing ink (edge spots removed) [mm, or px without a scale].
    metrics_all : contactpatch.PatchMetrics
        All ink of the print.
    n_blobs : int
        8-connected ink blobs of the print.
    n_edge_spots : int
        Blobs that touched the paper without bearing load (section 7.1.1).
    edge_spot_area : float [mm^2]
        Ink area of the edge spots.
    hull_px : (k, 2) float [px]
        Load-bearing hull, continuous (row, col) pixel coordinates (for overlays).
    band : dict
        ``{key: (low, high)}`` for each of ``BAND_KEYS`` over the thresholds
        x (1 -+ ``AnalysisOptions.sensitivity``).
    bbox : (row0, col0, row1, col1) int [px]
        The print's box on the sheet.
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
    """All prints of one scanned sheet.

    Attributes
    ----------
    path : str
        The scan's file ('' for a scan made in memory).
    page : int
        Page of a PDF (0-based).
    mm_per_px : float [mm / px]
    scale_source : str
        'given', 'metadata', 'pdf' or 'pixels'.
    unit : str
        'mm', or 'px' without a scale.
    method : str
        Threshold method ('otsu', 'fixed' or 'sauvola').
    threshold : float [grey level]
    shape : (rows, cols) int [px]
    prints : list of PrintResult
        Top to bottom.
    rejected : list of str
        Why each other ink group is not a print (label, line, dust).
    """

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
        """One table row per print.

        Parameters
        ----------
        load : float, optional [N]
        pressure : float, optional [N/mm^2]
            With ``load``, add the load / area comparison of section 4.1.1.

        Returns
        -------
        list of dict
            Keys carry their unit (``length_mm``, ``hull_area_mm2``, ...).
        """
        return [self.row(p.index, load=load, pressure=pressure) for p in self.prints]

    def row(self, index: int, *, load: float | None = None, pressure: float | None = None) -> dict:
        """The table row of print ``index`` (see :meth:`rows`).

        Parameters
        ----------
        index : int
            0-based, top to bottom.
        load : float, optional [N]
        pressure : float, optional [N/mm^2]

        Returns
        -------
        dict
        """
        p = self.prints[index]
        u = self.unit
        row = {
            "file": self.path,
            "page": self.page,
            "print": p.index,
            "n_prints": len(self.prints),
            "status": "ok",
            "error": "",
            "mm_per_px": self.mm_per_px,
            "dpi": mm_per_px_to_dpi(self.mm_per_px),
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
        row["hull_wkt"] = self._hull_wkt(p)
        return row

    def _hull_wkt(self, p: PrintResult) -> str:
        x, y = px_to_mm(
            p.hull_px[:, 0], p.hull_px[:, 1], n_rows=self.shape[0], mm_per_px=self.mm_per_px
        )
        ring = [*zip(x, y, strict=True), (x[0], y[0])]
        return "POLYGON ((" + ", ".join(f"{a:.4f} {b:.4f}" for a, b in ring) + "))"


def contact_pressure(metrics, load: float | None, pressure: float | None) -> dict:
    """Load / area and its percentage of the inflation pressure (section 4.1.1).

    Parameters
    ----------
    metrics : contactpatch.PatchMetrics
        Uses ``hull_area`` (gross) and ``area`` (net) [mm^2].
    load : float or None [N]
    pressure : float or None [N/mm^2]
        Inflation pressure.

    Returns
    -------
    dict
        ``load_per_hull_area_N_mm2``, ``load_per_net_area_N_mm2`` [N/mm^2] and their
        ``_pct`` of ``pressure`` [%]; NaN where not given.
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

    The outline is the iso-line ``field = 0`` (marching squares) around ``mask``: for
    an anti-aliased edge it is the 50 % coverage line, so the hull is not biased by
    the pixel staircase. (The hull of the pixel *squares* overshoots a rotated or
    curved edge by up to 0.5 (|cos| + |sin|) px per side, 1.3 px in extent at 20
    degrees; the hull of pixel *centres* falls short at the tips.) The net area
    stays the pixel count.
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


def edge_field(
    grey, mask, *, mm_per_px: float, options: AnalysisOptions | None = None
) -> np.ndarray:
    """Signed field whose zero line is the print's edge at half contrast.

    Half-way between the local paper (max filter) and the local ink (min filter)
    over ``options.edge_window_mm``: for ink of any darkness the 50 % coverage line,
    so darker or lighter inking does not move the measured outline (a global
    threshold does: the hull then follows the darkest stretch of a long edge). Where
    the local contrast is below half the print's paper-to-ink contrast (inside the
    ink, on bare paper) the mask decides.

    Parameters
    ----------
    grey : (h, w) float32 in [0, 1]
        The print's box of the scan.
    mask : (h, w) bool
        The print's ink in the box.
    mm_per_px : float [mm / px]
    options : AnalysisOptions, optional
        Uses ``edge_window_mm`` (defaults when None).

    Returns
    -------
    (h, w) float32
        Negative on ink, positive on paper.
    """
    import cv2

    opts = resolve_options(options)
    k = max(3, round(mm_to_px_length(opts.edge_window_mm, mm_per_px)) | 1)
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


@dataclass(frozen=True)
class MaskMeasurement:
    """Shared metrics of an ink mask and its outline.

    Attributes
    ----------
    metrics : contactpatch.PatchMetrics
        In mm (or px without a scale), sheet coordinates (x right, y up).
    hull_px : (k, 2) float [px]
        The gross outline, continuous (row, col) pixel coordinates of the sheet.
    """

    metrics: object
    hull_px: np.ndarray = field(repr=False)


def measure_mask(
    mask, r0: int, c0: int, *, n_rows: int, mm_per_px: float, field=None
) -> MaskMeasurement:
    """Shared metrics (:func:`contactpatch.measure`) of an ink mask cropped from a sheet.

    Parameters
    ----------
    mask : (h, w) bool
        Ink, cropped at row ``r0`` and column ``c0`` of the sheet [px].
    r0, c0 : int [px]
    n_rows : int [px]
        Height of the sheet.
    mm_per_px : float [mm / px]
    field : (h, w) float, optional
        Signed edge field over the crop (:func:`edge_field`) giving the sub-pixel
        outline; default: the pixel mask's own edge.

    Returns
    -------
    MaskMeasurement
    """
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
    net = min(area_px_to_mm2(len(rr), mm_per_px), hull.area)
    m = cp.measure(hull, net_area=net, net_centroid=(float(cx), float(cy)))
    return MaskMeasurement(m, hull_px)


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


@dataclass(frozen=True)
class _BandWindow:
    """A print's box grown by the group distance (sheet rows and cols [px]) and the
    region near the print's ink in it (``(h, w) bool``): where re-thresholded ink
    still belongs to this print."""

    rows: slice
    cols: slice
    region: np.ndarray


def _band_window(scan: Scan, g: Group, opts: AnalysisOptions) -> _BandWindow:
    import cv2

    pad = int(np.ceil(mm_to_px_length(opts.group_distance_mm, scan.mm_per_px)))
    h, w = scan.grey.shape
    r0, r1 = max(g.rows.start - pad, 0), min(g.rows.stop + pad, h)
    c0, c1 = max(g.cols.start - pad, 0), min(g.cols.stop + pad, w)
    region = np.zeros((r1 - r0, c1 - c0), np.uint8)
    region[g.rows.start - r0 : g.rows.stop - r0, g.cols.start - c0 : g.cols.stop - c0] = g.mask
    region = cv2.dilate(region, np.ones((2 * pad + 1, 2 * pad + 1), np.uint8)).astype(bool)
    return _BandWindow(slice(r0, r1), slice(c0, c1), region)


def sensitivity_band(
    scan: Scan,
    binarization: Binarization,
    group: Group,
    *,
    base: dict,
    options: AnalysisOptions | None = None,
) -> dict:
    """Re-measure one print at the threshold x (1 -+ ``options.sensitivity``).

    Parameters
    ----------
    scan : Scan
    binarization : Binarization
        The sheet's threshold (``level``).
    group : Group
        The print's ink at that threshold.
    base : dict
        ``{key: value}`` for ``BAND_KEYS`` at the threshold itself.
    options : AnalysisOptions, optional
        Uses ``sensitivity``, ``group_distance_mm``, ``speck_area_mm2`` and the edge
        spot and edge window settings (defaults when None).

    Returns
    -------
    dict
        ``{key: (low, high)}`` over the three thresholds.
    """
    opts = resolve_options(options)
    s = scan.mm_per_px
    n_rows = scan.grey.shape[0]
    win = _band_window(scan, group, opts)
    grey = scan.grey[win.rows, win.cols]
    level = binarization.level
    level = level if np.ndim(level) == 0 else level[win.rows, win.cols]
    speck_px = area_mm2_to_px(opts.speck_area_mm2, s)
    values = {k: [v] for k, v in base.items()}
    for f in (1.0 - opts.sensitivity, 1.0 + opts.sensitivity):
        ink = remove_specks((grey < level * f) & win.region, speck_px)
        if not ink.any():
            continue
        spots = edge_spots(Group(win.rows, win.cols, ink), 1.0 - grey, mm_per_px=s, options=opts)
        if not spots.load_bearing.any():
            continue
        fld = edge_field(grey, spots.load_bearing, mm_per_px=s, options=opts)
        m = measure_mask(
            spots.load_bearing,
            win.rows.start,
            win.cols.start,
            n_rows=n_rows,
            mm_per_px=s,
            field=fld,
        ).metrics
        for k, v in _band_values(m).items():
            values[k].append(v)
    return {k: (float(np.nanmin(v)), float(np.nanmax(v))) for k, v in values.items()}


@dataclass(frozen=True)
class FoundPrints:
    """Ink groups of a sheet, sorted into prints and the rest.

    Attributes
    ----------
    groups : list of Group
        The prints' ink (specks removed), top to bottom.
    rejected : list of str
        Why each other group is not a print.
    """

    groups: list[Group]
    rejected: list[str]


def find_prints(mask, *, mm_per_px: float, options: AnalysisOptions | None = None) -> FoundPrints:
    """Group a sheet's ink (:func:`group_blobs`), remove specks and keep the prints.

    Parameters
    ----------
    mask : (rows, cols) bool
        Ink of the sheet.
    mm_per_px : float [mm / px]
    options : AnalysisOptions, optional
        Grouping, speck and print-shape thresholds (defaults when None).

    Returns
    -------
    FoundPrints
    """
    opts = resolve_options(options)
    speck_px = area_mm2_to_px(opts.speck_area_mm2, mm_per_px)
    groups, rejected = [], []
    for g0 in group_blobs(mask, mm_per_px=mm_per_px, options=opts):
        g = Group(g0.rows, g0.cols, remove_specks(g0.mask, speck_px))
        if not g.mask.any():
            continue
        check = is_print(g, mm_per_px=mm_per_px, options=opts)
        if check.ok:
            groups.append(g)
        else:
            rejected.append(check.reason)
    return FoundPrints(groups, rejected)


def measure_print(
    scan: Scan,
    binarization: Binarization,
    group: Group,
    *,
    index: int = 0,
    sensitivity: bool = True,
    options: AnalysisOptions | None = None,
) -> PrintResult:
    """Measure one print: edge spots (section 7.1.1), outline, metrics, band.

    Parameters
    ----------
    scan : Scan
    binarization : Binarization
        The sheet's threshold.
    group : Group
        The print's ink (from :func:`find_prints`).
    index : int
        The print's number on the sheet (0-based, top to bottom).
    sensitivity : bool
        Compute the threshold sensitivity band (else each band is the value itself).
    options : AnalysisOptions, optional
        Defaults when None.

    Returns
    -------
    PrintResult
    """
    opts = resolve_options(options)
    s, n_rows = scan.mm_per_px, scan.grey.shape[0]
    g = group
    grey = scan.grey[g.rows, g.cols]
    spots = edge_spots(g, 1.0 - grey, mm_per_px=s, options=opts)
    kw = dict(n_rows=n_rows, mm_per_px=s)
    fld_all = edge_field(grey, g.mask, mm_per_px=s, options=opts)
    fld = edge_field(grey, spots.load_bearing, mm_per_px=s, options=opts)
    m_all = measure_mask(g.mask, g.rows.start, g.cols.start, field=fld_all, **kw)
    m = measure_mask(spots.load_bearing, g.rows.start, g.cols.start, field=fld, **kw)
    base = _band_values(m.metrics)
    if sensitivity:
        band = sensitivity_band(scan, binarization, g, base=base, options=opts)
    else:
        band = {k: (v, v) for k, v in base.items()}
    return PrintResult(
        index=index,
        metrics=m.metrics,
        metrics_all=m_all.metrics,
        n_blobs=spots.n_blobs,
        n_edge_spots=spots.n_spots,
        edge_spot_area=area_px_to_mm2(spots.spot_pixels, s),
        hull_px=m.hull_px,
        band=band,
        bbox=(g.rows.start, g.cols.start, g.rows.stop, g.cols.stop),
    )


def _as_scan(scan, opts: AnalysisOptions) -> Scan:
    """A Scan as given, or read from a path (scale from the file)."""
    if isinstance(scan, Scan):
        return scan
    if isinstance(scan, str | os.PathLike):
        return read_scan(scan, options=opts)
    raise InvalidInput(
        "scan", type(scan).__name__, "an inkprint.Scan (from read_scan) or a path to a scan"
    )


def analyze_scan(
    scan: Scan | str | os.PathLike,
    *,
    method: str = "otsu",
    threshold: float | None = None,
    window_mm: float = 15.0,
    sensitivity: bool = True,
    options: AnalysisOptions | None = None,
) -> SheetResult:
    """Find and measure every print on a scanned sheet.

    Parameters
    ----------
    scan : Scan, str or PathLike
        From :func:`inkprint.read_scan`, or a file read with it (the scale from the
        file's DPI; call :func:`read_scan` yourself to give one).
    method : {'otsu', 'fixed', 'sauvola'}
        Binarization (see :func:`inkprint.binarize`).
    threshold : float, optional
        Grey level in (0, 1) for ``method='fixed'``.
    window_mm : float [mm]
        Sauvola window.
    sensitivity : bool
        Compute the threshold sensitivity band.
    options : AnalysisOptions, optional
        Judgement thresholds (defaults when None).

    Returns
    -------
    SheetResult
        Lengths in mm (px for a scan without a scale), prints top to bottom.

    Raises
    ------
    NoInk
        Blank sheet, or nothing on it looks like a print.
    AllInk, ScanReadError, ScaleMissing, InvalidInput

    Examples
    --------
    A synthetic 70 x 8 mm slick print on a small 150 dpi sheet:

    >>> import tempfile
    >>> from pathlib import Path
    >>> from inkprint import analyze_scan
    >>> from inkprint.synth import PrintSpec, SheetSpec, render_sheet, save_scan
    >>> spec = SheetSpec((PrintSpec(70.0, 8.0, (50.0, 30.0)),), size=(100.0, 60.0))
    >>> image, (truth,) = render_sheet(spec)
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     path = save_scan(image, Path(tmp) / "sheet.png", dpi=spec.dpi)
    ...     result = analyze_scan(path, sensitivity=False)
    >>> m = result.prints[0].metrics
    >>> round(m.length, 1), round(m.width, 1), round(truth.length, 1), round(truth.width, 1)
    (70.0, 8.0, 70.0, 8.0)
    """
    opts = resolve_options(options)
    scan = _as_scan(scan, opts)
    s = scan.mm_per_px
    b = binarize(
        scan.grey,
        mm_per_px=s,
        method=method,
        threshold=threshold,
        window_mm=window_mm,
        options=opts,
    )
    found = find_prints(b.mask, mm_per_px=s, options=opts)
    prints = [
        measure_print(scan, b, g, index=i, sensitivity=sensitivity, options=opts)
        for i, g in enumerate(found.groups)
    ]
    if not prints:
        why = f" ({'; '.join(found.rejected[:3])})" if found.rejected else ""
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
        rejected=found.rejected,
    )
