"""QA overlay: the scan with each print's hull, fitted ellipse and axes, labelled,
and a box around every mark set aside (lines, text, dust, noise) with its kind."""

from __future__ import annotations

from collections import Counter

import numpy as np

from .coords import mm_to_px
from .light import to_uint8
from .read import Scan
from .results import PrintResult, SheetResult

_SHIFT = 4  # fractional bits for cv2 drawing
HULL = (0, 160, 0)
FLAGGED = (200, 0, 160)
ELLIPSE = (220, 40, 40)
AXES = (30, 90, 230)
TEXT = (0, 90, 0)
MARK = (235, 140, 0)
SCALE = (140, 60, 200)
#: dust specks are boxed only when at least this large [mm^2] (a page has hundreds)
DUST_BOX_MM2 = 0.5


class _Canvas:
    """An RGB image of a scan drawn at ``f`` times its size; draws in continuous
    (row, col) pixels of the scan and in sheet mm."""

    def __init__(self, scan: Scan, max_side: int) -> None:
        import cv2

        grey = to_uint8(scan.pixels)
        self.f = min(1.0, max_side / max(grey.shape))
        if self.f < 1.0:
            grey = cv2.resize(grey, None, fx=self.f, fy=self.f, interpolation=cv2.INTER_AREA)
        self.rgb = cv2.cvtColor(grey, cv2.COLOR_GRAY2RGB)
        self.n_rows, self.mm_per_px = scan.shape[0], scan.mm_per_px
        self.thick = max(1, round(2 * self.f * max(scan.shape) / 2400))

    def _pts(self, rows, cols) -> np.ndarray:
        """Continuous (row, col) -> cv2 fixed-point (x, y) on the canvas."""
        return (np.column_stack([cols, rows]) * self.f * (1 << _SHIFT)).round().astype(np.int32)

    def line_px(self, rows, cols, color, *, closed: bool) -> None:
        import cv2

        pts = self._pts(rows, cols)
        cv2.polylines(self.rgb, [pts], closed, color, self.thick, cv2.LINE_AA, _SHIFT)

    def line_mm(self, x, y, color, *, closed: bool) -> None:
        r, c = mm_to_px(x, y, n_rows=self.n_rows, mm_per_px=self.mm_per_px)
        self.line_px(r, c, color, closed=closed)

    def label(self, text: str, row: int, col: int, color=TEXT, scale: float = 0.45) -> None:
        """White-outlined text just above scan pixel (row, col)."""
        import cv2

        t = self.thick
        org = (int(col * self.f), max(int(row * self.f) - 6 * t, 12 * t))
        font = cv2.FONT_HERSHEY_SIMPLEX
        cv2.putText(self.rgb, text, org, font, scale * t, (255, 255, 255), 3 * t, cv2.LINE_AA)
        cv2.putText(self.rgb, text, org, font, scale * t, color, t, cv2.LINE_AA)

    def box(self, bbox, color) -> None:
        """A rectangle around scan pixels (row0, col0, row1, col1)."""
        import cv2

        r0, c0, r1, c1 = (round(v * self.f) for v in bbox)
        cv2.rectangle(self.rgb, (c0 - 1, r0 - 1), (c1, r1), color, max(1, self.thick // 2))


def _draw_marks(canvas: _Canvas, result: SheetResult) -> None:
    """Orange boxes around the marks set aside, a kind on each, a count legend."""
    for m in result.marks:
        if m.kind == "dust" and m.area_mm2 < DUST_BOX_MM2:
            continue
        canvas.box(m.bbox, MARK)
        canvas.label(m.kind, m.bbox[0], m.bbox[1], MARK, 0.35)
    counts = Counter(m.kind for m in result.marks)
    if counts:
        text = "set aside: " + ", ".join(f"{n} {k}" for k, n in counts.most_common())
        canvas.label(text, canvas.rgb.shape[0] / canvas.f - 4, 4, MARK, 0.4)


def _draw_scales(canvas: _Canvas, result: SheetResult) -> None:
    """Each ruler's scale found: the strip of its ticks and numbers, outlined in
    violet, labelled with its pitch (a print it crosses is judged for the ink there:
    ``mark_on_edge``; a pitch off a ruler's: ``scale_mismatch``)."""
    from .ruler import scale_band

    for sc in result.scales:
        band = scale_band(sc, mm_per_px=result.mm_per_px)  # (col, row) [px]
        canvas.line_px(band[:, 1], band[:, 0], SCALE, closed=True)
        r, c = band[:, 1].min(), band[np.argmin(band[:, 1]), 0]
        canvas.label(f"ruler {sc.pitch_mm:.3f} mm pitch", r, c, SCALE, 0.4)


def _draw_print(canvas: _Canvas, p: PrintResult, unit: str, flags: tuple, status: str) -> None:
    """One print's hull, ellipse, axes and label (``flags``, ``status``: with the
    sheet's, :meth:`SheetResult.print_flags`)."""
    color = FLAGGED if status == "flagged" else HULL
    canvas.line_px(p.hull_px[:, 0], p.hull_px[:, 1], color, closed=True)
    e = p.metrics.ellipse_direct
    if e:
        b = e.boundary(180)
        canvas.line_mm(b[:, 0], b[:, 1], ELLIPSE, closed=True)
    m = p.metrics
    cx, cy = m.centroid
    for half, ang in ((0.5 * m.length, m.orientation), (0.5 * m.width, m.orientation + np.pi / 2)):
        dx, dy = half * np.cos(ang), half * np.sin(ang)
        canvas.line_mm(
            np.array([cx - dx, cx + dx]), np.array([cy - dy, cy + dy]), AXES, closed=False
        )
    r0, c0, _, _ = p.bbox
    u = unit
    flags = f"  [{','.join(flags)}]" if flags else ""
    canvas.label(
        f"#{p.index}  L {m.length:.1f}  W {m.width:.2f} {u}  A {m.hull_area:.0f} {u}2{flags}",
        r0,
        c0,
        FLAGGED if status == "flagged" else TEXT,
    )


def draw_overlay(
    scan: Scan, result: SheetResult, path=None, *, max_side: int = 2400
) -> np.ndarray:
    """QA image: the scan with every print's outline, ellipse and axes, labelled.

    The hull is green (magenta for a flagged print), the direct-fit ellipse red and
    the length / width axes blue; each print is labelled with its number, size and
    flags. Every mark set aside (line, gridlines, text, noise; dust of at least
    :data:`DUST_BOX_MM2`) is boxed in orange with its kind, and the bottom line
    counts them; a ruler's scale is outlined in violet with its pitch.

    Parameters
    ----------
    scan : Scan
        The scan the result was measured on.
    result : SheetResult
        From :func:`inkprint.analyze_scan`.
    path : str or PathLike, optional
        Write the image here (PNG, atomically).
    max_side : int [px]
        Larger scans are scaled down to this many pixels on their long side.

    Returns
    -------
    (h, w, 3) uint8
        The RGB image.
    """
    canvas = _Canvas(scan, max_side)
    _draw_marks(canvas, result)
    _draw_scales(canvas, result)
    for i, p in enumerate(result.prints):
        _draw_print(canvas, p, result.unit, result.print_flags(i), result.print_status(i))
    if path is not None:
        from PIL import Image

        from tiremesh.io import atomic_path

        with atomic_path(path) as tmp:
            Image.fromarray(canvas.rgb).save(tmp, format="PNG")
    return canvas.rgb
