"""Group tread blobs into prints, and tell load-bearing ink from edge spots.

The thresholds named below are fields of :class:`inkprint.AnalysisOptions`.

Grouping (section 4.1.1, "groups of pixels are identified"): ink blobs closer than
``group_distance_mm`` belong to one print, so the isolated knobs and ribs of a tread
join while two prints on a sheet (Figure 3-2) stay apart. It is done on a max-pooled
copy of the mask (a few pixels per group distance), dilated by half the distance and
labelled. Groups too small (labels, dust), too thin or too elongated (ruler lines,
pen strokes) or too sparse (writing) are not prints.

Edge spots (section 7.1.1, "determining which sections near the edge actually bore
weight and which merely touched the paper"): the print's *core* is the convex hull
of its large, dark blobs (area >= ``edge_spot_area_mm2``, peak darkness >=
``edge_spot_faintness`` x the median of the large blobs'). A blob whose centroid
lies outside the core is taken to have touched the paper without bearing load when
it is *faint* (peak darkness below that fraction of the core's: ink that was not
pressed) or *small and isolated* (below the area and farther than
``edge_spot_distance_mm`` from the core). Small dark blobs right at the core's
edge (a knob clipped by the patch outline) are kept. The peak, not the mean, is used
because a small dot's anti-aliased rim lowers its mean. Results are reported both
with all ink and with load-bearing ink only.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .coords import area_px_to_mm2, mm_to_px_length, px_to_mm_length
from .options import AnalysisOptions, resolve_options


@dataclass(frozen=True)
class Group:
    """Ink of one candidate print.

    Attributes
    ----------
    rows, cols : slice [px]
        Bounding box in the sheet.
    mask : (h, w) bool
        The group's ink inside the box.
    """

    rows: slice
    cols: slice
    mask: np.ndarray

    @property
    def n_pixels(self) -> int:
        """Number of ink pixels [px]."""
        return int(self.mask.sum())


def _disk(radius: int):
    import cv2

    r = max(int(radius), 1)
    return cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (2 * r + 1, 2 * r + 1))


def _pooled_labels(mask, d_px: float) -> tuple[int, np.ndarray]:
    """Pooling factor and the labels of the pooled mask dilated by ``d_px / 2``."""
    import cv2

    f = max(1, int(d_px // 4))
    h, w = mask.shape
    H, W = -(-h // f) * f, -(-w // f) * f
    if (H, W) != (h, w):
        padded = np.zeros((H, W), bool)
        padded[:h, :w] = mask
    else:
        padded = mask
    small = padded.reshape(H // f, f, W // f, f).any(axis=(1, 3)).astype(np.uint8)
    grown = cv2.dilate(small, _disk(int(np.ceil(0.5 * d_px / f))))
    _, small_labels = cv2.connectedComponents(grown, connectivity=8)
    return f, small_labels


def group_blobs(mask, *, mm_per_px: float, options: AnalysisOptions | None = None) -> list[Group]:
    """Group ink blobs that lie within ``options.group_distance_mm`` of each other.

    Parameters
    ----------
    mask : (rows, cols) bool
        Ink of the sheet.
    mm_per_px : float [mm / px]
    options : AnalysisOptions, optional
        Uses ``group_distance_mm`` (defaults when None).

    Returns
    -------
    list of Group
        Ordered top to bottom (by the box's centre row), then left to right.
    """
    from scipy import ndimage

    opts = resolve_options(options)
    f, small_labels = _pooled_labels(mask, mm_to_px_length(opts.group_distance_mm, mm_per_px))
    h, w = mask.shape
    groups = []
    # boxes on the pooled image; the full-resolution group mask is read off per box
    for label, box in enumerate(ndimage.find_objects(small_labels), start=1):
        if box is None:
            continue
        rows = slice(box[0].start * f, min(box[0].stop * f, h))
        cols = slice(box[1].start * f, min(box[1].stop * f, w))
        lab = np.repeat(np.repeat(small_labels[box] == label, f, axis=0), f, axis=1)
        sub = mask[rows, cols] & lab[: rows.stop - rows.start, : cols.stop - cols.start]
        if sub.any():
            groups.append(Group(rows, cols, sub))
    groups.sort(key=lambda g: (g.rows.start + g.rows.stop, g.cols.start))
    return groups


@dataclass(frozen=True)
class PrintCheck:
    """Whether a group looks like a contact print.

    Attributes
    ----------
    ok : bool
    reason : str
        Why not ('' when ``ok``): a label, a line, writing or dust.
    """

    ok: bool
    reason: str = ""


def is_print(
    group: Group, *, mm_per_px: float, options: AnalysisOptions | None = None
) -> PrintCheck:
    """Whether a group looks like a contact print; if not, why (label, line, dust).

    Parameters
    ----------
    group : Group
    mm_per_px : float [mm / px]
    options : AnalysisOptions, optional
        Uses ``min_patch_area_mm2``, ``min_patch_width_mm``, ``max_patch_aspect`` and
        ``min_net_to_gross`` (defaults when None).

    Returns
    -------
    PrintCheck
    """
    import cv2

    opts = resolve_options(options)
    area = area_px_to_mm2(group.n_pixels, mm_per_px)
    if area < opts.min_patch_area_mm2:
        return PrintCheck(False, f"too little ink ({area:.1f} mm^2 < {opts.min_patch_area_mm2:g})")
    pts = np.column_stack(np.nonzero(group.mask)[::-1]).astype(np.float32)
    (_, _), (a, b), _ = cv2.minAreaRect(pts)
    length = px_to_mm_length(max(a, b) + 1, mm_per_px)
    width = px_to_mm_length(min(a, b) + 1, mm_per_px)
    if width < opts.min_patch_width_mm:
        return PrintCheck(False, f"a line ({width:.2f} mm wide)")
    if length / width > opts.max_patch_aspect:
        return PrintCheck(False, f"a line ({length / width:.0f} x longer than wide)")
    hull = cv2.convexHull(pts)
    fill = group.n_pixels / max(cv2.contourArea(hull) + 0.5 * cv2.arcLength(hull, True) + 1.0, 1.0)
    if fill < opts.min_net_to_gross:
        return PrintCheck(False, f"writing or marks ({100 * fill:.0f} % of its hull inked)")
    return PrintCheck(True)


@dataclass(frozen=True)
class EdgeSpots:
    """The section 7.1.1 split of one group's ink.

    Attributes
    ----------
    load_bearing : (h, w) bool
        The group's ink without edge spots.
    n_blobs : int
        8-connected ink blobs in the group.
    n_spots : int
        Blobs judged edge spots (touched the paper, bore no load).
    spot_pixels : int [px]
        Ink pixels of the edge spots.
    """

    load_bearing: np.ndarray
    n_blobs: int
    n_spots: int
    spot_pixels: int


@dataclass(frozen=True)
class _Blobs:
    """8-connected blobs of a group: labels (0 = paper), areas [mm^2], centroids
    (x = col, y = row) [px] and peak darkness, per blob 1..n."""

    labels: np.ndarray
    areas: np.ndarray
    centroids: np.ndarray
    peak: np.ndarray


def _blobs(group: Group, darkness, mm_per_px: float) -> _Blobs:
    import cv2

    n, lab, stats, cent = cv2.connectedComponentsWithStats(
        group.mask.astype(np.uint8), connectivity=8
    )
    peak = np.zeros(n)
    np.maximum.at(peak, lab[group.mask], np.asarray(darkness, float)[group.mask])
    areas = area_px_to_mm2(stats[1:, cv2.CC_STAT_AREA], mm_per_px)
    return _Blobs(lab, areas, cent[1:], peak[1:])


def _core_distance(blobs: _Blobs, core: np.ndarray) -> np.ndarray:
    """Signed distance [px] of each blob's centroid to the convex hull of the core
    blobs (< 0 outside)."""
    import cv2

    core_mask = np.concatenate([[False], core])[blobs.labels].astype(np.uint8)
    core_pts = np.concatenate(
        cv2.findContours(core_mask, cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_SIMPLE)[0]
    )
    hull = cv2.convexHull(core_pts)
    return np.array(
        [cv2.pointPolygonTest(hull, (float(x), float(y)), True) for x, y in blobs.centroids]
    )


def edge_spots(
    group: Group, darkness, *, mm_per_px: float, options: AnalysisOptions | None = None
) -> EdgeSpots:
    """Apply the section 7.1.1 rule to one group.

    Parameters
    ----------
    group : Group
    darkness : (h, w) float in [0, 1]
        1 - grey over the group's box.
    mm_per_px : float [mm / px]
    options : AnalysisOptions, optional
        Uses ``edge_spot_area_mm2``, ``edge_spot_faintness`` and
        ``edge_spot_distance_mm`` (defaults when None).

    Returns
    -------
    EdgeSpots
    """
    opts = resolve_options(options)
    blobs = _blobs(group, darkness, mm_per_px)
    n_blobs = len(blobs.areas)
    if n_blobs <= 1:
        return EdgeSpots(group.mask, n_blobs, 0, 0)
    large = blobs.areas >= opts.edge_spot_area_mm2
    if not large.any():
        large = blobs.areas == blobs.areas.max()
    ref = float(np.median(blobs.peak[large]))
    faint = blobs.peak < opts.edge_spot_faintness * ref
    core = large & ~faint
    if not core.any():
        core = large
    dist_mm = px_to_mm_length(_core_distance(blobs, core), mm_per_px)
    isolated = (blobs.areas < opts.edge_spot_area_mm2) & (-dist_mm > opts.edge_spot_distance_mm)
    spot = (dist_mm < 0) & (faint | isolated)
    is_spot = np.concatenate([[False], spot])[blobs.labels]
    return EdgeSpots(group.mask & ~is_spot, n_blobs, int(spot.sum()), int(is_spot.sum()))
