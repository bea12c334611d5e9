"""The prints in the report: each scanned sheet's QA overlay, each print's outline
over its model patch, and what the analysis set aside (Dressel 2013, 4.1.1).

* :func:`locate_scans` finds the scan files the print table names (the table holds
  the manifest's relative names): in the folders given, the table's folder and the
  working folder, directly or a few levels down, and checks each candidate against
  the table's ``sha256`` so a different file of the same name is never shown.
* :func:`qa_overlay` draws a sheet with every print's measured hull and number,
  scaled down, as JPEG bytes (the page embeds it; a click shows it large).
* :func:`outline_svg` draws one print's hull and ellipse with its model patch, both
  centred with the rolling direction up, at a scale shared by the whole report.
* :func:`set_aside` reads the sheet's list of ink groups that are not prints
  (labels, rulers, dust), when the print table carries one.
"""

from __future__ import annotations

import hashlib
import html
import json
import math
import os
from collections import defaultdict
from pathlib import Path

import numpy as np

from tiremesh.io import cell_number_or_nan as _f

#: columns that may hold a sheet's set-aside list (JSON list or ';'-separated text)
SET_ASIDE_COLUMNS = ("set_aside", "rejected")
#: folders not searched for scans
_SKIP_DIRS = {"node_modules", "__pycache__", "site-packages"}


def sheets_of(rows: list[dict]) -> dict[str, list[dict]]:
    """The print table's rows by sheet (file), in file order.

    Parameters
    ----------
    rows : list of dict

    Returns
    -------
    dict of str to list of dict
    """
    out = defaultdict(list)
    for r in rows:
        out[str(r.get("file", ""))].append(r)
    return dict(sorted(out.items()))


def _sha256(path: Path) -> str:
    h = hashlib.sha256()
    with path.open("rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _index_names(root: Path, names: set[str], depth: int) -> dict[str, list[Path]]:
    """Files under ``root`` (at most ``depth`` levels down) whose name is wanted."""
    found = defaultdict(list)
    root_depth = len(root.parts)
    for dirpath, dirnames, filenames in os.walk(root):
        here = Path(dirpath)
        if len(here.parts) - root_depth >= depth:
            dirnames[:] = []
        dirnames[:] = [d for d in dirnames if not d.startswith(".") and d not in _SKIP_DIRS]
        for f in filenames:
            if f in names:
                found[f].append(here / f)
    return found


def locate_scans(rows: list[dict], dirs=(), *, depth: int = 3) -> dict[str, Path]:
    """Where the scans of a print table are.

    Parameters
    ----------
    rows : list of dict
        Print rows (``file``, and ``sha256`` when the batch recorded it).
    dirs : sequence of str or PathLike
        Folders to look in first; then the working folder.
    depth : int
        How many folder levels below each to search for a file's name.

    Returns
    -------
    dict of str to Path
        ``file`` -> the scan, for the files found whose content matches the
        table's ``sha256`` (or that have none recorded).
    """
    want = {}
    for r in rows:
        want.setdefault(str(r.get("file", "")), str(r.get("sha256") or ""))
    roots = [Path(d) for d in dirs if d] + [Path.cwd()]
    found: dict[str, Path] = {}
    for root in roots:
        missing = {f for f in want if f not in found}
        if not missing or not root.is_dir():
            continue
        direct = {f: [root / f] for f in missing if (root / f).is_file()}
        names = {Path(f).name for f in missing if f not in direct}
        index = _index_names(root, names, depth) if names else {}
        for f in missing:
            for cand in direct.get(f, []) + index.get(Path(f).name, []):
                if not want[f] or _sha256(cand) == want[f]:
                    found[f] = cand
                    break
    return found


def _grey_image(path, rows: list[dict], max_side: int):
    """The scan in grey (uint8), the factor from its full-size pixels to these, and
    its full height [px].

    A JPEG or PNG is decoded at a reduced size when the overlay is that much smaller
    (OpenCV's DCT scaling, as :func:`inkprint.read_scan` decodes it otherwise);
    other files (PDF, TIFF, ...) through :func:`inkprint.read_scan`.
    """
    import cv2
    from PIL import Image

    from inkprint.read import read_scan

    p = Path(path)
    page = int(_f(rows[0].get("page", 0)) or 0) if rows else 0
    if page == 0 and p.suffix.lower() in (".jpg", ".jpeg", ".png"):
        with Image.open(p) as im:
            w, h = im.size
        k = next((k for k in (8, 4, 2) if max(w, h) >= k * max_side), 1)
        flags = {
            1: cv2.IMREAD_GRAYSCALE,
            2: cv2.IMREAD_REDUCED_GRAYSCALE_2,
            4: cv2.IMREAD_REDUCED_GRAYSCALE_4,
            8: cv2.IMREAD_REDUCED_GRAYSCALE_8,
        }
        a = cv2.imdecode(np.fromfile(p, np.uint8), flags[k])
        if a is not None and a.dtype == np.uint8 and a.shape == (-(-h // k), -(-w // k)):
            return a, 1.0 / k, h
    mmpp = next(
        (_f(r.get("mm_per_px")) for r in rows if math.isfinite(_f(r.get("mm_per_px")))), math.nan
    )
    scale = {"mm_per_px": mmpp} if math.isfinite(mmpp) else {"allow_pixels": True}
    scan = read_scan(p, page=page, **scale)
    return (np.clip(scan.grey, 0, 1) * 255).astype(np.uint8), 1.0, scan.grey.shape[0]


def qa_overlay(scan_path, rows: list[dict], *, max_side: int = 1000) -> bytes:
    """A sheet with each print's measured hull (green) and number, as JPEG bytes.

    Parameters
    ----------
    scan_path : str or PathLike
        The scan (read with the table's scale and page).
    rows : list of dict
        The sheet's rows (``hull_wkt`` [mm], ``print``, ``mm_per_px``, ``page``).
    max_side : int [px]
        Long side of the image (at most).

    Returns
    -------
    bytes
        JPEG (quality 70).
    """
    import cv2
    import shapely

    from inkprint.coords import mm_to_px

    ok = [r for r in rows if r.get("status", "ok") == "ok" and r.get("hull_wkt")]
    grey, f0, n_rows = _grey_image(scan_path, ok or rows, max_side)
    f1 = min(1.0, max_side / max(grey.shape))
    small = cv2.resize(grey, None, fx=f1, fy=f1, interpolation=cv2.INTER_AREA) if f1 < 1 else grey
    f = f0 * f1
    rgb = cv2.cvtColor(small, cv2.COLOR_GRAY2RGB)
    thick = max(1, round(max(small.shape) / 500))
    for r in ok:
        ring = np.asarray(shapely.from_wkt(r["hull_wkt"]).exterior.coords)
        mmpp = _f(r.get("mm_per_px"))
        rr, cc = mm_to_px(ring[:, 0], ring[:, 1], n_rows=n_rows, mm_per_px=mmpp)
        pts = (np.column_stack([cc, rr]) * f).round().astype(np.int32)
        cv2.polylines(rgb, [pts], True, (0, 150, 0), thick, cv2.LINE_AA)
        x, y = int(pts[:, 0].min()), max(int(pts[:, 1].min()) - 4 * thick, 12 * thick)
        label = f"#{r.get('print')}"
        for color, t in (((255, 255, 255), 3 * thick), ((0, 110, 0), thick)):
            font = cv2.FONT_HERSHEY_SIMPLEX
            cv2.putText(rgb, label, (x, y), font, 0.5 * thick, color, t, cv2.LINE_AA)
    bgr = cv2.cvtColor(rgb, cv2.COLOR_RGB2BGR)
    _, buf = cv2.imencode(".jpg", bgr, [cv2.IMWRITE_JPEG_QUALITY, 70])
    return buf.tobytes()


def _centred(geom, angle_deg: float):
    """The polygon's ring (n, 2) centred on its centroid, turned so its long axis
    (at ``angle_deg`` from +x) points up."""
    from shapely import affinity

    c = geom.centroid
    g = affinity.translate(geom, -c.x, -c.y)
    g = affinity.rotate(g, 90.0 - angle_deg, origin=(0, 0))
    return np.asarray(g.exterior.coords)


def _points(ring) -> str:
    """SVG points in mm, y up (the page's y runs down)."""
    return " ".join(f"{x:.1f},{-y:.1f}" for x, y in ring)


def outline_svg(row: dict, span: float, colour: str, *, width: float | None = None) -> str:
    """One print's hull (filled, the tire's colour) and ellipse (dotted) over its
    model patch (dashed), centred, rolling direction up, ``span`` mm tall.

    Parameters
    ----------
    row : dict
        A paired row (``hull_wkt``, ``angle_deg``, ``ellipse_length_mm``,
        ``ellipse_width_mm``, ``model_outline_wkt``) [mm].
    span : float [mm]
        Height the drawing shows (the same for every print: one scale).
    colour : str
        The tire's colour.
    width : float, optional [mm]
        Width the drawing shows (default half the span).

    Returns
    -------
    str
        An ``<svg>`` element with a 20 mm scale bar; empty without a hull.
    """
    import shapely

    if not row.get("hull_wkt"):
        return ""
    # simplified by 0.1 mm: a sixth of a pixel at the drawings' scale
    hull = shapely.from_wkt(row["hull_wkt"]).simplify(0.1)
    parts = [
        f'<polygon points="{_points(_centred(hull, _f(row.get("angle_deg", 0.0))))}" '
        f'fill="{colour}" fill-opacity="0.4" stroke="none"/>'
    ]
    el, ew = _f(row.get("ellipse_length_mm")), _f(row.get("ellipse_width_mm"))
    if math.isfinite(el) and math.isfinite(ew):
        parts.append(
            f'<ellipse cx="0" cy="0" rx="{ew / 2:.1f}" ry="{el / 2:.1f}" fill="none" '
            'stroke="#444" stroke-width="1" stroke-dasharray="2 2" '
            'vector-effect="non-scaling-stroke"/>'
        )
    if row.get("model_outline_wkt"):
        model = shapely.from_wkt(row["model_outline_wkt"]).simplify(0.1)
        parts.append(
            f'<polygon points="{_points(_centred(model, 0.0))}" fill="none" '
            'stroke="#222" stroke-width="1.3" stroke-dasharray="4 2" '
            'vector-effect="non-scaling-stroke"/>'
        )
    w, h = (0.5 * span if width is None else max(width, 24.0)), 1.08 * span
    y0 = 0.5 * h - 2
    parts.append(
        f'<path d="M{-10:.1f},{y0:.1f} h20" stroke="#222" stroke-width="1.5" '
        'vector-effect="non-scaling-stroke"/>'
        f'<text x="0" y="{y0 - 3:.1f}" font-size="{0.045 * span:.1f}" '
        'text-anchor="middle">20 mm</text>'
    )
    return (
        f'<svg class="outline" viewBox="{-w / 2:.1f} {-h / 2:.1f} {w:.1f} {h:.1f}" '
        f'role="img" aria-label="print {html.escape(str(row.get("print")))} over its model">'
        + "".join(parts)
        + "</svg>"
    )


def set_aside(rows: list[dict]) -> list[str] | None:
    """What the analysis set aside on a sheet (labels, rulers, dust), if recorded.

    Parameters
    ----------
    rows : list of dict
        The sheet's rows.

    Returns
    -------
    list of str or None
        The reasons, one per ink group; None when the table has no such column
        (older batches).
    """
    for r in rows:
        for col in SET_ASIDE_COLUMNS:
            if col in r and r[col] is not None:
                return _as_list(r[col])
    return None


def _as_list(value) -> list[str]:
    if isinstance(value, list | tuple):
        return [str(v) for v in value]
    text = str(value).strip()
    if not text:
        return []
    if text.startswith("["):
        try:
            return [str(v) for v in json.loads(text)]
        except ValueError:
            pass
    return [t.strip() for t in text.replace("|", ";").split(";") if t.strip()]


__all__ = [
    "SET_ASIDE_COLUMNS",
    "locate_scans",
    "outline_svg",
    "qa_overlay",
    "set_aside",
    "sheets_of",
]
