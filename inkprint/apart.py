"""Two prints joined across a band of bare paper: knobby prints stacked on a sheet
17 mm apart were one "print" (held-out set 11 sheet 22: two motorcycle prints, 122
and 87 mm long, joined into one 160 x 123 mm), because the gap is within three
times the knobs' own gaps (:func:`inkprint.group.linked_edges`).

A group is cut in two along a band of paper when all of these hold, the band read
across the group's principal axis and along it (the ink's projection on each, in
:data:`BIN_MM` bins):

* the band runs right across the group: no ink in it at all;
* it is at least :data:`APART_RATIO` times as wide as every other band across the
  group on that axis, and than ``group_distance_mm`` (under :data:`APART_SURE`
  times, or when the group was joined near the side-by-side rule's limit, both
  parts are flagged ``grouping_uncertain``);
* each part reaches at least :data:`APART_SIDE` times the band's width beyond it
  (a print, not a tip row or a label);
* each part *narrows* towards the band: its ink within :data:`FACE_DEPTH` of its
  extent from the band spans at most :data:`FACE_SHARE` of the part's widest
  extent along the band (two rounded outlines meeting). A car print's ribs either
  side of a wide groove face it with their full length (the groove runs through
  the footprint), and stay one print.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from .coords import mm_to_px_length, px_to_mm_length
from .group import Group, _straight_side, outline_points

__all__ = ["split_apart"]

#: bin of the ink's projection [mm]
BIN_MM = 0.25
#: the band is this many times as wide as any other across the group (two mtb
#: prints end to end 14 mm apart: 16.3 mm of paper between their knobs, knob
#: columns 5.5 mm apart)
APART_RATIO = 2.5
#: under this many times, the cut is flagged ``grouping_uncertain`` (the parts'
#: ``doubt_gap_mm``: the band's width)
APART_SURE = 4.0
#: each part reaches this many times the band's width beyond it
APART_SIDE = 2.0
#: a part's face: the ink within this share of its extent from the band ...
FACE_DEPTH = 0.1
#: ... spans at most this share of the part's widest extent along the band
FACE_SHARE = 0.8


def _bands(u: np.ndarray, bin_px: float):
    """Empty runs (start, stop) [px, on ``u``'s axis] between ink of a projection."""
    lo = u.min()
    occ = np.bincount(((u - lo) / bin_px).astype(np.int64)) > 0
    edges = np.flatnonzero(np.diff(occ.astype(np.int8)))
    starts, stops = edges[::2] + 1, edges[1::2] + 1  # empty from start to stop
    return lo + starts * bin_px, lo + stops * bin_px


def _narrows(u, v, at: float, side: int, depth: float) -> bool:
    """Whether the part of the ink on ``side`` (-1 below ``at``, +1 above) narrows
    towards ``at``: its extent along ``v`` within ``depth`` share of its extent on
    ``u`` from ``at`` is at most :data:`FACE_SHARE` of its widest."""
    part = (u - at) * side > 0
    pu, pv = u[part], v[part]
    d = np.abs(pu - at)
    near = d <= d.min() + depth * (d.max() - d.min())
    return np.ptp(pv[near]) <= FACE_SHARE * np.ptp(pv)


def split_apart(group: Group, *, mm_per_px: float, options) -> list[Group]:
    """The group, or its two parts when it is two prints across a band of paper
    (the module's rule).

    Parameters
    ----------
    group : Group
    mm_per_px : float [mm / px]
    options : AnalysisOptions
        Uses ``group_distance_mm``; ``group_mm`` (a distance given) turns the cut off.

    Returns
    -------
    list of Group
        ``[group]``, or its two parts (the same attributes, their own boxes).
    """
    import cv2

    if options.group_mm is not None:
        return [group]
    least = mm_to_px_length(options.group_distance_mm, mm_per_px)
    h, w = group.mask.shape
    # too small to hold two parts and a band: each part twice the band beyond it
    if np.hypot(h, w) < (1 + 2 * APART_SIDE) * APART_RATIO * least:
        return [group]
    # on a grid of BIN_MM cells (any ink in a cell): a cell's centre is within
    # half a cell of its ink, so a band of empty bins is paper
    q = max(1, int(mm_to_px_length(BIN_MM, mm_per_px)))
    small = cv2.resize(
        group.mask.view(np.uint8) * np.uint8(255),
        (max(w // q, 1), max(h // q, 1)),
        interpolation=cv2.INTER_AREA,
    )
    rr, cc = np.nonzero(small)
    if len(rr) < 50:
        return [group]
    sy, sx = h / small.shape[0], w / small.shape[1]  # sheet px per cell
    bin_px = max(sy, sx)
    y, x = (rr + 0.5) * sy, (cc + 0.5) * sx
    xy = np.column_stack([x - x.mean(), y - y.mean()])
    _, vecs = np.linalg.eigh(xy.T @ xy)
    for axis in vecs.T:
        u = xy @ axis
        v = xy @ np.array([-axis[1], axis[0]])
        starts, stops = _bands(u, bin_px)
        if not len(starts):
            continue
        widths = stops - starts
        k = int(np.argmax(widths))
        band = widths[k]
        others = np.delete(widths, k)
        floor = max(least, others.max() if len(others) else 0.0)
        if band < APART_RATIO * floor:
            continue
        if min(starts[k] - u.min(), u.max() - stops[k]) < APART_SIDE * band:
            continue
        if not (
            _narrows(u, v, starts[k], -1, FACE_DEPTH) and _narrows(u, v, stops[k], 1, FACE_DEPTH)
        ):
            continue
        parts = _cut(group, axis, xy_mean=(x.mean(), y.mean()), at=0.5 * (starts[k] + stops[k]))
        # near the limit, or joined near the side-by-side rule's (a doubt the group
        # carried): two prints, flagged, the warning naming --group-mm
        sure = band >= APART_SURE * floor
        # (a doubt the side-by-side rule carried goes when neither part has a
        # rib's straight side: two rounded prints, held-out 14 sheet 7)
        carried = group.doubt_gap_mm > 0 and any(_ribbed(p, mm_per_px) for p in parts)
        gap = 0.0 if sure and not carried else px_to_mm_length(band, mm_per_px)
        return [dataclasses.replace(p, doubt_gap_mm=gap, doubt_joined=False) for p in parts]
    return [group]


def _cut(group: Group, axis: np.ndarray, *, xy_mean, at: float) -> list[Group]:
    """The group's ink either side of the line ``u = at`` (``u`` along ``axis`` from
    ``xy_mean``, box pixels), each in its own box."""
    h, w = group.mask.shape
    yy, xx = np.mgrid[0:h, 0:w]
    u = (xx + 0.5 - xy_mean[0]) * axis[0] + (yy + 0.5 - xy_mean[1]) * axis[1]
    out = []
    for part in (group.mask & (u < at), group.mask & (u >= at)):
        rows, cols = np.flatnonzero(part.any(axis=1)), np.flatnonzero(part.any(axis=0))
        r0, r1, c0, c1 = rows[0], rows[-1] + 1, cols[0], cols[-1] + 1
        out.append(
            dataclasses.replace(
                group,
                rows=slice(group.rows.start + r0, group.rows.start + r1),
                cols=slice(group.cols.start + c0, group.cols.start + c1),
                mask=part[r0:r1, c0:c1],
            )
        )
    return out


def _ribbed(part: Group, mm_per_px: float) -> bool:
    """Whether a part's hull has a rib's straight side (:func:`inkprint.group._straight_side`)."""
    pts = outline_points(part.mask)
    return pts is not None and _straight_side(
        px_to_mm_length(pts.reshape(-1, 2).astype(float), mm_per_px)
    )
