"""Chart-paper gridlines taken out of a sheet's ink before the prints are grouped.

Gridlines are thin, straight, parallel to the sheet's sides, repeated and run
unbroken over most of the sheet (a print's tread lines stop at its edge). So: rows
(columns) with an unbroken run of ink over at least ``grid_span`` of the sheet's
width (height), in bands no thicker than a pen stroke (``stroke_width_mm``), at
least ``grid_min_lines`` of them (:class:`inkprint.AnalysisOptions`), are gridlines (a row of anti-aliased fringe
either side). Their ink is taken out except over the prints' ground: the rest of the
ink closed by the grouping distance (``group_distance_mm``), which spans the
grooves and the line's own width where it crosses a print. Outside, the line no
longer joins the print or runs along its edge, so the print measures as on plain
paper. Where a line runs along a print's edge (print ink right across the line
from the ink taken out, over more than ``edge_mark_mm``) the edge
cannot be told from the line: that print stays flagged ``mark_on_edge``. A grid
that does not come out this way (turned on the scanner, broken by a faint scan)
is left to the marks' sorting, which flags the prints it touches.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .components import row_counts
from .coords import mm_to_px_length, px_to_mm_length
from .options import AnalysisOptions, resolve_options


def _line_bands(covered: np.ndarray, max_px: float) -> list[tuple[int, int]]:
    """Runs [start, stop) of True in ``covered`` no longer than ``max_px``."""
    edges = np.flatnonzero(np.diff(np.r_[0, covered.astype(np.int8), 0]))
    return [(a, b) for a, b in zip(edges[::2], edges[1::2], strict=True) if b - a <= max_px]


def _run_ends(rows: np.ndarray) -> tuple:
    """Row, start and stop of every run of True along the rows of a bool array."""
    d = np.diff(np.pad(rows.view(np.int8), ((0, 0), (1, 1))), axis=1)
    r_up, c_up = np.nonzero(d == 1)
    _, c_down = np.nonzero(d == -1)  # row-major: the ends pair with the starts
    return r_up, c_up, c_down


def _runs(rows: np.ndarray) -> np.ndarray:
    """Length [px] of every run of True along the rows."""
    _, start, stop = _run_ends(np.ascontiguousarray(rows))
    return stop - start


def _longest_runs(rows: np.ndarray) -> np.ndarray:
    """Longest run of True in each row of a (n, w) bool array [px]."""
    r, start, stop = _run_ends(rows)
    best = np.zeros(rows.shape[0], int)
    np.maximum.at(best, r, stop - start)
    return best


def _line_rows(mask: np.ndarray, max_px: float, opts: AnalysisOptions) -> np.ndarray:
    """Rows of ``mask`` on horizontal gridlines, with a row of fringe either side."""
    h, w = mask.shape
    rows = np.zeros(h, bool)
    span, least = opts.grid_span * w, opts.grid_min_lines
    cand = np.flatnonzero(row_counts(mask) >= span)
    if len(cand) < least:  # the cheap test, on every sheet
        return rows
    covered = np.zeros(h, bool)
    covered[cand] = _longest_runs(mask[cand]) >= span
    bands = _line_bands(covered, max_px)
    if len(bands) < least:
        return rows
    for a, b in bands:
        rows[max(a - 1, 0) : b + 1] = True
    return rows


@dataclass(frozen=True)
class Gridlines:
    """Gridlines found on a sheet.

    Attributes
    ----------
    removed : (rows, cols) bool
        Their ink taken out (outside the prints).
    along_rows, along_cols : (rows, cols) bool
        Of it, the pixels of horizontal (vertical) lines with ink kept right
        across the line from them: where a line grazes a print's edge the edge
        cannot be told from the line (also a few pixels where a line leaves an
        edge at a slant).
    """

    removed: np.ndarray
    along_rows: np.ndarray
    along_cols: np.ndarray

    def along_mm(
        self,
        own: np.ndarray,
        r0: int,
        c0: int,
        *,
        mm_per_px: float,
        options: AnalysisOptions | None = None,
    ) -> float:
        """Length [mm] a print's edge runs along gridlines taken out.

        Parameters
        ----------
        own : (h, w) bool
            The print's ink, its box at sheet row ``r0``, column ``c0`` [px].
        r0, c0 : int [px]
        mm_per_px : float [mm / px]
        options : AnalysisOptions, optional
            Uses ``grid_graze_mm`` (defaults when None).

        Returns
        -------
        float [mm]
            The runs along the lines, each at least ``grid_graze_mm`` long, of
            gridline pixels next to the print's ink (a line leaving the print's
            edge at a slant touches it over a shorter run).
        """
        import cv2

        h, w = own.shape
        rows, cols = self.removed.shape
        a, b = max(r0 - 1, 0), max(c0 - 1, 0)
        e, f = min(r0 + h + 1, rows), min(c0 + w + 1, cols)
        near = np.zeros((e - a, f - b), np.uint8)
        near[r0 - a : r0 - a + h, c0 - b : c0 - b + w] = own[: e - r0, : f - c0]
        near = cv2.dilate(near, np.ones((3, 3), np.uint8)).view(bool)
        least = mm_to_px_length(resolve_options(options).grid_graze_mm, mm_per_px)
        total = 0
        for along in (self.along_rows[a:e, b:f] & near, (self.along_cols[a:e, b:f] & near).T):
            runs = _runs(along)
            total += int(runs[runs >= least].sum())
        return float(px_to_mm_length(total, mm_per_px))


def _closing(ink: np.ndarray, radius_px: float) -> np.ndarray:
    """Morphological closing by a disk (Euclidean distances): the ink with the
    gaps narrower than the disk between its parts filled."""
    import cv2

    far = cv2.distanceTransform((~ink).view(np.uint8), cv2.DIST_L2, cv2.DIST_MASK_PRECISE)
    grown = far <= radius_px
    back = cv2.distanceTransform(grown.view(np.uint8), cv2.DIST_L2, cv2.DIST_MASK_PRECISE)
    return back >= radius_px


def _touching(removed: np.ndarray, kept: np.ndarray, *, vertical: bool) -> np.ndarray:
    """Removed pixels with kept ink right next to them across the line."""
    nb = np.zeros_like(kept)
    if vertical:  # horizontal lines: across is up and down
        nb[1:] |= kept[:-1]
        nb[:-1] |= kept[1:]
    else:
        nb[:, 1:] |= kept[:, :-1]
        nb[:, :-1] |= kept[:, 1:]
    return removed & nb


def find_gridlines(
    mask: np.ndarray, *, mm_per_px: float, options: AnalysisOptions | None = None
) -> Gridlines | None:
    """The ink of chart-paper gridlines outside the prints.

    Parameters
    ----------
    mask : (rows, cols) bool
        Ink of the sheet.
    mm_per_px : float [mm / px]
    options : AnalysisOptions, optional
        Uses ``stroke_width_mm``, ``group_distance_mm``, ``grid_span`` and
        ``grid_min_lines`` (defaults when None).

    Returns
    -------
    Gridlines or None
        None when the sheet has no grid.
    """
    opts = resolve_options(options)
    stroke = max(1.0, mm_to_px_length(opts.stroke_width_mm, mm_per_px))
    rows = _line_rows(mask, stroke, opts)
    cols = _line_rows(mask.T, stroke, opts)
    if not rows.any() and not cols.any():
        return None
    h_line = mask & rows[:, None]
    v_line = mask & cols[None, :]
    lines = h_line | v_line
    # the prints' ground: the rest of the ink with its gaps under the group
    # distance closed (between tread elements, under a line crossing a print)
    body = _closing(mask & ~lines, mm_to_px_length(opts.group_distance_mm, mm_per_px) / 2)
    removed = lines & ~body
    kept = mask & ~removed
    along_rows = _touching(removed & h_line, kept, vertical=True)
    along_cols = _touching(removed & v_line, kept, vertical=False)
    return Gridlines(removed, along_rows, along_cols)
