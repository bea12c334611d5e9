"""Chart-paper gridlines taken out of a sheet's ink before the prints are grouped.

Gridlines are thin, straight, parallel to the sheet's sides, repeated and run
unbroken over most of the sheet (a print's tread lines stop at its edge). So: rows
(columns) with an unbroken run of ink over at least ``grid_span`` of the sheet's
width (height), in bands no thicker than a pen stroke (``stroke_width_mm``), at
least ``grid_min_lines`` of them (:class:`inkprint.AnalysisOptions`), spread over half
the sheet across them or more (:data:`GRID_SPREAD`: a print's thin strips of ink lie
within its width), are gridlines (a row of anti-aliased fringe either side). A line's pixel stays a print's ink where the rest of the ink lies
right across the line on both sides (a line crossing a print or a tread block);
elsewhere it is taken out, so it no longer joins a print, its grooves or a halo
speck (dots, ``dot_mm``, do not count as ink across). A line's pixel darker than
the line itself (``grid_ink_darker`` of its grey) is ink printed over it and stays
ink too (chart paper's lines are lighter than a print's ink). Where a line runs
along a print's edge the edge cannot be told from the line: the print is flagged
``mark_on_edge`` when the line's far side would move its length, width or area
by more than ``edge_uncertainty`` (:meth:`Gridlines.grazed`). A grid
that does not come out this way (turned on the scanner, broken by a faint scan)
is left to the marks' sorting, which flags the prints it touches.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .components import row_counts
from .coords import mm_to_px_length
from .options import AnalysisOptions, resolve_options

#: gridlines are spread over at least this share of the sheet across them: chart
#: paper is ruled all over, a print's thin strips of ink (between a slick print's
#: rows of pores, a ribbed print's ribs) lie within its width (a 101 x 18.5 mm print
#: with a square lattice of pores on a 130 x 60 mm scan: its strips, 78 % of the
#: scan long, were 12 "gridlines"; split in two, width -36 %, status ok)
GRID_SPREAD = 0.5


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
    if len(bands) < least or bands[-1][1] - bands[0][0] < GRID_SPREAD * h:
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
    line_rows, line_cols : (rows,) and (cols,) bool
        The rows (columns) on horizontal (vertical) lines.
    dark_below : float or None
        Grey below which a pixel on a line is ink printed over it
        (``grid_ink_darker`` of the lines' grey, :func:`_dark_on_line`); None when
        the grey levels were not given.
    """

    removed: np.ndarray
    along_rows: np.ndarray
    along_cols: np.ndarray
    line_rows: np.ndarray
    line_cols: np.ndarray
    dark_below: float | None = None

    def grazed(
        self,
        own: np.ndarray,
        r0: int,
        c0: int,
        *,
        mm_per_px: float,
        options: AnalysisOptions | None = None,
    ) -> np.ndarray:
        """The gridline ink taken out where it runs along a print's edge.

        Parameters
        ----------
        own : (h, w) bool
            The print's ink, its box at sheet row ``r0``, column ``c0`` [px],
            grown by :func:`stroke_px` + 1 beyond the ink (within the sheet).
        r0, c0 : int [px]
        mm_per_px : float [mm / px]
        options : AnalysisOptions, optional
            Uses ``grid_graze_mm`` and ``stroke_width_mm`` (defaults when None).

        Returns
        -------
        (h, w) bool
            The lines' ink next to the print's ink in runs along the lines at least
            ``grid_graze_mm`` long (a line leaving the print's edge at a slant
            touches it over a shorter run), a line's width either side: the edge
            lies somewhere in it.
        """
        import cv2

        opts = resolve_options(options)
        t = stroke_px(mm_per_px, opts) + 1
        box = (slice(r0, r0 + own.shape[0]), slice(c0, c0 + own.shape[1]))
        near = cv2.dilate(own.view(np.uint8), np.ones((3, 3), np.uint8)).view(bool)
        least = mm_to_px_length(opts.grid_graze_mm, mm_per_px)
        removed = self.removed[box]
        runs = _long_runs(self.along_rows[box] & near, least)
        band = cv2.dilate(runs.view(np.uint8), np.ones((2 * t + 1, 1), np.uint8)).view(bool)
        band &= removed & self.line_rows[box[0], None]
        runs = _long_runs((self.along_cols[box] & near).T, least).T
        cross = cv2.dilate(runs.view(np.uint8), np.ones((1, 2 * t + 1), np.uint8)).view(bool)
        return band | (cross & removed & self.line_cols[None, box[1]])


def stroke_px(mm_per_px: float, options: AnalysisOptions) -> int:
    """A pen stroke's width (``stroke_width_mm``) in whole pixels, at least 1: the
    widest a gridline's band is, fringe aside.

    Parameters
    ----------
    mm_per_px : float [mm / px]
    options : AnalysisOptions

    Returns
    -------
    int [px]
    """
    return int(np.ceil(max(1.0, mm_to_px_length(options.stroke_width_mm, mm_per_px))))


def _long_runs(rows: np.ndarray, least: float) -> np.ndarray:
    """The runs of True along the rows at least ``least`` [px] long."""
    r, start, stop = _run_ends(np.ascontiguousarray(rows))
    out = np.zeros(rows.shape, bool)
    for i, a, b in zip(r, start, stop, strict=True):
        if b - a >= least:
            out[i, a:b] = True
    return out


def _without_dots(ink: np.ndarray, dot_px: float) -> np.ndarray:
    """The ink without its pieces no longer than ``dot_px`` either way (specks)."""
    from .components import components_with_stats

    _, labels, stats, _ = components_with_stats(ink)
    dots = np.maximum(stats[:, 2], stats[:, 3]) <= dot_px
    dots[0] = False
    return ink & ~dots[labels] if dots.any() else ink


def _both_sides(ink: np.ndarray, reach: int, *, vertical: bool) -> np.ndarray:
    """Pixels with ink within ``reach`` [px] on both sides: above and below
    (``vertical``), else left and right."""
    import cv2

    shape = (reach + 1, 1) if vertical else (1, reach + 1)
    kernel = np.ones(shape, np.uint8)
    src = ink.view(np.uint8)
    last = (0, reach) if vertical else (reach, 0)  # anchor (x, y) at the kernel's end
    before = cv2.dilate(src, kernel, anchor=last)  # ink at offsets -reach..0
    after = cv2.dilate(src, kernel, anchor=(0, 0))  # ink at offsets 0..reach
    return (before & after).view(bool)


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


def _dark_on_line(grey, dark_below: float, lines, rest, dot_px: float) -> np.ndarray:
    """The lines' pixels darker than ``dark_below`` (``grid_ink_darker`` of their
    lower quartile: the line's core, not its fringe), in pieces, with the ink
    beside them, longer than a dot: ink printed over a line. Chart paper's lines
    are printed lighter than a print's ink, so a tread block the outline cut to a
    sliver lying on a line keeps its ink (a tip sliver on a line was lost: length
    -3.5 %, unflagged, at 200 dpi); a line as dark as the ink keeps nothing."""
    dark = lines & (grey < dark_below)
    if not dark.any():
        return dark
    return dark & _without_dots(dark | rest, dot_px)


def _dark_below(grey: np.ndarray, lines: np.ndarray, share: float) -> float:
    """``share`` of the lines' grey (the lower quartile of their pixels, a subsample)."""
    return share * float(np.percentile(grey[lines][::7], 25))


def find_gridlines(
    mask: np.ndarray,
    *,
    mm_per_px: float,
    options: AnalysisOptions | None = None,
    grey: np.ndarray | None = None,
) -> Gridlines | None:
    """The ink of chart-paper gridlines outside the prints.

    Parameters
    ----------
    mask : (rows, cols) bool
        Ink of the sheet.
    mm_per_px : float [mm / px]
    options : AnalysisOptions, optional
        Uses ``stroke_width_mm``, ``dot_mm``, ``grid_span`` and ``grid_min_lines``
        (defaults when None).
    grey : (rows, cols) uint8 or float, optional
        The sheet's grey levels (dark ink low). With them, a line's pixels darker
        than ``grid_ink_darker`` of the lines' own grey are ink printed over the
        line (:func:`_dark_on_line`), not the line.

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
    # a line's pixel is a print's ink where the rest of the ink lies right across
    # the line on both sides (a line crossing a print or a tread block); not in a
    # groove, along an edge, or between a print and a halo speck (dots left out:
    # a speck on the line beside the edge joined the print, width +8 %)
    rest = _without_dots(mask & ~lines, mm_to_px_length(opts.dot_mm, mm_per_px))
    reach = stroke_px(mm_per_px, opts) + 3  # the band: stroke wide, a row of fringe each side
    body = np.zeros_like(mask)
    dark_below = None
    if grey is not None:
        dark_below = _dark_below(grey, lines, opts.grid_ink_darker)
        body = _dark_on_line(
            grey, dark_below, lines, rest, mm_to_px_length(opts.dot_mm, mm_per_px)
        )
    for _ in range(2):  # twice: where two lines cross inside a print, each is ink
        ink = rest | body  # across the other (first pass: a hole of a line's width)
        body |= (h_line & _both_sides(ink, reach, vertical=True)) | (
            v_line & _both_sides(ink, reach, vertical=False)
        )
    removed = lines & ~body
    kept = mask & ~removed
    along_rows = _touching(removed & h_line, kept, vertical=True)
    along_cols = _touching(removed & v_line, kept, vertical=False)
    return Gridlines(removed, along_rows, along_cols, rows, cols, dark_below)
