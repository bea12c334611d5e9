"""Group tread blobs into prints, and tell load-bearing ink from edge spots.

Grouping (section 4.1.1, "groups of pixels are identified"): ink blobs closer than
``tol.group_distance_mm`` belong to one print, so the isolated knobs and ribs of a
tread join while two prints on a sheet (Figure 3-2) stay apart. It is done on a
max-pooled copy of the mask (a few pixels per group distance), dilated by half the
distance and labelled. Groups too small (labels, dust), too thin or too elongated
(ruler lines, pen strokes) are not prints.

Edge spots (section 7.1.1, "determining which sections near the edge actually bore
weight and which merely touched the paper"): the print's *core* is the convex hull
of its large, dark blobs (area >= ``tol.edge_spot_area_mm2``, peak darkness >=
``tol.edge_spot_faintness`` x the median of the large blobs'). A blob whose centroid
lies outside the core is taken to have touched the paper without bearing load when
it is *faint* (peak darkness below that fraction of the core's: ink that was not
pressed) or *small and isolated* (below the area and farther than
``tol.edge_spot_distance_mm`` from the core). Small dark blobs right at the core's
edge (a knob clipped by the patch outline) are kept. The peak, not the mean, is used
because a small dot's anti-aliased rim lowers its mean. Results are reported both
with all ink and with load-bearing ink only.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._tol import tol


@dataclass(frozen=True)
class Group:
    """Ink of one candidate print.

    Attributes
    ----------
    rows, cols : slice
        Bounding box in the sheet.
    mask : (h, w) bool
        The group's ink inside the box.
    """

    rows: slice
    cols: slice
    mask: np.ndarray

    @property
    def n_pixels(self) -> int:
        return int(self.mask.sum())


def _disk(radius: int):
    import cv2

    r = max(int(radius), 1)
    return cv2.getStructuringElement(cv2.MORPH_ELLIPSE, (2 * r + 1, 2 * r + 1))


def group_blobs(mask, *, mm_per_px: float, distance_mm: float | None = None) -> list[Group]:
    """Group ink blobs that lie within ``distance_mm`` of each other.

    Returns
    -------
    list of Group, ordered top to bottom (by the box's centre row).
    """
    import cv2
    from scipy import ndimage

    d_px = (tol.group_distance_mm if distance_mm is None else distance_mm) / mm_per_px
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


def is_print(group: Group, *, mm_per_px: float) -> tuple[bool, str]:
    """Whether a group looks like a contact print; if not, why (label, line, dust)."""
    import cv2

    area = group.n_pixels * mm_per_px**2
    if area < tol.min_patch_area_mm2:
        return False, f"too little ink ({area:.1f} mm^2 < {tol.min_patch_area_mm2:g})"
    pts = np.column_stack(np.nonzero(group.mask)[::-1]).astype(np.float32)
    (_, _), (a, b), _ = cv2.minAreaRect(pts)
    length, width = (max(a, b) + 1) * mm_per_px, (min(a, b) + 1) * mm_per_px
    if width < tol.min_patch_width_mm:
        return False, f"a line ({width:.2f} mm wide)"
    if length / width > tol.max_patch_aspect:
        return False, f"a line ({length / width:.0f} x longer than wide)"
    hull = cv2.convexHull(pts)
    fill = group.n_pixels / max(cv2.contourArea(hull) + 0.5 * cv2.arcLength(hull, True) + 1.0, 1.0)
    if fill < tol.min_net_to_gross:
        return False, f"writing or marks ({100 * fill:.0f} % of its hull inked)"
    return True, ""


@dataclass(frozen=True)
class EdgeSpots:
    """Attributes
    ----------
    load_bearing : (h, w) bool
        The group's ink without edge spots.
    n_blobs, n_spots : int
    spot_pixels : int
    """

    load_bearing: np.ndarray
    n_blobs: int
    n_spots: int
    spot_pixels: int


def edge_spots(group: Group, darkness, *, mm_per_px: float) -> EdgeSpots:
    """Apply the section 7.1.1 rule to one group (``darkness`` = 1 - grey, same box)."""
    import cv2

    ink = group.mask.astype(np.uint8)
    n, lab, stats, cent = cv2.connectedComponentsWithStats(ink, connectivity=8)
    if n <= 2:
        return EdgeSpots(group.mask, int(n - 1), 0, 0)
    areas = stats[1:, cv2.CC_STAT_AREA] * mm_per_px**2
    ink_labels = lab[group.mask]
    peak = np.zeros(n)
    np.maximum.at(peak, ink_labels, np.asarray(darkness, float)[group.mask])
    peak = peak[1:]
    large = areas >= tol.edge_spot_area_mm2
    if not large.any():
        large = areas == areas.max()
    ref = float(np.median(peak[large]))
    core = large & (peak >= tol.edge_spot_faintness * ref)
    if not core.any():
        core = large
    core_mask = np.concatenate([[False], core])[lab].astype(np.uint8)
    core_pts = np.concatenate(
        cv2.findContours(core_mask, cv2.RETR_EXTERNAL, cv2.CHAIN_APPROX_SIMPLE)[0]
    )
    hull = cv2.convexHull(core_pts)
    dist = np.array([cv2.pointPolygonTest(hull, (float(x), float(y)), True) for x, y in cent[1:]])
    outside = dist < 0
    faint = peak < tol.edge_spot_faintness * ref
    isolated = (areas < tol.edge_spot_area_mm2) & (-dist * mm_per_px > tol.edge_spot_distance_mm)
    spot = outside & (faint | isolated)
    is_spot = np.concatenate([[False], spot])[lab]
    return EdgeSpots(group.mask & ~is_spot, int(n - 1), int(spot.sum()), int(is_spot.sum()))
