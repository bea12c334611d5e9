"""Synthetic ink-print scans with exact ground truth (tests, demos, benchmarks).

Outline law (independent of the Rotta model, so model-vs-print comparisons are not
circular): each print is a superellipse ``|2u/L|^n + |2v/W|^n <= 1`` (``u`` along the
rolling direction, ``n`` = 2.4: blunter than an ellipse, like real prints) whose

* area is ``load / (kappa * pressure)`` with ``kappa`` ~ 1.03 (prints carry slightly
  more than inflation pressure, Figure 4-3),
* width is ``0.65 sqrt(A / pi) (r0 / 9.5 mm)^0.3`` (7.59 mm for the Maxxis of
  section 4.1.1 at 304 N and 100 psi; 7.57 mm measured),
* and on the 2.5 m drum the length is x 0.92 and the width x 1.12 of the plate's
  (Table 4-1 means).

Tread styles fill the outline: ``slick``, ``ribbed`` (longitudinal grooves),
``file`` (a lattice of small voids), ``knobby`` (staggered knobs clipped by the
outline), ``mtb`` (wide-groove knobs: gaps as wide as the knobs or wider), ``knurl``
(a fine tread: separate small diamonds on a staggered lattice) and ``car``
(ribs between circumferential grooves several mm wide, cut into blocks by lateral
grooves). Ground truth is the exact ink geometry (shapely): its convex hull's
length, width and area and its net area. The sheet adds uneven ink, halo spots near
the edges that bore no load (section 7.1.1, not in the truth), paper grain and a
background gradient, specks, a pen label, a ruler, rotation, two prints per sheet,
150 to 600 dpi, and optional JPEG artefacts. :mod:`inkprint.synth_effects` adds
what real sheets carry (rulers and gridlines across prints, labels touching them,
uneven light and shadows, photos, noise pages) and :mod:`inkprint.synth_cases` the
failure classes with their expected outcome.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from tiremesh.units import MPA_PER_BAR

from .coords import dpi_to_mm_per_px, mm_to_px, mm_to_px_length
from .errors import InvalidInput
from .synth_effects import (
    Grid,
    Line,
    Text,
    draw_grid,
    draw_line,
    draw_text,
    illumination,
    photograph,
    scanner_bed,
    texture_page,
)

TREADS = ("slick", "ribbed", "file", "knobby", "mtb", "car", "knurl")
LETTER = (215.9, 279.4)  # mm
SUPERELLIPSE_N = 2.4
KAPPA = 1.03
DRUM_LENGTH, DRUM_WIDTH = 0.92, 1.12  # Table 4-1 means, drum / plate
#: a print's box is supersampled up to 8x while this many canvas pixels or fewer
SUPERSAMPLED_PX = 8_000_000


def superellipse_area(length: float, width: float, n: float = SUPERELLIPSE_N) -> float:
    """Area of the superellipse ``|2u/L|^n + |2v/W|^n <= 1``.

    Parameters
    ----------
    length, width : float [mm]
        Extents ``L`` and ``W``.
    n : float
        Exponent (2 = ellipse).

    Returns
    -------
    float [mm^2]
    """
    return length * width * math.gamma(1 + 1 / n) ** 2 / math.gamma(1 + 2 / n)


def outline_law(
    load: float,
    pressure: float,
    tire_radius: float,
    *,
    surface: str = "plate",
    kappa: float = KAPPA,
) -> tuple[float, float]:
    """Length and width of a print from the module's outline law.

    Parameters
    ----------
    load : float [N]
    pressure : float [N/mm^2]
        Inflation pressure.
    tire_radius : float [mm]
        Cross-section radius of the tire.
    surface : {'plate', 'drum'}
    kappa : float
        Contact pressure over inflation pressure (area = load / (kappa pressure)).

    Returns
    -------
    length, width : float [mm]
    """
    for name, val in (("load", load), ("pressure", pressure), ("tire_radius", tire_radius)):
        if not (np.isfinite(val) and val > 0):
            raise InvalidInput(name, val, "> 0")
    if surface not in ("plate", "drum"):
        raise InvalidInput("surface", surface, "plate | drum")
    area = load / (kappa * pressure)
    width = 0.65 * math.sqrt(area / math.pi) * (tire_radius / 9.5) ** 0.3
    length = (
        area
        * math.gamma(1 + 2 / SUPERELLIPSE_N)
        / (width * math.gamma(1 + 1 / SUPERELLIPSE_N) ** 2)
    )
    if surface == "drum":
        length, width = length * DRUM_LENGTH, width * DRUM_WIDTH
    return length, width


@dataclass(frozen=True)
class PrintSpec:
    """One print on a sheet.

    Attributes
    ----------
    length, width : float [mm]
        Extents of the superellipse outline.
    center : (x, y) float [mm]
        On the sheet (x right, y up from the bottom-left corner).
    angle : float [deg]
        Turns the rolling direction from +x (counter-clockwise).
    tread : {'slick', 'ribbed', 'file', 'knobby', 'mtb', 'car', 'knurl'}
    ink : float in (0, 1]
        Mean darkness of the ink.
    unevenness : float
        Relative spread of the ink's darkness (smooth noise).
    halo_spots : int
        Faint dots just outside the outline that bore no load (section 7.1.1; not
        in the truth).
    exponent : float
        Superellipse exponent.
    block, gap : float, optional [mm]
        ``mtb``: knob size and the groove between knobs (default 5 and 6);
        ``knurl``: a diamond's length and the gap between two along the rolling
        direction (default 1.2 and 0.6);
        ``car``: rib width and circumferential groove width (default 28 and 10).
    sipe : float, optional [mm]
        ``car``: each rib cut into blocks as long as the grooves are wide by lateral
        sipes this wide (most car tires print so: the independent set's car prints,
        whose blocks are narrower along the rib than the grooves between ribs);
        ``mtb``: the knobs on the centre line split lengthwise by a sipe this wide.
    halo_touching : int
        Faint specks touching the outline (bore no load; not in the truth).
    rib : float, optional [mm]
        ``knurl``: a solid centre strip this wide along the rolling direction (a
        road tire's slick centre between its file shoulders).
    rib_groove : float [mm]
        ``knurl`` with ``rib``: bare paper this wide either side of the strip (a
        groove between the slick centre and the shoulders; 0: none).
    """

    length: float
    width: float
    center: tuple[float, float]
    angle: float = 0.0
    tread: str = "slick"
    ink: float = 0.85
    unevenness: float = 0.15
    halo_spots: int = 0
    exponent: float = SUPERELLIPSE_N
    block: float | None = None
    gap: float | None = None
    halo_touching: int = 0
    sipe: float | None = None
    rib: float | None = None
    rib_groove: float = 0.0


@dataclass(frozen=True)
class SheetSpec:
    """A sheet of prints to render.

    Attributes
    ----------
    prints : tuple of PrintSpec
    dpi : float [dots per inch]
        In [50, 1200].
    size : (width, height) float [mm]
        Default: US letter.
    grain : float
        Paper grain (standard deviation of the grey level).
    gradient : float
        Background darkening from the top-left to the bottom-right corner.
    specks : int
        Single-pixel dust specks.
    label : str, optional
        A pen label at the top left.
    ruler : bool
        A ruler along the right edge.
    seed : int
        Random seed (same seed, same image).
    marks : tuple
        :class:`~inkprint.synth_effects.Line`, ``Text`` and ``Grid`` marks.
    light : synth_effects.Light, optional
        Uneven illumination (multiplies the whole image).
    photo : synth_effects.Photo, optional
        The sheet photographed on a table (border, perspective).
    bed : synth_effects.Bed, optional
        A scan with the scanner's bed showing along sides and in punch holes.
    texture : {'noise', 'texture'}, optional
        A page of noise or texture (the prints, if any, are drawn over it).
    """

    prints: tuple[PrintSpec, ...]
    dpi: float = 150.0
    size: tuple[float, float] = LETTER
    grain: float = 0.025
    gradient: float = 0.04
    specks: int = 40
    label: str | None = None
    ruler: bool = False
    seed: int = 0
    marks: tuple = ()
    light: object = None
    photo: object = None
    texture: str | None = None
    bed: object = None


@dataclass(frozen=True)
class PrintTruth:
    """Exact ground truth of one print: load-bearing ink only.

    Attributes
    ----------
    ink : shapely geometry [mm]
        The ink, in sheet coordinates.
    length, width : float [mm]
        Extents of the ink's convex hull along and across ``angle``.
    hull_area : float [mm^2]
        Area of the convex hull (gross).
    net_area : float [mm^2]
        Area of the ink.
    angle : float [deg]
        Rolling direction from +x.
    """

    ink: object = field(repr=False)  # shapely geometry
    length: float
    width: float
    hull_area: float
    net_area: float
    angle: float


def _outline(spec: PrintSpec, n: int = 720):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    c, s = np.cos(t), np.sin(t)
    e = 2.0 / spec.exponent
    u = 0.5 * spec.length * np.sign(c) * np.abs(c) ** e
    v = 0.5 * spec.width * np.sign(s) * np.abs(s) ** e
    return np.column_stack([u, v])


def _tread(spec: PrintSpec, rng):
    """Ink geometry in the print's local (u along, v across) frame."""
    import shapely

    outline = shapely.Polygon(_outline(spec))
    L, W = spec.length, spec.width
    if spec.tread == "slick":
        return outline
    if spec.tread == "ribbed":
        grooves = [shapely.box(-L, v - 0.4, L, v + 0.4) for v in (-W / 5, W / 5)]
        return outline.difference(shapely.union_all(grooves))
    if spec.tread == "file":
        voids = []
        for i, u in enumerate(np.arange(-L / 2, L / 2, 2.0)):
            for v in np.arange(-W / 2 + (i % 2), W / 2, 2.0):
                voids.append(shapely.Point(u, v).buffer(0.45, quad_segs=4))
        return outline.difference(shapely.union_all(voids))
    if spec.tread == "knobby":
        knobs = []
        for i, u in enumerate(np.arange(-L / 2 - 2, L / 2 + 2, 4.5)):
            off = 1.6 * (i % 2)
            for v in np.arange(-W / 2 - 3 + off, W / 2 + 3, 3.2):
                knobs.append(shapely.box(u - 1.6, v - 1.1, u + 1.6, v + 1.1))
        ink = outline.intersection(shapely.union_all(knobs))
        # drop slivers a real knob edge would not print
        parts = [p for p in shapely.get_parts(ink) if p.area > 0.6]
        return shapely.union_all(parts)
    if spec.tread == "knurl":
        return _knurl(spec, outline)
    if spec.tread == "mtb":
        return _mtb(spec, outline)
    if spec.tread == "car":
        return _car(spec, outline)
    raise InvalidInput("tread", spec.tread, " | ".join(TREADS))


def _knurl(spec: PrintSpec, outline):
    """A fine tread: separate diamonds ``block`` mm long (default 1.2) and 0.7 of
    that wide on a staggered lattice, ``gap`` mm apart along the rolling direction
    (default 0.6); a diamond the outline cuts to under half of itself is dropped
    (too small to print); ``rib``: a solid centre strip, ``rib_groove`` mm of
    paper either side of it."""
    import shapely

    b = spec.block or 1.2
    g = spec.gap if spec.gap is not None else 0.6
    a, c = 0.5 * b, 0.35 * b  # half-diagonals, along and across
    pu, pv = 2 * a + g, c + 0.5 * g  # pitch along; rows across (staggered)
    L, W = spec.length, spec.width
    rib = spec.rib
    if rib is not None and (
        isinstance(rib, bool) or not isinstance(rib, numbers.Real) or not 0 < rib < W
    ):
        raise InvalidInput("rib", rib, f"a width in (0, {W:g}) mm (the print's width)")
    groove = spec.rib_groove
    if not isinstance(groove, numbers.Real) or not 0 <= groove < W / 2:
        raise InvalidInput("rib_groove", groove, f"a width in [0, {W / 2:g}) mm")
    cells = []
    for j, v in enumerate(np.arange(-W / 2 - pv, W / 2 + pv, pv)):
        for u in np.arange(-L / 2 - pu + 0.5 * pu * (j % 2), L / 2 + pu, pu):
            cells.append(shapely.Polygon([(u - a, v), (u, v - c), (u + a, v), (u, v + c)]))
    ink = outline.intersection(shapely.union_all(cells))
    if rib is not None and groove > 0:
        ink = ink.difference(shapely.box(-L, -0.5 * rib - groove, L, 0.5 * rib + groove))
    parts = [p for p in shapely.get_parts(ink) if p.area >= a * c]  # half a diamond: 2ac
    if rib is not None:
        parts.append(outline.intersection(shapely.box(-L, -0.5 * rib, L, 0.5 * rib)))
    return shapely.union_all(parts)


def _mtb(spec: PrintSpec, outline):
    """Wide-groove knobs: staggered square knobs, grooves as wide as the knobs."""
    import shapely

    b = spec.block or 5.0
    g = spec.gap if spec.gap is not None else 6.0
    pitch, L, W = b + g, spec.length, spec.width
    knobs = []
    for i, u in enumerate(np.arange(-L / 2 - pitch, L / 2 + pitch, pitch)):
        off = 0.5 * pitch * (i % 2)
        for v in np.arange(-W / 2 - pitch + off, W / 2 + pitch, pitch):
            if spec.sipe and abs(v) < 0.5 * b:  # split on the centre line
                h = 0.5 * spec.sipe
                knobs.append(shapely.box(u - b / 2, v - 0.45 * b, u + b / 2, v - h))
                knobs.append(shapely.box(u - b / 2, v + h, u + b / 2, v + 0.45 * b))
                continue
            knobs.append(shapely.box(u - b / 2, v - 0.45 * b, u + b / 2, v + 0.45 * b))
    ink = outline.intersection(shapely.union_all(knobs))
    # a knob that barely touched prints a part; keep parts of at least a quarter knob
    return shapely.union_all([p for p in shapely.get_parts(ink) if p.area >= 0.25 * b * b])


def _car(spec: PrintSpec, outline):
    """Car-like tread: ribs between wide circumferential grooves, cut into blocks."""
    import shapely

    rib = spec.block or 28.0
    g = spec.gap if spec.gap is not None else 10.0
    L, W = spec.length, spec.width
    n = max(2, round((W + g) / (rib + g)))
    rib = (W - (n - 1) * g) / n
    lateral, pitch = (0.4 * g, 1.2 * rib) if spec.sipe is None else (spec.sipe, g + spec.sipe)
    blocks = []
    for k in range(n):
        v0 = -W / 2 + k * (rib + g)
        off = 0.5 * pitch * (k % 2)
        for u in np.arange(-L / 2 - pitch + off, L / 2 + pitch, pitch):
            blocks.append(shapely.box(u, v0, u + pitch - lateral, v0 + rib))
    ink = outline.intersection(shapely.union_all(blocks))
    return shapely.union_all([p for p in shapely.get_parts(ink) if p.area >= 4.0])


def _place(geom, spec: PrintSpec):
    from shapely import affinity

    g = affinity.rotate(geom, spec.angle, origin=(0, 0))
    return affinity.translate(g, *spec.center)


def truth_of(ink, angle_deg: float) -> PrintTruth:
    """Ground truth of an ink geometry.

    Parameters
    ----------
    ink : shapely geometry [mm]
    angle_deg : float [deg]
        Rolling direction from +x: the hull's extents are measured along and across.

    Returns
    -------
    PrintTruth
    """
    from shapely import affinity

    hull = ink.convex_hull
    rot = affinity.rotate(hull, -angle_deg, origin=(0, 0))
    x0, y0, x1, y1 = rot.bounds
    return PrintTruth(ink, x1 - x0, y1 - y0, hull.area, ink.area, angle_deg)


def _fill(canvas, geom, to_px, value) -> None:
    """Rasterize a shapely geometry onto ``canvas`` (pixel centres at integers): a
    pixel is filled when its centre lies inside (even-odd rule, holes included).

    Centre sampling neither grows nor shrinks the shape, in area or in extent
    (cv2.fillPoly fills every pixel the boundary touches: shrunk by half a pixel to
    keep the area, its extremes still stood ~1/3 of a scan pixel out at 3x
    supersampling, and the prints were drawn 0.4 px wider than their truth).
    """
    import shapely

    rings = []
    for poly in shapely.get_parts(geom):
        if not poly.is_empty:
            rings += [poly.exterior, *poly.interiors]
    if not rings:
        return
    h, w = canvas.shape
    p = [to_px(np.asarray(r.coords)) for r in rings]
    a = np.concatenate([q[:-1] for q in p])
    b = np.concatenate([q[1:] for q in p])
    # rows whose centre y = i an edge crosses (half-open: min(y) <= i < max(y))
    lo = np.ceil(np.minimum(a[:, 1], b[:, 1]))
    n = np.clip(np.ceil(np.maximum(a[:, 1], b[:, 1])) - lo, 0, None).astype(np.int64)
    edge = np.repeat(np.arange(len(n)), n)
    row = lo[edge] + np.arange(len(edge)) - np.repeat(np.cumsum(n) - n, n)
    t = (row - a[edge, 1]) / (b[edge, 1] - a[edge, 1])
    x = a[edge, 0] + t * (b[edge, 0] - a[edge, 0])
    order = np.lexsort((x, row))
    row, x = row[order].astype(np.int64), x[order]
    # crossings pair up along each row: inside from the first of a pair to the second
    r0, start, stop = row[0::2], np.ceil(x[0::2]), np.ceil(x[1::2])
    ok = (r0 >= 0) & (r0 < h)
    r0 = r0[ok]
    start = np.clip(start[ok], 0, w).astype(np.int64)
    stop = np.clip(stop[ok], 0, w).astype(np.int64)
    # +1 at a span's start, -1 (255: uint8 arithmetic wraps, and is fast) past its end
    diff = np.zeros((h, w + 1), np.uint8)
    np.add.at(diff, (r0, start), np.uint8(1))
    np.add.at(diff, (r0, stop), np.uint8(255))
    canvas[np.cumsum(diff, axis=1, dtype=np.uint8)[:, :w] != 0] = value


def _smooth_noise(shape, scale_px: float, rng) -> np.ndarray:
    import cv2

    small = rng.standard_normal(
        (max(2, int(shape[0] / scale_px) + 2), max(2, int(shape[1] / scale_px) + 2))
    )
    big = cv2.resize(small.astype(np.float32), (shape[1], shape[0]), interpolation=cv2.INTER_CUBIC)
    return big / (big.std() or 1.0)


@dataclass(frozen=True)
class _Raster:
    """Pixel grid of a sheet: scale [mm / px], size [px] and supersampling factor."""

    mm_per_px: float
    rows: int
    cols: int
    ss: int

    def to_px(self, x, y):
        """Sheet (x, y) [mm] -> continuous (row, col) [px]."""
        return mm_to_px(x, y, n_rows=self.rows, mm_per_px=self.mm_per_px)

    def px(self, length_mm):
        """A length [mm] -> [px]."""
        return mm_to_px_length(length_mm, self.mm_per_px)


def _paper(spec: SheetSpec, grid: _Raster, rng) -> np.ndarray:
    """Paper grey with a gradient and grain, (rows, cols) float32."""
    yy = np.linspace(0, 1, grid.rows, dtype=np.float32)[:, None]
    xx = np.linspace(0, 1, grid.cols, dtype=np.float32)[None, :]
    paper = 0.96 - spec.gradient * (0.6 * yy + 0.4 * xx)
    return paper + spec.grain * rng.standard_normal((grid.rows, grid.cols)).astype(np.float32)


def _halo(p: PrintSpec, rng) -> list:
    """Faint dots just outside the print's outline (7.1.1), in sheet mm."""
    import shapely

    halo = []
    ring = shapely.Polygon(_outline(p)).exterior
    for _ in range(p.halo_spots):
        q = ring.interpolate(rng.uniform(0, 1), normalized=True)
        normal = np.array([q.x / (0.5 * p.length) ** 2, q.y / (0.5 * p.width) ** 2])
        u, v = np.array([q.x, q.y]) + normal / np.hypot(*normal) * rng.uniform(0.6, 2.5)
        halo.append(shapely.Point(u, v).buffer(rng.uniform(0.2, 0.45), quad_segs=6))
    for _ in range(p.halo_touching):  # specks right on the edge (rng used only if asked)
        q = ring.interpolate(rng.uniform(0, 1), normalized=True)
        halo.append(shapely.Point(q.x, q.y).buffer(rng.uniform(0.25, 0.4), quad_segs=6))
    return [_place(h, p) for h in halo]


def _coverage(geom, grid: _Raster, box: tuple[int, int, int, int]) -> np.ndarray:
    """Anti-aliased coverage in [0, 1] of ``geom`` over the pixel box (r0, c0, r1, c1)."""
    import cv2

    r0, c0, r1, c1 = box
    h, w = r1 - r0, c1 - c0
    # fine supersampling where the box is small (a narrow print's width is read to
    # a tenth of a pixel), the grid's own on large boxes
    ss = max(grid.ss, min(8, int(math.sqrt(SUPERSAMPLED_PX / max(h * w, 1)))))

    def to_px(xy):  # sheet mm -> supersampled (x, y) canvas pixels, centres at integers
        r, c = grid.to_px(xy[:, 0], xy[:, 1])
        return np.column_stack([(c - c0) * ss, (r - r0) * ss]) - 0.5

    canvas = np.zeros((h * ss, w * ss), np.uint8)
    _fill(canvas, geom, to_px, 255)
    return cv2.resize(canvas, (w, h), interpolation=cv2.INTER_AREA).astype(np.float32) / 255.0


def _draw_print(dark, ink, halo: list, p: PrintSpec, grid: _Raster, rng) -> None:
    """Darken ``dark`` with the print's ink (uneven) and its halo spots."""
    import shapely

    x0, y0, x1, y1 = ink.buffer(4.0).bounds
    top, left = grid.to_px(x0, y1)
    bottom, right = grid.to_px(x1, y0)
    c0, c1 = max(int(left), 0), min(int(np.ceil(right)), grid.cols)
    r0, r1 = max(int(top), 0), min(int(np.ceil(bottom)), grid.rows)
    box = (r0, c0, r1, c1)
    cover = _coverage(ink, grid, box)
    level = p.ink * (1.0 + p.unevenness * _smooth_noise(cover.shape, grid.px(5.0), rng))
    dark[r0:r1, c0:c1] = np.maximum(dark[r0:r1, c0:c1], cover * np.clip(level, 0.35, 1.0))
    if halo:
        hc = _coverage(shapely.union_all(halo), grid, box)
        dark[r0:r1, c0:c1] = np.maximum(dark[r0:r1, c0:c1], hc * 0.45 * p.ink)


def _add_specks(dark, n: int, rng) -> None:
    """Dust and paper specks, single pixels (below the speck size)."""
    rows, cols = dark.shape
    for _ in range(n):
        r, c = rng.integers(0, rows), rng.integers(0, cols)
        dark[r, c] = max(dark[r, c], rng.uniform(0.3, 0.8))


def _draw_label(out, text: str, grid: _Raster) -> None:
    """A pen label, top left."""
    import cv2

    org = (int(grid.px(12)), int(grid.px(14)))
    thick = max(1, int(grid.px(0.35)))
    cv2.putText(out, text, org, cv2.FONT_HERSHEY_SIMPLEX, grid.px(0.12), 40, thick, cv2.LINE_AA)


def _draw_ruler(out, grid: _Raster) -> None:
    """A ruler along the right edge, ticks every 10 mm."""
    import cv2

    x = int(grid.cols - grid.px(12))
    cv2.line(out, (x, int(grid.px(20))), (x, int(grid.px(170))), 30, max(1, int(grid.px(0.4))))
    for k in range(16):
        y = int(grid.px(20 + 10 * k))
        cv2.line(out, (x, y), (int(x - grid.px(3)), y), 30, max(1, int(grid.px(0.3))))


def render_sheet(spec: SheetSpec) -> tuple[np.ndarray, list[PrintTruth]]:
    """Render a sheet and the exact truth of its prints.

    Parameters
    ----------
    spec : SheetSpec

    Returns
    -------
    image : (rows, cols) uint8
        The grey scan (255 = white), ``spec.dpi`` dots per inch.
    truths : list of PrintTruth
        One per print, ordered as the prints are found: top to bottom. With a
        ``spec.photo``, in the photo's mm (the sheet shifted by the border).
    """
    if not 50 <= spec.dpi <= 1200:
        raise InvalidInput("dpi", spec.dpi, "[50, 1200]")
    rng = np.random.default_rng(spec.seed)
    mm = dpi_to_mm_per_px(spec.dpi)
    rows, cols = round(mm_to_px_length(spec.size[1], mm)), round(mm_to_px_length(spec.size[0], mm))
    grid = _Raster(mm, rows, cols, 3 if spec.dpi <= 300 else 2)  # supersampling for anti-aliasing
    paper = _paper(spec, grid, rng)
    dark = np.zeros((rows, cols), np.float32)
    extra = np.random.default_rng([spec.seed, 1])  # the effects' own stream
    if spec.texture:
        dark = texture_page(spec.texture, grid, extra)
    truths = []
    for p in spec.prints:
        ink = _place(_tread(p, rng), p)
        truths.append(truth_of(_clip_to_sheet(ink, spec), p.angle))
        _draw_print(dark, ink, _halo(p, rng), p, grid, rng)
    _add_specks(dark, spec.specks, rng)
    if spec.marks:
        _draw_marks(dark, spec, grid)
    img = np.clip(paper * (1.0 - dark), 0, 1)
    if spec.light is not None:
        img = img * illumination(spec.light, grid)
    out = (img * 255).astype(np.uint8)
    if spec.label:
        _draw_label(out, spec.label, grid)
    if spec.ruler:
        _draw_ruler(out, grid)
    if spec.bed is not None:
        out = scanner_bed(out, spec.bed, grid, rng=extra)
    if spec.photo is not None:
        out = photograph(out, spec.photo, grid, rng=extra)
        b = spec.photo.border
        truths = [_shift_truth(t, b, b) for t in truths]
    order = np.argsort([-t.ink.centroid.y for t in truths])
    return out, [truths[i] for i in order]


def _clip_to_sheet(ink, spec: SheetSpec):
    """The ink that lands on the sheet (a print running off the edge is cut)."""
    import shapely

    sheet = shapely.box(0.0, 0.0, *spec.size)
    return ink if sheet.contains(ink) else ink.intersection(sheet)


def _shift_truth(t: PrintTruth, dx: float, dy: float) -> PrintTruth:
    from shapely import affinity

    return truth_of(affinity.translate(t.ink, dx, dy), t.angle)


def _draw_marks(dark, spec: SheetSpec, grid: _Raster) -> None:
    """Lines, gridlines and pen labels (anti-aliased) into the darkness map."""
    canvas = np.zeros(dark.shape, np.uint8)
    for m in spec.marks:
        if isinstance(m, Line):
            draw_line(canvas, m, grid)
        elif isinstance(m, Grid):
            if not m.multiply:
                draw_grid(canvas, m, grid, size=spec.size)
        elif isinstance(m, Text):
            draw_text(canvas, m, grid)
        else:
            raise InvalidInput("marks", type(m).__name__, "Line | Grid | Text")
    np.maximum(dark, canvas.astype(np.float32) / 255.0, out=dark)
    for m in spec.marks:  # printed chart paper under the ink: the light passes both
        if isinstance(m, Grid) and m.multiply:
            lines = np.zeros(dark.shape, np.uint8)
            draw_grid(lines, m, grid, size=spec.size)
            dark[:] = 1.0 - (1.0 - dark) * (1.0 - lines.astype(np.float32) / 255.0)


def save_scan(image, path, *, dpi: float | None, jpeg_quality: int | None = None) -> Path:
    """Write a grey scan with its DPI, atomically.

    Parameters
    ----------
    image : (rows, cols) uint8, or a list of them
        Grey scan (255 = white); a list writes a multi-page PDF (one page each).
    path : str or PathLike
        .png, .jpg / .jpeg, .tif / .tiff or .pdf: the suffix sets the format.
    dpi : float or None [dots per inch]
        Stored in the file (PDF: the page size); None stores no DPI (not for PDF).
    jpeg_quality : int, optional
        JPEG quality (default 90).

    Returns
    -------
    Path
    """
    from PIL import Image

    from tiremesh.io import atomic_path

    path = Path(path)
    suffix = path.suffix.lower()
    pages = [Image.fromarray(a) for a in (image if isinstance(image, list | tuple) else [image])]
    if len(pages) > 1 and suffix != ".pdf":
        raise InvalidInput("image", f"{len(pages)} pages", "one image unless the path is a .pdf")
    if dpi is None and suffix == ".pdf":
        raise InvalidInput("dpi", dpi, "a resolution (a PDF page needs a size)")
    kw = {} if dpi is None else {"dpi": (dpi, dpi)}
    im = pages[0]
    with atomic_path(path) as tmp:
        if suffix in (".jpg", ".jpeg"):
            im.save(tmp, format="JPEG", quality=jpeg_quality or 90, **kw)
        elif suffix in (".tif", ".tiff"):
            im.save(tmp, format="TIFF", compression="tiff_lzw", **kw)
        elif suffix == ".pdf":
            im.save(tmp, format="PDF", resolution=dpi, save_all=True, append_images=pages[1:])
        elif suffix == ".png":
            im.save(tmp, format="PNG", compress_level=1, **kw)
        else:
            raise InvalidInput("path", str(path), "a .png, .jpg, .tif or .pdf file")
    return path


def drum_and_plate_sheet(
    *,
    tire_radius: float,
    load: float,
    pressure: float,
    dpi: float = 150.0,
    tread: str = "ribbed",
    seed: int = 0,
    label: str | None = None,
    angle: float = 0.0,
    halo_spots: int = 6,
) -> SheetSpec:
    """A sheet like Figure 3-2: the drum print on top, the plate print below.

    The prints follow :func:`outline_law` (``kappa`` within -2 %/+3 % of ``KAPPA``),
    are centred near x = 105 mm (drum at y = 190 mm, plate at 95 mm), turned by
    ``angle`` +- 3 degrees and inked at 0.75 to 0.9; the sheet has a ruler.

    Parameters
    ----------
    tire_radius : float [mm]
    load : float [N]
    pressure : float [N/mm^2]
    dpi : float [dots per inch]
    tread : {'slick', 'ribbed', 'file', 'knobby'}
    seed : int
        Random seed of the layout and of the rendering.
    label : str, optional
        Pen label.
    angle : float [deg]
        Rolling direction of both prints from +x.
    halo_spots : int
        Halo spots per print (section 7.1.1).

    Returns
    -------
    SheetSpec
    """
    rng = np.random.default_rng(seed)
    specs = []
    for surface, y in (("drum", 190.0), ("plate", 95.0)):
        L, W = outline_law(
            load, pressure, tire_radius, surface=surface, kappa=KAPPA * rng.uniform(0.98, 1.03)
        )
        specs.append(
            PrintSpec(
                L,
                W,
                (105.0 + rng.uniform(-5, 5), y),
                angle + rng.uniform(-3, 3),
                tread,
                ink=rng.uniform(0.75, 0.9),
                halo_spots=halo_spots,
            )
        )
    return SheetSpec(tuple(specs), dpi=dpi, label=label, ruler=True, seed=seed)


# Table 3-2 tires of the sample set: id, name, radius from the arc length [mm], rim [mm], tread
SAMPLE_TIRES = (
    (6, "Maxxis Radial Prototype 22-622", 9.527, 13.4, "ribbed"),
    (10, "Schwalbe Marathon Plus 37-622", 14.915, 18.7, "file"),
    (8, "Schwalbe Big Apple 55-622", 23.465, 18.7, "knobby"),
)
SAMPLE_PRESSURES_BAR = (4.0, 6.9)
SAMPLE_LOADS_N = (304.0, 500.0)


@dataclass(frozen=True)
class _Sample:
    """One sheet of the sample set: a tire at a pressure and load."""

    tire_id: int
    tire_name: str
    radius: float
    rim: float
    tread: str
    p_bar: float
    load: float
    seed: int

    @property
    def name(self) -> str:
        return f"tire{self.tire_id:02d}_{self.p_bar:g}bar_{self.load:.0f}N.jpg"

    def sheet(self, dpi: float) -> SheetSpec:
        return drum_and_plate_sheet(
            tire_radius=self.radius,
            load=self.load,
            pressure=self.p_bar * MPA_PER_BAR,
            dpi=dpi,
            tread=self.tread,
            seed=self.seed,
            label=f"{self.tire_name} {self.p_bar:g} bar {self.load:.0f} N",
        )


def _samples() -> list[_Sample]:
    cases = [
        (tire, p_bar, load)
        for tire in SAMPLE_TIRES
        for p_bar in SAMPLE_PRESSURES_BAR
        for load in SAMPLE_LOADS_N
    ]
    return [_Sample(*tire, p_bar, load, 100 + k) for k, (tire, p_bar, load) in enumerate(cases)]


def _manifest_rows(sample: _Sample, dpi: float) -> list[dict]:
    return [
        {
            "file": sample.name,
            "print": i,
            "tire": sample.tire_name,
            "tire_id": sample.tire_id,
            "rim_width_mm": sample.rim,
            "pressure_bar": sample.p_bar,
            "load_N": sample.load,
            "surface": surface,
            "drum_diameter_mm": 2500 if surface == "drum" else "",
            "dpi": dpi,
        }
        for i, surface in enumerate(("drum", "plate"))
    ]


def _truth_rows(sample: _Sample, truths: list[PrintTruth]) -> list[dict]:
    return [
        {
            "file": sample.name,
            "print": i,
            "length_mm": t.length,
            "width_mm": t.width,
            "hull_area_mm2": t.hull_area,
            "net_area_mm2": t.net_area,
            "angle_deg": t.angle,
        }
        for i, t in enumerate(truths)
    ]


def make_sample_set(out_dir, *, dpi: float = 150.0, jpeg_quality: int = 88) -> Path:
    """Write the bundled sample set: 12 sheets of two prints (drum and plate).

    Three tires of Table 3-2 at two pressures and two loads, JPEG scans, plus
    ``manifest.csv`` (one row per print: file, print, tire, pressure, load, surface,
    dpi) and ``truth.csv`` (the exact outlines' length, width and areas).

    Parameters
    ----------
    out_dir : str or PathLike
        Created if missing.
    dpi : float [dots per inch]
    jpeg_quality : int

    Returns
    -------
    Path
        The manifest.
    """
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    manifest, truth = [], []
    for sample in _samples():
        img, truths = render_sheet(sample.sheet(dpi))
        save_scan(img, out / sample.name, dpi=dpi, jpeg_quality=jpeg_quality)
        manifest.extend(_manifest_rows(sample, dpi))
        truth.extend(_truth_rows(sample, truths))
    _write_csv(truth, out / "truth.csv")
    return _write_csv(manifest, out / "manifest.csv")


def _write_csv(rows: list[dict], path: Path) -> Path:
    """CSV with the csv module's CRLF line ends, as the bundled ``assets/prints`` have
    (a regenerated sample set is byte-identical), atomically and spreadsheet-safe
    (:mod:`inkprint.csvsafe`)."""
    from .csvsafe import write_csv

    return write_csv(rows, path)


__all__ = [
    "PrintSpec",
    "PrintTruth",
    "SheetSpec",
    "drum_and_plate_sheet",
    "make_sample_set",
    "outline_law",
    "render_sheet",
    "save_scan",
    "superellipse_area",
    "truth_of",
]
