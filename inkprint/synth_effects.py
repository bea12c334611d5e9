"""What a real sheet adds to the prints: marks, light, a camera, texture (for :mod:`inkprint.synth`).

Each effect is a small frozen spec with exact geometry in sheet mm (x right, y up
from the bottom-left corner), drawn by :func:`inkprint.synth.render_sheet`:

* :class:`Line` - a straight line (a ruler's edge, with ticks), e.g. across a print;
* :class:`Grid` - chart-paper gridlines over the whole sheet;
* :class:`Text` - a pen label (Hershey font strokes), e.g. touching a print;
* :class:`Light` - uneven illumination: a gradient and a soft shadow (multiplies
  paper and ink alike, as light does);
* :class:`Photo` - the sheet photographed on a dark table, optionally not flat-on
  (a perspective homography of the page's corners);
* :class:`Bed` - the scanner's bed showing where the page does not cover the
  glass: dark wedges along one or two sides (a page shifted or skewed on it) and
  punch holes;
* ``SheetSpec.texture`` - a page of noise or texture with no print at all.

None of these is in the prints' truth: marks are not prints, light and texture are
not ink, and a tilted photo has no single mm scale (the analysis must flag it).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .errors import InvalidInput

#: OpenCV's Hershey stroke width as a fraction of the letters' height
STROKE_OF_HEIGHT = 0.145


@dataclass(frozen=True)
class Line:
    """A straight dark line, optionally with ruler ticks.

    Attributes
    ----------
    start, end : (x, y) float [mm]
    width : float [mm]
        Stroke width.
    darkness : float in (0, 1]
    ticks : float [mm]
        Tick spacing along the line (0: none); ticks are 3 mm long, every fifth 5 mm.
    """

    start: tuple[float, float]
    end: tuple[float, float]
    width: float = 0.4
    darkness: float = 0.85
    ticks: float = 0.0


@dataclass(frozen=True)
class Grid:
    """Gridlines over the whole sheet (chart paper).

    Attributes
    ----------
    spacing : float [mm]
    width : float [mm]
    darkness : float in (0, 1]
    multiply : bool
        The ink and the line both absorb (ink stamped on printed chart paper: the
        reflectances multiply, the ink over a line darker than either). Default:
        the darker of the two, as a line drawn over the print. Faint lines that
        multiply darken a print's blurred edge where they cross it
        (:mod:`inkprint.faintlines`).
    """

    spacing: float = 10.0
    width: float = 0.25
    darkness: float = 0.7
    multiply: bool = False


@dataclass(frozen=True)
class Text:
    """A pen label.

    Attributes
    ----------
    text : str
    origin : (x, y) float [mm]
        Bottom-left corner of the text.
    height : float [mm]
        Height of a capital letter.
    stroke : float [mm]
        Pen width (a pen's is thinner than ``AnalysisOptions.stroke_width_mm``, a
        marker's may be wider).
    darkness : float in (0, 1]
    """

    text: str
    origin: tuple[float, float]
    height: float = 4.0
    stroke: float = 0.45
    darkness: float = 0.85


@dataclass(frozen=True)
class Light:
    """Uneven light: a linear gradient, one soft-edged shadow and a vignette.

    Attributes
    ----------
    gradient : float [-]
        Illumination falls by this fraction across the sheet along ``direction``.
    direction : float [deg]
        Direction of the fall, from +x.
    shadow : tuple of (x, y) [mm]
        Polygon of the shadow (empty: none).
    shadow_depth : float [-]
        Illumination inside the shadow is ``1 - shadow_depth`` of outside.
    softness : float [mm]
        Width of the shadow's penumbra.
    vignette : float [-]
        Illumination falls by this fraction from the sheet's centre to its
        corners (quadratically with the distance, as a lens's falloff).
    """

    gradient: float = 0.4
    direction: float = 30.0
    shadow: tuple = ()
    shadow_depth: float = 0.45
    softness: float = 12.0
    vignette: float = 0.0


@dataclass(frozen=True)
class Photo:
    """The sheet photographed on a table.

    Attributes
    ----------
    border : float [mm]
        Table visible around the sheet.
    tilt : float [mm]
        How far the far edge's corners move in (perspective); 0 is flat-on.
    table : float in [0, 1]
        Grey level of the table.
    """

    border: float = 25.0
    tilt: float = 0.0
    table: float = 0.25


#: the sides of a scan a bed strip may run along
BED_SIDES = ("top", "bottom", "left", "right")


@dataclass(frozen=True)
class Bed:
    """The scanner's bed (or its dark lid) showing beside a page that does not
    cover the glass, and through its punch holes.

    Attributes
    ----------
    strips : tuple of (side, start, end)
        A dark wedge along ``side`` ('top', 'bottom', 'left' or 'right') of the
        image, ``start`` [mm] wide at the side's first end (left or top) and
        ``end`` [mm] at its other (a skewed page: a straight inner edge).
    holes : int
        Punch holes 6 mm across, 12 mm in from the left edge, spread over its
        height.
    level : float in [0, 1]
        Grey level of the bed.
    """

    strips: tuple = (("top", 5.0, 9.0),)
    holes: int = 0
    level: float = 0.25


def scanner_bed(img: np.ndarray, bed: Bed, grid, *, rng) -> np.ndarray:
    """The scan with the bed showing (see :class:`Bed`).

    Parameters
    ----------
    img : (rows, cols) uint8
    bed : Bed
    grid : inkprint.synth raster
        ``px(mm) -> px``.
    rng : numpy Generator

    Returns
    -------
    (rows, cols) uint8
    """
    import cv2

    for side, a, b in bed.strips:
        if side not in BED_SIDES:
            raise InvalidInput("side", side, " | ".join(BED_SIDES))
        if not (np.isfinite(a) and np.isfinite(b)):
            raise InvalidInput(
                "strips", (a, b), "finite widths [mm] (negative: ends off the image)"
            )
    if not (float(bed.holes).is_integer() and bed.holes >= 0):
        raise InvalidInput("holes", bed.holes, "a whole number >= 0")
    if not (np.isfinite(bed.level) and 0 <= bed.level <= 1):
        raise InvalidInput("level", bed.level, "a grey level in [0, 1]")
    rows, cols = img.shape
    shade = np.zeros(img.shape, np.uint8)
    for side, a, b in bed.strips:
        a, b = grid.px(a), grid.px(b)
        quad = {
            "top": [(0, 0), (cols, 0), (cols, b), (0, a)],
            "bottom": [(0, rows), (cols, rows), (cols, rows - b), (0, rows - a)],
            "left": [(0, 0), (0, rows), (b, rows), (a, 0)],
            "right": [(cols, 0), (cols, rows), (cols - b, rows), (cols - a, 0)],
        }[side]
        cv2.fillPoly(
            shade, [np.round(np.asarray(quad) * 16).astype(np.int32)], 255, cv2.LINE_AA, 4
        )
    for k in range(bed.holes):
        y = rows * (k + 1) / (bed.holes + 1)
        c = (round(16 * grid.px(12.0)), round(16 * y))
        cv2.circle(shade, c, round(16 * grid.px(3.0)), 255, -1, cv2.LINE_AA, 4)
    lid = bed.level * 255 + 6 * rng.standard_normal(img.shape)
    cover = shade.astype(np.float32) / 255.0  # anti-aliased edges
    return np.clip(img * (1 - cover) + lid * cover, 0, 255).astype(np.uint8)


def _check_unit(name: str, v: float) -> None:
    if not (np.isfinite(v) and 0 < v <= 1):
        raise InvalidInput(name, v, "a darkness in (0, 1]")


def draw_line(canvas, line: Line, grid) -> None:
    """Draw a :class:`Line` (darkness x 255) onto a uint8 canvas.

    Parameters
    ----------
    canvas : (rows, cols) uint8
        Darkness canvas (0 = none, 255 = black).
    line : Line
    grid : inkprint.synth raster
        ``to_px(x, y) [mm] -> (row, col) [px]`` and ``px(mm) -> px``.
    """
    import cv2

    _check_unit("darkness", line.darkness)
    value = round(255 * line.darkness)
    (x0, y0), (x1, y1) = line.start, line.end

    def _seg(a, b, w):
        r0, c0 = grid.to_px(*a)
        r1, c1 = grid.to_px(*b)
        pts = np.round(np.array([[c0, r0], [c1, r1]]) * 16).astype(np.int32)
        thick = max(1, round(grid.px(w)))
        cv2.line(
            canvas, tuple(map(int, pts[0])), tuple(map(int, pts[1])), value, thick, cv2.LINE_AA, 4
        )

    _seg((x0, y0), (x1, y1), line.width)
    if line.ticks > 0:
        length = float(np.hypot(x1 - x0, y1 - y0))
        ux, uy = (x1 - x0) / length, (y1 - y0) / length
        nx, ny = -uy, ux
        for k, s in enumerate(np.arange(0.0, length, line.ticks)):
            t = 5.0 if k % 5 == 0 else 3.0
            bx, by = x0 + ux * s, y0 + uy * s
            _seg((bx, by), (bx + nx * t, by + ny * t), 0.75 * line.width)


def draw_grid(canvas, spec: Grid, grid, *, size: tuple[float, float]) -> None:
    """Draw gridlines over the whole sheet.

    Parameters
    ----------
    canvas : (rows, cols) uint8
    spec : Grid
    size : (width, height) float [mm]
    grid : inkprint.synth raster
        As for :func:`draw_line`.
    """
    if not isinstance(spec.multiply, bool):
        raise InvalidInput("multiply", spec.multiply, "True or False")
    if not spec.spacing > 0:  # (np.arange with a step of 0 raised ZeroDivisionError)
        raise InvalidInput("spacing", spec.spacing, "a spacing > 0 mm")
    w, h = size
    for x in np.arange(spec.spacing / 2, w, spec.spacing):
        draw_line(canvas, Line((x, 0.0), (x, h), spec.width, spec.darkness), grid)
    for y in np.arange(spec.spacing / 2, h, spec.spacing):
        draw_line(canvas, Line((0.0, y), (w, y), spec.width, spec.darkness), grid)


def text_extent(text: Text) -> tuple[float, float]:
    """Width and height [mm] of a label as drawn (Hershey simplex).

    Parameters
    ----------
    text : Text

    Returns
    -------
    (width, height) : float [mm]
    """
    import cv2

    (w, h), _ = cv2.getTextSize(text.text, cv2.FONT_HERSHEY_SIMPLEX, 1.0, 1)
    return w * text.height / h, text.height


def draw_text(canvas, text: Text, grid) -> None:
    """Draw a :class:`Text` label with strokes ``text.stroke`` wide.

    OpenCV's Hershey strokes grow with the font scale (about 14 % of the letters'
    height); the glyphs are drawn at their size and thinned, or thickened (a
    marker's bold letters), to the pen's width.

    Parameters
    ----------
    canvas : (rows, cols) uint8
    text : Text
    grid : inkprint.synth raster
        As for :func:`draw_line`.
    """
    import cv2

    _check_unit("darkness", text.darkness)
    (w, h), base = cv2.getTextSize(text.text, cv2.FONT_HERSHEY_SIMPLEX, 1.0, 1)
    scale = grid.px(text.height) / h
    r, c = grid.to_px(*text.origin)
    x0, y0 = round(c), round(r)
    pad = int(scale * h) + 4
    box = np.zeros((int(scale * (h + base)) + 2 * pad, int(scale * w) + 2 * pad), np.uint8)
    cv2.putText(
        box,
        text.text,
        (pad, pad + int(scale * h)),
        cv2.FONT_HERSHEY_SIMPLEX,
        scale,
        255,
        1,
        cv2.LINE_AA,
    )
    grow = round((grid.px(text.stroke) - STROKE_OF_HEIGHT * grid.px(text.height)) / 2)
    disk = cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (3, 3))
    if grow < 0:
        box = cv2.erode(box, disk, iterations=-grow)
    elif grow > 0:  # a marker's bold letters (wider than a stroke, thick ink)
        box = cv2.dilate(box, disk, iterations=grow)
    top, left = y0 - pad - int(scale * h), x0 - pad
    r0, c0 = max(top, 0), max(left, 0)
    r1, c1 = min(top + box.shape[0], canvas.shape[0]), min(left + box.shape[1], canvas.shape[1])
    if r1 <= r0 or c1 <= c0:
        return
    ink = box[r0 - top : r1 - top, c0 - left : c1 - left].astype(np.float32) * text.darkness
    np.maximum(canvas[r0:r1, c0:c1], ink.astype(np.uint8), out=canvas[r0:r1, c0:c1])


def illumination(light: Light, grid) -> np.ndarray:
    """Illumination over the sheet (1 = full light), (rows, cols) float32.

    Parameters
    ----------
    light : Light
    grid : inkprint.synth raster
        ``rows``, ``cols``, ``mm_per_px``, ``to_px(x, y)`` and ``px(mm)``.

    Returns
    -------
    (rows, cols) float32
    """
    import cv2

    from .coords import px_to_mm

    kw = dict(n_rows=grid.rows, mm_per_px=grid.mm_per_px)
    _, y = px_to_mm(np.arange(grid.rows)[:, None] + 0.5, np.zeros((1, 1)), **kw)
    x, _ = px_to_mm(np.zeros((1, 1)), np.arange(grid.cols)[None, :] + 0.5, **kw)
    a = np.radians(light.direction)
    ramp = x * np.cos(a) + y * np.sin(a)
    ramp = (ramp - ramp.min()) / max(float(np.ptp(ramp)), 1e-9)
    field = (1.0 - light.gradient * ramp).astype(np.float32)
    if light.shadow:
        pts = np.asarray(light.shadow, float)
        r, c = grid.to_px(pts[:, 0], pts[:, 1])
        mask = np.zeros((grid.rows, grid.cols), np.float32)
        cv2.fillPoly(mask, [np.round(np.column_stack([c, r])).astype(np.int32)], 1.0)
        soft = cv2.GaussianBlur(mask, (0, 0), max(grid.px(light.softness) / 3.0, 0.5))
        field = field * (1.0 - light.shadow_depth * soft)
    if light.vignette:
        r2 = (x - x.mean()) ** 2 + (y - y.mean()) ** 2
        field = field * (1.0 - light.vignette * r2 / max(float(r2.max()), 1e-9))
    return field.astype(np.float32)


def photograph(img: np.ndarray, photo: Photo, grid, *, rng) -> np.ndarray:
    """Put the sheet on a table and, with ``tilt``, look at it off-axis.

    Parameters
    ----------
    img : (rows, cols) uint8
        The sheet.
    photo : Photo
    grid : inkprint.synth raster
        ``px(mm) -> px``.
    rng : numpy Generator

    Returns
    -------
    (rows', cols') uint8
        The photo (the sheet's pixels keep their scale at its near edge).
    """
    import cv2

    b = round(grid.px(photo.border))
    t = grid.px(photo.tilt)
    rows, cols = img.shape
    out_shape = (rows + 2 * b, cols + 2 * b)
    src = np.float32([[0, 0], [cols, 0], [cols, rows], [0, rows]])
    dst = np.float32([[b + t, b], [b + cols - t, b], [b + cols, b + rows], [b, b + rows]])
    h = cv2.getPerspectiveTransform(src, dst)
    table = photo.table * 255 + 6 * rng.standard_normal(out_shape)
    sheet = cv2.warpPerspective(
        img.astype(np.float32), h, out_shape[::-1], flags=cv2.INTER_AREA, borderValue=-1.0
    )
    inside = cv2.warpPerspective(
        np.ones_like(img, np.float32), h, out_shape[::-1], flags=cv2.INTER_LINEAR
    )
    photo_img = inside * np.maximum(sheet, 0) + (1 - inside) * table
    return np.clip(photo_img, 0, 255).astype(np.uint8)


def texture_page(kind: str, grid, rng) -> np.ndarray:
    """A page with no print: ``'noise'`` (pixel noise) or ``'texture'`` (rough,
    mottled paper with blobs of ~2 mm), darkness in [0, 1].

    Parameters
    ----------
    kind : {'noise', 'texture'}
    grid : inkprint.synth raster
        ``rows``, ``cols`` and ``px(mm) -> px``.
    rng : numpy Generator

    Returns
    -------
    (rows, cols) float32
        Darkness.
    """
    import cv2

    shape = (grid.rows, grid.cols)
    if kind == "noise":
        return rng.uniform(0.0, 1.0, shape).astype(np.float32)
    if kind == "texture":
        n = rng.standard_normal(shape).astype(np.float32)
        blob = cv2.GaussianBlur(n, (0, 0), max(grid.px(0.8), 1.0))
        blob /= blob.std() or 1.0
        return np.clip(0.5 + 0.3 * blob, 0, 1).astype(np.float32)
    raise InvalidInput("texture", kind, "'noise' | 'texture'")


__all__ = [
    "Bed",
    "Grid",
    "Light",
    "Line",
    "Photo",
    "Text",
    "draw_grid",
    "draw_line",
    "draw_text",
    "illumination",
    "photograph",
    "scanner_bed",
    "text_extent",
    "texture_page",
]
