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
``file`` (a lattice of small voids) and ``knobby`` (staggered knobs clipped by the
outline). Ground truth is the exact ink geometry (shapely): its convex hull's
length, width and area and its net area. The sheet adds uneven ink, halo spots near
the edges that bore no load (section 7.1.1, not in the truth), paper grain and a
background gradient, specks, a pen label, a ruler, rotation, two prints per sheet,
150 to 600 dpi, and optional JPEG artefacts.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from .errors import InvalidInput

TREADS = ("slick", "ribbed", "file", "knobby")
LETTER = (215.9, 279.4)  # mm
SUPERELLIPSE_N = 2.4
KAPPA = 1.03
DRUM_LENGTH, DRUM_WIDTH = 0.92, 1.12  # Table 4-1 means, drum / plate


def superellipse_area(length: float, width: float, n: float = SUPERELLIPSE_N) -> float:
    """Area of ``|2u/L|^n + |2v/W|^n <= 1`` [mm^2]."""
    return length * width * math.gamma(1 + 1 / n) ** 2 / math.gamma(1 + 2 / n)


def outline_law(
    load: float,
    pressure: float,
    tire_radius: float,
    *,
    surface: str = "plate",
    kappa: float = KAPPA,
) -> tuple[float, float]:
    """(length, width) [mm] of a print from the module's outline law.

    ``load`` [N], ``pressure`` [N/mm^2], ``tire_radius`` [mm], ``surface`` plate|drum.
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
    """One print on a sheet (mm, degrees).

    ``center`` is on the sheet (x right, y up from the bottom-left corner);
    ``angle`` turns the rolling direction from +x.
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


@dataclass(frozen=True)
class SheetSpec:
    prints: tuple[PrintSpec, ...]
    dpi: float = 150.0
    size: tuple[float, float] = LETTER
    grain: float = 0.025
    gradient: float = 0.04
    specks: int = 40
    label: str | None = None
    ruler: bool = False
    seed: int = 0


@dataclass(frozen=True)
class PrintTruth:
    """Exact ground truth of one print (mm): load-bearing ink only."""

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
    raise InvalidInput("tread", spec.tread, " | ".join(TREADS))


def _place(geom, spec: PrintSpec):
    from shapely import affinity

    g = affinity.rotate(geom, spec.angle, origin=(0, 0))
    return affinity.translate(g, *spec.center)


def truth_of(ink, angle_deg: float) -> PrintTruth:
    """Ground truth of an ink geometry: hull extents along / across ``angle``."""
    from shapely import affinity

    hull = ink.convex_hull
    rot = affinity.rotate(hull, -angle_deg, origin=(0, 0))
    x0, y0, x1, y1 = rot.bounds
    return PrintTruth(ink, x1 - x0, y1 - y0, hull.area, ink.area, angle_deg)


_SHIFT = 4  # fractional bits of cv2.fillPoly vertex coordinates (1/16 px)


def _fill(canvas, geom, to_px, value, *, shrink: float = 0.0):
    """Rasterize a shapely geometry onto ``canvas`` (pixel centres at integers).

    cv2.fillPoly also fills every pixel the boundary touches, which enlarges the shape
    by about half a pixel; the geometry is first shrunk by ``shrink`` (mm, half a
    canvas pixel) so the coverage matches the true area (to ~0.05 % at 3x supersampling).
    """
    import cv2
    import shapely

    g = geom.buffer(-shrink, join_style="mitre") if shrink else geom
    for poly in shapely.get_parts(g):
        if poly.is_empty:
            continue
        ext = np.round(to_px(np.asarray(poly.exterior.coords)) * (1 << _SHIFT)).astype(np.int32)
        cv2.fillPoly(canvas, [ext], value, lineType=cv2.LINE_8, shift=_SHIFT)
        holes = [
            np.round(to_px(np.asarray(r.coords)) * (1 << _SHIFT)).astype(np.int32)
            for r in poly.interiors
        ]
        if holes:
            cv2.fillPoly(canvas, holes, 0, lineType=cv2.LINE_8, shift=_SHIFT)


def _smooth_noise(shape, scale_px: float, rng) -> np.ndarray:
    import cv2

    small = rng.standard_normal(
        (max(2, int(shape[0] / scale_px) + 2), max(2, int(shape[1] / scale_px) + 2))
    )
    big = cv2.resize(small.astype(np.float32), (shape[1], shape[0]), interpolation=cv2.INTER_CUBIC)
    return big / (big.std() or 1.0)


def render_sheet(spec: SheetSpec) -> tuple[np.ndarray, list[PrintTruth]]:
    """Render a sheet: (rows, cols) uint8 grey image and the truth of each print
    (ordered as the prints are found: top to bottom)."""
    import cv2
    import shapely

    if not 50 <= spec.dpi <= 1200:
        raise InvalidInput("dpi", spec.dpi, "[50, 1200]")
    rng = np.random.default_rng(spec.seed)
    mm = 25.4 / spec.dpi
    rows, cols = round(spec.size[1] / mm), round(spec.size[0] / mm)
    yy = np.linspace(0, 1, rows, dtype=np.float32)[:, None]
    xx = np.linspace(0, 1, cols, dtype=np.float32)[None, :]
    paper = 0.96 - spec.gradient * (0.6 * yy + 0.4 * xx)
    paper = paper + spec.grain * rng.standard_normal((rows, cols)).astype(np.float32)
    dark = np.zeros((rows, cols), np.float32)
    truths = []
    ss = 3 if spec.dpi <= 300 else 2  # supersampling for anti-aliased edges
    for p in spec.prints:
        ink = _place(_tread(p, rng), p)
        truths.append(truth_of(ink, p.angle))
        halo = []
        ring = shapely.Polygon(_outline(p)).exterior
        for _ in range(p.halo_spots):  # faint dots just outside the outline (7.1.1)
            q = ring.interpolate(rng.uniform(0, 1), normalized=True)
            normal = np.array([q.x / (0.5 * p.length) ** 2, q.y / (0.5 * p.width) ** 2])
            u, v = np.array([q.x, q.y]) + normal / np.hypot(*normal) * rng.uniform(0.6, 2.5)
            halo.append(shapely.Point(u, v).buffer(rng.uniform(0.2, 0.45), quad_segs=6))
        halo = [_place(h, p) for h in halo]
        x0, y0, x1, y1 = ink.buffer(4.0).bounds
        c0, c1 = max(int(x0 / mm), 0), min(int(np.ceil(x1 / mm)), cols)
        r0, r1 = max(int(rows - y1 / mm), 0), min(int(np.ceil(rows - y0 / mm)), rows)
        h, w = r1 - r0, c1 - c0

        def to_px(xy, r0=r0, c0=c0):
            return (
                np.column_stack([(xy[:, 0] / mm - c0) * ss, (rows - xy[:, 1] / mm - r0) * ss])
                - 0.5
            )

        cov = np.zeros((h * ss, w * ss), np.uint8)
        _fill(cov, ink, to_px, 255, shrink=0.5 * mm / ss)
        cover = cv2.resize(cov, (w, h), interpolation=cv2.INTER_AREA).astype(np.float32) / 255.0
        level = p.ink * (1.0 + p.unevenness * _smooth_noise((h, w), 5.0 / mm, rng))
        dark[r0:r1, c0:c1] = np.maximum(dark[r0:r1, c0:c1], cover * np.clip(level, 0.35, 1.0))
        if halo:
            hcov = np.zeros((h * ss, w * ss), np.uint8)
            _fill(hcov, shapely.union_all(halo), to_px, 255, shrink=0.5 * mm / ss)
            hc = cv2.resize(hcov, (w, h), interpolation=cv2.INTER_AREA).astype(np.float32) / 255.0
            dark[r0:r1, c0:c1] = np.maximum(dark[r0:r1, c0:c1], hc * 0.45 * p.ink)
    for _ in range(spec.specks):  # dust and paper specks, below the speck size
        r, c = rng.integers(0, rows), rng.integers(0, cols)
        dark[r, c] = max(dark[r, c], rng.uniform(0.3, 0.8))
    img = np.clip(paper * (1.0 - dark), 0, 1)
    out = (img * 255).astype(np.uint8)
    if spec.label:  # a pen label, top left
        scale = 0.12 / mm
        cv2.putText(
            out,
            spec.label,
            (int(12 / mm), int(14 / mm)),
            cv2.FONT_HERSHEY_SIMPLEX,
            scale,
            40,
            max(1, int(0.35 / mm)),
            cv2.LINE_AA,
        )
    if spec.ruler:  # a ruler along the right edge, ticks every 10 mm
        x = int(cols - 12 / mm)
        cv2.line(out, (x, int(20 / mm)), (x, int(170 / mm)), 30, max(1, int(0.4 / mm)))
        for k in range(16):
            y = int((20 + 10 * k) / mm)
            cv2.line(out, (x, y), (int(x - 3 / mm), y), 30, max(1, int(0.3 / mm)))
    order = np.argsort([-t.ink.centroid.y for t in truths])
    return out, [truths[i] for i in order]


def save_scan(image: np.ndarray, path, *, dpi: float, jpeg_quality: int | None = None) -> Path:
    """Write a grey scan with its DPI (PNG, JPEG, TIFF or PDF from the suffix), atomically."""
    from PIL import Image

    from contactpatch._io import atomic_path

    path = Path(path)
    suffix = path.suffix.lower()
    im = Image.fromarray(image)
    with atomic_path(path) as tmp:
        if suffix in (".jpg", ".jpeg"):
            im.save(tmp, format="JPEG", quality=jpeg_quality or 90, dpi=(dpi, dpi))
        elif suffix in (".tif", ".tiff"):
            im.save(tmp, format="TIFF", dpi=(dpi, dpi), compression="tiff_lzw")
        elif suffix == ".pdf":
            im.save(tmp, format="PDF", resolution=dpi)
        elif suffix == ".png":
            im.save(tmp, format="PNG", dpi=(dpi, dpi))
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
    """A sheet like Figure 3-2: the drum print on top, the plate print below."""
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


def make_sample_set(out_dir, *, dpi: float = 150.0, jpeg_quality: int = 88) -> Path:
    """Write the bundled sample scans, ``manifest.csv`` (one row per print: file,
    print, tire, pressure, load, surface, dpi) and ``truth.csv`` (exact outlines)."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    manifest, truth = [], []
    k = 0
    for tire_id, tire_name, radius, rim, tread in SAMPLE_TIRES:
        for p_bar in SAMPLE_PRESSURES_BAR:
            for load in SAMPLE_LOADS_N:
                name = f"tire{tire_id:02d}_{p_bar:g}bar_{load:.0f}N.jpg"
                spec = drum_and_plate_sheet(
                    tire_radius=radius,
                    load=load,
                    pressure=0.1 * p_bar,
                    dpi=dpi,
                    tread=tread,
                    seed=100 + k,
                    label=f"{tire_name} {p_bar:g} bar {load:.0f} N",
                )
                img, truths = render_sheet(spec)
                save_scan(img, out / name, dpi=dpi, jpeg_quality=jpeg_quality)
                for i, (surface, t) in enumerate(zip(("drum", "plate"), truths, strict=True)):
                    manifest.append(
                        {
                            "file": name,
                            "print": i,
                            "tire": tire_name,
                            "tire_id": tire_id,
                            "rim_width_mm": rim,
                            "pressure_bar": p_bar,
                            "load_N": load,
                            "surface": surface,
                            "drum_diameter_mm": 2500 if surface == "drum" else "",
                            "dpi": dpi,
                        }
                    )
                    truth.append(
                        {
                            "file": name,
                            "print": i,
                            "length_mm": t.length,
                            "width_mm": t.width,
                            "hull_area_mm2": t.hull_area,
                            "net_area_mm2": t.net_area,
                            "angle_deg": t.angle,
                        }
                    )
                k += 1
    for fname, rows in (("manifest.csv", manifest), ("truth.csv", truth)):
        with (out / fname).open("w", newline="") as fh:
            w = csv.DictWriter(fh, fieldnames=list(rows[0]))
            w.writeheader()
            w.writerows(rows)
    return out / "manifest.csv"


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
