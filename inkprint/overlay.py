"""QA overlay: the scan with each print's hull, fitted ellipse and axes, labelled."""

from __future__ import annotations

import numpy as np

from .analyze import SheetResult
from .coords import mm_to_px
from .read import Scan

_SHIFT = 4  # fractional bits for cv2 drawing
HULL = (0, 160, 0)
ELLIPSE = (220, 40, 40)
AXES = (30, 90, 230)


def draw_overlay(
    scan: Scan, result: SheetResult, path=None, *, max_side: int = 2400
) -> np.ndarray:
    """RGB image of the scan with every print's hull (green), direct-fit ellipse
    (red) and length / width axes (blue), labelled with its number and size.
    Written to ``path`` (PNG, atomically) when given. Large scans are scaled down to
    ``max_side`` pixels."""
    import cv2

    grey = (np.clip(scan.grey, 0, 1) * 255).astype(np.uint8)
    f = min(1.0, max_side / max(grey.shape))
    if f < 1.0:
        grey = cv2.resize(grey, None, fx=f, fy=f, interpolation=cv2.INTER_AREA)
    rgb = cv2.cvtColor(grey, cv2.COLOR_GRAY2RGB)
    n_rows, s = scan.grey.shape[0], scan.mm_per_px
    thick = max(1, round(2 * f * max(scan.grey.shape) / 2400))
    u = result.unit

    def pts(rows, cols):  # continuous (row, col) -> cv2 fixed point (x, y)
        return (np.column_stack([cols, rows]) * f * (1 << _SHIFT)).round().astype(np.int32)

    for p in result.prints:
        cv2.polylines(
            rgb, [pts(p.hull_px[:, 0], p.hull_px[:, 1])], True, HULL, thick, cv2.LINE_AA, _SHIFT
        )
        e = p.metrics.ellipse_direct
        if e:
            b = e.boundary(180)
            r, c = mm_to_px(b[:, 0], b[:, 1], n_rows=n_rows, mm_per_px=s)
            cv2.polylines(rgb, [pts(r, c)], True, ELLIPSE, thick, cv2.LINE_AA, _SHIFT)
        m = p.metrics
        cx, cy = m.centroid
        for half, ang in (
            (0.5 * m.length, m.orientation),
            (0.5 * m.width, m.orientation + np.pi / 2),
        ):
            dx, dy = half * np.cos(ang), half * np.sin(ang)
            r, c = mm_to_px(
                np.array([cx - dx, cx + dx]),
                np.array([cy - dy, cy + dy]),
                n_rows=n_rows,
                mm_per_px=s,
            )
            cv2.polylines(rgb, [pts(r, c)], False, AXES, thick, cv2.LINE_AA, _SHIFT)
        r0, c0, _, _ = p.bbox
        text = f"#{p.index}  L {m.length:.1f}  W {m.width:.2f} {u}  A {m.hull_area:.0f} {u}2"
        org = (int(c0 * f), max(int(r0 * f) - 6 * thick, 12 * thick))
        cv2.putText(
            rgb,
            text,
            org,
            cv2.FONT_HERSHEY_SIMPLEX,
            0.45 * thick,
            (255, 255, 255),
            3 * thick,
            cv2.LINE_AA,
        )
        cv2.putText(
            rgb, text, org, cv2.FONT_HERSHEY_SIMPLEX, 0.45 * thick, (0, 90, 0), thick, cv2.LINE_AA
        )
    if path is not None:
        from PIL import Image

        from contactpatch._io import atomic_path

        with atomic_path(path) as tmp:
            Image.fromarray(rgb).save(tmp, format="PNG")
    return rgb
